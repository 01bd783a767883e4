"""Show a run log in the 3D viewer: the commanded and the measured arm side by side.

Reads a JSON-lines run log (:func:`hardware.runlog.read_run_log`) and turns it
into a neutral :class:`iik.planning.viewer.motion.Motion` at the sample times:

* **commanded**: the target of the last command sent before each sample
  (header ``q`` at the sample's ``k``) [rad]: what the modules were told to reach;
* **measured**: the positions the modules reported (``sample`` records) [rad].

The measured arm stands :data:`SIDE_BY_SIDE` m along +y from the commanded one,
each on its own platform. Every frame notes the largest joint error [deg]
and the tool-position error [mm] (Eq 4 FK of both) between the two.
"""

from __future__ import annotations

import os

import numpy as np

from iik import fk
from iik.planning.viewer import Shown, ViewOptions, show, style
from iik.planning.viewer.motion import Motion, MotionView, Track

from .errors import RunLogError
from .runlog import Run, read_run_log

__all__ = ["SIDE_BY_SIDE", "run_motion", "view_run"]

#: Offset of the measured arm along +y [m] (the arm reaches about 0.9 m).
SIDE_BY_SIDE = 1.2


def run_motion(run: Run, *, name: str = "run") -> Motion:
    """The commanded and measured arms of a parsed run log, at its sample times."""
    if len(run.samples_t) == 0:
        raise RunLogError(f"{name}: the run log has no samples to show")
    if len(run.q_planned) == 0:
        raise RunLogError(f"{name}: the run log's header has no planned trajectory")
    t = run.samples_t
    if np.any(run.samples_k < 0) or np.any(run.samples_k >= len(run.q_planned)):
        raise RunLogError(f"{name}: a sample names a target outside the planned trajectory")
    cmd = run.q_planned[run.samples_k]
    meas = run.samples_q
    if not np.all(np.isfinite(meas)):
        raise RunLogError(f"{name}: measured positions contain non-finite values")
    dq = np.degrees(np.abs(meas - cmd).max(axis=1))
    dp = np.linalg.norm(fk(meas)[:, :3, 3] - fk(cmd)[:, :3, 3], axis=1) * 1000
    notes = tuple(f"max joint error {a:.2f} deg, tool error {b:.1f} mm" for a, b in zip(dq, dp, strict=True))
    status = run.status or "incomplete (no end record)"
    headline = (f"Run log {name}: {len(run.command_t)} commands, {len(t)} samples, {t[-1]:.2f} s, "
                f"status {status}" + (f"; fault: {run.fault.get('message', '')}" if run.fault else "")
                + f". Commanded (target of the last command) at the base; measured beside it "
                  f"(+{SIDE_BY_SIDE} m along y). Largest joint error {dq.max():.2f} deg, "
                  f"tool error {dp.max():.1f} mm.")
    return Motion(
        title=f"iik view: run {name}", t=t - t[0], headline=headline, notes=notes,
        tracks=(Track("commanded", cmd, style.ARM),
                Track("measured", meas, style.MEASURED, (0.0, SIDE_BY_SIDE, 0.0))),
    )


def view_run(path: str | os.PathLike, options: ViewOptions | None = None) -> Shown:
    """Serve or export (``options.export``) the run log at ``path``; see :func:`iik.planning.viewer.present`.

    Raises:
        RunLogError: The log is missing, malformed or has no samples.
    """
    motion = run_motion(read_run_log(path), name=os.fspath(path))
    return show(MotionView(motion), options or ViewOptions(), headline=motion.headline)
