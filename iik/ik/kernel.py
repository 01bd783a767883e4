"""The compiled kernel (Numba): forward kinematics, Jacobians and the complete IK of any arm of
the class (``docs/IK_CLASS.md``).

Everything here is scalar code compiled with ``numba.njit``; the public functions live in
:mod:`iik.kinematics` and :mod:`iik.ik.solve`, which call this module (imported on first
use, so ``import iik`` does not load Numba). Units: metres and radians. Names of outputs,
codes and the arm vector: :mod:`iik.ik.layout`.

The complete IK of one pose (:func:`solve_many`; :func:`solve_many_parallel` on all cores):

1. **Pose** (:func:`_check_pose`): finite, bottom row, rotation orthonormal to
   ``orthonormal_tol`` and proper; replaced by the nearest rotation. The solver chain's pose
   (the tool pose, or its inverse for an arm read from the flange, between the solver
   chain's fixed base and tool transforms) gives the wrist point D and the axis z6.
2. **Eliminant** (:mod:`iik.ik.elimination`, :mod:`iik.ik.eliminant`): 18 first-degree
   coefficients; on each half circle theta_r + [-pi/2, pi/2] (theta_r = PSI, PSI + pi) F is
   a degree-8 Bernstein polynomial with a rounding-error bound.
3. **Certified isolation** (:mod:`iik.ik.bernstein`): every real root in a root leaf (one
   each, refined) or a cluster; every place where |F| comes within the tolerance-derived
   near threshold in a leaf. Clusters are re-expanded in double-double arithmetic
   (:mod:`iik.ik.ddarith`) and isolated again there (``PATH_EXTENDED``); a cluster still
   unresolved is a multiple root to ~1e-15 (``PATH_MULTIPLE``), tried as one candidate.
4. **Closed forms** (:func:`_closed_form`): theta2 from the two linear conditions (Cramer;
   where they are nearly parallel, each line's intersections with the circle too), theta3
   from z4 (both signs: the two wrist branches), theta4, theta5, theta6 from the frames.
5. **Verification**: every configuration's forward kinematics (the user's chain) against the
   pose as given; a configuration that misses by a little is polished by Newton /
   Levenberg-Marquardt steps on the full FK. Within (position_tol, rotation_tol): a
   solution; within approximate_tol: approximate (returned only when nothing is exact).
6. **Certificate**: every certified simple root gave a solution (else the root is refined in
   double-double and tried again; ``H_CERT`` says if it still failed). No cluster rule drops
   a root: rows are merged only when they agree to DISTINCT_TOL.
7. **Continua**: joints 3 and 6 collinear (D on axis 3 and z6 along it): theta3 free, theta6
   following; the eliminant vanishing identically (``PATH_DEGENERATE``): theta1 free.

**Compilation and cache.** Each entry point compiles on its first call and is cached on disk:
next to this file when that folder is writable, else in the user cache folder. The cache key
hashes every source file compiled into the entry points (:data:`SOURCES`).
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass

import numba
import numpy as np
from numba.core import caching as _nb_caching

from . import angles as _angles
from . import bernstein as _bz
from . import chain as _ch
from . import ddarith as _dd
from . import eliminant as _em
from . import elimination as _el
from . import layout as L

__all__ = [
    "ArmData",
    "arm_data",
    "fk_many",
    "jacobian_many",
    "solve_many",
    "solve_many_parallel",
    "continuum_members",
    "closed_form_march",
    "scratch",
    "work_counts",
    "STATS",
    "SOURCES",
]

# ----------------------------------------------------------------------------- cache
#: Every source file whose code the kernel compiles (the cache key hashes them all).
SOURCES = (__file__, _angles.__file__, _bz.__file__, _ch.__file__, _dd.__file__, _em.__file__, _el.__file__,
           L.__file__)


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


# ----------------------------------------------------------------------------- arm data
@dataclass(frozen=True)
class ArmData:
    """An arm as the kernel's read-only float vector (layout: :mod:`iik.ik.layout`, ``A_*``).

    Attributes:
        vector: (N_ARM,) the user chain, the solver chain, limits, reach and the eliminant's
            arm constants.
    """

    vector: np.ndarray


_ARM_DATA: dict[int, tuple[object, ArmData]] = {}


def arm_data(arm) -> ArmData:
    """The kernel's view of ``arm`` (an :class:`iik.arm.Arm`; built once per arm object)."""
    hit = _ARM_DATA.get(id(arm))
    if hit is not None and hit[0] is arm:
        return hit[1]
    v = np.ascontiguousarray(arm.kernel_vector(), dtype=np.float64).copy()
    if v.shape != (L.N_ARM,):
        raise ValueError(f"arm vector has shape {v.shape}, expected ({L.N_ARM},)")
    v.setflags(write=False)
    data = ArmData(v)
    if len(_ARM_DATA) > 64:
        _ARM_DATA.clear()
    _ARM_DATA[id(arm)] = (arm, data)
    return data


# ----------------------------------------------------------------------------- FK, Jacobians
@_inner
def _finite_rows(Q) -> bool:
    for i in range(Q.shape[0]):
        for j in range(6):
            if not math.isfinite(Q[i, j]):
                return False
    return True


@_entry()
def fk_many(Q, v, T) -> bool:
    """Forward kinematics of q (n, 6) [rad] into T (n, 4, 4) [m] for the user chain of the arm
    vector v; False (T untouched) if some q is not finite."""
    if not _finite_rows(Q):
        return False
    for i in range(Q.shape[0]):
        _ch.pose_into(_ch.chain_pose(Q[i], v, L.A_USER_DH, L.A_USER_BASE, L.A_USER_TOOL), T[i])
    return True


@_entry()
def jacobian_many(Q, v, J) -> bool:
    """Geometric Jacobians of q (n, 6) into J (n, 6, 6) (rows [v; w], base-frame axes, at the
    tool point); False if some q is not finite."""
    if not _finite_rows(Q):
        return False
    for i in range(Q.shape[0]):
        _ch.jacobian_into(Q[i], v, L.A_USER_DH, L.A_USER_BASE, L.A_USER_TOOL, J[i])
    return True


# ============================================================================= complete IK
#: Most theta1 candidates per pose.
_MAX_T1 = 48
#: Most configurations per pose (theta1 candidates x theta2 options x 2 wrist branches, and
#: the restarts near a collinear continuum).
MAX_CAND = 320
# Columns of the candidate table: q, residuals against the pose as given, class (1 exact,
# 2 approximate), continuum kind, candidate kind, smallest singular value, continuum sign,
# interval of the free joint, the theta1 candidate it came from.
_C_PRES, _C_RRES, _C_CLASS, _C_FREE, _C_KIND, _C_H3 = 6, 7, 8, 9, 10, 11
_C_SIGN, _C_LO, _C_HI, _C_ROOT = 12, 13, 14, 15
N_CAND = 16


def _layout(*sizes):
    """Offsets of consecutive regions of the given sizes, and the total."""
    out, o = [], 0
    for n in sizes:
        out.append(o)
        o += n
    return (*out, o)


# Scratch layout (one float64 buffer per serial loop, carved into views): pose terms and
# magnitudes, theta1 candidates and kinds, theta2 options, q work vectors, Bernstein work,
# leaves, stacks, Newton / LM vectors, work counters, an index buffer.
(
    _W_TERMS,
    _W_MAGS,
    _W_TH1,
    _W_KIND,
    _W_TH2,
    _W_Q,
    _W_Q2,
    _W_BW,
    _W_B,
    _W_M,
    _W_BL,
    _W_LEAF,
    _W_LEAF2,
    _W_STACK,
    _W_DD,
    _W_E,
    _W_DQ,
    _W_G,
    _W_ET,
    _W_QT,
    _W_STATS,
    _W_QR,
    _W_QB,
    _W_REL,
    _W_IDX,
    _W_CAND,
    N_SCRATCH,
) = _layout(
    18,
    18,
    _MAX_T1,
    _MAX_T1,
    8,
    6,
    6,
    60,
    9,
    9,
    9,
    _bz.N_LEAF * _bz.LEAF_WIDTH,
    _bz.N_LEAF * _bz.LEAF_WIDTH,
    96 * 12,
    60 * 2,
    6,
    6,
    6,
    6,
    6,
    16,
    6,
    6,
    _MAX_T1,
    MAX_CAND,
    MAX_CAND * N_CAND,
)
#: Work counters (cumulative, in the scratch buffer; :func:`work_counts`): what a profile reads.
STATS = (
    "poses",
    "theta1 candidates",
    "configurations",
    "polishes",
    "polish iterations",
    "extended clusters",
    "multiple roots",
    "near candidates",
    "degenerate poses",
    "certificate retries",
    "certificate failures",
    "poses on the extended path",
    "tube restarts",
    "theta2 restarts",
)
N_STATS = 16  # (room for the counters of STATS)
# matrix scratch (5, 6, 6): projected rotation, solver pose, Jacobian, normal equations, spare
_M_RU, _M_RC, _M_J, _M_A, _M_X = 0, 1, 2, 3, 4
N_MATS = 5

_TWO_PI = 2.0 * math.pi
_EPS = 2.220446049250313e-16
#: Reference angle of the first half circle (the second is PSI + pi): boundaries at
#: PSI +- pi/2, away from round angles a user is likely to type.
PSI = 0.3
_CPSI, _SPSI = math.cos(PSI), math.sin(PSI)
_PSI = math.atan2(_SPSI, _CPSI)

#: |h| (z6 or (D - C) / a4 across z3) below this: theta3 is free at the configuration [1].
FREE_TOL = 1e-9
#: Shared with the reference (:mod:`iik.ik.layout` says what they mean).
CONTINUUM_NEAR, RESTART_H, VANISH, NEAR_FREE2 = L.CONTINUUM_NEAR, L.RESTART_H, L.VANISH, L.NEAR_FREE2
#: The two conditions on theta2 are nearly parallel below this sine of their angle: each
#: condition's intersections with the unit circle are tried too.
PARALLEL = 1e-3
#: Configurations farther than this from the pose after the closed forms are not polished
#: [m per m of reach, rad].
NEAR_POSITION = 1e-3
NEAR_ROTATION = 1e-2
#: Rows closer than this [rad] joined by a segment within the tolerance are one solution.
CONNECTED = 1e-3
#: Steps of the path along a curved valley between two such rows (:func:`_bent_path`).
BENT_STEPS = 8
#: Near threshold of the isolation: |F| within this many (tolerance / reach) of its magnitude.
NEAR_FACTOR = 64.0
#: Certified roots closer than this in joint 1 [rad] are one for the certificate (a near-double
#: root on the singular set, its two roots 1e-8 ... 5e-7 apart: their configurations merge).
SAME_ROOT = 1e-6


