"""Plan a scenario end to end: thesis planner, whole-arm Coal check, fallbacks, timing.

:func:`plan_scenario` is the one entry point used by ``iik plan``, ``iik run``
(hardware), the verify report and the benchmark. Order of attempts (Sec 3.6:
"If any joint of the manipulator was found to be in a collision path with an
obstacle, the entire path is redesigned and verified again"):

1. ``thesis`` -- the thesis planner (:mod:`iik.planning`) with the branch of
   least effort (Eq 54) that covers every step;
2. ``thesis, other IK branch`` -- the other IK branches of the same path;
3. ``thesis, arc route`` -- segments with steps without IK solutions are
   replaced by the arc route of Sec 4.2.1.1;
4. ``thesis, redesigned: ...`` -- the obstacles' ellipsoids padded by a further
   50 / 100 mm (the thesis pads only the tool point, not the gripper or the
   links), then via-points raised / moved radially (or one via-point added above
   the midpoint when there was none);
5. ``rrt-connect`` -- OMPL RRT-Connect in joint space on Coal checks.

A path is accepted when the certified whole-arm clearance (steps and the
motions between them, :class:`iik.planning.collision.SceneCollision`) is at
least the scenario's safety zone and no two non-adjacent links touch. The
accepted joint path is timed by TOPP-RA within the velocity and acceleration
limits (:func:`iik.planning.timing.time_parameterize`) and every sample is
checked against the joint, velocity and acceleration limits.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from iik import THESIS_ARM, Arm, branch_switches, fk, path_effort
from iik.errors import IIKError
from iik.planning import Scenario, build_path, track_branches
from iik.planning.path import interpolate_joints
from iik.planning.planner import CartesianPath, all_solutions, track_dp
from iik.scene import THESIS_SCENE, Scene

from .collision import PathClearance, SceneCollision
from .scenario_io import dexterity_notes, load_scenario, platform_box, validate_scenario
from .timing import Trajectory, thesis_timing, time_parameterize

__all__ = ["PlanOptions", "PlanResult", "plan_scenario", "PlanningFailed"]


class PlanningFailed(IIKError, RuntimeError):
    """No method produced a path that keeps the safety zone (see ``result.reason``)."""

    def __init__(self, result: PlanResult):
        self.result = result
        super().__init__(f"scenario {result.scenario.name!r}: {result.reason}")


@dataclass(frozen=True)
class PlanOptions:
    """Knobs of :func:`plan_scenario`.

    Attributes:
        fallbacks: Allow branches/arcs/moved via-points/RRT-Connect after the thesis path.
        rrt: Allow the OMPL fallback.
        rrt_time: OMPL time limit per attempt [s].
        resolution: Continuous-check resolution [m] (see ``SceneCollision.path_clearance``).
        dt: Trajectory sample period [s].
        seed: OMPL seed.
        timing: Time-parameterise the accepted path.
    """

    fallbacks: bool = True
    rrt: bool = True
    rrt_time: float = 3.0
    resolution: float = 0.002
    dt: float = 0.01
    seed: int = 1
    timing: bool = True


@dataclass(frozen=True)
class PlanResult:
    """Outcome of planning one scenario.

    Attributes:
        scenario: The input.
        success: True iff a path keeps the safety zone everywhere and its timing
            respects every limit.
        method: Which attempt produced the path (see module docstring), or "none".
        reason: Why it failed (empty on success).
        q: (n, 6) joint path [rad] at the step-points.
        points: (n, 3) tool points [m] (forward kinematics of ``q``).
        effort: (n,) effort index of Eq 54 [rad].
        clearance: Whole-arm clearance (:class:`PathClearance`) of ``q``.
        min_clearance: Smallest certified clearance [m].
        path_length: Tool path length [m] (FK of the joint path, fine sampling).
        branch_switches: Step indices where the IK branch jumped.
        failed_steps: Steps without IK solution in the thesis path (first attempt).
        beta_changed_steps: Steps where beta was changed (Sec 3.6).
        alpha_changed_steps: Steps where alpha was changed (Sec 3.6: "any alpha").
        gamma_changed_steps: Steps where the gripper is turned by pi about its axis
            (gamma + pi, the same grasp for the symmetric gripper; theta6 -/+ pi).
        planning_time: Wall time of :func:`plan_scenario` without timing [s].
        attempts: Log of every attempt.
        cartesian: The thesis Cartesian path of the accepted attempt (None for RRT).
        trajectory: TOPP-RA timing of ``q`` (None if not timed / failed).
        thesis_trajectory: The thesis's timing (velocity proportional to effort).
        trajectory_clearance: Certified whole-arm clearance of the timed trajectory [m].
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
    planning_time: float
    attempts: tuple[str, ...] = ()
    cartesian: CartesianPath | None = None
    trajectory: Trajectory | None = None
    thesis_trajectory: Trajectory | None = None
    trajectory_clearance: float = float("nan")
    gamma_changed_steps: tuple[int, ...] = ()

    def summary(self) -> str:
        s = self.scenario
        head = f"{s.name}: {'OK' if self.success else 'FAILED'} via {self.method}"
        if not self.success:
            head += f" -- {self.reason}"
        tr = self.trajectory
        return (f"{head}\n  steps {len(self.q)}, tool path {self.path_length:.3f} m, "
                f"min whole-arm clearance {self.min_clearance * 1000:.1f} mm "
                f"(safety zone {s.safety_zone * 1000:.0f} mm), branch switches {len(self.branch_switches)}, "
                f"beta/alpha/gamma+pi changed at {len(self.beta_changed_steps)}/"
                f"{len(self.alpha_changed_steps)}/{len(self.gamma_changed_steps)} "
                f"steps, timed-trajectory clearance {self.trajectory_clearance * 1000:.1f} mm, "
                f"planning {self.planning_time * 1000:.0f} ms"
                + (f"\n  duration {tr.duration:.2f} s (TOPP-RA) vs {self.thesis_trajectory.duration:.2f} s "
                   "(thesis: velocity proportional to effort)"
                   if tr is not None and self.thesis_trajectory else ""))


