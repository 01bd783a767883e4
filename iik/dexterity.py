"""Dexterity (Sec 3.5), exact: the end-effector orientations the complete IK reaches at a point.

The question of Sec 3.5: at a tool point ``p``, which orientations can the end effector take?
This module answers it with the complete IK (:func:`iik.solve`) instead of the thesis's
formulas. An orientation is given by the angles of Eq 42 as corrected in :mod:`iik.rotations`
(Z-Y-Z, the convention :func:`iik.pose_from_euler` takes): ``beta`` is the polar angle of the
tool z axis from the base +z, ``alpha`` its azimuth, ``gamma`` the roll about it.

**Definition.** ``(alpha, beta)`` is *admissible* at ``p`` when some ``gamma`` gives a pose
with an IK solution inside the joint limits (the one limit test,
:meth:`iik.Arm.within_limits`; approximate rows do not count). For an arm whose tool z axis
is the last joint's axis and whose tool point lies on it (the thesis arm: Table II, d6 = -l5),
turning ``gamma`` turns joint 6 alone (Sec 3.5.1), so the test is one IK call on
``pose_from_euler(p, alpha, beta, 0)`` for the arm with joint 6 opened to a full turn; when
joint 6 spans a full turn itself (Table I: +-180 deg) every ``gamma`` is admissible too.

**Method (root-finding on feasibility).** Feasibility is evaluated on a grid (``alpha`` every
``2 pi / alpha_samples``, ``beta`` every ``pi / (beta_samples - 1)``); every change between
two neighbouring samples is a bracket whose end is found by bisection on the IK's
feasibility down to ``DexterityOptions.tol``. The ends of an ``beta`` interval are found the
same way, with the predicate "some alpha is admissible" evaluated at the grid alphas and
inside the alpha intervals of the feasible side of the bracket (they shrink to a point at the
end of the beta range). So every end reported is a point where feasibility changes, within
``tol``; a piece narrower than the grid step can be missed (``resolution`` says how fine).

The thesis's own formulas (Eq 43-51: a shell around joint 2 that the second-last joint must
lie in) are neither necessary nor sufficient; they are kept only as the thesis's rows in
``verification/checks/dexterity.py``, graded there by their false-admit and false-reject
rates against this set.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .arm import Arm
from .errors import DexterityError, InvalidInputError, UnreachablePoseError
from .ik.angles import wrap_angle
from .ik.solve import solve_batch
from .rotations import pose_from_euler
from .validation import as_float_array, as_points

__all__ = ["Dexterity", "DexterityOptions", "dexterity", "alpha_intervals", "admissible"]

_TWO_PI = 2.0 * math.pi
_AXIS_TOL = 1e-9  # [rad and m]: the tool z axis is joint 6's axis


@dataclass(frozen=True)
class DexterityOptions:
    """How finely :func:`dexterity` looks for the admissible sets.

    Attributes:
        alpha_samples: Grid samples of alpha over a full turn (default 180: every 2 deg).
        beta_samples: Grid samples of beta over [0, pi], both ends included (default 91: 2 deg).
        tol: Bisection stops when a bracket is narrower than this [rad].
    """

    alpha_samples: int = 180
    beta_samples: int = 91
    tol: float = 1e-9

    def __post_init__(self) -> None:
        for name, lo in (("alpha_samples", 4), ("beta_samples", 3)):
            v = getattr(self, name)
            if not isinstance(v, int) or isinstance(v, bool) or not lo <= v <= 100_000:
                raise InvalidInputError(name, f"expected an integer in {lo} .. 100000, got {v!r}")
        if not (isinstance(self.tol, (int, float)) and math.isfinite(self.tol) and 1e-14 <= self.tol <= 0.1):
            raise InvalidInputError("tol", f"expected a number in [1e-14, 0.1] rad, got {self.tol!r}")

    @property
    def resolution(self) -> tuple[float, float]:
        """Grid steps (alpha, beta) [rad]: pieces narrower than these may be missed."""
        return _TWO_PI / self.alpha_samples, math.pi / (self.beta_samples - 1)


@dataclass(frozen=True)
class Dexterity:
    """The admissible orientations at one point, from the complete IK (angles in rad, Eq 42).

    Like :class:`iik.IKResult`, a point where nothing is admissible is an answer, not an error:
    ``beta_intervals`` is empty and ``reason`` says why; :meth:`raise_if_unreachable` raises
    :class:`~iik.errors.UnreachablePoseError` on request.

    Attributes:
        point: The tool point [m], (3,), in the arm's base frame.
        arm: The arm the sets belong to.
        beta_intervals: Admissible beta, as disjoint ``(lo, hi)`` intervals in [0, pi], sorted.
        beta_end_alphas: For each beta interval, an alpha admissible at its lower and at its upper
            end (where the extreme tilt is reached: the alpha set shrinks to a point there).
        beta: The chosen beta, or None.
        alpha_intervals: For the chosen beta, the admissible alpha as ``(lo, hi)`` intervals with
            ``-pi <= lo <= hi`` and ``hi - lo <= 2 pi`` (an interval may run past +pi: angles are
            modulo 2 pi); ``(-pi, pi)`` is every alpha. Empty when ``beta`` is None.
        gamma_free: Every gamma is admissible with an admissible (alpha, beta) (joint 6 spans a
            full turn); else the gamma that fit depend on the solution (ask :func:`iik.solve`).
        resolution: Grid steps (alpha, beta) [rad] of the search (:class:`DexterityOptions`).
        tol: Every interval end is within this of a change of feasibility [rad].
        reason: Why nothing is admissible, else "".
    """

    point: np.ndarray
    arm: Arm
    beta_intervals: tuple[tuple[float, float], ...]
    beta_end_alphas: tuple[tuple[float, float], ...]
    beta: float | None
    alpha_intervals: tuple[tuple[float, float], ...]
    gamma_free: bool
    resolution: tuple[float, float]
    tol: float
    reason: str = ""

    @property
    def reachable(self) -> bool:
        """Is any orientation admissible at the point?"""
        return bool(self.beta_intervals)

    @property
    def beta_range(self) -> tuple[float, float] | None:
        """``(smallest, largest)`` admissible beta [rad] (the intervals may have gaps), or None."""
        if not self.beta_intervals:
            return None
        return self.beta_intervals[0][0], self.beta_intervals[-1][1]

    def raise_if_unreachable(self) -> Dexterity:
        """Return self, or raise :class:`~iik.errors.UnreachablePoseError` (with ``reason``)."""
        if not self.reachable:
            raise UnreachablePoseError(self.reason)
        return self

    def admits(self, alpha, beta) -> np.ndarray:
        """Is each ``(alpha, beta)`` [rad] admissible? Asks the IK (:func:`admissible`), not the intervals."""
        return admissible(self.point, alpha, beta, self.arm)


def _gamma_is_joint6(arm: Arm) -> tuple[bool, str]:
    """Is the tool z axis joint 6's axis, with the tool point on it (then gamma turns joint 6 alone)?"""
    from .kinematics import fk

    q = np.zeros(6)
    pts, dirs = arm.joint_axes(q)
    T = fk(q, arm)
    z, p = T[:3, 2], T[:3, 3]
    sin_angle = float(np.linalg.norm(np.cross(dirs[5], z)))
    off = float(np.linalg.norm(np.cross(p - pts[5], dirs[5])))
    if sin_angle > _AXIS_TOL or off > _AXIS_TOL:
        angle = math.asin(min(1.0, sin_angle))
        return False, (f"the tool z axis of {arm.name} is not joint 6's axis (angle {angle:.3g} rad, tool "
                       f"point {off:.3g} m off it): gamma does not turn joint 6 alone")
    return True, ""


