"""Tests of iik.solve / iik.solve_many (complete method): recovery, the issue's examples,
continua, certificates, unreachable poses and bad input."""

import warnings

import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

import iik
from iik import THESIS_ARM
from iik.errors import IIKError, InvalidInputError
from iik.ik.angles import wrap_angle as _wrap
from iik.ik.layout import MAX_SOLUTIONS
from verification.testing.completeness import contains

ARM = iik.THESIS_ARM
LO, HI = ARM.q_min, ARM.q_max
TOL = 1e-10


def _q_in_limits(draw):
    return np.array([draw(st.floats(float(LO[j]), float(HI[j]), allow_nan=False)) for j in range(6)])


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
    T = iik.fk(q, ARM)
    r = iik.solve(T, ARM, within_limits=False)
    assert r.count >= 1, r.reason
    assert np.all(r.position_residual <= TOL) and np.all(r.rotation_residual <= TOL)
    assert contains(r, q, T, ARM), (q, r.q)
    assert r.certificate.certified, r.certificate
    # within the limits the generating q survives the limit filter too (unless it sits on a stop)
    if np.min(np.minimum(q - LO, HI - q)) > 1e-6:
        assert contains(iik.solve(T, ARM), q, T, ARM)


# CI's failing case: near the collinear continuum, two rows with the same theta3 on different
# branches were taken for one tube of the numerical continuum and q* was dropped
@given(joints())
@example(np.array([0.0, 0.0, 0.0, 0.00010450465573719843, 0.0, 0.0]))
def test_recovers_generating_q(q):
    _check_recovers(q)


@given(near_singular())
def test_recovers_generating_q_near_singularities(q):
    _check_recovers(q)


def test_uniform_poses_take_the_double_path_and_are_certified():
    q = np.random.default_rng(11).uniform(LO, HI, size=(300, 6))
    T = iik.fk(q, ARM)
    res = iik.solve_many(T, ARM, within_limits=False)
    assert sum(r.certificate.path == "double" for r in res) >= 290
    for qi, r in zip(q, res, strict=True):
        assert r.certificate.certified and r.certificate.roots >= 1
        assert np.min(np.max(np.abs(_wrap(r.q - qi)), axis=1)) <= 1e-9  # strict, away from singularities
    assert all(2 * r.certificate.roots >= r.count for r in res)  # at most two rows per root


def test_solve_many_identical_to_solve():
    q = np.random.default_rng(3).uniform(LO, HI, size=(20, 6))
    T = iik.fk(q, ARM)
    many = iik.solve_many(T, ARM)
    for Ti, rm in zip(T, many, strict=True):
        r1 = iik.solve(Ti, ARM)
        assert np.array_equal(r1.q, rm.q) and r1.free_joints == rm.free_joints
        assert r1.certificate == rm.certificate


def test_deterministic_order():
    T = iik.fk(np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0]), ARM)
    r = iik.solve(T, ARM, within_limits=False)
    keys = [tuple(np.round(row, 9)) for row in r.q]
    assert keys == sorted(keys)


def test_result_is_frozen():
    r = iik.solve(iik.fk(np.zeros(6), ARM), ARM)
    with pytest.raises(ValueError):
        r.q[0, 0] = 1.0
    with pytest.raises(AttributeError):
        r.reason = "x"  # type: ignore[misc]


def test_rows_keeps_the_chosen_rows_of_every_per_row_field_in_order():
    r = iik.solve(iik.fk(np.array([0.3, -0.4, 0.5, 0.6, -0.7, 0.8]), ARM), ARM, within_limits=False)
    assert r.count >= 3
    sub = r.rows([2, 0])
    assert np.array_equal(sub.q, r.q[[2, 0]]) and sub.count == 2
    assert np.array_equal(sub.position_residual, r.position_residual[[2, 0]])
    assert np.array_equal(sub.within_limits, r.within_limits[[2, 0]])
    assert sub.free_joints == (r.free_joints[2], r.free_joints[0]) and sub.certificate == r.certificate
    mask = np.arange(r.count) != 1
    assert np.array_equal(r.rows(mask).q, r.q[mask]) and not r.rows(mask).q.flags.writeable


# ----------------------------------------------------------------------------- the issue's examples
EXAMPLE_THETA3 = [-1.4720058155065561, 0.87525106835483468, -2.6193481295067045e-07, -1.2350860980201843,
                  0.066116570625837756, 0.68674543598878923]
EXAMPLE_SINGULAR = [-0.098174782244782932, 0.039604219328399193, 1.5750793151239346, 1.3333398842778665,
                    -0.91264444006942114, 2.7605280164597836]
EXAMPLE_AXIS = [-2.5774765430748188, -1.8104375170509364, 2.7241642724654964, 0, -0.7860412576212541,
                0.068340130819575684]


@pytest.mark.parametrize("q", [EXAMPLE_THETA3, EXAMPLE_SINGULAR])
def test_issue_examples_return_the_generating_q_within_the_default_limits(q):
    q = np.array(q)
    assert ARM.within_limits(q)
    T = iik.fk(q, ARM)
    r = iik.solve(T, ARM)
    assert contains(r, q, T, ARM), (r.q, r.reason)
    assert np.min(np.max(np.abs(_wrap(r.q - q)), axis=1)) <= 1e-6


