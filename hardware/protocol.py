"""The PowerCube (Schunk/Amtec M5) CAN protocol: frames as typed messages.

Pure encode/decode, no I/O. Every frame in ``docs/POWERCUBE.md`` has a frozen
message class; :func:`encode` turns a message into a :class:`can.Message` and
:func:`decode` turns a :class:`can.Message` back, raising
:class:`~hardware.errors.ProtocolError` (and nothing else) on any malformed frame.

Identifiers (11 bit): ``0x0C0 + id`` GETPARAM, ``0x0E0 + id`` every other
host command, ``0x0A0 + id`` the module's reply (ACK), ``0x060 + id`` an
unsolicited state frame (u32 state bits, as libm5api's ``getUnsignedLong`` reads
it), ``0x100`` broadcast. Module ids are 1..31. All values are little-endian and
in SI units (rad, rad/s, rad/s^2, A); times on the wire are u16 milliseconds.

The echo rule (:func:`is_echo`): a reply answers a request only if its identifier
is ``0x0A0 + id``, ``data[0]`` is the command and, for parameter and motion
commands, ``data[1]`` is the parameter or motion code.
"""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass
from enum import Enum, IntEnum, IntFlag

import can

from .errors import ProtocolError

__all__ = [
    "ID_GET", "ID_SET", "ID_ACK", "ID_STATE", "ID_ALL", "MODULE_IDS",
    "Cmd", "Param", "ParamType", "Mode", "State", "ShortState",
    "CONFIG_BRAKE", "CONFIG_WATCHDOG", "BAUD_CODES", "PARAM_TYPES", "READABLE", "WRITABLE",
    "GetParam", "SetParam", "SetMove", "Command", "Broadcast",
    "ParamReply", "SetParamAck", "MoveAck", "CommandAck", "StateFrame",
    "Request", "Reply", "Message",
    "encode", "decode", "is_echo", "describe", "short_state",
]

ID_GET = 0x0C0  #: host -> module: GETPARAM
ID_SET = 0x0E0  #: host -> module: every other command
ID_ACK = 0x0A0  #: module -> host: reply
ID_STATE = 0x060  #: module -> host: unsolicited state frame
ID_ALL = 0x100  #: host -> all: broadcast, no reply
MODULE_IDS = range(1, 32)  #: valid module ids


class Cmd(IntEnum):
    """Command byte ``data[0]``."""

    RESET = 0x00
    HOME = 0x01
    HALT = 0x02
    WATCHDOG = 0x07
    SETPARAM = 0x08
    BAUDRATE = 0x09
    GETPARAM = 0x0A
    SETMOVE = 0x0B
    STARTMOVE = 0x0F


_PLAIN = (Cmd.RESET, Cmd.HOME, Cmd.HALT)
_BROADCAST = (Cmd.RESET, Cmd.HOME, Cmd.HALT, Cmd.WATCHDOG, Cmd.BAUDRATE, Cmd.STARTMOVE)


class ParamType(Enum):
    """Wire types of parameter values: (struct format, Python kind)."""

    U8 = "<B"
    U16 = "<H"
    I16 = "<h"
    U32 = "<I"
    I32 = "<i"
    F32 = "<f"
    F32_U8_U8 = "<fBB"  # FPOSSTATEDIO: position, short state, digital I/O

    @property
    def size(self) -> int:
        return struct.calcsize(self.value)


class Param(IntEnum):
    """Parameter code ``data[1]`` of GETPARAM/SETPARAM."""

    SERIALNO = 0x1A
    VERSION = 0x1D
    STATE = 0x27
    CONFIG = 0x39
    ACT_FPOS = 0x3C
    ACT_FVEL = 0x41
    FMINPOS = 0x45
    FMAXPOS = 0x46
    FMAXVEL = 0x48
    FMAXACC = 0x4A
    FMAXCUR = 0x4C
    ACT_FCUR = 0x4D
    FRAMPVEL = 0x4F
    FRAMPACC = 0x50
    FPOSSTATEDIO = 0x62


