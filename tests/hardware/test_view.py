"""A run log in the viewer: commanded vs measured arms, and bad logs as typed errors.

Logs come from the executor itself (a simulated arm on a virtual bus, both update
modes) and, for exact values and malformed cases, from hand-written records.
"""

import dataclasses
import json
import uuid

import can
import numpy as np
import pytest

import iik
import iik.arms
from hardware import PowerCubeArm, SimulatedArm, VirtualClock, execute, validate
from hardware.executor import ExecutionOptions, time_steps
from hardware.runlog import RunLog, RunLogError, read_run_log
from hardware.view import (
    LOG_VERSION,
    SIDE_BY_SIDE,
    commanded_steps,
    run_motion,
    run_warnings,
    side_by_side,
    view_run,
)
from iik import THESIS_ARM, fk
from iik.arms import same_arm, to_record
from iik.errors import InvalidInputError
from iik.planning.viewer import ViewOptions


def _write_log(path, *, samples=True, end=True, arm=THESIS_ARM, record=None):
    """A run log as the executor writes it; its header records ``arm`` (or the given ``record``)."""
    times = np.linspace(0.0, 1.0, 5)
    q = np.outer(times, [0.5, -0.4, 0.3, 0.2, -0.1, 0.6])
    with RunLog(path) as log:
        log.write({"type": "header", "version": LOG_VERSION, "module_ids": [1, 2, 3, 4, 5, 6],
                   "times": times.tolist(), "q": q.tolist(), "poses": fk(q, arm).tolist(), "early": 0.95,
                   "started": "2026-01-01T00:00:00", "arm": record or to_record(arm)})
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
    assert "0.57 deg" in m.notes[1] and m.notes[1].startswith("step 1:")  # 0.01 rad
    tool_mm = np.linalg.norm(fk(q[1] - 0.01, THESIS_ARM)[:3, 3] - fk(q[1], THESIS_ARM)[:3, 3]) * 1000
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


@pytest.fixture(scope="module", params=["thesis", "buffered"])
def executed(request, tmp_path_factory):
    """A run log written by :func:`hardware.execute` on a simulated arm (virtual bus), per update mode,
    on a virtual clock shared by the modules and the executor: its samples fall where the schedule puts
    them, however loaded the machine (on real time a loaded host sampled too seldom)."""
    ch, clock = f"view-{uuid.uuid4().hex}", VirtualClock()
    qa, qb = np.array([0.1, -0.3, 0.4, 0.5, -0.2, 0.7]), np.array([0.3, -0.1, 0.2, 0.6, 0.1, 0.5])
    q = qa + (qb - qa) * np.linspace(0, 1, 8)[:, None]
    tr = validate(time_steps(q, speed_fraction=0.5, min_step=0.05, arm=THESIS_ARM), q, iik.fk(q, THESIS_ARM),
                  arm=THESIS_ARM)
    log = tmp_path_factory.mktemp("run") / f"{request.param}.jsonl"
    sim = SimulatedArm.virtual(ch, lag=0.01, initial=qa, arm=THESIS_ARM, clock=clock.now)
    bus = can.Bus(interface="virtual", channel=ch)
    try:
        arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=5.0, arm=THESIS_ARM)  # ACK timeout not under test
        execute(arm, tr, log, clock=clock.now, sleep=clock.sleep,
                options=ExecutionOptions(settle=0.05, sample_period=0.005, update=request.param))
    finally:
        sim.close()
        bus.shutdown()
    return request.param, read_run_log(log), log


def test_commanded_target_is_the_step_being_executed(executed):
    """Thesis update: the last command sent. Buffered: the queued command waits for the step end."""
    mode, run, _ = executed
    assert run.header["version"] == LOG_VERSION and run.status == "ok" and len(run.samples_t) > 20
    k = commanded_steps(run)
    assert np.all(k <= run.samples_k)
    if mode == "thesis":
        assert not run.step_end and np.array_equal(k, run.samples_k)
        return
    last = max(run.step_end)
    for t, ki in zip(run.samples_t, k, strict=True):
        if ki >= 1:
            assert ki - 1 not in run.step_end or t >= run.step_end[ki - 1]  # its step has started ...
            assert ki == last or t < run.step_end[ki]  # ... and not yet ended
    assert np.any(k < run.samples_k)  # the last command sent was often still queued


