"""Tests of iik.solve / iik.solve_many (complete method) and its degenerate cases."""

import dataclasses
import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import iik
from iik.errors import IIKError, InvalidInputError
from iik.ik.angles import wrap_angle as _wrap
from iik.ik.compare import POSE_EPS, contains
from iik.ik.elimination import eliminant_coefficients
from iik.ik.reference import FREE_Q3_Q6, MAX_SOLUTIONS, POSITION_TOL, ROTATION_TOL, solve_arrays

ARM = iik.THESIS_ARM
LO, HI = ARM.q_min, ARM.q_max


def _q_in_limits(draw, **fixed):
    q = [draw(st.floats(float(LO[j]), float(HI[j]), allow_nan=False)) for j in range(6)]
    for j, v in fixed.items():
        q[int(j[1]) - 1] = v
    return np.array(q)


@st.composite
def joints(draw):
    return _q_in_limits(draw)


@st.composite
def near_singular(draw):
    """q within Table I with one joint at or very near a singular value."""
    q = _q_in_limits(draw)
    kind = draw(st.sampled_from(["q4", "q5", "q3+", "q3-", "q1hi", "q1lo"]))
    centre = {"q4": 0.0, "q5": 0.0, "q3+": np.pi / 2, "q3-": -np.pi / 2,
              "q1hi": float(HI[0]), "q1lo": float(LO[0])}[kind]
    j = {"q4": 3, "q5": 4, "q3+": 2, "q3-": 2, "q1hi": 0, "q1lo": 0}[kind]
    exp = draw(st.one_of(st.just(None), st.floats(-12, -2)))
    off = 0.0 if exp is None else draw(st.sampled_from([-1.0, 1.0])) * 10.0**exp
    if kind == "q1hi":
        off = -abs(off)
    if kind == "q1lo":
        off = abs(off)
    q[j] = centre + off
    return q


def _check_recovers(q):
    T = iik.fk(q)
    r = iik.solve(T, within_limits=False)
    assert r.count >= 1, r.reason
    assert np.all(r.position_residual <= POSITION_TOL)
    assert np.all(r.rotation_residual <= ROTATION_TOL)
    assert contains(r.q, q, T, ARM, free_joints=r.free_joints), (q, r.q)
    # within the limits the generating q must survive the limit filter too, unless it sits
    # on a stop closer than the accuracy the pose carries (POSE_EPS / sigma_min)
    smin = np.linalg.svd(iik.jacobian(q), compute_uv=False)[-1]
    margin = np.min(np.minimum(q - LO, HI - q))
    if margin > max(1e-7, POSE_EPS / smin):
        rl = iik.solve(T)
        assert contains(rl.q, q, T, ARM, free_joints=rl.free_joints)


@given(joints())
def test_recovers_generating_q(q):
    _check_recovers(q)


@given(near_singular())
def test_recovers_generating_q_near_singularities(q):
    _check_recovers(q)


def test_recovers_strictly_on_random_batch():
    """Away from singularities the generating q is recovered to 1e-9 rad (strict)."""
    rng = np.random.default_rng(11)
    q = rng.uniform(LO, HI, size=(3000, 6))
    sv = np.linalg.svd(iik.jacobian(q), compute_uv=False)[:, -1]
    q = q[sv > 1e-2]
    Q, V, _F, P, R = solve_arrays(iik.fk(q), ARM)
    d = np.max(np.abs(_wrap(Q - q[:, None, :])), axis=2)
    d[~V] = np.inf
    assert np.max(np.min(d, axis=1)) <= 1e-9
    assert np.nanmax(P) <= POSITION_TOL and np.nanmax(R) <= ROTATION_TOL
    assert V.sum(1).max() <= MAX_SOLUTIONS


def test_solve_many_identical_to_solve():
    rng = np.random.default_rng(3)
    q = rng.uniform(LO, HI, size=(25, 6))
    Ts = iik.fk(q)
    many = iik.solve_many(Ts)
    for T, rm in zip(Ts, many, strict=True):
        r1 = iik.solve(T)
        assert np.array_equal(r1.q, rm.q)
        assert np.array_equal(r1.position_residual, rm.position_residual)
        assert r1.free_joints == rm.free_joints


def test_deterministic_order():
    q = np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0])
    r = iik.solve(iik.fk(q), within_limits=False)
    keys = [tuple(np.round(row, 9)) for row in r.q]
    assert keys == sorted(keys)
    assert np.array_equal(r.q, iik.solve(iik.fk(q), within_limits=False).q)