wrap = _inner(_angles.wrap)  # the project's one wrap (iik/ik/angles.py), compiled from its source
gap = _inner(_angles.gap)  # |wrap(x)|, the mod form of iik.ik.angles.angle_distance


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
                return L.NONFINITE, 0.0, 0.0
    bot = max(abs(T[3, 0]), abs(T[3, 1]), abs(T[3, 2]), abs(T[3, 3] - 1.0))
    if bot > tol:
        return L.BOTTOM_ROW, bot, 0.0
    err = 0.0
    for i in range(3):
        for j in range(3):
            g = T[0, i] * T[0, j] + T[1, i] * T[1, j] + T[2, i] * T[2, j] - (1.0 if i == j else 0.0)
            err = max(err, abs(g))
    if err > tol:
        return L.NOT_ORTHONORMAL, err, 0.0
    det = (
        T[0, 0] * (T[1, 1] * T[2, 2] - T[1, 2] * T[2, 1])
        - T[0, 1] * (T[1, 0] * T[2, 2] - T[1, 2] * T[2, 0])
        + T[0, 2] * (T[1, 0] * T[2, 1] - T[1, 1] * T[2, 0])
    )
    if det < 0.0:
        return L.REFLECTION, err, 0.0
    for i in range(3):
        for j in range(3):
            Ru[i, j] = T[i, j]
    if err <= 64 * _EPS:
        return L.OK, err, 0.0
    _polar(Ru)
    dist = 0.0
    for i in range(3):
        for j in range(3):
            dist += (T[i, j] - Ru[i, j]) ** 2
    return L.OK, err, math.sqrt(dist)


@_inner
def _polar(Ru) -> None:
    """Ru (3, 3) replaced by its polar factor, the nearest rotation (Newton's iteration
    ``X <- (X + X^-T) / 2``, to 4 eps)."""
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
        step = max(
            abs(Ru[0, 0] - a),
            abs(Ru[0, 1] - b),
            abs(Ru[0, 2] - c),
            abs(Ru[1, 0] - d),
            abs(Ru[1, 1] - e),
            abs(Ru[1, 2] - f),
            abs(Ru[2, 0] - g),
            abs(Ru[2, 1] - h),
            abs(Ru[2, 2] - k),
        )
        if step <= 4 * _EPS:
            break


# ----------------------------------------------------------------------------- linear algebra
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


# ----------------------------------------------------------------------------- residuals, polish
@_inner
def _residuals(q, v, Ru, T):
    """(position [m], rotation [rad]) residuals of the user chain's fk(q) against (Ru, p of T)."""
    r = _ch.chain_pose(q, v, L.A_USER_DH, L.A_USER_BASE, L.A_USER_TOOL)
    return _ch.position_error_12(r, T), _ch.rotation_angle_12(r, Ru)


@_inner
def _pose_error(q, v, Ru, T, e):
    _ch.pose_error_vector(_ch.chain_pose(q, v, L.A_USER_DH, L.A_USER_BASE, L.A_USER_TOOL), Ru, T, e)


@_inner
def _polish(q, v, Ru, T, ws, wm, cols, n, iters, target):
    """Levenberg-Marquardt on the user chain's FK over joints ``cols[:n]``; q in place, wrapped.

    The first try of every iteration is the Newton step (J^-1 e; least squares for fewer
    joints or a singular J); a step that does not reduce the pose error is rejected and
    retried with more damping (so a near-singular valley is not jumped across). Stops when
    the error vector is below ``target`` [m, rad], a step is below 1e-14 rad, or the damping
    has grown without progress.
    """
    J, A = wm[_M_J], wm[_M_A]
    e, dq, g = ws[_W_E : _W_E + 6], ws[_W_DQ : _W_DQ + 6], ws[_W_G : _W_G + 6]
    et, qt = ws[_W_ET : _W_ET + 6], ws[_W_QT : _W_QT + 6]
    st = ws[_W_STATS : _W_STATS + N_STATS]
    st[3] += 1.0
    _pose_error(q, v, Ru, T, e)
    err = _sq(e)
    lam = 0.0
    fresh = False
    goal = target * target
    for _ in range(iters):
        if err <= goal:
            break
        st[4] += 1.0
        if not fresh:
            _ch.jacobian_into(q, v, L.A_USER_DH, L.A_USER_BASE, L.A_USER_TOOL, J)
        fresh = True
        if lam > 0.0 or n < 6 or not _newton_step(J, e, dq, A, g):
            _least_squares_step(J, e, cols, n, dq, A, g, lam)
        for j in range(6):
            qt[j] = q[j]
        big = 0.0
        for a in range(n):
            qt[cols[a]] += dq[a]
            big = max(big, abs(dq[a]))
        _pose_error(qt, v, Ru, T, et)
        errt = _sq(et)
        if errt <= err:
            for j in range(6):
                q[j], e[j] = qt[j], et[j]
            err, fresh = errt, False
            lam = 0.0 if lam <= 1e-10 else 0.1 * lam
            if big <= 1e-14:
                break
        else:
            if big <= 1e-14:
                break
            lam = 1e-10 if lam == 0.0 else 10.0 * lam
            if lam > 1e4:
                break
    for j in range(6):
        q[j] = wrap(q[j])


# ----------------------------------------------------------------------------- solver pose
@_inner
def _inverse(r):
    """Inverse of the rigid transform r (12-tuple)."""
    r00, r01, r02, r10, r11, r12, r20, r21, r22, px, py, pz = r
    return (
        r00,
        r10,
        r20,
        r01,
        r11,
        r21,
        r02,
        r12,
        r22,
        -(r00 * px + r10 * py + r20 * pz),
        -(r01 * px + r11 * py + r21 * pz),
        -(r02 * px + r12 * py + r22 * pz),
    )


@_inner
def _solver_pose(T, Ru, v):
    """The solver chain's frame-6 pose in its frame 0 (12-tuple) for the pose (Ru, p of T):
    ``B_s^-1 X T_s^-1`` with X the pose, or its inverse for an arm solved from the flange."""
    x = (
        Ru[0, 0],
        Ru[0, 1],
        Ru[0, 2],
        Ru[1, 0],
        Ru[1, 1],
        Ru[1, 2],
        Ru[2, 0],
        Ru[2, 1],
        Ru[2, 2],
        T[0, 3],
        T[1, 3],
        T[2, 3],
    )
    if v[L.A_REVERSED] != 0.0:
        x = _inverse(x)
    x = _ch.compose_fixed(_ch.load_fixed(v, L.A_SOLVER_BASE_INV), x)
    return _ch.compose_fixed(x, _ch.load_fixed(v, L.A_SOLVER_TOOL_INV))


@_inner
def _to_user(qc, q, v) -> None:
    """User joint angles q (6,) from the solver chain's joint angles qc (6,) (wrapped)."""
    if v[L.A_REVERSED] != 0.0:
        for j in range(6):
            q[j] = wrap(qc[5 - j])
    else:
        for j in range(6):
            q[j] = wrap(qc[j])


@_inner
def _to_solver(q, qc, v) -> None:
    if v[L.A_REVERSED] != 0.0:
        for j in range(6):
            qc[j] = q[5 - j]
    else:
        for j in range(6):
            qc[j] = q[j]


@_inner
def _user_col(v, j):
    """The user joint index of solver joint j (0-based)."""
    return 5 - j if v[L.A_REVERSED] != 0.0 else j


# ----------------------------------------------------------------------------- closed forms
@_inner
def _row(v, i):
    o = L.A_SOLVER_DH + 5 * i
    return v[o], v[o + 1], v[o + 2], v[o + 3], v[o + 4]


@_inner
def _in_plane(r, wx, wy, wz, s):
    """(cos, sin, angle) of the joint angle that turns the link frame r (at angle 0) so that the
    next axis, ``(s sin, -s cos, 0)`` in r for a 90-deg twist of sign s, points along w."""
    x = s * (r[0] * wx + r[3] * wy + r[6] * wz)
    y = -s * (r[1] * wx + r[4] * wy + r[7] * wz)
    n = math.hypot(x, y)
    if n == 0.0:
        return 1.0, 0.0, 0.0
    return y / n, x / n, math.atan2(x, y)


@_inner
def _upper_arm(C1, S1, c2, s2, P, v):
    """Frames 2 and 3 (at joint 3's angle 0) of the solver chain for joints 1 and 2 at DH angles
    with (cos, sin) (C1, S1), (c2, s2), and the wrist point's offset across axis 3:
    ``(r2, r30, D - C, h, |h|)`` with h the larger of z6 and (D - C) / a4 across z3 [1]."""
    ca, sa, a, d, _ = _row(v, 0)
    r = _ch.compose_link(_ch.IDENTITY, ca, sa, a, d, C1, S1)
    ca, sa, a, d, _ = _row(v, 1)
    r2 = _ch.compose_link(r, ca, sa, a, d, c2, s2)
    ca, sa, a, d, _ = _row(v, 2)
    r30 = _ch.compose_link(r2, ca, sa, a, d, 1.0, 0.0)
    z3x, z3y, z3z = r30[2], r30[5], r30[8]
    zx, zy, zz = P[2], P[5], P[8]
    ex, ey, ez = P[9] - r30[9], P[10] - r30[10], P[11] - r30[11]  # D - C
    a4 = v[L.A_SOLVER_DH + 5 * 4 + 2]
    k6 = zx * z3x + zy * z3y + zz * z3z
    h6x, h6y, h6z = zx - k6 * z3x, zy - k6 * z3y, zz - k6 * z3z
    kD = ex * z3x + ey * z3y + ez * z3z
    hDx, hDy, hDz = (ex - kD * z3x) / a4, (ey - kD * z3y) / a4, (ez - kD * z3z) / a4
    n6 = math.sqrt(h6x * h6x + h6y * h6y + h6z * h6z)
    nD = math.sqrt(hDx * hDx + hDy * hDy + hDz * hDz)
    h = (h6x, h6y, h6z) if n6 >= nD else (hDx, hDy, hDz)
    return r2, r30, (ex, ey, ez), h, max(n6, nD)


@_inner
def _wrist(r30, e, h, hmax, branch, P, v, qc) -> None:
    """Solver joints 3-6 into qc[2:6] for one wrist branch (the sign of z4 = +-(z3 x h) / |h|),
    from the frames of :func:`_upper_arm`; joint 3 at its offset (angle 0) where it is free."""
    z3x, z3y, z3z = r30[2], r30[5], r30[8]
    hx, hy, hz = h
    ex, ey, ez = e
    ca4, sa4, a4_, d4, o4 = _row(v, 3)
    o3 = v[L.A_SOLVER_DH + 14]
    if hmax <= FREE_TOL:  # theta3 free: the representative has joint 3 at 0
        c3, s3, t3 = math.cos(o3), math.sin(o3), o3
    else:
        sg = 1.0 if branch == 0 else -1.0
        c3, s3, t3 = _in_plane(
            r30, sg * (z3y * hz - z3z * hy), sg * (z3z * hx - z3x * hz), sg * (z3x * hy - z3y * hx), sa4
        )
    r3 = _ch.turn(r30, c3, s3)
    r40 = _ch.compose_link(r3, ca4, sa4, a4_, d4, 1.0, 0.0)
    a4 = v[L.A_SOLVER_DH + 5 * 4 + 2]
    x = (r40[0] * ex + r40[3] * ey + r40[6] * ez) / a4  # x4 along (D - C) / a4
    y = (r40[1] * ex + r40[4] * ey + r40[7] * ez) / a4
    nn = math.hypot(x, y)
    c4, s4 = (x / nn, y / nn) if nn > 0.0 else (1.0, 0.0)
    r4 = _ch.turn(r40, c4, s4)
    ca5, sa5, a5, d5, o5 = _row(v, 4)
    r50 = _ch.compose_link(r4, ca5, sa5, a5, d5, 1.0, 0.0)
    ca6, sa6, a6, d6, o6 = _row(v, 5)
    c5, s5, t5 = _in_plane(r50, P[2], P[5], P[8], sa6)
    r60 = _ch.compose_link(_ch.turn(r50, c5, s5), ca6, sa6, a6, d6, 1.0, 0.0)
    m00 = r60[0] * P[0] + r60[3] * P[3] + r60[6] * P[6]
    m10 = r60[1] * P[0] + r60[4] * P[3] + r60[7] * P[6]
    qc[2], qc[3] = t3 - o3, math.atan2(y, x) - o4
    qc[4], qc[5] = t5 - o5, math.atan2(m10, m00) - o6


