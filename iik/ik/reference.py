"""The complete inverse kinematics of the arm class in NumPy (``method="reference"``): an
independent path to the answer of the compiled kernel (:mod:`iik.ik.kernel`).

The two share the equations (:func:`iik.ik.elimination.pose_terms`: the general Eq 8 and
Eq 11, ``docs/IK_CLASS.md``) and nothing of how they are solved:

* **theta1**: every root of the degree-8 polynomial, as the eigenvalues of its companion
  matrix (batched LAPACK), with a per-pose reference angle chosen so that no root is near
  t = infinity; roots with an imaginary part up to :data:`IMAG_TOL` are kept (a near-double
  root loses its real pair to rounding); within a cluster of roots, F's sign changes on a grid
  in extended precision (np.longdouble), bisected, and the crossings of the two conditions'
  curves (:mod:`iik.ik.crossings`, which give theta2 too): where the kernel isolates with
  certified signs and re-expands clusters in double-double;
* **theta2**: every point of the unit circle on each of the two conditions (and Cramer's
  point), where the kernel takes Cramer's point unless the conditions are nearly parallel;
* **the wrist**: generic frames of the solver chain written here in NumPy;
* **verification**: every candidate is polished by batched Levenberg-Marquardt on the
  NumPy chain product (:func:`iik.dh.dh_chain`), kept if it reaches the pose within the
  tolerances, and merged with the rows it is connected to within the tolerance;
* **continua**: a row whose joint 3 is (nearly) free is snapped onto the collinear continuum
  and kept as one if that reaches the pose, else flagged numerical; an eliminant vanishing on
  the whole circle gives a theta1 continuum.

Frames and units: the arm's base frame, metres and radians.
"""

from __future__ import annotations

import numpy as np

from ..arm import Arm
from ..dh import dh_chain
from . import layout as L
from .angles import wrap_angle as _wrap
from .crossings import cluster_crossings
from .elimination import pose_terms

__all__ = ["solve_arrays", "IMAG_TOL", "POSITION_TOL", "ROTATION_TOL"]

#: Accept a solution only if |p_fk - p| <= POSITION_TOL [m] ...
POSITION_TOL = 1e-10
#: ... and the rotation angle between R_fk and R is <= ROTATION_TOL [rad].
ROTATION_TOL = 1e-10
#: Eigenvalues with |imag| up to this (relative to 1 + |t|) are theta1 candidates.
IMAG_TOL = 1e-3
#: Candidates whose joint 3 is this close to free (|z6| or |D - C| / a4 across z3) are also
#: started from RESTARTS angles of joint 3 around the circle.
RESTART_H = L.RESTART_H
#: ... from this many angles of joint 3.
RESTARTS = 24
#: Rows farther apart than this [rad] in some joint are never one solution (:func:`_connected`).
CONNECT_NEAR = 1e-2
_TWO_PI = 2.0 * np.pi
_GRID = np.arange(12) * (_TWO_PI / 12)


# ----------------------------------------------------------------------------- chain (NumPy)
def _fk_jac(arm: Arm, q: np.ndarray):
    """Tool poses (n, 4, 4) and geometric Jacobians (n, 6, 6) of the user chain."""
    F = np.array(arm.base) @ dh_chain(arm.dh_table(), q, all_frames=True)
    T = F[:, -1] @ np.array(arm.tool)
    z, o, p = F[:, :, :3, 2], F[:, :, :3, 3], T[:, None, :3, 3]
    J = np.concatenate([np.cross(z, p - o), z], axis=2).transpose(0, 2, 1)
    return T, J


def _errors(Tq, T):
    """Newton error vectors (n, 6) and residuals (position, rotation angle) against T (n, 4, 4)."""
    e = np.empty((len(Tq), 6))
    e[:, :3] = T[:, :3, 3] - Tq[:, :3, 3]
    M = T[:, :3, :3] @ np.transpose(Tq[:, :3, :3], (0, 2, 1))
    e[:, 3], e[:, 4], e[:, 5] = (
        0.5 * (M[:, 2, 1] - M[:, 1, 2]),
        0.5 * (M[:, 0, 2] - M[:, 2, 0]),
        0.5 * (M[:, 1, 0] - M[:, 0, 1]),
    )
    d = np.linalg.norm(Tq[:, :3, :3] - T[:, :3, :3], axis=(1, 2))
    return e, np.linalg.norm(e[:, :3], axis=1), 2.0 * np.arcsin(np.minimum(d / np.sqrt(8.0), 1.0))


