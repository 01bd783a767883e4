"""Box obstacles (:class:`iik.scene.Box`), enclosing ellipsoids (Eq 52-53), step-point repulsion (Sec 3.6.2).

Frames and units: every point is in the arm's base frame 0 [m].

Eq 53 as printed (``x_r = w / (cos b cos a)``, ``y_r = d / (cos b sin a)``,
``z_r = h / sin a`` with ``a = pi/4``, ``b = atan(cos a)``) does **not** touch
the box's corners in either reading of ``w, d, h``: with half-dimensions the
corners lie outside the ellipsoid (Eq 52 gives 1/3 + 1/3 + 1/2 = 7/6), with
full dimensions the ellipsoid is twice too large. The z radius needs
``sin(b)`` instead of ``sin(a)``; with half-dimensions the corrected radii are
``sqrt(3) * (w/2, d/2, h/2)`` and Eq 52 equals 1 at every corner. This module
uses the corrected form (:func:`enclosing_radii`); the printed one is kept in
``verification/checks/planning.py`` for the erratum row.

Repulsion (Sec 3.6.2.2): a step-point inside an obstacle's ellipsoid padded
by the safety zone (radii + 30 mm) is pushed along the unit normal of the plane
through the start, the goal and the point at the horizon ``[inf, 0, 0]``. A
plane through a point at infinity along +x contains the +x direction, so its
normal is ``n = (goal - start) x e_x`` (normalised). The thesis does not say
which side of the plane to push to; we push to the side with ``n_z > 0`` (over
the obstacle) and, for a horizontal ``n``, to the side of the point relative to
the ellipsoid's centre. If ``goal - start`` is parallel to x the plane is
undefined and we use ``(goal - start) x e_y`` (our choice).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from ..safety import SAFETY_ZONE  # re-exported: its home is iik.safety
from ..scene import Box
from ..validation import as_points

__all__ = [
    "SAFETY_ZONE",
    "Box",
    "enclosing_radii",
    "ellipsoid_value",
    "repulsion_normal",
    "repel_points",
]

_A = math.pi / 4  # Eq 53: alpha
_B = math.atan(math.cos(_A))  # Eq 53: beta, elevation of a cube's corner


def enclosing_radii(box: Box) -> np.ndarray:
    """Radii (x_r, y_r, z_r) [m] of the ellipsoid through the box's corners (Eq 53, corrected).

    ``w, d, h`` are the box's *half* dimensions and ``z_r`` uses ``sin(beta)``
    (printed: ``sin(alpha)``), giving ``sqrt(3) * half`` on each axis.
    """
    w, d, h = box.half
    return np.array([
        w / (math.cos(_B) * math.cos(_A)),  # Eq 53 x_r
        d / (math.cos(_B) * math.sin(_A)),  # Eq 53 y_r
        h / math.sin(_B),  # Eq 53 z_r, corrected: printed h / sin(alpha)
    ])


def ellipsoid_value(points, center, radii) -> np.ndarray:
    """Left-hand side of Eq 52 for each point: < 1 inside, 1 on, > 1 outside. (n,)."""
    p, _ = as_points(points, "points")
    c = np.asarray(center, float)
    r = np.asarray(radii, float)
    return np.sum(((p - c) / r) ** 2, axis=1)  # Eq 52


def repulsion_normal(start, goal) -> np.ndarray:
    """Unit normal of the plane through start, goal and ``[inf, 0, 0]`` (Sec 3.6.2.2).

    ``n = (goal - start) x e_x`` normalised, oriented so that ``n_z >= 0``.
    Falls back to ``(goal - start) x e_y`` when the path is parallel to x, and
    to ``e_z`` when start and goal coincide.
    """
    s, _ = as_points(start, "start")
    g, _ = as_points(goal, "goal")
    d = (g - s)[0]
    if np.linalg.norm(d) < 1e-12:
        return np.array([0.0, 0.0, 1.0])
    n = np.cross(d, [1.0, 0.0, 0.0])
    if np.linalg.norm(n) < 1e-9 * np.linalg.norm(d):
        n = np.cross(d, [0.0, 1.0, 0.0])
    n = n / np.linalg.norm(n)
    return -n if n[2] < 0 else n


def _push(p, n, c, r):
    """Smallest |t| moving p + t n onto the ellipsoid, on the preferred side."""
    u, v = (p - c) / r, n / r
    a, b, c0 = v @ v, 2.0 * (u @ v), u @ u - 1.0
    disc = math.sqrt(max(b * b - 4 * a * c0, 0.0))
    t_plus, t_minus = (-b + disc) / (2 * a), (-b - disc) / (2 * a)
    if n[2] > 1e-9:
        return t_plus
    side = (p - c) @ n
    return t_plus if side >= 0 else t_minus


def repel_points(points, boxes, start, goal, *, safety_zone: float = SAFETY_ZONE,
                 keep_ends: bool = True, max_rounds: int = 10) -> tuple[np.ndarray, np.ndarray]:
    """Push step-points out of every obstacle's padded ellipsoid (Sec 3.6.2.2).

    Args:
        points: (n, 3) step-points [m].
        boxes: Iterable of :class:`~iik.scene.Box`; only ``kind == "obstacle"`` ones repel.
        start, goal: The path's start and goal (3,) [m] defining the push direction.
        safety_zone: Added to every radius [m] (30 mm in the thesis).
        keep_ends: Leave the first and last points in place (they are the
            requested start/goal or via-points).
        max_rounds: Repeat over all obstacles until no point is inside (pushing
            out of one ellipsoid can push into another).

    Returns:
        ``(points (n, 3), moved (n,) bool)``.
    """
    pts, _ = as_points(points, "points")
    pts = pts.copy()
    n = repulsion_normal(start, goal)
    obstacles = [b for b in boxes if b.kind == "obstacle"]
    moved = np.zeros(len(pts), bool)
    lo, hi = (1, len(pts) - 1) if keep_ends else (0, len(pts))
    for _ in range(max_rounds):
        changed = False
        for box in obstacles:
            c = np.asarray(box.center)
            r = enclosing_radii(box) + safety_zone
            val = ellipsoid_value(pts[lo:hi], c, r) if hi > lo else np.zeros(0)
            for j in np.flatnonzero(val < 1.0 - 1e-9):
                i = lo + j
                pts[i] = pts[i] + _push(pts[i], n, c, r) * n
                moved[i] = changed = True
        if not changed:
            break
    return pts, moved


def __getattr__(name: str):
    """``Obstacle``: the deprecated name of :class:`iik.scene.Box` (the project's one box type)."""
    if name == "Obstacle":
        warnings.warn("iik.planning.Obstacle is deprecated: it is iik.scene.Box (also iik.planning.Box)",
                      DeprecationWarning, stacklevel=2)
        return Box
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
