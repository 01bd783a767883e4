"""Obstacles, the Eq 52-53 ellipsoid (corrected) and the Sec 3.6.2.2 repulsion."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from iik.errors import InvalidInputError
from iik.planning.obstacles import (
    SAFETY_ZONE,
    Box,
    ellipsoid_value,
    enclosing_radii,
    repel_points,
    repulsion_normal,
)
from iik.planning.path import straight_steps

dim = st.floats(0.02, 1.5)


@given(dim, dim, dim)
def test_corrected_ellipsoid_touches_every_corner(w, d, h):
    box = Box((0.1, -0.2, 0.3), (w, d, h))
    v = ellipsoid_value(box.corners, box.center, enclosing_radii(box))
    assert np.allclose(v, 1.0, atol=1e-12)
    # and contains the whole box: face centres and the centre are inside
    assert ellipsoid_value(np.array([box.center]), box.center, enclosing_radii(box))[0] == 0.0


@given(st.tuples(st.floats(-1, 1), st.floats(-1, 1), st.floats(-1, 1)),
       st.tuples(st.floats(-1, 1), st.floats(-1, 1), st.floats(-1, 1)))
def test_repulsion_normal_is_normal_to_the_plane_through_start_goal_and_x_infinity(s, g):
    s, g = np.array(s), np.array(g)
    n = repulsion_normal(s, g)
    assert np.isclose(np.linalg.norm(n), 1.0)
    assert n[2] >= 0
    d = g - s
    nd = np.linalg.norm(d)
    if np.linalg.norm(np.cross(d, [1, 0, 0])) > 1e-6 * max(nd, 1e-12) and nd > 1e-9:
        assert abs(n @ d) < 1e-9 * np.linalg.norm(d) + 1e-12
        assert abs(n[0]) < 1e-9  # contains the x direction


def test_repelled_points_are_outside_every_padded_ellipsoid():
    boxes = [Box((0.3, 0.0, 0.0), (0.1, 0.1, 0.2)), Box((0.3, 0.25, 0.05), (0.1, 0.1, 0.1))]
    s, g = np.array([0.3, 0.5, 0.0]), np.array([0.3, -0.4, 0.0])
    p = straight_steps(s, g)
    q, moved = repel_points(p, boxes, s, g)
    assert moved.any()
    assert np.allclose(q[0], s) and np.allclose(q[-1], g)
    for b in boxes:
        v = ellipsoid_value(q[1:-1], b.center, enclosing_radii(b) + SAFETY_ZONE)
        assert v.min() >= 1 - 1e-9
    # points move only along the normal
    n = repulsion_normal(s, g)
    delta = q - p
    assert np.allclose(np.cross(delta, n), 0, atol=1e-12)


def test_support_boxes_do_not_repel():
    b = Box((0.3, 0.0, 0.0), (0.3, 0.3, 0.3), kind="support")
    p = straight_steps([0.3, 0.5, 0], [0.3, -0.5, 0])
    q, moved = repel_points(p, [b], p[0], p[-1])
    assert not moved.any() and np.array_equal(p, q)


@pytest.mark.parametrize("kw,field", [({"size": (0.1, -0.1, 0.1)}, "size"),
                                      ({"center": (0, 0)}, "center"),
                                      ({"kind": "wall"}, "kind")])
def test_bad_boxes_are_named(kw, field):
    args = {"center": (0, 0, 0), "size": (0.1, 0.1, 0.1)} | kw
    with pytest.raises(InvalidInputError, match=field):
        Box(**args)


def test_obstacle_is_a_deprecated_name_of_the_one_box():
    import iik.planning
    import iik.planning.obstacles as obstacles
    from iik.scene import Box

    with pytest.warns(DeprecationWarning, match="iik.scene.Box"):
        assert obstacles.Obstacle is Box
    assert iik.planning.Box is Box
    b = Box((0.3, 0.0, 0.0), (0.2, 0.2, 0.2))
    assert b.contains([0.3, 0.0, 0.05]) is True
    np.testing.assert_array_equal(b.contains([[0.3, 0.0, 0.05], [1.0, 0.0, 0.0]]), [True, False])
    assert b.distance([0.6, 0.0, 0.0]) == pytest.approx(0.2)
