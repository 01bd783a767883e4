"""Inverse kinematics of the thesis arm (Sec 3.3): complete solver, thesis IIK, selection.

* :func:`solve` / :func:`solve_many`: all solutions of a pose (``method="complete"``
  by polynomial elimination, or ``method="thesis"``: Sec 3.3 with errata fixed).
* :func:`effort_index` (Eq 54), :func:`select`, :func:`follow_path`.
* :func:`pose_from_zxz`: a pose from a position and the Eq 42 angles (corrected;
  implemented in :mod:`iik.rotations`).
"""

from ..rotations import pose_matrix as pose_from_zxz
from ..rotations import zxz_from_matrix
from .result import IKResult
from .selection import PathResult, branch_signature, effort_index, follow_path, select, select_index
from .solve import METHODS, solve, solve_many

__all__ = [
    "IKResult",
    "METHODS",
    "solve",
    "solve_many",
    "pose_from_zxz",
    "zxz_from_matrix",
    "effort_index",
    "select",
    "select_index",
    "follow_path",
    "PathResult",
    "branch_signature",
]
