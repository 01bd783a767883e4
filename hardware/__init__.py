"""hardware: the PowerCube CAN protocol, driver, simulated arm, executor and runs.

Built on python-can; uses ``iik`` for limits and forward kinematics and ``iik.planning``
for planned scenarios.

* :mod:`hardware.protocol`: frames <-> typed messages (docs/POWERCUBE.md).
* :class:`BusConfig`: where the modules are (a python-can bus, their ids, the ACK timeout), validated once;
  with a :class:`SimConfig` simulated modules are attached to it in this process (:mod:`hardware.bus`).
* :class:`PowerCubeModule`, :class:`PowerCubeArm`: the driver (Table V functions), any ``can.BusABC``.
* :class:`hardware.sim.SimulatedArm`: simulated modules served on any bus (:func:`hardware.sim.serve`),
  on real time or a :class:`VirtualClock` (:mod:`hardware.clock`).
* :func:`validate` / :func:`execute`: validated FSTEP streaming with the early update of Sec 4.3.
* :func:`analyse`: joint and end-effector errors of a run log (Sec 4.3, Figs 46-56).
* :mod:`hardware.sources`: step targets from a scenario, a CSV file or the demo line.
* :func:`run`: one run end to end (``run(targets, bus, options, log)`` -> :class:`RunReport`), behind
  ``iik run``.
* :mod:`hardware.errors`: every error of the layer, under :class:`iik.errors.IIKError`.
"""

from iik.extras import require
from iik.lazy import lazy_exports

from . import errors  # light: the layer's errors, re-exported

require("hardware", __name__)

__getattr__, __dir__ = lazy_exports(__name__, {
    ".analysis": ("RunAnalysis", "analyse"),
    ".bus": ("BusConfig", "SimConfig", "open_bus"),
    ".clock": ("VirtualClock", "REAL_TIME"),
    ".driver": ("PowerCubeArm", "PowerCubeModule", "scan"),
    ".errors": tuple(errors.__all__),
    ".executor": ("ExecutionOptions", "ValidatedTrajectory", "ValidationOptions", "execute", "validate"),
    ".runlog": ("read_run_log",),
    ".runner": ("RunOptions", "RunReport", "run"),
    ".sim": ("SimulatedArm",),
    ".sources": ("StepTargets",),
})

__all__ = [
    "BusConfig",
    "SimConfig",
    "VirtualClock",
    "REAL_TIME",
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
    "RunOptions",
    "RunReport",
    "run",
    *errors.__all__,
]
