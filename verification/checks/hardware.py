"""Hardware execution checks (Sec 4.3, App. A, Table V) for ``iik verify``.

Every run is on the in-process simulated arm (:func:`hardware.sim.simulated_arm`), with the scenarios
planned as ``iik run`` plans them (:func:`_planned`). The simulator's tracking lag (a pure delay) and current
model are assumptions, not identified on the real modules, so what these rows measure is the *method* (FSTEP
streaming with the thesis's early update) on a simulated arm; the real arm's errors (Figs 46-55) are not
checkable here.

Time base. Executions run on a *fast-forward* clock shared by the simulator and the executor
(:class:`hardware.clock.FastForwardClock`): every wait of the executor advances the clock by its full length
but sleeps only 1/:data:`FAST_FORWARD` of it, and the host's own time (computation and bus round trips)
counts :data:`LATENCY_SCALE` of its real length. So what is graded is the streaming scheme, not this host's
load: whether the next step arrives within the last 5 % of the previous one depends on the scheme alone, and
two runs give the same verdicts. (With bus round trips at their real length, p3's 95 % update left 0-6 of
696 joint rests depending on the load, and one such rest too many flipped the Sec 4.3 row between two runs;
the early-update row still reports that real-latency count, ungraded.) The simulator's motion is an analytic
function of the clock, so the jumps are exact. The executor samples every 30 ms (:data:`SAMPLE_PERIOD`; on
p3 the errors agree with 10 ms sampling to 0.05 mm). The Table V round trips use the same clock, so their
timings do not depend on the host's load either.

Grades. Each Sec 4.3 claim is about the real arm: *not checkable* here; the simulation that reproduces it
is a separate *project* row (:func:`_simulated`), decided by the simulator's assumed 20 ms lag, not by the
PowerCube modules. Its forms are the simulated arm (:class:`SimArm`; slip: the logged errors read in the
wrong unit, no extra run) or the update fraction (slip: 100 %, no early update). The Table V round trip
tests our driver against our simulator: it holds *by construction*.
"""

from __future__ import annotations

import functools
import tempfile
import time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from hardware import analyse, execute, read_run_log
from hardware import protocol as P
from hardware.analysis import SAFETY_ZONE_PREDEFINED
from hardware.clock import FastForwardClock
from hardware.errors import SimulatorError
from hardware.executor import EARLY_UPDATE, ExecutionOptions
from hardware.sim import SIM_VERSION, simulated_arm
from hardware.sources import scenario_trajectory
from iik import THESIS_ARM
from iik.planning import scenario_path
from iik.planning.collision import SceneCollision
from iik.planning.obstacles import SAFETY_ZONE
from iik.planning.scenario_io import load_scenario
from verification.formula import per_run
from verification.registry import Erratum, Forms, Measure, Row, Scope, Section, Slip, SlipKind, Verdict
from verification.second_reading import Kind, Reading, search
from verification.thesis_index import title_of

__all__ = [
    "SECTION",
    "SimArm",
    "SimRun",
    "execute_scenario",
]

#: The executor sleeps 1/FAST_FORWARD of each wait; the clock advances by all of it.
FAST_FORWARD = 60.0
#: Share of the host's real time (computation, bus round trips) that the graded runs' clock counts.
LATENCY_SCALE = 0.01
#: Executor sampling period [s] (simulated time).
SAMPLE_PERIOD = 0.03
#: Real time [s] the driver waits for a reply of the in-process simulated modules in the graded runs:
#: on a loaded host their thread can be starved of the CPU for more than the driver's 0.5 s default,
#: and on the compressed clock a late reply barely moves the simulated timeline.
REQUEST_TIMEOUT = 5.0
#: The simulator's assumed tracking lag [s] (hardware.sim's default).
LAG = 0.02
_ORDER = 900.0
#: Runs as (scenario, number of leading step-points or None for all), by ``ctx.quick``: the waiting /
#: 95 % / buffered comparison; the predefined paths of Sec 4.3.1 (quick: the first 30 step-points of p3);
#: every path of the section, with the short planned scenarios of Sec 4.2.2, for the 30 mm row (Sec 4.3.2).
_COMPARE = {False: (("j", None), ("p3", None)), True: (("j", None),)}
_PREDEFINED = {False: (("p1", None), ("p2", None), ("p3", None)), True: (("p3", 30),)}
_MOTION = {
    False: _PREDEFINED[False] + (("j", None), ("b", None), ("h", None)),
    True: (("p3", 30), ("j", None)),
}
_DEP = ("sim-arm", "speed-limits", "scene", "l1", "lengths")
SECTION = Section("Hardware execution (Sec 4.3, App. A)", depends_on=_DEP)
_ON_REAL_ARM = "`iik run SCENARIO --interface socketcan --channel can0 --bitrate 500000`"


