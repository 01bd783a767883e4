"""One run end to end, python-can style: step targets -> validation -> the modules on a bus -> execution
-> analysis -> figures. The library behind ``iik run``.

``run(targets, bus, options, log)`` returns a :class:`RunReport`:

* ``targets``: :class:`hardware.sources.StepTargets` from one source (``iik run`` picks it:
  :func:`~hardware.sources.scenario_trajectory`, :func:`~hardware.sources.csv_trajectory` or
  :func:`~hardware.sources.demo_trajectory`, :meth:`~hardware.sources.StepTargets.slowed` to a speed).
  They carry the arm they are for: the simulated modules, the host's limit checks, the validation, the
  run log's header and the analysis all use it; a scenario's targets carry the scenario (its safety
  zone, its boxes for the log).
* ``bus``: :class:`hardware.bus.BusConfig`, where the modules are. The simulated arm is just another bus:
  with a :class:`~hardware.bus.SimConfig` the simulated modules are attached to the bus in this process
  (``BusConfig.simulated()``: a private ``virtual`` channel), and their clock is the executor's too (a
  :class:`~hardware.clock.VirtualClock` runs exactly and as fast as the requests go). Otherwise the modules
  are reached through python-can (``udp_multicast`` to a separate ``iik sim-arm``, ``socketcan`` for real
  modules).
* ``options``: :class:`RunOptions` (validation margin, execution: early and buffered update, the
  modules' watchdog; the safety zone; RESET and HOME first; figures).
* ``log``: a folder (a new ``<name>-<date>-<time>.jsonl`` each run, :func:`hardware.runlog.log_path`,
  never overwritten) or the ``.jsonl`` file to write.

Every target is validated (:func:`hardware.validate`: the arm's limits with a margin, Sec 3.2 speeds, FK
vs the planned pose) before the bus is opened. The run log is analysed as in Sec 4.3
(:func:`hardware.analyse`), and the run is ``ok`` only if its end-effector error stays inside its safety
zone. SIGTERM and SIGHUP stop a run like Ctrl-C (:mod:`iik.signals`): HALT, fault and end records, log
on disk. Nothing here prints: notes and executed steps are reported through callbacks.
"""

from __future__ import annotations

import contextlib
import math
import os
import signal
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from iik.errors import InvalidInputError, Remedy
from iik.signals import stop_on_signals
from iik.validation import bounded_number

from . import protocol as P
from .analysis import SAFETY_ZONE_PREDEFINED, RunAnalysis, analyse, plot_run, summary_text
from .bus import BusConfig
from .clock import REAL_TIME
from .driver import WATCHDOG_PERIOD, PowerCubeArm
from .executor import ExecutionOptions, RunResult, ValidationOptions, execute
from .runlog import read_run_log, reserve_log_path
from .sim import SimulatedArm, connect
from .sources import StepTargets

__all__ = ["RunOptions", "RunReport", "run", "failure_status", "MAX_ZONE"]

#: Largest safety zone of an ``ok`` run [m] (:attr:`RunOptions.zone`).
MAX_ZONE = 1.0


@dataclass(frozen=True)
class RunOptions:
    """How :func:`run` validates, executes and judges a run; validated when built
    (:class:`~iik.errors.InvalidInputError` naming the field).

    Attributes:
        validation: :class:`hardware.executor.ValidationOptions` (the margin inside the joint limits).
        execution: :class:`hardware.executor.ExecutionOptions` (early and buffered update, Sec 4.3; the
            modules' watchdog: a WATCHDOG broadcast every :data:`hardware.driver.WATCHDOG_PERIOD` = 40 ms,
            they stop if it stays away; ``iik run`` turns it on for a bus, off for the in-process simulation).
        zone: Largest end-effector error of an ``ok`` run, (0, 1] m; None: the scenario's safety zone
            (Sec 4.3.2), or the 10 mm of Sec 4.3.1 for a file or the demo.
        reset: RESET every module first (after a HALT). home: HOME the modules whose HOME_OK is clear.
        figures: Write the three PNG figures beside the run log.
    """

    validation: ValidationOptions = field(default_factory=ValidationOptions)
    execution: ExecutionOptions = field(default_factory=ExecutionOptions)
    zone: float | None = None
    reset: bool = False
    home: bool = False
    figures: bool = True

    def __post_init__(self) -> None:
        for name, kind in (("validation", ValidationOptions), ("execution", ExecutionOptions)):
            given = getattr(self, name)
            if not isinstance(given, kind):
                raise InvalidInputError(name, f"expected {kind.__name__}, got {type(given).__name__}")
        if self.zone is not None:
            object.__setattr__(self, "zone", bounded_number(self.zone, "zone", 0.0, MAX_ZONE, unit=" m",
                                                            open_lo=True))
        for name in ("reset", "home", "figures"):
            if not isinstance(getattr(self, name), bool):
                raise InvalidInputError(name, f"must be True or False, got {getattr(self, name)!r}")


