"""Typed errors of the ``hardware`` package, all rooted in :class:`iik.errors.IIKError`.

Each also derives from the matching built-in so generic handlers keep working:
a malformed frame is a ``ValueError``, a missing reply a ``TimeoutError``.

:class:`StopSignal` (defined in :mod:`iik.signals`, listed here with the layer's errors) is
the exception: SIGTERM or SIGHUP during a run is a ``KeyboardInterrupt`` (like Ctrl-C),
not an error, so that no ``except Exception`` swallows it before the arm is halted.
"""

from __future__ import annotations

from iik.errors import IIKError, Remedy
from iik.signals import StopSignal

__all__ = [
    "HardwareError",
    "ProtocolError",
    "CANTimeoutError",
    "SafetyError",
    "ModuleFault",
    "ModuleHalted",
    "DuplicateModuleError",
    "SecondControllerError",
    "BusError",
    "RunLogError",
    "SimulatorError",
    "StopSignal",
]


class HardwareError(IIKError):
    """Root of the errors raised by :mod:`hardware`."""


class ProtocolError(HardwareError, ValueError):
    """A CAN frame cannot be encoded or decoded as a PowerCube message.

    Attributes:
        reason: Human-readable reason, naming the offending field.
    """

    def __init__(self, reason: str):
        self.reason = reason
        super().__init__(reason)


class CANTimeoutError(HardwareError, TimeoutError):
    """No echoing reply arrived in time.

    Attributes:
        module_id: The module that did not answer.
        request: Short description of the request, e.g. ``"GETPARAM 0x3c"``.
        timeout: The time waited [s].
    """

    def __init__(self, module_id: int, request: str, timeout: float):
        self.module_id = module_id
        self.request = request
        self.timeout = timeout
        super().__init__(f"module {module_id}: no reply to {request} within {timeout * 1e3:.0f} ms")


class SafetyError(HardwareError, ValueError):
    """A command was refused before reaching the bus (limit, non-finite value, halted module).

    Attributes:
        argument: What was refused, as a user reads it, e.g. ``"step-point 12 (counting
            from 0), joint q4"`` or ``"traj.csv line 14 (step-point 12 ...), joint q4"``.
        reason: Why.
        step: Index of the refused step-point (from 0), or None.
        joint: Index of the refused joint (from 0; joint ``q{joint + 1}``), or None.
    """

    def __init__(self, argument: str, reason: str, *, step: int | None = None, joint: int | None = None,
                 remedy: Remedy | None = None):
        self.argument = argument
        self.reason = reason
        self.step = step
        self.joint = joint
        self.remedy = remedy
        super().__init__(f"{argument}: {reason}")


def target_name(step: int | None = None, joint: int | None = None) -> str:
    """How messages name step-point ``step`` and joint ``joint`` (both counted from 0):
    ``"step-point 5 (counting from 0), joint q1"``."""
    parts = [] if step is None else [f"step-point {step} (counting from 0)"]
    return ", ".join(parts + ([] if joint is None else [f"joint q{joint + 1}"]))


class ModuleFault(HardwareError):
    """A module reports an error (ERROR bit or an unsolicited state frame).

    Attributes:
        module_id: The faulty module.
        state: Its state bits (:class:`hardware.protocol.State`).
    """

    def __init__(self, module_id: int, state: int, detail: str = "", remedy: Remedy | None = None):
        from .protocol import State

        self.module_id = module_id
        self.state = State(state)
        self.remedy = remedy
        msg = f"module {module_id}: fault, state {self.state!r}"
        super().__init__(msg + (f" ({detail})" if detail else ""))


class ModuleHalted(SafetyError):
    """A motion command was refused because the module is halted (HALT latches until RESET)."""

    def __init__(self, module_id: int):
        self.module_id = module_id
        super().__init__(f"module {module_id}", "halted",
                         remedy=Remedy("call reset() before moving again ({})", "reset", True, rerun=True))


class DuplicateModuleError(HardwareError):
    """Two answers to one request: two modules with the same id on the bus (a wiring or
    configuration fault; also two simulated arms on one channel). Stops the run.

    Attributes:
        module_id: The id that answered twice.
        request: Short description of the request, e.g. ``"GETPARAM VERSION"``.
    """

    def __init__(self, module_id: int, request: str):
        self.module_id = module_id
        self.request = request
        super().__init__(f"module {module_id}: two answers to {request}: more than one module with id "
                         f"{module_id} is on the bus (give each module its own id)")


class SecondControllerError(HardwareError):
    """Another controller commands the modules on this bus: frames to the modules (a request or a
    broadcast) that this host did not send, e.g. two ``iik run`` on one channel. Two controllers
    on one arm is a fault: the run stops (HALT).

    Attributes:
        frame_id: The CAN identifier of the foreign frame.
        request: What it was, e.g. ``"GETPARAM VERSION to module 3"``.
    """

    def __init__(self, frame_id: int, request: str):
        self.frame_id = frame_id
        self.request = request
        super().__init__(f"two controllers on one bus: another host sent {request} (CAN id "
                         f"0x{frame_id:03x}), which this host did not send; stop the other controller "
                         "(another run on this channel?) and run again")


class BusError(HardwareError, OSError):
    """The CAN interface itself failed (python-can raised ``CanError``)."""


class RunLogError(HardwareError, ValueError):
    """A run log is missing, malformed or incomplete, or cannot be written."""


class SimulatorError(HardwareError, RuntimeError):
    """The simulated arm (:mod:`hardware.sim`) failed: it raised while serving a frame,
    or its modules did not come to rest in time.

    Attributes:
        reason: What went wrong, e.g. the first errors the server recorded.
    """

    def __init__(self, reason: str):
        self.reason = reason
        super().__init__(reason)