@dataclass(frozen=True)
class SimArm:
    """The simulated arm a run uses (the form of the error rows).

    Attributes:
        lag: Tracking lag of the measured signals behind the set-point [s].
        error_scale: Factor the run log's errors are read with (1: metres as logged; a slip reads them in
            the wrong unit).
    """

    lag: float = LAG
    error_scale: float = 1.0


@dataclass(frozen=True)
class SimRun:
    """One execution of a planned scenario on the simulated arm.

    Attributes:
        name: Scenario name (with ``[:n]`` if only the first n step-points ran).
        steps: Number of step-points.
        rests: Times a joint came to rest between two consecutive steps.
        changes: Step changes (6 joints x (steps - 2)).
        ee_error: (m,) step-point end-effector errors [m] (FK of the measured joints, Eq 4; as the run log
            is read: :attr:`SimArm.error_scale`).
        min_clearance: Smallest whole-arm clearance (Coal) of all measured joint
            samples to the scenario's boxes, platform and floor [m].
    """

    name: str
    steps: int
    rests: int
    changes: int
    ee_error: np.ndarray
    min_clearance: float

    @property
    def errors(self) -> str:
        """The largest and the mean step-point error in words [mm]."""
        return f"max {self.ee_error.max() * 1e3:.2f} mm, mean {self.ee_error.mean() * 1e3:.2f} mm"


@per_run
def _planned(ctx, name: str, limit: int | None):
    """(validated trajectory, scenario) for a shipped scenario, planned as ``iik run`` does
    (:func:`hardware.sources.scenario_trajectory`: the project's planner, step-points at the times
    ``iik plan`` writes for them, TOPP-RA within the Sec 3.2 limits)."""
    path = scenario_path(name)
    return scenario_trajectory(path).validate(limit=limit), load_scenario(path)


def execute_scenario(
    ctx,
    name: str,
    *,
    update: str = "thesis",
    early: float = EARLY_UPDATE,
    limit: int | None = None,
    lag: float = LAG,
    latency: float = LATENCY_SCALE,
) -> SimRun:
    """Plan ``name``, execute it on a fresh simulated arm with tracking lag ``lag`` [s] (starting at
    the first step-point) on the fast-forward clock counting ``latency`` of the host's time, and
    analyse the run log. Cached per run."""
    key = ("hardware.run", name, limit, update, float(early), float(lag), float(latency))
    if key in ctx.cache:
        return ctx.cache[key]
    traj, scenario = _planned(ctx, name, limit)
    ff = FastForwardClock(FAST_FORWARD, latency)
    options = ExecutionOptions(early=early, update=update, sample_period=SAMPLE_PERIOD)
    with tempfile.TemporaryDirectory(prefix="iik-verify-hw-") as tmp:
        log_path = Path(tmp) / f"{name}.jsonl"
        with simulated_arm(
            initial=traj.q[0], clock=ff.now, lag=lag, timeout=REQUEST_TIMEOUT, arm=THESIS_ARM
        ) as (sim, arm):
            arm.open()
            execute(arm, traj, log_path, options=options, clock=ff.now, sleep=ff.sleep)
            rests = sum(len(m.stops) for m in sim.modules.values())
            errors = list(sim.errors)
        run = read_run_log(log_path)
    if errors:
        raise SimulatorError(f"simulated arm raised while serving {name}: {errors[:3]}")
    checker = SceneCollision(scenario.obstacles, arm=THESIS_ARM)
    clearance = float(min(checker.nearest(q).distance for q in run.samples_q))
    label = name if limit is None else f"{name}[:{limit}]"
    ctx.cache[key] = SimRun(
        label, len(traj), rests, 6 * max(len(traj) - 2, 0), analyse(run).ee_error, clearance
    )
    return ctx.cache[key]


