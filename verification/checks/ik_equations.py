"""Sec 3.3 (IIK), Eq 5-33 one by one: each printed step against exact geometry.

Ground truth is Pinocchio on ``urdf/thesis_arm.urdf`` at random joint vectors q within
Table I: the joint points B (frame 2), C (frames 3-4), D (frame 5, the wrist) and E
(frame 6, the tool point), in the frame of Sec 3.3.1 (base origin moved up by l1), the
tool pose T = 0_6T, and the link transforms between frames. Every equation is measured
on its own, fed with exact inputs (the generating q and the true points), so one
erratum does not hide or fake another. Each check takes the printed form as its
argument and declares a known-good form and the slips a person could make in it for
the self-test.

The sample covers the whole of Table I uniformly and, where the formulas are hardest, the
neighbourhoods of their singular values (theta3 = +-90 deg, theta4 = 0, theta5 = 0,
theta4 + theta5 = 0 or 180 deg, joints on their limits) to within 10^U(-9, -2) rad. A formula
that divides by a quantity that vanishes there (Eq 20 by s4, Eq 27 by c3) or takes
sqrt(1 - x^2) near |x| = 1 (Eq 15, 21) is graded on its error times that quantity: exact
formulas evaluated in floating point lose accuracy as eps / |s4| there, and a tolerance on
the raw error would flip with the sampling, not with the formula. Steps that are identities
when fed the true values (Eq 10, 15-17, 21-23, 28, 29, 33) hold by construction and say why
(``Row.basis``). Each erratum is re-derived by a second reading (Table II chains by
``iik.dh``, not Pinocchio) over the nearby readings of its inputs.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from functools import partial

import numpy as np
from scipy.optimize import minimize_scalar

import iik
from iik.dh import dh_chain, dh_link_transform

from ..assumptions import EXACT_GEOMETRY
from ..formula import Formula, error_row, per_run
from ..numbers import fmt_q
from ..oracles.pinocchio_model import joint_placements
from ..registry import Erratum, Forms, Measure, Row, Section, Slip, SlipKind, Verdict, epsilon
from ..second_reading import Kind, Reading, search
from ..shorthand import cos_sin, wrap
from ..thesis_index import title_of
from .kinematics import appb_reading, rotation_transposed

ARM = iik.THESIS_ARM
L1, L2, L3, L4, L5 = ARM.lengths
_EZ = np.array([0.0, 0.0, 1.0])
TOL = 1e-12  # [m], [m^2], [-]: an identity evaluated in floating point
TOL_ANGLE = 1e-9  # [rad]: an angle recovered through atan2 / sqrt
SECTION = Section(
    "Inverse kinematics (Sec 3.3 IIK, Eq 5-33, solution counts, cost)",
    depends_on=EXACT_GEOMETRY,
    prefix="ik",
    order=20.0,
)


@dataclass(frozen=True)
class Sample:
    """Exact geometry at random q within Table I (arrays over n samples; m, rad).

    F are the joint placements 0_iT (base frame, i = 0..6; Pinocchio, or the iik.dh chain for a second
    reading); B, C, D, E the joint points of frames 2, 3, 5, 6 in the Sec 3.3.1 frame (origin moved up
    by l1). The last ``hard`` samples sit near the singular values (:func:`hard_joints`).
    """

    q: np.ndarray
    F: np.ndarray
    hard: int = 0

    B = property(lambda self: self.F[:, 2, :3, 3] - L1 * _EZ)
    C = property(lambda self: self.F[:, 3, :3, 3] - L1 * _EZ)
    D = property(lambda self: self.F[:, 5, :3, 3] - L1 * _EZ)
    E = property(lambda self: self.F[:, 6, :3, 3] - L1 * _EZ)
    R = property(lambda self: self.F[:, 6, :3, :3])
    p = property(lambda self: self.F[:, 6, :3, 3])

    @property
    def domain(self) -> str:
        return (
            f"{len(self.q) - self.hard} q uniform in Table I plus {self.hard} near the singular values "
            "(theta3 = +-90 deg, theta4 = 0, theta5 = 0, theta4 + theta5 = 0 or 180 deg, within 10^U(-9, -2) "
            "rad; a joint on its limit)"
        )

    def __len__(self) -> int:
        return len(self.q)

    def at(self, k: int) -> str:
        return fmt_q(self.q[k])

    def c(self, j: int) -> np.ndarray:
        return np.cos(self.q[:, j - 1])

    def s(self, j: int) -> np.ndarray:
        return np.sin(self.q[:, j - 1])

    def rel(self, i: int, j: int) -> np.ndarray:
        """i_jT = (0_iT)^-1 0_jT, (n, 4, 4)."""
        return np.linalg.inv(self.F[:, i]) @ self.F[:, j]


def make_sample(q: np.ndarray, hard: int = 0) -> Sample:
    """The :class:`Sample` of ``q`` from Pinocchio (the ground truth)."""
    return Sample(q, joint_placements(q), hard)


def dh_sample(q: np.ndarray) -> Sample:
    """The :class:`Sample` of ``q`` from the iik.dh chain instead of Pinocchio (second readings)."""
    return Sample(q, np.concatenate([np.broadcast_to(np.eye(4), (len(q), 1, 4, 4)), chain_frames(q)], 1))


def hard_joints(rng: np.random.Generator, n: int) -> np.ndarray:
    """``n`` joint vectors [rad] within Table I, each with one singular combination nearly or exactly at
    its singular value: theta3 = +-90 deg, theta4 = 0, theta5 = 0, theta4 + theta5 = 0, theta4 + theta5 =
    +-180 deg (off by 10^U(-9, -2) rad), or one joint exactly on a limit."""
    q = rng.uniform(ARM.q_min, ARM.q_max, size=(n, 6))
    kind = np.arange(n) % 6
    tiny = rng.choice([-1.0, 1.0], n) * 10 ** rng.uniform(-9, -2, n)
    sgn = rng.choice([-1.0, 1.0], n)
    q[kind == 0, 2] = (sgn * np.pi / 2 + tiny)[kind == 0]
    q[kind == 1, 3] = tiny[kind == 1]
    q[kind == 2, 4] = tiny[kind == 2]
    q[kind == 3, 4] = (-q[:, 3] + tiny)[kind == 3]
    t4 = sgn * rng.uniform(np.radians(62), np.radians(118), n)
    q[kind == 4, 3] = t4[kind == 4]
    q[kind == 4, 4] = (sgn * np.pi - t4 + tiny)[kind == 4]
    at = kind == 5
    j = rng.integers(0, 6, n)
    q[at, j[at]] = np.where(rng.random(n) < 0.5, ARM.q_min[j], ARM.q_max[j])[at]
    return np.clip(q, ARM.q_min, ARM.q_max)


@per_run
def sample(ctx) -> Sample:
    """The sample of this run: q uniform within Table I, then the hard ones (:func:`hard_joints`)."""
    q = ctx.rng("ik-equations").uniform(ARM.q_min, ARM.q_max, size=(ctx.n(3000, 300), 6))
    h = hard_joints(ctx.rng("ik-equations-hard"), ctx.n(1200, 120))
    return make_sample(np.concatenate([q, h]), hard=len(h))


#: Why the one-line steps hold by construction when fed the true sine and cosine.
_ATAN2_BASIS = ("atan2 of the true sine and cosine returns the angle: an identity of atan2, not a fact about "
                "the arm")
_PYTHAGORAS = ("+-sqrt(1 - x^2) with the true cosine (sine) is +-|sine| (cosine): Pythagoras, not a fact "
               "about the arm; which sign is right is graded by ik.four_configurations")
_SAME_TABLE = ("Pinocchio's model is generated from the same Table II (urdf/thesis_arm.urdf), so the "
               "product of its link transforms is its pose by associativity: an identity, not evidence about "
               "the thesis")


# ----------------------------------------------------------------------------- Eq 5-8
def _triple(E, D, C, v):
    """[ED x DC] . v, row by row."""
    return np.einsum("ni,ni->n", np.cross(D - E, C - D), v)


def eq5_printed(E, D, C, B):
    """[ED x DC] . BC (Eq 5), vectors as differences of the points."""
    return _triple(E, D, C, C - B)


@SECTION.check("Eq 5", forms=Forms(
    eq5_printed, lambda E, D, C, B: np.linalg.det(np.stack([D - E, C - D, C - B], 1)),
    "det[ED, DC, BC] (numpy)",
    (Slip(SlipKind.SWAP, "the base axis z0 written for BC",
          lambda E, D, C, B: _triple(E, D, C, np.broadcast_to(_EZ, B.shape))),
     Slip(SlipKind.OFF_BY_ONE, "AB (from the base) for BC (the letters one off)",
          lambda E, D, C, B: _triple(E, D, C, B))),
    epsilon(eq5_printed, 1e-9)))
def eq5_coplanar(ctx, triple):
    """Eq 5: B, C, D, E coplanar; ED along z6 = [r13 r23 r33]."""
    s = sample(ctx)
    ed = (s.D - s.E) / np.linalg.norm(s.D - s.E, axis=1, keepdims=True)
    m = (
        Measure("max |[ED x DC] . BC|", np.abs(triple(s.E, s.D, s.C, s.B)).max(), TOL, "m^3"),
        Measure("max |ED/|ED| - z6|", np.abs(ed - s.R[:, :, 2]).max(), TOL),
    )
    return Row.graded(
        "B, C, D and E lie in one plane for every q: [ED x DC] . BC = 0, with ED along the end-effector "
        "z axis [r13 r23 r33].",
        "Eq 5 (Sec 3.3.1)",
        f"Eq 5 with the true joint points (Pinocchio) at {len(s.q)} random q in Table I",
        None,
        m,
        fail=Verdict.DOES_NOT_HOLD,
        id="eq5",
        domain=s.domain,
    )


def eq6_printed(th1):
    return np.stack([L2 * np.cos(th1), L2 * np.sin(th1), np.zeros_like(th1)], 1)


def _eq6_rot(th1):
    return np.einsum("nij,j->ni", iik.euler_matrix(th1, np.zeros_like(th1), np.zeros_like(th1)), [L2, 0, 0])


def eq7_printed(th1, th2):
    c1, s1, c2, s2 = cos_sin(th1, th2)
    return np.stack([L2 * c1 + L3 * c2 * c1, L2 * s1 + L3 * c2 * s1, -L3 * s2], 1)


def _link3(th1, th2):
    """The unit vector of link 3 (from B to C)."""
    return np.stack([np.cos(th2) * np.cos(th1), np.cos(th2) * np.sin(th1), -np.sin(th2)], 1)


def eq8_printed(R, D, th1, th2):
    r13, r23, r33 = R[:, 0, 2], R[:, 1, 2], R[:, 2, 2]
    x, y, z = D.T
    c1, s1, c2, s2 = cos_sin(th1, th2)
    return (
        (r23 * z - r33 * y) * c2 * c1
        + (r33 * x - r13 * z) * c2 * s1
        + (r23 * x - r13 * y) * s2
        + r13 * L2 * s1 * s2
        - r23 * L2 * c1 * s2
    )


def eq8_geometric(R, D, th1, th2):
    """z6 . ((D - B) x u): Eq 5 with Eq 6-7 substituted (u the unit vector of link 3)."""
    return np.einsum("ni,ni->n", R[:, :, 2], np.cross(D - eq6_printed(th1), _link3(th1, th2)))


def _eq8_swap(R, D, th1, th2):
    """Eq 8 with r13 and r23 exchanged in its last two terms."""
    r13, r23 = R[:, 0, 2], R[:, 1, 2]
    c1, s1, _, s2 = cos_sin(th1, th2)
    return eq8_printed(R, D, th1, th2) - (r13 - r23) * L2 * s1 * s2 + (r23 - r13) * L2 * c1 * s2


@SECTION.check("Eq 8", forms=Forms(
    eq8_printed, eq8_geometric, "z6 . ((D - B) x u) (Eq 5 with Eq 6-7 substituted)",
    (Slip(SlipKind.SIGN, "the r13 l2 s1 s2 term with its sign flipped",
          lambda R, D, t1, t2: eq8_printed(R, D, t1, t2) - 2 * R[:, 0, 2] * L2 * np.sin(t1) * np.sin(t2)),
     Slip(SlipKind.SWAP, "r13 and r23 exchanged in the l2 terms", _eq8_swap)),
    epsilon(eq8_printed, 1e-9)))
def eq8_plane(ctx, eq8):
    """Eq 8: the expansion of Eq 5, as an identity in (theta1, theta2) and zero at the solution."""
    s = sample(ctx)
    rng = ctx.rng("eq8-any")
    th = np.stack([rng.uniform(-np.pi, np.pi, len(s.q)), rng.uniform(-np.pi, np.pi, len(s.q))], 1)
    return _identity_row(
        s, "Eq 8", "Substituting Eq 6 and 7 into Eq 5 gives Eq 8, which vanishes at the solution.",
        f"Eq 8 as printed with the true D and z6 of {len(s.q)} random poses: (a) against the triple product "
        "of Eq 5 with Eq 6-7 at random (theta1, theta2) (Eq 8 = -[ED x DC].BC / l3), (b) at the generating "
        "(theta1, theta2)", lambda t1, t2: eq8(s.R, s.D, t1, t2), th,
        eq8_geometric(s.R, s.D, th[:, 0], th[:, 1]), "z6 . ((D - B) x u)", "[-pi, pi]^2")


def _identity_row(s: Sample, key: str, claim: str, method: str, form, th, truth, corrected: str,
                  where: str) -> Row:
    """A printed equation E(theta1, theta2) = 0 graded (a) as an identity: ``form`` against ``truth`` at the
    angles ``th`` (n, 2) uniform in ``where``, (b) at the solution: ``form`` at the generating angles."""
    ident = np.abs(form(th[:, 0], th[:, 1]) - truth)
    k = int(np.argmax(ident))
    return Row.graded(
        claim, key, method, None,
        (Measure(f"max |{key} - ({corrected})| at any (theta1, theta2)", ident.max(), TOL, "m^2"),
         Measure(f"max |{key}| at the generating q", np.abs(form(s.q[:, 0], s.q[:, 1])).max(), TOL, "m^2")),
        id=key.lower().replace(" ", ""), domain=s.domain + f"; (a) at (theta1, theta2) uniform in {where}",
        erratum=Erratum(key, f"{key} as printed", corrected, f"{fmt_q(s.q[k])}, theta1 = {th[k, 0]:.4f}, "
                        f"theta2 = {th[k, 1]:.4f}: difference {ident[k]:.3g} m^2"),
    )


# ----------------------------------------------------------------------------- Eq 9, 9a-c, 10, 11
def _pq(R, D, th1):
    r13, r23, r33 = R[:, 0, 2], R[:, 1, 2], R[:, 2, 2]
    x, y, z = D.T
    c1, s1 = cos_sin(th1)
    P = (r23 * z - r33 * y) * c1 + (r33 * x - r13 * z) * s1
    Q = (r23 * x - r13 * y) + r13 * L2 * s1 - r23 * L2 * c1
    return P, Q


def eq9_printed(R, D, th1):
    """Both branches of Eq 9, read as theta2 = atan2(numerator, +-denominator) -> (2, n)."""
    P, Q = _pq(R, D, th1)
    return np.stack([np.arctan2(P, Q), np.arctan2(P, -Q)])


def eq9_corrected(R, D, th1):
    """Eq 8 reads P c2 + Q s2 = 0: tan(theta2) = -P/Q, both branches -> (2, n)."""
    P, Q = _pq(R, D, th1)
    return np.stack([np.arctan2(-P, Q), np.arctan2(P, -Q)])


def _eq9_miss(s: Sample, eq9) -> np.ndarray:
    """|theta2 - the nearer of the form's two branches| with the true D and theta1 [rad]."""
    return np.min(np.abs(wrap(eq9(s.R, s.D, s.q[:, 0]) - s.q[:, 1])), axis=0)


