"""Plan a scenario end to end: thesis planner, whole-arm Coal check, fallbacks, timing.

:func:`plan` is the one entry point (``iik plan``, ``iik run``, the verify report,
the notebook and the benchmark use it). The attempts are an ordered sequence
of steps (Sec 3.6: "If any joint of the manipulator was found to be in a
collision path with an obstacle, the entire path is redesigned and verified
again"); each returns the first candidate path that passes the acceptance
rule, or None:

0. ``thesis LJI`` -- only for ``mode = "LJI"`` (Sec 2.6): IK at the key points,
   joints interpolated linearly; otherwise the LEI steps below;
1. ``thesis`` -- the thesis planner with the branch of least effort (Eq 54)
   that covers every step; ``thesis, other IK branch`` -- the other branches of
   the same path (``+ orientation search`` when no branch covers every step at
   the nominal orientation and :func:`~iik.planning.track_dp` found one);
2. ``thesis, arc route`` -- segments with steps without IK solutions are
   replaced by the arc route of Sec 4.2.1.1;
3. ``thesis, redesigned: ...`` -- the obstacles' ellipsoids padded by a further
   50 / 100 mm (the thesis pads only the tool point, not the gripper or the
   links), then via-points raised / moved radially (or one via-point added above
   the midpoint when there was none);
4. ``rrt-connect`` -- OMPL RRT-Connect in joint space on Coal checks.

Steps 2-4 run only with ``PlanOptions.fallbacks`` (step 4 also needs ``rrt``).
The acceptance rule (:meth:`PathClearance.keeps`): the certified whole-arm
clearance (steps and the motions between them,
:class:`~iik.planning.SceneCollision`) is at least the scenario's safety zone
and no two non-adjacent links touch. The accepted joint path is timed by
TOPP-RA within the arm's velocity and acceleration limits
(:func:`~iik.planning.time_parameterize`); every sample is checked against the
joint, velocity and acceleration limits, and the timed curve is checked for
clearance again. Every candidate checked is logged as an :class:`Attempt`.

Requested via-points (``planning.via_points``) are part of the acceptance
rule: the tool passes within :data:`VIA_POINT_TOLERANCE` of each, so the steps
that would move or drop them (moved via-points, RRT-Connect) are skipped and
logged, and a plan that cannot pass them fails and says so. The planner's own
via-points (Table IV, Sec 3.6.3) may be repelled, moved or dropped.

Bounded: the scenario's checks cap the step-points
(:data:`~iik.planning.MAX_STEP_POINTS`); ``PlanOptions.timeout`` bounds the
time. Every stage reports through ``progress`` (:class:`~iik.planning.Budget`:
each stage and candidate, and every second inside long loops); past the
timeout :func:`plan` stops at the next check and returns a failed result with
``timed_out`` set, the attempts so far and the best of them.

The arm is the scenario's (its file's ``arm`` key) or the one given (``arm=``; the two must
agree), and the result carries it (:attr:`PlanResult.arm`). It is used throughout: IK and joint
limits, workspace checks, the collision model (:func:`~iik.planning.robot_model.arm_model`) and
the timing limits.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from iik.arm import Arm
from iik.errors import InvalidInputError
from iik.ik.solve import compile_clock
from iik.joint_path import JointPath, branch_switches, path_effort
from iik.kinematics import fk
from iik.scene import THESIS_SCENE, Scene

from .budget import Budget
from .cartesian import CartesianPath, build_path
from .collision import PathClearance, SceneCollision
from .errors import PlanningTimeout, ScenarioError
from .path import interpolate_joints, path_length
from .rrt import rrt_connect
from .scenario import Scenario
from .scenario_io import dexterity_notes, load_scenario, scenario_arm, scenario_path, validate_scenario
from .timing import Trajectory, thesis_timing, time_parameterize
from .tracking import Tracking, all_solutions, track_branches, track_dp

__all__ = ["PlanOptions", "Attempt", "PlanResult", "plan", "VIA_POINT_TOLERANCE"]

#: An accepted path passes every requested via-point within this distance [m] (its tool points).
VIA_POINT_TOLERANCE = 1e-3

#: Bounds of the numeric options: (low, high, unit); the low end is exclusive for 0.
_BOUNDS = {"rrt_time": (0.0, math.inf, "s"), "resolution": (1e-4, 0.1, "m"), "dt": (1e-3, 1.0, "s"),
           "timeout": (0.0, math.inf, "s")}


@dataclass(frozen=True)
class PlanOptions:
    """Options of :func:`plan`.

    Attributes:
        fallbacks: Allow branches/arcs/moved via-points/RRT-Connect after the thesis path.
        rrt: Allow the OMPL fallback (with ``fallbacks``).
        rrt_time: OMPL time limit per attempt [s] (and at most what is left of ``timeout``).
        resolution: Continuous-check resolution [m], 0.1 mm .. 0.1 m (see
            ``SceneCollision.path_clearance``).
        dt: Trajectory sample period [s], 1 ms .. 1 s.
        seed: OMPL seed (1 .. 2**31).
        timing: Time-parameterise the accepted path.
        timeout: Wall-time budget of :func:`plan` [s] (60 s: a shipped scenario needs
            well under 10 s); past it the plan stops with ``timed_out`` set. A one-time compile
            of the IK kernel (the first plan after an install) is not counted
            (:func:`iik.ik.compile_clock`).

    Raises:
        InvalidInputError: An option has the wrong type or an impossible value (named).
    """

    fallbacks: bool = True
    rrt: bool = True
    rrt_time: float = 3.0
    resolution: float = 0.002
    dt: float = 0.01
    seed: int = 1
    timing: bool = True
    timeout: float = 60.0

    def __post_init__(self) -> None:
        for name in ("fallbacks", "rrt", "timing"):
            if not isinstance(getattr(self, name), bool):
                raise InvalidInputError(name, f"expected True or False, got {getattr(self, name)!r}")
        for name, (lo, hi, unit) in _BOUNDS.items():
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
                raise InvalidInputError(name, f"expected a positive finite number of {unit}, got {v!r}")
            if not lo <= v <= hi:
                raise InvalidInputError(name, f"must be in [{lo:g}, {hi:g}] {unit}, got {v!r}")
        if isinstance(self.seed, bool) or not isinstance(self.seed, (int, np.integer)) or not (
                1 <= self.seed <= 2**31):
            raise InvalidInputError("seed", f"expected an integer in 1..2**31, got {self.seed!r}")


@dataclass(frozen=True)
class Attempt:
    """One entry of the attempt log: a candidate path checked, or a step that produced none.

    Attributes:
        label: What was tried, e.g. ``"thesis path, IK branch 2 (0 switches)"``.
        accepted: The path kept the safety zone and became the plan.
        clearance: Certified lower bound of the whole-arm clearance along the path [m] (steps, motions);
            NaN when no path was checked.
        self_clearance: Smallest distance between non-adjacent links at the steps [m] (NaN: none).
        closest_link, closest_object: The pair at the step of smallest clearance.
        reason: Why no path was checked, a note on the step, or why a path that kept the
            safety zone was rejected (a requested via-point missed).
    """

    label: str
    accepted: bool = False
    clearance: float = float("nan")
    self_clearance: float = float("nan")
    closest_link: str = ""
    closest_object: str = ""
    reason: str = ""

    def __str__(self) -> str:
        if math.isnan(self.clearance):
            return f"{self.label}: {self.reason}"
        return (f"{self.label}: clearance certified >= {self.clearance * 1000:.1f} mm "
                f"(nearest: {self.closest_link} to {self.closest_object}), "
                f"self {self.self_clearance * 1000:.1f} mm"
                + (f" -- {self.reason}" if self.reason else "") + (" -> accepted" if self.accepted else ""))


@dataclass(frozen=True)
class PlanResult:
    """Outcome of planning one scenario.

    Attributes:
        scenario: The input.
        success: True iff a path keeps the safety zone everywhere and its timing
            respects every limit.
        method: Which step produced the path (module docstring), or ``"none"``.
        reason: Why it failed (empty on success).
        q: (n, 6) joint path [rad] at the step-points.
        points: (n, 3) tool points [m] (forward kinematics of ``q``).
        effort: (n,) effort index of Eq 54 [rad].
        clearance: Whole-arm clearance (:class:`PathClearance`) of ``q``.
        min_clearance: A certified lower bound on the whole-arm clearance along ``q`` [m]: the exact
            distance at the steps and, between them, motion bounds refined only until the safety zone
            is proven (so it can lie well below the true minimum; ``clearance.step`` has the steps).
        path_length: Tool path length [m] (FK of the joint path, fine sampling).
        branch_switches: Step indices where the IK branch jumped.
        failed_steps: Steps of the thesis path without IK solution at the nominal orientation.
        beta_changed_steps: Steps of ``cartesian`` where beta was changed (Sec 3.6).
        alpha_changed_steps: Steps of ``cartesian`` where alpha was changed (Sec 3.6: "any alpha").
        gamma_changed_steps: Steps of ``cartesian`` where the gripper is turned by pi about its
            axis (gamma + pi, the same grasp for the symmetric gripper; theta6 -/+ pi).
        planning_time: Wall time of :func:`plan` without timing [s].
        timed_out: The plan stopped at ``PlanOptions.timeout`` (``success`` False; ``reason``
            says during what; ``q`` is the accepted path if only its timing was cut short).
        attempts: Every candidate checked, in order (:class:`Attempt`).
        notes: Advisory notes on the scenario (start/goal outside the Sec 3.5 dexterity range).
        cartesian: The thesis Cartesian path of the accepted attempt (None for RRT).
        trajectory: TOPP-RA timing of ``q`` (None if not timed / failed).
        thesis_trajectory: The thesis's timing (velocity proportional to effort).
        trajectory_clearance: Certified whole-arm clearance of the timed trajectory [m].
        arm: The arm planned for.
        scene: The scene planned in.
    """

    scenario: Scenario
    success: bool
    method: str
    reason: str
    q: np.ndarray
    points: np.ndarray
    effort: np.ndarray
    clearance: PathClearance | None
    min_clearance: float
    path_length: float
    branch_switches: tuple[int, ...]
    failed_steps: tuple[int, ...]
    beta_changed_steps: tuple[int, ...]
    alpha_changed_steps: tuple[int, ...]
    gamma_changed_steps: tuple[int, ...]
    planning_time: float
    attempts: tuple[Attempt, ...]
    notes: tuple[str, ...]
    cartesian: CartesianPath | None
    trajectory: Trajectory | None
    thesis_trajectory: Trajectory | None
    trajectory_clearance: float
    arm: Arm
    scene: Scene
    timed_out: bool = False

    @property
    def best_attempt(self) -> Attempt | None:
        """The checked candidate of largest clearance (the accepted one if any); None if none was checked."""
        return _best(self.attempts)

    @property
    def log(self) -> tuple[str, ...]:
        """The notes and every attempt, one display line each."""
        return self.notes + tuple(str(a) for a in self.attempts)

    def summary(self) -> str:
        """A few display lines: outcome, clearances, changes, durations (mm and s)."""
        s = self.scenario
        head = f"{s.name}: {'OK' if self.success else 'FAILED'} via {self.method}"
        if not self.success:
            head += f" -- {self.reason}"
        tr = self.trajectory
        certified = (f"whole-arm clearance certified >= {self.min_clearance * 1000:.1f} mm"
                     if np.isfinite(self.min_clearance) else "no path to certify a clearance for")
        timed = (f"timed-trajectory clearance {self.trajectory_clearance * 1000:.1f} mm"
                 if np.isfinite(self.trajectory_clearance) else "not timed")
        return (f"{head}\n  steps {len(self.q)}, tool path {self.path_length:.3f} m, {certified} "
                f"(safety zone {s.safety_zone * 1000:.0f} mm), branch switches {len(self.branch_switches)}, "
                f"beta/alpha/gamma+pi changed at {len(self.beta_changed_steps)}/"
                f"{len(self.alpha_changed_steps)}/{len(self.gamma_changed_steps)} "
                f"steps, {timed}, planning {self.planning_time * 1000:.0f} ms"
                + (f"\n  duration {tr.duration:.2f} s (TOPP-RA) vs {self.thesis_trajectory.duration:.2f} s "
                   "(thesis: velocity proportional to effort)"
                   if tr is not None and self.thesis_trajectory else ""))


def plan(scenario: Scenario | str | Path, options: PlanOptions = PlanOptions(), *, arm: Arm | None = None,
         scene: Scene = THESIS_SCENE, progress: Callable[[str], None] | None = None) -> PlanResult:
    """Plan, check and time one scenario for ``arm`` in ``scene``.

    Args:
        scenario: A :class:`Scenario`, a TOML file, or the name of a shipped scenario (``"j"``).
        options: :class:`PlanOptions`.
        arm: The arm (IK, joint limits, workspace, collision shapes, timing limits); None: the
            scenario's own (its file's ``arm`` key, :attr:`Scenario.arm`). Both given, they must
            be the same arm.
        scene: Platform and floor.
        progress: Called with a short message before each stage and candidate, and
            every second inside long loops (:class:`~iik.planning.Budget`).

    Raises:
        ScenarioError: The scenario names no arm and none is given, or names another one; the
            file is malformed, or start/goal/requested via-points are
            impossible (inside an obstacle, the platform, below the floor, outside the
            workspace), or the path would exceed :data:`~iik.planning.MAX_STEP_POINTS`.
        TimingError, SamplingError: TOPP-RA or OMPL failed.

    Returns:
        :class:`PlanResult`; ``success`` False with ``reason`` when no step keeps
        the safety zone and passes the requested via-points, or when ``options.timeout``
        ran out (``timed_out``) (a failure is a result, not an exception; use
        ``raise PlanningFailed(result)`` to turn it into one).
    """
    p = _problem(scenario, options, arm, scene, progress)
    log: list[Attempt] = []
    try:
        with compile_clock(p.budget.exclude):  # a one-time compile of the IK kernel is not planning
            p.budget.stage(f"IK along the thesis path ({p.thesis.n} step-points)")
            p = dataclasses.replace(p, tracking=track_branches(p.thesis, arm=p.arm, adapt_orientation=False,
                                                               budget=p.budget))
            for step in _steps(options):
                found = step(p, log)
                if found is not None:
                    return _result(p, found, log)
    except PlanningTimeout as exc:
        return _failed(p, log, _timeout_reason(exc, log), timed_out=True)
    vias = " through the requested via-points" if p.scenario.via_points else ""
    reason = ("thesis path rejected (fallbacks off)" if not options.fallbacks else
              f"no method kept the safety zone{vias}; last attempts: " + " | ".join(str(a) for a in log[-2:]))
    return _failed(p, log, reason)


def _best(attempts) -> Attempt | None:
    """The checked attempt of largest clearance, accepted ones first (None if none was checked)."""
    checked = [a for a in attempts if not math.isnan(a.clearance)]
    return max(checked, key=lambda a: (a.accepted, a.clearance), default=None)


def _timeout_reason(exc: PlanningTimeout, log: list[Attempt]) -> str:
    best = _best(log)
    return (f"timed out after {exc.elapsed:.1f} s (timeout {exc.timeout:g} s: PlanOptions.timeout) "
            f"during {exc.stage}; "
            + (f"best attempt so far: {best}" if best else "no candidate path was checked"))


@dataclass(frozen=True)
class _Problem:
    """The inputs every step reads: the scenario, options, arm, scene, collision model, thesis path."""

    scenario: Scenario
    options: PlanOptions
    arm: Arm
    scene: Scene
    checker: SceneCollision
    thesis: CartesianPath
    notes: tuple[str, ...]
    budget: Budget
    tracking: Tracking | None = None  # IK along the thesis path at the nominal orientation (Sec 3.6)

    @property
    def required(self) -> float:
        """The clearance every accepted path keeps [m]: the scenario's safety zone."""
        return self.scenario.safety_zone


