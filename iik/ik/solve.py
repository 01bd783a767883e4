"""Public inverse-kinematics entry points: :func:`solve`, :func:`solve_many`, :func:`solve_batch`.

Methods:

* ``"complete"`` (default): the compiled kernel (:mod:`iik.ik.kernel`): every solution,
  real roots of the eliminant isolated so that none can be missed.
* ``"reference"``: the same elimination vectorised in NumPy (:mod:`iik.ik.reference`),
  kept as an independent reference; the two agree (tested on 10^5 poses).
* ``"thesis"``: the Sec 3.3 IIK (theta1 grid + bisection, errata corrected,
  :mod:`iik.ik.thesis`), kept to reproduce and measure the thesis.

Every method takes the same options (:class:`~iik.ik.options.IKOptions`): rotations
within ``orthonormal_tol`` of orthonormal are projected and solved. Only the complete
method returns approximate configurations for poses just out of reach.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager

import numpy as np

from ..arm import LIMIT_TOL, THESIS_ARM, Arm
from ..errors import InvalidInputError
from ..kinematics import reach_bound
from . import poses as _poses
from .options import DEFAULT_OPTIONS, IKOptions
from .result import Continuum, IKBatch, IKResult

__all__ = ["solve", "solve_many", "solve_batch", "METHODS", "compile_notice", "COMPILE_MESSAGE"]

METHODS = ("complete", "reference", "thesis")

_F64 = np.dtype(np.float64)
_FREE = {0: (), 1: (1, 6), 2: (3, 6), 3: (1, 3, 6), 4: (3, 6)}  # 4: numerical (kernel)
_NO_FREE: dict[int, tuple] = {}
_KERNEL = None
_OPT_VECTORS: dict[int, tuple[IKOptions, np.ndarray]] = {}


def _kernel():
    """The compiled kernel module (imported on first use; Numba loads then)."""
    global _KERNEL
    if _KERNEL is None:
        from . import kernel

        _KERNEL = kernel
    return _KERNEL


def _check_args(method, options) -> IKOptions:
    if method not in METHODS:
        raise InvalidInputError("method", f"expected one of {METHODS}, got {method!r}")
    if options is None:
        return DEFAULT_OPTIONS
    if not isinstance(options, IKOptions):
        raise InvalidInputError("options", f"expected an IKOptions, got {type(options).__name__}")
    return options


def _option_vector(opts: IKOptions) -> np.ndarray:
    hit = _OPT_VECTORS.get(id(opts))
    if hit is not None and hit[0] is opts:
        return hit[1]
    v = np.array([opts.position_tol, opts.rotation_tol, opts.approximate_tol, opts.orthonormal_tol,
                  LIMIT_TOL])  # the kernel's OPT_* layout
    v.setflags(write=False)
    if len(_OPT_VECTORS) > 64:
        _OPT_VECTORS.clear()
    _OPT_VECTORS[id(opts)] = (opts, v)
    return v


# ----------------------------------------------------------------------------- the methods
def _complete(Tb: np.ndarray, arm: Arm, opts: IKOptions, within: bool):
    """Kernel outputs (q, info, flags, hdr) for validated-shape poses (n, 4, 4)."""
    k = _kernel()
    n = Tb.shape[0]
    q = np.empty((n, k.MAX_SOLUTIONS, 6))  # the kernel writes the padding too
    info = np.empty((n, k.MAX_SOLUTIONS, k.N_INFO))
    flags = np.empty((n, k.MAX_SOLUTIONS, 2), dtype=bool)
    hdr = np.empty((n, k.N_HDR))
    Tc = Tb if Tb.flags.c_contiguous else np.ascontiguousarray(Tb)
    if opts.parallel and n > 1:
        k.solve_many_parallel(Tc, k.arm_data(arm).vector, _option_vector(opts), within, q, info, flags, hdr)
    else:
        k.solve_many(Tc, k.arm_data(arm).vector, _option_vector(opts), within, k.scratch(), q, info,
                     flags, hdr)
    return q, info, flags, hdr


def _beyond_reach(Tb: np.ndarray, arm: Arm) -> np.ndarray:
    """Poses (n, 4, 4) whose position is farther than :func:`iik.kinematics.reach_bound` from the
    base origin (compared without squaring huge numbers: no overflow)."""
    with np.errstate(invalid="ignore"):  # (NaN positions are rejected by the pose check)
        p = np.abs(Tb[:, :3, 3])
        r = reach_bound(arm)
        big = p.max(axis=1) > r
        p = np.where(big[:, None], 0.0, p)
        return big | (np.einsum("ni,ni->n", p, p) > r * r)


def _numpy_method(Tb: np.ndarray, arm: Arm, opts: IKOptions, within: bool, method: str):
    """The reference or thesis method in the kernel's output layout."""
    from .compare import pose_residuals

    k = _kernel()  # (for its output layout)
    n = Tb.shape[0]
    status, measure, Ru, dist = _poses.check_poses(Tb, opts.orthonormal_tol)
    hdr = np.zeros((n, k.N_HDR))
    hdr[:, k.H_STATUS], hdr[:, k.H_MEASURE], hdr[:, k.H_PROJECTION] = status, measure, dist
    hdr[:, k.H_BEST_P], hdr[:, k.H_BEST_R] = np.inf, np.inf
    q = np.full((n, k.MAX_SOLUTIONS, 6), np.nan)
    info = np.full((n, k.MAX_SOLUTIONS, k.N_INFO), np.nan)
    info[:, :, k.I_FREE] = 0.0  # padding as the kernel writes it
    flags = np.zeros((n, k.MAX_SOLUTIONS, 2), dtype=bool)
    good = np.flatnonzero((status == _poses.OK) & ~_beyond_reach(Tb, arm))  # far: unreachable, no arithmetic
    if len(good) == 0:
        return q, info, flags, hdr
    Tu = Tb[good].copy()
    Tu[:, :3, :3] = Ru[good]
    if method == "thesis":
        from .thesis import solve_thesis_arrays

        Q, V, F, _P, _R = solve_thesis_arrays(Tu, arm)
    else:
        from .reference import solve_arrays

        Q, V, F, _P, _R = solve_arrays(Tu, arm, tol_p=opts.position_tol, tol_r=opts.rotation_tol)
    inside = arm.within_limits(Q.reshape(-1, 6)).reshape(Q.shape[:2]) & V
    keep = inside if within else V
    hdr[good, k.H_TOTAL] = V.sum(axis=1)
    for gi, i in enumerate(good):  # rows are sorted valid-first: keep them in order
        rows = np.flatnonzero(keep[gi])
        m = len(rows)
        hdr[i, k.H_COUNT] = m
        if m == 0:
            continue
        q[i, :m] = Q[gi, rows]
        pres, rres = pose_residuals(Q[gi, rows], np.broadcast_to(Tb[i], (m, 4, 4)), arm)
        info[i, :m, k.I_PRES], info[i, :m, k.I_RRES], info[i, :m, k.I_FREE] = pres, rres, F[gi, rows]
        flags[i, :m, 0] = inside[gi, rows]
        hdr[i, k.H_FREE] = np.count_nonzero(F[gi, rows])
    return q, info, flags, hdr


