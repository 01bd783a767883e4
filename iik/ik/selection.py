"""Choosing one IK solution: the effort index (Eq 54), joint limits, path following.

Sec 3.3.5 / Sec 4.2.1: among the solutions of a pose, the thesis picks the one
closest to the previous configuration, measured by the effort index of Eq 54::

    E_i = (1/6) sum_n |theta_{n,i} - theta_{n,i-1}|        [rad]

The difference is *not* wrapped: every joint has stops (Table I), so going
from +179 deg to -179 deg on joint 6 really is a 358 deg move.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import as_joints, as_poses
from ..arm import THESIS_ARM, Arm
from ..errors import InvalidInputError, UnreachablePoseError
from .result import IKResult

__all__ = ["effort_index", "select", "select_index", "PathResult", "follow_path", "branch_signature"]


def effort_index(q_prev, q) -> np.ndarray | float:
    """Eq 54: mean absolute joint change [rad] from ``q_prev`` (6,) to ``q`` (6,) or (k, 6)."""
    qp, bp = as_joints(q_prev, "q_prev")
    if bp:
        raise InvalidInputError("q_prev", f"expected one joint vector (6,), got shape {qp.shape}")
    qq, batched = as_joints(q, "q")
    E = np.sum(np.abs(qq - qp), axis=1) / 6.0  # Eq 54
    return E if batched else float(E[0])


def _candidates(result_or_q, arm: Arm) -> np.ndarray:
    if isinstance(result_or_q, IKResult):
        q = result_or_q.q
        return q[np.asarray(result_or_q.within_limits, bool)] if len(q) else q
    q = np.asarray(result_or_q, dtype=float) if not isinstance(result_or_q, np.ndarray) else result_or_q
    if q.size == 0:
        return np.zeros((0, 6))
    qb, _ = as_joints(q, "solutions")
    inside = np.atleast_1d(arm.within_limits(qb, tol=1e-7))
    return qb[inside]


def select_index(result_or_q, previous_q, *, arm: Arm = THESIS_ARM) -> tuple[int, float]:
    """Index (into the within-limit candidates) and Eq 54 effort of the best solution.

    Raises:
        UnreachablePoseError: no candidate inside the joint limits.
    """
    cand = _candidates(result_or_q, arm)
    if len(cand) == 0:
        reason = getattr(result_or_q, "reason", "") or "no solution inside the joint limits"
        raise UnreachablePoseError(f"nothing to select: {reason}")
    E = np.atleast_1d(effort_index(previous_q, cand))
    i = int(np.argmin(E))  # ties: the first in the deterministic order
    return i, float(E[i])


def select(result_or_q, previous_q, *, arm: Arm = THESIS_ARM) -> np.ndarray:
    """The solution (6,) [rad] inside the joint limits with the least Eq 54 effort.

    Args:
        result_or_q: An :class:`IKResult` or an array (k, 6) of candidate solutions.
        previous_q: The previous configuration (6,) [rad].
    """
    i, _ = select_index(result_or_q, previous_q, arm=arm)
    return _candidates(result_or_q, arm)[i].copy()


def branch_signature(q) -> np.ndarray:
    """A coarse branch label (k,) for solutions (k, 6): signs of theta4 (elbow) and theta5 (wrist)."""
    qb, _ = as_joints(q, "q")
    return (qb[:, 3] >= 0).astype(int) * 2 + (qb[:, 4] >= 0).astype(int)


@dataclass(frozen=True)
class PathResult:
    """One configuration per pose of a path.

    Attributes:
        q: (n, 6) [rad]; rows of unreachable poses repeat the previous q and have ``ok`` False.
        effort: (n,) Eq 54 effort from the previous step [rad] (0 at step 0).
        ok: (n,) a solution inside the limits existed.
        branch_switch: (n,) the chosen solution changed branch (elbow/wrist sign)
            or moved a joint by more than ``max_step``.
        counts: (n,) number of within-limit solutions at each pose.
    """

    q: np.ndarray
    effort: np.ndarray
    ok: np.ndarray
    branch_switch: np.ndarray
    counts: np.ndarray

    @property
    def switches(self) -> np.ndarray:
        """Indices of steps with a branch switch."""
        return np.flatnonzero(self.branch_switch)


def follow_path(Ts, q0=None, *, method: str = "complete", arm: Arm = THESIS_ARM,
                max_step: float = 0.5) -> PathResult:
    """Follow a sequence of poses (n, 4, 4), keeping one branch by least Eq 54 effort.

    Args:
        Ts: Poses [m] in base frame 0.
        q0: Starting configuration (6,) [rad]; default: the first solution of pose 0
            with the least effort from q = 0.
        method: IK method (see :func:`iik.solve`).
        max_step: A step with a joint change above this [rad] is flagged as a switch.
    """
    from .solve import solve_many

    Tb, _ = as_poses(Ts, "Ts")
    results = solve_many(Tb, method=method, within_limits=True, arm=arm)
    n = len(results)
    q = np.zeros((n, 6))
    E = np.zeros(n)
    ok = np.zeros(n, bool)
    sw = np.zeros(n, bool)
    counts = np.array([r.count for r in results])
    prev = np.zeros(6) if q0 is None else as_joints(q0, "q0")[0][0]
    for i, r in enumerate(results):
        if r.count == 0:
            q[i] = prev
            continue
        j, e = select_index(r, prev, arm=arm)
        qi = r.q[np.asarray(r.within_limits, bool)][j]
        if i > 0 or q0 is not None:
            E[i] = e
            sw[i] = (branch_signature(qi)[0] != branch_signature(prev)[0]) or bool(
                np.max(np.abs(qi - prev)) > max_step)
        q[i], ok[i], prev = qi, True, qi
    return PathResult(q=q, effort=E, ok=ok, branch_switch=sw, counts=counts)