def test_issue_example_axis_continuum_is_flagged_with_joint1_and_its_interval():
    """theta4 = 0 with the wrist centre on the joint-1 axis: every theta1 is a solution."""
    q = np.array(EXAMPLE_AXIS)
    T = iik.fk(q, ARM)
    r = iik.solve(T, ARM)
    assert r.certificate.path == "degenerate"
    rows = [i for i, fj in enumerate(r.free_joints) if 1 in fj]
    assert rows
    for i in rows:
        (c,) = r.continua[i]
        assert c.kind == "theta1" and c.free_joint == 1
        lo, hi = c.interval
        assert lo < r.q[i, 0] + 1e-9 and r.q[i, 0] < hi + 1e-9 and hi - lo > 1.0
        for th in np.linspace(lo, hi, 5):
            m = c.member(th)
            assert ARM.within_limits(m, tol=1e-6)
            assert np.allclose(iik.fk(m, ARM), T, atol=1e-9)
    assert contains(r, q, T, ARM)


@pytest.mark.parametrize("distance", [0.0, 1e-9, 1e-7, 1e-6])
def test_issue_item5_tool_point_at_the_base_loses_nothing(distance):
    """Issue 17 item 5: a tool point within 1e-6 m of the base lost solutions in the kernel and
    the reference. Configurations with the tool point at ``distance`` from the base origin
    (found by least squares from three starts): both methods return each generating q."""
    from scipy.optimize import least_squares

    rng = np.random.default_rng(17)
    for _ in range(3):
        d = rng.normal(size=3)
        d *= distance / np.linalg.norm(d)
        fit = least_squares(lambda x, d=d: iik.fk(x, ARM)[:3, 3] - d, rng.uniform(LO, HI), xtol=1e-15,
                            ftol=1e-15, gtol=1e-15)
        q = fit.x
        T = iik.fk(q, ARM)
        assert abs(np.linalg.norm(T[:3, 3]) - distance) <= 1e-12
        for method in ("complete", "reference"):
            r = iik.solve(T, ARM, method=method, within_limits=False)
            assert contains(r, q, T, ARM), (method, q.tolist(), r.q)


# ----------------------------------------------------------------------------- continua
def test_collinear_continuum_inside_table_i_with_its_interval():
    """theta4 = theta5 = 0 inside Table I: one row for the continuum, inside Table I; the fixed
    combination is theta3 - theta6 and every member of the interval reaches the pose."""
    q = np.array([0.98902373, 0.75632699, 0.01209722, 0.0, 0.0, 0.96039359])
    T = iik.fk(q, ARM)
    r = iik.solve(T, ARM)
    assert r.count >= 1 and np.all(r.within_limits)
    i = r.free_joints.index((3, 6))
    (c,) = r.continua[i]
    assert c.kind == "collinear" and (c.free_joint, c.coupled_joint) == (3, 6)
    assert c.fixed == "theta3 - theta6"
    assert c.value == pytest.approx(_wrap(q[2] - q[5]), abs=1e-9)
    assert c.interval == pytest.approx((LO[2], HI[2]))  # joint 6 spans a full turn
    for th in np.linspace(*c.interval, 7):
        m = c.member(th)
        assert ARM.within_limits(m) and np.allclose(iik.fk(m, ARM), T, atol=1e-10)
    assert contains(r, q, T, ARM)


def test_continuum_representative_moves_inside_the_limits():
    """theta3 = 170 deg on the collinear continuum: the row returned is a member inside Table I."""
    q = np.array([0.4, -0.3, np.radians(170.0), 0.0, 0.0, -0.2])
    T = iik.fk(q, ARM)
    r = iik.solve(T, ARM)
    rows = [i for i, f in enumerate(r.free_joints) if f == (3, 6)]
    assert rows and all(r.within_limits[i] for i in rows)
    for i in rows:
        (c,) = r.continua[i]
        assert c.interval[0] - 1e-12 <= r.q[i, 2] <= c.interval[1] + 1e-12
        assert np.allclose(iik.fk(r.q[i], ARM), T, atol=1e-10)


def test_near_continuum_tube_is_one_numerical_continuum_containing_the_generating_q():
    """theta4 = 1e-7, theta5 = -1e-7: the configurations within the tolerance form a tube around
    the broken theta3 circle; one row per tube, flagged numerical, whose members reach the pose."""
    q = np.array([0.6, 0.4, 1.2, 1e-7, -1e-7, -0.7])
    T = iik.fk(q, ARM)
    r = iik.solve(T, ARM, within_limits=False)
    kinds = [c.kind for cs in r.continua for c in cs]
    assert "numerical" in kinds or "collinear" in kinds
    assert r.count <= 4  # no pile of near-duplicate rows
    assert contains(r, q, T, ARM)
    c = next(c for cs in r.continua for c in cs)
    for th in (q[2] - 0.3, q[2], q[2] + 0.3):
        m = c.member(th)
        assert np.linalg.norm(iik.fk(m, ARM)[:3, 3] - T[:3, 3]) <= 1e-9


