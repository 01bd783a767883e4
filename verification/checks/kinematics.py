"""Checks of the thesis kinematics: Table I/II, Eq 4, Appendix B, Appendix C, Eq 42, and the URDF.

Every formula is transcribed *as printed* in a ``*_printed`` function below
(symbols as in the thesis: ``c1 = cos(theta1)``, ``s45 = sin(theta4 + theta5)``, ...)
and compared with ground truth: Pinocchio on ``urdf/thesis_arm.urdf``, the generic
DH product, central finite differences, ``scipy.spatial.transform.Rotation``.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
from scipy.spatial.transform import Rotation

from iik.arm import THESIS_ARM
from iik.dh import DHRow, DHTable, dh_chain, dh_link_transform
from iik.kinematics import fk, jacobian, position_jacobian
from iik.resources import urdf_path
from iik.rotations import euler_matrix
from iik.urdf import thesis_urdf

from ..oracles.pinocchio_model import thesis_model, tool_jacobians, tool_poses
from ..oracles.ur5 import UR5_BASE, UR5_TOOL, solve_base_tool, ur5_fk_pair
from ..plotting import draw_arm, draw_collision, draw_scene, new_figure
from ..registry import Erratum, Row, Verdict, register
from ..testing.strategies import BEYOND, sample_joints

SECTION = "Kinematics (Tables I-II, Eq 4, App. B, App. C, Eq 42)"
TOL_EXACT = 1e-12  # [m] and [-]: closed forms vs Pinocchio
TOL_FD = 1e-7  # [m/rad]: vs central finite differences (h = 1e-6)
_DEG = np.pi / 180
#: The joint vector [rad] used as counterexample where any generic q would do.
Q_COUNTEREXAMPLE = np.array([0.3, -0.4, 0.5, 0.6, -0.7, 0.8])


def _fmt_q(q) -> str:
    return "q = [" + ", ".join(f"{v:.4f}" for v in q) + "] rad"


def _trig(q):
    q = np.asarray(q, float)
    c = {i + 1: np.cos(q[..., i]) for i in range(6)}
    s = {i + 1: np.sin(q[..., i]) for i in range(6)}
    c45, s45 = np.cos(q[..., 3] + q[..., 4]), np.sin(q[..., 3] + q[..., 4])
    return c, s, c45, s45


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


def _sym(expr: str, L: dict) -> float:
    sign = -1.0 if expr.startswith("-") else 1.0
    key = expr.lstrip("-")
    return sign * (0.0 if key == "0" else L[key])


def table_ii_printed(arm=THESIS_ARM) -> DHTable:
    """Table II as printed (modified DH), with the arm's lengths substituted."""
    L = dict(zip(("l1", "l2", "l3", "l4", "l5"), arm.lengths, strict=True))
    rows = tuple(DHRow(alpha=al * _DEG, a=_sym(a, L), d=_sym(d, L), offset=off * _DEG)
                 for al, a, d, off in TABLE_II_PRINTED)
    lower = tuple(lo * _DEG for lo, _ in TABLE_I_PRINTED)
    upper = tuple(hi * _DEG for _, hi in TABLE_I_PRINTED)
    return DHTable(rows=rows, convention="modified", lower=lower, upper=upper, velocity=(1.0,) * 6)


def eq4_printed(q, arm=THESIS_ARM) -> np.ndarray:
    """Eq 4 exactly as printed -> (n, 4, 4)."""
    c, s, c45, s45 = _trig(np.atleast_2d(q))
    c1, c2, c3, c4, c6 = c[1], c[2], c[3], c[4], c[6]
    s1, s2, s3, s4, s6 = s[1], s[2], s[3], s[4], s[6]
    l1, l2, l3, l4, l5 = arm.lengths
    T = np.zeros(c1.shape + (4, 4))
    T[..., 0, 0] = c6 * (c45 * (s1 * s3 + c1 * s2 * c3) - s45 * c1 * c2) - s6 * (s1 * c3 - c1 * s2 * s3)
    T[..., 1, 0] = s6 * (c1 * c3 + s1 * s2 * s3) - c6 * (c45 * (c1 * s3 - s1 * s2 * c3) + s45 * s1 * c2)
    T[..., 2, 0] = c6 * (s45 * s2 + c45 * c2 * c3) + c2 * s3 * s6
    T[..., 0, 1] = -s6 * (c45 * (s1 * s3 + c1 * s2 * c3) - s45 * c1 * c2) - c6 * (c3 * s1 - c1 * s2 * s3)
    T[..., 1, 1] = s6 * (c45 * (c1 * s3 - s1 * s2 * c3) + s45 * s1 * c2) + c6 * (c1 * c3 + s1 * s2 * s3)
    T[..., 2, 1] = c2 * s3 * c6 - s6 * (s45 * s2 + c45 * c2 * c3)
    T[..., 0, 2] = -s45 * (s1 * s3 + c1 * s2 * c3) - c45 * c1 * c2
    T[..., 1, 2] = s45 * (c1 * s3 - s1 * s2 * c3) - c45 * s1 * c2
    T[..., 2, 2] = c45 * s2 - s45 * c2 * c3
    T[..., 0, 3] = (l2 * c1 + l3 * c1 * c2 + (l5 * s45 + l4 * s4) * (s1 * s3 + c1 * s2 * c3)
                    + (l5 * c45 + l4 * c4) * (c1 * c2))
    T[..., 1, 3] = (l2 * s1 + l3 * s1 * c2 - (l5 * s45 + l4 * s4) * (c1 * s3 - s1 * s2 * c3)
                    + (l5 * c45 + l4 * c4) * (s1 * c2))
    T[..., 2, 3] = l5 * (s45 * c2 * c3 - c45 * s2) + l4 * (c2 * c3 * s4 - c4 * s2) - l3 * s2 + l1
    T[..., 3, 3] = 1.0
    return T


