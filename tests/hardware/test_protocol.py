"""Protocol layer: every frame of docs/POWERCUBE.md, the echo rule, and fuzzing."""

import math
import struct

import can
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from hardware import protocol as P
from hardware.errors import ProtocolError

modules = st.integers(1, 31)
f32 = st.floats(allow_nan=False, allow_infinity=False, width=32)
u32 = st.integers(0, 2**32 - 1)


def _value_for(par):
    t = P.PARAM_TYPES[par]
    return {
        P.ParamType.F32: f32,
        P.ParamType.U16: st.integers(0, 0xFFFF),
        P.ParamType.U32: u32,
        P.ParamType.F32_U8_U8: st.tuples(f32, st.integers(0, 255).map(P.ShortState), st.integers(0, 255)),
    }[t]


def _with_value(cls, pars):
    return st.sampled_from(sorted(pars)).flatmap(
        lambda par: st.builds(cls, modules, st.just(par), _value_for(par)))


plain_modes = st.sampled_from(list(P.Mode))
set_moves = plain_modes.flatmap(lambda m: st.builds(
    P.SetMove, modules, st.just(m), f32,
    st.integers(0, 0xFFFF) if m.plain is P.Mode.FSTEP else st.none()))
move_acks = plain_modes.flatmap(lambda m: st.builds(
    P.MoveAck, modules, st.just(m), f32, st.integers(0, 255).map(P.ShortState), st.integers(0, 255))
    if m.extended else st.builds(P.MoveAck, modules, st.just(m)))
messages = st.one_of(
    st.builds(P.GetParam, modules, st.sampled_from(sorted(P.READABLE))),
    _with_value(P.SetParam, P.WRITABLE),
    set_moves,
    st.builds(P.Command, modules, st.sampled_from([P.Cmd.RESET, P.Cmd.HOME, P.Cmd.HALT])),
    st.sampled_from([P.Cmd.RESET, P.Cmd.HOME, P.Cmd.HALT, P.Cmd.WATCHDOG, P.Cmd.STARTMOVE]).map(P.Broadcast),
    st.integers(0, 3).map(lambda c: P.Broadcast(P.Cmd.BAUDRATE, c)),
    _with_value(P.ParamReply, P.READABLE),
    st.builds(P.SetParamAck, modules, st.sampled_from(sorted(P.WRITABLE))),
    move_acks,
    st.builds(P.CommandAck, modules, st.sampled_from([P.Cmd.RESET, P.Cmd.HOME, P.Cmd.HALT])),
    st.builds(P.StateFrame, modules, u32.map(P.State)),
)


@given(messages)
def test_round_trip(msg):
    frame = P.encode(msg)
    assert not frame.is_extended_id and 1 <= frame.dlc <= 8
    assert P.decode(frame) == msg  # f32 values are drawn as float32, so exact


@given(st.integers(0, 0x7FF), st.binary(min_size=0, max_size=8), st.booleans())
def test_arbitrary_frames_decode_or_raise_typed_error(arb, data, extended):
    frame = can.Message(arbitration_id=arb, data=data, is_extended_id=extended)
    try:
        msg = P.decode(frame)
    except ProtocolError:
        return
    # a frame that decodes re-encodes to a frame that decodes to the same message
    assert P.decode(P.encode(msg)) == msg


@given(messages, st.binary(min_size=0, max_size=8))
def test_corrupted_frames_never_crash(msg, tail):
    frame = P.encode(msg)
    bad = can.Message(arbitration_id=frame.arbitration_id, data=bytes(frame.data)[:1] + tail,
                      is_extended_id=False)
    try:
        P.decode(bad)
    except ProtocolError:
        pass


def test_identifiers_and_layouts_match_powercube_md():
    assert P.encode(P.GetParam(3, P.Param.ACT_FPOS)).arbitration_id == 0x0C3
    f = P.encode(P.GetParam(3, P.Param.ACT_FPOS))
    assert bytes(f.data) == bytes([0x0A, 0x3C])
    f = P.encode(P.SetMove(5, P.Mode.FSTEP, 0.5, 250))
    assert f.arbitration_id == 0x0E5 and f.dlc == 8
    assert bytes(f.data) == bytes([0x0B, 0x06]) + struct.pack("<fH", 0.5, 250)
    f = P.encode(P.SetMove(5, P.Mode.FRAMP, -1.0))
    assert f.dlc == 6 and bytes(f.data)[:2] == bytes([0x0B, 0x04])
    f = P.encode(P.SetParam(2, P.Param.FMAXCUR, 3.0))
    assert f.dlc == 6 and bytes(f.data) == bytes([0x08, 0x4C]) + struct.pack("<f", 3.0)
    f = P.encode(P.SetParam(2, P.Param.CONFIG, P.CONFIG_WATCHDOG | P.CONFIG_BRAKE))
    assert bytes(f.data) == bytes([0x08, 0x39, 0x08, 0, 0, 0x01])
    f = P.encode(P.ParamReply(1, P.Param.VERSION, 0x1234))
    assert f.arbitration_id == 0x0A1 and bytes(f.data) == bytes([0x0A, 0x1D, 0x34, 0x12])
    f = P.encode(P.MoveAck(7, P.Mode.FSTEP_EXT, 1.5, P.ShortState.MOTION, 3))
    assert f.dlc == 8 and bytes(f.data)[:2] == bytes([0x0B, 0x10])
    assert bytes(P.encode(P.Broadcast(P.Cmd.HALT)).data) == b"\x02"
    assert P.encode(P.Broadcast(P.Cmd.STARTMOVE)).arbitration_id == 0x100
    assert bytes(P.encode(P.Broadcast(P.Cmd.BAUDRATE, P.BAUD_CODES[500_000])).data) == b"\x09\x02"
    assert P.encode(P.StateFrame(4, P.State.ERROR)).arbitration_id == 0x064
    assert [m.as_extended() for m in (P.Mode.FRAMP, P.Mode.FSTEP, P.Mode.FVEL, P.Mode.FCUR)] == \
        [0x0E, 0x10, 0x11, 0x12]


