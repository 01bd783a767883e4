"""iik: kinematics, inverse kinematics, workspace, dexterity and planning for
the six-joint PowerCube arm of Mondragon Sanchez (2012).

Pure NumPy/SciPy; no I/O. Units are SI (m, rad, s) throughout.
"""

from .arm import THESIS_ARM, Arm
from .dh import DHRow, DHTable, dh_chain
from .errors import IIKError, InvalidInputError, ScenarioError, UnreachablePoseError
from .kinematics import fk, fk_chain, jacobian, joint_frames, position_jacobian

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
    "IIKError",
    "InvalidInputError",
    "ScenarioError",
    "UnreachablePoseError",
]
