"""``trackcert certify CASE -o FILE`` and ``trackcert check FILE`` (DESIGN.md, *CLI*).

``certify`` is a shell over :func:`theory.certify.certificate_bundle` (exit 0 written, 1 the
property is decided false, 3 no certificate could be made, 2 bad input); ``check`` over
``proofs_check``'s own entry point (0 valid, 1 invalid, 2 malformed).
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path
from typing import Annotated

import typer

import proofs_check.__main__
from proofs_check.deadline import DEFAULT_SECONDS
from theory.cli.common import COMMAND_LINE, check_output, console, print_json, reports_errors
from theory.core.errors import CaseError
from theory.kinds import load_case

__all__ = ["register", "write_atomically"]

OUTPUT = "-o/--output"


def write_atomically(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file and a rename (never half-written).

    Parameters
    ----------
    path : Path
        Destination.
    text : str
        Content (UTF-8).

    Raises
    ------
    OSError
        If the folder is not writable (the temporary file is removed).
    """
    path = Path(path)
    handle = tempfile.NamedTemporaryFile(
        "w", encoding="utf-8", dir=path.parent or Path("."), prefix=f".{path.name}.", delete=False
    )
    try:
        with handle:
            handle.write(text)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(handle.name, path)
    except BaseException:
        Path(handle.name).unlink(missing_ok=True)
        raise


def register(app: typer.Typer) -> None:
    """Add the ``certify`` and ``check`` commands to ``app``."""

    @app.command("certify")
    @reports_errors
    def certify(
        case: str = typer.Argument(..., help="Case file or bundled case name."),
        output: Annotated[
            Path | None, typer.Option("-o", "--output", help="Certificate file to write.")
        ] = None,
        seed: int = typer.Option(0, "--seed", help="Seed of random evaluation points."),
        as_json: bool = typer.Option(False, "--json", help="Print the certificate."),
    ) -> None:
        """Write every certificate the case supports (a bundle), re-checked exactly."""
        if output is not None:
            check_output(output, OUTPUT, folder=False)
        loaded = load_case(case)
        from theory.certify import certificate_bundle  # cvxpy: imported on use

        document = certificate_bundle(loaded, seed=seed)
        text = json.dumps(document, indent=1, ensure_ascii=False) + "\n"
        if output is not None:
            try:
                write_atomically(output, text)
            except OSError as error:
                raise CaseError(
                    OUTPUT, "a writable file path", str(output), file=COMMAND_LINE
                ) from error
        if as_json or output is None:
            print_json(document)
            return
        kinds = sorted({c["kind"] for c in document["certificates"]})
        console.print(
            f"wrote {len(document['certificates'])} certificates ({', '.join(kinds)}) "
            f"for {loaded.name} to {output}; check with: trackcert check {output}",
            markup=False,
            highlight=False,
        )

    @app.command("check")
    def check(
        file: str = typer.Argument(..., help="Certificate JSON file."),
        as_json: bool = typer.Option(False, "--json", help='Print {"valid", "checks"}.'),
        time_limit: float = typer.Option(
            DEFAULT_SECONDS, "--time-limit", help="Seconds of exact arithmetic before refusing."
        ),
    ) -> None:
        """Re-verify a certificate exactly with proofs_check (0 valid, 1 invalid, 2 malformed)."""
        args = [file, "--time-limit", str(time_limit), *(["--json"] if as_json else [])]
        raise typer.Exit(proofs_check.__main__.main(args))
