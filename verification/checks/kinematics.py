"""Checks of the thesis kinematics: Tables I-II, Eq 1, Eq 4, Eq 34-35, Appendix B, Appendix C, Eq 42.

Every formula is transcribed *as printed* below (symbols as in the thesis: ``c1 = cos(theta1)``,
``s45 = sin(theta4 + theta5)``, ...; where the report shows the printed text, the text itself is
evaluated, :func:`verification.shorthand.evaluate`) and measured against ground truth: Pinocchio on
``urdf/thesis_arm.urdf``, the generic DH product, central finite differences,
``scipy.spatial.transform.Rotation``. Each check takes the form it measures as an argument and declares a
known-good and a list of realistic slips (:class:`verification.registry.Forms`), so the self-test can show
that its verdict follows the measurement. Every erratum is re-derived by a second reading
(:mod:`verification.second_reading`): the link matrices from Craig's formula under each
nearby reading of their DH row, the Euler matrix from elementary rotations in every
convention.
"""

from __future__ import annotations

from dataclasses import replace
from functools import partial, reduce
from itertools import product

import numpy as np
import pinocchio as pin
from scipy.optimize import minimize
from scipy.spatial.transform import Rotation

from iik.arm import THESIS_ARM, thesis_arm
from iik.dh import DHRow, DHTable, dh_chain, dh_link_transform
from iik.kinematics import fk, jacobian, joint_frames, position_jacobian
from iik.planning.output import draw_arm_bodies
from iik.resources import urdf_path
from iik.rotations import rotation_angle
from iik.urdf import thesis_urdf, urdf_from_dh

from ..assumptions import EXACT_GEOMETRY
from ..formula import Formula, Points, per_run
from ..numbers import fmt_q, worst
from ..oracles.pinocchio_model import joint_placements, thesis_model, tool_jacobians, tool_poses
from ..oracles.ur5 import UR5_BASE, UR5_TOOL, solve_base_tool, ur5_fk_pair
from ..plotting import draw_arm, draw_collision, draw_scene, new_figure
from ..registry import (
    Erratum,
    Forms,
    Measure,
    Row,
    Scope,
    Section,
    Slip,
    SlipKind,
    Verdict,
    epsilon,
    off_by,
)
from ..second_reading import Kind, Reading, choices, moved_entries, search, sign_typos
from ..shorthand import cos_sin, evaluate, matrix
from ..testing.strategies import BEYOND, sample_joints

TOL_EXACT = 1e-12  # [m] and [-]: closed forms vs Pinocchio
#: The sampled domain of the full-range kinematics rows.
_JOINT_DOMAIN = (
    "{n} q: uniform in Table I widened by " + str(BEYOND) + " rad on every joint (the whole range and past "
    "it), plus in full runs the 729 corners {{lower, 0, upper}}^6 where the trigonometric signs flip"
)
TOL_FD = 1e-7  # [m/rad]: vs central finite differences (h = 1e-6)
_DEG = np.pi / 180
#: The joint vector [rad] used as counterexample where any generic q would do.
Q_COUNTEREXAMPLE = np.array([0.3, -0.4, 0.5, 0.6, -0.7, 0.8])
SECTION = Section(
    "Kinematics (Tables I-II, Eq 1, Eq 4, Eq 34-35, App. B, App. C, Eq 42)", depends_on=EXACT_GEOMETRY,
    order=10.0,
)


def _symbols(q, arm=THESIS_ARM) -> dict:
    """The thesis's shorthand at joint vectors ``q`` (..., 6) [rad]: ``c1 .. c6``, ``s1 .. s6``, ``c45``,
    ``s45`` (of theta4 + theta5), and ``arm``'s link lengths ``l1 .. l5`` [m]."""
    q = np.asarray(q, float)
    out = dict(zip(("l1", "l2", "l3", "l4", "l5"), arm.lengths, strict=True))
    for i in range(6):
        out[f"c{i + 1}"], out[f"s{i + 1}"] = cos_sin(q[..., i])
    out["c45"], out["s45"] = cos_sin(q[..., 3] + q[..., 4])
    return out


# ----------------------------------------------------------------------------- printed forms

#: Table II as printed: (alpha_{i-1} [deg], a_{i-1}, d_i, theta_i offset [deg]), lengths symbolic.
TABLE_II_PRINTED = (
    (0.0, "0", "l1", 0.0),
    (-90.0, "l2", "0", -90.0),
    (-90.0, "0", "l3", 0.0),
    (-90.0, "0", "0", -90.0),
    (0.0, "l4", "0", +90.0),
    (-90.0, "0", "-l5", 0.0),
)
#: Table I as printed [deg].
TABLE_I_PRINTED = ((-160, 160), (-120, 95), (-160, 160), (-119, 119), (-119, 119), (-180, 180))


def table_ii_printed(arm=THESIS_ARM) -> DHTable:
    """Table II as printed (modified DH), with the arm's lengths substituted."""
    L = dict(zip(("l1", "l2", "l3", "l4", "l5"), arm.lengths, strict=True))
    rows = tuple(
        DHRow(alpha=al * _DEG, a=float(evaluate(a, L)), d=float(evaluate(d, L)), offset=off * _DEG)
        for al, a, d, off in TABLE_II_PRINTED
    )
    lower = tuple(lo * _DEG for lo, _ in TABLE_I_PRINTED)
    upper = tuple(hi * _DEG for _, hi in TABLE_I_PRINTED)
    return DHTable(rows=rows, convention="modified", lower=lower, upper=upper, velocity=(1.0,) * 6)


#: Eq 4 as printed: the rows of 0_6T, entry by entry.
EQ4_TEXT = (
    (
        "c6 (c45 (s1 s3 + c1 s2 c3) - s45 c1 c2) - s6 (s1 c3 - c1 s2 s3)",
        "-s6 (c45 (s1 s3 + c1 s2 c3) - s45 c1 c2) - c6 (c3 s1 - c1 s2 s3)",
        "-s45 (s1 s3 + c1 s2 c3) - c45 c1 c2",
        "l2 c1 + l3 c1 c2 + (l5 s45 + l4 s4)(s1 s3 + c1 s2 c3) + (l5 c45 + l4 c4)(c1 c2)",
    ),
    (
        "s6 (c1 c3 + s1 s2 s3) - c6 (c45 (c1 s3 - s1 s2 c3) + s45 s1 c2)",
        "s6 (c45 (c1 s3 - s1 s2 c3) + s45 s1 c2) + c6 (c1 c3 + s1 s2 s3)",
        "s45 (c1 s3 - s1 s2 c3) - c45 s1 c2",
        "l2 s1 + l3 s1 c2 - (l5 s45 + l4 s4)(c1 s3 - s1 s2 c3) + (l5 c45 + l4 c4)(s1 c2)",
    ),
    (
        "c6 (s45 s2 + c45 c2 c3) + c2 s3 s6",
        "c2 s3 c6 - s6 (s45 s2 + c45 c2 c3)",
        "c45 s2 - s45 c2 c3",
        "l5 (s45 c2 c3 - c45 s2) + l4 (c2 c3 s4 - c4 s2) - l3 s2 + l1",
    ),
    ("0", "0", "0", "1"),
)


def eq4_printed(q, arm=THESIS_ARM, text=EQ4_TEXT) -> np.ndarray:
    """Eq 4 exactly as printed (``text``; another text for a slip) -> (n, 4, 4)."""
    return matrix(text, _symbols(np.atleast_2d(q), arm))


#: Appendix C entries (Eq 56) as printed.
APPC_TEXT = {
    "df1/dth1": "-l2 s1 - l3 s1 c2 + (l5 s45 + l4 s4)(c1 s3 - s1 s2 c3) - (l5 c45 + l4 c4)(s1 c2)",
    "df1/dth2": "-l3 c1 s2 + (l5 s45 + l4 s4)(c1 c2 c3) - (l5 c45 + l4 c4)(c1 s2)",
    "df1/dth3": "(l5 s45 + l4 s4)(s1 c3 - c1 s2 s3)",
    "df1/dth4": "(l5 c45 + l4 c4)(s1 s3 + c1 s2 c3) - (l5 s45 + l4 s4)(c1 c2)",
    "df1/dth5": "(l5 c45)(s1 s3 + c1 s2 c3) - l5 c1 c2 s45",
    "df2/dth1": "l2 c1 + l3 c1 c2 + (l5 s45 + l4 s4)(s1 s3 + c1 s2 c3) + (l5 c45 + l4 c4)(c1 c2)",
    "df2/dth2": "-l3 s1 s2 + (l5 s45 + l4 s4)(s1 c2 c3) - (l5 c45 + l4 c4)(s1 s2)",
    "df2/dth3": "-(l5 s45 + l4 s4)(c1 c3 + s1 s2 s3)",
    "df2/dth4": "-(l5 c45 + l4 c4)(c1 s3 - s1 s2 c3) - (l5 s45 + l4 s4)(s1 c2)",
    "df2/dth5": "-(l5 c45)(c1 s3 - s1 s2 c3) - l5 s1 c2 s45",
    "df3/dth1": "0",
    "df3/dth2": "-l5 (s45 s2 c3 + c45 c2) - l4 (s2 c3 s4 + c4 c2) - l3 c2",
    "df3/dth3": "-l5 s45 c2 s3 - l4 c2 s3 s4",
    "df3/dth4": "l5 (c45 c2 c3 + s45 s2) + l4 (c2 c3 c4 + s4 s2)",
    "df3/dth5": "l5 (c45 c2 c3 + s45 s2)",
}


def appc_printed(q, arm=THESIS_ARM) -> dict[str, np.ndarray]:
    """The 15 entries of Appendix C (Eq 56) exactly as printed (:data:`APPC_TEXT`), keyed ``"df1/dth1"``
    ..., each (n,) [m/rad]."""
    q = np.atleast_2d(q)
    S = _symbols(q, arm)
    return {k: evaluate(t, S) + np.zeros(len(q)) for k, t in APPC_TEXT.items()}


