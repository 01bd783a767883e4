"""The compiled kernel (Numba): forward kinematics, Jacobians and the complete IK.

Everything here is scalar code compiled with ``numba.njit``; the public functions live in
:mod:`iik.kinematics` and :mod:`iik.ik.solve`, which call this module (imported on first
use, so ``import iik`` does not load Numba). Units: metres and radians; frames as in
:mod:`iik.kinematics`.

The complete IK of one pose (:func:`solve_many`, a serial loop; :func:`solve_many_parallel`
on all cores):

1. The pose is checked (finite, bottom row, rotation orthonormal to ``orthonormal_tol``,
   det > 0) and its rotation replaced by the nearest rotation (polar factor).
2. theta2 is eliminated from Eq 8 and Eq 11 (:mod:`iik.ik.elimination`):
   ``F(theta1) = a^2 (P^2 + Q^2) - (b Q - c P)^2``, a trigonometric polynomial of degree 4,
   becomes with ``t = tan((theta1 - theta_r) / 2)`` a real polynomial ``p`` of degree 8
   (``theta_r`` of a 12-point grid with the largest |F(theta_r + pi)|: no root near t = inf).
3. **Root isolation** (:func:`_real_roots`). The real roots of p^(7), p^(6), ..., p' are found
   from the linear one up; consecutive roots of p^(k+1) bound intervals on which p^(k) is
   monotone, so each holds at most one root of p^(k), bracketed by a sign change and found
   by safeguarded Newton. Cauchy's bound B on the roots of p also bounds those of its
   derivatives (Gauss-Lucas), so [-B, B] holds them all. *Guarantee:* in exact arithmetic
   every real root of p is found, a root of odd multiplicity by its sign change and one of
   even multiplicity (a tangent root) as a critical point where p = 0. *Numerical limits:*
   p's coefficients carry rounding errors of ~1e-16 relative, so a root is only defined to
   ~eps^(1/m) for multiplicity m (1e-8 for a double root); where a value of a derivative is
   at rounding level its sign is unknown and the point is taken as a root of it; every
   critical point where |p| is below 1e-3 of the size of its terms becomes a candidate
   (kind 1: a tangent root, two roots closer than the arithmetic separates, or a pose just
   out of reach); a root nearer than ~1e-12 to another may come out as one candidate. Roots
   closer than 1e-5 rad and candidates of kind 1 are refined on the unsquared
   ``f_sigma = a N + sigma (b Q - c P)`` (its roots, its extremum, the roots of its local
   quadratic model), where a double root of F is a simple root of f_sigma' (full accuracy).
4. theta2 from Eq 8 (Eq 11 alone where P = Q = 0), theta3..theta5 by the corrected Eq 14-28
   (both wrist branches), theta6 from the remaining rotation (Eq 31-33).
5. Candidates that miss the tolerance by a little get Levenberg-Marquardt steps (Newton
   first) on the full FK before they are judged: within the tolerances (``position_tol``,
   ``rotation_tol``) a solution; within ``approximate_tol`` an approximate one (returned
   only if there is no solution); else dropped.
6. Continua: theta4 = theta4 + theta5 = 0 (mod pi) makes joints 3 and 6 collinear (theta3 -
   sign theta6 fixed), the tool point on the joint-1 axis with z6 vertical joints 1 and 6;
   the representative is moved inside the joint limits if any member is, and the feasible
   interval of the free joint is reported. Near such a continuum (|sin theta4|,
   |sin(theta4 + theta5)| <= 1e-4) the configurations within the tolerance form a thin
   family in which theta3 is loosely fixed: such rows are flagged as numerical continua.
7. Duplicates (1e-7 rad, one continuum, unfinished polish, or joined within the tolerance)
   are merged; rows sorted lexicographically; the joint-limit filter (LIMIT_TOL) applied.

**Compilation and cache.** Each entry point compiles on its first call (so a program that
only calls :func:`iik.fk` compiles only the FK) and is cached on disk: next to this file
when that folder is writable, else in the user cache folder (``~/.cache/numba``, or
``$NUMBA_CACHE_DIR`` when set), which is Numba's own fallback. The closed forms of
:mod:`iik.kinematics` and :mod:`iik.ik.elimination` are compiled into these entry points,
so the cache key covers those source files too (Numba alone keys a cache on the defining
file only and would keep a stale kernel after an edit of ``kinematics.py``).
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass

import numba
import numpy as np
from numba.core import caching as _nb_caching

from .. import kinematics as _kin
from ..arm import Arm
from . import elimination as _elim

__all__ = ["ArmData", "arm_data", "fk_many", "position_jacobian_many", "jacobian_many", "solve_many",
           "solve_many_parallel", "scratch", "work_counts", "STATS", "SOURCES"]

# ----------------------------------------------------------------------------- cache
#: Every source file whose code the kernel compiles (the cache key hashes them all).
SOURCES = (__file__, _kin.__file__, _elim.__file__)


def _digest() -> str:
    h = hashlib.sha256()
    for path in SOURCES:
        with open(path, "rb") as f:
            h.update(f.read())
    return h.hexdigest()


_DIGEST = _digest()


class _AllSourcesStamp:
    """Locator mixin: the cache is fresh only if every file of :data:`SOURCES` is unchanged."""

    def get_source_stamp(self):
        return super().get_source_stamp(), _DIGEST


class _UserProvidedLocator(_AllSourcesStamp, _nb_caching.UserProvidedCacheLocator):
    pass


class _InTreeLocator(_AllSourcesStamp, _nb_caching.InTreeCacheLocator):
    pass


class _UserWideLocator(_AllSourcesStamp, _nb_caching.UserWideCacheLocator):
    pass


class _CacheImpl(_nb_caching.CompileResultCacheImpl):
    # Numba's order: $NUMBA_CACHE_DIR, next to the source, then the user cache folder
    _locator_classes = [_UserProvidedLocator, _InTreeLocator, _UserWideLocator]


class _FunctionCache(_nb_caching.FunctionCache):
    _impl_class = _CacheImpl


def _entry(**options):
    """``numba.njit(**options)`` with the on-disk cache described in the module docstring.

    IEEE arithmetic (``error_model="numpy"``): x / 0 is inf or nan, never an exception. Under
    ``NUMBA_DISABLE_JIT=1`` (debugging) the plain Python function, uncached.
    """
    def wrap(fn):
        disp = numba.njit(error_model="numpy", **options)(fn)
        if numba.config.DISABLE_JIT:
            return disp
        disp._cache = _FunctionCache(disp.py_func)  # what njit(cache=True) does, with our key
        return disp
    return wrap


_inner = numba.njit(error_model="numpy")  # helpers: compiled into the entry points that call them

_terms = _inner(_kin.eq4_terms)
_position = _inner(_kin.eq4_position)
_wrist_axes = _inner(_kin.eq4_wrist_axes)
_rotation = _inner(_kin.eq4_rotation)
_app_c = _inner(_kin.app_c_position_jacobian)
_eq8_eq11 = _inner(_elim.eq8_eq11_terms)


# ----------------------------------------------------------------------------- arm data
@dataclass(frozen=True)
class ArmData:
    """An :class:`~iik.arm.Arm` as read-only float arrays for the kernel.

    Attributes:
        lengths: ``[l1, l2, l3, l4, l5]`` [m].
        dh: Table II rows ``[alpha, a, d, offset]`` (6, 4) (modified DH) [rad, m].
        lower, upper: Joint limits (6,) [rad] (Table I).
        vector: ``[lengths, lower, upper, dh.ravel(), reach bound]`` (42,), the IK kernel's
            argument (the reach bound of :func:`iik.kinematics.reach_bound` at :data:`REACH`).
    """

    lengths: np.ndarray
    dh: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    vector: np.ndarray


#: Index in :attr:`ArmData.vector` of :func:`iik.kinematics.reach_bound` [m].
REACH = 41
_ARM_DATA: dict[int, tuple[Arm, ArmData]] = {}


def _ro(a) -> np.ndarray:
    a = np.ascontiguousarray(a, dtype=np.float64).copy()
    a.setflags(write=False)
    return a


def arm_data(arm: Arm) -> ArmData:
    """The kernel's view of ``arm`` (built once per arm object)."""
    hit = _ARM_DATA.get(id(arm))
    if hit is not None and hit[0] is arm:
        return hit[1]
    table = arm.dh_table()
    dh = [[r.alpha, r.a, r.d, r.offset] for r in table.rows]
    vec = np.concatenate([arm.lengths, arm.q_min, arm.q_max, np.ravel(dh), [_kin.reach_bound(arm)]])
    data = ArmData(_ro(arm.lengths), _ro(dh), _ro(arm.q_min), _ro(arm.q_max), _ro(vec))
    if len(_ARM_DATA) > 64:
        _ARM_DATA.clear()
    _ARM_DATA[id(arm)] = (arm, data)
    return data


# ----------------------------------------------------------------------------- FK, Jacobians
@_inner
def _finite6(q) -> bool:
    for j in range(6):
        if not math.isfinite(q[j]):
            return False
    return True


@_inner
def _eq4_common(q, L):
    """The cosines and sines of joints 1-4 and of theta4 + theta5, and Eq 4's recurring terms
    A, B, W, V (:func:`iik.kinematics.eq4_terms`), of one q: what FK and the Jacobians share."""
    c1, s1 = math.cos(q[0]), math.sin(q[0])
    c2, s2 = math.cos(q[1]), math.sin(q[1])
    c3, s3 = math.cos(q[2]), math.sin(q[2])
    c4, s4 = math.cos(q[3]), math.sin(q[3])
    c45, s45 = math.cos(q[3] + q[4]), math.sin(q[3] + q[4])
    A, B, W, V = _terms(c1, s1, c2, s2, c3, s3, c4, s4, c45, s45, L[3], L[4])
    return c1, s1, c2, s2, c3, s3, c4, s4, c45, s45, A, B, W, V


@_inner
def _fk_into(q, L, T) -> None:
    """Eq 4 for one q into T (4, 4)."""
    c1, s1, c2, s2, c3, s3, c4, s4, c45, s45, A, B, W, V = _eq4_common(q, L)
    c6, s6 = math.cos(q[5]), math.sin(q[5])
    X1, X2, X3, Y1, Y2, Y3, Z1, Z2, Z3 = _wrist_axes(c1, s1, c2, s2, c3, s3, c45, s45, A, B)
    r11, r21, r31, r12, r22, r32 = _rotation(c6, s6, X1, X2, X3, Y1, Y2, Y3)
    px, py, pz = _position(c1, s1, c2, s2, c3, A, B, W, V, L[0], L[1], L[2])
    T[0, 0], T[0, 1], T[0, 2], T[0, 3] = r11, r12, Z1, px
    T[1, 0], T[1, 1], T[1, 2], T[1, 3] = r21, r22, Z2, py
    T[2, 0], T[2, 1], T[2, 2], T[2, 3] = r31, r32, Z3, pz
    T[3, 0], T[3, 1], T[3, 2], T[3, 3] = 0.0, 0.0, 0.0, 1.0


@_inner
def _finite_rows(Q) -> bool:
    for i in range(Q.shape[0]):
        if not _finite6(Q[i]):
            return False
    return True