@_inner
def _closed_form(t1, c2, s2, branch, P, v, qc):
    """Solver joint angles qc (6,) of one configuration: joint 1 at DH angle t1, joint 2 at the
    DH angle with (cos, sin) (c2, s2), wrist branch ``branch``; returns how far joint 3 is from
    free (:func:`_upper_arm`)."""
    r2, r30, e, h, hmax = _upper_arm(math.cos(t1), math.sin(t1), c2, s2, P, v)
    _wrist(r30, e, h, hmax, branch, P, v, qc)
    qc[0], qc[1] = t1 - v[L.A_SOLVER_DH + 4], math.atan2(s2, c2) - v[L.A_SOLVER_DH + 9]
    return hmax


# ----------------------------------------------------------------------------- theta2 options
@_inner
def _line_circle(al, be, ga, out, n):
    """Points of the unit circle on the line al x + be y = ga (or the closest one) as angles
    appended to out; the new count."""
    nn = math.hypot(al, be)
    if nn == 0.0 or not math.isfinite(nn):
        return n
    d = ga / nn
    fx, fy = d * al / nn, d * be / nn
    if abs(d) >= 1.0:
        out[n] = math.atan2(fy, fx)
        return n + 1
    hh = math.sqrt((1.0 - d) * (1.0 + d))
    tx, ty = -be / nn, al / nn
    out[n] = math.atan2(fy + hh * ty, fx + hh * tx)
    out[n + 1] = math.atan2(fy - hh * ty, fx - hh * tx)
    return n + 2


@_inner
def _conditions_at(terms, t1, t2):
    """The two conditions on (theta1, theta2) (DH angles) and their partial derivatives:
    ``(G1, G1_1, G1_2, G2, G2_1, G2_2)`` with G1 = R + P c2 + Q s2 (coplanarity, the general
    Eq 8) and G2 = a + b c2 + c s2 (length, the general Eq 11)."""
    C, S, c2, s2 = math.cos(t1), math.sin(t1), math.cos(t2), math.sin(t2)
    v = terms
    a, b, c = v[0] + v[1] * C + v[2] * S, v[3] + v[4] * C + v[5] * S, v[6] + v[7] * C + v[8] * S
    P, Q, R = v[9] + v[10] * C + v[11] * S, v[12] + v[13] * C + v[14] * S, v[15] + v[16] * C + v[17] * S
    a1, b1, c1 = -v[1] * S + v[2] * C, -v[4] * S + v[5] * C, -v[7] * S + v[8] * C
    P1, Q1, R1 = -v[10] * S + v[11] * C, -v[13] * S + v[14] * C, -v[16] * S + v[17] * C
    return (
        R + P * c2 + Q * s2,
        R1 + P1 * c2 + Q1 * s2,
        -P * s2 + Q * c2,
        a + b * c2 + c * s2,
        a1 + b1 * c2 + c1 * s2,
        -b * s2 + c * c2,
    )


@_inner
def _refine_12(terms, t1, t2):
    """(theta1, theta2) refined by Newton's method on the two unsquared conditions (at most 4
    steps, each kept only if it reduces them): a root of the eliminant is only as accurate as
    the squared F is steep; the pair of first-degree conditions is not squared."""
    g1, a11, a12, g2, a21, a22 = _conditions_at(terms, t1, t2)
    err = abs(g1) + abs(g2)
    for _ in range(4):
        det = a11 * a22 - a12 * a21
        if det == 0.0 or err == 0.0:
            break
        d1 = (g1 * a22 - g2 * a12) / det
        d2 = (a11 * g2 - a21 * g1) / det
        if not (abs(d1) <= 1e-3 and abs(d2) <= 1e-3):
            break
        n1, n2 = t1 - d1, t2 - d2
        h1, b11, b12, h2, b21, b22 = _conditions_at(terms, n1, n2)
        e = abs(h1) + abs(h2)
        if e >= err:
            break
        t1, t2, g1, a11, a12, g2, a21, a22, err = n1, n2, h1, b11, b12, h2, b21, b22, e
        if abs(d1) + abs(d2) <= 1e-15:
            break
    return t1, t2


@_inner
def _theta2_options(terms, th, kind, out):
    """DH angles of joint 2 to try at joint 1's DH angle th (into out (8,)): (the count, or -1
    when both conditions vanish; how small they are, :func:`_relative`, the larger of the two).

    Cramer's rule on the two conditions ``P c2 + Q s2 = -R`` and ``b c2 + c s2 = -a``; where
    they are nearly parallel (or for a candidate that is not a certified simple root) each
    condition's points on the unit circle as well."""
    C, S = math.cos(th), math.sin(th)
    a = _el.first_degree_at(terms[0], terms[1], terms[2], C, S)
    b = _el.first_degree_at(terms[3], terms[4], terms[5], C, S)
    c = _el.first_degree_at(terms[6], terms[7], terms[8], C, S)
    P = _el.first_degree_at(terms[9], terms[10], terms[11], C, S)
    Q = _el.first_degree_at(terms[12], terms[13], terms[14], C, S)
    R = _el.first_degree_at(terms[15], terms[16], terms[17], C, S)
    det = P * c - Q * b
    x, y = Q * a - R * c, R * b - P * a  # (c2, s2) det
    n = 0
    if det != 0.0 and (x != 0.0 or y != 0.0):
        out[0] = math.atan2(y, x) if det > 0.0 else math.atan2(-y, -x)
        n = 1
    if kind != L.KIND_ROOT or abs(det) <= PARALLEL * math.hypot(P, Q) * math.hypot(b, c) or n == 0:
        n = _line_circle(P, Q, -R, out, n)
        n = _line_circle(b, c, -a, out, n)
    rel = max(_relative(a, b, c, terms, 0), _relative(P, Q, R, terms, 9))
    if n == 0 or rel <= VANISH:
        return -1, rel  # both conditions vanish: every theta2 (docs/IK_CLASS.md section 5 C)
    return n, rel


@_inner
def _relative(x, y, z, terms, o):
    """|x| + |y| + |z| of three first-degree values (at theta1) relative to their coefficients'
    size (the largest of terms[o:o + 9])."""
    m = 0.0
    for k in range(9):
        m = max(m, abs(terms[o + k]))
    return (abs(x) + abs(y) + abs(z)) / m if m > 0.0 else 0.0


# ----------------------------------------------------------------------------- theta1 candidates
@_inner
def _push(th1, kinds, n, t, kind):
    """Append candidate t (DH angle of joint 1) of ``kind`` unless the table is full or holds it
    (within 1e-14 rad: the two halves share their end points); the new count."""
    if n >= _MAX_T1:
        return n
    for j in range(n):
        if abs(wrap(th1[j] - t)) <= 1e-14:
            if kind < kinds[j]:
                kinds[j] = kind
            return n
    th1[n], kinds[n] = wrap(t), kind
    return n + 1


@_inner
def _leaves_to_candidates(leaves, nl, u0, w, theta_r, th1, kinds, n, multiple_kind, st):
    """theta1 candidates from isolation leaves of the piece [u0, u0 + w] of a half circle with
    reference angle theta_r; a cluster leaf becomes one ``multiple_kind`` candidate (or -1)."""
    for i in range(nl):
        kind, a, b, e = leaves[i, 0], leaves[i, 1], leaves[i, 2], leaves[i, 3]
        co = leaves[i, 4:13]
        if kind == _bz.LEAF_ROOT:
            s = a + _bz.refine_root(co, e) * (b - a)
            k = L.KIND_ROOT
        elif kind == _bz.LEAF_NEAR:
            s = a + _bz.near_minimum(co) * (b - a)
            k = L.KIND_NEAR
            st[7] += 1.0
        else:
            if multiple_kind < 0:
                continue
            s = 0.5 * (a + b)
            k = multiple_kind
            st[6] += 1.0
        t = 2.0 * (u0 + s * w) - 1.0
        n = _push(th1, kinds, n, theta_r + 2.0 * math.atan(t), k)
    return n


@_inner
def _extended(terms, sgn, u0, u1, mag, thr, theta_r, ws, th1, kinds, n):
    """Re-expand the cluster [u0, u1] of a half circle in double-double and isolate it again;
    its theta1 candidates appended (an unresolved cluster as one multiple root)."""
    st = ws[_W_STATS : _W_STATS + N_STATS]
    st[5] += 1.0
    dd = ws[_W_DD : _W_DD + 120].reshape((60, 2))
    full, tmp, work = dd[0:9], dd[9:18], dd[18:51]
    _em.half_bernstein_dd(terms, _CPSI, _SPSI, sgn, work, full)
    bl = ws[_W_BL : _W_BL + 9]
    u1r, err = _em.dd_piece(full, u0, u1, tmp, bl)
    leaves = ws[_W_LEAF2 : _W_LEAF2 + _bz.N_LEAF * _bz.LEAF_WIDTH].reshape((_bz.N_LEAF, _bz.LEAF_WIDTH))
    stack = ws[_W_STACK : _W_STACK + 96 * 12].reshape((96, 12))
    nl = _bz.isolate(bl, err + _em.DD_GAMMA * mag, thr, leaves, stack)
    if nl < 0:  # too many pieces: the cluster's middle as one multiple root
        st[6] += 1.0
        t = 2.0 * (0.5 * (u0 + u1)) - 1.0
        return _push(th1, kinds, n, theta_r + 2.0 * math.atan(t), L.KIND_MULTIPLE)
    return _leaves_to_candidates(leaves, nl, u0, u1r - u0, theta_r, th1, kinds, n, L.KIND_MULTIPLE, st)


@_inner
def _half_magnitude(mags, half, ws):
    """The largest magnitude coefficient of F on one half circle (its rounding-error scale)."""
    bw, m = ws[_W_BW : _W_BW + 60], ws[_W_M : _W_M + 9]
    _em.half_bernstein(mags, abs(_CPSI), abs(_SPSI), 1.0, 1.0, bw, m)
    out = 0.0
    for i in range(9):
        out = max(out, m[i])
    return out


@_inner
def _flat_half(terms, half, thr, ws):
    """Is F within ``thr`` of zero on one half circle (every Bernstein coefficient)? A pose taken
    for degenerate because F is small against its natural size (P, Q and R of Eq 11 small) but not
    against its own rounding scale has genuine near-double roots: they are searched too."""
    bw, b = ws[_W_BW : _W_BW + 60], ws[_W_B : _W_B + 9]
    _em.half_bernstein(terms, _CPSI, _SPSI, 1.0 if half == 0 else -1.0, -1.0, bw, b)
    for i in range(9):
        if abs(b[i]) > thr:
            return False
    return True