def _roll_free_arm(arm: Arm) -> Arm:
    """The arm with joint 6 opened to a full turn: any roll of the tool is some gamma."""
    lo, hi = list(arm.lower), list(arm.upper)
    if lo[5] == -math.pi and hi[5] == math.pi:
        return arm
    lo[5], hi[5] = -math.pi, math.pi
    return arm.with_limits(lower=lo, upper=hi)


def _feasible(p: np.ndarray, alpha: np.ndarray, beta: np.ndarray, free: Arm) -> np.ndarray:
    """IK feasibility (an exact, in-limits solution of ``free``) at each (alpha, beta): bool (n,)."""
    n = alpha.size
    if n == 0:
        return np.zeros(0, bool)
    Ts = pose_from_euler(np.broadcast_to(p, (n, 3)), alpha, beta, np.zeros(n))
    b = solve_batch(Ts, free, within_limits=True)
    rows = np.arange(b.q.shape[1])[None, :] < b.count[:, None]
    return np.any(rows & ~b.approximate, axis=1)


def admissible(p, alpha, beta, arm: Arm) -> np.ndarray:
    """Is each ``(alpha, beta)`` [rad] (Eq 42, broadcast) admissible at the tool point ``p`` [m]?

    One IK call per orientation (:func:`iik.ik.solve_batch`): True when some gamma has an exact
    solution inside ``arm``'s joint limits. Returns a bool array of the broadcast shape.
    """
    pt = _point(p)
    a = as_float_array(alpha, "alpha")
    b = as_float_array(beta, "beta")
    a, b = np.broadcast_arrays(a, b)
    return _feasible(pt, a.ravel(), b.ravel(), _checked_free_arm(arm)).reshape(a.shape)


