"""Tests of iik.workspace: the corrected Sec 3.4.4 test and the closest reachable point."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import minimize_scalar

import iik
import iik.arms
from iik import THESIS_ARM
from iik.errors import IIKError, InvalidInputError
from iik.workspace import position_lm, tool_positions

ARM = iik.THESIS_ARM
L = ARM.l3 + ARM.l4 + ARM.l5

joints = st.tuples(*[st.floats(float(lo), float(hi)) for lo, hi in zip(ARM.q_min, ARM.q_max, strict=True)])


def test_public_api():
    for name in ("in_workspace", "closest_reachable", "ClosestReachable"):
        assert name in iik.__all__ and hasattr(iik, name)


def test_tool_positions_equal_fk():
    q = np.random.default_rng(0).uniform(ARM.q_min, ARM.q_max, size=(500, 6))
    assert np.abs(tool_positions(q[:, :5], THESIS_ARM) - iik.fk(q, THESIS_ARM)[:, :3, 3]).max() < 1e-14


def test_shapes_and_scalar():
    assert iik.in_workspace([0.5, 0.0, 0.3], THESIS_ARM) is True
    assert iik.in_workspace([2.0, 0.0, 0.3], THESIS_ARM) is False
    out = iik.in_workspace(np.zeros((4, 3)), THESIS_ARM)
    assert out.shape == (4,) and out.dtype == bool


@pytest.mark.parametrize("bad", [[np.nan, 0, 0], [0, 0], np.zeros((2, 2)), "abc", [[0, 0, np.inf]]])
def test_bad_points(bad):
    with pytest.raises(InvalidInputError) as e:
        iik.in_workspace(bad, THESIS_ARM)
    assert e.value.argument == "p"
    with pytest.raises(IIKError):
        iik.closest_reachable(bad, THESIS_ARM)


def test_no_reachable_point_rejected_batch():
    """Measured property of the corrected test: every reachable point is inside (no false outside)."""
    q = np.random.default_rng(1).uniform(ARM.q_min, ARM.q_max, size=(100_000, 6))
    assert iik.in_workspace(tool_positions(q[:, :5], THESIS_ARM), THESIS_ARM).all()


@settings(max_examples=200, deadline=None)
@given(joints)
def test_reachable_points_inside(q):
    assert iik.in_workspace(iik.fk(np.array(q), THESIS_ARM)[:3, 3], THESIS_ARM)


@settings(max_examples=100, deadline=None)
@given(st.floats(-2.7, 2.7), st.floats(-1.0, 1.0), st.floats(0.001, 0.5))
def test_region1_outside_sphere_is_outside(phi, el, extra):
    """Region 1 (Eq 38): beyond l3 + l4 + l5 from joint 2 nothing is reachable."""
    j2 = np.array([ARM.l2 * np.cos(phi), ARM.l2 * np.sin(phi), ARM.l1])
    u = np.array([np.cos(el) * np.cos(phi), np.cos(el) * np.sin(phi), np.sin(el)])
    p = j2 + (L + extra) * u
    assert not iik.in_workspace(p, THESIS_ARM)
    r = iik.closest_reachable(p, THESIS_ARM)
    assert r.moved
    assert r.distance == pytest.approx(extra, abs=1e-6)


def test_closest_reachable_is_reachable():
    rng = np.random.default_rng(2)
    P = rng.uniform([-1.2, -1.2, -0.8], [1.2, 1.2, 1.4], size=(40, 3))
    r = iik.closest_reachable(P, THESIS_ARM)
    assert r.point.shape == (40, 3) and r.q.shape == (40, 6)
    assert np.all(ARM.within_limits(r.q))
    assert np.abs(iik.fk(r.q, THESIS_ARM)[:, :3, 3] - r.point).max() < 1e-9
    assert np.allclose(np.linalg.norm(r.point - P, axis=1), r.distance)
    # relocated points are reachable, so the corrected test (no false outside) accepts them
    assert iik.in_workspace(r.point, THESIS_ARM).all()
    assert np.all(r.distance[~r.moved] == 0)


def test_closest_reachable_unchanged_for_reachable():
    q = np.random.default_rng(3).uniform(ARM.q_min, ARM.q_max, size=(30, 6))
    P = iik.fk(q, THESIS_ARM)[:, :3, 3]
    r = iik.closest_reachable(P, THESIS_ARM)
    assert not r.moved.any()
    assert np.array_equal(r.point, P)


def test_closest_reachable_known_point():
    r = iik.closest_reachable([1.0, 0.0, ARM.l1], THESIS_ARM)  # straight ahead, 0.099 m too far
    assert r.point == pytest.approx([ARM.l2 + L, 0.0, ARM.l1], abs=1e-7)
    assert r.distance == pytest.approx(1.0 - ARM.l2 - L, abs=1e-7)


def test_bad_tol():
    with pytest.raises(InvalidInputError):
        iik.closest_reachable([0.5, 0, 0.3], THESIS_ARM, tol=0.0)


def test_position_lm_converges():
    rng = np.random.default_rng(4)
    q = rng.uniform(ARM.q_min, ARM.q_max, size=(50, 6))[:, :5]
    P = tool_positions(q, THESIS_ARM)
    q0 = np.clip(q + rng.normal(0, 0.05, q.shape), ARM.q_min[:5], ARM.q_max[:5])
    _, res = position_lm(P, q0, THESIS_ARM)
    assert res.max() < 1e-8


@pytest.mark.parametrize("p", [[1e300, 0.0, 0.0], [1e308, 1e308, -1e308], [-1e200, 1.0, 1.0],
                               [0.0, 0.0, -1e250]])
def test_closest_reachable_far_away_points(p):
    """Points beyond any reach, up to the largest floats: no error and no warning; the answer is
    reachable (fk of the returned q), the same as for the point on its ray at 10^6 m (computed
    without the far-point proxy) to 1e-6 m, and the distance is measured to the point as given."""
    p = np.array(p)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = iik.closest_reachable(p, THESIS_ARM)
        assert not iik.in_workspace(p, THESIS_ARM)
    assert r.moved and np.allclose(iik.fk(r.q, THESIS_ARM)[:3, 3], r.point, atol=1e-12)
    ray = p / np.hypot(np.hypot(p[0], p[1]), p[2]) * 1e6
    assert np.max(np.abs(iik.closest_reachable(ray, THESIS_ARM).point - r.point)) <= 1e-6
    d = (r.point - p) / np.max(np.abs(p))
    assert r.distance == pytest.approx(np.max(np.abs(p)) * np.sqrt(np.sum(d * d)), rel=1e-12)


def test_another_arms_workspace_is_searched_with_its_own_fk():
    """For an arm not of the thesis's form (the CRX-10iA) Sec 3.4.4 does not apply: in_workspace asks the
    six-joint search of closest_reachable, which reaches FK points of random configurations inside the
    CRX's limits, and refuses points beyond its reach bound with a reachable suggestion on the boundary."""
    crx = iik.arms.get("crx10ia")
    q = np.random.default_rng(11).uniform(crx.q_min, crx.q_max, (200, 6))
    P = iik.fk(q, crx)[:, :3, 3]
    assert iik.in_workspace(P, crx).all()
    assert not iik.in_workspace(P, THESIS_ARM).all()  # the thesis arm's workspace is another
    far = np.array([[crx.reach + 0.2, 0.0, 0.3], [0.0, 0.0, crx.reach + 0.5]])
    assert not iik.in_workspace(far, crx).any()
    c = iik.closest_reachable(far, crx)
    assert c.moved.all() and np.all(c.distance > 0.19)
    np.testing.assert_allclose(iik.fk(c.q, crx)[:, :3, 3], c.point, atol=1e-9)  # reached by its q
    assert iik.closest_reachable(P[0], crx).distance == 0.0
    with pytest.raises(InvalidInputError):
        iik.in_workspace([np.nan, 0, 0], crx)


