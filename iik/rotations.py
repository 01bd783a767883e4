"""End-effector orientation from the Euler angles of Eq 42 (Sec 3.5.1), and back.

Sec 3.5.1 says the orientation uses "the Z-X-Z representation convention described
in [2]" (Craig) and prints Eq 42. Checked against ``scipy.spatial.transform.Rotation``
(``iik verify``, section "Kinematics"), the printed matrix is **Craig's Z-Y-Z** Euler
matrix ``R = Rz(alpha) Ry(beta) Rz(gamma)`` (intrinsic, scipy ``"ZYZ"``) with one wrong
entry: printed ``r21 = c_a c_b c_g - c_a s_g``, correct ``r21 = s_a c_b c_g + c_a s_g``.
Every other entry fits Z-Y-Z, not Z-X-Z (in Z-Y-Z, alpha is the azimuth and beta the
polar angle of ``z6 = [r13, r23, r33] = [c_a s_b, s_a s_b, c_b]``; Sec 3.5 measures its
own alpha, beta differently, see :mod:`iik.dexterity`). The functions here therefore
implement the corrected Eq 42, i.e. intrinsic Z-Y-Z, and are named for it:
:func:`euler_matrix`, :func:`euler_from_matrix` and :func:`pose_from_euler` take
``convention="ZYZ"`` (the default; any other scipy sequence, e.g. ``"ZXZ"`` for real
Z-X-Z data, is accepted too).

The old names ``zxz_matrix``, ``zxz_from_matrix`` and ``pose_from_zxz`` (which said Z-X-Z
but computed Z-Y-Z: scipy's ``"ZXZ"`` for (30, 40, 50) deg differs by 56 deg) are
deprecated aliases of the Z-Y-Z functions: they warn (``DeprecationWarning``) and will be
removed.

Angles in rad. Inputs broadcast; scalars give one (3, 3) matrix, arrays of shape (n,)
give (n, 3, 3).
"""

from __future__ import annotations

import functools
import re
import warnings
from collections.abc import Callable

import numpy as np
from scipy.spatial.transform import Rotation

from .errors import InvalidInputError
from .validation import as_float_array, as_points

__all__ = [
    "EULER_SEQUENCE",
    "euler_matrix",
    "euler_from_matrix",
    "pose_from_euler",
    "rotation_angle",
    "zxz_matrix",
    "zxz_from_matrix",
    "pose_from_zxz",
]

#: scipy sequence of the corrected Eq 42: intrinsic rotations about z, then the new y, then the new z.
EULER_SEQUENCE = "ZYZ"

_AXES = re.compile(r"[XYZ]{3}|[xyz]{3}")


def _convention(convention) -> str:
    """A scipy Euler sequence: three axes, intrinsic (upper case) or extrinsic (lower case), no two
    successive ones alike; else InvalidInputError."""
    c = convention
    if not isinstance(c, str) or not _AXES.fullmatch(c) or c[0] == c[1] or c[1] == c[2]:
        raise InvalidInputError("convention", "expected three axes such as 'ZYZ' (the corrected Eq 42) or "
                                              f"'ZXZ', 'XYZ' (scipy's notation), got {c!r}")
    return convention


def euler_matrix(alpha, beta, gamma, *, convention: str = EULER_SEQUENCE) -> np.ndarray:
    """Rotation matrix of the corrected Eq 42: ``Rz(alpha) Ry(beta) Rz(gamma)`` (``convention``
    "ZYZ"; another scipy sequence rotates about those axes instead).

    Args:
        alpha, beta, gamma: Euler angles [rad]; scalars or broadcastable 1-D arrays.
        convention: The Euler sequence (scipy's notation: upper case intrinsic).

    Returns:
        (3, 3) for scalar input, else (n, 3, 3). Columns are the end-effector axes in
        the base frame; with "ZYZ", column 3 (the approach axis z6) is
        ``[cos a sin b, sin a sin b, cos b]`` (Eq 42, r13 r23 r33).
    """
    seq = _convention(convention)
    a = as_float_array(alpha, "alpha")
    b = as_float_array(beta, "beta")
    g = as_float_array(gamma, "gamma")
    for name, v in (("alpha", a), ("beta", b), ("gamma", g)):
        if v.ndim > 1:
            raise InvalidInputError(name, f"expected a scalar or a 1-D array, got shape {v.shape}")
    try:
        a, b, g = np.broadcast_arrays(a, b, g)
    except ValueError:
        raise InvalidInputError(
            "alpha/beta/gamma", f"shapes {a.shape}, {b.shape}, {g.shape} do not broadcast"
        ) from None
    scalar = a.ndim == 0
    angles = np.stack([np.atleast_1d(a), np.atleast_1d(b), np.atleast_1d(g)], axis=-1)
    R = Rotation.from_euler(seq, angles).as_matrix()  # Eq 42 (corrected r21) for "ZYZ"
    return R[0] if scalar else R


