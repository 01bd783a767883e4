"""Files and figures of a plan (iik.planning.output)."""

import csv

import numpy as np

from iik.planning import PlanOptions, plan, write_outputs


def test_files_hold_the_plan(tmp_path):
    r = plan("j", PlanOptions(dt=0.02))
    files = write_outputs(r, tmp_path, figures=False)
    assert {f.name for f in files} == {"trajectory.csv", "steps.csv", "summary.txt"}
    lines = (tmp_path / "summary.txt").read_text().splitlines()
    assert lines[: len(r.summary().splitlines())] == r.summary().splitlines()
    assert lines[-len(r.log):] == [f"- {x}" for x in r.log]
    with (tmp_path / "steps.csv").open() as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == len(r.q)
    assert np.allclose([float(x["clearance"]) for x in rows], r.clearance.step, atol=1e-6)
    assert np.allclose([float(x["effort"]) for x in rows], r.effort, atol=1e-9)
    traj = np.loadtxt(tmp_path / "trajectory.csv", delimiter=",", skiprows=1)
    assert np.allclose(np.diff(traj[:, 0]), 0.02, atol=1e-3) and traj.shape[1] == 19


def test_steps_csv_carries_the_executed_step_times(tmp_path):
    """The t column of steps.csv is the plan's step schedule, what `iik run` executes."""
    r = plan("j")
    write_outputs(r, tmp_path, figures=False)
    with (tmp_path / "steps.csv").open() as f:
        rows = list(csv.DictReader(f))
    np.testing.assert_allclose([float(x["t"]) for x in rows], r.trajectory.step_t, atol=5e-7)
    np.testing.assert_allclose([[float(x[f"q{i}"]) for i in range(1, 7)] for x in rows], r.q, atol=1e-9)


def test_a_failed_plan_writes_no_executable_times(tmp_path):
    import dataclasses

    r = dataclasses.replace(plan("j"), success=False, reason="for the test")
    write_outputs(r, tmp_path, figures=False)
    with (tmp_path / "steps.csv").open() as f:
        assert "t" not in csv.DictReader(f).fieldnames
