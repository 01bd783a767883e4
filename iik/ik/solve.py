"""Public inverse-kinematics entry points: :func:`solve`, :func:`solve_many`, :func:`solve_batch`.

Methods:

* ``"complete"`` (default): the compiled kernel (:mod:`iik.ik.kernel`): every solution,
  real roots of the eliminant isolated so that none can be missed.
* ``"reference"``: the same elimination vectorised in NumPy (:mod:`iik.ik.reference`),
  kept as an independent reference; where the kernel certifies its answer the two return the
  same set (tested on every adversarial family, tests/iik/test_ik_families.py).
* ``"thesis"``: the Sec 3.3 IIK (theta1 grid + bisection, errata corrected,
  :mod:`iik.ik.thesis`), kept to reproduce and measure the thesis.

Every method takes the same options (:class:`~iik.ik.options.IKOptions`): rotations
within ``orthonormal_tol`` of orthonormal are projected and solved. Only the complete
method returns approximate configurations for poses just out of reach.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager

import numpy as np

from ..arm import LIMIT_TOL, Arm
from ..errors import InvalidInputError
from . import layout as L
from . import poses as _poses
from .angles import into_limits, wrap_angle
from .options import DEFAULT_OPTIONS, IKOptions
from .result import Certificate, Continuum, IKBatch, IKResult

__all__ = ["solve", "solve_many", "solve_batch", "METHODS", "compile_notice", "compile_clock",
           "COMPILE_MESSAGE"]

METHODS = ("complete", "reference", "thesis")

_F64 = np.dtype(np.float64)
_KERNEL = None
_OPT_VECTORS: dict[int, tuple[IKOptions, np.ndarray]] = {}


def _kernel():
    """The compiled kernel module (imported on first use; Numba loads then)."""
    global _KERNEL
    if _KERNEL is None:
        from . import kernel

        _KERNEL = kernel
    return _KERNEL


def _check_args(method, options, arm) -> IKOptions:
    if method not in METHODS:
        raise InvalidInputError("method", f"expected one of {METHODS}, got {method!r}")
    if not isinstance(arm, Arm):
        raise InvalidInputError("arm", f"expected an iik.Arm, got {type(arm).__name__}")
    if options is None:
        return DEFAULT_OPTIONS
    if not isinstance(options, IKOptions):
        raise InvalidInputError("options", f"expected an IKOptions, got {type(options).__name__}")
    return options


def _option_vector(opts: IKOptions) -> np.ndarray:
    hit = _OPT_VECTORS.get(id(opts))
    if hit is not None and hit[0] is opts:
        return hit[1]
    v = np.zeros(L.N_OPT)
    v[L.OPT_POSITION_TOL], v[L.OPT_ROTATION_TOL] = opts.position_tol, opts.rotation_tol
    v[L.OPT_APPROX_TOL], v[L.OPT_ORTHONORMAL_TOL], v[L.OPT_LIMIT_TOL] = (
        opts.approximate_tol,
        opts.orthonormal_tol,
        LIMIT_TOL,
    )
    v.setflags(write=False)
    if len(_OPT_VECTORS) > 64:
        _OPT_VECTORS.clear()
    _OPT_VECTORS[id(opts)] = (opts, v)
    return v


# ----------------------------------------------------------------------------- the methods
def _outputs(n: int):
    return (
        np.empty((n, L.MAX_SOLUTIONS, 6)),
        np.empty((n, L.MAX_SOLUTIONS, L.N_INFO)),
        np.empty((n, L.MAX_SOLUTIONS, 2), dtype=bool),
        np.empty((n, L.N_HDR)),
    )


def _complete(Tb: np.ndarray, arm: Arm, opts: IKOptions, within: bool):
    """Kernel outputs (q, info, flags, hdr) for validated-shape poses (n, 4, 4)."""
    k = _kernel()
    q, info, flags, hdr = _outputs(Tb.shape[0])  # the kernel writes the padding too
    Tc = Tb if Tb.flags.c_contiguous else np.ascontiguousarray(Tb)
    v = k.arm_data(arm).vector
    if opts.parallel and Tb.shape[0] > 1:
        import numba

        chunks = min(Tb.shape[0], 8 * numba.get_num_threads())
        k.solve_many_parallel(
            Tc, v, _option_vector(opts), within, np.zeros((chunks, k.N_BUFFER)), q, info, flags, hdr
        )
    else:
        k.solve_many(Tc, v, _option_vector(opts), within, k.scratch(), q, info, flags, hdr)
    return q, info, flags, hdr


def _beyond_reach(Tb: np.ndarray, arm: Arm) -> np.ndarray:
    """Poses (n, 4, 4) whose position is farther than the arm's reach bound from the base
    origin (compared without squaring huge numbers: no overflow)."""
    with np.errstate(invalid="ignore"):  # (NaN positions are rejected by the pose check)
        p = np.abs(Tb[:, :3, 3])
        r = arm.reach
        big = p.max(axis=1) > r
        p = np.where(big[:, None], 0.0, p)
        return big | (np.einsum("ni,ni->n", p, p) > r * r)


def _numpy_method(Tb: np.ndarray, arm: Arm, opts: IKOptions, within: bool, method: str):
    """The reference or thesis method in the kernel's output layout."""
    from .compare import pose_residuals

    n = Tb.shape[0]
    status, measure, Ru, dist = _poses.check_poses(Tb, opts.orthonormal_tol)
    q, info, flags, hdr = _outputs(n)
    q[:] = np.nan
    info[:] = np.nan
    info[:, :, L.I_FREE] = 0.0
    flags[:] = False
    hdr[:] = 0.0
    hdr[:, L.H_STATUS], hdr[:, L.H_MEASURE], hdr[:, L.H_PROJECTION] = status, measure, dist
    hdr[:, L.H_BEST_P], hdr[:, L.H_BEST_R] = np.inf, np.inf
    hdr[:, L.H_PATH] = -1.0
    good = np.flatnonzero((status == _poses.OK) & ~_beyond_reach(Tb, arm))  # far: unreachable
    if len(good) == 0:
        return q, info, flags, hdr
    Tu = Tb[good].copy()
    Tu[:, :3, :3] = Ru[good]
    cut = np.zeros(len(good), bool)
    if method == "thesis":
        from .thesis import solve_thesis_arrays

        Q, V, F, _P, _R = solve_thesis_arrays(Tu, arm, cut=cut)
    else:
        from .reference import solve_arrays

        Q, V, F, _P, _R = solve_arrays(Tu, arm, tol_p=opts.position_tol, tol_r=opts.rotation_tol, cut=cut)
    hdr[good[cut], L.H_CERT] = L.CERT_ROWS_DROPPED  # (a NumPy method's certificate says so)
    Q, inside = into_limits(Q, arm.q_min, arm.q_max, LIMIT_TOL)
    inside &= V
    keep = inside if within else V
    hdr[good, L.H_TOTAL] = V.sum(axis=1)
    for gi, i in enumerate(good):  # rows are sorted valid-first: keep them in order
        rows = np.flatnonzero(keep[gi])
        m = len(rows)
        hdr[i, L.H_COUNT] = m
        if m == 0:
            continue
        q[i, :m] = Q[gi, rows]
        pres, rres = pose_residuals(Q[gi, rows], np.broadcast_to(Tb[i], (m, 4, 4)), arm)
        info[i, :m, L.I_PRES], info[i, :m, L.I_RRES], info[i, :m, L.I_FREE] = pres, rres, F[gi, rows]
        flags[i, :m, 0] = inside[gi, rows]
        hdr[i, L.H_FREE] = np.count_nonzero(F[gi, rows])
    return q, info, flags, hdr


