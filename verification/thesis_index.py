"""The index of the thesis: every numbered equation, table, appendix and explicit claim.

The report opens with this index: each :class:`Item` lists the report rows that grade
it (with their verdicts), or says "definition: nothing to check" or "not checkable:
reason". Nothing may be silently missing: an item marked ``checked`` with no row is
shown as MISSING (and a test fails).

Rows are attached to items two ways:

* a row *covers* index keys (``Row.covers``, by default read from its ``reference``
  with :func:`parse_refs`: ``"Eq 9a-c"`` covers Eq 9a, 9b, 9c);
* an item names the checks that grade it (``Item.checks``, ``module:function``), for
  the claims of Chapter 4 and Sec 5.2 whose rows cite a section, not a key.

The list of equations was read from the extracted thesis text (its ``\\tag{}`` labels:
1-69 with 9a, 9b, 9c, 34b, 34c; the f1 line of Eq 34 carries no tag in the extraction
and is listed as Eq 34a).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

__all__ = [
    "Item",
    "ITEMS",
    "EQUATIONS",
    "TABLES",
    "APPENDICES",
    "parse_refs",
    "chapter_of",
    "chapter_of_reference",
    "title_of",
    "rank_of",
]

_HW = "verification.checks.hardware"
_PL = "verification.checks.planning"
_IK = "verification.checks.ik"
_PP = "verification.checks.predefined_paths"
_WS = "verification.checks.workspace"
_DX = "verification.checks.dexterity"
_SG = "verification.checks.singularities"
_KN = "verification.checks.kinematics"


@dataclass(frozen=True)
class Item:
    """One numbered equation, table, appendix or explicit claim of the thesis.

    Attributes:
        key: Index key (``"Eq 9a"``, ``"Table VI"``, ``"App. E"``, ``"Claim 4.5"``,
            ``"Sec 5.2 (2)"``).
        kind: ``"equation"``, ``"table"``, ``"appendix"``, ``"claim"`` or ``"conclusion"``.
        where: Where it is printed (section).
        title: What it says, briefly.
        status: ``"checked"``, ``"definition"`` or ``"not checkable"``.
        note: The reason for "definition" / "not checkable", or a remark.
        checks: ``module:function`` of checks whose rows grade it (besides the rows
            that cover ``key``).
    """

    key: str
    kind: str
    where: str
    title: str
    status: str = "checked"
    note: str = ""
    checks: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.status not in ("checked", "definition", "not checkable"):
            raise ValueError(f"{self.key}: unknown status {self.status!r}")
        if self.status != "checked" and not self.note:
            raise ValueError(f"{self.key}: a {self.status!r} item needs its note")


def _equations(sections: dict[str, dict[str, str]]) -> tuple[Item, ...]:
    """Index items of the numbered equations from ``{section: {number: title}}``; an equation listed in
    :data:`_DEFINITIONS` is a definition (with that note), every other one is checked."""
    items = []
    for where, titles in sections.items():
        for n, title in titles.items():
            note = _DEFINITIONS.get(n, "")
            items.append(Item(f"Eq {n}", "equation", where, title, "definition" if note else "checked", note))
    return tuple(items)


#: Equations that define rather than claim: what is checked in their place.
_DEFINITIONS = {
    "2": "the general position vector; this arm's instance is Eq 34 / Eq 55 (checked there)",
    "3": "the definition of the Jacobian; this arm's instance is Eq 35 / Eq 56 (checked there)",
    "52": "the ellipsoid equation of [19]; its radii (Eq 53) and the inside/outside test of Sec 3.6.2.2 are "
    "checked",
    "57": "the normal acceleration of Abdel-Malek [10], defined; it is evaluated through Q* (Eq 64-65)",
    "60": "a quadratic form in the parameter rates; H* (Eq 61) is checked",
    "64": "Eq 60 and Eq 62 substituted into Eq 57; Q* (Eq 65) is checked",
}
#: The numbered equations by the section that prints them: ``{section: {number: title}}``.
EQUATIONS: tuple[Item, ...] = _equations(
    {
        "Sec 2.2": {
            "1": "0_6T = 0_1T 1_2T 2_3T 3_4T 4_5T 5_6T = [R p; 0 1] (pose as product of link transforms)",
        },
        "Sec 2.4.1": {
            "2": "G_theta = [f1 f2 f3](theta_1..theta_n) for a general n-joint arm",
            "3": "D = J_theta D_theta, J_theta = [df_i/dtheta_j] for a general arm",
        },
        "Sec 3.2": {"4": "0_6T: the twelve entries r11..r33, px, py, pz of the forward kinematics"},
        "Sec 3.3.1": {
            "5": "[ED x DC] . BC = 0 (B, C, D, E coplanar)",
            "6": "p_B = [l2 c1, l2 s1, 0] is joint 2 (B; the base origin moved up by l1)",
            "7": "p_C = [l2 c1 + l3 c2 c1, l2 s1 + l3 c2 s1, -l3 s2] is joint 4 (C)",
            "8": "first simultaneous equation in theta1, theta2",
            "9": "tan(theta2) = [(r23 zD - r33 yD) c1 + (r33 xD - r13 zD) s1] / +-[(r23 xD - r13 yD) + r13 "
                 "l2 s1 - r23 l2 c1] gives theta2 from theta1",
            "9a": "x_D = p_x - r13 l5",
            "9b": "y_D = p_y - r23 l5",
            "9c": "z_D = p_z - l1 - r33 l5",
            "10": "|BC| + |DC| - l3 - l4 = 0 at the solution",
            "11": "||E|| = xD^2 + yD^2 + zD^2 + l2^2 + l3^2 - l4^2 - 2 (l2 + l3 c2)(xD c1 + yD s1) + 2 l3 "
                  "(zD s2 + l2 c2)",
            "12": "the minimum of ||E|| is at theta1 = atan2(py, px)",
            "13": "the maximum of ||E|| is at theta1 = atan2(py, px) +- pi",
        },
        "Sec 3.3.2": {
            "14": "c4 by the law of cosines",
            "15": "s4 = +-sqrt(1 - c4^2): one of the two signs is sin(theta4)",
            "16": "theta4 = atan2(s4, c4)",
        },
        "Sec 3.3.3": {
            "17": "0_5T = 0_2T 2_5T",
            "18": "0_2T^-1 0_5T = 2_5T with 0_2T^-1 and 2_5T printed",
            "19": "(0_2T^-1 0_5T)_34 = c1 yD - s1 xD = -l4 s3 s4 = (2_5T)_34",
            "20": "s3 = (s1 xD - c1 yD) / (l4 s4)",
            "21": "c3 = +-sqrt(1 - s3^2): one sign is cos(theta3)",
            "22": "theta3 = atan2(s3, c3)",
        },
        "Sec 3.3.4": {
            "23": "0_6T = 0_2T 2_6T",
            "24": "0_2T^-1 0_6T = 2_6T, whose entries used by Eq 25-26 are (1,3) = -c3 s45 and (2,3) = -c45",
            "25": "r13 c1 s2 + r23 s1 s2 + r33 c2 = -c3 s45",
            "26": "r13 c1 c2 + r23 s1 c2 - r33 s2 = -c45",
            "27": "s45 = (r13 c1 s2 + r23 s1 s2 + r33 c2) / (-c3)",
            "28": "theta5 = atan2(s45, c45) - theta4",
        },
        "Sec 3.3.5": {
            "29": "0_6T = 0_5T 5_6T",
            "30": "0_5T^-1 0_6T = 5_6T with row 3 of 0_5T^-1 and 5_6T printed",
            "31": "r11 (s1 c3 - c1 s2 s3) - r21 (c1 c3 + s1 s2 s3) - r31 c2 s3 = -s6",
            "32": "r12 (s1 c3 - c1 s2 s3) - r22 (c1 c3 + s1 s2 s3) - r32 c2 s3 = -c6",
            "33": "theta6 = atan2(s6, c6)",
        },
        "Sec 3.4.1": {
            "34": "G_theta = [f1 f2 f3]: theta6 does not move the tool point, f3 is free of theta1",
            "34a": "f1 = px of Eq 4 (printed without its tag in the extracted text)",
            "34b": "f2 = py of Eq 4",
            "34c": "f3 = pz of Eq 4",
            "35": "D = J_theta D_theta with the 3x5 Jacobian",
        },
        "Sec 3.4.4": {"36": "phi = atan2(py, px) selects region 1 (|phi| < 160 deg), 2 or 3"},
        "Sec 3.4.4.1": {
            "37": "joint 2 is at [l2 cos(phi), l2 sin(phi), l1] when theta1 = phi",
            "38": "region 1 (|phi| < 160 deg): outside the workspace iff rho1 = |p - joint 2| > l3 + l4 + l5",
        },
        "Sec 3.4.4.2": {
            "39": "regions 2/3: the farthest reach toward the point is at theta2 = -atan2(pz - l1, "
                  "sqrt(px^2 + py^2)) (link 3 aimed at the point's height)",
            "40": "joint 4 is at [(l2 - l3 c2) cos 160, (l2 - l3 c2) sin 160, l1 - l3 s2] with joint 1 at "
                  "160 deg",
            "41": "regions 2/3 (|phi| >= 160 deg): outside iff rho23 = |p - joint 4| > l4 + l5",
        },
        "Sec 3.5.1": {"42": "Euler-angle orientation matrix ('Z-X-Z convention of [2]')"},
        "Sec 3.5.2.1": {
            "43": "beta' = atan((pz - z2) / sqrt((px - x2)^2 + (py - y2)^2)) is the inclination of the line "
                  "from joint 2 to the end-effector",
            "44": "beta_max/min = beta' +- acos((l5^2 + rho^2 - (l3 + l4)^2) / (2 l5 rho)): the "
                  "inclinations of link 5 with links 3 and 4 aligned (outer SLJ boundary)",
        },
        "Sec 3.5.2.2": {
            "45": "beta_max/min = beta' +- acos((l5^2 + rho^2 - d^2) / (2 l5 rho)), d^2 = l3^2 + l4^2 - 2 "
                  "l3 l4 cos(180 - 119 deg): links 3 and 4 contracted",
        },
        "Sec 3.5.3.1": {
            "46": "alpha' = atan2(py, px) is the azimuth of the end-effector (link 5) when the entire arm "
                  "lies in one vertical plane: with beta' +- delta of Eq 43-45 it gives link 5's direction",
            "47": "h_SLJ = pz - l5 sin(beta)",
            "48": "delta = atan((h_SLJ - l1) / (l3 + l4)): the inclination of links 3-4 (aligned)",
            "49": "alpha_max/min = alpha' +- sigma, sigma = acos((rho^2 + (l5 cos b)^2 - ((l3 + l4) cos d + "
                  "l2)^2) / (2 rho l5 cos b)): links 3-4 aligned",
        },
        "Sec 3.5.3.2": {
            "50": "delta = atan((h_SLJ - l1) / phi): the inclination of links 3-4 (contracted, theta4 = "
                  "+-119 deg), phi their contracted length",
            "51": "alpha_max/min = alpha' +- sigma, sigma = acos((rho^2 + (l5 cos b)^2 - (phi cos d + "
                  "l2)^2) / (2 rho l5 cos b)): links 3-4 contracted",
        },
        "Sec 3.6.2.1": {
            "52": "ellipsoid (x - xc)^2/xr^2 + (y - yc)^2/yr^2 + (z - zc)^2/zr^2 = 1",
            "53": "x_r = w/(cos b cos a), y_r = d/(cos b sin a), z_r = h/sin a",
        },
        "Sec 4.2.1": {"54": "effort index E_i = sum_n |theta_n,i - theta_n,i-1| / 6"},
        "App. C": {
            "55": "G_theta = [f1 f2 f3] (= Eq 34a-c)",
            "56": "the 15 entries of the 3x5 Jacobian",
        },
        "App. E": {
            "57": "eta = a_n - v_t^2 / rho_0",
            "58": "q_i(lambda_i) = (qU + qL)/2 + (qU - qL)/2 sin(lambda_i)",
            "59": "N0 = null[G_q q_s]^T is the normal of the singular surface at the point",
            "60": "a_n = s'^T H* s'",
            "61": "H* = q_s^T [N0 G]_qq q_s + sum_i d(N0 G)/dq_i [q_i]_ss is the second derivative in s of "
                  "the normal component N0.G(q(s)) (a_n = s'^T H* s', Eq 60)",
            "62": "v_t^2/rho_0 = s'^T q_s^T G_q^T B^T [N0^T f]_uu B G_q q_s s'",
            "63": "B = [E f_u]^-1 E (E two independent rows of f_u) maps the tool's motion to the surface's "
                  "parameters: B G_q q_s = du*/ds",
            "64": "eta = s'^T Q* s'",
            "65": "Q* = H* - q_s^T G_q^T B^T [N0^T f]_uu B G_q q_s; the sign of its eigenvalues",
            "66": "sigma = N0^T G_qi delta q_i",
            "67": "delta q_i = +1 at a lower limit, -1 at an upper limit",
            "68": "K-bar = G_qi^T B^T [N0 G]_uu B G_qi - [N0 G]_qiqi, the difference in normal curvature, is "
                  "minus the second derivative of the tool's normal distance from the surface along joint i "
                  "(where Eq 66 = 0)",
            "69": "f(1) at A1: [(l2+l3+l4) c1 + l5 c1 c5 + l5 s1 s3 s5; ...; l5 c3 s5 + l1]",
        },
    }
)

def _table(number: str, where: str, title: str) -> Item:
    return Item(f"Table {number}", "table", where, title)


def _appendix(letter: str, title: str, status="checked", note="", checks=()) -> Item:
    return Item(f"App. {letter}", "appendix", f"App. {letter}", title, status, note, tuple(checks))


TABLES: tuple[Item, ...] = (
    _table("I", "Sec 3.2", "joint limits"),
    _table("II", "Sec 3.2", "Denavit-Hartenberg parameters"),
    _table("III", "Sec 3.6.3", "coordinates of the four via-points"),
    _table("IV", "Sec 3.6.3", "via-points required between regions A-G"),
    _table("V", "App. A", "PowerCube functions used"),
    _table("VI", "App. D", "type I and type II singularity sets s(1)-s(37)"),
    _table("VII", "App. D", "type III singularity sets s(38)-s(117)"),
)

APPENDICES: tuple[Item, ...] = (
    _appendix("A", "operational functions (Table V)"),
    _appendix("B", "link transformation matrices"),
    _appendix("C", "Jacobian (Eq 55-56)"),
    _appendix("D", "singularity sets (Tables VI-VII)"),
    _appendix("E", "normal-acceleration test at A1, A2, A6 (Eq 57-69)"),
    _appendix(
        "F",
        "the RoboWorks simulator",
        "not checkable",
        "a description of third-party software (RoboWorks 3.0) with no claim about the arm",
    ),
    _appendix("G", "the C++ program; relocating a point outside the workspace"),
    _appendix(
        "H",
        "joint angles and effort of the remaining nine scenarios",
        checks=(f"{_PL}:check_scenarios", f"{_PL}:check_smooth_joints"),
    ),
    _appendix(
        "I",
        "experimental errors of the remaining nine scenarios",
        "not checkable",
        "measurements of the real arm (Figs 84-110); the simulated arm cannot reproduce them "
        "(see the Sec 4.3 rows)",
        checks=(f"{_HW}:check_real_arm",),
    ),
)


def _claim(key, where, title, checks=(), status="checked", note="", kind="claim") -> Item:
    return Item(key, kind, where, title, status, note, tuple(checks))


CLAIMS: tuple[Item, ...] = (
    _claim(
        "Claim 3.1",
        "Sec 3.2",
        "the joint limits of Table I avoid hitting the manipulator itself",
        (f"{_KN}:table_i_self_collision",),
    ),
    _claim(
        "Claim 3.2",
        "Sec 3.3.1",
        "B, C, D and E lie in one plane regardless of the joint angles",
        (f"{_IK}_equations:eq5_coplanar",),
    ),
    _claim(
        "Claim 3.3",
        "Sec 3.3.3",
        "combining theta3 and theta4 gives four configurations per theta1 root",
        (f"{_IK}:four_configurations",),
    ),
    _claim(
        "Claim 3.4",
        "Sec 3.3.5",
        "up to 8 solutions, 16 in special cases; at least two (theta1, theta2) sets",
        (f"{_IK}:solution_counts", f"{_IK}:solution_counts_table_i"),
    ),
    _claim(
        "Claim 3.5",
        "Sec 3.3.1",
        "the theta1 scan with Eq 12-13 finds every solution (no misdetection)",
        (f"{_IK}:completeness",),
    ),
    _claim(
        "Claim 3.6", "Sec 3.4.3", "the workspace has no interior boundary", (f"{_WS}:no_interior_boundary",)
    ),
    _claim(
        "Claim 3.7",
        "Sec 3.4.3",
        "the exterior boundary is f(1), f(2), f(3) with the printed ranges",
        (f"{_WS}:three_surface_boundary",),
    ),
    _claim(
        "Claim 3.8",
        "Sec 3.4.2 / App. D",
        "Tables VI-VII list all the singularities found",
        (f"{_SG}:missing_singularities",),
    ),
    _claim("Claim 3.9", "Sec 3.5.1", "gamma has no limits: it only turns joint 6", (f"{_DX}:gamma_free",)),
    _claim(
        "Claim 3.10",
        "Sec 3.6.2.1",
        "the ellipsoid of Eq 53 touches every corner of the box",
        (f"{_PL}:check_eq53_ellipsoid",),
    ),
    _claim(
        "Claim 4.1", "Sec 4.2.1", "39 steps per segment keep every step within 30 mm", (f"{_PP}:step_length",)
    ),
    _claim(
        "Claim 4.2",
        "Sec 4.2.1.1, 4.2.1.2",
        "between the via-points of paths 1 and 2 the straight line had "
        "no solutions at the given orientations; an arc had",
        (f"{_PL}:check_arc_route",),
    ),
    _claim(
        "Claim 4.3",
        "Sec 4.2.1.1 (Figs 31, 35, 39)",
        "IIK and Newton give exactly the same joint values along the predefined paths",
        (f"{_PP}:iik_vs_newton",),
    ),
    _claim(
        "Claim 4.4",
        "Sec 4.2.1.1 (Figs 32, 36, 40)",
        "so the effort index (Eq 54) of both is identical",
        (f"{_PP}:iik_vs_newton",),
    ),
    _claim(
        "Claim 4.5",
        "Sec 4.2.1.1",
        "the IIK finds up to 8 solutions per position, Newton one",
        (f"{_IK}:solution_counts", f"{_IK}:solution_counts_table_i"),
    ),
    _claim(
        "Claim 4.6",
        "Sec 4.2.1.3",
        "the IIK derives multiple configurations whenever a solution exists",
        (f"{_IK}:completeness", f"{_PP}:iik_along_paths"),
    ),
    _claim(
        "Claim 4.7",
        "Sec 4.2.1.3 (Figs 33, 37, 41)",
        "the IIK needs less computation per solution than pseudo-inverse Newton",
        (f"{_IK}:benchmark",),
    ),
    _claim(
        "Claim 4.8",
        "Sec 4.2.2 (Fig 42)",
        "the planner gives collision-free paths in ten scenarios, with a "
        "safety zone between ellipsoid and path",
        (f"{_PL}:check_scenarios",),
    ),
    _claim(
        "Claim 4.9",
        "Sec 4.2.2 (Fig 42e)",
        "the planner chose two via-points to cross regions (Table IV)",
        (f"{_PL}:check_fig42e_via_points",),
    ),
    _claim(
        "Claim 4.10",
        "Sec 4.2.2 (Figs 43-44)",
        "the joint angles change smoothly from step to step",
        (f"{_PL}:check_smooth_joints",),
    ),
    _claim(
        "Claim 4.11",
        "Sec 4.2.2",
        "joint speeds were chosen proportional to the effort index",
        (f"{_PL}:check_thesis_timing",),
        "definition",
        "a design choice, not a claim: the thesis does not say the timing is feasible; whether it respects "
        "the speed and acceleration limits is a project-standard row",
    ),
    _claim(
        "Claim 4.12",
        "Sec 4.3, App. A",
        "PCube_moveStep follows the path: it takes a goal position and a time",
        (f"{_HW}:check_table_v",),
    ),
    _claim(
        "Claim 4.13",
        "Sec 4.3",
        "waiting for each step stops the joints (vibrations); sending the next "
        "command at 95 % removes the stops and adds some error",
        (f"{_HW}:check_early_update",),
    ),
    _claim(
        "Claim 4.14",
        "Sec 4.3.1",
        "the maximum end-effector error on predefined paths is <= 10 mm",
        (f"{_HW}:check_predefined_10mm",),
    ),
    _claim(
        "Claim 4.15",
        "Sec 4.3.2",
        "the error at the start and end of each path is zero",
        (f"{_HW}:check_safety_zone_30mm",),
    ),
    _claim(
        "Claim 4.16",
        "Sec 4.3.2 (Figs 54-55)",
        "a 30 mm safety zone suffices in motion; the mean error stays low",
        (f"{_HW}:check_safety_zone_30mm",),
    ),
    _claim(
        "Claim 4.17",
        "Sec 4.3.1-4.3.2",
        "the real arm's joint and end-effector errors (Figs 46-56)",
        (f"{_HW}:check_real_arm",),
        "not checkable",
        "needs the real PowerCube arm; the simulator's lag and current model are assumptions",
    ),
    _claim(
        "Claim 4.18",
        "Sec 4.3.2 (Fig 56)",
        "abrupt velocity changes on some joints caused no difficulty",
        status="not checkable",
        note="a statement about the real arm's behaviour (no measurement printed)",
    ),
    _claim(
        "Claim 4.19",
        "Sec 4.3",
        "visual inspection ensured the arm did not collide with an obstacle",
        status="not checkable",
        note="an observation of the experiments; the simulated counterpart is the "
        "measured clearance in the Sec 4.3.2 row",
    ),
)

CONCLUSIONS: tuple[Item, ...] = (
    _claim(
        "Sec 5.2 (1)",
        "Sec 5.2",
        "the IIK computed the joint angles at every position of the predefined "
        "paths and found all possible solutions",
        (f"{_PP}:iik_along_paths", f"{_IK}:completeness"),
        kind="conclusion",
    ),
    _claim(
        "Sec 5.2 (2)",
        "Sec 5.2",
        "the IIK needs less computation per solution than pseudo-inverse Newton",
        (f"{_IK}:benchmark",),
        kind="conclusion",
    ),
    _claim(
        "Sec 5.2 (3)",
        "Sec 5.2",
        "the workspace analysis identifies the reachable points; most parametric surfaces are not boundaries",
        (f"{_WS}:three_surface_boundary", f"{_WS}:no_interior_boundary"),
        kind="conclusion",
    ),
    _claim(
        "Sec 5.2 (4)",
        "Sec 5.2",
        "the algorithm recognised whether a position is inside the workspace in "
        "every trial; the analysis describes the boundaries accurately",
        (f"{_WS}:eq36_41",),
        kind="conclusion",
    ),
    _claim(
        "Sec 5.2 (5)",
        "Sec 5.2",
        "with the dexterity analysis at least one solution was obtained at any "
        "position inside the workspace when suitable orientations were chosen",
        (f"{_DX}:printed_admitted_set",),
        kind="conclusion",
    ),
    _claim(
        "Sec 5.2 (6)",
        "Sec 5.2",
        "obstacle avoidance verified in ten scenarios; smooth joint motion, minimum vibration",
        (f"{_PL}:check_scenarios", f"{_PL}:check_smooth_joints", f"{_HW}:check_early_update"),
        kind="conclusion",
    ),
    _claim(
        "Sec 5.2 (7)",
        "Sec 5.2",
        "the methods may interest engineers working on similar arms",
        status="not checkable",
        note="an opinion, not a measurable claim",
        kind="conclusion",
    ),
)

TEXT: tuple[Item, ...] = (
    _claim(
        "Cross-references",
        "whole text",
        "tables, figures, sections, points and references cited in the text",
        ("verification.checks.text:cross_references",),
    ),
)

#: Every index item, in report order.
ITEMS: tuple[Item, ...] = EQUATIONS + TABLES + APPENDICES + CLAIMS + CONCLUSIONS + TEXT

_ROMAN = r"(?:VII|VI|V|IV|III|II|I)"
_EQ_TOKEN = r"\d+[a-c]?(?:\s*-\s*(?:\d+[a-c]?|[a-c]))?"
_EQ = re.compile(rf"\bEqs?\.?\s+({_EQ_TOKEN}(?:\s*,\s*{_EQ_TOKEN})*)")
_TAB = re.compile(rf"\bTables?\s+({_ROMAN})(?:\s*-\s*({_ROMAN}))?\b")
_APP = re.compile(r"\b(?:App\.|Appendix)\s*([A-I])\b")
_ROMANS = ("I", "II", "III", "IV", "V", "VI", "VII")


def _expand_eq(token: str) -> list[str]:
    token = token.replace(" ", "")
    if "-" not in token:
        return [f"Eq {token}"]
    a, b = token.split("-")
    num_a, suf_a = re.match(r"(\d+)([a-c]?)", a).groups()
    if re.fullmatch(r"[a-c]", b):  # "9a-c"
        return [f"Eq {num_a}{chr(c)}" for c in range(ord(suf_a or "a"), ord(b) + 1)]
    num_b = re.match(r"(\d+)", b).group(1)
    return [f"Eq {k}" for k in range(int(num_a), int(num_b) + 1)]


def parse_refs(reference: str) -> tuple[str, ...]:
    """Index keys named in a free-text reference.

    >>> parse_refs("Eq 9a-c, Table VI, App. D")
    ('Eq 9a', 'Eq 9b', 'Eq 9c', 'Table VI', 'App. D')
    """
    keys: list[str] = []
    for m in _EQ.finditer(reference):
        for token in m.group(1).split(","):
            keys += _expand_eq(token.strip())
    for m in _TAB.finditer(reference):
        a = _ROMANS.index(m.group(1))
        b = _ROMANS.index(m.group(2)) if m.group(2) else a
        keys += [f"Table {_ROMANS[k]}" for k in range(a, b + 1)]
    keys += [f"App. {m.group(1)}" for m in _APP.finditer(reference)]
    return tuple(dict.fromkeys(keys))


def chapter_of(key: str) -> str:
    """The report chapter of an index key: ``"Chapter 2"`` ... ``"Appendices"``."""
    item = _BY_KEY.get(key)
    where = item.where if item else key
    if where == "whole text":
        return "Text"
    if where.startswith("App.") or key.startswith("App."):
        return "Appendices"
    m = re.match(r"Sec (\d)", where)
    return f"Chapter {m.group(1)}" if m else "Other"


def chapter_of_reference(reference: str) -> str:
    """The chapter of a free-text reference: its first index key, else its first 'Sec N' or 'App.'."""
    keys = parse_refs(reference)
    if keys:
        return chapter_of(keys[0])
    m = re.search(r"\bSec (\d)|\b(App\.|Appendix)", reference)
    if not m:
        return "Other"
    return f"Chapter {m.group(1)}" if m.group(1) else "Appendices"


_BY_KEY = {it.key: it for it in ITEMS}
_RANK = {it.key: k for k, it in enumerate(ITEMS)}


def _item(reference: str) -> Item:
    keys = parse_refs(reference) or (reference,)
    if keys[0] not in _BY_KEY:
        raise KeyError(f"{reference!r} names no item of the thesis index")
    return _BY_KEY[keys[0]]


def title_of(reference: str) -> str:
    """The index title of the first item a reference names (``"Eq 16"`` -> ``"theta4 = atan2(s4, c4)"``):
    what a check of it claims, written once.

    Raises:
        KeyError: the reference names no index item.
    """
    return _item(reference).title


def rank_of(reference: str) -> int:
    """The position in the index (report order) of the first item a reference names.

    Raises:
        KeyError: the reference names no index item.
    """
    return _RANK[_item(reference).key]
