"""One exception tree for the whole library (docs/cli.md, *Exit codes*).

Every class derives from :class:`TrackcertError` and from the builtin it refines, so callers may
catch either. The CLI turns any :class:`TrackcertError` into exit code 2 (bad input), 1 (the
property does not hold: :class:`PropertyFails`), 3 (inconclusive) or 4 (a fault of the machine,
:class:`FaultError`) with its message and never a traceback (:mod:`theory.core.verdicts`).
"""

from __future__ import annotations

__all__ = [
    "COMMAND_LINE",
    "ENVIRONMENT",
    "CaseError",
    "ClusterError",
    "FaultError",
    "InconclusiveError",
    "OutputError",
    "PropertyFails",
    "SolverError",
    "TrackcertError",
]

COMMAND_LINE = "<command line>"
"""The ``file`` of an error in a command-line option (not in a case file)."""

ENVIRONMENT = "<environment>"
"""The ``file`` of an error in an environment setting (``TRACKCERT_…``)."""


class TrackcertError(Exception):
    """Root of every error trackcert raises on purpose."""


class CaseError(TrackcertError, ValueError):
    """Invalid input: names the ``file`` (``<data>`` when the input is no file), the dotted
    ``field`` (``tdoa.agents[3]``), what was ``expected``, what was found (``got``, shown
    briefly) and, optionally, a ``hint`` on how to fix it."""

    def __init__(
        self,
        field: str,
        expected: str,
        got: object,
        *,
        file: str = "<data>",
        hint: str = "",
    ) -> None:
        self.file = file
        self.field = field
        self.expected = expected
        self.got = got
        self.hint = hint
        super().__init__(self._message())

    def _message(self) -> str:
        got = _brief(self.got)
        text = f"{self.file}: field '{self.field}': expected {self.expected}, got {got}"
        return f"{text}. {self.hint}" if self.hint else text

    def in_file(self, file: str) -> CaseError:
        """The same error, attributed to ``file``."""
        return CaseError(self.field, self.expected, self.got, file=file, hint=self.hint)


class SolverError(TrackcertError, RuntimeError):
    """A numerical solver failed or returned an answer that did not survive re-checking."""


class InconclusiveError(TrackcertError, ArithmeticError):
    """A verdict lies inside its tolerance: deciding it would be a guess (CLI exit code 3)."""


class PropertyFails(TrackcertError):  # noqa: N818 (a verdict, not a malfunction)
    """The property asked for is decided false, so there is nothing to certify (CLI exit code 1).

    For example ``trackcert certify`` on a case whose S-detectability an exact alternative
    certificate refutes. The message says which check decided it.
    """


class FaultError(TrackcertError):
    """The run could not finish for a reason that is neither the input nor the property: the
    machine failed (a write, the cluster). Never a verdict (CLI exit code 4)."""


class OutputError(FaultError, OSError):
    """Writing an output failed (a full disk, a lost permission): names the ``path`` as the user
    named it, the system's ``reason`` and what the output is now (``left``)."""

    def __init__(self, path: str, reason: str, left: str) -> None:
        self.path = path
        self.reason = reason
        super().__init__(f"could not write {path}: {reason}; {left}")


class ClusterError(FaultError, TimeoutError):
    """The Dask cluster cannot run the tasks (no worker joined it in time)."""


def _brief(value: object, limit: int = 120) -> str:
    try:
        text = repr(_plain(value))
    except ValueError:  # an integer beyond sys.get_int_max_str_digits()
        text = "a number too long to print"
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _plain(value: object, depth: int = 0) -> object:
    """``value`` with numpy scalars and arrays as plain Python (``-0.24``, not ``np.float64``)."""
    if type(value).__module__ == "numpy" and hasattr(value, "tolist"):
        return value.tolist()
    if depth < 8 and isinstance(value, list | tuple):
        return type(value)(_plain(v, depth + 1) for v in value[:50])
    return value