@_entry()
def fk_many(Q, L, T) -> bool:
    """Eq 4 of q (n, 6) into T (n, 4, 4); False (T untouched) if some q is not finite."""
    if not _finite_rows(Q):
        return False
    for i in range(Q.shape[0]):
        _fk_into(Q[i], L, T[i])
    return True


@_inner
def _position_jacobian_into(q, L, J) -> None:
    c1, s1, c2, s2, c3, s3, c4, s4, c45, s45, A, B, W, V = _eq4_common(q, L)
    e = _app_c(c1, s1, c2, s2, c3, s3, c4, s4, c45, s45, A, B, W, V, L[1], L[2], L[3], L[4])
    for k in range(15):
        J[k // 5, k % 5] = e[k]


@_entry()
def position_jacobian_many(Q, L, J) -> bool:
    """App. C of q (n, 6) into J (n, 3, 5); False if some q is not finite."""
    if not _finite_rows(Q):
        return False
    for i in range(Q.shape[0]):
        _position_jacobian_into(Q[i], L, J[i])
    return True


@_inner
def _jacobian_into(q, dh, J) -> None:
    """Geometric Jacobian (6, 6) at the tool point from the modified-DH chain of Table II."""
    r00, r01, r02, r10, r11, r12, r20, r21, r22 = 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0
    o0, o1, o2 = 0.0, 0.0, 0.0
    for i in range(6):
        ca, sa = math.cos(dh[i, 0]), math.sin(dh[i, 0])
        a, d = dh[i, 1], dh[i, 2]
        th = q[i] + dh[i, 3]
        ct, st = math.cos(th), math.sin(th)
        # link: RotX(alpha) TransX(a) RotZ(theta) TransZ(d)  (Craig, Table II)
        t0, t1, t2 = a, -sa * d, ca * d
        o0 += r00 * t0 + r01 * t1 + r02 * t2
        o1 += r10 * t0 + r11 * t1 + r12 * t2
        o2 += r20 * t0 + r21 * t1 + r22 * t2
        r00, r01, r02 = (r00 * ct + r01 * st * ca + r02 * st * sa,
                         -r00 * st + r01 * ct * ca + r02 * ct * sa, -r01 * sa + r02 * ca)
        r10, r11, r12 = (r10 * ct + r11 * st * ca + r12 * st * sa,
                         -r10 * st + r11 * ct * ca + r12 * ct * sa, -r11 * sa + r12 * ca)
        r20, r21, r22 = (r20 * ct + r21 * st * ca + r22 * st * sa,
                         -r20 * st + r21 * ct * ca + r22 * ct * sa, -r21 * sa + r22 * ca)
        J[0, i], J[1, i], J[2, i] = o0, o1, o2  # joint origin, replaced below
        J[3, i], J[4, i], J[5, i] = r02, r12, r22  # joint axis z_i
    for i in range(6):
        dx, dy, dz = o0 - J[0, i], o1 - J[1, i], o2 - J[2, i]
        zx, zy, zz = J[3, i], J[4, i], J[5, i]
        J[0, i] = zy * dz - zz * dy
        J[1, i] = zz * dx - zx * dz
        J[2, i] = zx * dy - zy * dx


@_entry()
def jacobian_many(Q, dh, J) -> bool:
    """Geometric Jacobians of q (n, 6) into J (n, 6, 6); False if some q is not finite."""
    if not _finite_rows(Q):
        return False
    for i in range(Q.shape[0]):
        _jacobian_into(Q[i], dh, J[i])
    return True


# ============================================================================= complete IK
# Layout of the option vector ``opt`` passed by iik.ik.solve (see IKOptions).
OPT_POSITION_TOL, OPT_ROTATION_TOL, OPT_APPROX_TOL, OPT_ORTHONORMAL_TOL, OPT_LIMIT_TOL = 0, 1, 2, 3, 4
N_OPT = 5

# Pose status codes (validation inside the kernel; iik.ik.solve turns them into typed errors).
OK, NONFINITE, BOTTOM_ROW, NOT_ORTHONORMAL, REFLECTION = 0, 1, 2, 3, 4

#: Upper bound on the number of distinct solutions returned (8 roots x 2 wrist branches).
MAX_SOLUTIONS = 16
#: Free-joint kinds (bit set): theta1/theta6 and theta3/theta6 continua; 4: a numerical
#: theta3/theta6 continuum (|sin theta4|, |sin(theta4 + theta5)| <= CONTINUUM_SIN but not exactly
#: singular: the pose fixes theta3 only loosely; no continuum data).
FREE_Q1_Q6, FREE_Q3_Q6, NUMERICAL_Q3_Q6 = 1, 2, 4

# Columns of a row of ``info`` (float64): residuals against the pose as given, flags and
# the continuum data (sign and feasible interval of the free joint, for theta1 then theta3).
I_PRES, I_RRES, I_WITHIN, I_APPROX, I_FREE = 0, 1, 2, 3, 4
I_S1, I_LO1, I_HI1, I_S3, I_LO3, I_HI3 = 5, 6, 7, 8, 9, 10
N_INFO = 11

# Header of a solved pose (float64, N_HDR): status, measure, projection distance, number of
# exact solutions before the limit filter, rows returned, the least residuals seen, rows on a
# continuum, and whether the rows are approximate.
H_STATUS, H_MEASURE, H_PROJECTION, H_TOTAL, H_COUNT, H_BEST_P, H_BEST_R, H_FREE, H_APPROX = range(9)
N_HDR = 9

# Columns of the candidate table (internal): q, residuals against the projected pose,
# class (1 exact, 2 approximate), free kind, continuum data as in ``info``.
_C_PRES, _C_RRES, _C_CLASS, _C_FREE = 6, 7, 8, 9
_C_S1, _C_LO1, _C_HI1, _C_S3, _C_LO3, _C_HI3, _C_PRIO = 10, 11, 12, 13, 14, 15, 16
N_CAND = 17
_MAX_T1 = 64  # theta1 candidates per pose
MAX_CAND = 192  # configurations per pose (x 2 theta2 options x 2 wrist branches)
_MAX_RST = 8  # restart sweeps per pose (one per valley)


def _layout(*sizes):
    """Offsets of consecutive regions of the given sizes, and the total."""
    out, o = [], 0
    for n in sizes:
        out.append(o)
        o += n
    return (*out, o)


# Scratch layout (one float64 buffer per serial loop, carved into views; no allocation per pose):
# coefficients, theta1 candidates and their kinds, q, theta2 options, a second q, p, roots and
# kinds of p, derivative roots, quadratics, products, Newton / LM vectors, work counters, a
# reordering buffer, restart sweeps (count and (theta1, theta2) pairs)
(_W_CO, _W_TH1, _W_CAREFUL, _W_Q, _W_TH2, _W_Q2, _W_P, _W_ROOTS, _W_KINDS, _W_CRIT, _W_NEW, _W_QUAD,
 _W_PROD, _W_E, _W_DQ, _W_G, _W_ET, _W_QT, _W_STATS, _W_TMP, _W_RST, N_WORK) = _layout(
    16, _MAX_T1, _MAX_T1, 6, 4, 6, 9, 16, 16, 10, 10, 12, 15, 6, 6, 6, 6, 6, 8, 2 * _MAX_T1, 1 + 2 * _MAX_RST)
#: Work counters (cumulative, in the scratch buffer; :func:`work_counts`): what a profile reads.
STATS = ("poses", "theta1 candidates", "configurations", "polishes", "polish iterations",
         "polish FK evaluations", "polish Jacobians", "continuum restarts")
# matrix scratch (N_MATS, 9, 9): projected rotation, a pose, a Jacobian, normal equations, derivatives
_M_RU, _M_T4, _M_J, _M_A, _M_D = 0, 1, 2, 3, 4
N_MATS = 5
#: Size of the scratch buffer of :func:`solve_many`.
N_SCRATCH = N_WORK + N_MATS * 81 + MAX_CAND * N_CAND + MAX_CAND


_TWO_PI = 2.0 * math.pi
_SQRT8 = math.sqrt(8.0)
_EPS = 2.220446049250313e-16
_GRID = np.arange(12) * (_TWO_PI / 12)  # reference angles for the t-substitution
_GRID_C, _GRID_S = np.cos(_GRID + np.pi), np.sin(_GRID + np.pi)
_ALL6 = np.arange(6)
_COLS_126 = np.array([0, 1, 5])

#: |h| (the s3, c3 direction scaled by s4 or s45) below this: theta3 is free at the candidate.
FREE_TOL = 1e-7
#: |sin theta4|, |sin(theta4 + theta5)| of a solution below this: tried as a theta3/theta6 continuum.
CONTINUUM_SIN = 1e-5
#: ... and below this (but not exactly singular): a numerical theta3/theta6 continuum. Near it
#: the configurations within the tolerance of the pose form a thin family in which theta3
#: (with theta6, theta4, theta5) varies a lot: the row is one of them, flagged (3, 6).
NUMERICAL_SIN = 1e-4
#: A critical point of the eliminant with |F| below this (relative to sum |c_i| |t|^i) may be a
#: double root (a tangent root, or two roots closer than the arithmetic separates) ...
TANGENT_REL = 1e-3
#: ... it becomes a candidate if the length error of Eq 11 there, |E| / (2 l4) [m], is below
#: this many times ``approximate_tol`` (an approximate solution can lie there).
TANGENT_REACH = 10.0
#: |p^(k)(x)| below this (relative to sum |c_i| |x|^i) is rounding noise: no sign (a root there).
ROUNDING_REL = 1e-14
#: theta1 roots closer than this [rad] are both treated as candidate double roots (F's roots
#: lose accuracy like eps / separation there).
CROWDED = 1e-5
#: Largest Newton step when a simple root of p is refined on f_sigma [rad] (such a root is
#: inaccurate only where F is nearly flat; the step bound keeps the refinement at that root).
REFINE_STEP = 1e-3
#: A cluster of double-root candidates is scanned for sign changes of f_sigma within this [rad] ...
SCAN_HALF = 1e-3
#: ... in this many steps.
SCAN_STEPS = 24
#: ... when a closed-form configuration there has |sin theta4|, |sin(theta4 + theta5)| below this.
SCAN_NEAR = 1e-2
#: Stalled polishes near the theta3/theta6 continuum whose (theta1, theta2) are this close [rad]
#: lie in one valley: one restart sweep around its theta3 circle serves them all.
VALLEY = 1e-3
#: A simple root of p whose rounding uncertainty (8 eps sum |c_i| |t|^i / |p'(t)|) exceeds this
#: [t units, ~rad] is treated as a double-root candidate.
UNCERTAIN_ROOT = 1e-9
#: Candidates farther than this from the pose after the closed forms are dropped unpolished [m], [rad].
NEAR_POSITION = 1e-3
NEAR_ROTATION = 1e-2


@_inner
def wrap(x):
    """Angle wrapped to (-pi, pi] (one addition for |x| <= 3 pi, the usual case)."""
    if x > math.pi:
        if x <= 3.0 * math.pi:
            return x - _TWO_PI
    elif x > -math.pi:
        return x
    elif x > -3.0 * math.pi:
        return x + _TWO_PI
    return math.pi - ((math.pi - x) % _TWO_PI)


# ----------------------------------------------------------------------------- pose input
@_inner
def _check_pose(T, tol, Ru):
    """Validate one pose and project its rotation onto the nearest rotation.

    Returns ``(status, measure, distance)``: ``measure`` is max |R^T R - I| (or the
    bottom-row error), ``distance`` the Frobenius distance from R to the rotation ``Ru``
    written out (the polar factor of R, by Newton's iteration ``X <- (X + X^-T) / 2``).
    Rotations orthonormal to 64 eps are used exactly as given.
    """
    for i in range(4):
        for j in range(4):
            if not math.isfinite(T[i, j]):
                return NONFINITE, 0.0, 0.0
    bot = max(abs(T[3, 0]), abs(T[3, 1]), abs(T[3, 2]), abs(T[3, 3] - 1.0))
    if bot > tol:
        return BOTTOM_ROW, bot, 0.0
    err = 0.0
    for i in range(3):
        for j in range(3):
            g = T[0, i] * T[0, j] + T[1, i] * T[1, j] + T[2, i] * T[2, j] - (1.0 if i == j else 0.0)
            err = max(err, abs(g))
    if err > tol:
        return NOT_ORTHONORMAL, err, 0.0
    det = (T[0, 0] * (T[1, 1] * T[2, 2] - T[1, 2] * T[2, 1])
           - T[0, 1] * (T[1, 0] * T[2, 2] - T[1, 2] * T[2, 0])
           + T[0, 2] * (T[1, 0] * T[2, 1] - T[1, 1] * T[2, 0]))
    if det < 0.0:
        return REFLECTION, err, 0.0
    for i in range(3):
        for j in range(3):
            Ru[i, j] = T[i, j]
    if err <= 64 * _EPS:
        return OK, err, 0.0
    for _ in range(20):
        a, b, c = Ru[0, 0], Ru[0, 1], Ru[0, 2]
        d, e, f = Ru[1, 0], Ru[1, 1], Ru[1, 2]
        g, h, k = Ru[2, 0], Ru[2, 1], Ru[2, 2]
        # X^-T = cofactor(X) / det(X)
        c00, c01, c02 = e * k - f * h, f * g - d * k, d * h - e * g
        c10, c11, c12 = c * h - b * k, a * k - c * g, b * g - a * h
        c20, c21, c22 = b * f - c * e, c * d - a * f, a * e - b * d
        det = a * c00 + b * c01 + c * c02
        Ru[0, 0], Ru[0, 1], Ru[0, 2] = 0.5 * (a + c00 / det), 0.5 * (b + c01 / det), 0.5 * (c + c02 / det)
        Ru[1, 0], Ru[1, 1], Ru[1, 2] = 0.5 * (d + c10 / det), 0.5 * (e + c11 / det), 0.5 * (f + c12 / det)
        Ru[2, 0], Ru[2, 1], Ru[2, 2] = 0.5 * (g + c20 / det), 0.5 * (h + c21 / det), 0.5 * (k + c22 / det)
        step = max(abs(Ru[0, 0] - a), abs(Ru[0, 1] - b), abs(Ru[0, 2] - c), abs(Ru[1, 0] - d),
                   abs(Ru[1, 1] - e), abs(Ru[1, 2] - f), abs(Ru[2, 0] - g), abs(Ru[2, 1] - h),
                   abs(Ru[2, 2] - k))
        if step <= 4 * _EPS:
            break
    dist = 0.0
    for i in range(3):
        for j in range(3):
            dist += (T[i, j] - Ru[i, j]) ** 2
    return OK, err, math.sqrt(dist)


# ----------------------------------------------------------------------------- residuals
@_inner
def _rotation_angle(T4, R):
    """Angle between the rotation of T4 and R: the formula of :func:`iik.rotations.rotation_angle`."""
    d = 0.0
    for i in range(3):
        for j in range(3):
            d += (T4[i, j] - R[i, j]) ** 2
    return 2.0 * math.asin(min(math.sqrt(d) / _SQRT8, 1.0))


@_inner
def _position_error(T4, T):
    return math.sqrt((T4[0, 3] - T[0, 3]) ** 2 + (T4[1, 3] - T[1, 3]) ** 2 + (T4[2, 3] - T[2, 3]) ** 2)


@_inner
def _residuals(q, L, Ru, T, T4):
    """(position [m], rotation [rad]) residuals of fk(q) (into T4) against (Ru, p)."""
    _fk_into(q, L, T4)
    return _position_error(T4, T), _rotation_angle(T4, Ru)


@_inner
def _pose_error(q, L, Ru, T, T4, e):
    """e = [p* - p(q); vee(Re - Re^T) / 2 with Re = R* R(q)^T], the vector Newton drives to 0."""
    _fk_into(q, L, T4)
    for i in range(3):
        e[i] = T[i, 3] - T4[i, 3]
    re01 = Ru[0, 0] * T4[1, 0] + Ru[0, 1] * T4[1, 1] + Ru[0, 2] * T4[1, 2]
    re02 = Ru[0, 0] * T4[2, 0] + Ru[0, 1] * T4[2, 1] + Ru[0, 2] * T4[2, 2]
    re10 = Ru[1, 0] * T4[0, 0] + Ru[1, 1] * T4[0, 1] + Ru[1, 2] * T4[0, 2]
    re12 = Ru[1, 0] * T4[2, 0] + Ru[1, 1] * T4[2, 1] + Ru[1, 2] * T4[2, 2]
    re20 = Ru[2, 0] * T4[0, 0] + Ru[2, 1] * T4[0, 1] + Ru[2, 2] * T4[0, 2]
    re21 = Ru[2, 0] * T4[1, 0] + Ru[2, 1] * T4[1, 1] + Ru[2, 2] * T4[1, 2]
    e[3], e[4], e[5] = 0.5 * (re21 - re12), 0.5 * (re02 - re20), 0.5 * (re10 - re01)


@_inner
def _least_squares_step(J, e, cols, n, dq, A, g, lam):
    """dq = (J_c^T J_c + mu I)^-1 J_c^T e over the columns ``cols[:n]`` (Cholesky); A, g scratch.

    mu = (1e-14 + lam) trace / n: a tiny floor keeps the normal equations positive definite
    at singular configurations (there the step is the minimum-norm Gauss-Newton step up to
    directions with singular values below ~1e-7, which the pose does not determine anyway);
    ``lam`` is the Levenberg-Marquardt damping.
    """
    tr = 0.0
    for a in range(n):
        ca = cols[a]
        s = 0.0
        for r in range(6):
            s += J[r, ca] * e[r]
        g[a] = s
        for b in range(a, n):
            cb = cols[b]
            s = 0.0
            for r in range(6):
                s += J[r, ca] * J[r, cb]
            A[a, b] = s
            A[b, a] = s
        tr += A[a, a]
    mu = (1e-14 + lam) * tr / n + 1e-300
    for a in range(n):
        A[a, a] += mu
    for a in range(n):  # Cholesky A = U^T U, U in the upper triangle
        s = A[a, a]
        for k in range(a):
            s -= A[k, a] * A[k, a]
        d = math.sqrt(s if s > mu else mu)
        A[a, a] = d
        for b in range(a + 1, n):
            s = A[a, b]
            for k in range(a):
                s -= A[k, a] * A[k, b]
            A[a, b] = s / d
    for a in range(n):  # U^T y = g
        s = g[a]
        for k in range(a):
            s -= A[k, a] * g[k]
        g[a] = s / A[a, a]
    for a in range(n - 1, -1, -1):  # U x = y
        s = g[a]
        for k in range(a + 1, n):
            s -= A[a, k] * g[k]
        g[a] = s / A[a, a]
    for a in range(n):
        dq[a] = g[a]


@_inner
def _newton_step(J, e, dq, A, g):
    """dq = J^-1 e (6 x 6, Gaussian elimination with partial pivoting); False if J is singular
    to 1e-12 of its largest pivot (then the caller takes a least-squares step)."""
    for r in range(6):
        g[r] = e[r]
        for c in range(6):
            A[r, c] = J[r, c]
    big = 0.0
    for k in range(6):
        p, best = k, abs(A[k, k])
        for r in range(k + 1, 6):
            if abs(A[r, k]) > best:
                p, best = r, abs(A[r, k])
        big = max(big, best)
        if best <= 1e-12 * big or best == 0.0:
            return False
        if p != k:
            for c in range(6):
                A[k, c], A[p, c] = A[p, c], A[k, c]
            g[k], g[p] = g[p], g[k]
        for r in range(k + 1, 6):
            f = A[r, k] / A[k, k]
            for c in range(k + 1, 6):
                A[r, c] -= f * A[k, c]
            g[r] -= f * g[k]
    for k in range(5, -1, -1):
        t = g[k]
        for c in range(k + 1, 6):
            t -= A[k, c] * dq[c]
        dq[k] = t / A[k, k]
    return True


@_inner
def _sq(e):
    return e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3] + e[4] * e[4] + e[5] * e[5]