def _run(Tb, arm, opts, within, method):
    if method == "complete":
        return _complete(Tb, arm, opts, within)
    return _numpy_method(Tb, arm, opts, within, method)


def _raise_first_bad(hdr, name: str, batched: bool, opts: IKOptions) -> None:
    bad = np.flatnonzero(hdr[:, L.H_STATUS] != _poses.OK)
    if len(bad):
        i = int(bad[0])
        raise _poses.pose_error(
            int(hdr[i, L.H_STATUS]),
            float(hdr[i, L.H_MEASURE]),
            name,
            i if batched else None,
            opts.orthonormal_tol,
        )


# ----------------------------------------------------------------------------- results
def _reason(count: int, total: int, approx: bool, closest_p: float, closest_r: float, opts: IKOptions) -> str:
    if count and not approx:
        return ""
    if count:
        return (
            f"approximate: no configuration reaches the pose within the tolerances "
            f"({opts.position_tol:g} m, {opts.rotation_tol:g} rad); the {count} configuration(s) "
            f"returned are within IKOptions.approximate_tol = {opts.approximate_tol:g} of it "
            "(least-residual configurations, flagged approximate)"
        )
    if total:
        return f"{total} solution(s) exist but none within the joint limits"
    if closest_p <= opts.approximate_tol and closest_r <= opts.approximate_tol:
        return (
            "unreachable within the joint limits: configurations within IKOptions.approximate_tol = "
            f"{opts.approximate_tol:g} of the pose exist, but none within the joint limits"
        )
    text = "unreachable: no joint configuration reaches this pose"
    if np.isfinite(closest_p):
        text += (
            f" (the closest configuration found misses it by {closest_p:.3g} m / {closest_r:.3g} rad, "
            f"more than IKOptions.approximate_tol = {opts.approximate_tol:g})"
        )
    return text