def _polish(arm: Arm, q, T, iters: int = 30, cols=None):
    """Batched Levenberg-Marquardt (over ``cols``, default all joints) of q (n, 6) towards T (n, 4, 4)."""
    q = q.copy()
    mask = np.ones(6) if cols is None else np.isin(np.arange(6), cols).astype(float)
    lam = np.zeros(len(q))  # Gauss-Newton first: damping would stall it along a thin valley
    Tq, J = _fk_jac(arm, q)
    e, pres, rres = _errors(Tq, T)
    err = np.einsum("ni,ni->n", e, e)
    eye = np.eye(6)
    for _ in range(iters):
        act = err > 1e-32
        if not act.any():
            break
        Jm = J * mask
        A = np.einsum("nri,nrj->nij", Jm, Jm)
        tr = np.trace(A, axis1=1, axis2=2)[:, None, None] / mask.sum()
        A = A + (lam[:, None, None] + 1e-24) * tr * eye + (1.0 - mask)[None, :, None] * eye
        g = np.einsum("nri,nr->ni", Jm, e)[..., None]
        try:
            dq = np.linalg.solve(A, g)[..., 0] * mask
        except np.linalg.LinAlgError:  # an exactly singular row: the pseudo-inverse, this step
            dq = (np.linalg.pinv(A, hermitian=True) @ g)[..., 0] * mask
        qn = q + np.where(act[:, None], dq, 0.0)
        Tn, Jn = _fk_jac(arm, qn)
        en, pn, rn = _errors(Tn, T)
        errn = np.einsum("ni,ni->n", en, en)
        ok = (errn <= err) & act
        q, e, J = (
            np.where(ok[:, None], qn, q),
            np.where(ok[:, None], en, e),
            np.where(ok[:, None, None], Jn, J),
        )
        pres, rres, err = np.where(ok, pn, pres), np.where(ok, rn, rres), np.where(ok, errn, err)
        lam = np.where(ok, 0.1 * lam, np.clip(10.0 * lam, 1e-12, 1e6))
    return _wrap(q), pres, rres


# ----------------------------------------------------------------------------- solver chain
def _solver_poses(T: np.ndarray, arm: Arm) -> np.ndarray:
    """The solver chain's frame-6 poses (n, 4, 4) for the tool poses T (n, 4, 4)."""
    s = arm.solver
    X = np.linalg.inv(T) if s.reversed else T
    return np.linalg.inv(s.base) @ X @ np.linalg.inv(s.tool)


def _link(row, th):
    ca, sa, a, d, off = row
    ct, st = np.cos(th + off), np.sin(th + off)
    Lk = np.zeros(th.shape + (4, 4))
    Lk[..., 0, 0], Lk[..., 0, 1], Lk[..., 0, 3] = ct, -st, a
    Lk[..., 1, 0], Lk[..., 1, 1], Lk[..., 1, 2], Lk[..., 1, 3] = ca * st, ca * ct, -sa, -sa * d
    Lk[..., 2, 0], Lk[..., 2, 1], Lk[..., 2, 2], Lk[..., 2, 3] = sa * st, sa * ct, ca, ca * d
    Lk[..., 3, 3] = 1.0
    return Lk


def _in_plane(F, w, s):
    """Joint angle (without offset handling) turning link frame F (at angle 0) so that the next
    axis, (s sin, -s cos, 0) in F for a 90-deg twist of sign s, lies along w (.., 3)."""
    x = s * np.einsum("...i,...i->...", F[..., :3, 0], w)
    y = -s * np.einsum("...i,...i->...", F[..., :3, 1], w)
    return np.arctan2(x, y)


def _wrist(arm: Arm, P, th1, th2, branch):
    """Solver joints 3-6 (m, 4) of joint 1, 2 angles (m,) [solver joint values], both in rad,
    for solver poses P (m, 4, 4) and branch signs (m,) (+1, -1); and h (m,)."""
    rows = arm.solver.rows
    F = _link(rows[0], th1) @ _link(rows[1], th2)
    F30 = F @ _link(rows[2], np.full(th1.shape, -rows[2][4]))
    z3 = F30[:, :3, 2]
    z6, D = P[:, :3, 2], P[:, :3, 3]
    e = D - F30[:, :3, 3]
    a4 = rows[4][2]
    h6 = z6 - np.einsum("ni,ni->n", z6, z3)[:, None] * z3
    hD = (e - np.einsum("ni,ni->n", e, z3)[:, None] * z3) / a4
    n6, nD = np.linalg.norm(h6, axis=1), np.linalg.norm(hD, axis=1)
    h = np.where((n6 >= nD)[:, None], h6, hD)
    z4 = branch[:, None] * np.cross(z3, h)
    t3 = _in_plane(F30, z4, rows[3][1])  # DH angle of joint 3
    q3 = np.where(np.maximum(n6, nD) <= 1e-12, 0.0, _wrap(t3 - rows[2][4]))  # free: joint 3 at 0
    F3 = F @ _link(rows[2], q3)
    F40 = F3 @ _link(rows[3], np.full(th1.shape, -rows[3][4]))
    x = np.einsum("ni,ni->n", F40[:, :3, 0], e) / a4
    y = np.einsum("ni,ni->n", F40[:, :3, 1], e) / a4
    q4 = _wrap(np.arctan2(y, x) - rows[3][4])
    F4 = F3 @ _link(rows[3], q4)
    F50 = F4 @ _link(rows[4], np.full(th1.shape, -rows[4][4]))
    q5 = _wrap(_in_plane(F50, z6, rows[5][1]) - rows[4][4])
    F60 = F4 @ _link(rows[4], q5) @ _link(rows[5], np.full(th1.shape, -rows[5][4]))
    m00 = np.einsum("ni,ni->n", F60[:, :3, 0], P[:, :3, 0])
    m10 = np.einsum("ni,ni->n", F60[:, :3, 1], P[:, :3, 0])
    q6 = _wrap(np.arctan2(m10, m00) - rows[5][4])
    return np.stack([q3, q4, q5, q6], axis=1), np.maximum(n6, nD)


