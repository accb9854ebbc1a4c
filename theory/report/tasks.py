"""What a worker runs for the report: claims of one case under a CPU-time limit, their records,
and the independent checker's verdict on their certificates.

A :class:`CheckTask` is a small picklable payload — claim ids, the case, the report's seed, the
time limit — and :func:`run_task` runs it on a Dask worker (or in this process with ``--workers
1``): it looks each claim up in its own process's registry (:func:`theory.registry.get_claim`),
runs it with its derived seed (:func:`derive_seed`) under :class:`time_limit`, and returns plain
data (:class:`TaskOutput`): the records, the reason of a claim that does not apply, the wall and
CPU time of each check, the bytes of the figures drawn (so the report can be written on a machine
that does not share the worker's disk), the checker's verdict on each certificate document
(:func:`check_document`: certificates are re-verified in parallel, not after all the checks) and
the worker's peak memory. A check that raises, runs past its limit or returns something malformed
is an ``inconclusive`` record of method ``none``: one check never stops the report. Claims of a
case registered with ``shares_work`` share one task and one :class:`RunCache` (:func:`plan_tasks`).

A worker started apart (``dask worker ADDRESS --preload theory.report.tasks``) imports every
claim module as it starts (:func:`dask_setup`), so a cluster kept running between commands pays
the imports once (docs/parallel.md).
"""

from __future__ import annotations

import ctypes
import hashlib
import importlib
import json
import os
import re
import resource
import socket
import subprocess
import sys
import tempfile
import threading
import time
import traceback
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from types import TracebackType
from typing import Any

import theory
from theory.core.case_file import Case
from theory.core.claims import (
    DOCUMENT_KEY,
    MODEL_CASE,
    Claim,
    ClaimResult,
    Context,
    Method,
    NotApplicable,
    RunCache,
    Status,
)
from theory.core.jsonable import canonical
from theory.registry import domains, get_claim

__all__ = [
    "MODEL_CASE",
    "RESULT_FIELDS",
    "CertificateChecker",
    "CheckOutput",
    "CheckTask",
    "Record",
    "TaskOutput",
    "TimeLimitExceeded",
    "certificate_bytes",
    "check_document",
    "check_with_cli",
    "clock_name",
    "dask_setup",
    "derive_seed",
    "document_name",
    "enforceable",
    "failed_task",
    "failure",
    "paper_of",
    "plan_tasks",
    "prechecked",
    "process_name",
    "run_batch",
    "run_task",
    "slug",
    "time_limit",
    "worker_modules",
]


# ------------------------------------------------------------------------------------ records
@dataclass(frozen=True)
class Record:
    """One line of the report: a claim's result on a case (or the failure to get one).

    ``result`` has its evidence, margin and tolerances made plain JSON data; its fields read
    through the record (``record.status``; ``record.id`` is its ``claim``). ``paper`` is the seed
    paper (:func:`paper_of`), ``seed`` the derived seed of a ``seeded`` claim (else ``None``).
    """

    result: ClaimResult
    source: str
    statement: str
    paper: str
    seed: int | None = None

    @property
    def id(self) -> str:
        """The claim id (``result.claim``)."""
        return self.result.claim

    def __getattr__(self, name: str) -> Any:
        if name in RESULT_FIELDS:
            return getattr(self.result, name)
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def with_evidence(self, evidence: dict[str, Any]) -> Record:
        """The same record with ``evidence`` (plain JSON) in place of the result's."""
        return replace(self, result=replace(self.result, evidence=evidence))

    def to_json(self) -> dict[str, Any]:
        """The result's record (:meth:`ClaimResult.to_json`) with statement, paper and seed."""
        return {
            **self.result.to_json(self.source),
            "statement": self.statement,
            "paper": self.paper,
            "seed": self.seed,
        }


RESULT_FIELDS = (
    "case",
    "method",
    "status",
    "finding",
    "message",
    "margin",
    "tolerance",
    "evidence",
    "figures",
)
"""Fields of :class:`~theory.core.claims.ClaimResult` read through a :class:`Record`."""


def paper_of(claim_id: str, source: str) -> str:
    """The seed paper of a claim: ``seed000.…`` names ``000``; else the first ``seed NNN`` of its
    ``source``; else ``other``."""
    match = re.match(r"seed(\d{3})\b", claim_id) or re.search(r"seed\s*(\d{3})", source)
    return match.group(1) if match else "other"


