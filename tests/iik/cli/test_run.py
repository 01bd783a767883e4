"""``iik run`` end to end: on the in-process simulated arm, and as a process against ``iik sim-arm``.

Where the subject is not real time (what is run, what is written, what is printed), the in-process
simulated modules run on a virtual clock shared with the executor (``simulated_time``), so the runs take
the time of their requests and what they measure does not depend on the machine's load; a run killed
mid-way, the signals and the runs against ``iik sim-arm`` keep real time.
"""

import csv
import functools
import json
import signal
import subprocess
import sys
import threading
import time

import can
import numpy as np
import pytest

import iik
from hardware import protocol as P
from hardware import read_run_log
from iik import THESIS_ARM
from iik.cli import main
from iik.files import PARTIAL_PREFIX

STEMS = ("joint_error", "ee_error", "velocity")
ANGLE = "--margin-deg: must be a finite angle in [0, 90) deg, got "


@pytest.fixture
def simulated_time(monkeypatch):
    """`iik run`'s in-process simulated modules on a :class:`hardware.VirtualClock` (the runner gives the
    executor the modules' clock)."""
    import hardware

    virtual = functools.partial(hardware.SimConfig, clock=hardware.VirtualClock())
    monkeypatch.setattr(hardware, "SimConfig", virtual)


