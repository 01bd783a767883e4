"""Checks of the dexterity analysis (Sec 3.5, Eq 42-51): the angle convention, Eq 43-51 one by
one against exact geometry, and the printed admitted set against an IK feasibility sweep.

Angles of Sec 3.5: link 5 points from the second-last joint (SLJ, joint 5) to the tool
point ``p``; beta is its inclination from the horizontal (Eq 43, 47) and alpha its azimuth
(Eq 46). Exact geometry comes from Pinocchio joint placements at the configurations the
text describes (links 3-4 aligned, theta4 = 0; or contracted, theta4 = +-119 deg; the arm
in one vertical plane, theta3 = 0). The IK ground truth: an orientation ``(alpha, beta)``
(Eq 42 convention, see :mod:`iik.rotations`) is feasible at ``p`` if ``iik.solve``
(complete solver) returns a solution within Table I for ``iik.pose_from_euler(p, alpha,
beta, 0)`` (gamma only turns joint 6, checked separately). The printed Eq 43-51 are
transcribed one by one and composed in :func:`printed_admits`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

import numpy as np

import iik
from iik import THESIS_ARM
from iik.dexterity import admissible, alpha_intervals, dexterity

from ..assumptions import EXACT_GEOMETRY
from ..formula import Formula, per_run
from ..numbers import fmt_q
from ..oracles.pinocchio_model import joint_placements
from ..plotting import new_figure
from ..registry import Forms, Measure, Row, Scope, Section, Slip, SlipKind, Verdict
from ..second_reading import Kind, Reading, search
from ..shorthand import wrap
from ..thesis_index import title_of

ARM = THESIS_ARM
_D = np.pi / 180
L1, L2, L3, L4, L5 = ARM.lengths
D_IN = np.sqrt(L3**2 + L4**2 - 2 * L3 * L4 * np.cos(np.pi - 119 * _D))  # Eq 45 / Eq 50 (d, phi)
TOL = 1e-9  # [rad or -]: an exact geometric identity through acos/atan
SECTION = Section("Dexterity (Sec 3.5, Eq 42-51)", depends_on=EXACT_GEOMETRY, order=50.0)


# ----------------------------------------------------------------------------- printed forms
@np.errstate(invalid="ignore", divide="ignore")
def printed_admits(p, alpha35, beta35) -> np.ndarray:
    """Eq 43-51 as printed (their transcriptions below, one per equation): is (alpha, beta) in the thesis's
    own angles [rad] admitted at ``p`` (3,) [m]?

    Cases (Sec 3.5.2-3.5.3): outer only -> beta' +- delta (Eq 44), alpha' +- sigma (Eq 49);
    ring -> Eq 44 with the Eq 45 interval removed, alpha in Eq 49's interval and outside Eq 51's;
    inner only -> beta' +- delta (Eq 45), alpha' +- sigma (Eq 51).
    """
    P = np.asarray(p, float)[None]
    a, b = np.asarray(alpha35, float), np.asarray(beta35, float)
    rho = _length(_from_joint2(P))[0]
    # Eq 44, 45: the outer and inner triangles close
    has_out, has_in = (abs((L5**2 + rho**2 - r**2) / (2 * L5 * rho)) <= 1 for r in (L3 + L4, D_IN))
    if not (has_out or has_in):
        return np.zeros(np.broadcast(a, b).shape, bool)
    bp, d_out, d_in = eq43_printed(P)[0], eq44_delta(rho, L3 + L4), eq44_delta(rho, D_IN)
    h, rxy = eq47_printed(P[0, 2], b), np.hypot(P[0, 0], P[0, 1])
    sigma_out, sigma_in = (eq49_sigma(rxy, b, eq48_printed(h, r), r) for r in (L3 + L4, D_IN))  # Eq 48-51
    ok_a = _in_ring(np.abs(wrap(a - eq46_printed(P)[0])), sigma_out, sigma_in, has_out, has_in)
    return _in_ring(np.abs(b - bp), d_out, d_in, has_out, has_in) & ok_a


def _in_ring(dev, outer, inner, has_out: bool, has_in: bool):
    """Sec 3.5.2-3.5.3's cases: ``dev`` within the outer bound (outer circle only), within the outer and
    beyond the inner (the ring), or within the inner (inner circle only)."""
    if not has_out:
        return dev <= inner
    return (dev <= outer) & (dev >= inner) if has_in else dev <= outer


# ----------------------------------------------------------------------------- exact geometry
@dataclass(frozen=True)
class Pose35:
    """Sec 3.5 quantities of configurations q (Pinocchio, base frame): tool point p, SLJ S, joint 2 J2 [m],
    link-5 unit vector a = (p - S)/l5, its inclination beta and azimuth alpha, the point's azimuth phi [rad];
    ``kind`` (:data:`_KIND_TEXT`) and, for the planar families, ``r`` the side of their triangle (l3 + l4 or
    d) per configuration."""

    q: np.ndarray
    p: np.ndarray
    S: np.ndarray
    J2: np.ndarray
    kind: str = ""
    r: np.ndarray | None = None

    a = property(lambda self: (self.p - self.S) / L5)
    beta = property(lambda self: np.arcsin(np.clip(self.a[:, 2], -1, 1)))
    alpha = property(lambda self: np.arctan2(self.a[:, 1], self.a[:, 0]))
    phi = property(lambda self: np.arctan2(self.p[:, 1], self.p[:, 0]))

    def __len__(self) -> int:
        return len(self.q)

    def at(self, k: int) -> str:
        return fmt_q(self.q[k])

    @property
    def domain(self) -> str:
        t2 = np.degrees(self.q[:, 1])
        return (f"{len(self.q)} configurations with {_KIND_TEXT[self.kind]}; the other joints uniform in "
                f"Table I, theta2 over the whole range ({t2.min():.0f}..{t2.max():.0f} deg), a third within "
                "10^U(-6, -1.5) rad of +-90 deg (link 3 vertical)")


def _pose35(q, kind: str = "", r=None) -> Pose35:
    F = joint_placements(q)
    return Pose35(q, F[:, 6, :3, 3], F[:, 5, :3, 3], F[:, 2, :3, 3], kind, r)


@per_run
def configurations(ctx, kind: str) -> Pose35:
    """The configurations the text describes (cached), the family ``kind`` (:data:`_KIND_TEXT`; "planar": both
    planar families, with their ``r``): theta2 over the whole of Table I, a third of the samples within
    10^U(-6, -1.5) rad of +-90 deg (link 3 vertical: where the inclination formulas are hardest); the planar
    ones keep p in front of the base axis (its azimuth is theta1)."""
    if kind == "planar":
        c, c2 = configurations(ctx, "aligned-planar"), configurations(ctx, "contracted-planar")
        r = np.concatenate([np.full(len(c.q), L3 + L4), np.full(len(c2.q), D_IN)])
        return _pose35(np.concatenate([c.q, c2.q]), kind, r)
    rng = ctx.rng(f"dex-{kind}")
    n = ctx.n(3000, 300)
    q = rng.uniform(ARM.q_min, ARM.q_max, (n, 6))
    near = np.arange(n) % 3 == 0
    q[near, 1] = (rng.choice([-1.0, 1.0], n) * np.pi / 2 + rng.choice([-1.0, 1.0], n)
                  * 10 ** rng.uniform(-6, -1.5, n))[near]
    q[:, 1] = np.clip(q[:, 1], ARM.q_min[1], ARM.q_max[1])
    q[:, 3] = 0.0 if kind.startswith("aligned") else rng.choice([-1.0, 1.0], n) * 119 * _D
    if kind.endswith("planar"):
        q[:, 2] = 0.0
    c = _pose35(q, kind)
    return _pose35(q[np.abs(wrap(c.phi - q[:, 0])) < 1e-9], kind) if kind.endswith("planar") else c


_KIND_TEXT = {
    "aligned-planar": ("theta3 = theta4 = 0 (links 3-4 aligned, the arm in one vertical plane; "
                       "p in front of the axis)"),
    "contracted-planar": ("theta3 = 0, theta4 = +-119 deg (links 3-4 contracted, one vertical plane; "
                          "p in front of the axis)"),
    "planar": "theta3 = 0 and theta4 = 0 or +-119 deg",
    "aligned": "theta4 = 0 (links 3-4 aligned), theta3 free",
    "contracted": "theta4 = +-119 deg (links 3-4 contracted), theta3 free",
}


def _family(kind: str):
    """The sampler of one family of configurations (:func:`configurations`)."""
    return lambda ctx: configurations(ctx, kind)


def _length(v: np.ndarray) -> np.ndarray:
    return np.linalg.norm(v, axis=1)


def _inclination(v: np.ndarray) -> np.ndarray:
    """The inclination [rad] of vectors (n, 3) from the horizontal."""
    return np.arcsin(v[:, 2] / _length(v))


# ----------------------------------------------------------------------------- Eq 43-47
def _from_joint2(p, l2: float = L2):
    """p - joint 2 (Eq 37: joint 2 at azimuth atan2(py, px), ``l2`` from the axis, at height l1) -> (n, 3)
    [m]."""
    phi = np.arctan2(p[:, 1], p[:, 0])
    return p - np.stack([l2 * np.cos(phi), l2 * np.sin(phi), np.full(len(p), L1)], 1)


def eq43_printed(p, l2: float = L2):
    """Eq 43: beta' = atan((pz - z2) / sqrt((px - x2)^2 + (py - y2)^2)), joint 2 by Eq 37."""
    v = _from_joint2(p, l2)
    return np.arctan(v[:, 2] / np.sqrt(v[:, 0] ** 2 + v[:, 1] ** 2))