# ----------------------------------------------------------------------------- eliminant
def _terms(P: np.ndarray, arm: Arm) -> np.ndarray:
    """The 18 first-degree coefficients (n, 6, 3) of a, b, c, P, Q, R."""
    k = arm.kernel_vector()
    t = pose_terms(P[:, 0, 2], P[:, 1, 2], P[:, 2, 2], P[:, 0, 3], P[:, 1, 3], P[:, 2, 3], k, L.A_CONST, -1.0)
    return np.stack([np.broadcast_to(x, (len(P),)) for x in t], axis=1).reshape(-1, 6, 3)


def _at(x, th):
    """First-degree polynomials x (n, ..., 3) at angles th (n, m) -> (n, m, ...)."""
    c, s = np.cos(th), np.sin(th)
    return x[:, None, ..., 0] + x[:, None, ..., 1] * c[..., None] + x[:, None, ..., 2] * s[..., None]


def _F(x, th):
    a, b, c, P, Q, R = (_at(x, th)[..., i] for i in range(6))
    return (Q * a - R * c) ** 2 + (R * b - P * a) ** 2 - (P * c - Q * b) ** 2


def _poly_t(x, thr):
    """Ascending coefficients (n, 9) of (1 + t^2)^4 F(thr + 2 atan t)."""
    cr, sr = np.cos(thr)[:, None], np.sin(thr)[:, None]
    c = x[..., 1] * cr + x[..., 2] * sr
    s = -x[..., 1] * sr + x[..., 2] * cr
    quad = np.stack([x[..., 0] + c, 2.0 * s, x[..., 0] - c], axis=-1)  # (n, 6, 3)

    def mul(u, v):
        out = np.zeros(u.shape[:-1] + (u.shape[-1] + v.shape[-1] - 1,))
        for i in range(u.shape[-1]):
            out[..., i : i + v.shape[-1]] += u[..., i : i + 1] * v
        return out

    a, b, cc, P, Q, R = (quad[:, i] for i in range(6))
    G1, G2, G3 = mul(Q, a) - mul(R, cc), mul(R, b) - mul(P, a), mul(P, cc) - mul(Q, b)
    return mul(G1, G1) + mul(G2, G2) - mul(G3, G3)


def _theta1(x):
    """theta1 candidates (n, 23) of the solver chain [DH angle] (NaN where none): the 8 roots, the
    means of close pairs (:func:`_pair_means`) and the roots of each cluster found again in
    extended precision (:func:`_cluster_roots`); and whether F vanishes on the whole circle."""
    n = len(x)
    Fg = np.abs(_F(x, np.broadcast_to(_GRID + np.pi, (n, 12))))
    scale = Fg.max(axis=1)
    thr = _GRID[np.argmax(Fg, axis=1)]
    p = _poly_t(x, thr)
    mag = np.abs(p).max(axis=1)
    flat = mag <= 1e-12 * np.maximum(np.abs(x).max(axis=(1, 2)) ** 4, 1e-300)
    out = np.full((n, 8), np.nan)
    ok = ~flat & (np.abs(p[:, 8]) > 1e-14 * mag) & (scale > 0)
    if ok.any():
        comp = np.zeros((ok.sum(), 8, 8))
        comp[:, 0, :] = -p[ok, 7::-1] / p[ok, 8:9]
        comp[:, np.arange(1, 8), np.arange(7)] = 1.0
        t = np.linalg.eigvals(comp)
        real = np.abs(t.imag) <= IMAG_TOL * (1.0 + np.abs(t))
        out[ok] = np.where(real, thr[ok, None] + 2.0 * np.arctan(t.real), np.nan)
    return np.concatenate([out, _pair_means(out), _cluster_roots(x, out)], axis=1), flat


def _pair_means(th):
    """The mean of each pair of neighbouring roots (n, 8) closer than 1e-3 rad (else NaN), (n, 7):
    a double root perturbed by rounding splits into two roots ~sqrt(eps) apart (or a complex
    pair) symmetrically about it, to first order, so their mean is the better estimate."""
    s = np.sort(th, axis=1)  # (NaN last)
    with np.errstate(invalid="ignore"):
        close = np.abs(s[:, 1:] - s[:, :-1]) <= 1e-3
    return np.where(close, 0.5 * (s[:, 1:] + s[:, :-1]), np.nan)


