"""Certified isolation of the real roots of a degree-8 polynomial in Bernstein form.

A polynomial on an interval is kept as its 9 Bernstein coefficients ``b`` and a bound ``E``
on their rounding error (|b_i - b_i exact| <= E for the exact polynomial of the problem).
Subdivision at the midpoint (de Casteljau) classifies every piece of [0, 1] by the signs of
its coefficients that exceed the bound (Descartes' rule of signs in the Bernstein basis:
the number of roots in the open piece is at most the number of sign variations V and has
its parity):

* ``V = 0`` and every |b_i| above the near threshold: no root, no near root (excluded);
* ``V = 1``: exactly one simple root (a **root** leaf, refined by safeguarded Newton);
* ``V = 0`` with some |b_i| at or below the near threshold, p not certainly monotone, on a
  short piece: no root, but |p| may have a local minimum close to 0 (a **near** leaf: that
  minimum is a candidate, where a solution within the tolerance can sit without an exact
  root); a monotone piece has its least |p| at an end, which is a neighbour's (or, at 0 and 1,
  the other half circle's: such an end piece is a near leaf too);
* ``V >= 2`` or a coefficient whose sign the bound leaves open, on a piece too short to split
  in double precision: a **cluster** (roots closer than the arithmetic separates; the caller
  re-expands it in double-double arithmetic, :mod:`iik.ik.ddarith`).

*Guarantee:* every real root of the exact polynomial in [0, 1] lies in a root leaf (one
each) or a cluster; every point where |p| is at most the near threshold lies in a root,
near or cluster leaf. De Casteljau's averages are convex combinations, so a bound E on the
parent bounds the children after adding the rounding of the averages (8 eps max |b|).

Everything is scalar Numba code compiled into the kernel (:mod:`iik.ik.kernel`).
"""

from __future__ import annotations

import numba

__all__ = [
    "LEAF_ROOT",
    "LEAF_NEAR",
    "LEAF_CLUSTER",
    "LEAF_WIDTH",
    "N_LEAF",
    "isolate",
    "casteljau_split",
    "value_and_slope",
    "refine_root",
    "near_minimum",
    "W_MIN",
    "W_NEAR",
]

_njit = numba.njit(error_model="numpy")

_EPS = 2.220446049250313e-16
LEAF_ROOT, LEAF_NEAR, LEAF_CLUSTER = 0, 1, 2
#: A leaf row: ``[kind, u0, u1, E, b0 .. b8]``.
LEAF_WIDTH = 13
#: Most leaves returned per call (8 roots, the rest near leaves and clusters).
N_LEAF = 40
#: Pieces shorter than this are not split in double precision [fraction of the interval].
W_MIN = 1e-11
#: Near leaves are pieces at most this long.
W_NEAR = 1.0 / 64.0
_STACK = 96


@_njit
def casteljau_split(b, left, right) -> None:
    """The Bernstein coefficients of the halves [0, 1/2] (left) and [1/2, 1] (right) of b (9,).

    In place in ``right``: level k+1 overwrites entries 0 .. 7-k of level k, so entry 8-k keeps
    the last entry of level k, which is the right half's coefficient 8-k."""
    for i in range(9):
        right[i] = b[i]
    for k in range(9):
        left[k] = right[0]
        for i in range(8 - k):
            right[i] = 0.5 * (right[i] + right[i + 1])


@_njit
def value_and_slope(b, s):
    """p(s) and dp/ds at s in [0, 1] of the Bernstein coefficients ``b`` (9,) (de Casteljau)."""
    w0, w1, w2, w3, w4, w5, w6, w7, w8 = b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], b[8]
    r = 1.0 - s
    w0, w1, w2, w3, w4, w5, w6, w7 = (
        r * w0 + s * w1,
        r * w1 + s * w2,
        r * w2 + s * w3,
        r * w3 + s * w4,
        r * w4 + s * w5,
        r * w5 + s * w6,
        r * w6 + s * w7,
        r * w7 + s * w8,
    )
    w0, w1, w2, w3, w4, w5, w6 = (
        r * w0 + s * w1,
        r * w1 + s * w2,
        r * w2 + s * w3,
        r * w3 + s * w4,
        r * w4 + s * w5,
        r * w5 + s * w6,
        r * w6 + s * w7,
    )
    w0, w1, w2, w3, w4, w5 = (
        r * w0 + s * w1,
        r * w1 + s * w2,
        r * w2 + s * w3,
        r * w3 + s * w4,
        r * w4 + s * w5,
        r * w5 + s * w6,
    )
    w0, w1, w2, w3, w4 = r * w0 + s * w1, r * w1 + s * w2, r * w2 + s * w3, r * w3 + s * w4, r * w4 + s * w5
    w0, w1, w2, w3 = r * w0 + s * w1, r * w1 + s * w2, r * w2 + s * w3, r * w3 + s * w4
    w0, w1, w2 = r * w0 + s * w1, r * w1 + s * w2, r * w2 + s * w3
    w0, w1 = r * w0 + s * w1, r * w1 + s * w2
    return r * w0 + s * w1, 8.0 * (w1 - w0)


