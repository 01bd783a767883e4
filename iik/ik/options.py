"""Options of the inverse kinematics: tolerances with documented defaults."""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

from ..errors import InvalidInputError

__all__ = ["IKOptions", "DEFAULT_OPTIONS", "ORTHONORMAL_TOL"]

#: Default :attr:`IKOptions.orthonormal_tol`, chosen from what real pose sources deliver. A rotation
#: whose entries are rounded to k decimals (error <= e = 0.5e-k each) has max |R^T R - I| <= 2 sqrt(3) e
#: + 3 e^2 (each entry of R^T E + E^T R + E^T E; a column of E has norm <= sqrt(3) e): 1.7e-6 for the
#: 6 decimals of a log file, 1.7e-4 for the 4 decimals a teach pendant shows (measured: 1.67e-4 on
#: 200 000 random rotations; 22 % of them exceeded the former default 1e-4), 1.7e-3 for 3 decimals;
#: float32 gives 1e-7. 1e-3 accepts 4-decimal data with a margin of 5.8 and still rejects a matrix
#: scaled by 1.001 (2e-3) or with an entry off by 0.01; 3-decimal data needs orthonormal_tol=2e-3.
ORTHONORMAL_TOL = 1e-3


@dataclass(frozen=True)
class IKOptions:
    """Tolerances of :func:`iik.solve` / :func:`iik.solve_many` (pass ``options=IKOptions(...)``).

    Attributes:
        position_tol: A configuration solves the pose if its tool point is within this of the
            requested one [m] ...
        rotation_tol: ... and its rotation within this angle of the requested one [rad]
            (after the projection below).
        orthonormal_tol: A rotation block with max |R^T R - I| up to this is projected onto the
            nearest rotation (polar decomposition) and solved; the result reports the distance
            (``rotation_projection``) and the residuals against the pose as given. Beyond it
            the pose is rejected (:class:`~iik.errors.NotOrthonormalError`). The default
            (:data:`ORTHONORMAL_TOL` = 1e-3) accepts float32 matrices and matrices rounded to
            6 or to 4 decimals (a teach pendant's display: at most 1.7e-4), and still rejects a
            scaled or wrong matrix (x 1.001: 2e-3); 3-decimal data needs 2e-3.
        approximate_tol: When no configuration solves the pose within the tolerances above
            (within the joint limits, if asked), configurations within this [m and rad] of it
            are returned, flagged ``approximate``: a pose this close to the reachable set is
            not called unreachable.
        parallel: :func:`iik.solve_many` runs the compiled kernel on all cores (Numba threads).
            Its first use compiles a second entry point (``solve_many_parallel``), once, cached
            on disk like the serial one: 37 s on the shared 2-core development machine (load
            3.7; the serial kernel, 41 s there, is compiled separately). Later processes load
            it in 0.05 s. On 2 cores it did not pay: 20 000 poses took 414 ms serial and 508 ms
            parallel, since both cores were already busy; it is for batches of thousands of
            poses on more, idle cores.
    """

    position_tol: float = 1e-10
    rotation_tol: float = 1e-10
    orthonormal_tol: float = ORTHONORMAL_TOL
    approximate_tol: float = 1e-5
    parallel: bool = False

    def __post_init__(self) -> None:
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name == "parallel":
                if not isinstance(v, bool):
                    raise InvalidInputError(f"options.{f.name}", f"expected True or False, got {v!r}")
                continue
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
                raise InvalidInputError(f"options.{f.name}", f"expected a positive finite number, got {v!r}")
            object.__setattr__(self, f.name, float(v))
        if self.orthonormal_tol >= 0.5:
            raise InvalidInputError("options.orthonormal_tol",
                                    f"must be below 0.5, got {self.orthonormal_tol}")
        for name in ("position_tol", "rotation_tol"):
            if getattr(self, name) > self.approximate_tol:
                raise InvalidInputError(f"options.{name}",
                                        f"{getattr(self, name):g} is larger than approximate_tol "
                                        f"= {self.approximate_tol:g}")


#: The defaults.
DEFAULT_OPTIONS = IKOptions()