def _cluster_roots(x, th, width: int = 8, grid: int = 256):
    """Roots of F in each cluster of eigenvalue roots th (n, 8) (neighbours closer than 1e-3
    rad), by sign changes on ``grid`` angles over the cluster (half its spread, at least 1e-5
    rad, beyond each end) and bisection, F evaluated in extended precision (np.longdouble from
    the double coefficients x): up to ``width`` per pose, NaN elsewhere, (n, width). In a
    cluster of nearly multiple roots the eigenvalues err by ~1e-4 and every candidate polishes
    onto the same solution (CRX-10iA off-singular: three solutions whose joint 6 lie 1.4e-4 rad
    apart; the reference found the middle one)."""
    out = np.full((len(th), width), np.nan)
    found = [[] for _ in range(len(th))]
    for i, lo, hi in _clusters(th):
        w = max(0.5 * (hi - lo), 1e-5)
        found[i] += _sign_changes(x[i], np.linspace(lo - w, hi + w, grid))
    for i, f in enumerate(found):
        out[i, : min(len(f), width)] = f[:width]
    return out


def _clusters(th):
    """Each cluster (pose, lowest, highest root) of the eigenvalue roots th (n, m) [rad]: two or
    more roots whose neighbours lie closer than 1e-3 rad."""
    for i, row in enumerate(np.sort(th, axis=1)):
        row = row[~np.isnan(row)]
        for g in np.split(row, np.flatnonzero(np.diff(row) > 1e-3) + 1):
            if len(g) > 1:
                yield i, float(g[0]), float(g[-1])


def _crossing_pairs(x, th):
    """(owners, theta1, theta2) [DH angles] of every crossing of the conditions' curves inside
    each cluster of the eigenvalue roots th (n, 8) (:func:`iik.ik.crossings.cluster_crossings`):
    the solutions of a cluster whose theta1 lie too close for F's sign to separate them."""
    own, t1, t2 = [], [], []
    for i, lo, hi in _clusters(th):
        a, b = cluster_crossings(x[i], lo, hi)
        own += [i] * len(a)
        t1.append(a)
        t2.append(b)
    if not own:
        return np.empty(0, int), np.empty(0), np.empty(0)
    return np.array(own), np.concatenate(t1), np.concatenate(t2)


def _F_long(x, th):
    """:func:`_F` of one pose's coefficients x (6, 3) at angles th (m,), in np.longdouble."""
    return _F(x[None].astype(np.longdouble), np.asarray(th, dtype=np.longdouble)[None])[0]


def _sign_changes(x, th, iters: int = 48) -> list:
    """The roots of F between neighbouring angles of th where its sign changes, by bisection."""
    f = _F_long(x, th)
    idx = np.flatnonzero(np.sign(f[:-1]) * np.sign(f[1:]) < 0)
    lo, hi = th[idx].astype(np.longdouble), th[idx + 1].astype(np.longdouble)
    flo = f[idx]
    for _ in range(iters):
        mid = 0.5 * (lo + hi)
        fm = _F_long(x, mid)
        left = np.sign(fm) == np.sign(flo)
        lo, flo, hi = np.where(left, mid, lo), np.where(left, fm, flo), np.where(left, hi, mid)
    return [float(v) for v in 0.5 * (lo + hi)]


def _theta2(x, own, th1):
    """theta2 options [DH angle] (m, 5) at (own, th1): Cramer's point and each condition's points
    on the unit circle (or the nearest point when the line misses it); NaN where none."""
    c, s = np.cos(th1), np.sin(th1)
    v = x[own, :, 0] + x[own, :, 1] * c[:, None] + x[own, :, 2] * s[:, None]
    a, b, cc, P, Q, R = v.T
    out = np.full((len(th1), 5), np.nan)
    det = P * cc - Q * b
    with np.errstate(invalid="ignore", divide="ignore"):
        out[:, 0] = np.where(
            det != 0, np.arctan2((R * b - P * a) * np.sign(det), (Q * a - R * cc) * np.sign(det)), np.nan
        )
    for k, (al, be, ga) in enumerate(((P, Q, -R), (b, cc, -a))):
        nn = np.hypot(al, be)
        with np.errstate(invalid="ignore", divide="ignore"):
            d = ga / nn
            fx, fy = d * al / nn, d * be / nn
            hh = np.sqrt(np.maximum(1.0 - d * d, 0.0))
            tx, ty = -be / nn, al / nn
        out[:, 1 + 2 * k] = np.arctan2(fy + hh * ty, fx + hh * tx)
        out[:, 2 + 2 * k] = np.arctan2(fy - hh * ty, fx - hh * tx)
    return out