def _acos(x):
    return np.arccos(np.clip(x, -1, 1))


def eq44_delta(rho, r):
    """Eq 44 / Eq 45: delta = acos((l5^2 + rho^2 - r^2) / (2 l5 rho)) with r = l3 + l4 or d."""
    return _acos((L5**2 + rho**2 - r**2) / (2 * L5 * rho))


def _printed(key: str) -> str:
    """The printed form of an index item: its title without the words after ": "."""
    return title_of(key).split(": ")[0]


#: The slips of the printed triangle of Eq 44 and Eq 45.
_DELTA_SLIPS = (
    Slip(SlipKind.SIGN, "l5^2 - rho^2 - r^2 in the numerator",
         lambda rho, r: _acos((L5**2 - rho**2 - r**2) / (2 * L5 * rho))),
    Slip(SlipKind.SWAP, "l5^2 and r^2 exchanged (the angle at the other vertex)",
         lambda rho, r: _acos((r**2 + rho**2 - L5**2) / (2 * L5 * rho))),
    Slip(SlipKind.FUNCTION, "asin for acos",
         lambda rho, r: np.arcsin(np.clip((L5**2 + rho**2 - r**2) / (2 * L5 * rho), -1, 1))),
)


def _beta_limits(key: str, r: float, note=None) -> Formula:
    """Eq 44 / Eq 45: link 5 at beta' +- delta (the printed triangle with side ``r``), as unit vectors, in
    the vertical plane of J2 and p."""
    def error(c, f):
        v = c.p - c.J2
        return _link5_error(c, r, np.arctan2(v[:, 1], v[:, 0]), delta=f)

    return Formula(key, eq44_delta, error, TOL, "-", _DELTA_SLIPS,
                   good_is="the printed triangle (it is right)", eps=1e-6, eps_is="delta + 1 urad",
                   measure=_GEOMETRY, note=note,
                   method="Pinocchio: the link-5 direction vs the two directions at beta' +- delta in the "
                   "plane of J2 and p (compared as unit vectors, so inclinations past 90 deg need no special "
                   "case)")


#: q [rad] of the counterexample that made Eq 46 an erratum before issue 19 (links 3-4 aligned, link 5 facing
#: the base axis): beta' + delta = 137.05 deg there.
OLD_EQ46_COUNTEREXAMPLE = np.array([1.0427, -0.3330, 0.0, 0.0, 2.0590, -2.3543])


def eq46_printed(p):
    return np.arctan2(p[:, 1], p[:, 0])


def _dir(alpha: np.ndarray, beta: np.ndarray) -> np.ndarray:
    """The unit vector at azimuth ``alpha`` and inclination ``beta`` in that vertical plane (Sec 3.5's angles:
    beta past 90 deg tilts it back over the vertical) -> (n, 3)."""
    horizontal = np.stack([np.cos(alpha), np.sin(alpha), 0 * alpha], 1)
    return np.cos(beta)[:, None] * horizontal + np.sin(beta)[:, None] * np.array([0.0, 0.0, 1.0])


def _link5_error(c: Pose35, r, alpha: np.ndarray, nominal=eq43_printed, delta=eq44_delta) -> np.ndarray:
    """|link 5 - the direction at (alpha, beta' +- delta)|, the nearer of the two (Eq 43-45's beta;
    ``nominal`` gives beta', ``delta(rho, r)`` the half-angle)."""
    bp, d = nominal(c.p), delta(_length(c.p - c.J2), r)
    return np.minimum(_length(_dir(alpha, bp + d) - c.a), _length(_dir(alpha, bp - d) - c.a))


def eq46_reading(ctx, c: Pose35, eq46):
    """Second reading of Eq 46 (the form): link 5 against the direction the thesis's angles describe, as
    stated (beta' by Eq 43 as printed) and under each reading below (the signed run first: it keeps Eq 46)."""
    stated = {"p": c.p, "beta'": eq43_printed, "projection": False}

    def misfit(x) -> float:
        alpha = np.asarray(eq46(x["p"]), float)
        if x["projection"]:
            return float(np.abs(wrap(alpha - c.alpha)).max())
        return float(_link5_error(c, c.r, alpha, x["beta'"]).max())

    readings = [
        Reading(Kind.SIGN, "Eq 43's run with its sign: beta' = atan2(pz - z2, |p_xy| - l2) (the square root "
                "drops the sign where p lies between the base axis and joint 2; Eq 46 as printed)",
                {"beta'": lambda p: np.arctan2(p[:, 2] - L1, np.hypot(p[:, 0], p[:, 1]) - L2)}),
        Reading(Kind.WHICH, "(px, py) measured from joint 2, as Eq 43 measures beta' (they differ by pi "
                "where p is horizontally within l2 of the base axis)", {"p": _from_joint2(c.p)}),
        Reading(Kind.CONVENTION, "beta within +-90 deg, alpha the azimuth of link 5's horizontal projection "
                "(the reading that made Eq 46 an erratum)", {"projection": True}),
    ]
    return search(stated, readings, misfit, TOL, printed="alpha' = atan2(py, px)",
                  stated_text="Sec 3.5's angles: alpha the azimuth of the arm's vertical plane, beta the "
                  "inclination in it (Eq 43-45: beta' +- delta, which runs past 90 deg)",
                  route="link 5 (p - SLJ) from Pinocchio joint placements vs the direction of (alpha', beta)",
                  measure="max |link 5 - direction of the angles| (unit vectors) or |alpha difference| [rad]")


def eq46_from_joint2(p):
    """alpha' as the azimuth of p seen from joint 2 (Eq 37's point at azimuth atan2(py, px)): the direction of
    Eq 43's run."""
    v = _from_joint2(p)
    return np.arctan2(v[:, 1], v[:, 0])


def _eq46_note(c: Pose35, err) -> str:
    """Where link 5 faces the base axis, where p lies between the axis and joint 2, the former erratum."""
    inward = np.einsum("ni,ni->n", c.a[:, :2], c.p[:, :2]) < 0
    beta = np.degrees(eq43_printed(c.p) + eq44_delta(_length(c.p - c.J2), c.r))
    close = np.hypot(c.p[:, 0], c.p[:, 1]) < L2
    far = ~close
    old = _pose35(OLD_EQ46_COUNTEREXAMPLE[None], r=np.array([L3 + L4]))  # the former erratum (issue 19)
    old_beta = eq43_printed(old.p) + eq44_delta(_length(old.p - old.J2), old.r)
    old_err = _link5_error(old, old.r, eq46_printed(old.p))[0]
    return (
        f"link 5 faces the base axis in {inward.mean():.0%} of these configurations (beta' + delta up to "
        f"{beta.max():.1f} deg; past 90 deg in {(beta > 90).mean():.0%}): there too the angles describe "
        f"link 5 exactly (max {err[far & inward].max() if (far & inward).any() else 0:.1e}; at the "
        f"configuration that made Eq 46 an erratum before issue 19, {fmt_q(OLD_EQ46_COUNTEREXAMPLE)}, beta' "
        f"+ delta = {np.degrees(old_beta[0]):.2f} deg and (alpha', beta) is link 5 to {old_err:.1e}); where "
        f"p is horizontally within l2 of the axis (between the axis and joint 2, {close.mean():.0%} of "
        "them) Eq 43's beta' is measured toward the axis and the pair misses by "
        f"{err[close].max() if close.any() else 0:.2g}; beyond joint 2 max "
        f"{err[far].max() if far.any() else 0:.1e}")


def eq47_printed(pz, beta):
    return pz - L5 * np.sin(beta)


# ----------------------------------------------------------------------------- Eq 48-51
def eq48_printed(h, r):
    """Eq 48 / Eq 50: delta = atan((h_SLJ - l1) / r), r = l3 + l4 (aligned) or phi (contracted)."""
    return np.arctan((h - L1) / r)


def eq48_corrected(h, r):
    return np.arcsin(np.clip((h - L1) / r, -1, 1))


#: d (Eq 45) = phi (Eq 50, 51) with its angle 180 - 119 = 61 taken as radians.
D_IN_RAD = float(np.sqrt(L3**2 + L4**2 - 2 * L3 * L4 * np.cos(61.0)))


def inclination_reading(c: Pose35, truth: np.ndarray, r: float, form, printed: str):
    """Second reading of Eq 48 / Eq 50 (the form): the inclination of links 3-4 (``truth`` [rad]) under each
    nearby reading of its stated inputs below."""
    stated = {"h": c.S[:, 2], "r": r, "sign": 1.0}

    def misfit(x) -> float:
        return float(np.abs(x["sign"] * form(x["h"], x["r"]) - truth).max())

    readings = [
        Reading(Kind.CONVENTION, "h_SLJ measured from the base (l1 not subtracted)", {"h": c.S[:, 2] + L1}),
        Reading(Kind.SIGN, "delta measured downward", {"sign": -1.0}),
    ]
    if r < L3 + L4:
        readings.append(Reading(Kind.UNIT, "phi with 180 - 119 = 61 taken as rad", {"r": D_IN_RAD}))
    return search(stated, readings, misfit, TOL, printed=printed,
                  stated_text="h_SLJ (Eq 47), l1, the segment's length "
                  f"{'l3 + l4' if r >= L3 + L4 else 'phi'}",
                  route="the inclination of joint 2 -> SLJ from Pinocchio joint placements",
                  measure="max |form - inclination| [rad]")


def _delta(key: str, r: float, why: str) -> Formula:
    """Eq 48 / Eq 50: the inclination of links 3-4 (the segment of length ``r``, joint 2 -> SLJ) from the true
    h_SLJ; corrected: asin for atan (``why``)."""
    text = _printed(key)
    good = text.replace("atan", "asin")
    err = lambda c, f: np.abs(f(c.S[:, 2], r) - _inclination(c.S - c.J2))
    return Formula(key, eq48_printed, err, TOL, "rad", (
        Slip(SlipKind.FUNCTION, "atan for asin (as printed)", eq48_printed),
        Slip(SlipKind.LENGTH, "l3 for the segment's length", lambda h, r: eq48_corrected(h, L3 + 0 * r)),
        Slip(SlipKind.SIGN, "h_SLJ + l1 (the base height added)", lambda h, r: eq48_corrected(h + 2 * L1, r)),
    ), good=eq48_corrected, good_is=good, eps=1e-6, eps_is="the good delta + 1 urad", text=text,
        corrected=f"{good} ({why})", measure=_GEOMETRY,
        method="Pinocchio: the inclination of J2 -> SLJ vs the form with the true h_SLJ",
        note=lambda c, err: f"|J2 - SLJ| = {r:.4f} m: the rise over the segment's length is a sine, not a "
        "tangent", reread=lambda ctx, c, f: inclination_reading(c, _inclination(c.S - c.J2), r, f, text))


def eq49_sigma(rho, beta, delta, r, reach=None):
    """Eq 49 / Eq 51: sigma = acos((rho^2 + (l5 cos b)^2 - (r cos d + l2)^2) / (2 rho l5 cos b)).

    rho = |p_xy|.

    ``reach`` (ignored here): the SLJ's true horizontal distance, used by the known-good form."""
    return _cos_law(rho, L5 * np.cos(beta), r * np.cos(delta) + L2)


def _cos_law(rho, lb, far, sign: float = 1.0):
    """The angle at the base axis of the triangle with sides ``rho`` (to p), ``lb`` (link 5 projected) and
    ``far`` (to the SLJ) [rad]; ``sign`` -1: the slip rho^2 - lb^2."""
    return _acos((rho**2 + sign * lb**2 - far**2) / (2 * rho * lb))


#: The slips of the printed law of cosines of Eq 49 and Eq 51.
_SIGMA_SLIPS = (
    Slip(SlipKind.SIGN, "rho^2 - (l5 cos b)^2 in the numerator",
         lambda rho, beta, delta, r, reach: _cos_law(rho, L5 * np.cos(beta), r * np.cos(delta) + L2, -1.0)),
    Slip(SlipKind.FUNCTION, "l5 sin(b) for l5 cos(b)",
         lambda rho, beta, delta, r, reach: eq49_sigma(rho, np.pi / 2 - beta, delta, r)),
    Slip(SlipKind.LENGTH, "the SLJ's distance without l2",
         lambda rho, beta, delta, r, reach: _cos_law(rho, L5 * np.cos(beta), r * np.cos(delta))),
)


def _sigma_inputs(c: Pose35):
    """Link 5's azimuth deviation |alpha - alpha'| [rad], rho = |p_xy|, the true delta (the inclination of
    links 3-4 in joint 1's vertical plane, Sec 3.5's convention: past 90 deg when link 3 leans over the axis;
    with link 3 leaning forward it is Eq 48/50 corrected) and the SLJ's true horizontal distance."""
    v = c.S - c.J2
    out = np.stack([np.cos(c.q[:, 0]), np.sin(c.q[:, 0])], 1)  # joint 1's vertical plane, outward
    delta = np.arctan2(v[:, 2], np.einsum("ni,ni->n", v[:, :2], out))
    rho, reach = np.hypot(c.p[:, 0], c.p[:, 1]), np.hypot(c.S[:, 0], c.S[:, 1])
    return np.abs(wrap(c.alpha - c.phi)), rho, delta, reach


def sigma_reading(c: Pose35, form, r: float, printed: str):
    """Second reading of Eq 49 / Eq 51 (the form): link 5's azimuth deviation under each nearby reading of
    delta's and beta's sign and of phi's 61 deg taken as radians."""
    target, rho, delta, reach = _sigma_inputs(c)
    stated = {"delta": delta, "r": r, "beta": c.beta}

    def misfit(x) -> float:
        return float(np.abs(target - form(rho, x["beta"], x["delta"], x["r"], reach)).max())

    readings = [
        Reading(Kind.SIGN, "delta measured the other way", {"delta": -delta}),
        Reading(Kind.SIGN, "beta measured the other way", {"beta": -c.beta}),
        Reading(Kind.UNIT, "phi with 180 - 119 = 61 taken as rad", {"r": D_IN_RAD}),
    ]
    return search(stated, readings, misfit, TOL, printed=printed,
                  stated_text="rho = |p_xy|, beta of link 5, delta of links 3-4, the segment's length",
                  route="link 5's azimuth from Pinocchio joint placements",
                  measure="max ||alpha - alpha'| - sigma| [rad]")


def _alpha_limits(key: str, r: float, corrected: str = "-") -> Formula:
    """Eq 49 / Eq 51: link 5's azimuth deviation |alpha - alpha'| is sigma, with the true delta fed in."""
    def error(c, f):
        dev, rho, delta, reach = _sigma_inputs(c)
        return np.abs(dev - f(rho, c.beta, delta, r, reach))

    def note(c, err):
        dev, rho, delta, _ = _sigma_inputs(c)
        chained = np.abs(dev - eq49_sigma(rho, c.beta, eq48_printed(c.S[:, 2], r), r))
        return (f"with the printed Eq {48 if r > D_IN else 50} delta chained in: max {chained.max():.3g} "
                "rad; link 3 leaning back over the axis (delta past 90 deg) in "
                f"{np.mean(np.abs(delta) > np.pi / 2):.0%} of the configurations")

    text = _printed(key)
    return Formula(key, eq49_sigma, error, TOL, "rad", _SIGMA_SLIPS,
                   good=lambda rho, beta, delta, r, reach: _cos_law(rho, L5 * np.cos(beta), reach),
                   good_is="the law of cosines with the SLJ's true horizontal distance", eps=1e-6,
                   eps_is="that sigma + 1 urad", text=text, corrected=corrected, measure=_GEOMETRY, note=note,
                   method="Pinocchio (link 5 leaves the vertical plane): the deviation |alpha - alpha'| "
                   "of link 5's azimuth from the point's vs sigma, with the true delta fed in (the "
                   "inclination of links 3-4 in joint 1's vertical plane: Eq 48/50 corrected where link 3 "
                   "leans forward, past 90 deg where it leans back over the axis)",
                   reread=lambda ctx, c, f: sigma_reading(c, f, r, text))


_GEOMETRY = "max |form - exact geometry|"

CHECKS = {
    **SECTION.formulas(
        _family("aligned-planar"),
        Formula("Eq 43", eq43_printed, lambda c, f: np.abs(f(c.p) - _inclination(c.p - c.J2)), TOL, "rad", (
            Slip(SlipKind.SWAP, "rise and run exchanged",
                 lambda p: np.arctan(np.linalg.norm(_from_joint2(p)[:, :2], axis=1) / _from_joint2(p)[:, 2])),
            Slip(SlipKind.LENGTH, "joint 2 at l3 from the axis (l3 for l2)", lambda p: eq43_printed(p, L3)),
        ), good=lambda p: _inclination(_from_joint2(p)), good_is="asin of the rise over |p - J2|", eps=1e-6,
            eps_is="that beta' + 1 urad", measure=_GEOMETRY,
            method="printed beta' vs the inclination of p - J2 with J2 from Pinocchio (theta1 = phi)",
            basis="beta' = atan(rise / run) and the reference asin(rise / |p - J2|) are two expressions of "
            "the inclination of the same vector (joint 2 by Eq 37, graded in workspace.eq37): an identity"),
        _beta_limits("Eq 44", L3 + L4),
    ),
    **SECTION.formulas(
        _family("contracted-planar"),
        _beta_limits("Eq 45", D_IN, note=lambda c, err: "|J2 - SLJ| = d to "
                     f"{np.abs(_length(c.S - c.J2) - D_IN).max():.1e} m"),
    ),
    **SECTION.formulas(
        _family("planar"),
        Formula("Eq 46", eq46_printed, lambda c, f: _link5_error(c, c.r, np.asarray(f(c.p), float)), TOL,
                "-", (
            Slip(SlipKind.SWAP, "atan2(px, py): the arguments exchanged",
                 lambda p: np.arctan2(p[:, 0], p[:, 1])),
            Slip(SlipKind.FUNCTION, "atan(py / px) for atan2 (the quadrant lost)",
                 lambda p: np.arctan(p[:, 1] / p[:, 0])),
            Slip(SlipKind.BRANCH, "atan2(py, px) + pi (the opposite azimuth)",
                 lambda p: eq46_printed(p) + np.pi),
        ), good=eq46_from_joint2, good_is="the azimuth of p seen from joint 2 (the direction of Eq 43's run)",
            eps=1e-3, eps_is="that azimuth + 1 mrad", measure=_GEOMETRY, note=_eq46_note,
            text="alpha' = atan2(py, px) paired with beta' of Eq 43 (run without its sign)",
            corrected="Eq 46 stands; Eq 43's run keeps its sign: beta' = atan2(pz - z2, |p_xy| - l2) "
            "(equivalently alpha' the azimuth of p seen from joint 2); the two differ only where p lies "
            "horizontally between the base axis and joint 2",
            method="Pinocchio: link 5 (p - SLJ) vs the unit vector at azimuth alpha' and inclination beta' "
            "+- delta in that vertical plane (Sec 3.5's angles: beta runs past 90 deg when link 5 tilts back "
            "over the vertical, Figs 21c, 24c)",
            reread=eq46_reading),
    ),
    **SECTION.formulas(
        _family("aligned"),
        Formula("Eq 47", eq47_printed, lambda c, f: np.abs(f(c.p[:, 2], c.beta) - c.S[:, 2]), 1e-12, "m", (
            Slip(SlipKind.FUNCTION, "l5 cos(beta) for l5 sin(beta)", lambda pz, b: pz - L5 * np.cos(b)),
            Slip(SlipKind.LENGTH, "l4 for l5", lambda pz, b: pz - L4 * np.sin(b)),
        ), eps_is="h + 1 nm", measure=_GEOMETRY,
            method="Pinocchio: z of joint 5 vs the form with the link-5 inclination beta",
            basis="beta is read from the same link-5 vector (asin of its rise over l5) whose rise the "
            "formula subtracts: pz - l5 sin(beta) is the SLJ's height by construction"),
        _delta("Eq 48", L3 + L4, "l3 + l4 is the segment's length, not its run"),
        _alpha_limits("Eq 49", L3 + L4),
    ),
    **SECTION.formulas(
        _family("contracted"),
        _delta("Eq 50", D_IN, "phi = d is the segment's length"),
        _alpha_limits("Eq 51", D_IN,
                      "no closed form of this shape: with theta4 = +-119 deg link 5 leaves the vertical "
                      "plane of joint 1 only if theta3 != 0, which takes link 4 and the SLJ out of it too, "
                      "so the SLJ is not at horizontal distance phi cos(delta) + l2 from the base axis (Fig "
                      "26 is not a configuration of this arm); the admissible alpha range follows from the "
                      "SLJ's true position (iik.dexterity)"),
    ),
}


# ----------------------------------------------------------------------------- convention, admitted sets
def sec35_as_printed(alpha35, beta35):
    """Read the Sec 3.5 angles as Eq 42's directly (what the thesis does)."""
    return alpha35, beta35


def sec35_to_eq42(alpha35, beta35):
    """z6 = -a (Table II: d6 = -l5): alpha_42 = alpha_35 + 180 deg, beta_42 = beta_35 + 90 deg."""
    return wrap(alpha35 + np.pi), beta35 + np.pi / 2


def _z6_gap(a, b, z6: np.ndarray, elevation: bool = False) -> np.ndarray:
    """The angle difference [rad] of Eq 42 angles (``a``, ``b``) from the azimuth and polar angle of ``z6``
    (n, 3) (with ``elevation``: its elevation from the horizontal); the azimuth not counted at the poles."""
    beta = np.arcsin(np.clip(z6[:, 2], -1, 1)) if elevation else np.arccos(np.clip(z6[:, 2], -1, 1))
    alpha = np.arctan2(z6[:, 1], z6[:, 0])
    return np.maximum(np.abs(wrap(a - alpha)) * (np.abs(z6[:, 2]) < 1 - 1e-12), np.abs(b - beta))


def _convention_error(c: Pose35, to_eq42) -> np.ndarray:
    """The angle difference [rad] of the Sec 3.5 angles of link 5 (a = (p - SLJ)/l5) through ``to_eq42`` from
    the Eq 42 angles of z6 (Pinocchio)."""
    return _z6_gap(*to_eq42(c.alpha, c.beta), joint_placements(c.q)[:, 6, :3, 2])


def convention_reading(ctx, c: Pose35, to_eq42):
    """Second reading of the Sec 3.5 / Eq 42 convention (the form): Eq 42's angles of z6 from the iik.dh chain
    under each nearby reading of the stated conventions below, vs the form's angles."""
    from .ik_equations import chain_frames

    a, b = to_eq42(c.alpha, c.beta)

    def misfit(x) -> float:
        return float(_z6_gap(a, b, chain_frames(c.q, d6=x["d6"])[:, 5, :3, 2], x["elevation"]).max())

    readings = [
        Reading(Kind.SIGN, "d6 = +l5 (z6 along link 5, as Eq 9 and App. B's 5_6T read it)", {"d6": L5}),
        Reading(Kind.CONVENTION, "Eq 42's beta read as an elevation from the horizontal",
                {"elevation": True}),
    ]
    return search({"d6": -L5, "elevation": False}, readings, misfit, TOL,
                  printed="Sec 3.5's (alpha, beta) of link 5 used as Eq 42's",
                  stated_text="Eq 42's matrix (r33 = cos beta: beta the polar angle of z6), Table II (d6 = "
                  "-l5)",
                  route="z6 of the Table II chain by iik.dh (not Pinocchio)",
                  measure="max angle difference [rad]")


CHECKS |= SECTION.formulas(_family("aligned"), Formula(
    "Eq 42 vs Eq 43-47", sec35_as_printed, _convention_error, TOL, "rad", (
        Slip(SlipKind.SIGN, "alpha, 90 deg - beta (z6 taken along link 5, d6 = +l5)",
             lambda a, b: (a, np.pi / 2 - b)),
        Slip(SlipKind.BRANCH, "alpha + 180 deg, 90 deg - beta (the other side of the pole)",
             lambda a, b: (wrap(a + np.pi), np.pi / 2 - b)),
        Slip(SlipKind.UNIT, "alpha + 180 deg, beta + 45 deg (a quarter turn taken as an eighth)",
             lambda a, b: (wrap(a + np.pi), b + np.pi / 4)),
    ), good=sec35_to_eq42, good_is="alpha + 180 deg, beta + 90 deg (z6 = -a)", eps=None, id="beta_convention",
    claim="The beta of Sec 3.5 (Eq 43-51) is the beta of the Euler matrix of Eq 42 (r13 = c_a s_b, r23 = s_a "
    "s_b, r33 = c_b), and alpha likewise.",
    text="beta = atan(rise/run) of link 5 (inclination from the horizontal, Eq 43, 47) and alpha' = "
    "atan2(py, px) (Eq 46), used as the Eq 42 Euler angles",
    corrected="beta_42 = beta_35 + 90 deg and alpha_42 = alpha_35 + 180 deg (z6 = -a); iik.dexterity returns "
    "Eq 42 angles",
    method="{n} configurations (Pinocchio): the Sec 3.5 angles of link 5 (a = (p - SLJ)/l5: azimuth, "
    "inclination) through the form vs the Eq 42 angles of z6 (azimuth, polar angle)",
    measure="max angle difference", note=lambda c, err: "z6 = -a in every configuration (d6 = -l5)",
    reread=convention_reading))


@dataclass(frozen=True)
class Sweep:
    """The exact admissible set on an orientation grid at reachable points (:func:`sweep`).

    Attributes:
        p: The points [m], base frame, shape (n, 3): fk of q uniform in Table I.
        alpha, beta: Eq 42's angles of the grid [rad], shape (nb * na,), alpha varying fastest: alpha at
            the ``na`` cell centres of [-pi, pi], beta at the ``nb`` of [0, pi].
        truth: Shape (n, nb * na): an IK solution within Table I for pose_from_euler(p, alpha, beta, 0).
        na, nb: The grid's numbers of alphas and betas.
    """

    p: np.ndarray
    alpha: np.ndarray
    beta: np.ndarray
    truth: np.ndarray
    na: int
    nb: int


@per_run
def sweep(ctx) -> Sweep:
    """The exact admissible set on a grid: :func:`iik.dexterity.admissible` (IK feasibility) at
    ``na x nb`` orientations of each of ``npts`` reachable points (300 in the full report)."""
    q = ctx.rng("dexterity-points").uniform(ARM.q_min, ARM.q_max, size=(ctx.n(300, 8), 6))
    P = iik.fk(q, ARM)[:, :3, 3]
    na, nb = ctx.n(36, 24), ctx.n(18, 12)
    A, B = np.meshgrid((np.arange(na) + 0.5) / na * 2 * np.pi - np.pi, (np.arange(nb) + 0.5) / nb * np.pi)
    A, B = A.ravel(), B.ravel()
    return Sweep(P, A, B, np.array([admissible(p, A, B, ARM) for p in P]), na, nb)


@dataclass(frozen=True)
class Rates:
    """How an admitted set compares with the exact one on the sweep (counts of grid orientations)."""

    admitted: int
    rejected: int
    false_admits: int  # admitted, but no IK solution within the limits
    false_rejects: int  # rejected, but an IK solution within the limits exists

    false_admit_rate = property(lambda self: self.false_admits / max(1, self.admitted))  # of the admitted
    false_reject_rate = property(lambda self: self.false_rejects / max(1, self.rejected))  # of the rejected

    def text(self) -> str:
        return (f"admitted {self.admitted}, rejected {self.rejected}; false admits {self.false_admits} "
                f"({self.false_admit_rate:.1%} of the admitted have no IK solution within Table I), false "
                f"rejects {self.false_rejects} ({self.false_reject_rate:.1%} of the rejected have one)")


def rates(adm: np.ndarray, truth: np.ndarray) -> Rates:
    """False-admit and false-reject counts of the admitted set ``adm`` against ``truth`` (same shape)."""
    adm, truth = np.asarray(adm, bool), np.asarray(truth, bool)
    return Rates(int(adm.sum()), int((~adm).sum()), int((adm & ~truth).sum()), int((~adm & truth).sum()))


def admitted_printed(p, A, B):
    """Eq 43-51 as printed, the angles converted to Eq 42's (the reading of dexterity.beta_convention)."""
    return printed_admits(p, A - np.pi, B - np.pi / 2)


def shell_admits(p, A, B, arm) -> np.ndarray:
    """Sec 3.5's model read exactly (the project's dexterity before issue 20): the second-last joint
    ``p - l5 a`` (``a = -z6``, the direction of link 5) lies in the shell around joint 2 between
    ``d`` (Eq 45, joint 4 at its limit) and ``l3 + l4`` (Eq 44), joint 2 placed by Eq 36-37 with
    joint 1 clipped to its limits. The angle of ``a`` from the joint-2 direction must lie between the
    cone half-angles of Eq 44 and Eq 45; no other joint limit enters. ``A``, ``B``: Eq 42 [rad]."""
    l1, l2, l3, l4, l5 = arm.lengths
    th1 = float(np.clip(np.arctan2(p[1], p[0]), arm.lower[0], arm.upper[0]))
    v = np.array([p[0] - l2 * np.cos(th1), p[1] - l2 * np.sin(th1), p[2] - l1])  # Eq 37
    rho = float(np.linalg.norm(v))
    r_out = l3 + l4
    r_in = np.sqrt(l3**2 + l4**2 - 2 * l3 * l4 * np.cos(np.pi - arm.upper[3]))  # Eq 45 d
    A, B = np.broadcast_arrays(np.asarray(A, float), np.asarray(B, float))
    if rho < 1e-12 or rho > r_out + l5 or rho + l5 < r_in:
        return np.zeros(A.shape, bool)
    c_out = (l5**2 + rho**2 - r_out**2) / (2 * l5 * rho)  # Eq 44: cos of the cone half-angle
    c_in = (l5**2 + rho**2 - r_in**2) / (2 * l5 * rho)  # Eq 45
    z6 = np.stack([np.sin(B) * np.cos(A), np.sin(B) * np.sin(A), np.cos(B)], axis=-1)
    cos_ae = -(z6 @ (v / rho))
    return (cos_ae <= min(c_in, 1.0) + 1e-12) & (cos_ae >= max(c_out, -1.0) - 1e-12)


_shell = partial(shell_admits, arm=ARM)


#: The known-good admission: exactly the orientations the sweep found solvable (sound by construction).
SOLVABLE_ONLY = object()
_SOUND = 0.999  # share of admitted orientations that must be solvable ("guarantees convergence")


def _sweep_forms(printed) -> Forms:
    """Forms of an admitted set graded on the sweep: good admits exactly the solved orientations, bad all."""
    return Forms(
        printed=printed,
        good=SOLVABLE_ONLY,
        good_is="exactly the orientations the sweep solves",
        slips=(
            Slip(SlipKind.CLAIM, "every orientation", lambda p, A, B: np.ones(A.shape, bool)),
            Slip(SlipKind.MODEL, "the angles used without the Eq 42 conversion (Sec 3.5's read as Eq 42's)",
                 printed_admits),
        ),
    )


def _sweep_row(ctx, admit, claim: str, reference: str, versus: str, reason: str, **fields) -> Row:
    """The row of the set ``admit`` admits (``versus`` in words), graded on the sweep: sound if at least
    ``_SOUND`` of what it admits is solvable; the row of Eq 43-51 as printed shows the sets at the first
    points (:func:`_figure`)."""
    sw = sweep(ctx)
    adm = sw.truth if admit is SOLVABLE_ONLY else np.array([admit(p, sw.alpha, sw.beta) for p in sw.p])
    r = rates(adm, sw.truth)
    return Row.graded(
        claim,
        reference,
        "the exact admissible set on a grid: iik.dexterity.admissible (the complete IK, a solution within "
        f"Table I for pose_from_euler(p, alpha, beta, 0); gamma turns joint 6 alone) vs {versus}",
        f"{r.text()}; of {sw.truth.size} orientations {int(sw.truth.sum())} are solvable",
        (Measure("share of admitted orientations that are solvable", 1.0 - r.false_admit_rate, _SOUND,
                 bound=">="),),
        fail=Verdict.DOES_NOT_HOLD,
        domain=f"{len(sw.p)} reachable points (fk of q uniform in Table I), a {sw.na} x {sw.nb} "
        "(alpha, beta) grid over every orientation of z6 at each",
        reason=reason,
        figures=(_figure(ctx, sw, adm),) if admit is admitted_printed else (),
        **fields,
    )


def _sweep_check(order: float, name: str, printed, claim: str, reference: str, versus: str, reason: str,
                 depends_on: tuple[str, ...] = ("l1", "lengths", "ik-sweep")) -> Callable:
    """Register the check ``name`` of the set ``printed`` admits (:func:`_sweep_row`; its row id: ``name``
    without "printed_")."""

    def check(ctx, admit):
        return _sweep_row(ctx, admit, claim, reference, versus, reason, id=name.removeprefix("printed_"))

    check.__name__ = check.__qualname__ = name
    check.__doc__ = f"{reference}: {claim}"
    return SECTION.check(order, depends_on=depends_on, forms=_sweep_forms(printed))(check)


printed_admitted_set = _sweep_check(
    51.0, "printed_admitted_set", admitted_printed,
    "The orientations Eq 43-51 admit at a point inside the workspace are reachable (at least one IK "
    "solution), so choosing them guarantees convergence.",
    "Sec 3.5.2-3.5.3, Eq 43-51, Sec 5.2",
    "the set Eq 43-51 admit (angles converted to Eq 42's)",
    "the SLJ-shell model ignores the joint-1, joint-2 and joint-5 limits and the roll geometry, and Eq "
    "48/50/51 are wrong (rows above): admitted orientations without an IK solution",
    ("l1", "lengths", "ik-sweep", "sec35-angles"),
)
shell_model = _sweep_check(
    51.2, "shell_model", _shell,
    "Sec 3.5's model read exactly (the second-last joint inside the shell of Eq 44-45, the angles converted "
    "to Eq 42's) admits only reachable orientations.",
    "Sec 3.5.2-3.5.3 (Figs 18-21), Eq 44-45",
    "the orientations whose link-5 direction lies in the cone between the Eq 44 and Eq 45 half-angles (the "
    "former iik.dexterity)",
    "the model ignores the joint-1, joint-2, joint-3 and joint-5 limits and where the wrist really is: it is "
    "neither a necessary nor a sufficient condition (false admits and false rejects above)",
)


# ----------------------------------------------------------------------------- the exact sets
_EDGE = 1e-7  # [rad]: a step across an interval end, 100 x the bisection tolerance
_GRID = 2 * _D  # [rad]: the grid of the slip that leaves the ends unrefined


def _moved(ends):
    """A slip: iik.dexterity's alpha intervals [rad] with each (lo, hi) replaced by ``ends(lo, hi)``."""
    return lambda p, beta, arm: tuple(ends(lo, hi) for lo, hi in alpha_intervals(p, beta, arm))


def _member(intervals, a, eps: float) -> tuple[np.ndarray, np.ndarray]:
    """Which alphas ``a`` [rad] lie in one of the ``intervals``, and which lie within ``eps`` of an end."""
    inside, near = np.zeros(np.shape(a), bool), np.zeros(np.shape(a), bool)
    for lo, hi in intervals:
        inside |= (a - lo) % (2 * np.pi) <= hi - lo + 1e-12
        near |= (np.abs(wrap(a - lo)) <= eps) | (np.abs(wrap(a - hi)) <= eps)
    return inside, near


@per_run
def _exact_sample(ctx):
    """Random reachable points fk(q), q uniform in Table I, with their exact dexterity."""
    q = ctx.rng("dexterity-exact").uniform(ARM.q_min, ARM.q_max, size=(ctx.n(5, 2), 6))
    return [(p, dexterity(p, ARM)) for p in iik.fk(q, ARM)[:, :3, 3]]


def _beta_end_errors(p, d) -> int:
    """Beta ends that are not a change of feasibility: the alpha iik.dexterity gives is admissible at the
    end, and 1e-7 rad outside no alpha is (7200 over the turn and 200 within 1e-3 rad of that alpha)."""
    bad, dense = 0, np.linspace(-np.pi, np.pi, 7200, endpoint=False)
    for (lo, hi), (a_lo, a_hi) in zip(d.beta_intervals, d.beta_end_alphas, strict=True):
        for end, a, inward in ((lo, a_lo, 1.0), (hi, a_hi, -1.0)):
            if end <= 0.0 or end >= np.pi:
                continue
            near = np.concatenate([dense, a + np.linspace(-1e-3, 1e-3, 200)])
            witness = bool(admissible(p, a, end, ARM))
            outside = bool(admissible(p, near, end - inward * _EDGE, ARM).any())
            bad += int(not witness or outside)
    return bad


@SECTION.check(
    51.5,
    depends_on=("l1", "lengths", "ik-sweep"),
    forms=Forms.right(alpha_intervals, (
        Slip(SlipKind.MODEL, "interval ends left on the 2 deg grid (no root-finding)", _moved(
            lambda lo, hi: (float(np.floor(lo / _GRID) * _GRID), float(np.ceil(hi / _GRID) * _GRID)))),
        Slip(SlipKind.CLAIM, "every interval a quarter degree wider at each end",
             _moved(lambda lo, hi: (lo - 0.25 * _D, hi + 0.25 * _D))),
    )),
)
def iik_dexterity(ctx, intervals):
    """(Project) iik.dexterity's alpha and beta intervals are the IK's feasible set, ends to 1e-7 rad."""
    sample = _exact_sample(ctx)
    dense = np.linspace(-np.pi, np.pi, 1440, endpoint=False)
    mismatch, ends_bad, checked, n_int = 0, 0, 0, 0
    beta_bad = sum(_beta_end_errors(p, d) for p, d in sample) if intervals is alpha_intervals else 0
    for p, d in sample:
        for lo, hi in d.beta_intervals:
            for beta in np.linspace(lo, hi, 5)[1:-1]:
                got = intervals(p, float(beta), ARM)
                inside, near = _member(got, dense, 1e-6)
                mismatch += int(np.sum((inside != admissible(p, dense, beta, ARM)) & ~near))
                checked += dense.size
                ends = [(a, b) for a, b in got if b - a < 2 * np.pi - 1e-12]  # a full turn has no ends
                n_int += len(ends)
                for a_lo, a_hi in ends:
                    probe = np.array([a_lo - _EDGE, a_lo + _EDGE, a_hi - _EDGE, a_hi + _EDGE])
                    ends_bad += int(np.any(admissible(p, probe, beta, ARM) != [False, True, True, False]))
    m = (
        Measure(f"grid orientations (of {checked}) whose membership is not IK feasibility", mismatch, 0),
        Measure(f"alpha interval ends (of {n_int}) that are not a change of feasibility within 1e-7 rad",
                ends_bad, 0),
        Measure("beta interval ends that are not a change of feasibility within 1e-7 rad", beta_bad, 0),
    )
    return Row.graded(
        "(Project) iik.dexterity is exact: its alpha and beta intervals are the orientations with an IK "
        "solution within Table I, each end a change of feasibility (root-found).",
        "iik.dexterity (exact, on the complete IK)",
        "at random reachable points: iik.dexterity's beta intervals; at 3 betas inside each, its alpha "
        "intervals vs iik.dexterity.admissible on 1440 alphas; each alpha end probed 1e-7 rad on either "
        "side; each beta end: a witness alpha 1e-7 rad inside, none of 7200 alphas 1e-7 rad outside",
        None,
        m,
        fail=Verdict.DOES_NOT_HOLD,
        domain=f"{len(sample)} points fk(q), q uniform in Table I; 3 betas per beta interval",
        scope=Scope.PROJECT,
        reason="an interval end is not where the IK's feasibility changes",
    )


def _figure(ctx, sw: Sweep, adm_pr) -> str:
    na, nb = sw.na, sw.nb
    n = min(3, len(sw.p))
    fig = new_figure(figsize=(4 * n, 3.4))
    ext = (-180, 180, 0, 180)
    for i in range(n):
        ax = fig.add_subplot(1, n, i + 1)
        ax.imshow(sw.truth[i].reshape(nb, na), origin="lower", extent=ext, aspect="auto", cmap="Greys",
                  vmin=0, vmax=1.5)
        p = sw.p[i]
        for adm, col in ((_shell(p, sw.alpha, sw.beta), "blue"), (adm_pr[i], "red")):
            if adm.any() and not adm.all():
                ax.contour(adm.reshape(nb, na).astype(float), levels=[0.5], colors=col, extent=ext)
        ax.set_title(f"p = [{p[0]:.2f}, {p[1]:.2f}, {p[2]:.2f}] m", fontsize=8)
        ax.set(xlabel="alpha [deg] (Eq 42)", ylabel="beta [deg] (Eq 42)")
    fig.suptitle("grey: exact (iik.dexterity: an IK solution within Table I); blue: Sec 3.5's model read "
                 "exactly; red: Eq 43-51 printed (converted)", fontsize=8)
    return ctx.save_figure(fig, "dexterity_alpha_beta.png", dpi=80)


@SECTION.check(
    52.0,
    depends_on=("l1", "lengths", "complete-solver"),
    forms=Forms.right((1, 2, 3, 4, 5), (
        Slip(SlipKind.CLAIM, "joints 1-6 unaffected", (1, 2, 3, 4, 5, 6)),
        Slip(SlipKind.OFF_BY_ONE, "joints 2-6 unaffected (the joint numbers one off)", (2, 3, 4, 5, 6)),
    ), good_is="the printed claim (joints 1-5 unaffected)"),
)
def gamma_free(ctx, unaffected):
    """Sec 3.5.1: gamma only changes joint 6 (a full turn), so any gamma works; ``unaffected`` joints stay."""
    T = iik.fk(ctx.rng("gamma").uniform(ARM.q_min, ARM.q_max, size=(ctx.n(40, 6), 6)), ARM)
    gam = np.linspace(-np.pi, np.pi, 13)[:-1]
    k, ok, moved, cols = len(gam), 0, 0.0, [j - 1 for j in unaffected]
    for t in T:
        a, b, _ = iik.euler_from_matrix(t[:3, :3])
        poses = iik.pose_from_euler(np.tile(t[:3, 3], (k, 1)), np.full(k, a), np.full(k, b), gam)
        res = iik.solve_many(poses, ARM)
        ok += sum(len(r.q) > 0 for r in res)
        base = np.sort(res[0].q[:, cols], axis=0)
        for r in res[1:]:
            if len(base) and len(r.q) == len(base):
                moved = max(moved, float(np.abs(wrap(np.sort(r.q[:, cols], axis=0) - base)).max()))
    m = (
        Measure(f"poses of {len(T) * k} without a solution when gamma changes", len(T) * k - ok, 0),
        Measure(f"max change of joints {list(unaffected)} across gamma", moved, 1e-6, "rad"),
    )
    return Row.graded(
        f"{title_of('Claim 3.9')}, which spans +-180 deg.",
        "Sec 3.5.1, Eq 42",
        "for poses fk(q) of random q, gamma replaced by 12 values over a full turn, solved with iik.solve "
        "(within Table I); solutions compared joint by joint (same solution count)",
        None,
        m,
        fail=Verdict.DOES_NOT_HOLD,
        domain=f"{len(T)} poses fk(q), q uniform in Table I, gamma at 12 values over a full turn each",
    )
