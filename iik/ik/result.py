"""The frozen result of an inverse-kinematics query."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["IKResult"]


def _ro(a, dtype=float) -> np.ndarray:
    arr = np.array(a, dtype=dtype, copy=True)
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True)
class IKResult:
    """All inverse-kinematics solutions of one pose.

    Attributes:
        q: Joint angles (k, 6) [rad], each wrapped to (-pi, pi]; k may be 0.
            Deterministic order (lexicographic in theta1, theta2, ...).
        position_residual: (k,) |p_fk(q) - p| [m].
        rotation_residual: (k,) rotation angle between R_fk(q) and R [rad].
        within_limits: (k,) bool, inside the arm's joint limits (Table I).
        free_joints: Per solution, the joints (1-based) of a continuum of
            solutions, e.g. ``(3, 6)`` when joints 3 and 6 are collinear
            (theta4 = theta5 = 0) and only their sum is fixed: the row is then
            one representative. Empty tuple for isolated solutions.
        reason: Why there is no solution (set when k == 0), else "".
        method: ``"complete"`` or ``"thesis"``.
    """

    q: np.ndarray
    position_residual: np.ndarray
    rotation_residual: np.ndarray
    within_limits: np.ndarray
    free_joints: tuple[tuple[int, ...], ...] = ()
    reason: str = ""
    method: str = "complete"
    info: dict = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "q", _ro(np.reshape(self.q, (-1, 6))))
        object.__setattr__(self, "position_residual", _ro(self.position_residual))
        object.__setattr__(self, "rotation_residual", _ro(self.rotation_residual))
        object.__setattr__(self, "within_limits", _ro(self.within_limits, bool))
        fj = tuple(tuple(int(j) for j in f) for f in self.free_joints) or ((),) * len(self.q)
        object.__setattr__(self, "free_joints", fj)

    @classmethod
    def _trusted(cls, q, position_residual, rotation_residual, within_limits, free_joints,
                 reason, method, info) -> IKResult:
        """Build without copying: the caller passes read-only float/bool arrays it owns
        ((k, 6), (k,), (k,), (k,)) and a normalised ``free_joints`` tuple (one per row)."""
        self = object.__new__(cls)
        self.__dict__.update(q=q, position_residual=position_residual,
                             rotation_residual=rotation_residual, within_limits=within_limits,
                             free_joints=free_joints, reason=reason, method=method, info=info)
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

    def to_dict(self, degrees: bool = False) -> dict:
        """JSON-ready dict; angles in rad (or degrees if ``degrees``), residuals in m / rad."""
        conv = np.degrees if degrees else (lambda x: x)
        return {
            "method": self.method,
            "count": self.count,
            "reason": self.reason,
            "angle_unit": "deg" if degrees else "rad",
            "solutions": [
                {
                    "q": [float(v) for v in conv(self.q[i])],
                    "position_residual_m": float(self.position_residual[i]),
                    "rotation_residual_rad": float(self.rotation_residual[i]),
                    "within_limits": bool(self.within_limits[i]),
                    "free_joints": list(self.free_joints[i]),
                }
                for i in range(self.count)
            ],
        }