@_inner
def _theta1_candidates(terms, mags, thr_rel, natural, ws, hdr):
    """Every theta1 candidate (DH angle of joint 1) of one pose into ws[_W_TH1:], kinds into
    ws[_W_KIND:]; returns the count, or -1 when F vanishes within the near threshold on the
    whole circle (the degenerate case: below the threshold relative to the larger of its own
    magnitude and ``natural``, the size F has for a pose whose coefficients are of the arm's
    size: a pose where every coefficient of Eq 8 is itself tiny makes F the square of small
    numbers). Header counters: roots, clusters, near candidates."""
    th1, kinds = ws[_W_TH1 : _W_TH1 + _MAX_T1], ws[_W_KIND : _W_KIND + _MAX_T1]
    bw, b, m = ws[_W_BW : _W_BW + 60], ws[_W_B : _W_B + 9], ws[_W_M : _W_M + 9]
    leaves = ws[_W_LEAF : _W_LEAF + _bz.N_LEAF * _bz.LEAF_WIDTH].reshape((_bz.N_LEAF, _bz.LEAF_WIDTH))
    stack = ws[_W_STACK : _W_STACK + 96 * 12].reshape((96, 12))
    st = ws[_W_STATS : _W_STATS + N_STATS]
    n, flat = 0, 0
    for half in range(2):
        sgn = 1.0 if half == 0 else -1.0
        theta_r = _PSI if half == 0 else _PSI + math.pi
        _em.half_bernstein(terms, _CPSI, _SPSI, sgn, -1.0, bw, b)
        _em.half_bernstein(mags, abs(_CPSI), abs(_SPSI), 1.0, 1.0, bw, m)
        mag = 0.0
        big = 0.0
        for i in range(9):
            mag = max(mag, m[i])
            big = max(big, abs(b[i]))
        thr = thr_rel * mag
        if big <= thr_rel * max(mag, natural):
            flat += 1
        nl = _bz.isolate(b, _em.GAMMA * mag, thr, leaves, stack)
        if nl < 0:  # too many pieces: the whole half in double-double
            hdr[L.H_CLUSTERS] += 1.0
            n = _extended(terms, sgn, 0.0, 1.0, mag, thr, theta_r, ws, th1, kinds, n)
            continue
        n = _leaves_to_candidates(leaves, nl, 0.0, 1.0, theta_r, th1, kinds, n, -1, st)
        for i in range(nl):
            if leaves[i, 0] == _bz.LEAF_CLUSTER:
                hdr[L.H_CLUSTERS] += 1.0
                n = _extended(terms, sgn, leaves[i, 1], leaves[i, 2], mag, thr, theta_r, ws, th1, kinds, n)
    if flat == 2:
        return -1
    for i in range(n):
        if kinds[i] == L.KIND_ROOT:
            hdr[L.H_ROOTS] += 1.0
        elif kinds[i] == L.KIND_NEAR:
            hdr[L.H_NEAR] += 1.0
    return n


# ----------------------------------------------------------------------------- configurations
@_inner
def _classify(q, pres, rres, h, kind, root, opt, scale, cand, nc, best):
    """Store configuration q (user joints) in row nc of the candidate table if it solves the
    pose (class 1) or comes within approximate_tol (class 2); the new count."""
    if pres + rres < best[0] + best[1]:
        best[0], best[1] = pres, rres
    if pres <= opt[L.OPT_POSITION_TOL] and rres <= opt[L.OPT_ROTATION_TOL]:
        cls = 1.0
    elif pres <= opt[L.OPT_APPROX_TOL] and rres <= opt[L.OPT_APPROX_TOL]:
        cls = 2.0
    else:
        return nc
    if nc >= MAX_CAND:
        return nc
    for j in range(6):
        cand[nc, j] = q[j]
    cand[nc, _C_PRES], cand[nc, _C_RRES], cand[nc, _C_CLASS] = pres, rres, cls
    near = CONTINUUM_NEAR * math.sqrt(max(opt[L.OPT_POSITION_TOL] / scale, opt[L.OPT_ROTATION_TOL]))
    cand[nc, _C_FREE] = L.FREE_NUMERICAL if h <= near else L.FREE_NONE
    cand[nc, _C_KIND], cand[nc, _C_H3] = kind, h
    cand[nc, _C_SIGN], cand[nc, _C_LO], cand[nc, _C_HI], cand[nc, _C_ROOT] = 0.0, np.nan, np.nan, root
    return nc + 1


@_inner
def _h3_of(q, P, v):
    """How far joint 3 is from free at the user configuration q (:func:`_upper_arm`)."""
    i0, i1 = _user_col(v, 0), _user_col(v, 1)
    t1 = q[i0] + v[L.A_SOLVER_DH + 4]
    t2 = q[i1] + v[L.A_SOLVER_DH + 9]
    return _upper_arm(math.cos(t1), math.sin(t1), math.cos(t2), math.sin(t2), P, v)[4]


@_inner
def _configurations(t1, kind, root, P, terms, v, Ru, T, opt, ws, wm, cand, nc, best, both):
    """Every configuration of one theta1 candidate (both wrist branches of every theta2 option),
    verified against the pose (and polished when it misses by a little) into cand. Near the
    collinear continuum the tube restarts (:func:`_tube_restarts`) start from the last wrist
    branch, or with ``both`` (the degenerate path) from each: there the restarts are what finds
    the band beside the theta1 continuum, and the coupling keeps the sign of joint 5, so the
    restarts of one branch never reach its wrist flip (docs/IK_CLASS.md section 6)."""
    th2, qc, q = ws[_W_TH2 : _W_TH2 + 8], ws[_W_Q2 : _W_Q2 + 6], ws[_W_Q : _W_Q + 6]
    st = ws[_W_STATS : _W_STATS + N_STATS]
    n2, rel = _theta2_options(terms, t1, kind, th2)
    ws[_W_REL + int(root)] = rel
    free2 = n2 < 0
    if free2:  # theta2 free: the member with joint 2 at 0 (flagged), and where joint 3 may be free
        th2[0], n2 = v[L.A_SOLVER_DH + 9], 1
        n2 = _aligned_theta2(t1, P, v, th2, n2)
    iters = 12 if kind == L.KIND_ROOT else 30
    for k in range(n2):
        u1, u2 = _refine_12(terms, t1, th2[k])
        c2, s2 = math.cos(u2), math.sin(u2)
        r2, r30, e, hv, h = _upper_arm(math.cos(u1), math.sin(u1), c2, s2, P, v)
        nb = 2 if h > FREE_TOL else 1
        for branch in range(nb):
            qc[0], qc[1] = u1 - v[L.A_SOLVER_DH + 4], u2 - v[L.A_SOLVER_DH + 9]
            st[2] += 1.0
            _wrist(r30, e, hv, h, branch, P, v, qc)
            _to_user(qc, q, v)
            n0 = nc
            nc = _verified(q, h, kind, root, iters, P, v, Ru, T, opt, ws, wm, cand, nc, best)
            if free2 and k == 0 and nc > n0:
                cand[nc - 1, _C_FREE] = L.FREE_Q2
            if h <= RESTART_H and (both or branch == nb - 1):
                _to_user(qc, q, v)
                nc = _tube_restarts(q, kind, root, P, v, Ru, T, opt, ws, wm, cand, nc, best)
    if not free2 and rel <= NEAR_FREE2:
        nc = _theta2_restarts(t1, kind, root, P, v, Ru, T, opt, ws, wm, cand, nc, best)
    return nc


@_inner
def _theta2_restarts(t1, kind, root, P, v, Ru, T, opt, ws, wm, cand, nc, best):
    """Near a theta2 continuum (both conditions on theta2 nearly vanish at the theta1 candidate
    t1, a DH angle) the pose fixes joint 2 only loosely and the conditions place it poorly: joint
    2 at 16 angles around the circle, both wrist branches, each polished and stored if it
    reaches the pose (not twice)."""
    qc, q = ws[_W_Q2 : _W_Q2 + 6], ws[_W_QR : _W_QR + 6]
    st = ws[_W_STATS : _W_STATS + N_STATS]
    for k in range(16):
        t2 = k * math.pi / 8.0
        r2, r30, e, hv, h = _upper_arm(math.cos(t1), math.sin(t1), math.cos(t2), math.sin(t2), P, v)
        qc[0], qc[1] = t1 - v[L.A_SOLVER_DH + 4], t2 - v[L.A_SOLVER_DH + 9]
        for branch in range(2):
            _wrist(r30, e, hv, h, branch, P, v, qc)
            _to_user(qc, q, v)
            st[13] += 1.0
            n1 = _verified(q, h, kind, root, 30, P, v, Ru, T, opt, ws, wm, cand, nc, best)
            if n1 > nc and not _repeats(cand, nc):
                nc = n1
    return nc


@_inner
def _verified(q, h, kind, root, iters, P, v, Ru, T, opt, ws, wm, cand, nc, best):
    """Configuration q (user joints; h: how far joint 3 is from free there) verified against
    the pose, polished when it misses by a little, and stored if it solves it; the new count."""
    tp, tr = opt[L.OPT_POSITION_TOL], opt[L.OPT_ROTATION_TOL]
    pres, rres = _residuals(q, v, Ru, T)
    if pres > NEAR_POSITION * v[L.A_SCALE] or rres > NEAR_ROTATION:
        if pres + rres < best[0] + best[1]:
            best[0], best[1] = pres, rres
        return nc
    if pres > 1e-3 * tp or rres > 1e-3 * tr:
        _polish(q, v, Ru, T, ws, wm, _ALL6, 6, iters, 1e-3 * min(tp, tr))
        pres, rres = _residuals(q, v, Ru, T)
        h = _h3_of(q, P, v)  # the polish may have moved joints 1 and 2
    return _classify(q, pres, rres, h, kind, root, opt, v[L.A_SCALE], cand, nc, best)


@_inner
def _tube_restarts(q0, kind, root, P, v, Ru, T, opt, ws, wm, cand, nc, best):
    """Near the collinear continuum (joint 3 within RESTART_H of free at the closed forms) the
    pose fixes joint 3 only through the tiny h, and the closed forms place it poorly: the
    configuration q0 is also started with joint 3 turned by k pi / 4 (k = 1 .. 7; joint 6 with
    it by the coupling) and polished, each start that reaches the pose stored (the reference's
    restarts; docs/IK_CLASS.md section 5)."""
    j, j6 = _user_col(v, 2), _user_col(v, 5)
    q, base = ws[_W_QR : _W_QR + 6], ws[_W_QB : _W_QB + 6]
    for i in range(6):
        base[i] = q0[i]
    s = _coupling_sign(base, j, j6, v, Ru, T, ws)
    st = ws[_W_STATS : _W_STATS + N_STATS]
    for k in range(1, 8):
        for i in range(6):
            q[i] = base[i]
        q[j] = wrap(base[j] + 0.25 * math.pi * k)
        q[j6] = wrap(base[j6] + s * 0.25 * math.pi * k)
        st[12] += 1.0
        n1 = _verified(q, 0.0, kind, root, 30, P, v, Ru, T, opt, ws, wm, cand, nc, best)
        if n1 > nc and not _repeats(cand, nc):
            nc = n1
    return nc


@_inner
def _repeats(cand, i):
    """Is row i of the candidate table within 1e-9 rad of an earlier row of its class (a restart
    that found a solution already there: not stored twice)?"""
    for r in range(i):
        if cand[r, _C_CLASS] == cand[i, _C_CLASS] and _distance(cand[r], cand[i]) <= L.DISTINCT_TOL:
            return True
    return False


@_inner
def _aligned_theta2(t1, P, v, th2, n):
    """On a theta2 continuum (joint 1 at DH angle t1): the DH angles of joint 2 where axis 3
    turns closest to z6 and to -z6 (z3 . z6 = k0 + kc cos + ks sin over joint 2, from three
    values), appended to th2: where z3 is along z6 joints 3 and 6 may be collinear, and a theta3
    continuum crosses the curve (docs/IK_CLASS.md section 5)."""
    C, S = math.cos(t1), math.sin(t1)
    r = _upper_arm(C, S, 1.0, 0.0, P, v)[1]
    ka = r[2] * P[2] + r[5] * P[5] + r[8] * P[8]
    r = _upper_arm(C, S, 0.0, 1.0, P, v)[1]
    kb = r[2] * P[2] + r[5] * P[5] + r[8] * P[8]
    r = _upper_arm(C, S, -1.0, 0.0, P, v)[1]
    kd = r[2] * P[2] + r[5] * P[5] + r[8] * P[8]
    kc, k0 = 0.5 * (ka - kd), 0.5 * (ka + kd)
    phi = math.atan2(kb - k0, kc)
    th2[n], th2[n + 1] = phi, wrap(phi + math.pi)
    return n + 2