PARAM_TYPES: dict[Param, ParamType] = {
    Param.SERIALNO: ParamType.U32,
    Param.VERSION: ParamType.U16,
    Param.STATE: ParamType.U32,
    Param.CONFIG: ParamType.U32,
    Param.ACT_FPOS: ParamType.F32,
    Param.ACT_FVEL: ParamType.F32,
    Param.FMINPOS: ParamType.F32,
    Param.FMAXPOS: ParamType.F32,
    Param.FMAXVEL: ParamType.F32,
    Param.FMAXACC: ParamType.F32,
    Param.FMAXCUR: ParamType.F32,
    Param.ACT_FCUR: ParamType.F32,
    Param.FRAMPVEL: ParamType.F32,
    Param.FRAMPACC: ParamType.F32,
    Param.FPOSSTATEDIO: ParamType.F32_U8_U8,
}
#: Parameters a host may read (GETPARAM).
READABLE = frozenset(PARAM_TYPES) - {Param.FRAMPVEL, Param.FRAMPACC}
#: Parameters a host may write (SETPARAM).
WRITABLE = frozenset({Param.CONFIG, Param.FMINPOS, Param.FMAXPOS, Param.FMAXVEL, Param.FMAXACC,
                      Param.FMAXCUR, Param.FRAMPVEL, Param.FRAMPACC})

CONFIG_BRAKE = 0x8  #: CONFIG bit: brake present
CONFIG_WATCHDOG = 0x01000000  #: CONFIG bit: watchdog enable
#: BAUDRATE broadcast codes by bit rate [bit/s].
BAUD_CODES = {125_000: 0, 250_000: 1, 500_000: 2, 1_000_000: 3}


class Mode(IntEnum):
    """Motion mode ``data[1]`` after SETMOVE (0x0B)."""

    FRAMP = 0x04
    FSTEP = 0x06
    FVEL = 0x07
    FCUR = 0x08
    FRAMP_EXT = 0x0E
    FSTEP_EXT = 0x10
    FVEL_EXT = 0x11
    FCUR_EXT = 0x12

    @property
    def extended(self) -> bool:
        """Extended modes reply with f32 position + u8 short state + u8 DIO."""
        return self in _EXT_TO_PLAIN

    @property
    def plain(self) -> Mode:
        """The plain mode of the same motion (FSTEP for FSTEP_EXT)."""
        return _EXT_TO_PLAIN.get(self, self)

    def as_extended(self) -> Mode:
        return _PLAIN_TO_EXT[self.plain]


_PLAIN_TO_EXT = {Mode.FRAMP: Mode.FRAMP_EXT, Mode.FSTEP: Mode.FSTEP_EXT,
                 Mode.FVEL: Mode.FVEL_EXT, Mode.FCUR: Mode.FCUR_EXT}
_EXT_TO_PLAIN = {v: k for k, v in _PLAIN_TO_EXT.items()}


class State(IntFlag):
    """Module state bits (parameter 0x27)."""

    ERROR = 0x1
    HOME_OK = 0x2
    HALTED = 0x4
    POWERFAULT = 0x8
    TOW_ERROR = 0x10
    COMM_ERROR = 0x20
    SWR = 0x40
    SW1 = 0x80
    SW2 = 0x100
    BRAKEACTIVE = 0x200
    CURLIMIT = 0x400
    MOTION = 0x800
    RAMP_ACC = 0x1000
    RAMP_STEADY = 0x2000
    RAMP_DEC = 0x4000
    RAMP_END = 0x8000
    INPROGRESS = 0x10000
    FULLBUFFER = 0x20000
    POW_VOLT_ERR = 0x40000
    POW_FET_TEMP = 0x80000
    POW_WDG_TEMP = 0x100000
    POW_SHORTCUR = 0x200000
    POW_HALLERR = 0x400000
    POW_INTEGRALERR = 0x800000
    CPU_OVERLOAD = 0x1000000
    BEYOND_HARD = 0x2000000
    BEYOND_SOFT = 0x4000000
    POW_SETUP_ERR = 0x8000000  # A: LOGIC_VOLT; B and C: POW_SETUP_ERR


