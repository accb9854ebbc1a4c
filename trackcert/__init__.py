"""trackcert: verify a robot network's localization, filtering and pursuit before the lake.

The public Python API. Every function takes plain objects (numpy arrays, a ``networkx`` graph or
an edge list, a discrete ``control.StateSpace``) or a case (a path, a bundled case name, a
mapping in the case-file format, a :func:`load_case` result, or another result), builds the same
:class:`~theory.core.case_file.Case` the case-file loader builds, and calls the library function
the matching ``trackcert`` command calls. Each returns a :class:`Result`: ``verdict``, ``margin``,
``tolerances``, ``evidence``, ``certificates``, ``to_json()`` (what ``trackcert <command> --json``
prints), ``to_case()`` (the case file that reproduces it) and a table in Jupyter.

>>> import numpy as np, networkx as nx, trackcert
>>> agents = np.array([[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2]])
>>> result = trackcert.topology(agents, [17, -5, -15], nx.path_graph(4))
>>> result.verdict
True

Agent ids shown to people are 1-based (as in case files and the papers); arrays and graph nodes
passed in are 0-based rows, as in numpy. Submodules: :mod:`trackcert.testing` (assertions for
your test suite), :mod:`trackcert.strategies` (hypothesis strategies), :mod:`trackcert.design`
(certified design answers).
"""

from __future__ import annotations

import html
import importlib
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

from theory import __version__
from theory.core.errors import CaseError, TrackcertError

__all__ = [
    "CaseError",
    "Certificate",
    "CheckResult",
    "DesignResult",
    "DkfResult",
    "IssResult",
    "PfResult",
    "Result",
    "SimulationResult",
    "TopologyResult",
    "TrackcertError",
    "__version__",
    "certify",
    "check",
    "consensus_weights",
    "dkf",
    "iss",
    "load_case",
    "pf",
    "simulate",
    "topology",
]

_SUBMODULES = ("design", "strategies", "testing")
_HEADER = frozenset({"case", "source", "verdict", "exit_code", "expectations"})


def __getattr__(name: str) -> Any:
    """``trackcert.testing``, ``trackcert.strategies`` and ``trackcert.design``, imported on use."""
    if name in _SUBMODULES:
        return importlib.import_module(f"trackcert.{name}")
    raise AttributeError(f"module 'trackcert' has no attribute {name!r}")


# --------------------------------------------------------------------------------------------
# results


@dataclass(frozen=True, eq=False, repr=False)
class Result:
    """What every trackcert function returns: a verdict with its margin, tolerances, evidence.

    Attributes
    ----------
    report : object
        The library's own record (e.g. ``theory.tdoa.observability.trajectory.TopologyReport``).
    case : Case or None
        The validated case the answer is about.
    case_data : mapping or None
        That case in the case-file format (``None``: it is read from ``case.file`` when needed).
    verdict : bool or None
        True the property holds, False it does not, None inconclusive (the message says why).
    margin : float or None
        How far the deciding quantity is from its threshold (its meaning is the subclass's).
    tolerances : dict
        The named tolerances used, as ``to_json()`` echoes them.
    evidence : dict
        The numbers behind the verdict (``to_json()`` without its header keys).
    certificates : tuple of dict
        Certificate documents the analysis produced (re-verifiable with :func:`check`).
    certificate : dict or None
        The one document :func:`check` takes (the first of ``certificates``).
    expectations : list of dict
        The case's ``expect`` block, judged (``expected``, ``got``, ``verdict``, …).
    exit_code : int
        The exit code the matching command returns on this case (0, 1 or 3).
    """

    report: Any
    case: Any = None
    case_data: Mapping[str, Any] | None = None

    command: ClassVar[str] = ""

    @property
    def verdict(self) -> bool | None:
        """True the property holds, False it does not, None inconclusive."""
        return self.report.verdict

    @property
    def margin(self) -> float | None:
        """Distance of the deciding quantity from its threshold (None: no margin)."""
        return None

    @property
    def tolerances(self) -> dict[str, Any]:
        """The named tolerances used."""
        return dict(self.to_json().get("tolerances") or {})

    @property
    def evidence(self) -> dict[str, Any]:
        """The numbers behind the verdict (the JSON record without its header)."""
        return {k: v for k, v in self.to_json().items() if k not in _HEADER}

    @property
    def certificates(self) -> tuple[dict[str, Any], ...]:
        """Certificate documents the analysis produced."""
        return ()

    @property
    def certificate(self) -> dict[str, Any] | None:
        """The document :func:`check` takes (None: none produced)."""
        return self.certificates[0] if self.certificates else None

    @property
    def expectations(self) -> list[dict[str, Any]]:
        """The case's ``expect`` block, judged key by key."""
        from theory.core.jsonable import plain

        return [plain(e.to_json()) for e in getattr(self.report, "expectations", ())]

    @property
    def exit_code(self) -> int:
        """The exit code of the matching command (0 holds, 1 fails, 3 inconclusive)."""
        from theory.core.verdicts import command_verdict, exit_code

        return exit_code(command_verdict(self.verdict, getattr(self.report, "expectations", ())))

    def to_json(self) -> dict[str, Any]:
        """The record ``trackcert <command> --json`` prints for the same case and options.

        Returns
        -------
        dict
            Plain JSON data (the keys of the command in ``docs/cli.md``).
        """
        from theory.core.jsonable import plain

        return plain(self._record())

    def to_case(self, path: str | os.PathLike[str] | None = None) -> dict[str, Any]:
        """The case file reproducing this result, optionally written as YAML to ``path``.

        Parameters
        ----------
        path : str or path-like, optional
            Where to write it (replaced whole or not at all); :func:`load_case` reads it back.

        Returns
        -------
        dict
            The case in the case-file format (``name``, ``kind``, the kind's block, …).

        Raises
        ------
        ValueError
            If the result has no case, or its case was built in memory without its data (pass
            the mapping or a path to the function instead).
        """
        data = self._case_data()
        if path is not None:
            import yaml

            from theory.core.atomic_output import write_file

            flow = {"sort_keys": False, "allow_unicode": True, "default_flow_style": None}
            write_file(path, yaml.safe_dump(data, **flow))  # a row of numbers on one line
        return data

    def summary(self) -> str:
        """The verdict as one sentence, as the command's last line says it.

        Returns
        -------
        str
        """
        return _VERDICT_WORD[self.verdict]

    def _record(self) -> dict[str, Any]:
        return self.report.to_json()

    def _table(self) -> tuple[Sequence[str], list[Sequence[Any]]]:
        return (), []

    def _case_data(self) -> dict[str, Any]:
        if self.case_data is not None:
            return _lists(self.case_data)
        if self.case is None or self.case.file == "<data>":
            raise ValueError(
                f"this {type(self).__name__} has no case file data; call the function with a "
                "mapping in the case-file format or a path to get one"
            )
        from theory.core.case_file import read_case_data

        return _lists(read_case_data(Path(self.case.file)))

    def __repr__(self) -> str:
        name = f" {self.case.name}" if self.case is not None else ""
        margin = "" if self.margin is None else f" (margin {self.margin:.4g})"
        return f"<{type(self).__name__}{name}: {self.summary()}{margin}>"

    def _repr_html_(self) -> str:
        word = _VERDICT_WORD[self.verdict]
        head = f"<strong>trackcert.{self.command}</strong>"
        if self.case is not None:
            head += f" · case <code>{html.escape(self.case.name)}</code>"
        head += f" · <strong style='color:{_COLOURS[self.verdict]}'>{word}</strong>"
        sentence = self.summary().removeprefix(word).lstrip(": ")
        if sentence:
            head += f": {html.escape(sentence)}"
        notes = [] if self.margin is None else [f"margin {self.margin:.4g}"]
        notes += [f"{k} = {_cell(v)}" for k, v in self.tolerances.items()]
        note = f"<br><small>{html.escape('; '.join(notes))}</small>" if notes else ""
        return (
            f"<div class='trackcert-result'><p>{head}{note}</p>{_html_table(*self._table())}</div>"
        )