def alpha_intervals(p, beta: float, arm: Arm, *, options: DexterityOptions | None = None
                    ) -> tuple[tuple[float, float], ...]:
    """The admissible alpha intervals [rad] at the tool point ``p`` [m] for one ``beta`` [rad] (Eq 42).

    Same intervals as ``dexterity(p, arm, beta=beta).alpha_intervals`` without computing the
    beta intervals (and without raising when ``beta`` admits nothing: the answer is ``()``).
    """
    opts = options or DexterityOptions()
    return _alpha_set(_point(p), _beta(beta), _checked_free_arm(arm), opts)


def _beta(beta) -> float:
    b = as_float_array(beta, "beta")
    if b.shape != ():
        raise InvalidInputError("beta", f"expected a scalar, got shape {b.shape}")
    if not 0.0 <= float(b) <= math.pi:
        raise InvalidInputError("beta", f"{float(b):.6g} rad is outside [0, pi]: a polar angle (Eq 42)")
    return float(b)


def _checked_free_arm(arm: Arm) -> Arm:
    if not isinstance(arm, Arm):
        raise InvalidInputError("arm", f"expected an iik.Arm, got {type(arm).__name__}")
    ok, why = _gamma_is_joint6(arm)
    if not ok:
        raise InvalidInputError("arm", why)
    return _roll_free_arm(arm)


def _point(p) -> np.ndarray:
    pb, batched = as_points(p, "p")
    if batched:
        raise InvalidInputError("p", f"expected one point of shape (3,), got shape {pb.shape}")
    return pb[0].astype(float)


def _bisect(pred, inside: np.ndarray, outside: np.ndarray, tol: float) -> np.ndarray:
    """Bisect every bracket (inside[i] feasible, outside[i] not) to ``tol``; returns the feasible ends.

    ``pred`` maps an array of parameters to bool; all brackets advance together (one batch per step).
    """
    inside, outside = inside.astype(float).copy(), outside.astype(float).copy()
    while inside.size and np.max(np.abs(outside - inside)) > tol:
        mid = 0.5 * (inside + outside)
        ok = pred(mid)
        inside = np.where(ok, mid, inside)
        outside = np.where(ok, outside, mid)
    return inside


def _intervals_on_circle(x: np.ndarray, ok: np.ndarray, pred, tol: float) -> tuple[tuple[float, float], ...]:
    """Admissible intervals of a periodic parameter sampled at sorted ``x`` (in [-pi, pi)) with ``ok``;
    the intervals start in (-pi, pi]."""
    if ok.all():
        return ((-math.pi, math.pi),)
    if not ok.any():
        return ()
    xn, okn = np.append(x, x[0] + _TWO_PI), np.append(ok, ok[0])
    up = np.nonzero(~okn[:-1] & okn[1:])[0]  # x[i] out, x[i+1] in: a start
    down = np.nonzero(okn[:-1] & ~okn[1:])[0]  # x[i] in, x[i+1] out: an end
    starts = _bisect(pred, xn[up + 1], xn[up], tol)
    ends = _bisect(pred, xn[down], xn[down + 1], tol)
    starts = wrap_angle(starts)
    out = []
    for s in np.sort(starts):
        e = ends[np.argmin((ends - s) % _TWO_PI)]
        e = s + (e - s) % _TWO_PI
        out.append((float(s), float(e)))
    return tuple(out)


def _alpha_set(p, beta: float, free: Arm, opts: DexterityOptions) -> tuple:
    """The admissible alpha intervals at ``beta``: grid samples, the ends between them bisected."""
    x = -math.pi + _TWO_PI * np.arange(opts.alpha_samples) / opts.alpha_samples
    ok = _feasible(p, x, np.full(x.size, beta), free)

    def pred(a):
        return _feasible(p, a, np.full(a.size, beta), free)

    return _intervals_on_circle(x, ok, pred, opts.tol)


def _runs(x: np.ndarray, ok: np.ndarray, pad: float) -> list[tuple[float, float]]:
    """Spans ``(lo - pad, hi + pad)`` around each run of consecutive admissible samples of sorted ``x``."""
    idx = np.nonzero(ok)[0]
    if idx.size == 0:
        return []
    breaks = np.nonzero(np.diff(idx) > 1)[0]
    firsts, lasts = np.r_[idx[0], idx[breaks + 1]], np.r_[idx[breaks], idx[-1]]
    return [(float(x[i] - pad), float(x[j] + pad)) for i, j in zip(firsts, lasts, strict=True)]


def _merged(spans: list[tuple[float, float]]) -> list[tuple[float, float]]:
    out: list[list[float]] = []
    for lo, hi in sorted(spans):
        if out and lo <= out[-1][1]:
            out[-1][1] = max(out[-1][1], hi)
        else:
            out.append([lo, hi])
    return [(lo, hi) for lo, hi in out]


