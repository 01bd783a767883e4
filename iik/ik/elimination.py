"""The eliminant of the arm class: two equations in (theta1, theta2), and theta2 eliminated.

The class (derivation: ``docs/IK_CLASS.md``; the thesis arm of Table II is one member) has
joint axes ``1 . 2 ∩ 3 ∩ 4 ∥ 5 ∩ 6`` with axes 3/4 and 5/6 perpendicular and the two
intersection points C = 3∩4 and D = 5∩6 level along the parallel axes (D - C is perpendicular
to them). In the solver chain (canonical modified DH: axis 1 is z0 through the origin; D is
the origin of frame 6) the pose gives the wrist point D and the axis z6. For a fixed theta1
two conditions on theta2 remain, both linear in (c2, s2) = (cos, sin) of theta2 + offset:

* **coplanarity** (the general Eq 8): z4 is perpendicular to z3, z6 and D - C, so
  ``det[z3, z6, D - B] = R + P c2 + Q s2 = 0`` (B = 2∩3, C = B + d3 z3);
* **length** (the general Eq 11): ``|D - C| = a4``, i.e.
  ``|D - B|^2 - 2 d3 z3.(D - B) + d3^2 - a4^2 = a + b c2 + c s2 = 0``.

Every coefficient ``a, b, c, P, Q, R`` is a first-degree trigonometric polynomial
``x0 + xc cos(theta1) + xs sin(theta1)`` (:func:`pose_terms`). Eliminating (c2, s2) with
c2^2 + s2^2 = 1 (Cramer) gives the eliminant of degree 4 in theta1::

    F = (Q a - R c)^2 + (R b - P a)^2 - (P c - Q b)^2,

which is the thesis's ``a^2 (P^2 + Q^2) - (b Q - c P)^2`` when R = 0 (Sec 3.3, corrected).

Frames and units: the solver chain's base frame 0, metres.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

__all__ = ["ArmConstants", "arm_constants", "pose_terms", "bracket", "first_degree_at"]

_njit = numba.njit(error_model="numpy")


@dataclass(frozen=True)
class ArmConstants:
    """The arm's part of the eliminant (solver chain, frame 1 rotating with theta1) [m, 1].

    Attributes:
        B: Point 2∩3 (origin of frame 2) in frame 1 (3,) [m].
        u0, uc, us: z3 = u0 + uc c2 + us s2 in frame 1 (unit-vector parts) (3,) each.
        Bx_u0, Bx_uc, Bx_us: B x u0, B x uc, B x us (3,) each [m].
        uB: (u0.B, uc.B, us.B) [m]; BB: |B|^2 [m^2]; d3: |C - B| signed [m]; a4: |D - C| [m].
        K0: |B|^2 + d3^2 - a4^2 + 2 d3 u0.B [m^2] (the theta1-free part of a).
    """

    B: tuple[float, float, float]
    u0: tuple[float, float, float]
    uc: tuple[float, float, float]
    us: tuple[float, float, float]
    Bx_u0: tuple[float, float, float]
    Bx_uc: tuple[float, float, float]
    Bx_us: tuple[float, float, float]
    uB: tuple[float, float, float]
    BB: float
    d3: float
    a4: float
    K0: float

    @property
    def vector(self) -> np.ndarray:
        """The 28 numbers in the kernel's order (:data:`iik.ik.layout.N_CONST`)."""
        return np.array(
            [
                *self.B,
                *self.u0,
                *self.uc,
                *self.us,
                *self.Bx_u0,
                *self.Bx_uc,
                *self.Bx_us,
                *self.uB,
                self.BB,
                self.d3,
                self.a4,
                self.K0,
            ],
            dtype=float,
        )


def arm_constants(
    ca1: float, sa1: float, a1: float, d2: float, ca2: float, sa2: float, d3: float, a4: float
) -> ArmConstants:
    """:class:`ArmConstants` from the solver chain's rows 2, 3 and 5 (cos/sin of the twists
    alpha1, alpha2, the length a1 and offset d2 of row 2, d3 of row 3, a4 of row 5).

    z3 in frame 1 is ``RotX(alpha1) RotZ(theta2) RotX(alpha2) z``, i.e.
    ``(sa2 s2, -ca1 sa2 c2 - sa1 ca2, -sa1 sa2 c2 + ca1 ca2)``.
    """
    B = np.array([a1, -sa1 * d2, ca1 * d2])  # RotX(alpha1) TransX(a1) TransZ(d2) origin
    u0 = np.array([0.0, -sa1 * ca2, ca1 * ca2])
    uc = np.array([0.0, -ca1 * sa2, -sa1 * sa2])
    us = np.array([sa2, 0.0, 0.0])
    t = lambda v: tuple(float(x) for x in v)  # noqa: E731
    return ArmConstants(
        B=t(B),
        u0=t(u0),
        uc=t(uc),
        us=t(us),
        Bx_u0=t(np.cross(B, u0)),
        Bx_uc=t(np.cross(B, uc)),
        Bx_us=t(np.cross(B, us)),
        uB=(float(u0 @ B), float(uc @ B), float(us @ B)),
        BB=float(B @ B),
        d3=float(d3),
        a4=float(a4),
        K0=float(B @ B + d3 * d3 - a4 * a4 + 2.0 * d3 * (u0 @ B)),
    )