def appc_printed(q, arm=THESIS_ARM) -> dict[str, np.ndarray]:
    """The 15 entries of Appendix C (Eq 56) exactly as printed, keyed ``"df1/dth1"`` ..."""
    c, s, c45, s45 = _trig(np.atleast_2d(q))
    c1, c2, c3, c4 = c[1], c[2], c[3], c[4]
    s1, s2, s3, s4 = s[1], s[2], s[3], s[4]
    _l1, l2, l3, l4, l5 = arm.lengths
    W = l5 * s45 + l4 * s4  # printed as (l5 s45 + l4 s4)
    V = l5 * c45 + l4 * c4  # printed as (l5 c45 + l4 c4)
    return {
        "df1/dth1": -l2 * s1 - l3 * s1 * c2 + W * (c1 * s3 - s1 * s2 * c3) - V * (s1 * c2),
        "df1/dth2": -l3 * c1 * s2 + W * (c1 * c2 * c3) - V * (c1 * s2),
        "df1/dth3": W * (s1 * c3 - c1 * s2 * s3),
        "df1/dth4": V * (s1 * s3 + c1 * s2 * c3) - W * (c1 * c2),
        "df1/dth5": (l5 * c45) * (s1 * s3 + c1 * s2 * c3) - l5 * c1 * c2 * s45,
        "df2/dth1": l2 * c1 + l3 * c1 * c2 + W * (s1 * s3 + c1 * s2 * c3) + V * (c1 * c2),
        "df2/dth2": -l3 * s1 * s2 + W * (s1 * c2 * c3) - V * (s1 * s2),
        "df2/dth3": -W * (c1 * c3 + s1 * s2 * s3),
        "df2/dth4": -V * (c1 * s3 - s1 * s2 * c3) - W * (s1 * c2),
        "df2/dth5": -(l5 * c45) * (c1 * s3 - s1 * s2 * c3) - l5 * s1 * c2 * s45,
        "df3/dth1": np.zeros_like(c1),
        "df3/dth2": -l5 * (s45 * s2 * c3 + c45 * c2) - l4 * (s2 * c3 * s4 + c4 * c2) - l3 * c2,
        "df3/dth3": -l5 * s45 * c2 * s3 - l4 * c2 * s3 * s4,
        "df3/dth4": l5 * (c45 * c2 * c3 + s45 * s2) + l4 * (c2 * c3 * c4 + s4 * s2),
        "df3/dth5": l5 * (c45 * c2 * c3 + s45 * s2),
    }


def eq55_printed(q, arm=THESIS_ARM) -> np.ndarray:
    """Eq 55 (App. C), = Eq 34a-c: the position vector G_theta = [f1, f2, f3] as printed -> (n, 3)."""
    c, s, c45, s45 = _trig(np.atleast_2d(q))
    c1, c2, c3, c4 = c[1], c[2], c[3], c[4]
    s1, s2, s3, s4 = s[1], s[2], s[3], s[4]
    l1, l2, l3, l4, l5 = arm.lengths
    f1 = (l2 * c1 + l3 * c1 * c2 + (l5 * s45 + l4 * s4) * (s1 * s3 + c1 * s2 * c3)
          + (l5 * c45 + l4 * c4) * (c1 * c2))
    f2 = (l2 * s1 + l3 * s1 * c2 - (l5 * s45 + l4 * s4) * (c1 * s3 - s1 * s2 * c3)
          + (l5 * c45 + l4 * c4) * (s1 * c2))
    f3 = l5 * (s45 * c2 * c3 - c45 * s2) + l4 * (c2 * c3 * s4 - c4 * s2) - l3 * s2 + l1
    return np.stack([f1, f2, f3], axis=-1)


#: Appendix C entries in the printed (LaTeX-ish) form, for the report.
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


def _m(rows) -> np.ndarray:
    return np.array(rows, dtype=float)