@settings(max_examples=60, deadline=None)
@given(st.floats(-1.2, 1.2), st.floats(-1.2, 1.2), st.floats(-0.6, 1.4), st.sampled_from([0, 1]))
def test_joint4_distance_is_the_nearest_over_joint_2s_range(x, y, z, end):
    """rho_23 (Eq 41) is joint 4's distance to p with joint 2 aimed at p *within Table I*: the
    minimum over joint 2's range. A plain clip of the aimed angle picks the wrong limit for an
    aim past one limit but nearer the other across +-pi (found: 0.1 m too far)."""
    from iik.workspace import joint4_distance

    p = np.array([[x, y, z]])
    th1 = (THESIS_ARM.lower[0], THESIS_ARM.upper[0])[end]
    l1, l2, l3 = THESIS_ARM.l1, THESIS_ARM.l2, THESIS_ARM.l3
    lo, hi = THESIS_ARM.lower[1], THESIS_ARM.upper[1]

    def dist(t2):
        j4 = np.stack([(l2 + l3 * np.cos(t2)) * np.cos(th1), (l2 + l3 * np.cos(t2)) * np.sin(th1),
                       l1 - l3 * np.sin(t2)], axis=-1)
        return np.linalg.norm(j4 - p, axis=-1)

    t2 = np.linspace(lo, hi, 20001)  # dense, then the best grid point refined between its neighbours
    i = int(np.argmin(dist(t2)))     # (the grid alone is up to ~4e-9 m off where the curvature is high)
    a, b = t2[max(i - 1, 0)], t2[min(i + 1, len(t2) - 1)]
    fine = minimize_scalar(lambda t: float(dist(np.array(t))[0]), bounds=(a, b), method="bounded",
                           options={"xatol": 1e-12})
    dense = min(float(dist(t2).min()), float(fine.fun))
    assert joint4_distance(p, th1, THESIS_ARM)[0] == pytest.approx(dense, abs=2e-9)


def test_joint4_distance_at_an_aim_across_pi():
    """The point found by the property above: joint 2 aimed at about 170 deg (past 95 deg, 70 deg
    from -120 deg across +-pi)."""
    from iik.workspace import joint4_distance

    p = np.array([[0.13986948, -0.2704922, 0.29736668]])
    th1 = THESIS_ARM.upper[0]
    t2 = THESIS_ARM.lower[1]  # the nearer limit on the circle
    l1, l2, l3 = THESIS_ARM.l1, THESIS_ARM.l2, THESIS_ARM.l3
    r = l2 + l3 * np.cos(t2)
    j4 = np.array([r * np.cos(th1), r * np.sin(th1), l1 - l3 * np.sin(t2)])
    assert joint4_distance(p, th1, THESIS_ARM)[0] == pytest.approx(np.linalg.norm(j4 - p[0]), abs=1e-12)