# ----------------------------------------------------------------------------- Table V
_ROUND_TRIP = (
    "a round trip of our driver against our simulated modules, both written from the same protocol "
    "description (docs/POWERCUBE.md)"
)
#: The frame each Table V function must put on the bus (POWERCUBE.md): type and (plain) mode, param or cmd.
_WIRE = {
    "moveStep": (P.SetMove, P.Mode.FSTEP),
    "moveRamp": (P.SetMove, P.Mode.FRAMP),
    "moveVel": (P.SetMove, P.Mode.FVEL),
    "moveCur": (P.SetMove, P.Mode.FCUR),
    "setMaxCur": (P.SetParam, P.Param.FMAXCUR),
    "homeAll": (P.Broadcast, P.Cmd.HOME),
    "homeModule": (P.Command, P.Cmd.HOME),
}


@SECTION.check(
    _ORDER,
    depends_on=("sim-arm",),
    by_construction=_ROUND_TRIP
    + ": it tests the software; the thesis's command set has no printed form to vary",
)
def check_table_v(ctx) -> Row:
    """Every Table V function round-trips against the simulated modules."""
    ff = FastForwardClock(FAST_FORWARD, LATENCY_SCALE)
    clock, wait_for = ff.now, ff.sleep  # waits in simulated time [s]
    q0 = np.full(6, 0.1)  # [rad], away from home
    ok: dict[str, bool] = {}

    def wait_until(states_ok, what: str, limit: float = 10.0) -> float:
        """Poll the modules' states every 2 ms of simulated time until ``states_ok(states)``; returns the
        simulated time it became true (``limit``: real seconds before giving up)."""
        deadline = time.monotonic() + limit
        while not states_ok(arm.states()):
            if time.monotonic() > deadline:
                raise SimulatorError(f"simulated modules: {what} not within {limit} s")
            wait_for(0.002)
        return clock()

    def wait_still() -> float:
        """Wait until no module is in progress or moving, then let the measurement catch up (the
        simulator's lag); returns the (simulated) time at which the set-points had stopped."""
        busy = P.State.INPROGRESS | P.State.MOTION
        done = wait_until(lambda states: not any(s & busy for s in states), "at rest")
        wait_for(0.1)  # > the simulator's tracking lag
        return done

    def homed(n: int):
        """The first ``n`` modules homed and at rest."""
        return lambda states: all(s & P.State.HOME_OK and not s & P.State.MOTION for s in states[:n])

    with simulated_arm(initial=q0, clock=clock, timeout=REQUEST_TIMEOUT, arm=THESIS_ARM) as (sim, arm):
        states = arm.open()  # PCube_openDevice: every module answers VERSION
        ok["openDevice"] = len(states) == 6 and all(m.version() == SIM_VERSION for m in arm.modules)
        ok["getPos"] = np.allclose(arm.get_pos(), q0, atol=1e-6)
        ok["getVel"] = np.allclose(arm.get_vel(), 0.0, atol=1e-9)
        ok["getCur"] = np.all(np.isfinite(arm.get_cur()))
        arm.set_max_cur(1.5)  # [A]
        back = np.array([m.get_param(P.Param.FMAXCUR) for m in arm.modules])
        ok["setMaxCur"] = np.allclose(back, 1.5) and np.all(np.abs(arm.get_cur()) <= 1.5 + 1e-6)
        first = arm.modules[0]
        first.home()  # PCube_homeModule
        wait_until(homed(1), "module 1 homed")
        ok["homeModule"] = abs(first.get_pos()) < 1e-6 and np.allclose(arm.get_pos()[1:], q0[1:], atol=1e-6)
        arm.home_all()  # PCube_homeAll (broadcast)
        wait_until(homed(6), "all modules homed")
        ok["homeAll"] = np.allclose(arm.get_pos(), 0.0, atol=1e-6)
        # PCube_moveRamp: 0.2 rad at 0.3 rad/s, 0.6 rad/s^2: trapezoid of d/v + v/a = 1.17 s
        d, v, a = 0.2, 0.3, 0.6
        t_cmd = clock()
        arm.move_ramp(np.full(6, d), v, a)
        waited = wait_still() - t_cmd
        ok["moveRamp"] = np.allclose(arm.get_pos(), d, atol=1e-5) and waited >= 0.95 * (d / v + v / a)
        # PCube_moveStep: -0.15 rad in 0.5 s at constant velocity -0.3 rad/s, then at rest at the target
        T, dq = 0.5, -0.15
        t_cmd = clock()
        arm.move_step(np.full(6, d + dq), T)
        wait_for(0.5 * T)
        mid_vel = arm.get_vel()
        step_time = wait_still() - t_cmd  # >= T: every module starts after t_cmd
        ok["moveStep"] = (
            np.allclose(mid_vel, dq / T, rtol=1e-3)
            and np.allclose(arm.get_pos(), d + dq, atol=1e-5)
            and T <= step_time < T + 0.5
        )
        # PCube_moveVel: 0.2 rad/s, then 0
        arm.move_vel(0.2)
        wait_for(0.5)
        ok["moveVel"] = np.allclose(arm.get_vel(), 0.2, atol=1e-6)
        arm.move_vel(0.0)
        # PCube_moveCur: +0.5 A; the simulator's (assumed) model turns it into motion in the current's
        # direction; the payload behaviour of Table V's description is not modelled
        arm.move_cur(0.5)
        wait_for(0.3)
        ok["moveCur"] = np.all(arm.get_vel() > 0.0)
        arm.move_vel(0.0)
        time.sleep(0.05)
        received = [m for _, m in sim.received()]
        serving_errors = list(sim.errors) + ([f"{sim.malformed} malformed"] if sim.malformed else [])
    ok["closeDevice"] = not serving_errors  # bus shut down by the context manager
    seen = {
        (type(m), m.mode.plain if isinstance(m, P.SetMove) else getattr(m, "param", getattr(m, "cmd", None)))
        for m in received
    }
    for fn, sig in _WIRE.items():
        ok[fn] = ok[fn] and sig in seen
    steps_ms = sorted(
        {m.time_ms for m in received if isinstance(m, P.SetMove) and m.mode.plain is P.Mode.FSTEP}
    )
    good = [f for f, v in ok.items() if v]
    bad = [f for f, v in ok.items() if not v]
    return Row(
        basis=_ROUND_TRIP + ": it shows the software agrees with itself, not that the real modules behave "
        "as Table V says",
        domain="every Table V function once, on six simulated modules",
        claim="The command set of Table V (App. A) works as described; the path is followed with the "
        "constant-velocity function PCube_moveStep, which receives a goal position and a time (Sec 4.3)",
        reference="Sec 4.3, App. A, Table V",
        method="hardware driver (python-can) against the in-process simulated modules on a virtual bus, "
        "fast-forward clock counting 1/100 of the host's time: each function's frame observed on the bus "
        "(POWERCUBE.md) and its effect read back: VERSION of 6 modules; getPos = initial 0.1 rad; getVel = "
        "0; setMaxCur 1.5 A read back (FMAXCUR) and |getCur| <= 1.5 A; home one module, then homeAll -> 0 "
        "rad; moveRamp 0.2 rad at 0.3 rad/s, 0.6 rad/s^2 (>= trapezoid time); moveStep -0.15 rad in 0.5 s "
        "(mid-step velocity -0.3 rad/s, target reached); moveVel 0.2 rad/s; moveCur +0.5 A moves forward",
        numbers=f"{len(good)}/{len(ok)} Table V functions round-trip "
        f"({', '.join('PCube_' + f for f in good)})"
        + (f"; FAILED: {', '.join('PCube_' + f for f in bad)}" if bad else "")
        + f"; FSTEP times on the wire: {steps_ms} ms; moveStep mid-step velocity "
        f"{float(np.mean(mid_vel)):.4f} rad/s, step done after {step_time:.3f} s",
        verdict=Verdict.IDENTITY if not bad else Verdict.DOES_NOT_HOLD,
        reason="" if not bad else f"{', '.join(bad)} did not round-trip",
    )