@dataclass(frozen=True)
class _Candidate:
    """An accepted path: the step's method name, joints, clearance, and (thesis) Cartesian path + branch."""

    method: str
    q: np.ndarray
    clearance: PathClearance
    cartesian: CartesianPath | None = None
    branch: JointPath | None = None


def _scenario(scenario, arm: Arm | None, scene: Scene) -> Scenario:
    """The scenario, validated, carrying the arm it is planned for (its own, or ``arm``)."""
    if isinstance(scenario, Scenario):
        scenario = dataclasses.replace(scenario, arm=scenario_arm(scenario, arm))
        validate_scenario(scenario, arm=scenario.arm, scene=scene)
        return scenario
    if isinstance(scenario, (str, Path)):
        return load_scenario(scenario_path(scenario), arm=arm, scene=scene)
    raise InvalidInputError("scenario", "expected a Scenario, a scenario file or a shipped scenario name, "
                                        f"got {type(scenario).__name__}")


def _problem(scenario, options, arm, scene, progress) -> _Problem:
    """Check the arguments, load and validate the scenario, build the thesis path (bounded, not timed)."""
    for name, value, kind in (("options", options, PlanOptions), ("scene", scene, Scene)):
        if not isinstance(value, kind):
            raise InvalidInputError(name, f"expected {kind.__name__}, got {type(value).__name__}")
    budget = Budget(options.timeout, progress)
    with compile_clock(budget.exclude):
        sc = _scenario(scenario, arm, scene)
        budget.say("thesis path (Sec 3.6)")
        thesis = build_path(sc, scene=scene)
        notes = tuple(dexterity_notes(sc, sc.arm))
    return _Problem(scenario=sc, options=options, arm=sc.arm, scene=scene,
                    checker=SceneCollision(sc.obstacles, arm=sc.arm, scene=scene), thesis=thesis,
                    notes=notes, budget=budget)