@dataclass(frozen=True)
class RunReport:
    """Outcome of :func:`run` (a fault raises instead, after HALT and with the log on disk).

    Attributes:
        targets: The step targets (before validation). bus: Where they ran. options: How.
        result: The executor's counts (log path, commands, samples, duration [s] on the run's clock).
        analysis: Step-point joint and end-effector errors (Sec 4.3).
        zone: The safety zone the end-effector error had to stay in [m].
        rests: Simulated runs: times a joint came to rest between two planned steps (the rest at the
            end of an approach to the start is by design, not counted); None on a bus.
        figures: Paths of the PNG figures written.
    """

    targets: StepTargets
    bus: BusConfig
    options: RunOptions
    result: RunResult
    analysis: RunAnalysis
    zone: float = SAFETY_ZONE_PREDEFINED
    rests: int | None = None
    figures: tuple[Path, ...] = field(default=())

    @property
    def ok(self) -> bool:
        """The run went to the end and its end-effector error stayed inside :attr:`zone`."""
        return self.analysis.status == "ok" and self.analysis.within(self.zone)

    @property
    def status(self) -> str:
        """``"ok"``, or ``"outside zone"`` (executed to the end, error beyond :attr:`zone`)."""
        return "ok" if self.ok else "outside zone"

    @property
    def step_changes(self) -> int:
        """Joint step changes between planned steps (joints x (n - 2)), the denominator of :attr:`rests`."""
        return self.targets.q.shape[1] * max(len(self.targets) - 2, 0)

    def summary(self) -> str:
        """The run's summary for a terminal (mm and degrees for display); its last line is the status."""
        r, ex = self.result, self.options.execution
        lines = [summary_text(self.analysis, self.targets.name)]
        if self.rests is not None and self.step_changes:
            lines.append(f"  simulated joints came to rest between two planned steps {self.rests} times (of "
                         f"{self.step_changes} step changes; update {ex.update}, early {ex.early})")
        elif self.rests is not None:
            lines.append("  one planned step: no step change for a joint to rest at")
        lines.append(f"run log: {r.log_path} ({r.commands} commands, {r.samples} samples, "
                     f"{r.duration:.2f} s)")
        lines += [f"figure: {p}" for p in self.figures]
        err, zone = self.analysis.max_ee_error * 1e3, self.zone * 1e3
        lines.append(f"status: {self.status} (max end-effector error {err:.2f} mm "
                     f"{'within' if self.ok else 'OUTSIDE'} the {zone:g} mm zone)")
        return "\n".join(lines)


def _check(targets: StepTargets, bus: BusConfig, options: RunOptions) -> None:
    """The arguments' types, and one module per joint of the targets' arm."""
    for name, value, kind in (("targets", targets, StepTargets), ("bus", bus, BusConfig),
                              ("options", options, RunOptions)):
        if not isinstance(value, kind):
            raise InvalidInputError(name, f"expected {kind.__name__}, got {type(value).__name__}")
    joints = targets.q.shape[1]
    if len(bus.module_ids) != joints:
        raise InvalidInputError("module_ids", f"need one module per joint of the arm {targets.arm.name!r}: "
                                              f"{joints} ids, got {list(bus.module_ids)}")


def _zone(targets: StepTargets, options: RunOptions) -> float:
    """The safety zone of the run [m] (:attr:`RunOptions.zone`)."""
    if options.zone is not None:
        return options.zone
    if targets.scenario is not None:
        return float(targets.scenario.safety_zone)
    return SAFETY_ZONE_PREDEFINED


def _scenario_header(targets: StepTargets) -> dict:
    """The scenario and its boxes [m, base frame] for the run log's header (``iik view --run`` draws them)."""
    sc = targets.scenario
    if sc is None:
        return {}
    return {"scenario": sc.name, "obstacles": [{"name": b.name, "kind": b.kind, "center": list(b.center),
                                                "size": list(b.size)} for b in sc.obstacles]}


def _prepare(arm: PowerCubeArm, options: RunOptions) -> None:
    """Open the arm (every module answers, once), RESET and HOME as asked; HALT if that fails."""
    try:
        arm.open()
        if options.reset:
            arm.reset()
        if options.home:
            for m, s in zip(arm.modules, arm.states(), strict=True):
                if not s & P.State.HOME_OK:
                    m.home()
            arm.wait_homed()
    except BaseException:
        with contextlib.suppress(BaseException):
            arm.halt()  # a homing motion may have started
        raise


class _Rests:
    """Rests of the simulated joints between planned steps: those the simulator recorded after the
    first planned step started (:meth:`progress` of step 1 marks it; by then every module has
    started that step: its FSTEP was acknowledged), so the settle after an approach is not one."""

    def __init__(self, sim: SimulatedArm | None, progress: Callable[[int, int], None] | None):
        self.sim, self.forward, self.before = sim, progress, 0

    def _count(self) -> int:
        return sum(len(m.stops) for m in self.sim.modules.values())

    def progress(self, k: int, n: int) -> None:
        if k == 1 and self.sim is not None:
            self.before = self._count()
        if self.forward is not None:
            self.forward(k, n)

    def between_steps(self) -> int | None:
        return None if self.sim is None else self._count() - self.before