def test_run_demo(tmp_path, capsys, simulated_time):
    # the 30 mm zone of Sec 4.3.2, as typed: the zone verdict is not under test here
    # (test_a_run_outside_its_zone_exits_1 is)
    assert main(["run", "--demo", "--sim-start", "plan", "--zone-mm", "30", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "end-effector error: max" in out and "30 mm zone" in out
    assert out.splitlines()[-1].startswith("status: ok (max end-effector error")
    (log,) = tmp_path.glob("demo-*.jsonl")
    assert read_run_log(log).status == "ok"
    for stem in STEMS:
        assert (tmp_path / f"{log.stem}_{stem}.png").stat().st_size > 1000


def test_a_run_outside_its_zone_exits_1(tmp_path, capsys, simulated_time):
    assert main(["run", "--demo", "--sim-start", "plan", "--lag", "0.2", "--out", str(tmp_path / "r.jsonl"),
                 "--no-figures"]) == 1
    assert "status: outside zone" in capsys.readouterr().out
    assert read_run_log(tmp_path / "r.jsonl").status == "ok"  # it did run to the end


def test_plan_output_runs_as_written_and_run_executes_the_same_trajectory(tmp_path, capsys, simulated_time):
    """`iik plan j --out D` then `iik run --trajectory D/steps.csv` (and D/trajectory.csv): both
    run to the end; `iik run j` executes exactly the step times and joints of D/steps.csv."""
    d = tmp_path / "plan"
    assert main(["plan", "j", "--out", str(d), "--no-figures"]) == 0
    with (d / "steps.csv").open() as f:
        rows = list(csv.DictReader(f))
    t = np.array([float(r["t"]) for r in rows])
    q = np.array([[float(r[f"q{i}"]) for i in range(1, 7)] for r in rows])
    logs = {}
    for name, argv in (("steps", ["--trajectory", str(d / "steps.csv")]),
                       ("dense", ["--trajectory", str(d / "trajectory.csv")]), ("j", ["j"])):
        logs[name] = tmp_path / f"{name}.jsonl"
        argv += ["--sim-start", "plan", "--zone-mm", "30", "--out", str(logs[name]), "--no-figures"]
        assert main(["run", *argv]) == 0, name
        run = read_run_log(logs[name])
        assert run.status == "ok" and list(run.command_k) == list(range(1, len(run.times))), name
    for name in ("steps", "j"):
        run = read_run_log(logs[name])
        np.testing.assert_allclose(run.times, t, atol=1e-9)
        np.testing.assert_allclose(run.q_planned, q, atol=1e-9)
    dense = np.loadtxt(d / "trajectory.csv", delimiter=",", skiprows=1)
    run = read_run_log(logs["dense"])
    np.testing.assert_allclose(run.times, dense[:, 0], atol=1e-9)  # every sample, 9.985 ms steps included
    assert run.times[-1] == pytest.approx(t[-1], abs=0.01)  # one duration: the plan's


def test_speed_is_honoured_with_a_trajectory(tmp_path, capsys, simulated_time):
    q = np.linspace(0, 1, 4)[:, None] * np.array([0.05, 0.04, -0.03, 0.02, 0.1, 0.0])
    path = tmp_path / "traj.csv"
    np.savetxt(path, np.column_stack([np.arange(4) * 0.06, q]), delimiter=",", header="t,q1,q2,q3,q4,q5,q6",
               comments="")
    assert main(["run", "--trajectory", str(path), "--speed", "0.5", "--zone-mm", "30",
                 "--out", str(tmp_path / "a.jsonl"), "--no-figures"]) == 0
    np.testing.assert_allclose(read_run_log(tmp_path / "a.jsonl").times, np.arange(4) * 0.12, atol=1e-9)


def test_run_refuses_an_out_of_limit_csv(tmp_path, capsys):
    q = np.zeros((3, 6))
    q[2, 1] = iik.THESIS_ARM.upper[1] + 0.01
    path = tmp_path / "bad.csv"
    np.savetxt(path, np.column_stack([np.arange(3) * 1.0, q]), delimiter=",",
               header="t,q1,q2,q3,q4,q5,q6", comments="")
    assert main(["run", "--trajectory", str(path), "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert f"SafetyError: {path} line 4 (step-point 2 (counting from 0)), joint q2:" in err
    assert not list(tmp_path.glob("*.jsonl"))


def test_run_needs_one_source(tmp_path, capsys):
    assert main(["run", "--out", str(tmp_path)]) == 2


@pytest.mark.parametrize(("argv", "named"), [
    (["run", "--demo", "--early", "2"], "--early"),
    (["run", "--demo", "--speed", "-1"], "--speed"),
    (["run", "--demo", "--speed", "0"], "--speed"),
    (["run", "--demo", "--margin-deg", "nan"], ANGLE + "nan"),
    (["run", "--demo", "--margin-deg", "-1"], ANGLE + "-1"),
    (["run", "--demo", "--lag", "nan"], "--lag: must be a finite number in [0, 1] s, got nan"),
    (["run", "--demo", "--lag", "-1"], "--lag: must be a finite number in [0, 1] s, got -1.0"),
    (["run", "--demo", "--timeout", "0"], "--timeout: must be a finite number in (0, 10] s, got 0.0"),
    (["run", "--demo", "--bitrate", "-5"], "--bitrate: must be a PowerCube bit rate"),
    (["run", "--demo", "--port", "0"], "--port"),
    (["run", "--demo", "--zone-mm", "0"], "--zone-mm: must be a finite number in (0, 1000] mm, got 0 mm"),
    (["run", "--demo", "--zone-mm", "-5"], "--zone-mm: must be a finite number in (0, 1000] mm, got -5 mm"),
    (["run", "--demo", "--modules", "1", "1", "2", "3", "4", "5"], "--modules"),
    (["run", "--demo", "--update", "sideways"], "--update"),
    (["run", "--demo", "--bogus"], "--bogus"),
    (["run", "--trajectory", "no/such/file.csv"], "--trajectory: cannot read no/such/file.csv: no such file"),
    (["run", "no-such-scenario"], "scenario"),
    (["run", "--demo", "--interface", "no-such-interface", "--channel", "x"], "no-such-interface"),
])
def test_run_bad_input_is_one_line_and_exit_2(argv, named, tmp_path, capfd):
    """Hostile options end in one stderr line naming the option as typed, exit 2, nothing on disk,
    no internal warning."""
    assert main([*argv, "--out", str(tmp_path / "out")]) == 2
    out, err = capfd.readouterr()
    err = err.strip().splitlines()
    # planning/validation notes may come first; the error is the one line after them
    errors = [line for line in err if "error" in line]
    assert len(errors) == 1 and errors[0].startswith("iik run: error: ") and named in errors[0], err
    if not errors[0].startswith(("iik run: error: argument", "iik run: error: unrecognized")):
        # a command line that parses is a run: its status line comes last on stdout
        assert out.strip().splitlines()[-1].startswith("status: error before the run (") and \
            out.strip().endswith("; nothing was executed)"), out
    assert "Traceback" not in "\n".join(err) and "Warning" not in "\n".join(err)
    assert not list((tmp_path / "out").glob("*.jsonl")) if (tmp_path / "out").exists() else True


def test_run_on_a_silent_bus_times_out_cleanly(tmp_path, capfd):
    """No module answers on an empty virtual bus: a CANTimeoutError line, the bus shut down
    (python-can's 'not properly shut down' warning never appears)."""
    assert main(["run", "--demo", "--interface", "virtual", "--channel", f"empty-{tmp_path.name}",
                 "--timeout", "0.05", "--out", str(tmp_path)]) == 2
    err = capfd.readouterr().err
    assert "CANTimeoutError: module 1: no reply" in err and "not properly shut down" not in err
    assert "Traceback" not in err


# ----------------------------------------------------------------------------- as processes
class _Listener:
    """A node on the bus recording every broadcast HALT it sees."""

    def __init__(self, udp):
        self.bus = can.Bus(interface="udp_multicast", channel=udp.group, port=udp.port)
        self.halts = []
        self.done = threading.Event()
        self.thread = threading.Thread(target=self._listen, daemon=True)
        self.thread.start()

    def _listen(self) -> None:
        while not self.done.is_set():
            f = self.bus.recv(0.05)
            if f is not None and f.arbitration_id == P.ID_ALL and bytes(f.data[:1]) == bytes([P.Cmd.HALT]):
                self.halts.append(time.monotonic())

    def close(self) -> None:
        self.done.set()
        self.thread.join(5)
        self.bus.shutdown()


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP])
def test_a_signal_to_iik_run_halts_the_arm_and_completes_the_log(udp_bus, tmp_path, signum):
    """SIGTERM/SIGHUP to a running `iik run` process: HALT on the bus, fault and end records on
    disk, the modules halted, exit 128 + signal, and the message says how to go on (--reset)."""
    udp_bus.start_sim()
    listener = _Listener(udp_bus)
    log = tmp_path / "run.jsonl"
    timeout = udp_bus.request_timeout()  # from a round trip measured now: a loaded machine gets more
    run = udp_bus.process("run", "--demo", *udp_bus.args, "--timeout", timeout, "--out", str(log),
                          "--no-figures")
    try:
        lines = []
        while not any("step 1/" in x for x in lines):  # the arm is moving along the trajectory
            line = run.stderr.readline()
            assert line, (lines, run.stdout.read())
            lines.append(line)
        assert any("watchdog on: WATCHDOG broadcast every 40 ms" in x for x in lines), lines
        run.send_signal(signum)
        rc = run.wait(timeout=30)
        err = lines + run.stderr.read().splitlines()
        out = run.stdout.read().strip().splitlines()
    finally:
        listener.close()
    name = signal.Signals(signum).name
    assert rc == 128 + signum, err
    assert err[-1].startswith(f"iik run: interrupted by {name}; HALT broadcast to every module; the run log "
                              f"{log} ends with the fault; the modules stay halted until reset: run again "
                              "with --reset"), err
    assert out[-1] == f"status: interrupted by {name} (HALT sent; run log {log})", out
    assert listener.halts, "no HALT broadcast seen on the bus"
    assert "not properly shut down" not in "\n".join(err) and "Traceback" not in "\n".join(err)
    records = read_run_log(log).records
    fault, end = records[-2:]
    assert fault["type"] == "fault" and fault["error"] == "StopSignal" and fault["halted"] is True
    assert fault["message"] == f"stopped by {name}"
    assert end == {"type": "end", "t": end["t"], "status": "fault"}
    from hardware import PowerCubeArm

    with PowerCubeArm.from_interface(interface="udp_multicast", channel=udp_bus.group, port=udp_bus.port,
                                     timeout=float(timeout), arm=THESIS_ARM) as arm:
        assert all(s & P.State.HALTED for s in arm.states())  # latched until --reset
    again = udp_bus.process("run", "--demo", *udp_bus.args, "--timeout", timeout, "--out",
                            str(tmp_path / "a"))
    _, err2 = again.communicate(timeout=60)
    assert again.returncode == 2 and "halted" in err2 and "iik run --reset" in err2, err2


def test_two_sim_arms_on_one_channel_are_a_fault(udp_bus, tmp_path):
    """Two `iik sim-arm` on one channel: every module id answers twice; the run stops before
    anything moves, with one line, and every bus is shut down."""
    udp_bus.start_sim()
    timeout = udp_bus.request_timeout()  # measured while one answers
    udp_bus.start_sim()
    run = udp_bus.process("run", "--demo", *udp_bus.args, "--timeout", timeout, "--out", str(tmp_path),
                          "--no-figures")
    _, err = run.communicate(timeout=300)
    assert run.returncode == 2, err
    (line,) = [x for x in err.splitlines() if "error" in x]
    assert line.startswith("iik run: error: DuplicateModuleError: module 1: two answers to GETPARAM VERSION")
    assert "not properly shut down" not in err and "Traceback" not in err
    assert not list(tmp_path.glob("*.jsonl"))


def test_a_run_killed_outright_leaves_the_previous_log_and_keeps_its_records_aside(tmp_path, capsys):
    """The run log is written beside its name and moved there when closed: SIGKILL (no cleanup
    possible) mid-run leaves the earlier `--out r.jsonl` exactly as it was, and the killed run's
    records, flushed line by line, in its `.partial-*-r.jsonl` sibling."""
    q = np.linspace(0, 1, 12)[:, None] * np.array([0.2, 0.1, -0.1, 0.1, 0.3, 0.0])
    path = tmp_path / "traj.csv"
    with path.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t"] + [f"q{i}" for i in range(1, 7)])
        for k, row in enumerate(q):
            w.writerow([f"{0.3 * k:.3f}"] + [f"{v:.6f}" for v in row])
    log = tmp_path / "r.jsonl"
    argv = ["run", "--trajectory", str(path), "--sim-start", "plan", "--zone-mm", "30", "--out", str(log),
            "--no-figures"]
    assert main(argv) == 0
    before = log.read_bytes()
    proc = subprocess.Popen([sys.executable, "-m", "iik.cli", *argv], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    try:
        lines = []
        while not any("step 2/" in x for x in lines):  # the log has records
            line = proc.stderr.readline()
            assert line, lines
            lines.append(line)
        proc.kill()
        proc.wait(timeout=30)
    finally:
        proc.kill()
    assert log.read_bytes() == before and read_run_log(log).status == "ok"
    (partial,) = [p for p in tmp_path.iterdir() if p.name.startswith(PARTIAL_PREFIX)]
    assert partial.name.endswith("-r.jsonl")
    kinds = [json.loads(line)["type"] for line in partial.read_text().splitlines()]
    assert kinds[0] == "header" and "command" in kinds and "end" not in kinds
