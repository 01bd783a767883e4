"""The complete inverse kinematics, vectorised in NumPy (``method="reference"``).

The compiled kernel (:mod:`iik.ik.kernel`, ``method="complete"``, the default) and
this module solve the same elimination; this one is kept as an independent
reference (tests show the two agree) and for its batched LAPACK root finding.

The thesis (Sec 3.3) reduces the problem to two equations in (theta1, theta2):
the coplanarity condition Eq 8 and the length error Eq 11 (:mod:`iik.ik.elimination`).
For a fixed theta1, Eq 8 is linear in (c2, s2)::

    P(theta1) c2 + Q(theta1) s2 = 0   =>   (c2, s2) = sigma (Q, -P) / N,  N = sqrt(P^2 + Q^2)

and Eq 11 reads ``E = a + b c2 + c s2``. Substituting and multiplying the two
signs sigma = +-1 together eliminates theta2::

    F(theta1) = a^2 (P^2 + Q^2) - (b Q - c P)^2 = 0,

a trigonometric polynomial of degree 4. With a pose-dependent reference angle
``theta_r`` and ``t = tan((theta1 - theta_r)/2)`` it becomes a real polynomial of
degree 8 in ``t``; here its roots are the eigenvalues of the companion matrix
(batched LAPACK). ``theta_r`` is chosen per pose so that ``theta1 = theta_r + pi``
(``t = infinity``, where the degree drops) is far from every root.

Each real root is refined by Newton's method on the *unsquared* equation
``f_sigma = a N + sigma (b Q - c P)``; spurious roots (introduced by squaring
or by accepting nearly-real eigenvalues of near-double roots) are removed by
the final forward-kinematics check. theta2 follows from Eq 8; theta3, theta4
and theta5 from the wrist point and the tool axis expressed in frame 2
(the corrected Eq 14-28); theta6 from the remaining rotation about z6
(Eq 31-33). Every candidate is finished by Newton steps on the full 6x6
Jacobian and kept only if its forward-kinematics residual is within the
tolerances.

Frames and units: base frame 0 of Table II, metres and radians. The wrist
point is ``D = p + l5 z6`` (frame 6 sits at ``d6 = -l5`` along z6, Table II).
"""

from __future__ import annotations

import numpy as np

from ..arm import Arm
from ..kinematics import fk, jacobian
from ..rotations import rotation_angle
from .angles import wrap_angle as _wrap
from .compare import pose_residuals
from .elimination import EliminantCoefficients, eliminant_coefficients

__all__ = ["solve_arrays", "dedupe", "FREE_NONE", "FREE_Q1_Q6", "FREE_Q3_Q6", "MAX_SOLUTIONS",
           "POSITION_TOL", "ROTATION_TOL", "CONTINUUM_SIN"]

#: Upper bound on the number of distinct solutions (8 roots x 2 wrist branches).
MAX_SOLUTIONS = 16
#: Accept a solution only if |p_fk - p| <= POSITION_TOL [m] ...
POSITION_TOL = 1e-10
#: ... and the rotation angle between R_fk and R is <= ROTATION_TOL [rad].
ROTATION_TOL = 1e-10

#: Free-joint flags (bit set) for continua of solutions.
FREE_NONE = 0
#: theta1 and theta6 axes collinear (wrist point on the joint-1 axis, z6 vertical).
FREE_Q1_Q6 = 1
#: theta3 and theta6 axes collinear (theta4 = theta5 = 0 or pi: wrist stretched along the upper arm).
FREE_Q3_Q6 = 2

#: |sin theta4| and |sin(theta4 + theta5)| below this: theta3/theta6 continuum (a pose fixes
#: q only to ~sqrt(machine eps) there, so the threshold sits well above 1e-8).
FREE_TOL = 1e-7

#: |sin theta4| and |sin(theta4 + theta5)| of a final solution below this: flagged as a
#: theta3/theta6 continuum (sigma_min(J) < ~1e-10 there: the pose fixes theta3 to ~1e-3 rad).
CONTINUUM_SIN = 1e-5

_TWO_PI = 2.0 * np.pi
_N_REF = 12  # candidate reference angles for the t-substitution


def _norm(x):
    """Euclidean norm over the last axis; the same arithmetic as ``np.linalg.norm(x, axis=-1)``."""
    return np.sqrt(np.add.reduce(x * x, axis=-1))