def _halted_note(bus: BusConfig, log_path: Path) -> str | None:
    """What to tell after a run stopped by a fault, if it had started (its log has records)."""
    if not log_path.exists() or log_path.stat().st_size == 0:
        return None
    return f"HALT broadcast to every module; the run log {log_path} ends with the fault"


def run(targets: StepTargets, bus: BusConfig, options: RunOptions = RunOptions(),
        log: str | os.PathLike = "runs", *, notify: Callable[[str], None] | None = None,
        progress: Callable[[int, int], None] | None = None) -> RunReport:
    """Validate ``targets``, execute them on the modules ``bus`` names and analyse the run log.

    Args:
        targets: What to run, with the arm it is for (:class:`hardware.sources.StepTargets`).
        bus: Where the modules are (:class:`hardware.bus.BusConfig`; with ``sim``, simulated in this
            process on the simulator's clock); one module per joint.
        options: How (:class:`RunOptions`).
        log: A folder (a new ``<name>-<date>-<time>.jsonl`` each run, figures beside it) or the ``.jsonl``
            file to write.
        notify: Called with a line of text at each stage before execution (the source's note,
            validated, watchdog).
        progress: Called with ``(k, n)`` after step ``k`` of ``n`` was commanded.

    Returns:
        :class:`RunReport`; :attr:`RunReport.ok` is False if the end-effector error left
        the safety zone (the run itself went to the end).

    Raises:
        IIKError: bad input (``InvalidInputError``), a target refused by validation (``SafetyError``),
            or a hardware fault during the run (``CANTimeoutError``, ``ModuleFault``, ``BusError``,
            ``DuplicateModuleError``...), after HALT was broadcast and the fault logged
            (the exception's note says where the log is).
        KeyboardInterrupt, StopSignal: Ctrl-C, SIGTERM or SIGHUP, handled the same way.

    An exception raised after the run started carries ``run_log`` (the log's path) besides its note.
    """
    _check(targets, bus, options)
    say = notify or (lambda text: None)
    with stop_on_signals():
        if targets.note:
            say(targets.note)
        traj = targets.validate(options.validation)
        say(f"{targets.name}: {len(traj)} step-points, {traj.times[-1]:.3f} s, validated for the arm "
            f"{targets.arm.name!r} (joint limits - {math.degrees(options.validation.margin):g} deg, speed "
            "limits, FK vs planned poses)")
        zone = _zone(targets, options)
        log_path = reserve_log_path(log, targets.name)
        if options.execution.watchdog:
            say(f"watchdog on: WATCHDOG broadcast every {WATCHDOG_PERIOD * 1e3:.0f} ms; the modules stop "
                "if it stays away (the watchdog option turns it off)")
        clock = bus.sim.clock if bus.sim is not None else REAL_TIME
        try:
            with connect(bus, arm=targets.arm) as (host, sim):
                _prepare(host, options)
                rests = _Rests(sim, progress)
                result = execute(host, traj, log_path, options=options.execution, progress=rests.progress,
                                 header=_scenario_header(targets), clock=clock.now, sleep=clock.sleep)
        except BaseException as exc:
            if (note := _halted_note(bus, log_path)) is not None:
                exc.add_note(note)
                exc.run_log = log_path  # the run started: HALT sent, the log ends with the fault
                if bus.sim is None and getattr(exc, "remedy", None) is None:
                    exc.remedy = Remedy("the modules stay halted until reset: run again with {}", "reset")
            elif Path(log).suffix != ".jsonl":
                log_path.unlink(missing_ok=True)  # reserved, never written: the run did not start
            raise
    analysis = analyse(read_run_log(result.log_path), targets.arm)  # the log's arm, checked against it
    figures = tuple(plot_run(analysis, log_path.parent, log_path.stem)) if options.figures else ()
    return RunReport(targets, bus, options, result, analysis, zone, rests.between_steps(), figures)


def failure_status(exc: BaseException) -> str:
    """The status line of a run that raised instead of returning a :class:`RunReport` (whose
    :meth:`~RunReport.summary` ends with the status otherwise): ``error before the run``,
    ``fault during the run`` (``exc.run_log`` set: HALT sent, the log ends with the fault) or
    ``interrupted by SIGNAL``."""
    log = getattr(exc, "run_log", None)
    during = f"HALT sent; run log {log}" if log is not None else "nothing was executed"
    if isinstance(exc, KeyboardInterrupt):
        name = signal.Signals(getattr(exc, "signum", signal.SIGINT)).name
        return f"status: interrupted by {name} ({during})"
    when = "fault during" if log is not None else "error before"
    return f"status: {when} the run ({type(exc).__name__}; {during})"
