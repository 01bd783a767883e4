"""Validated trajectory execution with FSTEP and the thesis's early update (Sec 4.3).

Two steps, and the second only accepts the output of the first:

1. :func:`validate` checks every target before anything can reach a bus: finite;
   inside Table I with a margin; joint speeds within the limits (Sec 3.2) for the
   step times as they will go on the wire (whole ms); FK (Eq 4) of each target
   matches its planned pose, i.e. the joints come from an FK-verified IK solution.
   It returns a :class:`ValidatedTrajectory`, which nothing else can construct.
2. :func:`execute` streams it: FSTEP (target + time) to every module, a broadcast
   STARTMOVE so all joints switch together, and the next command after 95 % of the
   previous one's time has elapsed ("sending the command in progress after the
   95 % of the total time required by the previous command had been consumed",
   Sec 4.3). Between commands it samples position, velocity, current and state of
   every module into a JSON-lines run log (:mod:`hardware.runlog`), flushed per line.

On any fault (ACK timeout, ERROR bit or unsolicited state frame, CAN error,
malformed reply, Ctrl-C) it broadcasts HALT, records the fault, fsyncs the log and
re-raises.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from iik.arm import THESIS_ARM, Arm
from iik.errors import InvalidInputError
from iik.kinematics import fk
from iik.rotations import rotation_angle

from . import protocol as P
from .driver import PowerCubeArm
from .errors import BusError, ModuleFault, SafetyError
from .runlog import RunLog

__all__ = ["ValidationOptions", "ValidatedTrajectory", "validate", "ExecutionOptions", "RunResult",
           "execute", "time_steps", "EARLY_UPDATE"]

#: Sec 4.3: the next command is sent after 95 % of the previous one's time.
EARLY_UPDATE = 0.95
_TOKEN = object()


@dataclass(frozen=True)
class ValidationOptions:
    """Limits applied by :func:`validate`.

    Attributes:
        margin: Keep targets this far inside Table I [rad].
        velocity_fraction: Allowed fraction of each joint's speed limit.
        fk_position_tol: Max distance between FK(target) and the planned position [m].
        fk_rotation_tol: Max angle between FK(target) and the planned orientation [rad].
        min_step: Shortest step time [s].
    """

    margin: float = math.radians(0.5)
    velocity_fraction: float = 1.0
    fk_position_tol: float = 1e-5
    fk_rotation_tol: float = 1e-4
    min_step: float = 0.01


class ValidatedTrajectory:
    """A joint trajectory that passed :func:`validate`. Read-only; build it only via
    :func:`validate` (the constructor refuses any other caller).

    Attributes:
        times: (n,) [s], starting at 0. ``q``: (n,6) [rad]. ``poses``: (n,4,4) [m].
        step_ms: (n-1,) step times as sent (u16 ms). ``arm``, ``options``.
    """

    __slots__ = ("times", "q", "poses", "step_ms", "arm", "options")

    def __init__(self, *, _token, times, q, poses, step_ms, arm, options):
        if _token is not _TOKEN:
            raise SafetyError("ValidatedTrajectory", "only hardware.executor.validate() creates one")
        for name, value in (("times", times), ("q", q), ("poses", poses), ("step_ms", step_ms)):
            value = np.array(value)
            value.setflags(write=False)
            object.__setattr__(self, name, value)
        object.__setattr__(self, "arm", arm)
        object.__setattr__(self, "options", options)

    def __setattr__(self, name, value):
        raise AttributeError("ValidatedTrajectory is read-only")

    def __len__(self) -> int:
        return len(self.times)

    def __repr__(self) -> str:
        return f"ValidatedTrajectory(n={len(self)}, duration={self.times[-1]:.3f} s)"


def validate(times, q, poses, *, arm: Arm = THESIS_ARM,
             options: ValidationOptions = ValidationOptions(),
             orientation_free=None) -> ValidatedTrajectory:
    """Check a planned trajectory target by target; see the module docstring.

    Args:
        times: (n,) strictly increasing times [s]; shifted so the first is 0.
        q: (n,6) joint targets [rad].
        poses: (n,4,4) planned poses of frame 6 [m] the targets were solved for.
        orientation_free: Optional (n,) bool: at these steps only the position is
            compared (the planner changed alpha/beta there on purpose, Sec 3.6).

    Raises:
        SafetyError: naming the first offending target, e.g. ``q[12, 3]``.
    """
    try:
        t = np.asarray(times, dtype=float)
        qa = np.asarray(q, dtype=float)
        Ta = np.asarray(poses, dtype=float)
    except (TypeError, ValueError) as exc:
        raise SafetyError("trajectory", f"not numeric ({exc})") from None
    if t.ndim != 1 or len(t) < 2:
        raise SafetyError("times", f"need a 1-D array of at least 2 times, got shape {t.shape}")
    n = len(t)
    if qa.shape != (n, 6):
        raise SafetyError("q", f"expected shape ({n}, 6), got {qa.shape}")
    if Ta.shape != (n, 4, 4):
        raise SafetyError("poses", f"expected shape ({n}, 4, 4), got {Ta.shape}")
    for name, a in (("times", t), ("q", qa), ("poses", Ta)):
        bad = np.argwhere(~np.isfinite(a))
        if len(bad):
            raise SafetyError(f"{name}[{', '.join(map(str, bad[0]))}]", "not finite")
    # Table I with a margin
    lo = arm.q_min + options.margin
    hi = arm.q_max - options.margin
    out = np.argwhere((qa < lo) | (qa > hi))
    if len(out):
        k, j = out[0]
        raise SafetyError(f"q[{k}, {j}]", f"{qa[k, j]:.6f} rad outside Table I "
                          f"[{arm.q_min[j]:.4f}, {arm.q_max[j]:.4f}] with margin {options.margin:.4f} rad")
    # step times as they go on the wire, and the speeds they imply
    dt = np.diff(t)
    if np.any(dt < options.min_step):
        k = int(np.argmax(dt < options.min_step))
        raise SafetyError(f"times[{k + 1}]", f"step of {dt[k]:.4f} s is shorter than {options.min_step} s")
    ms = np.rint(dt * 1000.0)
    if np.any(ms > 0xFFFF):
        raise SafetyError("times", "a step is longer than 65.535 s")
    vel = np.abs(np.diff(qa, axis=0)) / (ms[:, None] / 1000.0)
    vmax = np.asarray(arm.velocity) * options.velocity_fraction
    over = np.argwhere(vel > vmax)
    if len(over):
        k, j = over[0]
        raise SafetyError(f"q[{k + 1}, {j}]", f"needs {vel[k, j]:.4f} rad/s > limit {vmax[j]:.4f} rad/s")
    # FK of every target against its planned pose (Eq 4)
    try:
        from iik.validation import as_poses

        as_poses(Ta, "poses")
    except InvalidInputError as exc:
        raise SafetyError("poses", exc.reason) from None
    Tf = fk(qa, arm)
    dp = np.linalg.norm(Tf[:, :3, 3] - Ta[:, :3, 3], axis=1)
    dr = rotation_angle(Tf[:, :3, :3], Ta[:, :3, :3])
    if orientation_free is not None:
        free = np.asarray(orientation_free, dtype=bool)
        if free.shape != (n,):
            raise SafetyError("orientation_free", f"expected shape ({n},), got {free.shape}")
        dr = np.where(free, 0.0, dr)
    bad = np.flatnonzero((dp > options.fk_position_tol) | (dr > options.fk_rotation_tol))
    if len(bad):
        k = int(bad[0])
        raise SafetyError(f"q[{k}]", f"FK does not match the planned pose ({dp[k] * 1e3:.3f} mm, "
                          f"{math.degrees(dr[k]):.4f} deg)")
    return ValidatedTrajectory(_token=_TOKEN, times=t - t[0], q=qa, poses=Ta, step_ms=ms.astype(int),
                               arm=arm, options=options)


def time_steps(q, *, arm: Arm = THESIS_ARM, speed_fraction: float = 0.5, min_step: float = 0.05,
               ) -> np.ndarray:
    """Times [s] for step-points ``q`` (n,6): each step takes as long as its slowest
    joint needs at ``speed_fraction`` of its limit (at least ``min_step``), whole ms."""
    qa = np.asarray(q, dtype=float)
    v = np.asarray(arm.velocity) * speed_fraction
    dt = np.max(np.abs(np.diff(qa, axis=0)) / v, axis=1)
    dt = np.ceil(np.maximum(dt, min_step) * 1000.0) / 1000.0
    return np.concatenate([[0.0], np.cumsum(dt)])


@dataclass(frozen=True)
class ExecutionOptions:
    """How :func:`execute` streams.

    Attributes:
        early: Send the next command after this fraction of the previous step (Sec 4.3: 0.95).
        sample_period: Time between measurement samples [s] (as fast as the bus allows if 0).
        settle: Keep sampling this long after the last step ends [s].
        start_tolerance: Max |measured - q[0]| per joint to start without an approach [rad].
        approach: Move to ``q[0]`` first (FSTEP at ``approach_speed`` of the limits) if needed.
        approach_speed: Fraction of the speed limits for the approach.
        sync: Broadcast STARTMOVE after each command so all joints switch together
            (``update="thesis"``).
        update: ``"thesis"`` (Sec 4.3): the next command is sent after ``early`` of the
            previous step and replaces the rest of it at STARTMOVE, so up to 5 % of every
            step is cut. ``"buffered"``: the next command is sent ``1 - early`` of the
            current step (at least 20 ms, at most half of it) before that step ends on the
            modules' own timeline, and waits in their step buffer (FULLBUFFER); it starts
            exactly when the current step ends, so no step is cut and no joint stops.
        watchdog: Enable the modules' watchdog for the run (CONFIG bit + 40 ms broadcast),
            so the arm stops by itself if this process dies or the bus link is lost.
    """

    early: float = EARLY_UPDATE
    sample_period: float = 0.01
    settle: float = 0.2
    start_tolerance: float = 0.01
    approach: bool = True
    approach_speed: float = 0.25
    sync: bool = True
    update: str = "thesis"
    watchdog: bool = False


@dataclass(frozen=True)
class RunResult:
    """Outcome of a successful :func:`execute` (a fault raises instead)."""

    log_path: Path
    commands: int
    samples: int
    duration: float


class _Sampler:
    def __init__(self, arm: PowerCubeArm, log: RunLog, t0: float, clock):
        self.arm, self.log, self.t0, self.clock = arm, log, t0, clock
        self.count = 0
        self.error_frames = arm.link.error_frames

    def sample(self, k: int, deadline: float | None = None) -> bool:
        """Read state, position, velocity and current of every module and log them.

        Gives up (returns False, logs nothing) as soon as ``deadline`` passes, so a
        sample never delays the next command by more than one request."""
        rows = []
        for m in self.arm.modules:
            row = []
            for par in (P.Param.STATE, P.Param.ACT_FPOS, P.Param.ACT_FVEL, P.Param.ACT_FCUR):
                if deadline is not None and self.clock() >= deadline:
                    return False
                row.append(m.get_param(par))
                if par is P.Param.ACT_FPOS:
                    row.append(self.clock() - self.t0)  # when this position was read
            rows.append(row)
        st, q, tq, dq, cur = (list(c) for c in zip(*rows, strict=True))
        st = [int(v) for v in st]
        self.log.write({"type": "sample", "t": self.clock() - self.t0, "k": k, "q": q, "tq": tq,
                        "dq": dq, "cur": cur, "state": st})
        self.count += 1
        for m, s in zip(self.arm.modules, st, strict=True):
            if s & (P.State.ERROR | P.State.HALTED):
                raise ModuleFault(m.id, s, "reported in a state sample")
        if self.arm.link.faults:
            mid, s = next(iter(self.arm.link.faults.items()))
            raise ModuleFault(mid, s, "unsolicited state frame")
        if self.arm.link.error_frames > self.error_frames:
            raise BusError(f"{self.arm.link.error_frames - self.error_frames} CAN error frame(s) received")
        return True


def execute(arm: PowerCubeArm, trajectory: ValidatedTrajectory, log_path, *,
            options: ExecutionOptions = ExecutionOptions(),
            progress: Callable[[int, int], None] | None = None,
            clock: Callable[[], float] = time.monotonic,
            sleep: Callable[[float], None] = time.sleep) -> RunResult:
    """Stream ``trajectory`` to ``arm`` and log it to ``log_path`` (JSON lines).

    Raises:
        SafetyError: ``trajectory`` is not a :class:`ValidatedTrajectory`, or the arm
            is not where the trajectory starts and ``options.approach`` is off.
        CANTimeoutError, ModuleFault, BusError, ProtocolError, KeyboardInterrupt:
            after HALT was broadcast and the fault logged.
    """
    if not isinstance(trajectory, ValidatedTrajectory):
        raise SafetyError("trajectory", "must be a ValidatedTrajectory from hardware.executor.validate()")
    if len(arm.modules) != trajectory.q.shape[1]:
        raise SafetyError("arm", f"has {len(arm.modules)} modules, the trajectory "
                          f"{trajectory.q.shape[1]} joints")
    if not 0.0 < options.early <= 1.0:
        raise SafetyError("options.early", "must be in (0, 1]")
    if options.update not in ("thesis", "buffered"):
        raise SafetyError("options.update", f"must be 'thesis' or 'buffered', got {options.update!r}")
    tr = trajectory
    # Refusals before anything moves: no HALT needed, no log written.
    for m, s in zip(arm.modules, arm.states(), strict=True):
        if s & (P.State.ERROR | P.State.HALTED):
            raise ModuleFault(m.id, s, "before start: reset the module first")
    q_now = arm.get_pos()
    err = np.abs(q_now - tr.q[0])
    if np.max(err) > options.start_tolerance and not options.approach:
        raise SafetyError("arm", f"is {np.max(err):.4f} rad from the trajectory start")
    log = RunLog(log_path)
    log.write({"type": "header", "version": 1, "module_ids": list(arm.module_ids),
               "times": tr.times.tolist(), "q": tr.q.tolist(), "poses": tr.poses.tolist(),
               "step_ms": tr.step_ms.tolist(), "early": options.early, "sync": options.sync,
               "update": options.update,
               "bus": str(arm.bus.channel_info), "arm": tr.arm.name,
               "started": datetime.now(timezone.utc).isoformat()})
    t0 = clock()
    sampler = _Sampler(arm, log, t0, clock)
    n_cmd = 0

    def command(k: int, q, time_s: float, start: bool = True) -> float:
        nonlocal n_cmd
        t = clock()
        # extended FSTEP: each ACK carries the module's actual position when the command
        # arrived, i.e. the measurement at the step-point the early update leaves
        q_meas, short = arm.move_step(q, time_s, extended=True)
        if start:
            arm.start_move()
        log.write({"type": "command", "t": t - t0, "k": k, "q": [float(v) for v in q], "time_s": time_s,
                   "q_meas": [float(v) for v in q_meas], "short": [int(v) for v in short]})
        n_cmd += 1
        return t

    def step_point(k: int, t_end: float) -> None:
        log.write({"type": "step_end", "k": k, "t": t_end - t0})

    def sample_until(deadline: float, k: int) -> None:
        """Sample every ``sample_period`` until ``deadline`` without delaying the next command."""
        while True:
            sampler.sample(k, deadline)
            now = clock()
            if now >= deadline:
                return
            sleep(min(options.sample_period, deadline - now))

    try:
        if options.watchdog:
            arm.start_watchdog()
        if np.max(err) > options.start_tolerance:
            v = np.asarray(tr.arm.velocity) * options.approach_speed
            t_app = math.ceil(max(float(np.max(err / v)), 0.05) * 1000.0) / 1000.0
            ts = command(0, tr.q[0], t_app)
            sample_until(ts + t_app + options.settle, 0)
        else:
            sampler.sample(0)
        n = len(tr)
        step_end = -math.inf  # end of the current step on the modules' timeline (buffered)
        for k in range(1, n):
            dt = tr.step_ms[k - 1] / 1000.0
            if options.update == "thesis":  # Sec 4.3: next command after 95 % of this one
                ts = command(k, tr.q[k], dt, start=options.sync)
                next_at = ts + (options.early * dt if k < n - 1 else dt + options.settle)
            else:  # buffered: queue the next step shortly before this one ends
                ts = command(k, tr.q[k], dt, start=(k == 1))
                # the step starts when the previous one ends, or at once if that already
                # happened (a late command): keep the timeline so no buffered step is overwritten
                step_end = max(step_end, ts) + dt
                step_point(k, step_end)
                lead = min(max((1.0 - options.early) * dt, 0.020), 0.5 * dt)
                next_at = step_end - lead if k < n - 1 else step_end + options.settle
            if progress is not None:
                progress(k, n - 1)
            sample_until(next_at, k)
        if options.watchdog:
            arm.stop_watchdog(disable=True)
        log.write({"type": "end", "t": clock() - t0, "status": "ok"})
        log.close()
        return RunResult(Path(log_path), n_cmd, sampler.count, clock() - t0)
    except BaseException as exc:
        halted = True
        try:
            arm.halt()  # broadcast: one frame stops every module
        except BaseException:  # noqa: BLE001 - the fault being handled matters more
            halted = False
        if options.watchdog:
            try:  # halted already; keep the latch, stop refreshing and clear the bit
                arm.stop_watchdog(disable=True)
            except BaseException:  # noqa: BLE001
                pass
        try:
            log.write({"type": "fault", "t": clock() - t0, "error": type(exc).__name__,
                       "message": str(exc), "halted": halted, "command": n_cmd})
            log.write({"type": "end", "t": clock() - t0, "status": "fault"})
        finally:
            log.close()
        raise