# --------------------------------------------------------------------------- #
# First-degree trigonometric polynomials x0 + xc cos(th) + xs sin(th), as (..., 3)
# --------------------------------------------------------------------------- #

def _trig1(x, c, s):
    """x0 + xc cos + xs sin for coefficient rows x (..., 3)."""
    return x[..., 0] + x[..., 1] * c + x[..., 2] * s


def _F_cs(co: EliminantCoefficients, C, S):
    """F = a^2 (P^2+Q^2) - (bQ - cP)^2 from cos/sin of theta1 (broadcast to (n, m))."""
    X = co.abPQ[:, None]  # (n, 1, 4, 3)
    v = X[..., 0] + X[..., 1] * C[..., None] + X[..., 2] * S[..., None]
    a, b, P, Q = v[..., 0], v[..., 1], v[..., 2], v[..., 3]
    g = b * Q - co.c[:, None] * P
    return a * a * (P * P + Q * Q) - g * g


def _F_at(co, th):
    """F(theta1) = a^2 (P^2+Q^2) - (bQ - cP)^2 at angles th (n, m)."""
    return _F_cs(co, np.cos(th), np.sin(th))


def _quad_in_t(x, cr, sr):
    """Numerator of x0 + xc cos(th) + xs sin(th), th = th_r + phi, t = tan(phi/2).

    ``x`` (n, ..., 3), ``cr``/``sr`` broadcastable to ``x[..., 0]``. Returns ascending
    coefficients (n, ..., 3) of ``(1 + t^2) * x``.
    """
    x0 = x[..., 0]
    xc = x[..., 1] * cr + x[..., 2] * sr
    xs = -x[..., 1] * sr + x[..., 2] * cr
    out = np.empty(xc.shape + (3,))
    out[..., 0], out[..., 1], out[..., 2] = x0 + xc, 2 * xs, x0 - xc
    return out


def _pmul(a, b):
    """Batched product of ascending-coefficient polynomials (..., da) x (..., db) (same batch shape)."""
    da, db = a.shape[-1], b.shape[-1]
    out = np.zeros(a.shape[:-1] + (da + db - 1,))
    for i in range(da):
        out[..., i:i + db] += a[..., i:i + 1] * b
    return out


_GRID = np.arange(_N_REF) * (_TWO_PI / _N_REF)
_GRID_C, _GRID_S = np.cos(_GRID + np.pi), np.sin(_GRID + np.pi)
_ONE_T2 = np.array([1.0, 0.0, 1.0])
_DIAG8 = np.arange(8)
_SUB8 = (np.arange(1, 8), np.arange(7))  # companion-matrix subdiagonal


def _theta1_candidates(co, imag_tol: float = 1e-3):
    """All theta1 candidates (n, 8) [rad] (NaN where none) from the degree-8 polynomial."""
    n = co.a.shape[0]
    # Pick theta_r so that theta_r + pi (t = inf) is far from the roots:
    # the leading coefficient of the t-polynomial is F(theta_r + pi).
    Fg = np.abs(_F_cs(co, _GRID_C[None], _GRID_S[None]))
    th_r = _GRID[np.argmax(Fg, axis=1)]
    cr, sr = np.cos(th_r)[:, None], np.sin(th_r)[:, None]
    X = _quad_in_t(co.abPQ, cr, sr)  # (n, 4, 3): a, b, P, Q
    # five products at once: B Q, A A, P P, Q Q, (1 + t^2) P
    L = np.empty((n, 5, 3))
    L[:, :4] = X[:, [1, 0, 2, 3]]
    L[:, 4] = _ONE_T2
    BQ, A2, PP, QQ, P1 = _pmul(L, X[:, [3, 0, 2, 3, 2]]).transpose(1, 0, 2)
    G = BQ - co.c[:, None] * P1
    L2, R2 = np.empty((n, 2, 5)), np.empty((n, 2, 5))
    L2[:, 0], L2[:, 1], R2[:, 0], R2[:, 1] = A2, G, PP + QQ, G
    F2 = _pmul(L2, R2)
    F = F2[:, 0] - F2[:, 1]  # (n, 9) ascending
    lead = F[:, 8]
    scale = np.max(np.abs(F), axis=1)
    degenerate = scale <= 1e-300
    ok = (np.abs(lead) > 1e-14 * scale) & ~degenerate
    cand = np.full((n, 8), np.nan)
    imag = np.full((n, 8), np.nan)
    if ok.any():
        Fk = F[ok]
        comp = np.zeros((Fk.shape[0], 8, 8))
        comp[:, 0, :] = -Fk[:, 7::-1] / Fk[:, 8:9]
        comp[:, _SUB8[0], _SUB8[1]] = 1.0
        t = np.linalg.eigvals(comp)  # Companion-matrix eigenvalues: all 8 roots
        near_real = np.abs(t.imag) <= imag_tol * (1.0 + np.abs(t))
        th = th_r[ok, None] + 2.0 * np.arctan(t.real)
        cand[ok] = np.where(near_real, th, np.nan)
        imag[ok] = np.abs(t.imag) / (1.0 + np.abs(t))
    return cand, imag, th_r, ~ok & ~degenerate, degenerate


