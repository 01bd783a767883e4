"""Shorthand of the checks' transcriptions: the thesis's ``c1 = cos(theta1)``, ``s1 = sin(theta1)``,
``ca = cos(alpha)``, ..., and angle differences wrapped to one turn (:func:`iik.ik.angles.wrap_angle`)."""

from __future__ import annotations

import numpy as np

from iik.ik.angles import wrap_angle

__all__ = ["cos_sin", "wrap"]


def cos_sin(*angles) -> tuple:
    """``(cos a, sin a, cos b, sin b, ...)`` of the given angles [rad] (floats or arrays), in order."""
    return tuple(f(a) for a in angles for f in (np.cos, np.sin))


#: Angles [rad] (floats or arrays) wrapped to (-pi, pi]: how far apart two joint angles are. The
#: project's one wrap, :func:`iik.ik.angles.wrap_angle`, under the checks' short name.
wrap = wrap_angle
