"""Trajectories to execute: a planned scenario, a CSV file, or the built-in demo.

Each source returns the step times [s], joint targets (n, 6) [rad] and the planned
tool poses (n, 4, 4) [m] that :func:`hardware.validate` checks the targets against.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

__all__ = ["demo_trajectory", "csv_trajectory", "scenario_trajectory"]


def demo_trajectory(speed: float = 0.5):
    """(name, times, q, poses): a 30 mm-step straight line between two poses, IK per step."""
    from scipy.spatial.transform import Rotation, Slerp

    import iik
    from hardware.executor import time_steps

    qa = np.array([0.5, 0.1, 0.0, 0.4, 1.0, 0.0])  # away from the wrist singularity (q5 = 0)
    qb = np.array([0.0, 0.4, 0.0, 0.4, 1.0, 0.0])
    Ta, Tb = iik.fk(qa), iik.fk(qb)
    dist = float(np.linalg.norm(Tb[:3, 3] - Ta[:3, 3]))
    n = max(2, math.ceil(dist / 0.030)) + 1  # <= 30 mm per step (Sec 4.2.1)
    s = np.linspace(0.0, 1.0, n)
    slerp = Slerp([0.0, 1.0], Rotation.from_matrix(np.stack([Ta[:3, :3], Tb[:3, :3]])))
    poses = np.tile(np.eye(4), (n, 1, 1))
    poses[:, :3, :3] = slerp(s).as_matrix()
    poses[:, :3, 3] = (1 - s)[:, None] * Ta[:3, 3] + s[:, None] * Tb[:3, 3]
    q = np.empty((n, 6))
    prev = qa
    for k, T in enumerate(poses):
        q[k] = prev = iik.select(iik.solve(T), prev)  # Eq 54: least effort from the previous
    return "demo", time_steps(q, speed_fraction=speed), q, poses


def csv_trajectory(path: Path):
    """(name, times, q, poses) from a CSV with columns t,q1..q6; poses = FK(q)."""
    import iik
    from iik.errors import InvalidInputError

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
    return path.stem, t, q, iik.fk(q)


def scenario_trajectory(name: str, speed: float = 0.5):
    """(name, times, q, poses, orientation_free) for a scenario, planned by
    :func:`iik.planning.pipeline.plan_scenario` (thesis planner, Sec 3.6, with its
    fallbacks and the whole-arm Coal check).

    The planned poses are those of the thesis Cartesian path; where the planner
    changed alpha/beta (Sec 3.6) only the position is checked. For an RRT-Connect
    fallback path there is no Cartesian plan and the poses are FK of the joints.
    """
    from hardware.executor import time_steps
    from iik.kinematics import fk
    from iik.planning import PlanningFailed, PlanOptions, ScenarioError, plan, poses_of
    from iik.resources import scenarios_dir

    path = Path(name)
    if not path.is_file():
        shipped = scenarios_dir() / f"{name}.toml"
        if path.suffix or len(path.parts) > 1 or not shipped.is_file():
            names = ", ".join(sorted(f.stem for f in scenarios_dir().glob("*.toml")))
            raise ScenarioError("scenario", f"{name!r} is neither a scenario file nor a shipped "
                                f"scenario ({names})")
        path = shipped
    res = plan(path, PlanOptions(timing=False))
    if not res.success:
        raise PlanningFailed(res)
    q = np.asarray(res.q, dtype=float)
    cart = res.cartesian
    free = np.zeros(len(q), dtype=bool)
    if cart is not None and len(cart.points) == len(q):
        poses = poses_of(np.asarray(cart.points), np.asarray(cart.euler))
        free[list(res.beta_changed_steps) + list(res.alpha_changed_steps)
             + list(res.gamma_changed_steps)] = True
    else:
        print(f"{res.scenario.name}: planned by {res.method}; no Cartesian plan, poses are FK of the "
              "joints", file=sys.stderr)
        poses = fk(q)
    print(f"{res.scenario.name}: planned via {res.method} ({len(q)} step-points, min whole-arm clearance "
          f"{res.min_clearance * 1e3:.1f} mm)", file=sys.stderr)
    return res.scenario.name, time_steps(q, speed_fraction=speed), q, poses, free