_ALL6 = np.arange(6)
_COLS_FWD = np.array([0, 1, 5])  # solver joints 1, 2, 6 as user columns
_COLS_REV = np.array([5, 4, 0])
#: Row j: every user column but j (the joints refit while joint j is held).
_ALL_BUT = np.array([[k for k in range(6) if k != j] for j in range(6)])
_COLS_NO3_FWD = np.array([0, 1, 3, 4, 5])  # every joint but solver joint 3, as user columns
_COLS_NO3_REV = np.array([5, 4, 2, 1, 0])


@_inner
def _exact_from(cand, nc, i, th1, kinds, n1, v):
    """Did certified root i (joint 1's DH angles th1, kinds: the candidates) give a solution
    nearer to it in joint 1 than to any other certified root (farther than :data:`SAME_ROOT`)?
    One the refinement or the polish slid to along a shallow eliminant is the other root's, and
    leaves root i unaccounted for."""
    j1, off = _user_col(v, 0), v[L.A_SOLVER_DH + 4]
    for r in range(nc):
        if cand[r, _C_ROOT] != float(i) or cand[r, _C_CLASS] != 1.0:
            continue
        d = gap(cand[r, j1] + off - th1[i])
        mine = True
        for k in range(n1):
            other = k != i and kinds[k] == L.KIND_ROOT and gap(th1[k] - th1[i]) > SAME_ROOT
            if other and gap(cand[r, j1] + off - th1[k]) < d:
                mine = False
                break
        if mine:
            return True
    return False


# ----------------------------------------------------------------------------- continua
@_inner
def _free_interval(x, x6, s, lo, hi, lo6, hi6):
    """Feasible interval of a free joint x in [lo, hi] with the coupled joint x6 + s (x' - x) in
    [lo6, hi6] (modulo 2 pi); the piece containing x, else the nearest. (nan, nan) if empty."""
    if hi6 - lo6 >= _TWO_PI - 1e-12:
        return lo, hi
    best_a, best_b, best_d = np.nan, np.nan, np.inf
    for k in range(-3, 4):
        u0, u1 = lo6 + k * _TWO_PI, hi6 + k * _TWO_PI  # allowed unwrapped coupled joint
        a, b = x + s * (u0 - x6), x + s * (u1 - x6)
        a, b = max(min(a, b), lo), min(max(a, b), hi)
        if a > b:
            continue
        d = 0.0 if a <= x <= b else min(abs(x - a), abs(x - b))
        if d < best_d:
            best_a, best_b, best_d = a, b, d
    return best_a, best_b


@_inner
def _nearest_mod_pi(phi, t):
    """phi or phi + pi, whichever is nearer to t (mod 2 pi)."""
    a = wrap(phi)
    b = wrap(phi + math.pi)
    return a if abs(wrap(a - t)) <= abs(wrap(b - t)) else b


@_inner
def _snapped(qc, v):
    """Solver joints 4 and 5 of qc moved (in place) to where D is on axis 3 and z6 along it, the
    nearest such angles: the theta3/theta6 continuum through qc's joints 1-3."""
    t = (qc[0] + v[L.A_SOLVER_DH + 4], qc[1] + v[L.A_SOLVER_DH + 9], qc[2] + v[L.A_SOLVER_DH + 14])
    r = _ch.IDENTITY
    for i in range(3):
        ca, sa, a, d, o = _row(v, i)
        r = _ch.compose_link(r, ca, sa, a, d, math.cos(t[i]), math.sin(t[i]))
    z3x, z3y, z3z = r[2], r[5], r[8]
    ca, sa, a, d, o4 = _row(v, 3)
    r40 = _ch.compose_link(r, ca, sa, a, d, 1.0, 0.0)
    x = r40[0] * z3x + r40[3] * z3y + r40[6] * z3z
    y = r40[1] * z3x + r40[4] * z3y + r40[7] * z3z
    t4 = _nearest_mod_pi(math.atan2(y, x), qc[3] + o4)
    r4 = _ch.compose_link(r, ca, sa, a, d, math.cos(t4), math.sin(t4))
    ca, sa, a, d, o5 = _row(v, 4)
    r50 = _ch.compose_link(r4, ca, sa, a, d, 1.0, 0.0)
    sa6 = v[L.A_SOLVER_DH + 5 * 5 + 1]
    t5 = _nearest_mod_pi(_in_plane(r50, z3x, z3y, z3z, sa6)[2], qc[4] + o5)
    qc[3], qc[4] = wrap(t4 - o4), wrap(t5 - o5)


@_inner
def _coupling_sign(q, j, j6, v, Ru, T, ws):
    """+1 if moving joints j and j6 by the same angle keeps the pose, else -1."""
    qa = ws[_W_QT : _W_QT + 6]
    for k in range(6):
        qa[k] = q[k]
    qa[j] += 1.0
    qa[j6] += 1.0
    pa, ra = _residuals(qa, v, Ru, T)
    qa[j6] -= 2.0
    pb, rb = _residuals(qa, v, Ru, T)
    return 1.0 if pa + ra <= pb + rb else -1.0


@_inner
def _theta3_continuum(c, v, Ru, T, opt, ws, wm, lo, hi):
    """Row c near the theta3/theta6 continuum: snap it onto the continuum and refit joints 1, 2
    and 6 (solver numbering); if that reaches the pose, every member does (moving joints 3 and
    6 together along their common axis changes nothing): flag it, with the coupling sign, the
    feasible interval of the free joint and a representative inside it."""
    qc, q = ws[_W_Q2 : _W_Q2 + 6], ws[_W_Q : _W_Q + 6]
    _to_solver(c, qc, v)
    _snapped(qc, v)
    _to_user(qc, q, v)
    _polish(
        q,
        v,
        Ru,
        T,
        ws,
        wm,
        _COLS_REV if v[L.A_REVERSED] != 0.0 else _COLS_FWD,
        3,
        8,
        1e-3 * min(opt[L.OPT_POSITION_TOL], opt[L.OPT_ROTATION_TOL]),
    )
    pres, rres = _residuals(q, v, Ru, T)
    if pres > opt[L.OPT_POSITION_TOL] or rres > opt[L.OPT_ROTATION_TOL]:
        return  # a numerical continuum: flagged, no exact members
    j, j6 = _user_col(v, 2), _user_col(v, 5)
    s = _coupling_sign(q, j, j6, v, Ru, T, ws)
    a, b = _free_interval(q[j], q[j6], s, lo[j], hi[j], lo[j6], hi[j6])
    if math.isfinite(a) and not (a - opt[L.OPT_LIMIT_TOL] <= q[j] <= b + opt[L.OPT_LIMIT_TOL]):
        x = min(max(q[j], a), b)
        q[j6] = wrap(q[j6] + s * (x - q[j]))
        q[j] = x
    pres, rres = _residuals(q, v, Ru, T)
    for k in range(6):
        c[k] = q[k]
    c[_C_PRES], c[_C_RRES], c[_C_FREE] = pres, rres, L.FREE_Q3
    c[_C_SIGN], c[_C_LO], c[_C_HI] = s, a, b


@_inner
def _continua(cand, nc, v, Ru, T, opt, ws, wm, lo, hi) -> None:
    """Resolve every exact row flagged near the theta3/theta6 continuum (:func:`_theta3_continuum`)."""
    for i in range(nc):
        if cand[i, _C_CLASS] == 1.0 and cand[i, _C_FREE] == L.FREE_NUMERICAL:
            _theta3_continuum(cand[i], v, Ru, T, opt, ws, wm, lo, hi)


# ----------------------------------------------------------------------------- distinct rows
@_inner
def _same(cand, ia, ib, v, Ru, T, opt, ws, wm):
    """Are rows ia and ib one solution? Equal to DISTINCT_TOL in every joint; or one exact
    theta3/theta6 continuum (its fixed joints and its coupling equal); or joined, within
    CONNECTED rad, by a segment that stays within the tolerance of the pose (7 points) or by a
    bent path along it (:func:`_bent_path`): near a singularity the configurations within the
    tolerance form a thin valley in which the rounded pose's eliminant has several roots, one
    solution at the tolerance."""
    dmax = 0.0
    for j in range(6):
        dmax = max(dmax, abs(wrap(cand[ia, j] - cand[ib, j])))
    if dmax <= L.DISTINCT_TOL:
        return True
    if (
        cand[ia, _C_FREE] == L.FREE_Q3
        and cand[ib, _C_FREE] == L.FREE_Q3
        and cand[ia, _C_SIGN] == cand[ib, _C_SIGN]
    ):
        j, j6 = _user_col(v, 2), _user_col(v, 5)
        fixed = abs(
            wrap(
                (cand[ia, j] - cand[ia, _C_SIGN] * cand[ia, j6])
                - (cand[ib, j] - cand[ib, _C_SIGN] * cand[ib, j6])
            )
        )
        for k in range(6):
            if k != j and k != j6:
                fixed = max(fixed, abs(wrap(cand[ia, k] - cand[ib, k])))
        if fixed <= 1e-7:
            return True
    fa, fb = cand[ia, _C_FREE], cand[ib, _C_FREE]  # (a theta3 continuum crossing a theta2 one is kept)
    if fa == L.FREE_Q2 and fb != L.FREE_Q3 and _on_theta2_curve(cand[ia], cand[ib], v, Ru, T, ws):
        return True
    if fb == L.FREE_Q2 and fa != L.FREE_Q3 and _on_theta2_curve(cand[ib], cand[ia], v, Ru, T, ws):
        return True
    if cand[ia, _C_FREE] == L.FREE_NUMERICAL and cand[ib, _C_FREE] == L.FREE_NUMERICAL:
        if _one_tube(cand[ia], cand[ib], v, Ru, T, opt, ws, wm):
            return True
    return _connected(cand[ia], cand[ib], v, Ru, T, opt, ws) or _bent_path(
        cand[ia], cand[ib], v, Ru, T, opt, ws, wm
    )


@_inner
def _connected(a, b, v, Ru, T, opt, ws):
    """Are configurations a and b (rows whose first 6 entries are user joints) within CONNECTED
    rad of each other in every joint and joined by a straight segment that stays within the
    tolerance of the pose (checked at 7 points)?"""
    for k in range(6):
        if abs(wrap(b[k] - a[k])) > CONNECTED:
            return False
    q = ws[_W_QT : _W_QT + 6]
    for s in (0.5, 0.25, 0.75, 0.125, 0.375, 0.625, 0.875):
        for k in range(6):
            q[k] = a[k] + s * wrap(b[k] - a[k])
        pr, rr = _residuals(q, v, Ru, T)
        if pr > opt[L.OPT_POSITION_TOL] or rr > opt[L.OPT_ROTATION_TOL]:
            return False
    return True


