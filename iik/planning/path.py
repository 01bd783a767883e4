"""End-effector path primitives of Sec 3.6.1 and Sec 4.2.1.1.

All points are in the arm's base frame 0 [m]; angles in rad.

* :func:`straight_steps` -- the straight-line step-points of Sec 3.6.1: the
  X, Y, Z differences between two points are divided linearly. In the dense
  Linear End-effector Increment mode (LEI, Sec 2.6) the number of steps is
  ``ceil(length / max_step)`` so that no step exceeds ``max_step`` (30 mm in
  Sec 4.2.1); a fixed count (39 per segment in Sec 4.2.1) may be given instead.
* :func:`interpolate_joints` -- the sparse Linear Joint Increment mode (LJI,
  Sec 2.6): joints interpolated linearly between the IK solutions at the
  segment end points.
* :func:`arc_steps` -- the arc route the thesis used between via-points where
  the straight line had no IK solutions (Sec 4.2.1.1). The text does not
  define the arc; ours interpolates linearly in cylindrical coordinates
  about the joint-1 axis (radius, azimuth, height), i.e. it travels *around*
  the base instead of cutting towards it. The azimuth never wraps through
  +-180 deg (the joint-1 cut behind the arm, Sec 3.6.3).
* :func:`interpolate_orientation` -- the thesis's "gradual" change of the Z-Y-Z
  Euler angles (alpha, beta, gamma linearly, Sec 4.2.1) or a slerp between the
  start and goal rotations (``scipy.spatial.transform.Slerp``).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial.transform import Rotation, Slerp

from ..errors import InvalidInputError
from ..rotations import euler_matrix
from ..validation import as_float_array, as_joints, as_points

__all__ = [
    "MAX_STEP",
    "MAX_STEP_POINTS",
    "segment_length",
    "segment_steps",
    "straight_steps",
    "arc_steps",
    "interpolate_joints",
    "interpolate_orientation",
    "path_length",
    "densify",
]

#: Sec 4.2.1: "a maximum of 30 mm per step-point" [m].
MAX_STEP = 0.030

#: Most step-points of one Cartesian path (ours): bounds the memory and time of a plan
#: (IK, the orientation search and the Coal checks are linear in it). 5000 steps of the
#: thesis's 30 mm would be 150 m; the shipped scenarios have at most 118.
MAX_STEP_POINTS = 5000


def _point(p, name: str) -> np.ndarray:
    pb, batched = as_points(p, name)
    if batched:
        raise InvalidInputError(name, "expected one point of shape (3,)")
    return pb[0]


def _count(length: float, max_step: float, n_steps: int | None) -> int:
    """Steps of a segment of ``length`` [m]: ``n_steps``, or ``ceil(length / max_step)`` (at most 2**62)."""
    if n_steps is not None:
        if int(n_steps) != n_steps or n_steps < 1:
            raise InvalidInputError("n_steps", f"must be a positive integer, got {n_steps!r}")
        return int(n_steps)
    if not (np.isfinite(max_step) and max_step > 0):
        raise InvalidInputError("max_step", f"must be positive and finite, got {max_step!r}")
    ratio = length / max_step - 1e-12
    return max(1, math.ceil(ratio)) if ratio < 2.0**62 else 2**62


def _made(length: float, max_step: float, n_steps: int | None) -> int:
    """:func:`_count`, refused above :data:`MAX_STEP_POINTS` (the points are about to be made)."""
    n = _count(length, max_step, n_steps)
    if n >= MAX_STEP_POINTS:
        raise InvalidInputError("n_steps" if n_steps is not None else "max_step",
                                f"{n} steps over {length:.3f} m; at most {MAX_STEP_POINTS - 1} "
                                "(bounded memory)")
    return n


def straight_steps(a, b, *, max_step: float = MAX_STEP, n_steps: int | None = None) -> np.ndarray:
    """Step-points of the straight line from ``a`` to ``b`` (Sec 3.6.1), both included.

    Args:
        a, b: End points (3,) [m], base frame.
        max_step: Largest step length [m] (LEI mode); ignored if ``n_steps`` is given.
        n_steps: Fixed number of steps (e.g. 39 per segment, Sec 4.2.1).

    Returns:
        (n_steps + 1, 3) points [m]; ``a`` first and ``b`` last.
    """
    a, b = _point(a, "a"), _point(b, "b")
    n = _made(float(np.linalg.norm(b - a)), max_step, n_steps)
    s = np.linspace(0.0, 1.0, n + 1)[:, None]
    return a + s * (b - a)  # Sec 3.6.1: linear division of the X, Y, Z differences


def arc_steps(a, b, *, max_step: float = MAX_STEP, n_steps: int | None = None) -> np.ndarray:
    """Step-points of the arc route around the base from ``a`` to ``b`` (Sec 4.2.1.1).

    Cylindrical interpolation about the z axis of the base frame: radius,
    azimuth (``atan2(y, x)`` in (-pi, pi], never wrapping through the back)
    and height change linearly. Falls back to the straight line when either
    end lies on the z axis (azimuth undefined).

    Returns:
        (n + 1, 3) points [m], ``a`` first and ``b`` last.
    """
    a, b = _point(a, "a"), _point(b, "b")
    ra, rb = math.hypot(a[0], a[1]), math.hypot(b[0], b[1])
    if ra < 1e-9 or rb < 1e-9:
        return straight_steps(a, b, max_step=max_step, n_steps=n_steps)
    fa, fb = math.atan2(a[1], a[0]), math.atan2(b[1], b[0])
    s, cum, length = _arc_samples(a, b)
    n = _made(length, max_step, n_steps)
    # Equal arc-length spacing: invert the cumulative length.
    target = np.linspace(0.0, cum[-1], n + 1)
    out = _cyl(ra, rb, fa, fb, a[2], b[2], np.interp(target, cum, s))
    out[0], out[-1] = a, b
    return out


def _arc_samples(a: np.ndarray, b: np.ndarray):
    """Parameters, cumulative length [m] and length [m] of the arc route at 257 samples (fine quadrature)."""
    ra, rb = math.hypot(a[0], a[1]), math.hypot(b[0], b[1])
    fa, fb = math.atan2(a[1], a[0]), math.atan2(b[1], b[0])
    s = np.linspace(0.0, 1.0, 257)
    d = np.linalg.norm(np.diff(_cyl(ra, rb, fa, fb, a[2], b[2], s), axis=0), axis=1)
    return s, np.concatenate([[0.0], np.cumsum(d)]), float(d.sum())


def segment_length(a, b, *, route: str = "line") -> float:
    """Length [m] of the ``route`` (``"line"`` or ``"arc"``) from ``a`` to ``b`` (3,) [m]."""
    a, b = _point(a, "a"), _point(b, "b")
    if route not in ("line", "arc"):
        raise InvalidInputError("route", f"expected 'line' or 'arc', got {route!r}")
    if route == "line" or min(math.hypot(a[0], a[1]), math.hypot(b[0], b[1])) < 1e-9:
        return float(np.linalg.norm(b - a))
    return _arc_samples(a, b)[2]


def segment_steps(a, b, *, route: str = "line", max_step: float = MAX_STEP,
                  n_steps: int | None = None) -> int:
    """Number of steps :func:`straight_steps` / :func:`arc_steps` make from ``a`` to ``b`` (none made)."""
    return _count(segment_length(a, b, route=route), max_step, n_steps)


def _cyl(ra, rb, fa, fb, za, zb, s):
    r = ra + s * (rb - ra)
    f = fa + s * (fb - fa)
    z = za + s * (zb - za)
    return np.column_stack([r * np.cos(f), r * np.sin(f), z])


def interpolate_joints(q_keys, *, max_joint_step: float = 0.05) -> np.ndarray:
    """Linear joint increments between key configurations (LJI, Sec 2.6).

    Args:
        q_keys: (k, 6) joint vectors [rad] at the key points.
        max_joint_step: Largest per-joint increment per step [rad].

    Returns:
        (n, 6) joint path [rad] that contains every key configuration.
    """
    qk, _ = as_joints(q_keys, "q_keys")
    if not (np.isfinite(max_joint_step) and max_joint_step > 0):
        raise InvalidInputError("max_joint_step", "must be positive and finite")
    out = [qk[:1]]
    for q0, q1 in zip(qk[:-1], qk[1:], strict=True):
        n = max(1, math.ceil(np.abs(q1 - q0).max() / max_joint_step - 1e-12))
        s = np.linspace(0.0, 1.0, n + 1)[1:, None]
        out.append(q0 + s * (q1 - q0))
    return np.concatenate(out)


def interpolate_orientation(start_euler, goal_euler, n: int, *, method: str = "euler") -> np.ndarray:
    """Orientations for ``n`` points from the start to the goal orientation.

    Args:
        start_euler, goal_euler: Z-Y-Z Euler angles (alpha, beta, gamma) [rad] (corrected Eq 42).
        n: Number of points (>= 2), start and goal included.
        method: ``"euler"`` -- the thesis's gradual change: each Euler angle
            changes linearly (Sec 4.2.1); ``"slerp"`` -- spherical linear
            interpolation of the rotations (shortest rotation, constant rate).

    Returns:
        ``"euler"``: (n, 3) Euler angles [rad]. ``"slerp"``: (n, 3, 3) rotation matrices.
    """
    e0 = as_float_array(start_euler, "start_euler").reshape(-1)
    e1 = as_float_array(goal_euler, "goal_euler").reshape(-1)
    if e0.shape != (3,) or e1.shape != (3,):
        raise InvalidInputError("start_euler/goal_euler", "expected three Euler angles each")
    if int(n) != n or n < 2:
        raise InvalidInputError("n", f"needs at least 2 points, got {n!r}")
    s = np.linspace(0.0, 1.0, int(n))[:, None]
    if method == "euler":
        return e0 + s * (e1 - e0)
    if method == "slerp":
        R = Rotation.from_matrix(np.stack([euler_matrix(*e0), euler_matrix(*e1)]))
        return Slerp([0.0, 1.0], R)(s[:, 0]).as_matrix()
    raise InvalidInputError("method", f"expected 'euler' or 'slerp', got {method!r}")


def path_length(points) -> float:
    """Polyline length [m] of (n, 3) points."""
    pts, _ = as_points(points, "points")
    return float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())


def densify(points, max_step: float = MAX_STEP) -> tuple[np.ndarray, np.ndarray]:
    """Insert points on every polyline step longer than ``max_step`` [m].

    Returns:
        ``(points (m, 3), source (m,))`` where ``source[j]`` is the fractional
        index into the input of output point ``j`` (integers for kept points).
    """
    pts, _ = as_points(points, "points")
    out, src = [pts[0]], [0.0]
    for i in range(len(pts) - 1):
        d = float(np.linalg.norm(pts[i + 1] - pts[i]))
        k = max(1, math.ceil(d / max_step - 1e-12))
        for j in range(1, k + 1):
            t = j / k
            out.append(pts[i] + t * (pts[i + 1] - pts[i]))
            src.append(i + t)
    return np.array(out), np.array(src)
