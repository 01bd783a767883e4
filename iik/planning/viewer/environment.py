"""The surroundings drawn from the planner's own description: platform, floor, boxes, ellipsoids.

Everything comes from the objects the planner and the collision checker use:
the platform and the floor of :class:`iik.scene.Scene` (default
:data:`iik.scene.THESIS_SCENE`), the scenario's :class:`iik.scene.Box`
boxes (obstacles and supports) and their enclosing ellipsoids
(:func:`iik.planning.obstacles.enclosing_radii`, Eq 52-53 corrected). Frame:
the arm's base frame 0, z up [m]; the grid on the floor has 0.1 m cells.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import viser

from iik.scene import THESIS_SCENE, Box, Scene

from ..obstacles import enclosing_radii
from . import style

__all__ = ["draw_environment", "configure_server", "aim_camera", "camera_pose", "view_top", "legend_html",
           "fit_camera", "framing", "add_view_presets", "VIEW_PRESETS", "workspace_points"]


def configure_server(server: viser.ViserServer, title: str) -> None:
    """Theme, z-up world, default camera, no share button (the viewer stays on this machine)."""
    server.gui.configure_theme(show_share_button=False, control_width="medium")
    server.gui.set_panel_label(title)
    server.scene.set_up_direction("+z")
    aim_camera(server, style.CAMERA_LOOK_AT)


#: View presets: (azimuth, elevation) [deg] of the eye seen from the target (z up; x ahead of the arm).
VIEW_PRESETS = {"fit": (style.CAMERA_AZIMUTH_DEG, style.CAMERA_ELEVATION_DEG), "front": (0.0, 8.0),
                "side": (-90.0, 8.0), "top": (-90.0, 89.0)}


def workspace_points(arm, q, obstacles: Sequence[Box] = (), offset=(0.0, 0.0, 0.0)) -> np.ndarray:
    """Points [m] a view frames: the base, ``arm``'s joint origins and tool point at every ``q`` (k, 6)
    [rad] it shows (the workspace the motion sweeps) and the corners of the scenario's boxes."""
    from iik.kinematics import joint_frames

    qs = np.asarray(q, float).reshape(-1, 6)
    qs = qs[:: max(1, len(qs) // 200)]
    pts = [np.zeros((1, 3)), joint_frames(qs, arm)[:, :, :3, 3].reshape(-1, 3)]
    pts += [np.asarray(b.corners, float).reshape(-1, 3) for b in obstacles]
    return np.vstack(pts) + np.asarray(offset, float)


def framing(points, fov_deg: float, preset: str = "fit", *, aspect: float = 1.6,
            margin: float = 1.08) -> tuple[np.ndarray, np.ndarray]:
    """``(eye, target)`` [m] that show every point of ``points`` (n, 3) from the ``preset`` direction.

    The target is the centre of the points' bounding box; the distance fits their bounding sphere into
    the narrower of the vertical ``fov_deg`` and the horizontal field (``aspect`` width / height).
    """
    pts = np.asarray(points, float).reshape(-1, 3)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    target = 0.5 * (lo + hi)
    radius = max(float(np.linalg.norm(pts - target, axis=1).max()), 0.1)
    half = np.radians(fov_deg) / 2
    half = min(half, np.arctan(np.tan(half) * aspect))
    az, el = (np.radians(v) for v in VIEW_PRESETS[preset])
    direction = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
    return target + margin * radius / np.sin(half) * direction, target


def fit_camera(server: viser.ViserServer, points) -> tuple[np.ndarray, np.ndarray, float]:
    """Set the initial camera to frame ``points`` (the fit preset): ``(eye, target, vertical fov [deg])``."""
    fov = float(np.degrees(server.initial_camera.fov))
    eye, target = framing(points, fov)
    server.initial_camera.look_at = tuple(target)
    server.initial_camera.position = tuple(eye)
    return eye, target, fov


def add_view_presets(server: viser.ViserServer, points) -> dict:
    """Buttons Fit, Front, Side, Top in the live panel: each moves every connected client's camera to frame
    ``points`` from that side. Returns the buttons by preset name."""
    fov = float(np.degrees(server.initial_camera.fov))
    buttons = {}
    with server.gui.add_folder("View"):
        group = server.gui.add_button_group("camera", options=tuple(k.capitalize() for k in VIEW_PRESETS))

        @group.on_click
        def _(event) -> None:
            preset = str(group.value).lower()
            eye, target = framing(points, fov, preset)
            clients = [event.client] if event.client is not None else list(server.get_clients().values())
            for client in clients:
                with client.atomic():  # position first: viser's position setter carries look_at along
                    client.camera.position = tuple(eye)
                    client.camera.look_at = tuple(target)

        buttons["camera"] = group
    return buttons


def camera_pose(look_at, distance: float = style.CAMERA_DISTANCE) -> tuple[np.ndarray, np.ndarray]:
    """``(eye, target)`` [m]: ``distance`` from ``look_at`` at the style's azimuth and elevation."""
    az, el = np.radians(style.CAMERA_AZIMUTH_DEG), np.radians(style.CAMERA_ELEVATION_DEG)
    target = np.asarray(look_at, float)
    direction = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
    return target + distance * direction, target


def aim_camera(server: viser.ViserServer, look_at, distance: float = style.CAMERA_DISTANCE):
    """Set the initial camera (see :func:`camera_pose`); returns ``(eye, target, vertical fov [deg])``."""
    eye, target = camera_pose(look_at, distance)
    server.initial_camera.look_at = tuple(target)
    server.initial_camera.position = tuple(eye)
    return eye, target, float(np.degrees(server.initial_camera.fov))


def view_top(eye, target, fov_deg: float, fraction: float = 0.9) -> np.ndarray:
    """The scene point [m] at the top centre of the initial view, ``fraction`` of the way up from its middle.

    A label anchored there (``top-center``) stays on screen in a page with no panel (an export),
    whatever the window's width. The view's up vector is +z projected on the image plane.
    """
    eye, target = np.asarray(eye, float), np.asarray(target, float)
    fwd = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(fwd, [0.0, 0.0, 1.0])
    up = np.cross(right / np.linalg.norm(right), fwd)
    return target + up * fraction * np.linalg.norm(target - eye) * np.tan(np.radians(fov_deg) / 2)


def legend_html(arms: Sequence[tuple[str, style.Colour]] = ()) -> str:
    """The colour legend as HTML for the live panel; ``arms``: ``(name, colour)`` of each arm drawn
    (e.g. the commanded and the measured arm of a run), listed first instead of the generic arm."""
    import html

    entries = [(html.escape(n), c) for n, c in arms] + [e for e in style.LEGEND[1 if arms else 0:]]
    rows = "".join(f'<div><span style="display:inline-block;width:0.9em;height:0.9em;margin-right:0.4em;'
                   f'background:rgb{c}"></span>{name}</div>' for name, c in entries)
    return f'<div style="font-size:0.8em;padding:0 0.5em">{rows}</div>'


def draw_environment(server: viser.ViserServer, obstacles: Sequence[Box] = (), *,
                     scene: Scene = THESIS_SCENE, ellipsoids: bool = True,
                     safety_zone: float | None = None, offset=(0.0, 0.0, 0.0), root: str = "/scene") -> None:
    """Draw the platform, the floor (with a 0.1 m grid), the base frame and the scenario's boxes.

    Args:
        obstacles: Scenario boxes; ``kind == "obstacle"`` ones also get their
            Eq 52-53 ellipsoid (and, with ``safety_zone`` [m], the padded one of Sec 3.6.2.2).
        scene: Platform and floor.
        offset: Translation [m] of everything (for a second arm beside the first).
    """
    off = np.asarray(offset, float)
    s = server.scene
    p = scene.platform
    s.add_box(f"{root}/platform", color=style.PLATFORM, dimensions=tuple(p.size),
              position=tuple(p.center + off))
    s.add_grid(f"{root}/floor", width=2.0, height=2.0, plane="xy", cell_size=0.1, section_size=0.5,
               position=(off[0] + 0.3, off[1], scene.floor.z + 1e-3), plane_color=style.FLOOR,
               plane_opacity=0.35, shadow_opacity=0.2)
    s.add_frame(f"{root}/base_frame", axes_length=0.15, axes_radius=0.006, position=tuple(off))
    s.add_label(f"{root}/base_frame/label", "base frame 0 [m]",
                position=(0.0, -0.1, -0.03), font_screen_scale=0.7, anchor="top-right")
    for k, box in enumerate(obstacles):
        c = np.asarray(box.center) + off
        colour = style.OBSTACLE if box.kind == "obstacle" else style.SUPPORT
        node = f"{root}/boxes/{k}_{box.name}"
        s.add_box(node, color=colour, dimensions=tuple(box.size), position=tuple(c),
                  opacity=None if box.kind == "obstacle" else style.SUPPORT_OPACITY)
        s.add_label(f"{node}/label", f"{box.name} ({box.kind})", position=(0.0, 0.0, box.size[2] / 2 + 0.02),
                    font_screen_scale=0.8, anchor="bottom-center")
        if box.kind == "obstacle" and ellipsoids:
            r = enclosing_radii(box)  # Eq 53 (corrected)
            s.add_icosphere(f"{root}/ellipsoids/{k}_{box.name}", radius=1.0, scale=tuple(r),
                            color=style.ELLIPSOID, wireframe=True, opacity=0.5, position=tuple(c),
                            cast_shadow=False, receive_shadow=False)
            if safety_zone:
                s.add_icosphere(f"{root}/ellipsoids/{k}_{box.name}_zone", radius=1.0,
                                scale=tuple(r + safety_zone), color=style.ELLIPSOID, subdivisions=2,
                                opacity=0.08, position=tuple(c), cast_shadow=False, receive_shadow=False)
