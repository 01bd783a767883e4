"""Checks of the workspace analysis: Sec 3.4.3 (three boundary surfaces, no interior
boundary), Sec 3.4.4 (the Cartesian test, Eq 36-41, as a whole and equation by
equation) and App. G (relocating a point outside the workspace).

Ground truth is position reachability over Table I (every orientation allowed):
:class:`verification.oracles.reachability.ReachabilityOracle` (10^6 uniformly sampled
joint vectors through ``iik.fk`` + bounded LM position IK from the nearest samples).
Exact geometry (joint positions) comes from Pinocchio. The printed Eq 36-41 are
transcribed in :func:`eq36_41_printed`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

import numpy as np
from scipy.spatial import cKDTree

import iik
from iik.dh import dh_chain
from iik.ik.angles import clip_angle
from iik.workspace import in_workspace, tool_positions

from ..assumptions import EXACT_GEOMETRY
from ..formula import Formula, Points, per_run
from ..numbers import fmt_vec
from ..oracles.pinocchio_model import joint_placements
from ..oracles.reachability import oracle_for
from ..plotting import new_figure
from ..registry import Erratum, Forms, Measure, Row, Section, Slip, SlipKind, Verdict, epsilon
from ..second_reading import Kind, Reading, search
from ..shorthand import wrap
from ..thesis_index import title_of

_D = np.pi / 180
ARM = iik.THESIS_ARM
_DEP = ("l1", "lengths", "reachability")
SECTION = Section("Workspace (Sec 3.4.3-3.4.4, Eq 36-41, App. G)", depends_on=_DEP, order=40.0)
#: IK residuals in (1e-6, AMBIGUOUS) m mark the oracle's boundary band: such points are not graded.
AMBIGUOUS = 1e-4


# ----------------------------------------------------------------------------- printed forms
def eq36_printed(P):
    """Eq 36: phi = atan2(py, px) [rad] of points ``P`` (n, 3) [m]."""
    return np.arctan2(P[:, 1], P[:, 0])


def _behind(P) -> np.ndarray:
    """Regions 2/3 (Eq 36): |phi| >= 160 deg, behind the arm."""
    return np.abs(eq36_printed(P)) >= 160 * _D


def _polar(r, phi, z) -> np.ndarray:
    """Points (n, 3) [m] at radius ``r`` [m] and azimuth ``phi`` [rad] about the base axis, height ``z``."""
    return np.column_stack([r * np.cos(phi), r * np.sin(phi), z])


def eq37_printed(phi, arm=ARM) -> np.ndarray:
    """Eq 37: joint 2 at [l2 cos(phi), l2 sin(phi), l1] [m] with joint 1 at phi [rad] -> (n, 3)."""
    return np.stack([arm.l2 * np.cos(phi), arm.l2 * np.sin(phi), np.full_like(phi, arm.l1)], 1)


def eq39_printed(P, th1, *, sign: float = -1.0, arm=ARM):
    """Eq 39 as printed: theta2 = -atan2(pz - l1, sqrt(px^2 + py^2)) [rad] (link 3 aimed from the base
    axis; ``th1`` unused; ``sign``: the sign in front)."""
    return sign * np.arctan2(P[:, 2] - arm.l1, np.sqrt(P[:, 0] ** 2 + P[:, 1] ** 2))


def eq39_corrected(P, th1, *, sign: float = -1.0, atan=np.arctan2, arm=ARM):
    """Eq 39 corrected: theta2 = -atan2(pz - l1, u - l2) [rad], u = px cos(th1) + py sin(th1) (link 3 aimed
    from joint 2, joint 1 at ``th1`` [rad]), limited to Table I by the nearer limit on the circle.
    ``sign`` (the sign in front) and ``atan`` (``atan(y, x)``) are there for the slips."""
    u = P[:, 0] * np.cos(th1) + P[:, 1] * np.sin(th1)
    return clip_angle(sign * atan(P[:, 2] - arm.l1, u - arm.l2), arm.lower[1], arm.upper[1])


def eq40_corrected(th1, th2, *, sign: float = 1.0, arm=ARM, l3: float | None = None) -> np.ndarray:
    """Joint 4 [m] (n, 3) with joint 1 at ``th1``, joint 2 at ``th2`` [rad] and joint 3 at 0:
    ((l2 + l3 c2) cos th1, (l2 + l3 c2) sin th1, l1 - l3 s2) (Table II / Eq 4). Eq 40 prints ``sign``
    -1 (l2 - l3 c2); ``l3`` [m]: link 3's length, default the arm's (a slip takes l4)."""
    l3 = arm.l3 if l3 is None else l3
    r = arm.l2 + sign * l3 * np.cos(th2)
    return np.stack([r * np.cos(th1), r * np.sin(th1), arm.l1 - l3 * np.sin(th2)], 1)


def eq40_printed(th1, th2):
    """Eq 40 as printed: joint 4 at ((l2 - l3 c2) cos th1, (l2 - l3 c2) sin th1, l1 - l3 s2) [m]."""
    return eq40_corrected(th1, th2, sign=-1.0)


def eq36_41_test(
    p, arm=ARM, *, eq39: str = "printed", eq40_sign: float = -1.0, margin: float = 0.0,
    th1_rule: str = "region", reach1: float | None = None, reach23: float | None = None,
    eq39_sign: float = -1.0,
) -> np.ndarray:
    """The test of Sec 3.4.4 -> boolean (n,) 'within boundary' (0 of Eq 38/41).

    ``eq39``: ``"printed"`` (link 3 aimed from the base axis) or ``"corrected"`` (from joint 2,
    limited to Table I by the nearer limit on the circle); ``eq40_sign``: the sign in Eq 40's
    ``(l2 -+ l3 c2)`` (printed: -1);
    ``margin`` [m]: added to both reach radii (the tolerance test); ``th1_rule``: joint 1 in regions 2/3
    at the region's limit (``"region"``), at 160 deg in both (``"printed"``: Eq 40's cos(160 deg),
    sin(160 deg) literally) or at the other limit (``"other"``); ``reach1``, ``reach23`` [m]: the reach
    radii (default l3 + l4 + l5 and l4 + l5); ``eq39_sign``: the sign in front of Eq 39's atan2.
    """
    p = np.atleast_2d(p)
    r1 = arm.l3 + arm.l4 + arm.l5 if reach1 is None else reach1
    r23 = arm.l4 + arm.l5 if reach23 is None else reach23
    phi = eq36_printed(p)  # Eq 36
    rho1 = np.linalg.norm(p - eq37_printed(phi, arm), axis=1)  # Eq 37
    inside = ~(rho1 > r1 + margin)  # Eq 38
    for region, lim in ((phi >= 160 * _D, 160 * _D), (phi <= -160 * _D, -160 * _D)):
        th1 = {"region": lim, "printed": 160 * _D, "other": -lim}[th1_rule]
        eq39_form = {"printed": eq39_printed, "corrected": eq39_corrected}[eq39]
        th2 = eq39_form(p, th1, sign=eq39_sign, arm=arm)  # Eq 39
        rho23 = np.linalg.norm(p - eq40_corrected(th1, th2, sign=eq40_sign, arm=arm), axis=1)  # Eq 40
        inside = np.where(region, ~(rho23 > r23 + margin), inside)  # Eq 41
    return inside


def eq36_41_printed(p, arm=ARM) -> np.ndarray:
    """Eq 36-41 exactly as printed -> boolean (n,) 'within boundary'."""
    return eq36_41_test(p, arm)


#: Sec 3.4.3 as printed: surface -> (fixed joints {joint: deg}, free joint ranges {joint: (lo, hi) deg}).
BOUNDARY_SURFACES_PRINTED = {
    "f(1)": ({4: 0.0, 5: 0.0, 3: 0.0}, {1: (-160.0, 160.0), 2: (-120.0, 95.0)}),
    "f(2)": ({1: 160.0, 3: 90.0, 5: 0.0}, {2: (-100.0, 95.0), 4: (0.0, 41.0)}),
    "f(3)": ({1: -160.0, 3: 90.0, 5: 0.0}, {2: (-100.0, 95.0), 4: (-41.0, 0.0)}),
}
#: A description that does cover the boundary: f(1), and behind the arm joint 1 at a limit with the wrist
#: stretched (theta5 = 0) and theta2, theta3, theta4 free (the corrected Eq 39-41 surface lies in it).
BOUNDARY_COVERING = {
    "f(1)": BOUNDARY_SURFACES_PRINTED["f(1)"],
    "rear+": ({1: 160.0, 5: 0.0}, {2: (-120.0, 95.0), 3: (-160.0, 160.0), 4: (-119.0, 119.0)}),
    "rear-": ({1: -160.0, 5: 0.0}, {2: (-120.0, 95.0), 3: (-160.0, 160.0), 4: (-119.0, 119.0)}),
}
#: A description that misses part of it: f(1) with joint 1 limited to +-150 deg.
BOUNDARY_SHORT = {"f(1)": ({4: 0.0, 5: 0.0, 3: 0.0}, {1: (-150.0, 150.0), 2: (-120.0, 95.0)})}


def spec_points(spec: tuple, n, arm=ARM) -> tuple[np.ndarray, np.ndarray]:
    """Grid points on a surface description (fixed joints, free ranges) with ``n`` values per free joint
    (one number, or one per free joint) -> (points (m, 3) [m], q (m, 5) [rad])."""
    fixed, free = spec
    sizes = np.broadcast_to(n, len(free))
    axes = [np.linspace(a, b, k) * _D for (a, b), k in zip(free.values(), sizes, strict=True)]
    grids = np.meshgrid(*axes, indexing="ij")
    q = np.zeros((grids[0].size, 5))
    for j, v in fixed.items():
        q[:, j - 1] = v * _D
    for j, g in zip(free, grids, strict=True):
        q[:, j - 1] = g.ravel()
    return tool_positions(q, arm), q


def surface_points(name: str, n1: int, n2: int, arm=ARM) -> tuple[np.ndarray, np.ndarray]:
    """Grid of ``n1 x n2`` points on a printed Sec 3.4.3 surface -> (points (m, 3) [m], q (m, 5) [rad])."""
    return spec_points(BOUNDARY_SURFACES_PRINTED[name], (n1, n2), arm)


# ----------------------------------------------------------------------------- ground truth
@dataclass(frozen=True)
class ClassifiedPoints:
    """The test points of the classification checks and the oracle's verdict on each (:func:`_test_points`).

    Attributes:
        p: The points [m], base frame, shape (n, 3): the first ``n_box`` uniform in the box [-0.95, 0.95]^2
            x [-0.55, 1.15] m, the rest behind the arm (azimuth 150-210 deg, radius up to 0.95 m).
        n_box: How many of ``p`` are the box's.
        truth: Reachable by the oracle (IK residual < 1e-6 m), shape (n,).
        residual: The oracle's best IK residual [m], shape (n,).
        q: The oracle's best joints 1-5 [rad], shape (n, 5).
        graded: Decided clearly by the oracle (residual not in its boundary band), shape (n,).
    """

    p: np.ndarray
    n_box: int
    truth: np.ndarray
    residual: np.ndarray
    q: np.ndarray
    graded: np.ndarray

    def selected(self, region: str) -> np.ndarray:
        """The graded points of ``region``: ``"all"``, ``"1"`` or ``"23"`` (behind the arm, Eq 36)."""
        return self.graded & {"all": np.ones(len(self.p), bool), "1": ~_behind(self.p),
                              "23": _behind(self.p)}[region]

    @property
    def domain(self) -> str:
        """The points in words (a row's domain)."""
        return (
            f"{self.n_box} points uniform in the box [-0.95, 0.95]^2 x [-0.55, 1.15] m around the arm plus "
            f"{len(self.p) - self.n_box} at azimuth 150-210 deg (behind the arm, across joint 1's limits, "
            "where regions 2/3 begin), radius up to 0.95 m; points the oracle leaves undecided (IK residual "
            "1e-6..1e-4 m: the boundary band) are not graded"
        )


@per_run
def _test_points(ctx) -> ClassifiedPoints:
    """Uniform box points + points concentrated in regions 2/3, classified by the oracle; ``graded``: those
    it decides clearly (not in its boundary band)."""
    rng = ctx.rng("workspace-test-points")
    n1, n2 = ctx.n(10000, 1500), ctx.n(4000, 600)
    box = np.column_stack(
        [rng.uniform(-0.95, 0.95, n1), rng.uniform(-0.95, 0.95, n1), rng.uniform(-0.55, 1.15, n1)]
    )
    phi = rng.uniform(150 * _D, 210 * _D, n2)
    r = np.sqrt(rng.uniform(0, 0.95**2, n2))
    back = _polar(r, phi, rng.uniform(-0.55, 1.15, n2))
    pts = np.vstack([box, back])
    cls = oracle_for(ctx).classify(pts)
    graded = ~((cls.residual > 1e-6) & (cls.residual < AMBIGUOUS))
    return ClassifiedPoints(pts, n1, cls.reachable, cls.residual, cls.q, graded)


#: The map's cross-sections: plane -> (in words, the index of its vertical axis, that axis's range [m]).
_PLANES = {"xy": ("z = l1", 1, (-0.95, 0.95)), "xz": ("y = 0", 2, (-0.55, 1.15))}


@per_run
def _grid_plane(ctx, plane: str, n: int):
    """Grid of ``n x n`` points on the plane z = l1 (``"xy"``) or y = 0 (``"xz"``) [m] and their truth."""
    _, b, (lo, hi) = _PLANES[plane]
    X, V = np.meshgrid(np.linspace(-0.95, 0.95, n), np.linspace(lo, hi, n))
    P = np.zeros((X.size, 3))
    P[:, 2] = ARM.l1
    P[:, 0], P[:, b] = X.ravel(), V.ravel()
    return P, oracle_for(ctx).classify(P).reachable, X.shape, (-0.95, 0.95, lo, hi)


def _map_figure(ctx, name: str) -> str:
    """Cross-sections (z = l1 and y = 0): truth, Eq 36-41 printed and corrected, disagreements."""
    fig = new_figure(figsize=(12, 5.2))
    for k, (plane, (title, b, _)) in enumerate(_PLANES.items()):
        P, truth, shape, ext = _grid_plane(ctx, plane, ctx.n(80, 40))
        ax = fig.add_subplot(1, 2, k + 1)
        ax.imshow(truth.reshape(shape), origin="lower", extent=ext, cmap="Greys", alpha=0.35, vmin=0,
                  vmax=1.6)
        for pred, short, col, lab, size, marker, c_out, c_in in (
            (eq36_41_printed(P), "printed", "red", "Eq 36-41 as printed", 6, "s", "orange", "magenta"),
            (in_workspace(P, ARM), "corrected", "blue", "iik.in_workspace (corrected)", 10, "x", "cyan", "k"),
        ):
            ax.contour(pred.reshape(shape).astype(float), levels=[0.5], colors=col, extent=ext,
                       linewidths=1.2)
            ax.plot([], [], color=col, label=lab)
            for wrong, c, what in ((~pred & truth, c_out, "outside"), (pred & ~truth, c_in, "inside")):
                ax.scatter(P[wrong, 0], P[wrong, b], s=size, c=c, marker=marker,
                           label=f"{short}: false {what}")
        ax.set(aspect="equal", xlabel="x [m]", ylabel=f"{'xyz'[b]} [m]")
        ax.set_title(f"plane {title} (grey: reachable, ground truth)", fontsize=9)
    ax.legend(fontsize=7, loc="lower right")
    return ctx.save_figure(fig, name, dpi=80)


def classification_reading(ctx, test, region: str, printed: str):
    """Second reading of the Sec 3.4.4 test (``test``, a partial of :func:`eq36_41_test` or the printed
    one): the misclassified test points under each nearby reading of its stated inputs (joint 1 in regions
    2/3 at 160 deg in both, as Eq 40 prints it, or at the other limit; theta2 of Eq 39 measured the other
    way), against the oracle."""
    tp = _test_points(ctx)
    sel = tp.selected(region)
    kw = dict(getattr(test, "keywords", {}) or {})
    stated = {"th1_rule": kw.pop("th1_rule", "region"), "eq39_sign": kw.pop("eq39_sign", -1.0)}

    def misfit(x) -> float:
        pred = eq36_41_test(tp.p, **kw, **x)
        return float(np.sum(pred[sel] != tp.truth[sel]))

    readings = [
        Reading(Kind.LIMIT, "joint 1 at 160 deg in both regions 2 and 3 (Eq 40's cos 160, sin 160 literally)",
                {"th1_rule": "printed"}),
        Reading(Kind.LIMIT, "joint 1 at the other limit in regions 2/3", {"th1_rule": "other"}),
        Reading(Kind.SIGN, "theta2 of Eq 39 measured the other way", {"eq39_sign": -stated["eq39_sign"]}),
    ]
    return search(stated, readings, misfit, 0.0, printed=printed,
                  stated_text="regions by Eq 36 (joint 1 at its limit, +-160 deg, in regions 2/3), theta2 by "
                  "Eq 39",
                  route="the test re-evaluated under each reading against the reachability oracle (10^6 "
                  "joint samples + position IK)", measure="misclassified graded test points")


def _classification_row(ctx, form, key, region: str, printed: str, corrected: str = "-", *, claim: str = "",
                        rid: str = "", method: str = "") -> Row:
    """The row of a classification test (the form) on the graded test points of ``region`` ("all", "1",
    "23"); the id and the claim default to the index key's (``"Eq 38"`` -> ``eq38``, its title); ``method``
    is added to :data:`_COMPOSITE`."""
    tp = _test_points(ctx)
    P, truth = tp.p, tp.truth
    sel = tp.selected(region)
    pred = form(P)
    fi, fo = int(np.sum(pred[sel] & ~truth[sel])), int(np.sum(~pred[sel] & truth[sel]))
    bad = np.nonzero(sel & (pred != truth))[0]
    erratum = None
    if len(bad):
        i = bad[0]
        q = f", q[1..5] = {fmt_vec(tp.q[i])} rad" if truth[i] else ""
        where = (f"p = {fmt_vec(P[i])} m is {'reachable' if truth[i] else 'unreachable'} (IK residual "
                 f"{tp.residual[i]:.1e} m{q}); the form says {'inside' if pred[i] else 'outside'}")
        erratum = Erratum(key, printed, corrected, where)
    row = Row.graded(
        claim or f"{title_of(key)}.",
        key,
        _COMPOSITE + method,
        f"{int(sel.sum())} graded test points ({int(truth[sel].sum())} reachable; "
        f"{int((~tp.graded).sum())} in the oracle's boundary band not graded): false inside {fi}, "
        f"false outside {fo}",
        (Measure("misclassified test points", fi + fo, 0),),
        erratum=erratum,
        id=rid or key.lower().replace(" ", ""),
        domain=tp.domain + {"all": "", "1": "; region 1 only", "23": "; regions 2/3 only"}[region],
    )
    return row.reread_if_erratum(lambda: classification_reading(ctx, form, region, printed))


_COMPOSITE = (
    "Eq 36-41 transcribed; test points classified against ground-truth reachability (10^6 uniform joint "
    "samples through the Eq 4 position column + bounded LM position IK from the nearest samples; reachable "
    "if residual < 1e-6 m)"
)


def _corrected(**kw):
    """The test with Eq 39 and Eq 40 corrected, and ``kw`` (:func:`eq36_41_test`)."""
    return partial(eq36_41_test, **{"eq39": "corrected", "eq40_sign": 1.0, **kw})


@SECTION.check(
    "Eq 36",
    forms=Forms(
        printed=eq36_41_printed,
        good=partial(in_workspace, arm=ARM),
        good_is="iik.in_workspace (Eq 39 and Eq 40 corrected)",
        slips=(
            Slip(SlipKind.SIGN, "Eq 40 with l2 - l3 c2 (Eq 39 corrected)", _corrected(eq40_sign=-1.0)),
            Slip(SlipKind.LIMIT, "joint 1 at the other limit in regions 2/3", _corrected(th1_rule="other")),
            Slip(SlipKind.LENGTH, "region 1's reach l3 + l4 (l5 left out)",
                 _corrected(reach1=ARM.l3 + ARM.l4)),
        ),
        tolerance=Slip(SlipKind.EPSILON, "the corrected test with both radii 5 mm longer",
                       _corrected(margin=0.005)),
    ),
)
def eq36_41(ctx, test):
    """Sec 3.4.4 / Sec 5.2: the whole test (Eq 36-41) decides whether a point is inside the workspace."""
    row = _classification_row(
        ctx, test, "Sec 3.4.4, Eq 36-41", "all", "Eq 36-41 as printed",
        "Eq 39 and Eq 40 corrected (rows workspace.eq39, workspace.eq40)", rid="eq36_41",
        method=". Map: cross-sections z = l1, y = 0",
        claim="Eq 36-41 decide whether a point is inside the workspace (region 1: |p - joint 2| <= l3+l4+l5; "
        "regions 2/3: |p - joint 4| <= l4+l5 with joint 1 at its limit); 'the algorithm was capable of "
        "recognizing whether a given position was inside of the workspace ... during every trial' (Sec 5.2).",
    )
    figure = test is eq36_41_printed
    return row.replace(figures=(_map_figure(ctx, "workspace_eq36_41_map.png"),)) if figure else row


def _dh_frames(q) -> np.ndarray:
    """Frames 1..6 of Table II's chain by iik.dh (n, 6, 4, 4): index 1 is joint 2's, 2 joint 4's."""
    return dh_chain(ARM.dh_table(), q, all_frames=True)


def _joints_at(th1, th2, frame: int, frames=joint_placements) -> np.ndarray:
    """A joint's position [m] (n, 3) with joints 1-2 at ``th1``, ``th2`` [rad] and the others 0: the origin
    of ``frames(q)[:, frame]`` (Pinocchio's placements: 2 is joint 2, 3 joint 4; or :func:`_dh_frames`)."""
    th1, th2 = np.broadcast_arrays(th1, th2)
    q = np.zeros((len(th1), 6))
    q[:, 0], q[:, 1] = th1, th2
    return frames(q)[:, frame, :3, 3]


def _nearest_angle(P, grid, at, refine_at=None, lo=None, hi=None, iters: int = 50) -> np.ndarray:
    """The angle [rad] that brings a joint nearest to each point of ``P`` (n, 3) [m]: the nearest value of
    ``grid`` (m,), refined by golden-section search within one grid step (clipped to [lo, hi]).
    ``at(t)``: the joint's positions (k, 3) [m] at the angles ``t`` (k,); ``refine_at`` (default ``at``):
    the same by another route, for the refinement."""
    d = np.linalg.norm(P[:, None, :] - at(grid)[None, :, :], axis=2)
    t, h = grid[np.argmin(d, axis=1)], grid[1] - grid[0]
    a, b = t - h, t + h
    if lo is not None:
        a, b = np.clip(a, lo, hi), np.clip(b, lo, hi)
    g, at2 = (np.sqrt(5) - 1) / 2, refine_at or at
    for _ in range(iters):
        c, e = b - g * (b - a), a + g * (b - a)
        left = np.linalg.norm(P - at2(c), axis=1) < np.linalg.norm(P - at2(e), axis=1)
        a, b = np.where(left, a, c), np.where(left, e, b)
    return (a + b) / 2


@per_run
def _eq36_points(ctx) -> tuple[np.ndarray, np.ndarray]:
    """Points where Eq 36 is hardest: uniform in the box, within 1 mm of the base axis (where the azimuth is
    nearly undefined), within 1e-3 deg of the region limits +-160 deg and across +-180 deg, with the joint-1
    angle that brings joint 2 nearest to each: a grid over the whole turn of Pinocchio's joint-2 position
    (exact geometry), refined by golden-section search on Table II's first two links."""
    rng = ctx.rng("eq36")
    n = ctx.n(1000, 120)
    box = np.column_stack([rng.uniform(-0.95, 0.95, (n, 2)), rng.uniform(-0.55, 1.15, n)])
    r = 10 ** rng.uniform(-6, -3, n)  # 1 um .. 1 mm from the axis
    az = rng.uniform(-np.pi, np.pi, n)
    axis = _polar(r, az, rng.uniform(-0.55, 1.15, n))
    lim = rng.choice([-160.0, 160.0, 180.0], n) * _D + rng.uniform(-1e-3, 1e-3, n) * _D
    rr = rng.uniform(0.05, 0.95, n)
    edge = _polar(rr, lim, rng.uniform(-0.55, 1.15, n))
    P = np.vstack([box, axis, edge])
    grid = np.linspace(-np.pi, np.pi, 3600, endpoint=False)
    return P, _nearest_angle(P, grid, partial(_joints_at, th2=0.0, frame=2),
                             partial(_joints_at, th2=0.0, frame=1, frames=_dh_frames))


@SECTION.check(
    "Eq 36",
    depends_on=EXACT_GEOMETRY,
    forms=Forms.right(
        eq36_printed,
        (
            Slip(SlipKind.SWAP, "atan2(px, py): the arguments exchanged",
                 lambda P: np.arctan2(P[:, 0], P[:, 1])),
            Slip(SlipKind.FUNCTION, "atan(py / px) for atan2 (the quadrant lost)",
                 lambda P: np.arctan(P[:, 1] / P[:, 0])),
            Slip(SlipKind.BRANCH, "atan2(py, px) + pi (the opposite side)",
                 lambda P: eq36_printed(P) + np.pi),
        ),
        tolerance=epsilon(eq36_printed, 1e-6, "phi + 1 urad"),
    ),
)
def eq36_azimuth(ctx, eq36):
    """Eq 36: with joint 1 at phi = atan2(py, px) joint 2 is nearest to the point (Sec 3.4.4.1's farthest
    reach toward it); |phi| >= 160 deg is exactly where that joint-1 angle leaves Table I (regions 2/3)."""
    P, best = _eq36_points(ctx)
    phi = np.asarray(eq36(P), float)
    r = np.hypot(P[:, 0], P[:, 1])
    d_angle = np.abs(wrap(phi - best))
    # graded as the joint-2 distance it costs: an azimuth error at radius r moves joint 2's nearest point by
    # l2 * angle, but changes its distance to p only to second order near the axis
    gap = np.linalg.norm(P - _joints_at(phi, 0.0, 2), axis=1) - np.linalg.norm(P - _joints_at(best, 0.0, 2),
                                                                                axis=1)
    region_form = np.abs(phi) >= 160 * _D
    region_true = (best < ARM.lower[0]) | (best > ARM.upper[0])
    m = (
        Measure("max extra distance of joint 2 from p with joint 1 at the form's phi", gap.max(), 1e-9, "m"),
        Measure("points whose region (|phi| >= 160 deg) differs from 'the nearest joint-1 angle is outside "
                "Table I'", int(np.sum(region_form != region_true)), 0),
    )
    k = int(np.argmax(gap))
    return Row.graded(
        "phi = atan2(py, px) (Eq 36) is the joint-1 angle that brings joint 2 nearest to the point (the "
        "farthest reach toward it, Sec 3.4.4.1); region 1 is -160 < phi < 160 deg, where that angle is "
        "within Table I.",
        "Eq 36",
        "the joint-1 angle that puts joint 2 (Pinocchio) nearest to each point, by a 3600-point grid over "
        "the whole turn and golden-section refinement, vs the form; the extra distance it costs, and the "
        "region the form assigns vs whether that angle is outside Table I",
        f"max extra distance {gap.max():.2g} m (max angular difference {d_angle[r > 1e-3].max():.2g} rad "
        f"away from the axis, {d_angle.max():.2g} rad within 1 mm of it, where the azimuth barely matters); "
        f"points in the wrong region: {int(np.sum(region_form != region_true))}",
        m,
        id="eq36",
        domain=f"{len(P)} points: {len(P) // 3} uniform in the box [-0.95, 0.95]^2 x [-0.55, 1.15] m, "
        f"{len(P) // 3} within 1 um..1 mm of the base axis, {len(P) // 3} within 1e-3 deg of azimuth -160, "
        "160 or 180 deg",
        erratum=Erratum("Eq 36", "phi = atan2(py, px)", "the joint-1 angle nearest the point",
                        f"p = {fmt_vec(P[k])} m: joint 2 is {gap[k]:.3g} m farther than it need be"),
    )


def _phi_sample(ctx) -> Points:
    n = ctx.n(500, 50)
    return Points(ctx.rng("eq37").uniform(-np.pi, np.pi, n), f"{n} phi uniform over the whole turn (theta1 "
                  "= phi, the other joints 0)", "rad", "phi")


def _region_check(key: str, name: str, region: str, printed: str, good_is: str, bad_is: str, slips: tuple,
                  **test) -> Callable:
    """Register the check of one region's test (:func:`eq36_41_test` with ``test``) on the graded test points
    of ``region``: right as printed (``good_is``); ``slips`` are ``(kind, what, extra keywords)``; the
    tolerance test has its reach 5 mm short (``bad_is``)."""
    forms = Forms.right(
        partial(eq36_41_test, **test),
        tuple(Slip(k, what, partial(eq36_41_test, **{**test, **kw})) for k, what, kw in slips),
        tolerance=Slip(SlipKind.EPSILON, bad_is, partial(eq36_41_test, margin=-0.005, **test)),
        good_is=good_is,
    )

    def check(ctx, test):
        return _classification_row(ctx, test, key, region, printed)

    check.__name__ = check.__qualname__ = name
    check.__doc__ = f"{key}: {title_of(key)}."
    return SECTION.check(key, forms=forms)(check)


eq38_region1 = _region_check(
    "Eq 38", "eq38_region1", "1", "rho1 > l3 + l4 + l5", "the printed test (it is right)",
    "the reach l3 + l4 + l5 shortened by 5 mm", (
        (SlipKind.LENGTH, "reach l3 + l4 (l5 left out)", {"reach1": ARM.l3 + ARM.l4}),
        (SlipKind.LENGTH, "reach l2 + l3 + l4 + l5 (from the base axis)",
         {"reach1": ARM.l2 + ARM.l3 + ARM.l4 + ARM.l5}),
    ),
)


@dataclass(frozen=True)
class RearPoints(Points):
    """Points behind the arm (regions 2/3) with joint 1 at ``th1`` [rad] and ``best``, the theta2 [rad] that
    brings joint 4 nearest to each (grid and golden-section search)."""

    th1: float = 160 * _D
    best: np.ndarray | None = None


@per_run
def _rear_sample(ctx) -> RearPoints:
    """Points behind the arm, and the theta2 within Table I that brings joint 4 (joint 1 at 160 deg) nearest
    to each: a 2001-point grid, then golden-section refinement (exact geometry, independent of any closed
    form)."""
    rng = ctx.rng("eq39-points")
    n = ctx.n(400, 60)
    phi = rng.uniform(160 * _D, 200 * _D, n)
    r = np.where(np.arange(n) % 4 == 0, rng.uniform(0.01, 0.2, n), rng.uniform(0.05, 0.9, n))  # 1/4 near axis
    P = _polar(r, phi, rng.uniform(-0.5, 1.1, n))
    P = P[eq36_printed(P) >= 160 * _D]
    lo, hi = ARM.lower[1], ARM.upper[1]
    at = partial(_joints_at, 160 * _D, frame=2, frames=partial(iik.joint_frames, arm=ARM))  # joint 4
    best = _nearest_angle(P, np.linspace(lo, hi, 2001), at, lo=lo, hi=hi, iters=45)
    return RearPoints(P, f"{len(P)} points at azimuth 160-200 deg, radius 0.05-0.9 m (a quarter 0.01-0.2 m: "
                      "within l2 of the axis, where u - l2 changes sign), z from -0.5 to 1.1 m (theta2 "
                      "clipped at both Table I limits)", th1=160 * _D, best=best)


@per_run
def _dh_theta2(ctx, th1: float) -> np.ndarray:
    """theta2 within Table I that puts joint 4 (joint 1 at ``th1``) nearest to each rear point: a dense grid
    over Table II's first three links by iik.dh, refined by golden-section search (a route of its own: not
    Pinocchio, not the check's search)."""
    lo, hi = ARM.lower[1], ARM.upper[1]
    at = partial(_joints_at, th1, frame=2, frames=_dh_frames)  # joint 4
    return _nearest_angle(_rear_sample(ctx).values, np.linspace(lo, hi, 2001), at, lo=lo, hi=hi)


def eq39_reading(ctx, P, th1, eq39):
    """Second reading of Eq 39 (the form) on the check's points: the form under each nearby reading of its
    inputs (theta2 measured the other way, joint 1 at the other limit, the point given in Sec 3.3.1's frame
    moved up by l1) vs the nearest-joint-4 theta2 of a dense grid (:func:`_dh_theta2`)."""
    stated = {"sign": 1.0, "th1": th1, "dz": 0.0}

    def misfit(x) -> float:
        Q = P - np.array([0.0, 0.0, x["dz"]])
        return float(np.abs(x["sign"] * eq39(Q, x["th1"]) - _dh_theta2(ctx, x["th1"])).max())

    readings = [
        Reading(Kind.SIGN, "theta2 measured the other way", {"sign": -1.0}),
        Reading(Kind.LIMIT, "joint 1 at the other limit (-160 deg)", {"th1": -th1}),
        Reading(Kind.CONVENTION, "p given in Sec 3.3.1's frame (moved up by l1)", {"dz": ARM.l1}),
    ]
    return search(stated, readings, misfit, 1e-6, printed="theta2 = -atan2(pz - l1, sqrt(px^2 + py^2))",
                  stated_text="the point p (base frame), joint 1 at its limit (160 deg), Table II's l1",
                  route="a 2001-point theta2 grid of joint 4 by iik.dh, refined by golden section (not "
                  "Pinocchio)",
                  measure="max |form - nearest-joint-4 theta2| [rad]")


def eq40_reading(th2: np.ndarray, eq40):
    """Second reading of Eq 40 (the form at theta1 = 160 deg) vs joint 4 of the iik.dh chain under each nearby
    reading of its inputs: joint 1 at the other limit, theta2 measured the other way, 160 taken as rad, x
    and y exchanged."""
    stated = {"th1": 160 * _D, "th2": th2, "xy": False, "th1_form": 160 * _D}

    def misfit(x) -> float:
        j4 = _joints_at(x["th1"], x["th2"], 2, _dh_frames)
        f = eq40(np.full(len(th2), x["th1_form"]), th2)
        if x["xy"]:
            f = f[:, [1, 0, 2]]
        return float(np.linalg.norm(f - j4, axis=1).max())

    readings = [
        Reading(Kind.LIMIT, "joint 1 at the other limit (-160 deg)", {"th1": -160 * _D}),
        Reading(Kind.SIGN, "theta2 measured the other way", {"th2": -th2}),
        Reading(Kind.UNIT, "160 taken as rad", {"th1_form": 160.0, "th1": 160.0}),
        Reading(Kind.SWAP, "x4 and y4 exchanged", {"xy": True}),
    ]
    return search(stated, readings, misfit, 1e-12,
                  printed="x4 = (l2 - l3 c2) cos(160 deg), y4 = (l2 - l3 c2) sin(160 deg), z4 = l1 - l3 s2",
                  stated_text="joint 1 at 160 deg (region 2), theta2 of Eq 39, Table II's l1, l2, l3",
                  route="joint 4 (the origin of frame 3) of the Table II chain by iik.dh, not Pinocchio",
                  measure="max |form - joint 4| [m]")


def _eq40_cos_sin(th1, th2):
    """Eq 40 corrected with s2 for c2 in x4 (a slip)."""
    out = eq40_corrected(th1, th2)
    out[:, 0] = (ARM.l2 + ARM.l3 * np.sin(th2)) * np.cos(th1)
    return out


def _theta2_sample(ctx) -> Points:
    n = ctx.n(500, 50)
    return Points(ctx.rng("eq40").uniform(ARM.lower[1], ARM.upper[1], n),
                  f"{n} theta2 uniform over Table I (-120..95 deg), joint 1 at 160 deg", "rad", "theta2")


CHECKS = {
    **SECTION.formulas(_phi_sample, Formula(
        "Eq 37", eq37_printed, lambda s, f: np.linalg.norm(f(s.values) - _joints_at(s.values, 0, 2), axis=1),
        1e-12, "m", (
            Slip(SlipKind.SWAP, "[l2 sin(phi), l2 cos(phi), l1]",
                 lambda phi: eq37_printed(phi)[:, [1, 0, 2]]),
            Slip(SlipKind.LENGTH, "l3 for l2",
                 lambda phi: eq37_printed(phi) * np.array([ARM.l3 / ARM.l2] * 2 + [1])),
        ), eps_is="each coordinate moved by 1 nm", depends_on=EXACT_GEOMETRY,
        method="printed point vs the origin of frame 2 (Pinocchio) at theta1 = phi, {n} phi")),
    **SECTION.formulas(_rear_sample, Formula(
        "Eq 39", eq39_printed, lambda s, f: np.abs(f(s.values, s.th1) - s.best), 1e-6, "rad", (
            Slip(SlipKind.SIGN, "+atan2(pz - l1, u - l2)", partial(eq39_corrected, sign=1.0)),
            Slip(SlipKind.SWAP, "atan2's arguments exchanged",
                 partial(eq39_corrected, atan=lambda y, x: np.arctan2(x, y))),
            Slip(SlipKind.FUNCTION, "atan((pz - l1) / (u - l2)) for atan2 (the quadrant lost)",
                 partial(eq39_corrected, atan=lambda y, x: np.arctan(y / x))),
        ), good=eq39_corrected, good_is="theta2 = -atan2(pz - l1, u - l2), u along the joint-1 limit "
        "direction, limited to Table I by the nearer limit on the circle", eps=1e-3,
        eps_is="the good theta2 + 1 mrad", depends_on=("l1", "lengths"),
        text="theta2 = -atan2(pz - l1, sqrt(px^2 + py^2)) (link 3 aimed from the base axis)",
        corrected="theta2 = -atan2(pz - l1, u - l2), u = px cos(th1) + py sin(th1), limited to Table I by "
        "the nearer limit on the circle (aimed from joint 2: the nearest joint-4 position)",
        method="{n} points behind the arm (azimuth 160-200 deg): the theta2 within Table I that puts joint 4 "
        "(joint 1 at 160 deg) nearest to the point, by grid and golden-section search, vs the form",
        note=lambda s, err: f"median |form - nearest| {np.median(err):.3g} rad",
        reread=lambda ctx, s, f: eq39_reading(ctx, s.values, s.th1, f))),
    **SECTION.formulas(_theta2_sample, Formula(
        "Eq 40", eq40_printed, lambda s, f: np.linalg.norm(f(np.full(len(s), 160 * _D), s.values)
                                                           - _joints_at(160 * _D, s.values, 3), axis=1),
        1e-12, "m", (
            Slip(SlipKind.SIGN, "(l2 - l3 c2)", eq40_printed),
            Slip(SlipKind.FUNCTION, "s2 for c2 in x4", _eq40_cos_sin),
            Slip(SlipKind.LENGTH, "l4 for l3", partial(eq40_corrected, l3=ARM.l4)),
        ), good=eq40_corrected, good_is="(l2 + l3 c2) (cos th1, sin th1), l1 - l3 s2",
        eps_is="the good point moved by 1 nm", depends_on=EXACT_GEOMETRY,
        text="x4 = (l2 - l3 c2) cos(160 deg), y4 = (l2 - l3 c2) sin(160 deg)",
        corrected="x4 = (l2 + l3 c2) cos(th1), y4 = (l2 + l3 c2) sin(th1) (joint 4 is l3 beyond joint 2 "
        "along link 3, Table II / Eq 4; th1 = -160 deg in region 3)",
        method="printed point vs the origin of frames 3-4 (Pinocchio), theta1 = 160 deg, {n} theta2 within "
        "Table I", note=lambda s, err: "= 2 l3 |c2| at most",
        reread=lambda ctx, s, f: eq40_reading(s.values, f))),
}


eq41_regions23 = _region_check(
    "Eq 41", "eq41_regions23", "23", "rho23 > l4 + l5",
    "the printed test (with Eq 39-40 corrected it is right)", "the reach l4 + l5 shortened by 5 mm", (
        (SlipKind.LENGTH, "reach l4 (l5 left out)", {"reach23": ARM.l4}),
        (SlipKind.LIMIT, "joint 1 at the other limit", {"th1_rule": "other"}),
    ),
    eq39="corrected",
    eq40_sign=1.0,
)


@per_run
def _boundary_points(ctx):
    """Exterior-boundary points: the farthest sample per equal-area direction cell from (0, 0, l1), refined
    outward along the ray by IK bisection."""
    oracle = oracle_for(ctx)
    c = np.array([0.0, 0.0, ARM.l1])
    V = oracle.points - c
    r = np.linalg.norm(V, axis=1)
    az = np.arctan2(V[:, 1], V[:, 0])
    el = np.arcsin(np.clip(V[:, 2] / np.maximum(r, 1e-12), -1, 1))
    na, ne = ctx.n(48, 20), ctx.n(24, 10)
    ia = np.clip(((az + np.pi) / (2 * np.pi) * na).astype(int), 0, na - 1)
    ie = np.clip(((np.sin(el) + 1) / 2 * ne).astype(int), 0, ne - 1)
    cell = ia * ne + ie
    order = np.lexsort((r, cell))
    last = np.r_[cell[order][1:] != cell[order][:-1], True]
    b_idx = order[last]
    u = V[b_idx] / r[b_idx, None]
    lo, hi = r[b_idx].copy(), r[b_idx] + 0.04
    for _ in range(5):  # bisection along each ray with the IK oracle (1.25 mm)
        mid = 0.5 * (lo + hi)
        ok = oracle.classify(c + mid[:, None] * u, thorough=False).reachable
        lo, hi = np.where(ok, mid, lo), np.where(ok, hi, mid)
    return c + lo[:, None] * u, na, ne


_COVER_TOL = 0.01  # [m]: a boundary point lies on a surface if the surface passes this close


def _distance_to_surface(B: np.ndarray, spec: tuple, n: int) -> np.ndarray:
    """Distance [m] from each point to a surface description: nearest grid point, then Gauss-Newton on the
    free joints within their ranges (projection onto the surface)."""
    pts, q = spec_points(spec, n)
    _, idx = cKDTree(pts).query(B)
    q = q[idx].copy()
    free = [j - 1 for j in spec[1]]
    lo, hi = np.array(list(spec[1].values())).T * _D
    for _ in range(25):
        G = tool_positions(q, ARM)
        J = iik.position_jacobian(np.column_stack([q, np.zeros(len(q))]), ARM)[:, :, :5][:, :, free]
        dq = np.einsum("nij,nj->ni", np.linalg.pinv(J, rcond=1e-9), B - G)
        q[:, free] = np.clip(q[:, free] + dq, lo, hi)
    return np.linalg.norm(B - tool_positions(q, ARM), axis=1)


@SECTION.check(
    41.0,
    forms=Forms(
        printed=BOUNDARY_SURFACES_PRINTED,
        good=BOUNDARY_COVERING,
        good_is="f(1) and, behind the arm, joint 1 at its limit with theta5 = 0 and theta2..theta4 free",
        slips=(
            Slip(SlipKind.LIMIT, "f(1) alone with joint 1 within +-150 deg", BOUNDARY_SHORT),
            Slip(SlipKind.CLAIM, "the covering set without its rear surfaces (f(1) alone)",
                 {"f(1)": BOUNDARY_COVERING["f(1)"]}),
        ),
    ),
)
def three_surface_boundary(ctx, surfaces):
    """Sec 3.4.3: the exterior boundary consists of the printed surfaces (each boundary point on one)."""
    B, na, ne = _boundary_points(ctx)
    d = np.array([_distance_to_surface(B, spec, ctx.n(160, 60) if len(spec[1]) == 2 else ctx.n(24, 14))
                  for spec in surfaces.values()])
    dist, nearest = d.min(axis=0), np.array(list(surfaces))[d.argmin(axis=0)]
    covered = dist <= _COVER_TOL
    front = ~_behind(B)
    lines = [
        f"{len(B)} exterior-boundary points (farthest of the oracle's samples in each of {na}x{ne} "
        "equal-area direction cells from (0, 0, l1), refined along the ray by IK bisection to 1.25 mm); "
        f"within {_COVER_TOL * 1e3:.0f} mm of a surface: {int(covered.sum())} ({covered.mean():.1%}) ["
        + ", ".join(f"{k}: {int(np.sum(covered & (nearest == k)))}" for k in surfaces)
        + "]",
        f"|azimuth| < 160 deg: {int(covered[front].sum())} of {int(front.sum())} covered; |azimuth| >= 160 "
        f"deg: {int(covered[~front].sum())} of {int((~front).sum())}",
    ]
    fig = None
    if surfaces is BOUNDARY_SURFACES_PRINTED:
        lines += _side_test(ctx)
        fig = _coverage_figure(ctx, B, dist)
    return Row.graded(
        "The exterior workspace boundary consists of f(1) (s(1), th1 in [-160,160], th2 in [-120,95]), f(2) "
        "(th1=160, th3=90, th5=0; th2 in [-100,95], th4 in [0,41]) and f(3) (th1=-160, same, th4 in "
        "[-41,0]).",
        "Sec 3.4.3 (Fig 15)",
        "exterior-boundary points estimated from the oracle (see numbers) vs the surfaces sampled on grids "
        "(KD-tree distance); surface points of f(2), f(3) tested for an unreachable side",
        "\n".join(lines)
        + "\nNote: Sec 3.4.3 lists s(2) with th1 = +160 deg, while Table VI and App. E list s(2) with "
        "th1 = -160 deg (and s(3) with +160).",
        (Measure(f"share of boundary points farther than {_COVER_TOL * 1e3:.0f} mm from every surface",
                 1 - covered.mean(), 0.01),),
        fail=Verdict.DOES_NOT_HOLD,
        id="three_surfaces",
        domain=f"{len(B)} exterior-boundary points, one per equal-area direction cell ({na} x {ne}) around "
        "(0, 0, l1): every direction, behind the arm included",
        figures=(fig,) if fig else (),
        reason="f(1) is the exterior boundary for |azimuth| < 160 deg; behind the arm the boundary is the "
        "corrected Eq 39-41 surface (joint 1 at its limit, wrist stretched, |p - joint 4| = l4 + l5 with "
        "th3, th4 varying), not f(2)/f(3) (th3 = 90 fixed) with the printed ranges, most of whose points "
        "are interior",
    )


def _side_test(ctx) -> list[str]:
    """Do sampled points of the printed f(2), f(3) have an unreachable side (are they boundary points)?"""
    oracle = oracle_for(ctx)
    rng = ctx.rng("surface-sides")
    out = []
    for name in ("f(2)", "f(3)"):
        pts, q = surface_points(name, ctx.n(390, 100), ctx.n(82, 21))
        k = rng.choice(len(pts), size=min(len(pts), ctx.n(300, 40)), replace=False)
        J = iik.position_jacobian(np.column_stack([q[k], np.zeros(len(k))]), ARM)[:, :, :5]
        n0 = np.cross(J[:, :, 1], J[:, :, 3])
        n0 /= np.linalg.norm(n0, axis=1, keepdims=True)
        both = oracle.classify(pts[k] + 2e-3 * n0).reachable & oracle.classify(pts[k] - 2e-3 * n0).reachable
        out.append(
            f"{name}: {int((~both).sum())} of {len(k)} sampled surface points have an unreachable side at 2 "
            f"mm along the surface normal (boundary points); {int(both.sum())} are interior"
        )
    return out


def _coverage_figure(ctx, B, dist) -> str:
    """The boundary points ``B`` (n, 3) [m] by azimuth and height, coloured by ``dist`` [m] to a surface."""
    fig = new_figure(figsize=(7, 3.6))
    ax = fig.add_subplot(111)
    sc = ax.scatter(np.degrees(eq36_printed(B)), B[:, 2], c=np.minimum(dist * 1e3, 100), s=8, cmap="viridis")
    fig.colorbar(sc, ax=ax, label="distance to f(1)-f(3) [mm]")
    ax.axvline(160, color="r", lw=0.8)
    ax.axvline(-160, color="r", lw=0.8)
    ax.set_xlabel("azimuth of the boundary point [deg]")
    ax.set_ylabel("z [m]")
    ax.set_title("true exterior boundary vs the three printed surfaces (Sec 3.4.3)", fontsize=9)
    return ctx.save_figure(fig, "workspace_boundary_vs_surfaces.png", dpi=80)


@per_run
def _core(ctx) -> np.ndarray:
    """Reachability of uniform points in a 0.7 m cube around joint 2."""
    rng = ctx.rng("interior-core")
    m = ctx.n(6000, 600)
    x, y = rng.uniform(-0.35, 0.35, m), rng.uniform(-0.35, 0.35, m)
    core = np.column_stack([x, y, rng.uniform(ARM.l1 - 0.35, ARM.l1 + 0.35, m)])
    return oracle_for(ctx).classify(core).reachable


@SECTION.check(
    42.0,
    forms=Forms(
        printed=0.02,
        good=0.05,
        good_is="points at least 50 mm inside the f(1) sphere",
        slips=(
            Slip(SlipKind.SIGN, "margin -50 mm: points up to 50 mm outside the sphere", -0.05),
            Slip(SlipKind.UNIT, "a margin of -20 read as metres (every test point)", -20.0),
        ),
    ),
)
def no_interior_boundary(ctx, margin):
    """Sec 3.4.3: 'the 6-DOF manipulator does not have interior boundaries' (no void inside the outer one)."""
    tp = _test_points(ctx)
    P, truth = tp.p, tp.truth
    reach = ARM.l3 + ARM.l4 + ARM.l5 - margin
    deep = (np.linalg.norm(P - eq37_printed(eq36_printed(P)), axis=1) <= reach) & ~_behind(P)
    core = _core(ctx)
    n_void = int(np.sum(deep & ~truth)) + int((~core).sum())
    return Row.graded(
        f"{title_of('Claim 3.6')} (no unreachable void inside the exterior boundary).",
        "Sec 3.4.3",
        f"ground-truth reachability of the test points at least {margin * 1e3:.0f} mm inside the f(1) sphere "
        "(|azimuth| < 160 deg) and of a dense cube of points around joint 2 (+-0.35 m), where Fig 12d shows "
        "many singular surfaces",
        f"{int(deep.sum())} test points in the region: {int(np.sum(deep & ~truth))} "
        f"unreachable; {len(core)} points in the core cube: {int((~core).sum())} unreachable",
        (Measure("unreachable points inside the tested region", n_void, 0),),
        fail=Verdict.DOES_NOT_HOLD,
        domain=tp.domain + f"; those at least {margin * 1e3:.0f} mm inside the f(1) sphere, plus "
        f"{len(core)} points in a 0.7 m cube around joint 2",
    )


def radial_projection(p, arm=ARM, *, rear: bool = True) -> np.ndarray:
    """Our reading of App. G's relocation: move an outside point radially onto the Sec 3.4.4 boundary
    (region 1: onto the sphere l3+l4+l5 around joint 2, Eq 38; regions 2/3: onto the sphere l4+l5
    around joint 4, Eq 41 with corrected Eq 39-40). ``rear`` False: onto the region-1 sphere everywhere."""
    p = np.atleast_2d(p).astype(float)
    l1, l2, l3, l4, l5 = arm.lengths
    phi = eq36_printed(p)
    c = eq37_printed(phi, arm)
    R = np.full(len(p), l3 + l4 + l5)
    for region, th1 in ((phi >= arm.upper[0], arm.upper[0]), (phi <= arm.lower[0], arm.lower[0])):
        if rear and region.any():
            c[region] = eq40_corrected(th1, eq39_corrected(p[region], th1, arm=arm), arm=arm)
            R[region] = l4 + l5
    v = p - c
    n = np.linalg.norm(v, axis=1, keepdims=True)
    return np.where(n[:, 0:1] > R[:, None], c + v / n * R[:, None], p)


def _closest(P) -> np.ndarray:
    return iik.closest_reachable(P, ARM).point


def _pushed_out(P) -> np.ndarray:
    r = radial_projection(P)
    return r + 0.005 * (P - r) / np.linalg.norm(P - r, axis=1, keepdims=True)


def app_g_points(rng: np.random.Generator, m: int, arm=ARM) -> np.ndarray:
    """App. G's sample before the workspace test: ``m`` points (m, 3) [m], base frame, 0.5-1.3 m from
    (0, 0, l1) in uniform directions, the first ``m // 2`` turned behind the arm (azimuth 160-200 deg, their
    elevation kept)."""
    d = rng.normal(size=(m, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    back = np.arange(m) < m // 2
    az = rng.uniform(160 * _D, 200 * _D, m)
    d[back, :2] = np.hypot(d[back, 0], d[back, 1])[:, None] * np.column_stack([np.cos(az), np.sin(az)])[back]
    return np.array([0.0, 0.0, arm.l1]) + d * rng.uniform(0.5, 1.3, size=(m, 1))


@per_run
def _outside_points(ctx):
    """Points outside the workspace, half of them behind the arm, and their closest reachable points."""
    P = app_g_points(ctx.rng("app-g"), ctx.n(110, 30))
    P = P[~in_workspace(P, ARM)]
    return P, iik.closest_reachable(P, ARM)


@SECTION.check(
    43.0,
    forms=Forms(
        printed=radial_projection,
        good=_closest,
        good_is="iik.closest_reachable (bounded least squares over the joints)",
        slips=(
            Slip(SlipKind.SIGN, "the projection pushed 5 mm outside instead of onto the boundary",
                _pushed_out),
            Slip(SlipKind.MODEL, "every point projected onto the region-1 sphere "
                 "(regions 2/3 ignored)", partial(radial_projection, rear=False)),
        ),
    ),
)
def app_g_relocation(ctx, relocate):
    """App. G: a point outside the workspace is relocated 'at the closest position inside'."""
    P, closest = _outside_points(ctx)
    R = relocate(P)
    d_rel = np.linalg.norm(R - P, axis=1)
    inward = R + 1e-4 * (R - P) / np.maximum(d_rel[:, None], 1e-12)  # 0.1 mm back inside, off the boundary
    ok = oracle_for(ctx).classify(inward).reachable
    extra = d_rel - closest.distance
    r23 = _behind(P)
    fk_err = np.abs(iik.fk(closest.q, ARM)[:, :3, 3] - closest.point).max()
    return Row.graded(
        "A point outside the workspace is relocated to the closest position inside it.",
        "App. G (Figs 61-62), Sec 3.6.1",
        "the relocation (our reading of the thesis's: radial projection onto the Sec 3.4.4 boundary, Eq 38 / "
        "corrected Eq 41) vs iik.closest_reachable (bounded LM over joints 1-5 from 36 starts + trust-region "
        "polish; its point is fk(q) of a q inside Table I); reachability of the relocated point (0.1 mm back "
        "inside) by the IK oracle",
        f"{len(P)} points outside the workspace ({int(r23.sum())} at |azimuth| >= 160 deg): relocated point "
        f"reachable for {ok.mean():.1%}; | |relocation - p| - |closest - p| |: region 1 max "
        f"{np.abs(extra[~r23]).max() * 1e3:.4f} mm, regions 2/3 max {np.abs(extra[r23]).max() * 1e3:.4f} mm; "
        f"iik.closest_reachable: max |fk(q) - point| = {fk_err:.1e} m",
        (
            Measure("share of relocated points that are unreachable", 1 - ok.mean(), 0.0),
            Measure("max |relocation distance - closest distance|", np.abs(extra).max(), 1e-3, "m"),
        ),
        fail=Verdict.NOT_REPRODUCED,
        holds_as=Verdict.RECONSTRUCTION,
        id="app_g",
        reason="the relocation is not the closest reachable point",
        basis="the relocation rule is our reading: the thesis shows only its result (Figs 61-62), not how it "
        "relocates; graded is the radial projection onto the Sec 3.4.4 boundary (Eq 38 / corrected Eq 41)",
        domain=f"{len(P)} points outside the workspace (the test of Sec 3.4.4), 0.5-1.3 m from (0, 0, l1), "
        "half of them behind the arm (azimuth 160-200 deg)",
    )