def _continua(qrow: np.ndarray, irow: np.ndarray, arm: Arm, T: np.ndarray, opts: IKOptions) -> tuple:
    """The :class:`Continuum` of one row (empty for an isolated row)."""
    kind = int(irow[L.I_FREE])
    if kind == L.FREE_NONE:
        return ()
    rep = qrow.copy()
    rep.setflags(write=False)
    rev = arm.solver.reversed
    j3, j6 = (4, 1) if rev else (3, 6)  # solver joints 3 and 6 as user joints (1-based)
    tol = (opts.position_tol, opts.rotation_tol)
    Tc = np.array(T, dtype=float)
    Tc.setflags(write=False)
    if kind == L.FREE_Q3:
        if np.isnan(irow[L.I_CSIGN]):  # (a NumPy method: no interval from the kernel)
            return (
                Continuum("collinear", j3, j6, _numerical_sign(rep, arm, j3, j6), rep, None, arm, Tc, tol),
            )
        return (
            Continuum(
                "collinear",
                j3,
                j6,
                int(irow[L.I_CSIGN]),
                rep,
                (float(irow[L.I_CLO]), float(irow[L.I_CHI])),
                arm,
                Tc,
                tol,
            ),
        )
    if kind == L.FREE_NUMERICAL:
        return (Continuum("numerical", j3, j6, _numerical_sign(rep, arm, j3, j6), rep, None, arm, Tc, tol),)
    if kind == L.FREE_Q2:
        return (Continuum("theta2", 5 if rev else 2, None, 0, rep, None, arm, Tc, tol),)
    j1 = 6 if rev else 1
    return (Continuum("theta1", j1, None, 0, rep, None, arm, Tc, tol),)


def _numerical_sign(q: np.ndarray, arm: Arm, j: int, k: int) -> int:
    """+1 if moving joints j and k (1-based) by the same angle changes the pose least."""
    from ..kinematics import fk

    a, b = q.copy(), q.copy()
    a[j - 1] += 0.1
    a[k - 1] += 0.1
    b[j - 1] += 0.1
    b[k - 1] -= 0.1
    T0, Ta, Tb = fk(np.array([q, a, b]), arm)
    return 1 if np.abs(Ta - T0).sum() <= np.abs(Tb - T0).sum() else -1


_FREE_JOINTS = {
    L.FREE_NONE: lambda r: (),
    L.FREE_Q3: lambda r: (4, 1) if r else (3, 6),
    L.FREE_NUMERICAL: lambda r: (4, 1) if r else (3, 6),
    L.FREE_Q1: lambda r: (6,) if r else (1,),
    L.FREE_Q2: lambda r: (5,) if r else (2,),
    L.FREE_BAND: lambda r: (6,) if r else (1,),
}
#: The continuum code (FREE_*) of each kind of :class:`Continuum` (a numerical one without a
#: coupled joint: a band of joint 1).
_FREE_CODES = {
    "collinear": L.FREE_Q3, "theta1": L.FREE_Q1, "theta2": L.FREE_Q2, "numerical": L.FREE_NUMERICAL,
}


_CERTIFICATES: dict[tuple, Certificate] = {}


def _certificate(h) -> Certificate:
    """The :class:`Certificate` of a header row (a list; built once per distinct value)."""
    key = tuple(h[L.H_PATH : L.H_CERT + 1])
    hit = _CERTIFICATES.get(key)
    if hit is not None:
        return hit
    path, cert = int(h[L.H_PATH]), int(h[L.H_CERT])
    reason = "" if cert == L.CERT_OK else L.CERT_NAMES[cert]
    out = Certificate(reason=reason) if path < 0 else Certificate(  # (path < 0: a NumPy method)
        path=L.PATH_NAMES[path],
        certified=cert == L.CERT_OK,
        roots=int(h[L.H_ROOTS]),
        clusters=int(h[L.H_CLUSTERS]),
        near=int(h[L.H_NEAR]),
        reason=reason,
    )
    if len(_CERTIFICATES) > 4096:
        _CERTIFICATES.clear()
    _CERTIFICATES[key] = out
    return out


def _results(
    Tb, q, info, flags, hdr, method: str, opts: IKOptions, arm: Arm, within_only: bool
) -> list[IKResult]:
    """One :class:`IKResult` per pose: read-only views of the padded arrays."""
    for a in (q, info, flags):
        a.setflags(write=False)
    pres, rres = info[:, :, L.I_PRES], info[:, :, L.I_RRES]
    within, approx = flags[:, :, 0], flags[:, :, 1]
    rev = arm.solver.reversed
    out = []
    make = IKResult.trusted
    for i, h in enumerate(hdr.tolist()):
        k = int(h[L.H_COUNT])
        if h[L.H_FREE]:
            kinds = info[i, :k, L.I_FREE].astype(int).tolist()
            free = tuple(_FREE_JOINTS[f](rev) for f in kinds)
            cont = tuple(_continua(q[i, r], info[i, r], arm, Tb[i], opts) for r in range(k))
        else:
            free = cont = ((),) * k
        steps = _rewrites(h, within[i], Tb[i], arm, within_only)
        if steps & _DEGENERATE:
            out.append(
                _degenerate_result(Tb[i], q[i, :k], within[i, :k], cont, h, arm, opts, method, within_only)
            )
            continue
        isapprox = bool(h[L.H_APPROX])
        reason = (
            ""
            if (k and not isapprox)
            else _reason(k, int(h[L.H_TOTAL]), isapprox, h[L.H_BEST_P], h[L.H_BEST_R], opts)
        )
        out.append(
            make(
                q[i, :k],
                pres[i, :k],
                rres[i, :k],
                within[i, :k],
                free,
                reason,
                method,
                approx[i, :k],
                cont,
                float(h[L.H_PROJECTION]),
                _certificate(h),
            )
        )
        if steps & _INSIDE:
            out[-1] = _theta2_inside(out[-1], Tb[i], arm)
        if steps & _BANDS:
            out[-1] = _with_bands(out[-1], Tb[i], arm, opts)
    return out


