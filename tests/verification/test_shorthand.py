"""verification.shorthand: the thesis's c1, s1 notation."""

from __future__ import annotations

import numpy as np

from verification.shorthand import cos_sin


def test_cos_sin_pairs_each_angle_in_order():
    q = np.array([0.1, -2.0])
    c1, s1, c2, s2 = cos_sin(0.3, q)
    assert (c1, s1) == (np.cos(0.3), np.sin(0.3))
    assert np.array_equal(c2, np.cos(q)) and np.array_equal(s2, np.sin(q))
    assert cos_sin() == ()
