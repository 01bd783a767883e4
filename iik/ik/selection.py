"""Choosing one IK solution by the effort index (Eq 54) within the joint limits, and following a path.

Sec 3.3.5 / Sec 4.2.1: among the solutions of a pose, the thesis picks the one
closest to the previous configuration, measured by the effort index of Eq 54
(:func:`iik.joint_path.effort_index`).
"""

from __future__ import annotations

import numpy as np

from ..arm import Arm
from ..errors import UnreachablePoseError
from ..joint_path import BRANCH_SWITCH_STEP, JointPath, branch_switches, path_effort
from ..validation import as_joints, as_poses
from .nearest import Candidates
from .path_events import path_events

__all__ = ["select", "select_index", "follow_path", "branch_signature"]


def select_index(result_or_q, previous_q, *, arm: Arm) -> tuple[int, float]:
    """Index into the usable rows (:attr:`Candidates.q`; for arms whose joint ranges lie within
    (-pi, pi], the rows inside the limits) and the Eq 54 effort [rad] of the best solution,
    measured to its nearest configuration (a continuum's nearest member, a joint's nearest
    winding).

    Raises:
        UnreachablePoseError: no candidate inside the joint limits.
    """
    _, E = _nearest(result_or_q, previous_q, arm)
    i = int(np.argmin(E))  # ties: the first in the deterministic order
    return i, float(E[i])


def select(result_or_q, previous_q, *, arm: Arm) -> np.ndarray:
    """The configuration (6,) [rad] inside the joint limits with the least Eq 54 effort from
    ``previous_q``: over every solution, each joint's windings and each continuum's members
    (:mod:`iik.ik.nearest`), so a previous configuration that reaches the pose is returned as
    itself.

    Args:
        result_or_q: An :class:`IKResult` or an array (k, 6) of candidate solutions.
        previous_q: The previous configuration (6,) [rad].

    Raises:
        UnreachablePoseError: no candidate inside the joint limits.
    """
    Q, E = _nearest(result_or_q, previous_q, arm)
    return Q[int(np.argmin(E))].copy()


def _nearest(result_or_q, previous_q, arm: Arm) -> tuple[np.ndarray, np.ndarray]:
    """Each usable candidate's configuration nearest ``previous_q`` and its Eq 54 effort
    (:meth:`Candidates.nearest`); UnreachablePoseError if there is none."""
    cand = Candidates.of(result_or_q, arm=arm)
    if len(cand) == 0:
        reason = getattr(result_or_q, "reason", "") or "no solution inside the joint limits"
        raise UnreachablePoseError(f"nothing to select: {reason}")
    return cand.nearest(previous_q)


def branch_signature(q) -> np.ndarray:
    """A coarse branch label (k,) for solutions (k, 6): signs of theta4 (elbow) and theta5 (wrist)."""
    qb, _ = as_joints(q, "q")
    return (qb[:, 3] >= 0).astype(int) * 2 + (qb[:, 4] >= 0).astype(int)


def follow_path(Ts, q0=None, *, method: str = "complete", arm: Arm,
                max_step: float = BRANCH_SWITCH_STEP) -> JointPath:
    """Follow a sequence of poses (n, 4, 4), keeping one branch by least Eq 54 effort.

    Args:
        Ts: Poses [m] in base frame 0.
        q0: Starting configuration (6,) [rad]; default: the first solution of pose 0
            with the least effort from q = 0.
        method: IK method (see :func:`iik.solve`).
        max_step: A step with a joint change above this [rad] is a branch switch
            (:func:`iik.joint_path.branch_switches`); with ``q0`` given, step 0 is
            measured from ``q0``.

    Returns:
        :class:`~iik.joint_path.JointPath`; ``counts`` holds the within-limit
        solutions per pose, rows of unreachable poses repeat the previous q; ``events``
        names each switch, each singular crossing and each branch change without singularity
        (a cusp: back at an earlier pose at another configuration, :mod:`iik.ik.path_events`).
        Each step takes the configuration nearest the previous one (a continuum's member, a
        joint's winding), so the joint path stays continuous wherever the IK allows.
    """
    from .solve import solve_many

    Tb, _ = as_poses(Ts, "Ts")
    cands = [Candidates.of(r, arm=arm) for r in solve_many(Tb, method=method, within_limits=False, arm=arm)]
    n = len(cands)
    q = np.zeros((n, 6))
    ok = np.zeros(n, bool)
    prev = np.zeros(6) if q0 is None else as_joints(q0, "q0")[0][0]
    start = prev
    for i, c in enumerate(cands):
        if len(c):
            Q, E = c.nearest(prev)
            prev, ok[i] = Q[int(np.argmin(E))], True
        q[i] = prev
    if q0 is None:
        effort, switches = path_effort(q), branch_switches(q, max_step)
    else:
        full = np.vstack([start, q])
        effort, switches = path_effort(full)[1:], tuple(i - 1 for i in branch_switches(full, max_step))
    events = path_events(q, arm, max_step, method=method, start=None if q0 is None else start)
    return JointPath(q=q, ok=ok, effort=effort, switches=switches,
                     counts=np.array([len(c) for c in cands]), events=events)