#: What :func:`_results` does to a pose's kernel rows (:func:`_rewrites`), as bits: sort the
#: degenerate path's rows into theta1 continua and bands; move continuum rows outside the limits
#: into them; merge rows along bands of joint 1 beside a theta1 continuum.
_DEGENERATE, _INSIDE, _BANDS = 1, 2, 4


def _rewrites(h, within, T: np.ndarray, arm: Arm, within_only: bool) -> int:
    """What :func:`_results` does to the rows of one pose (bits ``_DEGENERATE | _INSIDE |
    _BANDS``; 0: they stand; always 0 for the NumPy methods): its header row h (a list), its rows'
    within-limits flags (MAX_SOLUTIONS,), the pose T (4, 4). The one rule behind :func:`solve`'s
    fast path, :func:`_results` and :func:`_changed` (:func:`solve_batch`)."""
    if h[L.H_PATH] == L.PATH_DEGENERATE:  # (with no row too: its certificate is the slow path's)
        return _DEGENERATE
    k = int(h[L.H_COUNT])
    steps = _INSIDE if within_only and h[L.H_FREE] and not within[:k].all() else 0
    return steps | (_BANDS if _band_candidate(h, T, arm) else 0)


#: Bands of joint 1 are looked for only with the wrist point within this fraction of the arm's
#: reach of the joint-1 axis (they exist beside a theta1 continuum: the family
#: near-wrist-on-axis1-theta4 puts the wrist point up to ~5e-4 of the reach off the axis).
BAND_AXIS_NEAR = 1e-3


def _band_candidate(h, T: np.ndarray, arm: Arm) -> bool:
    """May a pose T (4, 4) (its header row h, a list) of the complete method lie beside a theta1
    continuum without having taken the degenerate path: two or more rows from the extended or
    multiple-root path with near roots tried, and the wrist point (the origin of the solver
    chain's frame 6) within BAND_AXIS_NEAR of the reach from the joint-1 axis? (Never a pose of the
    double path: the usual case.)"""
    if not (h[L.H_PATH] == L.PATH_EXTENDED or h[L.H_PATH] == L.PATH_MULTIPLE):
        return False
    if h[L.H_NEAR] == 0 or h[L.H_COUNT] < 2:
        return False
    base_xy, tool_origin, near = _wrist_data(arm)
    if arm.solver.reversed:  # the solver solves the inverse pose: T^-1 applied to the point
        x = T[:3, :3].T @ (tool_origin[:3] - T[:3, 3])
    else:
        x = T[:3, :3] @ tool_origin[:3] + T[:3, 3]
    D = base_xy[:, :3] @ x + base_xy[:, 3]  # x, y of the wrist point in solver frame 0 (z: axis 1)
    return float(np.hypot(D[0], D[1])) <= near


_WRIST: dict[int, tuple] = {}


def _wrist_data(arm: Arm) -> tuple:
    """(rows x, y of the solver base's inverse (2, 4); the solver tool's inverse applied to the
    origin (4,) [m]; BAND_AXIS_NEAR times the reach [m]) of ``arm``, built once per arm object: the
    wrist point of a pose T is base^-1 T tool^-1 applied to the origin."""
    hit = _WRIST.get(id(arm))
    if hit is not None and hit[0] is arm:
        return hit[1]
    s = arm.solver
    data = (np.linalg.inv(s.base)[:2], np.linalg.inv(s.tool)[:, 3], BAND_AXIS_NEAR * arm.reach)
    if len(_WRIST) > 64:
        _WRIST.clear()
    _WRIST[id(arm)] = (arm, data)
    return data