def _run(Tb, arm, opts, within, method):
    if method == "complete":
        return _complete(Tb, arm, opts, within)
    return _numpy_method(Tb, arm, opts, within, method)


def _raise_first_bad(hdr, name: str, batched: bool, opts: IKOptions) -> None:
    bad = np.flatnonzero(hdr[:, 0] != _poses.OK)
    if len(bad):
        i = int(bad[0])
        raise _poses.pose_error(int(hdr[i, 0]), float(hdr[i, 1]), name, i if batched else None,
                                opts.orthonormal_tol)


# ----------------------------------------------------------------------------- results
def _reason(count: int, total: int, approx: bool, closest_p: float, closest_r: float, opts: IKOptions) -> str:
    if count and not approx:
        return ""
    if count:
        return (f"approximate: no configuration reaches the pose within the tolerances "
                f"({opts.position_tol:g} m, {opts.rotation_tol:g} rad); the {count} configuration(s) "
                f"returned are within IKOptions.approximate_tol = {opts.approximate_tol:g} of it "
                "(least-residual configurations, flagged approximate)")
    if total:
        return f"{total} solution(s) exist but none within the joint limits (Table I)"
    if closest_p <= opts.approximate_tol and closest_r <= opts.approximate_tol:
        return ("unreachable within the joint limits: configurations within IKOptions.approximate_tol = "
                f"{opts.approximate_tol:g} of the pose exist, but none within the joint limits (Table I)")
    text = "unreachable: no joint configuration reaches this pose"
    if np.isfinite(closest_p):
        text += (f" (the closest configuration found misses it by {closest_p:.3g} m / {closest_r:.3g} rad, "
                 f"more than IKOptions.approximate_tol = {opts.approximate_tol:g})")
    return text


def _continua(qrow: np.ndarray, free: int, cont: np.ndarray) -> tuple[Continuum, ...]:
    out = []
    for bit, j, base in ((1, 1, 0), (2, 3, 3)):
        s, lo, hi = cont[base], cont[base + 1], cont[base + 2]
        if free & bit and not np.isnan(s):  # no data: a numerical continuum (or a NumPy method)
            rep = qrow.copy()
            rep.setflags(write=False)
            val = float(qrow[j - 1] - s * qrow[5])
            val = float(np.pi - (np.pi - val) % (2 * np.pi))
            out.append(Continuum(free_joint=j, sign=int(s), value=val, interval=(float(lo), float(hi)),
                                 representative=rep))
    return tuple(out)


