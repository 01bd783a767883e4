"""Errors of an executed run, the analogues of the thesis's Figs 46-56 (Sec 4.3).

For each step-point k the measured joints are the actual positions the modules
reported in their ACKs to command k+1 (extended FSTEP), i.e. where the arm was when
the thesis's early update moved on; with the buffered update they are interpolated
from the samples at the end of step k on the modules' timeline; for the last
step-point (and for logs without them) they are the last sample logged for that
step, after settling.
The end-effector position is FK (Eq 4) of the measured joints, as in Sec 4.3 ("it
was calculated by inputting the obtained experimental joint angles into the forward
kinematics expression"), compared with the planned pose's position.

Sec 4.3.1 chose a 10 mm safety zone from the predefined paths; Sec 4.3.2 suggests
30 mm in motion (the planner's zone, :data:`iik.safety.SAFETY_ZONE`).
:attr:`RunAnalysis.max_ee_error` is compared with both.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from iik.arm import Arm
from iik.files import atomic_output
from iik.kinematics import fk
from iik.safety import SAFETY_ZONE, SAFETY_ZONE_PREDEFINED

from .errors import RunLogError
from .runlog import Run, run_arm

__all__ = ["RunAnalysis", "analyse", "plot_run", "summary_text", "SAFETY_ZONE_PREDEFINED"]



@dataclass(frozen=True)
class RunAnalysis:
    """Step-point errors of one run (SI units).

    Attributes:
        steps: (m,) step-point indices with a measurement.
        t: (m,) time of each step-point measurement [s].
        q_planned, q_measured: (m,6) [rad].
        joint_error: (m,6) measured - planned [rad].
        ee_error: (m,) |p(FK(q_measured)) - p(planned pose)| [m].
        samples_t, samples_dq: all samples' times [s] and joint velocities [rad/s].
        status: ``"ok"``, ``"fault"`` or ``None`` (incomplete log).
        arm: The arm whose FK gave the end-effector errors (the one the log records).
    """

    steps: np.ndarray
    t: np.ndarray
    q_planned: np.ndarray
    q_measured: np.ndarray
    joint_error: np.ndarray
    ee_error: np.ndarray
    samples_t: np.ndarray
    samples_dq: np.ndarray
    status: str | None
    arm: Arm

    @property
    def max_ee_error(self) -> float:
        return float(np.max(self.ee_error))

    @property
    def mean_ee_error(self) -> float:
        return float(np.mean(self.ee_error))

    @property
    def start_ee_error(self) -> float:
        return float(self.ee_error[0])

    @property
    def final_ee_error(self) -> float:
        return float(self.ee_error[-1])

    @property
    def max_joint_error(self) -> np.ndarray:
        return np.max(np.abs(self.joint_error), axis=0)

    @property
    def mean_joint_error(self) -> np.ndarray:
        return np.mean(np.abs(self.joint_error), axis=0)

    def within(self, zone: float = SAFETY_ZONE) -> bool:
        """Does the largest end-effector error stay inside a safety zone of ``zone`` m?"""
        return self.max_ee_error <= zone


def analyse(run: Run, arm: Arm | None = None) -> RunAnalysis:
    """Step-point joint and end-effector errors of a parsed run log, with the FK of the arm the log
    records (:func:`hardware.runlog.run_arm`; ``arm``, if given, must be that arm).

    Raises:
        RunLogError: no samples, or the log records no arm and none is given.
        InvalidInputError: (``arm``) ``arm`` is not the arm the log records.
    """
    arm = run_arm(run, arm)
    if len(run.samples_t) == 0:
        raise RunLogError("run log has no samples")
    at_send = {int(k): (float(t), qm) for t, k, qm in
               zip(run.command_t, run.command_k, run.command_q_meas, strict=True) if np.all(np.isfinite(qm))}
    steps, ts, qs = [], [], []
    for k in range(len(run.times)):
        hits = np.flatnonzero(run.samples_k == k)
        if k in run.step_end and k < len(run.times) - 1:  # buffered: where the arm was at the step end
            t = run.step_end[k]
            q = np.array([np.interp(t, run.samples_tq[:, j], run.samples_q[:, j])
                          for j in range(run.samples_q.shape[1])])
        elif k + 1 in at_send:  # measured by the ACK of command k+1 (extended FSTEP)
            t, q = at_send[k + 1]
        elif len(hits):  # last step-point (after settling), or a run that stopped here
            t, q = float(run.samples_t[hits[-1]]), run.samples_q[hits[-1]]
        else:
            continue
        steps.append(k)
        ts.append(t)
        qs.append(q)
    steps = np.asarray(steps, dtype=int)
    qm = np.asarray(qs, dtype=float)
    qp = run.q_planned[steps]
    p_meas = fk(qm, arm)[:, :3, 3]  # Eq 4 on the measured joints, as in Sec 4.3
    ee = np.linalg.norm(p_meas - run.poses[steps, :3, 3], axis=1)
    return RunAnalysis(steps=steps, t=np.asarray(ts), q_planned=qp, q_measured=qm,
                       joint_error=qm - qp, ee_error=ee, samples_t=run.samples_t,
                       samples_dq=run.samples_dq, status=run.status, arm=arm)


def summary_text(a: RunAnalysis, name: str = "run") -> str:
    """Human-readable summary (mm and degrees for display)."""
    done = {"ok": "executed to the end", "fault": "stopped by a fault"}.get(a.status, "incomplete log")
    lines = [
        f"{name}: {len(a.steps)} step-points measured, {done}",
        f"  end-effector error: max {a.max_ee_error * 1e3:.2f} mm, mean {a.mean_ee_error * 1e3:.2f} mm, "
        f"start {a.start_ee_error * 1e3:.2f} mm, end {a.final_ee_error * 1e3:.2f} mm",
        "  max |joint error| [deg]: " + " ".join(f"{np.degrees(v):.3f}" for v in a.max_joint_error),
        f"  within the 10 mm zone of Sec 4.3.1: {a.within(SAFETY_ZONE_PREDEFINED)}; "
        f"within the 30 mm zone of Sec 4.3.2: {a.within(SAFETY_ZONE)}",
    ]
    return "\n".join(lines)


def plot_run(a: RunAnalysis, out_dir, stem: str = "run") -> list[Path]:
    """Write three PNG figures (joint errors, EE error, joint velocities), each whole or not at
    all (:func:`iik.files.atomic_output`); returns their paths."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = Path(out_dir)

    def figure(name: str, draw, xlabel: str, ylabel: str, title: str, **legend) -> Path:
        fig, ax = plt.subplots(figsize=(7, 3.5))
        draw(ax)
        ax.set(xlabel=xlabel, ylabel=ylabel, title=title)
        ax.legend(**legend)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        with atomic_output(out / f"{stem}_{name}.png", "out", folder=False) as png:  # whole or not at all
            fig.savefig(png.path, dpi=110, format="png")
        plt.close(fig)
        return png.target

    def joints(ax, x, y) -> None:
        for j in range(y.shape[1]):
            ax.plot(x, y[:, j], label=f"joint {j + 1}")

    def ee(ax) -> None:
        ax.plot(a.steps, a.ee_error * 1e3, "k.-", label="|FK(measured) - planned|")
        ax.axhline(SAFETY_ZONE_PREDEFINED * 1e3, color="tab:orange", ls="--", label="10 mm (Sec 4.3.1)")
        ax.axhline(SAFETY_ZONE * 1e3, color="tab:red", ls="--", label="30 mm (Sec 4.3.2)")

    return [
        figure("joint_error", lambda ax: joints(ax, a.steps, np.degrees(a.joint_error)), "step-point",
               "measured - planned [deg]", "Joint error (analogue of Figs 46, 48, 50, 52)", ncol=3,
               fontsize=7),
        figure("ee_error", ee, "step-point", "end-effector error [mm]",
               f"End-effector error (analogue of Figs 47, 53): max {a.max_ee_error * 1e3:.1f} mm, "
               f"mean {a.mean_ee_error * 1e3:.1f} mm", fontsize=7),
        figure("velocity", lambda ax: joints(ax, a.samples_t, a.samples_dq), "time [s]",
               "measured velocity [rad/s]", "Joint velocities (analogue of Fig 56, PCube_getVel)",
               ncol=3, fontsize=7),
    ]
