"""Appendix E's formulas, each in a row of its own (Eq 58, 59, 61, 63, 62-65, 66-67, 68).

The App. E rows of :mod:`verification.checks.appendix_e` grade the numbers printed at A1, A2 and
A6; here each printed formula is graded on its own, so a right formula does not look falsified
beside a wrong printed number. The printed form of each formula (as
:mod:`verification.oracles.abdel_malek` implements it: Pinocchio Jacobians and their central
differences) is compared with what the quantity means
(:mod:`verification.oracles.normal_distance`: the Table II chain by ``iik.dh``, the surface
normal from its tangents, Hessians of the normal distance by central differences), at A1, A2,
A6 and at random points of the singular sets s(1), s(2) and s(26) with their free joints
uniform over Table I. Eq 68 is evaluated where the text applies it -- where Eq 66 vanishes
(points of s(24)-s(27) found by root finding) -- and its sign rule is graded against the side
to which the tool actually moves when the joint leaves its limit.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

import iik

from ..formula import Formula, per_run
from ..numbers import fmt_vec
from ..oracles.abdel_malek import (
    eq58_rates,
    eq59_normal,
    eq61_h_star,
    eq63_b,
    eq65_q_star,
    eq67_dq,
    eq68_kbar,
    hessian,
    position_and_jacobian,
)
from ..oracles.normal_distance import SurfacePoint, surface_point, tool_point
from ..registry import Erratum, Forms, Measure, Row, Section, Slip, SlipKind, epsilon
from ..second_reading import Kind, Reading, search
from .appendix_e import PRINTED
from .appendix_e import SECTION as _POINTS

ARM = iik.THESIS_ARM
SECTION = Section(_POINTS.title, depends_on=("lengths", "pinocchio"), prefix="appendix_e", order=47.5)
TOL = 1e-3  # [mm]: a formula vs its meaning (both in floating point, central differences: ~1e-5 mm)
_ROUTE = (
    "vs what it means: verification.oracles.normal_distance (Table II chain by iik.dh, central differences), "
    "at A1, A2, A6 and random points of s(1), s(2), s(26)"
)


@dataclass(frozen=True)
class Probe:
    """A point of a singular set with the printed formulas' ingredients (Pinocchio) and the meaning-based
    quantities (SI units).

    Attributes:
        name: ``"A1"`` or ``"s(26) #3"``; q0: joints 1-5 [rad]; free: the free joints (1-based).
        Gq: (3, 5) tool-point Jacobian; Hq: (3, 5, 5) its derivatives; qs, qss: Eq 58's rates at q0.
        sp: the meaning-based :class:`~verification.oracles.normal_distance.SurfacePoint`.
        rows: Eq 63's row pair (the best-conditioned one).
    """

    name: str
    q0: np.ndarray
    free: tuple[int, int]
    Gq: np.ndarray
    Hq: np.ndarray
    qs: np.ndarray
    qss: np.ndarray
    sp: SurfacePoint
    rows: tuple[int, int]
    _memo: dict = field(default_factory=dict, compare=False, repr=False)

    def meaning(self, what: str, *args):
        """``self.sp.<what>(*args)``, computed once (the meaning does not depend on any form)."""
        key = (what, args)
        if key not in self._memo:
            self._memo[key] = getattr(self.sp, what)(*args)
        return self._memo[key]

    @property
    def f_u(self) -> np.ndarray:
        return self.Gq[:, [j - 1 for j in self.free]]

    @property
    def N0(self) -> np.ndarray:
        return self.sp.N0

    def nf_uu(self) -> np.ndarray:
        u = [j - 1 for j in self.free]
        return np.einsum("k,kij->ij", self.N0, self.Hq)[np.ix_(u, u)]


def _probe(name, q0, free) -> Probe | None:
    q0 = np.asarray(q0, float)
    try:
        sp = surface_point(q0, free)
    except iik.InvalidInputError:
        return None
    _, qs, qss = eq58_rates(q0, ARM)
    _, Gq = position_and_jacobian(q0)
    return Probe(name, q0, tuple(free), Gq, hessian(q0), qs, qss, sp, sp.rows)


#: The singular sets sampled besides A1, A2, A6: each point's set (its joints but the free ones held).
_SETS = {"s(1)": "A1", "s(2)": "A2", "s(26)": "A6"}


class Probes(tuple):
    """Probes, or ``(joint, probe)`` pairs, with the sampled domain in words (a sample of
    :class:`~verification.formula.Formula`)."""

    domain: str

    def __new__(cls, items, domain: str):
        out = super().__new__(cls, items)
        out.domain = domain
        return out

    def at(self, k: int) -> str:
        p = self[k][1] if isinstance(self[k], tuple) else self[k]
        return f"at {p.name}, q0 = {fmt_vec(p.q0)} rad"


@per_run
def probes(ctx) -> Probes:
    """A1, A2, A6 and random points of s(1), s(2), s(26) (free joints uniform in Table I)."""
    out = [_probe(n, d.q0, d.free) for n, d in PRINTED.items()]
    rng = ctx.rng("appendix-e-formulas")
    for name, at in _SETS.items():
        q0, free = PRINTED[at].q0, PRINTED[at].free
        held = [j for j in range(5) if j + 1 not in free]
        for k in range(ctx.n(6, 2)):
            q = rng.uniform(ARM.q_min[:5], ARM.q_max[:5])
            q[held] = q0[held]
            out.append(_probe(f"{name} #{k + 1}", q, free))
    out = [p for p in out if p is not None]
    return Probes(out, _domain(out))


def _domain(ps) -> str:
    n = sum(1 for p in ps if not p.name.startswith("A"))
    return (
        f"A1, A2, A6 and {n} random points of s(1), s(2), s(26) (their free joints uniform over Table I; "
        "the fixed joints at their singular values and limits)"
    )


# ----------------------------------------------------------------------------- Eq 58
def eq58_printed(lo, hi, lam):
    """Eq 58: q = (qU + qL)/2 + (qU - qL)/2 sin(lambda) [rad]."""
    return (hi + lo) / 2 + (hi - lo) / 2 * np.sin(lam)


@SECTION.check(
    "Eq 58",
    forms=Forms.right(
        eq58_printed,
        (
            Slip(
                SlipKind.SWAP,
                "(qU - qL)/2 + (qU + qL)/2 sin(lambda): mid and half exchanged",
                lambda lo, hi, lam: (hi - lo) / 2 + (hi + lo) / 2 * np.sin(lam),
            ),
            Slip(
                SlipKind.FUNCTION,
                "cos(lambda) for sin(lambda)",
                lambda lo, hi, lam: (hi + lo) / 2 + (hi - lo) / 2 * np.cos(lam),
            ),
        ),
        tolerance=epsilon(eq58_printed, 1e-9),
    ),
)
def eq58_parameterisation(ctx, eq58):
    """Eq 58: lambda in [-pi/2, pi/2] maps onto Table I; q_s = (qU - qL)/2 cos(lambda) is its derivative."""
    lo, hi = ARM.q_min[:5], ARM.q_max[:5]
    lam = np.concatenate([[-np.pi / 2, np.pi / 2], np.linspace(-np.pi / 2, np.pi / 2, ctx.n(201, 21))])
    q, h = eq58(lo, hi, lam[:, None]), 1e-6  # (m, 5)
    ends = max(np.abs(q[0] - lo).max(), np.abs(q[1] - hi).max())
    fd = (eq58(lo, hi, lam[:, None] + h) - eq58(lo, hi, lam[:, None] - h)) / (2 * h)
    d_qs = np.abs(fd - (hi - lo) / 2 * np.cos(lam)[:, None]).max()  # vs q_s = (qU - qL)/2 cos(lambda)
    inside = np.all((q >= lo - 1e-12) & (q <= hi + 1e-12))
    return Row.graded(
        "Eq 58: q_i(lambda_i) = (qU + qL)/2 + (qU - qL)/2 sin(lambda_i) reaches the joint limits at lambda = "
        "-+pi/2 and stays within them; q_s = (qU - qL)/2 cos(lambda) (App. E).",
        "Eq 58",
        "the printed map on lambda over [-pi/2, pi/2] for joints 1-5 of Table I; its derivative by central "
        "differences vs the q_s App. E uses",
        None,
        (
            Measure("max |q(-+pi/2) - Table I limits|", ends, 1e-12, "rad"),
            Measure("max |dq/dlambda - (qU - qL)/2 cos(lambda)| (central differences)", d_qs, 1e-8),
            Measure("parameter values mapped outside Table I", 0 if inside else 1, 0),
        ),
        id="eq58",
        domain=f"{len(lam)} values of lambda over [-pi/2, pi/2] (both ends exactly), joints 1-5",
        erratum=Erratum(
            "Eq 58", "q = (qU + qL)/2 + (qU - qL)/2 sin(lambda)", "-", f"ends off by {ends:.3g} rad"
        ),
    )


# ----------------------------------------------------------------------------- Eq 59, 61, 63, 62-65
def _b_transposed(f_u, rows):
    E = np.zeros((2, 3))
    E[0, rows[0]] = E[1, rows[1]] = 1.0
    return np.linalg.inv(E @ f_u).T @ E


def _eq59_error(p: Probe, eq59) -> float:
    """|N0 of the form - the surface normal|, up to the sign."""
    n = np.asarray(eq59(p.Gq, p.qs), float)
    return min(np.abs(n - p.N0).max(), np.abs(n + p.N0).max())


def _eq65_error(p: Probe, eq65) -> float:
    H = eq61_h_star(p.N0, p.Hq, p.Gq, p.qs, p.qss)
    B = eq63_b(p.f_u, p.rows)
    return np.abs(np.asarray(eq65(H, B, p.Gq, p.qs, p.nf_uu())) - p.meaning("q_star", p.rows)).max() * 1e3


def _per_probe(error):
    """The error function of a formula measured at each probe: ``error(probe, form)`` -> float."""
    return lambda ps, form: np.array([error(p, form) for p in ps])


FORMULAS = SECTION.formulas(
    probes,
    Formula("Eq 59", eq59_normal, _per_probe(_eq59_error), 1e-6, "", (
        Slip(SlipKind.MODEL, "the null vector of G_q alone (q_s left out: the joint limits ignored)",
             lambda Gq, qs: eq59_normal(Gq, np.ones(5))),
        Slip(SlipKind.BRANCH, "the first left singular vector (the largest) for the null one",
             lambda Gq, qs: np.linalg.svd(Gq * qs[None, :])[0][:, 0]),
    ), eps=1e-6, text="N0 = null[G_q q_s]^T", method=_ROUTE,
        measure="max |N0 of Eq 59 - surface normal| (up to sign)"),
    Formula("Eq 61", eq61_h_star, _per_probe(
        lambda p, f: np.abs(np.asarray(f(p.N0, p.Hq, p.Gq, p.qs, p.qss)) - p.meaning("h_star")).max() * 1e3),
            TOL, "mm", (
        Slip(SlipKind.TERM, "without the sum of d(N0.G)/dq_i [q_i]_ss",
             lambda N0, Hq, Gq, qs, qss: eq61_h_star(N0, Hq, Gq, qs, np.zeros_like(qss))),
        Slip(SlipKind.SIGN, "minus the sum of d(N0.G)/dq_i [q_i]_ss",
             lambda N0, Hq, Gq, qs, qss: eq61_h_star(N0, Hq, Gq, qs, -qss)),
    ), eps=1e-6, text="H* = ...", method=_ROUTE, measure="max |H* of Eq 61 - Hessian of N0.G(q(s))|"),
    Formula("Eq 63", eq63_b, _per_probe(
        lambda p, f: np.abs(np.asarray(f(p.f_u, p.rows)) @ (p.Gq * p.qs[None, :])
                            - p.meaning("du_ds", p.rows)).max()),
            1e-6, "", (
        Slip(SlipKind.TRANSPOSE, "[E f_u]^-T E (the inverse transposed)", _b_transposed),
        Slip(SlipKind.SIGN, "-[E f_u]^-1 E", lambda f_u, rows: -eq63_b(f_u, rows)),
    ), eps=1e-6, text="B = [E f_u]^-1 E", method=_ROUTE + " (E the best-conditioned row pair)",
        measure="max |B G_q q_s - du*/ds|"),
    Formula("Eq 62-65", eq65_q_star, _per_probe(_eq65_error), TOL, "mm", (
        Slip(SlipKind.SIGN, "H* + q_s^T G_q^T B^T [N0 f]_uu B G_q q_s",
             lambda H, B, Gq, qs, Nf_uu: 2 * H - eq65_q_star(H, B, Gq, qs, Nf_uu)),
        Slip(SlipKind.TERM, "Q* = H* (the curvature term of Eq 62 left out)", lambda H, B, Gq, qs, Nf: H),
    ), eps=1e-6, id="eq65", text="Q* = ...", method=_ROUTE,
        claim="Eq 62-65: Q* = H* - q_s^T G_q^T B^T [N0 f]_uu B G_q q_s is the second derivative in s of the "
        "tool's normal distance from the singular surface (the normal acceleration eta = s'^T Q* s', Eq 57).",
        measure="max |Q* of Eq 65 - Hessian of the normal distance|"),
)


# ----------------------------------------------------------------------------- Eq 66-67
def eq66_67_printed(N0, Gq, q0):
    """Eq 66-67: ``{joint: sigma}`` = N0 . G_qi dq_i with dq_i = +1 at a lower limit, -1 at an upper one."""
    return {j: float(N0 @ Gq[:, j - 1] * dq) for j, dq in eq67_dq(q0, ARM).items()}


def _limit_joints(ctx) -> Probes:
    """``(joint, probe)`` for each joint at a limit of the probes that have one (A2, A6, s(2), s(26))."""
    ps = [p for p in probes(ctx) if eq67_dq(p.q0, ARM)]
    return Probes([(j, p) for p in ps for j in eq67_dq(p.q0, ARM)],
                  _domain(ps) + "; only the points with a joint on a limit (A2, A6, s(2), s(26))")


def _sigma_error(jp: tuple[int, Probe], eq66) -> float:
    """|sigma of the form - the tool's first-order normal motion| [mm] when joint j leaves its limit into the
    range."""
    j, p = jp
    dq = eq67_dq(p.q0, ARM)[j]
    into = ARM.q_min[j - 1] <= p.q0[j - 1] + 1e-3 * dq <= ARM.q_max[j - 1]
    return abs(eq66(p.N0, p.Gq, p.q0).get(j, np.inf) - p.meaning("sigma", j, dq if into else -dq)) * 1e3


FORMULAS |= SECTION.formulas(_limit_joints, Formula(
    "Eq 66-67", eq66_67_printed, _per_probe(_sigma_error), TOL, "mm", (
        Slip(SlipKind.LIMIT, "dq = -1 at a lower limit, +1 at an upper one",
             lambda N0, Gq, q0: {j: -v for j, v in eq66_67_printed(N0, Gq, q0).items()}),
        Slip(SlipKind.OFF_BY_ONE, "G_q of the next joint",
             lambda N0, Gq, q0: {j: float(N0 @ Gq[:, j % 5] * dq) for j, dq in eq67_dq(q0, ARM).items()}),
    ), eps=None, id="eq66_67", name="eq66_67_sigma", text="sigma = N0 G_qi dq_i",
    claim="Eq 66-67: sigma = N0 G_qi dq_i, dq_i = +1 at a lower limit and -1 at an upper one, is the "
    "first-order motion of the tool along N0 when joint i leaves its limit (into Table I).",
    method=_ROUTE + " with a joint at a limit",
    measure="max |sigma of Eq 66-67 - normal motion into the range|"))


# ----------------------------------------------------------------------------- Eq 68
@per_run
def _sigma_zero_points(ctx) -> Probes:
    """Points of s(24)-s(27) (theta2 and theta4 at limits, theta3 = 0, free theta1, theta5) where Eq 66
    vanishes for one of the joints at a limit: theta5 = 0 (sigma_4 = 0) and the roots of sigma_2(theta5), at
    random theta1."""
    rng = ctx.rng("eq68-points")
    out = []
    sets = [(t2, t4) for t2 in (ARM.q_min[1], ARM.q_max[1]) for t4 in (ARM.q_min[3], ARM.q_max[3])]
    for t2, t4 in sets[: ctx.n(4, 2)]:
        t1 = rng.uniform(ARM.q_min[0], ARM.q_max[0])
        for j, t5 in [(4, 0.0)] + [(2, t5) for t5 in _sigma2_roots(t1, t2, t4)]:
            q = np.array([t1, t2, 0.0, t4, t5])
            p = _probe(f"s(24-27) sigma_{j} = 0 at {fmt_vec(np.degrees(q), 1)} deg", q, (1, 5))
            # a sign change of the unnormalised normal through zero (tangents parallel) is not a root of sigma
            if p is not None and abs(p.sp.sigma(j, 1.0)) < 1e-7:
                out.append((j, p))
    return Probes(out, f"{len(out)} points of s(24)-s(27) (theta2, theta4 at limits, theta3 = 0) where "
                  "sigma_4 = 0 (theta5 = 0) or sigma_2 = 0 (roots in theta5), theta1 random in Table I")


def _sigma2_roots(t1: float, t2: float, t4: float) -> list[float]:
    """The theta5 [rad] in Table I where the unnormalised normal (f_theta1 x f_theta5) is orthogonal to G_q2
    at [t1, t2, 0, t4, theta5] (a grid, then Brent's method; continuous in theta5, unlike the unit normal)."""

    def s2(t5) -> np.ndarray:
        q = np.array([[t1, t2, 0.0, t4, t] for t in np.atleast_1d(t5)])
        d = [(tool_point(q + e) - tool_point(q - e)) / 2e-6 for e in np.eye(5)[[0, 4, 1]] * 1e-6]
        return np.einsum("ni,ni->n", np.cross(d[0], d[1]), d[2])

    grid = np.linspace(ARM.q_min[4] + 1e-3, ARM.q_max[4] - 1e-3, 241)
    vals = s2(grid)
    sign_changes = np.nonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0)[0]
    return [brentq(lambda t: s2(t)[0], grid[k], grid[k + 1], xtol=1e-15) for k in sign_changes]


