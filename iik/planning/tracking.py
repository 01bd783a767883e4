"""IK along a Cartesian path (Sec 3.6, Sec 4.2): every branch followed by the effort index (Eq 54).

* :func:`all_solutions` -- the usable IK solutions at every step-point, with the
  slight beta changes of Sec 3.6 ("another path with slight change in the beta
  orientation") and then larger alpha/beta changes where a step has none.
* :func:`track_branches` -- the thesis's choice: from each start solution the
  branch is followed by the minimum effort index (Eq 54) step by step.
* :func:`track_dp` (ours, used when some step has no solution at the nominal
  orientation even after the slight beta changes) -- a least-effort dynamic
  programme over IK branches and a small grid of alpha/beta changes (alpha is
  free in Sec 3.6; beta changes are penalised), with a penalty per branch switch.

Both return a :class:`Tracking` and take an optional :class:`~iik.planning.Budget`
(progress every second, :class:`~iik.planning.PlanningTimeout` past its deadline,
checked every :data:`IK_CHUNK` poses and every loop iteration). IK is solved for
the given :class:`~iik.arm.Arm`
(``iik.solve_many``); solutions within :data:`LIMIT_MARGIN` of one of that arm's
joint stops are not used, so the timed curve through the step-points cannot
overshoot a stop. Units: rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..arm import Arm
from ..ik import solve_many
from ..ik.nearest import Candidates
from ..joint_path import (
    BRANCH_SWITCH_STEP,
    JointPath,
    branch_switches,
    effort_matrix,
    path_effort,
)
from .budget import Budget
from .cartesian import CartesianPath, poses_of

__all__ = [
    "LIMIT_MARGIN",
    "RAMP",
    "IK_CHUNK",
    "BETA_STEPS",
    "ORIENTATION_OFFSETS",
    "DP_OFFSETS",
    "Tracking",
    "all_solutions",
    "track_branches",
    "track_dp",
]

#: Solutions closer than this to a joint stop are not used [rad]: a smooth timed
#: curve through a waypoint *on* a stop would overshoot it (e.g. theta6 = pi exactly).
LIMIT_MARGIN = 0.01

#: Steps on each side over which :func:`all_solutions` spreads a needed orientation change.
RAMP = 8

#: Poses solved per call of the IK between two budget checks.
IK_CHUNK = 256

#: Slight beta changes tried at a step without IK solutions [rad] (Sec 3.6), smallest first.
BETA_STEPS = tuple(math.radians(d) * s for d in (2, 4, 6, 8, 10, 15, 20) for s in (1, -1))


def _orientation_offsets() -> tuple[tuple[float, float], ...]:
    """(d_alpha, d_beta) [rad] tried after the slight beta changes, cheapest first.

    Sec 3.6: alpha "does not tilt the end-effector ... any alpha angle could be
    assigned by the path planning algorithm"; beta is moved further only if
    that fails. Cost: |d_beta| + |d_alpha| / 2.
    """
    da = [0, 20, -20, 45, -45, 90, -90, 135, -135, 180]
    db = [0, 10, -10, 20, -20, 30, -30, 45, -45, 60, -60]
    offs = sorted(((a, b) for a in da for b in db if (a, b) != (0, 0)),
                  key=lambda ab: (abs(ab[1]) + abs(ab[0]) / 2, abs(ab[1])))
    return tuple((math.radians(a), math.radians(b)) for a, b in offs)


#: Orientation changes tried when the slight beta changes fail (ours, beyond the thesis).
ORIENTATION_OFFSETS = _orientation_offsets()

#: Orientation grid of :func:`track_dp`: (d_alpha, d_beta) [rad].
DP_OFFSETS = tuple((math.radians(a), math.radians(b))
                   for a in (0, 90, -90, 180) for b in (0, 10, -10, 20, -20, 35, -35))


def _steps(mask) -> tuple[int, ...]:
    return tuple(int(i) for i in np.flatnonzero(mask))


@dataclass(frozen=True)
class Tracking:
    """IK followed along a Cartesian path of n step-points.

    Attributes:
        branches: Candidate joint paths (:class:`~iik.joint_path.JointPath`), best first.
        solutions_per_step: (n,) usable IK solutions offered at each step (after orientation changes).
        alpha_changed_steps, beta_changed_steps, gamma_changed_steps: Steps whose alpha / beta /
            gamma (the gripper's half turn) differ from the nominal orientation; for
            :func:`track_dp` those of the best branch.
        orientation_search: True when produced by :func:`track_dp`.
    """

    branches: tuple[JointPath, ...]
    solutions_per_step: np.ndarray
    alpha_changed_steps: tuple[int, ...] = ()
    beta_changed_steps: tuple[int, ...] = ()
    gamma_changed_steps: tuple[int, ...] = ()
    orientation_search: bool = False

    @property
    def complete(self) -> tuple[JointPath, ...]:
        """The branches with a solution at every step, in order."""
        return tuple(b for b in self.branches if b.complete)

    @property
    def failed_steps(self) -> tuple[int, ...]:
        """Steps without any usable IK solution."""
        return _steps(self.solutions_per_step == 0)


def _usable(res, arm: Arm) -> Candidates:
    """The solutions of one IK result with a configuration at least :data:`LIMIT_MARGIN` inside
    ``arm``'s stops (windings and continua considered, :class:`~iik.ik.selection.Candidates`)."""
    return Candidates.of(res, arm=arm, limit_tol=-LIMIT_MARGIN)


def _solve(points: np.ndarray, euler: np.ndarray, arm: Arm, budget: Budget) -> list[Candidates]:
    """Usable solutions at every pose, solved :data:`IK_CHUNK` poses at a time (a budget tick between)."""
    out: list[Candidates] = []
    for i in range(0, len(points), IK_CHUNK):
        budget.tick("IK poses", i, len(points))
        T = poses_of(points[i:i + IK_CHUNK], euler[i:i + IK_CHUNK])
        out += [_usable(r, arm) for r in solve_many(T, arm=arm, within_limits=False)]
    return out


def all_solutions(points: np.ndarray, euler: np.ndarray, *, arm: Arm,
                  beta_steps: tuple[float, ...] = BETA_STEPS, adapt_orientation: bool = True,
                  ramp: int = RAMP, budget: Budget | None = None) -> tuple[list[np.ndarray], np.ndarray]:
    """Usable IK solutions of ``arm`` at every step, with orientation changes where needed.

    First the nominal orientation; then, at steps without a solution, the slight
    beta changes of Sec 3.6 (``beta_steps``); then (``adapt_orientation``) the
    alpha/beta changes of :data:`ORIENTATION_OFFSETS`, cheapest first.

    Args:
        points, euler: (n, 3) tool points [m] and Z-Y-Z angles [rad] (corrected Eq 42).
        arm: The arm whose IK and joint limits are used.
        ramp: Spread every needed change linearly over this many steps on each
            side, then solve again (gradual orientation change, Sec 4.2.1).
        budget: Time budget and progress (:class:`~iik.planning.Budget`); default: none.

    Returns:
        ``(solutions, offsets)``: a list of (k_i, 6) arrays [rad] (one configuration per
        solution, :meth:`~iik.ik.selection.Candidates.configurations`) and the (n, 2)
        (d_alpha, d_beta) used at each step [rad].
    """
    sols, offs = _candidates(points, euler, arm, beta_steps, adapt_orientation, ramp, budget or Budget())
    return [c.configurations() for c in sols], offs


def _candidates(points, euler, arm, beta_steps, adapt_orientation, ramp, budget: Budget):
    """:func:`all_solutions` as :class:`~iik.ik.selection.Candidates` (continua kept)."""
    sols, offs = _solve_with_offsets(points, euler, arm, beta_steps, adapt_orientation, budget)
    if ramp > 0 and np.any(offs) and len(points) > 2:
        # Spread each needed change over +-ramp steps so orientation (and the joints)
        # change gradually instead of jumping at the first step that needs it.
        base = _ramp(offs, ramp)
        e2 = euler.copy()
        e2[:, 0] += base[:, 0]
        e2[:, 1] += base[:, 1]
        sols2, offs2 = _solve_with_offsets(points, e2, arm, beta_steps, adapt_orientation, budget)
        if sum(len(q) == 0 for q in sols2) <= sum(len(q) == 0 for q in sols):
            sols, offs = sols2, base + offs2
    return sols, offs


def _ramp(offs: np.ndarray, w: int) -> np.ndarray:
    """Triangular envelope: each step takes the strongest nearby offset, tapered over ``w`` steps."""
    n = len(offs)
    out = np.zeros_like(offs)
    best = np.zeros_like(offs)  # strongest |offset| x weight so far, per step and column
    for d in range(-w, w + 1):  # neighbour j = i + d in increasing j: the first strongest one wins
        lo, hi = max(0, -d), min(n, n - d)
        if lo >= hi:
            continue
        weight = max(0.0, 1.0 - abs(d) / (w + 1))
        near = offs[lo + d:hi + d]
        stronger = np.abs(near) * weight > best[lo:hi]
        best[lo:hi] = np.where(stronger, np.abs(near) * weight, best[lo:hi])
        out[lo:hi] = np.where(stronger, near * weight, out[lo:hi])
    return out


def _solve_with_offsets(points, euler, arm, beta_steps, adapt_orientation, budget: Budget):
    n = len(points)
    sols = _solve(points, euler, arm, budget)
    offs = np.zeros((n, 2))
    tries = [(0.0, db) for db in beta_steps]
    if adapt_orientation:
        tries += list(ORIENTATION_OFFSETS)
    for k, (da, db) in enumerate(tries):
        missing = [i for i in range(n) if len(sols[i]) == 0]
        if not missing:
            break
        budget.tick("orientation changes at steps without IK solutions", k, len(tries))
        e = euler[missing].copy()
        e[:, 0] += da
        e[:, 1] += db
        for i, q in zip(missing, _solve(points[missing], e, arm, budget), strict=True):
            if len(q):
                sols[i], offs[i] = q, (da, db)
    return sols, offs


def track_branches(path: CartesianPath, *, arm: Arm, beta_steps: tuple[float, ...] = BETA_STEPS,
                   switch_threshold: float = BRANCH_SWITCH_STEP, adapt_orientation: bool = True,
                   budget: Budget | None = None) -> Tracking:
    """Follow every IK branch along the path, choosing by the effort index (Eq 54).

    Args:
        path: From :func:`~iik.planning.build_path`.
        arm: The arm whose IK and joint limits are used.
        beta_steps: Beta offsets [rad] tried when a step has no solution (Sec 3.6).
        adapt_orientation: Then also try the alpha/beta changes of :data:`ORIENTATION_OFFSETS`.
        switch_threshold: A step whose largest joint change exceeds this [rad] is
            reported as a branch switch.
        budget: Time budget and progress (:class:`~iik.planning.Budget`); default: none.

    Returns:
        :class:`Tracking` with one branch per start solution, sorted by (complete
        first, number of switches, total effort); a step without a solution
        repeats the previous row (``ok`` False).
    """
    budget = budget or Budget()
    sols, offs = _candidates(path.points, path.euler, arm, beta_steps, adapt_orientation, RAMP, budget)
    n = path.n
    counts = np.array([len(s) for s in sols])
    branches = []
    starts = sols[0].configurations()
    for j, q0 in enumerate(starts):
        budget.tick("IK branches along the path", j, len(starts))
        qs = np.empty((n, 6))
        ok = np.zeros(n, bool)
        eff = np.zeros(n)
        qs[0], ok[0] = q0, True
        for i in range(1, n):
            if len(sols[i]) == 0:
                qs[i] = qs[i - 1]
                continue
            cand, e = sols[i].nearest(qs[i - 1])  # Eq 54 to every candidate's nearest configuration
            k = int(np.argmin(e))
            qs[i], ok[i], eff[i] = cand[k], True, e[k]
        branches.append(JointPath(q=qs, ok=ok, effort=eff, switches=branch_switches(qs, switch_threshold),
                                  counts=counts, beta_change=offs[:, 1].copy(),
                                  alpha_change=offs[:, 0].copy(), start_solution=j))
    branches.sort(key=lambda b: (not b.complete, len(b.switches), b.total_effort))
    return Tracking(branches=tuple(branches), solutions_per_step=counts,
                    alpha_changed_steps=_steps(offs[:, 0]), beta_changed_steps=_steps(offs[:, 1]))


def _offered(cand: Candidates, previous: np.ndarray) -> np.ndarray:
    """The configurations a DP layer offers for one pose: one per solution, and for a continuum
    also its member nearest each of the ``previous`` configurations (m, 6) [rad] (the continuum
    offers every member; staying put must be among the choices)."""
    q = cand.configurations()
    rows = [i for i in range(len(cand)) if cand.continua[i]]
    if not rows or len(previous) == 0:
        return q
    extra = np.concatenate([cand.nearest(p)[0][rows] for p in previous])
    allq = np.concatenate([q, extra])
    _, first = np.unique(np.round(allq, 9), axis=0, return_index=True)
    return allq[np.sort(first)]


def _half_turns(q: np.ndarray, arm: Arm) -> np.ndarray:
    """gamma + pi (theta6 -/+ pi), the same grasp for a gripper symmetric about z6: those inside margin."""
    qf = q.copy()
    qf[:, 5] -= np.pi * np.where(q[:, 5] >= 0, 1.0, -1.0)
    return qf[arm.within_limits(qf, tol=-LIMIT_MARGIN)] if len(qf) else qf


def _dp_layers(path: CartesianPath, arm: Arm, offsets, half_turn: bool, budget: Budget):
    """Candidates per step: (q (k, 6), offsets (k, 3) = (d_alpha, d_beta, d_gamma)) for every step."""
    n, K = path.n, len(offsets)
    off = np.asarray(offsets, float)
    e = np.repeat(path.euler[None], K, axis=0).copy()
    e[:, :, 0] += off[:, 0, None]
    e[:, :, 1] += off[:, 1, None]
    sols = _solve(np.tile(path.points, (K, 1)), e.reshape(-1, 3), arm, budget)
    layers = []
    before = [np.zeros((0, 6))] * K  # the previous step's configurations per orientation offset
    for i in range(n):
        budget.tick("orientation grid", i, n)
        qs, os_ = [], []
        for k in range(K):
            q = _offered(sols[k * n + i], before[k])
            turned = _half_turns(q, arm) if half_turn else np.zeros((0, 6))
            o3 = np.repeat(np.append(off[k], 0.0)[None], len(q) + len(turned), axis=0)
            o3[len(q):, 2] = np.pi
            before[k] = np.concatenate([q, turned])
            qs.append(before[k])
            os_.append(o3)
        layers.append((np.concatenate(qs), np.concatenate(os_)))
    return layers


def track_dp(path: CartesianPath, *, arm: Arm, offsets=DP_OFFSETS, w_change: float = 3.0,
             w_offset: float = 0.05, w_switch: float = 2.0, half_turn: bool = True,
             w_half_turn: float = 1.0, switch_threshold: float = BRANCH_SWITCH_STEP,
             budget: Budget | None = None) -> Tracking:
    """Least-effort joint path over IK branches *and* small orientation changes (dynamic programming).

    Used when the nominal orientations leave steps without solutions. At every
    step the candidates are the usable IK solutions of ``arm`` for each
    orientation offset in ``offsets`` (alpha is free, Sec 3.6; beta changes are
    penalised). The path minimises ``sum_i E_i + w_change |d offset_i| +
    w_offset |offset_i| + w_switch [max |dq_i| > switch_threshold]`` with
    ``E_i`` the effort index of Eq 54, i.e. the global form of the thesis's
    step-by-step least-effort choice (plus a penalty per branch switch). With
    ``half_turn`` every candidate is also offered with gamma + pi (theta6 -/+
    pi): the same grasp for the thesis's parallel gripper, symmetric about z6
    (URDF link6 shapes too); it removes theta6 swings of nearly a full turn at
    its +-180 deg stops. The half turn itself is free, switching it mid-path
    costs ``w_half_turn``. One path per start solution, sorted by (number of
    switches, total effort); none if a step has no candidate. ``budget``: time budget
    and progress (:class:`~iik.planning.Budget`); default: none.
    """
    budget = budget or Budget()
    layers = _dp_layers(path, arm, offsets, half_turn, budget)
    counts = np.array([len(q) for q, _ in layers])
    if np.any(counts == 0):
        return Tracking(branches=(), solutions_per_step=counts, orientation_search=True)
    # start candidates: nominal orientation (up to the gripper's half turn) if possible
    q_first, o_first = layers[0]
    nominal0 = np.all(o_first[:, :2] == 0, axis=1)
    starts = np.flatnonzero(nominal0) if nominal0.any() else np.arange(len(q_first))
    costs = _DPCosts(w_change, w_offset, w_switch, w_half_turn, switch_threshold)
    branches = [b for s0 in starts if (b := _dp_branch(layers, int(s0), costs, counts, budget)) is not None]
    branches.sort(key=lambda b: (len(b.switches), b.total_effort))
    if not branches:
        return Tracking(branches=(), solutions_per_step=counts, orientation_search=True)
    best = branches[0]
    return Tracking(branches=tuple(branches), solutions_per_step=counts,
                    alpha_changed_steps=best.changed_steps("alpha"),
                    beta_changed_steps=best.changed_steps("beta"),
                    gamma_changed_steps=best.changed_steps("gamma"), orientation_search=True)


@dataclass(frozen=True)
class _DPCosts:
    """The weights of :func:`track_dp` (see its docstring)."""

    w_change: float
    w_offset: float
    w_switch: float
    w_half_turn: float
    switch_threshold: float


def _dp_branch(layers, s0: int, c: _DPCosts, counts, budget: Budget) -> JointPath | None:
    """The least-cost path through ``layers`` from start candidate ``s0`` (None if unreachable)."""
    n = len(layers)
    cost = np.full(len(layers[0][0]), np.inf)
    cost[s0] = 0.0
    back = []
    for i in range(1, n):
        budget.tick(f"orientation search from start candidate {s0}", i, n)
        (qa, oa), (qb, ob) = layers[i - 1], layers[i]
        dO = np.abs(ob[None] - oa[:, None])
        C = (effort_matrix(qa, qb)  # Eq 54 for all pairs
             + c.w_change * dO[..., :2].sum(-1) + c.w_half_turn * (dO[..., 2] > 0)
             + c.w_offset * np.abs(ob[:, :2]).sum(-1)[None]
             + c.w_switch * (np.abs(qb[None, :, :] - qa[:, None, :]).max(-1) > c.switch_threshold))
        tot = cost[:, None] + C
        arg = np.argmin(tot, axis=0)
        back.append(arg)
        cost = tot[arg, np.arange(len(qb))]
    if not np.isfinite(cost.min()):
        return None
    idx = [int(np.argmin(cost))]
    for arg in reversed(back):
        idx.append(int(arg[idx[-1]]))
    idx.reverse()
    q = np.array([layers[i][0][j] for i, j in enumerate(idx)])
    o = np.array([layers[i][1][j] for i, j in enumerate(idx)])
    return JointPath(q=q, ok=np.ones(n, bool), effort=path_effort(q),
                     switches=branch_switches(q, c.switch_threshold), counts=counts, alpha_change=o[:, 0],
                     beta_change=o[:, 1], gamma_change=o[:, 2], start_solution=s0)
