"""Run logs: one JSON object per line, flushed line by line, fsync'd at a fault.

Record types (field ``"type"``):

* ``header``: ``version`` (:data:`RUN_LOG_VERSION`), ``module_ids``, planned ``times`` [s], ``q``
  [rad] (n,6), ``poses`` (n,4,4) [m], ``early`` (fraction of a step after which the next is sent),
  ``started`` (ISO time), ``arm``: the arm the trajectory was validated for and run on, as
  :func:`iik.arms.to_record` writes it (its name, its shipped name or URDF file and the file's
  SHA-256, and every number of its chain and limits). Version 1 logs recorded only the arm's
  display name. :func:`read_run_log` reads the arm back (:attr:`Run.arm`, :func:`iik.arms.from_record`),
  and the analysis and the viewer use it.
* ``command``: ``t`` [s since start], ``k`` (target index), ``q`` [rad], ``time_s``,
  ``q_meas`` (actual positions from the extended FSTEP ACKs [rad]) and ``short`` (short states).
* ``sample``: ``t``, ``k`` (last commanded target), measured ``q`` [rad] read at times
  ``tq`` [s], ``dq`` [rad/s], ``cur`` [A], ``state`` (u32 state bits per module).
* ``step_end``: ``k``, ``t``: when step k ends on the modules' timeline (buffered update).
* ``fault``: ``t``, ``error`` (exception type), ``message``, ``halted`` (HALT broadcast sent).
* ``end``: ``t``, ``status`` (``"ok"`` or ``"fault"``). A log without it is incomplete.

A log is written whole or not at all (:class:`iik.files.AtomicOutput`): into a temporary
sibling ``.partial-XXXXXXXX-NAME.jsonl``, flushed record by record, and moved to its name
when it is closed -- after its end record, also after a fault or a signal (the executor
writes the fault and the end, then closes it). A process killed outright (SIGKILL, power
loss) leaves the partial file with every record flushed so far, and an earlier log of the
same name as it was. :func:`read_run_log` reads at most :data:`MAX_RUN_LOG_BYTES`
(:func:`iik.files.read_text`).
"""

from __future__ import annotations

import json
import os
from collections.abc import Collection
from dataclasses import dataclass, field
from datetime import datetime
from pathlib import Path

import numpy as np

from iik.arm import Arm
from iik.arms import from_record, same_arm
from iik.errors import FileError, InvalidInputError, Remedy
from iik.files import AtomicOutput, read_text

from .errors import RunLogError

__all__ = ["RunLog", "Run", "read_run_log", "run_arm", "log_path", "reserve_log_path", "MAX_RUN_LOG_BYTES",
           "RUN_LOG_VERSION", "READ_VERSIONS", "MAX_SAME_NAME"]

#: The run-log format written (header ``version``): 2 records the arm (:func:`iik.arms.to_record`).
RUN_LOG_VERSION = 2
#: The formats :func:`read_run_log` reads: 1 recorded only the arm's display name.
READ_VERSIONS = (1, 2)

#: Largest run log :func:`read_run_log` reads [bytes] (a simulated run logs about 45 kB/s: over an hour).
MAX_RUN_LOG_BYTES = 200_000_000
#: Most logs of one name started in one second in one folder (:func:`log_path` numbers them).
MAX_SAME_NAME = 9999


def log_path(out: str | os.PathLike, name: str, when: datetime, existing: Collection[str] = ()) -> Path:
    """Where a run's log goes. Pure: nothing is read or written.

    ``out`` itself if it names a ``.jsonl`` file; else a new file in the folder ``out`` named for the run
    and the time ``when`` started it, ``<name>-<YYYYmmdd>-<HHMMSS>.jsonl``, or with ``-2``, ``-3``... while
    that name is among ``existing`` (the names of the files in ``out``).

    Raises:
        InvalidInputError: (``out``) the folder holds :data:`MAX_SAME_NAME` logs of that name and second.
    """
    out = Path(out)
    if out.suffix == ".jsonl":
        return out
    stem = f"{name}-{when.strftime('%Y%m%d-%H%M%S')}"
    taken = set(existing)
    for k in range(1, MAX_SAME_NAME + 1):
        file = f"{stem}.jsonl" if k == 1 else f"{stem}-{k}.jsonl"
        if file not in taken:
            return out / file
    raise InvalidInputError("out", f"{out} already holds {MAX_SAME_NAME} logs named {stem}-N.jsonl")


