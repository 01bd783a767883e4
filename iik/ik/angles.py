"""Joint-angle arithmetic shared by the IK modules, their tests and checks."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["wrap", "wrap_angle", "gap", "angle_distance", "into_limits", "clip_angle"]

_TWO_PI = 2.0 * np.pi


def wrap(x: float) -> float:
    """One angle [rad] wrapped to (-pi, pi]: the project's one wrap, for a float.

    Plain Python on purpose: the compiled IK kernel compiles this very function
    (``iik/ik/kernel.py``), so the kernel and the NumPy code share one rule. One addition for
    ``|x| <= 3 pi`` (the usual case); :func:`wrap_angle` is the same rule for arrays (tested equal).
    """
    if x > math.pi:
        if x <= 3.0 * math.pi:
            return x - _TWO_PI
    elif x > -math.pi:
        return x
    elif x > -3.0 * math.pi:
        return x + _TWO_PI
    return math.pi - ((math.pi - x) % _TWO_PI)


def wrap_angle(x):
    """Angles [rad] wrapped to (-pi, pi] (NumPy arrays or floats): :func:`wrap`'s rule, vectorised
    (equal to it bit for bit; an angle already in (-pi, pi] is returned unchanged)."""
    x = np.asarray(x, dtype=float)
    out = np.where(x > np.pi, x - _TWO_PI, np.where(x > -np.pi, x, x + _TWO_PI))
    far = (x > 3.0 * np.pi) | (x <= -3.0 * np.pi)
    if far.any():  # rare: the general form only where it is needed (inf gives nan, quietly)
        with np.errstate(invalid="ignore"):
            out = np.where(far, np.pi - np.mod(np.pi - x, _TWO_PI), out)
    return out[()]


def gap(x: float) -> float:
    """|wrap(x)| [rad] of one angle difference, in one operation (the mod form: its sign at +-pi
    does not matter). Plain Python: the kernel compiles it; :func:`angle_distance` is the same rule
    for arrays."""
    return abs(math.pi - ((math.pi - x) % _TWO_PI))


def angle_distance(a, b) -> np.ndarray:
    """Largest wrapped joint difference [rad] between joint vectors ``a`` and ``b`` (..., 6)."""
    d = np.asarray(a, float) - np.asarray(b, float)
    return np.abs(np.pi - np.mod(np.pi - d, _TWO_PI)).max(axis=-1)  # gap(d), in one pass


def into_limits(Q: np.ndarray, lower, upper, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """Configurations Q (..., 6) [rad] (angles wrapped to (-pi, pi]) with each joint outside
    [lower - tol, upper + tol] turned by +-2 pi where that brings it inside (limits not centred
    on 0, e.g. the CRX's joint 3, -71 .. 251 deg), and whether each configuration is then
    inside (...,). NaN is outside. The compiled kernel applies the same rule."""
    Q = np.asarray(Q, dtype=float)
    lo, hi = np.asarray(lower) - tol, np.asarray(upper) + tol
    with np.errstate(invalid="ignore"):
        shifted = np.where(Q < lo, Q + _TWO_PI, np.where(Q > hi, Q - _TWO_PI, Q))
        ok = (shifted >= lo) & (shifted <= hi)
    return np.where(ok, shifted, Q), np.all(ok, axis=-1)


def clip_angle(t, lo: float, hi: float) -> np.ndarray:
    """Angles ``t`` [rad] in (-pi, pi] limited to [lo, hi] [rad] by the nearer limit *on the
    circle*: a plain clip picks the wrong limit for an angle past one limit but nearer the other
    across +-pi (joint 2 of the thesis arm, -120 .. 95 deg, aimed at 170 deg: -120 deg is 70 deg
    away, 95 deg is 75)."""
    t = np.asarray(t, float)
    nearer = np.where(np.abs(wrap_angle(t - lo)) < np.abs(wrap_angle(t - hi)), lo, hi)
    return np.where((t >= lo) & (t <= hi), t, nearer)
