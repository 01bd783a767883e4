"""Benchmark: forward kinematics and Jacobians, iik (NumPy, batched) vs Pinocchio (per q).

Run: ``python benchmarks/bench_kinematics.py [n]``. Prints the median time per
configuration of each method over several repetitions, and its ratio to the
baseline (Pinocchio ``framesForwardKinematics`` in a Python loop) measured in
the same run.
"""

from __future__ import annotations

import sys

import numpy as np
import pinocchio as pin

import iik
from iik import THESIS_ARM
from iik.planning.robot_model import thesis_model
from verification.testing.strategies import sample_joints
from verification.testing.timing import median_seconds


def main(n: int = 2000) -> None:
    qs = sample_joints(np.random.default_rng(0), n)
    tm = thesis_model(THESIS_ARM)
    data = tm.model.createData()

    def pin_fk():
        for q in qs:
            pin.framesForwardKinematics(tm.model, data, q)

    def pin_jac():
        for q in qs:
            pin.computeFrameJacobian(tm.model, data, q, tm.tool_frame_id, pin.LOCAL_WORLD_ALIGNED)

    cases = {
        "pinocchio FK, loop (baseline)": pin_fk,
        "iik.fk (Eq 4), batch": lambda: iik.fk(qs, THESIS_ARM),
        "iik.fk_chain (Table II product), batch": lambda: iik.fk_chain(qs, THESIS_ARM),
        "iik.fk (Eq 4), loop": lambda: [iik.fk(q, THESIS_ARM) for q in qs[: n // 10]],
        "pinocchio frame Jacobian, loop": pin_jac,
        "iik.jacobian (6x6), batch": lambda: iik.jacobian(qs, THESIS_ARM),
        "iik.position_jacobian (App C), batch": lambda: iik.position_jacobian(qs, THESIS_ARM),
    }
    per = {}
    for name, fn in cases.items():
        m = n // 10 if name.endswith("loop") and name.startswith("iik") else n
        per[name] = median_seconds(fn) / m
    base = per["pinocchio FK, loop (baseline)"]
    print(f"n = {n} configurations; median time per configuration")
    for name, t in per.items():
        print(f"  {name:<42s} {t * 1e6:8.2f} us   x{base / t:6.2f} vs baseline")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 2000)