# ----------------------------------------------------------------------------- Sec 4.3, the real arm
_REAL = (
    "it is a statement about the real PowerCube arm (its joints stopping and vibrating, its measured "
    "errors): no real arm is attached to `iik verify`; the simulation that reproduces it is the project "
    "row below it, whose verdict the simulator's assumed tracking lag decides"
)
_SIM_BASIS = (
    "hardware.sim's arm: FSTEP at constant velocity and measured signals lagging by an assumed "
    "pure delay (20 ms), not identified on the real modules; the verdict follows that assumption"
)


def _simulated(order: float, forms: dict, **options):
    """Register a check of a Sec 4.3 claim whose function grades it on the simulated arm (:func:`_graded`):
    its rows are the thesis's claim, not checkable without the real arm (id: the function's name), and the
    simulation (id ``.sim``, the row the self-test grades); ``forms``: the :class:`Forms` but its rows."""

    def register(func):
        sim_id = f"{func.__name__}.sim"

        @functools.wraps(func)
        def check(ctx, form) -> list[Row]:
            sim = func(ctx, form)
            real = Row(
                sim.claim,
                sim.reference,
                f"would need the real arm ({_ON_REAL_ARM})",
                f"simulated: {sim.verdict.value} (row {sim_id})",
                Verdict.NOT_CHECKABLE,
                reason=_REAL,
                id=func.__name__,
                domain="-",
            )
            return [
                real,
                sim.replace(id=sim_id, claim="(Project) reproduced on the simulated arm: " + sim.claim),
            ]

        return SECTION.check(order, forms=Forms(**forms, rows=(sim_id,)), **options)(check)

    return register