def eq55_printed(q, arm=THESIS_ARM) -> np.ndarray:
    """Eq 55 (App. C), = Eq 34a-c: the position vector G_theta = [f1, f2, f3] as printed -> (n, 3) [m].

    App. C prints f1, f2, f3 letter for letter as p_x, p_y, p_z of Eq 4 (and as Eq 34a-c), so the
    transcription is that of Eq 4."""
    return eq4_printed(q, arm)[..., :3, 3]


#: Printed text of the Appendix B (modified set) matrices, rows separated by ';'.
APPB_TEXT = (
    "0_1T = [c1 -s1 0 0; s1 c1 0 0; 0 0 1 l1; 0 0 0 1]",
    "1_2T = [s2 c2 0 l2; 0 0 1 0; c2 -s2 0 0; 0 0 0 1] (read from garbled text)",
    "2_3T = [c3 -s3 0 0; 0 0 1 l3; -s3 c3 0 0; 0 0 0 1]",
    "3_4T = [s4 c4 0 0; 0 0 1 0; c4 -s4 0 0; 0 0 0 1] (read from garbled text)",
    "4_5T = [-s5 -c5 0 l4; c5 -s5 0 0; 0 0 1 0; 0 0 0 1]",
    "5_6T = [c6 -s6 0 0; 0 0 1 l5; -s6 c6 0 0; 0 0 0 1]",
)
#: The corrected matrices: 2_3T and 5_6T fixed, the others as printed.
APPB_CORRECTED = tuple({2: "2_3T = [c3 -s3 0 0; 0 0 1 l3; -s3 -c3 0 0; 0 0 0 1]",
                        5: "5_6T = [c6 -s6 0 0; 0 0 1 -l5; -s6 -c6 0 0; 0 0 0 1]"}.get(
    i, t.removesuffix(" (read from garbled text)")) for i, t in enumerate(APPB_TEXT))


def appb_modified_printed(q, arm=THESIS_ARM) -> list[np.ndarray]:
    """Appendix B, second set ("modified transformations", home = Fig 8), as printed (:data:`APPB_TEXT`).

    The extracted text is garbled for 1_2T and 3_4T (matrix rows split over lines and
    the bracket layout broken); they are read row by row in the only order that gives
    a 4x4 matrix. 0_1T, 2_3T, 4_5T and 5_6T are cleanly printed.
    """
    return [matrix(t, _symbols(q, arm)) for t in APPB_TEXT]


#: Eq 42 as printed (r21 as printed).
EQ42_TEXT = (
    ("ca cb cg - sa sg", "-ca cb sg - sa cg", "ca sb"),
    ("ca cb cg - ca sg", "-sa cb sg + ca cg", "sa sb"),
    ("-sb cg", "sb sg", "cb"),
)


def eq42_printed(alpha, beta, gamma) -> np.ndarray:
    """Eq 42 exactly as printed -> (3, 3) (or (n, 3, 3) for arrays)."""
    return matrix(EQ42_TEXT, dict(zip(("ca", "sa", "cb", "sb", "cg", "sg"), cos_sin(alpha, beta, gamma),
                                      strict=True)))


# ----------------------------------------------------------------------------- known-good and perturbed forms


def eq4_from_table_ii(q, arm=THESIS_ARM) -> np.ndarray:
    """Known-good Eq 4: the modified-DH product of Table II (iik.dh) -> (n, 4, 4)."""
    return dh_chain(table_ii_printed(arm), np.atleast_2d(q))


def _with_lengths(**lengths):
    """THESIS_ARM with some link lengths replaced (a wrong-link-length slip)."""
    t = THESIS_ARM.thesis_lengths
    vals = {k: lengths.get(k, getattr(t, k)) for k in ("l1", "l2", "l3", "l4", "l5")}
    return thesis_arm(**vals, lower=THESIS_ARM.lower, upper=THESIS_ARM.upper, name="slipped lengths")


#: Eq 4 with its -l3 s2 term in p_z written +l3 s2 (a slip).
_EQ4_PZ_SIGN = tuple(tuple(e.replace("- l3 s2", "+ l3 s2") for e in row) for row in EQ4_TEXT)


def rotation_transposed(T: np.ndarray) -> np.ndarray:
    """(..., 4, 4) poses with their rotation blocks transposed (a slip)."""
    T = np.array(T, dtype=float, copy=True)
    T[..., :3, :3] = np.swapaxes(T[..., :3, :3], -1, -2)
    return T


def _transposed_rotation(f):
    """``f`` with the rotation block of its (..., 4, 4) output transposed (a slip)."""
    return lambda q, arm=THESIS_ARM: rotation_transposed(f(q, arm))


def appb_from_table_ii(q, arm=THESIS_ARM) -> list[np.ndarray]:
    """Known-good App. B (home-pose set): Craig's link formula on each Table II row."""
    table = table_ii_printed(arm)
    return [dh_link_transform(table.rows[i], np.array([q[i]]), "modified")[0] for i in range(6)]


def appb_first_printed(qs, arm=THESIS_ARM) -> tuple[np.ndarray, np.ndarray]:
    """The legible part of App. B's first set as printed: 0_1T (n, 4, 4), printed as in the second set,
    and rows 1-2 of the rotation of 1_2T ('c2 -s2 0', '0 0 1') (n, 2, 3)."""
    return matrix(APPB_TEXT[0], _symbols(qs, arm)), matrix("[c2 -s2 0; 0 0 1]", _symbols(qs, arm))


def appb_first_from_dh(qs, arm=THESIS_ARM) -> tuple[np.ndarray, np.ndarray]:
    """Known-good: the same entries from Table II rows 1-2 without the home offsets."""
    r1, r2 = (replace(r, offset=0.0) for r in table_ii_printed(arm).rows[:2])
    return dh_link_transform(r1, qs[:, 0], "modified"), dh_link_transform(r2, qs[:, 1], "modified")[:, :2, :3]


def appc_from_iik(q, arm=THESIS_ARM) -> dict[str, np.ndarray]:
    """Known-good App. C entries: iik.position_jacobian (the corrected analytic Jacobian)."""
    J = position_jacobian(np.atleast_2d(q), arm)[..., :5]
    return {f"df{i + 1}/dth{j + 1}": J[:, i, j] for i in range(3) for j in range(5)}


#: Eq 34 / Eq 55 as printed: the joints each coordinate function takes (1-based).
EQ34_ARGUMENTS = {"f1": (1, 2, 3, 4, 5), "f2": (1, 2, 3, 4, 5), "f3": (2, 3, 4, 5)}


def _axis_rotation(axis: str, t: np.ndarray) -> np.ndarray:
    """Elementary rotation(s) about ``axis`` ("x", "y" or "z") by ``t`` [rad] -> (n, 3, 3)."""
    c, s = np.cos(t), np.sin(t)
    z, o = np.zeros_like(t), np.ones_like(t)
    m = {
        "x": ((o, z, z), (z, c, -s), (z, s, c)),
        "y": ((c, z, s), (z, o, z), (-s, z, c)),
        "z": ((c, -s, z), (s, c, z), (z, z, o)),
    }[axis]
    return np.stack([np.stack(r, -1) for r in m], -2)


#: Every Euler convention: the 12 axis sequences, intrinsic (R = R1 R2 R3) and extrinsic (R = R3 R2 R1).
EULER_SEQUENCES = tuple(a + b + c for a in "xyz" for b in "xyz" for c in "xyz" if a != b and b != c)


def euler_matrix(seq: str, intrinsic: bool, a, b, g) -> np.ndarray:
    """The rotation of angles (a, b, g) about the axes ``seq`` (e.g. "zyz"), composed from elementary
    rotations (not scipy): intrinsic R = R1(a) R2(b) R3(g), extrinsic R = R3(g) R2(b) R1(a)."""
    R1, R2, R3 = (_axis_rotation(ax, np.asarray(t, float)) for ax, t in zip(seq, (a, b, g), strict=True))
    return R1 @ R2 @ R3 if intrinsic else R3 @ R2 @ R1


#: Known-good Eq 42: Craig's Z-Y-Z matrix Rz(alpha) Ry(beta) Rz(gamma) (the printed one, r21 fixed).
eq42_zyz = partial(euler_matrix, "zyz", True)
#: The Z-X-Z matrix R = Rz(alpha) Rx(beta) Rz(gamma).
eq42_zxz = partial(euler_matrix, "zxz", True)


# ----------------------------------------------------------------------------- ground truth


def _fd_tool_point(qs: np.ndarray, step: np.ndarray, h: float = 1e-6) -> np.ndarray:
    """Central difference of the Pinocchio tool point along the joint direction ``step`` (6,) or (n, 6),
    (n, 3) [m/rad]."""
    return (tool_poses(qs + h * step)[:, :3, 3] - tool_poses(qs - h * step)[:, :3, 3]) / (2 * h)


def _fd_position_jacobian(qs: np.ndarray) -> np.ndarray:
    """Central differences (h = 1e-6 rad) of the Pinocchio tool point, (n, 3, 6) [m/rad]."""
    return np.stack([_fd_tool_point(qs, e) for e in np.eye(6)], -1)


def _samples(ctx, salt: str, full: int, quick: int) -> np.ndarray:
    """Uniform q in Table I widened by BEYOND, plus (full runs) the 3^6 = 729 corners {lower, 0, upper} of
    Table I (exact limits, where signs flip)."""
    corners = product(*zip(THESIS_ARM.q_min, np.zeros(6), THESIS_ARM.q_max, strict=True))
    qs = sample_joints(ctx.rng(salt), ctx.n(full, quick))
    return qs if ctx.quick else np.concatenate([qs, np.array(list(corners))])


