"""The frozen results of inverse-kinematics queries: one pose (:class:`IKResult`), a batch
as padded arrays (:class:`IKBatch`), and the description of a continuum (:class:`Continuum`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import UnreachablePoseError

__all__ = ["IKResult", "IKBatch", "Continuum"]


def _ro(a, dtype=float) -> np.ndarray:
    arr = np.array(a, dtype=dtype, copy=True)
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True)
class Continuum:
    """A row of an :class:`IKResult` that stands for a one-parameter family of solutions.

    Moving the free joint by an angle and joint 6 by ``sign`` times that angle leaves the
    pose unchanged, so ``theta_free - sign * theta6`` is fixed (:attr:`fixed`).

    Attributes:
        free_joint: The joint (1-based) that moves freely: 3 when joints 3 and 6 are
            collinear (theta4 = 0 and theta4 + theta5 = 0, mod pi), 1 when the tool point
            is on the joint-1 axis and z6 is vertical (joints 1 and 6 collinear).
        sign: +1 (``theta_free - theta6`` fixed) or -1 (``theta_free + theta6`` fixed).
        value: The fixed combination [rad], wrapped to (-pi, pi].
        interval: ``(lo, hi)`` [rad]: the values of the free joint for which the member of
            the family (joint 6 following, wrapped) is inside the joint limits (Table I),
            the piece containing the representative; ``(nan, nan)`` if there is none.
        representative: The row of the result (6,) [rad]; inside the limits whenever any
            member is.
    """

    free_joint: int
    sign: int
    value: float
    interval: tuple[float, float]
    representative: np.ndarray

    @property
    def fixed(self) -> str:
        """The fixed combination as text, e.g. ``"theta3 - theta6"``."""
        return f"theta{self.free_joint} {'-' if self.sign > 0 else '+'} theta6"

    def member(self, theta: float) -> np.ndarray:
        """The member of the family with the free joint at ``theta`` [rad] (joint 6 wrapped)."""
        q = np.array(self.representative, dtype=float)
        j = self.free_joint - 1
        q[5] = math.pi - (math.pi - (q[5] + self.sign * (theta - q[j]))) % (2 * math.pi)
        q[j] = theta
        return q


@dataclass(frozen=True)
class IKResult:
    """All inverse-kinematics solutions of one pose.

    Attributes:
        q: Joint angles (k, 6) [rad], each wrapped to (-pi, pi]; k may be 0.
            Deterministic order (lexicographic in theta1, theta2, ... rounded to 1e-9 rad).
        position_residual: (k,) |p_fk(q) - p| [m], against the pose as given.
        rotation_residual: (k,) rotation angle between R_fk(q) and R as given [rad]
            (:func:`iik.rotations.rotation_angle`; includes ``rotation_projection``).
        within_limits: (k,) bool, inside the arm's joint limits (Table I,
            :meth:`iik.arm.Arm.within_limits`).
        free_joints: Per solution, the joints (1-based) of a continuum of solutions:
            ``(3, 6)`` when joints 3 and 6 are collinear (theta4 = theta5 = 0: only
            theta3 - theta6 is fixed), ``(1, 6)`` when joints 1 and 6 are; the row is then
            one representative, described by ``continua``. ``(3, 6)`` without a ``continua``
            entry marks a numerical continuum: near joints 3 and 6 being collinear
            (|sin theta4|, |sin(theta4 + theta5)| <= 1e-4) the configurations within the
            tolerance form a thin family in which theta3 is only loosely fixed, and the row is
            one of them. Empty tuple for isolated solutions.
        reason: Why there is no solution, or why the solutions are approximate; else "".
        method: ``"complete"``, ``"reference"`` or ``"thesis"``.
        info: Free-form extras (not compared).
        approximate: (k,) bool: True where the row does not reach the pose within the
            tolerances but within ``IKOptions.approximate_tol`` (only returned when no row
            reaches it: then every row is approximate, least residual first in ``reason``).
        continua: Per solution, a tuple of :class:`Continuum` (one per free joint, empty for
            isolated solutions).
        rotation_projection: Frobenius distance from the given rotation block to the
            rotation that was solved (its nearest rotation); 0 for an orthonormal input.
    """

    q: np.ndarray
    position_residual: np.ndarray
    rotation_residual: np.ndarray
    within_limits: np.ndarray
    free_joints: tuple[tuple[int, ...], ...] = ()
    reason: str = ""
    method: str = "complete"
    info: dict = field(default_factory=dict, compare=False, repr=False)
    approximate: np.ndarray | None = None
    continua: tuple[tuple[Continuum, ...], ...] = ()
    rotation_projection: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "q", _ro(np.reshape(self.q, (-1, 6))))
        k = len(self.q)
        object.__setattr__(self, "position_residual", _ro(self.position_residual))
        object.__setattr__(self, "rotation_residual", _ro(self.rotation_residual))
        object.__setattr__(self, "within_limits", _ro(self.within_limits, bool))
        approx = np.zeros(k, bool) if self.approximate is None else self.approximate
        object.__setattr__(self, "approximate", _ro(approx, bool))
        fj = tuple(tuple(int(j) for j in f) for f in self.free_joints) or ((),) * k
        object.__setattr__(self, "free_joints", fj)
        object.__setattr__(self, "continua", tuple(tuple(c) for c in self.continua) or ((),) * k)
        object.__setattr__(self, "rotation_projection", float(self.rotation_projection))

    @classmethod
    def trusted(cls, q, position_residual, rotation_residual, within_limits, free_joints, reason,
                method, approximate, continua, rotation_projection) -> IKResult:
        """Build without copying or checking, for the solvers: read-only arrays ((k, 6), (k,),
        (k,), (k,) bool, (k,) bool) and per-row ``free_joints`` / ``continua`` tuples."""
        self = object.__new__(cls)
        self.__dict__.update(q=q, position_residual=position_residual,
                             rotation_residual=rotation_residual, within_limits=within_limits,
                             free_joints=free_joints, reason=reason, method=method, info={},
                             approximate=approximate, continua=continua,
                             rotation_projection=rotation_projection)
        return self

    def __len__(self) -> int:
        return len(self.q)

    @property
    def count(self) -> int:
        """Number of solutions k."""
        return len(self.q)

    @property
    def has_continuum(self) -> bool:
        """True if any returned row represents a continuum of solutions."""
        return any(self.free_joints)

    @property
    def is_approximate(self) -> bool:
        """True if the rows only approach the pose (see ``approximate``)."""
        return bool(self.count and self.approximate.all())

    def raise_if_unreachable(self) -> IKResult:
        """Return self, or raise :class:`~iik.errors.UnreachablePoseError` (with ``reason``)
        if there is no solution (within the limits, if they were asked for).

        The IK itself never raises for an unreachable pose (nor does :func:`iik.dexterity`);
        this is the request to.
        """
        if self.count == 0:
            raise UnreachablePoseError(self.reason or "no solution")
        return self

    def to_dict(self, degrees: bool = False) -> dict:
        """JSON-ready dict; angles in rad (or degrees if ``degrees``), residuals in m / rad."""
        conv = math.degrees if degrees else float

        def cont(c: Continuum) -> dict:
            return {"free_joint": c.free_joint, "fixed": c.fixed, "value": conv(c.value),
                    "interval": [conv(v) for v in c.interval]}

        return {
            "method": self.method,
            "count": self.count,
            "reason": self.reason,
            "angle_unit": "deg" if degrees else "rad",
            "rotation_projection": self.rotation_projection,
            "solutions": [
                {
                    "q": [conv(v) for v in self.q[i].tolist()],
                    "position_residual_m": float(self.position_residual[i]),
                    "rotation_residual_rad": float(self.rotation_residual[i]),
                    "within_limits": bool(self.within_limits[i]),
                    "approximate": bool(self.approximate[i]),
                    "free_joints": list(self.free_joints[i]),
                    "continua": [cont(c) for c in self.continua[i]],
                }
                for i in range(self.count)
            ],
        }


@dataclass(frozen=True)
class IKBatch:
    """All solutions of n poses as padded arrays (read-only): the array form of
    :func:`iik.solve_many`, for code that wants no Python object per pose.

    Row ``i`` of pose ``n`` is valid for ``i < count[n]``; the rest is padding (NaN / False / 0).

    Attributes:
        q: (n, 16, 6) [rad].
        count: (n,) rows returned per pose.
        position_residual, rotation_residual: (n, 16) against the poses as given [m], [rad].
        within_limits, approximate: (n, 16) bool, as in :class:`IKResult`.
        free: (n, 16) int bit set: 1 theta1/theta6 continuum, 2 theta3/theta6 continuum.
        continuum: (n, 16, 6) sign, interval low, interval high for the theta1 continuum, then
            for the theta3 continuum [-, rad, rad] (NaN where there is none).
        total: (n,) solutions that reach the pose exactly, before the joint-limit filter.
        rotation_projection: (n,) as in :class:`IKResult`.
        closest: (n, 2) least position [m] and rotation [rad] residuals of the candidates
            examined (inf if none): how far an unreachable pose is from the nearest one found.
        method: The method used.
    """

    q: np.ndarray
    count: np.ndarray
    position_residual: np.ndarray
    rotation_residual: np.ndarray
    within_limits: np.ndarray
    approximate: np.ndarray
    free: np.ndarray
    continuum: np.ndarray
    total: np.ndarray
    rotation_projection: np.ndarray
    closest: np.ndarray
    method: str = "complete"

    def __len__(self) -> int:
        return len(self.count)
