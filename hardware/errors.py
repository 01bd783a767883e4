"""Typed errors of the ``hardware`` package, all rooted in :class:`iik.errors.IIKError`.

Each also derives from the matching built-in so generic handlers keep working:
a malformed frame is a ``ValueError``, a missing reply a ``TimeoutError``.
"""

from __future__ import annotations

from iik.errors import IIKError

__all__ = [
    "HardwareError",
    "ProtocolError",
    "CANTimeoutError",
    "SafetyError",
    "ModuleFault",
    "ModuleHalted",
    "BusError",
    "RunLogError",
    "SimulatorError",
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
        argument: What was refused, e.g. ``"q[12, 3]"``.
        reason: Why.
    """

    def __init__(self, argument: str, reason: str):
        self.argument = argument
        self.reason = reason
        super().__init__(f"{argument}: {reason}")


class ModuleFault(HardwareError):
    """A module reports an error (ERROR bit or an unsolicited state frame).

    Attributes:
        module_id: The faulty module.
        state: Its state bits (:class:`hardware.protocol.State`).
    """

    def __init__(self, module_id: int, state: int, detail: str = ""):
        from .protocol import State

        self.module_id = module_id
        self.state = State(state)
        msg = f"module {module_id}: fault, state {self.state!r}"
        super().__init__(msg + (f" ({detail})" if detail else ""))


class ModuleHalted(SafetyError):
    """A motion command was refused because the module is halted (HALT latches until RESET)."""

    def __init__(self, module_id: int):
        self.module_id = module_id
        super().__init__(f"module {module_id}", "halted; call reset() before moving again")


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