@_inner
def _polish(q, L, dh, Ru, T, ws, wm, cols, n, iters):
    """Levenberg-Marquardt on the full FK over joints ``cols[:n]``; q in place, wrapped at the end.

    The first try of every iteration is the Newton step (6 joints, J^-1 e; least squares
    for fewer joints or a singular J); a step that does not reduce the pose error is
    rejected and retried with more damping (so a near-singular valley is not jumped
    across). Stops when a step is below 1e-14 rad or the damping has grown without
    progress: then q is a least-squares configuration (approximate if the error is not 0).
    """
    T4, J, A = wm[_M_T4, :4, :4], wm[_M_J, :6, :6], wm[_M_A, :6, :6]
    e, dq, g = ws[_W_E:_W_E + 6], ws[_W_DQ:_W_DQ + 6], ws[_W_G:_W_G + 6]
    et, qt = ws[_W_ET:_W_ET + 6], ws[_W_QT:_W_QT + 6]
    st = ws[_W_STATS:_W_STATS + 8]
    st[3] += 1.0
    _pose_error(q, L, Ru, T, T4, e)
    st[5] += 1.0
    err = _sq(e)
    lam = 0.0
    fresh = False
    for _ in range(iters):
        if err == 0.0:
            break
        st[4] += 1.0
        if not fresh:
            _jacobian_into(q, dh, J)
            st[6] += 1.0
        fresh = True
        if lam > 0.0 or n < 6 or not _newton_step(J, e, dq, A, g):
            _least_squares_step(J, e, cols, n, dq, A, g, lam)
        for j in range(6):
            qt[j] = q[j]
        big = 0.0
        for a in range(n):
            qt[cols[a]] += dq[a]
            big = max(big, abs(dq[a]))
        _pose_error(qt, L, Ru, T, T4, et)
        st[5] += 1.0
        errt = _sq(et)
        if errt <= err:
            for j in range(6):
                q[j], e[j] = qt[j], et[j]
            err, fresh = errt, False
            lam = 0.0 if lam <= 1e-10 else 0.1 * lam
            if big <= 1e-14:
                break
        else:
            lam = 1e-10 if lam == 0.0 else 10.0 * lam
            if lam > 1e4:
                break
    for j in range(6):
        q[j] = wrap(q[j])