# ---------------------------------------------------------------------------- the acceptance rule


def _check(p: _Problem, q: np.ndarray, label: str, log: list[Attempt]) -> PathClearance | None:
    """The acceptance rule, logged: certified whole-arm clearance of ``q`` and the requested via-points.

    Returns the clearance if the path is accepted, else None.
    """
    p.budget.stage(f"whole-arm check: {label}")
    pc = p.checker.path_clearance(q, p.required, resolution=p.options.resolution, budget=p.budget)
    missed = _missed_via_point(p, q)
    ok = pc.keeps(p.required) and not missed
    log.append(Attempt(label, ok, pc.minimum, pc.self_min, pc.closest_link, pc.closest_object, missed))
    return pc if ok else None


def _missed_via_point(p: _Problem, q: np.ndarray) -> str:
    """The requested via-point the tool of ``q`` misses by over :data:`VIA_POINT_TOLERANCE` ("" if none)."""
    if not p.scenario.via_points:
        return ""
    tool = fk(q, p.arm)[:, :3, 3]
    for i, v in enumerate(p.scenario.via_points):
        d = float(np.linalg.norm(tool - np.asarray(v), axis=1).min())
        if d > VIA_POINT_TOLERANCE:
            return f"misses the requested via-point planning.via_points[{i}] by {d * 1000:.1f} mm"
    return ""