@_inner
def _bent_path(a, b, v, Ru, T, opt, ws, wm):
    """Are a and b within CONNECTED rad of each other in every joint and joined along the floor of
    a curved valley of the tolerance (at a multiple root the configurations within the tolerance
    form a flat, curved blob that no straight segment crosses)? The joint that differs most is
    stepped from a's value to b's in BENT_STEPS steps, the other five refit from the previous
    point at each step; every point must reach the pose, no step may move a joint by more than
    a quarter of the distance (a jump to another solution), and the last point must be
    connected to b (:func:`_connected`)."""
    held, size = 0, 0.0
    for k in range(6):
        d = abs(wrap(b[k] - a[k]))
        if d > CONNECTED:
            return False
        if d > size:
            held, size = k, d
    if size <= L.DISTINCT_TOL:
        return True
    prev, q = ws[_W_Q : _W_Q + 6], ws[_W_Q2 : _W_Q2 + 6]
    for k in range(6):
        prev[k] = a[k]
    step = wrap(b[held] - a[held])
    target = 1e-3 * min(opt[L.OPT_POSITION_TOL], opt[L.OPT_ROTATION_TOL])
    for i in range(1, BENT_STEPS + 1):
        for k in range(6):
            q[k] = prev[k]
        q[held] = a[held] + step * i / BENT_STEPS
        _polish(q, v, Ru, T, ws, wm, _ALL_BUT[held], 5, 8, target)
        pr, rr = _residuals(q, v, Ru, T)
        if pr > opt[L.OPT_POSITION_TOL] or rr > opt[L.OPT_ROTATION_TOL] or _distance(q, prev) > 0.25 * size:
            return False
        for k in range(6):
            prev[k] = q[k]
    return _connected(prev, b, v, Ru, T, opt, ws)


@_inner
def _on_theta2_curve(a, b, v, Ru, T, ws):
    """Is row b a member of the theta2 continuum of row a (FREE_Q2)? b's joint 1 (solver
    numbering) is a's to 1e-6 rad and b is, to 1e-6 rad, the closed-form configuration at a's
    joint 1 and b's joint 2 on a's wrist branch (the curve through a: as joint 2 turns, the wrist
    follows its closed forms; docs/IK_CLASS.md section 5 C)."""
    i0, i1 = _user_col(v, 0), _user_col(v, 1)
    if abs(wrap(a[i0] - b[i0])) > 1e-6:
        return False
    P = _solver_pose(T, Ru, v)
    qc, q = ws[_W_Q2 : _W_Q2 + 6], ws[_W_Q : _W_Q + 6]
    t1 = a[i0] + v[L.A_SOLVER_DH + 4]
    mine = -1
    for branch in range(2):  # a's branch at its own joint 2
        t2 = a[i1] + v[L.A_SOLVER_DH + 9]
        _closed_form(t1, math.cos(t2), math.sin(t2), branch, P, v, qc)
        _to_user(qc, q, v)
        if _distance(q, a) <= 1e-6:
            mine = branch
    if mine < 0:
        return False
    t2 = b[i1] + v[L.A_SOLVER_DH + 9]
    _closed_form(t1, math.cos(t2), math.sin(t2), mine, P, v, qc)
    _to_user(qc, q, v)
    return _distance(q, b) <= 1e-6


@_inner
def _distance(a, b):
    """Largest wrapped joint difference of two configurations [rad]."""
    d = 0.0
    for k in range(6):
        d = max(d, abs(wrap(a[k] - b[k])))
    return d


@_inner
def _tube_member(qa, phi, v, Ru, T, opt, ws, wm, out):
    """The configuration of the near-continuum tube through qa with joint 3 (solver numbering) at
    phi: joint 6 moved with it by the coupling, the other four joints refit by Levenberg-
    Marquardt with joint 3 held. Returns its residuals (position, rotation)."""
    j, j6 = _user_col(v, 2), _user_col(v, 5)
    s = _coupling_sign(qa, j, j6, v, Ru, T, ws)
    for k in range(6):
        out[k] = qa[k]
    out[j6] = wrap(qa[j6] + s * (phi - qa[j]))
    out[j] = phi
    _polish(
        out,
        v,
        Ru,
        T,
        ws,
        wm,
        _COLS_NO3_REV if v[L.A_REVERSED] != 0.0 else _COLS_NO3_FWD,
        5,
        8,
        1e-3 * min(opt[L.OPT_POSITION_TOL], opt[L.OPT_ROTATION_TOL]),
    )
    return _residuals(out, v, Ru, T)


@_inner
def _one_tube(a, b, v, Ru, T, opt, ws, wm):
    """Are the near-continuum rows a and b on one tube of configurations within the tolerance
    (the continuum broken by the pose's distance from it)? Joints 1 and 2 (solver numbering)
    agree to CONNECTED, the tube's members at a quarter, half, three quarters and the whole of
    the arc of joint 3 from a to b (each refit from the previous one) reach the pose, and the
    last member is connected to b (:func:`_connected`): rows with the same joint 3 on two
    different branches near the continuum are not one tube."""
    for jj in (0, 1):
        k = _user_col(v, jj)
        if abs(wrap(a[k] - b[k])) > CONNECTED:
            return False
    j = _user_col(v, 2)
    d = wrap(b[j] - a[j])
    prev, q = ws[_W_Q : _W_Q + 6], ws[_W_Q2 : _W_Q2 + 6]
    for k in range(6):
        prev[k] = a[k]
    for f in (0.25, 0.5, 0.75, 1.0):  # continuation: each member refit from the previous one
        pr, rr = _tube_member(prev, wrap(a[j] + f * d), v, Ru, T, opt, ws, wm, q)
        if pr > opt[L.OPT_POSITION_TOL] or rr > opt[L.OPT_ROTATION_TOL]:
            return False
        for k in range(6):
            prev[k] = q[k]
    return _connected(prev, b, v, Ru, T, opt, ws)  # ... and the tube arrives at b


@_inner
def _key(cand, i, opt):
    """Of duplicates keep: a continuum, then a certified root's row, then the least residual."""
    return (
        (0.0 if cand[i, _C_FREE] == L.FREE_Q3 or cand[i, _C_FREE] == L.FREE_Q2 else 4.0)
        + (0.0 if cand[i, _C_KIND] == L.KIND_ROOT else 2.0)
        + 0.25 * (cand[i, _C_PRES] / opt[L.OPT_POSITION_TOL] + cand[i, _C_RRES] / opt[L.OPT_ROTATION_TOL])
    )


@_inner
def _before(cand, ia, ib):
    """Lexicographic order of rows by round(q, 9) (the deterministic order of results)."""
    for j in range(6):
        ka, kb = round(cand[ia, j] * 1e9), round(cand[ib, j] * 1e9)
        if ka != kb:
            return ka < kb
    return False


@_inner
def _distinct_sorted(cand, nc, cls, v, Ru, T, opt, ws, wm, idx):
    """Indices (into idx) of the distinct rows of class ``cls``, lexicographically sorted: (count,
    whether distinct rows beyond MAX_SOLUTIONS were left out). Of a group of duplicates the
    first by :func:`_key` is kept."""
    m = 0
    for i in range(nc):
        if cand[i, _C_CLASS] == cls:
            idx[m] = i
            m += 1
    for i in range(1, m):  # by _key (insertion sort; m is small)
        u = int(idx[i])
        key = _key(cand, u, opt)
        j = i - 1
        while j >= 0 and _key(cand, int(idx[j]), opt) > key:
            idx[j + 1] = idx[j]
            j -= 1
        idx[j + 1] = u
    k = 0
    dropped = False
    for i in range(m):
        dup = False
        for j in range(k):
            if _same(cand, int(idx[i]), int(idx[j]), v, Ru, T, opt, ws, wm):
                dup = True
                break
        if not dup:
            if k == L.MAX_SOLUTIONS:  # a 17th distinct row: the answer is cut (the certificate says so)
                dropped = True
                break
            idx[k] = idx[i]
            k += 1
    for i in range(1, k):  # lexicographic
        u = int(idx[i])
        j = i - 1
        while j >= 0 and _before(cand, u, int(idx[j])):
            idx[j + 1] = idx[j]
            j -= 1
        idx[j + 1] = u
    return k, dropped


# ----------------------------------------------------------------------------- degenerate case
@_inner
def _zeros_first_degree(x0, xc, xs, th1, kinds, n):
    """theta1 (DH angles) where x0 + xc cos + xs sin = 0, appended as special candidates."""
    r = math.hypot(xc, xs)
    if r == 0.0 or abs(x0) > r:
        return n
    base, w = math.atan2(xs, xc), math.acos(max(-1.0, min(1.0, -x0 / r)))
    n = _push(th1, kinds, n, base + w, L.KIND_SPECIAL)
    return _push(th1, kinds, n, base - w, L.KIND_SPECIAL)


@_inner
def _free_theta2_candidates(terms, th1, kinds, n):
    """theta1 (DH angles) where both conditions on theta2 vanish identically (a, b, c, P, Q and
    R all zero: theta2 free, docs/IK_CLASS.md section 5 C), appended as special candidates: the
    zeros of the one with the largest amplitude, in closed form, at which all six vanish to
    1e-9 of their size. (A root of the eliminant there is multiple and known only to ~1e-8,
    too coarse to see the six vanish.)"""
    best, o = 0.0, -1
    for k in range(6):
        r = math.hypot(terms[3 * k + 1], terms[3 * k + 2])
        if r > best:
            best, o = r, 3 * k
    if o < 0 or abs(terms[o]) > best * (1.0 + 1e-9):
        return n
    base = math.atan2(terms[o + 2], terms[o + 1])
    w = math.acos(max(-1.0, min(1.0, -terms[o] / best)))
    for t in (base + w, base - w):
        if _both_vanish(terms, math.cos(t), math.sin(t)):
            n = _push(th1, kinds, n, t, L.KIND_SPECIAL)
    return n


@_inner
def _both_vanish(terms, C, S):
    """Do both conditions on theta2 vanish identically (to VANISH of their coefficients' size,
    :func:`_relative`) at theta1 = atan2(S, C)?"""
    f = _el.first_degree_at
    a, b, c = f(terms[0], terms[1], terms[2], C, S), f(terms[3], terms[4], terms[5], C, S), f(
        terms[6], terms[7], terms[8], C, S
    )
    if _relative(a, b, c, terms, 0) > VANISH:
        return False
    P, Q, R = f(terms[9], terms[10], terms[11], C, S), f(terms[12], terms[13], terms[14], C, S), f(
        terms[15], terms[16], terms[17], C, S
    )
    return _relative(P, Q, R, terms, 9) <= VANISH


@_inner
def _degenerate_candidates(terms, ws):
    """theta1 candidates when F vanishes on the whole circle: two members of every branch of
    the theta1 continuum (theta_r and theta_r + pi), and the theta1 where one of the two
    conditions on theta2 vanishes identically (there the other gives two theta2: isolated
    solutions beside the continuum)."""
    th1, kinds = ws[_W_TH1 : _W_TH1 + _MAX_T1], ws[_W_KIND : _W_KIND + _MAX_T1]
    n = _push(th1, kinds, 0, _PSI, L.KIND_SPECIAL)
    n = _push(th1, kinds, n, _PSI + math.pi, L.KIND_SPECIAL)
    n = _zeros_first_degree(terms[9], terms[10], terms[11], th1, kinds, n)  # P = 0
    n = _zeros_first_degree(terms[12], terms[13], terms[14], th1, kinds, n)  # Q = 0
    n = _zeros_first_degree(terms[3], terms[4], terms[5], th1, kinds, n)  # b = 0
    n = _zeros_first_degree(terms[6], terms[7], terms[8], th1, kinds, n)  # c = 0
    return n