# ----------------------------------------------------------------------------- the solver
def solve_arrays(
    T: np.ndarray, arm: Arm, *, tol_p: float = POSITION_TOL, tol_r: float = ROTATION_TOL, cut=None
):
    """Every solution of each pose T (n, 4, 4) (validated, rotations proper).

    Returns ``(Q, V, F, P, R)``: configurations (n, MAX_SOLUTIONS, 6) [rad], valid mask
    (n, MAX_SOLUTIONS), continuum kinds (:mod:`iik.ik.layout` ``FREE_*``), position and
    rotation residuals [m, rad]; rows sorted valid-first and lexicographically. ``cut`` (n,)
    bool, if given, is set where a pose had more distinct rows than MAX_SOLUTIONS (the first
    ones in that order are kept).
    """
    n = len(T)
    P = _solver_poses(T, arm)
    x = _terms(P, arm)
    th1, flat = _theta1(x)
    grid = np.array([0.3, 0.3 + np.pi])
    th1 = np.where(flat[:, None], np.concatenate([grid, np.full(th1.shape[1] - 2, np.nan)])[None], th1)
    own, col = np.nonzero(~np.isnan(th1))
    t1 = th1[own, col]
    t2 = _theta2(x, own, t1)
    o2, k2 = np.nonzero(~np.isnan(t2))
    own2, t1f, t2f = own[o2], t1[o2], t2[o2, k2]
    cross = _crossing_pairs(x, th1[:, :8])
    own2, t1f, t2f = (np.concatenate([u, v]) for u, v in zip((own2, t1f, t2f), cross, strict=True))
    t1f, t2f = _refine_pairs(x, own2, t1f, t2f)
    rows = arm.solver.rows
    own3 = np.repeat(own2, 2)
    q1s, q2s = np.repeat(t1f - rows[0][4], 2), np.repeat(t2f - rows[1][4], 2)
    branch = np.tile([1.0, -1.0], len(own2))
    wr, hval = _wrist(arm, P[own3], q1s, q2s, branch)
    qs = np.column_stack([q1s, q2s, wr])
    qs, own3, hval = _restarts(qs, own3, hval, RESTART_H)
    f2 = np.zeros(len(qs), bool)
    extra = _theta2_free_rows(arm, P, x, th1, flat)
    if extra is not None:
        qs, own3, hval = np.concatenate([qs, extra[0]]), np.concatenate([own3, extra[1]]), np.concatenate(
            [hval, extra[2]]
        )
        f2 = np.concatenate([f2, extra[3]])
    q = qs[:, ::-1] if arm.solver.reversed else qs
    q, pres, rres = _polish(arm, _wrap(q), T[own3])
    keep = (pres <= tol_p) & (rres <= tol_r)
    qk = q[keep][:, ::-1] if arm.solver.reversed else q[keep]  # h where the polish ended
    hval = hval.copy()
    hval[keep] = _wrist(arm, P[own3[keep]], qk[:, 0], qk[:, 1], np.ones(int(keep.sum())))[1]
    return _collect(
        n, q[keep], own3[keep], pres[keep], rres[keep], hval[keep], f2[keep], flat, T, arm, tol_p, tol_r, cut
    )


def _conditions(x, own, t1, t2):
    """The two conditions G1 = R + P c2 + Q s2 and G2 = a + b c2 + c s2 at (t1, t2) [DH angles]
    (m,) and their Jacobian (m, 2, 2) in (t1, t2)."""
    c, s = np.cos(t1)[:, None], np.sin(t1)[:, None]
    v = x[own, :, 0] + x[own, :, 1] * c + x[own, :, 2] * s  # (m, 6): a, b, c, P, Q, R
    d = -x[own, :, 1] * s + x[own, :, 2] * c
    c2, s2 = np.cos(t2), np.sin(t2)
    G = np.stack([v[:, 5] + v[:, 3] * c2 + v[:, 4] * s2, v[:, 0] + v[:, 1] * c2 + v[:, 2] * s2], axis=1)
    J = np.empty((len(t1), 2, 2))
    J[:, 0, 0], J[:, 0, 1] = d[:, 5] + d[:, 3] * c2 + d[:, 4] * s2, -v[:, 3] * s2 + v[:, 4] * c2
    J[:, 1, 0], J[:, 1, 1] = d[:, 0] + d[:, 1] * c2 + d[:, 2] * s2, -v[:, 1] * s2 + v[:, 2] * c2
    return G, J


def _refine_pairs(x, own, t1, t2):
    """(theta1, theta2) candidates refined by Newton's method on the two unsquared conditions
    (4 steps, each kept where it reduces them and moves less than 1e-3 rad): a root of the
    squared eliminant is only as accurate as F is steep, the conditions are not squared."""
    G, J = _conditions(x, own, t1, t2)
    err = np.abs(G).sum(axis=1)
    for _ in range(4):
        det = J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0]
        with np.errstate(invalid="ignore", divide="ignore"):  # (Cramer's rule; det = 0: no step)
            step = np.stack([G[:, 0] * J[:, 1, 1] - G[:, 1] * J[:, 0, 1],
                             J[:, 0, 0] * G[:, 1] - J[:, 1, 0] * G[:, 0]], axis=1) / det[:, None]
        ok = np.all(np.isfinite(step), axis=1) & (np.abs(step).max(axis=1) <= 1e-3)
        n1, n2 = t1 - np.where(ok, step[:, 0], 0.0), t2 - np.where(ok, step[:, 1], 0.0)
        Gn, Jn = _conditions(x, own, n1, n2)
        en = np.abs(Gn).sum(axis=1)
        better = ok & (en < err)
        t1, t2 = np.where(better, n1, t1), np.where(better, n2, t2)
        G, J = np.where(better[:, None], Gn, G), np.where(better[:, None, None], Jn, J)
        err = np.where(better, en, err)
    return t1, t2


