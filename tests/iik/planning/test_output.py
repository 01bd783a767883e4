"""Files and figures of a plan (iik.planning.output)."""

import csv
import signal
import subprocess
import sys
import textwrap

import numpy as np

from iik.cli import main
from iik.planning import PLAN_FILES, PlanOptions, plan, write_outputs


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


INTERRUPTED_PLAN = textwrap.dedent("""
    import os, signal, sys, time
    import matplotlib.figure
    from iik.cli import main
    def savefig(self, *args, **kwargs):  # SIGTERM while the first figure is being written
        os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(30)
    matplotlib.figure.Figure.savefig = savefig
    sys.exit(main(["plan", "p3", "--out", sys.argv[1]]))
""")


def test_sigterm_while_writing_leaves_the_previous_plan_output_unmixed(tmp_path):
    """`iik plan p3 --out p` stopped by SIGTERM half-way through its files leaves p2's output as it was."""
    out = tmp_path / "p"
    assert main(["plan", "p2", "--out", str(out)]) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    assert set(before) == set(PLAN_FILES)
    res = subprocess.run([sys.executable, "-c", INTERRUPTED_PLAN, str(out)], capture_output=True, text=True,
                         timeout=600)
    assert res.returncode == 128 + signal.SIGTERM, res.stderr
    assert "iik plan: interrupted by SIGTERM" in res.stderr
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert [p.name for p in tmp_path.iterdir()] == ["p"]  # no temporary left behind


def test_an_out_folder_holding_other_files_is_refused_before_planning(tmp_path, capsys):
    (tmp_path / "notes.txt").write_text("mine")
    assert main(["plan", "p1", "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "iik plan: error: FileError: --out: " in err and "holds other things (notes.txt)" in err
    assert "planning p1" not in err and [p.name for p in tmp_path.iterdir()] == ["notes.txt"]
