"""The writer every command uses (theory.core.atomic_output): a folder replaced whole or not at
all, a file by one rename, what a killed writer left settled deterministically."""

from __future__ import annotations

import os
import signal
import subprocess
import sys

import pytest

from theory.core import atomic_output
from theory.core.atomic_output import recover, replaceable_problem, replaced_folder, write_file
from theory.core.errors import CaseError, OutputError


def _dead_pid() -> int:
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def _folder(path, **files: str):
    path.mkdir()
    for name, text in files.items():
        (path / name).write_text(text)
    return path


def test_a_folder_is_replaced_whole(tmp_path) -> None:
    target = _folder(tmp_path / "out", **{"report.json": "old", "stale.png": "old"})
    with replaced_folder(target, "report.json") as staging:
        (staging / "report.json").write_text("new")
    assert sorted(p.name for p in target.iterdir()) == ["report.json"]
    assert (target / "report.json").read_text() == "new"
    assert [p.name for p in tmp_path.iterdir()] == ["out"]


def test_an_error_while_writing_leaves_the_folder_as_it_was(tmp_path) -> None:
    target = _folder(tmp_path / "out", **{"report.json": "old"})
    with pytest.raises(KeyboardInterrupt), replaced_folder(target, "report.json") as staging:
        (staging / "report.json").write_text("half")
        raise KeyboardInterrupt
    assert (target / "report.json").read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["out"]


def test_an_os_error_names_the_users_path_not_the_staging_one(tmp_path) -> None:
    target = tmp_path / "out"
    with pytest.raises(OutputError) as info, replaced_folder(target, "report.json") as staging:
        raise OSError(28, "No space left on device", str(staging / "figures" / "a.png"))
    assert str(info.value) == (
        f"could not write {target}/figures/a.png: No space left on device; {target} was not "
        "created"
    )
    assert isinstance(info.value, OSError) and not target.exists()


def test_a_failed_second_rename_puts_the_old_folder_back(tmp_path, monkeypatch) -> None:
    target = _folder(tmp_path / "out", **{"report.json": "old"})
    real_rename, calls = os.rename, []

    def rename(source, destination):
        calls.append(source)
        if len(calls) == 2:
            raise OSError(5, "Input/output error", str(source))
        real_rename(source, destination)

    monkeypatch.setattr(atomic_output.os, "rename", rename)
    with pytest.raises(OutputError), replaced_folder(target, "report.json") as staging:
        (staging / "report.json").write_text("new")
    monkeypatch.undo()
    assert (target / "report.json").read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["out"]


def test_a_failed_rollback_keeps_the_old_folder_for_recover(tmp_path, monkeypatch) -> None:
    """Both the swap and its rollback fail: the old folder is never deleted; once this process
    is gone, ``recover`` (run first by every writer) puts it back."""
    target = _folder(tmp_path / "out", **{"report.json": "old"})
    real_rename, calls = os.rename, []

    def rename(source, destination):
        calls.append(source)
        if len(calls) >= 2:
            raise OSError(5, "Input/output error", str(source))
        real_rename(source, destination)

    monkeypatch.setattr(atomic_output.os, "rename", rename)
    with pytest.raises(OutputError), replaced_folder(target, "report.json") as staging:
        (staging / "report.json").write_text("new")
    monkeypatch.undo()
    (aside,) = tmp_path.glob(".out.trackcert-old-*")
    assert not target.exists() and (aside / "report.json").read_text() == "old"
    aside.rename(aside.with_name(aside.name.replace(f"-{os.getpid()}-", f"-{_dead_pid()}-")))
    recover(target)
    assert (target / "report.json").read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["out"]


def test_recover_after_a_sigkill_between_the_renames_brings_the_old_folder_back(tmp_path) -> None:
    pid = _dead_pid()
    _folder(tmp_path / f".out.trackcert-old-{pid}-00ff", **{"report.json": "old"})
    _folder(tmp_path / f".out.trackcert-new-{pid}-00aa", **{"report.json": "new"})
    recover(tmp_path / "out")
    assert (tmp_path / "out" / "report.json").read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["out"]


def test_recover_removes_stale_siblings_and_keeps_a_running_writers(tmp_path) -> None:
    pid = _dead_pid()
    target = _folder(tmp_path / "out", **{"report.json": "new"})
    _folder(tmp_path / f".out.trackcert-old-{pid}-01", **{"report.json": "old"})  # mid-delete
    (tmp_path / f".out.trackcert-tmp-{pid}-02").write_text("partial")
    running = _folder(tmp_path / f".out.trackcert-new-{os.getppid()}-03")
    other = _folder(tmp_path / f".other.trackcert-new-{pid}-04")
    recover(target)
    assert (target / "report.json").read_text() == "new"
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["out", running.name, other.name])


def test_write_file_replaces_a_file_in_one_rename(tmp_path, monkeypatch) -> None:
    path = tmp_path / "cert.json"
    path.write_text("old")
    write_file(path, "new")
    assert path.read_text() == "new"

    def full(descriptor: int) -> None:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(atomic_output.os, "fsync", full)
    with pytest.raises(OutputError, match=r"cert\.json: No space left on device; .* left"):
        write_file(path, "newer")
    assert path.read_text() == "new" and [p.name for p in tmp_path.iterdir()] == ["cert.json"]


def test_a_signal_during_the_swap_waits_for_it(tmp_path, monkeypatch) -> None:
    """SIGINT arriving between the two renames is delivered once both are done: the new folder is
    in place and the old one deleted before the command stops."""
    target = _folder(tmp_path / "out", **{"report.json": "old"})
    real_rename = os.rename

    def rename(source, destination):
        real_rename(source, destination)
        if ".trackcert-old-" in str(destination):
            signal.raise_signal(signal.SIGINT)

    monkeypatch.setattr(atomic_output.os, "rename", rename)
    with pytest.raises(KeyboardInterrupt), replaced_folder(target, "report.json") as staging:
        (staging / "report.json").write_text("new")
    assert (target / "report.json").read_text() == "new"
    assert [p.name for p in tmp_path.iterdir()] == ["out"]


def test_only_an_empty_folder_or_the_commands_own_output_is_replaced(tmp_path, monkeypatch) -> None:
    assert replaceable_problem(tmp_path / "new", "report.json") == ""
    assert replaceable_problem(_folder(tmp_path / "empty"), "report.json") == ""
    assert replaceable_problem(_folder(tmp_path / "r", **{"report.json": "x"}), "report.json") == ""
    mine = _folder(tmp_path / "mine", **{"thesis.tex": "years of work"})
    assert "holds other files" in replaceable_problem(mine, "report.json")
    with pytest.raises(CaseError, match="holds other files"), replaced_folder(mine, "report.json"):
        pass
    assert (mine / "thesis.tex").read_text() == "years of work"
    monkeypatch.chdir(mine)
    assert "current one" in replaceable_problem(".", "report.json")
    assert "current one" in replaceable_problem(tmp_path, "report.json")