def test_result_is_frozen():
    r = iik.solve(iik.fk(np.zeros(6) + 0.2))
    with pytest.raises(ValueError):
        r.q[0, 0] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.reason = "x"


def test_theta1_at_pi_where_plain_t_polynomial_loses_degree():
    """theta1 = pi: tan(theta1/2) is infinite; the plain t-polynomial has a zero leading coefficient."""
    q = np.array([np.pi, -0.4, 0.9, 0.8, -0.6, 1.2])
    T = iik.fk(q)
    co = eliminant_coefficients(T[None, :3, :3], T[None, :3, 3], ARM)

    def F(th):  # the eliminant a^2 (P^2 + Q^2) - (b Q - c P)^2
        a, b, P, Q = (x[0] + x[1] * np.cos(th) + x[2] * np.sin(th) for x in co.abPQ[0])
        return a * a * (P * P + Q * Q) - (b * Q - co.c[0] * P) ** 2

    scale = np.max(np.abs(F(np.linspace(0, 2 * np.pi, 16))))
    assert abs(F(np.pi)) <= 1e-12 * scale  # the leading coefficient of the plain t-polynomial
    r = iik.solve(T, within_limits=False)
    assert contains(r.q, q, T, ARM)
    assert np.min(np.max(np.abs(_wrap(r.q - q)), axis=1)) <= 1e-9
    assert not contains(iik.solve(T).q, q, T, ARM)  # theta1 = 180 deg is outside Table I


def test_tangent_root_elbow_stretched():
    """theta4 = 0 (B, C, D collinear) makes theta1 a double root of the eliminant."""
    q = np.array([0.4, -0.3, 0.5, 0.0, 0.7, -0.2])
    T = iik.fk(q)
    r = iik.solve(T, within_limits=False)
    assert np.min(np.max(np.abs(_wrap(r.q - q)), axis=1)) <= 1e-9


def test_near_double_roots_both_found():
    """theta4 = +-1e-5: two close theta1 roots; both configurations are returned."""
    base = np.array([0.4, -0.3, 0.5, 1e-5, 0.7, -0.2])
    T = iik.fk(base)
    r = iik.solve(T, within_limits=False)
    assert contains(r.q, base, T, ARM)
    assert np.min(np.max(np.abs(_wrap(r.q - base)), axis=1)) <= 1e-9


def test_continuum_q3_q6_is_flagged():
    """theta4 = theta5 = 0: joints 3 and 6 are collinear; a representative is flagged."""
    q = np.array([0.4, -0.3, 0.5, 0.0, 0.0, -0.2])
    T = iik.fk(q)
    r = iik.solve(T, within_limits=False)
    flagged = [i for i, f in enumerate(r.free_joints) if f == (3, 6)]
    assert flagged
    rep = r.q[flagged[0]].copy()
    assert abs(rep[3]) <= 1e-6 and abs(rep[4]) <= 1e-6
    # moving along the continuum keeps the pose: theta3 + theta6 (or the difference) is fixed
    for k in (+1, -1):
        moved = rep + np.array([0, 0, 0.3, 0, 0, k * 0.3])
        Tm = iik.fk(moved)
        if np.allclose(Tm, T, atol=1e-9):
            break
    else:
        pytest.fail("representative does not lie on a theta3/theta6 continuum")
    assert FREE_Q3_Q6


def test_joint6_wrap_at_pi():
    """theta6 = -pi and +pi are the same configuration; the solver reports it once, at +pi."""
    q = np.array([0.2, -0.3, 0.4, 0.9, -0.5, -np.pi])
    T = iik.fk(q)
    r = iik.solve(T)
    assert contains(r.q, q, T, ARM)
    assert np.all(r.q[:, 5] > -np.pi)
    assert np.all(r.within_limits)


def test_wrist_plane_degenerate_P_Q_zero():
    """z6 parallel to D - B: Eq 8 vanishes identically at that theta1 (P = Q = 0)."""
    rng = np.random.default_rng(5)
    found = 0
    for _ in range(200):
        q = rng.uniform(LO, HI)
        fr = iik.joint_frames(q)
        B = fr[1, :3, 3]
        D = fr[4, :3, 3]
        # rotate joint 5/6 so that z6 points along D - B: solve for theta5 with a 1-D search
        best = None
        for t5 in np.linspace(-np.pi, np.pi, 721):
            qq = q.copy()
            qq[4] = t5
            z = iik.fk(qq)[:3, 2]
            c = abs(np.dot(z, (D - B) / np.linalg.norm(D - B)))
            if best is None or c > best[0]:
                best = (c, qq)
        if best[0] > 1 - 1e-5:
            qq = best[1]
            T = iik.fk(qq)
            r = iik.solve(T, within_limits=False)
            assert contains(r.q, qq, T, ARM)
            found += 1
        if found >= 3:
            break
    assert found >= 1


