"""What happens to an IK branch followed along a path: switches, singular crossings and cusps
(:class:`~iik.joint_path.PathEvent`).

A *cuspidal* arm can move from one IK solution of a pose to another without meeting a
singularity (Wenger; the FANUC CRX cobots are cuspidal). For such an arm the sign of det J
(the aspect) does not tell the solutions apart, and no function of the configuration can name
"the same branch" everywhere; what *can* be observed is the definition itself: the path comes
back to a pose it visited before, at a different configuration, with no jump and no change of
det J's sign in between. :func:`path_events` reports exactly that as ``"cusp"``, beside the
``"switch"`` (a jump: a joint moves more than the switch threshold, or the branch does not
continue from one step to the next) and ``"singular"`` (det J changes sign, or reaches or leaves
0, between two steps without a jump) events. An open path that never revisits a pose can change posture
the same way unseen: this module does not claim otherwise.

Units: rad, m. det J is the 6x6 Jacobian's determinant at the tool point (:func:`iik.jacobian`);
its sign is checked at the steps, not between them.
"""

from __future__ import annotations

import numpy as np

from ..arm import Arm
from ..joint_path import PathEvent, branch_switches
from ..kinematics import fk, jacobian
from .angles import angle_distance

__all__ = ["path_events", "SAME_POSE", "SAME_CONFIGURATION", "SINGULAR", "SMOOTH_STEP", "CONTRACTION",
           "MAX_BISECTIONS"]

#: Two steps are at the same pose when their positions differ by at most this times the arm's
#: reach and their rotation matrices by at most this [1].
SAME_POSE = 1e-9
#: Two configurations differ when some joint differs by more than this modulo 2 pi [rad].
SAME_CONFIGURATION = 1e-6
#: det J counts as 0 below this times the arm's reach cubed [1] (det J is in m^3).
SINGULAR = 1e-12
#: A step whose joints all change by at most this is taken as continuous [rad]; larger steps are
#: bisected (:func:`_continues`) down to it.
SMOOTH_STEP = 1e-2
#: A continuous step's halves each take at most this fraction of its joint change.
CONTRACTION = 0.9
#: Deepest bisection of one step.
MAX_BISECTIONS = 24


def _pose_keys(q: np.ndarray, arm: Arm) -> np.ndarray:
    """(n, 12): each step's tool position over the reach and rotation matrix, for neighbour search."""
    T = fk(q, arm).reshape(-1, 4, 4)
    return np.concatenate([T[:, :3, 3] / arm.reach, T[:, :3, :3].reshape(-1, 9)], axis=1)


def _between(Ta: np.ndarray, Tb: np.ndarray) -> np.ndarray:
    """The pose halfway between two poses: the position's midpoint, the rotation's half turn."""
    from scipy.spatial.transform import Rotation

    T = np.eye(4)
    T[:3, 3] = 0.5 * (Ta[:3, 3] + Tb[:3, 3])
    half = 0.5 * Rotation.from_matrix(Ta[:3, :3].T @ Tb[:3, :3]).as_rotvec()
    T[:3, :3] = Ta[:3, :3] @ Rotation.from_rotvec(half).as_matrix()
    return T


def _continues(qa, Ta, qb, Tb, arm: Arm, method: str, depth: int = 0) -> bool:
    """Is qb (at pose Tb) where the IK branch through qa (at Ta) goes? Bisect the poses: the
    solution nearest qa at the middle pose (:class:`~iik.ik.nearest.Candidates`, the complete IK)
    must split the joint change into two parts each at most :data:`CONTRACTION` of it, and so on
    down to :data:`SMOOTH_STEP`. A continuous branch contracts (by 1/2, or 1/sqrt 2 next to a
    fold); a jump stays whole in one half however fine the bisection."""
    from .nearest import Candidates
    from .solve import solve

    d = angle_distance(qa, qb)
    if d <= SMOOTH_STEP or depth >= MAX_BISECTIONS:
        return True
    Tm = _between(Ta, Tb)
    cand = Candidates.of(solve(Tm, arm=arm, method=method, within_limits=False), arm=arm)
    if len(cand) == 0:
        return False  # no configuration halfway: the path left the reachable set
    Q, E = cand.nearest(qa)
    qm = Q[int(np.argmin(E))]
    if max(angle_distance(qa, qm), angle_distance(qm, qb)) > CONTRACTION * d:
        return False
    return _continues(qa, Ta, qm, Tm, arm, method, depth + 1) and _continues(qm, Tm, qb, Tb, arm, method,
                                                                           depth + 1)