def appb_modified_printed(q, arm=THESIS_ARM) -> list[np.ndarray]:
    """Appendix B, second set ("modified transformations", home = Fig 8), as printed.

    The extracted text is garbled for 1_2T and 3_4T (matrix rows split over lines and
    the bracket layout broken); they are read row by row in the only order that gives
    a 4x4 matrix. 0_1T, 2_3T, 4_5T and 5_6T are cleanly printed.
    """
    c, s, _, _ = _trig(q)
    l1, l2, l3, l4, l5 = arm.lengths
    c1, c2, c3, c4, c5, c6 = (c[i] for i in range(1, 7))
    s1, s2, s3, s4, s5, s6 = (s[i] for i in range(1, 7))
    return [
        _m([[c1, -s1, 0, 0], [s1, c1, 0, 0], [0, 0, 1, l1], [0, 0, 0, 1]]),  # 0_1T
        _m([[s2, c2, 0, l2], [0, 0, 1, 0], [c2, -s2, 0, 0], [0, 0, 0, 1]]),  # 1_2T (garbled)
        _m([[c3, -s3, 0, 0], [0, 0, 1, l3], [-s3, c3, 0, 0], [0, 0, 0, 1]]),  # 2_3T
        _m([[s4, c4, 0, 0], [0, 0, 1, 0], [c4, -s4, 0, 0], [0, 0, 0, 1]]),  # 3_4T (garbled)
        _m([[-s5, -c5, 0, l4], [c5, -s5, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]),  # 4_5T
        _m([[c6, -s6, 0, 0], [0, 0, 1, l5], [-s6, c6, 0, 0], [0, 0, 0, 1]]),  # 5_6T
    ]


#: Printed text of the Appendix B (modified set) matrices, rows separated by ';'.
APPB_TEXT = (
    "0_1T = [c1 -s1 0 0; s1 c1 0 0; 0 0 1 l1; 0 0 0 1]",
    "1_2T = [s2 c2 0 l2; 0 0 1 0; c2 -s2 0 0; 0 0 0 1] (read from garbled text)",
    "2_3T = [c3 -s3 0 0; 0 0 1 l3; -s3 c3 0 0; 0 0 0 1]",
    "3_4T = [s4 c4 0 0; 0 0 1 0; c4 -s4 0 0; 0 0 0 1] (read from garbled text)",
    "4_5T = [-s5 -c5 0 l4; c5 -s5 0 0; 0 0 1 0; 0 0 0 1]",
    "5_6T = [c6 -s6 0 0; 0 0 1 l5; -s6 c6 0 0; 0 0 0 1]",
)
APPB_CORRECTED = (
    APPB_TEXT[0],
    "1_2T = [s2 c2 0 l2; 0 0 1 0; c2 -s2 0 0; 0 0 0 1]",
    "2_3T = [c3 -s3 0 0; 0 0 1 l3; -s3 -c3 0 0; 0 0 0 1]",
    "3_4T = [s4 c4 0 0; 0 0 1 0; c4 -s4 0 0; 0 0 0 1]",
    APPB_TEXT[4],
    "5_6T = [c6 -s6 0 0; 0 0 1 -l5; -s6 -c6 0 0; 0 0 0 1]",
)


def eq42_printed(alpha, beta, gamma) -> np.ndarray:
    """Eq 42 exactly as printed -> (3, 3) (or (n, 3, 3) for arrays)."""
    ca, sa, cb, sb, cg, sg = (np.cos(alpha), np.sin(alpha), np.cos(beta), np.sin(beta),
                              np.cos(gamma), np.sin(gamma))
    R = np.stack([
        np.stack([ca * cb * cg - sa * sg, -ca * cb * sg - sa * cg, ca * sb], -1),
        np.stack([ca * cb * cg - ca * sg, -sa * cb * sg + ca * cg, sa * sb], -1),  # r21 as printed
        np.stack([-sb * cg, sb * sg, cb], -1),
    ], -2)
    return R


# ----------------------------------------------------------------------------- ground truth


def _fd_position_jacobian(qs: np.ndarray, h: float = 1e-6) -> np.ndarray:
    """Central differences of the Table II tool point, (n, 3, 6) [m/rad]."""
    table = THESIS_ARM.dh_table()
    J = np.empty((len(qs), 3, 6))
    for i in range(6):
        dq = np.zeros(6)
        dq[i] = h
        J[:, :, i] = (dh_chain(table, qs + dq)[:, :3, 3] - dh_chain(table, qs - dq)[:, :3, 3]) / (2 * h)
    return J


def _rot_angle(Ra: np.ndarray, Rb: np.ndarray) -> np.ndarray:
    """Geodesic angle [rad] between rotations, (n,)."""
    return Rotation.from_matrix(np.einsum("nji,njk->nik", Ra, Rb)).magnitude()


def _special_joints() -> np.ndarray:
    """The 3^6 = 729 corners {lower, 0, upper} of Table I (exact limits, where signs flip)."""
    grid = np.stack([THESIS_ARM.q_min, np.zeros(6), THESIS_ARM.q_max], axis=1)  # (6, 3)
    idx = np.indices((3,) * 6).reshape(6, -1).T
    return grid[np.arange(6), idx]


def _samples(ctx, salt: str, full: int, quick: int) -> np.ndarray:
    """Uniform q in Table I widened by BEYOND, plus (full runs) the 729 limit corners."""
    qs = sample_joints(ctx.rng(salt), ctx.n(full, quick))
    return qs if ctx.quick else np.concatenate([qs, _special_joints()])


# ----------------------------------------------------------------------------- checks


@register(SECTION, order=10.0)
def table_ii_encoding(ctx):
    """Table II and Table I as printed vs what iik.THESIS_ARM and the URDF encode."""
    printed = table_ii_printed()
    ours = THESIS_ARM.dh_table()
    d_rows = max(abs(getattr(a, k) - getattr(b, k))
                 for a, b in zip(printed.rows, ours.rows, strict=True) for k in ("alpha", "a", "d", "offset"))
    tm = thesis_model()
    lo, hi = tm.model.lowerPositionLimit, tm.model.upperPositionLimit
    d_lim = max(np.abs(lo - np.array(printed.lower)).max(), np.abs(hi - np.array(printed.upper)).max())
    revolute = [tm.model.joints[i].shortname() for i in range(1, tm.model.njoints)]
    ok_types = all(t.startswith("JointModelR") for t in revolute) and tm.model.nq == 6
    rows = [
        Row("The DH parameters of the arm are those of Table II (modified DH, offsets -90, -90, "
            "+90 deg on joints 2, 4, 5; d6 = -l5).", "Table II",
            "Printed table transcribed symbolically, lengths substituted, compared field by field "
            "with iik.THESIS_ARM.dh_table()",
            f"max |difference| = {d_rows:.1e} (rad or m)",
            Verdict.HOLDS if d_rows == 0 else Verdict.DOES_NOT_HOLD),
        Row("Joint limits are those of Table I.", "Table I",
            "urdf/thesis_arm.urdf loaded by Pinocchio; lower/upper position limits vs the printed "
            "degrees converted to rad; joint types",
            f"max |limit difference| = {d_lim:.1e} rad; {tm.model.nq} joints, types "
            f"{sorted(set(revolute))}",
            Verdict.HOLDS if d_lim <= 1e-15 and ok_types else Verdict.DOES_NOT_HOLD),
    ]
    return rows


@register(SECTION, order=11.0)
def urdf_is_generated(ctx):
    """The committed URDF is the generator's output."""
    committed = urdf_path().read_text(encoding="utf-8")
    same = committed == thesis_urdf()
    tm = thesis_model()
    fig = new_figure(figsize=(11, 5.2))
    for k, q in enumerate((np.zeros(6), np.array([0.5, -0.6, 0.4, 1.1, 0.7, 0.3]))):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        draw_collision(ax, tm.model, tm.collision_model, q)
        draw_arm(ax, q, color="k", lw=1, markersize=2)
        ax.set_xlim(-0.2, 1.0)
        ax.set_ylim(-0.5, 0.5)
        ax.set_zlim(0.0, 1.0)
        ax.set_box_aspect((1.2, 1.0, 1.0))
        ax.view_init(elev=20, azim=-60)
        ax.set_title(("home pose (Fig 8)" if k == 0 else _fmt_q(q)), fontsize=7)
    fig.suptitle("Assumed PowerCube collision shapes of urdf/thesis_arm.urdf (one colour per link)",
                 fontsize=9)
    fpath, frel = ctx.figure_path("collision_geometry.png")
    fig.savefig(fpath, dpi=90)
    return Row("urdf/thesis_arm.urdf is the output of iik.urdf.thesis_urdf() (Table I, Table II, "
               "speeds, efforts, collision shapes).", "Table I, Table II",
               "Byte comparison of the shipped file with the generator output",
               f"{len(committed)} bytes, identical: {same}",
               Verdict.HOLDS if same else Verdict.DOES_NOT_HOLD, figures=(frel,))


def _hist(ctx, name, series, xlabel, title):
    fig = new_figure(figsize=(6.4, 3.6))
    ax = fig.add_subplot()
    for label, v in series:
        v = np.maximum(np.asarray(v), 1e-19)
        ax.hist(np.log10(v), bins=40, alpha=0.6, label=label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("count")
    ax.set_title(title)
    ax.legend(fontsize=8)
    rel = ctx.save_figure(fig, name, dpi=90)
    return rel


@register(SECTION, order=12.0)
def eq4_vs_pinocchio(ctx):
    """Eq 4 (as printed) vs Pinocchio FK of the URDF vs the Table II DH product."""
    qs = _samples(ctx, "eq4", 20000, 400)
    T_pr = eq4_printed(qs)
    T_pin = tool_poses(qs)
    T_dh = dh_chain(table_ii_printed(), qs)
    T_iik = fk(qs)
    dp = {k: np.linalg.norm(T[:, :3, 3] - T_pin[:, :3, 3], axis=1)
          for k, T in (("eq4", T_pr), ("dh", T_dh), ("iik", T_iik))}
    dr = {k: _rot_angle(T[:, :3, :3], T_pin[:, :3, :3])
          for k, T in (("eq4", T_pr), ("dh", T_dh), ("iik", T_iik))}
    dr_entry = np.abs(T_pr[:, :3, :3] - T_pin[:, :3, :3]).max(axis=(1, 2))
    worst = int(np.argmax(dp["eq4"]))
    ok = dp["eq4"].max() <= TOL_EXACT and dr["eq4"].max() <= TOL_EXACT and dr_entry.max() <= TOL_EXACT
    fig = _hist(ctx, "eq4_errors.png",
                [("Eq 4 printed |dp|", dp["eq4"]), ("Table II DH product |dp|", dp["dh"]),
                 ("Eq 4 printed rotation angle", dr["eq4"])],
                "log10 error vs Pinocchio [m or rad]", f"Eq 4 vs Pinocchio, {len(qs)} q")
    # the arm at a few poses, in the thesis base frame
    f2 = new_figure(figsize=(6.4, 5.2))
    ax = f2.add_subplot(projection="3d")
    draw_scene(ax)
    poses = np.array([np.zeros(6), [0.6, -0.5, 0.3, 0.9, -0.4, 0.0], [-1.2, 0.4, -0.6, 1.3, 0.8, 0.0],
                      [2.2, -1.0, 1.0, -0.5, 1.2, 0.0]])
    for q in poses:
        draw_arm(ax, q, label=_fmt_q(q[:5]).replace(" rad", ""))
        ax.scatter(*tool_poses(q[None])[0, :3, 3], marker="x", color="k", s=40)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    ax.set_title("Arm (Table II frame origins) at 4 poses, platform and floor;\n"
                 "x = Pinocchio tool point", fontsize=9)
    ax.legend(fontsize=6, loc="upper left")
    p2, rel2 = ctx.figure_path("arm_poses.png")
    f2.savefig(p2, dpi=90)
    return Row(
        "Eq 4 gives the pose of frame 6 (position of the end-effector point and orientation).",
        "Eq 4 (with Table II, Fig 8)",
        f"Eq 4 transcribed as printed; {len(qs)} q (uniform in Table I widened by {BEYOND} rad, plus "
        "the 729 corners {lower, 0, upper}^6 in full runs); vs "
        "Pinocchio framesForwardKinematics of urdf/thesis_arm.urdf (frame 'tool') and vs the generic "
        "modified-DH product of Table II",
        f"Eq 4 vs Pinocchio: max |dp| = {dp['eq4'].max():.1e} m, max rotation angle = "
        f"{dr['eq4'].max():.1e} rad, max |dR_ij| = {dr_entry.max():.1e}; Table II product vs "
        f"Pinocchio: max |dp| = {dp['dh'].max():.1e} m, angle {dr['dh'].max():.1e} rad; iik.fk vs "
        f"Pinocchio: max |dp| = {dp['iik'].max():.1e} m, angle {dr['iik'].max():.1e} rad "
        f"(worst Eq 4 position at {_fmt_q(qs[worst])}); tolerance {TOL_EXACT:g}",
        Verdict.HOLDS if ok else Verdict.DOES_NOT_HOLD,
        figures=(fig, rel2),
    )


@register(SECTION, order=13.0)
def table_ii_vs_eq4(ctx):
    """Table II (generic DH product) vs Eq 4 (printed), directly."""
    qs = _samples(ctx, "tab2", 20000, 400)
    d = np.abs(dh_chain(table_ii_printed(), qs) - eq4_printed(qs)).max(axis=(1, 2))
    return Row("Eq 4 is the product 0_1T ... 5_6T of the Table II link transforms.",
               "Table II, Eq 4",
               f"Modified-DH product of the printed Table II vs Eq 4 as printed, {len(qs)} q",
               f"max over q and entries |T_TableII - T_Eq4| = {d.max():.1e} (m for p, - for R)",
               Verdict.HOLDS if d.max() <= TOL_EXACT else Verdict.DOES_NOT_HOLD)


@register(SECTION, order=14.0)
def appendix_b(ctx):
    """Appendix B link matrices as printed vs Table II (DH formula and Pinocchio) and Eq 4."""
    qs = _samples(ctx, "appb", 2000, 100)
    table = table_ii_printed()
    tm = thesis_model()
    data = tm.model.createData()
    pin_links = np.empty((len(qs), 6, 4, 4))
    for k, q in enumerate(qs):
        pin.forwardKinematics(tm.model, data, q)
        prev = pin.SE3.Identity()
        for i in range(6):
            cur = data.oMi[i + 1]
            pin_links[k, i] = (prev.inverse() * cur).homogeneous
            prev = cur
    dh_links = np.stack([dh_link_transform(table.rows[i], qs[:, i], "modified") for i in range(6)], 1)
    printed = np.stack([np.stack(appb_modified_printed(q), 0) for q in qs], 0)  # (n, 6, 4, 4)
    rows = []
    names = ("0_1T", "1_2T", "2_3T", "3_4T", "4_5T", "5_6T")
    for i, nm in enumerate(names):
        d_pin = np.abs(printed[:, i] - pin_links[:, i]).max(axis=(1, 2))
        d_dh = np.abs(printed[:, i] - dh_links[:, i]).max(axis=(1, 2))
        det = np.linalg.det(printed[:, i, :3, :3])
        garbled = i in (1, 3)
        method = ("Printed matrix (" + ("read from garbled extracted text" if garbled else "cleanly printed")
                  + f") vs Table II row {i + 1} by Craig's link formula and vs Pinocchio's joint-to-joint "
                  f"placement oMi[{i}]^-1 oMi[{i + 1}], {len(qs)} q")
        numbers = (f"max |printed - Pinocchio| = {d_pin.max():.2g}, max |printed - DH| = {d_dh.max():.2g}; "
                   f"det of printed rotation in [{det.min():.3f}, {det.max():.3f}]")
        if d_pin.max() <= TOL_EXACT and d_dh.max() <= TOL_EXACT:
            rows.append(Row(f"Appendix B (home-pose set) {nm} is the Table II link transform.",
                            f"App. B, {nm}", method, numbers, Verdict.HOLDS))
            continue
        q = Q_COUNTEREXAMPLE  # a generic q: every wrong entry shows
        P_q = appb_modified_printed(q)[i]
        pin.forwardKinematics(tm.model, data, q)
        T_q = (data.oMi[i].inverse() * data.oMi[i + 1]).homogeneous
        diff = np.argwhere(np.abs(P_q - T_q) > 1e-9)
        entries = ", ".join(f"({r + 1},{c + 1}): printed {P_q[r, c]:+.4f}, true {T_q[r, c]:+.4f}"
                            for r, c in diff)
        what = {2: "entry (3,2) has the wrong sign: with alpha2 = -90 deg it is -c3 (the printed "
                   "rotation block is not orthonormal: det = s3^2 - c3^2)",
                5: "entry (2,4) is +l5 but Table II has d6 = -l5 (so it must be -l5, as Eq 4 also "
                   "requires), and entry (3,2) has the wrong sign (-c6), as in 2_3T"}.get(i, "")
        rows.append(Row(
            f"Appendix B (home-pose set) {nm} is the Table II link transform.", f"App. B, {nm}",
            method, numbers, Verdict.ERRATUM,
            reason="may partly be a text-extraction loss of a minus sign; the printed product "
                   "does not reproduce Eq 4 either (next row)" if i == 2 else "",
            errata=(Erratum(f"App. B {nm}", APPB_TEXT[i], APPB_CORRECTED[i],
                            f"{_fmt_q(q)}: {entries}. {what}"),),
        ))
    # the product of the printed set vs Eq 4, and of the corrected set
    prod = printed[:, 0]
    for i in range(1, 6):
        prod = prod @ printed[:, i]
    e4 = eq4_printed(qs)
    d_prod = np.abs(prod - e4).max(axis=(1, 2))
    d_corr = np.abs(np.einsum("nij,njk,nkl,nlm,nmo,nop->nip", *[pin_links[:, i] for i in range(6)])
                    - e4).max(axis=(1, 2))
    def product_with_true(indices):
        mats = [pin_links[:, i] if i in indices else printed[:, i] for i in range(6)]
        return np.einsum("nij,njk,nkl,nlm,nmo,nop->nip", *mats)

    d_only23 = np.abs(product_with_true({2}) - e4).max()
    d_only56 = np.abs(product_with_true({5}) - e4).max()
    k = int(np.argmax(d_prod))
    p_ce_printed = np.round(np.linalg.multi_dot(appb_modified_printed(Q_COUNTEREXAMPLE))[:3, 3], 4).tolist()
    p_ce_eq4 = np.round(eq4_printed(Q_COUNTEREXAMPLE)[0, :3, 3], 4).tolist()
    q0 = np.zeros(6)
    p_home = np.linalg.multi_dot(appb_modified_printed(q0))[:3, 3]
    rows.append(Row(
        "The product of the Appendix B (home-pose set) matrices gives Eq 4.", "App. B, Eq 4",
        f"Product of the six printed matrices vs Eq 4 as printed, {len(qs)} q; also the product of "
        "the true link transforms (Pinocchio)",
        f"printed product: max |dT| = {d_prod.max():.3g} (at {_fmt_q(qs[k])}); at q = 0 it puts the "
        f"tool point at {np.round(p_home, 3).tolist()} m instead of Eq 4's "
        f"{np.round(eq4_printed(q0)[0, :3, 3], 3).tolist()} m; with only 2_3T corrected: "
        f"{d_only23:.3g}; with only 5_6T corrected: {d_only56:.3g}; product of the true "
        f"link transforms: max |dT| = {d_corr.max():.1e}",
        Verdict.ERRATUM if d_prod.max() > TOL_EXACT else Verdict.HOLDS,
        errata=(Erratum("App. B (product 0_1T..5_6T)", "product of the printed matrices (2_3T, 5_6T as "
                        "printed)", "product with the corrected 2_3T and 5_6T (= Table II, = Eq 4)",
                        f"{_fmt_q(Q_COUNTEREXAMPLE)}: printed product puts the tool point at "
                        f"{p_ce_printed} m, Eq 4 at {p_ce_eq4} m"),)
        if d_prod.max() > TOL_EXACT else (),
    ))
    # first set ("original", Craig's convention without the home offsets): legible entries only
    no_offset = DHTable(rows=tuple(DHRow(r.alpha, r.a, r.d, 0.0) for r in table.rows),
                        convention="modified", lower=table.lower, upper=table.upper,
                        velocity=table.velocity)
    T01 = dh_link_transform(no_offset.rows[0], qs[:, 0], "modified")
    T12 = dh_link_transform(no_offset.rows[1], qs[:, 1], "modified")
    c1, s1, c2, s2 = np.cos(qs[:, 0]), np.sin(qs[:, 0]), np.cos(qs[:, 1]), np.sin(qs[:, 1])
    one, zero, l1 = np.ones(len(qs)), np.zeros(len(qs)), THESIS_ARM.l1
    printed01 = np.stack([np.stack(r, -1) for r in (
        (c1, -s1, zero, zero), (s1, c1, zero, zero), (zero, zero, one, one * l1),
        (zero, zero, zero, one))], 1)
    printed12_rows = np.stack([np.stack((c2, -s2, zero), -1), np.stack((zero, zero, one), -1)], 1)
    d_orig = max(np.abs(printed01 - T01).max(), np.abs(printed12_rows - T12[:, :2, :3]).max())
    rows.append(Row(
        "Appendix B first set ('original transformations', no home offsets): the legible entries.",
        "App. B, first set (legible part)",
        f"0_1T (fully legible) and the rotation rows 1-2 of 1_2T ('c2 -s2 0', '0 0 1') vs Table II "
        f"rows 1-2 with the offsets removed, {len(qs)} q",
        f"max |printed - DH| = {d_orig:.1e}",
        Verdict.HOLDS if d_orig <= TOL_EXACT else Verdict.DOES_NOT_HOLD))
    rows.append(Row(
        "Appendix B first set ('original transformations', Craig's convention without the home "
        "offsets).", "App. B, first set",
        "Transcription of the extracted text", "0_1T legible (checked in the row above); 1_2T shows "
        "only fragments ('c2 -s2 0', '0 0 1', '-l2 -c2', the last unplaceable); 2_3T..5_6T absent",
        Verdict.NOT_CHECKABLE,
        reason="the extracted text of this set is garbled beyond 0_1T (matrix brackets and rows "
               "lost); only the second (home-pose) set can be checked",
    ))
    return rows


@register(SECTION, order=15.0)
def appendix_c(ctx):
    """Each printed entry of Appendix C vs Pinocchio's frame Jacobian and finite differences."""
    qs = _samples(ctx, "appc", 3000, 200)
    pr = appc_printed(qs)
    J_pin = tool_jacobians(qs)
    J_fd = _fd_position_jacobian(qs)
    J_iik = position_jacobian(qs)
    rows, worst = [], {}
    for key, val in pr.items():
        i, j = int(key[2]) - 1, int(key[-1]) - 1
        d_pin = np.abs(val - J_pin[:, i, j])
        d_fd = np.abs(val - J_fd[:, i, j])
        worst[key] = (d_pin.max(), d_fd.max())
        ok = d_pin.max() <= TOL_EXACT and d_fd.max() <= TOL_EXACT + TOL_FD
        method = (f"Printed entry {APPC_TEXT[key]} vs Pinocchio computeFrameJacobian(frame 'tool', "
                  f"LOCAL_WORLD_ALIGNED)[{i}, {j}] and central differences (h = 1e-6 rad) of the "
                  f"Table II tool point, {len(qs)} q")
        numbers = (f"max |printed - Pinocchio| = {d_pin.max():.1e} m/rad; "
                   f"max |printed - FD| = {d_fd.max():.1e}")
        if key == "df3/dth5":
            numbers += ("; the text after this entry carries a stray '1/2' (an extraction artifact, "
                        "not part of any entry)")
        if ok:
            rows.append(Row(f"Appendix C: {key} (Eq 56).", f"App. C, Eq 56 {key}", method, numbers,
                            Verdict.HOLDS))
        else:
            k = int(np.argmax(d_pin))
            rows.append(Row(
                f"Appendix C: {key} (Eq 56).", f"App. C, Eq 56 {key}", method, numbers, Verdict.ERRATUM,
                errata=(Erratum(f"App. C {key}", APPC_TEXT[key], "d/dtheta of Eq 55 (iik.position_jacobian)",
                                f"{_fmt_q(qs[k])}: printed {val[k]:.6f}, true {J_pin[k, i, j]:.6f}"),)))
    # Eq 55: the position vector the entries differentiate
    T_pin = tool_poses(qs)
    d55 = np.linalg.norm(eq55_printed(qs) - T_pin[:, :3, 3], axis=1)
    rows.insert(0, Row(
        "Appendix C: the global position vector G_theta = [f1, f2, f3] (f3 independent of theta1, "
        "none depends on theta6) is the Eq 4 position.", "Eq 34a-c, App. C Eq 55",
        f"Eq 55 transcribed as printed (Eq 34a-c print the same three functions) vs Pinocchio's "
        f"'tool' position, {len(qs)} q",
        f"max |G_theta - p_Pinocchio| = {d55.max():.1e} m",
        Verdict.HOLDS if d55.max() <= TOL_EXACT else Verdict.DOES_NOT_HOLD))
    # the rest of the 6x6 Jacobian: iik's analytic forms vs Pinocchio
    J6 = jacobian(qs)
    d6 = np.abs(J6 - J_pin).max()
    d35 = np.abs(J_iik - J_pin[:, :3, :5]).max()
    col6 = np.abs(J_pin[:, :3, 5]).max()
    rows.append(Row(
        "Joint 6 does not move the end-effector point (Eq 34), so the position Jacobian is 3x5; "
        "iik.position_jacobian and the full 6x6 iik.jacobian agree with Pinocchio.",
        "Eq 34, App. C (Eq 56)",
        f"Pinocchio LOCAL_WORLD_ALIGNED frame Jacobian of 'tool', {len(qs)} q",
        f"max |dp/dtheta6| = {col6:.1e} m/rad; max |iik.position_jacobian - Pinocchio| = {d35:.1e}; "
        f"max |iik.jacobian - Pinocchio| (6x6) = {d6:.1e}",
        Verdict.HOLDS if max(col6, d35, d6) <= TOL_EXACT else Verdict.DOES_NOT_HOLD))
    fig = new_figure(figsize=(7.5, 3.4))
    ax = fig.add_subplot()
    keys = list(worst)
    x = np.arange(len(keys))
    ax.bar(x - 0.2, [max(worst[k][0], 1e-19) for k in keys], 0.4, label="vs Pinocchio")
    ax.bar(x + 0.2, [max(worst[k][1], 1e-19) for k in keys], 0.4, label="vs central FD")
    ax.set_yscale("log")
    ax.set_xticks(x, keys, rotation=60, fontsize=7)
    ax.set_ylabel("max |error| [m/rad]")
    ax.set_title(f"Appendix C entries as printed, {len(qs)} q")
    ax.legend(fontsize=8)
    fig.tight_layout()
    path, rel = ctx.figure_path("appc_errors.png")
    fig.savefig(path, dpi=90)
    rows[0] = Row(**{**rows[0].__dict__, "figures": (rel,)})
    return rows


@register(SECTION, order=16.0)
def eq42_vs_scipy(ctx):
    """Eq 42 as printed vs scipy's Euler rotations."""
    rng = ctx.rng("eq42")
    n = ctx.n(20000, 500)
    a, b, g = rng.uniform(-np.pi, np.pi, n), rng.uniform(0, np.pi, n), rng.uniform(-np.pi, np.pi, n)
    P = eq42_printed(a, b, g)
    ang = np.stack([a, b, g], -1)
    zyz = Rotation.from_euler("ZYZ", ang).as_matrix()
    zxz = Rotation.from_euler("ZXZ", ang).as_matrix()
    ours = euler_matrix(a, b, g)
    d_zyz = np.abs(P - zyz)  # (n, 3, 3)
    d_zxz = np.abs(P - zxz)
    bad_zyz = [(r + 1, c + 1) for r in range(3) for c in range(3) if d_zyz[:, r, c].max() > 1e-12]
    n_zxz_ok = sum(d_zxz[:, r, c].max() <= 1e-12 for r in range(3) for c in range(3))
    orth = np.abs(np.einsum("nji,njk->nik", P, P) - np.eye(3)).max(axis=(1, 2))
    d_ours = np.abs(ours - zyz).max()
    fig = new_figure(figsize=(6.4, 3.2))
    ax = fig.add_subplot()
    labels = [f"r{r + 1}{c + 1}" for r in range(3) for c in range(3)]
    x = np.arange(9)
    ax.bar(x - 0.2, np.maximum(d_zyz.max(axis=0).ravel(), 1e-17), 0.4, label="vs scipy 'ZYZ'")
    ax.bar(x + 0.2, np.maximum(d_zxz.max(axis=0).ravel(), 1e-17), 0.4, label="vs scipy 'ZXZ'")
    ax.set_yscale("log")
    ax.set_xticks(x, labels)
    ax.set_ylabel("max |printed - scipy|")
    ax.set_title(f"Eq 42 as printed, entry by entry ({n} angle triples)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fpath, frel = ctx.figure_path("eq42_entries.png")
    fig.savefig(fpath, dpi=90)
    a0, b0, g0 = 0.5, 0.7, 0.3
    P0, Z0 = eq42_printed(a0, b0, g0), Rotation.from_euler("ZYZ", [a0, b0, g0]).as_matrix()
    wrong = bool(bad_zyz) or n_zxz_ok < 9  # as printed, neither Z-Y-Z nor Z-X-Z exactly
    return Row(
        "Eq 42 is the Z-X-Z Euler-angle orientation matrix of Craig [2].", "Eq 42 (Sec 3.5.1)",
        f"Eq 42 transcribed as printed vs scipy Rotation.from_euler('ZYZ') and ('ZXZ') (intrinsic), "
        f"{n} angle triples (alpha, gamma in [-pi, pi], beta in [0, pi])",
        f"vs 'ZYZ': entries differing by > 1e-12: {bad_zyz} (max |dr21| = {d_zyz[:, 1, 0].max():.3f}, "
        f"all others <= {np.delete(d_zyz.reshape(n, 9), 3, axis=1).max():.1e}); vs 'ZXZ': only "
        f"{n_zxz_ok} of 9 entries agree; printed matrix not orthonormal: max |R^T R - I| = "
        f"{orth.max():.2f}; iik.rotations.euler_matrix (corrected) vs scipy 'ZYZ': {d_ours:.1e}",
        Verdict.ERRATUM if wrong else Verdict.HOLDS,
        figures=(frel,),
        errata=() if not wrong else (
            Erratum("Eq 42 r21", "r21 = c_a c_b c_g - c_a s_g", "r21 = s_a c_b c_g + c_a s_g",
                    f"alpha, beta, gamma = {a0}, {b0}, {g0} rad: printed r21 = {P0[1, 0]:.6f}, "
                    f"Rz Ry Rz gives {Z0[1, 0]:.6f}; printed R^T R - I has max entry "
                    f"{np.abs(P0.T @ P0 - np.eye(3)).max():.3f}"),
            Erratum("Eq 42 / Sec 3.5.1 convention", "'Z-X-Z representation convention' (Sec 3.5.1)",
                    "the other eight printed entries are Craig's Z-Y-Z, R = Rz(alpha) Ry(beta) "
                    "Rz(gamma) (scipy 'ZYZ'): z6 = [r13 r23 r33] = [c_a s_b, s_a s_b, c_b], alpha its "
                    "azimuth, beta its polar angle; iik uses Z-Y-Z (how Sec 3.5's own alpha, beta map "
                    "to these is checked in the Dexterity section)",
                    f"alpha, beta, gamma = {a0}, {b0}, {g0} rad: printed r13 = {P0[0, 2]:.6f} = Z-Y-Z "
                    f"r13; Z-X-Z r13 = s_a s_b = "
                    f"{Rotation.from_euler('ZXZ', [a0, b0, g0]).as_matrix()[0, 2]:.6f}"),
        ),
    )


@register(SECTION, order=17.0)
def ur5_generator_check(ctx):
    """The URDF generator on a robot nobody here wrote: UR5 from its standard DH table."""
    qs = np.random.default_rng([ctx.seed, 5]).uniform(-np.pi, np.pi, (ctx.n(2000, 100), 6))
    Tg, Tr = ur5_fk_pair(qs)
    B, E = solve_base_tool(Tg[:50], Tr[:50])
    d_solved = max(np.abs(B - UR5_BASE).max(), np.abs(E - UR5_TOOL).max())
    Tm = UR5_BASE @ Tg @ UR5_TOOL
    dp = np.linalg.norm(Tm[:, :3, 3] - Tr[:, :3, 3], axis=1)
    dr = _rot_angle(Tm[:, :3, :3], Tr[:, :3, :3])
    ok = dp.max() <= 1e-9
    rel = _hist(ctx, "ur5_errors.png", [("|dp| [m]", dp), ("rotation angle [rad]", dr)],
                "log10 error, generated UR5 vs ur5_robot.urdf", f"UR5 from its DH table, {len(qs)} q")
    return Row(
        "(Project claim) The DH -> URDF generator is right: the UR5 built from its published "
        "standard DH table matches example-robot-data's ur5_robot.urdf.",
        "iik.urdf (Sec 3.2 method: DH description)",
        f"Pinocchio FK of the generated URDF (frame 'tool') vs ur5_robot.urdf (frame 'tool0') at "
        f"{len(qs)} q uniform in [-pi, pi]^6, after T_ref = B T_dh E with frozen B = RotZ(pi), "
        "E = I (solved in closed form from 50 q, see verification/ur5.py)",
        f"max |dp| = {dp.max():.1e} m, max rotation angle = {dr.max():.1e} rad (tolerance 1e-9 m; "
        f"the reference file rounds pi/2 to 1.57079632679); solved B, E differ from the frozen ones "
        f"by {d_solved:.1e}",
        Verdict.HOLDS if ok else Verdict.DOES_NOT_HOLD,
        figures=(rel,),
    )


@register(SECTION, order=17.5)
def panda_generator_check(ctx):
    """The URDF generator in the modified convention on a robot nobody here wrote: Franka Panda."""
    from ..oracles.panda import panda_fk_pair, panda_models

    _, _, ref, _ = panda_models()
    lo, hi = ref.lowerPositionLimit[:7], ref.upperPositionLimit[:7]
    qs = np.random.default_rng([ctx.seed, 7]).uniform(lo, hi, (ctx.n(2000, 100), 7))
    Tg, Tr = panda_fk_pair(qs)
    B, E = solve_base_tool(Tg[:50], Tr[:50])
    d_id = max(np.abs(B - np.eye(4)).max(), np.abs(E - np.eye(4)).max())
    dp = np.linalg.norm(Tg[:, :3, 3] - Tr[:, :3, 3], axis=1)
    dr = _rot_angle(Tg[:, :3, :3], Tr[:, :3, :3])
    ok = dp.max() <= 1e-9 and dr.max() <= 1e-9
    return Row(
        "(Project claim) The DH -> URDF generator maps Craig's modified DH (Table II's convention) "
        "right: the Franka Panda built from its published modified DH table matches "
        "example-robot-data's panda.urdf.",
        "iik.urdf (Sec 3.2 method: Craig's convention)",
        f"Pinocchio FK of the generated URDF (frame 'tool' = frame 7 + 0.107 m flange) vs panda.urdf "
        f"(frame 'panda_link8') at {len(qs)} q uniform within the Panda's limits; base and tool "
        "transforms solved in closed form from 50 q",
        f"max |dp| = {dp.max():.1e} m, max rotation angle = {dr.max():.1e} rad (tolerance 1e-9); "
        f"solved base/tool transforms differ from the identity by {d_id:.1e}",
        Verdict.HOLDS if ok else Verdict.DOES_NOT_HOLD,
    )


def _point_segment_distance(p, a, b):
    u = b - a
    t = np.clip(np.einsum("ni,ni->n", p - a, u) / np.einsum("ni,ni->n", u, u), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * u), axis=1)


def _tool_to_upper_arm(qs):
    """Distance [m] from the tool point E to the upper-arm axis segment J2-J34, (n,)."""
    from iik.kinematics import joint_frames

    F = joint_frames(qs)
    return _point_segment_distance(F[:, 5, :3, 3], F[:, 1, :3, 3], F[:, 2, :3, 3])


@register(SECTION, order=18.0)
def table_i_self_collision(ctx):
    """Sec 3.2: the Table I limits were chosen "to avoid hitting the manipulator itself"."""
    from scipy.optimize import minimize

    tm = thesis_model()
    data, gdata = tm.model.createData(), pin.GeometryData(tm.collision_model)
    qs = ctx.rng("selfcol").uniform(THESIS_ARM.q_min, THESIS_ARM.q_max, (ctx.n(10000, 500), 6))
    hit = np.array([pin.computeCollisions(tm.model, data, tm.collision_model, gdata, q, True) for q in qs])
    # geometry-independent: can the tool point reach the upper-arm axis within the limits?
    d = _tool_to_upper_arm(qs)
    q0 = qs[int(np.argmin(d))]
    bounds = list(zip(THESIS_ARM.q_min, THESIS_ARM.q_max, strict=True))
    res = minimize(lambda q: float(_tool_to_upper_arm(q[None])[0]), q0, bounds=bounds, method="L-BFGS-B")
    q_star = np.clip(res.x, THESIS_ARM.q_min, THESIS_ARM.q_max)
    d_star = float(_tool_to_upper_arm(q_star[None])[0])
    holds = d_star > 0.05 and not hit.any()
    return Row(
        "The joint limits of Table I keep the arm from hitting itself.", "Sec 3.2, Table I",
        f"(a) geometry-independent: minimum over q within Table I of the distance from the tool point "
        f"(Eq 4) to the upper-arm axis segment J2-J34 (sampling {len(qs)} q, then L-BFGS-B within the "
        f"limits); (b) Coal via Pinocchio on the assumed PowerCube collision shapes of "
        f"urdf/thesis_arm.urdf (non-adjacent links), {len(qs)} q uniform within Table I",
        f"(a) min distance = {d_star * 1000:.2g} mm at {_fmt_q(q_star)} (theta4 + theta5 = "
        f"{np.degrees(q_star[3] + q_star[4]):.0f} deg folds the wrist back onto the upper arm; any "
        f"physical upper arm is thicker than this); (b) {hit.mean() * 100:.1f} % of the sampled "
        f"configurations self-collide",
        Verdict.HOLDS if holds else Verdict.DOES_NOT_HOLD,
        reason="" if holds else "the limits bound each joint separately; theta4 + theta5 can reach "
                                "238 deg, so the gripper can be folded into the upper arm",
    )
