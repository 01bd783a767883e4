"""Pose mode: every IK solution of a tool pose as translucent arms, one picked; interactive IK.

Given a pose ``T`` (4x4, base frame 0, m) -- or a configuration ``q`` [rad],
whose pose is ``fk(q)`` -- the view solves the complete IK (:func:`iik.solve`,
solutions outside the limits included and marked), draws every solution as a
translucent arm and the picked one opaque, and lists in the panel each
solution's joint values against Table I, its FK residuals and its Eq 54 effort
index from ``previous`` (the given ``q``, else the home pose ``q = 0``). Links
moved by a joint outside Table I are red. With ``interactive=True`` a gizmo at
the tool frame moves the pose and every solution follows live.
"""

from __future__ import annotations

import time

import numpy as np
import viser

import iik
from iik import Arm
from iik.validation import as_joints, as_poses

from ..robot_model import arm_model
from . import style
from .bodies import ArmBody, joints_outside_limits, link_of_joint, outside_limits_text
from .environment import add_view_presets, draw_environment, fit_camera, legend_html, workspace_points
from .session import Animation

__all__ = ["PoseView", "MAX_SOLUTIONS"]

#: Largest number of IK solutions of a 6R pose (the complete solver's bound).
MAX_SOLUTIONS = 16


def _quat_wxyz(R: np.ndarray) -> np.ndarray:
    from scipy.spatial.transform import Rotation

    x, y, z, w = Rotation.from_matrix(R).as_quat()
    return np.array([w, x, y, z])


def _matrix(wxyz, position) -> np.ndarray:
    from scipy.spatial.transform import Rotation

    w, x, y, z = wxyz
    T = np.eye(4)
    T[:3, :3] = Rotation.from_quat([x, y, z, w]).as_matrix()
    T[:3, 3] = position
    return T


