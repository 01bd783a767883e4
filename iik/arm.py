"""The thesis arm as data: link lengths, Table I limits and Table II rows.

This module is the single source of truth for the arm's parameters. Nothing
else in the project copies these numbers; everything reads :data:`THESIS_ARM`
(or another :class:`Arm` built the same way).

Units: metres, radians, seconds.

Sources:
    * l2..l5 are recovered from Appendix E (point A1, the diagonal of H*),
      see ``docs/ARM.md``.
    * **l1 = 0.300 m is an assumption.** It is a pure z offset that cancels from
      every derivative in Appendix E, so nothing in the text fixes it.
    * Joint limits: Table I.
    * DH rows: Table II (Craig's modified convention; offsets -90, -90, +90 deg
      on joints 2, 4, 5 make the home pose q = 0; d6 = -l5).
    * Speeds: Section 3.2 gives 8.2 rad/s (square modules) and 1.2 rad/s
      (cylindrical modules) without saying which joint is which. The default,
      :data:`CONSERVATIVE_VELOCITY`, assumes the slower kind on every joint.
    * Accelerations are not given in the thesis; :data:`ASSUMED_ACCELERATION`
      is an assumption, kept as configuration.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .dh import DHRow, DHTable
from .errors import InvalidInputError

__all__ = [
    "Arm",
    "THESIS_ARM",
    "SQUARE_MODULE_SPEED",
    "CYLINDRICAL_MODULE_SPEED",
    "CONSERVATIVE_VELOCITY",
    "ASSUMED_ACCELERATION",
    "SQUARE_MODULE_TORQUE",
    "CYLINDRICAL_MODULE_TORQUE",
    "CONSERVATIVE_EFFORT",
    "LIMIT_TOL",
]

_DEG = np.pi / 180.0

#: Section 3.2: maximum speed of the square PowerCube modules [rad/s].
SQUARE_MODULE_SPEED = 8.2
#: Section 3.2: maximum speed of the cylindrical PowerCube modules [rad/s].
CYLINDRICAL_MODULE_SPEED = 1.2
#: Default per-joint speed limits [rad/s]: the slower module kind everywhere,
#: because the thesis does not say which joint is which kind.
CONSERVATIVE_VELOCITY = (CYLINDRICAL_MODULE_SPEED,) * 6
#: Assumed per-joint acceleration limits [rad/s^2] (not given in the thesis).
ASSUMED_ACCELERATION = (2.0,) * 6
#: Section 3.2: torque of the square PowerCube modules [N m].
SQUARE_MODULE_TORQUE = 372.0
#: Section 3.2: torque of the cylindrical PowerCube modules [N m].
CYLINDRICAL_MODULE_TORQUE = 239.0
#: Default per-joint effort limits [N m]: the weaker module kind everywhere,
#: matching :data:`CONSERVATIVE_VELOCITY` (the text does not say which joint is which).
CONSERVATIVE_EFFORT = (CYLINDRICAL_MODULE_TORQUE,) * 6

#: Numerical tolerance of every joint-limit test [rad]: a solution on a joint stop of a
#: near-singular pose may come out this far outside it (the pose fixes q only to
#: ~eps / sigma_min there). A margin *inside* the limits is a negative tolerance.
LIMIT_TOL = 1e-7

#: Table I, in degrees (display units; converted to rad below).
_TABLE_I_DEG = ((-160.0, 160.0), (-120.0, 95.0), (-160.0, 160.0),
                (-119.0, 119.0), (-119.0, 119.0), (-180.0, 180.0))


@dataclass(frozen=True)
class Arm:
    """A six-joint arm with the thesis's structure (Table II) and given lengths.

    Attributes:
        l1..l5: Link lengths [m] (Table II symbols).
        lower, upper: Joint limits [rad] (Table I for the thesis arm).
        velocity: Joint speed limits [rad/s].
        acceleration: Joint acceleration limits [rad/s^2].
        name: Display name.
        assumptions: Human-readable notes on which numbers are assumed.
        effort: Joint torque limits [N m] (Sec 3.2; written into the URDF).
    """

    l1: float
    l2: float
    l3: float
    l4: float
    l5: float
    lower: tuple[float, ...]
    upper: tuple[float, ...]
    velocity: tuple[float, ...] = CONSERVATIVE_VELOCITY
    acceleration: tuple[float, ...] = ASSUMED_ACCELERATION
    name: str = "arm"
    assumptions: tuple[str, ...] = field(default=())
    effort: tuple[float, ...] = CONSERVATIVE_EFFORT

    def __post_init__(self) -> None:
        for k in ("l1", "l2", "l3", "l4", "l5"):
            v = getattr(self, k)
            if not np.isfinite(v):
                raise InvalidInputError(k, "must be finite")
        for k in ("l3", "l4", "l5"):
            if getattr(self, k) <= 0:
                raise InvalidInputError(k, "must be positive")
        for k in ("acceleration", "effort"):
            vals = getattr(self, k)
            if len(vals) != 6 or any(not np.isfinite(v) or v <= 0 for v in vals):
                raise InvalidInputError(k, "needs six positive finite values")
        # Validates lower/upper/velocity lengths, order and finiteness.
        self.dh_table()

    @property
    def lengths(self) -> np.ndarray:
        """``[l1, l2, l3, l4, l5]`` [m]."""
        return np.array([self.l1, self.l2, self.l3, self.l4, self.l5])

    @property
    def q_min(self) -> np.ndarray:
        """Lower joint limits [rad], shape (6,)."""
        return np.array(self.lower)

    @property
    def q_max(self) -> np.ndarray:
        """Upper joint limits [rad], shape (6,)."""
        return np.array(self.upper)

    def dh_table(self) -> DHTable:
        """Table II as a modified-DH :class:`~iik.dh.DHTable`."""
        h = np.pi / 2
        rows = (
            DHRow(alpha=0.0, a=0.0, d=self.l1, offset=0.0),  # Table II row 1
            DHRow(alpha=-h, a=self.l2, d=0.0, offset=-h),  # row 2: theta2 - 90 deg
            DHRow(alpha=-h, a=0.0, d=self.l3, offset=0.0),  # row 3
            DHRow(alpha=-h, a=0.0, d=0.0, offset=-h),  # row 4: theta4 - 90 deg
            DHRow(alpha=0.0, a=self.l4, d=0.0, offset=+h),  # row 5: theta5 + 90 deg
            DHRow(alpha=-h, a=0.0, d=-self.l5, offset=0.0),  # row 6: d6 = -l5
        )
        return DHTable(rows=rows, convention="modified", lower=tuple(self.lower),
                       upper=tuple(self.upper), velocity=tuple(self.velocity))

    def within_limits(self, q, tol: float = LIMIT_TOL) -> np.ndarray:
        """Boolean (n,) or scalar: is each ``q`` [rad] inside the limits (Table I)?

        The one joint-limit test of the project. ``tol`` [rad] widens the limits
        (default :data:`LIMIT_TOL`, rounding at a stop); a negative ``tol`` is a
        margin inside them (the planner's and the executor's margins).
        """
        from .validation import as_joints

        qb, batched = as_joints(q, "q")
        ok = np.all((qb >= self.q_min - tol) & (qb <= self.q_max + tol), axis=1)
        return ok if batched else bool(ok[0])


THESIS_ARM = Arm(
    l1=0.300,  # ASSUMED: not fixed by the text (cancels in App. E); see ARM.md
    l2=0.122,  # App. E, A1: H*(1,1) = 1646.8
    l3=0.339,  # App. E, A1: H*(2,2) = 2705.2
    l4=0.175,  # App. E, A1: H*(4,4) = 1898
    l5=0.265,  # App. E, A1: H*(5,5) = 1143.1
    lower=tuple(lo * _DEG for lo, _ in _TABLE_I_DEG),  # Table I
    upper=tuple(hi * _DEG for _, hi in _TABLE_I_DEG),  # Table I
    name="thesis PowerCube arm (Mondragon Sanchez 2012)",
    assumptions=(
        "l1 = 0.300 m is assumed (a z offset the text never fixes).",
        "Joint speed limits default to 1.2 rad/s on every joint (the slower module "
        "kind of Sec 3.2); the text does not say which joint is which kind.",
        "Acceleration limits of 2.0 rad/s^2 are assumed (not in the thesis).",
        "Joint torque limits default to 239 N m on every joint (the weaker module "
        "kind of Sec 3.2), for the same reason as the speeds.",
    ),
)