def _free_theta2(x, th1):
    """theta1 [DH angle] (n, 8) where a, b, c, P, Q and R all vanish (theta2 free,
    docs/IK_CLASS.md section 5 C), or NaN: each root of the eliminant refined by Gauss-Newton on
    the six first-degree polynomials, kept if all six vanish to 1e-9 of their coefficients.
    (The kernel finds these angles in closed form; here they come from the eigenvalues.)"""
    t = th1.copy()
    for _ in range(8):
        c, s = np.cos(t)[..., None], np.sin(t)[..., None]
        v = x[:, None, :, 0] + x[:, None, :, 1] * c + x[:, None, :, 2] * s  # (n, 8, 6)
        dv = -x[:, None, :, 1] * s + x[:, None, :, 2] * c
        with np.errstate(invalid="ignore", divide="ignore"):
            step = np.sum(v * dv, -1) / np.sum(dv * dv, -1)
        t = t - np.where(np.abs(step) < 1e-2, step, 0.0)
    c, s = np.cos(t)[..., None], np.sin(t)[..., None]
    v = np.abs(x[:, None, :, 0] + x[:, None, :, 1] * c + x[:, None, :, 2] * s)
    size = np.abs(x).reshape(len(x), 2, 9).max(axis=2)  # (a, b, c) and (P, Q, R)
    with np.errstate(invalid="ignore"):
        ok = (v[..., :3].sum(-1) <= L.VANISH * size[:, None, 0]) & (
            v[..., 3:].sum(-1) <= L.VANISH * size[:, None, 1]
        )
    return np.where(ok, t, np.nan)


def _theta2_free_rows(arm: Arm, P, x, th1, flat):
    """Candidates (solver joints (m, 6), owners (m,), h (m,), is the continuum's representative
    (m,)) of every theta2 continuum at each distinct theta1 of :func:`_free_theta2`: joint 2 at 0
    (the representatives) and where a theta3 continuum may cross (:func:`_aligned_theta2`),
    both wrist branches; None if there is none."""
    t = np.where(flat[:, None], np.nan, _free_theta2(x, th1))
    own, col = np.nonzero(~np.isnan(t))
    if len(own) == 0:
        return None
    pairs = []
    for i, tt in zip(own, t[own, col], strict=True):
        if not any(i == j and abs(_wrap(tt - u)) <= 1e-9 for j, u in pairs):
            pairs.append((i, tt))
    own = np.repeat([i for i, _ in pairs], 6)
    rows = arm.solver.rows
    q1 = np.repeat([u - rows[0][4] for _, u in pairs], 6)
    q2 = np.concatenate([_aligned_theta2(arm, P[i], u - rows[0][4]) for i, u in pairs])
    wr, h = _wrist(arm, P[own], q1, q2, np.tile([1.0, -1.0], 3 * len(pairs)))
    first = np.tile([True, True, False, False, False, False], len(pairs))
    return np.column_stack([q1, q2, wr]), own, h, first


def _aligned_theta2(arm: Arm, P, q1):
    """Solver joint 2 values (6,) on a theta2 continuum at solver joint 1 = q1: 0 (twice, one
    per wrist branch), and (twice each) where axis 3 turns closest to z6 and to -z6, found by
    minimising and maximising z3 . z6 over a grid refined by golden sections (where z3 is
    along z6 a theta3 continuum crosses)."""
    rows = arm.solver.rows
    z6 = P[:3, 2]

    def dot(q2):
        F = _link(rows[0], np.full(np.shape(q2), q1)) @ _link(rows[1], q2) @ _link(
            rows[2], np.full(np.shape(q2), -rows[2][4])
        )
        return F[..., :3, 2] @ z6

    grid = np.linspace(-np.pi, np.pi, 73)
    d = dot(grid)
    out = [0.0, 0.0]
    for sgn in (1.0, -1.0):
        k = int(np.argmax(sgn * d))
        lo, hi = grid[k] - 2 * np.pi / 72, grid[k] + 2 * np.pi / 72
        for _ in range(60):
            m1, m2 = hi - 0.618 * (hi - lo), lo + 0.618 * (hi - lo)
            if sgn * dot(np.array(m1)) >= sgn * dot(np.array(m2)):
                hi = m2
            else:
                lo = m1
        out += [0.5 * (lo + hi)] * 2
    return np.array(out)


def _on_theta2_curve(a, b, T, arm: Arm) -> bool:
    """Is b a member of the theta2 continuum of row a: solver joint 1 equal to 1e-6 rad and b the
    closed-form configuration at a's joint 1 and b's joint 2 on a's wrist branch (to 1e-6 rad)?"""
    rev = arm.solver.reversed
    sa, sb = (a[::-1], b[::-1]) if rev else (np.asarray(a), np.asarray(b))
    if abs(_wrap(sa[0] - sb[0])) > 1e-6:
        return False
    P = _solver_poses(np.asarray(T)[None], arm)
    br = np.array([1.0, -1.0])
    wa, _ = _wrist(arm, np.repeat(P, 2, 0), np.full(2, sa[0]), np.full(2, sa[1]), br)
    mine = np.flatnonzero(np.max(np.abs(_wrap(wa - sa[2:])), axis=1) <= 1e-6)
    if len(mine) == 0:
        return False
    wb, _ = _wrist(arm, P, np.array([sa[0]]), np.array([sb[1]]), br[mine[:1]])
    return bool(np.max(np.abs(_wrap(wb[0] - sb[2:]))) <= 1e-6)