def _graded(claim, reference, method, numbers, measures, lag: float, reasons=None, **fields) -> Row:
    """The simulation of a Sec 4.3 claim, a project row graded by ``measures`` on the simulated arm with
    tracking lag ``lag`` [s] (consistent with our reconstruction, or not reproduced on it); ``method``
    follows the simulation's description. ``reasons``: (if it holds, if not)."""
    simulation = (
        "in-process simulated arm (hardware.sim: FSTEP = constant velocity to the target in the given time, "
        "joints at rest between steps that do not overlap; measured signals lag the set-point by a pure "
        f"delay of {lag * 1e3:.0f} ms, an assumption), host waits fast-forwarded and the host's own time "
        f"(bus round trips, computation) counted at {LATENCY_SCALE:g} of its length, samples every 30 ms; "
        "scenarios planned as `iik run` plans them (step-points at the times iik plan writes: TOPP-RA within "
        "the Sec 3.2 limits, whole ms), validated, streamed by hardware.executor; step-point error = "
        "|p(FK(measured q)) - planned p| (Eq 4, as in Sec 4.3)"
    )
    reason = f"on the simulated arm with a {lag * 1e3:.0f} ms lag (the real arm: see the not-checkable row)"
    holds, fails = reasons or (reason, reason)
    row = Row.graded(
        claim,
        reference,
        simulation + method,
        numbers,
        measures,
        fail=Verdict.NOT_REPRODUCED,
        holds_as=Verdict.RECONSTRUCTION,
        reason=fails,
        scope=Scope.PROJECT,
        basis=_SIM_BASIS,
        **fields,
    )
    return row.replace(reason=row.reason or holds)