def _f_derivs(co, own, th, sigma, second: bool = True):
    """f_sigma = a N + sigma (b Q - c P) and its first two derivatives (flat arrays).

    With ``second=False`` the second derivative is not computed (returned as None).
    """
    C, S = np.cos(th)[:, None], np.sin(th)[:, None]
    x = co.abPQ[own]  # (m, 4, 3)
    v = x[..., 0] + x[..., 1] * C + x[..., 2] * S
    d1 = -x[..., 1] * S + x[..., 2] * C
    a, b, P, Q = v.T
    a1, b1, P1, Q1 = d1.T
    c = co.c[own]
    N = np.hypot(P, Q)
    Ns = np.where(N > 1e-150, N, 1.0)
    u = P * P1 + Q * Q1
    N1 = u / Ns
    g = b * Q - c * P
    g1 = b1 * Q + b * Q1 - c * P1
    f = a * N + sigma * g
    f1 = a1 * N + a * N1 + sigma * g1
    if not second:
        return f, f1, None
    d2 = x[..., 0] - v  # second derivative of a first-degree trig polynomial
    a2, b2, P2, Q2 = d2.T
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        N2 = (P1 * P1 + P * P2 + Q1 * Q1 + Q * Q2) / Ns - u * u / Ns**3
    N2 = np.where(np.isfinite(N2), N2, 0.0)
    g2 = b2 * Q + 2 * b1 * Q1 + b * Q2 - c * P2
    f2 = a2 * N + 2 * a1 * N1 + a * N2 + sigma * g2
    return f, f1, f2


def _newton(co, own, th, sigma, order: int, iters: int = 8):
    """Newton on f_sigma (order 0) or on its derivative (order 1, the extremum)."""
    th = th.copy()
    act = np.arange(len(th))  # rows still moving (per row, so batches match single calls)
    for _ in range(iters):
        if len(act) == 0:
            break
        d = _f_derivs(co, own[act], th[act], sigma[act], second=order > 0)
        num, den = d[order], d[order + 1]
        nz = den != 0
        step = np.clip(np.where(nz, num / np.where(nz, den, 1.0), 0.0), -0.05, 0.05)
        th[act] -= step
        act = act[np.abs(step) > 1e-15]
    return th


def _theta1_list(co, cand, imag, cluster_tol: float = 1e-3):
    """Flat theta1 candidates: (owner, theta1, sigma, priority).

    Every near-real eigenvalue gives a Newton-refined root of the unsquared
    f_sigma (sigma chosen where |f_sigma| is smaller). Suspicious roots (complex
    pairs, clusters within ``cluster_tol``) also get, for both signs, the
    extremum of f_sigma (the exact location of a double root, priority 0) and
    the two roots of the local quadratic model around it (priority 2).
    """
    valid = ~np.isnan(cand)
    own0, col = np.nonzero(valid)
    th0 = cand[own0, col]
    C, S = np.cos(th0)[:, None], np.sin(th0)[:, None]
    x = co.abPQ[own0]
    a, b, P, Q = (x[..., 0] + x[..., 1] * C + x[..., 2] * S).T
    aN, g = a * np.hypot(P, Q), b * Q - co.c[own0] * P
    s0 = np.where(np.abs(aN + g) <= np.abs(aN - g), 1.0, -1.0)  # |f_+| <= |f_-|
    thA = _newton(co, own0, th0, s0, 0)
    d = np.abs(cand[:, :, None] - cand[:, None, :])
    d = np.minimum(d, _TWO_PI - d)
    d[:, _DIAG8, _DIAG8] = np.inf
    crowded = np.where(np.isnan(d), np.inf, d).min(axis=2) <= cluster_tol
    susp = (imag[own0, col] > 1e-12) | crowded[own0, col]
    owns, ths, sigs, prios = [own0], [thA], [s0], [np.where(susp, 1.0, 1.5)]
    if susp.any():
        o, t = own0[susp], th0[susp]
        for sg in (1.0, -1.0):
            sv = np.full(len(o), sg)
            tA = _newton(co, o, t, sv, 0)
            tB = _newton(co, o, t, sv, 1)
            f, _f1, f2 = _f_derivs(co, o, tB, sv)
            with np.errstate(divide="ignore", invalid="ignore"):
                delta = np.sqrt(-2.0 * f / f2)
            pair = np.isfinite(delta) & (delta <= cluster_tol)
            op, sp = o[pair], sv[pair]
            tC = _newton(co, op, tB[pair] + delta[pair], sp, 0)
            tD = _newton(co, op, tB[pair] - delta[pair], sp, 0)
            owns += [o, o, op, op]
            ths += [tA, tB, tC, tD]
            sigs += [sv, sv, sv[pair], sv[pair]]
            prios += [np.ones(len(o)), np.zeros(len(o)), np.full(pair.sum(), 2.0),
                      np.full(pair.sum(), 2.0)]
    if len(owns) == 1:
        return own0, _wrap(thA), s0, prios[0]
    return (np.concatenate(owns), _wrap(np.concatenate(ths)), np.concatenate(sigs),
            np.concatenate(prios))


