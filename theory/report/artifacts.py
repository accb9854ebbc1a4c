"""Files the claims produce — figures and certificates — copied into the report folder.

Claims return figures in :attr:`ClaimResult.figures` and certificates either as paths in their
evidence under ``certificate`` (one path) or ``certificates`` (a list), or as the certificate
itself under ``certificate_document`` (a JSON object: the claim then writes no file). The report
copies each file (or writes each document) to ``DIR/figures/<claim>/<case>/`` or
``DIR/certificates/<claim>/<case>/``, records its SHA-256 (so the figures' data is part of the
reproducible ``report.json``), puts the copy's path relative to ``DIR`` in the evidence (a
document is replaced by its file's path under ``certificate``), and re-verifies every
certificate with the independent checker, ``python -m proofs_check FILE --json`` (what
``trackcert check`` runs, DESIGN.md), recording that command's verdict next to it.

A certificate document is checked where its claim ran (:func:`check_document`, on the task's
worker, while other checks run): the verdict travels back keyed by the SHA-256 of the exact bytes
the report writes, and :func:`prechecked` reuses it for the report's copy of those bytes (naming
the copy in its ``command``) instead of running the checker again after all the checks.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import theory
from theory.core.claims import DOCUMENT_KEY
from theory.report.records import Record, slug

__all__ = [
    "CERTIFICATE_KEYS",
    "Artifacts",
    "CertificateChecker",
    "certificate_bytes",
    "check_document",
    "check_with_cli",
    "collect",
    "prechecked",
]

CERTIFICATE_KEYS = ("certificate", "certificates")
"""Evidence keys whose values are certificate paths (a string, or a list of strings)."""


CHECK_TIMEOUT = 300.0
"""Seconds allowed to the checker on one certificate before it counts as inconclusive."""

CertificateChecker = Callable[[Path, Path], dict[str, Any]]
"""``checker(relative_path, report_dir) -> verdict``; see :func:`check_with_cli`."""


@dataclass(frozen=True)
class Artifacts:
    """A record's files after copying: ``figures`` and ``certificates`` as report entries."""

    record: Record
    figures: tuple[dict[str, Any], ...]
    certificates: tuple[dict[str, Any], ...]


def collect(
    records: tuple[Record, ...], out_dir: Path, *, checker: CertificateChecker | None = None
) -> list[Artifacts]:
    """Copy every record's figures and certificates into ``out_dir`` and check the certificates.

    Parameters
    ----------
    records : tuple of Record
        The report's records.
    out_dir : Path
        The report folder (created if needed).
    checker : callable, optional
        Verifies one certificate; defaults to :func:`check_with_cli`.

    Returns
    -------
    list of Artifacts
        One per record, in order; each record's evidence has the certificate paths replaced by
        the copies' relative paths.
    """
    checker = check_with_cli if checker is None else checker
    taken: set[str] = set()
    collected = []
    for record in records:
        figures = tuple(_copy(Path(f), "figures", record, out_dir, taken) for f in record.figures)
        evidence = dict(record.evidence)
        certificates: list[dict[str, Any]] = []
        document = evidence.pop(DOCUMENT_KEY, None)
        for key in CERTIFICATE_KEYS:
            paths = _certificate_paths(evidence.get(key))
            if paths is None:
                continue
            copies = [_copy(Path(p), "certificates", record, out_dir, taken) for p in paths]
            for copy in copies:
                if copy["sha256"] is not None:
                    copy["check"] = checker(Path(copy["path"]), out_dir)
            certificates.extend(copies)
            relative = [c["path"] for c in copies]
            evidence[key] = relative[0] if isinstance(evidence[key], str) else relative
        if isinstance(document, dict):
            written = _write(document, record, out_dir, taken)
            written["check"] = checker(Path(written["path"]), out_dir)
            certificates.append(written)
            evidence["certificate"] = written["path"]
        collected.append(Artifacts(record.with_evidence(evidence), figures, tuple(certificates)))
    return collected


def _certificate_paths(value: object) -> list[str] | None:
    if isinstance(value, str):
        return [value]
    if isinstance(value, list) and all(isinstance(v, str) for v in value):
        return list(value)
    return None


def _copy(source: Path, folder: str, record: Record, out_dir: Path, taken: set[str]) -> dict:
    """Copy ``source`` under ``out_dir/folder/<claim>/<case>/`` with a name not used before."""
    name = _reserve(folder, record, slug(source.name), taken)
    if not source.is_file():
        return {"path": name, "sha256": None, "error": f"the claim's file {source.name} is missing"}
    target = out_dir / name
    target.parent.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(source, target)
    return {"path": name, "sha256": hashlib.sha256(target.read_bytes()).hexdigest()}


