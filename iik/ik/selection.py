"""Choosing one IK solution by the effort index (Eq 54) within the joint limits, and following a path.

Sec 3.3.5 / Sec 4.2.1: among the solutions of a pose, the thesis picks the one
closest to the previous configuration, measured by the effort index of Eq 54
(:func:`iik.joint_path.effort_index`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..arm import LIMIT_TOL, THESIS_ARM, Arm
from ..errors import UnreachablePoseError
from ..joint_path import BRANCH_SWITCH_STEP, JointPath, branch_switches, path_effort
from ..validation import as_joints, as_poses
from . import members as _members
from .nearest import nearest, windings
from .result import IKResult

__all__ = ["Candidates", "select", "select_index", "follow_path", "branch_signature"]


@dataclass(frozen=True)
class Candidates:
    """The solutions of one pose that a selection may pick from: every row with a configuration
    inside the arm's limits, its windings (q_i + 2 pi m) and its continuum's members considered
    (:mod:`iik.ik.nearest`).

    Attributes:
        q: (k, 6) the rows [rad] as the IK returned them (a continuum's representative).
        continua: Per row, its :class:`~iik.ik.result.Continuum` objects (empty if isolated).
        rows: Per row, its index in the :class:`IKResult` (or array) it came from.
        arm: The arm whose limits apply.
        limit_tol: Tolerance of the limits [rad] (negative: a margin inside the stops).
    """

    q: np.ndarray
    continua: tuple
    rows: tuple[int, ...]
    arm: Arm
    limit_tol: float = LIMIT_TOL
    _samples: dict = field(default_factory=dict, compare=False, repr=False)

    @classmethod
    def of(cls, result_or_q, *, arm: Arm, limit_tol: float = LIMIT_TOL) -> Candidates:
        """The candidates of an :class:`IKResult` or of an array (k, 6) of solutions [rad]."""
        if isinstance(result_or_q, IKResult):
            q, cont = np.asarray(result_or_q.q, float).reshape(-1, 6), result_or_q.continua
        else:
            raw = np.asarray(result_or_q) if not isinstance(result_or_q, np.ndarray) else result_or_q
            q = np.zeros((0, 6)) if raw.size == 0 else as_joints(raw, "solutions")[0]
            cont = ((),) * len(q)
        every = cls(q, tuple(cont), tuple(range(len(q))), arm, limit_tol)
        keep = [i for i in range(len(q)) if every._feasible(i)]
        return cls(q[keep], tuple(cont[i] for i in keep), tuple(keep), arm, limit_tol,
                   {keep.index(i): v for i, v in every._samples.items() if i in keep})

    def __len__(self) -> int:
        return len(self.q)

    def _feasible(self, i: int) -> bool:
        """Has row i a configuration inside the limits (the row's windings first: cheap)?"""
        if not np.isnan(windings(self.q[i], self.q[i], self.arm, self.limit_tol)).any():
            return True
        return bool(self.continua[i]) and self._nearest(i, self.q[i])[0] is not None

    def _nearest(self, i: int, previous):
        sampled = [c for c in self.continua[i] if c.kind != "collinear"]
        if sampled and i not in self._samples:
            self._samples[i] = _members.along(sampled[0])
        return nearest(self.q[i], self.continua[i], previous, self.arm, limit_tol=self.limit_tol,
                       samples=self._samples.get(i))

    def configurations(self) -> np.ndarray:
        """Per row, its configuration inside the limits nearest the row itself (k, 6) [rad]: the
        row, another winding of it, or a member of its continuum."""
        return np.array([self._nearest(i, self.q[i])[0] for i in range(len(self))]).reshape(-1, 6)

    def nearest(self, previous_q) -> tuple[np.ndarray, np.ndarray]:
        """Per row, the configuration nearest ``previous_q`` (6,) [rad] by Eq 54 inside the limits
        (k, 6) [rad] and its effort (k,) [rad]: the row itself, another winding of it, or the
        nearest member of its continuum."""
        prev = as_joints(previous_q, "previous_q")[0][0]
        out = [self._nearest(i, prev) for i in range(len(self))]
        return (np.array([q for q, _ in out]).reshape(-1, 6), np.array([e for _, e in out], dtype=float))


def select_index(result_or_q, previous_q, *, arm: Arm = THESIS_ARM) -> tuple[int, float]:
    """Index into the usable rows (:attr:`Candidates.q`; for arms whose joint ranges lie within
    (-pi, pi], the rows inside the limits) and the Eq 54 effort [rad] of the best solution,
    measured to its nearest configuration (a continuum's nearest member, a joint's nearest
    winding).

    Raises:
        UnreachablePoseError: no candidate inside the joint limits.
    """
    cand = Candidates.of(result_or_q, arm=arm)
    if len(cand) == 0:
        reason = getattr(result_or_q, "reason", "") or "no solution inside the joint limits"
        raise UnreachablePoseError(f"nothing to select: {reason}")
    _, E = cand.nearest(previous_q)
    i = int(np.argmin(E))  # ties: the first in the deterministic order
    return i, float(E[i])


def select(result_or_q, previous_q, *, arm: Arm = THESIS_ARM) -> np.ndarray:
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
    cand = Candidates.of(result_or_q, arm=arm)
    if len(cand) == 0:
        reason = getattr(result_or_q, "reason", "") or "no solution inside the joint limits"
        raise UnreachablePoseError(f"nothing to select: {reason}")
    Q, E = cand.nearest(previous_q)
    return Q[int(np.argmin(E))].copy()


def branch_signature(q) -> np.ndarray:
    """A coarse branch label (k,) for solutions (k, 6): signs of theta4 (elbow) and theta5 (wrist)."""
    qb, _ = as_joints(q, "q")
    return (qb[:, 3] >= 0).astype(int) * 2 + (qb[:, 4] >= 0).astype(int)


def follow_path(Ts, q0=None, *, method: str = "complete", arm: Arm = THESIS_ARM,
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
        solutions per pose, rows of unreachable poses repeat the previous q.
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
    return JointPath(q=q, ok=ok, effort=effort, switches=switches,
                     counts=np.array([len(c) for c in cands]))