def _joint_row(qs, claim: str, reference: str, method: str, *measures: Measure, **fields) -> Row:
    """A row graded on ``measures`` over the joint sample ``qs`` (:func:`_samples`), numbers from them."""
    return Row.graded(claim, reference, method, None, measures, domain=_JOINT_DOMAIN.format(n=len(qs)),
                      **fields)


@per_run
def _truth_poses(ctx, salt, full, quick):
    """(q, Pinocchio tool poses) for a sample."""
    qs = _samples(ctx, salt, full, quick)
    return qs, tool_poses(qs)


@per_run
def _jacobians(ctx):
    """On the App. C sample: Pinocchio's frame Jacobians (n, 6, 6) and the central differences of the tool
    point (n, 3, 6) [m/rad]."""
    qs = _samples(ctx, "appc", 3000, 200)
    return tool_jacobians(qs), _fd_position_jacobian(qs)


def _hist(ctx, name, series, xlabel, title):
    """Histograms of log10 of error series (``[(legend, values)]``, floored at 1e-19) as figures/name."""
    fig = new_figure(figsize=(6.4, 3.6))
    ax = fig.add_subplot()
    for label, v in series:
        ax.hist(np.log10(np.maximum(np.asarray(v), 1e-19)), bins=40, alpha=0.6, label=label)
    ax.set(xlabel=xlabel, ylabel="count", title=title)
    ax.legend(fontsize=8)
    return ctx.save_figure(fig, name, dpi=90)


def _bars(ctx, name, labels, series, ylabel, title, *, floor=1e-19, figsize=(7.5, 3.4), **ticks) -> str:
    """Two error series per label (``[(legend, values)] * 2``) as log-scale bars, saved as figures/name."""
    fig = new_figure(figsize=figsize)
    ax = fig.add_subplot()
    x = np.arange(len(labels))
    for k, (label, v) in enumerate(series):
        ax.bar(x + (k - 0.5) * 0.4, np.maximum(v, floor), 0.4, label=label)
    ax.set(yscale="log", ylabel=ylabel, title=title)
    ax.set_xticks(x, labels, **ticks)
    ax.legend(fontsize=8)
    return ctx.save_figure(fig, name)


#: The axis labels of a 3-D figure in base frame 0.
_XYZ_M = {"xlabel": "x [m]", "ylabel": "y [m]", "zlabel": "z [m]"}


# ----------------------------------------------------------------------------- checks


@SECTION.check(
    10.0,
    by_construction="a transcription round trip: the printed Tables I and II "
    "are compared with what the project encodes from them",
    depends_on=("text",),
)
def table_ii_encoding(ctx):
    """Table II and Table I as printed vs what iik.THESIS_ARM and the URDF encode."""
    printed = table_ii_printed()
    d_rows = max(abs(getattr(a, k) - getattr(b, k)) for a, b in zip(printed.rows, THESIS_ARM.dh_table().rows,
                 strict=True) for k in ("alpha", "a", "d", "offset"))
    tm = thesis_model(THESIS_ARM)
    d_lim = np.abs(np.concatenate([tm.model.lowerPositionLimit - printed.lower,
                                   tm.model.upperPositionLimit - printed.upper])).max()
    revolute = [tm.model.joints[i].shortname() for i in range(1, tm.model.njoints)]
    ok_types = all(t.startswith("JointModelR") for t in revolute) and tm.model.nq == 6
    m_lim = Measure("max |printed - URDF| limit", d_lim, 1e-15, "rad")
    return [
        Row.graded(
            "The DH parameters of the arm are those of Table II (modified DH, offsets -90, -90, +90 deg on "
            "joints 2, 4, 5; d6 = -l5).",
            "Table II",
            "Printed table transcribed symbolically, lengths substituted, compared field by field with "
            "iik.THESIS_ARM.dh_table()",
            None,
            (Measure("max |printed - encoded| DH field", d_rows, 0.0, "rad or m"),),
            fail=Verdict.DOES_NOT_HOLD,
            holds_as=Verdict.IDENTITY,
            basis="a transcription round trip: the project encodes Table II; comparing the encoding with "
            "the transcription shows the data entry, not that Table II describes the arm (Eq 4 and App. B "
            "test that)",
            domain="the six printed rows (alpha, a, d, offset)",
            id="table_ii",
        ),
        Row(
            "Joint limits are those of Table I.",
            "Table I",
            "urdf/thesis_arm.urdf loaded by Pinocchio; lower/upper position limits vs the printed "
            "degrees converted to rad; joint types",
            f"max |limit difference| = {d_lim:.1e} rad; {tm.model.nq} joints, types {sorted(set(revolute))}",
            Verdict.IDENTITY if (m_lim.holds and ok_types) else Verdict.DOES_NOT_HOLD,
            id="table_i",
            measures=(m_lim,),
            basis="a transcription round trip: the URDF's limits are generated from Table I",
            domain="the six printed limit pairs",
        ),
    ]


@SECTION.check(
    11.0,
    by_construction="a byte comparison of the shipped URDF with the generator output",
    depends_on=("collision-shapes",),
)
def urdf_is_generated(ctx):
    """The committed URDF is the generator's output (and a picture of its assumed shapes)."""
    committed = urdf_path().read_text(encoding="utf-8")
    same = committed == thesis_urdf(THESIS_ARM)
    tm = thesis_model(THESIS_ARM)
    fig = new_figure(figsize=(11, 5.6))
    for k, q in enumerate((np.zeros(6), np.array([0.5, -0.6, 0.4, 1.1, 0.7, 0.3]))):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        draw_collision(ax, tm.model, tm.collision_model, q)
        draw_arm(ax, q, color="k", lw=1, markersize=2, label="frame origins (Table II)")
        ax.set(xlim=(-0.2, 1.0), ylim=(-0.5, 0.5), zlim=(0.0, 1.0), **_XYZ_M)
        ax.set_box_aspect((1.2, 1.0, 1.0))  # equal scales: the limits' spans
        ax.view_init(elev=20, azim=-60)
        ax.set_title(("home pose (Fig 8)" if k == 0 else fmt_q(q)), fontsize=7)
    fig.legend(*ax.get_legend_handles_labels(), loc="lower center", ncol=8, fontsize=7)  # the links' shapes
    fig.suptitle(
        "Assumed PowerCube collision shapes of urdf/thesis_arm.urdf (one colour per link); base frame 0, "
        "x/y/z [m]",
        fontsize=9,
    )
    frel = ctx.save_figure(fig, "collision_geometry.png")
    return Row(
        "(Project) urdf/thesis_arm.urdf is the output of iik.urdf.thesis_urdf() (Table I, Table II, "
        "speeds, efforts, collision shapes).",
        "iik.urdf (Table I, Table II)",
        "Byte comparison of the shipped file with the generator output",
        f"{len(committed)} bytes, identical: {same}",
        Verdict.IDENTITY if same else Verdict.DOES_NOT_HOLD,
        figures=(frel,),
        id="urdf",
        scope=Scope.PROJECT,
        basis="a byte comparison of our file with our generator's output",
        domain="the committed file",
    )


@SECTION.check(
    "Eq 4",
    forms=Forms(
        printed=eq4_printed,
        good=eq4_from_table_ii,
        good_is="the modified-DH product of Table II (iik.dh)",
        slips=(
            Slip(SlipKind.SIGN, "p_z with -l3 s2 written +l3 s2", partial(eq4_printed, text=_EQ4_PZ_SIGN)),
            Slip(SlipKind.LENGTH, "l4 written for l5",
                 lambda q, arm=THESIS_ARM: eq4_printed(q, _with_lengths(l5=arm.l4))),
            Slip(SlipKind.TRANSPOSE, "the rotation block transposed", _transposed_rotation(eq4_printed)),
        ),
        tolerance=epsilon(eq4_printed, 1e-9, "Eq 4 with p_z moved by 1 nm", (2, 3)),
    ),
)
def eq4_vs_pinocchio(ctx, eq4):
    """Eq 4 (the form) vs Pinocchio FK of the URDF."""
    qs, T_pin = _truth_poses(ctx, "eq4", 20000, 400)
    T = eq4(qs)
    dp = np.linalg.norm(T[:, :3, 3] - T_pin[:, :3, 3], axis=1)
    dR = np.abs(T[:, :3, :3] - T_pin[:, :3, :3]).max(axis=(1, 2))
    dp_w, k = worst(dp)
    figs = (_hist(ctx, "eq4_errors.png", [("Eq 4 printed |dp|", dp), ("Eq 4 printed max |dR_ij|", dR)],
                  "log10 error vs Pinocchio [m or -]", f"Eq 4 vs Pinocchio, {len(qs)} q"),
            _arm_figure(ctx)) if eq4 is eq4_printed else ()
    return _joint_row(
        qs, "Eq 4 gives the pose of frame 6 (position of the end-effector point and orientation).",
        "Eq 4 (with Table II, Fig 8)", "Eq 4 transcribed as printed vs Pinocchio framesForwardKinematics of "
        "urdf/thesis_arm.urdf (frame 'tool')", Measure("max |dp| vs Pinocchio", dp.max(), TOL_EXACT, "m"),
        Measure("max |dR_ij| vs Pinocchio", dR.max(), TOL_EXACT), id="eq4", figures=figs,
        erratum=Erratum("Eq 4", "the printed entries", "the Table II product (iik.fk)",
                        f"{fmt_q(qs[k])}: position off by {dp_w:.3g} m"),
    )