@dataclass(frozen=True, eq=False, repr=False)
class TopologyResult(Result):
    """Distributed TDOA observability of every agent (seed 000 §4.2.2, Thm 4.2.3, Cor. 4.2.4).

    ``verdict``: every agent can localize the target (at every step of a moving scene).
    ``margin``: the least factor by which a deciding singular value clears ``rank_tol · σ_max``
    (a verdict is conclusive when it is at least ``inconclusive_factor``). ``agents``: one row
    per agent, 1-based ids. ``report`` is ``theory.tdoa.observability.trajectory.TopologyReport``.
    """

    command: ClassVar[str] = "topology"

    @property
    def margin(self) -> float:
        """The least factor by which a deciding singular value clears ``rank_tol · σ_max``."""
        return min(a.margin for step in self.report.result.steps for a in step.agents)

    @property
    def agents(self) -> list[dict[str, Any]]:
        """Per-agent verdicts at the first step (``id``, ``rank``, ``observable``, …)."""
        return self.to_json()["agents"]

    def summary(self) -> str:
        """The verdict as one sentence, as ``trackcert topology`` ends.

        Returns
        -------
        str
        """
        return self.report.sentence()

    def _record(self) -> dict[str, Any]:
        return {**self.report.to_json(), "exit_code": self.exit_code}

    def _table(self) -> tuple[Sequence[str], list[Sequence[Any]]]:
        columns = (
            "agent",
            "component",
            "rank O_i",
            "σ_min",
            "observable",
            "localizes",
            "paper's heuristic",
            "mirror ambiguous",
        )
        rows = [
            (
                a.id,
                a.component,
                a.rank,
                a.sigma_min,
                a.observable,
                a.localizes,
                a.heuristic_4_noncoplanar,
                a.mirror_ambiguous,
            )
            for a in self.report.result.steps[0].agents
        ]
        return columns, rows


@dataclass(frozen=True, eq=False, repr=False)
class DkfResult(Result):
    """S-detectability of a consensus Kalman filter and Thm 5.2.10's conditions (seed 000 ch. 5).

    ``verdict``: S-detectable (Def. 5.2.4), decided by an exact certificate (None when none
    decides). ``margin``: the rounded witness's margin when S-detectable, the infeasibility
    certificate's ε when not. ``certificates``: that exact certificate. ``report`` is
    ``theory.consensus.analysis.DkfReport``.
    """

    command: ClassVar[str] = "dkf"

    @property
    def margin(self) -> float | None:
        """The rounded witness's margin (S-detectable) or the certificate's ε (not)."""
        decision = self.report.analysis.decision
        if decision.verdict is None:
            return None
        return decision.witness_margin if decision.verdict else decision.lmi.cert_epsilon

    @property
    def certificates(self) -> tuple[dict[str, Any], ...]:
        """The exact certificate that decided S-detectability (either way)."""
        document = self.report.analysis.decision.certificate
        return () if document is None else (document,)

    def summary(self) -> str:
        """Whether the filter is S-detectable and why, in one sentence.

        Returns
        -------
        str
        """
        decision = self.report.analysis.decision
        word = {True: "S-detectable", False: "not S-detectable", None: "inconclusive"}
        return f"{word[decision.verdict]}: {decision.reason}"

    def _table(self) -> tuple[Sequence[str], list[Sequence[Any]]]:
        data = self.to_json()
        rows: list[Sequence[Any]] = [
            (
                "S-detectable (Def. 5.2.4)",
                data["s_detectability"]["certificate_route"],
                data["s_detectable"],
            ),
            (
                f"r(B), r(L) with the {data['gains_source']} gains",
                f"{_cell(data['spectral_radius_B'])}, {_cell(data['spectral_radius_L'])}",
                None,
            ),
        ]
        rows += [
            (
                f"agent {b['agent']}: w_ii < 1/r(A_i^u)²",
                f"{_cell(b['w_ii'])} vs {_cell(b['bound'])}",
                b["ok"],
            )
            for b in data["self_weight_bounds"]
        ]
        rows += [
            (f"source component {s['agents']} detectable", "", s["detectable"])
            for s in data["source_components"]
        ]
        rows += [
            (f"blind set {b['agents']}: |λ|² r(W_SS) < 1", _cell(b["value"]), b["ok"])
            for b in data["blind_sets"]
        ]
        rows.append(("coupled Riccati iteration", data["riccati"]["status"], None))
        return ("condition", "value", "holds"), rows


