"""iik.limits: the one joint-limit test, Arm.limit_violations, and Arm.within_limits answering from it."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import iik.arms
from iik import THESIS_ARM, InvalidInputError
from iik.limits import LimitViolation

ARMS = (THESIS_ARM, iik.arms.get("crx10ia"))
angles = arrays(float, st.tuples(st.integers(1, 20), st.just(6)), elements=st.floats(-4.0, 4.0))
margins = st.floats(-0.05, 0.3)


@given(angles, margins, st.sampled_from(ARMS))
def test_violations_are_exactly_the_values_beyond_the_limits_less_the_margin(q, margin, arm):
    found = arm.limit_violations(q, margin)
    lo, hi = np.asarray(arm.lower) + margin, np.asarray(arm.upper) - margin
    beyond = [(k, j) for k in range(len(q)) for j in range(6) if not lo[j] <= q[k, j] <= hi[j]]
    assert [(v.sample, v.joint) for v in found] == beyond and len(found) == len(beyond)
    assert bool(found) == bool(beyond)
    for v in found:
        assert v.amount > 0 and v.value == q[v.sample, v.joint] and v.margin == margin
        assert v.amount == pytest.approx(max(lo[v.joint] - v.value, v.value - hi[v.joint]), abs=1e-15)
        assert v.limit == (arm.lower if v.side == "lower" else arm.upper)[v.joint]
    np.testing.assert_array_equal(found.within, [all((k, j) not in beyond for j in range(6))
                                                 for k in range(len(q))])
    if beyond:
        assert found.worst.amount == max(v.amount for v in found)


@given(angles, st.floats(-0.05, 1e-3), st.sampled_from(ARMS))
def test_within_limits_is_no_violation_with_the_tolerance_outside(q, tol, arm):
    np.testing.assert_array_equal(arm.within_limits(q, tol), arm.limit_violations(q, -tol).within)
    assert arm.within_limits(q[0], tol) is arm.limit_violations(q[0], -tol).within


def test_one_configuration_and_chosen_joints():
    q = np.zeros(6)
    q[3] = np.radians(150)  # Table I: q4 in [-119, 119] deg
    (v,) = THESIS_ARM.limit_violations(q)
    assert isinstance(v, LimitViolation) and (v.sample, v.joint, v.side) == (0, 3, "upper")
    assert v.amount == pytest.approx(np.radians(31)) and THESIS_ARM.limit_violations(q).within is False
    assert not THESIS_ARM.limit_violations(np.zeros(6))
    # the columns may be other joints (simulated modules 7.. take joint 1's limits)
    found = THESIS_ARM.limit_violations([[3.0, 0.5]], joints=(0, 3))
    assert [(v.joint, v.sample) for v in found] == [(0, 0)] and found.batched


@pytest.mark.parametrize("kwargs, argument", [
    ({"margin": float("nan")}, "margin"), ({"margin": "0.1"}, "margin"), ({"joints": (0, 6)}, "joints"),
    ({"joints": ()}, "joints")])
def test_bad_arguments_are_named(kwargs, argument):
    with pytest.raises(InvalidInputError) as info:
        THESIS_ARM.limit_violations(np.zeros(6), **kwargs)
    assert info.value.argument == argument


def test_bad_configurations_are_named():
    with pytest.raises(InvalidInputError, match="q"):
        THESIS_ARM.limit_violations([0.0, np.nan, 0, 0, 0, 0])
    with pytest.raises(InvalidInputError, match="q"):
        THESIS_ARM.limit_violations(np.zeros(5))
