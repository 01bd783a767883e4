"""The thesis's Iterative Inverse Kinematics (IIK, Sec 3.3), as printed but with errata fixed.

Steps (vectorised over poses):

1. Wrist point ``D`` (Eq 9a-c, corrected sign ``D = p + l5 z6``; origin moved up by l1).
2. theta1 scan (Sec 3.3.1): a grid of theta1 values plus the Eq 12/13 points
   ``atan2(py, px)`` and ``atan2(py, px) +- pi``; for each, theta2 from Eq 9
   (corrected: ``tan(theta2) = -P / Q``, both signs) and the error of Eq 11.
   A sign change between neighbouring grid points is bisected down to
   ``tol_deg`` (the thesis's 1e-6 deg).
3. theta4 from Eq 14-16 (corrected ``+ yD s1``) with both signs of Eq 15.
4. theta3 from Eq 20-22 with both signs of Eq 21: the "four configurations
   per theta1 root" of Sec 3.3.3.
5. theta5 from Eq 26-28 (Eq 27 divides by -c3 as printed: singular at theta3 = +-90 deg).
6. theta6 from Eq 31-33.
7. Keep the configurations whose Eq 4 pose matches (Sec 3.3.5 does this check).

What the grid cannot see (two roots in one cell, tangent roots) is lost;
:mod:`iik.ik.kernel` and :mod:`iik.ik.reference` have no such gap. Units: m, rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..arm import Arm
from . import layout as L
from .angles import wrap_angle as _wrap
from .compare import pose_residuals
from .thesis_eliminant import EliminantCoefficients, eliminant_coefficients

__all__ = ["solve_thesis_arrays", "thesis_candidates", "ThesisCandidates", "eq11_error",
           "DEFAULT_GRID", "THESIS_TOL_DEG", "ACCEPT_TOL"]

#: Number of theta1 grid cells over the full turn (5 deg spacing).
DEFAULT_GRID = 72
#: Sec 4.2.1: "a similar tolerance of convergence was used (1e-6 degrees)".
THESIS_TOL_DEG = 1e-6
#: A configuration "satisfies Eq 4" if its pose error is below this [m] and [rad].
ACCEPT_TOL = 1e-6


def _trig1(x, c, s):
    """x0 + xc cos + xs sin for coefficient rows x (..., 3)."""
    return x[..., 0] + x[..., 1] * c + x[..., 2] * s


def eq11_error(co: EliminantCoefficients, th1: np.ndarray, s: float):
    """theta2 (Eq 9 corrected, sign s) and the Eq 11 error E [m^2] at theta1 values th1 (n, m)."""
    C, S = np.cos(th1), np.sin(th1)
    P = _trig1(co.P[:, None], C, S)
    Q = _trig1(co.Q[:, None], C, S)
    th2 = np.arctan2(-s * P, s * Q)  # Eq 9 (corrected numerator sign)
    a = _trig1(co.a[:, None], C, S)
    b = _trig1(co.b[:, None], C, S)
    E = a + b * np.cos(th2) + co.c[:, None] * np.sin(th2)  # Eq 11
    return th2, E


def _E_flat(co: EliminantCoefficients, idx, th1, s):
    C, S = np.cos(th1), np.sin(th1)
    P = _trig1(co.P[idx], C, S)
    Q = _trig1(co.Q[idx], C, S)
    th2 = np.arctan2(-s * P, s * Q)  # Eq 9 (corrected)
    a = _trig1(co.a[idx], C, S)
    b = _trig1(co.b[idx], C, S)
    return th2, a + b * np.cos(th2) + co.c[idx] * np.sin(th2)  # Eq 11


@dataclass(frozen=True)
class ThesisCandidates:
    """Every configuration Sec 3.3 tries, flat over all poses.

    Attributes:
        owner: (m,) pose index of each configuration.
        root: (m,) global index of its theta1 root (4 configurations per root, Sec 3.3.3).
        q: (m, 6) joint angles [rad].
        position_residual, rotation_residual: (m,) FK residuals [m], [rad].
        ok: (m,) satisfies Eq 4 within ``accept_tol`` (m and rad).
        n_roots: (n,) theta1 roots per pose.
        sigma: (m,) sign of Eq 9 used.
    """

    owner: np.ndarray
    root: np.ndarray
    q: np.ndarray
    position_residual: np.ndarray
    rotation_residual: np.ndarray
    ok: np.ndarray
    n_roots: np.ndarray
    sigma: np.ndarray


def _theta1_brackets(co: EliminantCoefficients, p: np.ndarray, n_grid: int):
    """Sec 3.3.1: the grid of theta1 [rad] plus the Eq 12/13 points, and every cell where the
    Eq 11 error changes sign for either sign of Eq 9: (pose index, lo, hi, sign) per cell."""
    n = p.shape[0]
    base = -np.pi + np.arange(n_grid) * (2 * np.pi / n_grid)
    phi = np.arctan2(p[:, 1], p[:, 0])  # Eq 12
    extra = np.stack([phi, _wrap(phi + np.pi)], axis=1)  # Eq 13 (+-pi are the same angle)
    grid = np.sort(np.concatenate([np.broadcast_to(base, (n, n_grid)), extra], axis=1), axis=1)
    grid = np.concatenate([grid, grid[:, :1] + 2 * np.pi], axis=1)  # close the circle
    owners, los, his, sig = [], [], [], []
    for s in (1.0, -1.0):
        _th2, E = eq11_error(co, grid, s)
        change = (E[:, :-1] * E[:, 1:] <= 0) & (grid[:, 1:] > grid[:, :-1])
        i, j = np.nonzero(change)
        owners.append(i)
        los.append(grid[i, j])
        his.append(grid[i, j + 1])
        sig.append(np.full(len(i), s))
    return tuple(np.concatenate(x) for x in (owners, los, his, sig))


def _bisect(co: EliminantCoefficients, own, lo, hi, s, tol: float):
    """Each sign-change cell [lo, hi] [rad] bisected down to ``tol`` [rad] (Sec 4.2.1):
    (theta1, theta2) at its midpoint [rad]."""
    _, Elo = _E_flat(co, own, lo, s)
    while len(lo) and np.max(hi - lo) > tol:
        mid = 0.5 * (lo + hi)
        _, Em = _E_flat(co, own, mid, s)
        left = Elo * Em <= 0
        hi = np.where(left, mid, hi)
        lo = np.where(left, lo, mid)
        Elo = np.where(left, Elo, Em)
    th1 = _wrap(0.5 * (lo + hi))
    th2, _ = _E_flat(co, own, th1, s)
    return th1, th2


def _four_configurations(R, D, th1, th2, arm: Arm) -> np.ndarray:
    """Sec 3.3.3: the four configurations (4 m, 6) [rad] of each root (theta1, theta2) (m,), in
    blocks [(+,+), (+,-), (-,+), (-,-)] of the signs of Eq 15 and Eq 21; R (m, 3, 3) the pose's
    rotation, D (m, 3) its wrist point [m] (Eq 9a-c)."""
    l1, l2, l3, l4, l5 = arm.lengths  # (an arm of the thesis's Table II form)
    xD, yD = D[:, 0], D[:, 1]
    c1, s1, c2, s2 = np.cos(th1), np.sin(th1), np.cos(th2), np.sin(th2)
    c4 = (np.sum(D**2, axis=1) + l2**2 - l3**2 - l4**2
          - 2 * l2 * (xD * c1 + yD * s1)) / (2 * l3 * l4)  # Eq 14 (corrected: + yD s1)
    c4 = np.clip(c4, -1.0, 1.0)
    z = R[:, :, 2]
    qs = []
    for sg4 in (1.0, -1.0):
        s4 = sg4 * np.sqrt(1.0 - c4**2)  # Eq 15
        th4 = np.arctan2(s4, c4)  # Eq 16
        with np.errstate(divide="ignore", invalid="ignore"):
            s3 = (s1 * xD - c1 * yD) / (l4 * s4)  # Eq 20
        s3 = np.clip(np.nan_to_num(s3), -1.0, 1.0)
        for sg3 in (1.0, -1.0):
            c3 = sg3 * np.sqrt(1.0 - s3**2)  # Eq 21
            th3 = np.arctan2(s3, c3)  # Eq 22
            with np.errstate(divide="ignore", invalid="ignore"):
                s45 = (z[:, 0] * c1 * s2 + z[:, 1] * s1 * s2 + z[:, 2] * c2) / (-c3)  # Eq 27
            s45 = np.nan_to_num(s45)
            c45 = -(z[:, 0] * c1 * c2 + z[:, 1] * s1 * c2 - z[:, 2] * s2)  # Eq 26
            th5 = _wrap(np.arctan2(s45, c45) - th4)  # Eq 28
            u = s1 * c3 - c1 * s2 * s3  # row 3 of 5_0 T (Eq 30)
            v = -(c1 * c3 + s1 * s2 * s3)
            w = -c2 * s3
            s6 = -(R[:, 0, 0] * u + R[:, 1, 0] * v + R[:, 2, 0] * w)  # Eq 31
            c6 = -(R[:, 0, 1] * u + R[:, 1, 1] * v + R[:, 2, 1] * w)  # Eq 32
            th6 = np.arctan2(s6, c6)  # Eq 33
            qs.append(np.stack([th1, _wrap(th2), th3, th4, th5, th6], axis=1))
    return np.concatenate(qs)


def thesis_candidates(T: np.ndarray, arm: Arm, *, n_grid: int = DEFAULT_GRID,
                      tol_deg: float = THESIS_TOL_DEG, accept_tol: float = ACCEPT_TOL) -> ThesisCandidates:
    """Run Sec 3.3 on validated poses ``T`` (n, 4, 4); every configuration it tries."""
    co = eliminant_coefficients(T[:, :3, :3], T[:, :3, 3], arm)
    own, lo, hi, s = _theta1_brackets(co, T[:, :3, 3], n_grid)
    th1, th2 = _bisect(co, own, lo, hi, s, np.radians(tol_deg))
    q = _four_configurations(T[own, :3, :3], co.D[own], th1, th2, arm)
    owner = np.tile(own, 4)
    if len(q):
        pres, rres = pose_residuals(q, T[owner], arm)
    else:
        pres = rres = np.zeros(0)
    ok = (pres <= accept_tol) & (rres <= accept_tol)
    return ThesisCandidates(owner=owner, root=np.tile(np.arange(len(own)), 4), q=q, position_residual=pres,
                            rotation_residual=rres, ok=ok, n_roots=np.bincount(own, minlength=T.shape[0]),
                            sigma=np.tile(s, 4))


def solve_thesis_arrays(T: np.ndarray, arm: Arm, cut=None, **kw):
    """Sec 3.3 solutions in the padded-array format of :func:`iik.ik.reference.solve_arrays`:
    ``(Q, V, F, P, R)``, distinct to 1e-5 rad (the thesis's bisection resolution), sorted;
    ``cut`` (n,) bool, if given, set where more than MAX_SOLUTIONS were distinct."""
    d = thesis_candidates(T, arm, **kw)
    n, M = T.shape[0], L.MAX_SOLUTIONS
    Q, V, F = np.full((n, M, 6), np.nan), np.zeros((n, M), bool), np.zeros((n, M), int)
    P, R = np.full((n, M), np.nan), np.full((n, M), np.nan)
    q = _wrap(d.q)
    for i in range(n):
        kept = []
        for j in np.flatnonzero(d.ok & (d.owner == i)):
            if all(np.max(np.abs(_wrap(q[j] - q[k]))) > 1e-5 for k in kept):
                kept.append(j)
        if cut is not None:
            cut[i] = len(kept) > M
        kept = sorted(kept, key=lambda j: tuple(np.round(q[j], 9)))[:M]
        m = len(kept)
        Q[i, :m], V[i, :m] = q[kept], True
        P[i, :m], R[i, :m] = d.position_residual[kept], d.rotation_residual[kept]
    return Q, V, F, P, R
