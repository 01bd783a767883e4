"""Inverse kinematics of the thesis arm (Sec 3.3): complete solver, thesis IIK, selection.

* :func:`solve` / :func:`solve_many`: all solutions of a pose (``method="complete"``
  by polynomial elimination, or ``method="thesis"``: Sec 3.3 with errata fixed).
* :func:`select` (least Eq 54 effort within Table I), :func:`follow_path`.
"""

from .result import IKResult
from .selection import branch_signature, follow_path, select, select_index
from .solve import METHODS, solve, solve_many

__all__ = [
    "IKResult",
    "METHODS",
    "solve",
    "solve_many",
    "select",
    "select_index",
    "follow_path",
    "branch_signature",
]
