"""Figures shared by checks and notebooks (matplotlib, Agg-safe; no pyplot state kept)."""

from __future__ import annotations

import numpy as np

from iik.arm import THESIS_ARM, Arm
from iik.kinematics import joint_frames
from iik.planning.output import box_faces, collision_faces
from iik.scene import THESIS_SCENE, Scene

__all__ = ["arm_points", "draw_arm", "draw_scene", "new_figure", "draw_collision"]


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
    """The platform box (translucent) and a 2 m x 2 m patch of the floor on a 3-D axes, base frame 0
    [m], with equal scales on x, y and z (limits x, y in [-1, 1], z from the floor to 1.2 m); labelled
    "platform" and "floor" for a legend."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    from iik.planning.viewer import style

    p = scene.platform
    grey = style.rgb01(style.PLATFORM)
    ax.add_collection3d(Poly3DCollection(box_faces(p.center, p.size), facecolor=grey, edgecolor=grey,
                                         alpha=0.2, linewidth=0.5, label="platform"))
    g = np.linspace(-1, 1, 9)
    X, Y = np.meshgrid(g, g)
    ax.plot_wireframe(X, Y, np.full_like(X, scene.floor.z), color="0.6", lw=0.4, label="floor")
    ax.set_xlim(-1, 1)
    ax.set_ylim(-1, 1)
    ax.set_zlim(scene.floor.z, 1.2)
    ax.set_box_aspect((2, 2, 1.2 - scene.floor.z))  # equal scale on all axes
    ax.view_init(elev=15, azim=-65)


def draw_collision(ax, model, collision_model, q, *, colours=None, alpha: float = 0.35) -> dict[str, tuple]:
    """Draw the collision shapes of a Pinocchio model at ``q`` [rad] (base frame 0, m) as translucent
    polygons placed by Pinocchio's ``oMg``, one colour per link (``colours``: {link: RGB}, default
    matplotlib's cycle), each labelled by its link for a legend; returns {link: colour}."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    used = {}
    for i, (link, faces) in enumerate(collision_faces(model, collision_model, q).items()):
        c = (colours or {}).get(link, f"C{i % 10}")
        ax.add_collection3d(Poly3DCollection(faces, facecolor=c, edgecolor=c, linewidth=0.3, alpha=alpha,
                                             label=link), autolim=False)
        used[link] = c
    return used