def _arm_figure(ctx) -> str:
    """The arm at 4 poses over the scene (a figure of the Eq 4 row)."""
    f2 = new_figure(figsize=(6.4, 5.6))
    ax = f2.add_subplot(projection="3d")
    draw_scene(ax)
    poses = np.array(
        [
            np.zeros(6),
            [0.6, -0.5, 0.3, 0.9, -0.4, 0.0],
            [-1.2, 0.4, -0.6, 1.3, 0.8, 0.0],
            [2.2, -1.0, 1.0, -0.5, 1.2, 0.0],
        ]
    )
    for k, q in enumerate(poses):
        draw_arm_bodies(ax, q, colour=f"C{k}", alpha=0.25, arm=THESIS_ARM)
        draw_arm(ax, q, color=f"C{k}", label=fmt_q(q[:5]).replace(" rad", ""), markersize=3)
        ax.scatter(*tool_poses(q[None])[0, :3, 3], marker="x", color="k", s=40)
    ax.set(**_XYZ_M)
    ax.set_title(
        "The arm at 4 poses: URDF collision shapes, Table II frame origins (dots), x = Pinocchio tool "
        "point;\nplatform and floor (iik.scene); base frame 0, x/y/z [m], equal scales",
        fontsize=8,
    )
    ax.legend(fontsize=6, loc="upper left")
    return ctx.save_figure(f2, "arm_poses.png")


def _table_edit(k: int, table: DHTable | None = None, **change) -> DHTable:
    """``table`` (default: Table II as printed) with row ``k`` (0-based) changed."""
    t = table_ii_printed() if table is None else table
    rows = list(t.rows)
    rows[k] = replace(rows[k], **change)
    return replace(t, rows=tuple(rows))


def _table_offsets_shifted() -> DHTable:
    """Table II with the joint offsets one row down (joint 2's -90 deg given to joint 3, ...)."""
    t = table_ii_printed()
    offs = [0.0] + [r.offset for r in t.rows][:-1]
    return replace(t, rows=tuple(replace(r, offset=o) for r, o in zip(t.rows, offs, strict=True)))


#: Table II with a1 = l2 + 1 nm (the tolerance test).
TABLE_NUDGED = _table_edit(1, a=THESIS_ARM.l2 + 1e-9)


@SECTION.check(
    "Eq 1",
    forms=Forms(
        printed=table_ii_printed(),
        good=THESIS_ARM.dh_table(),
        good_is="the project's encoding of Table II (iik.THESIS_ARM.dh_table())",
        slips=(
            Slip(SlipKind.SIGN, "d6 = +l5", _table_edit(5, d=THESIS_ARM.l5)),
            Slip(SlipKind.OFF_BY_ONE, "the joint offsets one row down", _table_offsets_shifted()),
            Slip(SlipKind.UNIT, "joint 2's offset -90 taken as rad", _table_edit(1, offset=-90.0)),
        ),
        tolerance=Slip(SlipKind.EPSILON, "Table II with a1 = l2 + 1 nm", TABLE_NUDGED),
    ),
)
def table_ii_vs_eq4(ctx, table):
    """Eq 1 with Table II: the product of the link transforms vs Eq 4 as printed and vs Pinocchio."""
    qs, T_pin = _truth_poses(ctx, "eq4", 20000, 400)
    T = dh_chain(table, qs)
    return _joint_row(
        qs, "Eq 4 is the product 0_1T ... 5_6T (Eq 1) of the Table II link transforms.",
        "Eq 1, Table II, Eq 4",
        "Modified-DH product (Craig) of the printed Table II vs Eq 4 as printed and vs Pinocchio (m for p, - "
        "for R)", Measure("max |T_TableII - T_Eq4|", np.abs(T - eq4_printed(qs)).max(), TOL_EXACT),
        Measure("max |T_TableII - T_Pinocchio|", np.abs(T - T_pin).max(), TOL_EXACT),
        fail=Verdict.DOES_NOT_HOLD, id="table_ii_product",
    )


_APPB_WHAT = {
    2: "entry (3,2) has the wrong sign: with alpha2 = -90 deg it is -c3 (the printed rotation block "
    "is not orthonormal: det = s3^2 - c3^2)",
    5: "entry (2,4) is +l5 but Table II has d6 = -l5 (so it must be -l5, as Eq 4 also requires), "
    "and entry (3,2) has the wrong sign (-c6), as in 2_3T",
}


def appb_reading(i: int, printed: np.ndarray, qs: np.ndarray, text: str = ""):
    """Second reading of App. B's link matrix ``i`` (0-based; ``printed`` (n, 4, 4) at ``qs``): Craig's
    formula on Table II row i+1 under each nearby reading of the row (the twist's sign, the offset d's
    sign, the joint angle's sign, the standard convention, the rotation transposed) and of the printed
    matrix (an entry in the neighbouring row of its column, an entry's sign flipped)."""
    row = table_ii_printed().rows[i]
    theta = qs[:, i]
    stated = {"alpha": row.alpha, "d": row.d, "a": row.a, "sign": 1.0, "convention": "modified",
              "transpose": False, "P": printed}

    def misfit(x) -> float:
        T = dh_link_transform(DHRow(x["alpha"], x["a"], x["d"], row.offset), x["sign"] * theta,
            x["convention"])
        return float(np.abs(x["P"] - (rotation_transposed(T) if x["transpose"] else T)).max())

    flipped = {"alpha": f"alpha{i} = {np.degrees(-row.alpha):+.0f} deg", "d": f"d{i + 1} = {-row.d:+.3f} m",
               "a": f"a{i} = {-row.a:+.3f} m"}
    readings = [
        *(Reading(Kind.SIGN, text, {k: -getattr(row, k)}) for k, text in flipped.items() if getattr(row, k)),
        Reading(Kind.SIGN, f"theta{i + 1} measured the other way", {"sign": -1.0}),
        *choices(Kind.CONVENTION, "convention", {"standard DH (Rz Tz Tx Rx)": "standard"}),
        *choices(Kind.SWAP, "transpose", {"the rotation transposed (row vs column vectors)": True}),
        *moved_entries("P", printed),
        *sign_typos("P", printed),
    ]
    return search(stated, readings, misfit, TOL_EXACT, printed=text or APPB_TEXT[i],
                  stated_text=f"Table II row {i + 1} (alpha{i} = {np.degrees(row.alpha):.0f} deg, a{i} = "
                  f"{row.a:.3f} m, d{i + 1} = {row.d:.3f} m, offset {np.degrees(row.offset):.0f} deg), "
                  "modified DH",
                  route="Craig's modified-DH link formula (iik.dh.dh_link_transform) on the Table II row, "
                  "not Pinocchio", measure="max |printed - re-derived| entry over the sampled q")


def appb_product_reading(printed: np.ndarray, qs: np.ndarray):
    """Second reading of the product of App. B's matrices (``printed`` (n, 6, 4, 4)) as Eq 4: the Table II
    chain under each nearby reading (d6's sign, a twist's sign, the rotation transposed, the factors in
    reverse order)."""
    base = table_ii_printed()
    stated = {"d6": base.rows[5].d, "alpha2": base.rows[2].alpha, "order": "forward", "transpose": False}

    def misfit(x) -> float:
        truth = dh_chain(_table_edit(2, _table_edit(5, base, d=x["d6"]), alpha=x["alpha2"]), qs)
        mats = printed if x["order"] == "forward" else printed[:, ::-1]
        prod = reduce(np.matmul, np.moveaxis(mats, 1, 0))
        return float(np.abs((rotation_transposed(prod) if x["transpose"] else prod) - truth).max())

    readings = [
        Reading(Kind.SIGN, "d6 = +l5", {"d6": -base.rows[5].d}),
        Reading(Kind.SIGN, "alpha2 = +90 deg", {"alpha2": -base.rows[2].alpha}),
        *choices(Kind.SWAP, "order", {"the factors multiplied in reverse order": "reverse"}),
        *choices(Kind.CONVENTION, "transpose", {"the product's rotation transposed": True}),
    ]
    return search(stated, readings, misfit, TOL_EXACT, printed="0_1T 1_2T ... 5_6T of App. B as printed",
                  stated_text="Table II (Eq 1: the product of its link transforms)",
                      route="the Table II chain "
                  "by iik.dh.dh_chain under each reading, not Pinocchio",
                  measure="max |product - re-derived chain| entry over the sampled q")


def _appb_slip(i: int, fix):
    """The good App. B matrices with matrix ``i`` replaced by ``fix(M, arm)``."""
    return lambda q, arm=THESIS_ARM: [fix(m, arm) if k == i else m
                                      for k, m in enumerate(appb_from_table_ii(q, arm))]


def _entry(M: np.ndarray, r: int, c: int, value: float) -> np.ndarray:
    """``M`` with entry (r, c) (0-based) set to ``value``."""
    M = M.copy()
    M[r, c] = value
    return M


_APPB_SLIPS = (
    Slip(SlipKind.SIGN, "4_5T with the sign of its (1,1) entry flipped", _appb_slip(4, lambda M, a: _entry(
        M, 0, 0, -M[0, 0]))),
    Slip(SlipKind.TRANSPOSE, "3_4T's rotation transposed", _appb_slip(3, lambda M, a: rotation_transposed(
        M))),
    Slip(SlipKind.LENGTH, "2_3T with l4 for l3 in its (2,4) entry", _appb_slip(2, lambda M, a: _entry(
        M, 1, 3, a.l4))),
)


def _pin_links(qs) -> np.ndarray:
    """Pinocchio's joint-to-joint placements oMi[i]^-1 oMi[i+1], (n, 6, 4, 4)."""
    P = joint_placements(qs)
    return np.stack([np.linalg.inv(P[:, i]) @ P[:, i + 1] for i in range(6)], 1)


@per_run
def _appb_truth(ctx):
    """The App. B sample's q and Pinocchio's joint-to-joint placements there (:func:`_pin_links`)."""
    qs = _samples(ctx, "appb", 2000, 100)
    return qs, _pin_links(qs)