# ----------------------------------------------------------------------------- one pose
@_inner
def _all_candidates(P, terms, mags, v, Ru, T, opt, ws, wm, cand, hdr, best, thr_rel):
    """Candidates of every theta1 candidate into cand; the count. Sets the path and certificate."""
    st = ws[_W_STATS : _W_STATS + N_STATS]
    th1, kinds = ws[_W_TH1 : _W_TH1 + _MAX_T1], ws[_W_KIND : _W_KIND + _MAX_T1]
    mabc = 0.0  # the size F has when Eq 8's coefficients are as large as Eq 11's allow
    for k in range(9):
        mabc = max(mabc, mags[k])
    n1 = _theta1_candidates(terms, mags, thr_rel, mabc * mabc * mabc, ws, hdr)
    degenerate = n1 < 0
    if not degenerate:
        n1 = _free_theta2_candidates(terms, th1, kinds, n1)
    if degenerate:
        st[8] += 1.0
        n1 = _degenerate_candidates(terms, ws)
        for half in range(2):  # and the roots of F, in double-double (isolated rows); near roots
            hm = _half_magnitude(mags, half, ws)  # too where F is small only against its natural size
            near = 0.0 if _flat_half(terms, half, thr_rel * hm, ws) else thr_rel * hm
            n1 = _extended(
                terms,
                1.0 if half == 0 else -1.0,
                0.0,
                1.0,
                hm,
                near,
                _PSI if half == 0 else _PSI + math.pi,
                ws,
                th1,
                kinds,
                n1,
            )
    st[1] += n1
    nc = 0
    for i in range(n1):
        nc = _configurations(
            th1[i], kinds[i], float(i), P, terms, v, Ru, T, opt, ws, wm, cand, nc, best, degenerate
        )
    hdr[L.H_CERT] = L.CERT_OK
    if degenerate:
        hdr[L.H_PATH] = L.PATH_DEGENERATE
        for i in range(nc):  # candidates for the theta1 continuum: iik.ik.solve sorts them into
            if cand[i, _C_CLASS] == 1.0:  # branches and isolated rows (iik.ik.members)
                cand[i, _C_FREE] = L.FREE_Q1
        return nc
    for i in range(n1):
        if kinds[i] == L.KIND_MULTIPLE:
            hdr[L.H_PATH] = L.PATH_MULTIPLE
        elif hdr[L.H_PATH] == L.PATH_DOUBLE and hdr[L.H_CLUSTERS] > 0:
            hdr[L.H_PATH] = L.PATH_EXTENDED
    for i in range(n1):  # the certificate: every certified root gave a solution
        if kinds[i] == L.KIND_ROOT and not _exact_from(cand, nc, i, th1, kinds, n1, v):
            st[9] += 1.0
            nc = _configurations(
                th1[i], L.KIND_NEAR, float(i), P, terms, v, Ru, T, opt, ws, wm, cand, nc, best, False
            )
            if not _exact_from(cand, nc, i, th1, kinds, n1, v):
                st[10] += 1.0
                hdr[L.H_CERT] = L.CERT_ROOT_WITHOUT_CONFIGURATION
    if nc >= MAX_CAND:
        hdr[L.H_CERT] = L.CERT_TABLE_FULL
    elif _near_theta2_continuum(ws[_W_REL : _W_REL + n1]):
        hdr[L.H_CERT] = L.CERT_NEAR_THETA2
    return nc


@_inner
def _near_theta2_continuum(rel):
    """Is some theta1 candidate near a theta2 continuum (both conditions on theta2 below
    NEAR_FREE2 of their size, ``rel`` per candidate from :func:`_configurations`) while none is
    on one (below VANISH)? There joint 2 is fixed only loosely by the pose, its solutions lie
    along a broken curve, and the restarts of :func:`_theta2_restarts` are not a proof that
    none was missed."""
    near, exact = False, False
    for r in rel:
        if r <= VANISH:
            exact = True
        elif r <= NEAR_FREE2:
            near = True
    return near and not exact


@_inner
def _into_limits(row, lo, hi, tol):
    """Is the configuration row[:6] (angles wrapped to (-pi, pi]) inside the limits [lo, hi]
    (widened by tol) once each joint outside them is turned by +-2 pi where that brings it in
    (limits not centred on 0, e.g. -71 .. 251 deg)? The joints are turned in place."""
    inside = True
    for j in range(6):
        x = row[j]
        if x < lo[j] - tol or x > hi[j] + tol:
            y = x + _TWO_PI if x < lo[j] - tol else x - _TWO_PI
            if lo[j] - tol <= y <= hi[j] + tol:
                row[j] = y
            else:
                inside = False
    return inside


@_inner
def _write_rows(cand, idx, k, within_only, approx, v, lo, hi, opt, outq, info, flags, m0):
    """Rows idx[:k] of cand into the outputs from row m0 (the limit filter applied); new count."""
    m = m0
    for ii in range(k):
        c = int(idx[ii])
        inside = _into_limits(cand[c], lo, hi, opt[L.OPT_LIMIT_TOL])
        if within_only and not inside and cand[c, _C_FREE] != L.FREE_Q1 and cand[c, _C_FREE] != L.FREE_Q2:
            continue  # (a theta1 or theta2 continuum may have members inside: iik.ik.solve moves it)
        for j in range(6):
            outq[m, j] = cand[c, j]
        info[m, L.I_PRES], info[m, L.I_RRES], info[m, L.I_FREE] = (
            cand[c, _C_PRES],
            cand[c, _C_RRES],
            cand[c, _C_FREE],
        )
        info[m, L.I_KIND], info[m, L.I_H3] = cand[c, _C_KIND], cand[c, _C_H3]
        info[m, L.I_CSIGN], info[m, L.I_CLO], info[m, L.I_CHI] = (
            cand[c, _C_SIGN],
            cand[c, _C_LO],
            cand[c, _C_HI],
        )
        flags[m, 0], flags[m, 1] = inside, approx
        m += 1
    return m


@_inner
def _solve_pose(T, v, opt, within_only, ws, wm, cand, outq, info, flags, hdr):
    """Every IK solution of one pose into outq (k, 6), info (k, N_INFO), flags (k, 2) (within
    the limits, approximate); the header into hdr."""
    for i in range(L.N_HDR):
        hdr[i] = 0.0
    Ru = wm[_M_RU, :3, :3]
    status, measure, dist = _check_pose(T, opt[L.OPT_ORTHONORMAL_TOL], Ru)
    hdr[L.H_STATUS], hdr[L.H_MEASURE], hdr[L.H_PROJECTION] = status, measure, dist
    hdr[L.H_BEST_P], hdr[L.H_BEST_R] = np.inf, np.inf
    st = ws[_W_STATS : _W_STATS + N_STATS]
    st[0] += 1.0
    if status != L.OK or _beyond(T, v[L.A_REACH] + opt[L.OPT_APPROX_TOL]):
        return 0
    P = _solver_pose(T, Ru, v)
    terms, mags = ws[_W_TERMS : _W_TERMS + 18], ws[_W_MAGS : _W_MAGS + 18]
    t = _el.pose_terms(P[2], P[5], P[8], P[9], P[10], P[11], v, L.A_CONST, -1.0)
    tm = _el.pose_terms(
        abs(P[2]), abs(P[5]), abs(P[8]), abs(P[9]), abs(P[10]), abs(P[11]), v, L.A_CONST_ABS, 1.0
    )
    for i in range(18):
        terms[i], mags[i] = t[i], tm[i]
    best = hdr[L.H_BEST_P : L.H_BEST_R + 1]
    scale = v[L.A_SCALE]
    thr = NEAR_FACTOR * (opt[L.OPT_POSITION_TOL] / scale + opt[L.OPT_ROTATION_TOL])
    nc = _all_candidates(P, terms, mags, v, Ru, T, opt, ws, wm, cand, hdr, best, thr)
    lo, hi = v[L.A_LOWER : L.A_LOWER + 6], v[L.A_UPPER : L.A_UPPER + 6]
    _continua(cand, nc, v, Ru, T, opt, ws, wm, lo, hi)
    idx = ws[_W_IDX : _W_IDX + MAX_CAND]
    k, dropped = _distinct_sorted(cand, nc, 1.0, v, Ru, T, opt, ws, wm, idx)
    if dropped:
        hdr[L.H_CERT] = L.CERT_ROWS_DROPPED
    hdr[L.H_TOTAL] = k
    m = _write_rows(cand, idx, k, within_only, False, v, lo, hi, opt, outq, info, flags, 0)
    approx = False
    if m == 0:  # nothing exact (within the limits if asked): near roots for approximate_tol too
        if k == 0 and hdr[L.H_PATH] != L.PATH_DEGENERATE:
            thr_a = NEAR_FACTOR * (opt[L.OPT_APPROX_TOL] / scale + opt[L.OPT_APPROX_TOL])
            nc = _all_candidates(P, terms, mags, v, Ru, T, opt, ws, wm, cand, hdr, best, thr_a)
        k = _distinct_sorted(cand, nc, 2.0, v, Ru, T, opt, ws, wm, idx)[0]
        m = _write_rows(cand, idx, k, within_only, True, v, lo, hi, opt, outq, info, flags, 0)
        approx = m > 0
    nfree = 0
    for r in range(m):
        nfree += info[r, L.I_FREE] != L.FREE_NONE
        if dist != 0.0:  # the rotation was projected: residuals against the pose as given
            pose = _ch.chain_pose(outq[r], v, L.A_USER_DH, L.A_USER_BASE, L.A_USER_TOOL)
            info[r, L.I_RRES] = _ch.rotation_angle_12(pose, T[:3, :3])
    hdr[L.H_COUNT], hdr[L.H_FREE], hdr[L.H_APPROX] = m, nfree, 1.0 if approx else 0.0
    if hdr[L.H_PATH] != L.PATH_DOUBLE:
        st[11] += 1.0
    return m


@_inner
def _beyond(T, reach):
    """Is the position of T farther than ``reach`` from the base origin (no overflow)?"""
    x, y, z = abs(T[0, 3]), abs(T[1, 3]), abs(T[2, 3])
    if max(x, y, z) > reach:
        return True
    return x * x + y * y + z * z > reach * reach


@_inner
def _pad(outq, info, flags, m):
    """Rows m.. of one pose's outputs: NaN, free kind 0, flags False (the padding of IKBatch)."""
    for r in range(m, outq.shape[0]):
        for j in range(6):
            outq[r, j] = np.nan
        for j in range(L.N_INFO):
            info[r, j] = np.nan
        info[r, L.I_FREE] = 0.0
        flags[r, 0], flags[r, 1] = False, False


@_inner
def _views(buf):
    """The scratch buffer carved into (ws, wm, cand)."""
    ws = buf[0:N_SCRATCH]
    wm = buf[N_SCRATCH : N_SCRATCH + N_MATS * 36].reshape((N_MATS, 6, 6))
    cand = ws[_W_CAND : _W_CAND + MAX_CAND * N_CAND].reshape((MAX_CAND, N_CAND))
    return ws, wm, cand


#: Size of the scratch buffer of :func:`solve_many`.
N_BUFFER = N_SCRATCH + N_MATS * 36


