"""Files and figures of a :class:`~iik.planning.PlanResult` (used by ``iik plan``, notebook, report).

* ``trajectory.csv`` -- the timed joint trajectory sampled every ``dt``: ``t`` [s], ``q1..q6``
  [rad], ``qd1..qd6`` [rad/s], ``qdd1..qdd6`` [rad/s^2];
* ``steps.csv`` -- per step-point: the time the arm executes it (``t`` [s], whole ms:
  :attr:`~iik.planning.Trajectory.step_t`; only for a successful plan), tool point [m],
  joints [rad], effort index (Eq 54) [rad], whole-arm clearance [m] with the closest link
  and object, and the certified clearance of the motion to the next step [m];

``iik run SCENARIO`` executes exactly the ``t, q1..q6`` of ``steps.csv``, and
``iik run --trajectory`` accepts either CSV as written (:mod:`iik.planning.timing`).
* ``summary.txt`` -- the summary, the notes and every attempt;
* ``scene.png`` (like Fig 42), ``joints.png`` (like Fig 43), ``effort.png`` (like Fig 44).
"""

from __future__ import annotations

import csv
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from iik.kinematics import joint_frames

from .obstacles import enclosing_radii

if TYPE_CHECKING:  # pragma: no cover
    from .pipeline import PlanResult

__all__ = ["write_outputs", "plot_scene", "plot_joints", "plot_effort"]


def write_outputs(res: PlanResult, out: Path, *, figures: bool = True) -> list[Path]:
    """Write the CSVs, the summary and (optionally) the figures into ``out``; return the paths."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    files = []
    if res.trajectory is not None:
        tr = res.trajectory
        p = out / "trajectory.csv"
        with p.open("w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["t"] + [f"q{i}" for i in range(1, 7)] + [f"qd{i}" for i in range(1, 7)]
                       + [f"qdd{i}" for i in range(1, 7)])
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
            w.writerow(["step"] + (["t"] if timed else []) + ["x", "y", "z"] + [f"q{i}" for i in range(1, 7)]
                       + ["effort", "clearance", "closest_link", "closest_object",
                          "motion_clearance_to_next"])
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


def _box_faces(center, size):
    c, h = np.asarray(center), 0.5 * np.asarray(size)
    v = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * h + c
    idx = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    return [[v[i] for i in f] for f in idx]


def plot_scene(res: PlanResult, ax, *, n_arms: int = 8) -> None:
    """3D scene like Fig 42: boxes, padded ellipsoids, the tool path and arm snapshots (base frame, m)."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    sc = res.scenario
    plat = res.scene.platform
    ax.add_collection3d(Poly3DCollection(_box_faces(plat.center, plat.size), facecolor="tab:red", alpha=0.15,
                                         edgecolor="tab:red", linewidth=0.5))
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 24), np.linspace(0, np.pi, 12))
    for b in sc.obstacles:
        col = "gold" if b.kind == "obstacle" else "tab:gray"
        ax.add_collection3d(Poly3DCollection(_box_faces(b.center, b.size), facecolor=col, alpha=0.35,
                                             edgecolor="k", linewidth=0.3))
        if b.kind == "obstacle":
            r = enclosing_radii(b) + sc.safety_zone
            x = b.center[0] + r[0] * np.cos(u) * np.sin(v)
            y = b.center[1] + r[1] * np.sin(u) * np.sin(v)
            z = b.center[2] + r[2] * np.cos(v)
            ax.plot_wireframe(x, y, z, color="tab:orange", linewidth=0.3, alpha=0.5)
    if res.cartesian is not None:
        P = res.cartesian.points
        ax.plot(P[:, 0], P[:, 1], P[:, 2], ".", color="tab:cyan", ms=2, label="thesis step-points")
    if len(res.points):
        ax.plot(res.points[:, 0], res.points[:, 1], res.points[:, 2], "-", color="tab:blue", lw=1.5,
                label=f"tool path ({res.method})")
        for i in np.linspace(0, len(res.q) - 1, min(n_arms, len(res.q))).astype(int):
            F = joint_frames(res.q[i], res.arm)
            pts = np.vstack([[0, 0, 0], F[:, :3, 3]])
            ax.plot(pts[:, 0], pts[:, 1], pts[:, 2], "-o", color="tab:blue", lw=0.8, ms=2, alpha=0.5)
        ax.scatter(*res.points[0], color="red", s=20, label="start")
        ax.scatter(*res.points[-1], color="blue", s=20, label="goal")
    fz = res.scene.floor.z
    ax.set_xlim(-0.6, 0.9)
    ax.set_ylim(-0.75, 0.75)
    ax.set_zlim(fz, fz + 1.5)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m] (base frame)")
    ax.set_title(sc.title or sc.name, fontsize=9)
    ax.legend(fontsize=7, loc="upper left")


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