def test_unreachable_pose_gives_reason():
    T = np.eye(4)
    T[:3, 3] = [5.0, 0.0, 0.0]
    r = iik.solve(T)
    assert r.count == 0 and "unreachable" in r.reason
    assert r.q.shape == (0, 6)


def test_outside_limits_reason():
    q = np.array([np.pi, -0.4, 0.9, 0.8, -0.6, 1.2])
    r_all = iik.solve(iik.fk(q), within_limits=False)
    r = iik.solve(iik.fk(q))
    assert r_all.count > 0
    if r.count == 0:
        assert "joint limits" in r.reason
    assert np.all(r.within_limits)
    assert r_all.within_limits.dtype == bool


@pytest.mark.parametrize(
    "bad, msg",
    [
        (np.full((4, 4), np.nan), "NaN"),
        (np.eye(3), "shape"),
        (np.diag([1.0, 2.0, 1.0, 1.0]), "orthonormal"),
        (np.diag([1.0, 1.0, -1.0, 1.0]), "det"),
        ("pose", "numbers"),
    ],
)
def test_bad_input_typed_errors(bad, msg):
    with pytest.raises(InvalidInputError) as e:
        iik.solve(bad)
    assert msg in str(e.value)
    assert isinstance(e.value, IIKError)


def test_batch_to_solve_and_bad_method():
    with pytest.raises(InvalidInputError):
        iik.solve(np.stack([np.eye(4)] * 2))
    with pytest.raises(InvalidInputError):
        iik.solve(np.eye(4), method="magic")


def test_pose_from_euler_round_trip():
    q = np.array([0.3, -0.2, 0.5, 0.7, -0.4, 0.9])
    T = iik.fk(q)
    a, b, g = iik.euler_from_matrix(T[:3, :3])
    T2 = iik.pose_from_euler(T[:3, 3], a, b, g)
    assert np.allclose(T, T2, atol=1e-12)
    assert contains(iik.solve(T2).q, q, T2, ARM)


def test_wrist_on_joint1_axis_with_vertical_tool():
    """D on the joint-1 axis and z6 vertical: Eq 8 nearly vanishes for every theta1 (theta1/theta6 axes
    collinear); the generating q is still recovered."""
    from scipy.optimize import least_squares

    def f(x):
        q = np.array([0, x[0], 0, x[1], x[2], 0])
        return [*iik.joint_frames(q)[4, :2, 3], *iik.fk(q)[:2, 2]]

    x = least_squares(f, [0.5, -2.0, 0.5], xtol=1e-15, ftol=1e-15, gtol=1e-15).x
    q = np.array([0.0, x[0], 0.0, x[1], x[2], 0.3])
    T = iik.fk(q)
    r = iik.solve(T, within_limits=False)
    assert contains(r.q, q, T, ARM, free_joints=r.free_joints)
    assert np.all(r.position_residual <= POSITION_TOL)


def test_clustered_candidates_are_deduplicated_not_truncated():
    """theta3 ~ 90 deg with theta4 ~ 90 deg: many clustered candidates; duplicates must merge
    before the 16-solution cap (regression: the generating q was cut off)."""
    q = np.array([2.507781185021448, 1.4742098351302193, 1.5707963268300342,
                  1.567367861137023, -1.0916596700323127, 1.8143558774026767])
    T = iik.fk(q)
    r = iik.solve(T, within_limits=False)
    assert r.count < MAX_SOLUTIONS
    assert contains(r.q, q, T, ARM, free_joints=r.free_joints)


# ----------------------------------------------------------------------------- continua (issue 10, item 4)
def test_issue_example_continuum_inside_table_i_with_its_interval():
    """q with theta4 = theta5 = 0 inside Table I: the representative is inside Table I, the fixed
    combination is theta3 - theta6 and every member of the free interval reaches the pose."""
    q = np.array([0.98902373, 0.75632699, 0.01209722, 0.0, 0.0, 0.96039359])
    T = iik.fk(q)
    r = iik.solve(T)
    assert r.count >= 1 and np.all(r.within_limits) and ARM.within_limits(r.q).all()
    i = r.free_joints.index((3, 6))
    (c,) = r.continua[i]
    assert c.free_joint == 3 and c.sign == 1 and c.fixed == "theta3 - theta6"
    assert c.value == pytest.approx(_wrap(q[2] - q[5]), abs=1e-9)
    assert c.interval == pytest.approx((LO[2], HI[2]))  # joint 6 spans a full turn
    assert np.array_equal(c.representative, r.q[i])
    for th in np.linspace(*c.interval, 7):
        m = c.member(th)
        assert ARM.within_limits(m)
        assert np.allclose(iik.fk(m), T, atol=1e-10)
    assert contains(r.q, q, T, ARM, free_joints=r.free_joints)


