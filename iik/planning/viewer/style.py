"""Colours and sizes of the viewer (one place, so the screenshots' checks and the legend agree)."""

from __future__ import annotations

__all__ = [
    "Colour", "rgb01", "ARM", "SOLUTION", "SELECTED", "SOLUTIONS", "TARGET_FRAME_LENGTH", "MEASURED",
    "OUT_OF_LIMITS", "NEAREST",
    "UNSAFE", "OBSTACLE", "SUPPORT", "SUPPORT_OPACITY", "PLATFORM", "FLOOR", "ELLIPSOID", "TOOL_PATH",
    "STEP_POINT",
    "VIA_POINT", "SWITCH", "CAMERA_LOOK_AT", "CAMERA_AZIMUTH_DEG", "CAMERA_ELEVATION_DEG",
    "CAMERA_DISTANCE", "LEGEND",
]

Colour = tuple[int, int, int]  # RGB, 0-255


def rgb01(c: Colour) -> tuple[float, float, float]:
    """RGB 0-255 -> 0-1."""
    return tuple(v / 255.0 for v in c)


ARM: Colour = (40, 90, 200)  # the planned / shown arm (blue)
SOLUTION: Colour = (90, 140, 230)  # other IK solutions (translucent light blue)
SELECTED: Colour = (40, 90, 200)
#: One colour per IK solution in pose mode (solution k: SOLUTIONS[k % 8]); no red (kept for limits).
SOLUTIONS: tuple[Colour, ...] = ((40, 90, 200), (20, 150, 140), (150, 80, 200), (200, 140, 0),
                                 (60, 160, 60), (200, 90, 160), (100, 110, 130), (0, 170, 220))
TARGET_FRAME_LENGTH = 0.12  # [m] axes of the target frame in pose mode
MEASURED: Colour = (20, 150, 140)  # measured arm of a run log (teal)
OUT_OF_LIMITS: Colour = (220, 30, 30)  # a link whose joint is outside Table I (red)
NEAREST: Colour = (250, 170, 0)  # link nearest the scene (amber)
UNSAFE: Colour = (230, 0, 120)  # nearest link inside the safety zone (magenta)
OBSTACLE: Colour = (210, 45, 40)  # scenario obstacles (red)
SUPPORT: Colour = (150, 110, 70)  # tables and shelves (brown, translucent: the arm shows through)
SUPPORT_OPACITY = 0.55
PLATFORM: Colour = (110, 110, 115)  # mobile platform (grey)
FLOOR: Colour = (200, 200, 200)
ELLIPSOID: Colour = (240, 150, 30)  # Eq 52-53 enclosing ellipsoids (orange wireframe)
TOOL_PATH: Colour = (20, 160, 60)  # tool path (green)
STEP_POINT: Colour = (10, 100, 30)
VIA_POINT: Colour = (170, 40, 190)  # via-points (purple)
SWITCH: Colour = (240, 120, 0)  # IK branch switch markers

#: Default camera (base frame): looking at CAMERA_LOOK_AT [m] from the front, slightly right, above.
CAMERA_LOOK_AT = (0.3, 0.0, 0.15)
CAMERA_AZIMUTH_DEG = -20.0
CAMERA_ELEVATION_DEG = 50.0
CAMERA_DISTANCE = 1.9

LEGEND = (
    ("arm (URDF collision shapes)", ARM),
    ("obstacle", OBSTACLE),
    ("support", SUPPORT),
    ("platform", PLATFORM),
    ("enclosing ellipsoid (Eq 52-53)", ELLIPSOID),
    ("tool path / step-points", TOOL_PATH),
    ("via-point", VIA_POINT),
    ("link nearest the scene", NEAREST),
    ("inside the safety zone", UNSAFE),
    ("joint outside Table I", OUT_OF_LIMITS),
)