# ----------------------------------------------------------------------------- second readings (iik.dh route)
def chain_frames(q: np.ndarray, d6: float | None = None) -> np.ndarray:
    """Every frame 0_iT (i = 1..6) of Table II (with its d6 [m] replaced by ``d6`` if given) by iik.dh, not
    Pinocchio: (n, 6, 4, 4)."""
    t = ARM.dh_table()
    if d6 is not None:
        t = dataclasses.replace(t, rows=t.rows[:5] + (dataclasses.replace(t.rows[5], d=d6),))
    return dh_chain(t, q, all_frames=True)


_DH_ROUTE = "the Table II chain of iik.dh.dh_chain under the reading (not Pinocchio)"


def _eq9_pair_gap(branches: np.ndarray, truth: np.ndarray, period: float) -> np.ndarray:
    """Per q, the larger of (a true solution's distance to the nearer printed branch) and (a printed
    branch's distance to the nearer true solution): zero iff the printed pair is the true pair."""
    def d(a, b):
        return np.abs((a - b + period / 2) % period - period / 2)

    miss = np.max([np.minimum(d(t, branches[0]), d(t, branches[1])) for t in truth], axis=0)
    spurious = np.max([np.minimum(d(b, truth[0]), d(b, truth[1])) for b in branches], axis=0)
    return np.maximum(miss, spurious)


def eq9_reading(ctx, s: Sample, eq9):
    """Second reading of Eq 9 (the form ``eq9``): its two branches against Eq 8's two solutions
    theta2 and theta2 + pi, the wrist point from the iik.dh chain, under the nearby readings of theta2
    (its sign, Table II's -90 deg offset, the formula read as a tangent only, theta2 mod pi)."""
    d = dh_sample(s.q)
    br = eq9(d.R, d.D, s.q[:, 0])
    stated = {"sign": 1.0, "offset": 0.0, "period": 2 * np.pi}

    def misfit(x) -> float:
        t2 = x["sign"] * s.q[:, 1] + x["offset"]
        gap = _eq9_pair_gap(br, np.stack([t2, t2 + np.pi]), x["period"])
        return float(np.nanmax(np.where(np.isnan(gap), np.inf, gap)))

    readings = [
        Reading(Kind.SIGN, "theta2 measured the other way", {"sign": -1.0}),
        Reading(Kind.CONVENTION, "theta2 without Table II's -90 deg offset", {"offset": -np.pi / 2}),
        Reading(Kind.CONVENTION, "the branches read as tangents only (theta2 mod pi)", {"period": np.pi}),
    ]
    return search(stated, readings, misfit, TOL_ANGLE, printed="tan(theta2) = P / (+-Q), both branches",
                  stated_text="theta2 of Table II (offset -90 deg), the two solutions of Eq 8 (theta2, "
                  "theta2 + pi)",
                  route=_DH_ROUTE,
                      measure="max over q of the gap between the printed and the true pair [rad]")


