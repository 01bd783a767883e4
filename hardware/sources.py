"""Trajectories to execute: a planned scenario, a CSV file, or the built-in demo.

Each source returns :class:`StepTargets`: the step times [s], joint targets (n, 6)
[rad] and the planned tool poses (n, 4, 4) [m] that :func:`hardware.validate`
checks the targets against. Nothing here prints; what a source has to say (which
planner method succeeded, the clearance) is in :attr:`StepTargets.note`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from iik.errors import InvalidInputError
from iik.ik import select, solve
from iik.kinematics import fk

from .executor import ValidatedTrajectory, ValidationOptions, time_steps, validate

__all__ = ["StepTargets", "demo_trajectory", "csv_trajectory", "scenario_trajectory"]

#: Largest Cartesian step between two step-points of the demo line [m] (Sec 4.2.1).
DEMO_STEP = 0.030


@dataclass(frozen=True)
class StepTargets:
    """Step-points to execute, before validation.

    Attributes:
        name: Name of the run (scenario name, CSV file stem, ``"demo"``).
        times: (n,) step times [s].
        q: (n, 6) joint targets [rad].
        poses: (n, 4, 4) planned poses of frame 6 in the base frame [m].
        orientation_free: (n,) bool: steps at which only the position is compared
            (the planner changed alpha/beta/gamma there on purpose, Sec 3.6), or None.
        note: What the source reports about itself (e.g. the planner's method), or "".
    """

    name: str
    times: np.ndarray
    q: np.ndarray
    poses: np.ndarray
    orientation_free: np.ndarray | None = None
    note: str = ""

    def __len__(self) -> int:
        return len(self.times)

    def validate(self, options: ValidationOptions | None = None, *,
                 limit: int | None = None) -> ValidatedTrajectory:
        """:func:`hardware.validate` of the first ``limit`` step-points (all if None), with
        ``options`` (default :class:`ValidationOptions`)."""
        n = len(self) if limit is None else min(int(limit), len(self))
        options = ValidationOptions() if options is None else options
        free = None if self.orientation_free is None else self.orientation_free[:n]
        return validate(self.times[:n], self.q[:n], self.poses[:n], options=options, orientation_free=free)


def demo_trajectory(speed: float = 0.5) -> StepTargets:
    """A straight line between two poses with step-points at most :data:`DEMO_STEP` apart
    (Sec 4.2.1), the least-effort IK solution (Eq 54) at each, timed at ``speed`` of the
    joint speed limits."""
    from scipy.spatial.transform import Rotation, Slerp

    qa = np.array([0.5, 0.1, 0.0, 0.4, 1.0, 0.0])  # away from the wrist singularity (q5 = 0)
    qb = np.array([0.0, 0.4, 0.0, 0.4, 1.0, 0.0])
    Ta, Tb = fk(qa), fk(qb)
    dist = float(np.linalg.norm(Tb[:3, 3] - Ta[:3, 3]))
    n = max(2, math.ceil(dist / DEMO_STEP)) + 1
    s = np.linspace(0.0, 1.0, n)
    slerp = Slerp([0.0, 1.0], Rotation.from_matrix(np.stack([Ta[:3, :3], Tb[:3, :3]])))
    poses = np.tile(np.eye(4), (n, 1, 1))
    poses[:, :3, :3] = slerp(s).as_matrix()
    poses[:, :3, 3] = (1 - s)[:, None] * Ta[:3, 3] + s[:, None] * Tb[:3, 3]
    q = np.empty((n, 6))
    prev = qa
    for k, T in enumerate(poses):
        q[k] = prev = select(solve(T), prev)  # Eq 54: least effort from the previous
    return StepTargets("demo", time_steps(q, speed_fraction=speed), q, poses)


def csv_trajectory(path: Path) -> StepTargets:
    """Step-points from a CSV file with the header columns ``t,q1..q6`` [s, rad]; the
    planned poses are FK (Eq 4) of the file's joints, so validation cannot catch a wrong IK."""
    path = Path(path)
    try:
        data = np.genfromtxt(path, delimiter=",", names=True, dtype=float)
    except (OSError, ValueError) as exc:
        raise InvalidInputError("trajectory", f"cannot read {path}: {exc}") from None
    cols = ["t", "q1", "q2", "q3", "q4", "q5", "q6"]
    if data.dtype.names is None or any(c not in data.dtype.names for c in cols):
        raise InvalidInputError("trajectory", f"{path} needs the header columns {','.join(cols)}")
    data = np.atleast_1d(data)
    t = np.asarray(data["t"], dtype=float)
    q = np.stack([np.asarray(data[c], dtype=float) for c in cols[1:]], axis=1)
    if not np.all(np.isfinite(q)) or not np.all(np.isfinite(t)):
        raise InvalidInputError("trajectory", f"{path} contains empty or non-numeric cells")
    return StepTargets(path.stem, t, q, fk(q))


def _plan(path: Path):
    """The planner's result for a scenario file (untimed: the steps are timed here)."""
    from iik.planning import PlanningFailed, PlanOptions, plan

    res = plan(path, PlanOptions(timing=False))
    if not res.success:
        raise PlanningFailed(res)
    return res


def scenario_trajectory(name: str | Path, speed: float = 0.5) -> StepTargets:
    """Step-points of a scenario (file or shipped name, :func:`iik.planning.scenario_path`) planned by
    the project's planner (thesis planner of Sec 3.6 with its fallbacks and the whole-arm
    Coal check), timed at ``speed`` of the joint speed limits.

    The planned poses are those of the thesis Cartesian path; where the planner
    changed alpha/beta (Sec 3.6) only the position is checked. For an RRT-Connect
    fallback path there is no Cartesian plan and the poses are FK of the joints.
    """
    from iik.planning import poses_of, scenario_path

    res = _plan(scenario_path(name))
    q = np.asarray(res.q, dtype=float)
    cart = res.cartesian
    free = np.zeros(len(q), dtype=bool)
    notes = []
    if cart is not None and len(cart.points) == len(q):
        poses = poses_of(np.asarray(cart.points), np.asarray(cart.euler))
        free[list(res.beta_changed_steps) + list(res.alpha_changed_steps)
             + list(res.gamma_changed_steps)] = True
    else:
        notes.append(f"{res.scenario.name}: planned by {res.method}; no Cartesian plan, poses are FK of "
                     "the joints")
        poses = fk(q)
    notes.append(f"{res.scenario.name}: planned via {res.method} ({len(q)} step-points, min whole-arm "
                 f"clearance {res.min_clearance * 1e3:.1f} mm)")
    return StepTargets(res.scenario.name, time_steps(q, speed_fraction=speed), q, poses, free,
                       "\n".join(notes))