@SECTION.check(
    "App. B",
    depends_on=EXACT_GEOMETRY + ("text",),
    forms=Forms(
        printed=appb_modified_printed,
        good=appb_from_table_ii,
        good_is="Craig's link formula on each Table II row",
        slips=_APPB_SLIPS,
        tolerance=epsilon(appb_from_table_ii, 1e-9, "the good matrices with (1,4) moved by 1 nm", (0, 3)),
    ),
)
def appendix_b(ctx, appb):
    """Appendix B link matrices (home-pose set, the form) vs Pinocchio's joint-to-joint placements, and
    their product vs Eq 4."""
    qs, pin_links = _appb_truth(ctx)
    printed = np.stack([np.stack(appb(q), 0) for q in qs], 0)  # (n, 6, 4, 4)
    P_q, T_q = appb(Q_COUNTEREXAMPLE), _pin_links(Q_COUNTEREXAMPLE[None])[0]
    rows = []
    for i, nm in enumerate(t[:4] for t in APPB_TEXT):  # "0_1T", ...
        det = np.linalg.det(printed[:, i, :3, :3])
        diff = np.argwhere(np.abs(P_q[i] - T_q[i]) > 1e-9)
        entries = ", ".join(f"({r + 1},{c + 1}): printed {P_q[i][r, c]:+.4f}, true {T_q[i][r, c]:+.4f}"
                            for r, c in diff) or "differences below 1e-9"
        rows.append(_joint_row(
            qs, f"Appendix B (home-pose set) {nm} is the Table II link transform.", f"App. B, {nm}",
            f"Printed matrix ({'read from garbled extracted text' if i in (1, 3) else 'cleanly printed'}) vs "
            f"Pinocchio's joint-to-joint placement oMi[{i}]^-1 oMi[{i + 1}]; det of the printed rotation in "
            f"[{det.min():.3f}, {det.max():.3f}]",
            Measure(f"max |{nm} - Pinocchio|", np.abs(printed[:, i] - pin_links[:, i]).max(), TOL_EXACT),
            id=f"appb.t{nm[0]}{nm[2]}",
            erratum=Erratum(f"App. B {nm}", APPB_TEXT[i], APPB_CORRECTED[i],
                            f"{fmt_q(Q_COUNTEREXAMPLE)}: {entries}. {_APPB_WHAT.get(i, '')}".strip()),
            reason="may partly be a text-extraction loss of a minus sign; the printed product does not "
            "reproduce Eq 4 either (next row)" if i == 2 else "",
        ).reread_if_erratum(lambda i=i: appb_reading(i, printed[:, i], qs)))
    prod = reduce(np.matmul, np.moveaxis(printed, 1, 0))  # 0_1T 1_2T ... 5_6T
    p_home = np.linalg.multi_dot(appb(np.zeros(6)))[:3, 3]
    p_home4 = eq4_printed(np.zeros(6))[0, :3, 3]
    p_ce = np.round(np.linalg.multi_dot(P_q)[:3, 3], 4).tolist()
    p_ce4 = np.round(eq4_printed(Q_COUNTEREXAMPLE)[0, :3, 3], 4).tolist()
    rows.append(_joint_row(
        qs, "The product of the Appendix B (home-pose set) matrices gives Eq 4.", "App. B, Eq 4",
        f"Product of the six matrices vs Eq 4 as printed; at q = 0 the product puts the tool point at "
        f"{np.round(p_home, 3).tolist()} m, Eq 4 at {np.round(p_home4, 3).tolist()} m",
        Measure("max |product - Eq 4|", np.abs(prod - eq4_printed(qs)).max(), TOL_EXACT),
        id="appb.product",
        erratum=Erratum("App. B (product 0_1T..5_6T)",
                        "product of the printed matrices (2_3T, 5_6T as printed)",
                        "product with the corrected 2_3T and 5_6T (= Table II, = Eq 4)",
                        f"{fmt_q(Q_COUNTEREXAMPLE)}: the product puts the tool point at {p_ce} m, Eq 4 at "
                        f"{p_ce4} m"),
    ).reread_if_erratum(lambda: appb_product_reading(printed, qs)))
    return rows


@SECTION.check(
    "App. B",
    depends_on=EXACT_GEOMETRY + ("text",),
    forms=Forms(
        printed=appb_first_printed,
        good=appb_first_from_dh,
        good_is="Table II rows 1-2 without the home offsets",
        slips=(
            Slip(SlipKind.OFF_BY_ONE, "the home-pose (second) set's 1_2T, offset -90 deg kept",
                 lambda qs, arm=THESIS_ARM: (appb_first_from_dh(qs, arm)[0],
                                             dh_link_transform(table_ii_printed(arm).rows[1], qs[:, 1],
                                                               "modified")[:, :2, :3])),
            Slip(SlipKind.SIGN, "1_2T's -s2 written +s2",
                 lambda qs, arm=THESIS_ARM: (appb_first_from_dh(qs, arm)[0],
                                             appb_first_from_dh(qs, arm)[1] * np.array([1.0, -1.0, 1.0]))),
        ),
        tolerance=epsilon(appb_first_from_dh, 1e-9, "every entry moved by 1 nm"),
        rows=("appb.first_legible",),
    ),
)
def appendix_b_first_set(ctx, first):
    """Appendix B, first set ('original transformations'): the legible entries, and what is not legible."""
    qs, pin_links = _appb_truth(ctx)
    T01, R12 = first(qs)
    t01_pin = pin_links[:, 0]  # joint 1 has no offset: 0_1T is the same in both sets
    # rotation rows 1-2 of Craig's link transform for Table II row 2 with no offset (alpha1 = -90 deg)
    r12 = (_axis_rotation("x", table_ii_printed().rows[1].alpha) @ _axis_rotation("z", qs[:, 1]))[:, :2, :]
    err = np.maximum(np.abs(T01 - t01_pin).max(axis=(1, 2)), np.abs(R12 - r12).max(axis=(1, 2)))
    return [
        _FIRST_LEGIBLE.row(Points(qs, _JOINT_DOMAIN.format(n=len(qs)), "rad", "q"), err),
        Row(
            "Appendix B first set ('original transformations', Craig's convention without the home offsets).",
            "App. B, first set",
            "Transcription of the extracted text",
            "0_1T legible (checked in the row above); 1_2T shows "
            "only fragments ('c2 -s2 0', '0 0 1', '-l2 -c2', the last unplaceable); 2_3T..5_6T absent",
            Verdict.NOT_CHECKABLE,
            id="appb.first_set",
            domain="the extracted text of App. B's first set",
            reason="the extracted text of this set is garbled beyond 0_1T (matrix brackets and rows lost); "
            "only the second (home-pose) set can be checked",
        ),
    ]


#: The legible entries of App. B's first set.
_FIRST_LEGIBLE = Formula(
    "App. B, first set (legible part)", None, None, TOL_EXACT, "", (), id="appb.first_legible",
    claim="Appendix B first set ('original transformations', no home offsets): the legible entries.",
    text="0_1T and rows 1-2 of 1_2T as read", corrected="Craig's formula on Table II rows 1-2, no offsets",
    measure="max |printed - truth|", method="0_1T (fully legible) vs Pinocchio's frame 1; the rotation rows "
    "1-2 of 1_2T ('c2 -s2 0', '0 0 1') vs Craig's formula on Table II row 2 without its -90 deg offset, "
    "{n} q")


@SECTION.check(
    "Eq 34a",
    forms=Forms(
        eq55_printed,
        lambda q, arm=THESIS_ARM: eq4_from_table_ii(q, arm)[:, :3, 3],
        "the position column of the Table II product",
        slips=(
            Slip(SlipKind.SIGN, "f3 with -l3 s2 written +l3 s2",
                 lambda q, arm=THESIS_ARM: eq4_printed(q, arm, _EQ4_PZ_SIGN)[..., :3, 3]),
            Slip(SlipKind.LENGTH, "l4 and l5 exchanged", lambda q, arm=THESIS_ARM: eq55_printed(
                q, _with_lengths(l4=arm.l5, l5=arm.l4))),
        ),
        tolerance=epsilon(eq55_printed, 1e-9, "each coordinate moved by 1 nm"),
    ),
)
def eq34_position(ctx, g_theta):
    """Eq 34a-c and Eq 55 (printed identically): the coordinate functions f1, f2, f3 vs Pinocchio."""
    qs, T_pin = _truth_poses(ctx, "appc", 3000, 200)
    s = Points(qs, _JOINT_DOMAIN.format(n=len(qs)), "rad", "q")
    err = np.abs(g_theta(qs) - T_pin[:, :3, 3])
    return [f.row(s, e) for f, e in zip(_COORDINATES, (*err.T, np.linalg.norm(err, axis=1)), strict=True)]


#: The rows of Eq 34a-c (one coordinate function each) and Eq 55 (G_theta); their claims are the index's.
_COORDINATES = tuple(
    Formula(f"Eq 34{c}", None, None, TOL_EXACT, "m", (), text=f"f{k + 1} as printed",
            corrected=f"p{x} of Eq 4", measure=f"max |f{k + 1} - p{x}|",
            method=f"f{k + 1} transcribed as printed vs Pinocchio's 'tool' position, {{n}} q")
    for k, (c, x) in enumerate(zip("abc", "xyz", strict=True))
) + (Formula("Eq 55 (App. C)", None, None, TOL_EXACT, "m", (), id="eq55", text="G_theta as printed",
             corrected="p of Eq 4", method="Eq 55 transcribed as printed (the same functions as Eq 34a-c) vs "
             "Pinocchio's 'tool' position, {n} q", measure="max |G_theta - p|"),)