@_simulated(
    _ORDER + 1,
    dict(
        printed=EARLY_UPDATE,
        good=EARLY_UPDATE,
        good_is="the printed 95 % (the simulation's model of the claim)",
        slips=(Slip(SlipKind.OFF_BY_ONE, "the next command after 100 % of the step (no early update)", 1.0),),
    ),
)
def check_early_update(ctx, early: float) -> Row:
    """Waiting for each step to finish stops the joints; the 95 % update removes the stops, adds error."""
    compared = _COMPARE[ctx.quick]
    schemes = (  # (label, executor options): waiting, the thesis's early update, ours
        ("waiting (100 %)", dict(early=1.0)),
        ("waiting (100 %)" if early >= 1.0 else f"thesis ({early * 100:.0f} %)", dict(early=early)),
        ("buffered", dict(update="buffered")),
    )
    runs = [[execute_scenario(ctx, name, limit=limit, **o) for _, o in schemes] for name, limit in compared]
    pairs = [(wait, thesis) for wait, thesis, _ in runs]
    fewest = min(w.rests for w, _ in pairs)
    left = max(t.rests / max(w.rests, 1) for w, t in pairs)
    added = min(t.ee_error.mean() - w.ee_error.mean() for w, t in pairs)
    m = (
        Measure("fewest joint rests of the waiting scheme", fewest, 1, bound=">="),
        Measure("largest share of the waiting scheme's rests left by the early update", left, 0.1),
        Measure(
            "smallest increase of the mean end-effector error by the early update",
            added,
            0.0,
            "m",
            bound=">=",
        ),
    )
    numbers = "; ".join(
        f"{r[0].name} ({r[0].steps} step-points, 5 % of the shortest step = "
        f"{0.05 * float(np.min(_planned(ctx, name, limit)[0].step_ms)):.1f} ms): "
        + ", ".join(
            f"{label}: {x.rests}/{x.changes} rests, EE error {x.errors}"
            for (label, _), x in zip(schemes, r, strict=True)
        )
        for r, (name, limit) in zip(runs, compared, strict=True)
    )
    if early == EARLY_UPDATE:  # ungraded: the same update with the host's bus round trips at full length
        real = [execute_scenario(ctx, n, early=early, limit=lim, latency=1.0) for n, lim in compared]
        numbers += (
            ". Not graded, with bus round trips at their real length on this host (load dependent): "
            + ", ".join(f"{r.name} {r.rests}/{r.changes} rests" for r in real)
        )
    return _graded(
        f"{title_of('Claim 4.13')} (Sec 4.3)",
        "Sec 4.3",
        ". Each scenario run three times: waiting (next command at 100 % of the step), "
        f"early update ({early * 100:.0f} %), buffered; rests = a joint at rest between two consecutive "
        "steps (SimModule.stops). Host latency is excluded from the graded runs (module docstring): the "
        "waiting scheme's next command then arrives within microseconds of the end of the step, so some of "
        "its step changes (about half or more) register as a rest and the count varies between runs, while "
        "the 95 % update is 5 % of a step (>= 2.5 ms) early, never a rest. Vibrations themselves need a "
        "structural model: not simulated",
        numbers + ". Buffered = ours: each step is queued in the modules' step buffer shortly before the "
        "current one ends, so no step is cut.",
        m,
        LAG,
        reasons=(
            "measured on the simulated arm (assumed lag); the real arm's vibrations are not checkable",
            "the early update did not remove the stops or did not add error",
        ),
        domain=f"scenarios {', '.join(n for n, _ in compared)}, every step-point",
    )


def _zone_rows(ctx, arm: SimArm, scenarios, zone: float, *more, what: str, per_run, **text) -> Row:
    """A safety-zone claim (Sec 4.3.1, 4.3.2): the largest step-point error of ``scenarios`` on ``arm``
    against ``zone`` [m], and ``more`` measures of the runs (``more(runs)``)."""
    runs = [execute_scenario(ctx, name, limit=limit, lag=arm.lag) for name, limit in scenarios]
    runs = [replace(r, ee_error=r.ee_error * arm.error_scale) for r in runs]  # as the arm's log is read
    worst = max(r.ee_error.max() for r in runs)
    return _graded(
        text["claim"] + " - checked for the method on a simulated arm",
        text["reference"],
        f"; thesis update (95 %); {text['method']}",
        "; ".join(per_run(r) for r in runs) + f"; worst {worst * 1e3:.2f} mm vs {zone * 1e3:.0f} mm",
        (Measure(f"largest step-point end-effector error{what}", worst, zone, "m"), *(f(runs) for f in more)),
        arm.lag,
        domain=", ".join(r.name for r in runs) + ": every step-point of each run",
    )


_ARM_FORMS = dict(
    printed=SimArm(),
    good=SimArm(),
    good_is="the simulated arm with its assumed lag (the printed form is the simulation's model)",
    slips=(Slip(SlipKind.UNIT, "the logged errors read in mm as m (x 1000)", SimArm(error_scale=1000.0)),),
)