class ShortState(IntFlag):
    """The short state byte of extended replies and of FPOSSTATEDIO."""

    NOT_OK = 0x01  # error, or not homed, or halted
    SWR = 0x02
    SW1 = 0x04
    SW2 = 0x08
    MOTION = 0x10
    RAMP_END = 0x20
    INPROGRESS = 0x40
    FULLBUFFER = 0x80


def short_state(state: int) -> ShortState:
    """The short state byte a module reports for its full ``state`` bits."""
    s = State(state)
    out = ShortState(0)
    if (s & (State.ERROR | State.HALTED)) or not (s & State.HOME_OK):
        out |= ShortState.NOT_OK
    for full, short in ((State.SWR, ShortState.SWR), (State.SW1, ShortState.SW1),
                        (State.SW2, ShortState.SW2), (State.MOTION, ShortState.MOTION),
                        (State.RAMP_END, ShortState.RAMP_END),
                        (State.INPROGRESS, ShortState.INPROGRESS),
                        (State.FULLBUFFER, ShortState.FULLBUFFER)):
        if s & full:
            out |= short
    return out


# ----------------------------------------------------------------------------- messages
@dataclass(frozen=True)
class GetParam:
    """Host reads ``param`` of ``module`` (identifier 0x0C0 + id, ``[0x0A, par]``)."""

    module: int
    param: Param


@dataclass(frozen=True)
class SetParam:
    """Host writes ``value`` to ``param`` (``[0x08, par, value...]``, DLC 3, 4 or 6)."""

    module: int
    param: Param
    value: float | int


@dataclass(frozen=True)
class SetMove:
    """Host starts a motion (``[0x0B, mode, f32 value (, u16 time_ms)]``).

    ``value`` is a position [rad] (ramp, step), a velocity [rad/s] or a current [A];
    ``time_ms`` is given for FSTEP (and FSTEP_EXT) only.
    """

    module: int
    mode: Mode
    value: float
    time_ms: int | None = None


@dataclass(frozen=True)
class Command:
    """Host sends a plain command (RESET, HOME, HALT) to one module, ``[cmd]``."""

    module: int
    cmd: Cmd


@dataclass(frozen=True)
class Broadcast:
    """Host sends a command to all modules on 0x100 (no reply); ``arg`` is the baud code."""

    cmd: Cmd
    arg: int | None = None


@dataclass(frozen=True)
class ParamReply:
    """Module answers GETPARAM: ``[0x0A, par, value...]``.

    For FPOSSTATEDIO ``value`` is ``(position, ShortState, dio)``.
    """

    module: int
    param: Param
    value: float | int | tuple


@dataclass(frozen=True)
class SetParamAck:
    """Module acknowledges SETPARAM: ``[0x08, par, ...]``."""

    module: int
    param: Param


@dataclass(frozen=True)
class MoveAck:
    """Module acknowledges SETMOVE: ``[0x0B, mode, ...]``; extended modes carry
    the actual position [rad], the short state and the digital I/O byte."""

    module: int
    mode: Mode
    position: float | None = None
    short: ShortState | None = None
    dio: int | None = None


@dataclass(frozen=True)
class CommandAck:
    """Module acknowledges a plain command: ``[cmd]``."""

    module: int
    cmd: Cmd


@dataclass(frozen=True)
class StateFrame:
    """Unsolicited state frame (0x060 + id): u32 state bits in ``data[0:4]``."""

    module: int
    state: State


Request = GetParam | SetParam | SetMove | Command | Broadcast
Reply = ParamReply | SetParamAck | MoveAck | CommandAck | StateFrame
Message = Request | Reply


# ----------------------------------------------------------------------------- encoding
#: Parameter messages: (identifier base, command, parameters allowed, carries a value, name).
_PARAM_FRAMES = {
    GetParam: (ID_GET, Cmd.GETPARAM, READABLE, False, "GETPARAM"),
    ParamReply: (ID_ACK, Cmd.GETPARAM, READABLE, True, "GETPARAM"),
    SetParam: (ID_SET, Cmd.SETPARAM, WRITABLE, True, "SETPARAM"),
    SetParamAck: (ID_ACK, Cmd.SETPARAM, WRITABLE, False, "SETPARAM"),
}