def _results(q, info, flags, hdr, method: str, opts: IKOptions) -> list[IKResult]:
    """One :class:`IKResult` per pose: read-only views of the padded arrays."""
    for a in (q, info, flags):
        a.setflags(write=False)
    pres, rres = info[:, :, 0], info[:, :, 1]
    within, approx = flags[:, :, 0], flags[:, :, 1]
    out = []
    make = IKResult.trusted
    for i, (_st, _m, proj, total, count, cp, cr, nfree, isapprox) in enumerate(hdr.tolist()):
        k = int(count)
        if nfree:
            kinds = info[i, :k, 4].astype(int).tolist()
            free = tuple(_FREE[f] for f in kinds)
            cont = tuple(_continua(q[i, r], f, info[i, r, 5:11]) for r, f in enumerate(kinds))
        else:
            free = cont = ((),) * k
        reason = "" if (k and not isapprox) else _reason(k, int(total), bool(isapprox), cp, cr, opts)
        out.append(make(q[i, :k], pres[i, :k], rres[i, :k], within[i, :k], free, reason, method,
                        approx[i, :k], cont, proj))
    return out


# ----------------------------------------------------------------------------- public API
def solve(T, *, method: str = "complete", within_limits: bool = True, arm: Arm = THESIS_ARM,
          options: IKOptions | None = None) -> IKResult:
    """All inverse-kinematics solutions of one end-effector pose.

    Args:
        T: Pose of frame 6 in base frame 0, (4, 4) homogeneous, position in m.
        method: ``"complete"`` (compiled elimination; every solution), ``"reference"`` (the
            same in NumPy) or ``"thesis"`` (Sec 3.3 as printed, with the errata corrected).
        within_limits: Keep only solutions inside the joint limits (Table I).
        arm: Arm parameters.
        options: Tolerances (:class:`~iik.ik.options.IKOptions`; defaults documented there).

    Returns:
        :class:`IKResult`. An unreachable pose gives an empty result with ``reason``
        (``result.raise_if_unreachable()`` raises instead); a pose just out of reach (within
        ``options.approximate_tol``) gives its least-residual configurations, flagged
        ``approximate``.

    Raises:
        InvalidInputError: wrong shape, NaN/inf, bad bottom row, a reflection, unknown method.
        NotOrthonormalError: a rotation block farther than ``options.orthonormal_tol`` from
            orthonormal (says how far, and which option to change).
    """
    opts = _check_args(method, options)
    if type(T) is np.ndarray and T.dtype is _F64 and T.shape == (4, 4):
        Tb, batched = T.reshape(1, 4, 4), False  # fast path: no copy
    else:
        Tb, batched = _poses.as_pose_batch(T, "T")
        if batched:
            raise InvalidInputError("T", f"expected one (4, 4) pose, got shape {Tb.shape}; use solve_many")
    q, info, flags, hdr = _run(Tb, arm, opts, within_limits, method)
    if hdr[0, 0] != _poses.OK:
        _raise_first_bad(hdr, "T", False, opts)
    return _results(q, info, flags, hdr, method, opts)[0]


def solve_many(Ts, *, method: str = "complete", within_limits: bool = True, arm: Arm = THESIS_ARM,
               options: IKOptions | None = None) -> list[IKResult]:
    """:func:`solve` for a batch (n, 4, 4) of poses; identical answers, one result per pose.

    The compiled kernel runs once over the batch (on all cores with
    ``IKOptions(parallel=True)``).
    """
    opts = _check_args(method, options)
    Tb, batched = _poses.as_pose_batch(Ts, "Ts")
    q, info, flags, hdr = _run(Tb, arm, opts, within_limits, method)
    _raise_first_bad(hdr, "Ts", batched, opts)
    return _results(q, info, flags, hdr, method, opts)


def solve_batch(Ts, *, method: str = "complete", within_limits: bool = True, arm: Arm = THESIS_ARM,
                options: IKOptions | None = None) -> IKBatch:
    """:func:`solve_many` as padded arrays (:class:`IKBatch`): no Python object per pose."""
    opts = _check_args(method, options)
    Tb, batched = _poses.as_pose_batch(Ts, "Ts")
    q, info, flags, hdr = _run(Tb, arm, opts, within_limits, method)
    _raise_first_bad(hdr, "Ts", batched, opts)
    count = hdr[:, 4].astype(int)  # (rows past the count are padding: NaN / free 0 / False)
    for a in (q, info, flags):
        a.setflags(write=False)
    out = [count, hdr[:, 3].astype(int), hdr[:, 2].copy(), hdr[:, 5:7].copy(), info[:, :, 4].astype(int)]
    for a in out:
        a.setflags(write=False)
    return IKBatch(q=q, count=out[0], position_residual=info[:, :, 0], rotation_residual=info[:, :, 1],
                   within_limits=flags[:, :, 0], approximate=flags[:, :, 1], free=out[4],
                   continuum=info[:, :, 5:11], total=out[1], rotation_projection=out[2], closest=out[3],
                   method=method)


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