def derive_seed(seed: int, claim_id: str, case: str) -> int:
    """The seed one claim receives on one case: the first 4 bytes (big-endian) of SHA-256 of
    ``"{seed}:{claim_id}:{case}"`` (stable across runs, platforms and the order of the checks)."""
    digest = hashlib.sha256(f"{seed}:{claim_id}:{case}".encode()).digest()
    return int.from_bytes(digest[:4], "big")


def slug(text: str) -> str:
    """``text`` as one safe path component (runs of other characters become ``_``)."""
    return re.sub(r"[^A-Za-z0-9._-]+", "_", text).strip("_") or "_"


# --------------------------------------------------------------------------- the time limit
class TimeLimitExceeded(BaseException):
    """A check used up its CPU-time limit.

    A :class:`BaseException`, like :class:`KeyboardInterrupt`, so that a check's own ``except
    Exception`` cannot swallow it. It is raised asynchronously as a class, so the limit travels
    as the class attribute ``seconds`` of a subclass made per limit (:func:`_expired`).
    """

    seconds: float = 0.0

    def __init__(self, seconds: float | None = None) -> None:
        if seconds is not None:
            self.seconds = seconds
        super().__init__(f"the check used up its CPU-time limit of {self.seconds:g} s")


def _expired(seconds: float) -> type[TimeLimitExceeded]:
    return type("TimeLimitExceeded", (TimeLimitExceeded,), {"seconds": seconds})


def enforceable() -> bool:
    """Whether :class:`time_limit` can interrupt a check (``PyThreadState_SetAsyncExc``)."""
    return hasattr(ctypes, "pythonapi") and hasattr(ctypes.pythonapi, "PyThreadState_SetAsyncExc")


def clock_name() -> str:
    """What :class:`time_limit` counts here: ``thread CPU time``, else ``process CPU time``."""
    return "thread CPU time" if hasattr(time, "pthread_getcpuclockid") else "process CPU time"


def _cpu_clock(thread_id: int) -> Callable[[], float]:
    """A function reading the CPU seconds of thread ``thread_id`` (readable from any thread)."""
    try:
        clock = time.pthread_getcpuclockid(thread_id)
    except (AttributeError, OSError):
        return time.process_time
    return lambda: time.clock_gettime(clock)


class time_limit:  # noqa: N801 (used as a context manager, like contextlib's)
    """Raise :class:`TimeLimitExceeded` in the ``with`` block once it has used ``seconds`` of CPU
    (``None``, or a Python where :func:`enforceable` is false: no limit).

    The limit is on work, not on the wall clock: it counts the CPU time of the thread running the
    block (its POSIX per-thread clock; lacking one, the whole process's, which is only stricter),
    so a check waiting for a core that other processes hold is not stopped — on a loaded
    two-core machine a check needing 40 s of CPU may take 300 s of wall time and still finish.
    A watcher thread sleeps for the CPU budget still unspent (a thread cannot use more CPU than
    wall time, so it never wakes late), reads the clock again and, once the budget is spent,
    raises the exception in the block's thread (``PyThreadState_SetAsyncExc``): one mechanism for
    the main thread of ``--workers 1`` and the thread a Dask task runs in (where ``SIGALRM``
    cannot be used). Native code is interrupted when it next returns to Python; work handed to
    other processes (the certificate checker) is not counted; a deadlock is not stopped. When the
    block exits first, an exception the watcher scheduled meanwhile is received and dropped
    before the block is left (:func:`_absorb_pending`), so nothing is raised after it.
    """

    def __init__(self, seconds: float | None) -> None:
        self.seconds = seconds
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._watcher: threading.Thread | None = None
        self._thread_id = 0
        self._open = False
        self._fired = False

    def __enter__(self) -> time_limit:
        if self.seconds is None or not enforceable():
            return self
        self._thread_id = threading.get_ident()
        clock = _cpu_clock(self._thread_id)
        self._open = True
        self._watcher = threading.Thread(
            target=self._watch, args=(clock, clock()), name="trackcert-time-limit", daemon=True
        )
        self._watcher.start()
        return self

    def _watch(self, clock: Callable[[], float], start: float) -> None:
        budget = float(self.seconds or 0.0)
        while not self._stop.wait(max(budget - (clock() - start), 0.0)):
            if clock() - start >= budget:
                self._expire(budget)
                return

    def _expire(self, budget: float) -> None:
        with self._lock:
            if self._open:
                self._fired = True
                ctypes.pythonapi.PyThreadState_SetAsyncExc(
                    ctypes.c_ulong(self._thread_id), ctypes.py_object(_expired(budget))
                )

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        trace: TracebackType | None,
    ) -> None:
        if self._watcher is None:
            return
        with self._lock:
            self._open = False
        delivered = kind is not None and issubclass(kind, TimeLimitExceeded)
        if self._fired and not delivered:
            _absorb_pending()
        self._stop.set()
        self._watcher.join()  # returns at once: the watcher is stopped or has fired
        self._watcher = None


