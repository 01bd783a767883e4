"""Solutions (theta1, theta2) of the two conditions inside a cluster of eliminant roots, found
as crossings of the conditions' curves (the NumPy reference's path, :mod:`iik.ik.reference`).

The two conditions of the solver chain (``docs/IK_CLASS.md``, Eq 11) are

    G1 = R + P cos theta2 + Q sin theta2 = 0,    G2 = a + b cos theta2 + c sin theta2 = 0,

with a, b, c, P, Q, R first-degree in (cos theta1, sin theta1). At a fixed theta2 each condition
is A + B cos theta1 + C sin theta1 = 0: two angles theta1 in closed form. A solution is a theta2
where a branch of G1's angle meets a branch of G2's. Where several solutions share nearly one
theta1 (a cluster: the eliminant's roots lie 1e-7 apart, its squared form changes sign over
intervals too thin for any grid in theta1 and the eigenvalues err by ~1e-4), the curves cross
at theta2 values radians apart, and the difference of the two branches changes sign there:
a grid in theta2 and bisection find each crossing. Nothing here uses the eliminant, so this is
independent of the kernel's isolation of its roots.

Angles are the solver chain's DH angles theta [rad] (joint value plus the row's offset).
"""

from __future__ import annotations

import numpy as np

from .angles import wrap_angle

__all__ = ["cluster_crossings", "CROSSING_GRID", "CROSSING_REACH"]

#: theta2 grid [points over the circle] on which the branch differences are sampled.
CROSSING_GRID = 2048
#: A crossing counts if its theta1 lies within the cluster widened by this much [rad].
CROSSING_REACH = 1e-3
#: (a, b, c) and (R, P, Q): the rows of x forming G2 and G1 (constant, cos theta2, sin theta2).
_G1, _G2 = (5, 3, 4), (0, 1, 2)
#: Offsets [rad] of the grid angles placed at and beside each fold.
_BESIDE = np.array([-1e-6, -1e-9, 0.0, 1e-9, 1e-6])


def _circle_terms(x, rows, t2):
    """(A, B, C) (3, m) of A + B cos theta1 + C sin theta1: the condition made of ``rows`` of
    one pose's coefficients x (6, 3) at theta2 = t2 (m,)."""
    c2, s2 = np.cos(t2), np.sin(t2)
    k, p, q = rows
    return np.stack([x[k, j] + x[p, j] * c2 + x[q, j] * s2 for j in range(3)])


def _branch(x, rows, t2, sign):
    """theta1 (m,) on one branch (sign +1 or -1) of a condition at theta2 = t2; NaN where the
    condition has no real theta1 there."""
    A, B, C = _circle_terms(x, rows, t2)
    h = np.hypot(B, C)
    with np.errstate(invalid="ignore", divide="ignore"):
        r = -A / h
        r = np.where(np.abs(r) <= 1.0 + 1e-12, np.clip(r, -1.0, 1.0), r)  # (a fold's own angle)
        return np.arctan2(C, B) + sign * np.arccos(r)


def _folds(x, rows):
    """The theta2 angles (m,) where a condition's two branches meet, A^2 = B^2 + C^2: with
    z = exp(i theta2), z^2 (A^2 - B^2 - C^2) is a polynomial of degree 4 in z, whose roots on
    the unit circle are the folds. Added to the grid, they keep a narrow island of real theta1
    (between two folds closer than the grid's spacing) from falling between two grid angles;
    returned with angles 1e-9 and 1e-6 rad to each side (a root of the quartic errs)."""

    def laurent(k):  # (z^-1, 1, z) coefficients of x[k, j] + x[p, j] cos + x[q, j] sin
        a, b, c = (x[r, k] for r in rows)
        return np.array([0.5 * (b + 1j * c), a, 0.5 * (b - 1j * c)])

    A, B, C = (laurent(k) for k in range(3))
    f = np.convolve(A, A) - np.convolve(B, B) - np.convolve(C, C)  # z^-2 ... z^2
    if np.abs(f).max() == 0.0:
        return np.empty(0)
    z = np.roots(f[::-1])
    fold = np.angle(z[np.abs(np.abs(z) - 1.0) <= 1e-6])
    return (fold[:, None] + _BESIDE).ravel()  # (a root may err to either side of the fold)


def _gap(x, t2, s1, s2):
    """G1's branch s1 minus G2's branch s2 [rad], wrapped, at theta2 = t2."""
    return wrap_angle(_branch(x, _G1, t2, s1) - _branch(x, _G2, t2, s2))