def _theta2_eq8(co, own, th1, sig):
    """theta2 from Eq 8 for the sign ``sig`` of each flat (own, th1), and N = |(P, Q)|."""
    C, S = np.cos(th1)[:, None], np.sin(th1)[:, None]
    x = co.abPQ[own][:, 2:]
    v = x[..., 0] + x[..., 1] * C + x[..., 2] * S
    P, Q = v[:, 0], v[:, 1]
    # Eq 9 corrected: tan(theta2) = -P / Q; sigma = -1 is the opposite direction
    t2 = np.where(sig > 0, np.arctan2(-P, Q), np.arctan2(P, -Q))
    return t2, np.hypot(P, Q)


def _theta2_eq11(co, own, th1):
    """The two theta2 roots of Eq 11 alone (m, 2), for rows where Eq 8 vanishes (P = Q = 0).

    Elsewhere they are spurious and removed by the FK check.
    """
    C, S = np.cos(th1), np.sin(th1)
    a = _trig1(co.a[own], C, S)
    b = _trig1(co.b[own], C, S)
    c = co.c[own]
    # Eq 11 alone: a + b c2 + c s2 = 0  ->  theta2 = atan2(c, b) +- acos(-a / |(b, c)|)
    r = np.sqrt(b * b + c * c)
    phi = np.arctan2(c, b)
    ratio = np.clip(-a / np.where(r > 0, r, 1.0), -1.0, 1.0)
    acs = np.arccos(ratio)
    return np.stack([phi + acs, phi - acs], axis=-1)


