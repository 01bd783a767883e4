"""Eq 54 in its three forms and branch switches (iik.joint_path)."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

import iik
from iik.joint_path import effort_matrix, path_effort

joints = st.lists(st.floats(-3.0, 3.0, allow_nan=False), min_size=6, max_size=6)


@given(st.lists(joints, min_size=1, max_size=5), st.lists(joints, min_size=1, max_size=5))
def test_effort_matrix_is_eq54_for_every_pair(qa, qb):
    A, B = np.array(qa), np.array(qb)
    E = effort_matrix(A, B)
    assert E.shape == (len(A), len(B))
    for i, a in enumerate(A):
        assert np.array_equal(E[i], iik.effort_index(a, B))  # the same formula, bit for bit
        for j, b in enumerate(B):
            assert E[i, j] == np.sum(np.abs(b - a)) / 6  # Eq 54


@given(st.lists(joints, min_size=2, max_size=8))
def test_path_effort_is_eq54_step_by_step(qs):
    Q = np.array(qs)
    E = path_effort(Q)
    steps = [effort_matrix(Q[i - 1], Q[i])[0, 0] for i in range(1, len(Q))]
    assert E[0] == 0 and np.array_equal(E[1:], steps)
