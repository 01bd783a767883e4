"""Tests of iik.dexterity (Sec 3.5 model, Eq 42 angle convention)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import iik
from iik import THESIS_ARM
from iik.dexterity import alpha_admissible
from iik.errors import DexterityError, IIKError, InvalidInputError, UnreachablePoseError

ARM = iik.THESIS_ARM
joints = st.tuples(*[st.floats(float(lo), float(hi)) for lo, hi in zip(ARM.q_min, ARM.q_max, strict=True)])


def test_public():
    assert "dexterity" in iik.__all__
    r = iik.dexterity([0.5, 0.1, 0.4], THESIS_ARM)
    assert r.case in ("outer", "ring", "inner")
    assert r.gamma_range == (ARM.lower[5], ARM.upper[5])
    with pytest.raises(AttributeError):
        r.case = "x"  # frozen


@pytest.mark.parametrize("bad", [[np.nan, 0, 0], [0, 0], np.zeros((2, 3)), "p"])
def test_bad_point(bad):
    with pytest.raises(InvalidInputError) as e:
        iik.dexterity(bad, THESIS_ARM)
    assert e.value.argument == "p"


def test_bad_beta_value():
    with pytest.raises(InvalidInputError):
        iik.dexterity([0.5, 0, 0.3], THESIS_ARM, beta=float("nan"))
    with pytest.raises(InvalidInputError):
        iik.dexterity([0.5, 0, 0.3], THESIS_ARM, beta=[1.0, 2.0])


def test_beta_outside_range_names_range():
    p = [0.8, 0.0, 0.3]
    r = iik.dexterity(p, THESIS_ARM)
    lo, hi = r.beta_range
    with pytest.raises(DexterityError) as e:
        iik.dexterity(p, THESIS_ARM, beta=hi + 0.1)
    err = e.value
    assert isinstance(err, IIKError) and isinstance(err, ValueError)
    assert err.argument == "beta" and err.beta_range == r.beta_range
    assert f"{lo:.6g}" in str(err) and f"{hi:.6g}" in str(err)


def test_outside_workspace_is_an_answer_like_ik():
    """dexterity and solve agree: an unreachable point is a result with a reason; raising is on request."""
    p = [1.5, 0.0, 0.3]
    r = iik.dexterity(p, THESIS_ARM)
    assert r.case == "unreachable" and not r.reachable and r.beta_range is None
    assert "outside the workspace" in r.reason and not alpha_admissible(r, 0.0, 1.0)
    assert iik.dexterity(p, THESIS_ARM, beta=1.0).case == "unreachable"  # a beta does not make it an error
    T = iik.pose_from_euler(p, 0.0, 1.0, 0.0)
    ik = iik.solve(T, THESIS_ARM)
    assert ik.count == 0 and ik.reason.startswith("unreachable")
    for res in (r, ik):
        with pytest.raises(UnreachablePoseError) as e:
            res.raise_if_unreachable()
        assert "unreachable" in str(e.value)
    reachable = iik.fk(np.array([0.3, -0.2, 0.4, 0.8, -0.5, 0.1]), THESIS_ARM)
    assert iik.dexterity(reachable[:3, 3], THESIS_ARM).raise_if_unreachable().reachable
    assert iik.solve(reachable, THESIS_ARM).raise_if_unreachable().count > 0


def test_home_pose_has_one_orientation():
    """Fully stretched (q = 0): only the arm's own approach direction (beta = 90 deg, alpha = 180 deg)."""
    T = iik.fk(np.zeros(6), THESIS_ARM)
    r = iik.dexterity(T[:3, 3], THESIS_ARM)
    assert r.case == "outer"
    assert r.beta_range[0] == pytest.approx(math.pi / 2, abs=1e-6)
    assert r.beta_range[1] == pytest.approx(math.pi / 2, abs=1e-6)
    a, b, _ = iik.euler_from_matrix(T[:3, :3])
    assert r.admits(a, b, tol=1e-6)
    # and ground truth agrees: a tilted approach at the same point is not solvable
    assert len(iik.solve(iik.pose_from_euler(T[:3, 3], a, b + 0.2, 0.0), THESIS_ARM).q) == 0


def test_outer_case_matches_eq44():
    """Outer case, unclipped: the inclination range is Eq 44's beta' +- delta."""
    p = np.array([0.7, 0.2, 0.45])
    r = iik.dexterity(p, THESIS_ARM)
    assert r.case == "outer"
    l1, l2, l3, l4, l5 = ARM.lengths
    phi = math.atan2(p[1], p[0])
    v = p - [l2 * math.cos(phi), l2 * math.sin(phi), l1]
    rho = np.linalg.norm(v)
    bp = math.atan(v[2] / math.hypot(v[0], v[1]))  # Eq 43
    d = math.acos((l5**2 + rho**2 - (l3 + l4) ** 2) / (2 * l5 * rho))  # Eq 44
    assert r.inclination_range == pytest.approx((bp - d, bp + d), abs=1e-12)
    assert r.beta_range == pytest.approx((bp - d + math.pi / 2, bp + d + math.pi / 2), abs=1e-12)


@settings(max_examples=60, deadline=None)
@given(joints, st.floats(0.0, 1.0), st.floats(-math.pi, math.pi))
def test_intervals_consistent(q, t, alpha):
    """alpha_intervals, admits() and alpha_admissible() describe the same set."""
    p = iik.fk(np.array(q), THESIS_ARM)[:3, 3]
    r = iik.dexterity(p, THESIS_ARM)
    if r.case == "none":
        assert r.beta_range is None
        return
    beta = r.beta_range[0] + t * (r.beta_range[1] - r.beta_range[0])
    rb = iik.dexterity(p, THESIS_ARM, beta=beta)
    assert 1 <= len(rb.alpha_intervals) <= 2
    in_iv = any(
        lo - 1e-9 <= alpha + k * 2 * math.pi <= hi + 1e-9
        for lo, hi in rb.alpha_intervals for k in (-1, 0, 1)
    )
    near_edge = any(min(abs((alpha - e + math.pi) % (2 * math.pi) - math.pi) for e in iv) < 1e-7
                    for iv in rb.alpha_intervals)
    if not near_edge:
        assert rb.admits(alpha, beta) == in_iv
        assert bool(alpha_admissible(r, alpha, beta)) == in_iv


def test_admitted_orientations_mostly_solvable():
    """Soundness of the model at a few outer-case points, against iik.solve (measured ~94 %)."""
    rng = np.random.default_rng(7)
    ok = total = 0
    for q in rng.uniform(ARM.q_min, ARM.q_max, size=(40, 6)):
        p = iik.fk(q, THESIS_ARM)[:3, 3]
        r = iik.dexterity(p, THESIS_ARM)
        if r.case != "outer":
            continue
        for t in (0.25, 0.5, 0.75):
            beta = r.beta_range[0] + t * (r.beta_range[1] - r.beta_range[0])
            rb = iik.dexterity(p, THESIS_ARM, beta=beta)
            lo, hi = rb.alpha_intervals[0]
            alpha = 0.5 * (lo + hi)
            total += 1
            ok += len(iik.solve(iik.pose_from_euler(p, alpha, beta, 0.0), THESIS_ARM).q) > 0
    assert total >= 20
    assert ok / total > 0.85