def _cusps(q, sign, switched, arm: Arm) -> list[PathEvent]:
    from scipy.spatial import cKDTree

    keys = _pose_keys(q, arm)
    # a segment i..j is clean when no step in (i, j] switched or changed det J's sign
    dirty = np.concatenate([[0], np.cumsum(switched[1:] | (sign[1:] != sign[:-1]) | (sign[1:] == 0))])
    out = []
    for i, j in sorted(cKDTree(keys).query_pairs(SAME_POSE, p=np.inf, output_type="ndarray").tolist(),
                       key=lambda ij: (ij[1], ij[0])):
        if out and out[-1].step == j:
            continue  # one event per step: the earliest revisited step
        gap = angle_distance(q[i], q[j])
        if gap > SAME_CONFIGURATION and dirty[j] == dirty[i] and sign[i] != 0:
            text = (f"cusp: branch change without singularity (back at the pose of step {i} at another "
                    f"configuration, {gap:.3g} rad away in a joint; det J kept its sign, no switch between)")
            out.append(PathEvent(j, "cusp", text, i))
    return out


def path_events(q, arm: Arm, switch_threshold: float, *, method: str = "complete",
                start=None) -> tuple[PathEvent, ...]:
    """The events of a followed joint path ``q`` (n, 6) [rad] of ``arm``, in step order (see the
    module docstring). A step is a switch when a joint moves more than ``switch_threshold``
    (:func:`~iik.joint_path.branch_switches`) or when the branch does not continue to it
    (:func:`_continues` between the poses of the two configurations, with the IK ``method``: a
    jump below the threshold). With ``start`` (6,) [rad], step 0 is measured from it."""
    q = np.asarray(q, dtype=float)
    full = q if start is None else np.vstack([start, q])
    shift = len(full) - len(q)
    if len(full) < 2:
        return ()
    T = fk(full, arm).reshape(-1, 4, 4)
    det = np.linalg.det(jacobian(full, arm).reshape(-1, 6, 6))
    sign = np.where(np.abs(det) <= SINGULAR * arm.reach**3, 0.0, np.sign(det))
    big = np.zeros(len(full), bool)
    big[list(branch_switches(full, switch_threshold))] = True
    ended = np.zeros(len(full), bool)
    for i in np.flatnonzero(~big[1:]) + 1:
        ended[i] = not _continues(full[i - 1], T[i - 1], full[i], T[i], arm, method)
    jump = np.concatenate([[0.0], np.abs(np.diff(full, axis=0)).max(axis=1)])
    events = [PathEvent(int(i) - shift, "switch", f"switch: a joint moved {jump[i]:.3g} rad in one step "
                                                  f"(more than {switch_threshold:g} rad)")
              for i in np.flatnonzero(big)]
    events += [PathEvent(int(i) - shift, "switch", f"switch: the branch ended (it does not continue from the "
                                                   f"previous step); the path jumped {jump[i]:.3g} rad")
               for i in np.flatnonzero(ended)]
    switched = big | ended
    for i in np.flatnonzero(~switched[1:] & (sign[1:] != sign[:-1])) + 1:
        text = f"singular: det J went from {det[i - 1]:.3g} to {det[i]:.3g} without a jump"
        events.append(PathEvent(int(i) - shift, "singular", text))
    events += _cusps(q, sign[shift:], switched[shift:], arm)
    return tuple(sorted(events, key=lambda e: (e.step, e.kind)))
