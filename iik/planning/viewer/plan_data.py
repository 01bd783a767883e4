"""What the viewer reads from the planner: one adapter, :func:`plan_scene`, and the per-frame clearance.

:func:`plan_scene` is the only function that reads a :class:`~iik.planning.PlanResult`
(and :func:`plan_for_view` the only one that calls the planner), so a change of the
planning API changes these two functions only. A plan that failed or timed out is
a view too: without an accepted path the arm stands at the start pose, and the
attempt log (:attr:`PlanView.attempts`, :attr:`PlanView.best`) and the reason say
what was tried. Frame: base frame 0 [m]; angles [rad]; times [s].
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import iik
from iik import Arm, fk
from iik.errors import IIKError
from iik.scene import THESIS_SCENE, Box, Scene

from ..cartesian import poses_of
from ..collision import Nearest, SceneCollision
from ..pipeline import Attempt, PlanOptions, PlanResult, plan

__all__ = ["PlanView", "plan_scene", "plan_for_view", "frame_clearance", "least_clearance", "UNTIMED_STEP"]

#: Seconds per step when a plan has no timed trajectory (the joint path is shown step by step).
UNTIMED_STEP = 0.2


@dataclass(frozen=True)
class PlanView:
    """The arrays and the attempt log the viewer draws for one plan.

    Attributes:
        name: Scenario name.
        headline: One line: outcome, method or reason, clearance, duration.
        success: The planner's verdict.
        method: The step that produced the path (``"none"`` without one).
        reason: Why the plan failed (empty on success).
        timed_out: The planner stopped at its time budget.
        attempts: The planner's attempt log, in order (:class:`~iik.planning.Attempt`).
        best: The accepted attempt, else the checked one of largest clearance (None: none checked).
        notes: Advisory notes on the scenario (start/goal outside the Sec 3.5 dexterity range).
        arm_shows: What the arm follows: the accepted path (timed or not), else the start pose.
        obstacles: Scenario boxes (obstacles and supports).
        safety_zone: Required clearance [m].
        t: (k,) frame times [s] (the TOPP-RA trajectory, or UNTIMED_STEP per step).
        q: (k, 6) joint angles at the frames [rad].
        step_q: (n, 6) joint path at the step-points [rad] (empty without an accepted path).
        step_points: (n, 3) tool step-points [m]: the accepted path's, else the rejected thesis path's.
        via_points: (m, 3) via-points [m].
        switch_steps: Step indices where the IK branch switched.
        switch_times: Frame time [s] of each switch (the frame nearest that step's configuration).
        arm: The arm planned for (its body, :func:`~iik.planning.robot_model.arm_model`, is drawn).
        scene: Platform and floor planned in.
        certified_clearance: The planner's certified lower bound on the whole-arm clearance along the
            accepted path, between steps included [m] (nan without an accepted path).
    """

    name: str
    headline: str
    success: bool
    method: str
    reason: str
    timed_out: bool
    attempts: tuple[Attempt, ...]
    best: Attempt | None
    notes: tuple[str, ...]
    arm_shows: str
    obstacles: tuple[Box, ...]
    safety_zone: float
    t: np.ndarray
    q: np.ndarray
    step_q: np.ndarray
    step_points: np.ndarray
    via_points: np.ndarray
    switch_steps: tuple[int, ...]
    switch_times: tuple[float, ...]
    arm: Arm
    scene: Scene = THESIS_SCENE
    certified_clearance: float = float("nan")


def _start_pose(result: PlanResult) -> tuple[np.ndarray, str]:
    """Where the arm stands without an accepted path: the least-effort IK solution of the start pose."""
    cart = result.cartesian
    if cart is not None and cart.n:
        try:
            q0 = iik.select(iik.solve(poses_of(cart.points[:1], cart.euler[:1])[0], arm=result.arm),
                            np.zeros(6), arm=result.arm)
            return q0, "the start pose (least-effort IK solution; no path was accepted)"
        except IIKError:
            pass
    return np.zeros(6), "the home pose q = 0 (no path was accepted; the start pose has no IK solution)"


def _headline(result: PlanResult, n_steps: int, switches: int) -> str:
    sc, traj = result.scenario, result.trajectory
    if not result.success:
        return f"{sc.name}: FAILED ({result.reason})"
    dur = f", {traj.duration:.2f} s (TOPP-RA)" if traj is not None else ""
    return (f"{sc.name}: OK via {result.method}; whole-arm clearance certified >= "
            f"{result.min_clearance * 1000:.1f} mm (safety zone {sc.safety_zone * 1000:.0f} mm), "
            f"{n_steps} step-points, {switches} IK branch switch(es){dur}")


def plan_scene(result: PlanResult) -> PlanView:
    """Adapter: the planner's result -> :class:`PlanView` (the one place that reads it)."""
    sc, cart, traj = result.scenario, result.cartesian, result.trajectory
    step_q = np.asarray(result.q, float).reshape(-1, 6)
    if traj is not None and len(traj.t):
        t, q = np.asarray(traj.t, float), np.asarray(traj.q, float)
        arm_shows = "the accepted path, timed by TOPP-RA"
    elif len(step_q):
        t, q = UNTIMED_STEP * np.arange(len(step_q)), step_q
        arm_shows = f"the accepted path, untimed ({UNTIMED_STEP} s per step-point)"
    else:
        q0, arm_shows = _start_pose(result)
        t, q = np.zeros(1), q0[None]
    if cart is not None and (len(cart.points) == len(step_q) or not len(step_q)):
        points = np.asarray(cart.points, float).reshape(-1, 3)
    else:
        points = fk(step_q, result.arm)[:, :3, 3] if len(step_q) else np.zeros((0, 3))
    via = np.asarray(cart.via_points, float).reshape(-1, 3) if cart is not None else np.zeros((0, 3))
    switches = tuple(int(i) for i in result.branch_switches)
    times = tuple(float(t[np.argmin(np.abs(q - step_q[i]).max(axis=1))]) for i in switches)
    return PlanView(
        name=sc.name, headline=_headline(result, len(step_q), len(switches)), success=bool(result.success),
        method=result.method, reason=result.reason, timed_out=bool(result.timed_out),
        attempts=tuple(result.attempts), best=result.best_attempt, notes=tuple(result.notes),
        arm_shows=arm_shows, obstacles=tuple(sc.obstacles), safety_zone=float(sc.safety_zone), t=t, q=q,
        step_q=step_q, step_points=points, via_points=via, switch_steps=switches, switch_times=times,
        arm=result.arm, scene=result.scene,
        certified_clearance=float(result.min_clearance) if result.success and len(step_q) else float("nan"))


def plan_for_view(scenario, options: PlanOptions | None = None, *, arm: Arm | None = None,
                  scene: Scene = THESIS_SCENE) -> PlanView:
    """Plan a scenario (a file, a shipped name or a :class:`~iik.planning.Scenario`) and adapt the result.

    ``arm``: the arm to plan for; None: the scenario's own (:func:`iik.planning.plan`).

    A plan that fails or times out is returned as a view (``success`` False), not raised.

    Raises:
        ScenarioError: The scenario does not exist or fails validation.
        InvalidInputError: ``options`` is not a :class:`~iik.planning.PlanOptions`.
    """
    return plan_scene(plan(scenario, options or PlanOptions(), arm=arm, scene=scene))


def frame_clearance(obstacles, q, *, arm: Arm, scene: Scene = THESIS_SCENE) -> tuple[Nearest, ...]:
    """The nearest arm link and scene object, their distance and nearest points at each ``q`` (k, 6) [rad]
    (:meth:`SceneCollision.nearest`, one per frame)."""
    checker = SceneCollision(tuple(obstacles), arm=arm, scene=scene)
    return tuple(checker.nearest(qk) for qk in np.asarray(q, float).reshape(-1, 6))


def least_clearance(frames: tuple[Nearest, ...]) -> int:
    """Index of the frame of least clearance (the first, on a tie)."""
    return int(np.argmin([n.distance for n in frames]))