@SECTION.check(
    "Eq 34",
    depends_on=("pinocchio",),
    forms=Forms.right(
        EQ34_ARGUMENTS,
        (
            Slip(SlipKind.OFF_BY_ONE, "f3 listed with theta1..theta4 (the joint numbers one off)",
                 {**EQ34_ARGUMENTS, "f3": (1, 2, 3, 4)}),
            Slip(SlipKind.CLAIM, "f3 written without theta2", {**EQ34_ARGUMENTS, "f3": (1, 3, 4, 5)}),
        ),
        good_is="the printed argument lists (theta6 in none, theta1 not in f3)",
    ),
)
def eq34_arguments(ctx, arguments):
    """Eq 34: the joints each coordinate depends on (theta6 in none, theta1 not in f3), vs Pinocchio."""
    rng = ctx.rng("eq34-args")
    qs = rng.uniform(THESIS_ARM.q_min, THESIS_ARM.q_max, (ctx.n(400, 60), 6))
    p0 = tool_poses(qs)[:, :3, 3]
    change = {}
    for j in range(6):
        q2 = qs.copy()
        q2[:, j] = rng.uniform(THESIS_ARM.q_min[j], THESIS_ARM.q_max[j], len(qs))
        change[j + 1] = np.abs(tool_poses(q2)[:, :3, 3] - p0).max(axis=0)  # (3,) per coordinate
    missing, lines = [0.0], []
    for k, f in enumerate(("f1", "f2", "f3")):
        absent = [j for j in range(1, 7) if j not in arguments[f]]
        missing.append(max((change[j][k] for j in absent), default=0.0))
        lines.append(f"{f}({', '.join(f'th{j}' for j in arguments[f])}): max change when a joint not in the "
                     f"list moves ({', '.join(f'th{j}' for j in absent)}) = {missing[-1]:.1e} m")
    return Row.graded(
        "Eq 34: joint 6 does not move the end-effector point, and f3 does not depend on theta1.",
        "Eq 34",
        f"Pinocchio tool position at {len(qs)} random q in Table I; each joint resampled in turn",
        "; ".join(lines),
        (Measure("max coordinate change from a joint not in the argument list", max(missing), TOL_EXACT,
                 "m"),),
        fail=Verdict.DOES_NOT_HOLD,
        id="eq34",
        domain=f"{len(qs)} q uniform in Table I; each joint in turn resampled uniformly over its whole range",
    )


def _appc_slip(change):
    """The good App. C entries (:func:`appc_from_iik`, ``J``) with ``change(J, q, arm)`` ({key: entry})
    in place of some."""
    return lambda q, arm=THESIS_ARM: (J := appc_from_iik(q, arm)) | change(J, np.atleast_2d(q), arm)


@SECTION.check(
    "Eq 56",
    forms=Forms(
        printed=appc_printed,
        good=appc_from_iik,
        good_is="iik.position_jacobian (the analytic Jacobian)",
        slips=(
            Slip(SlipKind.SIGN, "df1/dth1 with -l2 s1 written +l2 s1", _appc_slip(
                lambda J, q, arm: {"df1/dth1": J["df1/dth1"] + 2 * arm.l2 * np.sin(q[:, 0])})),
            Slip(SlipKind.SWAP, "the columns dth2 and dth3 of row f1 exchanged", _appc_slip(
                lambda J, q, arm: {"df1/dth2": J["df1/dth3"], "df1/dth3": J["df1/dth2"]})),
            Slip(SlipKind.TERM, "df3/dth2 without its -l3 c2 term", _appc_slip(
                lambda J, q, arm: {"df3/dth2": J["df3/dth2"] + arm.l3 * np.cos(q[:, 1])})),
        ),
        tolerance=epsilon(appc_printed, 1e-6, "each entry moved by 1 um/rad"),
    ),
)
def appendix_c(ctx, appc):
    """Each printed entry of Appendix C vs Pinocchio's frame Jacobian and finite differences; Eq 35."""
    qs = _samples(ctx, "appc", 3000, 200)
    J_pin, J_fd = _jacobians(ctx)
    pr = appc(qs)
    details = []
    for key, val in pr.items():
        i, j = int(key[2]) - 1, int(key[-1]) - 1
        d_pin, d_fd = np.abs(val - J_pin[:, i, j]), np.abs(val - J_fd[:, i, j])
        k = int(np.argmax(d_pin))
        details.append(Row.graded(
            f"{key} = {APPC_TEXT[key]}",
            f"App. C, Eq 56 {key}",
            "vs Pinocchio and central differences" + ("; the text after this entry carries a stray '1/2' (an "
                                                      "extraction artifact)" if key == "df3/dth5" else ""),
            None,
            (Measure("max |printed - Pinocchio|", d_pin.max(), TOL_EXACT, "m/rad"),
             Measure("max |printed - FD|", d_fd.max(), TOL_EXACT + TOL_FD, "m/rad")),
            id=key.replace("/", ""),
            erratum=Erratum(f"App. C {key}", APPC_TEXT[key], "d/dtheta of Eq 55 (iik.position_jacobian)",
                            f"{fmt_q(qs[k])}: printed {val[k]:.6f}, true {J_pin[k, i, j]:.6f}"),
        ))
    n_ok = sum(d.verdict is Verdict.HOLDS for d in details)
    worst_ = np.array([[m.value for m in d.measures] for d in details])  # (15, 2): vs Pinocchio, vs FD
    fig = _bars(ctx, "appc_errors.png", list(pr), [(w, worst_[:, i]) for i, w in
                enumerate(("vs Pinocchio", "vs central FD"))], "max |error| [m/rad]",
                f"Appendix C entries as printed, {len(qs)} q", rotation=60, fontsize=7)
    group = Row.grouped(
        "Appendix C: the 15 printed entries of the 3x5 Jacobian (Eq 56) are the derivatives of Eq 55.",
        "Eq 56 (App. C)",
        "each printed entry vs Pinocchio computeFrameJacobian(frame 'tool', LOCAL_WORLD_ALIGNED) and "
        f"central differences (h = 1e-6 rad) of the Pinocchio tool point, {len(qs)} q",
        f"{n_ok} of 15 entries match (worst |printed - Pinocchio| = {worst_[:, 0].max():.1e} "
        "m/rad)",
        details,
        "entries not matching",
        fail=Verdict.ERRATUM,
        id="appc",
        domain=_JOINT_DOMAIN.format(n=len(qs)),
        figures=(fig,),
    )
    # Eq 35: the assembled 3x5 matrix maps joint increments to tool-point increments
    J = np.stack([np.stack([pr[f"df{i + 1}/dth{j + 1}"] for j in range(5)], -1) for i in range(3)], 1)
    dq = ctx.rng("eq35").normal(size=(len(qs), 5))
    dq /= np.linalg.norm(dq, axis=1, keepdims=True)
    fd = _fd_tool_point(qs, np.pad(dq, ((0, 0), (0, 1))))  # theta6 fixed
    e35 = np.linalg.norm(np.einsum("nij,nj->ni", J, dq) - fd, axis=1)
    s35 = Points(qs, _JOINT_DOMAIN.format(n=len(qs)) + "; one random unit joint direction per q", "rad", "q")
    return [group, _EQ35.row(s35, e35)]


#: Eq 35 with the printed App. C matrix (the claim is the index's).
_EQ35 = Formula(
    "Eq 35", None, None, TOL_FD, "m/rad", (), text="J_theta of App. C", corrected="iik.position_jacobian",
    measure="max |J dtheta - dp/dtheta (FD)|",
    method="printed App. C matrix times a random unit joint direction vs the central difference (h = 1e-6 "
    "rad) of the Pinocchio tool point along it, {n} q",
    basis="Eq 35 is the definition of the Jacobian (the first-order change of the tool point); with the App. "
    "C entries right (row kinematics.appc) it holds by construction: this re-measures App. C")


@SECTION.check(
    15.5,
    depends_on=("pinocchio",),
    forms=Forms(
        printed=(fk, jacobian),
        good=(
            lambda q, arm=THESIS_ARM: tool_poses(np.atleast_2d(q)),
            lambda q, arm=THESIS_ARM: tool_jacobians(np.atleast_2d(q)),
        ),
        good_is="Pinocchio's FK and frame Jacobian themselves",
        slips=(
            Slip(SlipKind.TRANSPOSE, "iik.fk's rotation transposed", (_transposed_rotation(fk), jacobian)),
            Slip(SlipKind.SWAP, "the Jacobian's linear and angular rows exchanged",
                 (fk, lambda q, arm=THESIS_ARM: np.concatenate([jacobian(q, arm)[..., 3:, :],
                                                                jacobian(q, arm)[..., :3, :]], -2))),
        ),
        tolerance=Slip(SlipKind.EPSILON, "iik.fk with p_z moved by 1 nm",
                       (off_by(fk, 1e-9, (2, 3)), jacobian)),
    ),
)
def iik_kinematics(ctx, impl):
    """(Project) iik.fk and iik.jacobian (6x6) agree with Pinocchio."""
    fk_f, jac_f = impl
    qs, T_pin = _truth_poses(ctx, "appc", 3000, 200)
    J_pin = _jacobians(ctx)[0]
    T = fk_f(qs, THESIS_ARM)
    dp = np.linalg.norm(T[:, :3, 3] - T_pin[:, :3, 3], axis=1).max()
    dr = float(np.max(rotation_angle(T[:, :3, :3], T_pin[:, :3, :3])))
    return _joint_row(
        qs, "(Project) iik.fk and the 6x6 iik.jacobian agree with Pinocchio.", "iik.kinematics (Eq 4, Eq 56)",
        "Pinocchio framesForwardKinematics and computeFrameJacobian (LOCAL_WORLD_ALIGNED)",
        Measure("max |dp|", dp, TOL_EXACT, "m"), Measure("max rotation angle", dr, TOL_EXACT, "rad"),
        Measure("max |dJ|", np.abs(jac_f(qs, THESIS_ARM) - J_pin).max(), TOL_EXACT, "m/rad or -"),
        fail=Verdict.DOES_NOT_HOLD, scope=Scope.PROJECT,
    )


@per_run
def _euler_samples(ctx):
    """Eq 42's angle sample [rad]: alpha, gamma uniform in [-pi, pi], beta uniform in [0, pi]."""
    rng = ctx.rng("eq42")
    n = ctx.n(20000, 500)
    return rng.uniform(-np.pi, np.pi, n), rng.uniform(0, np.pi, n), rng.uniform(-np.pi, np.pi, n)


_CONVENTIONS = ("ZYZ", "ZXZ")
#: The angles (alpha, beta, gamma) [rad] of Eq 42's counterexamples.
_EULER_AT = (0.5, 0.7, 0.3)