@dataclass(frozen=True, eq=False, repr=False)
class IssResult(Result):
    """ISS Lyapunov analysis of the pursuit and coordination loop (seed 003, Thms 1–2 corrected).

    ``verdict``: every condition holds (None when a margin lies inside ``margin_tol``).
    ``margin``: the least margin of the conditions that have one. ``conditions``: one record
    per condition (``name``, ``status``, ``value``, ``margin``, ``source``, ``detail``).
    ``report`` is ``theory.pursuit.iss.IssReport``.
    """

    command: ClassVar[str] = "iss"

    @property
    def conditions(self) -> list[dict[str, Any]]:
        """Every condition of the analysis with its status and margin."""
        return self.to_json()["conditions"]

    @property
    def margin(self) -> float | None:
        """The least margin among the conditions that have one."""
        margins = [c["margin"] for c in self.conditions if c["margin"] is not None]
        return min(margins, default=None)

    def summary(self) -> str:
        """Which conditions fail or are undecided, in one sentence.

        Returns
        -------
        str
        """
        failing = [c["name"] for c in self.conditions if c["status"] in _NOT_HOLDING]
        return "every condition holds" if not failing else "not holding: " + ", ".join(failing)

    def _table(self) -> tuple[Sequence[str], list[Sequence[Any]]]:
        rows = [
            (c["name"], c["status"], c["value"], c["margin"], c["source"]) for c in self.conditions
        ]
        return ("condition", "status", "value", "margin", "source"), rows


@dataclass(frozen=True, eq=False, repr=False)
class SimulationResult(Result):
    """A closed-loop Monte Carlo simulation (``trackcert simulate``).

    ``verdict``: the case's expectations about the runs (True when it states none).
    ``agents``: one summary row per agent. ``metrics``: the filter's NEES/NIS against their χ²
    bands and OSPA/GOSPA. ``files``: the data and figures written; ``figures``: the PNG files
    among them. ``report`` is ``theory.sim.simulate.Simulation``.
    """

    command: ClassVar[str] = "simulate"

    @property
    def agents(self) -> list[dict[str, Any]]:
        """Per-agent summary rows (``id``, final and mean localization error, ANEES, …)."""
        return self.to_json()["agents"]

    @property
    def metrics(self) -> dict[str, Any]:
        """NEES and NIS tests per agent (value, band, margin, verdict, the safe side) and
        OSPA/GOSPA where positions are estimated (docs/simulation.md, *Filter metrics*)."""
        return self.to_json()["metrics"]

    @property
    def files(self) -> list[Path]:
        """Every file written (``runs.npz``, CSV tables, figures)."""
        return [Path(f) for f in self.report.finished.files]

    @property
    def figures(self) -> list[Path]:
        """The PNG figures written."""
        return [f for f in self.files if f.suffix == ".png"]

    def summary(self) -> str:
        """Runs, seed and the expectations' verdict in one sentence.

        Returns
        -------
        str
        """
        return f"{self.report.runs} run(s), seed {self.report.seed}; {_expected(self)}"

    def _table(self) -> tuple[Sequence[str], list[Sequence[Any]]]:
        return _agent_table(self.agents)


@dataclass(frozen=True, eq=False, repr=False)
class PfResult(Result):
    """Monte Carlo runs of seed 002's distributed TDOA particle filter (``trackcert pf``).

    ``verdict``: the case's expectations (True when it states none), judged from the claims'
    observations. ``agents``: per-node error summary; ``metrics``: NEES of the weighted particle
    cloud and NIS against their χ² bands, OSPA/GOSPA of the estimates; ``figures``: the PNG
    files written. ``report`` is ``theory.particle.report.PfReport``.
    """

    command: ClassVar[str] = "pf"

    @property
    def agents(self) -> list[dict[str, Any]]:
        """Per-node error summary rows (``id``, mean, final and tail errors, ANEES, …)."""
        return self.to_json()["agents"]

    @property
    def metrics(self) -> dict[str, Any]:
        """NEES and NIS tests per filtering node and OSPA/GOSPA (docs/particle-filter.md)."""
        return self.to_json()["metrics"]

    @property
    def figures(self) -> list[Path]:
        """The PNG figures written (none without a ``folder``)."""
        return [Path(f) for f in self.report.figures]

    def summary(self) -> str:
        """Runs, seed and the expectations' verdict in one sentence.

        Returns
        -------
        str
        """
        spec = self.report.case.spec
        return f"{spec.runs} run(s), seed {spec.seed}; {_expected(self)}"

    def _table(self) -> tuple[Sequence[str], list[Sequence[Any]]]:
        return _agent_table(self.agents)


@dataclass(frozen=True, eq=False, repr=False)
class Certificate(Result):
    """Every certificate a case supports, as ``trackcert certify`` writes it (a bundle).

    ``verdict``: True when certificates were made (each already accepted by ``proofs_check``),
    False when the property is decided false (nothing to certify), None when no certificate
    could be made (``reason`` says why; ``refuted`` marks the False case). ``certificate``: the
    bundle document; ``certificates``: the documents inside it. ``report`` is the bundle (or
    ``None``).
    """

    reason: str = ""
    refuted: bool = False

    command: ClassVar[str] = "certify"

    @property
    def verdict(self) -> bool | None:
        """True certified, False the property is decided false, None no certificate."""
        if self.report is not None:
            return True
        return False if self.refuted else None

    @property
    def certificate(self) -> dict[str, Any] | None:
        """The bundle document (what ``trackcert certify`` writes), or None."""
        return self.report

    @property
    def certificates(self) -> tuple[dict[str, Any], ...]:
        """The certificates inside the bundle."""
        return () if self.report is None else tuple(self.report["certificates"])

    @property
    def evidence(self) -> dict[str, Any]:
        """Kind and statement of each certificate, and why there are none."""
        return {"certificates": [_about(c) for c in self.certificates], "reason": self.reason}

    @property
    def tolerances(self) -> dict[str, Any]:
        """None: a certificate is checked exactly."""
        return {}

    def summary(self) -> str:
        """How many certificates of which kinds, or why there are none.

        Returns
        -------
        str
        """
        if self.report is None:
            return self.reason
        kinds = sorted({c["kind"] for c in self.certificates})
        return f"{len(self.certificates)} certificate(s) ({', '.join(kinds)}), re-checked exactly"

    def write(self, path: str | os.PathLike[str]) -> Path:
        """Write the bundle as ``trackcert certify -o`` does (replaced whole or not at all).

        Parameters
        ----------
        path : str or path-like
            The JSON file; ``trackcert check`` and :func:`check` read it.

        Returns
        -------
        Path

        Raises
        ------
        ValueError
            If there is no certificate to write.
        """
        import json

        from theory.core.atomic_output import write_file

        if self.report is None:
            raise ValueError(f"no certificate to write: {self.reason}")
        return write_file(path, json.dumps(self.report, indent=1, ensure_ascii=False) + "\n")

    def _record(self) -> dict[str, Any]:
        return self.report if self.report is not None else {"valid": False, "error": self.reason}

    def _table(self) -> tuple[Sequence[str], list[Sequence[Any]]]:
        rows = [(c["kind"], c["statement"]) for c in map(_about, self.certificates)]
        return ("kind", "claim"), rows