def eq9abc_printed(p, z6):
    """Eq 9a-c: D = [px - r13 l5, py - r23 l5, pz - l1 - r33 l5] (Sec 3.3.1 frame)."""
    return p - L5 * z6 - L1 * _EZ


def eq9abc_corrected(p, z6):
    return p + L5 * z6 - L1 * _EZ


def wrist_reading(s: Sample, eq9abc, k: int, printed: str):
    """Second reading of coordinate ``k`` of Eq 9a-c (the form ``eq9abc``): the form applied to the tool
    pose of the iik.dh chain under each nearby reading of Table II and Sec 3.3.1 (d6's sign, z6 read from
    the rotation's third row, the l1 shift of Sec 3.3.1 left out), vs that chain's frame-5 origin."""
    stated = {"d6": -L5, "transpose": False, "shift": L1}

    def misfit(x) -> float:
        F = chain_frames(s.q, d6=x["d6"])
        R = F[:, 5, :3, :3]
        z6 = R[:, 2, :] if x["transpose"] else R[:, :, 2]
        form = eq9abc(F[:, 5, :3, 3], z6) + (L1 - x["shift"]) * _EZ
        wrist = F[:, 4, :3, 3] - x["shift"] * _EZ
        return float(np.abs(form[:, k] - wrist[:, k]).max())

    readings = [
        Reading(Kind.SIGN, "d6 = +l5 (z6 pointing from the wrist to the tool, as App. B's 5_6T prints it)",
                {"d6": L5}),
        Reading(Kind.SWAP, "r13 r23 r33 read from the third row (the rotation transposed)",
            {"transpose": True}),
        Reading(Kind.CONVENTION, "the base frame not moved up by l1 (Sec 3.3.1's shift left out)",
            {"shift": 0.0}),
    ]
    return search(stated, readings, misfit, TOL, printed=printed,
                  stated_text="Table II (d6 = -l5), Eq 4's pose, Sec 3.3.1's frame moved up by l1",
                  route=_DH_ROUTE, measure="max |form - frame-5 origin| [m]")


def _wrist_length(p, z6):
    return p + L4 * z6 - L1 * _EZ


@SECTION.check("Eq 9a", forms=Forms(
    eq9abc_printed, eq9abc_corrected, "D = p + l5 z6 - l1 e_z (Table II: d6 = -l5)",
    (Slip(SlipKind.SIGN, "D = p - l5 z6 (the sign of l5)", eq9abc_printed),
     Slip(SlipKind.LENGTH, "l4 for l5", _wrist_length),
     Slip(SlipKind.TERM, "z_D without its -l1", lambda p, z6: p + L5 * z6)),
    epsilon(eq9abc_corrected, 1e-9, "each coordinate moved by 1 nm")))
def wrist_point(ctx, eq9abc):
    """Eq 9a, 9b, 9c: the wrist point D (joint 5) from the pose, one row per coordinate."""
    s = sample(ctx)
    err = eq9abc(s.p, s.R[:, :, 2]) - s.D
    rows = [f.row(s, err[:, k]) for k, f in enumerate(_WRIST)]
    return [r.reread_if_erratum(lambda k=k, f=f: wrist_reading(s, eq9abc, k, title_of(f.key)))
            for k, (r, f) in enumerate(zip(rows, _WRIST, strict=True))]


#: The rows of Eq 9a-c, one coordinate of D each (their printed forms are the index titles).
_WRIST = tuple(
    Formula(f"Eq 9{c}", None, None, TOL, "m", (), claim=f"Eq 9{c}: {title_of(f'Eq 9{c}')} is the {x}_D "
            "coordinate of joint 5.", corrected=f"{title_of(f'Eq 9{c}').replace('- r', '+ r')} (Table II has "
            "d6 = -l5: z6 points from the tool back to the wrist)",
            method="printed coordinate vs the origin of frame 5 (Pinocchio) minus l1 e_z",
            note=lambda s, e, sym=sym: f"max |error| = 2 l5 |{sym}| <= 2 l5 = {2 * L5:.3f} m")
    for c, x, sym in zip("abc", "xyz", ("r13", "r23", "r33"), strict=True)
)


def eq10_printed(B, C, D):
    return np.linalg.norm(C - B, axis=1) + np.linalg.norm(D - C, axis=1) - L3 - L4


def _eq10_lengths(B, C, D):
    return np.maximum(np.abs(np.linalg.norm(C - B, axis=1) - L3), np.abs(np.linalg.norm(D - C, axis=1) - L4))


def _eq10_off(s: Sample, err) -> str:
    """Eq 10 at a wrong theta1 (theta1 + 0.1 rad, theta2 from Eq 9): the condition must notice it."""
    th1 = s.q[:, 0] + 0.1
    th2 = eq9_corrected(s.R, s.D, th1)[0]
    off = np.abs(eq10_printed(eq6_printed(th1), eq7_printed(th1, th2), s.D))
    return (
        f"at theta1 + 0.1 rad (theta2 from Eq 9) the median value is {np.median(off):.3f} m: the condition "
        "discriminates"
    )


def eq11_printed(D, th1, th2):
    x, y, z = D.T
    c1, s1, c2, s2 = cos_sin(th1, th2)
    return (
        x**2
        + y**2
        + z**2
        + L2**2
        + L3**2
        - L4**2
        - 2 * (L2 + L3 * c2) * (x * c1 + y * s1)
        + 2 * L3 * (z * s2 + L2 * c2)
    )


def eq11_geometric(D, th1, th2):
    """|D - C(theta1, theta2)|^2 - l4^2."""
    return np.sum((D - eq7_printed(th1, th2)) ** 2, axis=1) - L4**2


def _eq11_swap(D, th1, th2):
    x, y = D[:, 0], D[:, 1]
    c1, s1, c2, _ = cos_sin(th1, th2)
    return eq11_printed(D, th1, th2) + 2 * (L2 + L3 * c2) * ((x * c1 + y * s1) - (x * s1 + y * c1))


@SECTION.check("Eq 11", forms=Forms(
    eq11_printed, eq11_geometric, "|D - C|^2 - l4^2 with C of Eq 7",
    (Slip(SlipKind.SIGN, "- 2 l3 (zD s2 + l2 c2) for + 2 l3 (...)", lambda D, t1, t2: eq11_printed(D, t1, t2)
          - 4 * L3 * (D[:, 2] * np.sin(t2) + L2 * np.cos(t2))),
     Slip(SlipKind.SWAP, "xD s1 + yD c1 for xD c1 + yD s1", _eq11_swap),
     Slip(SlipKind.LENGTH, "l5^2 for l4^2", lambda D, t1, t2: eq11_printed(D, t1, t2) + L4**2 - L5**2)),
    epsilon(eq11_printed, 1e-9, "the printed value moved by 1e-9 m^2")))
def eq11_error(ctx, eq11):
    """Eq 11 as an identity in (theta1, theta2) (|D - C|^2 - l4^2, C from Pinocchio), zero at the solution."""
    s = sample(ctx)
    th = ctx.rng("eq11-any").uniform(ARM.q_min[:2], ARM.q_max[:2], (len(s.q), 2))
    C_any = make_sample(np.pad(th, ((0, 0), (0, 4)))).C  # the frame-3 origin at (theta1, theta2, 0, ...)
    return _identity_row(
        s, "Eq 11", "||E|| (Eq 11) is the length error |DC|^2 - l4^2 of Eq 10; it vanishes at the solution.",
        f"Eq 11 as printed with the true D of {len(s.q)} random poses: (a) at random (theta1, theta2) within "
        "Table I against |D - C|^2 - l4^2 with C the frame-3 origin from Pinocchio, (b) at the generating "
        "(theta1, theta2)", lambda t1, t2: eq11(s.D, t1, t2), th, np.sum((s.D - C_any) ** 2, axis=1) - L4**2,
        "|D - C|^2 - l4^2", "Table I")


# ----------------------------------------------------------------------------- Eq 12-13
def _e_of_theta1(R, D, th):
    """||E|| (Eq 11) along theta1 for both branches of the corrected Eq 9: (2, n, m)."""
    n, m = th.shape
    Rr = np.repeat(R, m, axis=0)
    Dr = np.repeat(D, m, axis=0)
    t = th.ravel()
    br = eq9_corrected(Rr, Dr, t)
    return np.stack([eq11_printed(Dr, t, br[b]).reshape(n, m) for b in range(2)])


def _signed_e(R, D, t, sign: float) -> np.ndarray:
    """sign * ||E|| at theta1 = t (n,), the better branch for that sign: min over branches of sign * E."""
    return (sign * _e_of_theta1(R, D, np.asarray(t)[:, None])[:, :, 0]).min(axis=0)