def _eq42_compare(ctx, eq42):
    """The form on sampled angles: angles, matrices, |form - scipy| and matching entries per convention, and
    the form at the counterexample angles :data:`_EULER_AT`."""
    a, b, g = _euler_samples(ctx)
    P = eq42(a, b, g)
    dev = {c: np.abs(P - Rotation.from_euler(c, np.stack([a, b, g], -1)).as_matrix()) for c in _CONVENTIONS}
    counts = {c: int(np.sum(dev[c].max(axis=0) <= TOL_EXACT)) for c in _CONVENTIONS}
    return (a, b, g), P, dev, counts, eq42(*_EULER_AT)


@SECTION.check(
    "Eq 42",
    depends_on=("text",),
    forms=Forms(
        printed=eq42_printed,
        good=eq42_zyz,
        good_is="the Z-Y-Z matrix (Craig), composed from elementary rotations",
        slips=(
            Slip(SlipKind.TRANSPOSE, "the Z-Y-Z matrix transposed",
                 lambda a, b, g: np.swapaxes(eq42_zyz(a, b, g), -1, -2)),
            Slip(SlipKind.SIGN, "r31 = +s_b c_g", lambda a, b, g: eq42_zyz(a, b, g) * np.array(
                [[1, 1, 1], [1, 1, 1], [-1, 1, 1]])),
            Slip(SlipKind.SWAP, "alpha and gamma exchanged", lambda a, b, g: eq42_zyz(g, b, a)),
        ),
        tolerance=epsilon(eq42_zyz, 1e-9, "the good matrix with r33 moved by 1e-9", (2, 2)),
    ),
)
def eq42_matrix(ctx, eq42):
    """Eq 42 (the form) is the Euler-angle rotation matrix of some Z-?-Z convention (scipy as reference)."""
    (a, b, g), P, dev, matching, P0 = _eq42_compare(ctx, eq42)
    best = max(_CONVENTIONS, key=lambda c: (matching[c], -dev[c].max()))  # the convention most entries follow
    orth = np.abs(np.einsum("nji,njk->nik", P, P) - np.eye(3)).max()
    m = (
        Measure(f"max |printed - scipy '{best}'|", dev[best].max(), TOL_EXACT),
        Measure("max |R^T R - I|", orth, TOL_EXACT),
    )
    bad_entries = [(r + 1, c + 1) for r in range(3) for c in range(3) if dev[best][:, r, c].max() > TOL_EXACT]
    fig = _bars(ctx, "eq42_entries.png", [f"r{r + 1}{c + 1}" for r in range(3) for c in range(3)],
                [(f"vs scipy '{c}'", dev[c].max(axis=0).ravel()) for c in _CONVENTIONS], "max |form - scipy|",
                f"Eq 42 entry by entry ({len(a)} angle triples)", floor=1e-17, figsize=(6.4, 3.2))
    a0, b0, g0 = _EULER_AT
    Z0 = Rotation.from_euler(best, _EULER_AT).as_matrix()
    r, c = (bad_entries or [(2, 1)])[0]  # the first entry that differs (the erratum, if the row fails)
    return Row.graded(
        "Eq 42 is an Euler-angle orientation matrix R = Rz(alpha) R(beta) Rz(gamma).",
        "Eq 42 (Sec 3.5.1)",
        f"Eq 42 transcribed as printed vs scipy Rotation.from_euler('ZYZ') and ('ZXZ') (intrinsic), {len(a)} "
        "angle triples (alpha, gamma in [-pi, pi], beta in [0, pi]); orthonormality",
        f"closest convention {best}: entries differing by > 1e-12: {bad_entries}; max deviation "
        f"{dev[best].max():.3g}; max |R^T R - I| = {orth:.2g}",
        m,
        id="eq42",
        figures=(fig,),
        erratum=Erratum(f"Eq 42 r{r}{c}", f"r{r}{c} = {EQ42_TEXT[r - 1][c - 1]}",
                        "r21 = s_a c_b c_g + c_a s_g" if (r, c) == (2, 1) else f"r{r}{c} of {best}",
                        f"alpha, beta, gamma = {a0}, {b0}, {g0} rad: printed r{r}{c} = {P0[r - 1, c - 1]:.6f}"
                        f", {best} gives {Z0[r - 1, c - 1]:.6f}; printed R^T R - I has max entry "
                        f"{np.abs(P0.T @ P0 - np.eye(3)).max():.3f}"),
        domain=f"{len(a)} angle triples: alpha, gamma uniform in [-pi, pi], beta uniform in [0, pi] (both "
        "poles of the polar angle included)",
    ).reread_if_erratum(lambda: eq42_reading(
        ctx, eq42, [(r - 1, c - 1) for r, c in bad_entries],
        ", ".join(f"r{r}{c}" for r, c in bad_entries) + " as printed", count=False))


@SECTION.check(
    "Eq 42",
    depends_on=("text",),
    forms=Forms(
        printed=eq42_printed,
        good=eq42_zxz,
        good_is="the Z-X-Z matrix, composed from elementary rotations",
        slips=(
            Slip(SlipKind.MODEL, "the Z-Y-Z matrix in closed form", eq42_zyz),
            Slip(SlipKind.TRANSPOSE, "the Z-X-Z matrix transposed (extrinsic)",
                 lambda a, b, g: np.swapaxes(eq42_zxz(a, b, g), -1, -2)),
        ),
    ),
)
def eq42_convention(ctx, eq42):
    """Sec 3.5.1 names Eq 42 'the Z-X-Z convention of [2]': how many of the form's entries are Z-X-Z?"""
    (a, b, g), _, _, counts, P0 = _eq42_compare(ctx, eq42)
    m = (Measure("entries of Eq 42 that are not Z-X-Z", 9 - counts["ZXZ"], 0),)
    a0, b0, g0 = _EULER_AT
    return Row.graded(
        "Eq 42 follows 'the Z-X-Z representation convention described in [2]'.",
        "Eq 42, Sec 3.5.1",
        f"each of the 9 entries vs scipy 'ZXZ' and 'ZYZ' (intrinsic) on {len(a)} angle triples",
        f"entries matching Z-X-Z: {counts['ZXZ']} of 9; matching Z-Y-Z: {counts['ZYZ']} of 9",
        m,
        erratum=Erratum(
            "Eq 42 / Sec 3.5.1 convention",
            "'Z-X-Z representation convention' (Sec 3.5.1)",
            "Craig's Z-Y-Z, R = Rz(alpha) Ry(beta) Rz(gamma) (scipy 'ZYZ'): z6 = [r13 r23 r33] = "
            "[c_a s_b, s_a s_b, c_b], alpha its azimuth, beta its polar angle; iik uses Z-Y-Z (how Sec "
            "3.5's own alpha, beta map to these is checked in the Dexterity section)",
            f"alpha, beta, gamma = {a0}, {b0}, {g0} rad: printed r13 = {P0[0, 2]:.6f} = Z-Y-Z r13; Z-X-Z "
            f"r13 = s_a s_b = {Rotation.from_euler('ZXZ', _EULER_AT).as_matrix()[0, 2]:.6f}",
        ),
        domain=f"{len(a)} angle triples: alpha, gamma uniform in [-pi, pi], beta uniform in [0, pi]",
    ).reread_if_erratum(lambda: eq42_reading(
        ctx, eq42, [(r, c) for r in range(3) for c in range(3) if (r, c) != (1, 0)],
        "the entries of Eq 42 other than r21 (r21 is a typo of its own, row kinematics.eq42)", count=True))


def eq42_reading(ctx, eq42, entries, printed: str, *, count: bool):
    """Second reading of Eq 42 (the form ``eq42``) on the check's angle sample: under every Euler convention,
    the angles' signs, alpha and gamma swapped and the matrix transposed. ``entries``: the (row, column)
    pairs (0-based) compared; ``count``: grade the number of entries that differ (else the largest
    difference)."""
    a, b, g = (x[:2000] for x in _euler_samples(ctx))  # 2000 triples: enough to tell 24 conventions apart
    P = eq42(a, b, g)
    stated = {"conv": ("zxz", True), "a": a, "b": b, "g": g, "transpose": False}

    def misfit(x) -> float:
        R = euler_matrix(*x["conv"], x["a"], x["b"], x["g"])
        if x["transpose"]:
            R = np.swapaxes(R, -1, -2)
        d = np.array([np.abs(P[:, r, c] - R[:, r, c]).max() for r, c in entries])
        return float(np.sum(d > TOL_EXACT)) if count else float(d.max())

    others = {f"the {s.upper()} {w} convention": (s, i) for s in EULER_SEQUENCES
              for i, w in ((True, "intrinsic"), (False, "extrinsic")) if (s, i) != stated["conv"]}
    readings = [
        *choices(Kind.CONVENTION, "conv", others),
        Reading(Kind.SIGN, "alpha measured the other way", {"a": -a}),
        Reading(Kind.SIGN, "beta measured the other way", {"b": -b}),
        Reading(Kind.SIGN, "gamma measured the other way", {"g": -g}),
        Reading(Kind.SWAP, "alpha and gamma swapped", {"a": g, "g": a}),
        *choices(Kind.SWAP, "transpose", {"the matrix transposed (row vs column vectors)": True}),
    ]
    which = ", ".join(f"r{r + 1}{c + 1}" for r, c in entries)
    return search(stated, readings, misfit, 0.0 if count else TOL_EXACT, printed=printed,
                  stated_text="'the Z-X-Z representation convention described in [2]' (Sec 3.5.1), "
                  "R = Rz(alpha) Rx(beta) Rz(gamma)",
                  route=f"elementary rotations composed by hand (euler_matrix), not scipy, on {len(a)} of "
                  "the angle triples",
                  measure=(f"entries of {which} that differ (> {TOL_EXACT:g})" if count
                           else f"max |printed - re-derived| of {which}"))


