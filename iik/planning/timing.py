"""Time-parameterise a joint path within velocity and acceleration limits (TOPP-RA).

The geometric joint path (the IK solutions at the step-points) is
interpolated by a clamped cubic spline over its cumulative joint-space arc
length (``toppra.SplineInterpolator``); if the spline overshoots a limit, a
shape-preserving PCHIP curve is tried instead and retimed time-optimally by TOPP-RA
(``toppra.algorithm.TOPPRA``) under the joint velocity limits ``arm.velocity``
and acceleration limits ``arm.acceleration``. The result is sampled at ``dt``
and every sample is checked against the joint limits *with the executor's margin*
(:data:`EXECUTION_MARGIN`), the velocity and the acceleration limits
(:attr:`Trajectory.violations`), so that what the planner writes the arm can run.

One trajectory from plan to run. The arm executes the step-points themselves
(FSTEP: constant velocity from one to the next, Sec 4.3) at the times the TOPP-RA
curve passes them, on the FSTEP clock: :attr:`Trajectory.step_t` are those times
rounded to whole milliseconds (:data:`STEP_RESOLUTION`), each step at least
:data:`MIN_STEP` long and slow enough for the joint speed limits at its rounded
length (:func:`step_schedule`). ``iik plan`` writes them (``steps.csv``, column ``t``)
and ``iik run`` executes exactly them; the dense samples (``trajectory.csv``) follow
the same timing law every ``dt`` and are accepted by ``iik run --trajectory`` too.

:func:`thesis_timing` is the thesis's scheme for comparison (Sec 4.2.2: "The
angular velocity chosen for the 6-DOF manipulator is proportional to the joint
effort index"): every step takes the same time, scaled so the fastest joint
just reaches its speed limit; velocity is then proportional to the step's joint
change (and so to the effort index of Eq 54).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from iik.arm import Arm
from iik.validation import as_joints

from ..safety import EXECUTION_MARGIN, MIN_STEP, STEP_RESOLUTION  # re-exported: their home is iik.safety
from .errors import TimingError
from .path import interpolate_joints

__all__ = ["Trajectory", "time_parameterize", "thesis_timing", "step_schedule", "EXECUTION_MARGIN",
           "STEP_RESOLUTION", "MIN_STEP"]



@dataclass(frozen=True)
class Trajectory:
    """A timed joint trajectory sampled every ``dt``.

    Attributes:
        t: (m,) times [s]; q, qd, qdd: (m, 6) [rad, rad/s, rad/s^2].
        duration: Total time [s].
        method: How it was timed.
        violations: Human-readable limit violations found at the samples (empty = none).
        step_q: (n, 6) the input waypoints (step-points) [rad], or None.
        step_t: (n,) times [s] at which the arm executes them: the curve's passing times on
            the FSTEP clock (:func:`step_schedule`); None for :func:`thesis_timing`.
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    duration: float
    method: str
    violations: tuple[str, ...] = ()
    step_q: np.ndarray | None = None
    step_t: np.ndarray | None = None


def _check(q, qd, qdd, arm: Arm, joint_margin: float, tol: float = 1e-9) -> tuple[str, ...]:
    out = []
    v, a = np.asarray(arm.velocity), np.asarray(arm.acceleration)
    worst = arm.limit_violations(q, joint_margin).worst
    if worst is not None and worst.amount > tol:
        out.append(f"joint q{worst.joint + 1} comes {math.degrees(worst.amount):.3f} deg beyond Table I less "
                   f"the execution margin of {math.degrees(joint_margin):g} deg (sample {worst.sample}, "
                   "counting from 0)")
    if np.any(np.abs(qd) > v * (1 + 1e-9)):
        out.append(f"velocity limit exceeded: max |qd|/v = {(np.abs(qd) / v).max():.4f}")
    if np.any(np.abs(qdd) > a * (1 + 1e-9)):
        out.append(f"acceleration limit exceeded: max |qdd|/a = {(np.abs(qdd) / a).max():.4f}")
    return tuple(out)


def _dedupe(Q: np.ndarray) -> np.ndarray:
    keep = np.concatenate([[True], np.linalg.norm(np.diff(Q, axis=0), axis=1) > 1e-9])
    return Q[keep]