def _check_module(module) -> int:
    if isinstance(module, bool) or not isinstance(module, int) or module not in MODULE_IDS:
        raise ProtocolError(f"module id must be an int in 1..31, got {module!r}")
    return module


def _pack(ptype: ParamType, value, what: str) -> bytes:
    if ptype is ParamType.F32_U8_U8:
        try:
            pos, short, dio = value
        except (TypeError, ValueError):
            raise ProtocolError(f"{what}: expected (position, short state, dio)") from None
        return _pack(ParamType.F32, pos, what) + _pack(ParamType.U8, int(short), what) + \
            _pack(ParamType.U8, dio, what)
    if ptype is ParamType.F32:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ProtocolError(f"{what}: expected a number, got {type(value).__name__}")
        if not math.isfinite(value):
            raise ProtocolError(f"{what}: value {value!r} is not finite")
        if abs(value) > 3.4028234663852886e38:
            raise ProtocolError(f"{what}: value {value!r} overflows f32")
        return struct.pack("<f", value)
    if isinstance(value, bool) or not isinstance(value, int):
        raise ProtocolError(f"{what}: expected an integer, got {type(value).__name__}")
    try:
        return struct.pack(ptype.value, value)
    except struct.error:
        raise ProtocolError(f"{what}: {value} does not fit {ptype.name}") from None


def _frame(arbitration_id: int, data: bytes) -> can.Message:
    return can.Message(arbitration_id=arbitration_id, data=data, is_extended_id=False)


def encode(msg: Message) -> can.Message:
    """The CAN frame of a message (request or reply). Raises :class:`ProtocolError`."""
    if isinstance(msg, Broadcast):
        cmd = Cmd(msg.cmd) if msg.cmd in _BROADCAST else None
        if cmd not in _BROADCAST:
            raise ProtocolError(f"command {msg.cmd!r} cannot be broadcast")
        if cmd is Cmd.BAUDRATE:
            if msg.arg not in BAUD_CODES.values():
                raise ProtocolError(f"baud code must be 0..3, got {msg.arg!r}")
            return _frame(ID_ALL, bytes([cmd, msg.arg]))
        if msg.arg is not None:
            raise ProtocolError(f"broadcast {cmd.name} takes no argument")
        return _frame(ID_ALL, bytes([cmd]))
    module = _check_module(msg.module)
    if type(msg) in _PARAM_FRAMES:
        base, cmd, allowed, carries_value, where = _PARAM_FRAMES[type(msg)]
        par = _param(msg.param, allowed, where)
        value = _pack(PARAM_TYPES[par], msg.value, par.name) if carries_value else b""
        return _frame(base + module, bytes([cmd, par]) + value)
    if isinstance(msg, SetMove):
        mode = _mode(msg.mode)
        payload = _pack(ParamType.F32, msg.value, f"{mode.name} value")
        if mode.plain is Mode.FSTEP:
            if msg.time_ms is None:
                raise ProtocolError(f"{mode.name} needs time_ms")
            payload += _pack(ParamType.U16, msg.time_ms, f"{mode.name} time_ms")
        elif msg.time_ms is not None:
            raise ProtocolError(f"{mode.name} takes no time")
        return _frame(ID_SET + module, bytes([Cmd.SETMOVE, mode]) + payload)
    if isinstance(msg, MoveAck):
        mode = _mode(msg.mode)
        data = bytes([Cmd.SETMOVE, mode])
        if mode.extended:
            data += _pack(ParamType.F32_U8_U8, (msg.position, msg.short, msg.dio), "extended reply")
        elif (msg.position, msg.short, msg.dio) != (None, None, None):
            raise ProtocolError(f"plain mode {mode.name} reply carries no position")
        return _frame(ID_ACK + module, data)
    if isinstance(msg, (Command, CommandAck)):
        if msg.cmd not in _PLAIN:
            raise ProtocolError(f"{msg.cmd!r} is not a plain command (RESET, HOME, HALT)")
        return _frame((ID_SET if isinstance(msg, Command) else ID_ACK) + module, bytes([msg.cmd]))
    if isinstance(msg, StateFrame):
        return _frame(ID_STATE + module, _pack(ParamType.U32, int(msg.state), "state"))
    raise ProtocolError(f"not a PowerCube message: {type(msg).__name__}")