def _edited_generator(edit):
    """A wrong generator: the DH table edited by ``edit(table) -> table`` before ``urdf_from_dh``."""
    return lambda table, **kw: urdf_from_dh(edit(table), **kw)


#: A deliberately wrong generator: d of the first row moved by 1 um.
SHIFTED_GENERATOR = _edited_generator(lambda t: _table_edit(0, t, d=t.rows[0].d + 1e-6))
_GEN_FORMS = Forms.right(
    urdf_from_dh,
    (
        Slip(SlipKind.MODEL, "the table read in the other DH convention (standard <-> modified)",
             _edited_generator(lambda t: replace(t, convention="standard" if t.convention == "modified"
                                                 else "modified"))),
        Slip(SlipKind.SIGN, "every twist alpha with its sign flipped", _edited_generator(
            lambda t: replace(t, rows=tuple(replace(r, alpha=-r.alpha) for r in t.rows)))),
    ),
    tolerance=Slip(SlipKind.EPSILON, "a generator that moves d of the first row by 1 um", SHIFTED_GENERATOR),
    good_is="iik.urdf.urdf_from_dh (the generator under test)",
)


def _generator_row(fk_pair, qs, generator, base, tool, within: str, note: str, **fields):
    """The generated URDF's poses (``fk_pair``, at ``qs`` uniform ``within``) mapped by the frozen ``base``,
    ``tool`` vs the reference file's: the row graded on position errors [m] and rotation angles [rad] <=
    1e-9 each (a generator that is right), and the errors; ``note`` introduces how far the base and tool
    solved in closed form from 50 q are from the frozen ones."""
    Tg, Tr = fk_pair(qs, generator=generator)
    B, E = solve_base_tool(Tg[:50], Tr[:50])
    T = base @ Tg @ tool
    dp = np.linalg.norm(T[:, :3, 3] - Tr[:, :3, 3], axis=1)
    dr = rotation_angle(T[:, :3, :3], Tr[:, :3, :3])
    return Row.graded(
        **fields,
        numbers=f"max |dp| = {dp.max():.1e} m, max rotation angle = {dr.max():.1e} rad (tolerance 1e-9"
        f"{note} {max(np.abs(B - base).max(), np.abs(E - tool).max()):.1e}",
        measures=(Measure("max |dp|", dp.max(), 1e-9, "m"), Measure("max rotation angle", dr.max(), 1e-9,
                                                                     "rad")),
        fail=Verdict.DOES_NOT_HOLD,
        scope=Scope.PROJECT,
        domain=f"{len(qs)} q uniform {within}",
    ), dp, dr


@SECTION.check(17.0, depends_on=(), forms=_GEN_FORMS)
def ur5_generator_check(ctx, generator):
    """The URDF generator on a robot nobody here wrote: UR5 from its standard DH table."""
    qs = np.random.default_rng([ctx.seed, 5]).uniform(-np.pi, np.pi, (ctx.n(2000, 100), 6))
    row, dp, dr = _generator_row(
        ur5_fk_pair, qs, generator, UR5_BASE, UR5_TOOL, "in [-pi, pi]^6",
        "; the reference file rounds pi/2 to 1.57079632679); solved B, E differ from the frozen ones by",
        claim="(Project) The DH -> URDF generator is right: the UR5 built from its published standard DH "
        "table matches example-robot-data's ur5_robot.urdf.",
        reference="iik.urdf (Sec 3.2 method: DH description)",
        method=f"Pinocchio FK of the generated URDF (frame 'tool') vs ur5_robot.urdf (frame 'tool0') at "
        f"{len(qs)} q uniform in [-pi, pi]^6, after T_ref = B T_dh E with frozen B = RotZ(pi), E = I (solved "
        "in closed form from 50 q, see verification/oracles/ur5.py)",
        id="ur5",
    )
    return row.replace(figures=(_hist(ctx, "ur5_errors.png", [("|dp| [m]", dp), ("rotation angle [rad]", dr)],
                                      "log10 error, generated UR5 vs ur5_robot.urdf",
                                      f"UR5 from its DH table, {len(qs)} q"),))


@SECTION.check(17.5, depends_on=(), forms=_GEN_FORMS)
def panda_generator_check(ctx, generator):
    """The URDF generator in the modified convention on a robot nobody here wrote: Franka Panda."""
    from ..oracles.panda import panda_fk_pair, panda_models

    _, _, ref, _ = panda_models()
    lo, hi = ref.lowerPositionLimit[:7], ref.upperPositionLimit[:7]
    qs = np.random.default_rng([ctx.seed, 7]).uniform(lo, hi, (ctx.n(2000, 100), 7))
    return _generator_row(
        panda_fk_pair, qs, generator, np.eye(4), np.eye(4), "within the Panda's limits",
        "); solved base/tool transforms differ from the identity by",
        claim="(Project) The DH -> URDF generator maps Craig's modified DH (Table II's convention) right: "
        "the Franka Panda built from its published modified DH table matches example-robot-data's "
        "panda.urdf.",
        reference="iik.urdf (Sec 3.2 method: Craig's convention)",
        method=f"Pinocchio FK of the generated URDF (frame 'tool' = frame 7 + 0.107 m flange) vs panda.urdf "
        f"(frame 'panda_link8') at {len(qs)} q uniform within the Panda's limits; base and tool transforms "
        "solved in closed form from 50 q",
        id="panda",
    )[0]


def _tool_to_upper_arm(qs):
    """Distance [m] from the tool point E to the upper-arm axis segment J2-J34 (a to b), (n,)."""
    F = joint_frames(qs, THESIS_ARM)
    p, a, b = F[:, 5, :3, 3], F[:, 1, :3, 3], F[:, 2, :3, 3]
    t = np.clip(np.einsum("ni,ni->n", p - a, b - a) / np.einsum("ni,ni->n", b - a, b - a), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * (b - a)), axis=1)


def _limits(lo_deg, hi_deg) -> tuple[np.ndarray, np.ndarray]:
    """Joint limits given in degrees as (lower, upper) [rad]."""
    return np.radians(np.array(lo_deg, float)), np.radians(np.array(hi_deg, float))


def _wrist_limits(w: float) -> tuple[np.ndarray, np.ndarray]:
    """Table I with theta2 <= 80 deg and theta4, theta5 within +-w deg [rad]."""
    return _limits([-160, -120, -160, -w, -w, -180], [160, 80, 160, w, w, 180])


#: Table I as printed [rad]; a narrower set the claim holds for; and that set with joints 4-5 widened again.
TABLE_I_LIMITS = _limits(*zip(*TABLE_I_PRINTED, strict=True))
SAFE_LIMITS, UNSAFE_LIMITS = _wrist_limits(30), _wrist_limits(119)
#: A self-collision must stay this far [m] from the upper-arm axis to be "avoided" (a PowerCube half-width).
MIN_CLEARANCE = 0.05


@SECTION.check(
    18.0,
    depends_on=("l1", "lengths", "collision-shapes"),
    forms=Forms(
        printed=TABLE_I_LIMITS,
        good=SAFE_LIMITS,
        good_is="Table I with theta2 <= 80 deg and theta4, theta5 within +-30 deg",
        slips=(
            Slip(SlipKind.LIMIT, "the same with theta4, theta5 back to +-119 deg", UNSAFE_LIMITS),
            Slip(SlipKind.UNIT, "theta4, theta5 limits of +-30 read as rad (no limit at all)",
                 _wrist_limits(np.degrees(30))),
        ),
    ),
)
def table_i_self_collision(ctx, limits):
    """Sec 3.2: the Table I limits (the form) were chosen "to avoid hitting the manipulator itself"."""
    lo, hi = limits
    tm = thesis_model(THESIS_ARM)
    data, gdata = tm.model.createData(), pin.GeometryData(tm.collision_model)
    qs = ctx.rng("selfcol").uniform(lo, hi, (ctx.n(10000, 500), 6))
    hit = np.array([pin.computeCollisions(tm.model, data, tm.collision_model, gdata, q, True) for q in qs])
    q0 = qs[int(np.argmin(_tool_to_upper_arm(qs)))]  # the sampled q nearest to the upper-arm axis
    res = minimize(lambda q: float(_tool_to_upper_arm(q[None])[0]), q0, bounds=list(zip(lo, hi, strict=True)),
                   method="L-BFGS-B")
    q_star = np.clip(res.x, lo, hi)
    d_star = float(_tool_to_upper_arm(q_star[None])[0])
    return Row.graded(
        "The joint limits of Table I keep the arm from hitting itself.",
        "Sec 3.2, Table I",
        "(a) geometry-independent: minimum over q within the limits of the distance from the tool point (Eq "
        f"4) to the upper-arm axis segment J2-J34 (sampling {len(qs)} q, then L-BFGS-B within the limits), "
        f">= {MIN_CLEARANCE * 1e3:.0f} mm required; (b) Coal via Pinocchio on the assumed PowerCube "
        "collision shapes of urdf/thesis_arm.urdf (non-adjacent links), "
        f"{len(qs)} q uniform within the limits",
        f"(a) min distance = {d_star * 1000:.2g} mm at {fmt_q(q_star)} (theta4 + theta5 = "
        f"{np.degrees(q_star[3] + q_star[4]):.0f} deg); (b) {hit.mean() * 100:.1f} % of the sampled "
        "configurations self-collide",
        (Measure("min distance tool point - upper-arm axis", d_star, MIN_CLEARANCE, "m", bound=">="),
         Measure("fraction of sampled q in self-collision (Coal)", hit.mean(), 0.0)),
        fail=Verdict.DOES_NOT_HOLD,
        domain=f"{len(qs)} q uniform within the limits under test, then a bounded local search from the "
        "worst",
        reason="the limits bound each joint separately; theta4 + theta5 can reach 238 deg, so the gripper "
        "can be folded into the upper arm (and with theta2 near 95 deg link 3 meets the base module)",
    )
