"""A run log in the viewer: commanded vs measured arms, and bad logs as typed errors."""

import numpy as np
import pytest

from hardware.runlog import RunLog, RunLogError, read_run_log
from hardware.view import SIDE_BY_SIDE, run_motion, view_run
from iik import fk
from iik.planning.viewer import ViewOptions


def _write_log(path, *, samples=True, end=True):
    times = np.linspace(0.0, 1.0, 5)
    q = np.outer(times, [0.5, -0.4, 0.3, 0.2, -0.1, 0.6])
    with RunLog(path) as log:
        log.write({"type": "header", "module_ids": [1, 2, 3, 4, 5, 6], "times": times.tolist(),
                   "q": q.tolist(), "poses": fk(q).tolist(), "early": 0.95, "started": "2026-01-01T00:00:00"})
        for k in range(5):
            log.write({"type": "command", "t": 0.25 * k, "k": k, "q": q[k].tolist(), "time_s": 0.25})
            if samples:
                meas = q[k] - 0.01 * (k > 0)  # lags the command by 0.01 rad on every joint
                log.write({"type": "sample", "t": 0.25 * k + 0.1, "k": k, "q": meas.tolist(),
                           "tq": [0.25 * k + 0.1] * 6, "dq": [0.0] * 6, "cur": [0.1] * 6, "state": [0] * 6})
        if end:
            log.write({"type": "end", "t": 1.2, "status": "ok"})
    return q


def test_run_motion_pairs_each_sample_with_its_command(tmp_path):
    q = _write_log(tmp_path / "r.jsonl")
    m = run_motion(read_run_log(tmp_path / "r.jsonl"), name="r")
    cmd, meas = m.tracks
    assert np.allclose(m.t, np.arange(5) * 0.25)  # sample times from the first sample
    assert np.allclose(cmd.q, q) and np.allclose(meas.q[1:], q[1:] - 0.01)
    assert meas.offset == (0.0, SIDE_BY_SIDE, 0.0) and cmd.offset == (0.0, 0.0, 0.0)
    assert "0.57 deg" in m.notes[1]  # 0.01 rad
    tool_mm = np.linalg.norm(fk(q[1] - 0.01)[:3, 3] - fk(q[1])[:3, 3]) * 1000
    assert f"{tool_mm:.1f} mm" in m.notes[1] and "status ok" in m.headline


def test_bad_logs_are_run_log_errors(tmp_path):
    (tmp_path / "bad.jsonl").write_text("not json\n")
    with pytest.raises(RunLogError, match="not JSON"):
        view_run(tmp_path / "bad.jsonl", ViewOptions(export=tmp_path / "x"))
    _write_log(tmp_path / "empty.jsonl", samples=False)
    with pytest.raises(RunLogError, match="no samples"):
        view_run(tmp_path / "empty.jsonl", ViewOptions(export=tmp_path / "x"))
    assert not (tmp_path / "x").exists()


def test_a_run_exports_as_two_arms(tmp_path):
    _write_log(tmp_path / "r.jsonl", end=False)
    shown = view_run(tmp_path / "r.jsonl", ViewOptions(export=tmp_path / "out"))
    assert shown.result.frames == 5 and (tmp_path / "out" / "index.html").is_file()
    assert "incomplete" in shown.headline
