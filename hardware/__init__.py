"""hardware: the PowerCube CAN protocol, driver, simulated arm, executor and runs.

Built on python-can; uses ``iik`` for limits and forward kinematics and ``iik.planning``
for planned scenarios.

* :mod:`hardware.protocol`: frames <-> typed messages (docs/POWERCUBE.md).
* :class:`PowerCubeModule`, :class:`PowerCubeArm`: the driver (Table V functions), any ``can.BusABC``.
* :class:`hardware.sim.SimulatedArm`: simulated modules served on any bus (:func:`hardware.sim.serve`).
* :func:`validate` / :func:`execute`: validated FSTEP streaming with the early update of Sec 4.3.
* :func:`analyse`: joint and end-effector errors of a run log (Sec 4.3, Figs 46-56).
* :mod:`hardware.sources`: step targets from a scenario, a CSV file or the demo line.
* :func:`run`: one run end to end (:class:`RunRequest` -> :class:`RunReport`), behind ``iik run``.
* :mod:`hardware.errors`: every error of the layer, under :class:`iik.errors.IIKError`.
"""

from iik.extras import require
from iik.lazy import lazy_exports

from . import errors  # light: the layer's errors, re-exported

require("hardware", __name__)

__getattr__, __dir__ = lazy_exports(__name__, {
    ".analysis": ("RunAnalysis", "analyse"),
    ".driver": ("PowerCubeArm", "PowerCubeModule", "open_bus", "scan"),
    ".errors": tuple(errors.__all__),
    ".executor": ("ExecutionOptions", "ValidatedTrajectory", "ValidationOptions", "execute", "validate"),
    ".runlog": ("read_run_log",),
    ".runner": ("RunReport", "RunRequest", "run"),
    ".sim": ("SimulatedArm",),
    ".sources": ("StepTargets",),
})

__all__ = [
    "PowerCubeModule",
    "PowerCubeArm",
    "SimulatedArm",
    "open_bus",
    "scan",
    "validate",
    "execute",
    "ValidatedTrajectory",
    "ValidationOptions",
    "ExecutionOptions",
    "analyse",
    "RunAnalysis",
    "read_run_log",
    "StepTargets",
    "RunRequest",
    "RunReport",
    "run",
    *errors.__all__,
]
