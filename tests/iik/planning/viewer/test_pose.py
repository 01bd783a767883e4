"""Pose mode: every IK solution, the limit marks and the default choice."""

import numpy as np
import pytest

import iik
from iik import THESIS_ARM
from iik.errors import InvalidInputError
from iik.planning.viewer import PoseView
from iik.planning.viewer.bodies import joints_outside_limits, outside_limits_text


def test_every_configuration_reaches_the_pose():
    T = iik.pose_from_euler([0.4, 0.3, 0.2], np.pi, np.radians(120), 0.0)
    view = PoseView(T, arm=THESIS_ARM)
    qs = view.configurations()
    assert len(qs) == iik.solve(T, THESIS_ARM, within_limits=False).count >= 2
    assert np.allclose(iik.fk(qs, THESIS_ARM), T, atol=1e-8)
    assert len(view.options()) == len(qs)
    # The default choice is iik.select's: least effort (Eq 54) from q = 0 within Table I.
    assert np.allclose(qs[view.selected], iik.select(view.result, previous_q=np.zeros(6), arm=THESIS_ARM))


@pytest.mark.parametrize("j", range(6))
def test_limit_marks_agree_with_the_one_limit_test(j):
    arm = iik.THESIS_ARM
    q = 0.5 * (arm.q_min + arm.q_max)
    q[j] = arm.q_max[j] + 0.1
    assert joints_outside_limits(q, THESIS_ARM) == (j,)
    assert not arm.within_limits(q)
    q[j] = arm.q_max[j]
    assert joints_outside_limits(q, THESIS_ARM) == () and arm.within_limits(q)


def test_q_outside_the_limits_is_shown_with_one_warning_line():
    view = PoseView(q=[0.1, -0.3, 0.4, 3.0, -0.2, 3.5], arm=THESIS_ARM)
    assert len(view.warnings) == 1 and "\n" not in view.warnings[0]
    assert "q4 = 3.0000 rad" in view.warnings[0] and "q6 = 3.5000 rad" in view.warnings[0]
    assert "q5" not in view.warnings[0] and "outside Table I" in view.warnings[0]
    assert np.array_equal(view.configurations()[0], [0.1, -0.3, 0.4, 3.0, -0.2, 3.5])
    assert "**OUT**" in view.describe(0) and "OUTSIDE LIMITS" in view.options()[0]
    assert PoseView(q=[0.1, -0.3, 0.4, 1.0, -0.2, 0.7], arm=THESIS_ARM).warnings == ()


def test_outside_limits_text_names_each_joint_with_its_limits():
    arm = iik.THESIS_ARM
    q = 0.5 * (arm.q_min + arm.q_max)
    assert outside_limits_text(q, THESIS_ARM) == ""
    q[1] = arm.q_min[1] - 0.25
    text = outside_limits_text(q, THESIS_ARM)
    assert text.startswith(f"q2 = {q[1]:.4f} rad ({np.degrees(q[1]):.1f} deg) is outside Table I")
    assert f"[{arm.q_min[1]:.4f}, {arm.q_max[1]:.4f}] rad" in text


def test_bad_pose_arguments_are_typed_errors():
    with pytest.raises(InvalidInputError):
        PoseView(q=[0.0, np.nan, 0, 0, 0, 0], arm=THESIS_ARM)
    with pytest.raises(InvalidInputError):
        PoseView(np.eye(4), q=np.zeros(6), arm=THESIS_ARM)
    with pytest.raises(InvalidInputError):
        PoseView(np.ones((4, 4)), arm=THESIS_ARM)
