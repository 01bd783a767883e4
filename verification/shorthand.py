"""The thesis's trigonometric shorthand for transcribing printed formulas: ``c1 = cos(theta1)``,
``s1 = sin(theta1)``, ``ca = cos(alpha)``, ..."""

from __future__ import annotations

import numpy as np

__all__ = ["cos_sin"]


def cos_sin(*angles) -> tuple:
    """``(cos a, sin a, cos b, sin b, ...)`` of the given angles [rad] (floats or arrays), in order."""
    return tuple(f(a) for a in angles for f in (np.cos, np.sin))