def _follow(p: _Problem, cpath: CartesianPath, label: str, log: list[Attempt], method: str,
            other_branch: str | None = None, tracking: Tracking | None = None) -> _Candidate | None:
    """The first IK branch along ``cpath`` (least effort first) that keeps the safety zone.

    When no branch covers every step at the nominal orientation (and fallbacks
    are on) the orientation search (:func:`track_dp`) supplies the branches.
    """
    nominal = tracking or track_branches(cpath, arm=p.arm, adapt_orientation=False, budget=p.budget)
    tr = nominal
    no_sol = nominal.failed_steps
    if not tr.complete and p.options.fallbacks:
        p.budget.stage(f"orientation search (IK branches x orientation grid): {label}")
        tr = track_dp(cpath, arm=p.arm, budget=p.budget)
        label += " + orientation search"
        if tr.complete:
            log.append(Attempt(label, reason=f"{len(no_sol)} steps had no solution at the nominal "
                                             "orientation"))
    if not tr.complete:
        log.append(Attempt(label, reason=f"no IK branch covers every step ({len(no_sol)} steps without "
                                         f"solution at the nominal orientation, e.g. {list(no_sol[:5])})"))
        return None
    for k, b in enumerate(tr.complete):
        pc = _check(p, b.q, f"{label}, IK branch {b.start_solution} ({len(b.switches)} switches)", log)
        if pc is not None:
            name = method if k == 0 or other_branch is None else other_branch
            return _Candidate(name + (" + orientation search" if tr.orientation_search else ""), b.q, pc,
                              cpath, b)
        if not p.options.fallbacks:
            break
    return None


