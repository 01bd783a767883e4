"""The crossings of the two conditions' curves (iik.ik.crossings): every solution (theta1, theta2)
of two conditions built to vanish there is found, and each crossing returned solves both."""

from __future__ import annotations

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

from iik.ik.crossings import CROSSING_REACH, cluster_crossings

_ANGLE = st.floats(-3.0, 3.0)


def _conditions(x, t1, t2):
    """(G1, G2) of coefficients x (6, 3) at (t1, t2), written out from the module's docstring."""
    v = x[:, :1] + x[:, 1:2] * np.cos(t1) + x[:, 2:] * np.sin(t1)  # a, b, c, P, Q, R
    a, b, c, P, Q, R = v
    return R + P * np.cos(t2) + Q * np.sin(t2), a + b * np.cos(t2) + c * np.sin(t2)


def _vanishing_at(seed, t1, t2):
    """Random coefficients (6, 3) whose conditions both vanish at (t1, t2)."""
    x = np.random.default_rng(seed).normal(size=(6, 3))
    g1, g2 = _conditions(x, np.array([t1]), np.array([t2]))
    x[5, 0] -= g1[0]
    x[0, 0] -= g2[0]
    return x


@settings()
@given(seed=st.integers(0, 2**32 - 1), t1=_ANGLE, t2=_ANGLE)
@example(seed=62, t1=-0.3096221439330944, t2=-0.7938025818599606)  # beside a fold of G2
@example(seed=310, t1=2.136049827666966, t2=-0.4041926357296086)  # a second crossing 2e-3 away
@example(seed=1602, t1=-2.062490272753805, t2=-2.929294017913545)  # on an island 3e-3 wide
@example(seed=1000070, t1=-0.4995496011313856, t2=1.0820506982767846)  # an island 1.9e-3 wide
def test_a_solution_inside_the_window_is_found_and_every_crossing_solves_both(seed, t1, t2):
    """Found: also beside a fold, two crossings within one grid step, on an island of real
    theta1 narrower than the grid. The examples were missed by versions without the folds in
    the grid (seeds 62, 1602), without the dips (310, 1602), or with the folds but not the
    angles beside them (1000070: the quartic's roots err to the side without a real theta1)."""
    x = _vanishing_at(seed, t1, t2)
    a, b = cluster_crossings(x, t1 - 1e-4, t1 + 1e-4)
    g1, g2 = _conditions(x, a, b)
    assert np.all(np.abs(g1) <= 1e-9 * np.abs(x).max()) and np.all(np.abs(g2) <= 1e-9 * np.abs(x).max())
    assert np.all(np.abs(a - t1) <= 1e-4 + CROSSING_REACH + 1e-12)
    hit = np.hypot(a - t1, np.angle(np.exp(1j * (b - t2))))
    assert len(hit) and hit.min() <= 1e-6, (a, b, t1, t2)


def test_exactly_the_solutions_inside_the_window_are_returned():
    """G1 = cos theta1 + sin theta2, G2 = sin theta1 + 2 cos theta2 - 1: sin theta1 = 1/3 (a
    simple root each side) or -1 (a tangency); solved at theta1 = asin(1/3) and pi - asin(1/3),
    with sin theta2 = -cos theta1, cos theta2 = 1/3, and at (-pi/2, 0)."""
    x = np.zeros((6, 3))
    x[5] = [0.0, 1.0, 0.0]  # R = cos theta1
    x[4, 0] = 1.0  # Q
    x[0] = [-1.0, 0.0, 1.0]  # a = sin theta1 - 1
    x[1, 0] = 2.0  # b
    for t1 in (np.arcsin(1 / 3), np.pi - np.arcsin(1 / 3)):
        a, b = cluster_crossings(x, t1 - 1e-5, t1 + 1e-5)
        t2 = np.arctan2(-np.cos(t1), 1 / 3)
        assert len(a) == 1 and abs(a[0] - t1) <= 1e-12 and abs(b[0] - t2) <= 1e-9, (a, b, t1, t2)
    for t1 in (-1.0, 0.0, 1.0, 2.0, np.pi):  # no solution within CROSSING_REACH of these
        assert len(cluster_crossings(x, t1, t1)[0]) == 0
