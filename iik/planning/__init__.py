"""Collision-free path planning of Sec 3.6 (pure NumPy; collision checks are injected).

* :mod:`.path` -- straight-line (LEI/LJI) and arc step-points, orientation interpolation.
* :mod:`.obstacles` -- boxes, the enclosing ellipsoid (Eq 52-53, corrected), repulsion.
* :mod:`.viapoints` -- Table III, Table IV and the inferred region layout of Fig 29.
* :mod:`.scenario` -- the :class:`Scenario` dataclass and its geometric checks.
* :mod:`.planner` -- step-points + orientations, IK along the path by the effort index.
"""

from .obstacles import SAFETY_ZONE, Obstacle, enclosing_radii, repel_points, repulsion_normal
from .path import MAX_STEP, arc_steps, interpolate_joints, interpolate_orientation, straight_steps
from .planner import CartesianPath, JointPath, all_solutions, build_path, poses_of, track_branches, track_dp
from .scenario import Scenario, Waypoint, check_scenario
from .viapoints import TABLE_IV, VIA_POINTS, region_of, via_point_path, via_points_for

__all__ = [
    "SAFETY_ZONE",
    "MAX_STEP",
    "Obstacle",
    "enclosing_radii",
    "repel_points",
    "repulsion_normal",
    "arc_steps",
    "straight_steps",
    "interpolate_joints",
    "interpolate_orientation",
    "CartesianPath",
    "JointPath",
    "all_solutions",
    "build_path",
    "poses_of",
    "track_branches",
    "track_dp",
    "Scenario",
    "Waypoint",
    "check_scenario",
    "TABLE_IV",
    "VIA_POINTS",
    "region_of",
    "via_point_path",
    "via_points_for",
]
