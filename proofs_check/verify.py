"""Checking a whole certificate (or a bundle of them): format, kind dispatch, verdict.

A bundle is ``{"format", "kind": "bundle", "case"?, "certificates": [...]}``; it is valid when
every certificate in it is. Check names inside a bundle are prefixed with the certificate's
position and kind.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any

from proofs_check import deadline
from proofs_check import parse as p
from proofs_check.kinds import KINDS, Check

__all__ = ["Verdict", "check_certificate", "check_file"]

TOP_REQUIRED = ("format", "kind", "claim", "data", "witness")
TOP_OPTIONAL = ("source", "case", "produced_by")


@dataclass(frozen=True)
class Verdict:
    """The checker's answer: ``valid`` iff every check passed (and there was at least one)."""

    checks: tuple[Check, ...]

    @property
    def valid(self) -> bool:
        """Whether every check passed."""
        return bool(self.checks) and all(c.valid for c in self.checks)

    def to_json(self) -> dict[str, Any]:
        """``{"valid", "checks": [{"name", "valid", "detail"}]}``."""
        return {"valid": self.valid, "checks": [asdict(c) for c in self.checks]}


def check_certificate(
    cert: dict[str, Any], *, time_limit: float = deadline.DEFAULT_SECONDS
) -> Verdict:
    """Verify parsed certificate JSON within ``time_limit`` seconds of arithmetic.

    Raises
    ------
    MalformedError
        If the format version, the kind or any field is not as ``docs/certificates.md`` says,
        or the certificate is too costly to check (size limits, work estimate, time limit).
    """
    with deadline.budget(time_limit):
        return _check(cert)


def _check(cert: dict[str, Any]) -> Verdict:
    _format(cert)
    if cert.get("kind") == "bundle":
        p.fields(cert, "top level", ("format", "kind", "certificates"), TOP_OPTIONAL)
        items = cert["certificates"]
        if not isinstance(items, list) or not items or len(items) > p.MAX_ITEMS:
            why = f"certificates: expected a non-empty list of at most {p.MAX_ITEMS}"
            raise p.MalformedError(why)
        checks: list[Check] = []
        for k, item in enumerate(items):
            where = f"certificates[{k + 1}]"
            if isinstance(item, dict) and item.get("kind") == "bundle":
                raise p.MalformedError(f"{where}: bundles cannot be nested")
            try:
                kind, inner = _single(item, "top level")
            except p.MalformedError as error:
                raise p.MalformedError(f"{where}: {error}") from None
            checks += [Check(f"[{k + 1} {kind}] {c.name}", c.valid, c.detail) for c in inner]
        return Verdict(tuple(checks))
    return Verdict(tuple(_single(cert, "top level")[1]))


def _format(cert: Any) -> None:
    if not isinstance(cert, dict) or cert.get("format") != p.FORMAT:
        got = cert.get("format") if isinstance(cert, dict) else None
        raise p.MalformedError(f"format: expected {p.FORMAT!r}, got {str(got)[:60]!r}")


def _single(cert: Any, where: str) -> tuple[str, list[Check]]:
    _format(cert)
    p.fields(cert, where, TOP_REQUIRED, TOP_OPTIONAL)
    kind = p.text(cert["kind"], "kind", tuple(KINDS))
    return kind, KINDS[kind](cert)


def check_file(path: str, *, time_limit: float = deadline.DEFAULT_SECONDS) -> Verdict:
    """Read and verify the certificate file at ``path`` (raises ``MalformedError``)."""
    return check_certificate(p.load(path), time_limit=time_limit)