@dataclass(frozen=True, eq=False, repr=False)
class CheckResult(Result):
    """A certificate re-verified in exact arithmetic by ``proofs_check`` (``trackcert check``).

    ``verdict``: every check holds. ``checks``: one record per check (``name``, ``valid``,
    ``detail``). ``report`` is ``proofs_check.Verdict``.
    """

    command: ClassVar[str] = "check"

    @property
    def verdict(self) -> bool:
        """Whether every check of the certificate holds."""
        return self.report.valid

    @property
    def checks(self) -> list[dict[str, Any]]:
        """Every check with its verdict and detail."""
        return self.to_json()["checks"]

    def summary(self) -> str:
        """VALID, or INVALID with the first failing check.

        Returns
        -------
        str
        """
        failing = [c for c in self.checks if not c["valid"]]
        if not failing:
            return f"certificate VALID ({len(self.checks)} checks)"
        return f"certificate INVALID: {failing[0]['name']}: {failing[0]['detail']}"

    def _table(self) -> tuple[Sequence[str], list[Sequence[Any]]]:
        return ("check", "valid", "detail"), [
            (c["name"], c["valid"], c["detail"]) for c in self.checks
        ]


@dataclass(frozen=True, eq=False, repr=False)
class DesignResult(Result):
    """A certified design answer of :mod:`trackcert.design` (``trackcert design …``).

    Wraps the library's frozen answer (``report``): ``verdict``, ``tolerances`` and
    ``certificates`` are the answer's own when it has them; ``to_json()`` its JSON keys.
    """

    command: ClassVar[str] = "design"

    @property
    def verdict(self) -> bool | None:
        """The answer's own verdict (True when it has none: answered)."""
        return getattr(self.report, "verdict", True)

    @property
    def tolerances(self) -> dict[str, Any]:
        """The answer's tolerances."""
        return dict(getattr(self.report, "tolerances", None) or {})

    @property
    def certificates(self) -> tuple[dict[str, Any], ...]:
        """The answer's certificates."""
        return tuple(getattr(self.report, "certificates", None) or ())

    @property
    def exit_code(self) -> int:
        """The design command's exit code for the answer."""
        from theory.core.verdicts import exit_code

        return exit_code(self.verdict)


_VERDICT_WORD = {True: "HOLDS", False: "FAILS", None: "INCONCLUSIVE"}
_COLOURS = {True: "#1a7f37", False: "#cf222e", None: "#9a6700"}
_NOT_HOLDING = ("fails", "inconclusive")
_OPEN_ROWS = 12  # longer tables start collapsed


def _expected(result: Result) -> str:
    records = result.expectations
    if not records:
        return "the case states no expectations"
    unmet = [e["key"] for e in records if e["verdict"] != "met"]
    return "every expectation met" if not unmet else f"expectations not met: {', '.join(unmet)}"


def _about(certificate: Mapping[str, Any]) -> dict[str, Any]:
    claim = certificate.get("claim")
    statement = claim.get("statement", "") if isinstance(claim, Mapping) else str(claim or "")
    return {"kind": certificate.get("kind", ""), "statement": statement}


def _agent_table(agents: list[dict[str, Any]]) -> tuple[Sequence[str], list[Sequence[Any]]]:
    if not agents:
        return (), []
    columns = [k for k, v in agents[0].items() if not isinstance(v, list | dict)]
    return columns, [[a[c] for c in columns] for a in agents]


def _cell(value: Any) -> str:
    if isinstance(value, bool) or value is None:
        return {True: "yes", False: "no", None: "–"}[value]
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


def _html_table(columns: Sequence[str], rows: list[Sequence[Any]]) -> str:
    if not rows:
        return ""
    head = "".join(f"<th>{html.escape(str(c).replace('_', ' '))}</th>" for c in columns)
    body = "".join(
        "<tr>" + "".join(f"<td>{html.escape(_cell(v))}</td>" for v in row) + "</tr>" for row in rows
    )
    table = f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"
    if len(rows) <= _OPEN_ROWS:
        return table
    return f"<details><summary>{len(rows)} rows</summary>{table}</details>"


# --------------------------------------------------------------------------------------------
# inputs: plain objects and cases → the case-file data the loader validates