# ----------------------------------------------------------------------------- the eliminant
@_inner
def _coefficients(Ru, T, L, co):
    """The eliminant's coefficients (:func:`iik.ik.elimination.eq8_eq11_terms`) into co (16,):
    ``a, b, P, Q`` as ``[const, cos, sin]`` (0-11), ``c`` (12), the wrist point D (13-15)."""
    v = _eq8_eq11(Ru[0, 2], Ru[1, 2], Ru[2, 2], T[0, 3], T[1, 3], T[2, 3], L[0], L[1], L[2], L[3], L[4])
    for i in range(16):
        co[i] = v[i]


@_inner
def _abPQ(co, C, S):
    a = co[0] + co[1] * C + co[2] * S
    b = co[3] + co[4] * C + co[5] * S
    P = co[6] + co[7] * C + co[8] * S
    Q = co[9] + co[10] * C + co[11] * S
    return a, b, P, Q


@_inner
def _F(co, C, S):
    """F = a^2 (P^2 + Q^2) - (b Q - c P)^2 (theta2 eliminated from Eq 8 and Eq 11)."""
    a, b, P, Q = _abPQ(co, C, S)
    g = b * Q - co[12] * P
    return a * a * (P * P + Q * Q) - g * g


@_inner
def _eliminant(co, cr, sr, p, ws, wm):
    """Ascending coefficients p (9,) of (1 + t^2)^4 F(theta_r + 2 atan t), a degree-8 polynomial.

    Each trig polynomial x becomes the quadratic (1 + t^2) x = (x0 + x_c') + 2 x_s' t + (x0 - x_c') t^2
    (x_c', x_s' its cos/sin coefficients turned by theta_r).
    """
    q = ws[_W_QUAD:_W_QUAD + 12]
    for k in range(4):
        x0, xc, xs = co[3 * k], co[3 * k + 1], co[3 * k + 2]
        c = xc * cr + xs * sr
        s = -xc * sr + xs * cr
        q[3 * k], q[3 * k + 1], q[3 * k + 2] = x0 + c, 2.0 * s, x0 - c
    c = co[12]
    A2, PQ, G = ws[_W_PROD:_W_PROD + 5], ws[_W_PROD + 5:_W_PROD + 10], ws[_W_PROD + 10:_W_PROD + 15]
    for i in range(5):
        A2[i], PQ[i], G[i] = 0.0, 0.0, 0.0
    for i in range(3):
        for j in range(3):
            A2[i + j] += q[i] * q[j]
            PQ[i + j] += q[6 + i] * q[6 + j] + q[9 + i] * q[9 + j]
            G[i + j] += q[3 + i] * q[9 + j] - c * q[6 + i] * (1.0 if j != 1 else 0.0)
    for k in range(9):
        p[k] = 0.0
    for i in range(5):
        for j in range(5):
            p[i + j] += A2[i] * PQ[j] - G[i] * G[j]


@_inner
def _horner(c, deg, x):
    """p(x), p'(x) and sum |c_i| |x|^i (the scale of the rounding error of p(x))."""
    f = c[deg]
    df = 0.0
    m = abs(f)
    ax = abs(x)
    for i in range(deg - 1, -1, -1):
        df = df * x + f
        f = f * x + c[i]
        m = m * ax + abs(c[i])
    return f, df, m


@_inner
def _bracketed_root(c, deg, x0, x1, f0, f1, flat0, flat1, rtol):
    """The root of a polynomial in [x0, x1] where it changes sign (f0, f1: values at the ends).

    Newton's method safeguarded by bisection (every iterate stays in the shrinking
    bracket); it starts where the cubic with the end values and zero end slopes (``flat0``,
    ``flat1``: the ends are critical points) crosses zero. Stops when the step is below
    ``rtol`` (1 + |x|), the bracket is at rounding level, or |p(x)| is below the rounding
    error of its evaluation (8 eps sum |c_i| |x|^i).
    """
    r = f0 / (f0 - f1)  # in (0, 1)
    if flat0 and flat1:  # inverse of 3 s^2 - 2 s^3
        s = 0.5 - math.sin(math.asin(1.0 - 2.0 * r) / 3.0)
    elif flat0:  # inverse of s^2
        s = math.sqrt(r)
    elif flat1:  # inverse of 1 - (1 - s)^2
        s = 1.0 - math.sqrt(1.0 - r)
    else:
        s = r
    x = x0 + s * (x1 - x0)
    if not (x0 < x < x1):
        x = 0.5 * (x0 + x1)
    step_old = x1 - x0
    for _ in range(200):
        f, df, m = _horner(c, deg, x)
        if abs(f) <= 8 * _EPS * m:
            return x
        if (f < 0.0) == (f0 < 0.0):
            x0, f0 = x, f
        else:
            x1 = x
        xn = x - f / df if df != 0.0 else x0 - 1.0
        if not (x0 < xn < x1) or abs(xn - x) > 0.5 * step_old:
            xn = 0.5 * (x0 + x1)
        step_old = abs(xn - x)
        if step_old <= rtol * (1.0 + abs(x)) or x1 - x0 <= 4 * _EPS * (1.0 + abs(x)):
            return xn
        x = xn
    return x


@_inner
def _real_roots(p, ws, wm):
    """Every real root of the degree-8 polynomial ``p``, by isolation on monotone pieces.

    The derivatives p^(7), ..., p' are treated from the linear one up (the linear and
    quadratic ones in closed form): the (sorted) real roots of p^(k+1) cut [-B, B] (B:
    Cauchy's bound, which by Gauss-Lucas also holds for the derivatives) into pieces on
    which p^(k) is monotone, so each piece holds at most one root of p^(k), found by
    :func:`_bracketed_root` where p^(k) changes sign. For p itself, a critical point
    where |p| is below :data:`TANGENT_REL` of the magnitude of its terms is reported as
    a candidate double root (kind 1). Roots go to ws[_W_ROOTS:], kinds to
    ws[_W_KINDS:], sorted; returns how many.
    """
    roots, kinds = ws[_W_ROOTS:_W_ROOTS + 16], ws[_W_KINDS:_W_KINDS + 16]
    lead = abs(p[8])
    bound = 0.0
    for i in range(8):
        bound = max(bound, abs(p[i]))
    bound = 1.0 + bound / lead
    D = wm[_M_D]  # D[k] = coefficients of p^(k)
    for i in range(9):
        D[0, i] = p[i]
    for k in range(1, 9):
        for i in range(9 - k):
            D[k, i] = D[k - 1, i + 1] * (i + 1)
    crit, new = ws[_W_CRIT:_W_CRIT + 10], ws[_W_NEW:_W_NEW + 10]
    crit[0] = -D[7, 0] / D[7, 1]  # p^(7) is linear
    ncrit = 1
    c0, c1, c2 = D[6, 0], D[6, 1], D[6, 2]  # p^(6) is quadratic
    disc = c1 * c1 - 4.0 * c0 * c2
    if disc > 0.0:
        qq = -0.5 * (c1 + math.copysign(math.sqrt(disc), c1))
        ra, rb = qq / c2, c0 / qq
        crit[0], crit[1] = min(ra, rb), max(ra, rb)
        ncrit = 2
    else:
        ncrit = 0
    nk = 0
    for k in range(5, -1, -1):
        deg = 8 - k
        ck = D[k]
        nnew = 0
        xa = -bound
        fa, _, _ = _horner(ck, deg, xa)
        for j in range(ncrit + 1):
            xb = crit[j] if j < ncrit else bound
            fb, _, mb = _horner(ck, deg, xb)
            # a value at rounding level has no sign: the end point counts as a root itself
            zero = k > 0 and j < ncrit and abs(fb) <= ROUNDING_REL * mb
            if zero:
                fb = 0.0
            if (fa < 0.0 and fb > 0.0) or (fa > 0.0 and fb < 0.0):
                new[nnew] = _bracketed_root(ck, deg, xa, xb, fa, fb, j > 0, j < ncrit,
                                            1e-15 if k == 0 else 1e-9)
                nnew += 1
            if zero and k > 0:
                new[nnew] = xb
                nnew += 1
            xa, fa = xb, fb
        if k > 0:
            for j in range(nnew):
                crit[j] = new[j]
            ncrit = nnew
            continue
        i_new = 0  # p itself: merge simple roots and candidate double roots, in order
        for j in range(ncrit):
            x = crit[j]
            before = i_new < nnew and new[i_new] < x and (j == 0 or new[i_new] > crit[j - 1])
            while i_new < nnew and new[i_new] < x:
                roots[nk], kinds[nk] = new[i_new], 0.0
                nk += 1
                i_new += 1
            after = i_new < nnew and (j + 1 >= ncrit or new[i_new] < crit[j + 1])
            f, _, m = _horner(ck, deg, x)
            size = _horner(ck, deg, max(1.0, abs(x)))[2]  # sum |c_i| max(1, |x|)^i: p's scale there
            # an extremum between two roots found on both sides adds nothing, unless it is
            # at rounding level (then the two roots may be one double root)
            if abs(f) <= TANGENT_REL * size and not (before and after and abs(f) > 1e3 * ROUNDING_REL * m):
                roots[nk], kinds[nk] = x, 1.0
                nk += 1
        while i_new < nnew:
            roots[nk], kinds[nk] = new[i_new], 0.0
            nk += 1
            i_new += 1
    return nk


# ----------------------------------------------------------------------------- candidates
@_inner
def _theta1_candidates(co, L, opt, ws, wm):
    """theta1 candidates [rad] from the real roots of the eliminant (into ws[_W_TH1:]).

    ws[_W_CAREFUL:] marks candidates from double-root candidates, crowded roots and a
    degenerate eliminant (every theta1 a root): they are always polished and tried with
    both signs of Eq 8. Returns how many.
    """
    th1, careful = ws[_W_TH1:_W_TH1 + _MAX_T1], ws[_W_CAREFUL:_W_CAREFUL + _MAX_T1]
    # theta_r: the grid angle whose opposite (t = infinity) is farthest from a root
    best, ir = -1.0, 0
    for i in range(12):
        v = abs(_F(co, _GRID_C[i], _GRID_S[i]))
        if v > best:
            best, ir = v, i
    thr = _GRID[ir]
    p = ws[_W_P:_W_P + 9]
    _eliminant(co, math.cos(thr), math.sin(thr), p, ws, wm)
    scale = 0.0
    for i in range(9):
        scale = max(scale, abs(p[i]))
    # the size F would have without cancellation: F = 0 identically below ~1e-12 of it
    sa = abs(co[0]) + abs(co[1]) + abs(co[2])
    sb = abs(co[3]) + abs(co[4]) + abs(co[5])
    sp = abs(co[6]) + abs(co[7]) + abs(co[8])
    sq = abs(co[9]) + abs(co[10]) + abs(co[11])
    mag = sa * sa * (sp * sp + sq * sq) + (sb * sq + abs(co[12]) * sp) ** 2
    n = 0
    if scale <= 1e-12 * mag or abs(p[8]) <= 1e-14 * scale:
        # every theta1 solves the eliminant (wrist point on the joint-1 axis): the solutions lie
        # where Eq 8 vanishes identically (P = Q = 0: z6 in the arm's plane), reached by
        # _min_pq from representatives a quarter turn apart (one lies on every half circle;
        # where P = Q = 0 for every theta1, z6 vertical, they stay: the theta1/theta6 continuum)
        for k in range(4):
            n = _push(th1, careful, n, _min_pq(co, k * 0.5 * math.pi), 1.0)
        return n
    for i in range(9):
        p[i] /= scale
    nr = _real_roots(p, ws, wm)
    roots, kinds = ws[_W_ROOTS:_W_ROOTS + 16], ws[_W_KINDS:_W_KINDS + 16]
    reach = max(TANGENT_REACH * opt[OPT_APPROX_TOL], 1e-9)
    weak = 1e-6 * (math.sqrt(co[13] ** 2 + co[14] ** 2 + co[15] ** 2) + L[1] + L[2])
    for i in range(nr):
        if n >= _MAX_T1:
            break
        t = wrap(thr + 2.0 * math.atan(roots[i]))
        kind = kinds[i]
        if kind == 0.0:
            # a simple root where p is flat at its rounding level is uncertain by more than
            # UNCERTAIN_ROOT: treated like a double-root candidate (f_sigma refined and scanned)
            _, dp, m = _horner(p, 8, roots[i])
            if 8.0 * _EPS * m > UNCERTAIN_ROOT * abs(dp):
                kind = 1.0
        elif kind == 1.0:
            # keep a double-root candidate only if Eq 11 can (nearly) hold there:
            # |E| = |a N +- g| / N is 2 l4 times the length error; unknown where N = 0
            a, b, P, Q = _abPQ(co, math.cos(t), math.sin(t))
            N = math.hypot(P, Q)
            g = b * Q - co[12] * P
            if N > weak and min(abs(a * N + g), abs(a * N - g)) / N > 2.0 * L[3] * reach:
                continue
        th1[n], careful[n] = t, kind
        n += 1
    # roots closer than CROWDED: F's roots are inaccurate there, refine and polish both
    for i in range(n):
        for j in range(i + 1, n):
            if abs(wrap(th1[i] - th1[j])) <= CROWDED:
                careful[i], careful[j] = 1.0, 1.0
    return n