@_njit
def _classify(b, E, thr):
    """(variations, open signs, min |b|, max |b|) of b with the error bound E."""
    v, nz = 0, 0
    last = 0
    lo, hi = 1e308, 0.0
    for i in range(9):
        x = b[i]
        ax = abs(x)
        lo = min(lo, ax)
        hi = max(hi, ax)
        if x > E:
            sg = 1
        elif x < -E:
            sg = -1
        else:
            nz += 1
            continue
        if last != 0 and sg != last:
            v += 1
        last = sg
    return v, nz, lo, hi


@_njit
def _monotone(b, E):
    """Is p certainly monotone on the piece (the differences of its coefficients, p' / 8 in
    Bernstein form, all of one sign beyond their error bound 2 E)?"""
    pos, neg = False, False
    for i in range(8):
        d = b[i + 1] - b[i]
        if d > 2.0 * E:
            pos = True
        elif d < -2.0 * E:
            neg = True
        else:
            return False
    return not (pos and neg)


@_njit
def _push_leaf(out, n, kind, u0, u1, E, b):
    if n >= N_LEAF:
        return n
    if kind == LEAF_CLUSTER and n > 0 and out[n - 1, 0] == LEAF_CLUSTER and out[n - 1, 2] == u0:
        out[n - 1, 2] = u1  # adjacent clusters: one
        out[n - 1, 3] = max(out[n - 1, 3], E)
        return n
    out[n, 0], out[n, 1], out[n, 2], out[n, 3] = kind, u0, u1, E
    for i in range(9):
        out[n, 4 + i] = b[i]
    return n + 1


#: What :func:`_piece` says of a piece besides a leaf kind: nothing there, or split it.
_NOTHING, _SPLIT = -1, -2


@_njit
def _piece(cur, e, thr, u0, u1):
    """What to do with the piece [u0, u1] of [0, 1] whose Bernstein coefficients are ``cur`` (9,)
    with error bound ``e``: a leaf kind (LEAF_ROOT, LEAF_NEAR, LEAF_CLUSTER), _NOTHING (no root
    and |p| above ``thr``, or a near minimum only at an end that is not one of [0, 1]) or
    _SPLIT; and the largest |coefficient| (for the error bound of the halves)."""
    w = u1 - u0
    v, nz, lo, hi = _classify(cur, e, thr)
    if nz != 0:  # a coefficient within the error bound of 0: a cluster, or split
        return (LEAF_CLUSTER if w <= W_MIN or hi <= 4.0 * e else _SPLIT), hi
    if v == 1:
        return LEAF_ROOT, hi
    if v != 0:
        return (LEAF_CLUSTER if w <= W_MIN else _SPLIT), hi
    if lo > thr:
        return _NOTHING, hi
    if _monotone(cur, e):  # no interior minimum of |p|: only an end can be one
        at_start = u0 == 0.0 and abs(cur[0]) <= abs(cur[8]) and abs(cur[0]) <= thr
        at_end = u1 == 1.0 and abs(cur[8]) < abs(cur[0]) and abs(cur[8]) <= thr
        return (LEAF_NEAR if at_start or at_end else _NOTHING), hi
    return (LEAF_NEAR if w <= W_NEAR else _SPLIT), hi