def _restarts(qs, own, hval, near):
    """Near the collinear continuum joint 3 is fixed only loosely by the pose and the closed
    forms place it poorly: each such candidate (solver joints) is also started from RESTARTS
    angles of joint 3 around the circle, joint 6 turned with it (both ways). (The tube around
    a continuum broken by 1e-9 rad is thin: a start farther than ~0.3 rad from a solution along
    it may not reach it within the polish's iterations; the kernel starts from 8 angles with
    the coupling's sign, from a joint 3 placed by the closed forms.)"""
    idx = np.flatnonzero(hval <= near)
    if len(idx) == 0:
        return qs, own, hval
    extra = []
    for k in range(1, RESTARTS):
        for sg in (1.0, -1.0):
            e = qs[idx].copy()
            e[:, 2] += k * 2 * np.pi / RESTARTS
            e[:, 5] += sg * k * 2 * np.pi / RESTARTS
            extra.append(e)
    reps = len(extra)
    return (
        np.concatenate([qs] + extra),
        np.concatenate([own] + [own[idx]] * reps),
        np.concatenate([hval] + [hval[idx]] * reps),
    )


def _connected(a, b, T, arm: Arm, tol_p, tol_r) -> bool:
    """Rows a and b (within CONNECT_NEAR rad) in one connected piece of the set that reaches the
    pose within the tolerance: 9 points of the segment between them do, or else 9 points of a
    bent path do (the joint that moves most stepped along the segment, the others refit with it
    held; no point moved farther than the rows are apart).
    Near a multiple root that set is a thin curved blob (residual ~ c d^2 along it, c ~ 1e-3),
    and beside the collinear continuum a tube whose points 1e-3 rad from it lie up to 7e-3 rad
    apart: a straight segment between two of its points leaves it, and the rows would count as
    several solutions (filling the 16 rows and pushing out isolated solutions)."""
    d = _wrap(b - a)
    size = float(np.max(np.abs(d)))
    if size > CONNECT_NEAR:
        return False
    pts = a + np.linspace(0.1, 0.9, 9)[:, None] * d
    Tq, _ = _fk_jac(arm, pts)
    _, pr, rr = _errors(Tq, np.broadcast_to(T, (9, 4, 4)))
    if np.all(pr <= tol_p) and np.all(rr <= tol_r):
        return True
    held = int(np.argmax(np.abs(d)))  # (held where a and b agree, the points would slide to either)
    cols = [k for k in range(6) if k != held]
    out, pr, rr = _polish(arm, pts, np.broadcast_to(T, (9, 4, 4)), iters=12, cols=cols)
    return bool(np.all(pr <= tol_p) and np.all(rr <= tol_r) and np.max(np.abs(_wrap(out - pts))) <= size)


def _snap(arm: Arm, q, T, tol_p, tol_r):
    """The collinear continuum through q (joint 3 free), if it reaches the pose: the row with
    solver joints 4 and 5 moved onto it and joints 1, 2, 6 refit; else None."""
    rev = arm.solver.reversed
    qs = q[::-1].copy() if rev else q.copy()
    rows = arm.solver.rows
    F = np.eye(4)
    for i in range(3):
        F = F @ _link(rows[i], np.array(qs[i]))
    z3 = F[:3, 2]
    F40 = F @ _link(rows[3], np.array(-rows[3][4]))
    phi = np.arctan2(F40[:3, 1] @ z3, F40[:3, 0] @ z3)
    t4 = min((phi, phi + np.pi), key=lambda t: abs(_wrap(t - qs[3] - rows[3][4])))
    qs[3] = _wrap(t4 - rows[3][4])
    F50 = F @ _link(rows[3], np.array(qs[3])) @ _link(rows[4], np.array(-rows[4][4]))
    s6 = rows[5][1]
    phi = np.arctan2(s6 * (F50[:3, 0] @ z3), -s6 * (F50[:3, 1] @ z3))
    t5 = min((phi, phi + np.pi), key=lambda t: abs(_wrap(t - qs[4] - rows[4][4])))
    qs[4] = _wrap(t5 - rows[4][4])
    qn = qs[::-1].copy() if rev else qs
    cols = [5, 4, 0] if rev else [0, 1, 5]
    qn, pr, rr = _polish(arm, qn[None], T[None], iters=20, cols=cols)
    return qn[0] if pr[0] <= tol_p and rr[0] <= tol_r else None