def _wrist(R, D, th1, th2, arm: Arm, free_tol: float):
    """theta3..theta5 for (theta1, theta2) (shape (n, m)); two branches -> (n, m, 2, 3)."""
    l1, l2, l3, l4, l5 = arm.lengths
    c1, s1, c2, s2 = np.cos(th1), np.sin(th1), np.cos(th2), np.sin(th2)
    # Rows of 2_0 R (Eq 18, rotation part): frame-2 axes in base coordinates.
    R2 = np.zeros(c1.shape + (3, 3))
    R2[..., 0, 0], R2[..., 0, 1], R2[..., 0, 2] = c1 * s2, s1 * s2, c2
    R2[..., 1, 0], R2[..., 1, 1], R2[..., 1, 2] = c1 * c2, s1 * c2, -s2
    R2[..., 2, 0], R2[..., 2, 1] = -s1, c1
    B = np.zeros(c1.shape + (3,))
    B[..., 0], B[..., 1] = l2 * c1, l2 * s1
    w = D[:, None, :] - B  # D - B
    z = R[:, None, :, 2]
    d2 = np.sum(R2 * w[..., None, :], axis=-1)  # D in frame 2
    z2 = np.sum(R2 * z[..., None, :], axis=-1)  # z6 in frame 2
    dx, dy, dz, zx, zy, zz = d2[..., 0], d2[..., 1], d2[..., 2], z2[..., 0], z2[..., 1], z2[..., 2]
    # Eq 18 last column: D_2 = (l4 c3 s4, l3 + l4 c4, -l4 s3 s4); Eq 25/26: z6_2 = (-c3 s45, -c45, s3 s45)
    hp = np.empty(dx.shape + (2,))
    hp[..., 0], hp[..., 1] = -dz, dx
    hp /= l4  # = s4 (s3, c3)
    ho = np.empty(dx.shape + (2,))
    ho[..., 0], ho[..., 1] = zz, -zx  # = s45 (s3, c3)
    npos = _norm(hp)
    nori = _norm(ho)
    h = np.where((npos >= nori)[..., None], hp, ho)
    free = np.maximum(npos, nori) <= free_tol
    h = np.where(free[..., None], np.array([0.0, 1.0]), h)  # representative theta3 = 0
    th3a = np.arctan2(h[..., 0], h[..., 1])
    th3 = np.empty(th3a.shape + (2,))
    th3[..., 0], th3[..., 1] = th3a, _wrap(th3a + np.pi)  # the two wrist branches
    c3, s3 = np.cos(th3), np.sin(th3)
    s4 = (c3 * dx[..., None] - s3 * dz[..., None]) / l4
    c4 = np.broadcast_to(((dy - l3) / l4)[..., None], s4.shape)
    th4 = np.arctan2(s4, c4)  # Eq 16
    s45 = -c3 * zx[..., None] + s3 * zz[..., None]  # Eq 25 and its (3,3) companion
    c45 = np.broadcast_to(-zy[..., None], s45.shape)  # Eq 26
    th5 = _wrap(np.arctan2(s45, c45) - th4)  # Eq 28
    out = np.empty(th3.shape + (3,))
    out[..., 0], out[..., 1], out[..., 2] = th3, th4, th5
    return out, free


def _pose_error(q, T, arm: Arm):
    Tq = fk(q, arm)
    ep = T[:, :3, 3] - Tq[:, :3, 3]
    Re = T[:, :3, :3] @ np.swapaxes(Tq[:, :3, :3], 1, 2)
    er = 0.5 * np.stack([Re[:, 2, 1] - Re[:, 1, 2], Re[:, 0, 2] - Re[:, 2, 0],
                         Re[:, 1, 0] - Re[:, 0, 1]], axis=1)
    return np.concatenate([ep, er], axis=1)


def _solve6(J, e):
    """Solve J dq = e for a stack of 6x6 systems; pseudo-inverse where J is (near) singular."""
    det = np.abs(np.linalg.det(J))
    ok = det > 1e-12
    dq = np.empty_like(e)
    if ok.any():
        dq[ok] = np.linalg.solve(J[ok], e[ok, :, None])[..., 0]
    if not ok.all():
        dq[~ok] = np.einsum("nij,nj->ni", np.linalg.pinv(J[~ok], rcond=1e-13), e[~ok])
    return dq


def _snap_continuum(q, T, arm: Arm, iters: int = 6):
    """Continuum representatives with theta4, theta4 + theta5 snapped to exact multiples of pi.

    theta3 is kept; theta1, theta2 and theta6 are re-fitted by Gauss-Newton on
    the 6x3 Jacobian columns (the pose is consistent on the continuum).
    """
    q = q.copy()
    s4 = np.round(q[:, 3] / np.pi) * np.pi
    s45 = np.round((q[:, 3] + q[:, 4]) / np.pi) * np.pi
    q[:, 3], q[:, 4] = s4, s45 - s4
    cols = [0, 1, 5]
    for _ in range(iters):
        e = _pose_error(q, T, arm)
        J = jacobian(q, arm)[:, :, cols]
        dq = np.einsum("nij,nj->ni", np.linalg.pinv(J, rcond=1e-12), e)
        q[:, cols] += dq
    return _wrap(q)


def _newton_polish(q, T, arm: Arm, iters: int = 12, step_tol: float = 1e-14):
    """Newton steps on the full 6x6 Jacobian towards poses T (q (m, 6), T (m, 4, 4)).

    At least one step for every row; rows stop once their step is below ``step_tol``.
    Singular Jacobians are handled by the pseudo-inverse.
    """
    q = q.copy()
    active = np.arange(len(q))
    for _ in range(iters):
        if len(active) == 0:
            break
        qa = q[active]
        e = _pose_error(qa, T[active], arm)
        J = jacobian(qa, arm)
        dq = _solve6(J, e)
        q[active] = qa + dq
        active = active[np.max(np.abs(dq), axis=1) > step_tol]
    return q