def _grid_best(R, D, sign: float, n_grid: int) -> np.ndarray:
    """theta1 [rad] of the best point (least sign * ||E||) of an ``n_grid``-point grid over the turn, per
    pose (in blocks of 25 poses: the grid is large)."""
    grid = np.linspace(-np.pi, np.pi, n_grid, endpoint=False)
    out = np.empty(len(D))
    for lo in range(0, len(D), 25):
        sl = slice(lo, min(lo + 25, len(D)))
        vals = (sign * _e_of_theta1(R[sl], D[sl], np.broadcast_to(grid, (sl.stop - sl.start, n_grid)))).min(0)
        out[sl] = grid[np.argmin(vals, axis=1)]
    return out


def _extremum(R, D, sign: float, n_grid: int = 721, iters: int = 40) -> np.ndarray:
    """theta1 of the global minimum (sign +1) or maximum (sign -1) of ||E|| over theta1 and both branches:
    a grid, then golden-section search in the best cell's neighbourhood."""
    h = 2 * np.pi / n_grid
    a = _grid_best(R, D, sign, n_grid) - h
    b = a + 2 * h
    g, f = (np.sqrt(5) - 1) / 2, partial(_signed_e, R, D, sign=sign)
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(iters):
        left = fc < fd
        b = np.where(left, d, b)
        a = np.where(left, a, c)
        c, d = np.where(left, b - g * (b - a), d), np.where(left, c, a + g * (b - a))
        fc, fd = np.where(left, f(c), fd), np.where(left, fc, f(d))
    return wrap((a + b) / 2)


def eq12_printed(p, D, R):
    return np.arctan2(p[:, 1], p[:, 0])


def eq13_printed(p, D, R):
    return wrap(np.arctan2(p[:, 1], p[:, 0]) + np.pi)


def eq13_corrected(p, D, R):
    return wrap(np.arctan2(D[:, 1], D[:, 0]) + np.pi)


@dataclass(frozen=True)
class NumericArgmin:
    """Known-good Eq 12/13: theta1 [rad] of the extremum of ||E|| per pose by a 3600-point grid, then
    Brent's bounded search (scipy) on the best cell's bracket: a different search from the check's grid and
    golden section; ``offset`` [rad] moves the answer (the tolerance test)."""

    sign: float
    offset: float = 0.0

    def __call__(self, p, D, R):
        key = (self.sign, hash(D.tobytes()), hash(R.tobytes()))
        if key not in _ARGMIN:  # a pure function of (D, R): computed once per process
            h, f = 2 * np.pi / 3600, partial(_signed_e, sign=self.sign)
            _ARGMIN[key] = wrap(np.array([
                minimize_scalar(lambda t, k=k: f(R[k:k + 1], D[k:k + 1], [t])[0], bounds=(t0 - h, t0 + h),
                                method="bounded", options={"xatol": 1e-13}).x
                for k, t0 in enumerate(_grid_best(R, D, self.sign, 3600))]))
        return _ARGMIN[key] + self.offset


_ARGMIN: dict = {}
_EXT_TOL = 1e-9  # [m^2]: "at" the extremum = within this of its ||E|| value (near-ties count as hits)
_EXT_SHARE = 0.99  # share of random poses the statement must hit
#: Per sign: the extremum (+1 the minimum, -1 the maximum) and Eq 12 / Eq 13 as printed.
_EXTREMA = {1.0: ("minimum", "min = atan2(py, px)"), -1.0: ("maximum", "max = atan2(py, px) +- pi")}


def extremum_reading(form, sign: float, R, D, p):
    """Second reading of Eq 12 / Eq 13 (the form): the share of poses at which the form, under each nearby
    reading of its inputs (the wrist point D for the tool point p, the arguments exchanged, theta1's sign,
    the opposite side), sits at the extremum found by the reference search (:class:`NumericArgmin`, not the
    check's golden section)."""
    best = _signed_e(R, D, NumericArgmin(sign)(p, D, R), sign)
    stated = {"point": p, "swap": False, "sign": 1.0, "turn": 0.0}

    def misfit(x) -> float:
        pt = x["point"][:, [1, 0, 2]] if x["swap"] else x["point"]
        at = wrap(x["sign"] * form(pt, D, R) + x["turn"])
        return float(1.0 - np.mean(_signed_e(R, D, at, sign) - best <= _EXT_TOL))

    readings = [
        Reading(Kind.WHICH, "the wrist point D (x_D, y_D) for the tool point p", {"point": D + L1 * _EZ}),
        Reading(Kind.SWAP, "atan2's arguments exchanged (px, py)", {"swap": True}),
        Reading(Kind.SIGN, "theta1 measured the other way", {"sign": -1.0}),
        Reading(Kind.WHICH, "the opposite side (+ pi)", {"turn": np.pi}),
    ]
    what, printed = _EXTREMA[sign]
    return search(stated, readings, misfit, 1.0 - _EXT_SHARE, printed=printed,
                  stated_text="p = (px, py, pz) the end-effector point ('theta1 oriented toward the "
                  "end-effector')",
                  route=f"the {what} of ||E|| by a 3600-point grid and Brent's bounded search (scipy)",
                  measure=f"share of poses NOT at the {what} (within {_EXT_TOL:g} m^2)")


def _extremum_row(ctx, form, sign: float, key: str) -> Row:
    """Eq 12 (``sign`` +1) or Eq 13 (-1): is ||E|| at the form's theta1 the extremum over theta1?"""
    s, (what, printed) = sample(ctx), _EXTREMA[sign]
    m_pts = min(len(s.q), ctx.n(600, 80))
    R, D, p = s.R[:m_pts], s.D[:m_pts], s.p[:m_pts]
    found = _extremum(R, D, sign)
    best = _signed_e(R, D, found, sign)
    at_form = wrap(form(p, D, R))
    gap = _signed_e(R, D, at_form, sign) - best  # >= 0 unless the form beats the search
    phi_d = wrap(np.arctan2(D[:, 1], D[:, 0]) + (0.0 if sign > 0 else np.pi))
    hit_d = np.mean(_signed_e(R, D, phi_d, sign) - best <= _EXT_TOL)
    hit_d_pi = np.mean(_signed_e(R, D, wrap(phi_d + np.pi), sign) - best <= _EXT_TOL)
    share = float(np.mean(gap <= _EXT_TOL))
    m = (Measure(f"share of poses where ||E|| at the form is within {_EXT_TOL:g} m^2 of its {what}", share,
                 _EXT_SHARE, bound=">="),)
    k = int(np.argmax(gap))
    corrected = (
        "min at atan2(yD, xD), the wrist point's azimuth (|D - B| is smallest there): the global minimum "
        f"in {hit_d:.1%} of random poses, else at atan2(yD, xD) + pi ({hit_d_pi:.1%})"
        if sign > 0
        else f"max = atan2(yD, xD) +- pi (the wrist point's azimuth; {hit_d:.1%} of random poses)"
    )
    row = Row.graded(
        f"The {what} of ||E|| (Eq 11) over theta1 lies at {printed.split('= ')[1]}.",
        key,
        f"||E|| over theta1 with theta2 from Eq 9 (corrected, both branches; the {what} over both), true D "
        f"of {m_pts} random poses: global {what} by a 721-point grid then golden-section search to 1e-10 "
        f"rad; the form hits it if ||E|| there is within {_EXT_TOL:g} m^2 of the {what} (a near-tie counts "
        "as a hit)",
        f"the form is at the {what} in {share:.1%} of poses (median angular miss "
        f"{np.median(np.abs(wrap(at_form - found))):.3g} rad); atan2(yD, xD){'' if sign > 0 else ' + pi'} is "
        f"in {hit_d:.1%}",
        m,
        id=key.lower().replace(" ", ""),
        domain=f"the first {m_pts} poses of the uniform sample ({s.domain.split(' plus')[0]}); theta1 over "
        "the whole turn",
        erratum=Erratum(key, printed, corrected, f"{fmt_q(s.q[k])}: the {what} of ||E|| is at theta1 = "
                        f"{found[k]:.4f} rad, the form gives {at_form[k]:.4f} rad (||E|| differs by "
                        f"{abs(gap[k]):.3g} m^2)"),
    )
    return row.reread_if_erratum(lambda: extremum_reading(form, sign, R, D, p))


@SECTION.check("Eq 12", forms=Forms(
    eq12_printed, NumericArgmin(1.0), "the minimiser found by a 3600-point grid and Brent's bounded search",
    (Slip(SlipKind.BRANCH, "atan2(yD, xD) + pi (the maximum's side)", eq13_corrected),
     Slip(SlipKind.SWAP, "atan2(xD, yD): the arguments exchanged",
          lambda p, D, R: np.arctan2(D[:, 0], D[:, 1]))),
    Slip(SlipKind.EPSILON, "the good minimiser + 1 mrad", NumericArgmin(1.0, 1e-3))))
def eq12_minimum(ctx, form):
    """Eq 12: the minimum of ||E|| (not of |E|) over theta1."""
    return _extremum_row(ctx, form, 1.0, "Eq 12")


@SECTION.check("Eq 13", forms=Forms(
    eq13_printed, eq13_corrected, "atan2(yD, xD) + pi (the wrist point's opposite azimuth)",
    (Slip(SlipKind.BRANCH, "atan2(yD, xD) without the pi (the minimum's side)",
          lambda p, D, R: np.arctan2(D[:, 1], D[:, 0])),
     Slip(SlipKind.SIGN, "-atan2(yD, xD) + pi", lambda p, D, R: wrap(np.pi - np.arctan2(D[:, 1], D[:, 0])))),
    epsilon(eq13_corrected, 1e-3, "the good form + 1 mrad")))
