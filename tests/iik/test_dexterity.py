"""iik.dexterity: the exact admissible orientations at a point, from the complete IK (Eq 42 angles)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import iik
from iik.dexterity import DexterityOptions, admissible, alpha_intervals
from iik.errors import DexterityError, IIKError, InvalidInputError, UnreachablePoseError

ARM = iik.THESIS_ARM
COARSE = DexterityOptions(alpha_samples=90, beta_samples=46)  # 4 deg: fast, the ends still root-found
joints = st.tuples(*[st.floats(float(lo), float(hi)) for lo, hi in zip(ARM.q_min, ARM.q_max, strict=True)])
# The issue's point: the thesis model rejected beta = 1.709 rad here, yet it has IK solutions.
ISSUE_Q = np.array([0.8822, -1.6532, 0.8189, -0.4771, 1.853, -2.6934])


def _solvable(p, alpha, beta) -> bool:
    """Ground truth by the public IK: some gamma of 12 has an exact solution within Table I."""
    n = 12
    T = iik.pose_from_euler(np.tile(p, (n, 1)), np.full(n, alpha), np.full(n, beta),
                            np.linspace(-math.pi, math.pi, n, endpoint=False))
    return any(len(r.q) and not r.is_approximate for r in iik.solve_many(T, ARM))


def test_public_and_frozen():
    assert {"dexterity", "Dexterity"} <= set(iik.__all__)
    r = iik.dexterity([0.5, 0.1, 0.4], ARM, options=COARSE)
    assert r.reachable and r.gamma_free and r.resolution == COARSE.resolution
    with pytest.raises(AttributeError):
        r.beta = 1.0  # frozen


def test_the_arm_is_an_argument():
    with pytest.raises(TypeError):
        iik.dexterity([0.5, 0.1, 0.4])  # no quiet default to the thesis arm
    with pytest.raises(InvalidInputError) as e:
        iik.dexterity([0.5, 0.1, 0.4], "thesis")
    assert e.value.argument == "arm"


@pytest.mark.parametrize("bad", [[np.nan, 0, 0], [0, 0], np.zeros((2, 3)), "p"])
def test_bad_point(bad):
    with pytest.raises(InvalidInputError) as e:
        iik.dexterity(bad, ARM)
    assert e.value.argument == "p"


@pytest.mark.parametrize("beta", [float("nan"), [1.0, 2.0], -0.1, 4.0])
def test_bad_beta(beta):
    with pytest.raises(InvalidInputError) as e:
        iik.dexterity([0.5, 0, 0.3], ARM, beta=beta)
    assert e.value.argument == "beta"


@pytest.mark.parametrize(("kw", "argument"), [({"alpha_samples": 2}, "alpha_samples"),
                                               ({"beta_samples": 10**9}, "beta_samples"),
                                               ({"tol": 0.0}, "tol"), ({"tol": float("nan")}, "tol")])
def test_bad_options_name_the_option(kw, argument):
    with pytest.raises(InvalidInputError) as e:
        DexterityOptions(**kw)
    assert e.value.argument == argument


def test_the_issue_point_admits_what_the_thesis_model_rejected():
    """beta = 1.709 rad at the issue's point: admissible (the Sec 3.5 model said no), and solvable."""
    p = iik.fk(ISSUE_Q, ARM)[:3, 3]
    r = iik.dexterity(p, ARM, beta=1.709)
    assert any(lo <= 1.709 <= hi for lo, hi in r.beta_intervals)
    assert r.alpha_intervals
    lo, hi = r.alpha_intervals[0]
    assert _solvable(p, 0.5 * (lo + hi), 1.709)


def test_beta_outside_every_interval_names_them():
    p = iik.fk(ISSUE_Q, ARM)[:3, 3]
    r = iik.dexterity(p, ARM, options=COARSE)
    lo = r.beta_intervals[0][0]
    assert lo > 0.2
    with pytest.raises(DexterityError) as e:
        iik.dexterity(p, ARM, beta=lo - 0.2, options=COARSE)
    err = e.value
    assert isinstance(err, IIKError) and isinstance(err, ValueError)
    assert err.argument == "beta" and err.beta_intervals == r.beta_intervals
    assert f"{lo:.6g}" in str(err) and "exact, from the IK" in str(err)