def test_an_executed_run_is_shown_and_exported(executed, tmp_path):
    mode, run, log = executed
    m = run_motion(run, name="r")
    assert np.allclose(m.tracks[0].q, run.q_planned[commanded_steps(run)]) and m.warnings == ()
    assert f"{mode} update, status ok" in m.headline and "during the planned steps" in m.headline
    shown = view_run(log, ViewOptions(export=tmp_path / "out"))
    assert shown.result.frames >= 2 and (tmp_path / "out" / "index.html").is_file()


def test_what_the_view_cannot_show_faithfully_is_a_warning(tmp_path):
    _write_log(tmp_path / "r.jsonl")
    run = read_run_log(tmp_path / "r.jsonl")
    assert run_warnings(run) == ()
    newer = dict(run.header, version=LOG_VERSION + 1)
    warnings = run_warnings(dataclasses.replace(run, header=newer))
    assert len(warnings) == 1 and f"version {LOG_VERSION + 1}" in warnings[0]
    # an arm read from a URDF file that has since changed: rebuilt from the log's numbers, body generated
    crx = iik.arms.get("crx10ia")
    copy = tmp_path / "crx.urdf"
    copy.write_text(open(crx.urdf).read())
    record = to_record(iik.Arm.from_urdf(copy, name="crx copy"))
    copy.write_text(open(crx.urdf).read() + "<!-- edited -->\n")
    _write_log(tmp_path / "c.jsonl", arm=crx, record=record)
    run = read_run_log(tmp_path / "c.jsonl")
    assert run.arm.urdf == "" and same_arm(run.arm, crx)
    assert "missing or changed" in run_warnings(run)[0]


def test_the_view_uses_the_arm_the_log_records(tmp_path):
    """A log of the CRX-10iA is drawn as the CRX (its FK in the notes, its URDF body), beside it by its reach;
    an explicitly given other arm is refused; a log from before arms were recorded (version 1, the arm's
    display name) still reads; one with no arm at all needs one given."""
    crx = iik.arms.get("crx10ia")
    q = _write_log(tmp_path / "c.jsonl", arm=crx)
    m = run_motion(read_run_log(tmp_path / "c.jsonl"), name="c")
    assert m.arm is crx and m.tracks[1].offset[1] == side_by_side(crx) > SIDE_BY_SIDE
    tool_mm = np.linalg.norm(fk(q[1] - 0.01, crx)[:3, 3] - fk(q[1], crx)[:3, 3]) * 1000
    thesis_mm = np.linalg.norm(fk(q[1] - 0.01, THESIS_ARM)[:3, 3] - fk(q[1], THESIS_ARM)[:3, 3]) * 1000
    assert f"{tool_mm:.1f} mm" in m.notes[1] and f"{tool_mm:.1f}" != f"{thesis_mm:.1f}"
    assert "'crx10ia'" in m.headline
    with pytest.raises(InvalidInputError, match="not the arm the run log records") as info:
        view_run(tmp_path / "c.jsonl", ViewOptions(export=tmp_path / "x"), arm=THESIS_ARM)
    assert info.value.argument == "arm" and not (tmp_path / "x").exists()
    _write_log(tmp_path / "v1.jsonl", record=THESIS_ARM.name)  # version 1 recorded the display name
    assert read_run_log(tmp_path / "v1.jsonl").arm is THESIS_ARM
    _write_log(tmp_path / "none.jsonl")
    lines = (tmp_path / "none.jsonl").read_text().splitlines()
    header = json.loads(lines[0])
    del header["arm"]
    (tmp_path / "none.jsonl").write_text("\n".join([json.dumps(header), *lines[1:]]) + "\n")
    with pytest.raises(RunLogError, match="records no arm"):
        run_motion(read_run_log(tmp_path / "none.jsonl"))
    assert run_motion(read_run_log(tmp_path / "none.jsonl"), arm=THESIS_ARM).arm is THESIS_ARM