def eq13_maximum(ctx, form):
    """Eq 13: the maximum of ||E|| over theta1."""
    return _extremum_row(ctx, form, -1.0, "Eq 13")


# ----------------------------------------------------------------------------- Eq 14-16
def _eq14(D, th1, sy: float):
    """Eq 14 with ``sy`` the sign of yD s1 (printed: -1): c4 = (xD^2 + yD^2 + zD^2 + l2^2 - l3^2 - l4^2
    - 2 l2 (xD c1 + sy yD s1)) / (2 l3 l4)."""
    x, y, z = D.T
    c1, s1 = cos_sin(th1)
    return (x**2 + y**2 + z**2 + L2**2 - L3**2 - L4**2 - 2 * L2 * (x * c1 + sy * y * s1)) / (2 * L3 * L4)


eq14_printed, eq14_corrected = partial(_eq14, sy=-1.0), partial(_eq14, sy=1.0)


def eq14_reading(s: Sample, eq14):
    """Second reading of Eq 14 (the form): cos(theta4) of the generating q vs the form fed the wrist point of
    the iik.dh chain under each nearby reading (the y axis mirrored, theta1 measured the other way, theta1 on
    the other side, the wrist point of the printed Eq 9). A reading must also keep Eq 11, printed two
    equations before from the same D and theta1 (it holds as stated): its residual, over 2 l3 l4 (the scale
    of c4), counts in the misfit."""
    d = dh_sample(s.q)
    stated = {"mirror": 1.0, "D": d.D, "turn": 0.0, "sign1": 1.0}

    def misfit(x) -> float:
        D = x["D"] * np.array([1.0, x["mirror"], 1.0])
        th1 = x["sign1"] * x["mirror"] * s.q[:, 0] + x["turn"]
        c4 = float(np.abs(eq14(D, th1) - s.c(4)).max())
        e11 = float(np.abs(eq11_printed(D, th1, s.q[:, 1])).max()) / (2 * L3 * L4)  # Eq 11 = 0 at a solution
        return max(c4, e11)

    readings = [
        Reading(Kind.CONVENTION, "the y axis mirrored (y_D and theta1 with the other sign)",
            {"mirror": -1.0}),
        Reading(Kind.SIGN, "theta1 measured the other way (s1 with the other sign; reproduces Eq 14 alone)",
                {"sign1": -1.0}),
        Reading(Kind.WHICH, "theta1 of the other root (theta1 + pi)", {"turn": np.pi}),
        Reading(Kind.WHICH, "the wrist point of the printed Eq 9 (p - l5 z6)",
                {"D": eq9abc_printed(d.p, d.R[:, :, 2])}),
    ]
    return search(stated, readings, misfit, TOL, printed="c4 = (... - 2 l2 (xD c1 - yD s1)) / (2 l3 l4)",
                  stated_text="the wrist point D (Eq 9 corrected), theta1, Table II's l2, l3, l4; Eq 11 from "
                  "the same D and theta1",
                  route=_DH_ROUTE, measure="max(|form - cos(theta4)|, |Eq 11| / (2 l3 l4))")


def eq15_printed(c4):
    r = np.sqrt(1 - c4**2)
    return np.stack([r, -r])


def _eq15_good(c4):
    r = np.sin(np.arccos(np.clip(c4, -1, 1)))
    return np.stack([r, -r])


def _branches(form, x, truth):
    return np.min(np.abs(form(x) - truth), axis=0)


#: The slips of +-sqrt(1 - x^2) (Eq 15, 21).
_ROOT_SLIPS = (
    Slip(SlipKind.BRANCH, "the + root only", lambda x: np.stack([np.sqrt(1 - x**2)] * 2)),
    Slip(SlipKind.TERM, "sqrt(1 - x): the square dropped", lambda x: np.stack([np.sqrt(np.abs(1 - x)),
                                                                               -np.sqrt(np.abs(1 - x))])),
)
#: Tolerance of a step graded on |error| x |divisor| (a division by a vanishing quantity, or sqrt near 0):
#: floating point gives about eps there.
TOL_SCALED = 1e-14


# ----------------------------------------------------------------------------- Eq 17-22
def _links(q: np.ndarray, first: int, last: int) -> np.ndarray:
    """Product of the Table II link transforms first..last (1-based), (n, 4, 4)."""
    table = ARM.dh_table()
    T = np.broadcast_to(np.eye(4), (len(q), 4, 4)).copy()
    for i in range(first - 1, last):
        T = T @ dh_link_transform(table.rows[i], q[:, i], "modified")
    return T


def _matrix(*rows) -> np.ndarray:
    """The (n, r, c) matrices of ``rows`` of entries (arrays over n samples, or numbers)."""
    entries = np.broadcast_arrays(*(np.asarray(e, float) for r in rows for e in r))
    return np.stack(entries, -1).reshape(entries[0].shape + (len(rows), len(rows[0])))


def eq18_inverse_printed(q):
    c1, s1, c2, s2 = cos_sin(q[:, 0], q[:, 1])
    return _matrix(
        [c1 * s2, s1 * s2, c2, -L1 * c2 - L2 * s2],
        [c1 * c2, s1 * c2, -s2, L1 * s2 - L2 * c2],
        [-s1, c1, 0, 0],
        [0, 0, 0, 1],
    )


def eq18_t25_printed(q):
    c3, s3, c4, s4 = cos_sin(q[:, 2], q[:, 3])
    c45, s45 = cos_sin(q[:, 3] + q[:, 4])
    return _matrix(
        [c3 * c45, -c3 * s45, -s3, L4 * c3 * s4],
        [-s45, -c45, 0, L4 * c4 + L3],
        [-s3 * c45, s3 * s45, -c3, -L4 * s3 * s4],
        [0, 0, 0, 1],
    )


def _eq18_dh(q):
    return np.linalg.inv(_links(q, 1, 2)), _links(q, 3, 5)


def _eq18_t25_sign(q):
    inv, t25 = _eq18_dh(q)
    t25 = t25.copy()
    t25[:, 1, 3] = L4 * np.cos(q[:, 3]) - L3
    return inv, t25


@SECTION.check("Eq 18", forms=Forms(
    lambda q: (eq18_inverse_printed(q), eq18_t25_printed(q)), _eq18_dh,
    "inverse of the Table II product 0_2T, and 2_5T from Table II",
    (Slip(SlipKind.TRANSPOSE, "0_2T^-1 with R for R^T",  # the translation -R^T p kept
          lambda q: (rotation_transposed(_eq18_dh(q)[0]), _eq18_dh(q)[1])),
     Slip(SlipKind.SIGN, "2_5T's (2,4) entry l4 c4 - l3", _eq18_t25_sign)),
    Slip(SlipKind.EPSILON, "both moved by 1e-9", lambda q: tuple(M + 1e-9 for M in _eq18_dh(q))),
    rows=("eq18.inverse", "eq18.t25")))
def eq18_matrices(ctx, mats):
    """Eq 18: the printed 0_2T^-1 and 2_5T (base frame) vs Pinocchio."""
    s = sample(ctx)
    inv, t25 = mats(s.q)
    return [
        error_row(s, np.abs(inv - np.linalg.inv(s.F[:, 2])).max(axis=(1, 2)), TOL, "m or -", key="Eq 18",
                  id="eq18.inverse", claim="The printed 0_2T^-1 is the inverse of the frame-2 pose.",
                  method="printed matrix vs inv(0_2T) from Pinocchio (base frame at the mounting plane, "
                  "z = 0)", printed="0_2T^-1 as printed",
                  note="it contains l1: it belongs to the unshifted base frame (see eq18.frame)"),
        error_row(s, np.abs(t25 - s.rel(2, 5)).max(axis=(1, 2)), TOL, "m or -", key="Eq 18", id="eq18.t25",
                  claim="The printed 2_5T is the transform from frame 2 to frame 5.",
                  method="printed matrix vs (0_2T)^-1 0_5T from Pinocchio", printed="2_5T as printed"),
    ]


def eq18_frame_reading(ctx, s: Sample, wrist):
    """Second reading of Eq 18 with the D of Eq 9 (the form ``wrist``): the printed 0_2T^-1 times 0_5T
    built from the iik.dh chain's rotation and the form's D, vs the printed 2_5T, under each nearby reading
    of D's frame (the base frame not moved up by l1, moved down)."""
    d = dh_sample(s.q)
    D = wrist(d)
    stated = {"shift": 0.0}

    def misfit(x) -> float:
        return float(_eq18_frame_gap(d, D + x["shift"] * _EZ).max())

    readings = [
        Reading(Kind.CONVENTION, "D in the base frame (not moved up by l1: the frame of the printed 0_2T^-1)",
                {"shift": L1}),
        Reading(Kind.SIGN, "the frame moved down by l1", {"shift": -L1}),
    ]
    return search(stated, readings, misfit, TOL,
        printed="0_2T^-1 with -l1 c2 - l2 s2 and l1 s2 - l2 c2 in column 4",
                  stated_text="D of Eq 9 in the frame of Sec 3.3.1 (moved up by l1, Eq 9c)",
                  route=_DH_ROUTE, measure="max |printed 0_2T^-1 0_5T - printed 2_5T| [m]")