def test_nothing_admissible_is_an_answer_like_ik():
    """dexterity and solve agree: an unreachable point is a result with a reason; raising is on request."""
    p = [1.5, 0.0, 0.3]
    r = iik.dexterity(p, ARM, options=COARSE)
    assert not r.reachable and r.beta_range is None and r.beta_intervals == ()
    assert "no orientation" in r.reason
    assert iik.dexterity(p, ARM, beta=1.0, options=COARSE).alpha_intervals == ()
    with pytest.raises(UnreachablePoseError):
        r.raise_if_unreachable()
    reachable = iik.fk(np.array([0.3, -0.2, 0.4, 0.8, -0.5, 0.1]), ARM)
    assert iik.dexterity(reachable[:3, 3], ARM, options=COARSE).raise_if_unreachable().reachable


def test_interval_ends_are_changes_of_feasibility():
    """Each alpha end: admissible 1e-7 rad inside, not 1e-7 rad outside; each beta end has a witness."""
    p = iik.fk(ISSUE_Q, ARM)[:3, 3]
    r = iik.dexterity(p, ARM, beta=2.0)
    assert r.alpha_intervals
    for lo, hi in r.alpha_intervals:
        probe = admissible(p, [lo - 1e-7, lo + 1e-7, hi - 1e-7, hi + 1e-7], 2.0, ARM)
        assert probe.tolist() == [False, True, True, False]
    for (lo, hi), (a_lo, a_hi) in zip(r.beta_intervals, r.beta_end_alphas, strict=True):
        assert admissible(p, a_lo, lo, ARM) and admissible(p, a_hi, hi, ARM)
        if lo > 0:
            assert not admissible(p, np.linspace(-math.pi, math.pi, 3600), lo - 1e-7, ARM).any()


@settings(max_examples=15, deadline=None)
@given(joints, st.floats(0.05, 0.95), st.floats(-math.pi, math.pi))
def test_the_intervals_are_the_solvable_set(q, t, alpha):
    """Membership of alpha_intervals agrees with solving the pose (any gamma), away from the ends."""
    p = iik.fk(np.array(q), ARM)[:3, 3]
    beta = t * math.pi
    ivs = alpha_intervals(p, beta, ARM, options=COARSE)
    inside = any((alpha - lo) % (2 * math.pi) <= hi - lo for lo, hi in ivs)
    near_end = any(abs((alpha - e + math.pi) % (2 * math.pi) - math.pi) < 1e-6 for iv in ivs for e in iv)
    if not near_end:
        assert inside == _solvable(p, alpha, beta)
        assert inside == bool(admissible(p, alpha, beta, ARM))


def test_a_set_narrower_than_the_grid_is_missed_and_the_reason_says_so():
    """Fully stretched (q = 0) only the arm's own approach direction is admissible: one orientation, which
    no grid hits. The answer is honest about it; admissible() still says yes to that orientation."""
    T = iik.fk(np.zeros(6), ARM)
    a, b, _ = iik.euler_from_matrix(T[:3, :3])
    r = iik.dexterity(T[:3, 3], ARM, options=COARSE)
    assert not r.reachable and "narrower than 4 deg may be missed" in r.reason
    assert admissible(T[:3, 3], a, b, ARM)
    assert not admissible(T[:3, 3], a, b + 0.2, ARM)


def test_an_arm_whose_roll_is_not_joint_6_is_refused_by_name():
    tool = np.eye(4)
    tool[0, 3] = 0.05  # tool point off joint 6's axis: gamma would move it
    arm = iik.Arm(dh=ARM.dh, tool=tool, name="offset tool")
    with pytest.raises(InvalidInputError) as e:
        iik.dexterity([0.5, 0.1, 0.4], arm)
    assert e.value.argument == "arm" and "joint 6" in e.value.reason