def _tool_length(q: np.ndarray, arm: Arm) -> float:
    if len(q) < 2:
        return 0.0
    n = max(2, int(np.ceil(np.abs(np.diff(q, axis=0)).max(axis=1).sum() / 0.01)) + 1)
    s = np.linspace(0, len(q) - 1, min(n, 20 * len(q)))
    i = np.minimum(np.floor(s).astype(int), len(q) - 2)
    t = (s - i)[:, None]
    Q = q[i] * (1 - t) + q[i + 1] * t
    p = fk(Q, arm)[:, :3, 3]
    return float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())


def plan_scenario(scenario: Scenario | str | Path, *, options: PlanOptions = PlanOptions(),
                  arm: Arm = THESIS_ARM, scene: Scene = THESIS_SCENE,
                  solve_many: Callable | None = None,
                  progress: Callable[[str], None] | None = None) -> PlanResult:
    """Plan, check and time one scenario (a :class:`Scenario` or a TOML path).

    Raises:
        ScenarioError: The file is malformed, or start/goal are impossible
            (inside an obstacle, the platform, below the floor, outside the workspace).

    Returns:
        :class:`PlanResult`; ``success`` False with ``reason`` when no method keeps
        the safety zone (no exception: the failure is a result). Use
        ``raise PlanningFailed(result)`` to turn it into an error.
    """
    t0 = time.perf_counter()
    say = progress or (lambda msg: None)
    if isinstance(scenario, (str, Path)):
        sc = load_scenario(scenario, scene=scene)
    else:
        sc = scenario
        validate_scenario(sc, scene=scene)
    plat = platform_box(scene)
    checker = SceneCollision(sc.obstacles, scene=scene)
    req = sc.safety_zone
    attempts: list[str] = list(dexterity_notes(sc))
    first_failed: tuple[int, ...] = ()
    first_beta: tuple[int, ...] = ()

    def try_path(cpath: CartesianPath, label: str, first: bool = False):
        nonlocal first_failed, first_beta
        branches, info = track_branches(cpath, solve_many=solve_many, adapt_orientation=False)
        no_sol = tuple(int(i) for i in np.flatnonzero(info["solutions_per_step"] == 0))
        if first:
            first_failed, first_beta = no_sol, info["beta_changed_steps"]
        complete = [b for b in branches if b.complete]
        if not complete and options.fallbacks:
            # Orientation search (alpha free, beta changed): least-effort dynamic programme.
            branches, info = track_dp(cpath, solve_many=solve_many)
            label += " + orientation search"
            if branches:
                attempts.append(f"{label}: {len(no_sol)} steps had no solution at the nominal orientation")
            complete = branches
        if not complete:
            attempts.append(f"{label}: no IK branch covers every step "
                            f"({len(no_sol)} steps without solution at the nominal orientation, "
                            f"e.g. {list(no_sol[:5])})")
            return None, no_sol
        for k, b in enumerate(complete):
            pc = checker.path_clearance(b.q, req, resolution=options.resolution)
            ok = pc.minimum >= req and pc.self_min > 0
            attempts.append(f"{label}, IK branch {b.start_solution} ({len(b.switches)} switches): "
                            f"min clearance {pc.minimum * 1000:.1f} mm ({pc.step_link[np.argmin(pc.step)]} "
                            f"to {pc.step_object[np.argmin(pc.step)]}), self {pc.self_min * 1000:.1f} mm"
                            + (" -> accepted" if ok else ""))
            if ok:
                info["label"] = label
                return (b, pc, k, info), no_sol
            if not options.fallbacks:
                break
        return None, no_sol

    def accept(b, pc, method, cpath, info):
        if "orientation search" in info.get("label", ""):
            method += " + orientation search"
        return _finish(sc, b.q, pc, method, cpath, b.switches, info["beta_changed_steps"],
                       info["alpha_changed_steps"], info.get("gamma_changed_steps", ()))

    def _finish(sc, q, pc, method, cpath, switches, beta_steps, alpha_steps, gamma_steps=(), reason=""):
        t_plan = time.perf_counter() - t0
        success = not reason
        traj = thesis = None
        traj_clear = float("nan")
        if options.timing and success:
            say("timing (TOPP-RA)")
            traj = time_parameterize(q, arm, dt=options.dt)
            thesis = thesis_timing(q, arm)
            if traj.violations:
                success, reason = False, "timing violates limits: " + "; ".join(traj.violations)
            else:
                # The timed curve is a spline through the checked waypoints: check it too.
                say("checking the timed trajectory")
                tc = checker.path_clearance(traj.q, sc.safety_zone, resolution=options.resolution,
                                            check_self=False)
                traj_clear = tc.minimum
                if traj_clear < sc.safety_zone:
                    success = False
                    reason = (f"timed trajectory comes within {traj_clear * 1000:.1f} mm of the scene "
                              f"(< {sc.safety_zone * 1000:.0f} mm) between waypoints")
        return PlanResult(
            scenario=sc, success=success, method=method if q is not None else "none", reason=reason,
            q=q if q is not None else np.zeros((0, 6)),
            points=fk(q, arm)[:, :3, 3] if q is not None and len(q) else np.zeros((0, 3)),
            effort=path_effort(q) if q is not None else np.zeros(0), clearance=pc,
            min_clearance=pc.minimum if pc is not None else float("nan"),
            path_length=_tool_length(q, arm) if q is not None else 0.0,
            branch_switches=tuple(switches), failed_steps=first_failed,
            beta_changed_steps=tuple(beta_steps), alpha_changed_steps=tuple(alpha_steps),
            planning_time=t_plan, attempts=tuple(attempts),
            cartesian=cpath, trajectory=traj, thesis_trajectory=thesis,
            trajectory_clearance=traj_clear, gamma_changed_steps=tuple(gamma_steps))

    say("thesis path (Sec 3.6)")
    cpath = build_path(sc, platform=plat, floor_z=scene.floor.z)
    if sc.mode == "LJI":
        # Sec 2.6: IK only at start, via-points and goal; joints interpolated linearly.
        keys = np.asarray(cpath.key_index)
        kpath = dataclasses.replace(cpath, points=cpath.points[keys], euler=cpath.euler[keys],
                                    segment=np.arange(len(keys)), key_index=tuple(range(len(keys))),
                                    repelled=cpath.repelled[keys], lifted=cpath.lifted[keys])
        branches, info = track_branches(kpath, solve_many=solve_many)
        for k, b in enumerate(b for b in branches if b.complete):
            q = interpolate_joints(b.q, max_joint_step=0.05)
            pc = checker.path_clearance(q, req, resolution=options.resolution)
            ok = pc.minimum >= req and pc.self_min > 0
            attempts.append(f"LJI (Sec 2.6), key IK branch {b.start_solution}: min clearance "
                            f"{pc.minimum * 1000:.1f} mm" + (" -> accepted" if ok else ""))
            if ok:
                return _finish(sc, q, pc, "thesis LJI" if k == 0 else "thesis LJI, other IK branch", kpath,
                               branch_switches(q), info["beta_changed_steps"], info["alpha_changed_steps"])
        attempts.append("LJI: no key-point branch keeps the safety zone; falling back to LEI")
    found, no_sol = try_path(cpath, "thesis path", first=True)
    if found:
        b, pc, k, info = found
        return accept(b, pc, "thesis" if k == 0 else "thesis, other IK branch", cpath, info)
    if not options.fallbacks:
        return _fail(sc, attempts, cpath, first_failed, first_beta, t0,
                     "thesis path rejected (fallbacks off)")

    # Arc route where a straight segment had steps without solutions (Sec 4.2.1.1).
    if no_sol and "line" in cpath.routes:
        bad = {int(cpath.segment[i]) for i in no_sol}
        routes = tuple("arc" if (k in bad and r == "line") else r for k, r in enumerate(cpath.routes))
        if routes != cpath.routes:
            say("arc route (Sec 4.2.1.1)")
            c2 = build_path(sc, platform=plat, floor_z=scene.floor.z, via_points=cpath.via_points,
                            routes=routes)
            found, _ = try_path(c2, f"arc route {routes}")
            if found:
                b, pc, k, info = found
                return accept(b, pc, "thesis, arc route", c2, info)

    # Redesign: a wider padding around the obstacles (the thesis pads only the tool
    # point), then moved via-points.
    say("redesigned path (wider padding, moved via-points)")
    for vias, routes, pad, label in _variants(sc, cpath):
        sc2 = sc if pad == 0 else dataclasses.replace(sc, safety_zone=sc.safety_zone + pad)
        c2 = build_path(sc2, platform=plat, floor_z=scene.floor.z, via_points=vias, routes=routes)
        found, _ = try_path(c2, label)
        if found:
            b, pc, k, info = found
            return accept(b, pc, "thesis, redesigned: " + label, c2, info)

    if options.rrt:
        say("RRT-Connect (OMPL) in joint space")
        from .rrt import rrt_connect

        ends = all_solutions(cpath.points[[0, -1]], cpath.euler[[0, -1]], solve_many=solve_many)[0]
        good = []
        for which, Q in zip(("start", "goal"), ends, strict=True):
            ok = [q for q in Q if checker._min(q)[0] >= req and checker._self(q) > 0]
            good.append(ok)
            if not ok:
                attempts.append(f"rrt-connect: no {which} IK solution keeps {req * 1000:.0f} mm clearance "
                                f"({len(Q)} solutions)")
        if good[0] and good[1]:
            pairs = sorted(((a, b) for a in good[0] for b in good[1]),
                           key=lambda ab: float(np.abs(ab[0] - ab[1]).sum()))[:3]
            for j, (qa, qb) in enumerate(pairs):
                P = rrt_connect(qa, qb, checker, required=req, arm=arm, time_limit=options.rrt_time,
                                seed=options.seed + j)
                if P is None:
                    attempts.append(f"rrt-connect attempt {j}: no path in {options.rrt_time:.1f} s")
                    continue
                pc = checker.path_clearance(P, req, resolution=options.resolution)
                ok = pc.minimum >= req and pc.self_min > 0
                attempts.append(f"rrt-connect attempt {j}: {len(P)} states, min clearance "
                                f"{pc.minimum * 1000:.1f} mm" + (" -> accepted" if ok else ""))
                if ok:
                    return _finish(sc, P, pc, "rrt-connect", None, branch_switches(P), (), ())
    return _fail(sc, attempts, cpath, first_failed, first_beta, t0, _reason(attempts))


