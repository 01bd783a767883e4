"""Plan mode: the planned motion with its path, ellipsoids, via-points, clearance and branch switches.

Shows a :class:`~iik.planning.viewer.plan_data.PlanView`: the arm (URDF
collision shapes) along the timed trajectory, the tool path actually traced
(FK of the frames) and the planned step-points, the via-points, the enclosing
ellipsoids of Eq 52-53, the IK branch switches (marked on the live time slider
and at the tool point) and, at every frame, the link nearest the scene with a
line to the nearest obstacle point and its clearance in mm, coloured when the
clearance is below the scenario's safety zone. Frame: base frame 0 [m].
"""

from __future__ import annotations

import numpy as np
import viser

from iik import fk
from iik.scene import THESIS_SCENE, Scene

from . import style
from .bodies import ArmBody
from .environment import aim_camera, draw_environment, legend_html
from .plan_data import FrameClearance, PlanView, frame_clearance
from .session import Animation

__all__ = ["PlanScene"]


class PlanScene:
    """A :class:`PlanView` as a viewer view (see :mod:`iik.planning.viewer.session`)."""

    def __init__(self, plan: PlanView, *, scene: Scene = THESIS_SCENE):
        self.plan = plan
        self.scene = scene
        self.title = f"iik view: scenario {plan.name}"
        self.camera = None  # (eye, target, vertical fov [deg]) once built
        self.clearance: FrameClearance = frame_clearance(plan.obstacles, plan.q, scene=scene) if len(plan.q) \
            else FrameClearance(np.zeros(0), (), (), np.zeros((0, 3)), np.zeros((0, 3)))

    def label(self, i: int) -> str:
        """Clearance text of frame ``i``: nearest link, object, distance in mm."""
        c, zone = self.clearance, self.plan.safety_zone
        d = c.distance[i]
        warn = " - INSIDE THE SAFETY ZONE" if d < zone else ""
        return f"{c.link[i]} to {c.obstacle[i]}: {d * 1000:.1f} mm (zone {zone * 1000:.0f} mm){warn}"

    def status(self, i: int) -> str:
        p = self.plan
        q = ", ".join(f"{v:.1f}" for v in np.degrees(p.q[i]))
        return f"**t = {p.t[i]:.2f} s** &nbsp; nearest: {self.label(i)}  \nq = [{q}] deg"

    def build(self, server: viser.ViserServer) -> Animation | None:
        p, s = self.plan, server.scene
        draw_environment(server, p.obstacles, scene=self.scene, safety_zone=p.safety_zone)
        server.gui.add_markdown(f"{p.headline}\n\nUnits: m, mm for clearances; frame: arm base frame 0 "
                                "(z up); floor grid 0.1 m.")
        server.gui.add_html(legend_html())
        if len(p.q):
            tool = fk(p.q)[:, :3, 3]
            s.add_line_segments("/plan/tool_path", np.stack([tool[:-1], tool[1:]], axis=1),
                                colors=style.TOOL_PATH, thickness=0.006)
        if len(p.step_points):
            s.add_point_cloud("/plan/step_points", p.step_points, colors=style.STEP_POINT, point_size=0.018,
                              point_shape="circle")
        for k, v in enumerate(p.via_points):
            s.add_icosphere(f"/plan/via_points/{k}", radius=0.02, color=style.VIA_POINT, position=tuple(v))
            s.add_label(f"/plan/via_points/{k}/label", f"via-point {k + 1}", position=(0.0, 0.0, 0.04))
        for k, (i, t) in enumerate(zip(p.switch_steps, p.switch_times, strict=True)):
            s.add_icosphere(f"/plan/switches/{k}", radius=0.025, color=style.SWITCH,
                            position=tuple(p.step_points[i]), opacity=0.8)
            s.add_label(f"/plan/switches/{k}/label", f"IK branch switch, step {i}, t = {t:.2f} s",
                        position=(0.0, 0.0, 0.05))
        s.add_label("/plan/title", f"scenario {p.name}: {'OK' if p.success else 'FAILED'}; clearance in mm "
                    f"(safety zone {p.safety_zone * 1000:.0f} mm); base frame 0, m", position=(0.2, 0.0, 1.1),
                    anchor="bottom-center")
        pts = np.vstack([p.step_points.reshape(-1, 3), np.zeros((1, 3)),
                         np.array([b.center for b in p.obstacles]).reshape(-1, 3)])
        self.camera = aim_camera(server, 0.5 * (pts.min(axis=0) + pts.max(axis=0)))
        arm = ArmBody(server, "/plan/arm", colour=style.ARM)
        if not len(p.q):
            arm.show(np.zeros(6))
            return None
        gap = s.add_line_segments("/plan/nearest/line", np.zeros((1, 2, 3)), colors=style.NEAREST,
                                  thickness=0.004)
        tag = s.add_label("/plan/nearest/label", "", anchor="bottom-left")

        def show(i: int) -> None:
            c = self.clearance
            arm.show(p.q[i])
            unsafe = c.distance[i] < p.safety_zone
            arm.paint({c.link[i]: style.UNSAFE if unsafe else style.NEAREST})
            gap.points = np.stack([c.on_link[i], c.on_obstacle[i]])[None].astype(np.float32)
            gap.colors = np.array([[style.UNSAFE if unsafe else style.NEAREST] * 2], np.uint8)
            tag.position = tuple(0.5 * (c.on_link[i] + c.on_obstacle[i]))
            tag.text = self.label(i)

        marks = tuple((t, "switch") for t in p.switch_times)
        return Animation(times=p.t, show=show, marks=marks, status=self.status)
