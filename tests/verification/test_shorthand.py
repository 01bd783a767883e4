"""verification.shorthand: the thesis's c1, s1 notation."""

from __future__ import annotations

import numpy as np
import pytest

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


def test_evaluate_reads_a_product_as_printed():
    from verification.shorthand import evaluate

    s = {"l2": 2.0, "s1": 0.5, "c1": 0.25, "s45": 3.0}
    assert evaluate("-l2 s1 + (l2 s45)(c1 - s1)", s) == -2.0 * 0.5 + (2.0 * 3.0) * (0.25 - 0.5)
    assert evaluate("1.5 c1", s) == 1.5 * 0.25 and evaluate("0", s) == 0
    with pytest.raises(NameError):
        evaluate("l9 s1", s)
    with pytest.raises(ValueError, match="cannot read"):
        evaluate("s1 ** 2; x", s)


def test_matrix_broadcasts_the_printed_entries():
    from verification.shorthand import matrix

    c = np.array([1.0, 0.0])
    M = matrix("0_1T = [c1 -s1 0; s1 c1 l1] (note)", {"c1": c, "s1": 1 - c, "l1": 0.5})
    assert M.shape == (2, 2, 3) and np.array_equal(M[1], [[0, -1, 0], [1, 0, 0.5]])
    assert np.array_equal(matrix((("c1", "0"),), {"c1": 2.0}), [[2.0, 0.0]])
