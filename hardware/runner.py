"""One run end to end: step targets -> validation -> arm (simulated or on a bus) -> execution
-> analysis -> figures. The library behind ``iik run``.

:func:`run` takes a :class:`RunRequest` (what to execute and how) and returns a
:class:`RunReport`. The trajectory comes from one source (:mod:`hardware.sources`):
a scenario planned by the project's planner (Sec 3.6) and timed as ``iik plan`` times
it, a CSV file (``iik plan``'s files qualify as written), or the demo line; ``speed``
slows any of them. The arm is the scenario's own, or the one given (``RunRequest.arm``,
required for a CSV file or the demo); the simulated modules, the host's limit checks,
the validation, the run log's header and the analysis all use it. Every target is
validated (:func:`hardware.validate`: Table I with a margin, Sec 3.2 speeds, FK vs the
planned pose) before the arm is opened. Without an
``interface`` the arm is simulated in-process (:func:`hardware.sim.simulated_arm`);
otherwise the modules are reached through python-can (``udp_multicast`` to a separate
``iik sim-arm``, ``socketcan`` for real modules), with the modules' watchdog on unless
turned off. The run log (``OUT/<name>-<date>-<time>.jsonl``, never overwritten; or the
file ``out`` names) is analysed as in Sec 4.3 (:func:`hardware.analyse`), and the run
is ``ok`` only if its end-effector error stays inside its safety zone.

SIGTERM and SIGHUP stop a run like Ctrl-C (:mod:`iik.signals`): HALT, fault and
end records, log on disk. Nothing here prints: notes and executed steps are reported
through callbacks.
"""

from __future__ import annotations

import contextlib
import math
import signal
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from datetime import datetime
from pathlib import Path

from iik.arm import Arm
from iik.errors import InvalidInputError, Remedy
from iik.safety import EXECUTION_MARGIN
from iik.signals import stop_on_signals

from . import protocol as P
from .analysis import SAFETY_ZONE_PREDEFINED, RunAnalysis, analyse, plot_run, summary_text
from .driver import WATCHDOG_PERIOD, PowerCubeArm
from .executor import EARLY_UPDATE, ExecutionOptions, RunResult, ValidationOptions, execute
from .runlog import read_run_log
from .sim import SimulatedArm, simulated_arm
from .sources import DEMO_SPEED, StepTargets, csv_trajectory, demo_trajectory, scenario_trajectory

__all__ = ["RunRequest", "RunReport", "run", "failure_status", "SIM_TIMEOUT", "BUS_TIMEOUT", "MAX_TIMEOUT",
           "MAX_ZONE"]

#: ACK timeout [s] for the in-process simulation: generous, since its threads share one interpreter
#: (and a loaded machine) with the host; it never goes silent unless a fault is injected.
SIM_TIMEOUT = 2.0
#: ACK timeout [s] on a real bus (or a simulator in another process).
BUS_TIMEOUT = 0.1
#: Longest ACK timeout accepted [s] (a reply takes milliseconds; more only hides a dead bus).
MAX_TIMEOUT = 10.0
#: Largest safety zone of an ``ok`` run [m] (:attr:`RunRequest.zone`).
MAX_ZONE = 1.0
UPDATES = ("thesis", "buffered")
SIM_STARTS = ("home", "plan")


def _number(value, name: str, lo: float, hi: float, unit: str, *, open_lo: bool = True) -> float:
    """``value`` as a float in (lo, hi] (or [lo, hi] if not ``open_lo``); else InvalidInputError."""
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value) \
        and (value > lo if open_lo else value >= lo) and value <= hi
    if not ok:
        where = f"({lo:g}, {hi:g}]" if open_lo else f"[{lo:g}, {hi:g}]"
        raise InvalidInputError(name, f"must be a finite number in {where}{unit}, got {value!r}")
    return float(value)


def _integer(value, name: str, allowed, what: str) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or value not in allowed:
        raise InvalidInputError(name, f"must be {what}, got {value!r}")