def _bisect(x, lo, hi, s1, s2, iters: int = 60):
    """theta2 values (m,) where the gap of branches (s1, s2) changes sign inside [lo, hi]."""
    glo = _gap(x, lo, s1, s2)
    for _ in range(iters):
        mid = 0.5 * (lo + hi)
        gm = _gap(x, mid, s1, s2)
        left = np.sign(gm) == np.sign(glo)
        lo, glo, hi = np.where(left, mid, lo), np.where(left, gm, glo), np.where(left, hi, mid)
    return 0.5 * (lo + hi)


def _brackets(d):
    """(pair, i) of each grid interval [t2[i], t2[i + 1]] over which the gap d (pairs of
    branches, grid angles) changes sign. (A fold is itself a grid angle, :func:`_folds`.)"""
    with np.errstate(invalid="ignore"):  # (a gap near +-pi changes sign by wrapping)
        small = np.abs(d) <= 1.0
        change = small[:, :-1] & small[:, 1:] & (np.sign(d[:, :-1]) * np.sign(d[:, 1:]) <= 0)
    return np.nonzero(change)


def _dips(d):
    """(pair, i) of each grid angle where |d| has a local minimum (|d| <= 0.1, both neighbours
    of its sign): two crossings between t2[i - 1] and t2[i + 1] would cancel in the signs of d
    there."""
    a, m, b = d[:, :-2], d[:, 1:-1], d[:, 2:]
    with np.errstate(invalid="ignore"):
        dip = (np.abs(m) <= np.abs(a)) & (np.abs(m) <= np.abs(b)) & (np.abs(m) <= 0.1)
        dip &= (np.sign(a) == np.sign(m)) & (np.sign(b) == np.sign(m))
    pair, i = np.nonzero(dip)
    return pair, i + 1


def _extrema(x, lo, hi, s1, s2, sg, iters: int = 60):
    """The extremum (a minimum of sg * gap of branches s1, s2) inside each [lo, hi], by golden
    sections. Returns the intervals (lo, hi, s1, s2) on each side of an extremum of the other
    sign (two crossings), and the extrema (theta2, s1) where the gap vanishes to 1e-13 (a
    tangency)."""
    a, b = lo, hi
    for _ in range(iters):
        u, v = b - 0.618 * (b - a), a + 0.618 * (b - a)
        first = sg * _gap(x, u, s1, s2) <= sg * _gap(x, v, s1, s2)
        a, b = np.where(first, a, u), np.where(first, v, b)
    ext = 0.5 * (a + b)
    de = _gap(x, ext, s1, s2)
    with np.errstate(invalid="ignore"):
        over = np.sign(de) == -sg
        touch = ~over & (np.abs(de) <= 1e-13)
    e, two = ext[over], lambda v: np.tile(v[over], 2)
    sides = (np.concatenate([lo[over], e]), np.concatenate([e, hi[over]]), two(s1), two(s2))
    return sides, (ext[touch], s1[touch])


#: The four pairs of branches (G1's sign, G2's sign), as columns.
_S1, _S2 = np.array([[1.0], [1.0], [-1.0], [-1.0]]), np.array([[1.0], [-1.0], [1.0], [-1.0]])


def cluster_crossings(x, lo: float, hi: float, grid: int = CROSSING_GRID):
    """Every crossing (theta1 (m,), theta2 (m,)) [DH angles, rad] of the two conditions of one
    pose's coefficients x (6, 3) whose theta1 lies in [lo - CROSSING_REACH, hi + CROSSING_REACH]
    (a cluster of eliminant roots). Two crossings within one grid step (2 pi / grid in
    theta2) are told apart at the dip of the gap between them, and a tangency where that dip
    reaches 0 to 1e-13 rad; more than two within one step, or a pair whose dip is not a
    minimum of |gap| on the grid, can still be missed. The caller polishes and verifies each
    crossing."""
    t2 = np.sort(np.concatenate([np.linspace(-np.pi, np.pi, grid + 1), _folds(x, _G1), _folds(x, _G2)]))
    mid, reach = 0.5 * (lo + hi), 0.5 * (hi - lo) + CROSSING_REACH
    d = wrap_angle(_branch(x, _G1, t2[None], _S1) - _branch(x, _G2, t2[None], _S2))  # (4, m)
    p, i = _dips(d)
    (lo2, hi2, u1, u2), (touch, t1s) = _extrema(
        x, t2[i - 1], t2[i + 1], _S1[p, 0], _S2[p, 0], np.sign(d[p, i])
    )
    p, i = _brackets(d)
    s1, s2 = np.concatenate([_S1[p, 0], u1]), np.concatenate([_S2[p, 0], u2])
    r2 = _bisect(x, np.concatenate([t2[i], lo2]), np.concatenate([t2[i + 1], hi2]), s1, s2)
    r2 = np.concatenate([r2, touch])
    r1 = wrap_angle(_branch(x, _G1, r2, np.concatenate([s1, t1s])))
    inside = np.abs(wrap_angle(r1 - mid)) <= reach
    return r1[inside], r2[inside]