def _eq18_frame_gap(s: Sample, D) -> np.ndarray:
    """max |printed 0_2T^-1 0_5T (rotation of ``s``, last column D) - printed 2_5T| per q [m or -]."""
    T05 = s.F[:, 5].copy()
    T05[:, :3, 3] = D
    return np.abs(eq18_inverse_printed(s.q) @ T05 - eq18_t25_printed(s.q)).max(axis=(1, 2))


def eq19_printed(q, D):
    c1, s1 = cos_sin(q[:, 0])
    return np.stack([c1 * D[:, 1] - s1 * D[:, 0], -L4 * np.sin(q[:, 2]) * np.sin(q[:, 3])])


def _eq19_good(q, D):
    row3 = np.stack([-np.sin(q[:, 0]), np.cos(q[:, 0]), np.zeros(len(q))], 1)
    return np.stack([np.einsum("ni,ni->n", row3, D), -L4 * np.sin(q[:, 2]) * np.sin(q[:, 3])])


def eq20_printed(q, D):
    c1, s1 = cos_sin(q[:, 0])
    return (s1 * D[:, 0] - c1 * D[:, 1]) / (L4 * np.sin(q[:, 3]))


def eq24_printed(q):
    c3, c45, s45 = np.cos(q[:, 2]), np.cos(q[:, 3] + q[:, 4]), np.sin(q[:, 3] + q[:, 4])
    return np.stack([-c3 * s45, -c45], 1)


def eq25_lhs(R, q):
    r13, r23, r33 = R[:, 0, 2], R[:, 1, 2], R[:, 2, 2]
    c1, s1, c2, s2 = cos_sin(q[:, 0], q[:, 1])
    return r13 * c1 * s2 + r23 * s1 * s2 + r33 * c2


def eq26_lhs(R, q):
    r13, r23, r33 = R[:, 0, 2], R[:, 1, 2], R[:, 2, 2]
    c1, s1, c2, s2 = cos_sin(q[:, 0], q[:, 1])
    return r13 * c1 * c2 + r23 * s1 * c2 - r33 * s2


def eq27_printed(a13, a33, c3, s3):
    """s45 = (r13 c1 s2 + r23 s1 s2 + r33 c2) / (-c3); ``a13`` is that numerator."""
    return a13 / (-c3)


def eq27_companion(a13, a33, c3, s3):
    """s45 = -c3 a13 + s3 a33 (Eq 25 and its row-3 companion s3 s45): valid for every theta3."""
    return -c3 * a13 + s3 * a33


def _theta5_error(s45_form, s: Sample, c3, s3) -> np.ndarray:
    """|theta5 through Eq 27 (the form) and Eq 28 (c45 from Eq 26) - the true theta5| [rad], NaN as inf (a
    division by c3 = 0)."""
    q = s.q
    a33 = -np.sin(q[:, 0]) * s.R[:, 0, 2] + np.cos(q[:, 0]) * s.R[:, 1, 2]  # (0_2T^-1 R)_33 = s3 s45
    with np.errstate(divide="ignore", invalid="ignore"):
        s45 = s45_form(eq25_lhs(s.R, q), a33, c3, s3)
        err = np.abs(wrap(np.arctan2(s45, -eq26_lhs(s.R, q)) - q[:, 3] - q[:, 4]))
    return np.where(np.isnan(err), np.inf, err)


#: |c3| = 10^U(_C3_EXP) in the near-singular sample of Eq 27.
_C3_EXP = (-10, -3)


@per_run
def _near_c3_zero(ctx) -> Sample:
    """q uniform in Table I but theta3 = +-90 deg +- 10^U(_C3_EXP) rad."""
    rng, n, pm = ctx.rng("eq27-near"), ctx.n(1500, 150), [-1.0, 1.0]
    q = rng.uniform(ARM.q_min, ARM.q_max, size=(n, 6))
    q[:, 2] = rng.choice(pm, n) * np.pi / 2 + rng.choice(pm, n) * 10 ** rng.uniform(*_C3_EXP, n)
    return make_sample(q)


def _eq27_plus(a13, a33, c3, s3):
    return a13 / c3


_EQ27 = Forms(eq27_printed, eq27_companion, "s45 = -c3 (Eq 25 left side) + s3 (its row-3 companion)", (
    Slip(SlipKind.SIGN, "s45 = (...) / (+c3)", _eq27_plus),
    Slip(SlipKind.FUNCTION, "s45 = (...) / (-s3): the sine for the cosine", lambda a, b, c3, s3: a / -s3),
), epsilon(eq27_companion, 1e-6, "the good s45 + 1e-6"))


@SECTION.check("Eq 27", forms=_EQ27)
def eq27_s45(ctx, eq27):
    """Eq 27-28 on random q, including |c3| down to 1e-10 (theta3 within 1e-3..1e-10 rad of +-90 deg), graded
    on |error| |c3| (the division by c3 costs eps / |c3|; at c3 = 0 exactly see eq27.c3_zero)."""
    s, near = sample(ctx), _near_c3_zero(ctx)
    both = Sample(np.concatenate([s.q, near.q]), np.concatenate([s.F, near.F]), s.hard)
    c3 = np.cos(both.q[:, 2])
    err = _theta5_error(eq27, both, c3, np.sin(both.q[:, 2]))
    raw_near = err[len(s.q):]
    small = np.abs(c3[len(s.q):])
    ok = raw_near <= TOL_ANGLE
    bound = float(small[~ok].max()) if (~ok).any() else 0.0
    return error_row(
        both, err, TOL_SCALED, "rad", key="Eq 27", id="eq27",
        claim="s45 = (r13 c1 s2 + r23 s1 s2 + r33 c2) / (-c3), then theta5 by Eq 28.",
        method=f"theta5 through Eq 27 and Eq 28 (c45 from Eq 26) with the true pose and theta1..theta4, vs "
        f"the generating theta5; {len(s.q)} q of the IK sample plus {len(near.q)} with |c3| = 10^U{_C3_EXP}; "
        "graded on |error| |c3|: an exact formula that divides by c3 loses eps / |c3| in floating point, so "
        "a raw tolerance would flip with the sampling (at c3 = 0 itself it is 0/0: row eq27.c3_zero)",
        printed="s45 = (...) / (-c3)",
        corrected="s45 = -c3 (...) + s3 (-s1 r13 + c1 r23)",
        note=f"raw error on the near-singular set: max {np.max(raw_near):.1e} rad at |c3| = "
        f"{small[int(np.argmax(raw_near))]:.1e}; the raw error exceeds {TOL_ANGLE:g} rad only where |c3| <= "
        f"{bound:.1e} (smallest |c3| sampled {small.min():.1e})",
        scale=("c3", c3),
        domain=both.domain + f"; plus {len(near.q)} with |c3| = 10^U{_C3_EXP}",
    )


@SECTION.check("Eq 27", forms=_EQ27)
def eq27_c3_zero(ctx, eq27):
    """The exact case c3 = 0 (theta3 = +-90 deg; Eq 21 gives c3 = 0 exactly when s3 = +-1): Eq 27 is 0/0."""
    rng = ctx.rng("eq27-exact")
    n = ctx.n(400, 60)
    q = rng.uniform(ARM.q_min, ARM.q_max, size=(n, 6))
    sgn = rng.choice([-1.0, 1.0], n)
    q[:, 2] = sgn * np.pi / 2
    err = _theta5_error(eq27, make_sample(q), np.zeros(n), sgn)
    k = int(np.argmax(err))
    return Row.graded(
        "Eq 27-28 give theta5 also at theta3 = +-90 deg (c3 = 0).",
        "Eq 27 (c3 = 0)",
        f"{n} poses with theta3 = +-90 deg; c3 = 0 and s3 = +-1 exactly (what Eq 21 returns there); theta5 "
        f"through Eq 27-28 with the true pose and theta1, theta2, theta4; worst at {fmt_q(q[k])}",
        None,
        (Measure("share of poses whose theta5 is recovered", np.mean(err <= TOL_ANGLE), 1.0, bound=">="),),
        fail=Verdict.DOES_NOT_HOLD,
        id="eq27.c3_zero",
        domain=f"{n} q uniform in Table I with theta3 = +-90 deg exactly",
        reason="Eq 27 divides by c3: at theta3 = +-90 deg it is 0/0 (the numerator is -c3 s45 = 0) and "
        "theta5 is lost; s45 = -c3 (Eq 25 left side) + s3 (-s1 r13 + c1 r23) holds for every theta3",
    )


def _eq28_error(s: Sample, eq28) -> np.ndarray:
    t45 = s.q[:, 3] + s.q[:, 4]
    return wrap(eq28(np.sin(t45), np.cos(t45), s.q[:, 3]) - s.q[:, 4])


def eq30_row3_printed(q):
    c1, s1, c2, s2, c3, s3 = cos_sin(q[:, 0], q[:, 1], q[:, 2])
    return np.stack([s1 * c3 - c1 * s2 * s3, -c1 * c3 - s1 * s2 * s3, -c2 * s3], 1)