# ---------------------------------------------------------------------------- the steps, in order


def _lji(p: _Problem, log: list[Attempt]) -> _Candidate | None:
    """Sec 2.6 LJI: IK only at start, via-points and goal; joints interpolated linearly."""
    if p.scenario.mode != "LJI":
        return None
    kpath = p.thesis.key_path()
    for k, b in enumerate(track_branches(kpath, arm=p.arm, budget=p.budget).complete):
        q = interpolate_joints(b.q, max_joint_step=0.05)
        if (pc := _check(p, q, f"LJI (Sec 2.6), key IK branch {b.start_solution}", log)) is not None:
            return _Candidate("thesis LJI" if k == 0 else "thesis LJI, other IK branch", q, pc, kpath, b)
    log.append(Attempt("LJI", reason="no key-point branch keeps the safety zone; falling back to LEI"))
    return None


def _thesis(p: _Problem, log: list[Attempt]) -> _Candidate | None:
    """The thesis path (Sec 3.6) on the branch of least effort, then its other IK branches."""
    return _follow(p, p.thesis, "thesis path", log, "thesis", "thesis, other IK branch", p.tracking)


def _arc_route(p: _Problem, log: list[Attempt]) -> _Candidate | None:
    """Arcs instead of the straight segments that had steps without IK solutions (Sec 4.2.1.1)."""
    cpath, no_sol = p.thesis, p.tracking.failed_steps
    if not no_sol or "line" not in cpath.routes:
        return None
    bad = {int(cpath.segment[i]) for i in no_sol}
    routes = tuple("arc" if (k in bad and r == "line") else r for k, r in enumerate(cpath.routes))
    if routes == cpath.routes:
        return None
    p.budget.stage("arc route (Sec 4.2.1.1)")
    label = f"arc route {routes}"
    planner_vias = None if p.scenario.via_points is not None else cpath.via_points  # requested: kept as given
    arcs = _build(p, log, label, p.scenario, via_points=planner_vias, routes=routes)
    return None if arcs is None else _follow(p, arcs, label, log, "thesis, arc route")


