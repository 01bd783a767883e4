"""Several arms following recorded joint tracks side by side (e.g. commanded and measured in a run log).

A :class:`Motion` is a neutral description (no hardware types): frame times and,
per arm, its joint track, colour and base offset, plus one note per frame. The
``hardware`` layer builds one from a run log (:mod:`hardware.view`); this layer
draws it. Frame: each arm's base frame 0, shifted by its ``offset`` [m].
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import viser

from iik.arm import Arm
from iik.errors import InvalidInputError
from iik.scene import THESIS_SCENE, Scene

from ..robot_model import arm_model
from .bodies import ArmBody
from .environment import add_view_presets, draw_environment, fit_camera, legend_html, workspace_points
from .session import Animation
from .style import Colour

__all__ = ["Track", "Motion", "MotionView"]


@dataclass(frozen=True)
class Track:
    """One arm's joint track: ``q`` (k, 6) [rad] at the frame times, in ``colour``, at ``offset`` [m]."""

    name: str
    q: np.ndarray
    colour: Colour
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        q = np.asarray(self.q, float)
        if q.ndim != 2 or q.shape[1] != 6 or not np.all(np.isfinite(q)):
            raise InvalidInputError(f"track {self.name}",
                                    f"q must be a finite (k, 6) array, got shape {q.shape}")
        object.__setattr__(self, "q", q)


@dataclass(frozen=True)
class Motion:
    """Frame times ``t`` (k,) [s], the tracks of ``arm`` (every track is that arm: its FK, its body), and an
    optional note per frame (shown with the time).

    ``warnings``: what the view cannot show faithfully (printed by ``iik view``, shown in the panel).
    ``obstacles``: the scenario's boxes (:class:`~iik.scene.Box`), drawn around every arm.
    """

    title: str
    t: np.ndarray
    tracks: tuple[Track, ...]
    arm: Arm
    notes: tuple[str, ...] = ()
    headline: str = ""
    warnings: tuple[str, ...] = ()
    obstacles: tuple = ()

    def __post_init__(self) -> None:
        t = np.asarray(self.t, float)
        if t.ndim != 1 or len(t) == 0 or np.any(np.diff(t) < 0) or not np.all(np.isfinite(t)):
            raise InvalidInputError("t", "must be a non-empty, finite, non-decreasing (k,) array [s]")
        if any(len(tr.q) != len(t) for tr in self.tracks):
            raise InvalidInputError("tracks", "every track needs one configuration per frame time")
        if self.notes and len(self.notes) != len(t):
            raise InvalidInputError("notes", "must be empty or one per frame")
        if not isinstance(self.arm, Arm):
            raise InvalidInputError("arm", f"expected an iik.Arm, got {type(self.arm).__name__}")
        object.__setattr__(self, "t", t)


class MotionView:
    """A :class:`Motion` as a view: every arm on its own platform, a label per arm, a note per frame."""

    def __init__(self, motion: Motion, *, scene: Scene = THESIS_SCENE):
        self.motion = motion
        self.arm = motion.arm
        self.model = arm_model(motion.arm)
        self.scene = scene
        self.camera = None
        self.title = motion.title
        self.warnings = motion.warnings

    def status(self, i: int) -> str:
        m = self.motion
        return f"**t = {m.t[i]:.2f} s**" + (f" &nbsp; {m.notes[i]}" if m.notes else "")

    def build(self, server: viser.ViserServer) -> Animation | None:
        m = self.motion
        if m.headline or m.warnings:
            server.gui.add_markdown(m.headline + "".join(f"\n\n**Warning:** {w}" for w in m.warnings))
        server.gui.add_html(legend_html(tuple((tr.name, tr.colour) for tr in m.tracks)))
        arms, pts = [], []
        for k, tr in enumerate(m.tracks):
            draw_environment(server, m.obstacles, scene=self.scene, offset=tr.offset, root=f"/scene{k}",
                             ellipsoids=False)
            arms.append(ArmBody(server, f"/motion/{k}", colour=tr.colour, offset=tr.offset, model=self.model))
            server.scene.add_label(f"/motion/{k}/name", tr.name, position=(0.0, 0.0, 1.0),
                                   anchor="bottom-center")
            pts.append(workspace_points(self.arm, tr.q, m.obstacles, tr.offset))
        pts = np.vstack(pts) if pts else np.zeros((1, 3))
        self.camera = fit_camera(server, pts)
        add_view_presets(server, pts)
        top = np.array([0.5 * (pts[:, 0].min() + pts[:, 0].max()), 0.5 * (pts[:, 1].min() + pts[:, 1].max()),
                        pts[:, 2].max() + 0.1])
        note = server.scene.add_label("/motion/note", "", position=tuple(top), anchor="bottom-center")

        def show(i: int) -> None:
            for arm, tr in zip(arms, m.tracks, strict=True):
                arm.show(tr.q[i])
            note.text = f"t = {m.t[i]:.2f} s" + (f"; {m.notes[i]}" if m.notes else "")

        return Animation(times=m.t, show=show, status=self.status)