@dataclass(frozen=True)
class RunRequest:
    """What :func:`run` executes, and how. Give exactly one of ``scenario``, ``trajectory``, ``demo``.

    Attributes:
        scenario: A scenario TOML file, or the name of a shipped scenario (e.g. ``"j"``).
        trajectory: A CSV file with columns ``t,q1..q6`` [s, rad].
        demo: The built-in straight-line demo (:func:`hardware.sources.demo_trajectory`).
        arm: The arm run (:class:`iik.Arm`). With a scenario None means the scenario's own arm (a
            given one must be the same arm); a trajectory file or the demo needs one.
        interface, channel, bitrate, port: The python-can bus; ``interface=None`` simulates
            the arm in-process. ``bitrate`` [bit/s] is a PowerCube rate (125k, 250k, 500k, 1M).
        modules: The six module ids in joint order.
        timeout: ACK timeout (0, 10] s; None: :data:`SIM_TIMEOUT` simulated, :data:`BUS_TIMEOUT` on a bus.
        early, update: See :class:`hardware.executor.ExecutionOptions` (Sec 4.3).
        watchdog: The modules' watchdog (a WATCHDOG broadcast every
            :data:`hardware.driver.WATCHDOG_PERIOD` = 40 ms; they stop if it stays away);
            None: on for a bus interface, off for the in-process simulation.
        speed: Run at this fraction (0, 1] of the source's speed: every step lasts 1/speed as
            long (scenario: as ``iik plan`` times it; CSV: as written; demo: timed at
            :data:`hardware.sources.DEMO_SPEED` of the joint speed limits).
        margin: Keep targets this far inside Table I [rad] (0 to 90 deg; default 0.5 deg).
        zone: Largest end-effector error of an ``ok`` run [m]; None: the scenario's safety
            zone (Sec 4.3.2), or the 10 mm of Sec 4.3.1 for a file or the demo.
        lag: Tracking lag of the simulated arm [0, 1] s.
        sim_start: The simulated arm starts at q = 0 (``"home"``) or at the first target (``"plan"``).
        reset: RESET every module first. home: HOME the modules whose HOME_OK is clear.
        out: Folder of the run log (a new ``<name>-<date>-<time>.jsonl`` each run) and figures,
            or a ``.jsonl`` file to write exactly (figures beside it).
        figures: Write the three PNG figures.
    """

    scenario: str | Path | None = None
    trajectory: Path | None = None
    demo: bool = False
    arm: Arm | None = None
    interface: str | None = None
    channel: str | None = None
    bitrate: int | None = None
    port: int | None = None
    modules: tuple[int, ...] = (1, 2, 3, 4, 5, 6)
    timeout: float | None = None
    early: float = EARLY_UPDATE
    update: str = "thesis"
    speed: float = 1.0
    margin: float = EXECUTION_MARGIN
    zone: float | None = None
    lag: float = 0.02
    sim_start: str = "home"
    watchdog: bool | None = None
    reset: bool = False
    home: bool = False
    out: Path = Path("runs")
    figures: bool = True

    def __post_init__(self) -> None:
        if sum(x is not None for x in (self.scenario, self.trajectory, self.demo or None)) != 1:
            raise InvalidInputError("run", "no trajectory or more than one",
                                    Remedy("give exactly one of {}", ("scenario", "trajectory", "demo")))
        mods = tuple(self.modules)
        if len(mods) != 6 or len(set(mods)) != 6 or any(
                isinstance(i, bool) or not isinstance(i, int) or i not in P.MODULE_IDS for i in mods):
            raise InvalidInputError("modules", f"need six distinct ids in 1..31, got {list(mods)}")
        object.__setattr__(self, "modules", mods)
        if self.timeout is not None:
            _number(self.timeout, "timeout", 0.0, MAX_TIMEOUT, " s")
        if self.bitrate is not None:
            _integer(self.bitrate, "bitrate", P.BAUD_CODES, "a PowerCube bit rate, one of "
                     + ", ".join(f"{b}" for b in P.BAUD_CODES) + " bit/s (docs/POWERCUBE.md)")
        if self.port is not None:
            _integer(self.port, "port", range(1, 65536), "a UDP port in 1..65535")
        _number(self.early, "early", 0.0, 1.0, " (fraction of a step)")
        _number(self.speed, "speed", 0.0, 1.0, " (fraction of the planned speed)")
        number = isinstance(self.margin, (int, float)) and not isinstance(self.margin, bool)
        if not (number and 0.0 <= self.margin < math.pi / 2):
            shown = f"{math.degrees(self.margin):g} deg" if number else repr(self.margin)
            raise InvalidInputError("margin", f"must be a finite angle in [0, 90) deg, got {shown}")
        if self.zone is not None:
            _number(self.zone, "zone", 0.0, MAX_ZONE, " m")
        _number(self.lag, "lag", 0.0, 1.0, " s", open_lo=False)
        if self.watchdog not in (None, True, False):
            raise InvalidInputError("watchdog", f"must be True, False or None, got {self.watchdog!r}")
        for name, allowed in (("update", UPDATES), ("sim_start", SIM_STARTS)):
            value = getattr(self, name)
            if value not in allowed:
                raise InvalidInputError(name, f"must be one of {', '.join(allowed)}, got {value!r}")
        object.__setattr__(self, "out", Path(self.out))
        if self.arm is not None and not isinstance(self.arm, Arm):
            raise InvalidInputError("arm", f"expected an iik.Arm, got {type(self.arm).__name__}")
        if self.arm is None and self.scenario is None:
            raise InvalidInputError("arm", "a trajectory file or the demo does not say which arm it is for",
                                    Remedy("give it as {}", "arm"))

    @property
    def simulated(self) -> bool:
        """True if the arm is simulated in-process."""
        return self.interface is None

    @property
    def watchdog_on(self) -> bool:
        """Whether the run enables the modules' watchdog (default: on a bus interface)."""
        return (not self.simulated) if self.watchdog is None else self.watchdog

    @property
    def where(self) -> str:
        """Where the run executes, for messages."""
        if self.simulated:
            return "simulated arm (in-process, virtual bus)"
        return f"{self.interface}:{self.channel}"


