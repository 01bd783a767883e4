"""Time-parameterise a joint path within velocity and acceleration limits (TOPP-RA).

The geometric joint path (the IK solutions at the step-points) is
interpolated by a clamped cubic spline over its cumulative joint-space arc
length (``toppra.SplineInterpolator``); if the spline overshoots a limit, a
shape-preserving PCHIP curve is tried instead and retimed time-optimally by TOPP-RA
(``toppra.algorithm.TOPPRA``) under the joint velocity limits ``arm.velocity``
and acceleration limits ``arm.acceleration``. The result is sampled at ``dt``
and every sample is checked against the joint, velocity and acceleration limits
(:attr:`Trajectory.violations`).

:func:`thesis_timing` is the thesis's scheme for comparison (Sec 4.2.2: "The
angular velocity chosen for the 6-DOF manipulator is proportional to the joint
effort index"): every step takes the same time, scaled so the fastest joint
just reaches its speed limit; velocity is then proportional to the step's joint
change (and so to the effort index of Eq 54).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from iik.arm import THESIS_ARM, Arm
from iik.validation import as_joints

from .errors import TimingError
from .path import interpolate_joints

__all__ = ["Trajectory", "time_parameterize", "thesis_timing"]


@dataclass(frozen=True)
class Trajectory:
    """A timed joint trajectory sampled every ``dt``.

    Attributes:
        t: (m,) times [s]; q, qd, qdd: (m, 6) [rad, rad/s, rad/s^2].
        duration: Total time [s].
        method: How it was timed.
        violations: Human-readable limit violations found at the samples (empty = none).
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    duration: float
    method: str
    violations: tuple[str, ...] = ()


def _check(q, qd, qdd, arm: Arm, tol: float = 1e-6) -> tuple[str, ...]:
    out = []
    lo, hi = arm.q_min, arm.q_max
    v, a = np.asarray(arm.velocity), np.asarray(arm.acceleration)
    if np.any(q < lo - tol) or np.any(q > hi + tol):
        out.append(f"joint limit exceeded by {max((lo - q).max(), (q - hi).max()):.2e} rad")
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


def time_parameterize(qs, arm: Arm = THESIS_ARM, *, dt: float = 0.01,
                      gridpoints: int | None = None, margin: float = 0.95) -> Trajectory:
    """Time-optimal timing of the joint path ``qs`` (n, 6) [rad] by TOPP-RA within ``arm``'s limits.

    Starts and ends at rest. A path with a single distinct configuration gives
    a zero-length trajectory. Curves tried in turn until every sample respects
    the limits (else the first one is returned with its :attr:`~Trajectory.violations`):
    1) a cubic spline through the waypoints (C2, smooth accelerations); 2) the same
    through the polyline densified to 0.02 rad (hugs the polyline; slower at
    corners); 3) a shape-preserving PCHIP curve through the waypoints on a fine grid.

    Raises:
        TimingError: TOPP-RA failed or found no parameterisation (its exception is the cause).
    """
    Q, _ = as_joints(qs, "qs")
    Q = _dedupe(Q)
    if len(Q) < 2:
        z = np.zeros((1, 6))
        return Trajectory(np.zeros(1), Q[:1].copy(), z, z, 0.0, "static")
    timed = []
    for kind in ("spline", "dense spline", "pchip"):
        timed.append(_toppra(_curve(Q, kind, gridpoints), kind, arm, margin, dt))
        if not timed[-1].violations:
            break
    tr = timed[-1] if not timed[-1].violations else timed[0]
    tr.q[0], tr.q[-1] = Q[0], Q[-1]
    return tr


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


def _toppra(curve, kind: str, arm: Arm, margin: float, dt: float) -> Trajectory:
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
        bad = _check(q, qd, qdd, arm)
        if not bad:
            break
    return Trajectory(t, q, qd, qdd, T, f"toppra {kind} (limits x{m:.2f})", bad)


def thesis_timing(qs, arm: Arm = THESIS_ARM) -> Trajectory:
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
