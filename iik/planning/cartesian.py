"""The thesis's Cartesian path (Sec 3.6.1-3.6.3, Sec 4.2.1): step-points, repulsion, orientations.

:func:`build_path` joins start, via-points (Table IV or explicit) and goal by
straight lines (or arcs, Sec 4.2.1.1) divided into step-points (<= 30 mm, or a
fixed count such as 39 per segment; at most :data:`~iik.planning.MAX_STEP_POINTS`
in all); points inside an obstacle's padded ellipsoid are repelled (Eq 52-53,
Sec 3.6.2.2), and so are the planner's via-points (Sec 3.6.3), never the
scenario's requested ones (Sec 4.2.1: the tool "must pass through such
via-points"); step-points under the platform or floor safety level are lifted;
too-long steps created by repulsion are subdivided and repelled again. Orientations follow the gradual Euler
change (or slerp). Frames and units: base frame 0, m, rad (Z-Y-Z angles of the
corrected Eq 42).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidInputError
from ..rotations import euler_from_matrix, pose_from_euler
from ..scene import Box, Scene
from .errors import ScenarioError
from .obstacles import ellipsoid_value, enclosing_radii, repel_points
from .path import MAX_STEP_POINTS, arc_steps, densify, interpolate_orientation, straight_steps
from .scenario import Scenario, check_step_points
from .viapoints import via_point_path

__all__ = ["CartesianPath", "build_path", "poses_of"]


@dataclass(frozen=True)
class CartesianPath:
    """End-effector step-points and orientations (base frame, m, rad).

    Attributes:
        points: (n, 3) tool points [m].
        euler: (n, 3) Z-Y-Z angles (alpha, beta, gamma) [rad] per point (corrected Eq 42).
        segment: (n,) index of the segment each point belongs to.
        key_index: Indices of start, via-points and goal in ``points``.
        via_points: (k, 3) via-points used [m] (after repulsion).
        via_numbers: Table III numbers when chosen by Table IV, else ().
        routes: Route per segment (``"line"`` / ``"arc"``).
        repelled: (n,) True where Sec 3.6.2.2 moved the point.
        lifted: (n,) True where the platform/floor rule lifted the point.
        min_ellipsoid_value: Smallest Eq 52 value over points and padded ellipsoids
            (>= 1 means every point is outside every padded ellipsoid).
    """

    points: np.ndarray
    euler: np.ndarray
    segment: np.ndarray
    key_index: tuple[int, ...]
    via_points: np.ndarray
    via_numbers: tuple[int, ...]
    routes: tuple[str, ...]
    repelled: np.ndarray
    lifted: np.ndarray
    min_ellipsoid_value: float

    @property
    def n(self) -> int:
        """Number of step-points."""
        return len(self.points)

    def key_path(self) -> CartesianPath:
        """Only start, via-points and goal (the key points of the LJI mode, Sec 2.6)."""
        keys = np.asarray(self.key_index)
        return dataclasses.replace(self, points=self.points[keys], euler=self.euler[keys],
                                   segment=np.arange(len(keys)), key_index=tuple(range(len(keys))),
                                   repelled=self.repelled[keys], lifted=self.lifted[keys])


def poses_of(points: np.ndarray, euler: np.ndarray) -> np.ndarray:
    """(n, 4, 4) tool poses from points [m] and Z-Y-Z angles [rad] (corrected Eq 42)."""
    euler = np.asarray(euler, float)
    return pose_from_euler(points, euler[:, 0], euler[:, 1], euler[:, 2]).reshape(-1, 4, 4)


def _alpha_auto(points: np.ndarray) -> np.ndarray:
    """"Any alpha" default: the tool tilts outward (wrist nearer the base than the tool).

    Eq 46's alpha' = atan2(py, px) is the azimuth of the approach direction
    (wrist -> tool). Our z6 points tool -> wrist (d6 = -l5, Table II), so the
    same tool attitude is alpha' + pi in the corrected Eq 42.
    """
    return np.arctan2(points[:, 1], points[:, 0]) + np.pi  # Eq 46, expressed for z6


def _lift(points: np.ndarray, platform: Box | None, floor_z: float | None, s: float, keep: set[int]):
    """Platform/floor avoidance: lift step-points into the safety level ``s`` [m] above them."""
    pts = points.copy()
    lifted = np.zeros(len(pts), bool)
    for i in range(len(pts)):
        if i in keep:
            continue
        if platform is not None:
            c, h = np.asarray(platform.center), platform.half
            if np.all(np.abs(pts[i, :2] - c[:2]) <= h[:2] + s) and pts[i, 2] < c[2] + h[2] + s:
                pts[i, 2] = c[2] + h[2] + s
                lifted[i] = True
        if floor_z is not None and pts[i, 2] < floor_z + s:
            pts[i, 2] = floor_z + s
            lifted[i] = True
    return pts, lifted


def _key_points(sc: Scenario, via_points) -> tuple[np.ndarray, np.ndarray, tuple[int, ...]]:
    """(start, via-points, goal) rows, the via-points (k, 3) [m] and their Table III numbers.

    The scenario's requested via-points stay where they are; the planner's own
    (Table IV, or ``via_points`` given by a redesign) are repelled like step-points.
    """
    p0 = np.asarray(sc.start.position, float)
    p1 = np.asarray(sc.goal.position, float)
    nums: tuple[int, ...] = ()
    if via_points is not None:
        vias = np.asarray(via_points, float).reshape(-1, 3)
    elif sc.via_points is not None:  # requested: the tool passes through them (Sec 4.2.1), never moved
        vias = np.reshape(sc.via_points, (-1, 3))
        return np.vstack([p0, vias, p1]), vias, nums
    else:
        vias, nums = via_point_path(p0, p1)  # Table IV
    if len(vias):  # the planner's via-points may be repelled by ordinary obstacles too (Sec 3.6.3)
        vias, _ = repel_points(np.vstack([p0, vias, p1]), sc.obstacles, p0, p1, safety_zone=sc.safety_zone)
        vias = vias[1:-1]
    return np.vstack([p0, vias, p1]), vias, nums


def _orientations(sc: Scenario, points: np.ndarray) -> np.ndarray:
    """Euler angles (n, 3) [rad] changed gradually along the travelled path (Sec 4.2.1).

    "Any alpha" (alpha None): alpha' + pi with gamma + pi (a half turn of the
    symmetric gripper about its axis), which keeps theta6 mid-range.
    """
    p0, p1 = np.asarray(sc.start.position, float), np.asarray(sc.goal.position, float)
    a0 = sc.start.alpha if sc.start.alpha is not None else float(_alpha_auto(p0[None])[0])
    a1 = sc.goal.alpha if sc.goal.alpha is not None else float(_alpha_auto(p1[None])[0])
    g0 = sc.start.gamma + (np.pi if sc.start.alpha is None else 0.0)
    g1 = sc.goal.gamma + (np.pi if sc.goal.alpha is None else 0.0)
    e0 = np.array([a0, sc.start.beta, g0])
    e1 = np.array([a1, sc.goal.beta, g1])
    cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
    t = cum / cum[-1] if cum[-1] > 0 else np.linspace(0, 1, len(points))
    if sc.orientation == "euler":
        euler = e0 + t[:, None] * (e1 - e0)
        if sc.start.alpha is None and sc.goal.alpha is None:
            euler[:, 0] = _alpha_auto(points)  # "any alpha" (Sec 3.6): face along the azimuth
        return euler
    grid = interpolate_orientation(e0, e1, 201, method="slerp")
    R = grid[np.rint(t * 200).astype(int)]
    return np.array([np.asarray(euler_from_matrix(r), float).reshape(-1)[:3] for r in R])


def build_path(sc: Scenario, *, scene: Scene | None = None, via_points=None,
               routes: tuple[str, ...] | None = None) -> CartesianPath:
    """Cartesian step-points with orientations for scenario ``sc`` (Sec 3.6).

    Args:
        sc: The scenario (base frame, m, rad).
        scene: Its platform is lifted over, never repelled (Sec 3.6.3), and points stay a
            safety zone above its floor; ``None``: no platform and no floor.
        via_points: The planner's own via-points ((k, 3) [m], repelled like step-points);
            default: ``sc.via_points`` (requested: kept in place), else Table IV by region.
        routes: Override the per-segment routes.

    Raises:
        ScenarioError: (``planning.max_step`` / ``planning.steps_per_segment``) the path
            would have more than :data:`~iik.planning.MAX_STEP_POINTS` step-points.
    """
    platform = scene.platform if scene is not None else None
    floor_z = scene.floor.z if scene is not None else None
    keys, vias, nums = _key_points(sc, via_points)
    nseg = len(keys) - 1
    routes = tuple(routes or sc.segments or ("line",) * nseg)
    if len(routes) != nseg:
        raise InvalidInputError("routes", f"needs {nseg} entries, got {len(routes)}")
    check_step_points(sc, keys, routes)  # bounded memory before any point is made
    p0, p1 = keys[0], keys[-1]
    pts, seg, key_index = [keys[:1]], [0], [0]
    for k in range(nseg):
        f = arc_steps if routes[k] == "arc" else straight_steps
        s = f(keys[k], keys[k + 1], max_step=sc.max_step, n_steps=sc.steps_per_segment)
        pts.append(s[1:])
        seg.extend([k] * (len(s) - 1))
        key_index.append(key_index[-1] + len(s) - 1)
    points = np.concatenate(pts)
    segment = np.asarray(seg)
    fixed = set(key_index)
    repelled = np.zeros(len(points), bool)
    lifted = np.zeros(len(points), bool)
    max_step = sc.max_step if sc.steps_per_segment is None else max(sc.max_step,
                                                                     _max_step(keys, sc.steps_per_segment))
    for _ in range(6):
        keep = np.zeros(len(points), bool)
        keep[list(fixed)] = True
        moved_pts, moved = repel_points(points, sc.obstacles, p0, p1, safety_zone=sc.safety_zone)
        moved_pts[keep] = points[keep]  # via-points stay where they are (already repelled)
        moved &= ~keep
        points, lift = _lift(moved_pts, platform, floor_z, sc.safety_zone, fixed)
        repelled |= moved
        lifted |= lift
        dense, src = densify(points, max_step)
        if len(dense) == len(points):
            break
        if len(dense) > MAX_STEP_POINTS:
            raise ScenarioError("planning.max_step",
                                f"the path repelled around the obstacles needs {len(dense)} step-points of "
                                f"at most {max_step:g} m; at most {MAX_STEP_POINTS} are allowed (bounded "
                                "memory and time)")
        old = np.rint(src).astype(int)
        kept = np.isclose(src, old)
        idx_map = {int(o): j for j, o in enumerate(old) if kept[j]}
        fixed = {idx_map[i] for i in fixed}
        key_index = [idx_map[i] for i in key_index]
        segment = segment[np.minimum(np.ceil(src - 1e-9).astype(int), len(segment) - 1)]
        repelled = np.where(kept, repelled[old], False)
        lifted = np.where(kept, lifted[old], False)
        points = dense
    return CartesianPath(points=points, euler=_orientations(sc, points), segment=segment,
                         key_index=tuple(key_index), via_points=vias, via_numbers=nums, routes=routes,
                         repelled=repelled, lifted=lifted, min_ellipsoid_value=_min_ellipsoid(sc, points))


def _min_ellipsoid(sc: Scenario, points: np.ndarray) -> float:
    """Smallest Eq 52 value of the inner step-points over the padded obstacle ellipsoids."""
    vmin = np.inf
    for box in sc.obstacles:
        if box.kind == "obstacle" and len(points) > 2:
            v = ellipsoid_value(points[1:-1], box.center, enclosing_radii(box) + sc.safety_zone)
            vmin = min(vmin, float(v.min()))
    return vmin


def _max_step(keys: np.ndarray, n: int) -> float:
    return float(np.linalg.norm(np.diff(keys, axis=0), axis=1).max() / n) * 1.0000001