@_njit
def bracket(vx, vy, vz, ex, ey, ez, s):
    """``v . RotZ(theta1) e`` as ``(x0, xc, xs)`` of ``x0 + xc cos(theta1) + xs sin(theta1)``
    (v a vector of the pose in frame 0, e a vector of the arm in frame 1). ``s = -1``; with
    ``s = +1`` and absolute inputs, the sums of the absolute terms (a rounding-error scale)."""
    return vz * ez, vx * ex + vy * ey, vy * ex + s * vx * ey


@_njit
def pose_terms(zx, zy, zz, Dx, Dy, Dz, k, o, s):
    """The six first-degree trigonometric polynomials ``a, b, c, P, Q, R`` of one pose, as 18
    numbers ``(x0, xc, xs)`` each, from the tool axis z6 and the wrist point D (solver frame
    0) and the arm constants ``k[o:o + 28]`` (:attr:`ArmConstants.vector`).

    ``s = -1`` gives the values. With ``s = +1``, absolute inputs and absolute constants every
    subtraction becomes an addition: the sums of the absolute terms, which bound the rounding
    error of the values (:mod:`iik.ik.kernel`).
    """
    mx, my, mz = zy * Dz + s * zz * Dy, zz * Dx + s * zx * Dz, zx * Dy + s * zy * Dx  # m = z6 x D
    B0, B1, B2 = k[o], k[o + 1], k[o + 2]
    d3, K0 = k[o + 25], k[o + 27]
    # a = |D|^2 + K0 - 2 <D, B + d3 u0>                              (the general Eq 11, constant part)
    g0, gc, gs = bracket(Dx, Dy, Dz, B0 + d3 * k[o + 3], B1 + d3 * k[o + 4], B2 + d3 * k[o + 5], s)
    a0, ac, as_ = Dx * Dx + Dy * Dy + Dz * Dz + K0 + 2.0 * s * g0, 2.0 * s * gc, 2.0 * s * gs
    # b = -2 d3 (<D, uc> - uc.B),  c = -2 d3 (<D, us> - us.B)          (the general Eq 11, c2 and s2)
    h0, hc, hs = bracket(Dx, Dy, Dz, k[o + 6], k[o + 7], k[o + 8], s)
    b0, bc, bs = 2.0 * d3 * (k[o + 22] + s * h0), 2.0 * s * d3 * hc, 2.0 * s * d3 * hs
    h0, hc, hs = bracket(Dx, Dy, Dz, k[o + 9], k[o + 10], k[o + 11], s)
    c0, cc, cs = 2.0 * d3 * (k[o + 23] + s * h0), 2.0 * s * d3 * hc, 2.0 * s * d3 * hs
    # P, Q, R = <m, u> - <z6, B x u> for u = uc, us, u0                (the general Eq 8)
    m0, mc, ms = bracket(mx, my, mz, k[o + 6], k[o + 7], k[o + 8], s)
    n0, nc, ns = bracket(zx, zy, zz, k[o + 15], k[o + 16], k[o + 17], s)
    P0, Pc, Ps = m0 + s * n0, mc + s * nc, ms + s * ns
    m0, mc, ms = bracket(mx, my, mz, k[o + 9], k[o + 10], k[o + 11], s)
    n0, nc, ns = bracket(zx, zy, zz, k[o + 18], k[o + 19], k[o + 20], s)
    Q0, Qc, Qs = m0 + s * n0, mc + s * nc, ms + s * ns
    m0, mc, ms = bracket(mx, my, mz, k[o + 3], k[o + 4], k[o + 5], s)
    n0, nc, ns = bracket(zx, zy, zz, k[o + 12], k[o + 13], k[o + 14], s)
    R0, Rc, Rs = m0 + s * n0, mc + s * nc, ms + s * ns
    return (a0, ac, as_, b0, bc, bs, c0, cc, cs, P0, Pc, Ps, Q0, Qc, Qs, R0, Rc, Rs)


@_njit
def first_degree_at(x0, xc, xs, C, S):
    """``x0 + xc C + xs S`` (C, S: cos and sin of theta1)."""
    return x0 + xc * C + xs * S
