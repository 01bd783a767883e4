"""Figures shared by checks and notebooks (matplotlib, Agg-safe; no pyplot state kept)."""

from __future__ import annotations

import numpy as np

from iik.arm import THESIS_ARM, Arm
from iik.kinematics import joint_frames
from iik.scene import THESIS_SCENE, Scene

__all__ = ["arm_points", "draw_arm", "draw_scene", "new_figure", "shape_edges", "draw_collision"]


def new_figure(*args, **kwargs):
    """A matplotlib Figure not registered with pyplot (safe in threads and loops)."""
    from matplotlib.figure import Figure

    return Figure(*args, **kwargs)


def arm_points(q, arm: Arm = THESIS_ARM) -> np.ndarray:
    """Polyline of the arm [m] in base frame 0: base, frame 1..6 origins -> (7, 3)."""
    F = joint_frames(q, arm)
    return np.vstack([np.zeros(3), F[:, :3, 3]])


def draw_arm(ax, q, arm: Arm = THESIS_ARM, **kwargs):
    """Draw the arm at ``q`` [rad] on a 3-D axes (thesis base frame, m); returns the line."""
    P = arm_points(q, arm)
    (line,) = ax.plot(P[:, 0], P[:, 1], P[:, 2], marker="o", **kwargs)
    T = joint_frames(q, arm)[-1]
    z = T[:3, 2] * 0.08  # approach axis z6 (points back along the last link, Table II)
    ax.plot(*np.stack([T[:3, 3], T[:3, 3] - z]).T, color=line.get_color(), lw=3)
    return line


def draw_scene(ax, scene: Scene = THESIS_SCENE) -> None:
    """Outline the platform box and the floor (2 m x 2 m patch) on a 3-D axes, equal scale."""
    lo, hi = np.asarray(scene.platform.lower), np.asarray(scene.platform.upper)
    for a in (0, 1, 2):
        for b in (lo, hi):
            for c in (lo, hi):
                p0, p1 = lo.copy(), hi.copy()
                others = [k for k in (0, 1, 2) if k != a]
                p0[others[0]] = p1[others[0]] = b[others[0]]
                p0[others[1]] = p1[others[1]] = c[others[1]]
                ax.plot(*np.stack([p0, p1]).T, color="goldenrod", lw=1)
    g = np.linspace(-1, 1, 9)
    X, Y = np.meshgrid(g, g)
    ax.plot_wireframe(X, Y, np.full_like(X, scene.floor.z), color="0.5", lw=0.4)
    ax.set_xlim(-1, 1)
    ax.set_ylim(-1, 1)
    ax.set_zlim(scene.floor.z, 1.2)
    ax.set_box_aspect((2, 2, 1.2 - scene.floor.z))  # equal scale on all axes
    ax.view_init(elev=15, azim=-65)


def shape_edges(geom, M: np.ndarray) -> list[np.ndarray]:
    """Wireframe polylines (each (k, 3), metres) of a coal Box or Cylinder placed at 4x4 ``M``."""
    import coal

    R, t = M[:3, :3], M[:3, 3]
    lines = []
    if isinstance(geom, coal.Box):
        h = np.asarray(geom.halfSide)
        corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * h
        for i in range(8):
            for j in range(i + 1, 8):
                if np.sum(np.abs(corners[i] - corners[j]) > 0) == 1:
                    lines.append(np.stack([corners[i], corners[j]]) @ R.T + t)
    elif isinstance(geom, coal.Cylinder):
        a = np.linspace(0, 2 * np.pi, 25)
        r, hz = geom.radius, geom.halfLength
        for z in (-hz, hz):
            lines.append(np.stack([r * np.cos(a), r * np.sin(a), np.full_like(a, z)], 1) @ R.T + t)
        for k in range(4):
            c, s = r * np.cos(k * np.pi / 2), r * np.sin(k * np.pi / 2)
            lines.append(np.array([[c, s, -hz], [c, s, hz]]) @ R.T + t)
    return lines


def draw_collision(ax, model, collision_model, q, **kwargs) -> None:
    """Draw the collision shapes of a Pinocchio model at ``q`` [rad], one colour per link."""
    import pinocchio as pin

    data, gdata = model.createData(), pin.GeometryData(collision_model)
    pin.forwardKinematics(model, data, np.asarray(q, float))
    pin.updateGeometryPlacements(model, data, collision_model, gdata)
    per_link: dict[str, list[np.ndarray]] = {}
    for k, go in enumerate(collision_model.geometryObjects):
        lines = per_link.setdefault(model.frames[go.parentFrame].name, [])
        for line in shape_edges(go.geometry, gdata.oMg[k].homogeneous):
            lines += [line, np.full((1, 3), np.nan)]  # NaN rows break the polyline
    for i, lines in enumerate(per_link.values()):
        ax.plot(*np.concatenate(lines).T, color=f"C{i % 10}", lw=0.7, **kwargs)