@_inner
def _f_sigma(co, th, sigma):
    """The unsquared eliminant f = a N + sigma (b Q - c P), N = |(P, Q)|, and its first two
    derivatives in theta1 (F = f_+ f_-)."""
    C, S = math.cos(th), math.sin(th)
    a, b, P, Q = _abPQ(co, C, S)
    a1, b1 = -co[1] * S + co[2] * C, -co[4] * S + co[5] * C
    P1, Q1 = -co[7] * S + co[8] * C, -co[10] * S + co[11] * C
    a2, b2, P2, Q2 = co[0] - a, co[3] - b, co[6] - P, co[9] - Q  # x'' = x0 - x
    c = co[12]
    N = math.hypot(P, Q)
    u = P * P1 + Q * Q1
    N1 = u / N
    N2 = (P1 * P1 + P * P2 + Q1 * Q1 + Q * Q2) / N - u * u / (N * N * N)
    g = b * Q - c * P
    g1 = b1 * Q + b * Q1 - c * P1
    g2 = b2 * Q + 2.0 * b1 * Q1 + b * Q2 - c * P2
    f = a * N + sigma * g
    f1 = a1 * N + a * N1 + sigma * g1
    f2 = a2 * N + 2.0 * a1 * N1 + a * N2 + sigma * g2
    return f, f1, f2


@_inner
def _newton_f(co, th, sigma, order):
    """Newton on f_sigma (order 0: a root) or on its derivative (order 1: the extremum, where a
    double root of F is a simple root), from th; steps clipped to 0.05 rad."""
    for _ in range(12):
        f, f1, f2 = _f_sigma(co, th, sigma)
        num, den = (f, f1) if order == 0 else (f1, f2)
        if den == 0.0 or not math.isfinite(num / den):
            break
        step = min(max(num / den, -0.05), 0.05)
        th -= step
        if abs(step) <= 1e-15:
            break
    return wrap(th)


@_inner
def _raw_last(th1, careful, n, n_raw, tmp):
    """Order the theta1 candidates (stable): refined and simple ones, then the kind-1 ones found
    by refinement (index >= n_raw: where Eq 8 vanishes), then the unrefined double-root
    candidates (kind 1, index < n_raw). The roots of f_sigma found from a cluster are tried
    before the cluster itself, so that a pose whose eliminant is flat at rounding level (many
    kind-1 roots of noise) cannot fill the candidate table with them."""
    m = 0
    for rank in range(3):
        for i in range(n):
            r = 0 if careful[i] != 1.0 else (1 if i >= n_raw else 2)
            if r == rank:
                tmp[m], tmp[_MAX_T1 + m] = th1[i], careful[i]
                m += 1
    for i in range(n):
        th1[i], careful[i] = tmp[i], tmp[_MAX_T1 + i]


@_inner
def _refine_root(co, th, sigma):
    """A root of f_sigma near the eliminant root th [rad] by Newton (steps clipped to
    REFINE_STEP); th itself when the first step is at rounding level (the usual case)."""
    for _ in range(8):
        f, f1, _ = _f_sigma(co, th, sigma)
        if f1 == 0.0 or not math.isfinite(f / f1):
            break
        step = min(max(f / f1, -REFINE_STEP), REFINE_STEP)
        if abs(step) <= 1e-15:
            break
        th -= step
    return wrap(th)


@_inner
def _small_f(co, th, sigma):
    """Is |f_sigma(th)| below TANGENT_REL of the size f_sigma has without cancellation (from the
    magnitudes of the coefficients)? A double-root candidate of F = f_+ f_- is a near root of
    one factor; the other factor, if not small there, has no root nearby to refine."""
    a, b, P, Q = _abPQ(co, math.cos(th), math.sin(th))
    N = math.hypot(P, Q)
    g = b * Q - co[12] * P
    sa = abs(co[0]) + abs(co[1]) + abs(co[2])
    sb = abs(co[3]) + abs(co[4]) + abs(co[5])
    sp = abs(co[6]) + abs(co[7]) + abs(co[8])
    sq = abs(co[9]) + abs(co[10]) + abs(co[11])
    return abs(a * N + sigma * g) <= TANGENT_REL * (sa * math.hypot(sp, sq) + sb * sq + abs(co[12]) * sp)


@_inner
def _near_continuum_at(co, Ru, L, th, scale, ws):
    """Does a closed-form configuration at theta1 = th (theta2 from Eq 8 with the better sign, or
    from Eq 11 where Eq 8 vanishes) lie near the theta3/theta6 continuum (|sin theta4| and
    |sin(theta4 + theta5)| <= SCAN_NEAR)? There F is flat at its rounding level over ~1e-3 rad."""
    q, t2 = ws[_W_Q2:_W_Q2 + 6], ws[_W_TH2:_W_TH2 + 4]
    C, S = math.cos(th), math.sin(th)
    a, b, P, Q = _abPQ(co, C, S)
    N = math.hypot(P, Q)
    g = b * Q - co[12] * P
    if N > 1e-6 * scale:
        t2[0], n2 = (math.atan2(-P, Q) if abs(a * N + g) <= abs(a * N - g) else math.atan2(P, -Q)), 1
    else:
        r, phi = math.hypot(b, co[12]), math.atan2(co[12], b)
        acs = math.acos(min(max(-a / r if r > 0 else 0.0, -1.0), 1.0))
        t2[0], t2[1], n2 = phi + acs, phi - acs, 2
    for k in range(n2):
        _wrist(Ru, co, L, C, S, math.cos(t2[k]), math.sin(t2[k]), 0, q)
        if abs(math.sin(q[3])) <= SCAN_NEAR and abs(math.sin(q[3] + q[4])) <= SCAN_NEAR:
            return True
    return False


@_inner
def _push(th1, careful, n, t, kind):
    """Append theta1 candidate t of ``kind`` unless the table is full or holds it (1e-8 rad,
    same kind: refinements of one cluster land alike, up to the ~1e-9 rad to which a flat
    f_sigma fixes its root); the new count."""
    if n >= _MAX_T1:
        return n
    for j in range(n):
        if careful[j] == kind and abs(wrap(th1[j] - t)) <= 1e-8:
            return n
    th1[n], careful[n] = t, kind
    return n + 1


@_inner
def _scan_roots(co, c, sigma, kind, th1, careful, n):
    """Append (as ``kind``) every sign change of f_sigma on SCAN_STEPS steps within SCAN_HALF
    rad of c, refined by :func:`_bracketed_f`; the new count.

    Where F is flat at its rounding level (a cluster of double-root candidates near the
    theta3/theta6 continuum, |F| ~ 1e-20) p cannot place a root, but f_sigma, evaluated
    directly, still changes sign at it: a simple root of f_sigma whose slope is ~1e-11 lies
    up to ~2e-4 rad from the cluster and has no extremum nearby.
    """
    h = 2.0 * SCAN_HALF / SCAN_STEPS
    xa = c - SCAN_HALF
    fa, _, _ = _f_sigma(co, xa, sigma)
    for k in range(1, SCAN_STEPS + 1):
        xb = c - SCAN_HALF + k * h
        fb, _, _ = _f_sigma(co, xb, sigma)
        if (fa < 0.0 and fb > 0.0) or (fa > 0.0 and fb < 0.0):
            n = _push(th1, careful, n, wrap(_bracketed_f(co, sigma, xa, xb, fa, fb)), kind)
        xa, fa = xb, fb
    return n


@_inner
def _root_beside(co, tb, fb, d, sigma):
    """The root of f_sigma on the side ``d`` of its extremum tb (value fb), about |d| away: the
    first sign change at tb + d, tb + 2 d, tb + 4 d, ... (6 tries) is bracketed and refined by
    safeguarded Newton (near a point where P = Q = 0, f_sigma curves too sharply for plain
    Newton); plain Newton from tb + d if no sign change is found."""
    xa, fa = tb, fb
    for k in range(6):
        xb = tb + d * (1 << k)
        f1, _, _ = _f_sigma(co, xb, sigma)
        if (f1 < 0.0) != (fb < 0.0):
            return wrap(_bracketed_f(co, sigma, xa, xb, fa, f1))
        xa, fa = xb, f1
    return _newton_f(co, tb + d, sigma, 0)


@_inner
def _bracketed_f(co, sigma, x0, x1, f0, f1):
    """The root of f_sigma between x0 and x1 (f0, f1 of opposite signs): Newton kept inside the
    shrinking bracket, bisection where it would leave it; to 1e-15 rad."""
    x = x0 - f0 * (x1 - x0) / (f1 - f0)
    for _ in range(100):
        f, df, _ = _f_sigma(co, x, sigma)
        if f == 0.0:
            return x
        if (f < 0.0) == (f0 < 0.0):
            x0, f0 = x, f
        else:
            x1, f1 = x, f
        xn = x - f / df if df != 0.0 else 0.5 * (x0 + x1)
        if not (min(x0, x1) < xn < max(x0, x1)):
            xn = 0.5 * (x0 + x1)
        if abs(xn - x) <= 1e-15 or abs(x1 - x0) <= 1e-15:
            return xn
        x = xn
    return x


@_inner
def _sign_group(kind):
    """The sign of Eq 8 a theta1 candidate is tried with: 0 both (kinds 0, 1), 1 (+: 2, 4), 2 (-: 3, 5)."""
    return 0 if kind < 2.0 else (1 if kind == 2.0 or kind == 4.0 else 2)