def _code(code) -> str:
    return f"0x{code:02x}" if isinstance(code, int) else repr(code)


def _mode(code, where: str = "SETMOVE") -> Mode:
    try:
        return Mode(code)
    except (ValueError, TypeError):
        raise ProtocolError(f"{where}: unknown motion mode {_code(code)}") from None


def _param(code, allowed, where: str) -> Param:
    if type(code) is Param and code in allowed:  # the common case, without an Enum lookup
        return code
    try:
        par = Param(code)
    except (ValueError, TypeError):
        raise ProtocolError(f"{where}: unknown parameter {_code(code)}") from None
    if par not in allowed:
        raise ProtocolError(f"{where}: parameter {par.name} not allowed here")
    return par


# ----------------------------------------------------------------------------- decoding
def _unpack(ptype: ParamType, data: bytes, what: str):
    if len(data) != ptype.size:
        raise ProtocolError(f"{what}: expected {ptype.size} value bytes ({ptype.name}), got {len(data)}")
    vals = struct.unpack(ptype.value, data)
    if ptype in (ParamType.F32, ParamType.F32_U8_U8) and not math.isfinite(vals[0]):
        raise ProtocolError(f"{what}: value is not finite")
    if ptype is ParamType.F32_U8_U8:
        return (vals[0], ShortState(vals[1]), vals[2])
    return vals[0]


def decode(frame: can.Message) -> Message:
    """The message carried by a CAN frame; :class:`ProtocolError` if it is not a
    well-formed PowerCube frame (wrong identifier, length, code or value)."""
    try:
        arb = int(frame.arbitration_id)
        data = bytes(frame.data or b"")[: int(frame.dlc)]
        extended, remote, error = bool(frame.is_extended_id), bool(frame.is_remote_frame), \
            bool(frame.is_error_frame)
    except (AttributeError, TypeError, ValueError) as exc:
        raise ProtocolError(f"not a CAN message ({exc})") from None
    if extended or remote or error:
        raise ProtocolError("extended, remote and error frames are not PowerCube frames")
    if not data or len(data) > 8:
        raise ProtocolError(f"frame 0x{arb:03x}: data length {len(data)} (need 1..8)")
    if arb == ID_ALL:
        return _decode_broadcast(data)
    base, module = arb & ~0x1F, arb & 0x1F
    if module == 0 or base not in (ID_GET, ID_SET, ID_ACK, ID_STATE):
        raise ProtocolError(f"identifier 0x{arb:03x} is not a PowerCube identifier")
    cmd_code = data[0]
    where = f"frame 0x{arb:03x}"
    if base == ID_STATE:
        if len(data) < 4:
            raise ProtocolError(f"{where}: state frame needs 4 bytes, got {len(data)}")
        return StateFrame(module, State(struct.unpack("<I", data[:4])[0]))
    if base == ID_GET:
        if cmd_code != Cmd.GETPARAM or len(data) != 2:
            raise ProtocolError(f"{where}: GETPARAM frame must be [0x0A, par]")
        return GetParam(module, _param(data[1], READABLE, where))
    if base == ID_SET:
        if cmd_code in _PLAIN:
            if len(data) != 1:
                raise ProtocolError(f"{where}: plain command takes DLC 1, got {len(data)}")
            return Command(module, Cmd(cmd_code))
        if len(data) < 2:
            raise ProtocolError(f"{where}: command 0x{cmd_code:02x} needs a second byte")
        if cmd_code == Cmd.SETPARAM:
            return _decode_param(SetParam, module, data, where)
        if cmd_code == Cmd.SETMOVE:
            mode = _mode(data[1], where)
            if mode.plain is Mode.FSTEP:
                if len(data) != 8:
                    raise ProtocolError(f"{where}: {mode.name} needs DLC 8, got {len(data)}")
                value = _unpack(ParamType.F32, data[2:6], f"{where} {mode.name}")
                return SetMove(module, mode, value, struct.unpack("<H", data[6:8])[0])
            return SetMove(module, mode, _unpack(ParamType.F32, data[2:], f"{where} {mode.name}"))
        raise ProtocolError(f"{where}: unknown command 0x{cmd_code:02x}")
    # ACK
    if cmd_code in _PLAIN:
        return CommandAck(module, Cmd(cmd_code))
    if len(data) < 2:
        raise ProtocolError(f"{where}: reply to 0x{cmd_code:02x} needs a second byte")
    if cmd_code == Cmd.GETPARAM:
        return _decode_param(ParamReply, module, data, where)
    if cmd_code == Cmd.SETPARAM:
        return _decode_param(SetParamAck, module, data, where)
    if cmd_code == Cmd.SETMOVE:
        mode = _mode(data[1], where)
        if mode.extended:
            pos, short, dio = _unpack(ParamType.F32_U8_U8, data[2:], f"{where} {mode.name} reply")
            return MoveAck(module, mode, pos, short, dio)
        return MoveAck(module, mode)  # B: a third byte 0x64 may follow; ignored
    raise ProtocolError(f"{where}: unknown reply command 0x{cmd_code:02x}")