def _as_rotations(R, name: str, tol: float) -> tuple[np.ndarray, bool]:
    arr = as_float_array(R, name)
    if arr.shape == (3, 3):
        arr, batched = arr[None], False
    elif arr.ndim == 3 and arr.shape[1:] == (3, 3):
        batched = True
    else:
        raise InvalidInputError(name, f"expected shape (3, 3) or (n, 3, 3), got {arr.shape}")
    err = np.abs(np.einsum("nji,njk->nik", arr, arr) - np.eye(3)).max(axis=(1, 2)) if len(arr) else []
    if np.any(np.asarray(err) > tol):
        raise InvalidInputError(name, f"is not orthonormal (max |R^T R - I| = {np.max(err):.3g})")
    if len(arr) and np.any(np.linalg.det(arr) < 0):
        raise InvalidInputError(name, "has det -1 (a reflection, not a rotation)")
    return arr, batched


def euler_from_matrix(R, *, convention: str = EULER_SEQUENCE, orthonormal_tol: float = 1e-6) -> np.ndarray:
    """Euler angles ``(alpha, beta, gamma)`` [rad] of the corrected Eq 42 (``convention``) for
    rotation(s) ``R``.

    Returns (3,) or (n, 3); for "ZYZ" ``beta`` is in [0, pi] and ``alpha``, ``gamma`` in [-pi, pi].
    At ``beta`` = 0 or pi only ``alpha +- gamma`` is defined; then ``gamma`` = 0.

    Raises:
        InvalidInputError: wrong shape, NaN/inf, not orthonormal, a reflection, or an unknown
            convention.
    """
    seq = _convention(convention)
    arr, batched = _as_rotations(R, "R", orthonormal_tol)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # gimbal lock: documented above
        angles = Rotation.from_matrix(arr).as_euler(seq)
    return angles if batched else angles[0]


def pose_from_euler(p, alpha, beta, gamma, *, convention: str = EULER_SEQUENCE) -> np.ndarray:
    """Homogeneous pose(s) [m] from position ``p`` (3,) or (n, 3) and the Euler angles [rad] of
    ``convention`` (default: the corrected Eq 42, Z-Y-Z)."""
    pb, batched = as_points(p, "p")
    R = euler_matrix(alpha, beta, gamma, convention=convention)
    Rb = R[None] if R.ndim == 2 else R
    if len(Rb) != len(pb) and 1 not in (len(Rb), len(pb)):
        raise InvalidInputError("p", f"{len(pb)} points for {len(Rb)} orientations")
    n = max(len(Rb), len(pb))
    T = np.zeros((n, 4, 4))
    T[:, :3, :3] = Rb
    T[:, :3, 3] = pb
    T[:, 3, 3] = 1.0
    return T if (batched or R.ndim == 3) else T[0]


def rotation_angle(R1, R2) -> np.ndarray:
    """Angle [rad] of the rotation ``R1^T R2`` between rotation matrices (..., 3, 3).

    Computed as ``2 asin(|R1 - R2|_F / sqrt(8))``, which is exact for rotations and,
    unlike ``arccos((tr - 1) / 2)``, accurate near 0 (the residuals IK and the
    executor compare against tolerances of 1e-10 rad and below).
    """
    d = np.sqrt(np.sum((np.asarray(R1) - np.asarray(R2)) ** 2, axis=(-2, -1)))
    return 2.0 * np.arcsin(np.minimum(d / np.sqrt(8.0), 1.0))


def _deprecated(old: str, new: Callable) -> Callable:
    """``new`` under the deprecated name ``old`` (it warns once per call site)."""

    @functools.wraps(new)
    def alias(*args, **kwargs):
        warnings.warn(f"iik.{old} is deprecated: the corrected Eq 42 it computes is Z-Y-Z (scipy 'ZYZ'), not "
                      f"Z-X-Z; use iik.{new.__name__} (convention='ZYZ', the same angles and result)",
                      DeprecationWarning, stacklevel=2)
        return new(*args, **kwargs)

    alias.__name__ = alias.__qualname__ = old
    alias.__doc__ = f"Deprecated alias of :func:`{new.__name__}` (Z-Y-Z, the corrected Eq 42; it warns)."
    return alias


#: The thesis calls Eq 42 "Z-X-Z"; it is Z-Y-Z (module docstring): the old names, deprecated.
zxz_matrix = _deprecated("zxz_matrix", euler_matrix)
zxz_from_matrix = _deprecated("zxz_from_matrix", euler_from_matrix)
pose_from_zxz = _deprecated("pose_from_zxz", pose_from_euler)
