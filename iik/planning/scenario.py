"""A pick-and-place scenario as a frozen dataclass, and its geometric checks.

Units: positions [m] in the arm's base frame 0; angles [rad] (Z-X-Z Euler
angles of Eq 42). The file loader (:mod:`iik.planning.scenario_io`) converts
file units and frames and then calls :func:`check_scenario` for the geometric
checks: start/goal outside every box, the platform and the floor, and inside
the workspace (``in_workspace`` / ``closest_reachable`` callables, bound to the
arm by the loader).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .errors import ScenarioError
from .obstacles import SAFETY_ZONE, Obstacle
from .path import MAX_STEP

__all__ = ["Waypoint", "Scenario", "check_scenario"]


@dataclass(frozen=True)
class Waypoint:
    """An end-effector target: tool point and Z-X-Z orientation.

    Attributes:
        position: Tool point (3,) [m], base frame.
        alpha, beta, gamma: Euler angles [rad] (Eq 42). ``alpha=None`` means
            "any alpha" (Sec 3.6: alpha does not tilt the tool): the planner
            uses the azimuth-facing alpha' of Eq 46, ``atan2(py, px)``.
    """

    position: tuple[float, float, float]
    alpha: float | None
    beta: float
    gamma: float = 0.0


@dataclass(frozen=True)
class Scenario:
    """Everything the planner needs for one task.

    Attributes:
        name: Short id (file stem), e.g. ``"j"``.
        title: The thesis caption, e.g. ``"Fig 42j: from the top of one table to another"``.
        reference: Thesis figure/section.
        reconstruction: What in the scenario is reconstructed (not printed).
        start, goal: :class:`Waypoint`.
        obstacles: Boxes (obstacles and supports), base frame.
        via_points: ``None`` = choose by Table IV (:mod:`~iik.planning.viapoints`);
            otherwise explicit (k, 3) via-points [m].
        segments: Per-segment route ``"line"`` or ``"arc"`` (len = k + 1), or ``None`` = all lines.
        steps_per_segment: Fixed steps per segment (39 in Sec 4.2.1) or ``None`` (by ``max_step``).
        max_step: Largest step [m] (30 mm, Sec 4.2.1).
        orientation: ``"euler"`` (gradual Euler change, thesis) or ``"slerp"``.
        mode: ``"LEI"`` (dense Cartesian steps) or ``"LJI"`` (joint interpolation).
        safety_zone: Ellipsoid padding and required whole-arm clearance [m].
        source: Where it was loaded from (for messages).
    """

    name: str
    start: Waypoint
    goal: Waypoint
    title: str = ""
    reference: str = ""
    reconstruction: str = ""
    obstacles: tuple[Obstacle, ...] = ()
    via_points: tuple[tuple[float, float, float], ...] | None = None
    segments: tuple[str, ...] | None = None
    steps_per_segment: int | None = None
    max_step: float = MAX_STEP
    orientation: str = "euler"
    mode: str = "LEI"
    safety_zone: float = SAFETY_ZONE
    source: str = field(default="", compare=False)

    def __post_init__(self) -> None:
        if self.orientation not in ("euler", "slerp"):
            raise ScenarioError("planning.orientation",
                                f"expected 'euler' or 'slerp', got {self.orientation!r}")
        if self.mode not in ("LEI", "LJI"):
            raise ScenarioError("planning.mode", f"expected 'LEI' or 'LJI', got {self.mode!r}")
        if not (np.isfinite(self.max_step) and 0 < self.max_step <= 0.5):
            raise ScenarioError("planning.max_step", f"must be in (0, 0.5] m, got {self.max_step!r}")
        if not (np.isfinite(self.safety_zone) and 0 <= self.safety_zone <= 0.5):
            raise ScenarioError("planning.safety_zone", f"must be in [0, 0.5] m, got {self.safety_zone!r}")
        if self.steps_per_segment is not None and not (1 <= self.steps_per_segment <= 10000):
            raise ScenarioError("planning.steps_per_segment", "must be an integer in 1..10000")
        if self.via_points is not None and self.segments is not None:
            if len(self.segments) != len(self.via_points) + 1:
                raise ScenarioError(
                    "planning.segments",
                    f"needs {len(self.via_points) + 1} entries (via-points + 1), got {len(self.segments)}")
        for i, s in enumerate(self.segments or ()):
            if s not in ("line", "arc"):
                raise ScenarioError(f"planning.segments[{i}]", f"expected 'line' or 'arc', got {s!r}")


def check_scenario(sc: Scenario, *, platform: Obstacle | None = None, floor_z: float | None = None,
                   in_workspace: Callable | None = None,
                   closest_reachable: Callable | None = None) -> None:
    """Raise :class:`~iik.planning.ScenarioError` if the task is impossible as stated.

    Checks (Sec 3.6.1: "the initial and final points were verified to be inside
    the manipulator workspace ... also checked to be outside the mobile robot
    base and any obstacles"):

    * start/goal not inside any box, the platform, or below the floor;
    * start/goal inside the workspace (if ``in_workspace`` is given), with the
      closest reachable point in the message (``closest_reachable``).
    """
    for fld, wp in (("start", sc.start), ("goal", sc.goal)):
        p = np.asarray(wp.position, float)
        for k, box in enumerate(sc.obstacles):
            if box.contains(p)[0]:
                raise ScenarioError(f"{fld}.position",
                                    f"{_mm(p)} lies inside {box.kind} {box.name!r} (obstacles[{k}])")
        if platform is not None and platform.contains(p)[0]:
            raise ScenarioError(f"{fld}.position", f"{_mm(p)} lies inside the mobile platform")
        if floor_z is not None and p[2] < floor_z:
            raise ScenarioError(f"{fld}.position",
                                f"{_mm(p)} is below the floor (z = {floor_z:.3f} m in the base frame)")
        if in_workspace is not None and not bool(np.asarray(in_workspace(p)).reshape(-1)[0]):
            hint = ""
            if closest_reachable is not None:
                c = np.asarray(closest_reachable(p), float).reshape(-1)[:3]
                hint = f"; closest reachable point {_mm(c)} ({np.linalg.norm(c - p) * 1000:.0f} mm away)"
            raise ScenarioError(f"{fld}.position", f"{_mm(p)} is outside the workspace{hint}")


def _mm(p) -> str:
    return "[" + ", ".join(f"{v:.3f}" for v in np.asarray(p, float)) + "] m"
