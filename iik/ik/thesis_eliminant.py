"""The thesis's own form of the eliminant (Sec 3.3): Eq 8 and Eq 11 as first-degree
trigonometric polynomials in theta1, for an arm of the thesis's Table II form.

This is what the thesis's IIK (:mod:`iik.ik.thesis`) scans, in the thesis's symbols (a, b, c,
P, Q; theta2 as in Table I). The complete solver uses the general eliminant of the arm class
(:mod:`iik.ik.elimination`, ``docs/IK_CLASS.md``), which for the thesis arm is the same pair of
equations in the DH angle theta2 - 90 deg (tested).

The thesis (Sec 3.3) reduces the problem to two equations in (theta1, theta2):
the coplanarity condition Eq 8 and the length error Eq 11 (corrected forms, see
``iik verify``)::

    Eq 8:   P(theta1) c2 + Q(theta1) s2 = 0
    Eq 11:  E = a(theta1) + b(theta1) c2 + c s2 = 0

where ``a, b, P, Q`` are ``x0 + xc cos(theta1) + xs sin(theta1)`` and ``c`` is a
constant. Eliminating theta2 gives ``F(theta1) = a^2 (P^2 + Q^2) - (b Q - c P)^2``.
:func:`eq8_eq11_terms` is the one place the coefficients are written: it works on
floats and on arrays, and the compiled kernel (:mod:`iik.ik.kernel`) compiles it.

Frames and units: base frame 0 (Table II), metres; the wrist point ``D`` is in the
frame of Sec 3.3.1 (origin moved up by ``l1``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..arm import Arm

__all__ = ["EliminantCoefficients", "eliminant_coefficients", "eq8_eq11_terms"]


def eq8_eq11_terms(r13, r23, r33, px, py, pz, l1, l2, l3, l4, l5):
    """The 16 numbers of the eliminant for a pose (tool axis z6 = (r13, r23, r33), point p [m]).

    Returns ``(a0, ac, as_, b0, bc, bs, P0, Pc, Ps, Q0, Qc, Qs, c, xD, yD, zD)`` [m, m^2].
    """
    xD = px + l5 * r13  # Eq 9a (corrected sign: D = p + l5 z6, Table II has d6 = -l5)
    yD = py + l5 * r23  # Eq 9b (corrected sign)
    zD = pz + l5 * r33 - l1  # Eq 9c (corrected sign; Sec 3.3.1 moves the origin up by l1)
    K = xD * xD + yD * yD + zD * zD + l2 * l2 + l3 * l3 - l4 * l4
    # Eq 11: E = a + b c2 + c s2
    a0, ac, as_ = K, -2.0 * l2 * xD, -2.0 * l2 * yD
    b0, bc, bs = 2.0 * l3 * l2, -2.0 * l3 * xD, -2.0 * l3 * yD
    c = 2.0 * l3 * zD
    # Eq 8: P c2 + Q s2 = 0, P = (r23 zD - r33 yD) c1 + (r33 xD - r13 zD) s1,
    #       Q = (r23 xD - r13 yD) + r13 l2 s1 - r23 l2 c1
    P0, Pc, Ps = 0.0, r23 * zD - r33 * yD, r33 * xD - r13 * zD
    Q0, Qc, Qs = r23 * xD - r13 * yD, -r23 * l2, r13 * l2
    return a0, ac, as_, b0, bc, bs, P0, Pc, Ps, Q0, Qc, Qs, c, xD, yD, zD


@dataclass(frozen=True)
class EliminantCoefficients:
    """Coefficients of the eliminant for n poses (read-only arrays).

    Attributes:
        abPQ: (n, 4, 3) ``a, b, P, Q`` as ``[const, cos, sin]`` coefficients in theta1
            [m^2, m^2, m, m]; :attr:`a`, :attr:`b`, :attr:`P`, :attr:`Q` are views of it.
        c: (n,) the constant of Eq 11 [m^2].
        D: (n, 3) wrist point in the frame of Sec 3.3.1 [m].
    """

    abPQ: np.ndarray
    c: np.ndarray
    D: np.ndarray

    a = property(lambda self: self.abPQ[:, 0], doc="(n, 3) coefficients of a [m^2] (a view of abPQ).")
    b = property(lambda self: self.abPQ[:, 1], doc="(n, 3) coefficients of b [m^2] (a view of abPQ).")
    P = property(lambda self: self.abPQ[:, 2], doc="(n, 3) coefficients of P [m] (a view of abPQ).")
    Q = property(lambda self: self.abPQ[:, 3], doc="(n, 3) coefficients of Q [m] (a view of abPQ).")


def eliminant_coefficients(R: np.ndarray, p: np.ndarray, arm: Arm) -> EliminantCoefficients:
    """:func:`eq8_eq11_terms` for rotations R (n, 3, 3) and positions p (n, 3) [m] (validated)."""
    t = arm.thesis_lengths
    v = eq8_eq11_terms(
        R[:, 0, 2], R[:, 1, 2], R[:, 2, 2], p[:, 0], p[:, 1], p[:, 2], t.l1, t.l2, t.l3, t.l4, t.l5
    )
    n = len(p)
    abPQ = np.empty((n, 4, 3))
    for k in range(12):
        abPQ[:, k // 3, k % 3] = v[k]
    c = np.array(np.broadcast_to(v[12], (n,)), dtype=float)
    D = np.stack(v[13:16], axis=1)
    for x in (abPQ, c, D):
        x.setflags(write=False)
    return EliminantCoefficients(abPQ, c, D)
