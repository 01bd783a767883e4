"""Files and figures of a :class:`~iik.planning.PlanResult` (used by ``iik plan``, notebook, report).

* ``trajectory.csv`` -- the timed joint trajectory sampled every ``dt``: ``t`` [s], ``q1..q6``
  [rad], ``qd1..qd6`` [rad/s], ``qdd1..qdd6`` [rad/s^2];
* ``steps.csv`` -- per step-point: the time the arm executes it (``t`` [s], whole ms:
  :attr:`~iik.planning.Trajectory.step_t`; only for a successful plan), tool point [m],
  joints [rad], effort index (Eq 54) [rad], whole-arm clearance [m] with the closest link
  and object, and the certified clearance of the motion to the next step [m];
  (the columns of both: :mod:`iik.trajectory_csv`, which the reader uses too)

``iik run SCENARIO`` executes exactly the ``t, q1..q6`` of ``steps.csv``, and
``iik run --trajectory`` accepts either CSV as written (:mod:`iik.planning.timing`).
* ``summary.txt`` -- the summary, the notes and every attempt;
* ``scene.png`` (like Fig 42), ``joints.png`` (like Fig 43), ``effort.png`` (like Fig 44).

The folder is written whole or not at all (:func:`iik.files.atomic_output`): into a temporary
sibling, moved into place when every file is written; an interrupt leaves the previous
output as it was. An existing folder is replaced only if it holds nothing but these files
(:data:`PLAN_FILES`).
"""

from __future__ import annotations

import csv
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from iik.arm import Arm
from iik.files import atomic_output
from iik.trajectory_csv import TRAJECTORY_COLUMNS, steps_columns

from .obstacles import enclosing_radii

if TYPE_CHECKING:  # pragma: no cover
    from .pipeline import PlanResult

__all__ = ["PLAN_FILES", "write_outputs", "plot_scene", "plot_joints", "plot_effort", "box_faces",
           "collision_faces", "draw_arm_bodies", "set_equal_axes"]


#: Every file :func:`write_outputs` writes (an output folder holding anything else is not replaced).
PLAN_FILES = ("trajectory.csv", "steps.csv", "summary.txt", "scene.png", "joints.png", "effort.png")


def write_outputs(res: PlanResult, out: Path, *, figures: bool = True) -> list[Path]:
    """Write the CSVs, the summary and (optionally) the figures into the folder ``out``, whole or
    not at all (module docstring); return the paths written.

    Raises:
        FileError: (argument ``out``) ``out`` is a file, holds other things than
            :data:`PLAN_FILES`, or cannot be written.
    """
    with atomic_output(out, "out", folder=True, owns=PLAN_FILES) as o:
        files = _write_files(res, o.path, figures)
    return [o.final(f) for f in files]


def _write_files(res: PlanResult, out: Path, figures: bool) -> list[Path]:
    files = []
    if res.trajectory is not None:
        tr = res.trajectory
        p = out / "trajectory.csv"
        with p.open("w", newline="") as f:
            w = csv.writer(f)
            w.writerow(TRAJECTORY_COLUMNS)
            for k in range(len(tr.t)):
                row = np.concatenate([tr.q[k], tr.qd[k], tr.qdd[k]])
                w.writerow([f"{tr.t[k]:.6f}"] + [f"{v:.9f}" for v in row])
        files.append(p)
    if len(res.q):
        p = out / "steps.csv"
        c = res.clearance
        timed = res.success and res.trajectory is not None and res.trajectory.step_t is not None
        with p.open("w", newline="") as f:
            w = csv.writer(f)
            w.writerow(steps_columns(timed))
            for i in range(len(res.q)):
                mot = c.motion[i] if i < len(c.motion) else float("nan")
                w.writerow([i] + ([f"{res.trajectory.step_t[i]:.3f}"] if timed else [])
                           + [f"{v:.6f}" for v in res.points[i]] + [f"{v:.9f}" for v in res.q[i]]
                           + [f"{res.effort[i]:.9f}", f"{c.step[i]:.6f}", c.step_link[i], c.step_object[i],
                              f"{mot:.6f}"])
        files.append(p)
    p = out / "summary.txt"
    p.write_text(res.summary() + "\n" + "\n".join(f"- {line}" for line in res.log) + "\n")
    files.append(p)
    if figures and len(res.q):
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        for name, fn, kw in (("scene.png", plot_scene, {"projection": "3d"}),
                             ("joints.png", plot_joints, {}), ("effort.png", plot_effort, {})):
            fig = plt.figure(figsize=(7, 5.5) if name == "scene.png" else (7, 4))
            ax = fig.add_subplot(111, **kw)
            fn(res, ax)
            fig.tight_layout()
            fig.savefig(out / name, dpi=110)
            plt.close(fig)
            files.append(out / name)
    return files


