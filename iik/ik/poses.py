"""Pose input of the IK: structural checks, projection onto the nearest rotation, typed errors.

A pose is a (4, 4) homogeneous transform [m]. Its bottom row must be [0, 0, 0, 1]
and its rotation block proper (det > 0) and orthonormal to within
``IKOptions.orthonormal_tol`` (max |R^T R - I|); such a block is replaced by the
nearest rotation (polar decomposition, Frobenius norm) before solving, and the
distance is reported. The compiled kernel runs the same checks
(:func:`iik.ik.kernel` ``_check_pose``); this module is the NumPy version (reference
and thesis methods) and the one place the errors are worded.
"""

from __future__ import annotations

import numpy as np

from ..errors import InvalidInputError, NotOrthonormalError
from ..validation import as_float_array
from .options import ORTHONORMAL_TOL

__all__ = ["OK", "NONFINITE", "BOTTOM_ROW", "NOT_ORTHONORMAL", "REFLECTION", "as_pose_batch",
           "check_poses", "pose_error"]

# Status codes (the kernel's are the same numbers).
OK, NONFINITE, BOTTOM_ROW, NOT_ORTHONORMAL, REFLECTION = 0, 1, 2, 3, 4

#: Rotations orthonormal to this (max |R^T R - I|) are used exactly as given.
EXACT = 64 * np.finfo(float).eps


def as_pose_batch(T, name: str) -> tuple[np.ndarray, bool]:
    """``(T (n, 4, 4) float64, batched)``: type and shape checked (values are checked later)."""
    try:
        arr = np.asarray(T)
    except Exception as exc:  # ragged nested lists, exotic objects
        raise InvalidInputError(name, f"cannot be read as an array ({exc})") from None
    if arr.dtype != np.float64:
        arr = as_float_array(T, name)  # finiteness of float64 input: check_poses / the kernel
    if arr.shape == (4, 4):
        return arr[None], False
    if arr.ndim == 3 and arr.shape[1:] == (4, 4):
        return arr, True
    raise InvalidInputError(name, "expected homogeneous transforms of shape (4x4) or (n, 4x4), "
                                  f"got shape {arr.shape}")


def check_poses(T: np.ndarray, tol: float):
    """Per pose: ``(status, measure, R_used, distance)`` for poses (n, 4, 4) (finite).

    ``measure`` is the bottom-row error or max |R^T R - I|; ``R_used`` (n, 3, 3) the nearest
    rotation (SVD polar factor) where the block is within ``tol`` of orthonormal, else the
    block; ``distance`` the Frobenius distance between the two.
    """
    n = len(T)
    status = np.zeros(n, dtype=int)
    finite = np.all(np.isfinite(T), axis=(1, 2))
    T = np.where(finite[:, None, None], T, 0.0)
    bottom = np.max(np.abs(T[:, 3, :] - [0.0, 0.0, 0.0, 1.0]), axis=1)
    R = T[:, :3, :3]
    err = np.abs(np.einsum("nji,njk->nik", R, R) - np.eye(3)).max(axis=(1, 2))
    det = np.linalg.det(R)
    status[det < 0] = REFLECTION
    status[err > tol] = NOT_ORTHONORMAL
    status[bottom > tol] = BOTTOM_ROW
    status[~finite] = NONFINITE
    measure = np.where(status == BOTTOM_ROW, bottom, err)
    Ru = R.copy()
    fix = (status == OK) & (err > EXACT)
    if fix.any():
        U, _, Vt = np.linalg.svd(R[fix])
        Ru[fix] = U @ Vt
    dist = np.sqrt(np.sum((R - Ru) ** 2, axis=(1, 2)))
    return status, measure, Ru, dist


def pose_error(status: int, measure: float, name: str, index: int | None, tol: float) -> InvalidInputError:
    """The typed error for a failed pose check (``index`` for a pose of a batch)."""
    at = "" if index is None else f" at index {index}"
    if status == NONFINITE:
        return InvalidInputError(name, "contains NaN or inf" + at)
    if status == BOTTOM_ROW:
        return InvalidInputError(name, f"bottom row must be [0, 0, 0, 1]{at} (off by {measure:.3g})")
    if status == NOT_ORTHONORMAL:
        return NotOrthonormalError(
            name,
            f"rotation block is not orthonormal (max |R^T R - I| = {measure:.3g}{at}); rotations within "
            f"IKOptions.orthonormal_tol = {tol:g} of orthonormal are projected onto the nearest rotation "
            f"and solved (the default {ORTHONORMAL_TOL:g} takes float32 and entries rounded to 4 decimals, "
            "which deviate by at most 1.7e-4; 3 decimals deviate by up to 1.7e-3): raise that option to "
            "accept this one",
            float(measure), tol, index)
    return InvalidInputError(name, "rotation block has det -1 (a reflection)" + at)