def _theta2_inside(r: IKResult, T: np.ndarray, arm: Arm) -> IKResult:
    """With ``within_limits``: each theta2 continuum row outside the limits (the kernel keeps
    them) replaced by a member inside them, or left out if none is found."""
    import dataclasses

    from .compare import pose_residuals
    from .members import inside_member

    keep, rows, conts = [], [], []
    for i, cs in enumerate(r.continua):
        if r.within_limits[i]:
            keep.append(i)
            rows.append(r.q[i])
            conts.append(cs)
        elif cs and cs[0].kind == "theta2":
            m = inside_member(cs[0])
            if m is not None:
                m = _ro(m)
                keep.append(i)
                rows.append(m)
                conts.append((dataclasses.replace(cs[0], representative=m),))
    if len(keep) == r.count:
        return r
    Q = np.array(rows).reshape(-1, 6)
    pres, rres = pose_residuals(Q, np.broadcast_to(T, (len(Q), 4, 4)), arm)
    return dataclasses.replace(
        r, q=Q, position_residual=pres, rotation_residual=rres, within_limits=np.ones(len(Q), bool),
        free_joints=tuple(r.free_joints[i] for i in keep), approximate=r.approximate[keep],
        continua=tuple(conts),
        reason=r.reason or ("" if len(Q) else "no solution within the joint limits (a theta2 continuum "
                                              "has no member inside them)"),
    )


def _ro(a: np.ndarray) -> np.ndarray:
    a = np.array(a)
    a.setflags(write=False)
    return a


def _degenerate_result(T, q, within, cont, h, arm: Arm, opts: IKOptions, method: str, within_only: bool):
    """A degenerate pose's result: one row per branch of the theta1 continuum (its representative
    inside the limits when a member is) and the isolated solutions beside it."""
    import dataclasses

    from .compare import pose_residuals
    from .members import closes, inside_member, theta1_branches

    flagged = [r for r, c in enumerate(cont) if c]
    owner: list = [None] * len(cont)
    for r, o in zip(flagged, theta1_branches([cont[r][0] for r in flagged]), strict=True):
        owner[r] = None if o is None else flagged[o]
    rows, conts = [], []
    for r, o in enumerate(owner):
        if o is None:
            if within[r] or not within_only:
                rows.append(q[r])
                conts.append(())
        elif o == r:
            c = cont[r][0]
            rep = inside_member(c) if within_only else c.representative
            if rep is not None:
                rep = np.array(rep)
                rep.setflags(write=False)
                rows.append(rep)
                conts.append((dataclasses.replace(c, representative=rep),))
    cert, approx, total = _certificate(h), False, int(h[L.H_TOTAL])
    if all(o is None for o in owner):  # no theta1 continuum reaches the pose: the slow path
        exact, total = _with_reference(T, rows, arm, opts, within_only, total)
        approx = not exact and bool(h[L.H_APPROX])  # else the kernel's approximate rows, flagged
        rows = rows if approx else exact
        conts = [()] * len(rows)
        cert = dataclasses.replace(cert, path=L.SLOW_PATH, certified=False,
                                   reason=_NO_CONTINUUM + (_APPROXIMATE if approx else ""))
    elif not all(closes(c[0]) for c in conts if c):  # a band beside the theta1 continuum
        cert = dataclasses.replace(cert, certified=False, reason=_NOT_CLOSED)
    if not approx:
        keep, conts = _bands(rows, conts, T, arm, opts)
        rows = [rows[i] for i in keep]
    Q = np.array(rows).reshape(-1, 6)
    pres, rres = pose_residuals(Q, np.broadcast_to(T, (len(Q), 4, 4)), arm) if len(Q) else (np.zeros(0),) * 2
    free = tuple(_FREE_JOINTS[L.FREE_Q1](arm.solver.reversed) if c else () for c in conts)  # (bands too)
    Q, inside = into_limits(Q, arm.q_min, arm.q_max, LIMIT_TOL)
    reason = "" if len(Q) else _reason(0, total, False, h[L.H_BEST_P], h[L.H_BEST_R], opts)
    reason = reason or cert.reason
    return IKResult.trusted(
        _ro(Q),
        _ro(pres),
        _ro(rres),
        _ro(np.atleast_1d(inside)),
        free,
        reason,
        method,
        _ro(np.full(len(Q), approx)),
        tuple(conts),
        float(h[L.H_PROJECTION]),
        cert,
    )


_NO_CONTINUUM = (
    "the eliminant vanishes within its rounding on the whole circle (taken for a theta1 continuum), "
    "but no theta1 continuum reaches the pose within the tolerances: its isolated roots cannot be "
    "told from the rounding, so the rows are merged with the NumPy reference's (slow path)"
)


_NOT_CLOSED = (
    "the theta1 continuum's members do not close around the circle: it is a band of joint 1 "
    "beside the continuum (the wrist point just off the joint-1 axis), whose branches and "
    "isolated solutions are found by restarts, not proven complete"
)


