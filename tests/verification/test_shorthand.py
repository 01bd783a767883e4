"""verification.shorthand: the thesis's c1, s1 notation."""

from __future__ import annotations

import numpy as np

from verification.shorthand import cos_sin, wrap


def test_cos_sin_pairs_each_angle_in_order():
    q = np.array([0.1, -2.0])
    c1, s1, c2, s2 = cos_sin(0.3, q)
    assert (c1, s1) == (np.cos(0.3), np.sin(0.3))
    assert np.array_equal(c2, np.cos(q)) and np.array_equal(s2, np.sin(q))
    assert cos_sin() == ()


def test_wrap_keeps_angles_within_one_turn():
    a = np.array([-np.pi, 0.5, np.pi, 3 * np.pi + 0.25, -7.0])
    w = wrap(a)
    assert np.all((w > -np.pi) & (w <= np.pi))  # the project's one convention, (-pi, pi]
    assert np.allclose(np.cos(w), np.cos(a)) and np.allclose(np.sin(w), np.sin(a))


def test_wrap_is_the_projects_one_wrap():
    from iik.ik.angles import wrap_angle

    assert wrap is wrap_angle
