"""iik: kinematics, inverse kinematics, workspace, dexterity and planning for
the six-joint PowerCube arm of Mondragon Sanchez (2012).

Pure NumPy/SciPy; no I/O. Units are SI (m, rad, s) throughout. Each name is imported when first
used (:mod:`iik.lazy`): ``import iik`` itself loads no NumPy.
"""

from .lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(__name__, {
    ".arm": ("Arm", "THESIS_ARM"),
    ".dh": ("DHRow", "DHTable", "dh_chain"),
    ".kinematics": ("fk", "fk_chain", "jacobian", "joint_frames", "position_jacobian"),
    ".ik": ("IKResult", "solve", "solve_many", "select", "follow_path"),
    ".joint_path": ("JointPath", "PathEvent", "path_effort", "branch_switches", "BRANCH_SWITCH_STEP",
                    "effort_index"),
    ".rotations": ("pose_from_euler", "euler_matrix", "euler_from_matrix", "rotation_angle",
                   "pose_from_zxz", "zxz_from_matrix", "zxz_matrix"),  # the zxz names: deprecated aliases
    ".scene": ("Box", "Scene", "THESIS_SCENE"),
    ".errors": ("IIKError", "InvalidInputError", "UnreachablePoseError", "NotOrthonormalError",
                "DexterityError", "MissingExtraError"),
    ".dexterity": ("dexterity", "Dexterity"),
    ".workspace": ("in_workspace", "closest_reachable", "ClosestReachable"),
})

__all__ = [
    "Arm",
    "THESIS_ARM",
    "DHRow",
    "DHTable",
    "dh_chain",
    "fk",
    "fk_chain",
    "jacobian",
    "joint_frames",
    "position_jacobian",
    "IKResult",
    "JointPath",
    "PathEvent",
    "path_effort",
    "branch_switches",
    "BRANCH_SWITCH_STEP",
    "solve",
    "solve_many",
    "select",
    "effort_index",
    "follow_path",
    "pose_from_euler",
    "euler_matrix",
    "euler_from_matrix",
    "rotation_angle",
    "pose_from_zxz",  # deprecated aliases (they warn): Eq 42 is Z-Y-Z
    "zxz_from_matrix",
    "zxz_matrix",
    "Box",
    "Scene",
    "THESIS_SCENE",
    "IIKError",
    "InvalidInputError",
    "UnreachablePoseError",
    "NotOrthonormalError",
    "MissingExtraError",
    "dexterity",
    "Dexterity",
    "DexterityError",
    "in_workspace",
    "closest_reachable",
    "ClosestReachable",
]