def reserve_log_path(out: str | os.PathLike, name: str, when: datetime | None = None) -> Path:
    """:func:`log_path` in the folder ``out`` as it is now (created if missing), at ``when`` (default now):
    the file is created empty here, so that no other run takes its name; for a ``.jsonl`` ``out`` only its
    folder is created (an earlier log of that name stays until the new one replaces it whole).

    Raises:
        InvalidInputError: (``out``) the folder cannot be created or written, or every name is taken.
    """
    out = Path(out)
    folder = out.parent if out.suffix == ".jsonl" else out
    when = datetime.now() if when is None else when
    try:
        folder.mkdir(parents=True, exist_ok=True)
        if out.suffix == ".jsonl":
            return out
        existing = set(os.listdir(folder))
        while True:
            path = log_path(out, name, when, existing)
            try:
                path.open("x").close()
                return path
            except FileExistsError:  # another run took it meanwhile
                existing.add(path.name)
    except OSError as exc:
        raise InvalidInputError("out", f"cannot write the run log in {folder}: {exc.strerror}") from None


class RunLog:
    """Append-only JSON-lines writer; every record is flushed to the OS at once, into the
    temporary :attr:`partial`, which :meth:`close` moves to :attr:`path` (module docstring)."""

    def __init__(self, path: str | os.PathLike):
        self.path = Path(path)
        try:
            self._out = AtomicOutput(self.path, "out", folder=False)
            self.partial = self._out.path
            self._f = open(self.partial, "w", encoding="utf-8")  # noqa: SIM115 - closed in close()
        except (FileError, OSError) as exc:
            reason = exc.reason if isinstance(exc, FileError) else exc
            raise RunLogError(f"{self.path}: cannot write the run log ({reason})") from None

    def write(self, record: dict) -> None:
        self._f.write(json.dumps(record, separators=(",", ":"), allow_nan=False) + "\n")
        self._f.flush()

    def sync(self) -> None:
        """Flush and fsync (at a fault, so nothing is lost if the process dies next)."""
        self._f.flush()
        os.fsync(self._f.fileno())

    def close(self) -> None:
        """Flush, fsync, close and move the log to :attr:`path`."""
        if not self._f.closed:
            self.sync()
            self._f.close()
            try:
                self._out.commit()
            except FileError as exc:
                raise RunLogError(f"{self.path}: cannot write the run log ({exc.reason}); its records are "
                                  f"in {self.partial}") from None

    def __enter__(self) -> RunLog:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


@dataclass(frozen=True)
class Run:
    """A parsed run log. Arrays are SI; ``samples_*`` are in time order. ``arm``: the arm the log
    records (None if its header names none)."""

    header: dict
    arm: Arm | None
    times: np.ndarray  # (n,) planned times [s]
    q_planned: np.ndarray  # (n,6)
    poses: np.ndarray  # (n,4,4)
    command_t: np.ndarray  # (c,)
    command_k: np.ndarray  # (c,)
    command_q_meas: np.ndarray  # (c,6) actual positions when each command arrived (NaN if absent)
    samples_t: np.ndarray  # (m,)
    samples_k: np.ndarray  # (m,)
    samples_q: np.ndarray  # (m,6)
    samples_tq: np.ndarray  # (m,6) time each position was read [s] (= samples_t if not logged)
    samples_dq: np.ndarray  # (m,6)
    samples_cur: np.ndarray  # (m,6)
    samples_state: np.ndarray  # (m,6) int
    step_end: dict  # k -> end time of step k on the modules' timeline [s] (buffered update)
    fault: dict | None
    status: str | None  # None: the log has no end record
    records: list = field(repr=False, default_factory=list)

    @property
    def complete(self) -> bool:
        return self.status is not None