def box_faces(center, size) -> list[list[np.ndarray]]:
    """The six faces (4 corners each, [m]) of an axis-aligned box of full ``size`` at ``center``."""
    c, h = np.asarray(center), 0.5 * np.asarray(size)
    v = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * h + c
    idx = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    return [[v[i] for i in f] for f in idx]


def _shape_faces(geom, M: np.ndarray, n: int = 16) -> list[np.ndarray]:
    """Polygons (each (k, 3) [m]) of a coal Box or Cylinder placed at the 4x4 pose ``M``."""
    import coal

    if isinstance(geom, coal.Box):
        local = [np.array(f) for f in box_faces((0.0, 0.0, 0.0), 2.0 * np.asarray(geom.halfSide))]
    elif isinstance(geom, coal.Cylinder):
        a = np.linspace(0.0, 2.0 * np.pi, n + 1)
        ring = np.stack([geom.radius * np.cos(a), geom.radius * np.sin(a)], axis=1)
        lo = np.column_stack([ring, np.full(n + 1, -geom.halfLength)])
        hi = np.column_stack([ring, np.full(n + 1, geom.halfLength)])
        local = [lo[:-1], hi[:-1]] + [np.array([lo[k], lo[k + 1], hi[k + 1], hi[k]]) for k in range(n)]
    else:
        raise TypeError(f"cannot draw a {type(geom).__name__} collision shape (boxes and cylinders only)")
    return [f @ M[:3, :3].T + M[:3, 3] for f in local]


def collision_faces(model, collision_model, q) -> dict[str, list[np.ndarray]]:
    """Polygons of a Pinocchio model's collision shapes at ``q`` [rad], per link, placed by
    Pinocchio's ``oMg`` (base frame 0, each polygon (k, 3) [m])."""
    import pinocchio as pin

    from .robot_model import collision_link

    data, gdata = model.createData(), pin.GeometryData(collision_model)
    pin.forwardKinematics(model, data, np.asarray(q, float))
    pin.updateGeometryPlacements(model, data, collision_model, gdata)
    out: dict[str, list[np.ndarray]] = {}
    for k, go in enumerate(collision_model.geometryObjects):
        faces = _shape_faces(go.geometry, gdata.oMg[k].homogeneous)
        out.setdefault(collision_link(model, go), []).extend(faces)
    return out


def draw_arm_bodies(ax, q, *, arm: Arm, colour=(0.16, 0.35, 0.78), alpha: float = 0.3,
                    link_colours=None, zorder: float = 3.0) -> np.ndarray:
    """Draw the body of ``arm`` (:func:`~iik.planning.robot_model.arm_model`) at ``q`` (6,) [rad] on a 3-D
    axes (base frame 0, m).

    Args:
        colour: RGB (0-1) of every link, unless ``link_colours`` ({link name: RGB}) says otherwise.
        alpha: Opacity of the faces.

    Returns:
        All vertices drawn (k, 3) [m] (for the axis limits).
    """
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    from .robot_model import arm_model

    tm = arm_model(arm)
    verts = []
    for link, faces in collision_faces(tm.model, tm.collision_model, q).items():
        c = (link_colours or {}).get(link, colour)
        # ragged faces (caps, quads): no autoscaling, the caller sets the limits
        ax.add_collection3d(Poly3DCollection(faces, facecolor=c, edgecolor=c, linewidth=0.2, alpha=alpha,
                                             zorder=zorder), autolim=False)
        verts.extend(faces)
    return np.vstack(verts)