@_simulated(_ORDER + 2, _ARM_FORMS)
def check_predefined_10mm(ctx, arm: SimArm) -> Row:
    """Sec 4.3.1: max end-effector error on predefined paths 1-3 <= 10 mm (the method, simulated)."""
    return _zone_rows(
        ctx,
        arm,
        _PREDEFINED[ctx.quick],
        SAFETY_ZONE_PREDEFINED,
        what="",
        per_run=lambda r: f"{r.name} ({r.steps} step-points): {r.errors}",
        claim=f"{title_of('Claim 4.14')}, here paths 1-3, so 10 mm is the minimum safety zone there "
        "(Sec 4.3.1, Figs 46-51)",
        reference="Sec 4.3.1",
        method="quick: first 30 step-points of p3 only" if ctx.quick else "p1, p2, p3 in full",
    )


@_simulated(_ORDER + 3, _ARM_FORMS, depends_on=_DEP + ("collision-shapes", "platform"))
def check_safety_zone_30mm(ctx, arm: SimArm) -> Row:
    """Sec 4.3.2: 30 mm is enough in motion; start and end errors are zero."""

    def clearance(runs) -> Measure:
        least = min(r.min_clearance for r in runs)
        return Measure("smallest whole-arm clearance of the measured motion", least, 0.0, "m", bound=">=")

    def ends(runs) -> Measure:
        worst = max(max(float(r.ee_error[0]), float(r.ee_error[-1])) for r in runs)
        return Measure("largest error at the start or end of a path", worst, 1e-4, "m")

    return _zone_rows(
        ctx,
        arm,
        _MOTION[ctx.quick],
        SAFETY_ZONE,
        clearance,
        ends,
        what=" in motion",
        per_run=lambda r: (
            f"{r.name}: {r.errors}, start {r.ee_error[0] * 1e3:.3f} mm, end {r.ee_error[-1] * 1e3:.3f} mm, "
            f"min measured clearance {r.min_clearance * 1e3:.1f} mm"
        ),
        claim=f"{title_of('Claim 4.16')}; {title_of('Claim 4.15')}: the early update does not compromise "
        "accuracy (Sec 4.3.2)",
        reference="Sec 4.3.2",
        method="every path executed in this section; whole-arm clearance (Coal, URDF collision shapes) of "
        "every measured joint sample to the scenario's boxes, platform and floor",
    )


@SECTION.check(
    _ORDER + 4,
    depends_on=("sim-arm",),
    by_construction="a statement about the real arm's measurements: always not checkable without it",
)
def check_real_arm(ctx) -> Row:
    return Row(
        claim=f"{title_of('Claim 4.17')}, hence the 10 mm and 30 mm zones as numbers of the real arm",
        reference="Sec 4.3.1, 4.3.2",
        method=f"would need the real arm: {_ON_REAL_ARM} logs the same step-point errors",
        numbers="-",
        verdict=Verdict.NOT_CHECKABLE,
        domain="none: the claim is about the real arm's measurements",
        reason="no real arm is attached to `iik verify`; the simulator's tracking lag (pure delay), current "
        "model and host latency are assumptions, not identified from the real modules, and the thesis gives "
        "no joint speeds, so the simulated errors are not the real arm's",
    )


# ----------------------------------------------------------------------------- App. A, Table V descriptions
#: What a Table V description may say a limit command limits, and the quantity's unit.
_UNITS = {"velocity": "rad/s", "current": "A", "position": "rad"}
_SET_MAX_CUR = "PCube_setMaxCur(0.3), then a 0.6 rad/s velocity command for 1 s"


