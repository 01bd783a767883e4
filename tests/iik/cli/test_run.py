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


@pytest.mark.parametrize(("argv", "named"), [
    (["run", "--demo", "--early", "2"], "--early"),
    (["run", "--demo", "--speed", "-1"], "--speed"),
    (["run", "--demo", "--margin-deg", "nan"], "--margin-deg"),
    (["run", "--demo", "--modules", "1", "1", "2", "3", "4", "5"], "--modules"),
    (["run", "--demo", "--update", "sideways"], "--update"),
    (["run", "--demo", "--bogus"], "--bogus"),
    (["run", "--trajectory", "no/such/file.csv"], "--trajectory"),
    (["run", "no-such-scenario"], "scenario"),
    (["run", "--demo", "--interface", "no-such-interface", "--channel", "x"], "no-such-interface"),
])
def test_run_bad_input_is_one_line_and_exit_2(argv, named, tmp_path, capsys):
    """Hostile options end in one stderr line naming the option as typed, exit 2, nothing on disk."""
    assert main([*argv, "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    # planning/validation notes may come first; the error is the one line after them
    errors = [line for line in err if "error" in line]
    assert len(errors) == 1 and errors[0].startswith("iik run: error: ") and named in errors[0], err
    assert "Traceback" not in "\n".join(err)
    assert not list((tmp_path / "out").glob("*.jsonl")) if (tmp_path / "out").exists() else True


def test_run_on_a_silent_bus_times_out_cleanly(tmp_path, capfd):
    """No module answers on an empty virtual bus: a CANTimeoutError line, the bus shut down
    (python-can's 'not properly shut down' warning never appears)."""
    assert main(["run", "--demo", "--interface", "virtual", "--channel", f"empty-{tmp_path.name}",
                 "--timeout", "0.05", "--out", str(tmp_path)]) == 2
    err = capfd.readouterr().err
    assert "CANTimeoutError: module 1: no reply" in err and "not properly shut down" not in err
    assert "Traceback" not in err