def test_exact_singular_poses_inside_table_i_have_a_solution_inside_table_i():
    rng = np.random.default_rng(21)
    fixes = ({3: 0.0, 4: 0.0}, {3: 0.0}, {4: 0.0}, {2: np.pi / 2}, {2: -np.pi / 2}, {0: HI[0]}, {0: LO[0]})
    for fix in fixes:
        q = rng.uniform(LO, HI, size=(60, 6))
        for j, val in fix.items():
            q[:, j] = val
        for qi, r in zip(q, iik.solve_many(iik.fk(q, ARM), ARM), strict=True):
            assert r.count >= 1 and not r.is_approximate, (qi, r.reason)
            assert ARM.within_limits(r.q).all()


def test_theta1_theta6_continuum_is_resolved():
    """Tool point on the joint-1 axis and z6 vertical: joints 1 and 6 collinear (theta1 free)."""
    from scipy.optimize import least_squares

    def f(x):
        q = np.array([0, x[0], 0, x[1], x[2], 0])
        T = iik.fk(q, ARM)
        return [*T[:2, 3], *T[:2, 2]]

    x = least_squares(f, [0.5, -2.0, 0.5], xtol=1e-15, ftol=1e-15, gtol=1e-15).x
    q = np.array([0.0, x[0], 0.0, x[1], x[2], 0.3])
    T = iik.fk(q, ARM)
    r = iik.solve(T, ARM, within_limits=False)
    rows = [i for i, fj in enumerate(r.free_joints) if 1 in fj]
    assert rows, r.free_joints
    for i in rows:
        (c,) = r.continua[i]
        for th in (-1.0, 0.5, 2.0):
            assert np.allclose(iik.fk(c.member(th), ARM), T, atol=1e-9)
    assert contains(r, q, T, ARM)


def test_clustered_candidates_are_deduplicated_not_truncated():
    """theta3 ~ 90 deg with theta4 ~ 90 deg: many clustered candidates; the generating q survives."""
    q = np.array([2.507781185021448, 1.4742098351302193, 1.5707963268300342,
                  1.567367861137023, -1.0916596700323127, 1.8143558774026767])
    T = iik.fk(q, ARM)
    r = iik.solve(T, ARM, within_limits=False)
    assert r.count < MAX_SOLUTIONS
    assert contains(r, q, T, ARM)


def test_unreachable_pose_gives_reason():
    T = np.eye(4)
    T[:3, 3] = [5.0, 0.0, 0.0]
    r = iik.solve(T, ARM)
    assert r.count == 0 and "unreachable" in r.reason
    assert r.q.shape == (0, 6)


def test_outside_limits_reason():
    q = np.array([np.pi, -0.4, 0.9, 0.8, -0.6, 1.2])
    r_all = iik.solve(iik.fk(q, ARM), ARM, within_limits=False)
    r = iik.solve(iik.fk(q, ARM), ARM)
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
        iik.solve(bad, THESIS_ARM)
    assert msg in str(e.value)
    assert isinstance(e.value, IIKError)


def test_batch_to_solve_and_bad_method():
    with pytest.raises(InvalidInputError):
        iik.solve(np.stack([np.eye(4)] * 2), THESIS_ARM)
    with pytest.raises(InvalidInputError):
        iik.solve(np.eye(4), THESIS_ARM, method="magic")


def test_pose_from_euler_round_trip():
    q = np.array([0.3, -0.2, 0.5, 0.7, -0.4, 0.9])
    T = iik.fk(q, ARM)
    a, b, g = iik.euler_from_matrix(T[:3, :3])
    T2 = iik.pose_from_euler(T[:3, 3], a, b, g)
    assert np.allclose(T, T2, atol=1e-12)
    assert contains(iik.solve(T2, ARM), q, T2, ARM)


@pytest.mark.parametrize("method", ["complete", "reference", "thesis"])
@pytest.mark.parametrize("position", [[1e308, 0.0, 0.0], [-1e308, 1e308, 1e308], [0.0, 0.0, 1e200],
                                      [1.3, 0.0, 0.3]])
def test_pose_beyond_any_reach_is_unreachable_without_warnings(method, position):
    T = np.eye(4)
    T[:3, 3] = position
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an overflow inside would raise here
        r = iik.solve(T, THESIS_ARM, method=method)
        reachable = iik.fk(np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0]), THESIS_ARM)
        many = iik.solve_many(np.stack([T, reachable]), THESIS_ARM, method=method)
    assert r.count == 0 and r.reason.startswith("unreachable")
    assert many[0].count == 0 and many[1].count > 0


def test_reach_bound_bounds_the_tool_point():
    """The guard's bound: no q (not even outside Table I) puts the tool point beyond it, and it is
    not loose by more than the link offsets that cannot line up (here 9 %)."""
    q = np.random.default_rng(7).uniform(-np.pi, np.pi, size=(200_000, 6))
    far = np.max(np.linalg.norm(iik.fk(q, THESIS_ARM)[:, :3, 3], axis=1))
    bound = ARM.reach
    assert far <= bound <= 1.1 * far
