"""The arm's body in the viewer: its collision shapes, drawn by Pinocchio's ViserVisualizer.

Every arm on screen (the planned arm, each IK solution, the commanded and the
measured arm of a run) is one :class:`ArmBody`: a
:class:`pinocchio.visualize.ViserVisualizer` on the shared :class:`viser.ViserServer`,
loaded from the model of the arm in use (:func:`iik.planning.robot_model.arm_model`: its
URDF's shapes, e.g. ``urdf/thesis_arm.urdf``, or shapes generated along its links)
with the collision shapes as the visible body. Frame: the arm's base frame 0 [m];
``offset`` shifts the whole arm (to put two arms side by side).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pinocchio as pin
import viser
from pinocchio.visualize import ViserVisualizer

from iik import Arm
from iik.arm import LIMIT_TOL
from iik.errors import InvalidInputError
from iik.validation import as_joints

from ..robot_model import ArmModel, collision_link, link_of_joint
from .style import Colour, rgb01

__all__ = ["ArmBody", "joints_outside_limits", "outside_limits_text", "link_of_joint"]


def _outside(q, arm: Arm):
    """The violations of one configuration ``q`` (6,) [rad] (:meth:`iik.Arm.limit_violations`, with the
    rounding tolerance :data:`iik.arm.LIMIT_TOL` of :meth:`iik.Arm.within_limits`)."""
    if as_joints(q, "q")[1]:
        raise InvalidInputError("q", f"expected one configuration (6,), got shape {np.shape(q)}")
    return arm.limit_violations(q, -LIMIT_TOL)


def joints_outside_limits(q, arm: Arm) -> tuple[int, ...]:
    """0-based indices of the joints of ``q`` (6,) [rad] outside the arm's limits (Table I)."""
    return tuple(v.joint for v in _outside(q, arm))


def outside_limits_text(q, arm: Arm) -> str:
    """One line naming each joint of ``q`` (6,) [rad] outside Table I with its value and limits; "" if none.

    Joints are named ``q1`` .. ``q6`` (as in the thesis); values in rad and deg.
    """
    deg = np.degrees
    return "; ".join(
        f"q{v.joint + 1} = {v.value:.4f} rad ({deg(v.value):.1f} deg) is outside {arm.limits_name} "
        f"[{v.lower:.4f}, {v.upper:.4f}] rad ([{deg(v.lower):.1f}, {deg(v.upper):.1f}] deg)"
        for v in _outside(q, arm))


class ArmBody:
    """One arm on a viser scene, at a configuration, in a colour.

    Args:
        server: The viser server (or its ``scene`` owner) to draw on.
        name: Scene-tree root of this arm, e.g. ``"/plan/arm"``.
        colour: RGB 0-255.
        opacity: 0 (invisible) .. 1 (opaque).
        offset: Translation [m] of the arm's base in the scene (base frame 0 otherwise).
        model: The arm's Pinocchio model and body (:func:`iik.planning.robot_model.arm_model`).
    """

    def __init__(self, server: viser.ViserServer, name: str, *, colour: Colour, model: ArmModel,
                 opacity: float = 1.0, offset=(0.0, 0.0, 0.0)):
        tm = model
        self.model = model
        self.name = name.rstrip("/")
        self.colour = colour
        self.opacity = float(opacity)
        self._root = server.scene.add_frame(self.name, show_axes=False, position=tuple(offset))
        self._viz = ViserVisualizer(tm.model, tm.collision_model, pin.GeometryModel())
        self._viz.initViewer(viewer=server)
        self._viz.loadViewerModel(rootNodeName=self.name, collision_color=[*rgb01(colour), self.opacity])
        self._viz.displayVisuals(False)
        self._viz.displayCollisions(True)
        prefix = f"{self.name}/collision/"
        self._shapes: dict[str, list] = {}
        for g in tm.collision_model.geometryObjects:
            self._shapes.setdefault(collision_link(tm.model, g), []).append(self._viz.frames[prefix + g.name])
        self._paint: dict[str, tuple[Colour, float]] = {}
        self.q = np.zeros(tm.model.nq)
        self._viz.display(self.q)  # posed (home) from the start, never a heap of shapes at the origin

    @property
    def links(self) -> tuple[str, ...]:
        """Names of the links that have collision shapes."""
        return tuple(self._shapes)

    def shapes(self, link: str) -> tuple:
        """The viser handles of ``link``'s collision shapes."""
        return tuple(self._shapes[link])

    def show(self, q) -> None:
        """Place the arm at ``q`` (6,) [rad]."""
        qb, _ = as_joints(q, "q")
        self.q = qb[0].copy()
        self._viz.display(self.q)

    def link_position(self, link: str) -> np.ndarray:
        """Scene position [m] of the first shape of ``link`` at the last shown ``q``."""
        return np.asarray(self._shapes[link][0].position, float) + np.asarray(self._root.position, float)

    @property
    def visible(self) -> bool:
        return bool(self._root.visible)

    @visible.setter
    def visible(self, value: bool) -> None:
        self._root.visible = bool(value)
        self._viz.collisionRootFrame.visible = bool(value)
        if value:
            self._viz.display(self.q)

    def paint(self, links: Mapping[str, Colour] | None = None, *, opacity: float | None = None) -> None:
        """Colour the given links (others back to the arm's colour); only changed shapes are sent."""
        links = links or {}
        if opacity is not None:
            self.opacity = float(opacity)
        for link, shapes in self._shapes.items():
            want = (links.get(link, self.colour), self.opacity)
            if self._paint.get(link) == want:
                continue
            self._paint[link] = want
            for h in shapes:
                h.color = tuple(int(c) for c in want[0])
                h.opacity = want[1]
