"""The singularity sets of Appendix D (Tables VI and VII) as data, plus helpers.

A singularity set fixes some of joints 1-5 and leaves the others free; its
image under the position map (Eq 34) is a singular parametric surface
(Sec 3.4.2). Joint 6 does not move the tool point and never appears.

Values are stored in rad (the tables print degrees). Table VI is transcribed
from the extracted text, where merged cells appear blank: a blank cell takes
the value of the row above in the same column (the usual reading of the
table's layout). Known transcription problems are recorded per set in
``note`` (e.g. s(33) and s(34) print identically).

Table VII (type III, constraint singularities) lists groups of eight sets:
three joints at one of their two limits (2^3 combinations) and two free
joints. The group s(94)-s(101) is garbled in the text (only two fixed joints
survive); it is read as the one combination of three fixed joints that no
other group uses, {1, 4, 5}.

The kind of each set follows Abdel-Malek & Yeh [12]: ``"I"`` rank deficiency
of the full position Jacobian, ``"II"`` of the reduced Jacobian (joints held
at a limit removed), ``"III"`` constraint singularity (three joints at limits).
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import product

import numpy as np

from .arm import THESIS_ARM, Arm
from .errors import InvalidInputError

__all__ = [
    "SingularitySet",
    "TABLE_VI",
    "TABLE_VII",
    "ALL_SETS",
    "singularity_set",
    "sample_set",
    "at_limit_mask",
    "reduced_rank",
]

_D = np.pi / 180.0
V = None  # "variable" in the tables


@dataclass(frozen=True)
class SingularitySet:
    """One row of Table VI or one member of a group of Table VII.

    Attributes:
        index: k in s(k).
        kind: ``"I"``, ``"II"`` or ``"III"`` (Abdel-Malek & Yeh [12]).
        fixed: ``((joint, value_rad), ...)``; joints are 1-based (1..5).
        table: ``"VI"`` or ``"VII"``.
        printed: The row as printed, in degrees (``None`` = variable/blank/NA).
        note: Transcription remarks (garbled cells, duplicates).
    """

    index: int
    kind: str
    fixed: tuple[tuple[int, float], ...]
    table: str
    printed: tuple = ()
    note: str = ""

    @property
    def name(self) -> str:
        return f"s({self.index})"

    @property
    def free(self) -> tuple[int, ...]:
        """Free joints (1-based) among 1..5."""
        fx = {j for j, _ in self.fixed}
        return tuple(j for j in range(1, 6) if j not in fx)

    def fixed_dict(self) -> dict[int, float]:
        return dict(self.fixed)


# Table VI as printed (degrees; None = "variable", blank or "NA").
# Columns theta1..theta5. Blank cells inherit from the row above (merged cells).
_TABLE_VI_PRINTED = {
    1: ("I", (V, V, V, 0, 0)),  # theta3 printed "NA"
    2: ("II", (-160, V, 90, V, 0)),
    3: ("II", (160, "^", 90, "^", 0)),
    4: ("II", (-160, -120, V, "^", 0)),
    5: ("II", (-160, 95, "^", "^", 0)),
    6: ("II", (160, -120, "^", "^", 0)),
    7: ("II", (160, 95, "^", "^", 0)),
    8: ("II", (-160, V, -160, "^", 0)),
    9: ("II", (-160, "^", 160, "^", 0)),
    10: ("II", (160, "^", -160, "^", 0)),
    11: ("II", (160, "^", 160, "^", 0)),
    12: ("II", (-160, "^", -90, -119, V)),
    13: ("II", (-160, "^", 90, -119, "^")),
    14: ("II", (160, "^", -90, -119, "^")),
    15: ("II", (160, "^", 90, -119, "^")),
    16: ("II", (-160, "^", -90, 119, "^")),
    17: ("II", (-160, "^", 90, 119, "^")),
    18: ("II", (160, "^", -90, 119, "^")),
    19: ("II", (160, "^", 90, 119, "^")),
    20: ("II", (V, -120, -160, V, 0)),
    21: ("II", ("^", -120, 160, "^", 0)),
    22: ("II", ("^", 95, -160, "^", 0)),
    23: ("II", ("^", 95, 160, "^", 0)),
    24: ("II", ("^", -120, 0, -119, V)),
    25: ("II", ("^", -120, 0, 119, "^")),
    26: ("II", ("^", 95, 0, -119, "^")),
    27: ("II", ("^", 95, 0, 119, "^")),
    28: ("II", (V, -120, 0, V, -119)),
    29: ("II", ("^", -120, 0, "^", 119)),
    30: ("II", ("^", 95, 0, "^", -119)),
    31: ("II", ("^", 95, 0, "^", 119)),
    32: ("II", ("^", V, 0, -119, -119)),
    33: ("II", ("^", "^", -90, -119, -119)),
    34: ("II", ("^", "^", -90, -119, -119)),
    35: ("II", ("^", "^", 0, -119, 119)),
    36: ("II", ("^", "^", -90, -119, 119)),
    37: ("II", ("^", "^", 90, -119, 119)),
}
_NOTES = {
    1: "theta3 printed 'NA' (it does not move the tool when theta4 = theta5 = 0); treated as free.",
    33: "prints identically to s(34) in the extracted text (theta3 = -90, theta4 = theta5 = -119): "
        "one of them is garbled (by the pattern of s(35)-s(37) probably theta3 = +90).",
    34: "prints identically to s(33); see there.",
}


def _build_table_vi() -> tuple[SingularitySet, ...]:
    rows, prev = [], None
    for k, (kind, cells) in _TABLE_VI_PRINTED.items():
        vals = []
        for j, c in enumerate(cells):
            vals.append(prev[j] if (isinstance(c, str) and c == "^") else c)
        prev = vals
        fixed = tuple((j + 1, float(v) * _D) for j, v in enumerate(vals) if v is not None)
        rows.append(SingularitySet(k, kind, fixed, "VI", tuple(vals), _NOTES.get(k, "")))
    return tuple(rows)


#: Table VII groups: (first index, fixed joints). Values: both limits of each.
_TABLE_VII_GROUPS = (
    (38, (1, 2, 3)),
    (46, (1, 2, 4)),
    (54, (1, 2, 5)),
    (62, (2, 3, 4)),
    (70, (3, 4, 5)),
    (78, (1, 3, 5)),
    (86, (1, 3, 4)),
    (94, (1, 4, 5)),  # garbled in the text: only theta1 and theta5 limits survive
    (102, (2, 3, 5)),
    (110, (2, 4, 5)),
)


def _build_table_vii(arm: Arm) -> tuple[SingularitySet, ...]:
    rows = []
    for first, joints in _TABLE_VII_GROUPS:
        for m, ends in enumerate(product((0, 1), repeat=3)):
            fixed = tuple(
                (j, (arm.lower[j - 1], arm.upper[j - 1])[e]) for j, e in zip(joints, ends, strict=True)
            )
            note = ("garbled group: printed cells give only theta1 and theta5 at limits; "
                    "read as {1, 4, 5}, the one three-joint combination no other group has"
                    if first == 94 else "")
            printed = tuple(
                (round(dict(fixed)[j] / _D) if j in dict(fixed) else None) for j in range(1, 6)
            )
            rows.append(SingularitySet(first + m, "III", fixed, "VII", printed, note))
    return tuple(rows)


TABLE_VI: tuple[SingularitySet, ...] = _build_table_vi()
TABLE_VII: tuple[SingularitySet, ...] = _build_table_vii(THESIS_ARM)
ALL_SETS: tuple[SingularitySet, ...] = TABLE_VI + TABLE_VII


def singularity_set(k: int) -> SingularitySet:
    """The set s(k), k = 1..117."""
    for s in ALL_SETS:
        if s.index == k:
            return s
    raise InvalidInputError("k", f"no singularity set s({k}); Appendix D has s(1)..s(117)")


def sample_set(s: SingularitySet, n: int, rng: np.random.Generator, arm: Arm) -> np.ndarray:
    """``n`` joint vectors (n, 6) [rad] on set ``s``: free joints uniform in Table I, joint 6 = 0."""
    q = rng.uniform(arm.q_min, arm.q_max, size=(n, 6))
    q[:, 5] = 0.0
    for j, v in s.fixed:
        q[:, j - 1] = v
    return q


def at_limit_mask(q, arm: Arm, tol: float = 1e-9) -> np.ndarray:
    """Boolean (n, 5): is joint 1..5 of each ``q`` at a Table I limit (within ``tol`` rad)?"""
    q = np.atleast_2d(np.asarray(q, dtype=float))[:, :5]
    return (np.abs(q - arm.q_min[:5]) <= tol) | (np.abs(q - arm.q_max[:5]) <= tol)


def reduced_rank(J: np.ndarray, at_limit: np.ndarray, rtol: float = 1e-9) -> tuple[np.ndarray, np.ndarray]:
    """Rank of the reduced (constraint) Jacobian of Abdel-Malek & Yeh [12].

    The columns of joints held at a limit are dropped (with the
    parameterisation of Eq 58, ``q_s`` has a zero entry there).

    Args:
        J: Position Jacobians (n, 3, 5) [m/rad].
        at_limit: (n, 5) boolean.
        rtol: Singular values below ``rtol * max(1, sigma_max)`` count as zero.

    Returns:
        ``(rank (n,), smallest singular value of the reduced Jacobian (n,))``; the
        smallest value is 0 when fewer than three columns remain.
    """
    J = np.asarray(J, dtype=float)
    Jr = np.where(at_limit[:, None, :], 0.0, J)
    sv = np.linalg.svd(Jr, compute_uv=False)  # (n, 3)
    scale = np.maximum(1.0, sv[:, :1])
    rank = (sv > rtol * scale).sum(axis=1)
    return rank, sv[:, 2]