def _residuals_theta6(T0, th6, T):
    """:func:`pose_residuals` of q from ``T0 = fk(q with theta6 = 0)`` without a second FK.

    The tool point does not move with theta6 and ``R(q) = R0 Rz(theta6)``; written
    as below, every entry is bit-for-bit the Eq 4 expression :func:`fk` evaluates.
    """
    c6, s6 = np.cos(th6)[:, None], np.sin(th6)[:, None]
    R0 = T0[:, :3, :3]
    R = np.empty_like(R0)
    R[:, :, 0] = c6 * R0[:, :, 0] + s6 * R0[:, :, 1]
    R[:, :, 1] = -s6 * R0[:, :, 0] + c6 * R0[:, :, 1]
    R[:, :, 2] = R0[:, :, 2]
    return (_norm(T0[:, :3, 3] - T[:, :3, 3]),
            rotation_angle(R, T[:, :3, :3]))


def solve_arrays(T: np.ndarray, arm: Arm, *, tol_p: float = POSITION_TOL,
                 tol_r: float = ROTATION_TOL):
    """All IK solutions of a batch of poses, as padded arrays (the vectorised core).

    Args:
        T: Validated poses (n, 4, 4) [m], base frame 0.
        arm: Arm parameters.

    Returns:
        ``(q, valid, free, pres, rres)``: ``q`` (n, 16, 6) [rad], wrapped to
        (-pi, pi] and sorted (valid rows first, lexicographic); ``valid`` (n, 16)
        bool; ``free`` (n, 16) int flags (:data:`FREE_Q1_Q6`, :data:`FREE_Q3_Q6`);
        ``pres`` (n, 16) [m] and ``rres`` (n, 16) [rad] FK residuals.
    """
    n = T.shape[0]
    R, p = T[:, :3, :3], T[:, :3, 3]
    co = eliminant_coefficients(R, p, arm)
    cand, imag, _thr, _lowdeg, degenerate = _theta1_candidates(co)
    own, t1, sig, prio = _theta1_list(co, cand, imag)
    careful = prio != 1.5  # from a suspicious (clustered / complex) root: always polish
    prio = np.where(careful, prio, 1.0)
    fr1 = np.zeros(len(own), dtype=bool)
    if degenerate.any():
        # F identically zero: theta1 is free (continuum); representatives 0 and pi.
        dg = np.flatnonzero(degenerate)
        own = np.concatenate([own, dg, dg])
        t1 = np.concatenate([t1, np.zeros(len(dg)), np.full(len(dg), np.pi)])
        sig = np.concatenate([sig, np.ones(2 * len(dg))])
        prio = np.concatenate([prio, np.ones(2 * len(dg))])
        careful = np.concatenate([careful, np.ones(2 * len(dg), dtype=bool)])
        fr1 = np.concatenate([fr1, np.ones(2 * len(dg), dtype=bool)])
    t2, N = _theta2_eq8(co, own, t1, sig)
    # Where Eq 8 vanishes identically (P = Q = 0) theta2 comes from Eq 11 alone.
    scale = _norm(co.D)[own] + arm.l2 + arm.l3
    weak = (N <= 1e-6 * scale) | fr1
    if weak.any():
        opts = _theta2_eq11(co, own[weak], t1[weak])
        own = np.concatenate([own, own[weak], own[weak]])
        t1 = np.concatenate([t1, t1[weak], t1[weak]])
        t2 = np.concatenate([t2, opts[:, 0], opts[:, 1]])
        prio = np.concatenate([prio, prio[weak], prio[weak]])
        careful = np.concatenate([careful | weak, np.ones(2 * int(weak.sum()), dtype=bool)])
        fr1 = np.concatenate([fr1, fr1[weak], fr1[weak]])
    wr, free3 = _wrist(R[own], co.D[own], t1[:, None], t2[:, None], arm, FREE_TOL)
    k = len(t1)
    q = np.empty((k, 2, 6))
    q[..., 0] = t1[:, None]
    q[..., 1] = _wrap(t2)[:, None]
    q[..., 2:5] = wr[:, 0]
    q[..., 5] = 0.0
    flf = np.repeat(fr1 * FREE_Q1_Q6 + free3[:, 0] * FREE_Q3_Q6, 2)
    # On a theta3/theta6 continuum both wrist branches are the same continuum: keep one.
    keep_branch = np.ones((k, 2), dtype=bool)
    keep_branch[:, 1] = ~free3[:, 0]
    qf = q.reshape(-1, 6)[keep_branch.reshape(-1)]
    flf = flf[keep_branch.reshape(-1)]
    owner = np.repeat(own, 2)[keep_branch.reshape(-1)]
    prio = np.repeat(prio, 2)[keep_branch.reshape(-1)]
    careful = np.repeat(careful, 2)[keep_branch.reshape(-1)]
    Tq = fk(qf, arm)
    Tt = T[owner]
    near = _norm(Tq[:, :3, 3] - Tt[:, :3, 3]) <= 1e-3
    qf, flf, owner, Tt, prio, careful, Tq = (x[near] for x in (qf, flf, owner, Tt, prio, careful, Tq))
    # theta6: R_fk(theta6 = 0)^T R = Rz(theta6) (Eq 31-33 equivalently)
    M = np.einsum("nji,njk->nik", Tq[:, :3, :3], Tt[:, :3, :3])
    qf[:, 5] = np.arctan2(M[:, 1, 0], M[:, 0, 0])
    pres, rres = _residuals_theta6(Tq, qf[:, 5], Tt)
    polish = (pres <= 1e-3) & (rres <= 1e-2) & (careful | (pres > 1e-14) | (rres > 1e-14))
    if polish.any():
        qf[polish] = _newton_polish(qf[polish], Tt[polish], arm)
        pres[polish], rres[polish] = pose_residuals(qf[polish], Tt[polish], arm)
    qf = _wrap(qf)
    # Continuum flags from the final q.
    s4, s45 = np.abs(np.sin(qf[:, 3])), np.abs(np.sin(qf[:, 3] + qf[:, 4]))
    flf = np.where((s4 <= CONTINUUM_SIN) & (s45 <= CONTINUUM_SIN), flf | FREE_Q3_Q6, flf & ~FREE_Q3_Q6)
    c36 = (flf & FREE_Q3_Q6) > 0
    if c36.any():
        qs = _snap_continuum(qf[c36], Tt[c36], arm)
        ps, rs = pose_residuals(qs, Tt[c36], arm)
        better = (ps <= tol_p) & (rs <= tol_r)
        idx = np.flatnonzero(c36)[better]
        qf[idx], pres[idx], rres[idx] = qs[better], ps[better], rs[better]
    keep = (pres <= tol_p) & (rres <= tol_r)
    qf, flf, owner, pres, rres, prio = (x[keep] for x in (qf, flf, owner, pres, rres, prio))
    return dedupe(n, qf, flf, owner, pres, rres, prio=prio, T=T, arm=arm,
                   near=1e-4 if tol_p <= POSITION_TOL else 0.0)


