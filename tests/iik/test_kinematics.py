"""iik.kinematics: Eq 4 vs an independent Table II product, Jacobians vs finite differences,
batch == loop, and typed errors on bad input."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import iik
from iik import THESIS_ARM, InvalidInputError
from verification.testing.strategies import joint_batches, joint_vectors

ARM = iik.THESIS_ARM


def _rotx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _rotz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _tr(x=0.0, z=0.0):
    T = np.eye(4)
    T[0, 3], T[2, 3] = x, z
    return T


def table_ii_fk(q):
    """Independent Table II (Craig: RotX(alpha) TransX(a) RotZ(theta) TransZ(d)), written here."""
    l1, l2, l3, l4, l5 = ARM.l1, ARM.l2, ARM.l3, ARM.l4, ARM.l5
    h = math.pi / 2
    rows = [(0, 0, l1, q[0]), (-h, l2, 0, q[1] - h), (-h, 0, l3, q[2]),
            (-h, 0, 0, q[3] - h), (0, l4, 0, q[4] + h), (-h, 0, -l5, q[5])]
    T = np.eye(4)
    for alpha, a, d, theta in rows:
        T = T @ _rotx(alpha) @ _tr(x=a) @ _rotz(theta) @ _tr(z=d)
    return T


@given(joint_vectors())
def test_fk_matches_independent_table_ii(q):
    T = iik.fk(q, THESIS_ARM)
    ref = table_ii_fk(q)
    assert np.abs(T[:3, 3] - ref[:3, 3]).max() <= 1e-12
    assert np.abs(T[:3, :3] - ref[:3, :3]).max() <= 1e-12
    np.testing.assert_array_equal(T[3], [0, 0, 0, 1])


@given(joint_vectors())
def test_fk_chain_matches_fk(q):
    assert np.abs(iik.fk_chain(q, THESIS_ARM) - iik.fk(q, THESIS_ARM)).max() <= 1e-12


def test_home_pose_is_stretched_along_x():
    T = iik.fk(np.zeros(6), THESIS_ARM)
    np.testing.assert_allclose(T[:3, 3], [ARM.l2 + ARM.l3 + ARM.l4 + ARM.l5, 0, ARM.l1], atol=1e-15)


def _fd(f, q, h=1e-6):
    cols = []
    for i in range(6):
        dq = np.zeros(6)
        dq[i] = h
        cols.append((f(q + dq) - f(q - dq)) / (2 * h))
    return np.stack(cols, axis=-1)


@given(joint_vectors())
def test_position_jacobian_matches_finite_differences(q):
    J_fd = _fd(lambda x: table_ii_fk(x)[:3, 3], q)
    J = iik.position_jacobian(q, THESIS_ARM)
    assert J.shape == (3, 6)
    np.testing.assert_allclose(J, J_fd, atol=1e-8, rtol=0)
    np.testing.assert_allclose(J_fd[:, 5], 0.0, atol=1e-8)  # Eq 34: joint 6 does not move p


@given(joint_vectors())
def test_jacobian_matches_finite_differences(q):
    J = iik.jacobian(q, THESIS_ARM)
    assert J.shape == (6, 6)
    np.testing.assert_allclose(J[:3], _fd(lambda x: table_ii_fk(x)[:3, 3], q), atol=1e-8, rtol=0)
    # angular part: dR/dq_i R^T = [w_i]x
    R = table_ii_fk(q)[:3, :3]
    dR = _fd(lambda x: table_ii_fk(x)[:3, :3].ravel(), q).reshape(3, 3, 6)
    for i in range(6):
        W = dR[:, :, i] @ R.T
        w = np.array([W[2, 1], W[0, 2], W[1, 0]])
        np.testing.assert_allclose(J[3:, i], w, atol=1e-8, rtol=0)


@given(joint_batches())
def test_batch_equals_loop(qs):
    for f in (iik.fk, iik.fk_chain, iik.position_jacobian, iik.jacobian, iik.joint_frames):
        batch = f(qs, THESIS_ARM)
        loop = np.stack([f(q, THESIS_ARM) for q in qs])
        np.testing.assert_array_equal(batch, loop)


BAD = [
    (np.zeros(5), "shape"),
    (np.zeros((2, 7)), "shape"),
    (np.zeros((2, 3, 6)), "shape"),
    ([0, 0, 0, np.nan, 0, 0], "NaN"),
    ([0, 0, 0, np.inf, 0, 0], "NaN or inf"),
    ("0 0 0 0 0 0", "numbers"),
    (["a", "b", "c", "d", "e", "f"], "numeric"),
    ([[0, 0], [0, 0, 0]], "array"),
    (None, "numeric"),
    ([0, 0, 0, 0, 0, 1j], "complex"),
]


@pytest.mark.parametrize("f", [iik.fk, iik.fk_chain, iik.position_jacobian, iik.jacobian])
@pytest.mark.parametrize("bad,word", BAD)
def test_bad_input_is_a_typed_error_naming_q(f, bad, word):
    with pytest.raises(InvalidInputError) as exc:
        f(bad, THESIS_ARM)
    assert exc.value.argument == "q"
    assert isinstance(exc.value, iik.IIKError)


@given(st.integers(0, 5), st.sampled_from([np.nan, np.inf, -np.inf]))
def test_any_non_finite_entry_is_rejected(i, v):
    q = np.zeros(6)
    q[i] = v
    with pytest.raises(InvalidInputError, match="NaN or inf"):
        iik.fk(q, THESIS_ARM)


@given(joint_batches())
def test_compiled_closed_forms_equal_the_same_formulas_run_by_numpy(qs):
    """iik.fk runs the Eq 4 closed forms compiled (one q or a batch); the same functions
    evaluated by NumPy on arrays agree to rounding (sin/cos implementations differ)."""
    from iik.kinematics import eq4_position, eq4_rotation, eq4_terms, eq4_wrist_axes

    c, s = np.cos(qs).T, np.sin(qs).T
    c45, s45 = np.cos(qs[:, 3] + qs[:, 4]), np.sin(qs[:, 3] + qs[:, 4])
    A, B, W, V = eq4_terms(c[0], s[0], c[1], s[1], c[2], s[2], c[3], s[3], c45, s45, ARM.l4, ARM.l5)
    X1, X2, X3, Y1, Y2, Y3, Z1, Z2, Z3 = eq4_wrist_axes(c[0], s[0], c[1], s[1], c[2], s[2], c45, s45, A, B)
    r11, r21, r31, r12, r22, r32 = eq4_rotation(c[5], s[5], X1, X2, X3, Y1, Y2, Y3)
    p = eq4_position(c[0], s[0], c[1], s[1], c[2], A, B, W, V, ARM.l1, ARM.l2, ARM.l3)
    T = iik.fk(qs, THESIS_ARM)
    np.testing.assert_allclose(T[:, :3, 3], np.stack(p, axis=1), atol=1e-15)
    R = np.stack([np.stack([r11, r12, Z1], 1), np.stack([r21, r22, Z2], 1), np.stack([r31, r32, Z3], 1)], 1)
    np.testing.assert_allclose(T[:, :3, :3], R, atol=1e-15)


def test_one_q_fast_path_accepts_any_layout_and_dtype():
    q = np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0])
    T = iik.fk(q, THESIS_ARM)
    strided = np.zeros(12)
    strided[::2] = q
    for variant in (strided[::2], list(q), tuple(q), q.reshape(1, 6)[0]):
        np.testing.assert_array_equal(iik.fk(variant, THESIS_ARM), T)
    assert np.abs(iik.fk(q.astype(np.float32), THESIS_ARM) - T).max() < 1e-6
    np.testing.assert_array_equal(iik.jacobian(strided[::2], THESIS_ARM), iik.jacobian(q, THESIS_ARM))
