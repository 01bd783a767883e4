"""Double-double arithmetic (about 32 significant digits) for the IK kernel's extended path.

A double-double number is a pair ``(hi, lo)`` with |lo| <= ulp(hi) / 2, exact sum hi + lo.
Error-free transformations: Knuth's two-sum and Dekker's two-product (Veltkamp's split; no
fused multiply-add is assumed, and Numba compiles without fast-math, so IEEE rounding holds).
Relative error of an operation: about 4 eps^2 (Dekker 1971; Shewchuk 1997). The transformations
are exact unless a product underflows (|a b| below ~1e-290) or overflows; the kernel's
numbers are scaled lengths and angles, far from both.

Used by :mod:`iik.ik.kernel` to build the eliminant's Bernstein coefficients on a cluster of
roots that double precision cannot separate (``PATH_EXTENDED``).
"""

from __future__ import annotations

import numba

__all__ = ["two_sum", "two_prod", "dd_add", "dd_mul", "dd_mul_d", "dd_lin"]

_njit = numba.njit(error_model="numpy")
_SPLIT = 134217729.0  # 2^27 + 1


@_njit
def two_sum(a, b):
    """s + e = a + b exactly, s = fl(a + b)."""
    s = a + b
    bb = s - a
    e = (a - (s - bb)) + (b - bb)
    return s, e


@_njit
def _fast_two_sum(a, b):
    s = a + b
    e = b - (s - a)
    return s, e


@_njit
def _split(a):
    c = _SPLIT * a
    hi = c - (c - a)
    return hi, a - hi


@_njit
def two_prod(a, b):
    """p + e = a b exactly, p = fl(a b) (Dekker's product)."""
    p = a * b
    ah, al = _split(a)
    bh, bl = _split(b)
    e = ((ah * bh - p) + ah * bl + al * bh) + al * bl
    return p, e


@_njit
def dd_add(ah, al, bh, bl):
    """(ah + al) + (bh + bl) in double-double."""
    s, e = two_sum(ah, bh)
    t, f = two_sum(al, bl)
    e += t
    s, e = _fast_two_sum(s, e)
    e += f
    return _fast_two_sum(s, e)


@_njit
def dd_mul(ah, al, bh, bl):
    """(ah + al) (bh + bl) in double-double."""
    p, e = two_prod(ah, bh)
    e += ah * bl + al * bh
    return _fast_two_sum(p, e)


@_njit
def dd_mul_d(ah, al, b):
    """(ah + al) b for a double b, in double-double."""
    p, e = two_prod(ah, b)
    e += al * b
    return _fast_two_sum(p, e)


@_njit
def dd_lin(ah, al, wa, bh, bl, wb):
    """wa (ah + al) + wb (bh + bl) for doubles wa, wb (a de Casteljau step)."""
    xh, xl = dd_mul_d(ah, al, wa)
    yh, yl = dd_mul_d(bh, bl, wb)
    return dd_add(xh, xl, yh, yl)