def _absorb_pending(seconds: float = 0.1) -> None:
    """Receive, here, a :class:`TimeLimitExceeded` scheduled just as the block ended, and drop it.

    The exception is raised at the interpreter's next check (every loop iteration), so this loop
    receives it at once. It is never *withdrawn* (``PyThreadState_SetAsyncExc(id, NULL)``):
    CPython would leave its "asynchronous exception pending" signal set with nothing to raise,
    and every later instruction of the thread would take the slow path (a hypothesis search
    after it ran about 1000× slower). If the block swallowed it, the loop runs out after
    ``seconds``.
    """
    end = time.monotonic() + seconds
    try:
        while time.monotonic() < end:
            pass
    except TimeLimitExceeded:
        return


# ------------------------------------------------------------------------------ certificates
CHECK_TIMEOUT = 300.0
"""Seconds allowed to the checker on one certificate before it counts as inconclusive."""

CertificateChecker = Callable[[Path, Path], dict[str, Any]]
"""``checker(relative_path, report_dir) -> verdict`` (:func:`check_with_cli`)."""


def certificate_bytes(document: dict) -> bytes:
    """The file the report writes for a certificate ``document``: UTF-8 JSON, indent 1, newline."""
    return (json.dumps(document, indent=1, ensure_ascii=False) + "\n").encode("utf-8")


def document_name(document: dict) -> str:
    """The file name of a certificate document: ``<kind>.json``."""
    return f"{slug(str(document.get('kind', 'certificate')))}.json"


def check_document(document: dict) -> tuple[str, dict[str, Any]]:
    """The SHA-256 of :func:`certificate_bytes` of ``document`` and :func:`check_with_cli`'s
    verdict on those bytes, written to a temporary folder (where the claim's task runs)."""
    content = certificate_bytes(document)
    name = Path(document_name(document))
    with tempfile.TemporaryDirectory(prefix="trackcert-certificate-") as folder:
        (Path(folder) / name).write_bytes(content)
        verdict = check_with_cli(name, Path(folder))
    return hashlib.sha256(content).hexdigest(), verdict


def prechecked(verdicts: Mapping[str, dict[str, Any]]) -> CertificateChecker:
    """A checker reusing ``verdicts`` (:func:`check_document`'s, by the SHA-256 of the bytes
    checked) for a file with those bytes, its ``command`` naming the file; any other file is
    checked now."""

    def checker(relative: Path, out_dir: Path) -> dict[str, Any]:
        digest = hashlib.sha256((out_dir / relative).read_bytes()).hexdigest()
        if digest not in verdicts:
            return check_with_cli(relative, out_dir)
        return {**verdicts[digest], "command": _command_line(relative)}

    return checker


