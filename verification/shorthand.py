"""Shorthand of the checks' transcriptions: the thesis's ``c1 = cos(theta1)``, ``s1 = sin(theta1)``,
``ca = cos(alpha)``, ..., and angle differences wrapped to one turn."""

from __future__ import annotations

import numpy as np

__all__ = ["cos_sin", "wrap"]


def cos_sin(*angles) -> tuple:
    """``(cos a, sin a, cos b, sin b, ...)`` of the given angles [rad] (floats or arrays), in order."""
    return tuple(f(a) for a in angles for f in (np.cos, np.sin))


def wrap(a):
    """Angles [rad] (floats or arrays) wrapped to [-pi, pi): how far apart two joint angles are."""
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi
