"""Appendix E: the normal-acceleration boundary test (Eq 57-69) at points A1, A2 and A6.

Every number App. E prints is compared with the same quantity recomputed by
:mod:`verification.oracles.abdel_malek` (Pinocchio on the shipped URDF), within the
printed rounding; each conclusion ("motion only along +N0", "both ways") is compared
with ground truth: reachability of ``p +- 2 mm N0`` by the oracle. The printed numbers
(mm, as printed) are the form under test; the self-test substitutes our recomputed
numbers (must hold) and the same numbers 5 % off with flipped conclusions (must not).

Circularity: the link lengths l2..l5 were recovered from the diagonal of A1's H*
(``docs/ARM.md``), so H*(1,1), (2,2), (4,4), (5,5) at A1 agree by construction; that
entry is marked ``lengths-circular``. The off-diagonal terms, B, Q*, eig(Q*) and A2's
sigma are independent confirmations.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import partial

import numpy as np

import iik
from iik import THESIS_ARM

from ..assumptions import EXACT_GEOMETRY
from ..formula import Formula, Points, Printed, per_run
from ..numbers import fmt_matrix, fmt_vec
from ..oracles.abdel_malek import NormalAcceleration, eq67_dq, normal_acceleration
from ..oracles.normal_distance import parameters, surface_point, tool_point
from ..oracles.reachability import oracle_for
from ..plotting import new_figure
from ..registry import Erratum, Forms, Measure, Row, Section, Slip, SlipKind, Verdict
from ..second_reading import Kind, Reading, choices, digit_slips, moved_entries, search, sign_typos
from ..shorthand import cos_sin

_D = np.pi / 180
EPS = 2e-3  # [m] probe distance along N0
SECTION = Section("Normal-acceleration boundary test (App. E, Eq 57-69)",
                  depends_on=("lengths", "pinocchio", "reachability"))


@dataclass(frozen=True)
class Point:
    """What App. E prints at a point (or the same quantities recomputed), in its units (mm, rad).

    Attributes:
        q0: Joints 1-5 [rad]. free: The free joints (1-based). surface: Its singular set, as printed.
        N0: The surface normal. eig: eig(Q*) [mm]. conclusion: The side motion is admissible to (``"+N0"``,
            ``"-N0"``, ``"both"`` or ``"none"``). claim, ref: The claim and reference of the point's row.
        u0, H, B, Q: Printed at A1 only: Eq 58's lambda at q0, H* [mm], B [1/mm], Q* [mm].
        dq, sigma: Printed at A2 only: ``{joint: delta q}`` (Eq 67), ``{joint: sigma [mm]}`` (Eq 66).
    """

    q0: np.ndarray
    free: tuple[int, int]
    surface: str
    N0: np.ndarray
    eig: np.ndarray
    conclusion: str
    claim: str
    ref: str
    u0: np.ndarray | None = None
    H: np.ndarray | None = None
    B: np.ndarray | None = None
    Q: np.ndarray | None = None
    dq: dict[int, float] | None = None
    sigma: dict[int, float] | None = None


#: App. E as printed (mm, rad; conclusions as printed; each point's claim and reference for its row).
PRINTED = {
    "A1": Point(
        q0=np.array([-7 * np.pi / 9, 0, 0, 0, 0]),
        free=(1, 2),
        surface="f(1), s(1) = [th4 = 0, th5 = 0]",
        u0=np.array([1.0654, 0.1165, 0, 0, 0]),
        N0=np.array([0.7660, 0.6428, 0.0]),
        H=np.array(
            [
                [1646.8, 0, 0, 0, 0],
                [0, 2705.2, 0, -1703, -1025.7],
                [0, 0, 0, 0, 0],
                [0, 1703, 0, 1898, 1143.1],
                [0, -1025.7, 0, 1143.1, 1143.1],
            ]
        ),
        B=np.array([[0, -0.0014, 0], [0, 0, -0.0013]]),
        Q=np.array([[0, 0, 0, 0, 0]] * 3 + [[0, 0, 0, 825.96, 497.45], [0, 0, 0, 497.45, 754.25]], float),
        eig=np.array([0, 0, 0, 291.4, 1288.9]),
        conclusion="+N0",
        claim="A1 on f(1) (s(1)): u0, N0, H*, B, Q*, eig(Q*) as printed; Q* semi-positive definite, so the "
        "normal acceleration is admissible only along +N0 (f(1) is a boundary there).",
        ref="App. E, point A1 (Eq 58-65)",
    ),
    "A2": Point(
        q0=np.array([-160 * _D, np.pi / 12, 90 * _D, -np.pi / 3, 0]),
        free=(2, 4),
        surface="f(2), s(2) = [th1 = -160, th3 = 90, th5 = 0]",
        N0=np.array([0.750, 0.6486, 0.1294]),
        eig=np.array([983.4, 238.7, 2240.9, 437.7, 1086.9]),
        dq={1: -1.0},
        sigma={1: 389.2341},
        conclusion="+N0",
        claim="A2 on f(2) (s(2)): joint 1 at its limit, Q* positive definite, sigma = 389.2341 has the sign "
        "of the eigenvalues, so motion only along +N0 (f(2) is a boundary there).",
        ref="App. E, point A2 (Eq 59-67)",
    ),
    "A6": Point(
        q0=np.array([0, 95 * _D, 0, -119 * _D, np.pi / 3]),
        free=(1, 5),
        surface="f(26), s(26) = [th2 = 95, th3 = 0, th4 = -119]",
        N0=np.array([-0.698, 0, -0.9976]),
        eig=np.array([-83.2630, 91.8674, 295.45, 314.77, 852.52]),
        conclusion="both",
        claim="A6 on f(26): Q* indefinite, so the surface admits motion both ways (not a boundary).",
        ref="App. E, point A6 (Eq 59-68)",
    ),
}
#: A2 read with theta1 at its upper limit (+160 deg): the reading that reproduces its N0, delta q1 and sigma.
A2_READ = "A2 (theta1 = +160 deg)"
_TOL_UNIT = 1e-3  # N0, u0: printed to 3-4 decimals
_TOL_B = 1e-4  # [1/mm]: B printed to 4 decimals
_REL, _ABS = 2e-3, 0.1  # H*, Q*, eig, sigma [mm]: 0.2 % (the lengths are known to 1 mm) + 0.1 mm


@per_run
def _results(ctx) -> dict[str, NormalAcceleration]:
    """Our numbers at each point, and at A2 read with theta1 = +160 deg (:data:`A2_READ`)."""
    res = {
        name: normal_acceleration(
            d.q0, d.free, normal_hint=d.N0, prefer_rows=(1, 2) if name == "A1" else None
        )
        for name, d in PRINTED.items()
    }
    a2 = PRINTED["A2"]
    res[A2_READ] = normal_acceleration(np.r_[-a2.q0[0], a2.q0[1:]], a2.free, normal_hint=a2.N0)
    return res


@per_run
def _sides(ctx) -> dict[str, str]:
    """The side each of :func:`_results`' points can move to (ground truth): reachability of p +- EPS N0,
    ``"+N0"``, ``"-N0"``, ``"both"`` or ``"none"``."""
    sides = {}
    for name, r in _results(ctx).items():
        cls = oracle_for(ctx).classify(np.array([r.point + EPS * r.N0, r.point - EPS * r.N0]))
        plus, minus = bool(cls.reachable[0]), bool(cls.reachable[1])
        sides[name] = "both" if (plus and minus) else ("+N0" if plus else ("-N0" if minus else "none"))
    return sides


def printed_values(ctx) -> dict[str, Point]:
    """The form as printed."""
    return PRINTED


def recomputed_values(ctx, slip: str = "") -> dict[str, Point]:
    """Known-good form: our numbers, with each conclusion the ground-truth side. With ``slip`` a realistic
    slip in them: ``"eig_h"`` the eigenvalues of H* for those of Q* (Eq 65's curvature term left out),
    ``"dq"`` Eq 67 read the other way (-1 at a lower limit, sigma computed with it), ``"limits"`` Eq 58
    inverted with q^U and q^L exchanged (u0 of A1 with both signs flipped)."""
    res, sides, out = _results(ctx), _sides(ctx), {}
    for name, d in PRINTED.items():
        r, mm = res[name], res[name].in_mm()
        eig = _eig_h(mm) if slip == "eig_h" else np.sort(mm["eig"])
        v = replace(d, N0=r.N0, eig=eig, conclusion=sides[name])
        if name == "A1":
            v = replace(v, u0=-r.lam0 if slip == "limits" else r.lam0, H=mm["H"], B=mm["B"], Q=mm["Q"])
        if name == "A2":
            sign = -1.0 if slip == "dq" else 1.0
            v = replace(v, dq={j: sign * x for j, x in eq67_dq(r.q0).items()},
                        sigma={j: sign * x for j, x in mm["sigma"].items()})
        out[name] = v
    return out


def _eig_h(mm: dict) -> np.ndarray:
    """The sorted eigenvalues of (the symmetric part of) H* [mm]."""
    return np.sort(np.linalg.eigvalsh(0.5 * (mm["H"] + mm["H"].T)))


def perturbed_values(ctx) -> dict[str, Point]:
    """Deliberately wrong: the recomputed numbers 5 % off, the conclusions flipped, the step signs flipped."""
    flip = {"+N0": "-N0", "-N0": "+N0", "both": "+N0", "none": "both"}
    out = {}
    for name, v in recomputed_values(ctx).items():
        off = {k: np.asarray(x) * 1.05 + (0.05 if k in ("u0", "N0") else 0.0)
               for k in ("u0", "N0", "H", "B", "Q", "eig") if (x := getattr(v, k)) is not None}
        if v.sigma is not None:
            off.update(sigma={j: s * 1.05 for j, s in v.sigma.items()}, dq={j: -s for j, s in v.dq.items()})
        out[name] = replace(v, conclusion=flip[v.conclusion], **off)
    return out


# ----------------------------------------------------------------------------- second readings
_MEANING = "what the quantity means (verification.oracles.normal_distance: the Table II chain by iik.dh, " \
    "not Pinocchio, not the printed formulas)"
_CACHE: dict = {}


def _by_meaning(x: dict, hint, misfit) -> float:
    """``misfit(N0, eig(Q*) [mm], H* [mm])`` by their meaning at the reading ``x`` (its q0 and free joints),
    N0's sign chosen along ``hint``; inf where the surface has no normal (the surface's quantities are cached
    per process: a pure function of q0 and the free joints)."""
    key = (np.asarray(x["q0"], float).round(12).tobytes(), tuple(x["free"]))
    if key not in _CACHE:
        try:
            sp = surface_point(x["q0"], x["free"])
            _CACHE[key] = (sp.N0, np.linalg.eigvalsh(sp.q_star()) * 1e3, sp.h_star() * 1e3)
        except (iik.InvalidInputError, np.linalg.LinAlgError):
            _CACHE[key] = None
    if _CACHE[key] is None:
        return float("inf")
    n, eig, H = _CACHE[key]
    sgn = -1.0 if np.dot(n, hint) < 0 else 1.0
    return float(misfit(sgn * n, np.sort(sgn * eig), sgn * H))


def _scaled(printed, ours):
    """|printed - ours| in units of the printed rounding (_ABS + _REL |ours|)."""
    return np.abs(printed - ours) / (_ABS + _REL * np.abs(ours))


def _q0_readings(name: str) -> list[Reading]:
    """Nearby readings of point ``name``'s stated joints: each non-zero angle's sign, a joint at a limit at
    its other limit, and (A2) Sec 3.4.3's s(2) with theta1 = +160 deg."""
    q0 = PRINTED[name].q0
    lo, hi = THESIS_ARM.q_min[:5], THESIS_ARM.q_max[:5]
    out = []
    for j in range(5):
        v = q0[j]
        other = hi[j] if abs(v - lo[j]) < 1e-9 else (lo[j] if abs(v - hi[j]) < 1e-9 else None)
        if other is not None:
            out.append(Reading(Kind.LIMIT, f"theta{j + 1} at its other limit ({np.degrees(other):+.0f} deg)",
                               {"q0": np.r_[q0[:j], other, q0[j + 1 :]]}))
        if v != 0 and (other is None or abs(-v - other) > 1e-9):
            out.append(Reading(Kind.SIGN, f"theta{j + 1} = {np.degrees(-v):+.1f} deg",
                               {"q0": np.r_[q0[:j], -v, q0[j + 1 :]]}))
    return out


def _search(pv: Point, readings, misfit, tol: float, printed: str, measure: str, route: str = _MEANING,
            **stated):
    """:func:`~verification.second_reading.search` of a value printed at the point ``pv``: stated are its q0,
    its free joints, the quantities printed there and ``stated``."""
    given = {k: getattr(pv, k) for k in ("u0", "N0", "eig", "H", "dq") if getattr(pv, k) is not None}
    return search({"q0": pv.q0, "free": pv.free, **given, **stated}, readings, misfit, tol,
                  printed=printed, route=route, measure=measure,
                  stated_text=f"q0 = {fmt_vec(np.degrees(pv.q0), 1)} deg on {pv.surface}, free joints "
                  f"{pv.free}")


def _n0_misfit(x) -> float:
    """max |printed N0 - surface normal| at the reading ``x`` (the normal's sign along the printed one)."""
    return _by_meaning(x, x["N0"], lambda n, eig, H: np.abs(np.asarray(x["N0"], float) - n).max())


def reading_n0(name: str, pv: Point):
    """Second reading of a printed N0: the surface normal at each nearby reading of the point, vs the printed
    vector read as typed or one digit slip away (sign of N0 free)."""
    return _search(pv, _q0_readings(name) + digit_slips("N0", pv.N0), _n0_misfit, _TOL_UNIT,
                   f"N0 = {fmt_vec(pv.N0)}", "max |printed - surface normal| (up to sign)")


def reading_eig(name: str, pv: Point):
    """Second reading of printed eigenvalues of Q*: Q* as the Hessian of the normal distance at each nearby
    reading of the point and of its free joints (the other pairs), vs the printed values (sorted)."""
    pr = np.sort(np.asarray(pv.eig, float))
    pairs = [(a, b) for a in range(1, 6) for b in range(a + 1, 6) if (a, b) != pv.free]
    readings = choices(Kind.WHICH, "free", {f"free joints {a}, {b}": (a, b) for a, b in pairs})

    def misfit(x) -> float:
        return _by_meaning(x, PRINTED[name].N0, lambda n, eig, H: _scaled(pr, eig).max())

    return _search(pv, _q0_readings(name) + readings, misfit, 1.0, f"eig(Q*) = {fmt_vec(pr, 2)} mm",
                   f"max |printed - ours| / ({_ABS} mm + {_REL:.1%}) over the sorted eigenvalues")


def reading_u0(pv: Point):
    """Second reading of A1's u0: Eq 58 inverted at each nearby reading of q0 (and with the limits exchanged),
    vs the printed u0 read as typed, one digit slip away or with an entry's sign flipped. A reading of q0 must
    also keep the N0 printed beside u0 from the same q0 (it holds as stated): a q0 that reproduces u0 but not
    N0 does not explain the slip."""

    def misfit(x) -> float:
        lam = parameters(x["q0"])
        u0 = float(np.abs(np.asarray(x["u0"], float) - (-lam if x["swap"] else lam)).max())
        return max(u0, _n0_misfit(x))

    readings = _q0_readings("A1") + [Reading(Kind.LIMIT, "Eq 58 with q^U and q^L exchanged", {"swap": True})]
    readings += digit_slips("u0", pv.u0) + sign_typos("u0", pv.u0)
    return _search(pv, readings, misfit, _TOL_UNIT, f"u0 = {fmt_vec(pv.u0)}",
                   "max(|printed u0 - lambda(q0)|, |printed N0 - surface normal|)",
                   "Eq 58 inverted (arcsin) at the reading's joints; the N0 printed beside it by its meaning "
                   "(verification.oracles.normal_distance) at the same joints", swap=False)


def reading_h(pv: Point, mask: np.ndarray, what: str):
    """Second reading of A1's printed H* entries ``mask``: the Hessian of N0.G(q(s)) at each nearby reading,
    vs the printed matrix as typed, transposed or with an entry moved."""
    def misfit(x) -> float:
        pr = np.asarray(x["H"], float)
        return _by_meaning(x, PRINTED["A1"].N0, lambda n, eig, H: _scaled(pr, H)[mask].max())

    readings = _q0_readings("A1") + [Reading(Kind.SWAP, "H* transposed", {"H": np.asarray(pv.H, float).T})]
    readings += moved_entries("H", pv.H) + moved_entries("H", pv.H, within="row") + sign_typos("H", pv.H)
    return _search(pv, readings, misfit, 1.0, what, f"max |printed - ours| / ({_ABS} mm + {_REL:.1%})")


def reading_dq(pv: Point):
    """Second reading of A2's delta q1: Eq 67 at each nearby reading of q0, vs the printed step."""
    def misfit(x) -> float:
        ours = eq67_dq(x["q0"])
        return float(max(abs(x["dq"].get(j, 0.0) - ours.get(j, 0.0)) for j in set(ours) | set(x["dq"])))

    return _search(pv, _q0_readings("A2"), misfit, 0.0,
                   f"delta q = {pv.dq} 'because joint 1 is at its lower limit'",
                   "largest difference of the printed step from Eq 67's",
                   "Eq 67 at the reading's joints (+1 at a lower limit, -1 at an upper one)")


# ----------------------------------------------------------------------------- rows
#: The quantities App. E prints at a point, graded within their printed rounding.
_MM = (_ABS, "mm", _REL)  # tolerance, unit, relative tolerance of the values in mm
_U0 = Printed("u0", "u0", _TOL_UNIT)
_N0 = Printed("n0", "N0", _TOL_UNIT, measure="max |printed - ours| (up to sign)")
_H_OFF = Printed("h_offdiag", "H* off the diagonal", *_MM, 1, "max |printed - ours| off the diagonal")
_H_DIAG = Printed("h_diag", "the diagonal of H*", *_MM, 1, "max |printed - ours| on the diagonal")
_B = Printed("b", "B (rows (2,3) as the thesis chose)", _TOL_B, "1/mm")
_Q = Printed("q", "Q*", *_MM, 2)
_EIG = Printed("eig", "sorted eig(Q*)", *_MM, 2, "max |printed - ours| (sorted)")
_SIGMA = Printed("sigma", "|sigma|", 1e-3, "mm", 1e-3, 4, "|printed - ours|")


def _n0(name, pv, r) -> Row:
    norm = float(np.linalg.norm(pv.N0))
    # N0's sign is a convention: ours along the printed one
    n0 = r.N0 if np.abs(pv.N0 - r.N0).max() <= np.abs(pv.N0 + r.N0).max() else -r.N0
    return _N0.row(
        f"App. E, {name}, Eq 59",
        pv.N0,
        n0,
        note=f" (left null vector of G_q q_s); printed norm {norm:.4f}",
        why=f"at q0 = {fmt_vec(r.q0)} rad the normal of the surface is {fmt_vec(r.N0)}; the printed "
        f"vector has norm {norm:.3f}" + ("" if abs(norm - 1) < 1e-3 else " (not a unit vector)"),
        reread=lambda: reading_n0(name, pv),
    )


def _a1(pv, r) -> list[Row]:
    """A1's u0, N0, H* (off the diagonal; on it, circular), B and Q*."""
    mm, off = r.in_mm(), ~np.eye(5, dtype=bool)
    return [
        _U0.row(
            "App. E, A1, Eq 58",
            pv.u0,
            r.lam0,
            note=" (Eq 58 inverted at q0)",
            why=f"q1(lambda = +1.0654) = {np.degrees(2.7925 * np.sin(1.0654)):.1f} deg, not -140 deg (Eq 58 "
            "inverted at theta1 = -7 pi/9: sin(lambda1) = -140/160)",
            reread=lambda: reading_u0(pv),
        ),
        _n0("A1", pv, r),
        _H_OFF.row(
            "App. E, A1, Eq 61",
            np.where(off, pv.H, 0.0),
            np.where(off, mm["H"], 0.0),
            why=f"H*(4,2) = +1703 is printed with H*(2,4) = -1703; Eq 61 at q0 = {fmt_vec(r.q0)} rad gives "
            f"H*(2,4) = {mm['H'][1, 3]:.2f}, H*(4,2) = {mm['H'][3, 1]:.2f} mm (a Hessian-based quadratic "
            "form: symmetric); only the symmetric value reproduces the printed Q*(2,4) = Q*(4,2) = 0",
            reread=lambda: reading_h(pv, off, "the off-diagonal entries of H* as printed (H*(4,2) = +1703)"),
        ),
        _H_DIAG.row(
            "App. E, A1, Eq 61",
            np.diagonal(pv.H),
            mm["H"].diagonal(),
            depends_on=("lengths-circular", "pinocchio"),
            basis="circular: l2..l5 were recovered from these four numbers (docs/ARM.md), so they agree by "
            "construction",
        ),
        _B.row("App. E, A1, Eq 63", pv.B, mm["B"]),
        _Q.row("App. E, A1, Eq 62-65", pv.Q, mm["Q"]),
    ]


def _eig(name, pv, mm) -> Row:
    pr, eig_h = np.sort(np.asarray(pv.eig, float)), _eig_h(mm)
    return _EIG.row(
        f"App. E, {name}, Eq 65",
        pr,
        np.sort(mm["eig"]),
        note=f"; eig(H*) = {fmt_vec(eig_h, 1)} mm",
        why=f"moving only a free joint {pv.free} moves the point along the surface, so "
        f"eta = 0 and Q* has zero eigenvalues; the printed list has {int(np.sum(np.abs(pr) < 1e-9))} "
        f"zeros (eig(H*) = {fmt_vec(eig_h, 1)} mm)",
        reread=lambda: reading_eig(name, pv),
    )


def _sigma(pv, r, side) -> list[Row]:
    """A2's sigma (Eq 66, with the printed step) and its step delta q1 (Eq 67)."""
    mm, eq67 = r.in_mm(), eq67_dq(r.q0)
    # Eq 66 with the printed step: sigma = N0 . G_q1 * (printed delta q1)
    s_ours = mm["sigma"][1] * pv.dq.get(1, 0.0) / eq67[1]
    return [
        _SIGMA.row(
            "App. E, A2, Eq 66",
            pv.sigma[1],
            s_ours,
            limit=1e-3 * abs(s_ours),
            note=f" (Eq 66 with the printed delta q1 = {pv.dq.get(1)})",
        ),
        Row.graded(
            "A2: delta q1 = -1 because joint 1 is at its lower limit (Eq 67).",
            "App. E, A2, Eq 67",
            "",
            f"printed delta q = {pv.dq} | Eq 67 gives {eq67} (+1 at a lower limit)",
            (Measure("signs differing from Eq 67", float(pv.dq != eq67), 0.0),),
            erratum=Erratum(
                "App. E, A2, delta q1",
                "delta q1 = -1 because joint 1 is at its lower limit",
                "delta q1 = +1 at a lower limit (Eq 67)",
                f"with Eq 67, sigma = N0.G_q1 dq1 = {mm['sigma'][1]:.4f} mm: the opposite sign of the "
                f"positive eigenvalues, so motion is admissible both ways; ground truth: {side}",
            ),
            id="dq",
        ).reread_if_erratum(lambda: reading_dq(pv)),
    ]


_SIDE_TEXT = {"+N0": "only along +N0 (a boundary)", "both": "both ways (not a boundary)"}


def _conclusion(name, pv, side, r, note: str = "") -> Row:
    return Row.graded(
        f"{name}: motion is admissible {_SIDE_TEXT.get(pv.conclusion, pv.conclusion)}.",
        f"App. E, {name}",
        "",
        f"printed {pv.conclusion} | ground truth {side} (reachability of p +- 2 mm "
        f"N0, p = {fmt_vec(r.point * 1e3, 1)} mm) | Abdel-Malek's test with our numbers: {r.verdict}" + note,
        (Measure("printed side differs from ground truth", float(pv.conclusion != side), 0.0),),
        fail=Verdict.DOES_NOT_HOLD,
        reason="ground truth disagrees",
        id="conclusion",
    )


#: Remarks on a point, after its numbers in the report's appendix.
_REMARKS = {
    "A1": "The text says Q* is semi-definite only when a joint is at a limit; at A1 no joint is at a limit "
    "and Q* still has three zero eigenvalues (th1, th2 move along the surface; th3 does not move the tool).",
    "A2": "A2's th4 = -60 deg is also outside the printed range of f(3) (th4 in [-41, 0]).",
}


def _appendix(name, r) -> str:
    """The point's long numbers (for the report's appendix): our Q*, sigma and K-bar (Eq 66, 68) [mm]."""
    mm = r.in_mm()
    sigma = ", ".join(f"th{j}: {v:.2f}" for j, v in mm["sigma"].items()) or "-"
    kbar = ", ".join(f"th{j}: {v:.1f}" for j, v in mm["kbar"].items()) or "-"
    return (
        f"{name}, q0 = {fmt_vec(r.q0)} rad, p = {fmt_vec(r.point * 1e3, 1)} mm\n"
        f"Q* ours: {fmt_matrix(mm['Q'], 2)}\nsigma: {sigma} mm; K-bar (Eq 68): {kbar} mm\n"
        + _REMARKS.get(name, "")
    ).rstrip()


def _point(name, pv, res, sides) -> Row:
    """Point ``name``'s row: one detail per quantity printed there (u0, N0, H*, B, Q*, eig(Q*), sigma, delta
    q, the conclusion), its verdict the worst of theirs (does not hold, erratum, input slip, holds)."""
    r, side = res[name], sides[name]
    note = ""
    if name == "A2":
        note = (
            f" | second reading with theta1 = +160 deg (the reading that reproduces the printed N0, delta q1 "
            f"and the sign of sigma): Abdel-Malek's test {res[A2_READ].verdict} as printed, ground truth "
            f"{sides[A2_READ]}: the local test is right there, the point is still reached from both sides by "
            "other configurations"
        )
    details = _a1(pv, r) if name == "A1" else [_n0(name, pv, r)]
    details += [_eig(name, pv, r.in_mm())]
    details += (_sigma(pv, r, side) if name == "A2" else []) + [_conclusion(name, pv, side, r, note)]
    refuted = any(d.verdict is Verdict.DOES_NOT_HOLD for d in details)
    return Row.grouped(
        pv.claim,
        pv.ref,
        "every printed quantity vs the same quantity recomputed with Pinocchio (Eq 58-68 by "
        "verification.oracles.abdel_malek; Hessians by central differences), within the printed "
        f"rounding (N0, u0 {_TOL_UNIT:g}; B {_TOL_B:g} 1/mm; mm values {_REL:.1%} + {_ABS} mm); the "
        "conclusion vs reachability of p +- 2 mm N0 (ground truth)",
        None,
        details,
        "printed quantities that disagree",
        fail=None,
        passing="printed quantities agree",
        failing="disagree",
        reason="the printed conclusion disagrees with ground truth" if refuted else "",
        id=name.lower(),
        domain=f"the printed point {name} (q0 as stated) and its +-{EPS * 1e3:.0f} mm probes along N0",
        appendix=_appendix(name, r),
    )


@SECTION.check(
    48.0,
    forms=Forms(
        printed=printed_values,
        good=recomputed_values,
        good_is="our recomputed numbers, conclusions from ground truth",
        slips=(
            Slip(SlipKind.TERM, "eig(H*) for eig(Q*) (Eq 65's curvature term left out)",
                 partial(recomputed_values, slip="eig_h")),
            Slip(SlipKind.SIGN, "Eq 67 read the other way (-1 at a lower limit)",
                 partial(recomputed_values, slip="dq")),
            Slip(SlipKind.LIMIT, "Eq 58 inverted with q^U and q^L exchanged",
                 partial(recomputed_values, slip="limits")),
        ),
        tolerance=Slip(SlipKind.EPSILON, "our numbers 5 % off, conclusions and step signs flipped",
                       perturbed_values),
    ),
)
def appendix_e(ctx, values):
    """A1, A2, A6: every printed number vs ours; every conclusion vs reachability (one row per point)."""
    res, sides, pv = _results(ctx), _sides(ctx), values(ctx)
    rows = [_point(name, pv[name], res, sides) for name in PRINTED]
    rows[0] = rows[0].replace(figures=(_eig_figure(ctx, res, pv),))
    return rows


def _eig_figure(ctx, results, pv) -> str:
    fig = new_figure(figsize=(10, 3))
    for k, name in enumerate(PRINTED):
        ax = fig.add_subplot(1, 3, k + 1)
        x = np.arange(5)
        ax.bar(x - 0.2, np.sort(np.asarray(pv[name].eig, float)), 0.4, label="thesis (printed)")
        ax.bar(x + 0.2, np.sort(results[name].eig * 1e3), 0.4, label="ours (Pinocchio)")
        ax.axhline(0, color="k", lw=0.5)
        ax.set_title(f"{name}: eig(Q*) [mm], sorted", fontsize=9)
        ax.set_xticks(x)
        if k == 0:
            ax.legend(fontsize=7)
    return ctx.save_figure(fig, "appendix_e_eigenvalues.png", dpi=80)


def eq69_printed(q):
    """Eq 69 as printed: f(1) at A1 -> (n, 3) [m]."""
    l1, l2, l3, l4, l5 = THESIS_ARM.lengths
    c1, s1, c3, s3, c5, s5 = cos_sin(q[:, 0], q[:, 2], q[:, 4])
    return np.stack(
        [
            (l2 + l3 + l4) * c1 + l5 * c1 * c5 + l5 * s1 * s3 * s5,
            (l2 + l3 + l4) * s1 + l5 * s1 * c5 - l5 * c1 * s3 * s5,
            l5 * c3 * s5 + l1,
        ],
        1,
    )


def eq69_corrected(q, sign: float = 1.0, links: slice = slice(2, 5)):
    """f(1) on s(1) (theta4 = theta5 = 0): [(l2 + L c2) c1, (l2 + L c2) s1, l1 - L s2] [m], L = l3 + l4 + l5;
    slips: ``sign`` -1 (l1 + L s2), ``links`` other lengths summed into L."""
    l1, l2 = THESIS_ARM.lengths[:2]
    L = sum(THESIS_ARM.lengths[links])
    c1, s1, c2, s2 = cos_sin(q[:, 0], q[:, 1])
    return np.stack([(l2 + L * c2) * c1, (l2 + L * c2) * s1, l1 - sign * L * s2], 1)


def eq69_reading(ctx, f1):
    """Second reading of Eq 69 (the form): which singular set's surface it is. The tool point of the Table II
    chain (iik.dh) with each pair of joints held at 0, the others uniform in Table I, vs the form."""
    q = ctx.rng("eq69-reading").uniform(THESIS_ARM.q_min, THESIS_ARM.q_max, (ctx.n(200, 40), 6))

    def misfit(x) -> float:
        qq = q.copy()
        qq[:, [j - 1 for j in x["pair"]]] = 0.0
        return float(np.linalg.norm(f1(qq) - tool_point(qq[:, :5]), axis=1).max())

    pairs = [(a, b) for a in range(1, 6) for b in range(a + 1, 6) if (a, b) != (4, 5)]
    readings = choices(Kind.WHICH, "pair", {f"the set [theta{p[0]} = 0, theta{p[1]} = 0]": p for p in pairs})
    return search({"pair": (4, 5)}, readings, misfit, 1e-12,
        printed="f(1) = [(l2+l3+l4) c1 + l5 c1 c5 + l5 s1 s3 s5; ...; "
                  "l5 c3 s5 + l1]", stated_text="s(1) = [theta4 = 0, theta5 = 0] (App. E, Table VI)",
                  route="the tool point of the Table II chain by iik.dh with the pair held at 0",
                  measure="max |f(1) - tool point| [m]")


def _on_s1(ctx) -> Points:
    """Joint vectors [rad] uniform in Table I on s(1) (theta4 = theta5 = 0)."""
    q = ctx.rng("eq69").uniform(THESIS_ARM.q_min, THESIS_ARM.q_max, (ctx.n(400, 50), 6))
    q[:, 3:5] = 0.0
    return Points(q, f"{len(q)} q uniform in Table I with theta4 = theta5 = 0 (the whole surface f(1))",
                  "rad", "q")


CHECKS = SECTION.formulas(_on_s1, Formula(
    "Eq 69 (App. E)", eq69_printed, lambda s, f: np.linalg.norm(f(s.values) - iik.fk(s.values, THESIS_ARM)[
        :, :3, 3], axis=1), 1e-12, "m", (
        Slip(SlipKind.SIGN, "l1 + L s2 for l1 - L s2", lambda q: eq69_corrected(q, -1.0)),
        Slip(SlipKind.LENGTH, "L = l3 + l4 (l5 left out)", lambda q: eq69_corrected(q, links=slice(2, 4))),
    ), good=eq69_corrected, good_is="f(1) = [(l2 + L c2) c1, (l2 + L c2) s1, l1 - L s2], L = l3 + l4 + l5",
    eps_is="the good point + 1 nm", order=48.5, depends_on=EXACT_GEOMETRY, id="eq69", name="eq69_surface",
    text="f(1) = [(l2+l3+l4) c1 + l5 c1 c5 + l5 s1 s3 s5; (l2+l3+l4) s1 + l5 s1 c5 - l5 c1 s3 s5; l5 c3 s5 + "
    "l1] (the surface theta2 = theta4 = 0)",
    corrected="f(1) = [(l2 + (l3+l4+l5) c2) c1; (l2 + (l3+l4+l5) c2) s1; l1 - (l3+l4+l5) s2] (theta4 = "
    "theta5 = 0, free theta1, theta2 as in u(1); the printed H*(2,2) = q_s2^2 (l3+l4+l5) needs this form)",
    method="printed f(1) vs the Eq 4 tool point (iik.fk, = Pinocchio) at {n} random q with theta4 = theta5 = "
    "0", measure="max |f(1) - tool point|", reread=lambda ctx, s, f: eq69_reading(ctx, f)))