@_entry(_nrt=False)
def solve_many(Ts, v, opt, within_only, buf, outq, info, flags, hdr):
    """:func:`_solve_pose` for poses Ts (n, 4, 4) into padded outq (n, 16, 6), info
    (n, 16, N_INFO), flags (n, 16, 2) bool and hdr (n, N_HDR): a serial loop.

    ``v``: the arm vector; ``opt``: the option vector (OPT_*); ``buf`` (N_BUFFER,) float64 is
    working memory allocated by the caller (the kernel runs without Numba's reference counting).
    """
    ws, wm, cand = _views(buf)
    for i in range(Ts.shape[0]):
        _solve_pose(Ts[i], v, opt, within_only, ws, wm, cand, outq[i], info[i], flags[i], hdr[i])
        _pad(outq[i], info[i], flags[i], int(hdr[i, L.H_COUNT]))


@_entry(parallel=True, _nrt=False)
def solve_many_parallel(Ts, v, opt, within_only, bufs, outq, info, flags, hdr):
    """:func:`solve_many` on all cores: ``numba.prange`` over ``len(bufs)`` chunks of poses, each
    with its own working memory ``bufs[c]`` (N_BUFFER,) allocated by the caller (no allocation
    or reference counting inside the parallel loop)."""
    n = Ts.shape[0]
    m = bufs.shape[0]
    chunk = (n + m - 1) // m
    for c in numba.prange(m):
        ws, wm, cand = _views(bufs[c])
        for i in range(c * chunk, min(n, (c + 1) * chunk)):
            _solve_pose(Ts[i], v, opt, within_only, ws, wm, cand, outq[i], info[i], flags[i], hdr[i])
            _pad(outq[i], info[i], flags[i], int(hdr[i, L.H_COUNT]))


_BUFFER = None


def scratch() -> np.ndarray:
    """The working memory of :func:`solve_many` (one buffer: the kernel holds the GIL)."""
    global _BUFFER
    if _BUFFER is None:
        _BUFFER = np.zeros(N_BUFFER)
    return _BUFFER


def work_counts(reset: bool = False) -> dict[str, int]:
    """The work counters of :func:`scratch` (:data:`STATS`, cumulative over the serial calls of
    this process; ``reset`` zeroes them after reading): what a profile of the kernel reads."""
    w = scratch()[_W_STATS : _W_STATS + len(STATS)]
    out = {k: int(x) for k, x in zip(STATS, w, strict=True)}
    if reset:
        w[:] = 0.0
    return out


# ----------------------------------------------------------------------------- continuum members
@_entry(_nrt=False)
def continuum_members(T, v, opt, q0, cols, col, coupled, sign, thetas, buf, out_q, out_res) -> bool:
    """Members of a continuum through q0 (6,), in order: user joint ``col`` at each of ``thetas``
    (n,), the ``coupled`` joint (>= 0) moved by ``sign`` times the step, the other joints
    (``cols`` (5,): every joint but ``col``) refit by Levenberg-Marquardt from the previous
    member. Into out_q (n, 6) and out_res (n, 2) (position [m], rotation [rad] residuals).
    False if the pose does not pass the pose check."""
    ws, wm, _ = _views(buf)
    Ru = wm[_M_RU, :3, :3]
    status, _, _ = _check_pose(T, opt[L.OPT_ORTHONORMAL_TOL], Ru)
    if status != L.OK:
        return False
    q = ws[_W_Q : _W_Q + 6]
    for k in range(6):
        q[k] = q0[k]
    target = 1e-3 * min(opt[L.OPT_POSITION_TOL], opt[L.OPT_ROTATION_TOL])
    for i in range(thetas.shape[0]):
        if coupled >= 0:
            q[coupled] = wrap(q[coupled] + sign * (thetas[i] - q[col]))
        q[col] = thetas[i]
        _polish(q, v, Ru, T, ws, wm, cols, 5, 12, target)
        q[col] = thetas[i]  # (the polish wraps; keep the value asked for)
        pres, rres = _residuals(q, v, Ru, T)
        for k in range(6):
            out_q[i, k] = q[k]
        out_res[i, 0], out_res[i, 1] = pres, rres
    return True


#: A closed-form configuration that misses the pose is taken as the next member of a march only
#: when none reaches it: this is added to its distance [rad] (more than any wrapped distance, pi).
MISS_PENALTY = 10.0


@_inner
def _closed_row(t1, t2, branch, P, v, qc, row):
    """The closed-form configuration with solver joints 1, 2 at DH angles t1, t2 and wrist branch
    ``branch``, unpolished, into row[:6] (user joints)."""
    _closed_form(t1, math.cos(t2), math.sin(t2), branch, P, v, qc)
    _to_user(qc, row, v)


@_inner
def _mod_distance(a, b):
    """Largest wrapped joint difference of two configurations [rad], |x| by the mod form as
    :func:`iik.ik.angles.angle_distance` (NaN if any difference is NaN, as NumPy's max)."""
    d = 0.0
    for k in range(6):
        x = gap(a[k] - b[k])
        if x > d or math.isnan(x):  # (NaN stays)
            d = x
    return d


@_inner
def _nearest_closed_form(t1, t2, terms, P, v, Ru, T, ws, rows, prev, ptol, rtol):
    """Of the closed-form configurations with solver joint 1 at DH angle t1 (every theta2 option,
    or solver joint 2 at DH angle t2 where that is not NaN; both wrist branches), the one nearest
    prev (6,) (:func:`_mod_distance`), MISS_PENALTY added to one that misses the tolerance, the
    first of equals (NumPy's argmin: the first NaN wins): its index b (rows[b, :6], user joints)
    and residuals [m, rad]; (-1, inf, inf) if there is none. Only what can matter is computed:
    a configuration whose joint-2 difference alone exceeds the best distance is skipped (from
    finite inputs the closed forms give no NaN), and the nearest wins if it reaches the pose (any
    other is at least as far); else every configuration is weighed with its penalty."""
    th2, qc = ws[_W_TH2 : _W_TH2 + 8], ws[_W_Q2 : _W_Q2 + 6]
    if math.isnan(t2):
        n2 = max(_theta2_options(terms, t1, L.KIND_SPECIAL, th2)[0], 0)
    else:
        th2[0], n2 = t2, 1
    m, j2, o2 = min(2 * n2, rows.shape[0]), _user_col(v, 1), v[L.A_SOLVER_DH + 9]
    b, best = -1, math.inf
    for r in range(m):
        x = wrap(math.atan2(math.sin(th2[r // 2]), math.cos(th2[r // 2])) - o2) - prev[j2]
        if gap(x) > best:  # (joint 2 of the row, as _to_user)
            continue
        _closed_row(t1, th2[r // 2], r % 2, P, v, qc, rows[r])
        d = _mod_distance(rows[r], prev)
        if math.isnan(d):
            pres, rres = _residuals(rows[r, :6], v, Ru, T)
            return r, pres, rres
        if d < best:
            best, b = d, r
    if b < 0:
        return -1, math.inf, math.inf
    pres, rres = _residuals(rows[b, :6], v, Ru, T)
    if pres <= ptol and rres <= rtol:
        return b, pres, rres
    best = math.inf  # the nearest misses: every configuration with its penalty
    for r in range(m):
        _closed_row(t1, th2[r // 2], r % 2, P, v, qc, rows[r])
        p, q = _residuals(rows[r, :6], v, Ru, T)
        d = _mod_distance(rows[r], prev) + (0.0 if p <= ptol and q <= rtol else MISS_PENALTY)
        if d < best or math.isnan(d):
            best, b, pres, rres = d, r, p, q
            if math.isnan(d):
                break
    return b, pres, rres


@_entry(_nrt=False)
def closed_form_march(T, v, opt, q0, starts, joint1, joint2, buf, out_q, out_res) -> bool:
    """A theta1 or theta2 continuum followed by its exact closed forms: at each step i, solver
    joint 1 at ``joint1[i]`` [rad] (and solver joint 2 at ``joint2[i]`` where that is not NaN),
    the closed-form configuration nearest the previous member taken (:func:`_march_step`; no
    polish: the members are exact). The previous member of step i is ``q0[starts[i]]`` (q0
    (k, 6)) where ``starts[i] >= 0`` (a march begins there), else step i - 1's. Into out_q
    (n, 6) (user joints) and out_res (n, 2) [m, rad]; where there is no closed form, the previous
    member with infinite residuals. False if the pose does not pass the pose check."""
    ws, wm, cand = _views(buf)
    Ru = wm[_M_RU, :3, :3]
    status, _, _ = _check_pose(T, opt[L.OPT_ORTHONORMAL_TOL], Ru)
    if status != L.OK:
        return False
    P = _solver_pose(T, Ru, v)
    terms = ws[_W_TERMS : _W_TERMS + 18]
    t = _el.pose_terms(P[2], P[5], P[8], P[9], P[10], P[11], v, L.A_CONST, -1.0)
    for k in range(18):
        terms[k] = t[k]
    prev, rows = ws[_W_QB : _W_QB + 6], cand[: L.MAX_SOLUTIONS]
    c1, c2 = _user_col(v, 0), _user_col(v, 1)
    a0, b0 = 0.0, 0.0
    for i in range(joint1.shape[0]):
        if starts[i] >= 0:
            for k in range(6):
                prev[k] = q0[starts[i], k]
            a0 = joint1[i] - wrap(joint1[i] - prev[c1])  # (the values asked for may be unwrapped)
            b0 = joint2[i] - wrap(joint2[i] - prev[c2])
        out_res[i, 0], out_res[i, 1] = _march_step(
            a0, b0, joint1[i], joint2[i], terms, P, v, Ru, T, ws, rows, prev, opt
        )
        a0, b0 = joint1[i], joint2[i]
        for k in range(6):
            out_q[i, k] = prev[k]
    return True


#: A march step whose nearest closed-form member moves a joint by more than this [rad] is
#: halved: where the curve passes near a wrist singularity (theta5 ~ 1e-3 on a theta1
#: continuum) joints 3 and 6 swing by ~pi within 0.02 rad of joint 1, and a whole step lands
#: on the other branch of the pose (the wrong branch is ~2 rad away, the right one close).
MARCH_JUMP = 0.25
#: ... down to steps of this [rad] (where the branches do meet the swing is a jump).
MARCH_MIN_STEP = 1e-9


@_inner
def _march_step(a0, b0, a1, b1, terms, P, v, Ru, T, ws, rows, prev, opt):
    """One step of :func:`closed_form_march` from the free values (a0, b0) of the member prev
    (6,) to (a1, b1) (b1 NaN: joint 2 by its closed forms): substeps halved while the nearest
    member jumps by more than MARCH_JUMP; prev becomes the member at (a1, b1). Its residuals."""
    o1, o2 = v[L.A_SOLVER_DH + 4], v[L.A_SOLVER_DH + 9]
    da, db = a1 - a0, (0.0 if math.isnan(b1) else b1 - b0)
    size = max(abs(da), abs(db))
    least = 1.0 if size <= MARCH_MIN_STEP else MARCH_MIN_STEP / size
    s, h = 0.0, 1.0
    pres, rres = math.inf, math.inf
    while True:
        f = min(s + h, 1.0)
        t2 = b1 + o2 if math.isnan(b1) else b0 + f * db + o2
        b, pres, rres = _nearest_closed_form(
            a0 + f * da + o1, t2, terms, P, v, Ru, T, ws, rows, prev,
            opt[L.OPT_POSITION_TOL], opt[L.OPT_ROTATION_TOL],
        )
        if b >= 0 and f - s > least and _mod_distance(rows[b], prev) > MARCH_JUMP:
            h = 0.5 * (f - s)
            continue
        if b >= 0:
            for k in range(6):
                prev[k] = rows[b, k]
        if f >= 1.0:
            return pres, rres
        s, h = f, min(2.0 * h, 1.0 - f)
