"""Joint-angle arithmetic shared by the IK modules, their tests and checks."""

from __future__ import annotations

import numpy as np

__all__ = ["wrap_angle", "angle_distance"]

_TWO_PI = 2.0 * np.pi


def wrap_angle(x):
    """Angles [rad] wrapped to (-pi, pi] (NumPy arrays or floats)."""
    return np.pi - np.mod(np.pi - x, _TWO_PI)


def angle_distance(a, b) -> np.ndarray:
    """Largest wrapped joint difference [rad] between joint vectors ``a`` and ``b`` (..., 6)."""
    return np.max(np.abs(wrap_angle(np.asarray(a, float) - np.asarray(b, float))), axis=-1)