@_inner
def _min_pq(co, th):
    """Newton on d(P^2 + Q^2)/2 = P P' + Q Q' from th: where Eq 8 vanishes identically."""
    for _ in range(12):
        C, S = math.cos(th), math.sin(th)
        P, Q = co[6] + co[7] * C + co[8] * S, co[9] + co[10] * C + co[11] * S
        P1, Q1 = -co[7] * S + co[8] * C, -co[10] * S + co[11] * C
        P2, Q2 = co[6] - P, co[9] - Q
        num, den = P * P1 + Q * Q1, P1 * P1 + P * P2 + Q1 * Q1 + Q * Q2
        if den == 0.0 or not math.isfinite(num / den):
            break
        step = min(max(num / den, -0.05), 0.05)
        th -= step
        if abs(step) <= 1e-15:
            break
    return wrap(th)


@_inner
def _wrist(Ru, co, L, c1, s1, c2, s2, branch, out):
    """theta3, theta4, theta5 of one wrist branch for (theta1, theta2) (corrected Eq 14-28).

    The wrist point and the tool axis are expressed in frame 2 (rotation of Eq 18):
    ``D_2 = (l4 c3 s4, l3 + l4 c4, -l4 s3 s4)`` and ``z6_2 = (-c3 s45, -c45, s3 s45)``
    (Eq 18, 25, 26). Returns True if theta3 is free at this candidate (s4 = s45 = 0 to
    :data:`FREE_TOL`; then theta3 = 0 is the representative).
    """
    l2, l3, l4 = L[1], L[2], L[3]
    wx, wy, wz = co[13] - l2 * c1, co[14] - l2 * s1, co[15]  # D - B
    zx0, zy0, zz0 = Ru[0, 2], Ru[1, 2], Ru[2, 2]
    # rows of the frame-2 rotation (Eq 18): D and z6 in frame 2
    dx = c1 * s2 * wx + s1 * s2 * wy + c2 * wz
    dy = c1 * c2 * wx + s1 * c2 * wy - s2 * wz
    dz = -s1 * wx + c1 * wy
    zx = c1 * s2 * zx0 + s1 * s2 * zy0 + c2 * zz0
    zy = c1 * c2 * zx0 + s1 * c2 * zy0 - s2 * zz0
    zz = -s1 * zx0 + c1 * zy0
    hp0, hp1 = -dz / l4, dx / l4  # = s4 (s3, c3)
    ho0, ho1 = zz, -zx  # = s45 (s3, c3)
    npos, nori = math.hypot(hp0, hp1), math.hypot(ho0, ho1)
    h0, h1 = (hp0, hp1) if npos >= nori else (ho0, ho1)
    free = max(npos, nori) <= FREE_TOL
    if free:
        h0, h1 = 0.0, 1.0
    th3 = math.atan2(h0, h1)
    if branch == 1:
        th3 = wrap(th3 + math.pi)
    c3, s3 = math.cos(th3), math.sin(th3)
    th4 = math.atan2((c3 * dx - s3 * dz) / l4, (dy - l3) / l4)  # Eq 14-16
    th5 = wrap(math.atan2(-c3 * zx + s3 * zz, -zy) - th4)  # Eq 25-28
    out[2], out[3], out[4] = th3, th4, th5
    return free


@_inner
def _theta6(q, L, Ru, T4):
    """theta6 from R(q with theta6 = 0)^T R = Rz(theta6) (Eq 31-33 equivalently); T4 = fk(q).

    The pose at theta6 = 0 is computed once; turning its x and y axes by theta6 (Eq 4,
    :func:`iik.kinematics.eq4_rotation`) gives fk(q) to rounding (cos and sin of theta6
    are taken from the normalised (m00, m10) whose atan2 is theta6).
    """
    q[5] = 0.0
    _fk_into(q, L, T4)
    m10 = T4[0, 1] * Ru[0, 0] + T4[1, 1] * Ru[1, 0] + T4[2, 1] * Ru[2, 0]
    m00 = T4[0, 0] * Ru[0, 0] + T4[1, 0] * Ru[1, 0] + T4[2, 0] * Ru[2, 0]
    q[5] = math.atan2(m10, m00)
    h = math.hypot(m00, m10)
    c6, s6 = (m00 / h, m10 / h) if h > 0.0 else (1.0, 0.0)
    r11, r21, r31, r12, r22, r32 = _rotation(c6, s6, T4[0, 0], T4[1, 0], T4[2, 0],
                                             -T4[0, 1], -T4[1, 1], -T4[2, 1])
    T4[0, 0], T4[1, 0], T4[2, 0], T4[0, 1], T4[1, 1], T4[2, 1] = r11, r21, r31, r12, r22, r32


@_inner
def _coupling_sign(q, L, Ru, T, ws, wm, j):
    """+1 if moving joint j and joint 6 by the same angle keeps the pose, else -1 (j = 0 or 2)."""
    T4, qa = wm[_M_T4, :4, :4], ws[_W_Q2:_W_Q2 + 6]
    for k in range(6):
        qa[k] = q[k]
    qa[j] += 1.0
    qa[5] += 1.0
    pa, ra = _residuals(qa, L, Ru, T, T4)
    qa[5] -= 2.0
    pb, rb = _residuals(qa, L, Ru, T, T4)
    return 1.0 if pa + ra <= pb + rb else -1.0


@_inner
def _free_interval(x, x6, s, lo, hi, lo6, hi6):
    """Feasible interval of a free joint x in [lo, hi] with theta6 = x6 + s (x' - x) in [lo6, hi6]
    (modulo 2 pi); the piece containing x, else the nearest. (nan, nan) if empty."""
    if hi6 - lo6 >= _TWO_PI - 1e-12:
        return lo, hi
    best_a, best_b, best_d = np.nan, np.nan, np.inf
    for k in range(-3, 4):
        u0, u1 = lo6 + k * _TWO_PI, hi6 + k * _TWO_PI  # allowed unwrapped theta6
        a, b = x + s * (u0 - x6), x + s * (u1 - x6)
        a, b = max(min(a, b), lo), min(max(a, b), hi)
        if a > b:
            continue
        d = 0.0 if a <= x <= b else min(abs(x - a), abs(x - b))
        if d < best_d:
            best_a, best_b, best_d = a, b, d
    return best_a, best_b


@_inner
def _resolve_continuum(c, L, Ru, T, ws, wm, lo, hi, j, col, ltol):
    """Sign, feasible interval and an in-limit representative of a joint-j/joint-6 continuum.

    The representative moves along the continuum (joint j and joint 6 together) only if it
    is outside the limits; then to the nearest feasible value of joint j.
    """
    s = _coupling_sign(c, L, Ru, T, ws, wm, j)
    a, b = _free_interval(c[j], c[5], s, lo[j], hi[j], lo[5], hi[5])
    c[col], c[col + 1], c[col + 2] = s, a, b
    if math.isfinite(a) and not (a - ltol <= c[j] <= b + ltol):
        x = min(max(c[j], a), b)
        c[5] = wrap(c[5] + s * (x - c[j]))
        c[j] = x


@_inner
def _within(q, lo, hi, tol):
    """The joint-limit test of :meth:`iik.arm.Arm.within_limits` (``tol``: LIMIT_TOL)."""
    for j in range(6):
        if q[j] < lo[j] - tol or q[j] > hi[j] + tol:
            return False
    return True


@_inner
def _finish(q, pres, rres, polish, iters, prio, L, dh, Ru, T, opt, cand, nc, ws, wm, best):
    """Polish (if asked) and classify configuration q into row nc of cand; the new count."""
    if polish:
        _polish(q, L, dh, Ru, T, ws, wm, _ALL6, 6, iters)
        pres, rres = _residuals(q, L, Ru, T, wm[_M_T4, :4, :4])
    if pres + rres < best[0] + best[1]:
        best[0], best[1] = pres, rres
    if pres <= opt[OPT_POSITION_TOL] and rres <= opt[OPT_ROTATION_TOL]:
        cls = 1.0
    elif pres <= opt[OPT_APPROX_TOL] and rres <= opt[OPT_APPROX_TOL]:
        cls = 2.0
    else:
        return nc
    for j in range(6):
        cand[nc, j] = q[j]
    cand[nc, _C_PRES], cand[nc, _C_RRES], cand[nc, _C_CLASS], cand[nc, _C_FREE] = pres, rres, cls, 0.0
    for j in range(_C_S1, _C_HI3 + 1):
        cand[nc, j] = np.nan
    cand[nc, _C_PRIO] = prio
    return nc + 1


@_inner
def _add_candidate(q, careful, prio, L, dh, Ru, T, opt, cand, nc, ws, wm, best):
    """Finish one closed-form configuration (theta6, polish, classify) into row nc of cand.

    ``prio`` 0 marks a configuration from the extremum of f_sigma (the exact place of a double
    root): of duplicates it is kept (:func:`_distinct_sorted`).
    """
    T4 = wm[_M_T4, :4, :4]
    ws[_W_STATS + 2] += 1.0
    _theta6(q, L, Ru, T4)
    pres = _position_error(T4, T)
    if pres > NEAR_POSITION:
        return nc
    rres = _rotation_angle(T4, Ru)
    if rres > NEAR_ROTATION:
        return nc
    polish = pres > 1e-3 * opt[OPT_POSITION_TOL] or rres > 1e-3 * opt[OPT_ROTATION_TOL]
    if polish and careful:
        # candidates near a double root crowd: skip one already found and finished (1e-9 rad)
        for i in range(nc):
            if cand[i, _C_CLASS] == 1.0 and not _unfinished(cand, i, opt):
                d = 0.0
                for j in range(6):
                    d = max(d, abs(wrap(cand[i, j] - q[j])))
                if d <= 1e-9:
                    return nc
    n0 = nc
    iters = 20 if careful else 12
    nc = _finish(q, pres, rres, polish, iters, prio, L, dh, Ru, T, opt, cand, nc, ws, wm, best)
    if careful and polish and (nc == n0 or _unfinished(cand, nc - 1, opt)) and nc + 8 <= MAX_CAND \
            and abs(math.sin(q[3])) <= 1e-2 and abs(math.sin(q[3] + q[4])) <= 1e-2 and _new_valley(q, ws):
        # stalled near the theta3/theta6 continuum, where the residual is a long flat valley in
        # theta3 (with theta6): start again from 7 more theta3 around the circle (once per valley)
        qs = ws[_W_Q2:_W_Q2 + 6]
        ws[_W_STATS + 7] += 1.0
        s = _coupling_sign(q, L, Ru, T, ws, wm, 2)
        for k in range(1, 8):
            for j in range(6):
                qs[j] = q[j]
            qs[2] = wrap(q[2] + k * _TWO_PI / 8)
            qs[5] = wrap(q[5] + s * k * _TWO_PI / 8)
            nc = _finish(qs, 0.0, 0.0, True, 20, prio, L, dh, Ru, T, opt, cand, nc, ws, wm, best)
    return nc


@_inner
def _new_valley(q, ws):
    """Is q's (theta1, theta2) more than VALLEY rad from every restart sweep of this pose so far
    (then it is recorded)? One sweep samples the whole theta3 circle of a valley."""
    rst = ws[_W_RST:_W_RST + 1 + 2 * _MAX_RST]
    n = int(rst[0])
    for k in range(n):
        if abs(wrap(q[0] - rst[1 + 2 * k])) <= VALLEY and abs(wrap(q[1] - rst[2 + 2 * k])) <= VALLEY:
            return False
    if n >= _MAX_RST:
        return False
    rst[1 + 2 * n], rst[2 + 2 * n], rst[0] = q[0], q[1], n + 1
    return True