def _bands(rows, conts, T, arm: Arm, opts: IKOptions) -> tuple[list, list]:
    """The isolated rows (6,) [rad] of a degenerate pose sorted into bands of joint 1
    (:func:`iik.ik.members.theta1_bands`): beside the theta1 continuum the configurations within
    the tolerance fill intervals of joint 1, on which the rounded eliminant's roots fall anywhere.
    One row per band, flagged as a ``"numerical"`` continuum of joint 1 (no coupled joint: its
    members hold joint 1 and refit the others): the indices of the rows kept and their continua
    (the other rows' unchanged)."""
    from .members import theta1_bands

    iso = [i for i, c in enumerate(conts) if not c]
    if not iso:
        return list(range(len(rows))), list(conts)
    Tc = _ro(np.array(T, dtype=float))
    j1, tol = (6 if arm.solver.reversed else 1), (opts.position_tol, opts.rotation_tol)
    bands = [Continuum("numerical", j1, None, 0, _ro(rows[i]), None, arm, Tc, tol) for i in iso]
    owner = dict(zip(iso, theta1_bands(bands), strict=True))
    keep, out = [], []
    for i, c in enumerate(conts):
        o = owner.get(i)
        if c or o is None or iso[o] == i:
            keep.append(i)
            out.append(c if c or o is None else (bands[o],))
    return keep, out


def _with_bands(r: IKResult, T, arm: Arm, opts: IKOptions) -> IKResult:
    """:func:`_bands` on a result of the extended or multiple-root path with near roots (beside
    the theta1 continuum, farther from it than the degenerate path reaches, the eliminant's near
    roots fall along the bands of joint 1): one flagged row per band. The certificate does not
    hold then: the bands are found by restarts, not proven complete (the 10^5-pose run of
    near-wrist-on-axis1-theta4 counted q* missed on one such pose, certified)."""
    import dataclasses

    if r.count < 1 or r.approximate.any():
        return r
    keep, conts = _bands(list(r.q), list(r.continua), T, arm, opts)
    if not any(c and c[0].band for c in conts):
        return r
    free = tuple(
        _FREE_JOINTS[L.FREE_BAND](arm.solver.reversed) if c and c[0].band else r.free_joints[i]
        for i, c in zip(keep, conts, strict=True)
    )
    cert = dataclasses.replace(r.certificate, certified=False, reason=_BANDS_FOUND)
    return dataclasses.replace(r.rows(keep), free_joints=free, continua=tuple(conts), certificate=cert)


_BANDS_FOUND = (
    "rows along bands of joint 1 beside a theta1 continuum (the wrist point just off the joint-1 "
    "axis): the bands are found by restarts, not proven complete"
)


_APPROXIMATE = (
    "; neither the kernel's rows nor the reference's reach it within the tolerances: the rows "
    "returned are the kernel's within IKOptions.approximate_tol, flagged approximate (an exact "
    "solution may still have been missed)"
)


def _with_reference(T, rows, arm: Arm, opts: IKOptions, within_only: bool, total: int) -> tuple[list, int]:
    """The rows (6,) [rad] and those of the NumPy reference for pose T, each only if it reaches
    the pose within the tolerances (the kernel's rows of a degenerate pose include its
    approximate candidates) and is not already among them (1e-9 rad in every joint, wrapped);
    and how many solutions exist, inside the limits or not (the larger of ``total``, the
    kernel's count, and the reference's)."""
    from .compare import pose_residuals

    rq, _, _, rhdr = _numpy_method(T[None], arm, opts, within_only, "reference")
    total = max(total, int(rhdr[0, L.H_TOTAL]))
    both = np.array(list(rows) + list(rq[0, : int(rhdr[0, L.H_COUNT])])).reshape(-1, 6)
    pres, rres = pose_residuals(both, np.broadcast_to(T, (len(both), 4, 4)), arm)
    out: list = []
    for x in both[(pres <= opts.position_tol) & (rres <= opts.rotation_tol)]:
        if not out or np.min(np.max(np.abs(wrap_angle(np.array(out) - x)), axis=1)) > 1e-9:
            out.append(x)
    return out, total


