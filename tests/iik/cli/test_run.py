"""``iik run`` end to end on the in-process simulated arm."""

import numpy as np
import pytest

import iik
from hardware import read_run_log
from iik.cli import main
from iik.resources import scenarios_dir


def test_run_demo(tmp_path, capsys):
    assert main(["run", "--demo", "--sim-start", "plan", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "end-effector error: max" in out and "30 mm zone" in out
    run = read_run_log(tmp_path / "demo.jsonl")
    assert run.status == "ok"
    for stem in ("joint_error", "ee_error", "velocity"):
        assert (tmp_path / f"demo_{stem}.png").stat().st_size > 1000


def test_run_csv_trajectory(tmp_path, capsys):
    q = np.linspace(0, 1, 4)[:, None] * np.array([0.05, 0.04, -0.03, 0.02, 0.1, 0.0])
    t = np.arange(4) * 0.06
    path = tmp_path / "traj.csv"
    np.savetxt(path, np.column_stack([t, q]), delimiter=",", header="t,q1,q2,q3,q4,q5,q6", comments="")
    assert main(["run", "--trajectory", str(path), "--out", str(tmp_path), "--no-figures"]) == 0
    assert read_run_log(tmp_path / "traj.jsonl").status == "ok"


def test_run_refuses_an_out_of_limit_csv(tmp_path, capsys):
    q = np.zeros((3, 6))
    q[2, 1] = iik.THESIS_ARM.upper[1] + 0.01
    path = tmp_path / "bad.csv"
    np.savetxt(path, np.column_stack([np.arange(3) * 1.0, q]), delimiter=",",
               header="t,q1,q2,q3,q4,q5,q6", comments="")
    assert main(["run", "--trajectory", str(path), "--out", str(tmp_path)]) == 2
    assert "SafetyError" in capsys.readouterr().err and not (tmp_path / "bad.jsonl").exists()


def test_run_needs_one_source(tmp_path, capsys):
    assert main(["run", "--out", str(tmp_path)]) == 2


@pytest.mark.skipif(not list(scenarios_dir().glob("j.toml")), reason="scenario j.toml not shipped yet")
def test_run_thesis_scenario_j(tmp_path, capsys):
    assert main(["run", "j", "--sim-start", "plan", "--speed", "1.0", "--out", str(tmp_path),
                 "--no-figures"]) == 0
    assert "end-effector error" in capsys.readouterr().out