def set_equal_axes(ax, points, *, margin: float = 0.05) -> np.ndarray:
    """Cubic limits around ``points`` (k, 3) [m] plus ``margin`` with equal scales on x, y and z;
    returns the (3, 2) limits."""
    P = np.asarray(points, float).reshape(-1, 3)
    P = P[np.all(np.isfinite(P), axis=1)]
    c = 0.5 * (P.min(axis=0) + P.max(axis=0))
    r = 0.5 * float(np.ptp(P, axis=0).max()) + margin
    limits = np.stack([c - r, c + r], axis=1)
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    ax.set_zlim(*limits[2])
    ax.set_box_aspect(np.ptp(limits, axis=1))
    return limits


def _legend(ax, entries, **kwargs) -> None:
    """A legend from ``(label, colour, kind)`` with kind ``"patch"``, ``"line"`` or a marker."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    handles = [Patch(facecolor=c, edgecolor=c, alpha=0.6, label=lab) if kind == "patch"
               else Line2D([], [], color=c, lw=1.5 if kind == "line" else 0, marker=None if kind == "line"
                           else kind, label=lab) for lab, c, kind in entries]
    ax.legend(handles=handles, **kwargs)


def plot_scene(res: PlanResult, ax, *, n_arms: int = 5) -> None:
    """3D scene like Fig 42 in base frame 0 [m], equal scales: platform, obstacles, supports, the
    padded Eq 52-53 ellipsoids, the tool path with step-points and via-points, the arm's URDF
    collision shapes at ``n_arms`` instants, and the link nearest the scene at the step of least
    clearance (amber, magenta inside the safety zone) with that clearance in mm."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    from .collision import SceneCollision
    from .viewer import style

    rgb = style.rgb01
    sc = res.scenario
    ax.computed_zorder = False  # draw in layers: scene, arms, path, nearest link (all translucent)
    plat = res.scene.platform
    pts = [np.asarray(box_faces(plat.center, plat.size)).reshape(-1, 3)]
    grey = rgb(style.PLATFORM)
    ax.add_collection3d(Poly3DCollection(box_faces(plat.center, plat.size), alpha=0.25, linewidth=0.4,
                                         zorder=1, facecolor=grey, edgecolor=grey))
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 24), np.linspace(0, np.pi, 12))
    for b in sc.obstacles:
        col = rgb(style.OBSTACLE if b.kind == "obstacle" else style.SUPPORT)
        alpha = 0.45 if b.kind == "obstacle" else 0.5 * style.SUPPORT_OPACITY
        ax.add_collection3d(Poly3DCollection(box_faces(b.center, b.size), facecolor=col, alpha=alpha,
                                             edgecolor="k", linewidth=0.3, zorder=1))
        pts.append(np.asarray(b.corners))
        if b.kind == "obstacle":
            r = enclosing_radii(b) + sc.safety_zone
            x = b.center[0] + r[0] * np.cos(u) * np.sin(v)
            y = b.center[1] + r[1] * np.sin(u) * np.sin(v)
            z = b.center[2] + r[2] * np.cos(v)
            ax.plot_wireframe(x, y, z, color=rgb(style.ELLIPSOID), linewidth=0.3, alpha=0.5, zorder=2)
    entries = [("arm (URDF collision shapes)", rgb(style.ARM), "patch"),
               ("obstacle", rgb(style.OBSTACLE), "patch"), ("support", rgb(style.SUPPORT), "patch"),
               ("platform", rgb(style.PLATFORM), "patch"),
               (f"ellipsoid + {sc.safety_zone * 1e3:.0f} mm zone (Eq 52-53)", rgb(style.ELLIPSOID), "line")]
    title = f"{sc.title or sc.name} ({res.method})"
    if len(res.points):
        P = res.points
        ax.plot(P[:, 0], P[:, 1], P[:, 2], "-", color=rgb(style.TOOL_PATH), lw=1.5, zorder=4)
        ax.plot(P[:, 0], P[:, 1], P[:, 2], ".", color=rgb(style.STEP_POINT), ms=2.5, zorder=4)
        entries += [("tool path", rgb(style.TOOL_PATH), "line"), ("step-points", rgb(style.STEP_POINT), ".")]
        if res.cartesian is not None and len(res.cartesian.via_points):
            V = np.asarray(res.cartesian.via_points).reshape(-1, 3)
            ax.scatter(V[:, 0], V[:, 1], V[:, 2], color=rgb(style.VIA_POINT), marker="D", s=25,
                       depthshade=False, zorder=4)
            entries.append(("via-point", rgb(style.VIA_POINT), "D"))
        pts.append(P)
        worst = int(np.argmin(res.clearance.step)) if res.clearance is not None else 0
        for i in sorted(set(np.linspace(0, len(res.q) - 1, min(n_arms, len(res.q))).astype(int)) - {worst}):
            pts.append(draw_arm_bodies(ax, res.q[i], arm=res.arm, colour=rgb(style.ARM), alpha=0.07))
        n = SceneCollision(sc.obstacles, arm=res.arm, scene=res.scene).nearest(res.q[worst])
        near = rgb(style.UNSAFE if n.distance < sc.safety_zone else style.NEAREST)
        pts.append(draw_arm_bodies(ax, res.q[worst], arm=res.arm, colour=rgb(style.ARM), alpha=0.3,
                                   link_colours={n.link: near}, zorder=3.5))
        seg = np.stack([n.on_link, n.on_object])
        ax.plot(seg[:, 0], seg[:, 1], seg[:, 2], "-o", color=near, lw=2.0, ms=3, zorder=5)
        d_mm = n.distance * 1e3
        ax.text(*seg.mean(axis=0), f" {d_mm:.1f} mm", color="k", fontsize=8, zorder=6)
        entries += [(f"nearest link at step {worst}: {n.link} to {n.object}, {d_mm:.1f} mm", near, "line")]
        title += (f"\nleast clearance at the step-points {d_mm:.1f} mm "
                  f"(safety zone {sc.safety_zone * 1e3:.0f} mm)")
    set_equal_axes(ax, np.vstack(pts))
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    ax.set_title(title + "\nbase frame 0, x/y/z [m]; clearances in mm", fontsize=8)
    ax.view_init(elev=25, azim=-60)
    _legend(ax, entries, fontsize=6, loc="upper left", bbox_to_anchor=(0.0, 1.0))


