"""Public inverse-kinematics entry points: :func:`solve` and :func:`solve_many`.

``method="complete"`` (default) is the elimination solver of
:mod:`iik.ik.complete` (all solutions, cannot miss a root);
``method="thesis"`` is the Sec 3.3 IIK (theta1 grid + bisection) of
:mod:`iik.ik.thesis`, kept to reproduce and measure the thesis.
"""

from __future__ import annotations

import numpy as np

from .._validate import as_poses
from ..arm import THESIS_ARM, Arm
from ..errors import InvalidInputError
from . import complete as _complete
from .result import IKResult

__all__ = ["solve", "solve_many", "METHODS"]

METHODS = ("complete", "thesis")
#: A solution on a joint stop of a near-singular pose may come out slightly outside it
#: (the pose fixes q only to ~eps / sigma_min there); accept this much [rad].
LIMIT_TOL = 1e-7

_FREE = {_complete.FREE_Q1_Q6: (1, 6), _complete.FREE_Q3_Q6: (3, 6),
         _complete.FREE_Q1_Q6 | _complete.FREE_Q3_Q6: (1, 3, 6)}


def _check_method(method: str) -> None:
    if method not in METHODS:
        raise InvalidInputError("method", f"expected one of {METHODS}, got {method!r}")


def _build(q, valid, flags, pres, rres, arm, within_limits, method, info=None):
    k = valid
    qq, pp, rr, ff = q[k], pres[k], rres[k], flags[k]
    inside = np.atleast_1d(arm.within_limits(qq, tol=LIMIT_TOL)) if len(qq) else np.zeros(0, bool)
    if np.any(ff):  # a continuum representative stands for q within CONTINUUM_TOL of it
        inside = inside | (np.atleast_1d(arm.within_limits(qq, tol=_complete.CONTINUUM_TOL)) & (ff > 0))
    total = len(qq)
    if within_limits:
        qq, pp, rr, ff, inside = qq[inside], pp[inside], rr[inside], ff[inside], inside[inside]
    reason = ""
    if len(qq) == 0:
        reason = ("unreachable: no joint configuration reaches this pose"
                  if total == 0 else
                  f"{total} solution(s) exist but none within the joint limits (Table I)")
    free = tuple(_FREE.get(int(f), ()) for f in ff)
    return IKResult(q=qq, position_residual=pp, rotation_residual=rr, within_limits=inside,
                    free_joints=free, reason=reason, method=method, info=info or {})


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
    return solve_many(Tb, method=method, within_limits=within_limits, arm=arm)[0]


def solve_many(Ts, *, method: str = "complete", within_limits: bool = True,
               arm: Arm = THESIS_ARM) -> list[IKResult]:
    """:func:`solve` for a batch (n, 4, 4) of poses (vectorised); identical answers."""
    _check_method(method)
    Tb, _ = as_poses(Ts, "Ts")
    if method == "thesis":
        from .thesis import solve_thesis_arrays

        arrays = solve_thesis_arrays(Tb, arm)
    else:
        arrays = _complete.solve_arrays(Tb, arm)
    q, valid, flags, pres, rres = arrays
    return [_build(q[i], valid[i], flags[i], pres[i], rres[i], arm, within_limits, method)
            for i in range(len(Tb))]