def check_with_cli(relative: Path, out_dir: Path) -> dict[str, Any]:
    """The independent checker's verdict, ``python -m proofs_check RELATIVE --json`` run in
    ``out_dir`` (what ``trackcert check`` runs, without the library's start-up).

    Returns ``command``, ``exit_code``, ``valid`` (``None`` when the checker gave no verdict) and
    either ``checks`` (the checker's list) or ``error`` (its last words, e.g. a timeout).
    """
    command = [relative.as_posix(), "--json"]
    root = str(Path(theory.__file__).resolve().parent.parent)
    inherited = [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([root, *inherited]))
    shown = _command_line(relative)
    try:
        checker = [sys.executable, "-m", "proofs_check", *command]
        done = subprocess.run(
            checker, cwd=out_dir, env=env, capture_output=True, text=True, timeout=CHECK_TIMEOUT
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
    return f"python -m proofs_check {relative.as_posix()} --json"


# ------------------------------------------------------------------------------------- tasks
@dataclass(frozen=True)
class CheckTask:
    """Claims (ids, looked up on the worker) to run in order on one case (``None``: the model
    claims), with the report's seed, the time limit of each check and whether to draw."""

    claims: tuple[str, ...]
    case: Case | None
    seed: int
    seconds: float | None
    figures: bool

    @property
    def case_name(self) -> str:
        """The case's name (``-`` for model claims)."""
        return MODEL_CASE if self.case is None else self.case.name


@dataclass(frozen=True)
class CheckOutput:
    """What one claim returned on the task's case.

    ``not_applicable`` is ``None`` when it returned results, else the reason it gave (``""``:
    none); ``figures`` the drawn files' bytes by name ``<claim>/<case>/<file>`` (the records name
    them so); ``certificate_checks`` the checker's verdicts by SHA-256 (:func:`check_document`);
    ``started`` the ``time.time()`` it began where it ran (``None``: never ran).
    """

    claim: str
    case: str
    records: tuple[Record, ...]
    not_applicable: str | None
    wall_seconds: float
    cpu_seconds: float
    figures: dict[str, bytes]
    certificate_checks: dict[str, dict[str, Any]] = field(default_factory=dict)
    started: float | None = None


@dataclass(frozen=True)
class TaskOutput:
    """A finished task: one output per claim, the ``host:pid`` that ran it, its peak memory."""

    checks: tuple[CheckOutput, ...]
    worker: str
    peak_rss: int


def plan_tasks(
    checks: Sequence[tuple[Claim, Case | None]],
    *,
    seed: int,
    seconds: float | None,
    figures: bool,
) -> list[CheckTask]:
    """The tasks running ``checks`` (in report order): per case, one task for the claims that
    share work (where the first of them is), one task for each other claim."""
    tasks: list[CheckTask] = []
    sharing: dict[str, int] = {}
    for claim, case in checks:
        name = MODEL_CASE if case is None else case.name
        if claim.shares_work and name in sharing:
            task = tasks[sharing[name]]
            tasks[sharing[name]] = replace(task, claims=(*task.claims, claim.id))
            continue
        if claim.shares_work:
            sharing[name] = len(tasks)
        tasks.append(CheckTask((claim.id,), case, seed, seconds, figures))
    return tasks


def worker_modules() -> tuple[str, ...]:
    """The modules a worker imports to run any check: this one and every domain's registry (the
    engine's ``preload``, :func:`theory.core.parallel.engine`)."""
    return (__name__, *(domain.__name__ for domain in domains()))


def dask_setup(worker: Any) -> None:
    """Import :func:`worker_modules` as a Dask worker starts (``--preload theory.report.tasks``)."""
    for module in worker_modules():
        importlib.import_module(module)


def run_task(task: CheckTask) -> TaskOutput:
    """Run every claim of ``task`` on its case, one :class:`RunCache` shared between them; a
    claim's failure is an ``inconclusive`` record, never an exception."""
    cache = RunCache()
    with tempfile.TemporaryDirectory(prefix="trackcert-task-") as folder:
        root = Path(folder) if task.figures else None
        checks = tuple(_check(claim_id, task, cache, root) for claim_id in task.claims)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    return TaskOutput(checks, process_name(), peak)


def run_batch(batch: Sequence[CheckTask]) -> tuple[TaskOutput, ...]:
    """:func:`run_task` of each task of ``batch``, in order (one engine task)."""
    return tuple(run_task(task) for task in batch)


def process_name() -> str:
    """``host:pid`` of this process (names the worker a check ran on)."""
    return f"{socket.gethostname()}:{os.getpid()}"


def failed_task(task: CheckTask, claims: dict[str, Claim], error: BaseException) -> TaskOutput:
    """The output of a task that never returned (its worker died, its payload did not pickle…):
    every check an ``inconclusive`` record saying why."""
    name = task.case_name
    outputs = []
    for claim_id in task.claims:
        claim = claims[claim_id]
        record = failure(claim, name, error, _recorded_seed(claim, task))
        outputs.append(CheckOutput(claim_id, name, (record,), None, 0.0, 0.0, {}))
    return TaskOutput(tuple(outputs), "", 0)


def failure(claim: Claim, case: str, error: BaseException, seed: int | None) -> Record:
    """An ``inconclusive`` record of method ``none`` saying why ``claim`` gave no result on
    ``case`` (a :class:`TimeLimitExceeded` says so plainly)."""
    kind = type(error).__name__
    message = (
        str(error)
        if isinstance(error, TimeLimitExceeded)
        else f"the check failed to run: {kind}: {error}"
    )
    evidence = {"error": {"type": kind, "message": str(error), "where": _where(error)}}
    result = ClaimResult(
        Status.INCONCLUSIVE, Method.NONE, evidence, message=message, claim=claim.id, case=case
    )
    return _wrap(claim, result, seed)


def _check(claim_id: str, task: CheckTask, cache: RunCache, root: Path | None) -> CheckOutput:
    name = task.case_name
    began, started, cpu = time.time(), time.perf_counter(), time.process_time()
    try:
        claim = get_claim(claim_id)
    except KeyError as error:
        missing = Claim(claim_id, "", "", (), lambda case, ctx: [])
        record = failure(missing, name, error, None)
        return CheckOutput(claim_id, name, (record,), None, 0.0, 0.0, {})
    folder = None if root is None else root / slug(claim.id) / slug(name)
    try:
        records = _run_one(claim, task, cache, folder)
        reason = None if records else ""
    except NotApplicable as why:
        records, reason = [], str(why)
    wall, cpu = time.perf_counter() - started, time.process_time() - cpu
    records, figures = _ship_figures(records, root)
    verdicts = dict(
        check_document(r.evidence[DOCUMENT_KEY])
        for r in records
        if isinstance(r.evidence.get(DOCUMENT_KEY), dict)
    )
    return CheckOutput(claim_id, name, tuple(records), reason, wall, cpu, figures, verdicts, began)


def _recorded_seed(claim: Claim, task: CheckTask) -> int | None:
    """The claim's derived seed, recorded for a ``seeded`` claim only."""
    return derive_seed(task.seed, claim.id, task.case_name) if claim.seeded else None


def _run_one(claim: Claim, task: CheckTask, cache: RunCache, folder: Path | None) -> list[Record]:
    name = task.case_name
    seed = _recorded_seed(claim, task)
    ctx = Context(cache, derive_seed(task.seed, claim.id, name), folder)
    try:
        with time_limit(task.seconds):
            results = claim.run(task.case, ctx)
        return [_record(claim, name, result, seed) for result in results]
    except NotApplicable:
        raise
    except (Exception, SystemExit, TimeLimitExceeded) as error:  # one check never stops the report
        return [failure(claim, name, error, seed)]


def _ship_figures(
    records: list[Record], root: Path | None
) -> tuple[list[Record], dict[str, bytes]]:
    """The records with figures named relative to ``root``, and those files' bytes."""
    if root is None:
        return records, {}
    figures: dict[str, bytes] = {}
    shipped = []
    for record in records:
        names = []
        for path in map(Path, record.figures):
            name = path.relative_to(root).as_posix() if path.is_relative_to(root) else path.name
            if path.is_file():
                figures[name] = path.read_bytes()
            names.append(name)
        shipped.append(replace(record, result=replace(record.result, figures=tuple(names))))
    return shipped, figures


def _record(claim: Claim, case: str, result: ClaimResult, seed: int | None) -> Record:
    evidence = canonical(result.evidence, "evidence")
    if not isinstance(evidence, dict):
        raise TypeError(f"evidence is a {type(result.evidence).__name__}, not a mapping")
    plain = replace(
        result,
        claim=claim.id,
        case=case,
        evidence=evidence,
        margin=canonical(result.margin, "margin"),
        tolerance=canonical(dict(result.tolerance), "tolerance"),
        figures=tuple(str(f) for f in result.figures),
    )
    return _wrap(claim, plain, seed)


def _wrap(claim: Claim, result: ClaimResult, seed: int | None) -> Record:
    return Record(result, claim.source, claim.statement, paper_of(claim.id, claim.source), seed)


def _where(error: BaseException) -> str:
    """``file:line in function`` of the innermost frame, the file relative to the package root."""
    frames = traceback.extract_tb(error.__traceback__)
    if not frames:
        return ""
    frame = frames[-1]
    root = Path(__file__).resolve().parents[2]
    path = Path(frame.filename).resolve()
    shown = path.relative_to(root).as_posix() if path.is_relative_to(root) else path.name
    return f"{shown}:{frame.lineno} in {frame.name}"