#: Eq 68 as printed (verification.oracles.abdel_malek).
eq68_printed = eq68_kbar


def _kbar_at(p: Probe, j: int, form) -> float:
    NG_qq = np.einsum("k,kij->ij", p.N0, p.Hq)
    return float(form(p.Gq[:, j - 1], eq63_b(p.f_u, p.rows), p.nf_uu(), NG_qq[j - 1, j - 1]))


def rule_printed(kbar: float) -> float:
    """The printed rule: K-bar > 0 -> motion along +N0 (+1), K-bar < 0 -> along -N0 (-1)."""
    return float(np.sign(kbar))


def rule_corrected(kbar: float) -> float:
    """K-bar > 0 -> the tool moves to the -N0 side (phi ~ -K t^2 / 2)."""
    return float(-np.sign(kbar))


_STEP = 1e-2  # [rad]: how far joint i leaves its limit to see which side the tool moves to


def _sides(pts, rule, n0: float = 1.0, out: float = 1.0, alt_rows: bool = False):
    """At each point ``(j, probe)``: the side ``rule`` predicts from K-bar's sign (+1: +N0) and the side the
    tool goes to when joint j leaves its limit by ``_STEP`` (the sign of its normal distance); under the
    nearby readings N0 the other way (``n0`` -1), the joint moved out of its range (``out`` -1) and Eq 63's
    other row pair (``alt_rows``)."""
    pred, seen = [], []
    for j, p in pts:
        rows = [r for r in ((0, 1), (0, 2), (1, 2)) if r != p.rows][0] if alt_rows else p.rows
        dq = eq67_dq(p.q0, ARM).get(j, 1.0) * out
        pred.append(rule(_kbar_at(p, j, eq68_printed) * n0))
        seen.append(float(np.sign(n0 * p.meaning("offset", j, _STEP * dq, rows))))
    return np.array(pred), np.array(seen)