def _write(document: dict, record: Record, out_dir: Path, taken: set[str]) -> dict:
    """Write a certificate ``document`` as ``DIR/certificates/<claim>/<case>/<kind>.json``."""
    path = _reserve("certificates", record, _document_name(document), taken)
    target = out_dir / path
    target.parent.mkdir(parents=True, exist_ok=True)
    content = certificate_bytes(document)
    target.write_bytes(content)
    return {"path": path, "sha256": hashlib.sha256(content).hexdigest()}


def _document_name(document: dict) -> str:
    return f"{slug(str(document.get('kind', 'certificate')))}.json"


def certificate_bytes(document: dict) -> bytes:
    """The file the report writes for a certificate ``document``: UTF-8 JSON, indent 1, newline.

    Parameters
    ----------
    document : dict
        The certificate.

    Returns
    -------
    bytes
    """
    return (json.dumps(document, indent=1, ensure_ascii=False) + "\n").encode("utf-8")


def check_document(document: dict) -> tuple[str, dict[str, Any]]:
    """The independent checker's verdict on the file :func:`certificate_bytes` makes of
    ``document``, written to a temporary folder (where a claim's task runs).

    Parameters
    ----------
    document : dict
        The certificate.

    Returns
    -------
    (str, dict)
        The SHA-256 of the bytes checked, and :func:`check_with_cli`'s verdict on them.
    """
    content = certificate_bytes(document)
    name = Path(_document_name(document))
    with tempfile.TemporaryDirectory(prefix="trackcert-certificate-") as folder:
        (Path(folder) / name).write_bytes(content)
        verdict = check_with_cli(name, Path(folder))
    return hashlib.sha256(content).hexdigest(), verdict


def prechecked(verdicts: Mapping[str, dict[str, Any]]) -> CertificateChecker:
    """A checker reusing ``verdicts`` (by SHA-256 of the file's bytes), else :func:`check_with_cli`.

    Parameters
    ----------
    verdicts : mapping of str to dict
        Verdicts of :func:`check_document`, by the SHA-256 of the bytes checked.

    Returns
    -------
    CertificateChecker
        Its verdict on a file whose bytes were checked already is that verdict, with the
        ``command`` naming the file given; any other file is checked now.
    """

    def checker(relative: Path, out_dir: Path) -> dict[str, Any]:
        digest = hashlib.sha256((out_dir / relative).read_bytes()).hexdigest()
        if digest not in verdicts:
            return check_with_cli(relative, out_dir)
        return {**verdicts[digest], "command": _command_line(relative)}

    return checker


def _reserve(folder: str, record: Record, name: str, taken: set[str]) -> str:
    """``folder/<claim>/<case>/name``, prefixed ``2-``, ``3-`` … until unused; marks it used."""
    base = f"{folder}/{slug(record.id)}/{slug(record.case)}"
    path, index = f"{base}/{name}", 2
    while path in taken:
        path, index = f"{base}/{index}-{name}", index + 1
    taken.add(path)
    return path


def check_with_cli(relative: Path, out_dir: Path) -> dict[str, Any]:
    """Run the independent checker, ``python -m proofs_check RELATIVE --json``, in ``out_dir``.

    It is what ``trackcert check`` runs, without the library's start-up (about 0.05 s a
    certificate instead of 1 s).

    Parameters
    ----------
    relative : Path
        The certificate's path relative to ``out_dir`` (so the verdict names no absolute path).
    out_dir : Path
        The report folder, used as the working directory.

    Returns
    -------
    dict
        ``command``, ``exit_code``, ``valid`` (``True``/``False``, or ``None`` when the checker
        gave no verdict) and either ``checks`` (the checker's list) or ``error`` (its last line of
        stderr, e.g. when the checker cannot be found).
    """
    command = [relative.as_posix(), "--json"]
    root = str(Path(theory.__file__).resolve().parent.parent)
    inherited = [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([root, *inherited]))
    shown = _command_line(relative)
    try:
        done = subprocess.run(
            [sys.executable, "-m", "proofs_check", *command],
            cwd=out_dir,
            env=env,
            capture_output=True,
            text=True,
            timeout=CHECK_TIMEOUT,
            check=False,
        )
    except subprocess.TimeoutExpired:
        return {"command": shown, "exit_code": None, "valid": None, "error": "timed out"}
    try:
        verdict = json.loads(done.stdout)
    except json.JSONDecodeError:
        lines = [line.strip(" │╭╮╰╯─") for line in (done.stderr or done.stdout).splitlines()]
        error = " ".join(line for line in lines if line) or "no output"
        return {"command": shown, "exit_code": done.returncode, "valid": None, "error": error}
    valid = verdict.get("valid") if isinstance(verdict, dict) else None
    checks = verdict.get("checks", []) if isinstance(verdict, dict) else []
    return {
        "command": shown,
        "exit_code": done.returncode,
        "valid": valid if isinstance(valid, bool) else None,
        "checks": checks,
    }


def _command_line(relative: Path) -> str:
    """The checker's command line on ``relative``, as the report shows it."""
    return f"python -m proofs_check {relative.as_posix()} --json"
