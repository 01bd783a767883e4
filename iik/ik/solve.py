"""Public inverse-kinematics entry points: :func:`solve` and :func:`solve_many`.

``method="complete"`` (default) is the elimination solver of
:mod:`iik.ik.complete` (all solutions, cannot miss a root);
``method="thesis"`` is the Sec 3.3 IIK (theta1 grid + bisection) of
:mod:`iik.ik.thesis`, kept to reproduce and measure the thesis.
"""

from __future__ import annotations

import numpy as np

from ..arm import LIMIT_TOL, THESIS_ARM, Arm
from ..errors import InvalidInputError
from ..validation import as_poses
from . import complete as _complete
from .result import IKResult

__all__ = ["solve", "solve_many", "METHODS"]

METHODS = ("complete", "thesis")

_FREE = {_complete.FREE_Q1_Q6: (1, 6), _complete.FREE_Q3_Q6: (3, 6),
         _complete.FREE_Q1_Q6 | _complete.FREE_Q3_Q6: (1, 3, 6)}


def _check_method(method: str) -> None:
    if method not in METHODS:
        raise InvalidInputError("method", f"expected one of {METHODS}, got {method!r}")


def _readonly(a):
    a.setflags(write=False)
    return a


def _build_all(q, valid, flags, pres, rres, arm, within_limits, method):
    """One :class:`IKResult` per pose from the padded arrays (n, S, ...) of a solver.

    Vectorised over the batch: the limit test runs once on all rows; each result
    holds read-only views of one compacted copy.
    """
    lo, hi = arm.q_min, arm.q_max
    inside = np.all((q >= lo - LIMIT_TOL) & (q <= hi + LIMIT_TOL), axis=-1)
    # a continuum representative stands for q within CONTINUUM_TOL of it
    tol_c = _complete.CONTINUUM_TOL
    inside |= (flags > 0) & np.all((q >= lo - tol_c) & (q <= hi + tol_c), axis=-1)
    inside &= valid
    total = valid.sum(axis=1)
    keep = inside if within_limits else valid
    counts = keep.sum(axis=1)
    qq = _readonly(q[keep])
    pp, rr = _readonly(pres[keep]), _readonly(rres[keep])
    ii, ff = _readonly(inside[keep]), flags[keep].tolist()
    bounds = np.concatenate([[0], np.cumsum(counts)]).tolist()
    anyflag = np.any((flags > 0) & keep, axis=1).tolist()
    out = []
    for i, (k, t) in enumerate(zip(counts.tolist(), total.tolist(), strict=True)):
        a, b = bounds[i], bounds[i + 1]
        if k == 0:
            reason = ("unreachable: no joint configuration reaches this pose" if t == 0 else
                      f"{t} solution(s) exist but none within the joint limits (Table I)")
        else:
            reason = ""
        free = tuple(_FREE.get(f, ()) for f in ff[a:b]) if anyflag[i] else ((),) * k
        out.append(IKResult._trusted(qq[a:b], pp[a:b], rr[a:b], ii[a:b], free, reason, method, {}))
    return out


def solve(T, *, method: str = "complete", within_limits: bool = True,
          arm: Arm = THESIS_ARM) -> IKResult:
    """All inverse-kinematics solutions of one end-effector pose.

    Args:
        T: Pose of frame 6 in base frame 0, (4, 4) homogeneous, position in m.
        method: ``"complete"`` (elimination; every solution) or ``"thesis"``
            (Sec 3.3 as printed, with the errata corrected).
        within_limits: Keep only solutions inside the joint limits (Table I).
        arm: Arm parameters.

    Returns:
        :class:`IKResult`. An unreachable pose gives an empty result with ``reason``.

    Raises:
        InvalidInputError: wrong shape, NaN/inf, non-orthonormal rotation, unknown method.
    """
    _check_method(method)
    Tb, batched = as_poses(T, "T")
    if batched:
        raise InvalidInputError("T", f"expected one (4, 4) pose, got shape {Tb.shape}; use solve_many")
    return _solve_batch(Tb, method, within_limits, arm)[0]


def solve_many(Ts, *, method: str = "complete", within_limits: bool = True,
               arm: Arm = THESIS_ARM) -> list[IKResult]:
    """:func:`solve` for a batch (n, 4, 4) of poses (vectorised); identical answers."""
    _check_method(method)
    Tb, _ = as_poses(Ts, "Ts")
    return _solve_batch(Tb, method, within_limits, arm)


def _solve_batch(Tb, method, within_limits, arm):
    if method == "thesis":
        from .thesis import solve_thesis_arrays

        arrays = solve_thesis_arrays(Tb, arm)
    else:
        arrays = _complete.solve_arrays(Tb, arm)
    return _build_all(*arrays, arm, within_limits, method)
