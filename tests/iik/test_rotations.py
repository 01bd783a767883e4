"""iik.rotations: the corrected Eq 42 (Craig's Z-Y-Z), its inverse, batching and typed errors."""

import math
import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

import iik
from iik import InvalidInputError
from iik.rotations import euler_from_matrix, euler_matrix, pose_from_euler

ang = st.floats(-math.pi, math.pi, allow_nan=False)
polar = st.floats(1e-3, math.pi - 1e-3, allow_nan=False)


def _rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def _ry(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1.0, 0], [-s, 0, c]])


@given(ang, ang, ang)
def test_matrix_is_rz_ry_rz(a, b, g):
    np.testing.assert_allclose(euler_matrix(a, b, g), _rz(a) @ _ry(b) @ _rz(g), atol=1e-14)


@given(ang, ang, ang)
def test_corrected_eq42_entries(a, b, g):
    """Every entry of Eq 42 as printed except r21, which is corrected."""
    R = euler_matrix(a, b, g)
    ca, sa, cb, sb = math.cos(a), math.sin(a), math.cos(b), math.sin(b)
    cg, sg = math.cos(g), math.sin(g)
    expect = [[ca * cb * cg - sa * sg, -ca * cb * sg - sa * cg, ca * sb],
              [sa * cb * cg + ca * sg, -sa * cb * sg + ca * cg, sa * sb],
              [-sb * cg, sb * sg, cb]]
    np.testing.assert_allclose(R, expect, atol=1e-14)


@given(ang, polar, ang)
def test_round_trip(a, b, g):
    e = euler_from_matrix(euler_matrix(a, b, g))
    np.testing.assert_allclose(euler_matrix(*e), euler_matrix(a, b, g), atol=1e-12)
    assert 0 <= e[1] <= math.pi
    d = np.asarray(e) - [a, b, g]
    np.testing.assert_allclose(np.arctan2(np.sin(d), np.cos(d)), 0.0, atol=1e-9)  # -pi and pi are one angle


def test_gimbal_lock_gives_gamma_zero_and_same_matrix():
    R = euler_matrix(0.4, 0.0, 0.3)
    e = euler_from_matrix(R)
    assert e[2] == 0.0
    np.testing.assert_allclose(euler_matrix(*e), R, atol=1e-14)


@given(st.lists(st.tuples(ang, ang, ang), min_size=1, max_size=6))
def test_batch_equals_loop(triples):
    a, b, g = (np.array(x) for x in zip(*triples, strict=True))
    batch = euler_matrix(a, b, g)
    assert batch.shape == (len(triples), 3, 3)
    np.testing.assert_array_equal(batch, np.stack([euler_matrix(*t) for t in triples]))
    np.testing.assert_allclose(euler_from_matrix(batch),
                               np.stack([euler_from_matrix(m) for m in batch]), atol=0)


def test_pose_from_euler():
    T = pose_from_euler([0.1, 0.2, 0.3], 0.1, 0.2, 0.3)
    np.testing.assert_array_equal(T[:3, 3], [0.1, 0.2, 0.3])
    np.testing.assert_array_equal(T[:3, :3], euler_matrix(0.1, 0.2, 0.3))
    assert pose_from_euler([[0, 0, 0]] * 3, [0.1, 0.2, 0.3], 0, 0).shape == (3, 4, 4)
    with pytest.raises(InvalidInputError):
        pose_from_euler([[0, 0, 0]] * 3, [0.1, 0.2], 0, 0)


@pytest.mark.parametrize("args,arg", [
    ((math.nan, 0, 0), "alpha"), ((0, math.inf, 0), "beta"), ((0, 0, "x"), "gamma"),
    ((np.zeros((2, 2)), 0, 0), "alpha"), ((np.zeros(2), np.zeros(3), 0), "alpha/beta/gamma"),
])
def test_bad_angles(args, arg):
    with pytest.raises(InvalidInputError) as exc:
        euler_matrix(*args)
    assert exc.value.argument == arg


@pytest.mark.parametrize("R", [np.eye(4), np.ones((3, 3)), np.diag([1.0, 1.0, -1.0]),
                               np.full((3, 3), np.nan), "I", np.zeros((2, 3))])
def test_bad_matrix(R):
    with pytest.raises(InvalidInputError) as exc:
        euler_from_matrix(R)
    assert exc.value.argument == "R"


def test_zyz_is_not_zxz():
    """The corrected Eq 42 is scipy's 'ZYZ'; its 'ZXZ' for (30, 40, 50) deg is 56 deg away."""
    a = np.radians([30.0, 40.0, 50.0])
    zyz = Rotation.from_euler("ZYZ", a).as_matrix()
    np.testing.assert_allclose(euler_matrix(*a), zyz, atol=1e-15)
    assert math.degrees(iik.rotation_angle(euler_matrix(*a), Rotation.from_euler("ZXZ", a).as_matrix())) > 55
    np.testing.assert_allclose(euler_matrix(*a, convention="ZXZ"), Rotation.from_euler("ZXZ", a).as_matrix(),
                               atol=1e-15)  # real Z-X-Z data can be read too
    np.testing.assert_allclose(euler_from_matrix(zyz, convention="ZYZ"), a, atol=1e-12)
    for bad in ("ZZY", "zyx ", "ZyZ", 3, "ZY"):
        with pytest.raises(InvalidInputError) as info:
            euler_matrix(*a, convention=bad)
        assert info.value.argument == "convention"


@pytest.mark.parametrize(("old", "new", "args"), [
    ("zxz_matrix", "euler_matrix", (0.1, 0.2, 0.3)),
    ("zxz_from_matrix", "euler_from_matrix", (euler_matrix(0.1, 0.2, 0.3),)),
    ("pose_from_zxz", "pose_from_euler", ([0.4, 0.3, 0.2], 0.1, 0.2, 0.3)),
])
def test_the_old_zxz_names_are_deprecated_aliases_that_warn(old, new, args):
    with pytest.warns(DeprecationWarning, match=f"iik.{old} is deprecated: .* is Z-Y-Z .*use iik.{new}"):
        got = getattr(iik, old)(*args)
    np.testing.assert_array_equal(got, getattr(iik, new)(*args))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        getattr(iik, new)(*args)  # the new names do not warn