def _beta_end(p, free, opts, b_in: float, b_out: float) -> tuple[float, float]:
    """Bisect beta from a feasible ``b_in`` to an infeasible ``b_out``: the end, an alpha admissible at it.

    "Some alpha is admissible at beta" is tested on the alpha grid and on 33 samples across each
    span of alphas admissible at the feasible side (near the end the set shrinks to a point, like
    the square root of the distance to it, so the samples follow it down).
    """
    grid = -math.pi + _TWO_PI * np.arange(opts.alpha_samples) / opts.alpha_samples
    step = _TWO_PI / opts.alpha_samples
    ok = _feasible(p, grid, np.full(grid.size, b_in), free)
    spans, witness = _runs(grid, ok, step), float(grid[np.argmax(ok)])
    while abs(b_out - b_in) > opts.tol:
        mid = 0.5 * (b_in + b_out)
        fine = [np.linspace(lo, hi, 33) for lo, hi in spans]
        x = np.concatenate([grid, *fine])
        ok = _feasible(p, x, np.full(x.size, mid), free)
        if not ok.any():
            b_out = mid
            continue
        b_in, witness = mid, float(x[np.argmax(ok)])
        at = grid.size
        spans = _runs(grid, ok[:at], step)
        for f in fine:
            spans += _runs(f, ok[at:at + f.size], f[1] - f[0])
            at += f.size
        spans = _merged(spans)
    return b_in, float(wrap_angle(witness))


def _beta_set(p, free: Arm, opts: DexterityOptions) -> tuple[tuple, tuple]:
    """The admissible beta intervals and, for each, an admissible alpha at its two ends."""
    betas = np.linspace(0.0, math.pi, opts.beta_samples)
    grid = -math.pi + _TWO_PI * np.arange(opts.alpha_samples) / opts.alpha_samples
    A, B = np.meshgrid(grid, betas)
    ok_ab = _feasible(p, A.ravel(), B.ravel(), free).reshape(B.shape)
    ok = ok_ab.any(axis=1)
    out, wit, i, last = [], [], 0, len(betas) - 1
    while i <= last:
        if not ok[i]:
            i += 1
            continue
        j = i
        while j < last and ok[j + 1]:
            j += 1
        lo, a_lo = ((betas[0], grid[np.argmax(ok_ab[0])]) if i == 0
                    else _beta_end(p, free, opts, betas[i], betas[i - 1]))
        hi, a_hi = ((betas[last], grid[np.argmax(ok_ab[last])]) if j == last
                    else _beta_end(p, free, opts, betas[j], betas[j + 1]))
        out.append((float(lo), float(hi)))
        wit.append((float(a_lo), float(a_hi)))
        i = j + 1
    return tuple(out), tuple(wit)


def dexterity(p, arm: Arm, *, beta: float | None = None,
              options: DexterityOptions | None = None) -> Dexterity:
    """The admissible beta intervals at ``p`` and, for a chosen ``beta``, the alpha intervals (exact).

    Args:
        p: Tool point [m], shape (3,), in the arm's base frame.
        arm: The arm (its tool z axis must be joint 6's axis, see the module doc).
        beta: Optional polar angle [rad] of the tool z axis (Eq 42 convention).
        options: Grid and bisection tolerance (:class:`DexterityOptions`).

    Returns:
        :class:`Dexterity`. Nothing admissible (the point out of reach, or reached only outside
        the limits) is an answer with empty intervals and a ``reason``.

    Raises:
        InvalidInputError: NaN/inf, a wrong shape, or an arm whose roll is not joint 6.
        DexterityError: ``beta`` outside every admissible interval at a point where some are.
    """
    opts = options or DexterityOptions()
    pt = _point(p)
    beta = None if beta is None else _beta(beta)
    free = _checked_free_arm(arm)
    gamma_free = float(arm.upper[5]) - float(arm.lower[5]) >= _TWO_PI - 1e-12
    betas, witnesses = _beta_set(pt, free, opts)
    reason = "" if betas else (
        f"no orientation at p = [{pt[0]:.4f}, {pt[1]:.4f}, {pt[2]:.4f}] m has an IK solution within the "
        f"joint limits of {arm.name} (a grid of {opts.alpha_samples} x {opts.beta_samples} orientations: a "
        f"set narrower than {math.degrees(max(opts.resolution)):.3g} deg may be missed)")
    alphas: tuple[tuple[float, float], ...] = ()
    if beta is not None:
        if betas and not any(lo - opts.tol <= beta <= hi + opts.tol for lo, hi in betas):
            raise DexterityError(beta, betas)
        alphas = _alpha_set(pt, beta, free, opts)
    return Dexterity(point=pt, arm=arm, beta_intervals=betas, beta_end_alphas=witnesses, beta=beta,
                     alpha_intervals=alphas,
                     gamma_free=gamma_free, resolution=opts.resolution, tol=opts.tol, reason=reason)
