"""Local dexterity (Sec 3.5): which end-effector orientations are possible at a point.

The thesis's model (Sec 3.5, Figs 18-26): the tool point ``p`` is reached with
link 5 (length ``l5``) coming from the second-last joint (SLJ, joint 5), and
the SLJ lies in a spherical shell around joint 2 (placed as in Eq 36-37 at
azimuth ``phi = atan2(py, px)``): at most ``l3 + l4`` away (links 3 and 4
aligned, exterior boundary) and at least ``d`` away (joint 4 at its limit,
interior boundary, Eq 45 / Eq 50). The service sphere of radius ``l5`` around
``p`` cuts that shell: outer intersection only (end effector facing outside),
both (ring effect) or inner only (facing inside), Figs 20-21.

Writing ``e`` for the unit vector from joint 2 to ``p`` (elevation ``beta'``,
Eq 43) and ``a`` for the direction of link 5 (SLJ -> tool), the SLJ
``p - l5 a`` is in the shell exactly when the angle between ``a`` and ``e``
lies in ``[delta_in, delta_out]`` with ``cos delta = (l5^2 + rho^2 - r^2) /
(2 l5 rho)`` and ``r = l3 + l4`` (Eq 44) or ``r = d`` (Eq 45). This module
evaluates that condition exactly:

* beta range: the elevations of admissible ``a``; in the outer case this is
  Eq 44's ``beta' +- delta`` (clipped to +-90 deg);
* alpha range for a chosen beta: the azimuths of admissible ``a`` at that
  elevation, ``alpha_c +- [w_in, w_out]`` (one interval, or two in the ring
  case), from the spherical law of cosines; the thesis's Eq 49 / Eq 51
  instead use a projected triangle (checked separately in ``iik verify``);
* gamma is free: it only turns joint 6, whose range (Table I) is a full turn
  (Sec 3.5.1).

**Angle convention.** Results are in the convention of Eq 42 as corrected in
:mod:`iik.rotations` (the one :func:`iik.pose_from_euler` takes): ``beta`` is
the polar angle of the tool z axis ``z6 = [r13, r23, r33]`` from +z and
``alpha`` its azimuth. Frame 6's z axis points from the tool back along link 5
(Table II, ``d6 = -l5``), so ``z6 = -a``. The thesis's Sec 3.5 angles are
those of ``a`` measured from the horizontal (Eq 43 ``atan`` of rise over run,
Eq 47 ``h = pz - l5 sin(beta)``): ``beta_42 = beta_35 + 90 deg`` and
``alpha_42 = alpha_35 + 180 deg`` (reported as an erratum by ``iik verify``).
The Sec 3.5 values are kept in the result as ``inclination_range``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .arm import Arm
from .errors import DexterityError, InvalidInputError, UnreachablePoseError
from .validation import as_float_array, as_points

__all__ = ["Dexterity", "dexterity", "alpha_admissible"]

_HALF_PI = 0.5 * math.pi


@dataclass(frozen=True)
class Dexterity:
    """Admissible end-effector orientations at one point (angles in rad, Eq 42 convention).

    Like :class:`iik.IKResult`, an unreachable point is an answer, not an error: ``case`` is
    ``"unreachable"`` and ``reason`` says why; :meth:`raise_if_unreachable` raises
    :class:`~iik.errors.UnreachablePoseError` on request.

    Attributes:
        point: The tool point [m], (3,).
        case: ``"outer"``, ``"ring"`` or ``"inner"`` (Figs 20-21), ``"none"`` when the
            service sphere lies inside the inner SLJ boundary (the model admits nothing, although
            the point may be reachable: ``iik verify`` measures how often), or ``"unreachable"``
            (farther than ``l3 + l4 + l5`` from joint 2, Eq 38: no orientation at all).
        beta_range: ``(beta_min, beta_max)``: polar angle of z6 from +z (None for ``"none"``).
        inclination_range: The same range in the thesis's Sec 3.5 convention
            (elevation of link 5 above the horizontal): ``beta - pi/2``.
        beta: The chosen beta, or None.
        alpha_intervals: For the chosen beta, admissible alpha intervals
            ``((lo, hi), ...)`` (1 or 2; angles are modulo 2 pi, ``lo <= hi``,
            ``hi - lo <= 2 pi``). Empty when ``beta`` is None.
        alpha_center: Azimuth of z6 in the nominal plane (Eq 46's alpha' + pi).
        alpha_halfwidth: ``(w_in, w_out)``: admissible alpha = center +- [w_in, w_out].
        gamma_range: ``(-pi, pi)``: any gamma (joint 6 spans a full turn, Sec 3.5.1).
        nominal_inclination: beta' of Eq 43 [rad].
        delta_out, delta_in: Cone half-angles of Eq 44 / Eq 45 [rad] (``pi`` /
            ``0`` when that boundary does not cut the service sphere).
        reason: Why nothing is admissible (cases ``"unreachable"`` and ``"none"``), else "".
    """

    point: np.ndarray
    case: str
    beta_range: tuple[float, float] | None
    inclination_range: tuple[float, float] | None
    beta: float | None
    alpha_intervals: tuple[tuple[float, float], ...]
    alpha_center: float
    alpha_halfwidth: tuple[float, float]
    gamma_range: tuple[float, float]
    nominal_inclination: float
    delta_out: float
    delta_in: float
    reason: str = ""

    @property
    def reachable(self) -> bool:
        """False if the point is outside the workspace (case ``"unreachable"``)."""
        return self.case != "unreachable"

    def raise_if_unreachable(self) -> Dexterity:
        """Return self, or raise :class:`~iik.errors.UnreachablePoseError` (with ``reason``) if
        the point is outside the workspace (the same request as
        :meth:`iik.IKResult.raise_if_unreachable`)."""
        if not self.reachable:
            raise UnreachablePoseError(self.reason)
        return self

    def admits(self, alpha: float, beta: float, tol: float = 0.0) -> bool:
        """Is ``(alpha, beta)`` admissible (any gamma)? ``tol`` widens every bound [rad]."""
        if self.beta_range is None or not (self.beta_range[0] - tol <= beta <= self.beta_range[1] + tol):
            return False
        w_in, w_out = _alpha_widths(beta - _HALF_PI, self.nominal_inclination, self.delta_in,
                                    self.delta_out)
        if w_out < 0:
            return False
        dev = abs((alpha - self.alpha_center + math.pi) % (2 * math.pi) - math.pi)
        return w_in - tol <= dev <= w_out + tol


def _clip1(x: float) -> float:
    return -1.0 if x < -1.0 else (1.0 if x > 1.0 else x)


def _alpha_widths(inc: float, inc0: float, d_in: float, d_out: float) -> tuple[float, float]:
    """Half-widths (w_in, w_out) of |alpha - alpha_c| at link-5 elevation ``inc``; w_out < 0 if none.

    Spherical law of cosines: cos(angle(a, e)) = cos(inc) cos(inc0) cos(dA) + sin(inc) sin(inc0).
    """
    cc = math.cos(inc) * math.cos(inc0)
    ss = math.sin(inc) * math.sin(inc0)
    if cc < 1e-12:  # a or e vertical: the angle does not depend on alpha
        ang = math.acos(_clip1(ss))
        return (0.0, math.pi) if d_in - 1e-12 <= ang <= d_out + 1e-12 else (0.0, -1.0)
    hi = (math.cos(d_in) - ss) / cc  # angle >= d_in  <=>  cos(dA) <= hi
    lo = (math.cos(d_out) - ss) / cc  # angle <= d_out <=>  cos(dA) >= lo
    if lo > 1.0 + 1e-12 or hi < -1.0 - 1e-12 or lo > hi + 1e-12:
        return 0.0, -1.0
    return math.acos(_clip1(hi)), math.acos(_clip1(lo))


def alpha_admissible(result: Dexterity, alpha, beta) -> np.ndarray:
    """Vectorised :meth:`Dexterity.admits` over arrays of ``alpha``, ``beta`` [rad] (Eq 42)."""
    a = as_float_array(alpha, "alpha")
    b = as_float_array(beta, "beta")
    a, b = np.broadcast_arrays(a, b)
    if result.beta_range is None:
        return np.zeros(a.shape, bool)
    inc = b - _HALF_PI
    inc0, d_in, d_out = result.nominal_inclination, result.delta_in, result.delta_out
    cc = np.cos(inc) * math.cos(inc0)
    ss = np.sin(inc) * math.sin(inc0)
    cosang = cc * np.cos(a - result.alpha_center) + ss
    ok = (cosang <= math.cos(d_in) + 1e-12) & (cosang >= math.cos(d_out) - 1e-12)
    return ok & (b >= result.beta_range[0] - 1e-12) & (b <= result.beta_range[1] + 1e-12)


def _point3(p) -> tuple[float, float, float]:
    """One point (3,) [m] as three finite floats (fast path for float64 arrays), else a typed error."""
    if isinstance(p, np.ndarray) and p.shape == (3,) and p.dtype == np.float64:
        x, y, z = p.tolist()
        if math.isfinite(x) and math.isfinite(y) and math.isfinite(z):
            return x, y, z
    pb, batched = as_points(p, "p")
    if batched:
        raise InvalidInputError("p", f"expected one point of shape (3,), got shape {pb.shape}")
    x, y, z = pb[0].tolist()
    return x, y, z


def dexterity(p, arm: Arm, beta: float | None = None) -> Dexterity:
    """Admissible beta range at ``p`` and, for a chosen ``beta``, the alpha range (Sec 3.5).

    Args:
        p: Tool point [m], shape (3,), base frame 0.
        beta: Optional polar angle [rad] of z6 (Eq 42 convention, see module doc).
        arm: Arm parameters.

    Returns:
        :class:`Dexterity`; for ``p`` outside the workspace (farther than ``l3 + l4 + l5``
        from joint 2, Eq 38) case ``"unreachable"`` with a ``reason`` (like an empty
        :class:`iik.IKResult`; ``.raise_if_unreachable()`` raises instead).

    Raises:
        InvalidInputError: NaN/inf or a wrong shape.
        DexterityError: ``beta`` outside the admissible range at a reachable point (names the range).
    """
    px, py, pz = _point3(p)
    if beta is not None:
        if isinstance(beta, float) and math.isfinite(beta):
            pass  # fast path
        else:
            b = as_float_array(beta, "beta")
            if b.shape != ():
                raise InvalidInputError("beta", f"expected a scalar, got shape {b.shape}")
            beta = float(b)
    l1, l2, l3, l4, l5 = arm.l1, arm.l2, arm.l3, arm.l4, arm.l5
    lim4 = float(arm.upper[3])
    phi = math.atan2(py, px)  # Eq 36
    th1 = min(max(phi, arm.lower[0]), arm.upper[0])  # joint 1 cannot point beyond its limits
    vx, vy, vz = px - l2 * math.cos(th1), py - l2 * math.sin(th1), pz - l1  # Eq 37
    rho = math.sqrt(vx * vx + vy * vy + vz * vz)  # Eq 44
    r_out = l3 + l4
    r_in = math.sqrt(l3 * l3 + l4 * l4 - 2 * l3 * l4 * math.cos(math.pi - lim4))  # Eq 45 d
    gamma_range = (float(arm.lower[5]), float(arm.upper[5]))
    if rho > r_out + l5 + 1e-12:
        reason = (f"unreachable: p = [{px:.4f}, {py:.4f}, {pz:.4f}] m is outside the workspace: "
                  f"{rho:.4f} m from joint 2, more than l3 + l4 + l5 = {r_out + l5:.4f} m (Eq 38)")
        return Dexterity(point=np.array((px, py, pz)), case="unreachable", beta_range=None,
                         inclination_range=None, beta=None, alpha_intervals=(), alpha_center=0.0,
                         alpha_halfwidth=(0.0, -1.0), gamma_range=gamma_range, nominal_inclination=0.0,
                         delta_out=0.0, delta_in=math.pi, reason=reason)
    if rho + l5 < r_in - 1e-12 or rho < 1e-12:  # service sphere inside the inner SLJ boundary
        if beta is not None:
            raise DexterityError(beta, None)
        return Dexterity(point=np.array((px, py, pz)), case="none", beta_range=None, inclination_range=None,
                         beta=None, alpha_intervals=(), alpha_center=0.0, alpha_halfwidth=(0.0, -1.0),
                         gamma_range=gamma_range, nominal_inclination=0.0, delta_out=0.0, delta_in=math.pi,
                         reason="the Sec 3.5 model admits no orientation here (service sphere inside the "
                                "inner boundary of the second-last joint)")
    inc0 = math.atan2(vz, math.hypot(vx, vy))  # Eq 43 (beta')
    c_out = (l5 * l5 + rho * rho - r_out * r_out) / (2 * l5 * rho)  # Eq 44
    c_in = (l5 * l5 + rho * rho - r_in * r_in) / (2 * l5 * rho)  # Eq 45
    d_out = math.acos(_clip1(c_out)) if c_out > -1.0 else math.pi
    d_in = math.acos(_clip1(c_in)) if c_in < 1.0 else 0.0
    outer_cut, inner_cut = c_out > -1.0, c_in < 1.0
    case = "ring" if (outer_cut and inner_cut) else ("outer" if outer_cut else "inner")
    lo = max(inc0 - d_out, -inc0 - (math.pi - d_in), -_HALF_PI)
    hi = min(inc0 + d_out, -inc0 + (math.pi - d_in), _HALF_PI)
    beta_range = (lo + _HALF_PI, hi + _HALF_PI)  # beta_42 = inclination + 90 deg
    alpha_c = math.atan2(vy, vx) + math.pi  # z6 = -a: azimuth + 180 deg (Eq 46)
    alpha_c = (alpha_c + math.pi) % (2 * math.pi) - math.pi
    intervals: tuple[tuple[float, float], ...] = ()
    widths = (0.0, math.pi)
    if beta is not None:
        if not (beta_range[0] - 1e-12 <= beta <= beta_range[1] + 1e-12):
            raise DexterityError(beta, beta_range)
        w_in, w_out = _alpha_widths(beta - _HALF_PI, inc0, d_in, d_out)
        w_out = max(w_out, w_in)  # at the range ends the interval shrinks to a point
        widths = (w_in, w_out)
        if w_out >= math.pi - 1e-12 and w_in <= 1e-12:
            intervals = ((alpha_c - math.pi, alpha_c + math.pi),)
        elif w_in <= 1e-12:
            intervals = ((alpha_c - w_out, alpha_c + w_out),)
        else:
            intervals = ((alpha_c - w_out, alpha_c - w_in), (alpha_c + w_in, alpha_c + w_out))
    return Dexterity(
        point=np.array((px, py, pz)), case=case, beta_range=beta_range, inclination_range=(lo, hi),
        beta=beta, alpha_intervals=intervals, alpha_center=alpha_c, alpha_halfwidth=widths,
        gamma_range=(float(arm.lower[5]), float(arm.upper[5])), nominal_inclination=inc0,
        delta_out=d_out, delta_in=d_in,
    )