class _PchipPath:
    """C1 shape-preserving joint path (scipy PCHIP) for TOPP-RA.

    Unlike a cubic spline it never overshoots its waypoints, so a path whose
    waypoints respect the joint limits respects them everywhere.
    """

    def __init__(self, s: np.ndarray, Q: np.ndarray):
        from scipy.interpolate import PchipInterpolator

        self._p = PchipInterpolator(s, Q, axis=0)
        self._d1 = self._p.derivative(1)
        self._d2 = self._p.derivative(2)
        self._s, self._Q = s, Q

    def __call__(self, ss, order: int = 0):
        return (self._p, self._d1, self._d2)[order](ss)

    @property
    def dof(self) -> int:
        return self._Q.shape[1]

    @property
    def path_interval(self) -> np.ndarray:
        return np.array([self._s[0], self._s[-1]])

    @property
    def waypoints(self):
        return self._s, self._Q

    def eval(self, ss):
        return self(ss, 0)

    def evald(self, ss):
        return self(ss, 1)

    def evaldd(self, ss):
        return self(ss, 2)


def time_parameterize(qs, arm: Arm, *, dt: float = 0.01,
                      gridpoints: int | None = None, margin: float = 0.95,
                      joint_margin: float = EXECUTION_MARGIN) -> Trajectory:
    """Time-optimal timing of the joint path ``qs`` (n, 6) [rad] by TOPP-RA within ``arm``'s limits.

    Starts and ends at rest. A path with a single distinct configuration gives
    a zero-length trajectory. Curves tried in turn until every sample respects
    the limits (else the first one is returned with its :attr:`~Trajectory.violations`):
    1) a cubic spline through the waypoints (C2, smooth accelerations); 2) the same
    through the polyline densified to 0.02 rad (hugs the polyline; slower at
    corners); 3) a shape-preserving PCHIP curve through the waypoints on a fine grid.

    Args:
        margin: Fraction of the velocity and acceleration limits TOPP-RA plans with.
        joint_margin: Every sample stays this far inside Table I [rad]
            (:data:`EXECUTION_MARGIN`: what ``hardware.validate`` requires by default).

    Raises:
        TimingError: TOPP-RA failed or found no parameterisation (its exception is the cause).
    """
    Q0, _ = as_joints(qs, "qs")
    Q = _dedupe(Q0)
    if len(Q) < 2:
        z = np.zeros((1, 6))
        return Trajectory(np.zeros(1), Q[:1].copy(), z, z, 0.0, "static", step_q=Q0.copy(),
                          step_t=step_schedule(np.zeros(len(Q0)), Q0, arm))
    timed = []
    for kind in ("spline", "dense spline", "pchip"):
        timed.append(_toppra(_curve(Q, kind, gridpoints), kind, arm, margin, joint_margin, dt, Q0))
        if not timed[-1].violations:
            break
    tr = timed[-1] if not timed[-1].violations else timed[0]
    tr.q[0], tr.q[-1] = Q[0], Q[-1]
    return tr


def step_schedule(t, q, arm: Arm, *, min_step: float = MIN_STEP,
                  resolution: float = STEP_RESOLUTION) -> np.ndarray:
    """Times [s] at which the arm executes the step-points ``q`` (n, 6) [rad] meant for times ``t``.

    Each time is ``t`` rounded to ``resolution`` (FSTEP's whole milliseconds), except that a
    step is never shorter than ``min_step`` nor than its slowest joint needs at its speed
    limit; where that holds a step-point back, the later ones follow as early as allowed.
    Starts at 0. A step's joint speeds are then at most ``arm.velocity`` at its rounded length.
    """
    ta, qa = np.asarray(t, dtype=float), np.asarray(q, dtype=float)
    ticks = np.rint((ta - ta[0]) / resolution)
    need = np.ceil(np.maximum(np.max(np.abs(np.diff(qa, axis=0)) / np.asarray(arm.velocity), axis=1),
                              min_step) / resolution - 1e-9)
    out = np.zeros(len(ta))
    for k in range(1, len(ta)):
        out[k] = max(ticks[k], out[k - 1] + need[k - 1])
    return out * resolution


