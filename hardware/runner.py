"""One run end to end: step targets -> validation -> arm (simulated or on a bus) -> execution
-> analysis -> figures. The library behind ``iik run``.

:func:`run` takes a :class:`RunRequest` (what to execute and how) and returns a
:class:`RunReport`. The trajectory comes from one source (:mod:`hardware.sources`):
a scenario planned by the project's planner (Sec 3.6), a CSV file, or the demo line.
Every target is validated (:func:`hardware.validate`: Table I with a margin, Sec 3.2
speeds, FK vs the planned pose) before the arm is opened. Without an ``interface``
the arm is simulated in-process (:func:`hardware.sim.simulated_arm`); otherwise the
modules are reached through python-can (``udp_multicast`` to a separate ``iik
sim-arm``, ``socketcan`` for real modules). The run log (``OUT/<name>.jsonl``) is
analysed as in Sec 4.3 (:func:`hardware.analyse`).

Nothing here prints: notes and executed steps are reported through callbacks.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

from iik.errors import InvalidInputError

from . import protocol as P
from .analysis import RunAnalysis, analyse, plot_run, summary_text
from .driver import PowerCubeArm
from .executor import EARLY_UPDATE, ExecutionOptions, RunResult, ValidationOptions, execute
from .runlog import read_run_log
from .sim import SimulatedArm, simulated_arm
from .sources import StepTargets, csv_trajectory, demo_trajectory, scenario_trajectory

__all__ = ["RunRequest", "RunReport", "run", "SIM_TIMEOUT", "BUS_TIMEOUT"]

#: ACK timeout [s] for the in-process simulation, whose threads share one interpreter.
SIM_TIMEOUT = 0.5
#: ACK timeout [s] on a real bus (or a simulator in another process).
BUS_TIMEOUT = 0.1
UPDATES = ("thesis", "buffered")
SIM_STARTS = ("home", "plan")


def _number(value, name: str, lo: float, hi: float = math.inf, *, open_lo: bool = True) -> float:
    """``value`` as a float in (lo, hi] (or [lo, hi] if not ``open_lo``); else InvalidInputError."""
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value) \
        and (value > lo if open_lo else value >= lo) and value <= hi
    if not ok:
        where = f"({lo:g}, {hi:g}]" if open_lo else f"[{lo:g}, {hi:g}]"
        raise InvalidInputError(name, f"must be a finite number in {where}, got {value!r}")
    return float(value)


@dataclass(frozen=True)
class RunRequest:
    """What :func:`run` executes, and how. Give exactly one of ``scenario``, ``trajectory``, ``demo``.

    Attributes:
        scenario: A scenario TOML file, or the name of a shipped scenario (e.g. ``"j"``).
        trajectory: A CSV file with columns ``t,q1..q6`` [s, rad].
        demo: The built-in straight-line demo (:func:`hardware.sources.demo_trajectory`).
        interface, channel, bitrate, port: The python-can bus; ``interface=None`` simulates
            the arm in-process.
        modules: The six module ids in joint order.
        timeout: ACK timeout [s]; None: :data:`SIM_TIMEOUT` simulated, :data:`BUS_TIMEOUT` on a bus.
        early, update, watchdog: See :class:`hardware.executor.ExecutionOptions` (Sec 4.3).
        speed: Fraction of the joint speed limits used to time the steps (Sec 3.2).
        margin: Keep targets this far inside Table I [rad].
        lag: Tracking lag of the simulated arm [s].
        sim_start: The simulated arm starts at q = 0 (``"home"``) or at the first target (``"plan"``).
        reset: RESET every module first. home: HOME the modules whose HOME_OK is clear.
        out: Folder of the run log and figures. figures: Write the three PNG figures.
    """

    scenario: str | Path | None = None
    trajectory: Path | None = None
    demo: bool = False
    interface: str | None = None
    channel: str | None = None
    bitrate: int | None = None
    port: int | None = None
    modules: tuple[int, ...] = (1, 2, 3, 4, 5, 6)
    timeout: float | None = None
    early: float = EARLY_UPDATE
    update: str = "thesis"
    speed: float = 0.5
    margin: float = math.radians(0.5)
    lag: float = 0.02
    sim_start: str = "home"
    watchdog: bool = False
    reset: bool = False
    home: bool = False
    out: Path = Path("runs")
    figures: bool = True

    def __post_init__(self) -> None:
        if sum(x is not None for x in (self.scenario, self.trajectory, self.demo or None)) != 1:
            raise InvalidInputError("run", "give exactly one of SCENARIO, --trajectory FILE or --demo")
        mods = tuple(self.modules)
        if len(mods) != 6 or len(set(mods)) != 6 or any(
                isinstance(i, bool) or not isinstance(i, int) or i not in P.MODULE_IDS for i in mods):
            raise InvalidInputError("modules", f"need six distinct ids in 1..31, got {list(mods)}")
        object.__setattr__(self, "modules", mods)
        if self.timeout is not None:
            _number(self.timeout, "timeout", 0.0)
        _number(self.early, "early", 0.0, 1.0)
        _number(self.speed, "speed", 0.0, 1.0)
        number = isinstance(self.margin, (int, float)) and not isinstance(self.margin, bool)
        if not (number and 0.0 <= self.margin < math.pi / 2):
            shown = f"{math.degrees(self.margin):g} deg" if number else repr(self.margin)
            raise InvalidInputError("margin", f"must be in [0, 90) deg, got {shown}")
        _number(self.lag, "lag", 0.0, open_lo=False)
        for name, allowed in (("update", UPDATES), ("sim_start", SIM_STARTS)):
            value = getattr(self, name)
            if value not in allowed:
                raise InvalidInputError(name, f"must be one of {', '.join(allowed)}, got {value!r}")
        object.__setattr__(self, "out", Path(self.out))

    @property
    def simulated(self) -> bool:
        """True if the arm is simulated in-process."""
        return self.interface is None

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
        rests: Simulated runs: times a joint came to rest between two steps; None on a bus.
        figures: Paths of the PNG figures written.
    """

    request: RunRequest
    targets: StepTargets
    result: RunResult
    analysis: RunAnalysis
    rests: int | None = None
    figures: tuple[Path, ...] = field(default=())

    @property
    def step_changes(self) -> int:
        """Joint step changes of the run (6 x (n - 2)), the denominator of :attr:`rests`."""
        return len(self.request.modules) * max(len(self.targets) - 2, 0)

    def summary(self) -> str:
        """The run's summary for a terminal (mm and degrees for display)."""
        r, req = self.result, self.request
        lines = [summary_text(self.analysis, self.targets.name)]
        if self.rests is not None:
            lines.append(f"  simulated joints came to rest between two steps {self.rests} times (of "
                         f"{self.step_changes} step changes; update {req.update}, early {req.early})")
        lines.append(f"run log: {r.log_path} ({r.commands} commands, {r.samples} samples, "
                     f"{r.duration:.2f} s)")
        lines += [f"figure: {p}" for p in self.figures]
        return "\n".join(lines)


