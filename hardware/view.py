"""Show a run log in the 3D viewer: the commanded and the measured arm side by side.

Reads a JSON-lines run log (:func:`hardware.runlog.read_run_log`, format versions
:data:`hardware.runlog.READ_VERSIONS`) and turns it into a neutral
:class:`iik.planning.viewer.motion.Motion` of the arm the log records
(:func:`hardware.runlog.run_arm`: its FK and its body) at the sample times:

* **commanded**: the target of the step the modules were executing at each sample
  (:func:`commanded_steps`; header ``q`` at that step) [rad]. With the thesis's early
  update (Sec 4.3) a step starts when its command is sent; with the buffered update a
  command waits in the modules' buffer until the previous step ends (``step_end``
  records), so the last command sent is not yet the one being executed;
* **measured**: the positions the modules reported (``sample`` records) [rad].

The measured arm stands :data:`SIDE_BY_SIDE` m along +y from the commanded one,
each on its own platform. Every frame notes the largest joint difference [deg]
and the tool-position difference [mm] (FK of the log's arm for both) between the measured arm
and the commanded target (during a step the arm is still on its way to it).
"""

from __future__ import annotations

import os

import numpy as np

from iik import Arm, fk
from iik.planning.viewer import Shown, ViewOptions, show, style
from iik.planning.viewer.motion import Motion, MotionView, Track
from iik.scene import Box

from .errors import RunLogError
from .runlog import READ_VERSIONS, RUN_LOG_VERSION, Run, read_run_log, run_arm

__all__ = ["SIDE_BY_SIDE", "LOG_VERSION", "commanded_steps", "run_motion", "run_obstacles", "run_warnings",
           "view_run", "side_by_side"]

#: Least offset of the measured arm along +y [m] (the thesis arm reaches about 0.9 m); a longer arm
#: stands farther away (:func:`side_by_side`).
SIDE_BY_SIDE = 1.2

#: The run-log format version this view was written for (header ``version``; it reads every one of
#: :data:`hardware.runlog.READ_VERSIONS`).
LOG_VERSION = RUN_LOG_VERSION


def side_by_side(arm: Arm) -> float:
    """Offset [m] along +y of the measured arm: :data:`SIDE_BY_SIDE`, or the arm's reach bound
    (:attr:`iik.Arm.reach`) for an arm that reaches farther."""
    return max(SIDE_BY_SIDE, round(arm.reach, 1))


def commanded_steps(run: Run) -> np.ndarray:
    """(m,) index of the target the modules were executing at each sample.

    The last command sent (the sample's ``k``), except with the buffered update, where
    a queued step starts only when the previous one ends (its ``step_end`` record): then
    it is the first step that had not ended at the sample's time.
    """
    k = run.samples_k.copy()
    if run.step_end:
        steps = np.array(sorted(run.step_end))
        ends = np.array([run.step_end[s] for s in steps])
        in_progress = steps[np.minimum(np.searchsorted(ends, run.samples_t, side="right"), len(steps) - 1)]
        k = np.minimum(k, in_progress)
    return k


def _fault(run: Run) -> str:
    f = run.fault
    if not f:
        return ""
    halt = "HALT sent" if f.get("halted") else "HALT not confirmed"
    return f"; fault: {f.get('error', 'error')}: {f.get('message', '')} ({halt})"


def _headline(run: Run, name: str, k: np.ndarray, dq: np.ndarray, dp: np.ndarray, arm: Arm) -> str:
    """Counts, duration, update mode, status, fault; the largest differences during the planned steps."""
    t, steps = run.samples_t, k >= 1  # step 0: the start (an approach reaches it when the arm was elsewhere)
    largest = (f"Largest difference to the target during the planned steps {dq[steps].max():.2f} deg, "
               f"{dp[steps].max():.1f} mm at the tool" if steps.any() else "No planned step was commanded")
    approached = 0 in run.command_k and steps.any()
    approach = f", approach to the start {t[steps][0] - t[0]:.2f} s" if approached else ""
    status = run.status or "incomplete (no end record)"
    return (f"Run log {name}: arm {arm.name!r}, {len(run.command_t)} commands, {len(t)} samples, "
            f"{t[-1] - t[0]:.2f} s{approach}, {run.header.get('update', 'thesis')} update, status "
            f"{status}{_fault(run)}. Commanded target at the base; measured beside it "
            f"(+{side_by_side(arm):g} m along y). {largest}.")


