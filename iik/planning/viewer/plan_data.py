"""What the viewer reads from the planner: one adapter, :func:`plan_scene`, and the per-frame clearance.

The planner's result type is being restructured; :func:`plan_scene` is the only
function that reads it (and :func:`plan_for_view` the only one that calls the
planner), so a change of the planning API changes these two functions only.
Frame: base frame 0 [m]; angles [rad]; times [s].
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from iik import fk
from iik.scene import THESIS_SCENE, Scene

from ..collision import SceneCollision
from ..obstacles import Obstacle

__all__ = ["PlanView", "FrameClearance", "plan_scene", "plan_for_view", "frame_clearance"]

#: Seconds per step when a plan has no timed trajectory (the joint path is shown step by step).
UNTIMED_STEP = 0.2


@dataclass(frozen=True)
class PlanView:
    """The arrays the viewer draws for one plan.

    Attributes:
        name: Scenario name.
        headline: One line: success, method, clearance, duration.
        success: The planner's verdict.
        obstacles: Scenario boxes (obstacles and supports).
        safety_zone: Required clearance [m].
        t: (k,) frame times [s] (the TOPP-RA trajectory, or UNTIMED_STEP per step).
        q: (k, 6) joint angles at the frames [rad].
        step_q: (n, 6) joint path at the step-points [rad].
        step_points: (n, 3) planned tool step-points [m] (the Cartesian path, else FK of ``step_q``).
        via_points: (m, 3) via-points [m].
        switch_steps: Step indices where the IK branch switched.
        switch_times: Frame time [s] of each switch (the frame nearest that step's configuration).
    """

    name: str
    headline: str
    success: bool
    obstacles: tuple[Obstacle, ...]
    safety_zone: float
    t: np.ndarray
    q: np.ndarray
    step_q: np.ndarray
    step_points: np.ndarray
    via_points: np.ndarray
    switch_steps: tuple[int, ...]
    switch_times: tuple[float, ...]


@dataclass(frozen=True)
class FrameClearance:
    """Whole-arm clearance at each frame (Coal distances).

    Attributes:
        distance: (k,) smallest arm-to-scene distance [m] (negative: penetration).
        link: (k,) link attaining it.
        obstacle: (k,) scene object attaining it (a box name, ``platform`` or ``floor``).
        on_link, on_obstacle: (k, 3) the two nearest points [m].
    """

    distance: np.ndarray
    link: tuple[str, ...]
    obstacle: tuple[str, ...]
    on_link: np.ndarray
    on_obstacle: np.ndarray


def plan_scene(result) -> PlanView:
    """Adapter: the planner's result -> :class:`PlanView` (the one place that reads it)."""
    sc = result.scenario
    step_q = np.asarray(result.q, float).reshape(-1, 6)
    traj = result.trajectory
    if traj is not None and len(traj.t):
        t, q = np.asarray(traj.t, float), np.asarray(traj.q, float)
    else:
        t, q = UNTIMED_STEP * np.arange(len(step_q)), step_q
    cart = result.cartesian
    if cart is not None and len(cart.points) == len(step_q):
        points = np.asarray(cart.points, float)
    else:
        points = fk(step_q)[:, :3, 3] if len(step_q) else np.zeros((0, 3))
    via = np.asarray(cart.via_points, float).reshape(-1, 3) if cart is not None else np.zeros((0, 3))
    switches = tuple(int(i) for i in result.branch_switches)
    times = tuple(float(t[np.argmin(np.abs(q - step_q[i]).max(axis=1))]) for i in switches) if len(q) else ()
    verdict = "OK" if result.success else f"FAILED ({result.reason})"
    dur = f", {traj.duration:.2f} s (TOPP-RA)" if traj is not None else ""
    headline = (f"{sc.name}: {verdict} via {result.method}; min whole-arm clearance "
                f"{result.min_clearance * 1000:.1f} mm (safety zone {sc.safety_zone * 1000:.0f} mm), "
                f"{len(step_q)} step-points, {len(switches)} IK branch switch(es){dur}")
    return PlanView(name=sc.name, headline=headline, success=bool(result.success),
                    obstacles=tuple(sc.obstacles), safety_zone=float(sc.safety_zone), t=t, q=q,
                    step_q=step_q, step_points=points, via_points=via, switch_steps=switches,
                    switch_times=times)


def plan_for_view(scenario: str | Path, *, scene: Scene = THESIS_SCENE) -> PlanView:
    """Plan a scenario (file or shipped name) with the default options and adapt the result.

    Raises:
        ScenarioError: The scenario does not exist or fails validation.
    """
    from ..pipeline import plan

    return plan_scene(plan(scenario, scene=scene))


def frame_clearance(obstacles, q, *, scene: Scene = THESIS_SCENE) -> FrameClearance:
    """Nearest arm link and scene object, their distance and nearest points at each ``q`` (k, 6) [rad]."""
    checker = SceneCollision(tuple(obstacles), scene=scene)
    near = [checker.nearest(qk) for qk in np.asarray(q, float).reshape(-1, 6)]
    return FrameClearance(distance=np.array([n.distance for n in near]), link=tuple(n.link for n in near),
                          obstacle=tuple(n.object for n in near),
                          on_link=np.array([n.on_link for n in near]).reshape(-1, 3),
                          on_obstacle=np.array([n.on_object for n in near]).reshape(-1, 3))