@dataclass(frozen=True)
class RunReport:
    """Outcome of :func:`run` (a fault raises instead, after HALT and with the log on disk).

    Attributes:
        request: What was run. targets: The step targets (before validation).
        result: The executor's counts (log path, commands, samples, duration [s]).
        analysis: Step-point joint and end-effector errors (Sec 4.3).
        zone: The safety zone the end-effector error had to stay in [m].
        rests: Simulated runs: times a joint came to rest between two planned steps (the rest at the
            end of an approach to the start is by design, not counted); None on a bus.
        figures: Paths of the PNG figures written.
    """

    request: RunRequest
    targets: StepTargets
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
        """Joint step changes between planned steps (6 x (n - 2)), the denominator of :attr:`rests`."""
        return len(self.request.modules) * max(len(self.targets) - 2, 0)

    def summary(self) -> str:
        """The run's summary for a terminal (mm and degrees for display); its last line is the status."""
        r, req = self.result, self.request
        lines = [summary_text(self.analysis, self.targets.name)]
        if self.rests is not None and self.step_changes:
            lines.append(f"  simulated joints came to rest between two planned steps {self.rests} times (of "
                         f"{self.step_changes} step changes; update {req.update}, early {req.early})")
        elif self.rests is not None:
            lines.append("  one planned step: no step change for a joint to rest at")
        lines.append(f"run log: {r.log_path} ({r.commands} commands, {r.samples} samples, "
                     f"{r.duration:.2f} s)")
        lines += [f"figure: {p}" for p in self.figures]
        err, zone = self.analysis.max_ee_error * 1e3, self.zone * 1e3
        lines.append(f"status: {self.status} (max end-effector error {err:.2f} mm "
                     f"{'within' if self.ok else 'OUTSIDE'} the {zone:g} mm zone)")
        return "\n".join(lines)


def _targets(request: RunRequest) -> StepTargets:
    if request.demo:
        targets = demo_trajectory(request.arm, DEMO_SPEED)
    elif request.trajectory is not None:
        targets = csv_trajectory(request.trajectory, request.arm)
    else:
        targets = scenario_trajectory(request.scenario, arm=request.arm)
    return targets.slowed(request.speed)


def _scenario_header(request: RunRequest, arm: Arm) -> dict:
    """The scenario and its boxes [m, base frame] for the run log's header (``iik view --run`` draws them)."""
    if request.scenario is None:
        return {}
    from iik.planning import load_scenario, scenario_path

    sc = load_scenario(scenario_path(request.scenario), arm=arm)
    return {"scenario": sc.name, "obstacles": [{"name": b.name, "kind": b.kind, "center": list(b.center),
                                                "size": list(b.size)} for b in sc.obstacles]}


def _zone(request: RunRequest, arm: Arm) -> float:
    """The safety zone of the run [m] (:attr:`RunRequest.zone`)."""
    if request.zone is not None:
        return request.zone
    if request.scenario is not None:
        from iik.planning import load_scenario, scenario_path

        return float(load_scenario(scenario_path(request.scenario), arm=arm).safety_zone)
    return SAFETY_ZONE_PREDEFINED


def _log_path(request: RunRequest, name: str) -> Path:
    """The run log's path: ``out`` if it names a ``.jsonl`` file, else a new file in the folder
    ``out`` (``<name>-<date>-<time>.jsonl``, ``-2``, ``-3``... if taken), created here so no
    other run takes it."""
    out = request.out
    folder = out.parent if out.suffix == ".jsonl" else out
    try:
        folder.mkdir(parents=True, exist_ok=True)
        if out.suffix == ".jsonl":
            return out
        stem = f"{name}-{datetime.now().strftime('%Y%m%d-%H%M%S')}"
        for k in range(1, 10_000):
            path = folder / (stem if k == 1 else f"{stem}-{k}")
            path = path.with_name(path.name + ".jsonl")
            try:
                path.open("x").close()
                return path
            except FileExistsError:
                continue
    except OSError as exc:
        raise InvalidInputError("out", f"cannot write the run log in {folder}: {exc.strerror}") from None
    raise InvalidInputError("out", f"{folder} already holds 9999 logs named {stem}-N.jsonl")


