"""Denavit-Hartenberg tables and the generic chain product.

Two conventions are supported (angles in rad, lengths in m):

* ``"modified"`` (Craig): ``T_i = RotX(alpha_{i-1}) TransX(a_{i-1}) RotZ(theta_i) TransZ(d_i)``,
  the convention of the thesis's Table II.
* ``"standard"`` (classic): ``T_i = RotZ(theta_i) TransZ(d_i) TransX(a_i) RotX(alpha_i)``,
  the convention in which e.g. the UR5 table is published.

For a row the joint angle is ``theta_i = q_i + offset``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from .errors import InvalidInputError
from .validation import as_joints

__all__ = ["DHRow", "DHTable", "dh_chain", "dh_link_transform"]

Convention = Literal["modified", "standard"]


@dataclass(frozen=True)
class DHRow:
    """One DH row: ``alpha`` [rad], ``a`` [m], ``d`` [m], joint ``offset`` [rad]."""

    alpha: float
    a: float
    d: float
    offset: float = 0.0


@dataclass(frozen=True)
class DHTable:
    """An ordered revolute chain with joint limits.

    Attributes:
        rows: One :class:`DHRow` per joint.
        convention: ``"modified"`` (Craig) or ``"standard"``.
        lower, upper: Joint limits [rad], one per row.
        velocity: Joint speed limits [rad/s], one per row.
    """

    rows: tuple[DHRow, ...]
    convention: Convention
    lower: tuple[float, ...]
    upper: tuple[float, ...]
    velocity: tuple[float, ...]

    def __post_init__(self) -> None:
        n = len(self.rows)
        if n == 0:
            raise InvalidInputError("rows", "a DH table needs at least one row")
        if self.convention not in ("modified", "standard"):
            raise InvalidInputError(
                "convention", f"must be 'modified' or 'standard', got {self.convention!r}"
            )
        for name in ("lower", "upper", "velocity"):
            vals = getattr(self, name)
            if len(vals) != n:
                raise InvalidInputError(name, f"has {len(vals)} entries for {n} rows")
            if not all(np.isfinite(v) for v in vals):
                raise InvalidInputError(name, "contains NaN or inf")
        for i, row in enumerate(self.rows):
            if not all(np.isfinite((row.alpha, row.a, row.d, row.offset))):
                raise InvalidInputError(f"rows[{i}]", "contains NaN or inf")
        for i, (lo, hi) in enumerate(zip(self.lower, self.upper, strict=True)):
            if not lo < hi:
                raise InvalidInputError(f"lower[{i}]", f"lower limit {lo} is not below upper {hi}")
        if any(v <= 0 for v in self.velocity):
            raise InvalidInputError("velocity", "speed limits must be positive")

    @property
    def dof(self) -> int:
        return len(self.rows)


def dh_link_transform(row: DHRow, theta: np.ndarray, convention: Convention) -> np.ndarray:
    """Link transform(s) for joint angle(s) ``theta`` (shape (n,)) -> (n, 4, 4)."""
    theta = np.asarray(theta, dtype=float) + row.offset
    ct, st = np.cos(theta), np.sin(theta)
    ca, sa = np.cos(row.alpha), np.sin(row.alpha)
    T = np.zeros(theta.shape + (4, 4))
    T[..., 3, 3] = 1.0
    if convention == "modified":
        # Craig: RotX(alpha) TransX(a) RotZ(theta) TransZ(d)
        T[..., 0, 0], T[..., 0, 1], T[..., 0, 3] = ct, -st, row.a
        T[..., 1, 0], T[..., 1, 1], T[..., 1, 2], T[..., 1, 3] = st * ca, ct * ca, -sa, -sa * row.d
        T[..., 2, 0], T[..., 2, 1], T[..., 2, 2], T[..., 2, 3] = st * sa, ct * sa, ca, ca * row.d
    else:
        # standard: RotZ(theta) TransZ(d) TransX(a) RotX(alpha)
        T[..., 0, 0], T[..., 0, 1], T[..., 0, 2], T[..., 0, 3] = ct, -st * ca, st * sa, row.a * ct
        T[..., 1, 0], T[..., 1, 1], T[..., 1, 2], T[..., 1, 3] = st, ct * ca, -ct * sa, row.a * st
        T[..., 2, 1], T[..., 2, 2], T[..., 2, 3] = sa, ca, row.d
    return T


def dh_chain(table: DHTable, q, *, all_frames: bool = False) -> np.ndarray:
    """Product of the link transforms of ``table`` at joint angles ``q`` [rad].

    Args:
        table: The DH table.
        q: Joint angles, shape (dof,) or (n, dof).
        all_frames: If true, return every cumulative frame ``0_T_i`` for
            i = 1..dof, shape (dof, 4, 4) or (n, dof, 4, 4).

    Returns:
        ``0_T_dof`` as (4, 4) or (n, 4, 4), in the base frame, metres.
    """
    qb, batched = as_joints(q, "q", table.dof)
    T = np.broadcast_to(np.eye(4), (qb.shape[0], 4, 4)).copy()
    frames = []
    for i, row in enumerate(table.rows):
        T = T @ dh_link_transform(row, qb[:, i], table.convention)
        frames.append(T)
    out = np.stack(frames, axis=1) if all_frames else T
    return out if batched else out[0]
