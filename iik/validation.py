"""Input validation shared by every public ``iik`` function.

Each helper turns user input into a float64 NumPy array or raises
:class:`~iik.errors.InvalidInputError` naming the argument and the reason.
Nothing here lets an exception from inside NumPy escape.
"""

from __future__ import annotations

import math

import numpy as np

from .errors import InvalidInputError, NotOrthonormalError

__all__ = ["as_float_array", "as_joints", "as_points", "as_poses", "bounded_number"]


def as_float_array(value, name: str) -> np.ndarray:
    """Convert ``value`` to a finite float64 array, or raise ``InvalidInputError``."""
    if isinstance(value, (str, bytes)):
        raise InvalidInputError(name, f"expected numbers, got {type(value).__name__}")
    try:
        arr = np.asarray(value)
    except Exception as exc:  # ragged nested lists, exotic objects
        raise InvalidInputError(name, f"cannot be read as an array ({exc})") from None
    if arr.dtype == object or not (
        np.issubdtype(arr.dtype, np.number) or arr.dtype == np.bool_
    ):
        raise InvalidInputError(name, f"expected a numeric array, got dtype {arr.dtype}")
    if np.iscomplexobj(arr):
        raise InvalidInputError(name, "complex values are not accepted")
    arr = arr.astype(np.float64, copy=False)
    if not np.all(np.isfinite(arr)):
        raise InvalidInputError(name, "contains NaN or inf")
    return arr


def _as_batch(value, name: str, tail: tuple[int, ...], what: str) -> tuple[np.ndarray, bool]:
    arr = as_float_array(value, name)
    k = len(tail)
    if arr.shape == tail:
        return arr[None, ...], False
    if arr.ndim == k + 1 and arr.shape[1:] == tail:
        return arr, True
    shape = "x".join(map(str, tail))
    raise InvalidInputError(
        name, f"expected {what} of shape ({shape}) or (n, {shape}), got shape {arr.shape}"
    )


def as_joints(q, name: str = "q", dof: int = 6) -> tuple[np.ndarray, bool]:
    """Return ``(q_batch (n, dof), was_batched)`` for joint angles in rad."""
    return _as_batch(q, name, (dof,), "joint angles")


def as_points(p, name: str = "p") -> tuple[np.ndarray, bool]:
    """Return ``(p_batch (n, 3), was_batched)`` for Cartesian points in m."""
    return _as_batch(p, name, (3,), "points")


def as_poses(T, name: str = "T", *, orthonormal_tol: float = 1e-6) -> tuple[np.ndarray, bool]:
    """Return ``(T_batch (n, 4, 4), was_batched)`` for homogeneous transforms.

    Checks the bottom row is ``[0, 0, 0, 1]`` and the rotation block is a proper
    rotation (``R^T R = I`` and ``det R = +1`` within ``orthonormal_tol``).
    """
    Ts, batched = _as_batch(T, name, (4, 4), "homogeneous transforms")
    if not np.allclose(Ts[:, 3, :], [0.0, 0.0, 0.0, 1.0], atol=orthonormal_tol, rtol=0):
        raise InvalidInputError(name, "bottom row must be [0, 0, 0, 1]")
    R = Ts[:, :3, :3]
    err = np.abs(np.einsum("nji,njk->nik", R, R) - np.eye(3)).max(axis=(1, 2))
    if np.any(err > orthonormal_tol):
        i = int(np.argmax(err))
        raise NotOrthonormalError(
            name,
            f"rotation block is not orthonormal (max |R^T R - I| = {err[i]:.3g}"
            + (f" at index {i}" if batched else "")
            + ")",
            float(err[i]), orthonormal_tol, i if batched else None,
        )
    det = np.linalg.det(R)
    if np.any(det < 0):
        raise InvalidInputError(name, "rotation block has det -1 (a reflection)")
    return Ts, batched


def bounded_number(value, name: str, lo: float, hi: float, *, unit: str = "", open_lo: bool = False) -> float:
    """``value`` as a float if it is a finite real number (not a bool) in ``[lo, hi]`` (``(lo, hi]`` with
    ``open_lo``); else :class:`~iik.errors.InvalidInputError` naming ``name``, the interval and ``unit``
    (e.g. ``" s"``)."""
    real = isinstance(value, (int, float, np.integer, np.floating)) \
        and not isinstance(value, (bool, np.bool_))
    ok = real and math.isfinite(value) and (value > lo if open_lo else value >= lo) and value <= hi
    if not ok:
        where = f"({lo:g}, {hi:g}]" if open_lo else f"[{lo:g}, {hi:g}]"
        raise InvalidInputError(name, f"must be a finite number in {where}{unit}, got {value!r}")
    return float(value)