@SECTION.check(
    _ORDER + 5,
    depends_on=("sim-arm", "text"),
    forms=Forms(
        printed="velocity",
        good="current",
        good_is="the value limits the current [A] (FMAXCUR)",
        slips=(
            Slip(SlipKind.UNIT, "the value in rad (a position limit)", "position"),
            Slip(SlipKind.UNIT, "the value in rad/s (a speed limit, as printed)", "velocity"),
        ),
    ),
)
def check_set_max_cur(ctx, quantity: str) -> Row:
    """Table V: PCube_setMaxCur limits ... 'by specifying the new value in rad/s' (``quantity``: what the
    value limits, in its unit :data:`_UNITS`)."""
    unit = _UNITS[quantity]
    ff = FastForwardClock(FAST_FORWARD, LATENCY_SCALE)
    with simulated_arm(clock=ff.now, timeout=REQUEST_TIMEOUT, arm=THESIS_ARM) as (sim, arm):
        arm.open()
        m = arm.modules[0]
        p0 = m.get_pos()
        m.set_max_cur(0.3)
        m.move_vel(0.6)  # [rad/s], twice "0.3 rad/s"
        ff.sleep(1.0)
        observed = {
            "velocity": abs(m.get_vel()),
            "current": abs(m.get_cur()),
            "position": abs(m.get_pos() - p0),
        }
        m.move_vel(0.0)
        frames = [msg for _, msg in sim.received() if isinstance(msg, P.SetParam) and msg.module == m.id]
    wrote = (
        f"0x{int(frames[0].param):02X}, {frames[0].param.name}, {frames[0].value}" if frames else "nothing"
    )
    held = min(observed, key=lambda k: abs(observed[k] - 0.3))  # the quantity the command held at 0.3
    misplaced = Reading(
        Kind.MOVED,
        "'rad/s' a unit misplaced from the neighbouring rows (PCube_getVel, PCube_moveRamp): this row's own "
        "'maximum current' gives A",
        {"unit": "A"},
    )
    return Row.graded(
        f"PCube_setMaxCur limits the {quantity}, 'specifying ... the new value in {unit}' (Table V)",
        "App. A, Table V",
        "the driver's PCube_setMaxCur(0.3) on the virtual bus (the frame it writes, POWERCUBE.md's parameter "
        f"table), then a 0.6 rad/s velocity command for 1 s on the simulated module: is the {quantity} held "
        f"at 0.3 {unit}?",
        f"SETPARAM written: ({wrote}); after 1 s: velocity {observed['velocity']:.3f} rad/s, current "
        f"{observed['current']:.3f} A, moved {observed['position']:.3f} rad",
        (Measure(f"|{quantity}| [{unit}] after {_SET_MAX_CUR}", observed[quantity], 0.3 * (1 + 1e-3)),),
        erratum=Erratum(
            "Table V (PCube_setMaxCur)",
            f"the new value in {unit}",
            "the new value in A (parameter FMAXCUR 0x4C, a current; speeds are FMAXVEL 0x48)",
            f"PCube_setMaxCur(0.3) writes ({wrote}); a 0.6 rad/s velocity command still reaches "
            f"{observed['velocity']:.2f} rad/s while the current is held at {observed['current']:.2f} A",
        ),
        domain=f"one simulated module: {_SET_MAX_CUR}",
    ).reread_if_erratum(
        lambda: search(
            {"unit": unit},
            [misplaced],
            lambda x: 0.0 if x["unit"] == _UNITS[held] else 1.0,
            0.0,
            printed=f"PCube_setMaxCur ... 'the new value in {unit}'",
            stated_text="'Sets the actual maximum current' (the same row); FMAXCUR (POWERCUBE.md)",
            route="the quantity the simulated module holds at 0.3 after PCube_setMaxCur(0.3)",
            measure="the printed unit differs from that quantity's (0 = same)",
        )
    )


@SECTION.check(
    _ORDER + 6,
    depends_on=("sim-arm", "text"),
    by_construction="a reading of the description: deciding it needs the real modules or a dynamics model of "
    "the joint under load (always not checkable here)",
)
def check_move_cur(ctx) -> Row:
    return Row(
        claim="PCube_moveCur 'starts a constant current motion ... keeps the speed of the joint constant no "
        "matter what the payload is' (Table V)",
        reference="App. A, Table V",
        method="reading: Table V describes PCube_moveVel the same way (current adapted to the payload to "
        "keep the speed constant); a constant current is a constant motor torque, so the speed changes with "
        "the payload. The simulator's FCUR model (velocity proportional to current) is an assumption and "
        "cannot decide it",
        numbers="-",
        verdict=Verdict.NOT_CHECKABLE,
        domain="Table V's description of PCube_moveCur (and of PCube_moveVel beside it)",
        reason="finding: the description is that of velocity control (PCube_moveVel), not of current "
        "control; deciding it needs the real modules or a dynamics model of the joint under load",
    )
