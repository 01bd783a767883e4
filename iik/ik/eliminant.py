"""The eliminant F (:mod:`iik.ik.elimination`) on a half circle, as a degree-8 polynomial in
Bernstein form, in double precision with a rounding-error bound and in double-double.

theta1 = theta_r + phi with phi = 2 atan(t), t in [-1, 1] (a half circle; the other half has
theta_r + pi). Each first-degree trigonometric polynomial x of theta1 becomes
``(1 + t^2) x / 2``, whose Bernstein coefficients on t in [-1, 1] are
``(x0 - xs', xc', x0 + xs')`` with ``(xc', xs')`` the cos/sin coefficients turned by theta_r.
Products are convolutions of *scaled* Bernstein coefficients (``C(n, k) b_k``), so
``F ((1 + t^2) / 2)^4`` has Bernstein coefficients ``F_hat_k / C(8, k)``: the same signs,
the same roots (the factor is positive).

*The problem.* The 18 coefficients of :func:`iik.ik.elimination.pose_terms`, as computed
in double precision, and (cos, sin) of theta_r as stored define F exactly; the error bound
:data:`GAMMA` times the magnitude bounds the rounding of the double-precision construction
(an a-priori bound: ~24 roundings in sequence, each relative eps to the sum of absolute
terms). The double-double construction has relative error ~1e-31 of the magnitude.
"""

from __future__ import annotations

import numba

from .ddarith import dd_add, dd_mul, two_prod, two_sum

__all__ = ["GAMMA", "DD_GAMMA", "half_bernstein", "half_bernstein_dd", "dd_piece"]

_njit = numba.njit(error_model="numpy")

_EPS = 2.220446049250313e-16
#: Rounding-error bound of :func:`half_bernstein`, relative to its magnitude.
GAMMA = 64.0 * _EPS
#: ... and of :func:`half_bernstein_dd` (double-double).
DD_GAMMA = 4096.0 * _EPS * _EPS
_BINOM8 = (1.0, 8.0, 28.0, 56.0, 70.0, 56.0, 28.0, 8.0, 1.0)


@_njit
def _conv33(a, b, out, o) -> None:
    """Scaled degree-2 x degree-2 product into out[o:o + 5]."""
    out[o] = a[0] * b[0]
    out[o + 1] = a[0] * b[1] + a[1] * b[0]
    out[o + 2] = a[0] * b[2] + a[1] * b[1] + a[2] * b[0]
    out[o + 3] = a[1] * b[2] + a[2] * b[1]
    out[o + 4] = a[2] * b[2]


@_njit
def _quad(terms, i, cr, sr, sgn, s, out) -> None:
    """Scaled Bernstein coefficients (3,) of (1 + t^2) x / 2 for the first-degree polynomial
    terms[3i:3i + 3] on the half circle theta_r + [-pi/2, pi/2] (sgn = -1: theta_r + pi).
    With s = +1, absolute terms and (|cr|, |sr|): magnitudes."""
    x0, xc, xs = terms[3 * i], terms[3 * i + 1], terms[3 * i + 2]
    if s < 0.0:
        c = sgn * (xc * cr + xs * sr)  # cos coefficient turned by theta_r
        t = sgn * (xs * cr - xc * sr)  # sin coefficient turned by theta_r
        out[0], out[1], out[2] = x0 - t, 2.0 * c, x0 + t
    else:
        c = xc * cr + xs * sr
        t = xs * cr + xc * sr
        out[0], out[1], out[2] = x0 + t, 2.0 * c, x0 + t


@_njit
def half_bernstein(terms, cr, sr, sgn, s, work, b) -> None:
    """Bernstein coefficients b (9,) of F on the half circle theta_r + [-pi/2, pi/2]
    (``sgn = -1``: the other half) from the 18 pose terms. ``s = -1``: values; ``s = +1`` with
    absolute terms and (|cr|, |sr|): magnitudes (bounds of the sums of absolute terms).
    ``work`` (60,) is scratch."""
    qa, qb, qc = work[0:3], work[3:6], work[6:9]
    qP, qQ, qR = work[9:12], work[12:15], work[15:18]
    _quad(terms, 0, cr, sr, sgn, s, qa)
    _quad(terms, 1, cr, sr, sgn, s, qb)
    _quad(terms, 2, cr, sr, sgn, s, qc)
    _quad(terms, 3, cr, sr, sgn, s, qP)
    _quad(terms, 4, cr, sr, sgn, s, qQ)
    _quad(terms, 5, cr, sr, sgn, s, qR)
    g = work[18:38]  # four degree-4 products at a time
    G = work[38:53]  # G1, G2, G3 (scaled, degree 4)
    _conv33(qQ, qa, g, 0)
    _conv33(qR, qc, g, 5)
    _conv33(qR, qb, g, 10)
    _conv33(qP, qa, g, 15)
    for k in range(5):
        G[k] = g[k] + s * g[5 + k]  # G1 = Q a - R c
        G[5 + k] = g[10 + k] + s * g[15 + k]  # G2 = R b - P a
    _conv33(qP, qc, g, 0)
    _conv33(qQ, qb, g, 5)
    for k in range(5):
        G[10 + k] = g[k] + s * g[5 + k]  # G3 = P c - Q b
    for k in range(9):  # F_hat = G1^2 + G2^2 - G3^2 (scaled, degree 8)
        acc = 0.0
        for i in range(max(0, k - 4), min(4, k) + 1):
            j = k - i
            acc += G[i] * G[j] + G[5 + i] * G[5 + j] + s * G[10 + i] * G[10 + j]
        b[k] = acc / _BINOM8[k]


