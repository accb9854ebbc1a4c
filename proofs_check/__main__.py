"""``python -m proofs_check FILE [--json]``: exit 0 valid, 1 invalid, 2 malformed."""

from __future__ import annotations

import argparse
import json
import sys

from proofs_check.deadline import DEFAULT_SECONDS
from proofs_check.parse import MalformedError
from proofs_check.verify import check_file

__all__ = ["main"]


def main(argv: list[str] | None = None) -> int:
    """Check one certificate file; print the checks (or JSON) and return the exit code."""
    parser = argparse.ArgumentParser(prog="proofs_check", description=__doc__)
    parser.add_argument("file", help="certificate JSON file")
    parser.add_argument("--json", action="store_true", help='print {"valid", "checks"}')
    parser.add_argument(
        "--time-limit",
        type=float,
        default=DEFAULT_SECONDS,
        help=f"seconds of exact arithmetic before refusing (default {DEFAULT_SECONDS:g})",
    )
    args = parser.parse_args(argv)
    try:
        verdict = check_file(args.file, time_limit=args.time_limit)
    except MalformedError as error:
        if args.json:
            print(json.dumps({"valid": False, "error": str(error), "checks": []}))
        print(f"malformed: {args.file}: {error}", file=sys.stderr)
        return 2
    if args.json:
        print(json.dumps(verdict.to_json(), indent=2, ensure_ascii=False))
    else:
        for check in verdict.checks:
            print(f"{'ok  ' if check.valid else 'FAIL'} {check.name}: {check.detail}")
        print("certificate VALID" if verdict.valid else "certificate INVALID")
    return 0 if verdict.valid else 1


if __name__ == "__main__":
    sys.exit(main())