def _targets(request: RunRequest) -> StepTargets:
    if request.demo:
        return demo_trajectory(request.speed)
    if request.trajectory is not None:
        return csv_trajectory(request.trajectory)
    return scenario_trajectory(request.scenario, request.speed)


@contextlib.contextmanager
def _open_arm(request: RunRequest, initial) -> Iterator[tuple[SimulatedArm | None, PowerCubeArm]]:
    """``(sim, arm)``: an in-process simulated arm, or ``(None, arm)`` on the request's bus."""
    if request.simulated:
        with simulated_arm(request.modules, lag=request.lag, initial=initial,
                           timeout=request.timeout or SIM_TIMEOUT) as (sim, arm):
            yield sim, arm
        return
    kw = {"port": request.port} if request.port is not None else {}
    with PowerCubeArm.from_interface(request.modules, interface=request.interface, channel=request.channel,
                                     bitrate=request.bitrate, timeout=request.timeout or BUS_TIMEOUT,
                                     **kw) as arm:
        yield None, arm


def _prepare(arm: PowerCubeArm, request: RunRequest) -> None:
    """Open the arm (every module answers), RESET and HOME as requested."""
    arm.open()
    if request.reset:
        arm.reset()
    if request.home:
        for m, s in zip(arm.modules, arm.states(), strict=True):
            if not s & P.State.HOME_OK:
                m.home()
        arm.wait_homed()


def run(request: RunRequest, *, notify: Callable[[str], None] | None = None,
        progress: Callable[[int, int], None] | None = None) -> RunReport:
    """Plan or read the trajectory, validate it, execute it and analyse the run log.

    Args:
        request: What to run (:class:`RunRequest`).
        notify: Called with a line of text at each stage before execution (planned,
            validated).
        progress: Called with ``(k, n)`` after step ``k`` of ``n`` was commanded.

    Raises:
        IIKError: bad input (``InvalidInputError``, ``ScenarioError``), a plan that
            failed, a target refused by validation (``SafetyError``), or a hardware
            fault during the run (``CANTimeoutError``, ``ModuleFault``, ``BusError``...),
            after HALT was broadcast and the fault logged.
    """
    say = notify or (lambda text: None)
    targets = _targets(request)
    if targets.note:
        say(targets.note)
    traj = targets.validate(ValidationOptions(margin=request.margin))
    say(f"{targets.name}: {len(traj)} step-points, {traj.times[-1]:.2f} s planned, validated "
        f"(Table I - {math.degrees(request.margin):g} deg, speed limits, FK vs planned poses)")
    try:
        request.out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InvalidInputError("out", f"cannot create the folder {request.out}: {exc.strerror}") from None
    log_path = request.out / f"{targets.name}.jsonl"
    options = ExecutionOptions(early=request.early, update=request.update, watchdog=request.watchdog)
    initial = traj.q[0] if request.sim_start == "plan" else None
    with _open_arm(request, initial) as (sim, arm):
        _prepare(arm, request)
        result = execute(arm, traj, log_path, options=options, progress=progress)
        rests = None if sim is None else sum(len(m.stops) for m in sim.modules.values())
    analysis = analyse(read_run_log(result.log_path))
    figures = tuple(plot_run(analysis, request.out, targets.name)) if request.figures else ()
    return RunReport(request, targets, result, analysis, rests, figures)
