"""hardware: the PowerCube CAN protocol, driver, simulated arm and executor.

Built on python-can; uses ``iik`` for limits and forward kinematics.

* :mod:`hardware.protocol`: frames <-> typed messages (POWERCUBE.md).
* :class:`PowerCubeModule`, :class:`PowerCubeArm`: the driver (Table V functions), any ``can.BusABC``.
* :class:`hardware.sim.SimulatedArm`: simulated modules served on any bus.
* :func:`validate` / :func:`execute`: validated FSTEP streaming with the early update of Sec 4.3.
* :func:`analyse`: joint and end-effector errors of a run log (Sec 4.3, Figs 46-56).
"""

from .analysis import RunAnalysis, analyse
from .driver import PowerCubeArm, PowerCubeModule, scan
from .errors import (
    BusError,
    CANTimeoutError,
    HardwareError,
    ModuleFault,
    ModuleHalted,
    ProtocolError,
    SafetyError,
)
from .executor import ExecutionOptions, ValidatedTrajectory, ValidationOptions, execute, validate
from .runlog import read_run_log
from .sim import SimulatedArm

__all__ = [
    "PowerCubeModule",
    "PowerCubeArm",
    "SimulatedArm",
    "scan",
    "validate",
    "execute",
    "ValidatedTrajectory",
    "ValidationOptions",
    "ExecutionOptions",
    "analyse",
    "RunAnalysis",
    "read_run_log",
    "HardwareError",
    "ProtocolError",
    "CANTimeoutError",
    "SafetyError",
    "ModuleFault",
    "ModuleHalted",
    "BusError",
]