# ----------------------------------------------------------------------------- public API
def solve(
    T,
    arm: Arm,
    *,
    method: str = "complete",
    within_limits: bool = True,
    options: IKOptions | None = None,
) -> IKResult:
    """All inverse-kinematics solutions of one tool pose.

    Args:
        T: Tool pose in the arm's base frame, (4, 4) homogeneous, position in m.
        arm: The arm (:class:`iik.Arm`; :mod:`iik.arms` lists the shipped ones).
        method: ``"complete"`` (compiled elimination; every solution, with a certificate),
            ``"reference"`` (an independent NumPy solver of the same class) or ``"thesis"``
            (Sec 3.3 as printed, with the errata corrected; arms of the thesis's form).
        within_limits: Keep only solutions inside the joint limits (Table I).
        options: Tolerances (:class:`~iik.ik.options.IKOptions`; defaults documented there).

    Returns:
        :class:`IKResult`. An unreachable pose gives an empty result with ``reason``
        (``result.raise_if_unreachable()`` raises instead); a pose just out of reach (within
        ``options.approximate_tol``) gives its least-residual configurations, flagged
        ``approximate``. ``result.certificate`` says which path the pose took.

    Raises:
        InvalidInputError: wrong shape, NaN/inf, bad bottom row, a reflection, unknown method.
        NotOrthonormalError: a rotation block farther than ``options.orthonormal_tol`` from
            orthonormal (says how far, and which option to change).
    """
    opts = _check_args(method, options, arm)
    if type(T) is np.ndarray and T.dtype is _F64 and T.shape == (4, 4):
        Tb, batched = T[None], False  # fast path: no copy
    else:
        Tb, batched = _poses.as_pose_batch(T, "T")
        if batched:
            raise InvalidInputError("T", f"expected one (4, 4) pose, got shape {Tb.shape}; use solve_many")
    q, info, flags, hdr = _run(Tb, arm, opts, within_limits, method)
    h = hdr[0].tolist()
    if h[L.H_STATUS] != _poses.OK:
        _raise_first_bad(hdr, "T", False, opts)
    if method == "complete" and h[L.H_COUNT] and not (h[L.H_FREE] or h[L.H_APPROX]) and (
        h[L.H_PATH] == L.PATH_DOUBLE or not _rewrites(h, flags[0, :, 0], Tb[0], arm, within_limits)
    ):  # (the double path: never rewritten, the usual pose's shortcut)
        return _isolated_result(q, info, flags, h)
    return _results(Tb, q, info, flags, hdr, method, opts, arm, within_limits)[0]


_EMPTY = tuple(((),) * k for k in range(L.MAX_SOLUTIONS + 1))


def _isolated_result(q, info, flags, h) -> IKResult:
    """:func:`_results` for one pose whose rows are all isolated exact solutions (the usual
    case), with less Python: what a single call's time is mostly made of."""
    k = int(h[L.H_COUNT])
    q.setflags(False), info.setflags(False), flags.setflags(False)  # (write; positional: cheaper)
    return IKResult.trusted(
        q[0, :k], info[0, :k, L.I_PRES], info[0, :k, L.I_RRES], flags[0, :k, 0], _EMPTY[k], "",
        "complete", flags[0, :k, 1], _EMPTY[k], h[L.H_PROJECTION], _certificate(h),
    )


def solve_many(
    Ts,
    arm: Arm,
    *,
    method: str = "complete",
    within_limits: bool = True,
    options: IKOptions | None = None,
) -> list[IKResult]:
    """:func:`solve` for a batch (n, 4, 4) of poses; identical answers, one result per pose.

    The compiled kernel runs once over the batch (on all cores with
    ``IKOptions(parallel=True)``).
    """
    opts = _check_args(method, options, arm)
    Tb, batched = _poses.as_pose_batch(Ts, "Ts")
    q, info, flags, hdr = _run(Tb, arm, opts, within_limits, method)
    _raise_first_bad(hdr, "Ts", batched, opts)
    return _results(Tb, q, info, flags, hdr, method, opts, arm, within_limits)


def solve_batch(
    Ts,
    arm: Arm,
    *,
    method: str = "complete",
    within_limits: bool = True,
    options: IKOptions | None = None,
) -> IKBatch:
    """:func:`solve_many` as padded arrays (:class:`IKBatch`): no Python object per pose."""
    opts = _check_args(method, options, arm)
    Tb, batched = _poses.as_pose_batch(Ts, "Ts")
    q, info, flags, hdr = _run(Tb, arm, opts, within_limits, method)
    _raise_first_bad(hdr, "Ts", batched, opts)
    certified = _settled(Tb, q, info, flags, hdr, arm, opts, within_limits)
    count = hdr[:, L.H_COUNT].astype(int)  # (rows past the count are padding: NaN / free 0 / False)
    for a in (q, info, flags):
        a.setflags(write=False)
    out = [
        count,
        hdr[:, L.H_TOTAL].astype(int),
        hdr[:, L.H_PROJECTION].copy(),
        hdr[:, L.H_BEST_P : L.H_BEST_R + 1].copy(),
        info[:, :, L.I_FREE].astype(int),
        hdr[:, L.H_PATH].astype(int),
        certified,
    ]
    for a in out:
        a.setflags(write=False)
    return IKBatch(
        q=q,
        count=out[0],
        position_residual=info[:, :, L.I_PRES],
        rotation_residual=info[:, :, L.I_RRES],
        within_limits=flags[:, :, 0],
        approximate=flags[:, :, 1],
        free=out[4],
        info=info,
        total=out[1],
        rotation_projection=out[2],
        closest=out[3],
        path=out[5],
        certified=out[6],
        method=method,
    )