def eq30_t56_printed(q):
    c6, s6 = cos_sin(q[:, 5])
    return _matrix([c6, -s6, 0, 0], [0, 0, 1, 0], [-s6, -c6, 0, -L5], [0, 0, 0, 1])


def eq30_t56_corrected(q):
    T = eq30_t56_printed(q)
    T[:, 1, 3], T[:, 2, 3] = -L5, 0.0
    return T


@SECTION.check("Eq 30", forms=Forms(
    lambda q: (eq30_row3_printed(q), eq30_t56_printed(q)),
    lambda q: (eq30_row3_printed(q), eq30_t56_corrected(q)),
    "row 3 as printed and 5_6T with -l5 in entry (2,4) (Table II: d6 = -l5 along y5)",
    (Slip(SlipKind.SIGN, "row 3's -c2 s3 written +c2 s3",
          lambda q: (eq30_row3_printed(q) * np.array([1.0, 1.0, -1.0]), eq30_t56_corrected(q))),
     Slip(SlipKind.TRANSPOSE, "5_6T's rotation transposed",
          lambda q: (eq30_row3_printed(q), rotation_transposed(eq30_t56_corrected(q))))),
    Slip(SlipKind.EPSILON, "the good matrices moved by 1e-9",
         lambda q: (eq30_row3_printed(q) + 1e-9, eq30_t56_corrected(q) + 1e-9))))
def eq30_matrices(ctx, mats):
    """Eq 30: the printed row 3 of 0_5T^-1 and the printed 5_6T vs Pinocchio."""
    s = sample(ctx)
    row3, t56 = mats(s.q)
    rows = [
        error_row(s, np.abs(row3 - np.linalg.inv(s.F[:, 5])[:, 2, :3]).max(axis=1), TOL, "-", key="Eq 30",
                  id="eq30.row3",
                  claim="Row 3 of 0_5T^-1 is [s1 c3 - c1 s2 s3, -c1 c3 - s1 s2 s3, -c2 s3, x].",
                  method="printed row vs inv(0_5T) from Pinocchio", printed="row 3 of 0_5T^-1 as printed"),
        error_row(s, np.abs(t56 - s.rel(5, 6)).max(axis=(1, 2)), TOL, "m or -", key="Eq 30", id="eq30.t56",
                  claim="The printed 5_6T is the transform from frame 5 to frame 6.",
                  method="printed matrix vs (0_5T)^-1 0_6T from Pinocchio",
                  printed="5_6T = [c6 -s6 0 0; 0 0 1 0; -s6 -c6 0 -l5; 0 0 0 1]",
                  corrected="5_6T = [c6 -s6 0 0; 0 0 1 -l5; -s6 -c6 0 0; 0 0 0 1] (the offset d6 = -l5 lies "
                  "along y5, row 2); harmless for Eq 31-32, which use only entries (3,1) and (3,2)"),
    ]
    rows[1] = rows[1].reread_if_erratum(lambda: appb_reading(5, t56, s.q, "5_6T of Eq 30 as printed"))
    return rows


def eq31_lhs(R, q, col=0):
    """Row 3 of 0_5T^-1 (Eq 30) times column ``col`` + 1 of R: Eq 31 (col 0), Eq 32 (col 1)."""
    return np.einsum("ni,ni->n", eq30_row3_printed(q), R[:, :, col])


eq32_lhs = partial(eq31_lhs, col=1)


# ----------------------------------------------------------------------------- the printed steps, declared
def _angle(sn, cs):
    return np.angle(cs + 1j * sn)


_ATAN2_SLIPS = (
    Slip(SlipKind.SWAP, "atan2(c, s): the arguments exchanged", lambda sn, cs: np.arctan2(cs, sn)),
    Slip(SlipKind.FUNCTION, "atan(s / c) for atan2 (the quadrant lost)", lambda sn, cs: np.arctan(sn / cs)),
)
_COMPOSE_SLIPS = (
    Slip(SlipKind.SWAP, "the factors in the wrong order", lambda a, b: b @ a),
    Slip(SlipKind.TRANSPOSE, "the second factor's rotation transposed",
         lambda a, b: a @ rotation_transposed(b)),
)


def _atan2_step(number: int, j: int) -> Formula:
    """Eq 16, 22, 33: theta_j = atan2(s_j, c_j) with the true sine and cosine."""
    return Formula(f"Eq {number}", np.arctan2, lambda s, f: wrap(f(s.s(j), s.c(j)) - s.q[:, j - 1]), TOL,
                   "rad", _ATAN2_SLIPS, good=_angle, good_is="the argument of c + i s", eps=1e-6,
                   eps_is="atan2 + 1 urad", method=f"with the true s{j}, c{j} vs theta{j}",
                   basis=_ATAN2_BASIS)


def _composition(number: int, split: int, upto: int) -> Formula:
    """Eq 17, 23, 29: 0_uptoT = 0_splitT split_uptoT, the Table II link products composed by the form."""
    def error(s, f):
        return np.abs(f(_links(s.q, 1, split), _links(s.q, split + 1, upto)) - s.F[:, upto]).max(axis=(1, 2))

    return Formula(
        f"Eq {number}", lambda a, b: a @ b, error, TOL, "m or -", _COMPOSE_SLIPS,
        good=lambda a, b: np.einsum("nij,njk->nik", a, b), good_is="the same product written with einsum",
        fail=Verdict.DOES_NOT_HOLD, basis=_SAME_TABLE,
        method=f"products of the Table II link transforms 1..{split} and {split + 1}..{upto} composed as "
        f"printed vs Pinocchio's 0_{upto}T")


def _element(number: int, lhs, rhs_is: str, rhs) -> Formula:
    """Eq 25, 26, 31, 32: an element of the rotation printed as ``lhs(R, q) = right side``, the left side
    right; its slips: the right side's sign, theta1 and theta2 exchanged in the left side."""

    def swapped(R, q):
        return lhs(R, q[:, [1, 0, 2, 3, 4, 5]])

    return Formula(f"Eq {number}", lhs, lambda s, f: f(s.R, s.q) - rhs(s), TOL, "-", (
        Slip(SlipKind.SIGN, "the right side's sign flipped", lambda R, q: -lhs(R, q)),
        Slip(SlipKind.SWAP, "theta1 and theta2 exchanged in the left side", swapped),
    ), good_is="the printed left side (it is right)", eps_is="the left side moved by 1e-9",
        method=f"printed left side with the true pose and joint angles vs {rhs_is}")


