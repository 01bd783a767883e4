"""Arms as data: a six-joint revolute chain (modified DH, base and tool transforms, limits).

This module is the single source of truth for an arm's parameters. The thesis arm
(:data:`THESIS_ARM`) is built here from Table I and Table II; other arms come from a URDF
(:meth:`Arm.from_urdf`) or a DH table (:class:`Arm` itself). Every arm is checked against the
kinematic class the complete IK solves (:mod:`iik.kinematic_class`); outside it the
constructor raises :class:`~iik.kinematic_class.NotInClassError` with a near-miss report.

Units: metres, radians, seconds, newton metres.

Sources of the thesis arm:
    * l2..l5 are recovered from Appendix E (point A1, the diagonal of H*), see ``docs/ARM.md``.
    * **l1 = 0.300 m is an assumption.** It is a pure z offset that cancels from every
      derivative in Appendix E, so nothing in the text fixes it.
    * Joint limits: Table I. DH rows: Table II (Craig's modified convention; offsets -90, -90,
      +90 deg on joints 2, 4, 5 make the home pose q = 0; d6 = -l5).
    * Speeds: Section 3.2 gives 8.2 rad/s (square modules) and 1.2 rad/s (cylindrical modules)
      without saying which joint is which. The default, :data:`CONSERVATIVE_VELOCITY`, assumes
      the slower kind on every joint.
    * Accelerations are not given in the thesis; :data:`ASSUMED_ACCELERATION` is an assumption.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from .dh import DHRow, DHTable
from .errors import InvalidInputError
from .kinematic_class import (
    ANGLE_TOL,
    LENGTH_TOL,
    NotInClassError,
    SolverChain,
    axis_lines,
    chain_from_lines,
    solver_chain,
)
from .limits import LimitViolations, excess

__all__ = [
    "Arm",
    "ThesisLengths",
    "thesis_arm",
    "THESIS_ARM",
    "SQUARE_MODULE_SPEED",
    "CYLINDRICAL_MODULE_SPEED",
    "CONSERVATIVE_VELOCITY",
    "ASSUMED_ACCELERATION",
    "SQUARE_MODULE_TORQUE",
    "CYLINDRICAL_MODULE_TORQUE",
    "CONSERVATIVE_EFFORT",
    "LIMIT_TOL",
]

_DEG = np.pi / 180.0

#: Section 3.2: maximum speed of the square PowerCube modules [rad/s].
SQUARE_MODULE_SPEED = 8.2
#: Section 3.2: maximum speed of the cylindrical PowerCube modules [rad/s].
CYLINDRICAL_MODULE_SPEED = 1.2
#: Default per-joint speed limits [rad/s]: the slower module kind everywhere,
#: because the thesis does not say which joint is which kind.
CONSERVATIVE_VELOCITY = (CYLINDRICAL_MODULE_SPEED,) * 6
#: Assumed per-joint acceleration limits [rad/s^2] (not given in the thesis).
ASSUMED_ACCELERATION = (2.0,) * 6
#: Section 3.2: torque of the square PowerCube modules [N m].
SQUARE_MODULE_TORQUE = 372.0
#: Section 3.2: torque of the cylindrical PowerCube modules [N m].
CYLINDRICAL_MODULE_TORQUE = 239.0
#: Default per-joint effort limits [N m]: the weaker module kind everywhere,
#: matching :data:`CONSERVATIVE_VELOCITY` (the text does not say which joint is which).
CONSERVATIVE_EFFORT = (CYLINDRICAL_MODULE_TORQUE,) * 6

#: Numerical tolerance of every joint-limit test [rad]: a solution on a joint stop of a
#: near-singular pose may come out this far outside it (the pose fixes q only to
#: ~eps / sigma_min there). A margin *inside* the limits is a negative tolerance.
LIMIT_TOL = 1e-7

#: Table I, in degrees (display units; converted to rad below).
_TABLE_I_DEG = (
    (-160.0, 160.0),
    (-120.0, 95.0),
    (-160.0, 160.0),
    (-119.0, 119.0),
    (-119.0, 119.0),
    (-180.0, 180.0),
)

_IDENTITY = tuple(tuple(float(x) for x in row) for row in np.eye(4))


def _transform(T, name: str) -> tuple:
    """A rigid transform (4, 4) as nested tuples, validated."""
    try:
        A = np.asarray(T, dtype=float)
    except (TypeError, ValueError):
        raise InvalidInputError(name, "is not a 4x4 array of numbers") from None
    if A.shape != (4, 4) or not np.all(np.isfinite(A)):
        raise InvalidInputError(name, f"expected a finite (4, 4) transform, got shape {A.shape}")
    if (
        np.max(np.abs(A[3] - [0, 0, 0, 1])) > 1e-12
        or np.max(np.abs(A[:3, :3].T @ A[:3, :3] - np.eye(3))) > 1e-9
        or np.linalg.det(A[:3, :3]) < 0
    ):
        raise InvalidInputError(name, "is not a rigid transform (rotation block and bottom row [0, 0, 0, 1])")
    return tuple(tuple(float(x) for x in row) for row in A)


def _urdf_file(path, base_link: str, tip_link: str) -> str:
    """The absolute path of the URDF file ``path`` if the arm's base link is the file's root link
    (so the file's shapes sit in the arm's base frame); "" for URDF text or a chain from another link."""
    import os

    from .urdf_read import read_urdf_chain

    if isinstance(path, str) and path.lstrip().startswith("<"):
        return ""
    try:
        root = read_urdf_chain(path, None, tip_link).base_link
    except InvalidInputError:
        return ""
    return os.path.abspath(os.fspath(path)) if root == base_link else ""


def _cos_sin(x: float) -> tuple[float, float]:
    k = round(x / (math.pi / 2))
    if abs(x - k * (math.pi / 2)) <= ANGLE_TOL:
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[k % 4]
    return math.cos(x), math.sin(x)


@dataclass(frozen=True)
class ThesisLengths:
    """The link lengths l1..l5 [m] of an arm of the thesis's Table II form."""

    l1: float
    l2: float
    l3: float
    l4: float
    l5: float


