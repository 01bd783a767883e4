"""Benchmark: PowerCube request round trips on python-can's virtual bus.

Run: ``python benchmarks/bench_hardware.py [n]``. Prints the median time of

* the baseline: a raw frame echoed by a bare python-can thread (no protocol),
* one driver request (GETPARAM ACT_FPOS: encode, send, echo rule, decode) answered
  by ``hardware.sim.SimulatedArm``,
* one executor sample (state, position, velocity, current of six modules: 24 requests),
* protocol encode+decode alone,
* one FSTEP command of six modules, unchecked (six SETMOVE requests) and through
  ``PowerCubeArm.move_step`` (limits and the step's speed checked against FMAXVEL first),

each with its ratio to the raw-echo baseline measured in the same run. The executor's
sample budget follows from it: a 50 ms FSTEP leaves room for a few samples. Last, parsing
a 10 000-line trajectory CSV (``hardware.sources.csv_trajectory``: line/column errors, plain
decimals) against ``numpy.loadtxt`` of the same file.
"""

from __future__ import annotations

import sys
import tempfile
import threading
import uuid
from pathlib import Path

import can
import numpy as np

from hardware import PowerCubeArm, SimulatedArm
from hardware import protocol as P
from hardware.sources import csv_trajectory
from iik import THESIS_ARM
from verification.testing.timing import median_seconds


def _raw_echo_baseline(n: int) -> float:
    ch = f"bench-{uuid.uuid4().hex}"
    stop = threading.Event()
    a, b = can.Bus(interface="virtual", channel=ch), can.Bus(interface="virtual", channel=ch)

    def echo():
        while not stop.is_set():
            f = b.recv(0.002)
            if f is not None:
                b.send(can.Message(arbitration_id=0x0A1, data=f.data, is_extended_id=False))

    th = threading.Thread(target=echo, daemon=True)
    th.start()
    frame = can.Message(arbitration_id=0x0C1, data=[0x0A, 0x3C], is_extended_id=False)

    def once():
        a.send(frame)
        a.recv(1.0)

    try:
        return median_seconds(once, 5, calls=n)
    finally:
        stop.set()
        th.join()
        a.shutdown()
        b.shutdown()


def main(n: int = 500) -> None:
    base = _raw_echo_baseline(n)
    ch = f"bench-{uuid.uuid4().hex}"
    with SimulatedArm.virtual(ch, arm=THESIS_ARM), can.Bus(interface="virtual", channel=ch) as bus:
        arm = PowerCubeArm(bus, (1, 2, 3, 4, 5, 6), timeout=1.0, arm=THESIS_ARM)
        m = arm.modules[0]
        req = median_seconds(m.get_pos, 5, calls=n)

        def sample():
            for mod in arm.modules:
                for par in (P.Param.STATE, P.Param.ACT_FPOS, P.Param.ACT_FVEL, P.Param.ACT_FCUR):
                    mod.get_param(par)

        smp = median_seconds(sample, 5, calls=max(n // 24, 5))
        flip = [0.0]

        def raw_step():
            flip[0] = 0.01 - flip[0]
            for mod in arm.modules:
                arm.link.request(P.SetMove(mod.id, P.Mode.FSTEP, flip[0], 100))

        def checked_step():
            flip[0] = 0.01 - flip[0]
            arm.move_step(np.full(6, flip[0]), 0.1)

        raw = median_seconds(raw_step, 5, calls=max(n // 6, 5))
        checked = median_seconds(checked_step, 5, calls=max(n // 6, 5))
    msg = P.GetParam(1, P.Param.ACT_FPOS)
    reply = P.encode(P.ParamReply(1, P.Param.ACT_FPOS, 0.5))
    codec = median_seconds(lambda: (P.encode(msg), P.decode(reply)), 5, calls=n * 10)
    print(f"{'what':44s} {'median':>10s} {'x baseline':>10s}")
    for name, t in (("raw echo on virtual (baseline)", base),
                    ("driver request GETPARAM (SimulatedArm)", req),
                    ("executor sample, 6 modules x 4 requests", smp),
                    ("protocol encode + decode", codec),
                    ("FSTEP x 6, unchecked SETMOVE requests", raw),
                    ("FSTEP x 6, PowerCubeArm.move_step (checked)", checked)):
        print(f"{name:44s} {t * 1e6:8.1f} us {t / base:10.2f}")
    _csv_bench()


def _csv_bench(lines: int = 10_000) -> None:
    """csv_trajectory vs numpy.loadtxt on the same file (the baseline of this row)."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "t.csv"
        q = np.linspace(0, 1, lines)[:, None] * np.full(6, 0.3)
        np.savetxt(path, np.column_stack([np.arange(lines) * 0.01, q]), delimiter=",", fmt="%.9f",
                   header="t,q1,q2,q3,q4,q5,q6", comments="")
        base = median_seconds(lambda: np.loadtxt(path, delimiter=",", skiprows=1), 5)
        ours = median_seconds(lambda: csv_trajectory(path, THESIS_ARM), 5)
    print(f"{'CSV ' + str(lines) + ' lines, numpy.loadtxt (baseline)':44s} {base * 1e3:8.1f} ms {1.0:10.2f}")
    print(f"{'CSV ' + str(lines) + ' lines, csv_trajectory':44s} {ours * 1e3:8.1f} ms {ours / base:10.2f}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 500)
