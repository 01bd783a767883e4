"""The IK kernel's shared names: every output index, status code, candidate kind, path and
constant that the compiled kernel (:mod:`iik.ik.kernel`), the NumPy reference
(:mod:`iik.ik.reference`), the public entry points (:mod:`iik.ik.solve`) and the comparators
read. Numba reads module constants at compile time, so they are plain ints and floats.

Units: metres and radians.
"""

from __future__ import annotations

__all__ = [
    "OK",
    "NONFINITE",
    "BOTTOM_ROW",
    "NOT_ORTHONORMAL",
    "REFLECTION",
    "MAX_SOLUTIONS",
    "N_INFO",
    "I_PRES",
    "I_RRES",
    "I_FREE",
    "I_KIND",
    "I_H3",
    "I_CSIGN",
    "I_CLO",
    "I_CHI",
    "N_HDR",
    "H_STATUS",
    "H_MEASURE",
    "H_PROJECTION",
    "H_TOTAL",
    "H_COUNT",
    "H_BEST_P",
    "H_BEST_R",
    "H_FREE",
    "H_APPROX",
    "H_PATH",
    "H_ROOTS",
    "H_CLUSTERS",
    "H_NEAR",
    "H_CERT",
    "PATH_DOUBLE",
    "PATH_EXTENDED",
    "PATH_MULTIPLE",
    "PATH_DEGENERATE",
    "PATH_REFERENCE",
    "PATH_NAMES",
    "SLOW_PATH",
    "CERT_OK",
    "CERT_ROOT_WITHOUT_CONFIGURATION",
    "CERT_TABLE_FULL",
    "CERT_ROWS_DROPPED",
    "CERT_NEAR_THETA2",
    "CERT_NAMES",
    "FREE_NONE",
    "FREE_Q1",
    "FREE_Q3",
    "FREE_NUMERICAL",
    "FREE_Q2",
    "FREE_BAND",
    "FREE_JOINTS_CANONICAL",
    "KIND_ROOT",
    "KIND_NEAR",
    "KIND_MULTIPLE",
    "KIND_SPECIAL",
    "KIND_NAMES",
    "OPT_POSITION_TOL",
    "OPT_ROTATION_TOL",
    "OPT_APPROX_TOL",
    "OPT_ORTHONORMAL_TOL",
    "OPT_LIMIT_TOL",
    "N_OPT",
    "DISTINCT_TOL",
    "CONTINUUM_NEAR",
    "RESTART_H",
    "VANISH",
    "NEAR_FREE2",
    "A_USER_DH",
    "A_USER_BASE",
    "A_USER_TOOL",
    "A_SOLVER_DH",
    "A_SOLVER_BASE_INV",
    "A_SOLVER_TOOL_INV",
    "A_REVERSED",
    "A_LOWER",
    "A_UPPER",
    "A_REACH",
    "A_SCALE",
    "A_CONST",
    "N_CONST",
    "A_CONST_ABS",
    "N_ARM",
]

# ----------------------------------------------------------------------------- pose status
#: Pose status codes: the kernel's validation result (iik.ik.poses words the errors).
OK, NONFINITE, BOTTOM_ROW, NOT_ORTHONORMAL, REFLECTION = 0, 1, 2, 3, 4

# ----------------------------------------------------------------------------- outputs
#: Most distinct solutions of an arm of the class: 8 real roots of the eliminant x 2 wrist branches.
MAX_SOLUTIONS = 16

#: Columns of a solution row of ``info``: residuals against the pose as given [m, rad], the
#: continuum kind (FREE_*), the candidate kind the row came from (KIND_*), and how far joint 3
#: was from free at the closed forms (the size of z6 or (D - C) / a4 across z3) [1].
I_PRES, I_RRES, I_FREE, I_KIND, I_H3 = 0, 1, 2, 3, 4
#: ... and of a theta3 continuum: the coupling sign (the coupled joint moves by sign times the
#: free joint) and the feasible interval of the free joint inside the limits [rad].
I_CSIGN, I_CLO, I_CHI = 5, 6, 7
N_INFO = 8

#: Header of a solved pose: status, measure, projection distance, exact solutions before the
#: limit filter, rows returned, least residuals seen, rows on a continuum, rows approximate,
#: the path the pose took (PATH_*), real roots of the eliminant, clusters sent to the extended
#: path, near-root candidates, and the certificate (CERT_*).
(
    H_STATUS,
    H_MEASURE,
    H_PROJECTION,
    H_TOTAL,
    H_COUNT,
    H_BEST_P,
    H_BEST_R,
    H_FREE,
    H_APPROX,
    H_PATH,
    H_ROOTS,
    H_CLUSTERS,
    H_NEAR,
    H_CERT,
) = range(14)
N_HDR = 14

# ----------------------------------------------------------------------------- paths
#: The pose was certified in double precision: every real root of the eliminant isolated
#: with certified signs (Bernstein sign variations with rounding-error bounds).
PATH_DOUBLE = 0
#: Some cluster of roots could not be separated in double precision; it was re-expanded in
#: double-double arithmetic (~1e-32) and separated there.
PATH_EXTENDED = 1
#: A cluster stayed unresolved even in double-double: roots that coincide to ~1e-15 in
#: tan(theta1 / 2), returned as one (a multiple root, e.g. at a continuum or a singularity).
PATH_MULTIPLE = 2
#: The eliminant vanishes identically within its rounding bound: every theta1 solves the
#: elimination (a theta1 continuum); solved by the degenerate-case analysis.
PATH_DEGENERATE = 3
#: The path of a degenerate pose without a theta1 continuum, re-solved by the NumPy reference
#: (:func:`iik.ik.solve.solve`; not a kernel path: only ``solve_batch`` writes the code).
PATH_REFERENCE = 4
PATH_NAMES = ("double", "extended", "multiple-root", "degenerate", "reference")
SLOW_PATH = PATH_NAMES[PATH_REFERENCE]

