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
malformed reply, a duplicate module id, Ctrl-C, SIGTERM or SIGHUP) it broadcasts HALT,
records the fault, fsyncs the log and re-raises (:mod:`iik.signals`).

Times are compared as they go on the wire: a step lasts a whole number of
milliseconds (FSTEP's u16, the time resolution of the protocol), so a step time is
rounded to the nearest millisecond before it is checked (a tolerance of 0.5 ms):
the 9.985 ms steps of a trajectory sampled every 10 ms are 10 ms steps.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from iik.arm import Arm
from iik.arms import same_arm, to_record
from iik.errors import InvalidInputError, Remedy
from iik.kinematics import fk
from iik.rotations import rotation_angle
from iik.safety import EXECUTION_MARGIN, MIN_STEP
from iik.signals import stop_on_signals
from iik.validation import bounded_number

from . import protocol as P
from .driver import SPEED_TOLERANCE, PowerCubeArm
from .errors import BusError, ModuleFault, SafetyError, target_name
from .runlog import RUN_LOG_VERSION, RunLog

#: Rounding of the modules' soft limits as they come back on the wire (float32) [rad].
SOFT_LIMIT_TOL = 1e-6

__all__ = ["ValidationOptions", "ValidatedTrajectory", "validate", "check_poses", "ExecutionOptions",
           "RunResult", "execute", "time_steps", "EARLY_UPDATE", "UPDATES"]

#: Sec 4.3: the next command is sent after 95 % of the previous one's time.
EARLY_UPDATE = 0.95
#: The update modes of :class:`ExecutionOptions`.
UPDATES = ("thesis", "buffered")
_TOKEN = object()


@dataclass(frozen=True)
class ValidationOptions:
    """Limits applied by :func:`validate`.

    Attributes:
        margin: Keep targets this far inside Table I [rad], [0, 90) deg (checked when built; default
            :data:`iik.safety.EXECUTION_MARGIN`, 0.5 deg, which planned trajectories keep).
        velocity_fraction: Allowed fraction of each joint's speed limit.
        fk_position_tol: Max distance between FK(target) and the planned position [m].
        fk_rotation_tol: Max angle between FK(target) and the planned orientation [rad].
        min_step: Shortest step time [s], compared in whole milliseconds as sent.
    """

    margin: float = EXECUTION_MARGIN
    velocity_fraction: float = 1.0
    fk_position_tol: float = 1e-5
    fk_rotation_tol: float = 1e-4
    min_step: float = MIN_STEP

    def __post_init__(self) -> None:
        number = isinstance(self.margin, (int, float)) and not isinstance(self.margin, bool)
        if not (number and 0.0 <= self.margin < math.pi / 2):
            shown = f"{math.degrees(self.margin):g} deg" if number else repr(self.margin)
            raise InvalidInputError("margin", f"must be a finite angle in [0, 90) deg, got {shown}")


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


def validate(times, q, poses, *, arm: Arm,
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
        SafetyError: naming the first offending target (step-point and joint, counted
            from 0 and as ``q1..q6``) in ``argument`` and in ``step``/``joint``.
    """
    try:
        t = np.asarray(times, dtype=float)
        qa = np.asarray(q, dtype=float)
        Ta = np.asarray(poses, dtype=float)
    except (TypeError, ValueError) as exc:
        raise SafetyError("trajectory", f"not numeric ({exc})") from None
    if t.ndim != 1 or len(t) < 2:
        raise SafetyError("times", f"need at least 2 step-points, got {t.size}")
    n = len(t)
    if qa.shape != (n, 6):
        raise SafetyError("q", f"expected shape ({n}, 6), got {qa.shape}")
    if Ta.shape != (n, 4, 4):
        raise SafetyError("poses", f"expected shape ({n}, 4, 4), got {Ta.shape}")
    for name, a in (("times", t), ("q", qa), ("poses", Ta)):
        bad = np.argwhere(~np.isfinite(a))
        if len(bad):
            k, j = int(bad[0][0]), (int(bad[0][1]) if name == "q" else None)
            raise SafetyError(target_name(k, j), f"{name} not finite", step=k, joint=j)
    if not (isinstance(options.margin, (int, float)) and math.isfinite(options.margin)):
        raise SafetyError("options.margin", f"must be a finite angle [rad], got {options.margin!r}")
    out = arm.limit_violations(qa, options.margin)  # Table I with a margin
    if out:
        v = out[0]
        raise SafetyError(target_name(v.sample, v.joint), f"{v.value:.6f} rad outside {arm.limits_name} "
                          f"[{v.lower:.4f}, {v.upper:.4f}] rad less the margin of {v.margin:.4f} rad "
                          f"({math.degrees(v.margin):g} deg)", step=v.sample, joint=v.joint)
    step_ms = _step_ms(t, options.min_step)
    vel = np.abs(np.diff(qa, axis=0)) / (step_ms[:, None] / 1000.0)
    vmax = np.asarray(arm.velocity) * options.velocity_fraction
    over = np.argwhere(vel > vmax)
    if len(over):
        k, j = (int(v) for v in over[0])
        raise SafetyError(target_name(k + 1, j), f"the step to it ({step_ms[k]} ms) needs {vel[k, j]:.4f} "
                          f"rad/s > limit {vmax[j]:.4f} rad/s", step=k + 1, joint=j)
    check_poses(qa, Ta, arm=arm, options=options, orientation_free=orientation_free)
    return ValidatedTrajectory(_token=_TOKEN, times=t - t[0], q=qa, poses=Ta, step_ms=step_ms,
                               arm=arm, options=options)


def _step_ms(t: np.ndarray, min_step: float) -> np.ndarray:
    """Step times as they go on the wire: whole ms (nearest; a tolerance of 0.5 ms), each at
    least ``min_step`` [s] (compared in whole ms too) and at most 65535 ms."""
    with np.errstate(over="ignore", invalid="ignore"):  # absurd times are refused below, not warned about
        dt = np.diff(t)
    longest = 0xFFFF / 1000.0 + 0.0005
    if np.any(~np.isfinite(dt) | (dt >= longest)):
        k = int(np.argmax(~np.isfinite(dt) | (dt >= longest)))
        raise SafetyError(target_name(k + 1), f"the step to it takes {dt[k]:.6g} s, longer than 65.535 s "
                          "(FSTEP's u16 ms)", step=k + 1)
    ms = np.rint(np.maximum(dt, -1.0) * 1000.0)
    least = max(int(round(min_step * 1000.0)), 1)
    if np.any(ms < least):
        k = int(np.argmax(ms < least))
        took = f"{dt[k] * 1e3:.3f} ms" if dt[k] > -1.0 else f"{dt[k]:.6g} s (times must increase)"
        raise SafetyError(target_name(k + 1), f"the step to it takes {took}, {ms[k]:.0f} ms on the wire "
                          f"(whole ms): shorter than the {least} ms minimum", step=k + 1)
    return ms.astype(int)


def check_poses(q, poses, *, arm: Arm, options: ValidationOptions = ValidationOptions(),
                orientation_free=None) -> None:
    """FK (Eq 4) of every target ``q`` (n,6) [rad] against its planned pose ``poses`` (n,4,4) [m]:
    the targets come from an FK-verified IK solution. Raises :class:`SafetyError` naming the
    first step-point (counted from 0) whose FK is farther than the options' tolerances."""
    qa, Ta = np.asarray(q, dtype=float), np.asarray(poses, dtype=float)
    n = len(qa)
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
        raise SafetyError(target_name(k), f"FK does not match the planned pose ({dp[k] * 1e3:.3f} mm, "
                          f"{math.degrees(dr[k]):.4f} deg)", step=k)


def time_steps(q, *, arm: Arm, speed_fraction: float = 0.5, min_step: float = 0.05,
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
    """How :func:`execute` streams; validated when built (:class:`~iik.errors.InvalidInputError` naming
    the field).

    Attributes:
        early: Send the next command after this fraction of the previous step (Sec 4.3: 0.95).
        sample_period: Time between measurement samples [s] (as fast as the bus allows if 0).
        settle: Keep sampling this long after the last step ends [s]; one complete sample
            follows, so the final error is measured at rest however slow the bus is.
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

    def __post_init__(self) -> None:
        bounded_number(self.early, "early", 0.0, 1.0, unit=" (fraction of a step)", open_lo=True)
        bounded_number(self.approach_speed, "approach_speed", 0.0, 1.0,
                       unit=" (fraction of the speed limits)", open_lo=True)
        for name, hi, unit in (("sample_period", 1.0, " s"), ("settle", 10.0, " s"),
                               ("start_tolerance", math.pi, " rad")):
            bounded_number(getattr(self, name), name, 0.0, hi, unit=unit)
        if self.update not in UPDATES:
            raise InvalidInputError("update", f"must be one of {', '.join(UPDATES)}, got {self.update!r}")
        for name in ("approach", "sync", "watchdog"):
            if not isinstance(getattr(self, name), bool):
                raise InvalidInputError(name, f"must be True or False, got {getattr(self, name)!r}")


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
            sleep: Callable[[float], None] = time.sleep,
            header: dict | None = None) -> RunResult:
    """Stream ``trajectory`` to ``arm`` and log it to ``log_path`` (JSON lines).

    ``header``: further fields of the log's header record (e.g. the scenario and its boxes, which
    ``iik view --run`` draws); JSON-serialisable, and they cannot replace the executor's own fields.

    SIGTERM and SIGHUP are handled like Ctrl-C meanwhile (:func:`iik.signals.stop_on_signals`).

    Raises:
        SafetyError: ``trajectory`` is not a :class:`ValidatedTrajectory`; a step is faster than a
            module's own speed limit (FMAXVEL) or a target outside its soft limits (FMINPOS/FMAXPOS:
            modules set up for another arm than the trajectory's); the host's limit check is
            another arm's; or the arm is not where the trajectory starts and ``options.approach``
            is off. Nothing is sent then.
        ModuleFault: a module reports an error or a halt before the start (nothing is sent).
        CANTimeoutError, ModuleFault, BusError, ProtocolError, DuplicateModuleError,
        KeyboardInterrupt, StopSignal: after HALT was broadcast and the fault logged.
    """
    if not isinstance(trajectory, ValidatedTrajectory):
        raise SafetyError("trajectory", "must be a ValidatedTrajectory from hardware.executor.validate()")
    if len(arm.modules) != trajectory.q.shape[1]:
        raise SafetyError("arm", f"has {len(arm.modules)} modules, the trajectory "
                          f"{trajectory.q.shape[1]} joints")
    if not isinstance(options, ExecutionOptions):
        raise InvalidInputError("options", f"expected ExecutionOptions, got {type(options).__name__}")
    tr = trajectory
    # Refusals before anything moves: no HALT needed, no log written.
    for m, s in zip(arm.modules, arm.states(), strict=True):
        if s & (P.State.ERROR | P.State.HALTED):
            what = "halted (HALT latches)" if s & P.State.HALTED else "in error"
            raise ModuleFault(m.id, s, f"before start: {what}",
                              Remedy("reset it first: {}", "reset", True, rerun=True))
    limits = arm.speed_limits()  # the modules' own FMAXVEL may be below the Sec 3.2 limits
    over = np.argwhere(np.abs(np.diff(tr.q, axis=0)) / (tr.step_ms[:, None] / 1000.0)
                       > limits * (1.0 + SPEED_TOLERANCE))
    if len(over):
        k, j = (int(v) for v in over[0])
        raise SafetyError(target_name(k + 1, j), f"the step to it needs more than module "
                          f"{arm.module_ids[j]}'s speed limit of {limits[j]:.4f} rad/s", step=k + 1, joint=j)
    soft = np.array([m.soft_limits() for m in arm.modules])  # FMINPOS/FMAXPOS: set for the arm they move
    outside = np.argwhere((tr.q < soft[:, 0] - SOFT_LIMIT_TOL) | (tr.q > soft[:, 1] + SOFT_LIMIT_TOL))
    if len(outside):
        k, j = (int(v) for v in outside[0])
        lo, hi = soft[j]
        raise SafetyError(target_name(k, j), f"{tr.q[k, j]:.4f} rad is outside module {arm.module_ids[j]}'s "
                          f"soft limits [{lo:.4f}, {hi:.4f}] rad (are the modules set up for the arm "
                          f"{tr.arm.name!r}?)", step=k, joint=j)
    if arm.arm is not None and not same_arm(arm.arm, tr.arm):
        raise SafetyError("arm", f"the modules' limits are those of the arm {arm.arm.name!r}; the trajectory "
                                 f"is for {tr.arm.name!r}")
    err = np.abs(arm.get_pos() - tr.q[0])
    if np.max(err) > options.start_tolerance and not options.approach:
        raise SafetyError("arm", f"is {np.max(err):.4f} rad from the trajectory start")
    with stop_on_signals():
        log = RunLog(log_path)
        log.write({**(header or {}), "type": "header", "version": RUN_LOG_VERSION,
                   "module_ids": list(arm.module_ids),
                   "times": tr.times.tolist(), "q": tr.q.tolist(), "poses": tr.poses.tolist(),
                   "step_ms": tr.step_ms.tolist(), "early": options.early, "sync": options.sync,
                   "update": options.update, "watchdog": options.watchdog,
                   "bus": str(arm.bus.channel_info), "arm": to_record(tr.arm),
                   "started": datetime.now(timezone.utc).isoformat()})
        stream = _Stream(arm, tr, log, options, clock, sleep)
        try:
            stream.run(err, progress)
            log.write({"type": "end", "t": clock() - stream.t0, "status": "ok"})
            log.close()
            return RunResult(Path(log_path), stream.commands, stream.sampler.count, clock() - stream.t0)
        except BaseException as exc:
            stream.stop(exc)
            raise


class _Stream:
    """The streaming of one validated trajectory (:func:`execute`), and its stop on a fault."""

    def __init__(self, arm: PowerCubeArm, tr: ValidatedTrajectory, log: RunLog, options: ExecutionOptions,
                 clock, sleep):
        self.arm, self.tr, self.log, self.options = arm, tr, log, options
        self.clock, self.sleep = clock, sleep
        self.t0 = clock()
        self.sampler = _Sampler(arm, log, self.t0, clock)
        self.commands = 0

    def command(self, k: int, q, time_s: float, start: bool = True) -> float:
        """FSTEP every joint to ``q`` in ``time_s`` (and STARTMOVE); returns when it was sent."""
        t = self.clock()
        # extended FSTEP: each ACK carries the module's actual position when the command
        # arrived, i.e. the measurement at the step-point the early update leaves
        q_meas, short = self.arm.move_step(q, time_s, extended=True)
        if start:
            self.arm.start_move()
        self.log.write({"type": "command", "t": t - self.t0, "k": k, "q": [float(v) for v in q],
                        "time_s": time_s, "q_meas": [float(v) for v in q_meas],
                        "short": [int(v) for v in short]})
        self.commands += 1
        return t

    def sample_until(self, deadline: float, k: int) -> None:
        """Sample every ``sample_period`` until ``deadline`` without delaying the next command."""
        while True:
            self.sampler.sample(k, deadline)
            now = self.clock()
            if now >= deadline:
                return
            self.sleep(min(self.options.sample_period, deadline - now))

    def run(self, err: np.ndarray, progress) -> None:
        """Approach the start if needed, then every step (Sec 4.3 or buffered update)."""
        tr, options = self.tr, self.options
        if options.watchdog:
            self.arm.start_watchdog()
        if np.max(err) > options.start_tolerance:
            v = np.asarray(tr.arm.velocity) * options.approach_speed
            t_app = math.ceil(max(float(np.max(err / v)), 0.05) * 1000.0) / 1000.0
            ts = self.command(0, tr.q[0], t_app)
            self.sample_until(ts + t_app + options.settle, 0)
        else:
            self.sampler.sample(0)
        n = len(tr)
        step_end = -math.inf  # end of the current step on the modules' timeline (buffered)
        for k in range(1, n):
            dt = tr.step_ms[k - 1] / 1000.0
            if options.update == "thesis":  # Sec 4.3: next command after 95 % of this one
                ts = self.command(k, tr.q[k], dt, start=options.sync)
                next_at = ts + (options.early * dt if k < n - 1 else dt + options.settle)
            else:  # buffered: queue the next step shortly before this one ends
                ts = self.command(k, tr.q[k], dt, start=(k == 1))
                # the step starts when the previous one ends, or at once if that already
                # happened (a late command): keep the timeline so no buffered step is overwritten
                step_end = max(step_end, ts) + dt
                self.log.write({"type": "step_end", "k": k, "t": step_end - self.t0})
                lead = min(max((1.0 - options.early) * dt, 0.020), 0.5 * dt)
                next_at = step_end - lead if k < n - 1 else step_end + options.settle
            if progress is not None:
                progress(k, n - 1)
            self.sample_until(next_at, k)
        self.sampler.sample(n - 1)  # one complete sample after the settle time: the final pose at rest
        if options.watchdog:
            self.arm.stop_watchdog(disable=True)

    def stop(self, exc: BaseException) -> None:
        """HALT every module (one broadcast), stop the watchdog, log the fault and the end, fsync."""
        halted = True
        try:
            self.arm.halt()  # broadcast: one frame stops every module
        except BaseException:  # noqa: BLE001 - the fault being handled matters more
            halted = False
        if self.options.watchdog:
            try:  # halted already; keep the latch, stop refreshing and clear the bit
                self.arm.stop_watchdog(disable=True)
            except BaseException:  # noqa: BLE001
                pass
        try:
            self.log.write({"type": "fault", "t": self.clock() - self.t0, "error": type(exc).__name__,
                            "message": str(exc), "halted": halted, "command": self.commands})
            self.log.write({"type": "end", "t": self.clock() - self.t0, "status": "fault"})
        finally:
            self.log.close()