@dataclass(frozen=True)
class Arm:
    """A six-joint revolute arm of the IK's class: ``tool pose = base . links(q) . tool``.

    Attributes:
        dh: The chain as a modified-DH table (Craig): rows, joint limits [rad] and speed
            limits [rad/s] (for the thesis arm: Table II, Table I, Sec 3.2).
        base: Fixed transform (4, 4) from the arm's base frame to DH frame 0 [m].
        tool: Fixed transform (4, 4) from the last DH frame to the tool frame [m].
        acceleration: Joint acceleration limits [rad/s^2].
        effort: Joint torque limits [N m].
        name: Display name (the registry name for shipped arms, :mod:`iik.arms`).
        joint_names: The joints' names (a URDF's, or ``joint1``..``joint6``).
        source: Where the numbers come from (a file and its origin).
        assumptions: Human-readable notes on which numbers are assumed.
        limits_name: What the joint limits are called in messages ("Table I" for the thesis arm).
        urdf: The URDF file the arm was read from (absolute path; "" for an arm built from a DH
            table, or changed after reading, e.g. :meth:`scaled`). Its collision shapes are the
            arm's body in the collision checks and the viewer (:mod:`iik.planning.robot_model`).
        solver: The canonical member of the class the IK solves in (derived; read from the
            base or from the flange), with the class report.
    """

    dh: DHTable
    base: tuple = _IDENTITY
    tool: tuple = _IDENTITY
    acceleration: tuple[float, ...] = ASSUMED_ACCELERATION
    effort: tuple[float, ...] = CONSERVATIVE_EFFORT
    name: str = "arm"
    joint_names: tuple[str, ...] = tuple(f"joint{i}" for i in range(1, 7))
    source: str = ""
    assumptions: tuple[str, ...] = field(default=())
    limits_name: str = "the joint limits"
    urdf: str = ""
    solver: SolverChain = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if not isinstance(self.dh, DHTable) or self.dh.convention != "modified" or self.dh.dof != 6:
            raise InvalidInputError("dh", "expected a modified-DH DHTable of 6 rows")
        object.__setattr__(self, "base", _transform(self.base, "base"))
        object.__setattr__(self, "tool", _transform(self.tool, "tool"))
        for k in ("acceleration", "effort"):
            vals = tuple(float(v) for v in getattr(self, k))
            if len(vals) != 6 or any(not math.isfinite(v) or v <= 0 for v in vals):
                raise InvalidInputError(k, "needs six positive finite values")
            object.__setattr__(self, k, vals)
        if len(self.joint_names) != 6:
            raise InvalidInputError("joint_names", "needs six names")
        if not isinstance(self.urdf, str):
            raise InvalidInputError("urdf", f"expected a URDF file's path as a string, got {self.urdf!r}")
        rows = [(r.alpha, r.a, r.d, r.offset) for r in self.dh.rows]
        object.__setattr__(
            self, "solver", solver_chain(rows, np.array(self.base), np.array(self.tool), argument=self.name)
        )

    # ------------------------------------------------------------------ constructors
    @classmethod
    def from_urdf(
        cls,
        path,
        base_link: str | None = None,
        tip_link: str | None = None,
        *,
        tool=None,
        name: str | None = None,
        acceleration=None,
    ) -> Arm:
        """The arm of a URDF's revolute chain (:func:`iik.urdf_read.read_urdf_chain`).

        Args:
            path: URDF file (or URDF text).
            base_link, tip_link: The chain's ends (defaults: the root link; the single leaf below
                the last revolute joint). Fixed joints in between are folded in.
            tool: An extra fixed transform after the tip link (4, 4) [m].
            name: Display name (default: the robot's name).
            acceleration: Joint acceleration limits [rad/s^2] (URDFs carry none; default 2.0).

        Raises:
            InvalidInputError: the file or chain is unusable (names the file and why).
            NotInClassError: the arm is outside the class (with the near-miss report).
        """
        from .urdf_read import read_urdf_chain

        ch = read_urdf_chain(path, base_link, tip_link)
        F = np.eye(4)
        pts, dirs = [], []
        for j in ch.joints:
            F = F @ j.origin
            pts.append(F[:3, 3].copy())
            dirs.append(F[:3, :3] @ j.axis)
        # a URDF joint at 0 is at its q = 0 frame, where the lines were taken: DH angle =
        # URDF angle + the row's offset (the angle between consecutive common normals there)
        end = F @ ch.tip @ (np.eye(4) if tool is None else np.asarray(_transform(tool, "tool")))
        size = float(sum(np.linalg.norm(j.origin[:3, 3]) for j in ch.joints) + np.linalg.norm(ch.tip[:3, 3]))
        rows, base, tl, _raw = chain_from_lines(
            np.array(pts), np.array(dirs), np.eye(4), end, size, LENGTH_TOL, ANGLE_TOL
        )
        missing = [j.name for j in ch.joints if j.velocity <= 0]
        if missing:
            raise InvalidInputError(ch.source, f"joints {missing} have no positive velocity limit")
        table = DHTable(
            rows=tuple(DHRow(alpha=a, a=aa, d=d, offset=o) for a, aa, d, o in rows),
            convention="modified",
            lower=tuple(j.lower for j in ch.joints),
            upper=tuple(j.upper for j in ch.joints),
            velocity=tuple(j.velocity for j in ch.joints),
        )
        notes = (
            ("Acceleration limits of 2.0 rad/s^2 are assumed (a URDF carries none).",)
            if acceleration is None
            else ()
        )
        effort = tuple(j.effort if j.effort > 0 else 1.0 for j in ch.joints)
        try:
            return cls(
                dh=table,
                base=base,
                tool=tl,
                acceleration=ASSUMED_ACCELERATION if acceleration is None else tuple(acceleration),
                effort=effort,
                name=name or ch.robot,
                joint_names=tuple(j.name for j in ch.joints),
                source=f"{ch.source} ({ch.base_link} -> {ch.tip_link})",
                assumptions=notes,
                urdf=_urdf_file(path, ch.base_link, ch.tip_link),
            )
        except NotInClassError as exc:  # name the file, as every other error of a URDF does
            raise NotInClassError(ch.source, exc.reports) from None

    # ------------------------------------------------------------------ variants
    def with_limits(
        self,
        *,
        lower=None,
        upper=None,
        velocity=None,
        acceleration=None,
        effort=None,
        name: str | None = None,
    ) -> Arm:
        """This arm with other joint limits [rad, rad/s, rad/s^2, N m] (None: unchanged; other position
        limits are no longer called by the old limits' name)."""
        dh = dataclasses.replace(
            self.dh,
            lower=tuple(self.dh.lower if lower is None else lower),
            upper=tuple(self.dh.upper if upper is None else upper),
            velocity=tuple(self.dh.velocity if velocity is None else velocity),
        )
        return dataclasses.replace(
            self,
            dh=dh,
            acceleration=self.acceleration if acceleration is None else tuple(acceleration),
            effort=self.effort if effort is None else tuple(effort),
            name=self.name if name is None else name,
            limits_name=self.limits_name if lower is None and upper is None else "the joint limits",
        )

    def scaled(self, factor: float, name: str | None = None) -> Arm:
        """This arm with every length (DH a, d and the base and tool translations) times ``factor``."""
        if not (isinstance(factor, (int, float)) and math.isfinite(factor) and factor > 0):
            raise InvalidInputError("factor", f"must be a positive finite number, got {factor!r}")
        rows = tuple(dataclasses.replace(r, a=r.a * factor, d=r.d * factor) for r in self.dh.rows)
        base, tool = np.array(self.base), np.array(self.tool)
        base[:3, 3] *= factor
        tool[:3, 3] *= factor
        return dataclasses.replace(
            self,
            dh=dataclasses.replace(self.dh, rows=rows),
            base=base,
            tool=tool,
            name=name or f"{self.name} x{factor:g}",
            urdf="",  # the file's shapes have the old lengths
        )

    # ------------------------------------------------------------------ limits
    @property
    def lower(self) -> tuple[float, ...]:
        """Lower joint limits [rad]."""
        return self.dh.lower

    @property
    def upper(self) -> tuple[float, ...]:
        """Upper joint limits [rad]."""
        return self.dh.upper

    @property
    def velocity(self) -> tuple[float, ...]:
        """Joint speed limits [rad/s]."""
        return self.dh.velocity

    @property
    def q_min(self) -> np.ndarray:
        """Lower joint limits [rad], shape (6,)."""
        return np.array(self.dh.lower)

    @property
    def q_max(self) -> np.ndarray:
        """Upper joint limits [rad], shape (6,)."""
        return np.array(self.dh.upper)

    def dh_table(self) -> DHTable:
        """The chain's modified-DH table (Table II for the thesis arm): a new object each call."""
        return dataclasses.replace(self.dh)

    def within_limits(self, q, tol: float = LIMIT_TOL) -> np.ndarray:
        """Boolean (n,) or scalar: is each ``q`` [rad] inside the limits (Table I)?

        ``limit_violations(q, margin=-tol).within``, without listing the violations: the same
        test (:func:`iik.limits.excess`). ``tol`` [rad] widens the limits (default
        :data:`LIMIT_TOL`, rounding at a stop); a negative ``tol`` is a margin inside them.
        """
        from .validation import as_joints

        qb, batched = as_joints(q, "q")
        ok = np.all(excess(qb, self.q_min, self.q_max, -tol) <= 0.0, axis=1)
        return ok if batched else bool(ok[0])

    def limit_violations(self, q, margin: float = 0.0, *, joints=None) -> LimitViolations:
        """The joint values of ``q`` [rad] beyond the limits (Table I) less ``margin`` [rad].

        The project's one joint-limit test (:mod:`iik.limits`): the executor's margin, the
        simulated modules' start, the timing's samples and the viewer ask it. A negative
        ``margin`` is a tolerance outside the limits.

        Args:
            q: One configuration (k,) or a batch (n, k) [rad].
            margin: Kept inside each limit [rad].
            joints: The joint (from 0) of each of the k columns; default all six, in order.

        Returns:
            :class:`~iik.limits.LimitViolations`: a sequence of
            :class:`~iik.limits.LimitViolation` (sample, joint, value, limits, amount), true if
            any; ``.within`` per configuration.
        """
        from .validation import as_joints

        cols = tuple(range(6)) if joints is None else tuple(int(j) for j in joints)
        if not cols or any(j not in range(6) for j in cols):
            raise InvalidInputError("joints", f"expected joint indices in 0..5, got {joints!r}")
        if not (isinstance(margin, (int, float)) and math.isfinite(margin)):
            raise InvalidInputError("margin", f"expected a finite number [rad], got {margin!r}")
        qb, batched = as_joints(q, "q", dof=len(cols))
        lower, upper = self.q_min[list(cols)], self.q_max[list(cols)]
        return LimitViolations(q=qb, excess=excess(qb, lower, upper, float(margin)), joints=cols, lower=lower,
                               upper=upper, margin=float(margin), batched=batched)

    # ------------------------------------------------------------------ geometry
    @property
    def reach(self) -> float:
        """An upper bound on the distance of the tool point from the base origin [m]: each
        link moves the next frame's origin by at most |a| + |d|, whatever the angles."""
        return float(
            np.linalg.norm(np.array(self.base)[:3, 3])
            + sum(abs(r.a) + abs(r.d) for r in self.dh.rows)
            + np.linalg.norm(np.array(self.tool)[:3, 3])
        )

    @property
    def thesis_lengths(self) -> ThesisLengths:
        """l1..l5 [m] of an arm of the thesis's Table II form (identity base and tool).

        Raises:
            InvalidInputError: the arm is not of that form (the thesis's formulas of Sec 3.4,
                3.5 and App. D are written for it).
        """
        h = math.pi / 2
        pattern = (
            (0.0, 0.0, None, 0.0),
            (-h, None, 0.0, -h),
            (-h, 0.0, None, 0.0),
            (-h, 0.0, 0.0, -h),
            (0.0, None, 0.0, h),
            (-h, 0.0, None, 0.0),
        )
        ok = np.allclose(np.array(self.base), np.eye(4)) and np.allclose(np.array(self.tool), np.eye(4))
        for r, pat in zip(self.dh.rows, pattern, strict=True):
            for v, p in zip((r.alpha, r.a, r.d, r.offset), pat, strict=True):
                ok = ok and (p is None or abs(v - p) <= 1e-12)
        if not ok:
            raise InvalidInputError("arm", f"{self.name!r} is not of the thesis's Table II form")
        r = self.dh.rows
        return ThesisLengths(r[0].d, r[1].a, r[2].d, r[4].a, -r[5].d)

    @property
    def l1(self) -> float:
        return self.thesis_lengths.l1

    @property
    def l2(self) -> float:
        return self.thesis_lengths.l2

    @property
    def l3(self) -> float:
        return self.thesis_lengths.l3

    @property
    def l4(self) -> float:
        return self.thesis_lengths.l4

    @property
    def l5(self) -> float:
        return self.thesis_lengths.l5

    @property
    def lengths(self) -> np.ndarray:
        """``[l1, l2, l3, l4, l5]`` [m] (thesis form only, :attr:`thesis_lengths`)."""
        t = self.thesis_lengths
        return np.array([t.l1, t.l2, t.l3, t.l4, t.l5])

    def kernel_vector(self) -> np.ndarray:
        """The arm as the IK kernel's float vector (:mod:`iik.ik.layout`, ``A_*``)."""
        from .ik import layout as L
        from .ik.elimination import arm_constants

        v = np.zeros(L.N_ARM)
        for i, r in enumerate(self.dh.rows):
            v[L.A_USER_DH + 5 * i : L.A_USER_DH + 5 * i + 5] = (*_cos_sin(r.alpha), r.a, r.d, r.offset)
        v[L.A_USER_BASE : L.A_USER_BASE + 12] = np.array(self.base)[:3].ravel()
        v[L.A_USER_TOOL : L.A_USER_TOOL + 12] = np.array(self.tool)[:3].ravel()
        s = self.solver
        for i, r in enumerate(s.rows):
            v[L.A_SOLVER_DH + 5 * i : L.A_SOLVER_DH + 5 * i + 5] = r
        v[L.A_SOLVER_BASE_INV : L.A_SOLVER_BASE_INV + 12] = np.linalg.inv(s.base)[:3].ravel()
        v[L.A_SOLVER_TOOL_INV : L.A_SOLVER_TOOL_INV + 12] = np.linalg.inv(s.tool)[:3].ravel()
        v[L.A_REVERSED] = 1.0 if s.reversed else 0.0
        v[L.A_LOWER : L.A_LOWER + 6], v[L.A_UPPER : L.A_UPPER + 6] = self.q_min, self.q_max
        v[L.A_REACH] = self.reach
        v[L.A_SCALE] = self.reach
        (ca1, sa1, a1, d2, _), (ca2, sa2, _, d3, _), r5 = s.rows[1], s.rows[2], s.rows[4]
        k = arm_constants(ca1, sa1, a1, d2, ca2, sa2, d3, r5[2]).vector
        v[L.A_CONST : L.A_CONST + L.N_CONST] = k
        v[L.A_CONST_ABS : L.A_CONST_ABS + L.N_CONST] = np.abs(k)
        return v

    def joint_axes(self, q=None):
        """Joint axis lines at q (default 0): points (6, 3) [m] and unit directions (6, 3) in
        the base frame."""
        rows = [(*_cos_sin(r.alpha), r.a, r.d, r.offset) for r in self.dh.rows]
        pts, dirs, _ = axis_lines(rows, np.array(self.base), np.array(self.tool), q)
        return pts, dirs