@_inner
def _connected(cand, ia, ib, L, Ru, T, ws, wm, tol_p, tol_r):
    """Does the joint-space segment between rows ia and ib stay within (tol_p, tol_r) of the
    pose (3 inner points)?"""
    T4, q = wm[_M_T4, :4, :4], ws[_W_Q2:_W_Q2 + 6]
    for s in (0.25, 0.5, 0.75):
        for j in range(6):
            q[j] = cand[ia, j] + s * wrap(cand[ib, j] - cand[ia, j])
        pr, rr = _residuals(q, L, Ru, T, T4)
        if pr > tol_p or rr > tol_r:
            return False
    return True


@_inner
def _unfinished(cand, i, opt):
    """Has row i not converged (residual above 1/1000 of the tolerance)?"""
    return cand[i, _C_PRES] > 1e-3 * opt[OPT_POSITION_TOL] or cand[i, _C_RRES] > 1e-3 * opt[OPT_ROTATION_TOL]


@_inner
def _order_key(cand, i, opt):
    """Of duplicates keep the finished row, then the extremum one (priority 0), then the least residual."""
    return (2.0 * _unfinished(cand, i, opt) + cand[i, _C_PRIO]
            + 0.25 * (cand[i, _C_PRES] / opt[OPT_POSITION_TOL] + cand[i, _C_RRES] / opt[OPT_ROTATION_TOL]))


@_inner
def _same(cand, ia, ib, L, Ru, T, ws, wm, opt):
    """Are candidate rows ia and ib one solution? (to 1e-7 rad; one continuum; within 0.1 rad of
    each other when one has converged and the other not; joined within 1e-4 rad by a segment
    inside 1/100 of the tolerance (near a singularity a pose fixes q only to ~sqrt(eps)); or,
    near the theta3/theta6 continuum, joined within 0.1 rad by a segment inside the tolerance).
    Rows are tried by priority and residual (:func:`_distinct_sorted`), so the converged one of
    such a pair is kept."""
    dmax = 0.0
    for j in range(6):
        dmax = max(dmax, abs(wrap(cand[ia, j] - cand[ib, j])))
    if dmax <= 1e-7:
        return True
    fa, fb = int(cand[ia, _C_FREE]), int(cand[ib, _C_FREE])
    if fa != 0 and fa == fb and fa != NUMERICAL_Q3_Q6:  # one exact continuum
        fixed = 0.0
        for j in range(5):
            if (j == 0 and fa & FREE_Q1_Q6) or (j == 2 and fa & FREE_Q3_Q6):
                continue
            fixed = max(fixed, abs(wrap(cand[ia, j] - cand[ib, j])))
        if fixed <= 1e-6:
            return True
    # near a fold or a continuum the polish converges slowly or stalls in a shallow valley of
    # the residual: a row that has not converged (residual above 1/1000 of the tolerance)
    # within 0.1 rad of one that has is that one, approached along the valley
    if dmax <= 0.1 and _unfinished(cand, ia, opt) != _unfinished(cand, ib, opt):
        return True
    # near the theta3/theta6 continuum the rows within the tolerance form a long valley: two of
    # its rows up to 0.1 rad apart are one if the segment between them stays in it
    if dmax <= 1e-4:
        return _connected(cand, ia, ib, L, Ru, T, ws, wm, 1e-2 * opt[OPT_POSITION_TOL],
                          1e-2 * opt[OPT_ROTATION_TOL])
    if dmax <= 0.1 and _near_q3_q6(cand, ia) and _near_q3_q6(cand, ib):
        return _connected(cand, ia, ib, L, Ru, T, ws, wm, opt[OPT_POSITION_TOL], opt[OPT_ROTATION_TOL])
    return False


@_inner
def _near_q3_q6(cand, i):
    return abs(math.sin(cand[i, 3])) <= 1e-3 and abs(math.sin(cand[i, 3] + cand[i, 4])) <= 1e-3


@_inner
def _before(cand, ia, ib):
    """Lexicographic order of rows by round(q, 9) (the deterministic order of results)."""
    for j in range(6):
        ka, kb = round(cand[ia, j] * 1e9), round(cand[ib, j] * 1e9)
        if ka != kb:
            return ka < kb
    return False


@_inner
def _distinct_sorted(cand, nc, cls, L, Ru, T, ws, wm, opt, idx):
    """Indices (into idx) of the distinct rows of class ``cls``, lexicographically sorted; count.

    Of a group of duplicates the first by :func:`_order_key` is kept. At most :data:`MAX_SOLUTIONS`:
    the first by :func:`_order_key` (converged rows before unfinished ones), then sorted.
    """
    m = 0
    for i in range(nc):
        if cand[i, _C_CLASS] == cls:
            idx[m] = i
            m += 1
    for i in range(1, m):  # by _order_key (insertion sort; m is small)
        v = int(idx[i])
        key = _order_key(cand, v, opt)
        j = i - 1
        while j >= 0 and _order_key(cand, int(idx[j]), opt) > key:
            idx[j + 1] = idx[j]
            j -= 1
        idx[j + 1] = v
    k = 0
    for i in range(m):
        dup = False
        for j in range(k):
            if _same(cand, int(idx[i]), int(idx[j]), L, Ru, T, ws, wm, opt):
                dup = True
                break
        if not dup:
            idx[k] = idx[i]
            k += 1
            if k == MAX_SOLUTIONS:
                break
    for i in range(1, k):  # lexicographic
        v = int(idx[i])
        j = i - 1
        while j >= 0 and _before(cand, v, int(idx[j])):
            idx[j + 1] = idx[j]
            j -= 1
        idx[j + 1] = v
    return k


# ----------------------------------------------------------------------------- one pose
@_inner
def _configurations(T, L, dh, opt, ws, wm, cand, best):
    """Every candidate configuration of one (validated, projected) pose into cand; count."""
    Ru, co, q, th2s = wm[_M_RU, :3, :3], ws[_W_CO:_W_CO + 16], ws[_W_Q:_W_Q + 6], ws[_W_TH2:_W_TH2 + 4]
    _coefficients(Ru, T, L, co)
    n1 = _theta1_candidates(co, L, opt, ws, wm)
    th1, careful = ws[_W_TH1:_W_TH1 + _MAX_T1], ws[_W_CAREFUL:_W_CAREFUL + _MAX_T1]
    scale = math.sqrt(co[13] ** 2 + co[14] ** 2 + co[15] ** 2) + L[1] + L[2]
    nc = 0
    ws[_W_RST] = 0.0  # no restart sweep yet
    ws[_W_STATS] += 1.0
    n1_roots = n1
    for i in range(n1_roots):
        # a careful candidate also gets, for both signs, the root and the extremum of the
        # unsquared f_sigma by Newton (accurate where F has a double root, unlike F's roots),
        # the two roots near the extremum (two roots closer than F's arithmetic resolves) and
        # the sign changes of f_sigma around it (roots where F is flat at rounding level)
        clustered = False  # one refinement per cluster of careful roots (Newton lands alike)
        scanned = False  # one scan per SCAN_HALF
        for j in range(i):
            if careful[j] == 1.0:
                dj = abs(wrap(th1[j] - th1[i]))
                clustered |= dj <= CROWDED
                scanned |= dj <= 0.5 * SCAN_HALF
        if careful[i] == 1.0 and not clustered:
            C, S = math.cos(th1[i]), math.sin(th1[i])
            a, b, P, Q = _abPQ(co, C, S)
            if math.hypot(P, Q) <= 1e-6 * scale:
                # Eq 8 vanishes near here: the theta1 where P = Q = 0 (minimum of P^2 + Q^2)
                n1 = _push(th1, careful, n1, _min_pq(co, th1[i]), 1.0)
            else:
                for sg in (1.0, -1.0):
                    known = 2.0 if sg > 0 else 3.0  # careful, with this sign of Eq 8
                    if not _small_f(co, th1[i], sg):
                        continue  # F is small here through the other sign's factor
                    n1 = _push(th1, careful, n1, _newton_f(co, th1[i], sg, 0), known)
                    tb = _newton_f(co, th1[i], sg, 1)
                    n1 = _push(th1, careful, n1, tb, known + 2.0)  # 4, 5: the extremum
                    # the two roots of the local quadratic model around the extremum
                    f, _, f2 = _f_sigma(co, tb, sg)
                    d2 = -2.0 * f / f2
                    if 0.0 < d2 <= 1e-4:
                        d = math.sqrt(d2)
                        n1 = _push(th1, careful, n1, _root_beside(co, tb, f, d, sg), known)
                        n1 = _push(th1, careful, n1, _root_beside(co, tb, f, -d, sg), known)
            if not scanned and _near_continuum_at(co, Ru, L, th1[i], scale, ws):
                # (also where Eq 8 vanishes: f_sigma is continuous through it)
                n1 = _scan_roots(co, th1[i], 1.0, 2.0, th1, careful, n1)
                n1 = _scan_roots(co, th1[i], -1.0, 3.0, th1, careful, n1)
    ws[_W_STATS + 1] += n1
    _raw_last(th1, careful, n1, n1_roots, ws[_W_TMP:_W_TMP + 2 * _MAX_T1])
    for i in range(n1):
        # refinements often land on the same theta1: one try per value and sign of Eq 8; of a
        # cluster of kind-1 candidates (within CROWDED) only the first is tried (they are tried
        # last, the refined one first: the rest lie within F's rounding of it)
        repeat = False
        for j in range(i):
            if careful[i] < 4.0 and abs(th1[j] - th1[i]) <= 1e-13 and (
                    careful[j] == 1.0 or _sign_group(careful[j]) == _sign_group(careful[i])):
                repeat = True  # (an extremum, kinds 4 and 5, is always tried: it has priority)
                break
            if careful[i] == 1.0 and careful[j] == 1.0 and abs(wrap(th1[j] - th1[i])) <= CROWDED:
                repeat = True
                break
        if repeat:
            continue
        C, S = math.cos(th1[i]), math.sin(th1[i])
        a, b, P, Q = _abPQ(co, C, S)
        N = math.hypot(P, Q)
        g = b * Q - co[12] * P
        weak = N <= 1e-6 * scale
        if careful[i] == 0.0 and not weak:
            # a simple root of p is only as accurate as p is steep there: refine it on the
            # unsquared f_sigma of its sign (where F = f_+ f_- is flat, f_sigma is not)
            t = _refine_root(co, th1[i], 1.0 if abs(a * N + g) <= abs(a * N - g) else -1.0)
            if t != th1[i]:  # (it may land where Eq 8 vanishes: weak again)
                th1[i] = t
                C, S = math.cos(t), math.sin(t)
                a, b, P, Q = _abPQ(co, C, S)
                N = math.hypot(P, Q)
                g = b * Q - co[12] * P
                weak = N <= 1e-6 * scale
        # Eq 8 (corrected Eq 9): (c2, s2) = sigma (Q, -P) / N, sigma where |a N + sigma g| is least
        if careful[i] == 1.0:
            th2s[0], th2s[1] = math.atan2(-P, Q), math.atan2(P, -Q)
            n2 = 2
        elif careful[i] == 2.0 or careful[i] == 4.0:
            th2s[0], n2 = math.atan2(-P, Q), 1
        elif careful[i] == 3.0 or careful[i] == 5.0:
            th2s[0], n2 = math.atan2(P, -Q), 1
        else:
            th2s[0] = math.atan2(-P, Q) if abs(a * N + g) <= abs(a * N - g) else math.atan2(P, -Q)
            n2 = 1
        if weak:
            # Eq 8 vanishes (P = Q = 0): theta2 from Eq 11 alone, a + b c2 + c s2 = 0
            r = math.hypot(b, co[12])
            phi = math.atan2(co[12], b)
            acs = math.acos(min(max(-a / r if r > 0 else 0.0, -1.0), 1.0))
            th2s[n2], th2s[n2 + 1] = phi + acs, phi - acs
            n2 += 2
        for k in range(n2):
            t2 = wrap(th2s[k])
            c2, s2 = math.cos(t2), math.sin(t2)
            for branch in range(2):
                if nc >= MAX_CAND:
                    return nc
                q[0], q[1] = th1[i], t2
                _wrist(Ru, co, L, C, S, c2, s2, branch, q)  # (both branches: near a continuum
                # they are distinct solutions; on it they merge as one continuum)
                prio = 0.0 if careful[i] >= 4.0 else 1.0
                nc = _add_candidate(q, careful[i] != 0.0 or weak, prio, L, dh, Ru, T, opt, cand, nc, ws, wm,
                                    best)
    return nc


