"""Plan mode: the planned motion with its path, ellipsoids, via-points, clearance and branch switches.

Shows a :class:`~iik.planning.viewer.plan_data.PlanView`: the arm (URDF
collision shapes) along the timed trajectory, the tool path actually traced
(FK of the frames) and the planned step-points, the via-points, the enclosing
ellipsoids of Eq 52-53, the IK branch switches (marked on the live time slider
and at the tool point) and, at every frame, the link nearest the scene with a
line to the nearest obstacle point and its clearance in mm, coloured when the
clearance is below the scenario's safety zone. The planner's attempt log
(:mod:`.attempts`) is a table in the live panel and a label in the scene (so an
export shows it too). A plan that failed or timed out is shown the same way, with
its reason and best attempt; without an accepted path the arm stands at the start
pose and the rejected thesis path's step-points are drawn. Frame: base frame 0 [m].
"""

from __future__ import annotations

import numpy as np
import viser

from iik import fk

from ..robot_model import arm_model
from . import style
from .attempts import attempt_lines, attempt_table
from .bodies import ArmBody
from .environment import (
    add_view_presets,
    draw_environment,
    fit_camera,
    legend_html,
    view_top,
    workspace_points,
)
from .plan_data import PlanView, frame_clearance, least_clearance
from .session import Animation

__all__ = ["PlanScene"]