def rule_reading(pts, rule):
    """Second reading of the K-bar rule: the side predicted by ``rule`` vs the measured one under the nearby
    readings of its inputs (:func:`_sides`)."""

    def misfit(x) -> float:
        return float(np.sum(np.not_equal(*_sides(pts, rule, **x))))

    readings = [
        Reading(Kind.SIGN, "N0 the other way", {"n0": -1.0}),
        Reading(Kind.LIMIT, "the joint moved out of its range (dq of the other limit)", {"out": -1.0}),
        Reading(Kind.CONVENTION, "Eq 63's other row pair", {"alt_rows": True}),
    ]
    return search(
        {"n0": 1.0, "out": 1.0, "alt_rows": False},
        readings,
        misfit,
        0.0,
        printed="'If K-bar > 0 the singular surface admits motion in the "
        "direction of N0; if K-bar < 0 in the opposite direction'",
        stated_text="K-bar of Eq 68, N0 of Eq 59, dq of Eq 67",
        route="the sign of the tool's normal distance after the joint leaves its "
        f"limit by {_STEP:g} rad (verification.oracles.normal_distance)",
        measure="points where the predicted side is wrong",
    )


def _measured(pts, err) -> str:
    """K-bar at each point and the side the tool goes to (the rule's row's note)."""
    seen = _sides(pts, rule_printed)[1]
    return "measured: " + "; ".join(
        f"K-bar_{j} = {_kbar_at(p, j, eq68_printed) * 1e3:.0f} mm -> {'+' if s > 0 else '-'}N0"
        for s, (j, p) in zip(seen, pts, strict=True)
    )