def _reason(attempts: list[str]) -> str:
    return "no method kept the safety zone; last attempts: " + " | ".join(attempts[-2:])


def _fail(sc, attempts, cpath, failed, beta, t0, reason) -> PlanResult:
    return PlanResult(scenario=sc, success=False, method="none", reason=reason, q=np.zeros((0, 6)),
                      points=np.zeros((0, 3)), effort=np.zeros(0), clearance=None,
                      min_clearance=float("nan"), path_length=0.0, branch_switches=(),
                      failed_steps=failed, beta_changed_steps=beta, alpha_changed_steps=(),
                      planning_time=time.perf_counter() - t0, attempts=tuple(attempts), cartesian=cpath)


def _variants(sc: Scenario, cpath: CartesianPath):
    """Redesigns: wider padding; moved via-points (raised, radially); an added via-point."""
    v = cpath.via_points
    has_obstacles = any(b.kind == "obstacle" for b in sc.obstacles)
    if has_obstacles:
        for pad in (0.05, 0.10):
            yield (v if len(v) else None), cpath.routes, pad, f"padding +{pad * 1000:.0f} mm"
    if len(v):
        for dz in (0.10, 0.20):
            w = v.copy()
            w[:, 2] += dz
            yield w, cpath.routes, 0.0, f"via-points raised {dz:.2f} m"
        for f in (1.15, 0.85):
            w = v.copy()
            w[:, :2] *= f
            yield w, cpath.routes, 0.0, f"via-points moved radially x{f:.2f}"
    else:
        p0, p1 = np.asarray(sc.start.position), np.asarray(sc.goal.position)
        mid = 0.5 * (p0 + p1)
        for dz in (0.15, 0.30):
            w = (mid + [0, 0, dz])[None]
            yield w, ("line", "line"), 0.0, f"via-point added {dz:.2f} m above the midpoint"
            yield w, ("arc", "arc"), 0.0, f"via-point added {dz:.2f} m above the midpoint (arcs)"
