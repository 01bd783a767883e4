"""The adapter from the planner's result and the per-frame clearance."""

import dataclasses
from types import SimpleNamespace

import numpy as np
import pytest

import iik
from iik import THESIS_ARM
from iik.planning import PlanOptions, plan, scenario_path
from iik.planning.collision import Nearest
from iik.planning.errors import ScenarioError
from iik.planning.viewer import frame_clearance, least_clearance, plan_for_view, plan_scene
from iik.planning.viewer.plan_data import UNTIMED_STEP


@pytest.fixture(scope="module")
def result_j():
    return plan("j")


def test_plan_scene_reads_the_timed_trajectory_and_the_path(result_j):
    view = plan_scene(result_j)
    assert view.name == "j" and view.success
    assert np.array_equal(view.t, result_j.trajectory.t) and np.array_equal(view.q, result_j.trajectory.q)
    assert np.all(np.diff(view.t) > 0)
    # The step-points are the planned tool points; the joint path reaches them (Eq 4 FK).
    assert np.allclose(iik.fk(view.step_q, THESIS_ARM)[:, :3, 3], view.step_points, atol=1e-6)
    # The trajectory starts and ends at the path's ends.
    assert np.allclose(view.q[0], view.step_q[0], atol=1e-6)
    assert np.allclose(view.q[-1], view.step_q[-1], atol=1e-6)
    assert {b.name for b in view.obstacles} == {b.name for b in result_j.scenario.obstacles}
    assert "j: OK" in view.headline and "mm" in view.headline


def test_switch_times_point_at_the_switching_steps(result_j):
    """A result with a branch switch: its time is the frame at that step's configuration."""
    q = np.zeros((5, 6))
    q[3:, 0] = 1.0  # a jump of 1 rad > BRANCH_SWITCH_STEP between steps 2 and 3
    t = np.linspace(0, 2, 41)
    tq = np.interp(t, [0, 0.5, 1.0, 1.5, 2.0], q[:, 0])
    traj = SimpleNamespace(t=t, q=np.column_stack([tq] + [np.zeros_like(t)] * 5), duration=2.0)
    res = dataclasses.replace(result_j, q=q, trajectory=traj, cartesian=None,
                              branch_switches=iik.branch_switches(q))
    view = plan_scene(res)
    assert view.switch_steps == (3,)
    assert view.switch_times == (1.5,)
    assert view.via_points.shape == (0, 3)
    assert np.allclose(view.step_points, iik.fk(q, THESIS_ARM)[:, :3, 3])


def test_a_failed_plan_is_a_view_with_its_best_attempt_and_the_start_pose():
    res = plan("a", PlanOptions(fallbacks=False, timing=False))
    assert not res.success and len(res.q) == 0
    view = plan_scene(res)
    assert not view.success and view.reason == res.reason and view.headline == f"a: FAILED ({res.reason})"
    assert view.attempts == res.attempts and view.best == res.best_attempt and view.best is not None
    # Without an accepted path the arm stands at the start pose: one frame, IK of the scenario's start.
    assert view.q.shape == (1, 6) and view.t.shape == (1,) and "start pose" in view.arm_shows
    assert np.allclose(iik.fk(view.q[0], THESIS_ARM)[:3, 3], res.scenario.start.position, atol=1e-6)
    assert iik.THESIS_ARM.within_limits(view.q[0])
    # The rejected thesis path's step-points are still drawn.
    assert np.array_equal(view.step_points, res.cartesian.points) and len(view.step_q) == 0


def test_an_accepted_path_whose_timing_ran_out_is_shown_untimed(result_j):
    res = dataclasses.replace(result_j, success=False, timed_out=True, trajectory=None,
                              reason="timed out after 0.1 s during checking the timed trajectory")
    view = plan_scene(res)
    assert view.timed_out and not view.success and view.headline.startswith("j: FAILED (timed out")
    assert np.array_equal(view.q, result_j.q) and np.allclose(np.diff(view.t), UNTIMED_STEP)
    assert "untimed" in view.arm_shows


def test_a_plan_cut_by_its_timeout_is_still_a_view():
    view = plan_for_view("j", PlanOptions(timeout=1e-3))
    assert view.timed_out and not view.success and "timed out" in view.reason
    assert len(view.q) >= 1 and ("start pose" in view.arm_shows) == (len(view.step_q) == 0)


def test_frame_clearance_nearest_points_are_consistent(result_j):
    """Coal's nearest points lie on the obstacle and are ``distance`` apart (checked by Box.distance)."""
    view = plan_scene(result_j)
    q = view.q[:: max(1, len(view.q) // 25)]
    c = frame_clearance(view.obstacles, q, arm=THESIS_ARM)
    assert len(c) == len(q) and all(isinstance(n, Nearest) for n in c)
    boxes = {b.name: b for b in view.obstacles}
    for n in c:
        gap = np.linalg.norm(n.on_link - n.on_object)
        if n.distance > 1e-6:
            assert gap == pytest.approx(n.distance, abs=1e-6)
        if n.object in boxes:
            box = boxes[n.object]
            assert box.distance(n.on_object) == pytest.approx(0.0, abs=1e-6)
            assert box.distance(n.on_link) == pytest.approx(max(n.distance, 0.0), abs=1e-6)
    # No frame of the accepted plan enters the safety zone.
    assert min(n.distance for n in c) >= view.safety_zone - 1e-9
    assert c[least_clearance(c)].distance == min(n.distance for n in c)


def test_unknown_scenario_names_the_argument():
    with pytest.raises(ScenarioError, match="neither a scenario file nor a shipped"):
        scenario_path("no_such_scenario")
