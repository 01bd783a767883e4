"""Arms outside the class: Arm.from_urdf raises NotInClassError naming the file, with a near-miss
report in mm and degrees whose numbers are measured (checked here against published data)."""

import math

import numpy as np
import pytest

import iik
from iik.errors import InvalidInputError
from iik.kinematic_class import NotInClassError
from iik.resources import urdf_path
from verification.oracles.ur5 import UR5_A, UR5_D, ur5_reference_path


def _condition(report, text):
    return next(c for c in report.conditions if c.text == text)


def _tilted_crx(tmp_path, degrees: float):
    """The shipped CRX-10iA URDF with the J3 axis (the first ``0 -1 0`` axis) turned about x."""
    text = urdf_path("crx10ia.urdf").read_text()
    d = math.radians(degrees)
    tilted = text.replace('<axis xyz="0 -1 0"/>', f'<axis xyz="0 {-math.cos(d)!r} {math.sin(d)!r}"/>', 1)
    assert tilted != text
    path = tmp_path / "crx10ia_tilted.urdf"
    path.write_text(tilted)
    return path


def test_ur5_is_another_class_and_the_report_measures_its_published_offsets():
    path = ur5_reference_path()
    with pytest.raises(NotInClassError) as info:
        iik.Arm.from_urdf(path, tip_link="tool0")
    err = info.value
    assert isinstance(err, InvalidInputError) and isinstance(err, ValueError)
    first = str(err).splitlines()[0]
    assert str(path) in first and "closest when read from the flange" in first and " mm" in first
    base, flange = err.reports
    assert not base.member and not flange.member
    # read from the flange the UR5's wrist is 2 ∩ 3 and 4 ∥ 5 ∩ 6; what fails are its arm offsets,
    # measured here as the published DH lengths (Universal Robots: a3 = -0.39225, d4 = 0.10915 m)
    assert _condition(flange, "axes 3 and 4 intersect").deviation == pytest.approx(abs(UR5_A[2]), abs=1e-9)
    level = "the points 3∩4 and 5∩6 are level along axes 4 and 5"
    assert _condition(flange, level).deviation == pytest.approx(UR5_D[3], abs=1e-9)
    assert math.degrees(_condition(flange, "axes 3 and 4 are perpendicular").deviation) == pytest.approx(90)
    assert "392.25 mm" in str(err) and "109.15 mm" in str(err)


@pytest.mark.parametrize("degrees", [0.1, 1.0, 10.0])
def test_a_crx_with_one_axis_tilted_is_reported_by_how_much(tmp_path, degrees):
    iik.Arm.from_urdf(urdf_path("crx10ia.urdf"))  # the shipped file is a member
    path = _tilted_crx(tmp_path, degrees)
    with pytest.raises(NotInClassError) as info:
        iik.Arm.from_urdf(path)
    first = str(info.value).splitlines()[0]
    assert str(path) in first and "closest when read from the flange" in first
    flange = info.value.reports[1]
    dev = _condition(flange, "axes 4 and 5 are parallel").deviation  # the CRX's J3 ∥ J2, reversed
    assert math.degrees(dev) == pytest.approx(degrees, abs=1e-9)
    assert f"axes 4 and 5 are parallel, off by {degrees:g} deg" in first
    for text in ("axes 2 and 3 intersect", "axes 3 and 4 are perpendicular", "axes 5 and 6 intersect"):
        assert _condition(flange, text).holds  # the tilt breaks only what it touches
    # the nearly parallel pair is measured as parallel, not through the common normal of two skew
    # lines (which lies hundreds of metres away for 0.1 deg: "level, off by 309397 mm" before)
    assert [c.text for c in flange.conditions if not c.holds] == ["axes 4 and 5 are parallel"]
    assert "FAILS" not in first.split("axes 4 and 5 are parallel")[1]


def test_a_tilt_within_the_tolerance_is_accepted(tmp_path):
    arm = iik.Arm.from_urdf(_tilted_crx(tmp_path, math.degrees(1e-11)))
    q = np.random.default_rng(2).uniform(arm.q_min, arm.q_max, 6)
    assert iik.solve(iik.fk(q, arm), arm=arm, within_limits=False).count >= 1