@_njit
def isolate(b, E, thr, out, stack):
    """Classify [0, 1] for the Bernstein coefficients ``b`` (9,) with error bound ``E`` and
    near threshold ``thr`` into leaves ``out`` (N_LEAF, LEAF_WIDTH), left to right; returns
    how many (at most N_LEAF; -1 if more were needed: the caller treats the whole interval
    as a cluster). ``stack`` (_STACK, 12) is scratch: ``[u0, u1, E, b0 .. b8]`` per piece.
    """
    n = 0
    stack[0, 0], stack[0, 1], stack[0, 2] = 0.0, 1.0, E
    for i in range(9):
        stack[0, 3 + i] = b[i]
    top = 1
    cur = stack[_STACK - 3, 3:12]
    left = stack[_STACK - 2, 3:12]
    right = stack[_STACK - 1, 3:12]
    while top > 0:
        top -= 1
        u0, u1, e = stack[top, 0], stack[top, 1], stack[top, 2]
        for i in range(9):
            cur[i] = stack[top, 3 + i]
        kind, hi = _piece(cur, e, thr, u0, u1)
        if kind == _NOTHING:
            continue
        if n >= N_LEAF or (kind == _SPLIT and top + 2 > _STACK - 3):
            return -1  # a leaf past N_LEAF (never dropped), or a piece past the stack
        if kind != _SPLIT:
            n = _push_leaf(out, n, kind, u0, u1, e, cur)
            continue
        casteljau_split(cur, left, right)
        ec = e + 8.0 * _EPS * hi
        um = u0 + 0.5 * (u1 - u0)
        # push the right half first: the left one is taken next (leaves come out sorted)
        stack[top, 0], stack[top, 1], stack[top, 2] = um, u1, ec
        for i in range(9):
            stack[top, 3 + i] = right[i]
        stack[top + 1, 0], stack[top + 1, 1], stack[top + 1, 2] = u0, um, ec
        for i in range(9):
            stack[top + 1, 3 + i] = left[i]
        top += 2
    return n


@_njit
def refine_root(b, E):
    """The root s in (0, 1) of a root leaf's coefficients b (its end values of opposite signs):
    Newton's method kept inside the shrinking bracket (bisection where it would leave it).
    Stops when the bracket is at rounding level or |p(s)| is within the error bound."""
    s0, s1 = 0.0, 1.0
    f0 = b[0]
    s = b[0] / (b[0] - b[8])  # the chord
    if not (0.0 < s < 1.0):
        s = 0.5
    noise = E + 16.0 * _EPS * max(abs(b[0]), abs(b[8]))
    for _ in range(100):
        f, df = value_and_slope(b, s)
        if abs(f) <= noise:
            return s
        if (f < 0.0) == (f0 < 0.0):
            s0, f0 = s, f
        else:
            s1 = s
        sn = s - f / df if df != 0.0 else 0.5 * (s0 + s1)
        if not (s0 < sn < s1):
            sn = 0.5 * (s0 + s1)
        if abs(sn - s) <= 2.0 * _EPS * max(abs(s), 1e-300) or s1 - s0 <= 4.0 * _EPS:
            return sn
        s = sn
    return s


@_njit
def near_minimum(b):
    """Where |p| is least on [0, 1] for a near leaf's coefficients b (no root inside): the root
    of p' if p' changes sign (Newton inside the bracket), else the better end."""
    d0 = 8.0 * (b[1] - b[0])
    d1 = 8.0 * (b[8] - b[7])
    if (d0 < 0.0) == (d1 < 0.0) or d0 == 0.0 or d1 == 0.0:
        return 0.0 if abs(b[0]) <= abs(b[8]) else 1.0
    s0, s1 = 0.0, 1.0
    s = 0.5
    for _ in range(60):
        # p'(s) and p''(s) by central differences of value_and_slope's slope
        h = 1e-7
        _, g = value_and_slope(b, s)
        _, g2 = value_and_slope(b, min(s + h, 1.0))
        _, g1 = value_and_slope(b, max(s - h, 0.0))
        if (g < 0.0) == (d0 < 0.0):
            s0 = s
        else:
            s1 = s
        dg = (g2 - g1) / (min(s + h, 1.0) - max(s - h, 0.0))
        sn = s - g / dg if dg != 0.0 else 0.5 * (s0 + s1)
        if not (s0 < sn < s1):
            sn = 0.5 * (s0 + s1)
        if abs(sn - s) <= 1e-13 or s1 - s0 <= 1e-13:
            return sn
        s = sn
    return s
