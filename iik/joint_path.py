"""A joint path and what the thesis measures along it: the effort index (Eq 54) and branch switches.

Sec 3.3.5 / Sec 4.2.1: among the solutions of a pose the thesis takes the one
closest to the previous configuration, measured by the effort index of Eq 54::

    E_i = (1/6) sum_n |theta_{n,i} - theta_{n,i-1}|        [rad]

The difference is *not* wrapped: every joint has stops (Table I), so going from
+179 deg to -179 deg on joint 6 really is a 358 deg move.

A *branch switch* is a step whose largest joint change exceeds
:data:`BRANCH_SWITCH_STEP`: the path jumped to another IK branch (the thesis's
figures show them as the sudden joint swings of Sec 4.2). Every part of the
project that reports switches uses :func:`branch_switches`.

Units: rad. This module is the one home of :func:`effort_index` (with its
all-pairs and along-a-path forms :func:`effort_matrix` and :func:`path_effort`),
:func:`branch_switches` and :class:`JointPath`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .errors import InvalidInputError
from .validation import as_joints

__all__ = ["BRANCH_SWITCH_STEP", "effort_index", "effort_matrix", "path_effort", "branch_switches",
           "PathEvent", "JointPath"]

#: A step whose largest joint change exceeds this is a branch switch [rad].
BRANCH_SWITCH_STEP = 0.5


def _eq54(dq: np.ndarray) -> np.ndarray:
    """Eq 54 over the last axis of joint changes ``dq`` (..., 6) [rad]: ``sum |dq_n| / 6``."""
    return np.sum(np.abs(dq), axis=-1) / 6.0  # Eq 54


def effort_index(q_prev, q) -> np.ndarray | float:
    """Eq 54: mean absolute joint change [rad] from ``q_prev`` (6,) to ``q`` (6,) or (k, 6)."""
    qp, bp = as_joints(q_prev, "q_prev")
    if bp:
        raise InvalidInputError("q_prev", f"expected one joint vector (6,), got shape {qp.shape}")
    qq, batched = as_joints(q, "q")
    E = _eq54(qq - qp)
    return E if batched else float(E[0])


def effort_matrix(q_from, q_to) -> np.ndarray:
    """Eq 54 for every pair: ``E[a, b]`` from ``q_from[a]`` (m, 6) to ``q_to[b]`` (k, 6) [rad], (m, k)."""
    qa, _ = as_joints(q_from, "q_from")
    qb, _ = as_joints(q_to, "q_to")
    return _eq54(qb[None, :, :] - qa[:, None, :])


def path_effort(q) -> np.ndarray:
    """Eq 54 at every step of a joint path (n, 6) [rad]: (n,) with ``E_0 = 0``."""
    qb, _ = as_joints(q, "q")
    E = np.zeros(len(qb))
    E[1:] = _eq54(np.diff(qb, axis=0))
    return E


def branch_switches(q, threshold: float = BRANCH_SWITCH_STEP) -> tuple[int, ...]:
    """Indices i >= 1 of the steps of a joint path (n, 6) [rad] with ``max |q_i - q_{i-1}| > threshold``."""
    qb, _ = as_joints(q, "q")
    if len(qb) < 2:
        return ()
    return tuple(int(i) + 1 for i in np.flatnonzero(np.abs(np.diff(qb, axis=0)).max(axis=1) > threshold))


def _column(value, n: int, dtype=float) -> np.ndarray:
    return np.zeros(n, dtype) if value is None else np.asarray(value, dtype)


@dataclass(frozen=True)
class PathEvent:
    """Something that happened to the IK branch at one step of a followed path.

    Kinds:

    * ``"switch"``: the branch jumped: some joint moved more than the switch threshold in one
      step (:func:`branch_switches`), or less but the branch did not continue to it (it ended
      at a fold: :mod:`iik.ik.path_events`).
    * ``"singular"``: the path met a singular configuration without a jump: det J changed sign,
      or reached or left 0, from the previous step to this one.
    * ``"cusp"``: a branch change without singularity: the path is back at the pose of step
      ``earlier``, at another configuration (some joint differs by more than 1e-6 rad modulo
      2 pi), and between the two steps it made no switch and det J kept its sign at every step.
      Two IK solutions of one pose joined by a continuous path without a singularity: only a
      cuspidal arm can do this (Wenger; the FANUC CRX is one).

    Attributes:
        step: The step (index into the path's ``q``).
        kind: ``"switch"``, ``"singular"`` or ``"cusp"``.
        detail: What happened, in words and numbers.
        earlier: For ``"cusp"``, the earlier step at the same pose; else None.
    """

    step: int
    kind: str
    detail: str
    earlier: int | None = None


@dataclass(frozen=True)
class JointPath:
    """One configuration per step of a path (an IK branch followed along it).

    Attributes:
        q: (n, 6) joint angles [rad]; rows of steps without a solution repeat the previous row.
        ok: (n,) True where the step has a solution (possibly after an orientation change).
        effort: (n,) effort index E_i of Eq 54 from the previous step [rad] (E_0 = 0).
        switches: Step indices where the branch jumped (:func:`branch_switches`).
        counts: (n,) number of within-limit solutions offered at each step (0 where unknown).
        alpha_change, beta_change: (n,) Euler-angle offsets applied at each step [rad] (0 = nominal).
        gamma_change: (n,) gamma offset [rad]: 0, or pi for the gripper's half turn.
        start_solution: Index of the start solution this branch began from.
        events: What happened to the branch (:class:`PathEvent`), in step order; filled by
            :func:`iik.follow_path`.
    """

    q: np.ndarray
    ok: np.ndarray
    effort: np.ndarray
    switches: tuple[int, ...] = ()
    counts: np.ndarray | None = field(default=None)
    alpha_change: np.ndarray | None = field(default=None)
    beta_change: np.ndarray | None = field(default=None)
    gamma_change: np.ndarray | None = field(default=None)
    start_solution: int = 0
    events: tuple[PathEvent, ...] = ()

    def __post_init__(self) -> None:
        n = len(self.q)
        for name, dtype in (("counts", int), ("alpha_change", float), ("beta_change", float),
                            ("gamma_change", float)):
            object.__setattr__(self, name, _column(getattr(self, name), n, dtype))
        object.__setattr__(self, "switches", tuple(int(i) for i in self.switches))
        object.__setattr__(self, "events", tuple(self.events))

    @property
    def n(self) -> int:
        """Number of steps."""
        return len(self.q)

    @property
    def complete(self) -> bool:
        """Every step has a solution."""
        return bool(np.all(self.ok))

    @property
    def failed_steps(self) -> tuple[int, ...]:
        """Steps without a solution."""
        return tuple(int(i) for i in np.flatnonzero(~np.asarray(self.ok, bool)))

    @property
    def total_effort(self) -> float:
        """Sum of the Eq 54 effort over the path [rad]."""
        return float(np.sum(self.effort))

    def changed_steps(self, angle: str) -> tuple[int, ...]:
        """Steps where ``angle`` (``"alpha"``, ``"beta"`` or ``"gamma"``) was changed."""
        if angle not in ("alpha", "beta", "gamma"):
            raise InvalidInputError("angle", f"expected 'alpha', 'beta' or 'gamma', got {angle!r}")
        return tuple(int(i) for i in np.flatnonzero(getattr(self, f"{angle}_change")))