def _build(p: _Problem, log: list[Attempt], label: str, sc: Scenario, **kw) -> CartesianPath | None:
    """:func:`build_path` of a variant; None (logged) if it would exceed the step-point limit."""
    try:
        return build_path(sc, scene=p.scene, **kw)
    except ScenarioError as exc:
        log.append(Attempt(label, reason=str(exc)))
        return None


@dataclass(frozen=True)
class _Redesign:
    """One redesigned path: wider padding of the obstacles and/or other via-points and routes."""

    label: str
    via_points: np.ndarray | None
    routes: tuple[str, ...]
    padding: float = 0.0  # added to the safety zone of the ellipsoids [m]


def _redesigns(p: _Problem, log: list[Attempt]) -> _Candidate | None:
    """Wider padding around the obstacles (the thesis pads only the tool point), then moved via-points."""
    p.budget.stage("redesigned path (wider padding, moved via-points)")
    if p.scenario.via_points:
        log.append(Attempt("redesigns that move via-points", reason="skipped: the via-points are requested "
                                                                    "(planning.via_points)"))
    for r in _variants(p.scenario, p.thesis):
        p.budget.stage(f"redesigned path: {r.label}")
        sc = p.scenario if r.padding == 0 else dataclasses.replace(
            p.scenario, safety_zone=p.scenario.safety_zone + r.padding)
        cpath = _build(p, log, r.label, sc, via_points=r.via_points, routes=r.routes)
        if cpath is not None and (found := _follow(p, cpath, r.label, log, "thesis, redesigned: " + r.label)):
            return found
    return None


