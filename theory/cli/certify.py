"""``trackcert certify CASE -o FILE`` and ``trackcert check FILE`` (docs/certificates.md).

``certify`` is a shell over :func:`theory.registry.certificate_bundle` (exit 0 written, 1 the
property is decided false, 3 no certificate could be made, 2 bad input, 4 the file could not be
written: it is then left as it was, :func:`theory.core.atomic_output.write_file`); ``check``
over ``proofs_check``'s own entry point (0 valid, 1 invalid, 2 malformed).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

import typer

import proofs_check.__main__
from proofs_check.deadline import DEFAULT_SECONDS
from theory.cli.common import check_file_output, console, print_json, reports_errors
from theory.core.atomic_output import write_file
from theory.kinds import load_case

__all__ = ["register"]

OUTPUT = "-o/--output"


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
            check_file_output(output, OUTPUT)
        loaded = load_case(case)
        from theory.registry import certificate_bundle  # the domains: imported on use

        document = certificate_bundle(loaded, seed=seed)
        text = json.dumps(document, indent=1, ensure_ascii=False) + "\n"
        if output is not None:
            write_file(output, text)
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
