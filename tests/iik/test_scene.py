"""iik.scene: the platform and floor of Sec 4.2.1 in the arm's base frame."""

import numpy as np
import pytest

import iik
from iik import InvalidInputError
from iik.scene import PLATFORM_HEIGHT, TABLE_HEIGHT, THESIS_SCENE, AxisBox, Box


def test_heights_of_sec_4_2_1():
    s = THESIS_SCENE
    assert s.floor.z == -PLATFORM_HEIGHT == -0.45  # arm base on the platform top
    assert s.platform.upper[2] == 0.0 and s.platform.lower[2] == s.floor.z
    assert s.z_at_height(TABLE_HEIGHT) == pytest.approx(0.35)


def test_arm_base_stands_on_platform_and_floor_is_reachable():
    s = THESIS_SCENE
    assert s.platform.contains([0.0, 0.0, 0.0])
    arm = iik.THESIS_ARM
    reach = arm.l3 + arm.l4 + arm.l5  # from joint 2 (at height l1)
    assert arm.l1 - s.floor.z < reach  # path 2 of Sec 4.2.1 starts on the floor


def test_box_queries_and_batches():
    b = THESIS_SCENE.platform
    pts = np.array([[0, 0, -0.1], [1, 0, 0], [0.2, 0, 0]])
    np.testing.assert_array_equal(b.contains(pts), [True, False, False])
    np.testing.assert_allclose(b.distance(pts), [0.0, 0.9, 0.1])
    assert b.contains([0.15, 0, 0], margin=0.06)
    assert THESIS_SCENE.floor.height_of([0, 0, 0]) == pytest.approx(0.45)


@pytest.mark.parametrize("lo,hi", [((0, 0, 0), (1, 1, 0)), ((0, 0), (1, 1)), ((0, 0, np.nan), (1, 1, 1))])
def test_bad_box(lo, hi):
    with pytest.raises(InvalidInputError):
        Box.from_corners("b", lo, hi)


def test_one_box_type():
    """The platform is a Box like any scenario box; the old names are deprecated aliases of it."""
    p = THESIS_SCENE.platform
    assert isinstance(p, Box) and p.kind == "support" and p.name == "platform"
    np.testing.assert_allclose(p.lower, (-0.55, -0.25, -0.45))
    np.testing.assert_allclose(p.upper, (0.10, 0.25, 0.0))
    assert p.contains([0.0, 0.0, -0.1]) is True and isinstance(p.distance([1.0, 0.0, 0.0]), float)
    with pytest.warns(DeprecationWarning, match="Box.from_corners"):
        old = AxisBox("platform", p.lower, p.upper)
    assert isinstance(old, Box) and np.allclose(old.center, p.center) and np.allclose(old.size, p.size)


def test_bad_points():
    with pytest.raises(InvalidInputError):
        THESIS_SCENE.platform.contains([0, 0])
    with pytest.raises(InvalidInputError):
        THESIS_SCENE.z_at_height(float("nan"))
