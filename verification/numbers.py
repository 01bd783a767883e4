"""Formatting of measured numbers for report rows (one style across the checks)."""

from __future__ import annotations

import numpy as np

__all__ = ["fmt_q", "fmt_vec", "fmt_matrix", "worst"]


def fmt_q(q) -> str:
    """``"q = [0.3000, ...] rad"`` for a joint vector [rad]."""
    return "q = [" + ", ".join(f"{v:.4f}" for v in np.ravel(q)) + "] rad"


def fmt_vec(v, nd: int = 4) -> str:
    """``"[a b c]"`` with ``nd`` decimals."""
    return "[" + " ".join(f"{x:.{nd}f}" for x in np.ravel(v)) + "]"


def fmt_matrix(a, nd: int = 1) -> str:
    """Rows separated by ``"; "`` (one line)."""
    a = np.atleast_2d(a)
    return "[" + "; ".join(" ".join(f"{v:.{nd}f}" for v in row) for row in a) + "]"


def worst(err: np.ndarray) -> tuple[float, int]:
    """``(max value, index of the first maximum)`` of a 1-D error array, NaN counted as inf."""
    e = np.where(np.isnan(err), np.inf, np.asarray(err, float))
    i = int(np.argmax(e))
    return float(e[i]), i