def _variants(sc: Scenario, cpath: CartesianPath):
    """Redesigns: wider padding; moved via-points (raised, radially; never requested ones); an added one."""
    v = cpath.via_points
    requested = sc.via_points is not None  # kept in place: build_path uses them when via_points is None
    if any(b.kind == "obstacle" for b in sc.obstacles):
        for pad in (0.05, 0.10):
            yield _Redesign(f"padding +{pad * 1000:.0f} mm", v if len(v) and not requested else None,
                            cpath.routes, pad)
    if len(v) and requested:
        return
    if len(v):
        for dz in (0.10, 0.20):
            yield _Redesign(f"via-points raised {dz:.2f} m", v + [0.0, 0.0, dz], cpath.routes)
        for f in (1.15, 0.85):
            yield _Redesign(f"via-points moved radially x{f:.2f}", v * [f, f, 1.0], cpath.routes)
    else:
        mid = 0.5 * (np.asarray(sc.start.position) + np.asarray(sc.goal.position))
        for dz in (0.15, 0.30):
            w = (mid + [0, 0, dz])[None]
            yield _Redesign(f"via-point added {dz:.2f} m above the midpoint", w, ("line", "line"))
            yield _Redesign(f"via-point added {dz:.2f} m above the midpoint (arcs)", w, ("arc", "arc"))


def _rrt_connect(p: _Problem, log: list[Attempt]) -> _Candidate | None:
    """OMPL RRT-Connect in joint space between the start/goal IK solutions that keep the zone."""
    if p.scenario.via_points:
        log.append(Attempt("rrt-connect", reason="skipped: it cannot pass the requested via-points "
                                                 "(planning.via_points)"))
        return None
    p.budget.stage("RRT-Connect (OMPL) in joint space")
    req = p.required
    ends = all_solutions(p.thesis.points[[0, -1]], p.thesis.euler[[0, -1]], arm=p.arm, budget=p.budget)[0]
    good = []
    for which, Q in zip(("start", "goal"), ends, strict=True):
        good.append([q for q in Q if p.checker.keeps(q, req)])
        if not good[-1]:
            log.append(Attempt("rrt-connect", reason=f"no {which} IK solution keeps {req * 1000:.0f} mm "
                                                     f"clearance ({len(Q)} solutions)"))
    if not (good[0] and good[1]):
        return None
    pairs = sorted(((a, b) for a in good[0] for b in good[1]),
                   key=lambda ab: float(np.abs(ab[0] - ab[1]).sum()))  # nearest pairs first
    for j, (qa, qb) in enumerate(pairs[:3]):
        p.budget.stage(f"RRT-Connect attempt {j}")
        limit = min(p.options.rrt_time, max(p.budget.remaining, 1e-3))
        P = rrt_connect(qa, qb, p.checker, required=req, arm=p.arm, time_limit=limit, seed=p.options.seed + j)
        if P is None:
            log.append(Attempt(f"rrt-connect attempt {j}", reason=f"no path in {limit:.1f} s"))
        elif (pc := _check(p, P, f"rrt-connect attempt {j} ({len(P)} states)", log)) is not None:
            return _Candidate("rrt-connect", P, pc)
    return None


def _steps(options: PlanOptions) -> tuple[Callable[[_Problem, list[Attempt]], _Candidate | None], ...]:
    """The steps :func:`plan` runs, in order (module docstring)."""
    if not options.fallbacks:
        return (_lji, _thesis)
    return (_lji, _thesis, _arc_route, _redesigns) + ((_rrt_connect,) if options.rrt else ())


# ---------------------------------------------------------------------------- the result


@dataclass(frozen=True)
class _Timed:
    trajectory: Trajectory | None = None
    thesis: Trajectory | None = None
    clearance: float = float("nan")
    reason: str = ""
    timed_out: bool = False


