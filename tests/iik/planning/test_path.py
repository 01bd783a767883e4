"""Path primitives of Sec 3.6.1 / 4.2.1.1 (iik.planning.path)."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from iik.errors import InvalidInputError
from iik.planning import path
from iik.rotations import euler_matrix

coord = st.floats(-1.0, 1.0)
point = st.tuples(coord, coord, coord).map(np.array)


@given(point, point)
def test_straight_steps_are_at_most_30mm_and_collinear(a, b):
    p = path.straight_steps(a, b)
    assert np.allclose(p[0], a) and np.allclose(p[-1], b)
    steps = np.linalg.norm(np.diff(p, axis=0), axis=1)
    assert steps.max() <= path.MAX_STEP + 1e-12
    # every point on the segment a-b
    d = b - a
    if np.linalg.norm(d) > 1e-9:
        r = np.cross(p - a, d) / np.linalg.norm(d)
        assert np.abs(r).max() < 1e-9


def test_fixed_count_of_39_steps():
    p = path.straight_steps([0, 0, 0], [0.9, 0.3, 0.1], n_steps=39)
    assert len(p) == 40
    assert np.allclose(np.diff(p, axis=0), np.diff(p, axis=0)[0])


@given(point, point)
def test_arc_keeps_radius_and_height_linear_in_azimuth(a, b):
    if np.hypot(*a[:2]) < 0.05 or np.hypot(*b[:2]) < 0.05:
        return
    p = path.arc_steps(a, b)
    assert np.allclose(p[0], a) and np.allclose(p[-1], b)
    assert np.linalg.norm(np.diff(p, axis=0), axis=1).max() <= path.MAX_STEP * 1.05
    phi = np.unwrap(np.arctan2(p[:, 1], p[:, 0]))
    r = np.hypot(p[:, 0], p[:, 1])
    s = (phi - phi[0]) / (phi[-1] - phi[0]) if abs(phi[-1] - phi[0]) > 1e-6 else None
    if s is not None:
        assert np.allclose(r, r[0] + s * (r[-1] - r[0]), atol=1e-9)
        assert np.allclose(p[:, 2], a[2] + s * (b[2] - a[2]), atol=1e-9)
    # never wraps through the joint-1 cut behind the arm (azimuth stays in (-pi, pi])
    assert np.all(np.abs(np.diff(phi)) < np.pi)


def test_orientation_euler_and_slerp_end_at_the_targets():
    e0, e1 = np.array([0.1, 0.2, 0.3]), np.array([1.0, 0.8, -0.5])
    E = path.interpolate_orientation(e0, e1, 11)
    assert np.allclose(E[0], e0) and np.allclose(E[-1], e1)
    assert np.allclose(np.diff(E, axis=0), (e1 - e0) / 10)
    R = path.interpolate_orientation(e0, e1, 11, method="slerp")
    assert np.allclose(R[0], euler_matrix(*e0)) and np.allclose(R[-1], euler_matrix(*e1))
    ang = [np.arccos(np.clip((np.trace(R[i].T @ R[i + 1]) - 1) / 2, -1, 1)) for i in range(10)]
    assert np.ptp(ang) < 1e-9  # constant rate


def test_lji_joint_interpolation_contains_keys_and_bounds_steps():
    keys = np.array([[0, 0, 0, 0, 0, 0], [0.5, -0.2, 0.1, 0, 0.3, 1.0], [0.4, 0, 0, 0, 0, 0]], float)
    q = path.interpolate_joints(keys, max_joint_step=0.05)
    assert np.abs(np.diff(q, axis=0)).max() <= 0.05 + 1e-12
    for k in keys:
        assert np.min(np.abs(q - k).max(axis=1)) < 1e-12


def test_densify_inserts_points_only_where_needed():
    p = np.array([[0, 0, 0], [0.01, 0, 0], [0.11, 0, 0]], float)
    d, src = path.densify(p, 0.03)
    assert np.linalg.norm(np.diff(d, axis=0), axis=1).max() <= 0.03 + 1e-12
    assert np.allclose(d[np.isclose(src, np.round(src))], p)


@pytest.mark.parametrize("bad", [[0, 0], [np.nan, 0, 0], "abc"])
def test_bad_points_are_named(bad):
    with pytest.raises(InvalidInputError, match="a"):
        path.straight_steps(bad, [0, 0, 0])


def test_bad_method_and_counts():
    with pytest.raises(InvalidInputError, match="method"):
        path.interpolate_orientation([0, 0, 0], [1, 1, 1], 3, method="lerp")
    with pytest.raises(InvalidInputError, match="n_steps"):
        path.straight_steps([0, 0, 0], [1, 0, 0], n_steps=0)


@given(point, point, st.sampled_from(["line", "arc"]), st.floats(0.005, 0.2),
       st.one_of(st.none(), st.integers(1, 50)))
def test_segment_steps_count_the_steps_without_making_them(a, b, route, max_step, n_steps):
    make = path.arc_steps if route == "arc" else path.straight_steps
    pts = make(a, b, max_step=max_step, n_steps=n_steps)
    assert path.segment_steps(a, b, route=route, max_step=max_step, n_steps=n_steps) == len(pts) - 1
    if route == "line":
        assert path.segment_length(a, b) == pytest.approx(path.path_length(pts), rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("make", [path.straight_steps, path.arc_steps])
@pytest.mark.parametrize("kw,argument", [({"max_step": 1e-7}, "max_step"), ({"max_step": 5e-324}, "max_step"),
                                         ({"n_steps": 10**6}, "n_steps")])
def test_step_primitives_refuse_unbounded_step_counts(make, kw, argument):
    with pytest.raises(InvalidInputError) as exc:
        make([0.3, 0.2, 0.1], [0.3, -0.2, 0.1], **kw)
    assert exc.value.argument == argument and "at most 4999" in exc.value.reason
    # counted, not made
    assert path.segment_steps([0.3, 0.2, 0.1], [0.3, -0.2, 0.1], max_step=5e-324) == 2**62
