"""Collision-free pick-and-place planning (Sec 3.6, Sec 4.2): the layer a user plans with.

``plan("j")`` plans a shipped scenario end to end; ``plan(path)`` a TOML file;
``plan(Scenario(...), PlanOptions(...), arm=..., scene=...)`` anything else.

* :mod:`.pipeline` -- :func:`plan`, :class:`PlanOptions`, :class:`PlanResult`, :class:`Attempt`;
* :mod:`.scenario`, :mod:`.scenario_io` -- the :class:`Scenario` and its TOML files (load, validate, write);
* :mod:`.cartesian` -- the thesis's step-points, repulsion and orientations (Sec 3.6.1-3.6.3);
* :mod:`.tracking` -- IK along the path by the effort index (Eq 54), orientation search;
* :mod:`.path`, :mod:`.obstacles`, :mod:`.viapoints` -- lines/arcs, Eq 52-53 ellipsoids and
  repulsion, Table III/IV;
* :mod:`.collision`, :mod:`.robot_model` -- whole-arm Coal distances from the arm's URDF (Pinocchio);
* :mod:`.rrt` -- the OMPL RRT-Connect fallback; :mod:`.timing` -- TOPP-RA timing;
* :mod:`.output` -- CSV files and figures of a result; :mod:`.errors` -- the layer's errors;
* :mod:`.budget` -- the time budget (``PlanOptions.timeout``) and progress reports of a plan.

Units: m, rad, s; frames: the arm's base frame 0.
"""

from ..extras import require
from ..lazy import lazy_exports

require("planning", __name__)

__getattr__, __dir__ = lazy_exports(__name__, {
    ".budget": ("Budget",),
    ".cartesian": ("CartesianPath", "build_path", "poses_of"),
    ".collision": ("PathClearance", "SceneCollision"),
    ".errors": ("PlanningError", "PlanningFailed", "PlanningTimeout", "SamplingError", "ScenarioError",
                "TimingError"),
    ".obstacles": ("SAFETY_ZONE", "Box", "Obstacle", "ellipsoid_value", "enclosing_radii", "repel_points",
                   "repulsion_normal"),
    ".output": ("PLAN_FILES", "plot_effort", "plot_joints", "plot_scene", "write_outputs"),
    ".path": ("MAX_STEP", "MAX_STEP_POINTS", "arc_steps", "densify", "interpolate_joints",
              "interpolate_orientation", "path_length", "segment_length", "segment_steps", "straight_steps"),
    ".pipeline": ("VIA_POINT_TOLERANCE", "Attempt", "PlanOptions", "PlanResult", "plan"),
    ".robot_model": ("ArmModel", "ThesisModel", "arm_model", "thesis_model"),
    ".rrt": ("rrt_connect",),
    ".scenario": ("MAX_ANGLE", "MAX_COORDINATE", "MAX_OBSTACLES", "MAX_STEPS_PER_SEGMENT", "Scenario",
                  "Waypoint", "check_scenario", "check_step_points"),
    ".scenario_io": ("MAX_FILE_SIZE", "dexterity_notes", "load_scenario",
                     "scenario_from_dict", "scenario_path", "scenario_to_toml", "shipped_scenario_paths",
                     "thesis_scenario_paths",
                     "validate_scenario", "write_scenario"),
    ".timing": ("Trajectory", "thesis_timing", "time_parameterize"),
    ".tracking": ("LIMIT_MARGIN", "Tracking", "all_solutions", "track_branches", "track_dp"),
    ".viapoints": ("REGIONS", "TABLE_IV", "TABLE_IV_PRINTED", "VIA_POINTS", "region_bounds", "region_of",
                   "via_point_path", "via_points_for"),
})

__all__ = [
    # planning a scenario
    "plan",
    "PlanOptions",
    "PlanResult",
    "Attempt",
    "Budget",
    "VIA_POINT_TOLERANCE",
    # scenarios and their files
    "Scenario",
    "Waypoint",
    "Box",
    "Obstacle",  # deprecated alias of Box (it warns)
    "check_scenario",
    "check_step_points",
    "load_scenario",
    "validate_scenario",
    "scenario_from_dict",
    "scenario_to_toml",
    "write_scenario",
    "scenario_path",
    "thesis_scenario_paths",
    "shipped_scenario_paths",
    "dexterity_notes",
    # bounds of a scenario (memory and time)
    "MAX_STEP_POINTS",
    "MAX_STEPS_PER_SEGMENT",
    "MAX_COORDINATE",
    "MAX_OBSTACLES",
    "MAX_ANGLE",
    "MAX_FILE_SIZE",
    # the thesis planner (Sec 3.6)
    "SAFETY_ZONE",
    "MAX_STEP",
    "CartesianPath",
    "build_path",
    "poses_of",
    "straight_steps",
    "arc_steps",
    "densify",
    "path_length",
    "segment_length",
    "segment_steps",
    "interpolate_joints",
    "interpolate_orientation",
    "enclosing_radii",
    "ellipsoid_value",
    "repel_points",
    "repulsion_normal",
    "REGIONS",
    "VIA_POINTS",
    "TABLE_IV",
    "TABLE_IV_PRINTED",
    "region_bounds",
    "region_of",
    "via_point_path",
    "via_points_for",
    # IK along the path
    "LIMIT_MARGIN",
    "Tracking",
    "all_solutions",
    "track_branches",
    "track_dp",
    # collision, sampling, timing
    "ArmModel",
    "arm_model",
    "ThesisModel",
    "thesis_model",
    "SceneCollision",
    "PathClearance",
    "rrt_connect",
    "Trajectory",
    "time_parameterize",
    "thesis_timing",
    # outputs
    "write_outputs",
    "PLAN_FILES",
    "plot_scene",
    "plot_joints",
    "plot_effort",
    # errors
    "PlanningError",
    "ScenarioError",
    "PlanningFailed",
    "TimingError",
    "SamplingError",
    "PlanningTimeout",
]
