"""Run-log analysis: step-point selection and FK-based end-effector errors."""

import numpy as np
import pytest

import iik
from hardware.analysis import analyse, plot_run, summary_text
from hardware.errors import RunLogError
from hardware.runlog import RunLog, read_run_log
from iik import THESIS_ARM
from iik.arms import same_arm, to_record
from iik.errors import InvalidInputError


def write_log(path, q, poses, samples, end=True, arm=THESIS_ARM):
    """A run log as the executor writes it; its header records ``arm`` (None: no arm)."""
    record = {} if arm is None else {"arm": to_record(arm)}
    with RunLog(path) as log:
        log.write({"type": "header", "module_ids": [1, 2, 3, 4, 5, 6], "times": list(range(len(q))),
                   "q": q.tolist(), "poses": poses.tolist()} | record)
        for t, k, qm in samples:
            log.write({"type": "sample", "t": t, "k": k, "q": list(qm), "dq": [0.0] * 6, "cur": [0.5] * 6,
                       "state": [2] * 6})
        if end:
            log.write({"type": "end", "t": 9.0, "status": "ok"})


def test_step_point_is_the_last_sample_of_each_step(tmp_path):
    q = np.array([[0.1, -0.2, 0.3, 0.4, 0.5, 0.6]] * 3) + np.arange(3)[:, None] * 0.05
    T = iik.fk(q, THESIS_ARM)
    d = np.array([0.0, 0.01, 0.0, 0.0, 0.0, 0.0])
    samples = [(0.0, 0, q[0] + 5 * d), (0.1, 0, q[0]),          # start: last sample exact
               (0.2, 1, q[1] + 9 * d), (0.3, 1, q[1] + d),      # step 1: off by d on joint 2
               (0.4, 2, q[2] - 3 * d), (0.5, 2, q[2])]          # end: exact
    write_log(tmp_path / "r.jsonl", q, T, samples)
    a = analyse(read_run_log(tmp_path / "r.jsonl"))
    np.testing.assert_array_equal(a.steps, [0, 1, 2])
    np.testing.assert_allclose(a.joint_error, [np.zeros(6), d, np.zeros(6)], atol=1e-12)
    expected = np.linalg.norm(iik.fk(q[1] + d, THESIS_ARM)[:3, 3] - T[1, :3, 3])
    assert a.ee_error[1] == pytest.approx(expected) and expected > 1e-3
    assert a.start_ee_error == 0 and a.final_ee_error == 0
    assert a.max_ee_error == pytest.approx(expected) and a.mean_ee_error == pytest.approx(expected / 3)
    assert a.within(0.030) == (expected <= 0.030)
    assert "end-effector error" in summary_text(a)
    paths = plot_run(a, tmp_path / "fig")
    assert all(p.exists() and p.stat().st_size > 1000 for p in paths)


def test_malformed_logs_raise_typed_errors(tmp_path):
    p = tmp_path / "bad.jsonl"
    p.write_text('{"type": "sample"}\n')
    with pytest.raises(RunLogError):
        read_run_log(p)
    p.write_text("not json\n")
    with pytest.raises(RunLogError):
        read_run_log(p)
    with pytest.raises(RunLogError):
        read_run_log(tmp_path / "missing.jsonl")
    q = np.zeros((2, 6))
    write_log(p, q, iik.fk(q, THESIS_ARM), [], end=False)
    run = read_run_log(p)
    assert not run.complete
    with pytest.raises(RunLogError, match="no samples"):
        analyse(run)


def test_the_analysis_uses_the_arm_the_log_records(tmp_path):
    """The FK of the end-effector error is the recorded arm's: a scaled arm's log measured with the scaled
    arm has zero error where the thesis arm's FK would put the tool elsewhere; another arm given is refused,
    and a log that records none needs one."""
    arm = THESIS_ARM.scaled(1.25, name="thesis x1.25")
    q = np.array([[0.1, -0.2, 0.3, 0.4, 0.5, 0.6]] * 3) + np.arange(3)[:, None] * 0.05
    T = iik.fk(q, arm)
    samples = [(0.1 * k, k, q[k]) for k in range(3)]
    write_log(tmp_path / "s.jsonl", q, T, samples, arm=arm)
    run = read_run_log(tmp_path / "s.jsonl")
    assert run.arm is not None and same_arm(run.arm, arm) and not same_arm(run.arm, THESIS_ARM)
    a = analyse(run)
    assert same_arm(a.arm, arm) and a.max_ee_error < 1e-12
    thesis_error = np.linalg.norm(iik.fk(q, THESIS_ARM)[:, :3, 3] - T[:, :3, 3], axis=1).max()
    assert thesis_error > 0.05  # what the thesis arm's FK would have reported
    with pytest.raises(InvalidInputError, match="not the arm the run log records") as info:
        analyse(run, THESIS_ARM)
    assert info.value.argument == "arm"
    write_log(tmp_path / "n.jsonl", q, T, samples, arm=None)
    with pytest.raises(RunLogError, match="records no arm"):
        analyse(read_run_log(tmp_path / "n.jsonl"))
    assert analyse(read_run_log(tmp_path / "n.jsonl"), arm).max_ee_error < 1e-12


def test_unwritable_log_path_is_typed(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(RunLogError):
        RunLog(blocker / "sub" / "run.jsonl")
