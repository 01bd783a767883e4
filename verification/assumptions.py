"""What a verdict depends on besides the thesis text: the named assumptions of the report.

Every :class:`~verification.registry.Row` lists the ids of the assumptions its verdict
rests on (``Row.depends_on``); the report prints the legend once and the ids per row,
and ``verification.json`` carries both. Add an assumption here, never as free text in
a check, so that one id means one thing across the report.

The numbers behind these assumptions live in one place each (``iik.THESIS_ARM``,
``iik.scene``, ``urdf/thesis_arm.urdf``, ``scenarios/``, ``hardware.sim``); this module
only names them.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Assumption", "ASSUMPTIONS", "EXACT_GEOMETRY", "assumption"]


@dataclass(frozen=True)
class Assumption:
    """One thing a verdict depends on.

    Attributes:
        id: Short stable key used in rows and in ``verification.json``.
        text: What is assumed, and where its value lives.
    """

    id: str
    text: str


_ALL = (
    Assumption(
        "l1",
        "l1 = 0.300 m is assumed: the thesis never prints it (a constant z offset that "
        "cancels from every derivative in App. E); iik.THESIS_ARM.l1",
    ),
    Assumption(
        "lengths",
        "l2..l5 = 0.122, 0.339, 0.175, 0.265 m are not printed: they were recovered "
        "from the diagonal of H* at App. E point A1 (docs/ARM.md); iik.THESIS_ARM",
    ),
    Assumption(
        "lengths-circular",
        "CIRCULAR: the compared numbers are among those l2..l5 were fitted "
        "to (H*(1,1), (2,2), (4,4), (5,5) at App. E point A1), so they "
        "agree by construction and confirm nothing",
    ),
    Assumption(
        "text",
        "the printed form is transcribed from the extracted thesis text; where the "
        "extraction is garbled the row says how it was read",
    ),
    Assumption(
        "pinocchio",
        "ground truth from Pinocchio on urdf/thesis_arm.urdf (generated from "
        "Table II by iik.urdf; the generator is itself checked on the UR5 and "
        "the Franka Panda)",
    ),
    Assumption(
        "reachability",
        "ground-truth reachability: 10^6 (quick: 10^5) uniform joint samples "
        "within Table I plus bounded numerical position IK (residual < 1e-6 m); "
        "points within about 1e-4 m of the boundary may be misclassified",
    ),
    Assumption(
        "ik-sweep",
        "ground truth for orientations: iik.solve (complete solver, every "
        "solution, within Table I) on a finite (alpha, beta) grid",
    ),
    Assumption(
        "complete-solver",
        "reference solutions from iik.solve (complete elimination solver, "
        "verified separately: FK residual and generating-q recovery)",
    ),
    Assumption(
        "collision-shapes",
        "collision shapes of urdf/thesis_arm.urdf (boxes and cylinders "
        "sized as PowerCube modules) are assumed; the thesis gives none",
    ),
    Assumption(
        "scene",
        "scenes are reconstructed (scenarios/*.toml): start, goal, via-points, "
        "orientations and obstacle sizes are not printed",
    ),
    Assumption(
        "sec36-method",
        "the Sec 3.6 planner is reconstructed (iik.planning.build_path, track_branches): "
        "repulsion along the printed plane normal, Eq 53 corrected, least-effort IK "
        "(Eq 54) per step, the orientation search where the nominal orientation has no "
        "solution; the thesis does not say which start configuration it took (the first "
        "IK branch whose arm does not touch the scene is taken)",
    ),
    Assumption(
        "platform",
        "the platform box (0.65 x 0.50 x 0.45 m) and the floor at z = -0.45 m "
        "are assumed (iik.scene); the thesis gives only the heights",
    ),
    Assumption(
        "speed-limits",
        "joint speed limits: 1.2 rad/s on every joint (the slower module kind "
        "of Sec 3.2; the text does not say which joint is which)",
    ),
    Assumption("accel-limits", "joint acceleration limits of 2.0 rad/s^2 are assumed (not in the thesis)"),
    Assumption(
        "sim-arm",
        "the arm is hardware.sim: FSTEP moves at constant velocity, measured "
        "signals lag by an assumed pure delay, an assumed current model; no real "
        "PowerCube is attached",
    ),
    Assumption(
        "host-timing",
        "wall-clock timings of Python/NumPy code on this machine (load dependent); the thesis timed C++",
    ),
    Assumption(
        "sec35-angles",
        "Sec 3.5's alpha, beta (azimuth and inclination of link 5) are "
        "converted to Eq 42's (alpha + 180 deg, beta + 90 deg), the reading "
        "the Dexterity section establishes",
    ),
)

#: Every assumption by id.
ASSUMPTIONS: dict[str, Assumption] = {a.id: a for a in _ALL}


#: What a comparison with exact geometry rests on: Pinocchio on the shipped URDF, built with the
#: recovered lengths and the assumed l1.
EXACT_GEOMETRY = ("l1", "lengths", "pinocchio")


def assumption(key: str) -> Assumption:
    """The assumption ``key``; raises ``KeyError`` naming the known ids."""
    try:
        return ASSUMPTIONS[key]
    except KeyError:
        raise KeyError(f"unknown assumption {key!r}; known: {', '.join(ASSUMPTIONS)}") from None