def _decode_param(kind, module: int, data: bytes, where: str):
    """A parameter message ``kind`` (a key of :data:`_PARAM_FRAMES`) from ``[cmd, par, value...]``."""
    _, _, allowed, carries_value, _ = _PARAM_FRAMES[kind]
    par = _param(data[1], allowed, where)
    if not carries_value:
        return kind(module, par)
    return kind(module, par, _unpack(PARAM_TYPES[par], data[2:], f"{where} {par.name}"))


def _decode_broadcast(data: bytes) -> Broadcast:
    cmd_code = data[0]
    if cmd_code not in [int(c) for c in _BROADCAST]:
        raise ProtocolError(f"broadcast: command 0x{cmd_code:02x} cannot be broadcast")
    cmd = Cmd(cmd_code)
    if cmd is Cmd.BAUDRATE:
        if len(data) != 2 or data[1] not in BAUD_CODES.values():
            raise ProtocolError("broadcast BAUDRATE must be [0x09, code 0..3]")
        return Broadcast(cmd, data[1])
    if len(data) != 1:
        raise ProtocolError(f"broadcast {cmd.name} takes DLC 1, got {len(data)}")
    return Broadcast(cmd)


# ----------------------------------------------------------------------------- echo rule
def _echo_key(request: Request) -> tuple[int, int, int | None]:
    if isinstance(request, GetParam):
        return request.module, Cmd.GETPARAM, int(request.param)
    if isinstance(request, SetParam):
        return request.module, Cmd.SETPARAM, int(request.param)
    if isinstance(request, SetMove):
        return request.module, Cmd.SETMOVE, int(request.mode)
    if isinstance(request, Command):
        return request.module, int(request.cmd), None
    raise ProtocolError(f"{type(request).__name__} expects no reply")


def is_echo(request: Request, frame: can.Message) -> bool:
    """The echo rule of docs/POWERCUBE.md: does ``frame`` answer ``request``?

    True iff the identifier is 0x0A0 + id, ``data[0]`` is the command and, for
    parameter and motion commands, ``data[1]`` is the parameter or motion code.
    """
    module, cmd, code = _echo_key(request)
    data = bytes(frame.data or b"")[: frame.dlc]
    if frame.is_extended_id or frame.is_remote_frame or frame.is_error_frame:
        return False
    if frame.arbitration_id != ID_ACK + module or len(data) < 1 or data[0] != cmd:
        return False
    return code is None or (len(data) >= 2 and data[1] == code)


def describe(msg: Message) -> str:
    """Short human-readable name of a message, e.g. ``"GETPARAM ACT_FPOS"``."""
    if isinstance(msg, (GetParam, ParamReply)):
        return f"GETPARAM {Param(msg.param).name}"
    if isinstance(msg, (SetParam, SetParamAck)):
        return f"SETPARAM {Param(msg.param).name}"
    if isinstance(msg, (SetMove, MoveAck)):
        return f"SETMOVE {Mode(msg.mode).name}"
    if isinstance(msg, (Command, CommandAck, Broadcast)):
        return Cmd(msg.cmd).name
    return type(msg).__name__