def _settled(Tb, q, info, flags, hdr, arm: Arm, opts: IKOptions, within_only: bool) -> np.ndarray:
    """The padded outputs of poses Tb (n, 4, 4) made :func:`solve_many`'s answer, in place: the
    poses whose kernel rows :func:`_results` changes (:func:`_changed`) are solved into an
    :class:`IKResult` and written back (:func:`_write_result`). Returns the certified mask (n,)."""
    certified = hdr[:, L.H_CERT] == L.CERT_OK  # (every degenerate pose is among those changed)
    idx = _changed(Tb, flags, hdr, arm, within_only)
    if not idx:
        return certified
    res = _results(Tb[idx], q[idx], info[idx], flags[idx], hdr[idx], "complete", opts, arm, within_only)
    for i, r in zip(idx, res, strict=True):
        _write_result(r, q[i], info[i], flags[i], hdr[i])
        certified[i] = r.certificate.certified
    return certified


def _changed(Tb, flags, hdr, arm: Arm, within_only: bool) -> list[int]:
    """The poses whose kernel rows :func:`_results` changes (:func:`_rewrites`), asked only of
    those off the double path or with a continuum row: the usual batch costs no Python."""
    maybe = (hdr[:, L.H_PATH] != L.PATH_DOUBLE) | (hdr[:, L.H_FREE] > 0)
    if not maybe.any():
        return []
    return [i for i in np.flatnonzero(maybe).tolist()
            if _rewrites(hdr[i].tolist(), flags[i, :, 0], Tb[i], arm, within_only)]


def _write_result(r: IKResult, q: np.ndarray, info: np.ndarray, flags: np.ndarray, h: np.ndarray) -> None:
    """One pose's :class:`IKResult` into its padded rows q (16, 6), info (16, N_INFO), flags
    (16, 2) and header h (N_HDR,). Columns only the kernel knows (I_KIND, I_H3) are NaN."""
    k = r.count
    q[:], info[:], flags[:] = np.nan, np.nan, False
    q[:k], info[:, L.I_FREE] = r.q, L.FREE_NONE
    info[:k, L.I_PRES], info[:k, L.I_RRES] = r.position_residual, r.rotation_residual
    flags[:k, 0], flags[:k, 1] = r.within_limits, r.approximate
    for j, cs in enumerate(r.continua):
        if cs:
            c = cs[0]
            info[j, L.I_FREE], info[j, L.I_CSIGN] = L.FREE_BAND if c.band else _FREE_CODES[c.kind], c.sign
            if c.limits_interval is not None:
                info[j, L.I_CLO], info[j, L.I_CHI] = c.limits_interval
    h[L.H_COUNT], h[L.H_FREE], h[L.H_APPROX] = k, sum(map(bool, r.continua)), float(r.approximate.any())
    if r.certificate.path == L.SLOW_PATH:
        h[L.H_PATH] = L.PATH_REFERENCE


#: What :func:`compile_notice` says.
COMPILE_MESSAGE = "compiling the IK kernel, once"


@contextmanager
def compile_notice(emit: Callable[[str], None] | None = None) -> Iterator[None]:
    """Say :data:`COMPILE_MESSAGE` (one line) when Numba starts compiling a function of the
    project inside the block: on the first call after an install (or after the kernel's
    sources changed), about 10-20 s. Loading the compiled kernel from its on-disk cache, as
    every later process does, compiles nothing and says nothing, however long a loaded
    machine takes to load it. (``IKOptions(parallel=True)`` compiles its own entry point on
    its first use: also said.)

    Args:
        emit: Receives the message (default: print to stderr).
    """
    from numba.core import event

    say = emit or (lambda m: print(m, file=sys.stderr, flush=True))
    said: list[bool] = []

    class _FirstCompile(event.Listener):
        def on_start(self, ev) -> None:
            func = getattr(ev.data.get("dispatcher"), "py_func", None)
            if not said and getattr(func, "__module__", "").startswith("iik."):
                said.append(True)
                say(COMPILE_MESSAGE)

        def on_end(self, ev) -> None:
            pass

    with event.install_listener("numba:compile", _FirstCompile()):
        yield


@contextmanager
def compile_clock(on_compiled: Callable[[float], None]) -> Iterator[None]:
    """Report the wall time [s] of each Numba compilation that starts inside the block (the
    outermost one of a nested chain: the kernel's entry points compile their helpers), so a
    caller with a deadline can leave the one-time compile out of it (``iik.planning.Budget``:
    a first plan after an install, or several processes compiling at once on a loaded machine,
    took 70-120 s of compiling). Loading the compiled kernel from its cache reports nothing.

    Args:
        on_compiled: Called with the seconds each compilation took, when it ends.
    """
    from numba.core import event

    depth, began = [0], [0.0]

    class _Clock(event.Listener):
        def on_start(self, ev) -> None:
            if depth[0] == 0:
                began[0] = time.perf_counter()
            depth[0] += 1

        def on_end(self, ev) -> None:
            depth[0] -= 1
            if depth[0] == 0:
                on_compiled(time.perf_counter() - began[0])

    with event.install_listener("numba:compile", _Clock()):
        yield