@_njit
def _quad_dd(terms, i, cr, sr, sgn, out) -> None:
    """:func:`_quad` (values) in double-double: out (3, 2) hi/lo."""
    x0, xc, xs = terms[3 * i], terms[3 * i + 1], terms[3 * i + 2]
    p1h, p1l = two_prod(xc, cr)
    p2h, p2l = two_prod(xs, sr)
    ch, cl = dd_add(p1h, p1l, p2h, p2l)
    p1h, p1l = two_prod(xs, cr)
    p2h, p2l = two_prod(-xc, sr)
    th, tl = dd_add(p1h, p1l, p2h, p2l)
    ch, cl, th, tl = sgn * ch, sgn * cl, sgn * th, sgn * tl
    out[0, 0], out[0, 1] = dd_add(x0, 0.0, -th, -tl)
    out[1, 0], out[1, 1] = 2.0 * ch, 2.0 * cl
    out[2, 0], out[2, 1] = dd_add(x0, 0.0, th, tl)


@_njit
def _conv33_dd(a, b, out, o, w) -> None:
    """w * (scaled degree-2 x degree-2 product) added into out[o:o + 5] (double-double)."""
    for k in range(5):
        for i in range(max(0, k - 2), min(2, k) + 1):
            ph, pl = dd_mul(a[i, 0], a[i, 1], b[k - i, 0], b[k - i, 1])
            out[o + k, 0], out[o + k, 1] = dd_add(out[o + k, 0], out[o + k, 1], w * ph, w * pl)


@_njit
def half_bernstein_dd(terms, cr, sr, sgn, work, b) -> None:
    """:func:`half_bernstein` (values) in double-double: b (9, 2) hi/lo. ``work`` (33, 2)."""
    q = work[0:18]  # six quadratics (3, 2) each
    for i in range(6):
        _quad_dd(terms, i, cr, sr, sgn, q[3 * i : 3 * i + 3])
    qa, qb, qc, qP, qQ, qR = q[0:3], q[3:6], q[6:9], q[9:12], q[12:15], q[15:18]
    G = work[18:33]
    for k in range(15):
        G[k, 0], G[k, 1] = 0.0, 0.0
    _conv33_dd(qQ, qa, G, 0, 1.0)
    _conv33_dd(qR, qc, G, 0, -1.0)
    _conv33_dd(qR, qb, G, 5, 1.0)
    _conv33_dd(qP, qa, G, 5, -1.0)
    _conv33_dd(qP, qc, G, 10, 1.0)
    _conv33_dd(qQ, qb, G, 10, -1.0)
    for k in range(9):
        h, lo = 0.0, 0.0
        for i in range(max(0, k - 4), min(4, k) + 1):
            j = k - i
            for g, w in ((0, 1.0), (5, 1.0), (10, -1.0)):
                ph, pl = dd_mul(G[g + i, 0], G[g + i, 1], G[g + j, 0], G[g + j, 1])
                h, lo = dd_add(h, lo, w * ph, w * pl)
        # divide by C(8, k): q1 = h / c, remainder exactly, second quotient
        c = _BINOM8[k]
        q1 = h / c
        ph, pl = two_prod(q1, c)
        rh, rl = dd_add(h, lo, -ph, -pl)
        q2 = (rh + rl) / c
        b[k, 0], b[k, 1] = two_sum(q1, q2)


@_njit
def _split_dd(b, u, keep_right, tmp) -> None:
    """de Casteljau at u in double-double, in place: b (9, 2) becomes the piece [u, 1]
    (keep_right) or [0, u] of itself. tmp (9, 2) scratch.

    Level k+1 overwrites entries 0 .. 7-k of level k, so entry 8-k keeps the last entry of
    level k: at the end b holds the right piece; the first entries (the left piece) go to tmp.
    """
    rh, rl = two_sum(1.0, -u)
    for k in range(9):
        tmp[k, 0], tmp[k, 1] = b[0, 0], b[0, 1]
        for i in range(8 - k):
            xh, xl = dd_mul(b[i, 0], b[i, 1], rh, rl)
            yh, yl = dd_mul(b[i + 1, 0], b[i + 1, 1], u, 0.0)
            b[i, 0], b[i, 1] = dd_add(xh, xl, yh, yl)
    if not keep_right:
        for i in range(9):
            b[i, 0], b[i, 1] = tmp[i, 0], tmp[i, 1]


@_njit
def dd_piece(b, u0, u1, tmp, out):
    """The Bernstein coefficients of the piece [u0, u1] of the double-double b (9, 2) (b is
    overwritten), rounded into out (9,); returns ``(u1 actually used, max |rounding|)``."""
    _split_dd(b, u0, True, tmp)  # [u0, 1]
    r = (u1 - u0) / (1.0 - u0)
    _split_dd(b, r, False, tmp)  # [u0, u0 + r (1 - u0)]
    err = 0.0
    for i in range(9):
        out[i] = b[i, 0] + b[i, 1]
        err = max(err, abs(b[i, 1]), abs((b[i, 0] - out[i]) + b[i, 1]))
    return u0 + r * (1.0 - u0), err