class PoseView:
    """All IK solutions of one pose (or of ``fk(q)``), as a viewer view.

    Args:
        T: Tool pose (4, 4) [m]; or
        q: A configuration (6,) [rad] shown as given (even outside the limits: then the links its
            joints outside Table I move are red, and :attr:`warnings` has one line naming them).
        previous: Reference configuration of the effort index (default: ``q``, else zeros).
        interactive: Add a draggable gizmo for the tool pose (live viewer only).
        arm: The arm (limits, FK, IK, its body: :func:`~iik.planning.robot_model.arm_model`).
    """

    def __init__(self, T=None, *, q=None, previous=None, interactive: bool = False, arm: Arm):
        if (T is None) == (q is None):
            raise iik.InvalidInputError("pose", "give exactly one of T (a pose) or q (a configuration)")
        self.arm = arm
        self.model = arm_model(arm)
        self.given = None if q is None else as_joints(q, "q")[0][0]
        if self.given is not None:
            T = iik.fk(self.given, arm)
        self.T = as_poses(T, "T")[0][0]
        if previous is not None:
            self.previous, self.reference = as_joints(previous, "previous")[0][0], "the reference q"
        elif self.given is not None:
            self.previous, self.reference = self.given, "the given q"
        else:
            self.previous, self.reference = np.zeros(6), "the home pose q = 0"
        self.interactive = interactive
        self.live_only = interactive
        self.title = "iik view: interactive IK" if interactive else "iik view: pose"
        self.warnings: tuple[str, ...] = ()
        outside = "" if self.given is None else outside_limits_text(self.given, arm)
        if outside:
            self.warnings = (f"{outside}; shown anyway, the links those joints move in red",)
        self.result = iik.solve(self.T, within_limits=False, arm=arm)
        self.selected = self._default_selection()
        self.solve_time = 0.0

    def _default_selection(self) -> int:
        """The given q; else the least-effort solution within the limits (as :func:`iik.select`); else 0."""
        r = self.result
        if self.given is not None or not np.any(r.within_limits):
            return 0
        idx = np.flatnonzero(r.within_limits)
        return int(idx[np.argmin(np.atleast_1d(iik.effort_index(self.previous, r.q[idx])))])

    def configurations(self) -> np.ndarray:
        """(m, 6): the given ``q`` (if any) first, then every IK solution [rad]."""
        sols = np.asarray(self.result.q).reshape(-1, 6)
        return sols if self.given is None else np.vstack([self.given[None], sols])

    def describe(self, i: int) -> str:
        """Markdown: joint values vs Table I, limit flags, residuals and effort of configuration ``i``."""
        qs, arm = self.configurations(), self.arm
        q = qs[i]
        bad = set(joints_outside_limits(q, arm))
        rows = "\n".join(
            f"| {j + 1} | {np.degrees(q[j]):8.2f} | {np.degrees(arm.q_min[j]):7.1f} .. "
            f"{np.degrees(arm.q_max[j]):6.1f} | {'**OUT**' if j in bad else 'ok'} |" for j in range(6))
        E = iik.effort_index(self.previous, q)
        T = iik.fk(q, arm)
        dp = np.linalg.norm(T[:3, 3] - self.T[:3, 3])
        dR = iik.rotation_angle(T[:3, :3], self.T[:3, :3])
        limits = arm.limits_name.removeprefix("the ")
        return (f"| joint | q [deg] | {limits} [deg] | limits |\n|---|---|---|---|\n{rows}\n\n"
                f"Effort index (Eq 54) from {self.reference}: **{E:.4f} rad** ({np.degrees(E):.2f} deg); "
                f"FK residuals {dp:.1e} m, {dR:.1e} rad")

    def options(self) -> tuple[str, ...]:
        names = []
        if self.given is not None:
            names.append("given q" + ("" if not self.warnings else " (OUTSIDE LIMITS)"))
        for k in range(self.result.count):
            lim = "in limits" if self.result.within_limits[k] else "outside limits"
            E = iik.effort_index(self.previous, self.result.q[k])
            names.append(f"solution {k}: {lim}, E = {E:.3f} rad")
        return tuple(names)

    def summary(self) -> str:
        p = self.T[:3, 3]  # in m, as given: a far (unreachable) point prints as typed, no overflow
        a = np.degrees(iik.euler_from_matrix(self.T[:3, :3]))
        r = self.result
        head = (f"Tool at ({p[0]:.4g}, {p[1]:.4g}, {p[2]:.4g}) m, Eq 42 angles "
                f"({a[0]:.1f}, {a[1]:.1f}, {a[2]:.1f}) deg: **{r.count} IK solution(s)**, "
                f"{int(np.sum(r.within_limits))} within {self.arm.limits_name}")
        if r.count == 0:
            head += f" ({r.reason})"
        if self.solve_time:
            head += f"; solved in {self.solve_time * 1e6:.0f} us"
        return head + "".join(f"\n\n**Warning:** {w}" for w in self.warnings)

    def colour(self, k: int) -> style.Colour:
        """Colour of configuration ``k`` (:meth:`configurations`): its own, one per solution."""
        return style.SOLUTIONS[k % len(style.SOLUTIONS)]

    def _target(self, server: viser.ViserServer):
        """The target frame (axes at the pose), with a label saying whether it is reached."""
        frame = server.scene.add_frame("/pose/target", wxyz=_quat_wxyz(self.T[:3, :3]),
                                       position=tuple(self.T[:3, 3]), axes_length=style.TARGET_FRAME_LENGTH,
                                       axes_radius=0.006)
        label = server.scene.add_label("/pose/target/label", "", position=(0.0, 0.0, 0.03),
                                       anchor="bottom-left", font_screen_scale=0.8)

        def update() -> None:
            frame.wxyz, frame.position = _quat_wxyz(self.T[:3, :3]), tuple(self.T[:3, 3])
            label.text = "target" if self.result.count else "target (unreachable: no IK solution)"

        update()
        self.target_label = label
        return update

    def _joint_sliders(self, server: viser.ViserServer, on_change) -> list:
        """Six sliders [deg] over each joint's limits (wider when the given q is outside them)."""
        sliders = []
        with server.gui.add_folder("Joints [deg]"):
            for j in range(6):
                lo = min(float(np.degrees(self.arm.q_min[j])), float(np.degrees(self.given[j])))
                hi = max(float(np.degrees(self.arm.q_max[j])), float(np.degrees(self.given[j])))
                sl = server.gui.add_slider(f"q{j + 1}", min=round(lo, 1), max=round(hi, 1), step=0.1,
                                           initial_value=float(np.degrees(self.given[j])))
                sl.on_update(lambda _event: on_change(np.radians([s.value for s in sliders])))
                sliders.append(sl)
        return sliders

    def set_q(self, q) -> None:
        """Show another configuration ``q`` (6,) [rad]: its pose, every IK solution of it, its warnings."""
        self.given = as_joints(q, "q")[0][0]
        self.T = iik.fk(self.given, self.arm)
        outside = outside_limits_text(self.given, self.arm)
        self.warnings = (f"{outside}; shown anyway, the links those joints move in red",) if outside else ()
        self.result = iik.solve(self.T, within_limits=False, arm=self.arm)
        self.selected = 0

    def build(self, server: viser.ViserServer) -> Animation | None:
        draw_environment(server)
        near = np.abs(self.T[:3, 3]).max() <= 3 * self.arm.reach  # a far target is shown by its label only
        pts = np.vstack([workspace_points(self.arm, np.zeros((1, 6))), self.T[None, :3, 3][:int(near)],
                         workspace_points(self.arm, self.configurations().reshape(-1, 6))])
        self.camera = fit_camera(server, pts)
        add_view_presets(server, pts)
        bodies: list[ArmBody] = []
        summary = server.gui.add_markdown(self.summary())
        opts = self.options() or ("none",)
        pick = server.gui.add_dropdown("configuration", options=opts, initial_value=opts[self.selected])
        table = server.gui.add_markdown("")
        server.gui.add_html(legend_html())
        labels: list = []
        toggles: list = []
        toggle_folder = server.gui.add_folder("Show solutions")
        update_target = self._target(server)
        self.bodies, self.toggles = bodies, toggles

        def body(k: int) -> ArmBody:
            while len(bodies) <= k:
                n = len(bodies)
                bodies.append(ArmBody(server, f"/pose/arm{n}", colour=self.colour(n), model=self.model,
                                      opacity=0.25))
                labels.append(server.scene.add_label(f"/pose/label{n}", f"#{n}", font_screen_scale=0.8))
                with toggle_folder:
                    tg = server.gui.add_checkbox(f"#{n}", initial_value=True)
                tg.on_update(lambda _event: redraw())
                toggles.append(tg)
            return bodies[k]

        def redraw() -> None:
            qs = self.configurations()
            for k, q in enumerate(qs):
                b = body(k)
                name = "given q" if (self.given is not None and k == 0) else \
                    f"#{k - (self.given is not None)}"
                toggles[k].label = name
                shown = bool(toggles[k].value)
                red = {link_of_joint(self.model, j): style.OUT_OF_LIMITS
                       for j in joints_outside_limits(q, self.arm)}
                b.show(q)
                b.paint(red, opacity=1.0 if k == self.selected else 0.35)
                b.visible = shown
                labels[k].text = name
                elbow = iik.joint_frames(q, self.arm)[2][:3, 3]
                labels[k].position = tuple(elbow + [0.0, 0.0, 0.05 + 0.035 * k])  # stacked: no overlap
                labels[k].visible = shown
                toggles[k].visible = True
            for k in range(len(qs), len(bodies)):
                bodies[k].visible = False
                labels[k].visible = False
                toggles[k].visible = False
            summary.content = self.summary()
            table.content = self.describe(self.selected) if len(qs) else ""
            update_target()

        def refresh_choices() -> None:
            opts = self.options() or ("none",)
            pick.options = opts
            pick.value = opts[self.selected]
            redraw()

        @pick.on_update
        def _(_event) -> None:
            opts = self.options()
            if pick.value in opts:
                self.selected = opts.index(pick.value)
                redraw()

        if self.given is not None and not self.interactive:
            self.sliders = self._joint_sliders(server, lambda q: (self.set_q(q), refresh_choices()))

        if self.interactive:
            gizmo = server.scene.add_transform_controls("/pose/gizmo", scale=0.15,
                                                        wxyz=_quat_wxyz(self.T[:3, :3]),
                                                        position=tuple(self.T[:3, 3]))

            @gizmo.on_update
            def _(_event) -> None:
                self.T = _matrix(gizmo.wxyz, gizmo.position)
                t0 = time.perf_counter()
                self.result = iik.solve(self.T, within_limits=False, arm=self.arm)
                self.solve_time = time.perf_counter() - t0
                self.given = None
                self.warnings = ()
                self.selected = self._default_selection()
                refresh_choices()

        redraw()
        return None
