"""Eq 54 effort index, selection and path following."""

import numpy as np
import pytest

import iik
from iik import THESIS_ARM
from iik.errors import InvalidInputError, UnreachablePoseError
from iik.ik.selection import branch_signature


def test_effort_index_eq54():
    a = np.zeros(6)
    b = np.array([0.6, -0.6, 0.0, 0.0, 0.0, 1.2])
    assert iik.effort_index(a, b) == pytest.approx(2.4 / 6)
    assert np.allclose(iik.effort_index(a, np.stack([a, b])), [0.0, 0.4])
    # not wrapped: joint 6 from +179 deg to -179 deg is a 358 deg move
    c = np.array([0, 0, 0, 0, 0, np.radians(179)])
    assert iik.effort_index(c, -c) == pytest.approx(np.radians(358) / 6)
    with pytest.raises(InvalidInputError):
        iik.effort_index(np.zeros(5), b)


def test_select_picks_generating_q_from_itself():
    q = np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0])
    r = iik.solve(iik.fk(q, THESIS_ARM), THESIS_ARM)
    assert np.allclose(iik.select(r, q, arm=THESIS_ARM), q, atol=1e-9)
    other = r.q[np.argmax(iik.effort_index(q, r.q))]
    assert np.allclose(iik.select(r, other, arm=THESIS_ARM), other)


def test_select_respects_limits_and_empty():
    cand = np.array([[3.0, 0, 0, 0, 0, 0], [0.1, 0, 0, 0, 0, 0]])  # 3.0 rad > 160 deg
    assert np.allclose(iik.select(cand, np.array([3.0, 0, 0, 0, 0, 0]), arm=THESIS_ARM), cand[1])
    T = np.eye(4)
    T[:3, 3] = [5, 0, 0]
    with pytest.raises(UnreachablePoseError):
        iik.select(iik.solve(T, THESIS_ARM), np.zeros(6), arm=THESIS_ARM)


def test_follow_path_keeps_branch_on_smooth_path():
    q0 = np.array([0.2, -0.4, 0.5, 0.9, -0.5, 0.3])
    qs = q0 + np.linspace(0, 1, 40)[:, None] * np.array([0.3, 0.2, -0.2, 0.1, 0.2, 0.5])
    path = iik.follow_path(iik.fk(qs, THESIS_ARM), q0, arm=THESIS_ARM)
    assert np.all(path.ok)
    assert np.allclose(path.q, qs, atol=1e-8)
    assert path.switches == ()
    assert np.all(branch_signature(path.q) == branch_signature(q0)[0])


def test_follow_path_reports_switch():
    q0 = np.array([0.2, -0.4, 0.5, 0.9, -0.5, 0.3])
    qs = np.stack([q0, q0, q0])
    start = q0 * np.array([1, 1, 1, -1, -1, 1]) + np.array([0, 0, np.pi, 0, 0, 0])
    path = iik.follow_path(iik.fk(qs, THESIS_ARM), start, arm=THESIS_ARM)
    assert path.switches[0] == 0