def _table_i() -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Table I's lower and upper limits [rad]."""
    return tuple(lo * _DEG for lo, _ in _TABLE_I_DEG), tuple(hi * _DEG for _, hi in _TABLE_I_DEG)


def thesis_arm(
    l1: float,
    l2: float,
    l3: float,
    l4: float,
    l5: float,
    *,
    lower=None,
    upper=None,
    velocity=CONSERVATIVE_VELOCITY,
    acceleration=ASSUMED_ACCELERATION,
    effort=CONSERVATIVE_EFFORT,
    name: str = "arm of the thesis's form",
    assumptions: tuple[str, ...] = (),
) -> Arm:
    """An arm of the thesis's Table II form with link lengths l1..l5 [m] (Table I limits by default)."""
    for k, val in (("l1", l1), ("l2", l2), ("l3", l3), ("l4", l4), ("l5", l5)):
        if not isinstance(val, (int, float)) or not math.isfinite(val):
            raise InvalidInputError(k, "must be finite")
    for k, val in (("l3", l3), ("l4", l4), ("l5", l5)):
        if val <= 0:
            raise InvalidInputError(k, "must be positive")
    lower = tuple(lo * _DEG for lo, _ in _TABLE_I_DEG) if lower is None else tuple(lower)
    upper = tuple(hi * _DEG for _, hi in _TABLE_I_DEG) if upper is None else tuple(upper)
    h = np.pi / 2
    rows = (
        DHRow(alpha=0.0, a=0.0, d=l1, offset=0.0),  # Table II row 1
        DHRow(alpha=-h, a=l2, d=0.0, offset=-h),  # row 2: theta2 - 90 deg
        DHRow(alpha=-h, a=0.0, d=l3, offset=0.0),  # row 3
        DHRow(alpha=-h, a=0.0, d=0.0, offset=-h),  # row 4: theta4 - 90 deg
        DHRow(alpha=0.0, a=l4, d=0.0, offset=+h),  # row 5: theta5 + 90 deg
        DHRow(alpha=-h, a=0.0, d=-l5, offset=0.0),  # row 6: d6 = -l5
    )
    table = DHTable(rows=rows, convention="modified", lower=lower, upper=upper, velocity=tuple(velocity))
    return Arm(
        dh=table,
        acceleration=tuple(acceleration),
        effort=tuple(effort),
        name=name,
        source="Mondragon Sanchez 2012, Table I and Table II",
        assumptions=assumptions,
        limits_name="Table I" if (table.lower, table.upper) == _table_i() else "the joint limits",
    )


THESIS_ARM = thesis_arm(
    l1=0.300,  # ASSUMED: not fixed by the text (cancels in App. E); see ARM.md
    l2=0.122,  # App. E, A1: H*(1,1) = 1646.8
    l3=0.339,  # App. E, A1: H*(2,2) = 2705.2
    l4=0.175,  # App. E, A1: H*(4,4) = 1898
    l5=0.265,  # App. E, A1: H*(5,5) = 1143.1
    name="thesis PowerCube arm (Mondragon Sanchez 2012)",
    assumptions=(
        "l1 = 0.300 m is assumed (a z offset the text never fixes).",
        "Joint speed limits default to 1.2 rad/s on every joint (the slower module "
        "kind of Sec 3.2); the text does not say which joint is which kind.",
        "Acceleration limits of 2.0 rad/s^2 are assumed (not in the thesis).",
        "Joint torque limits default to 239 N m on every joint (the weaker module "
        "kind of Sec 3.2), for the same reason as the speeds.",
    ),
)