def _connected(qa, qb, T, arm: Arm, tol_p: float = POSITION_TOL, tol_r: float = ROTATION_TOL):
    """Does the joint-space segment qa -> qb stay within the FK tolerance of T (3 interior points)?"""
    d = _wrap(qb - qa)
    ok = np.ones(len(qa), dtype=bool)
    for s in (0.25, 0.5, 0.75):
        pr, rr = pose_residuals(qa + s * d, T, arm)
        ok &= (pr <= tol_p) & (rr <= tol_r)
    return ok


def _canonical_order(qf, owner):
    """Order of rows by (owner, round(q, 9) lexicographically): the deterministic order.

    Same permutation as ``np.lexsort`` on the seven keys (``np.round(x, 9)`` is
    ``rint(x 1e9) / 1e9``, so the integers ``rint(x 1e9)`` order and tie alike), but
    sorts (owner, theta1) packed in one int64 plus theta2, theta3 first and falls back
    to all keys only if rows still tie.
    """
    key = np.rint(qf * 1e9).astype(np.int64)  # |q| <= pi: |key| < 2**32
    head = owner.astype(np.int64) * (1 << 33) + (key[:, 0] + (1 << 32))
    order = np.lexsort((key[:, 2], key[:, 1], head))
    k = key[order]
    h = head[order]
    tie = (h[1:] == h[:-1]) & np.all(k[1:, 1:3] == k[:-1, 1:3], axis=1)
    if tie.any():  # sort each run of tied rows by theta4..theta6 (stable, in place)
        member = np.zeros(len(order), dtype=bool)
        member[1:] |= tie
        member[:-1] |= tie
        gid = np.cumsum(np.concatenate([[True], ~tie]))
        idx = np.flatnonzero(member)
        ks = k[idx]
        order[idx] = order[idx][np.lexsort((ks[:, 5], ks[:, 4], ks[:, 3], gid[idx]))]
    return order