#: The certificate: every real root became configurations (CERT_OK); else why not.
CERT_OK = 0
CERT_ROOT_WITHOUT_CONFIGURATION = 1
CERT_TABLE_FULL = 2
CERT_ROWS_DROPPED = 3
CERT_NEAR_THETA2 = 4
CERT_NAMES = (
    "certified",
    "a certified root gave no configuration within the tolerance nearer to it than to another root",
    "the candidate table was full",
    "more distinct solutions than MAX_SOLUTIONS rows: some were left out",
    "near a theta2 continuum (both conditions on theta2 nearly vanish): joint 2 is fixed only "
    "loosely and solutions along the broken curve may be missed",
)

# ----------------------------------------------------------------------------- continua
#: Continuum kinds of a row (bit set, canonical joint numbering of the solver chain):
#: theta1 free (the eliminant vanishes: joint 1 and the joints that follow it move),
#: theta3 free (joints 3 and 6 collinear), a numerical theta3/theta6 continuum (within the
#: tolerance the pose fixes theta3 only loosely; no exact members), or theta2 free (both
#: conditions on theta2 vanish at a theta1: D on axis 2, docs/IK_CLASS.md section 5 C).
FREE_NONE, FREE_Q1, FREE_Q3, FREE_NUMERICAL, FREE_Q2 = 0, 1, 2, 4, 8
#: A numerical continuum of joint 1 (a band beside a theta1 continuum, no coupled joint): found by
#: :mod:`iik.ik.solve`, not the kernel (only ``solve_batch`` writes the code).
FREE_BAND = FREE_NUMERICAL | FREE_Q1
#: The canonical free joint of each bit (1-based).
FREE_JOINTS_CANONICAL = ((FREE_Q1, 1), (FREE_Q3, 3))

# ----------------------------------------------------------------------------- candidates
#: theta1 candidate kinds: a certified simple root; a near root (a local minimum of |F| below
#: the tolerance-derived bound: a solution within the tolerance may sit there without an exact
#: root); an unresolved multiple root; a special theta1 of the degenerate case.
KIND_ROOT, KIND_NEAR, KIND_MULTIPLE, KIND_SPECIAL = 0, 1, 2, 3
KIND_NAMES = ("root", "near root", "multiple root", "special")

# ----------------------------------------------------------------------------- options
#: Layout of the option vector passed to the kernel (see IKOptions).
OPT_POSITION_TOL, OPT_ROTATION_TOL, OPT_APPROX_TOL, OPT_ORTHONORMAL_TOL, OPT_LIMIT_TOL = 0, 1, 2, 3, 4
N_OPT = 5

#: Two rows within this of each other in every joint [rad] are one solution.
DISTINCT_TOL = 1e-9

# ----------------------------------------------------------------------------- shared thresholds
#: A row is near the collinear (theta3/theta6) continuum when h, how far joint 3 is from free
#: (the size of z6 or (D - C) / a4 across z3) [1], is below this many times
#: sqrt(max(position_tol / reach, rotation_tol)): there the configurations within the tolerance
#: form a tube around the broken circle (its residual grows like reach x h^2 along it).
CONTINUUM_NEAR = 30.0
#: Configurations with h below this [1] are also started from other angles of joint 3 (the
#: closed forms place joint 3 poorly near the continuum).
RESTART_H = 1e-2
#: Both conditions on theta2 vanish (theta2 free) when their values at theta1 are below this
#: fraction of their coefficients' size; below NEAR_FREE2, near a theta2 continuum.
VANISH = 1e-9
NEAR_FREE2 = 1e-4

# ----------------------------------------------------------------------------- arm vector
#: Layout of the arm vector (:attr:`iik.ik.kernel.ArmData.vector`): a DH row is
#: ``(cos alpha, sin alpha, a, d, offset)`` (modified DH, Craig); a fixed transform is its
#: 3 x 4 block, row-major. The user chain is the arm as given (FK, Jacobian, residuals); the
#: solver chain is the canonical member of the class the closed forms work in (the user chain
#: itself, or the user chain read from the flange, for a reversed arm). The solver chain's
#: fixed transforms are stored inverted: the kernel maps a pose into the solver chain.
A_USER_DH, A_USER_BASE, A_USER_TOOL = 0, 30, 42
A_SOLVER_DH, A_SOLVER_BASE_INV, A_SOLVER_TOOL_INV = 54, 84, 96
A_REVERSED, A_LOWER, A_UPPER, A_REACH, A_SCALE = 108, 109, 115, 121, 122
#: The eliminant's arm constants (:func:`iik.ik.elimination.arm_constants`), N_CONST of them,
#: then their absolute values (the rounding-error scale).
A_CONST = 123
N_CONST = 28
A_CONST_ABS = A_CONST + N_CONST
N_ARM = A_CONST_ABS + N_CONST