def test_param_types_sizes():
    sizes = {t: t.size for t in P.ParamType}
    assert sizes == {P.ParamType.U8: 1, P.ParamType.U16: 2, P.ParamType.I16: 2, P.ParamType.U32: 4,
                     P.ParamType.I32: 4, P.ParamType.F32: 4, P.ParamType.F32_U8_U8: 6}


@pytest.mark.parametrize("arb,data", [
    (0x0C3, [0x0A]),                 # GETPARAM without a parameter
    (0x0C3, [0x0A, 0x3C, 0]),        # GETPARAM too long
    (0x0C3, [0x0A, 0x99]),           # unknown parameter
    (0x0C3, [0x0A, 0x4F]),           # FRAMPVEL is write-only
    (0x0E3, [0x08, 0x3C, 0, 0, 0, 0]),  # ACT_FPOS is read-only
    (0x0E3, [0x08, 0x4C, 0, 0]),     # f32 write with 2 value bytes
    (0x0E3, [0x0B, 0x06, 0, 0, 0, 0]),  # FSTEP without time
    (0x0E3, [0x0B, 0x05, 0, 0, 0, 0]),  # unknown mode
    (0x0E3, [0x0B, 0x04] + list(struct.pack("<f", math.nan))),  # NaN target
    (0x0E3, [0x02, 0x00]),           # HALT with DLC 2
    (0x0A3, [0x0A, 0x3C, 0, 0]),     # truncated reply
    (0x0A3, [0x0B, 0x10, 0, 0]),     # extended reply without position
    (0x0E0, [0x02]),                 # module id 0
    (0x123, [0x02]),                 # foreign identifier
    (0x100, [0x0A]),                 # GETPARAM cannot be broadcast
    (0x100, [0x09, 7]),              # bad baud code
    (0x063, [0, 0]),                 # short state frame
    (0x0C3, []),                     # empty
])
def test_malformed_frames_are_rejected(arb, data):
    with pytest.raises(ProtocolError):
        P.decode(can.Message(arbitration_id=arb, data=data, is_extended_id=False))


@pytest.mark.parametrize("msg", [
    P.SetMove(1, P.Mode.FSTEP, 0.1, 70000), P.SetMove(1, P.Mode.FSTEP, math.inf, 10),
    P.SetMove(1, P.Mode.FVEL, 0.1, 10), P.SetParam(1, P.Param.ACT_FPOS, 0.0),
    P.GetParam(0, P.Param.STATE), P.GetParam(32, P.Param.STATE), P.Command(1, P.Cmd.SETMOVE),
    P.Broadcast(P.Cmd.GETPARAM), P.SetParam(1, P.Param.CONFIG, -1),
])
def test_unencodable_messages_raise_protocol_error(msg):
    with pytest.raises(ProtocolError):
        P.encode(msg)


def test_echo_rule():
    req = P.GetParam(2, P.Param.ACT_FPOS)
    good = P.encode(P.ParamReply(2, P.Param.ACT_FPOS, 0.25))
    assert P.is_echo(req, good)
    assert not P.is_echo(req, P.encode(P.ParamReply(3, P.Param.ACT_FPOS, 0.25)))  # other module
    assert not P.is_echo(req, P.encode(P.ParamReply(2, P.Param.ACT_FVEL, 0.25)))  # other parameter
    assert not P.is_echo(req, P.encode(P.CommandAck(2, P.Cmd.HALT)))  # other command
    assert not P.is_echo(req, P.encode(P.GetParam(2, P.Param.ACT_FPOS)))  # the request itself
    assert not P.is_echo(req, P.encode(P.StateFrame(2, P.State.ERROR)))
    mv = P.SetMove(2, P.Mode.FSTEP, 0.1, 100)
    assert P.is_echo(mv, P.encode(P.MoveAck(2, P.Mode.FSTEP)))
    assert not P.is_echo(mv, P.encode(P.MoveAck(2, P.Mode.FRAMP)))
    assert P.is_echo(P.Command(2, P.Cmd.HALT), P.encode(P.CommandAck(2, P.Cmd.HALT)))
    with pytest.raises(ProtocolError):
        P.is_echo(P.Broadcast(P.Cmd.HALT), good)  # broadcasts get no reply


@given(u32)
def test_short_state_from_full_state(bits):
    s = P.State(bits)
    short = P.short_state(bits)
    not_ok = bool(s & (P.State.ERROR | P.State.HALTED)) or not (s & P.State.HOME_OK)
    assert bool(short & P.ShortState.NOT_OK) == not_ok
    assert bool(short & P.ShortState.FULLBUFFER) == bool(s & P.State.FULLBUFFER)
    assert bool(short & P.ShortState.MOTION) == bool(s & P.State.MOTION)


def test_state_bits_are_the_documented_values():
    assert P.State.ERROR == 0x1 and P.State.HALTED == 0x4 and P.State.RAMP_END == 0x8000
    assert P.State.FULLBUFFER == 0x20000 and P.State.BEYOND_SOFT == 0x4000000
    assert P.State.POW_SETUP_ERR == 0x8000000
    assert all(bin(int(b)).count("1") == 1 for b in P.State)
    assert np.sum([int(b) for b in P.State]) == 2**28 - 1