def dedupe(n, qf, flf, owner, pres, rres, tol: float = 1e-7, prio=None, T=None, arm=None,
            near: float = 1e-4):
    """Distinct solutions per pose, sorted lexicographically; padded to MAX_SOLUTIONS.

    Two solutions are the same if every wrapped joint difference is <= ``tol`` rad;
    Near a singularity a pose fixes q only to ~sqrt(machine eps); rows within
    ``near`` rad whose connecting segment stays inside 1/100 of the FK
    tolerance of ``T`` are the same solution too. Of a group of duplicates the one with the lowest
    ``prio`` (then the first in lexicographic order) is kept.
    """
    if prio is None:
        prio = np.zeros(len(qf))
    out_q = np.zeros((n, MAX_SOLUTIONS, 6))
    out_v = np.zeros((n, MAX_SOLUTIONS), dtype=bool)
    out_f = np.zeros((n, MAX_SOLUTIONS), dtype=int)
    out_p = np.full((n, MAX_SOLUTIONS), np.nan)
    out_r = np.full((n, MAX_SOLUTIONS), np.nan)
    if len(qf) == 0:
        return out_q, out_v, out_f, out_p, out_r
    order = _canonical_order(qf, owner)
    qf, flf, owner, pres, rres, prio = (x[order] for x in (qf, flf, owner, pres, rres, prio))
    starts = np.searchsorted(owner, np.arange(n))
    rank = np.arange(len(owner)) - starts[owner]
    K = int(rank.max()) + 1
    # Duplicates share theta1; compare each row with the following rows in theta1
    # order while they are within `near` (theta1 near -pi is compared as theta1 + 2 pi).
    t1 = np.where(qf[:, 0] < -np.pi + 1e-6, qf[:, 0] + _TWO_PI, qf[:, 0])
    o2 = np.lexsort((t1, owner))
    dup_flat = np.zeros(len(qf), dtype=bool)
    # pos: positions i in o2 whose pair (i, i + sft) may still be a candidate. Sorted by
    # (owner, theta1), a pair that fails at shift sft fails at every larger shift, so
    # each row is only carried while it has a near neighbour (linear, not N x K).
    pos = np.arange(len(o2))
    for sft in range(1, K):
        pos = pos[pos + sft < len(o2)]
        a, b = o2[pos], o2[pos + sft]
        cand = (owner[a] == owner[b]) & (np.abs(t1[a] - t1[b]) <= max(near, tol))
        if not cand.any():
            break  # sorted by theta1: larger shifts are farther apart
        pos = pos[cand]
        a, b = a[cand], b[cand]
        d = np.abs(qf[a] - qf[b])
        dmax = np.max(np.minimum(d, _TWO_PI - d), axis=1)
        same = dmax <= tol
        # two representatives of one theta3/theta6 continuum
        c36 = ((flf[a] & flf[b] & FREE_Q3_Q6) > 0) & (dmax <= np.pi)
        if c36.any():
            dfix = np.abs(_wrap(qf[a][:, [0, 1, 3, 4]] - qf[b][:, [0, 1, 3, 4]]))
            same |= c36 & (np.max(dfix, axis=1) <= 1e-6)
        maybe = ~same & (dmax <= near)
        if T is not None and maybe.any():
            same[maybe] = _connected(qf[a[maybe]], qf[b[maybe]], T[owner[a[maybe]]], arm,
                                     1e-2 * POSITION_TOL, 1e-2 * ROTATION_TOL)
        a, b = a[same], b[same]
        # of a duplicate pair drop the higher priority value, ties: the later row
        drop_b = prio[b] > prio[a]
        drop_b |= (prio[b] == prio[a]) & (b > a)
        dup_flat[np.where(drop_b, b, a)] = True
    present = np.zeros((n, K), dtype=bool)
    present[owner, rank] = True
    dup = np.zeros((n, K), dtype=bool)
    dup[owner, rank] = dup_flat
    keep = present & ~dup
    slot = np.cumsum(keep, axis=1) - 1
    slot_r = slot[owner, rank]
    sel = keep[owner, rank] & (slot_r < MAX_SOLUTIONS)
    o, s = owner[sel], slot_r[sel]
    out_q[o, s], out_v[o, s], out_f[o, s] = qf[sel], True, flf[sel]
    out_p[o, s], out_r[o, s] = pres[sel], rres[sel]
    return out_q, out_v, out_f, out_p, out_r