def run_motion(run: Run, *, name: str = "run", arm: Arm | None = None) -> Motion:
    """The commanded and measured arms of a parsed run log, at its sample times, drawn as the arm the
    log records (``arm``, if given, must be that arm: :func:`hardware.runlog.run_arm`)."""
    arm = run_arm(run, arm)
    if len(run.samples_t) == 0:
        raise RunLogError(f"{name}: the run log has no samples to show")
    if len(run.q_planned) == 0:
        raise RunLogError(f"{name}: the run log's header has no planned trajectory")
    if np.any(run.samples_k < 0) or np.any(run.samples_k >= len(run.q_planned)):
        raise RunLogError(f"{name}: a sample names a target outside the planned trajectory")
    k = commanded_steps(run)
    cmd, meas = run.q_planned[k], run.samples_q
    if not np.all(np.isfinite(meas)):
        raise RunLogError(f"{name}: measured positions contain non-finite values")
    dq = np.degrees(np.abs(meas - cmd).max(axis=1))
    dp = np.linalg.norm(fk(meas, arm)[:, :3, 3] - fk(cmd, arm)[:, :3, 3], axis=1) * 1000
    notes = tuple(f"step {s}: measured - commanded target: joints {a:.2f} deg, tool {b:.1f} mm"
                  for s, a, b in zip(k, dq, dp, strict=True))
    return Motion(title=f"iik view: run {name}", t=run.samples_t - run.samples_t[0],
                  headline=_headline(run, name, k, dq, dp, arm), notes=notes, warnings=run_warnings(run),
                  obstacles=run_obstacles(run, name),
                  tracks=(Track("commanded target", cmd, style.ARM),
                          Track(f"measured arm (PCube_getPos), +{side_by_side(arm):g} m along y", meas,
                                style.MEASURED, (0.0, side_by_side(arm), 0.0))), arm=arm)


def run_obstacles(run: Run, name: str = "run") -> tuple[Box, ...]:
    """The scenario's boxes recorded in the log's header (none for a CSV or demo run)."""
    def box(b: dict) -> Box:
        return Box(center=tuple(float(v) for v in b["center"]), size=tuple(float(v) for v in b["size"]),
                        name=str(b["name"]), kind=str(b["kind"]))

    try:
        return tuple(box(b) for b in run.header.get("obstacles", ()))
    except (KeyError, TypeError, ValueError) as exc:
        raise RunLogError(f"{name}: the header's obstacles do not parse ({exc})") from None


def run_warnings(run: Run) -> tuple[str, ...]:
    """What the view cannot show faithfully: a log format it does not know, an arm rebuilt from the
    log's numbers (its URDF file is gone or changed: its body is generated, not the file's)."""
    out = []
    version = run.header.get("version", LOG_VERSION)
    if version not in READ_VERSIONS:
        out.append(f"run-log format version {version}; this viewer reads versions "
                   f"{', '.join(map(str, READ_VERSIONS))}")
    rec = run.header.get("arm")
    if isinstance(rec, dict) and rec.get("urdf") and run.arm is not None and not run.arm.urdf:
        out.append(f"the run's arm {run.arm.name!r} was read from {rec['urdf']}, which is missing or "
                   "changed: it is drawn with shapes generated along its links")
    return tuple(out)


def view_run(path: str | os.PathLike, options: ViewOptions | None = None, *, arm: Arm | None = None) -> Shown:
    """Serve or export (``options.export``) the run log at ``path``; see :func:`iik.planning.viewer.present`.
    The arm is the one the log records; ``arm``, if given, must be that arm.

    Raises:
        RunLogError: The log is missing, malformed or has no samples, or records no arm and none is given.
        InvalidInputError: (``arm``) ``arm`` is not the arm the log records.
    """
    motion = run_motion(read_run_log(path), name=os.fspath(path), arm=arm)
    return show(MotionView(motion), options or ViewOptions(), headline=motion.headline)