class PlanScene:
    """A :class:`PlanView` as a viewer view (see :mod:`iik.planning.viewer.session`)."""

    def __init__(self, plan: PlanView):
        self.plan = plan
        self.title = f"iik view: scenario {plan.name}"
        self.camera = None  # (eye, target, vertical fov [deg]) once built
        #: The nearest pair at each frame (:class:`~iik.planning.collision.Nearest`); the frame of the least.
        self.clearance = frame_clearance(plan.obstacles, plan.q, arm=plan.arm, scene=plan.scene)
        self.least = least_clearance(self.clearance)
        #: The scene's caption: units and frame, the verdict and the attempt log (an export has no panel).
        self.caption = (f"scenario {plan.name}: clearances in mm (zone {plan.safety_zone * 1000:.0f} mm); "
                        f"base frame 0, m\n{attempt_lines(plan)}")

    def label(self, i: int) -> str:
        """Clearance text of frame ``i``: nearest link, object, distance in mm."""
        n, zone = self.clearance[i], self.plan.safety_zone
        warn = " - INSIDE THE SAFETY ZONE" if n.distance < zone else ""
        return f"{n.link} to {n.object}: {n.distance * 1000:.1f} mm (zone {zone * 1000:.0f} mm){warn}"

    def clearance_summary(self) -> str:
        """Markdown: the actual minimum along the motion (where, when) beside the certified lower bound."""
        p, k = self.plan, self.least
        n = self.clearance[k]
        zone = p.safety_zone * 1000
        bound = (f"**{p.certified_clearance * 1000:.1f} mm** (the planner's certified lower bound, between "
                 "the frames included)" if np.isfinite(p.certified_clearance) else "none (no accepted path)")
        return (f"Actual minimum along the motion: **{n.distance * 1000:.1f} mm** at t = {p.t[k]:.2f} s "
                f"(frame {k} of {len(p.t)}), {n.link} to {n.object}.  \nCertified: {bound}.  \n"
                f"Safety zone {zone:.0f} mm.")

    def _clearance_panel(self, server: viser.ViserServer) -> None:
        import viser.uplot as uplot

        p = self.plan
        mm = np.array([n.distance for n in self.clearance]) * 1000
        cert = np.full_like(mm, p.certified_clearance * 1000)
        zone = np.full_like(mm, p.safety_zone * 1000)
        with server.gui.add_folder("Clearance"):
            server.gui.add_markdown(self.clearance_summary())
            if len(p.t) > 1:
                server.gui.add_uplot(
                    data=(p.t, mm, cert, zone),
                    series=(
                        uplot.Series(label="t [s]"),
                        uplot.Series(label="clearance [mm]", stroke=_css(style.NEAREST), width=2),
                        uplot.Series(label="certified bound [mm]", stroke=_css(style.TOOL_PATH), dash=(6, 4)),
                        uplot.Series(label="safety zone [mm]", stroke=_css(style.UNSAFE), dash=(2, 3))),
                    scales={"x": uplot.Scale(time=False, auto=True)},
                    title="whole-arm clearance vs time", aspect=1.6)

    def status(self, i: int) -> str:
        p = self.plan
        q = ", ".join(f"{v:.1f}" for v in np.degrees(p.q[i]))
        return f"**t = {p.t[i]:.2f} s** &nbsp; nearest: {self.label(i)}  \nq = [{q}] deg"

    def build(self, server: viser.ViserServer) -> Animation | None:
        p, s = self.plan, server.scene
        draw_environment(server, p.obstacles, scene=p.scene, safety_zone=p.safety_zone)
        server.gui.add_markdown(f"{p.headline}\n\nUnits: m, mm for clearances; frame: arm base frame 0 "
                                f"(z up); floor grid 0.1 m. The arm shows {p.arm_shows}.")
        server.gui.add_html(legend_html())
        self._clearance_panel(server)
        with server.gui.add_folder("Attempt log", expand_by_default=False):
            server.gui.add_markdown(attempt_table(p))
        if len(p.step_q) and len(p.q) > 1:
            tool = fk(p.q, p.arm)[:, :3, 3]
            s.add_line_segments("/plan/tool_path", np.stack([tool[:-1], tool[1:]], axis=1),
                                colors=style.TOOL_PATH, thickness=0.006)
        if len(p.step_points):
            s.add_point_cloud("/plan/step_points", p.step_points, colors=style.STEP_POINT, point_size=0.018,
                              point_shape="circle")
            if not len(p.step_q):
                s.add_label("/plan/step_points/label", "thesis path (step-points), not accepted",
                            position=tuple(p.step_points[0] + [0.0, 0.0, 0.06]), anchor="bottom-center")
        for k, v in enumerate(p.via_points):
            s.add_icosphere(f"/plan/via_points/{k}", radius=0.02, color=style.VIA_POINT, position=tuple(v))
            s.add_label(f"/plan/via_points/{k}/label", f"via-point {k + 1}", position=(0.0, 0.0, 0.04))
        for k, (i, t) in enumerate(zip(p.switch_steps, p.switch_times, strict=True)):
            s.add_icosphere(f"/plan/switches/{k}", radius=0.025, color=style.SWITCH,
                            position=tuple(p.step_points[i]), opacity=0.8)
            s.add_label(f"/plan/switches/{k}/label", f"IK branch switch, step {i}, t = {t:.2f} s",
                        position=(0.0, 0.0, 0.05))
        pts = np.vstack([workspace_points(p.arm, p.q, p.obstacles), p.step_points.reshape(-1, 3)])
        self.camera = fit_camera(server, pts)
        add_view_presets(server, pts)
        s.add_label("/plan/caption", self.caption, position=tuple(view_top(*self.camera)),
                    anchor="top-center", font_screen_scale=0.85)
        arm = ArmBody(server, "/plan/arm", colour=style.ARM, model=arm_model(p.arm))
        gap = s.add_line_segments("/plan/nearest/line", np.zeros((1, 2, 3)), colors=style.NEAREST,
                                  thickness=0.004)
        tag = s.add_label("/plan/nearest/label", "", anchor="bottom-left")

        def show(i: int) -> None:
            n = self.clearance[i]
            arm.show(p.q[i])
            unsafe = n.distance < p.safety_zone
            arm.paint({n.link: style.UNSAFE if unsafe else style.NEAREST})
            gap.points = np.stack([n.on_link, n.on_object])[None].astype(np.float32)
            gap.colors = np.array([[style.UNSAFE if unsafe else style.NEAREST] * 2], np.uint8)
            tag.position = tuple(0.5 * (n.on_link + n.on_object))
            tag.text = self.label(i)

        marks = tuple((t, "switch") for t in p.switch_times)
        k = self.least
        jumps = ((f"Jump to the minimum clearance (t = {p.t[k]:.2f} s)", float(p.t[k])),) \
            if len(p.t) > 1 else ()
        return Animation(times=p.t, show=show, marks=marks, status=self.status, jumps=jumps)


def _css(c: style.Colour) -> str:
    return f"rgb({c[0]}, {c[1]}, {c[2]})"