def read_run_log(path: str | os.PathLike) -> Run:
    """Parse a run log; :class:`RunLogError` if it is unreadable (missing, not a regular file,
    over :data:`MAX_RUN_LOG_BYTES`, not UTF-8) or malformed."""
    p = Path(path)
    try:
        lines = read_text(p, "run", limit=MAX_RUN_LOG_BYTES, what="a run log").splitlines()
    except FileError as exc:
        raise RunLogError(exc.reason) from None
    records = []
    for i, line in enumerate(lines, 1):
        try:
            rec = json.loads(line)
        except json.JSONDecodeError as exc:
            raise RunLogError(f"{p}:{i}: not JSON ({exc})") from None
        if not isinstance(rec, dict) or "type" not in rec:
            raise RunLogError(f"{p}:{i}: record without a type")
        records.append(rec)
    if not records or records[0]["type"] != "header":
        raise RunLogError(f"{p}: first record must be the header")
    h = records[0]
    try:
        times = np.asarray(h["times"], dtype=float)
        q = np.asarray(h["q"], dtype=float).reshape(-1, 6)
        poses = np.asarray(h["poses"], dtype=float).reshape(-1, 4, 4)
        cmds = [r for r in records if r["type"] == "command"]
        smp = [r for r in records if r["type"] == "sample"]
        n_mod = len(h["module_ids"])

        def arr(key, dtype=float):
            return np.asarray([r[key] for r in smp], dtype=dtype).reshape(-1, n_mod)

        run = Run(
            header=h, arm=_arm(h, p), times=times, q_planned=q, poses=poses,
            command_t=np.asarray([r["t"] for r in cmds], dtype=float),
            command_k=np.asarray([r["k"] for r in cmds], dtype=int),
            command_q_meas=np.asarray([r.get("q_meas") or [np.nan] * n_mod for r in cmds],
                                      dtype=float).reshape(-1, n_mod),
            samples_t=np.asarray([r["t"] for r in smp], dtype=float),
            samples_k=np.asarray([r["k"] for r in smp], dtype=int),
            samples_q=arr("q"), samples_dq=arr("dq"), samples_cur=arr("cur"),
            samples_tq=np.asarray([r.get("tq") or [r["t"]] * n_mod for r in smp],
                                  dtype=float).reshape(-1, n_mod),
            step_end={int(r["k"]): float(r["t"]) for r in records if r["type"] == "step_end"},
            samples_state=arr("state", np.int64),
            fault=next((r for r in records if r["type"] == "fault"), None),
            status=next((r["status"] for r in records if r["type"] == "end"), None),
            records=records,
        )
    except (KeyError, TypeError, ValueError) as exc:
        raise RunLogError(f"{p}: malformed record ({exc})") from None
    if len(times) != len(q) or len(q) != len(poses):
        raise RunLogError(f"{p}: header times/q/poses lengths differ")
    return run


def _arm(header: dict, path: Path) -> Arm | None:
    """The arm a header records (None without an ``arm`` entry)."""
    if header.get("arm") is None:
        return None
    try:
        return from_record(header["arm"], "arm")
    except InvalidInputError as exc:
        raise RunLogError(f"{path}: the header's arm: {exc.reason}") from None


def run_arm(run: Run, arm: Arm | None = None) -> Arm:
    """The arm of a run: the one its log records; ``arm``, if given, must be the same arm
    (:func:`iik.arms.same_arm`); a log that records none needs ``arm``.

    Raises:
        InvalidInputError: (``arm``) ``arm`` is not the arm the log records.
        RunLogError: the log records no arm and none is given.
    """
    if arm is not None and not isinstance(arm, Arm):
        raise InvalidInputError("arm", f"expected an iik.Arm, got {type(arm).__name__}")
    if run.arm is None:
        if arm is None:
            err = RunLogError("the run log records no arm")
            err.remedy = Remedy("give the arm it was run on as {}", "arm")
            raise err
        return arm
    if arm is not None and not same_arm(arm, run.arm):
        raise InvalidInputError("arm", f"{arm.name!r} is not the arm the run log records ({run.arm.name!r})")
    return run.arm