def _lists(value: Any) -> Any:
    """Arrays, numpy scalars and tuples as the plain lists and numbers of a case file."""
    if hasattr(value, "tolist"):
        return value.tolist()
    if isinstance(value, Mapping):
        return {k: _lists(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_lists(v) for v in value]
    return value


def _resolve(source: Any, tolerances: Mapping[str, Any] | None = None) -> tuple[Any, Any]:
    """``(Case, case data or None)`` of a case-like ``source``, ``tolerances`` merged into its
    ``tolerances:`` block; validated by the case-file loader."""
    from theory.core.case_file import Case, read_case_data, resolve_case_path
    from theory.kinds import parse_case

    extra = {k: v for k, v in (tolerances or {}).items() if v is not None}
    file = "<data>"
    if isinstance(source, Result):
        if source.case is None:
            raise TypeError(f"a {type(source).__name__} has no case to analyse")
        file = source.case.file  # messages keep naming the file the case came from
        source = source.case_data if source.case_data is not None else source.case
    if isinstance(source, Case):
        if not extra:
            return source, None
        if source.file == "<data>":
            raise ValueError(
                "tolerances can be changed only on a case with its data: pass the mapping or a "
                "path instead of the Case"
            )
        file, source = source.file, read_case_data(Path(source.file))
    elif isinstance(source, str | os.PathLike):
        path = resolve_case_path(source)
        file, source = str(path), read_case_data(path)
    elif not isinstance(source, Mapping):
        raise TypeError(
            "expected a case: a path, a bundled case name, a mapping in the case-file format, "
            f"a trackcert.load_case result or a trackcert result; got {type(source).__name__}"
        )
    data = _lists(source)
    if extra:
        data["tolerances"] = {**(data.get("tolerances") or {}), **extra}
    return parse_case(data, file=file), data


def _is_case(value: Any) -> bool:
    from theory.core.case_file import Case

    return isinstance(value, Case | Result | Mapping | str | os.PathLike)


def _refuse(function: str, **given: Any) -> None:
    """A TypeError naming the arguments that cannot go with a case."""
    extra = sorted(name for name, value in given.items() if value)
    if extra:
        raise TypeError(f"{function}(case) takes no {', '.join(extra)}: they are the case's")


def _case_mapping(name: str, source: str, kind: str, block: dict, tolerances: dict) -> dict:
    data: dict[str, Any] = {"name": name, "source": source, "kind": kind, kind: block}
    chosen = {k: v for k, v in tolerances.items() if v is not None}
    if chosen:
        data["tolerances"] = chosen
    return data


def _edges(graph: Any, n: int, directed: bool | None) -> tuple[list[list[int]], bool]:
    """1-based edges and the direction flag of a networkx graph or a 0-based edge list."""
    if hasattr(graph, "is_directed") and hasattr(graph, "edges"):
        if directed is not None and directed != graph.is_directed():
            raise ValueError(f"directed={directed} contradicts the graph ({type(graph).__name__})")
        directed, pairs = graph.is_directed(), list(graph.edges())
        outside = [v for v in graph.nodes if not (_is_index(v) and 0 <= v < n)]
        if outside:
            raise ValueError(
                f"graph node {outside[0]!r} is not a row of agents (nodes are 0-based row "
                f"indices 0..{n - 1})"
            )
    else:
        pairs = _lists(graph)
        if not isinstance(pairs, list) or not all(
            isinstance(p, list) and len(p) == 2 and all(map(_is_index, p)) for p in pairs
        ):
            raise ValueError(
                f"graph: expected a networkx graph or 0-based pairs [i, j]; got {graph!r}"
            )
    for i, j in pairs:
        if i == j:
            raise ValueError(f"graph has a self-loop at node {i} (w_ii > 0 is implied; drop it)")
        if not (0 <= i < n and 0 <= j < n):
            raise ValueError(f"graph edge ({i}, {j}) names a node outside 0..{n - 1}")
    return [[int(i) + 1, int(j) + 1] for i, j in pairs], bool(directed)


def _is_index(value: Any) -> bool:
    import numbers

    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


# --------------------------------------------------------------------------------------------
# the functions


def load_case(path: str | os.PathLike[str]) -> Any:
    """Load and validate a case file, or a bundled case by name.

    Parameters
    ----------
    path : str or path-like
        A YAML case file, or the name of a bundled case (``trackcert cases`` lists them).

    Returns
    -------
    Case
        The validated case, accepted by every function of this module.

    Raises
    ------
    CaseError
        Naming the file, the field, what was expected and what was found.
    """
    from theory.kinds import load_case as load

    return load(path)


def consensus_weights(graph: Any, rule: str = "metropolis", *, n: int | None = None) -> Any:
    r"""The named consensus weights on a graph, exactly as case files define them.

    ``metropolis``: :math:`w_{ij} = 1/(1 + \max(d_i, d_j))` on each edge and
    :math:`w_{ii} = 1 - \sum_j w_{ij}` (undirected graphs); ``uniform``:
    :math:`w_{ij} = 1/(d_i + 1)` for :math:`j \in N_i \cup \{i\}` (in-neighbours of a digraph).

    Parameters
    ----------
    graph : networkx.Graph, networkx.DiGraph or sequence of pairs
        Nodes are 0-based agent indices; a ``DiGraph`` edge ``(s, r)`` means ``s`` sends to ``r``.
    rule : {"metropolis", "uniform"}
        The weight rule.
    n : int, optional
        Number of agents (default: the graph's number of nodes; required for an edge list).

    Returns
    -------
    numpy.ndarray
        The ``n × n`` row-stochastic matrix, for :func:`dkf` or :func:`topology`.

    Raises
    ------
    ValueError
        For an unknown rule, Metropolis weights on a directed graph, or a node outside
        ``0..n-1``.
    """
    import numpy as np

    from theory.core.network import adjacency_from_edges, metropolis_weights, uniform_weights

    if n is None:
        if not hasattr(graph, "number_of_nodes"):
            raise ValueError("consensus_weights of an edge list needs n, the number of agents")
        n = graph.number_of_nodes()
    edges, directed = _edges(graph, n, None)
    hears = adjacency_from_edges(
        n, np.array(edges, dtype=int).reshape(-1, 2) - 1, directed=directed
    )
    if rule == "uniform":
        return uniform_weights(hears)
    if rule != "metropolis":
        raise ValueError(f"rule {rule!r} is not one of ['metropolis', 'uniform']")
    if directed:
        raise ValueError("Metropolis weights are defined for undirected graphs; use 'uniform'")
    return metropolis_weights(hears)


def topology(
    agents: Any,
    target: Any = None,
    graph: Any = None,
    weights: Any = "metropolis",
    T: float = 1.0,
    *,
    comm_range: float | None = None,
    directed: bool | None = None,
    rank_tol: float | None = None,
    inconclusive_factor: float | None = None,
    network_rank: bool = True,
    name: str = "network",
    source: str = "",
) -> TopologyResult:
    r"""Decide, for every agent, whether its distributed TDOA filter can localize the target.

    Agent ``i`` localizes the target iff the stacked TDOA Jacobians of the agents its
    information reaches have rank ``d`` (``rank O_i = 2 d``); decided exactly on the coordinates
    as given, with the paper's "≥ 4 connected non-coplanar agents" heuristic reported beside it,
    the mirror ambiguity of coplanar receivers, and the rank and detectability of the networked
    pair :math:`(W \otimes A, D_H)`. What ``trackcert topology`` runs.

    Parameters
    ----------
    agents : array_like or case
        ``N × d`` agent positions (``d`` = 2 or 3), or ``steps × N × d`` for moving agents.
        Or a whole case (path, bundled name, mapping, :func:`load_case` result or a result);
        then give no ``target`` and no ``graph``.
    target : array_like
        The target position (``d`` numbers, or ``steps × d``), where the Jacobians are evaluated.
    graph : networkx.Graph, networkx.DiGraph or sequence of pairs, optional
        Who exchanges estimates with whom; nodes are 0-based row indices of ``agents``. A
        ``DiGraph`` edge ``(s, r)`` means ``s`` sends to ``r``. Omit it with ``comm_range`` or an
        explicit ``weights`` matrix (whose support is then the graph).
    weights : {"metropolis", "uniform"} or array_like
        The consensus weights: a rule, or an ``N × N`` row-stochastic matrix, positive exactly
        on the graph's edges and the diagonal.
    T : float
        Ping period in seconds (> 0; the verdict holds for any ``T ≠ 0``).
    comm_range : float, optional
        Instead of ``graph``: agents closer than this distance communicate.
    directed : bool, optional
        Whether an edge list is directed (a networkx graph says so itself).
    rank_tol : float, optional
        Relative rank tolerance (default ``theory.core.observability.RANK_TOL``).
    inconclusive_factor : float, optional
        A decision whose margin is below this factor is inconclusive (default
        ``theory.core.tolerances.INCONCLUSIVE_FACTOR``).
    network_rank : bool
        Rank the whole networked pair too (cubic in a component's size; the per-agent verdicts
        do not need it).
    name, source : str
        The case's name and where it comes from (kept by :meth:`Result.to_case`).

    Returns
    -------
    TopologyResult

    Raises
    ------
    CaseError
        If an input is invalid (the message names the case-file field it becomes, e.g.
        ``tdoa.agents``; ids in it are 1-based).
    TypeError
        If a case is given together with ``target`` or ``graph``.

    References
    ----------
    seed 000 §4.2.2, eqs. (4.24), (4.36), Thm 4.2.3, Cor. 4.2.4; seed 001 Theorem 1.

    Examples
    --------
    >>> import networkx as nx, trackcert
    >>> agents = [[-7, 3, 5], [1, -2, -5], [5, -1, 4], [7, 4, -2]]
    >>> trackcert.topology(agents, [17, -5, -15], nx.path_graph(4)).verdict
    True
    """
    from theory.tdoa.observability.trajectory import topology_report

    tolerances = {"rank_tol": rank_tol, "inconclusive_factor": inconclusive_factor}
    if _is_case(agents):
        _refuse(
            "topology",
            target=target is not None,
            graph=graph is not None,
            weights=not (isinstance(weights, str) and weights == "metropolis"),
            T=T != 1.0,
            comm_range=comm_range is not None,
            directed=directed is not None,
            name=name != "network",
            source=source != "",
        )
        case, data = _resolve(agents, tolerances)
    else:
        block: dict[str, Any] = {"T": T, "agents": _lists(agents), "target": _lists(target)}
        if graph is not None:
            n = (
                len(block["agents"][-1])
                if _is_trajectory(block["agents"])
                else len(block["agents"])
            )
            block["edges"], block["directed"] = _edges(graph, n, directed)
        elif directed is not None:
            block["directed"] = directed
        if comm_range is not None:
            block["comm_range"] = comm_range
        block["weights"] = _lists(weights)
        case, data = _resolve(_case_mapping(name, source, "tdoa", block, tolerances))
    return TopologyResult(topology_report(case, network_rank=network_rank), case, data)


def _is_trajectory(agents: Any) -> bool:
    return (
        bool(agents)
        and isinstance(agents[0], list)
        and bool(agents[0])
        and isinstance(agents[0][0], list)
    )


def dkf(
    A: Any,
    C: Any = None,
    W: Any = None,
    Q: Any = None,
    R: Any = None,
    *,
    L: Any = None,
    order: str = "consensus-then-filter",
    self_weight: bool = True,
    solver: str = "CLARABEL",
    rank_tol: float | None = None,
    lmi_margin: float | None = None,
    cert_tol: float | None = None,
    value_tol: float | None = None,
    name: str = "dkf",
    source: str = "",
) -> DkfResult:
    r"""S-detectability and the necessary conditions of a consensus Kalman filter.

    The network runs :math:`x_{k+1} = A x_k + w_k`, agent ``i`` measures
    :math:`y_i = C_i x + v_i` and fuses its neighbours' estimates with the row-stochastic ``W``
    (seed 000 eqs. (5.1)–(5.4)). Decides S-detectability (Def. 5.2.4) by an LMI whose answer is
    re-verified as an exact certificate, checks Thm 5.2.10's self-weight bounds
    :math:`w_{ii} < 1 / r(A_i^u)^2`, the source components and blind sets, and runs the coupled
    Riccati iteration. What ``trackcert dkf`` runs.

    Parameters
    ----------
    A : array_like, control.StateSpace or case
        The ``n × n`` system matrix; or a discrete-time ``control.StateSpace`` (its ``A`` and
        ``C`` are used, ``B`` and ``D`` are not: the noise enters through ``Q``); or a whole
        case (then give no other array).
    C : sequence of array_like, or sequence of output selections
        One ``p_i × n`` measurement matrix per agent (``[]`` for an agent without a sensor). With
        a ``StateSpace``: per agent, the 0-based indices of the outputs it measures.
    W : array_like
        ``N × N`` row-stochastic consensus weights, ``w_ii > 0`` (directed allowed).
    Q : array_like
        ``n × n`` process-noise covariance, positive definite.
    R : sequence of array_like, or array_like
        One ``p_i × p_i`` positive-definite covariance per agent; with a ``StateSpace`` also the
        ``p × p`` covariance of all outputs, from which each agent's block is taken.
    L : sequence of array_like, optional
        One ``n × p_i`` gain per agent to check instead of the certificate's.
    order : {"consensus-then-filter", "filter-then-consensus"}
        The order of the consensus and filter steps (eqs. (5.3)–(5.4), or App. C.3).
    self_weight : bool
        Bisect each agent's largest S-detectable self-weight (``max_self_weight``; slower).
    solver : {"CLARABEL", "SCS"}
        The conic solver of the LMI (its answer is re-checked exactly either way).
    rank_tol, lmi_margin, cert_tol, value_tol : float, optional
        The named tolerances (defaults in ``theory.core.tolerances``), kept in the case.
    name, source : str
        The case's name and where it comes from.

    Returns
    -------
    DkfResult

    Raises
    ------
    CaseError
        If a matrix is invalid (the message names its case-file field, e.g. ``dkf.W``).
    ValueError
        If a ``StateSpace`` is continuous-time or an output index is out of range.
    TypeError
        If a case is given together with matrices.

    References
    ----------
    seed 000 Def. 5.2.4, Thm 5.2.10, eqs. (5.1)–(5.9), App. A, C.
    """
    from theory.consensus.analysis import dkf_report
    from theory.registry import claims_for

    tolerances = {
        "rank_tol": rank_tol,
        "lmi_margin": lmi_margin,
        "cert_tol": cert_tol,
        "value_tol": value_tol,
    }
    if _is_case(A):
        _refuse(
            "dkf",
            C=C is not None,
            W=W is not None,
            Q=Q is not None,
            R=R is not None,
            L=L is not None,
            order=order != "consensus-then-filter",
            name=name != "dkf",
            source=source != "",
        )
        case, data = _resolve(A, tolerances)
    else:
        if _is_state_space(A):
            A, C, R = _from_state_space(A, C, R)
        block = {
            "A": _lists(A),
            "C": _per_agent(C),
            "W": _lists(W),
            "Q": _lists(Q),
            "R": _per_agent(R),
            "order": order,
        }
        if L is not None:
            block["L"] = _per_agent(L)
        case, data = _resolve(_case_mapping(name, source, "dkf", block, tolerances))
    report = dkf_report(case, claims_for(case), search_self_weight=self_weight, solver=solver)
    return DkfResult(report, case, data)


def _per_agent(matrices: Any) -> Any:
    """Per-agent matrices as nested lists (an empty matrix becomes ``[]``)."""
    if matrices is None or isinstance(matrices, str | Mapping):
        return matrices
    return [_lists(m) for m in matrices]


def _is_state_space(value: Any) -> bool:
    import sys

    control = sys.modules.get("control")
    return control is not None and isinstance(value, control.StateSpace)


def _from_state_space(system: Any, outputs: Any, R: Any) -> tuple[Any, list, Any]:
    """``(A, C_i, R_i)`` of a discrete StateSpace and per-agent output selections."""
    import numpy as np

    if not system.isdtime(strict=True):
        raise ValueError(
            "dkf needs a discrete-time StateSpace (dt > 0 or True); discretize it first, "
            "e.g. control.c2d(sys, Ts)"
        )
    p = system.C.shape[0]
    picks = [[i] if _is_index(i) else list(i) for i in outputs]
    for agent, chosen in enumerate(picks):
        bad = [i for i in chosen if not (_is_index(i) and 0 <= i < p)]
        if bad:
            raise ValueError(f"outputs[{agent}]: {bad[0]!r} is not an output index in 0..{p - 1}")
    C = [np.asarray(system.C)[chosen, :] for chosen in picks]
    try:
        full = np.asarray(R, dtype=float)
    except (TypeError, ValueError):  # ragged: one matrix per agent
        full = None
    if full is not None and full.shape == (p, p):
        R = [full[np.ix_(chosen, chosen)] for chosen in picks]
    return np.asarray(system.A), C, R


def iss(
    config: Any = None, /, *, margin_tol: float | None = None, name: str = "pursuit", **fields: Any
) -> IssResult:
    """ISS Lyapunov analysis of range-based cooperative pursuit (seed 003, corrected).

    Checks the conditions of Theorems 1–2 as corrected in ``docs/errata.md`` (Δ of full row
    rank, which needs ε₁ ≠ 0; K positive definite; a strongly connected graph; Lemma 1's left
    eigenvector) exactly where they are exact, and reports the decay rates and ISS gains of the
    pursuit and coordination loops. What ``trackcert iss`` runs.

    Parameters
    ----------
    config : case or mapping, optional
        A pursuit case (path, bundled name, :func:`load_case` result, a result, or a mapping
        with ``kind: pursuit``), or the fields of a ``pursuit:`` block as a mapping. Omit it to
        give the fields as keywords.
    margin_tol : float, optional
        Relative margin under which a condition is inconclusive (kept in the case's
        ``tolerances``).
    name : str
        The case's name when it is built from fields.
    **fields
        The ``pursuit:`` block's fields (``dim``, ``controller``, ``omega_bar``, ``epsilon``,
        ``K_p``, ``k_gamma``, ``k_c``, ``trackers``, ``edges`` (1-based ``[s, r]``, as in seed
        003), ``target``, ``dekf``), arrays allowed; see ``theory/pursuit/case.py``.

    Returns
    -------
    IssResult

    Raises
    ------
    TypeError
        If a field name is unknown, or fields are given with ``config``.
    CaseError
        If a field's value is invalid (the message names it, e.g. ``pursuit.k_gamma``).

    References
    ----------
    seed 003 Theorems 1–2, eqs. (22), (45)–(50), (66); Lemmas 1 and 3.
    """
    from theory.pursuit.case import FIELDS
    from theory.pursuit.iss import iss_report

    unknown = sorted(set(fields) - set(FIELDS))
    if unknown:
        raise TypeError(f"iss() got unknown fields {unknown}; pursuit fields are {list(FIELDS)}")
    if config is not None and fields:
        raise TypeError("iss() takes a config or fields, not both")
    tolerances = {"margin_tol": margin_tol}
    if config is None or (isinstance(config, Mapping) and "kind" not in config):
        block = _lists(dict(config or fields))
        case, data = _resolve(_case_mapping(name, "", "pursuit", block, tolerances))
    else:
        _refuse("iss", name=name != "pursuit")
        case, data = _resolve(config, tolerances)
    return IssResult(iss_report(case), case, data)


def simulate(
    case: Any,
    *,
    runs: int | None = None,
    seed: int | None = None,
    steps: int | None = None,
    folder: str | os.PathLike[str] | None = None,
    figures: bool = True,
    workers: int = 1,
) -> SimulationResult | PfResult:
    """Simulate a case's closed loop over Monte Carlo runs; write data and figures.

    ``kind: tdoa-sim`` runs the network filters of seed 000 §4.2 on moving agents, ``dkf`` the
    consensus Kalman filter of ch. 5, ``pursuit`` seed 003's trackers with the DEKF, ``pf`` the
    particle filter (as :func:`pf`). A static 3-D ``kind: tdoa`` scene (e.g. a
    :func:`topology` result) is simulated as it was checked: the agents hold their positions
    (``b: .inf``), the target starts at rest, the network and weights are the scene's
    (``theory.tdoa.case.scene_simulation``). What ``trackcert simulate`` runs.

    Parameters
    ----------
    case : case
        A path, bundled case name, mapping in the case-file format, :func:`load_case` result or
        a result.
    runs : int, optional
        Monte Carlo runs (default 1; ``pf`` cases: the case's own).
    seed : int, optional
        Root seed; run ``i`` uses child ``i`` of ``SeedSequence(seed)`` (default 0; ``pf``: the
        case's).
    steps : int, optional
        Override the case's number of steps (not for ``pf`` cases).
    folder : str or path-like, optional
        Where ``runs.npz``, the CSV tables, the figures and ``summary.json`` go (replaced whole
        if it holds an earlier simulation). Default: a new temporary folder, kept.
    figures : bool
        Draw the PNG figures.
    workers : int
        Local worker processes (the results are the same for any count).

    Returns
    -------
    SimulationResult or PfResult

    Raises
    ------
    CaseError
        If the kind is not simulated, a count exceeds its limit, or ``folder`` holds other
        files.
    """
    import tempfile

    from theory.core.validation import check_count, positive_int
    from theory.kinds import simulator_for
    from theory.sim.simulate import simulate_case

    loaded, data = _resolve(case)
    if loaded.kind == "pf":
        if steps is not None:
            raise TypeError("simulate() of a pf case takes no steps (the case sets them)")
        return pf(case, runs=runs, seed=seed, folder=folder, workers=workers, figures=figures)
    if loaded.kind == "tdoa":
        from theory.tdoa.case import scene_simulation

        sim = {
            "name": loaded.name,
            "source": loaded.source,
            "kind": "tdoa-sim",
            "tdoa-sim": scene_simulation(loaded.spec),
        }
        loaded, data = _resolve(sim)
    for option, value in (("runs", runs), ("steps", steps)):
        if value is not None:
            check_count(option, positive_int(value, option), option)
    chosen = simulator_for(loaded, steps, runs or 1)
    where = Path(folder) if folder is not None else Path(tempfile.mkdtemp(prefix="trackcert-"))
    simulation = simulate_case(
        loaded,
        chosen,
        folder=where,
        runs=runs or 1,
        seed=seed or 0,
        workers=workers,
        figures=figures,
    )
    return SimulationResult(simulation, loaded, data)


def pf(
    case: Any,
    *,
    runs: int | None = None,
    seed: int | None = None,
    folder: str | os.PathLike[str] | None = None,
    workers: int = 1,
    figures: bool = True,
) -> PfResult:
    """Run seed 002's distributed TDOA particle filter on a ``kind: pf`` case, with its claims.

    Each filtering node runs a particle filter on its own TDOA measurements, shares ``m``
    particles with its neighbours (seed 002 §3.2), and the claims judge convergence, the value of
    the consensus step and the learned motion model against the case's ``expect`` block. What
    ``trackcert pf`` runs.

    Parameters
    ----------
    case : case
        A ``kind: pf`` case (path, bundled name, mapping, :func:`load_case` result or result).
    runs : int, optional
        Monte Carlo runs (default: the case's ``runs``).
    seed : int, optional
        Base seed (default: the case's ``seed``).
    folder : str or path-like, optional
        Where ``pf.json`` and the figures go (replaced whole); default: write nothing.
    workers : int
        Local worker processes (the results are the same for any count).
    figures : bool
        Draw the PNG figures into ``folder``.

    Returns
    -------
    PfResult

    Raises
    ------
    CaseError
        If the case is not ``kind: pf``, or ``runs`` exceeds the limits.

    References
    ----------
    seed 002 §3.2–§3.3, eqs. (3.9)–(3.11); Figs. 3.2–3.6.
    """
    from theory.core.parallel import engine
    from theory.particle.case import check_pf_runs
    from theory.particle.report import pf_report

    loaded, data = _resolve(case)
    if runs is not None:
        check_pf_runs(loaded, runs, "runs")
    with engine(workers) as runner:
        report = pf_report(
            loaded,
            runs=runs,
            seed=seed,
            out=None if folder is None else Path(folder),
            runner=runner,
            figures=figures,
        )
    return PfResult(report, loaded, data)


def certify(result: Any, *, seed: int = 0) -> Certificate:
    """Every certificate the case supports, each re-verified by ``proofs_check`` as written.

    ``tdoa``: generic-rank certificates of the network and of each agent's observability;
    ``dkf``: S-detectability with the LMI witness's gains (and the case's own gains); ``pursuit``:
    the ISS certificate. What ``trackcert certify`` writes.

    Parameters
    ----------
    result : Result or case
        A result of :func:`topology`, :func:`dkf` or :func:`iss`, or a case.
    seed : int
        Seed of the random evaluation points (recorded in the certificates).

    Returns
    -------
    Certificate
        ``verdict`` False (no certificate) when the property is decided false, None when no
        certificate could be made; ``reason`` says which.
    """
    from theory.core.errors import InconclusiveError, PropertyFails
    from theory.registry import certificate_bundle

    case, data = _resolve(result)
    try:
        return Certificate(certificate_bundle(case, seed=seed), case, data)
    except PropertyFails as error:
        return Certificate(None, case, data, reason=f"the property fails: {error}", refuted=True)
    except InconclusiveError as error:
        return Certificate(None, case, data, reason=str(error))


def check(certificate: Any, *, time_limit: float | None = None) -> CheckResult:
    """Re-verify a certificate in exact rational arithmetic with ``proofs_check``.

    ``proofs_check`` imports nothing from trackcert's library; it re-derives every inequality
    from the data and the witness and trusts no number the certificate states about itself.
    What ``trackcert check`` runs.

    Parameters
    ----------
    certificate : Certificate, dict, str or path-like
        A :func:`certify` result, a certificate document, or a certificate JSON file.
    time_limit : float, optional
        Seconds of exact arithmetic before refusing (default ``proofs_check``'s).

    Returns
    -------
    CheckResult

    Raises
    ------
    proofs_check.MalformedError
        A ``ValueError``: the document is not a certificate ``proofs_check`` accepts to check.
    """
    import json

    import proofs_check
    import proofs_check.parse
    from proofs_check.deadline import DEFAULT_SECONDS

    limit = DEFAULT_SECONDS if time_limit is None else time_limit
    if isinstance(certificate, Certificate):
        if certificate.report is None:
            raise ValueError(f"nothing to check: {certificate.reason}")
        certificate = certificate.report
    if isinstance(certificate, Mapping):
        text = json.dumps(certificate, ensure_ascii=False)
        verdict = proofs_check.check_certificate(proofs_check.parse.loads(text), time_limit=limit)
    elif isinstance(certificate, str | os.PathLike):
        verdict = proofs_check.check_file(os.fspath(certificate), time_limit=limit)
    else:
        raise TypeError(f"expected a certificate, a document or a file; got {type(certificate)}")
    return CheckResult(verdict)