CHECKS = SECTION.formulas(
    sample,
    Formula("Eq 6", eq6_printed, lambda s, f: np.linalg.norm(f(s.q[:, 0]) - s.B, axis=1), TOL, "m", (
        Slip(SlipKind.SWAP, "[l2 s1, l2 c1, 0]", lambda t: eq6_printed(t)[:, [1, 0, 2]]),
        Slip(SlipKind.LENGTH, "l3 for l2", lambda t: eq6_printed(t) * (L3 / L2)),
    ), good=_eq6_rot, good_is="Rz(theta1) [l2 0 0]", eps_is="each coordinate moved by 1 nm",
        method="printed p_B vs the origin of frame 2 (Pinocchio) minus l1 e_z"),
    Formula("Eq 7", eq7_printed, lambda s, f: np.linalg.norm(f(s.q[:, 0], s.q[:, 1]) - s.C, axis=1), TOL,
            "m", (
        Slip(SlipKind.SIGN, "z_C = +l3 s2", lambda t1, t2: eq7_printed(t1, t2) * np.array([1.0, 1.0, -1.0])),
        Slip(SlipKind.SWAP, "c1 and s1 exchanged in the l3 terms", lambda t1, t2: eq7_printed(t1, t2) + L3
             * np.stack([np.cos(t2) * (np.sin(t1) - np.cos(t1)), np.cos(t2) * (np.cos(t1) - np.sin(t1)),
                         0 * t1], 1)),
        Slip(SlipKind.LENGTH, "l4 for l3",
             lambda t1, t2: _eq6_rot(t1) + (eq7_printed(t1, t2) - _eq6_rot(t1)) * (L4 / L3)),
    ), good=lambda t1, t2: _eq6_rot(t1) + L3 * _link3(t1, t2), good_is="p_B + l3 (unit vector of link 3)",
        eps_is="each coordinate moved by 1 nm",
        method="printed p_C vs the origin of frames 3-4 (Pinocchio) minus l1 e_z"),
    Formula("Eq 9", eq9_printed, _eq9_miss, TOL_ANGLE, "rad", (
        Slip(SlipKind.SIGN, "tan(theta2) = +P/Q", lambda R, D, t: -eq9_corrected(R, D, t)),
        Slip(SlipKind.SWAP, "numerator and denominator exchanged", lambda R, D, t: np.stack(
            [np.arctan2(_pq(R, D, t)[1], -_pq(R, D, t)[0]), np.arctan2(-_pq(R, D, t)[1], _pq(R, D, t)[0])])),
        Slip(SlipKind.BRANCH, "one branch only", lambda R, D, t: eq9_corrected(R, D, t)[[0, 0]]),
    ), good=eq9_corrected, good_is="tan(theta2) = -P/Q (both branches)", eps=1e-6,
        eps_is="the good branches moved by 1 urad", text="tan(theta2) = P / (+-Q)",
        corrected="tan(theta2) = -P / Q, i.e. (c2, s2) = +-(Q, -P) / sqrt(P^2 + Q^2) (Eq 8 reads P c2 + Q s2 "
        "= 0); as tangents the printed '-' branch is right and the '+' branch spurious",
        method="both branches, read as theta2 = atan2(numerator, +-denominator), with the true D and theta1, "
        "vs the generating theta2; {n} random q",
        note=lambda s, err: f"theta2 missed in {np.mean(err > TOL_ANGLE):.1%} of q", reread=eq9_reading),
    Formula("Eq 10", eq10_printed, lambda s, f: f(s.B, s.C, s.D), TOL, "m", (
        Slip(SlipKind.LENGTH, "l5 for l4", lambda B, C, D: eq10_printed(B, C, D) + L4 - L5),
        Slip(SlipKind.SIGN, "|BC| - |DC| - l3 - l4",
             lambda B, C, D: eq10_printed(B, C, D) - 2 * np.linalg.norm(D - C, axis=1)),
    ), good=_eq10_lengths, good_is="the two length conditions |BC| = l3, |DC| = l4", eps=1e-6,
        eps_is="the good form moved by 1 um", method="Eq 10 with the true points B, C, D", note=_eq10_off,
        basis="the distances between Pinocchio's joint points are the link lengths by construction of the "
        "model (Table II), so Eq 10 at the true points is zero identically: it shows the condition is "
        "written right, not a fact about the arm (the note shows it discriminates)"),
    Formula("Eq 14", eq14_printed, lambda s, f: f(s.D, s.q[:, 0]) - s.c(4), TOL, "-", (
        Slip(SlipKind.SIGN, "... - 2 l2 (xD c1 - yD s1)", eq14_printed),
        Slip(SlipKind.SIGN, "+ l3^2 for - l3^2", lambda D, t: eq14_corrected(D, t) + L3 / L4),
        Slip(SlipKind.LENGTH, "2 l3 l5 in the denominator", lambda D, t: eq14_corrected(D, t) * L4 / L5),
    ), good=eq14_corrected, good_is="the law of cosines on triangle B, C, D: ... - 2 l2 (xD c1 + yD s1)",
        eps_is="good + 1e-9",
        text="c4 = (xD^2 + yD^2 + zD^2 + l2^2 - l3^2 - l4^2 - 2 l2 (xD c1 - yD s1)) / (2 l3 l4)",
        corrected="... - 2 l2 (xD c1 + yD s1) (|D - B|^2 = |D|^2 + l2^2 - 2 l2 (xD c1 + yD s1))",
        method="printed c4 with the true D and theta1 vs cos(theta4) of the generating q",
        reread=lambda ctx, s, form: eq14_reading(s, form)),
    Formula("Eq 15", eq15_printed, lambda s, f: _branches(f, s.c(4), s.s(4)), TOL_SCALED, "-", _ROOT_SLIPS,
            good=_eq15_good, good_is="+-sin(acos(c4))", eps_is="both branches moved by 1e-9",
            method="both signs with the true c4 vs sin(theta4)", basis=_PYTHAGORAS,
            scale=("s4", lambda s: s.s(4))),
    _atan2_step(16, 4),
    _composition(17, 2, 5),
    Formula("Eq 18", lambda s: s.D, lambda s, wrist: _eq18_frame_gap(s, wrist(s)), TOL, "m", (
        Slip(SlipKind.SIGN, "D moved up by l1 the wrong way (z_D + 2 l1)", lambda s: s.D + 2 * L1 * _EZ),
        Slip(SlipKind.LENGTH, "D shifted by l2 for l1", lambda s: s.D + L2 * _EZ),
    ), good=lambda s: s.D + L1 * _EZ,
        good_is="D in the base frame (z = 0 at the mounting plane), the frame of the printed 0_2T^-1",
        eps=Slip(SlipKind.EPSILON, "the good D moved by 1 nm", lambda s: s.D + L1 * _EZ + 1e-9),
        id="eq18.frame",
        claim="Eq 18 holds with 0_5T built from the D of Eq 9 (x_D, y_D, z_D 'known from Equation 9b').",
        method="printed 0_2T^-1 times 0_5T with the true rotation and D in the frame of Sec 3.3.1 (Eq 9c: "
        "origin moved up by l1), vs the printed 2_5T",
        text="0_2T^-1 with -l1 c2 - l2 s2 and l1 s2 - l2 c2 in column 4, applied to Eq 9's D",
        corrected="in the frame of Eq 9 the column is [-l2 s2, -l2 c2, 0] (drop the l1 terms), or D must "
        "keep z_D = p_z + r33 l5; harmless: only the (3,4) entry, which has no l1 term, is used (Eq 19)",
        note=lambda s, err: "entries (1,4), (2,4) are off by l1 c2, l1 s2 (max "
        f"{L1 * np.abs(s.c(2)).max():.3f} m); the (3,4) entry used by Eq 19 is exact",
        reread=eq18_frame_reading),
    Formula("Eq 19", eq19_printed, lambda s, f: np.abs(f(s.q, s.D) - s.rel(2, 5)[:, 2, 3]).max(axis=0), TOL,
            "m", (
        Slip(SlipKind.SWAP, "c1 xD - s1 yD", lambda q, D: np.stack(
            [np.cos(q[:, 0]) * D[:, 0] - np.sin(q[:, 0]) * D[:, 1], eq19_printed(q, D)[1]])),
        Slip(SlipKind.SIGN, "+l4 s3 s4", lambda q, D: eq19_printed(q, D) * np.array([[1.0], [-1.0]])),
    ), good=_eq19_good, good_is="row 3 of 0_2T^-1 times D, and -l4 s3 s4", eps_is="both sides moved by 1 nm",
        method="both printed expressions with the true D and q vs the (3,4) entry of 2_5T from Pinocchio"),
    Formula("Eq 20", eq20_printed, lambda s, f: f(s.q, s.D) - s.s(3), TOL_SCALED, "-", (
        Slip(SlipKind.SIGN, "(c1 yD - s1 xD) / (l4 s4)", lambda q, D: -eq20_printed(q, D)),
        Slip(SlipKind.LENGTH, "l3 s4 in the denominator", lambda q, D: eq20_printed(q, D) * L4 / L3),
        Slip(SlipKind.FUNCTION, "l4 c4 for l4 s4",
             lambda q, D: eq20_printed(q, D) * np.sin(q[:, 3]) / np.cos(q[:, 3])),
    ), method="with the true D, theta1, theta4 vs sin(theta3)", scale=("s4", lambda s: s.s(4)),
        note=lambda s, err: f"smallest |s4| sampled {np.abs(s.s(4)).min():.1e} (s4 = 0, theta4 = 0, is 0/0: "
        "the wrist on the link-3 axis, singular set s(1)); graded on |error| |s4|: the division by s4 costs "
        "eps / |s4|"),
    Formula("Eq 21", eq15_printed, lambda s, f: _branches(f, s.s(3), s.c(3)), TOL_SCALED, "-", _ROOT_SLIPS,
            good=_eq15_good, good_is="+-sin(acos(s3)) read as cosines", eps_is="both branches moved by 1e-9",
            method="both signs with the true s3 vs cos(theta3)", basis=_PYTHAGORAS,
            scale=("c3", lambda s: s.c(3))),
    _atan2_step(22, 3),
    _composition(23, 2, 6),
    Formula("Eq 24", eq24_printed, lambda s, f: np.abs(f(s.q) - s.rel(2, 6)[:, :2, 2]).max(axis=1), TOL,
            "-", (
        Slip(SlipKind.SWAP, "(1,3) = -s3 s45",
             lambda q: np.stack([-np.sin(q[:, 2]) * np.sin(q[:, 3] + q[:, 4]), eq24_printed(q)[:, 1]], 1)),
        Slip(SlipKind.SIGN, "(2,3) = +c45", lambda q: eq24_printed(q) * np.array([1.0, -1.0])),
    ), good_is="the printed entries (they are right)",
        method="printed entries vs (0_2T)^-1 0_6T from Pinocchio"),
    _element(25, eq25_lhs, "-c3 s45", lambda s: -s.c(3) * np.sin(s.q[:, 3] + s.q[:, 4])),
    _element(26, eq26_lhs, "-c45", lambda s: -np.cos(s.q[:, 3] + s.q[:, 4])),
    Formula("Eq 28", lambda sn, cs, t4: np.arctan2(sn, cs) - t4, _eq28_error, TOL, "rad", (
        Slip(SlipKind.SIGN, "atan2(s45, c45) + theta4", lambda sn, cs, t4: np.arctan2(sn, cs) + t4),
        Slip(SlipKind.SWAP, "atan2(c45, s45) - theta4", lambda sn, cs, t4: np.arctan2(cs, sn) - t4),
    ), good=lambda sn, cs, t4: _angle(sn, cs) - t4, good_is="arg(c45 + i s45) - theta4", eps=1e-6,
        eps_is="the good form + 1 urad",
        method="with the true s45, c45, theta4 vs theta5", basis=_ATAN2_BASIS + " (minus the true theta4)"),
    _composition(29, 5, 6),
    _element(31, eq31_lhs, "-sin(theta6)", lambda s: -s.s(6)),
    _element(32, eq32_lhs, "-cos(theta6)", lambda s: -s.c(6)),
    _atan2_step(33, 6),
)
