"""End to end: ``iik plan`` on a file outside the repository, limits at every sample."""

import csv

import numpy as np
import pytest

from iik import THESIS_ARM
from iik.cli import main
from iik.planning.pipeline import PlanOptions, plan_scenario
from iik.resources import scenarios_dir


@pytest.fixture(scope="module")
def repo_result():
    return plan_scenario(scenarios_dir() / "j.toml")


def test_repo_scenario_j_plans_with_safety_zone(repo_result):
    r = repo_result
    assert r.success, r.reason
    assert r.min_clearance >= r.scenario.safety_zone
    assert r.trajectory_clearance >= r.scenario.safety_zone
    assert r.clearance.self_min > 0


def test_external_file_plans_the_same_through_iik_plan(tmp_path, repo_result):
    src = (scenarios_dir() / "j.toml").read_text()
    ext = tmp_path / "elsewhere" / "my_task.toml"
    ext.parent.mkdir()
    ext.write_text(src)
    out = tmp_path / "out"
    assert main(["plan", str(ext), "--out", str(out), "--no-figures"]) == 0
    with (out / "steps.csv").open() as f:
        rows = list(csv.DictReader(f))
    q = np.array([[float(r[f"q{i}"]) for i in range(1, 7)] for r in rows])
    assert np.allclose(q, repo_result.q, atol=1e-8)
    clear = np.array([float(r["clearance"]) for r in rows])
    assert clear.min() >= repo_result.scenario.safety_zone


def test_trajectory_respects_joint_velocity_and_acceleration_limits(tmp_path):
    out = tmp_path / "o"
    assert main(["plan", str(scenarios_dir() / "j.toml"), "--out", str(out), "--no-figures"]) == 0
    data = np.loadtxt(out / "trajectory.csv", delimiter=",", skiprows=1)
    t, q, qd, qdd = data[:, 0], data[:, 1:7], data[:, 7:13], data[:, 13:19]
    assert np.all(np.diff(t) > 0)
    assert np.all(q >= THESIS_ARM.q_min) and np.all(q <= THESIS_ARM.q_max)
    assert np.all(np.abs(qd) <= np.asarray(THESIS_ARM.velocity) * (1 + 1e-9))
    assert np.all(np.abs(qdd) <= np.asarray(THESIS_ARM.acceleration) * (1 + 1e-9))
    # finite differences agree with the reported velocities (the CSV is one consistent trajectory)
    fd = np.diff(q, axis=0) / np.diff(t)[:, None]
    assert np.abs(fd - 0.5 * (qd[1:] + qd[:-1])).max() < 0.05


def test_impossible_scenario_exits_with_typed_error(tmp_path, capsys):
    p = tmp_path / "bad.toml"
    p.write_text((scenarios_dir() / "j.toml").read_text().replace("position = [0.3, 0.27, 0.9]",
                                                                  "position = [2.0, 0.27, 0.9]"))
    assert main(["plan", str(p), "--out", str(tmp_path / "o")]) == 2
    assert "ScenarioError: goal.position" in capsys.readouterr().err


def test_thesis_only_mode_reports_honestly():
    r = plan_scenario(scenarios_dir() / "a.toml", options=PlanOptions(fallbacks=False, timing=False))
    # the thesis planner alone keeps the tool point off the padded ellipsoid but not the gripper
    assert not r.success and "thesis path rejected" in r.reason


def test_lji_mode_interpolates_joints_between_key_points(tmp_path):
    p = tmp_path / "lji.toml"
    text = (scenarios_dir() / "j.toml").read_text()
    p.write_text(text.replace('frame = "floor"', 'frame = "floor"\n[planning]\nmode = "LJI"'))
    r = plan_scenario(p, options=PlanOptions(timing=False))
    assert r.success, r.reason
    if r.method.startswith("thesis LJI"):
        assert np.abs(np.diff(r.q, axis=0)).max() <= 0.05 + 1e-12
        assert len(r.cartesian.points) == 2  # start and goal only (no via-points in j)