def plot_joints(res: PlanResult, ax) -> None:
    """Joint angles per step-point like Fig 43 (degrees for display)."""
    for j in range(6):
        ax.plot(np.degrees(res.q[:, j]), label=f"theta{j + 1}")
    ax.set_xlabel("step")
    ax.set_ylabel("joint angle [deg]")
    ax.set_title(f"{res.scenario.name}: joint angles ({res.method})", fontsize=9)
    ax.legend(fontsize=7, ncol=3)
    ax.grid(alpha=0.3)


def plot_effort(res: PlanResult, ax) -> None:
    """Effort index (Eq 54) per step like Fig 44, with the whole-arm clearance on a second axis."""
    ax.plot(np.degrees(res.effort), color="tab:purple", label="effort index E (Eq 54)")
    ax.set_xlabel("step")
    ax.set_ylabel("E [deg]")
    ax2 = ax.twinx()
    ax2.plot(res.clearance.step * 1000, color="tab:green", alpha=0.6, label="whole-arm clearance")
    ax2.axhline(res.scenario.safety_zone * 1000, color="tab:green", ls="--", lw=0.8)
    ax2.set_ylabel("clearance [mm]")
    ax.set_title(f"{res.scenario.name}: effort index and clearance", fontsize=9)
    ax.legend(fontsize=7, loc="upper left")
    ax2.legend(fontsize=7, loc="upper right")
