"""Residuals of configurations against poses, for the NumPy methods, the tests and the checks.

(Whether a configuration is among an IK answer, and comparisons with the oracle, live in
:mod:`verification.testing.completeness`.)
"""

from __future__ import annotations

import numpy as np

from ..arm import Arm
from ..kinematics import fk
from ..rotations import rotation_angle

__all__ = ["pose_residuals"]


def pose_residuals(q: np.ndarray, T: np.ndarray, arm: Arm) -> tuple[np.ndarray, np.ndarray]:
    """Position [m] and rotation [rad] residuals of ``fk(q)`` against ``T`` (batched)."""
    Tq = fk(q, arm)
    return (np.linalg.norm(Tq[..., :3, 3] - T[..., :3, 3], axis=-1),
            rotation_angle(Tq[..., :3, :3], T[..., :3, :3]))
