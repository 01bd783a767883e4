"""The frozen results of inverse-kinematics queries: one pose (:class:`IKResult`), a batch
as padded arrays (:class:`IKBatch`), and the description of a continuum (:class:`Continuum`)."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import UnreachablePoseError
from .angles import wrap

__all__ = ["IKResult", "IKBatch", "Continuum", "Certificate"]


def _ro(a, dtype=float) -> np.ndarray:
    arr = np.array(a, dtype=dtype, copy=True)
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True)
class Continuum:
    """A row of an :class:`IKResult` that stands for a one-parameter family of configurations
    reaching the pose (within the tolerances).

    Kinds (``docs/IK_CLASS.md`` derives them):

    * ``"collinear"``: two joint axes are collinear (for the thesis arm joints 3 and 6 when
      theta4 = 0 and theta4 + theta5 = 0, mod pi): moving the free joint by an angle and the
      coupled joint by ``sign`` times it leaves the pose unchanged, so
      ``theta_free - sign * theta_coupled`` is fixed (:attr:`value`). Every member is exact.
    * ``"theta1"``: the eliminant vanishes identically (e.g. the wrist centre on the joint-1
      axis with theta4 = 0): every angle of the free joint has a configuration; the others
      follow it along a curve (:meth:`member` follows it).
    * ``"theta2"``: both conditions on theta2 vanish at one theta1 (the wrist point on axis 2;
      impossible for the thesis arm): joint 2 is free, the others follow it.
    * ``"numerical"``: the pose is within about (tolerance / reach)^(1/2) of a collinear
      continuum: the configurations within the tolerance form a thin tube around the broken
      circle, in which the pose fixes the free joint only loosely. :meth:`member` refits the
      other joints with the free one held; :attr:`interval` is where that stays within the
      tolerance. With no coupled joint (free joint 1, or 6 for an arm read from the flange):
      a band of joint 1 beside a theta1 continuum (the wrist point just off the joint-1 axis),
      followed the same way.

    Attributes:
        kind: ``"collinear"``, ``"theta1"``, ``"theta2"`` or ``"numerical"``.
        free_joint: The joint (1-based) that moves freely.
        coupled_joint: The joint (1-based) that follows it with ``sign`` (collinear and
            numerical kinds), else None (also for a numerical band of joint 1).
        sign: +1 or -1 (or 0 for the theta1 kind).
        representative: The row of the result (6,) [rad]; inside the limits whenever any
            member found is.
        limits_interval: The feasible interval of the free joint inside the joint limits
            (``(lo, hi)`` [rad], the piece containing the representative; ``(nan, nan)`` if
            there is none), when the kernel computed it (collinear kind); else None and
            :attr:`interval` computes it on first use.
        arm, pose, tolerance: What :meth:`member` solves (the arm, the pose as given (4, 4) and
            (position_tol, rotation_tol)).
        marches: The members followed so far along the continuum, kept for later calls
            (filled on demand by :mod:`iik.ik.members`; not part of the value).
    """

    kind: str
    free_joint: int
    coupled_joint: int | None
    sign: int
    representative: np.ndarray
    limits_interval: tuple[float, float] | None = None
    arm: object = field(default=None, compare=False, repr=False)
    pose: np.ndarray | None = field(default=None, compare=False, repr=False)
    tolerance: tuple[float, float] = (1e-10, 1e-10)
    marches: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    @property
    def fixed(self) -> str:
        """The fixed combination as text, e.g. ``"theta3 - theta6"`` (collinear kind)."""
        if self.coupled_joint is None:
            return f"theta{self.free_joint} free"
        return f"theta{self.free_joint} {'-' if self.sign > 0 else '+'} theta{self.coupled_joint}"

    @property
    def band(self) -> bool:
        """Is this a band of joint 1 beside a theta1 continuum (kind ``"numerical"`` without a
        coupled joint)?"""
        return self.kind == "numerical" and self.coupled_joint is None

    @property
    def value(self) -> float:
        """``theta_free - sign * theta_coupled`` [rad], wrapped (the collinear kind's invariant)."""
        if self.coupled_joint is None:
            return math.nan
        r = self.representative
        x = float(r[self.free_joint - 1] - self.sign * r[self.coupled_joint - 1])
        return wrap(x)

    def member(self, theta: float) -> np.ndarray:
        """The member with the free joint at ``theta`` [rad] (6,) (angles wrapped)."""
        theta = float(theta)
        if self.kind == "collinear":
            q = np.array(self.representative, dtype=float)
            j, k = self.free_joint - 1, self.coupled_joint - 1
            q[k] = wrap(q[k] + self.sign * (theta - q[j]))
            q[j] = theta
            return q
        from .members import follow

        return follow(self, np.array([theta]))[0][0]

    @property
    def interval(self) -> tuple[float, float]:
        """The values of the free joint (``(lo, hi)`` [rad]) whose members reach the pose and
        lie inside the joint limits: the piece containing the representative (``(nan, nan)``
        if none)."""
        if self.limits_interval is not None:
            return self.limits_interval
        cached = self.__dict__.get("_interval")
        if cached is None:
            from .members import feasible_interval

            cached = feasible_interval(self)
            self.__dict__["_interval"] = cached
        return cached


@dataclass(frozen=True)
class Certificate:
    """How the complete IK solved a pose and what it proved (:mod:`iik.ik.kernel`).

    Attributes:
        path: ``"double"`` (every real root of the eliminant isolated with certified signs in
            double precision), ``"extended"`` (clusters of roots re-expanded and separated in
            double-double), ``"multiple-root"`` (a cluster unresolved even there: roots that
            coincide to ~1e-15, returned as one), ``"degenerate"`` (the eliminant vanishes: a
            theta1 continuum), ``"reference"`` (it vanishes within its rounding but no theta1
            continuum reaches the pose: rows merged with the NumPy reference's, not certified),
            or ``"numpy"`` for the NumPy methods.
        certified: Every certified root of the eliminant gave a configuration within the
            tolerances (else ``reason`` says what failed).
        roots: Real roots of the eliminant found; ``clusters``: clusters re-expanded;
            ``near``: near roots tried (minima of |F| within the tolerance-derived bound).
        reason: Empty when certified. For the NumPy methods (never certified): empty, or that
            more distinct solutions were found than MAX_SOLUTIONS rows hold (some left out).
    """

    path: str = "numpy"
    certified: bool = False
    roots: int = 0
    clusters: int = 0
    near: int = 0
    reason: str = ""


@dataclass(frozen=True)
class IKResult:
    """All inverse-kinematics solutions of one pose.

    Attributes:
        q: Joint angles (k, 6) [rad], each wrapped to (-pi, pi], or turned by 2 pi into the
            joint limits where the wrapped angle is outside them and the turned one inside
            (limits not centred on 0, e.g. the CRX's joint 3, -71 .. 251 deg); k may be 0.
            Deterministic order (lexicographic in the wrapped angles rounded to 1e-9 rad).
        position_residual: (k,) |p_fk(q) - p| [m], against the pose as given.
        rotation_residual: (k,) rotation angle between R_fk(q) and R as given [rad]
            (:func:`iik.rotations.rotation_angle`; includes ``rotation_projection``).
        within_limits: (k,) bool, inside the arm's joint limits (Table I,
            :meth:`iik.arm.Arm.within_limits`).
        free_joints: Per solution, the joints (1-based) of a continuum of solutions:
            ``(3, 6)`` when joints 3 and 6 are collinear (theta4 = theta5 = 0: only
            theta3 - theta6 is fixed), ``(1, 6)`` when joints 1 and 6 are; the row is then
            one representative, described by ``continua``. ``(3, 6)`` without a ``continua``
            entry marks a numerical continuum: near joints 3 and 6 being collinear
            (|sin theta4|, |sin(theta4 + theta5)| <= 1e-4) the configurations within the
            tolerance form a thin family in which theta3 is only loosely fixed, and the row is
            one of them. Empty tuple for isolated solutions.
        reason: Why there is no solution, or why the solutions are approximate; else "".
        method: ``"complete"``, ``"reference"`` or ``"thesis"``.
        info: Free-form extras (not compared).
        approximate: (k,) bool: True where the row does not reach the pose within the
            tolerances but within ``IKOptions.approximate_tol`` (only returned when no row
            reaches it: then every row is approximate, least residual first in ``reason``).
        continua: Per solution, a tuple of :class:`Continuum` (one per free joint, empty for
            isolated solutions).
        rotation_projection: Frobenius distance from the given rotation block to the
            rotation that was solved (its nearest rotation); 0 for an orthonormal input.
        certificate: Which path the pose took and what the kernel proved (:class:`Certificate`).
    """

    q: np.ndarray
    position_residual: np.ndarray
    rotation_residual: np.ndarray
    within_limits: np.ndarray
    free_joints: tuple[tuple[int, ...], ...] = ()
    reason: str = ""
    method: str = "complete"
    info: dict = field(default_factory=dict, compare=False, repr=False)
    approximate: np.ndarray | None = None
    continua: tuple[tuple[Continuum, ...], ...] = ()
    rotation_projection: float = 0.0
    certificate: Certificate = field(default_factory=Certificate)

    def __post_init__(self) -> None:
        object.__setattr__(self, "q", _ro(np.reshape(self.q, (-1, 6))))
        k = len(self.q)
        object.__setattr__(self, "position_residual", _ro(self.position_residual))
        object.__setattr__(self, "rotation_residual", _ro(self.rotation_residual))
        object.__setattr__(self, "within_limits", _ro(self.within_limits, bool))
        approx = np.zeros(k, bool) if self.approximate is None else self.approximate
        object.__setattr__(self, "approximate", _ro(approx, bool))
        fj = tuple(tuple(int(j) for j in f) for f in self.free_joints) or ((),) * k
        object.__setattr__(self, "free_joints", fj)
        object.__setattr__(self, "continua", tuple(tuple(c) for c in self.continua) or ((),) * k)
        object.__setattr__(self, "rotation_projection", float(self.rotation_projection))

    @classmethod
    def trusted(
        cls,
        q,
        position_residual,
        rotation_residual,
        within_limits,
        free_joints,
        reason,
        method,
        approximate,
        continua,
        rotation_projection,
        certificate=None,
    ) -> IKResult:
        """Build without copying or checking, for the solvers: read-only arrays ((k, 6), (k,),
        (k,), (k,) bool, (k,) bool) and per-row ``free_joints`` / ``continua`` tuples. (Item by
        item into the instance dict: a single pose's call is made of steps like this one.)"""
        self = object.__new__(cls)
        d = self.__dict__
        d["q"], d["position_residual"], d["rotation_residual"] = q, position_residual, rotation_residual
        d["within_limits"], d["free_joints"], d["reason"] = within_limits, free_joints, reason
        d["method"], d["info"], d["approximate"] = method, {}, approximate
        d["continua"], d["rotation_projection"] = continua, rotation_projection
        d["certificate"] = certificate if certificate is not None else Certificate()
        return self

    def __len__(self) -> int:
        return len(self.q)

    def rows(self, keep) -> IKResult:
        """The result with only the rows ``keep`` (indices or a (k,) bool mask), in that order;
        every other field unchanged."""
        idx = np.arange(self.count)[np.asarray(keep)]
        return dataclasses.replace(
            self, q=self.q[idx], position_residual=self.position_residual[idx],
            rotation_residual=self.rotation_residual[idx], within_limits=self.within_limits[idx],
            approximate=self.approximate[idx], free_joints=tuple(self.free_joints[i] for i in idx),
            continua=tuple(self.continua[i] for i in idx),
        )

    @property
    def count(self) -> int:
        """Number of solutions k."""
        return len(self.q)

    @property
    def has_continuum(self) -> bool:
        """True if any returned row represents a continuum of solutions."""
        return any(self.free_joints)

    @property
    def is_approximate(self) -> bool:
        """True if the rows only approach the pose (see ``approximate``)."""
        return bool(self.count and self.approximate.all())

    def raise_if_unreachable(self) -> IKResult:
        """Return self, or raise :class:`~iik.errors.UnreachablePoseError` (with ``reason``)
        if there is no solution (within the limits, if they were asked for).

        The IK itself never raises for an unreachable pose (nor does :func:`iik.dexterity`);
        this is the request to.
        """
        if self.count == 0:
            raise UnreachablePoseError(self.reason or "no solution")
        return self

    def to_dict(self, degrees: bool = False) -> dict:
        """JSON-ready dict; angles in rad (or degrees if ``degrees``), residuals in m / rad."""
        conv = math.degrees if degrees else float

        def cont(c: Continuum) -> dict:
            return {
                "kind": c.kind,
                "free_joint": c.free_joint,
                "coupled_joint": c.coupled_joint,
                "fixed": c.fixed,
                "value": None if math.isnan(c.value) else conv(c.value),
                "interval": [conv(v) for v in c.interval],
            }

        return {
            "method": self.method,
            "count": self.count,
            "reason": self.reason,
            "angle_unit": "deg" if degrees else "rad",
            "rotation_projection": self.rotation_projection,
            "path": self.certificate.path,
            "certified": self.certificate.certified,
            "solutions": [
                {
                    "q": [conv(v) for v in self.q[i].tolist()],
                    "position_residual_m": float(self.position_residual[i]),
                    "rotation_residual_rad": float(self.rotation_residual[i]),
                    "within_limits": bool(self.within_limits[i]),
                    "approximate": bool(self.approximate[i]),
                    "free_joints": list(self.free_joints[i]),
                    "continua": [cont(c) for c in self.continua[i]],
                }
                for i in range(self.count)
            ],
        }


@dataclass(frozen=True)
class IKBatch:
    """All solutions of n poses as padded arrays (read-only): the array form of
    :func:`iik.solve_many` (the same rows, flags, continuum codes and certificate), for code
    that wants no Python object per pose.

    Row ``i`` of pose ``n`` is valid for ``i < count[n]``; the rest is padding (NaN / False / 0).

    Attributes:
        q: (n, 16, 6) [rad].
        count: (n,) rows returned per pose.
        position_residual, rotation_residual: (n, 16) against the poses as given [m], [rad].
        within_limits, approximate: (n, 16) bool, as in :class:`IKResult`.
        free: (n, 16) int continuum kind (:mod:`iik.ik.layout` ``FREE_*``; 0 for isolated rows;
            ``FREE_BAND`` for a band of joint 1 beside a theta1 continuum).
        info: (n, 16, N_INFO) the kernel's row data (:mod:`iik.ik.layout` ``I_*``). For a pose
            whose rows :func:`iik.solve_many` sorts (theta1 continua and bands, continuum rows
            moved into the limits) the rows are solve_many's: I_KIND and I_H3 are NaN there.
        total: (n,) solutions that reach the pose exactly, before the joint-limit filter.
        rotation_projection: (n,) as in :class:`IKResult`.
        closest: (n, 2) least position [m] and rotation [rad] residuals of the candidates
            examined (inf if none): how far an unreachable pose is from the nearest one found.
        path, certified: (n,) the path code (``PATH_*``; ``PATH_REFERENCE`` for the slow path)
            and whether the certificate holds, as in :attr:`IKResult.certificate`.
        method: The method used.
    """

    q: np.ndarray
    count: np.ndarray
    position_residual: np.ndarray
    rotation_residual: np.ndarray
    within_limits: np.ndarray
    approximate: np.ndarray
    free: np.ndarray
    info: np.ndarray
    total: np.ndarray
    rotation_projection: np.ndarray
    closest: np.ndarray
    path: np.ndarray
    certified: np.ndarray
    method: str = "complete"

    def __len__(self) -> int:
        return len(self.count)