def _collect(n, q, own, pres, rres, hval, f2, flat, T, arm, tol_p, tol_r, cut):
    """Distinct rows per pose, continua flagged (theta2 continua first), in the kernel's layout;
    ``cut`` (n,) (or None) set where more than MAX_SOLUTIONS were distinct."""
    M = L.MAX_SOLUTIONS
    Q, V, F = np.full((n, M, 6), np.nan), np.zeros((n, M), bool), np.zeros((n, M), int)
    Pr, Rr = np.full((n, M), np.nan), np.full((n, M), np.nan)
    near = L.CONTINUUM_NEAR * np.sqrt(max(tol_p / arm.reach, tol_r))
    for i in range(n):
        idx = np.flatnonzero(own == i)
        idx = idx[np.lexsort((pres[idx] + rres[idx], ~f2[idx]))]
        idx = _coarse_distinct(q, idx)
        kept, kinds = [], []
        for j in idx:
            row, kind = q[j], L.FREE_NONE
            if f2[j]:
                kind = L.FREE_Q2
            elif flat[i]:
                kind = L.FREE_Q1
            elif hval[j] <= near:
                snapped = _snap(arm, row, T[i], tol_p, tol_r)
                kind = L.FREE_NUMERICAL if snapped is None else L.FREE_Q3
                row = row if snapped is None else snapped
            if any(
                _same(row, q_k, k_k, kind, T[i], arm, tol_p, tol_r)
                for q_k, k_k in zip(kept, kinds, strict=True)
            ):
                continue
            kept.append(row)
            kinds.append(kind)
        order = sorted(range(len(kept)), key=lambda k: tuple(np.round(kept[k], 9)))[:M]
        if cut is not None:
            cut[i] = len(kept) > M
        for m, k in enumerate(order):
            Q[i, m], V[i, m], F[i, m] = kept[k], True, kinds[k]
        if order:
            Tq, _ = _fk_jac(arm, Q[i, : len(order)])
            _, Pr[i, : len(order)], Rr[i, : len(order)] = _errors(
                Tq, np.broadcast_to(T[i], (len(order), 4, 4))
            )
    return Q, V, F, Pr, Rr


def _coarse_distinct(q, idx, radius: float = 1e-6):
    """The rows of idx (best first) farther than ``radius`` from every earlier one."""
    out = []
    for j in idx:
        if not out or np.min(np.max(np.abs(_wrap(q[out] - q[j])), axis=1)) > radius:
            out.append(j)
    return np.array(out, dtype=int)


def _same(a, b, kb, ka, T, arm, tol_p, tol_r) -> bool:
    """One solution: equal to DISTINCT_TOL, connected within the tolerance, or on one continuum
    (collinear: joint 3 and its coupling; numerical and theta1: joints 1 and 2 of the solver
    chain agree to 1e-3, the tube or curve between them checked by the kernel's rules)."""
    if np.max(np.abs(_wrap(a - b))) <= L.DISTINCT_TOL:
        return True
    if L.FREE_Q2 in (ka, kb) and L.FREE_Q3 not in (ka, kb):  # (crossing continua are both kept)
        c, d = (b, a) if kb == L.FREE_Q2 else (a, b)
        if _on_theta2_curve(c, d, T, arm):
            return True
    if ka == kb and ka in (L.FREE_Q3, L.FREE_NUMERICAL, L.FREE_Q1):
        rev = arm.solver.reversed
        fixed = [5, 4] if rev else [0, 1]
        if ka == L.FREE_Q1:
            return _connected(a, b, T, arm, tol_p, tol_r)
        if np.max(np.abs(_wrap(a[fixed] - b[fixed]))) > 1e-3:
            return False
        return ka == L.FREE_Q3 or _one_tube(a, b, T, arm, tol_p, tol_r)
    return _connected(a, b, T, arm, tol_p, tol_r)


def _one_tube(a, b, T, arm: Arm, tol_p, tol_r) -> bool:
    """Near-continuum rows a and b on one tube within the tolerance: the members at 1/4, 1/2,
    3/4 and the whole of the arc of joint 3 from a to b (joint 6 moved with it, the other joints
    refit with joint 3 held, each member from the previous one) reach the pose, and the last
    member is connected to b (rows with one joint 3 on two branches are not one tube)."""
    rev = arm.solver.reversed
    j, j6 = (3, 0) if rev else (2, 5)
    s = (
        1.0
        if abs(_wrap(b[j6] - a[j6] - (b[j] - a[j]))) <= abs(_wrap(b[j6] - a[j6] + (b[j] - a[j])))
        else -1.0
    )
    d = _wrap(b[j] - a[j])
    cols = [k for k in range(6) if k != j]
    prev = np.array(a, dtype=float)
    for f in (0.25, 0.5, 0.75, 1.0):
        pt = prev.copy()
        pt[j] = a[j] + f * d
        pt[j6] = prev[j6] + s * (pt[j] - prev[j])
        out, pr, rr = _polish(arm, pt[None], T[None], iters=12, cols=cols)
        if not (pr[0] <= tol_p and rr[0] <= tol_r):
            return False
        prev = out[0]
    return _connected(prev, b, T, arm, tol_p, tol_r)