FORMULAS |= SECTION.formulas(
    _sigma_zero_points,
    Formula("Eq 68", eq68_printed, lambda pts, f: np.array(
        [abs(_kbar_at(p, j, f) - p.meaning("kbar", j, p.rows)) * 1e3 for j, p in pts]), TOL, "mm", (
        Slip(SlipKind.SIGN, "the two terms of Eq 68 exchanged",
             lambda g, B, Nf, NG: -eq68_kbar(g, B, Nf, NG)),
        Slip(SlipKind.TERM, "without the G_qi^T B^T [N0 G]_uu B G_qi term", lambda g, B, Nf, NG: float(-NG)),
    ), eps=1e-6, text="K-bar = ...",
        method="Eq 68 as printed (Pinocchio) vs the second derivative of the normal distance phi along "
        "joint i alone (verification.oracles.normal_distance), at the points where sigma_i = 0",
        note=lambda pts, err: "K-bar = "
        + ", ".join(f"{_kbar_at(p, j, eq68_printed) * 1e3:.1f}" for j, p in pts) + " mm",
        measure="max |K-bar of Eq 68 - (-d2 phi/dq_i^2)|"),
    Formula("Eq 68", rule_printed, lambda pts, rule: np.not_equal(*_sides(pts, rule)), 0, "", (
        Slip(SlipKind.SIGN, "K-bar > 0 -> the +N0 side (as printed)", rule_printed),
        Slip(SlipKind.CLAIM, "always the +N0 side", lambda k: 1.0),
    ), good=rule_corrected,
        good_is="K-bar > 0 -> the -N0 side (K-bar is minus the normal distance's curvature)",
        eps=None, id="eq68.rule", name="eq68_rule", count=True, note=_measured,
        measure="points where the rule predicts the wrong side",
        text="K-bar > 0: motion in the direction of N0; K-bar < 0: opposite",
        corrected="K-bar > 0: motion opposite to N0 (the tool's normal distance is about -K-bar t^2 / 2), or "
        "K-bar with its two terms exchanged",
        claim="Eq 68: 'If K-bar > 0 the singular surface admits motion in the direction of N0. If K-bar < 0 "
        "the singular surface admits motion in the opposite direction of N0.'",
        method="at the points where sigma_i = 0 (row eq68): the side the rule predicts from K-bar's sign vs "
        f"the side of the surface the tool goes to when joint i leaves its limit by {_STEP:g} rad (the sign "
        "of its normal distance, verification.oracles.normal_distance)",
        reread=lambda ctx, pts, rule: rule_reading(pts, rule)),
)