@_inner
def _continua(T, L, dh, lo, hi, opt, ws, wm, cand, nc):
    """Flag and resolve the continua among the exact candidates.

    theta3/theta6: theta4 = 0 and theta4 + theta5 = 0 (mod pi), joints 3 and 6 collinear; kept
    as a continuum only if the snapped representative reaches the pose (then every member
    does). theta1/theta6: the tool point on the joint-1 axis and z6 vertical, to within half
    the tolerance (then every member is within it).
    """
    Ru, q, T4 = wm[_M_RU, :3, :3], ws[_W_Q:_W_Q + 6], wm[_M_T4, :4, :4]
    tp, tr, ltol = opt[OPT_POSITION_TOL], opt[OPT_ROTATION_TOL], opt[OPT_LIMIT_TOL]
    pxy = math.hypot(T[0, 3], T[1, 3])
    tilt = math.hypot(Ru[0, 2], Ru[1, 2])
    for i in range(nc):
        c = cand[i]
        if c[_C_CLASS] != 1.0:
            continue
        s4, s45 = abs(math.sin(c[3])), abs(math.sin(c[3] + c[4]))
        if s4 <= NUMERICAL_SIN and s45 <= NUMERICAL_SIN and (s4 > CONTINUUM_SIN or s45 > CONTINUUM_SIN):
            c[_C_FREE] = NUMERICAL_Q3_Q6
        elif s4 <= CONTINUUM_SIN and s45 <= CONTINUUM_SIN:
            for j in range(6):
                q[j] = c[j]
            s4 = round(q[3] / math.pi) * math.pi
            s45 = round((q[3] + q[4]) / math.pi) * math.pi
            q[3], q[4] = s4, s45 - s4
            _polish(q, L, dh, Ru, T, ws, wm, _COLS_126, 3, 6)  # refit theta1, theta2, theta6
            pres, rres = _residuals(q, L, Ru, T, T4)
            if pres <= tp and rres <= tr:
                for j in range(6):
                    c[j] = q[j]
                c[_C_PRES], c[_C_RRES], c[_C_FREE] = pres, rres, FREE_Q3_Q6
            else:  # a numerical continuum: flagged, not resolved (no exact members)
                c[_C_FREE] = NUMERICAL_Q3_Q6
        if 2 * pxy + c[_C_PRES] <= tp and 2 * tilt + c[_C_RRES] <= tr and c[_C_FREE] != NUMERICAL_Q3_Q6:
            c[_C_FREE] = int(c[_C_FREE]) | FREE_Q1_Q6
        f = int(c[_C_FREE])
        if f != 0 and f != NUMERICAL_Q3_Q6:
            if f & FREE_Q1_Q6:
                _resolve_continuum(c, L, Ru, T, ws, wm, lo, hi, 0, _C_S1, ltol)
            if f & FREE_Q3_Q6:
                _resolve_continuum(c, L, Ru, T, ws, wm, lo, hi, 2, _C_S3, ltol)
            c[_C_PRES], c[_C_RRES] = _residuals(c, L, Ru, T, T4)


@_inner
def _beyond(T, reach):
    """Is the position of T farther than ``reach`` from the base origin (no overflow)?"""
    x, y, z = abs(T[0, 3]), abs(T[1, 3]), abs(T[2, 3])
    if max(x, y, z) > reach:
        return True
    return x * x + y * y + z * z > reach * reach


@_inner
def _solve_pose(T, L, dh, lo, hi, reach, opt, within_only, ws, wm, cand, idx, outq, info, flags, hdr):
    """Every IK solution of one pose into outq (k, 6), info (k, N_INFO) and flags (k, 2)
    (within the limits, approximate); header into hdr."""
    for i in range(N_HDR):
        hdr[i] = 0.0
    Ru, T4 = wm[_M_RU, :3, :3], wm[_M_T4, :4, :4]
    status, measure, dist = _check_pose(T, opt[OPT_ORTHONORMAL_TOL], Ru)
    hdr[H_STATUS], hdr[H_MEASURE], hdr[H_PROJECTION] = status, measure, dist
    hdr[H_BEST_P], hdr[H_BEST_R] = np.inf, np.inf
    if status != OK or _beyond(T, reach + opt[OPT_APPROX_TOL]):
        return 0  # (beyond the reach bound: unreachable, without arithmetic on huge numbers)
    nc = _configurations(T, L, dh, opt, ws, wm, cand, hdr[H_BEST_P:H_BEST_R + 1])
    _continua(T, L, dh, lo, hi, opt, ws, wm, cand, nc)
    k = _distinct_sorted(cand, nc, 1.0, L, Ru, T, ws, wm, opt, idx)
    hdr[H_TOTAL] = k
    approx, m, ltol, nfree = False, 0, opt[OPT_LIMIT_TOL], 0
    for r in range(2):
        for ii in range(k):
            c = int(idx[ii])
            inside = _within(cand[c], lo, hi, ltol)
            if within_only and not inside:
                continue
            for j in range(6):
                outq[m, j] = cand[c, j]
            if dist == 0.0:  # the rotation was used as given: the residuals are the candidate's
                info[m, I_PRES], info[m, I_RRES] = cand[c, _C_PRES], cand[c, _C_RRES]
            else:  # residuals against the pose as given
                _fk_into(outq[m], L, T4)
                info[m, I_PRES], info[m, I_RRES] = _position_error(T4, T), _rotation_angle(T4, T[:3, :3])
            info[m, I_FREE] = cand[c, _C_FREE]
            nfree += cand[c, _C_FREE] != 0.0
            for j in range(6):
                info[m, I_S1 + j] = cand[c, _C_S1 + j]
            flags[m, 0], flags[m, 1] = inside, approx
            m += 1
        if m > 0 or r == 1:
            break
        # nothing exact (within the limits if asked): the least-residual configurations, flagged
        k = _distinct_sorted(cand, nc, 2.0, L, Ru, T, ws, wm, opt, idx)
        approx = True
    hdr[H_COUNT], hdr[H_FREE], hdr[H_APPROX] = m, nfree, 1.0 if approx and m > 0 else 0.0
    return m


@_inner
def _pad(outq, info, flags, m):
    """Rows m.. of one pose's outputs: NaN, free kind 0, flags False (the padding of :class:`IKBatch`)."""
    for r in range(m, outq.shape[0]):
        for j in range(6):
            outq[r, j] = np.nan
        for j in range(N_INFO):
            info[r, j] = np.nan
        info[r, I_FREE] = 0.0
        flags[r, 0], flags[r, 1] = False, False


@_entry(_nrt=False)
def solve_many(Ts, armv, opt, within_only, scratch, outq, info, flags, hdr):
    """:func:`_solve_pose` for poses Ts (n, 4, 4) into padded outq (n, 16, 6), info
    (n, 16, N_INFO), flags (n, 16, 2) bool and hdr (n, N_HDR): a serial loop (one pose: n = 1).
    Rows past a pose's count are padding (NaN, free kind 0, False).

    ``armv``: :attr:`ArmData.vector`; ``opt``: the option vector (OPT_*); ``scratch``
    (N_SCRATCH,) float64 is working memory, allocated by the caller: the kernel runs without
    Numba's reference counting, which would cost more than the arithmetic.
    """
    L, lo, hi, dh, reach = armv[0:5], armv[5:11], armv[11:17], armv[17:41].reshape((6, 4)), armv[REACH]
    ws = scratch[0:N_WORK]
    wm = scratch[N_WORK:N_WORK + N_MATS * 81].reshape((N_MATS, 9, 9))
    o = N_WORK + N_MATS * 81
    cand = scratch[o:o + MAX_CAND * N_CAND].reshape((MAX_CAND, N_CAND))
    idx = scratch[o + MAX_CAND * N_CAND:N_SCRATCH]
    for i in range(Ts.shape[0]):
        _solve_pose(Ts[i], L, dh, lo, hi, reach, opt, within_only, ws, wm, cand, idx, outq[i], info[i],
                    flags[i], hdr[i])
        _pad(outq[i], info[i], flags[i], int(hdr[i, H_COUNT]))


_SCRATCH = None


def work_counts(reset: bool = False) -> dict[str, int]:
    """The work counters of :func:`scratch` (:data:`STATS`, cumulative over the serial calls of
    this process; ``reset`` zeroes them after reading): what a profile of the kernel reads."""
    w = scratch()[_W_STATS:_W_STATS + len(STATS)]
    out = {k: int(v) for k, v in zip(STATS, w, strict=True)}
    if reset:
        w[:] = 0.0
    return out


def scratch() -> np.ndarray:
    """The working memory of :func:`solve_many` (one buffer: the kernel holds the GIL)."""
    global _SCRATCH
    if _SCRATCH is None:
        _SCRATCH = np.zeros(N_SCRATCH)
    return _SCRATCH


@_entry(parallel=True)
def solve_many_parallel(Ts, armv, opt, within_only, outq, info, flags, hdr):
    """:func:`solve_many` on all cores (``numba.prange`` over chunks of 64 poses)."""
    L, lo, hi, dh, reach = armv[0:5], armv[5:11], armv[11:17], armv[17:41].reshape((6, 4)), armv[REACH]
    n = Ts.shape[0]
    chunk = 64
    for c in numba.prange((n + chunk - 1) // chunk):
        ws = np.zeros(N_WORK)
        wm = np.zeros((N_MATS, 9, 9))
        cand = np.zeros((MAX_CAND, N_CAND))
        idx = np.zeros(MAX_CAND)
        for i in range(c * chunk, min(n, (c + 1) * chunk)):
            _solve_pose(Ts[i], L, dh, lo, hi, reach, opt, within_only, ws, wm, cand, idx, outq[i], info[i],
                        flags[i], hdr[i])
            _pad(outq[i], info[i], flags[i], int(hdr[i, H_COUNT]))