@contextlib.contextmanager
def _open_arm(request: RunRequest, initial, arm: Arm) -> Iterator[tuple[SimulatedArm | None, PowerCubeArm]]:
    """``(sim, host)``: an in-process simulated ``arm``, or ``(None, host)`` on the request's bus; the
    host checks targets against ``arm``'s limits."""
    if request.simulated:
        with simulated_arm(request.modules, arm=arm, lag=request.lag, initial=initial,
                           timeout=request.timeout or SIM_TIMEOUT) as (sim, host):
            yield sim, host
        return
    kw = {"port": request.port} if request.port is not None else {}
    with PowerCubeArm.from_interface(request.modules, interface=request.interface, channel=request.channel,
                                     bitrate=request.bitrate, timeout=request.timeout or BUS_TIMEOUT, arm=arm,
                                     **kw) as host:
        yield None, host


def _prepare(arm: PowerCubeArm, request: RunRequest) -> None:
    """Open the arm (every module answers, once), RESET and HOME as requested; HALT if that fails."""
    try:
        arm.open()
        if request.reset:
            arm.reset()
        if request.home:
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


def _halted_note(request: RunRequest, log_path: Path) -> str | None:
    """What to tell after a run stopped by a fault, if it had started (its log has records)."""
    if not log_path.exists() or log_path.stat().st_size == 0:
        return None
    return f"HALT broadcast to every module; the run log {log_path} ends with the fault"


def run(request: RunRequest, *, notify: Callable[[str], None] | None = None,
        progress: Callable[[int, int], None] | None = None) -> RunReport:
    """Plan or read the trajectory, validate it, execute it and analyse the run log.

    Args:
        request: What to run (:class:`RunRequest`).
        notify: Called with a line of text at each stage before execution (planned,
            validated, watchdog).
        progress: Called with ``(k, n)`` after step ``k`` of ``n`` was commanded.

    Returns:
        :class:`RunReport`; :attr:`RunReport.ok` is False if the end-effector error left
        the safety zone (the run itself went to the end).

    Raises:
        IIKError: bad input (``InvalidInputError``, ``ScenarioError``), a plan that
            failed, a target refused by validation (``SafetyError``), or a hardware
            fault during the run (``CANTimeoutError``, ``ModuleFault``, ``BusError``,
            ``DuplicateModuleError``...), after HALT was broadcast and the fault logged
            (the exception's note says where the log is).
        KeyboardInterrupt, StopSignal: Ctrl-C, SIGTERM or SIGHUP, handled the same way.

    An exception raised after the run started carries ``run_log`` (the log's path) besides its note.
    """
    say = notify or (lambda text: None)
    with stop_on_signals():
        targets = _targets(request)
        if targets.note:
            say(targets.note)
        traj = targets.validate(ValidationOptions(margin=request.margin))
        say(f"{targets.name}: {len(traj)} step-points, {traj.times[-1]:.3f} s, validated for the arm "
            f"{targets.arm.name!r} (joint limits - {math.degrees(request.margin):g} deg, speed limits, FK vs "
            "planned poses)")
        zone = _zone(request, targets.arm)
        log_path = _log_path(request, targets.name)
        if request.watchdog_on:
            say(f"watchdog on: WATCHDOG broadcast every {WATCHDOG_PERIOD * 1e3:.0f} ms; the modules stop "
                "if it stays away (--no-watchdog to turn it off)")
        options = ExecutionOptions(early=request.early, update=request.update, watchdog=request.watchdog_on)
        initial = traj.q[0] if request.sim_start == "plan" else None
        try:
            with _open_arm(request, initial, targets.arm) as (sim, arm):
                _prepare(arm, request)
                rests = _Rests(sim, progress)
                result = execute(arm, traj, log_path, options=options, progress=rests.progress,
                                 header=_scenario_header(request, targets.arm))
        except BaseException as exc:
            if (note := _halted_note(request, log_path)) is not None:
                exc.add_note(note)
                exc.run_log = log_path  # the run started: HALT sent, the log ends with the fault
                if not request.simulated and getattr(exc, "remedy", None) is None:
                    exc.remedy = Remedy("the modules stay halted until reset: run again with {}", "reset")
            elif request.out.suffix != ".jsonl":
                log_path.unlink(missing_ok=True)  # reserved, never written: the run did not start
            raise
    analysis = analyse(read_run_log(result.log_path), targets.arm)  # the log's arm, checked against it
    figures = tuple(plot_run(analysis, log_path.parent, log_path.stem)) if request.figures else ()
    return RunReport(request, targets, result, analysis, zone, rests.between_steps(), figures)


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