def _time(p: _Problem, q: np.ndarray) -> _Timed:
    """TOPP-RA timing within the arm's limits, its limit check, and the timed curve's clearance."""
    p.budget.stage("timing (TOPP-RA)")
    traj = time_parameterize(q, p.arm, dt=p.options.dt)
    thesis = thesis_timing(q, p.arm)
    if traj.violations:
        return _Timed(traj, thesis, reason="timing violates limits: " + "; ".join(traj.violations))
    # The timed curve is a spline through the checked waypoints: check it too.
    p.budget.stage("checking the timed trajectory")
    c = p.checker.path_clearance(traj.q, p.required, resolution=p.options.resolution,
                                 check_self=False, budget=p.budget).minimum
    reason = "" if c >= p.required else (
        f"timed trajectory comes within {c * 1000:.1f} mm of the scene (< {p.required * 1000:.0f} mm) "
        "between waypoints")
    return _Timed(traj, thesis, c, reason)


def _tool_length(q: np.ndarray, arm: Arm) -> float:
    """Length [m] of the tool's path along the joint path ``q``, sampled at <= 0.01 rad joint steps."""
    if len(q) < 2:
        return 0.0
    n = max(2, int(np.ceil(np.abs(np.diff(q, axis=0)).max(axis=1).sum() / 0.01)) + 1)
    s = np.linspace(0, len(q) - 1, min(n, 20 * len(q)))
    i = np.minimum(np.floor(s).astype(int), len(q) - 2)
    t = (s - i)[:, None]
    return path_length(fk(q[i] * (1 - t) + q[i + 1] * t, arm)[:, :3, 3])


def _result(p: _Problem, c: _Candidate, log: list[Attempt]) -> PlanResult:
    """The one result builder of an accepted path (timed when ``options.timing``)."""
    planning_time = p.budget.elapsed
    try:
        timed = _time(p, c.q) if p.options.timing else _Timed()
    except PlanningTimeout as exc:
        timed = _Timed(reason=_timeout_reason(exc, log), timed_out=True)
    b = c.branch
    return PlanResult(
        scenario=p.scenario, success=not timed.reason, method=c.method, reason=timed.reason, q=c.q,
        points=fk(c.q, p.arm)[:, :3, 3], effort=path_effort(c.q), clearance=c.clearance,
        min_clearance=c.clearance.minimum, path_length=_tool_length(c.q, p.arm),
        branch_switches=branch_switches(c.q), failed_steps=p.tracking.failed_steps,
        beta_changed_steps=b.changed_steps("beta") if b else (),
        alpha_changed_steps=b.changed_steps("alpha") if b else (),
        gamma_changed_steps=b.changed_steps("gamma") if b else (),
        planning_time=planning_time, attempts=tuple(log), notes=p.notes, cartesian=c.cartesian,
        trajectory=timed.trajectory, thesis_trajectory=timed.thesis, trajectory_clearance=timed.clearance,
        arm=p.arm, scene=p.scene, timed_out=timed.timed_out)


def _failed(p: _Problem, log: list[Attempt], reason: str, timed_out: bool = False) -> PlanResult:
    """The result when no step kept the safety zone (or the time ran out first)."""
    tr = p.tracking
    return PlanResult(
        scenario=p.scenario, success=False, method="none", reason=reason, q=np.zeros((0, 6)),
        points=np.zeros((0, 3)), effort=np.zeros(0), clearance=None, min_clearance=float("nan"),
        path_length=0.0, branch_switches=(), failed_steps=tr.failed_steps if tr else (),
        beta_changed_steps=tr.beta_changed_steps if tr else (),
        alpha_changed_steps=tr.alpha_changed_steps if tr else (),
        gamma_changed_steps=(), planning_time=p.budget.elapsed, attempts=tuple(log), notes=p.notes,
        cartesian=p.thesis, trajectory=None, thesis_trajectory=None, trajectory_clearance=float("nan"),
        arm=p.arm, scene=p.scene, timed_out=timed_out)
