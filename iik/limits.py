"""The joint-limit test: which joint values lie beyond an arm's limits less a margin.

The project's one limit test (Table I for the thesis arm): :meth:`iik.Arm.limit_violations` returns
:class:`LimitViolations`, and :meth:`iik.Arm.within_limits` answers from the same :func:`excess`. The
executor's validation, the simulated modules' start, the timing's samples and the viewer ask them.

A margin keeps values that far *inside* the limits; a negative margin is a tolerance outside them.
Units: rad.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

__all__ = ["LimitViolation", "LimitViolations", "excess"]


def excess(q: np.ndarray, lower: np.ndarray, upper: np.ndarray, margin: float = 0.0) -> np.ndarray:
    """How far each value of ``q`` (..., k) lies beyond its limits ``lower``, ``upper`` (k,) less
    ``margin`` [rad]: ``max(lower + margin - q, q - (upper - margin))``, positive beyond, else <= 0."""
    return np.maximum((lower + margin) - q, q - (upper - margin))


@dataclass(frozen=True)
class LimitViolation:
    """One joint value beyond its limits less a margin.

    Attributes:
        sample: The configuration's row in the batch (0 for one configuration).
        joint: The joint, counted from 0 (joint ``q{joint + 1}``).
        value: Its value [rad].
        lower, upper: The joint's limits [rad].
        margin: The margin kept inside them [rad] (negative: a tolerance outside them).
        amount: How far beyond its limit less the margin the value lies [rad], > 0.
    """

    sample: int
    joint: int
    value: float
    lower: float
    upper: float
    margin: float
    amount: float

    @property
    def side(self) -> str:
        """``"lower"`` or ``"upper"``: the limit the value passes."""
        return "lower" if self.value - self.lower < self.upper - self.value else "upper"

    @property
    def limit(self) -> float:
        """The limit the value passes [rad]."""
        return self.lower if self.side == "lower" else self.upper


@dataclass(frozen=True, eq=False)
class LimitViolations:
    """The limit test of one configuration or a batch (:meth:`iik.Arm.limit_violations`).

    A sequence of :class:`LimitViolation`, by sample and then joint; true if there is any.

    Attributes:
        q: The values tested (n, k) [rad].
        excess: How far each lies beyond its limits less the margin (n, k) [rad] (:func:`excess`).
        joints: The joint (from 0) of each column.
        lower, upper: The limits of each column (k,) [rad].
        margin: The margin kept inside them [rad].
        batched: The input was a batch (n, k), not one configuration (k,).
    """

    q: np.ndarray
    excess: np.ndarray
    joints: tuple[int, ...]
    lower: np.ndarray
    upper: np.ndarray
    margin: float
    batched: bool

    @property
    def within(self):
        """Is each configuration within the limits less the margin? (n,) bools, or a bool for one."""
        ok = np.all(self.excess <= 0.0, axis=1)
        return ok if self.batched else bool(ok[0])

    def _at(self, k: int, c: int) -> LimitViolation:
        return LimitViolation(sample=k, joint=self.joints[c], value=float(self.q[k, c]),
                              lower=float(self.lower[c]), upper=float(self.upper[c]),
                              margin=float(self.margin), amount=float(self.excess[k, c]))

    def __iter__(self) -> Iterator[LimitViolation]:
        return (self._at(int(k), int(c)) for k, c in np.argwhere(self.excess > 0.0))

    def __len__(self) -> int:
        return int(np.count_nonzero(self.excess > 0.0))

    def __bool__(self) -> bool:
        return bool(np.any(self.excess > 0.0))

    def __getitem__(self, i: int) -> LimitViolation:
        k, c = np.argwhere(self.excess > 0.0)[i]
        return self._at(int(k), int(c))

    @property
    def worst(self) -> LimitViolation | None:
        """The violation of the largest amount (the first, on a tie), or None."""
        if not self:
            return None
        k, c = np.unravel_index(int(np.argmax(self.excess)), self.excess.shape)
        return self._at(int(k), int(c))
