"""iik: kinematics, inverse kinematics, workspace, dexterity and planning for
the six-joint PowerCube arm of Mondragon Sanchez (2012).

Pure NumPy/SciPy; no I/O. Units are SI (m, rad, s) throughout.
"""

from .arm import THESIS_ARM, Arm
from .dexterity import Dexterity, dexterity
from .dh import DHRow, DHTable, dh_chain
from .errors import DexterityError, IIKError, InvalidInputError, NotOrthonormalError, UnreachablePoseError
from .ik import (
    IKResult,
    follow_path,
    select,
    solve,
    solve_many,
)
from .joint_path import BRANCH_SWITCH_STEP, JointPath, PathEvent, branch_switches, effort_index, path_effort
from .kinematics import fk, fk_chain, jacobian, joint_frames, position_jacobian
from .rotations import (
    euler_from_matrix,
    euler_matrix,
    pose_from_euler,
    pose_from_zxz,
    rotation_angle,
    zxz_from_matrix,
    zxz_matrix,
)
from .scene import THESIS_SCENE, Scene
from .workspace import ClosestReachable, closest_reachable, in_workspace

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
    "Scene",
    "THESIS_SCENE",
    "IIKError",
    "InvalidInputError",
    "UnreachablePoseError",
    "NotOrthonormalError",
    "dexterity",
    "Dexterity",
    "DexterityError",
    "in_workspace",
    "closest_reachable",
    "ClosestReachable",
]