def test_exact_singular_poses_inside_table_i_have_a_solution_inside_table_i():
    rng = np.random.default_rng(21)
    fixes = ({3: 0.0, 4: 0.0}, {3: 0.0}, {4: 0.0}, {2: np.pi / 2}, {2: -np.pi / 2}, {0: HI[0]}, {0: LO[0]})
    for fix in fixes:
        q = rng.uniform(LO, HI, size=(150, 6))
        for j, v in fix.items():
            q[:, j] = v
        for qi, r in zip(q, iik.solve_many(iik.fk(q)), strict=True):
            assert r.count >= 1 and not r.is_approximate, (qi, r.reason)
            assert ARM.within_limits(r.q).all()


def test_continuum_representative_moves_inside_the_limits():
    """A theta3/theta6 continuum whose solver representative would be outside Table I
    (theta3 = 170 deg) still returns a member inside it, at the end of the interval."""
    q = np.array([0.4, -0.3, np.radians(170.0), 0.0, 0.0, -0.2])
    T = iik.fk(q)
    r = iik.solve(T)
    rows = [i for i, f in enumerate(r.free_joints) if f == (3, 6)]
    assert rows and all(r.within_limits[i] for i in rows)
    for i in rows:
        (c,) = r.continua[i]
        assert c.interval[0] - 1e-12 <= r.q[i, 2] <= c.interval[1] + 1e-12
        assert np.allclose(iik.fk(r.q[i]), T, atol=1e-10)


def test_theta1_theta6_continuum_is_resolved():
    """Tool point on the joint-1 axis and z6 vertical: joints 1 and 6 collinear."""
    from scipy.optimize import least_squares

    def f(x):
        q = np.array([0, x[0], 0, x[1], x[2], 0])
        return [*iik.fk(q)[:2, 3], *iik.fk(q)[:2, 2]]

    x = least_squares(f, [0.5, -2.0, 0.5], xtol=1e-15, ftol=1e-15, gtol=1e-15).x
    q = np.array([0.0, x[0], 0.0, x[1], x[2], 0.3])
    T = iik.fk(q)
    T[:2, 3] = 0.0  # exactly on the axis, z6 exactly vertical
    T[:3, 2] = [0.0, 0.0, np.sign(T[2, 2])]
    T[:3, :3] = np.linalg.svd(T[:3, :3])[0] @ np.linalg.svd(T[:3, :3])[2]
    r = iik.solve(T, within_limits=False)
    rows = [i for i, fj in enumerate(r.free_joints) if 1 in fj]
    assert rows, r.free_joints
    for i in rows:
        c = next(c for c in r.continua[i] if c.free_joint == 1)
        assert c.fixed in ("theta1 - theta6", "theta1 + theta6")
        for th in (-1.0, 0.5, 2.0):
            assert np.allclose(iik.fk(c.member(th)), T, atol=1e-9)


@pytest.mark.parametrize("method", ["complete", "reference", "thesis"])
@pytest.mark.parametrize("position", [[1e308, 0.0, 0.0], [-1e308, 1e308, 1e308], [0.0, 0.0, 1e200],
                                      [1.3, 0.0, 0.3]])
def test_pose_beyond_any_reach_is_unreachable_without_warnings(method, position):
    T = np.eye(4)
    T[:3, 3] = position
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an overflow inside would raise here
        r = iik.solve(T, method=method)
        reachable = iik.fk(np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0]))
        many = iik.solve_many(np.stack([T, reachable]), method=method)
    assert r.count == 0 and r.reason.startswith("unreachable")
    assert many[0].count == 0 and many[1].count > 0


def test_reach_bound_bounds_the_tool_point():
    """The guard's bound: no q (not even outside Table I) puts the tool point beyond it, and it is
    not loose by more than the link offsets that cannot line up (here 9 %)."""
    q = np.random.default_rng(7).uniform(-np.pi, np.pi, size=(200_000, 6))
    far = np.max(np.linalg.norm(iik.fk(q)[:, :3, 3], axis=1))
    bound = iik.kinematics.reach_bound()
    assert far <= bound <= 1.1 * far