def _passing_times(grid: np.ndarray, sd: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Times [s] at which a constant-acceleration parameterisation (TOPP-RA's
    ``ParametrizeConstAccel``: path speed ``sd`` at ``grid``) reaches the path positions ``s``."""
    ts = np.concatenate([[0.0], np.cumsum(2.0 * np.diff(grid) / (sd[:-1] + sd[1:]))])
    i = np.clip(np.searchsorted(grid, s, side="right") - 1, 0, len(grid) - 2)
    ds = s - grid[i]
    x = sd[i] ** 2 + (sd[i + 1] ** 2 - sd[i] ** 2) * ds / (grid[i + 1] - grid[i])  # sd^2 is linear in s
    denom = sd[i] + np.sqrt(np.maximum(x, 0.0))
    return ts[i] + np.divide(2.0 * ds, denom, out=np.zeros_like(ds), where=denom > 0)


def _curve(Q: np.ndarray, kind: str, gridpoints: int | None):
    """(geometric path, TOPP-RA grid) of one of the curves of :func:`time_parameterize`."""
    import toppra as ta

    W = interpolate_joints(Q, max_joint_step=0.02) if kind == "dense spline" else Q
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(W, axis=0), axis=1))])
    s = s / s[-1]
    if kind == "pchip":
        grid = np.unique(np.concatenate([np.linspace(a, b, 9, endpoint=False)
                                         for a, b in zip(s[:-1], s[1:], strict=True)] + [[1.0]]))
        return _PchipPath(s, W), grid
    grid = np.linspace(0, 1, gridpoints or int(min(2000, max(200, 8 * len(W)))))
    return ta.SplineInterpolator(s, W, bc_type="clamped"), grid


def _toppra(curve, kind: str, arm: Arm, margin: float, joint_margin: float, dt: float,
            waypoints: np.ndarray) -> Trajectory:
    """TOPP-RA on ``curve``; limits scaled by ``margin`` and tightened until every sample is inside.

    TOPP-RA enforces the limits at grid points only, so plan inside them and
    tighten until every sample of the result respects the true limits.
    """
    import toppra.algorithm as algo
    import toppra.constraint as constraint

    path, grid = curve
    for m in (margin, 0.85 * margin, 0.7 * margin, 0.5 * margin):
        v = m * np.asarray(arm.velocity, float)
        a = m * np.asarray(arm.acceleration, float)
        try:
            instance = algo.TOPPRA([constraint.JointVelocityConstraint(np.column_stack([-v, v])),
                                    constraint.JointAccelerationConstraint(np.column_stack([-a, a]))],
                                   path, gridpoints=grid, parametrizer="ParametrizeConstAccel")
            traj = instance.compute_trajectory(0.0, 0.0)
        except Exception as exc:  # toppra raises plain ValueError/AssertionError/...: wrap at the boundary
            raise TimingError(f"TOPP-RA failed on the {kind} joint path: {exc}") from exc
        if traj is None:
            raise TimingError(f"TOPP-RA found no feasible parameterisation of the {kind} joint path")
        T = float(traj.duration)
        t = np.linspace(0.0, T, max(2, int(np.ceil(T / dt)) + 1))
        q, qd, qdd = traj(t), traj(t, 1), traj(t, 2)
        bad = _check(q, qd, qdd, arm, joint_margin)
        if not bad or bad[0].startswith("joint"):  # slower timing cannot move the curve off a stop
            break
    data = instance.problem_data
    steps = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(waypoints, axis=0), axis=1))])
    t_wp = _passing_times(np.asarray(data.gridpoints, float), np.asarray(data.sd_vec, float),
                          np.clip(steps / steps[-1], 0.0, 1.0))
    return Trajectory(t, q, qd, qdd, T, f"toppra {kind} (limits x{m:.2f})", bad, step_q=waypoints.copy(),
                      step_t=step_schedule(t_wp, waypoints, arm))


def thesis_timing(qs, arm: Arm) -> Trajectory:
    """The thesis's timing: equal time per step, velocity proportional to the step's effort.

    Each step lasts ``max_i max_n |dq_n,i| / v_n``: the largest step just reaches
    the speed limit. Velocities are piecewise constant (infinite acceleration at
    step changes, as with the PowerCube's constant-velocity command, Sec 4.3).
    """
    Q, _ = as_joints(qs, "qs")
    Q = _dedupe(Q)
    if len(Q) < 2:
        z = np.zeros((1, 6))
        return Trajectory(np.zeros(1), Q[:1].copy(), z, z, 0.0, "thesis (static)")
    dq = np.diff(Q, axis=0)
    h = float((np.abs(dq) / np.asarray(arm.velocity)).max())
    t = np.arange(len(Q)) * h
    qd = np.vstack([dq / h, np.zeros((1, 6))])
    qdd = np.full_like(Q, np.nan)
    return Trajectory(t, Q, qd, qdd, float(t[-1]), "thesis: velocity proportional to effort index")
