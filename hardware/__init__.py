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

from . import errors
from .analysis import RunAnalysis, analyse
from .driver import PowerCubeArm, PowerCubeModule, open_bus, scan
from .errors import *  # noqa: F403 - the layer's errors, listed in errors.__all__
from .executor import ExecutionOptions, ValidatedTrajectory, ValidationOptions, execute, validate
from .runlog import read_run_log
from .runner import RunReport, RunRequest, run
from .sim import SimulatedArm
from .sources import StepTargets

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
