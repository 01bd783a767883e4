"""The recovery table of issue 17: per adversarial family, how often the complete IK returns the
generating configuration q*, and how its answers compare with the dense multi-start oracle
and with the NumPy reference.

    python benchmarks/bench_ik.py --recovery 2000 --arm crx10ia

Per family (:mod:`verification.testing.families`, any shipped arm): ``n`` configurations q*
(seeded), poses fk(q*), solved by the kernel with ``within_limits=False``:

* **q* found**: the answer contains q* (:func:`~verification.testing.completeness.contains`);
  **missed, certified**: q* missed while the certificate held (a silent loss: issue 17's
  "never silently fewer" broken);
  **within limits**: for the q* inside the joint limits, the default call (limits applied)
  contains it too;
* **wrong rows**: rows that miss the pose by more than the tolerance by the oracle's own
  forward kinematics (NumPy DH product, not the kernel's), or, for a row flagged approximate
  (returned only when no row reaches the pose), by more than ``IKOptions.approximate_tol``;
* **continua**: poses with a continuum row flagged (by kind);
* **uncertified**: poses whose certificate does not hold (each with its reason); **paths**: how
  often each certificate path ran;
* **oracle**: on every ``oracle_every``-th pose, the dense multi-start Levenberg-Marquardt
  search (:mod:`verification.oracles.multistart`, ``starts`` starts): its solutions the
  answer does not contain (missed), and how many of them on poses whose certificate held (a
  silent loss);
* **reference**: on every ``reference_every``-th pose, the NumPy reference; poses whose
  solution sets differ (:func:`~verification.testing.completeness.agreement`).

Units: radians, metres.
"""

from __future__ import annotations

import sys
from collections import Counter
from dataclasses import dataclass, field

import numpy as np

import iik
from iik.arm import Arm
from verification.oracles.multistart import OracleOptions, multistart_ik, pose_residuals_np
from verification.testing.completeness import agreement, contains, coverage
from verification.testing.families import FAMILIES, Family, FamilyEmpty

__all__ = ["RecoveryOptions", "RecoveryRow", "recovery", "recovery_table", "print_recovery", "pose_stats",
           "PoseStats"]

_TOL = (1e-10, 1e-10)


@dataclass(frozen=True)
class RecoveryOptions:
    """Sizes of :func:`recovery`.

    Attributes:
        n: Poses per family.
        oracle_every: The oracle runs on every k-th pose (0: never).
        starts: Oracle starts per pose (the issue asks for >= 200).
        reference_every: The reference runs on every k-th pose (0: never).
        seed: Seed of the configurations.
    """

    n: int = 2000
    oracle_every: int = 50
    starts: int = 256
    reference_every: int = 20
    seed: int = 20120101


@dataclass(frozen=True)
class RecoveryRow:
    """One family's line of the recovery table (see the module docstring).

    ``examples`` holds up to three silent losses (q* missed while the certificate held) as
    (index of the pose in the family's sample, q* as a list), to replay them.
    """

    family: str
    poses: int
    found: int = 0
    silent: int = 0
    inside: int = 0
    found_inside: int = 0
    wrong_rows: int = 0
    continua: dict = field(default_factory=dict)
    uncertified: int = 0
    paths: dict = field(default_factory=dict)
    oracle_poses: int = 0
    oracle_solutions: int = 0
    missed_vs_oracle: int = 0
    missed_vs_oracle_certified: int = 0
    reference_poses: int = 0
    reference_differs: int = 0
    empty: str = ""
    examples: tuple = ()


@dataclass(frozen=True)
class PoseStats:
    """What the recovery table counts for one pose (module docstring).

    Attributes:
        found: The answer contains q*. inside: q* is inside the joint limits. found_inside: the
            default call (limits applied) contains it too. wrong: Rows that miss the pose.
        kinds: Kinds of the continua flagged.
    """

    found: bool
    inside: bool
    found_inside: bool
    wrong: int
    kinds: tuple[str, ...]


def pose_stats(arm: Arm, q, T, r) -> PoseStats:
    """The counts of one pose: q* (6,) [rad], its pose T (4, 4) [m] and the kernel's answer r."""
    found = contains(r, q, T, arm, _TOL)
    inside = bool(arm.within_limits(q, tol=-1e-6))
    found_in = inside and contains(iik.solve(T, arm), q, T, arm, _TOL)
    pres, rres = pose_residuals_np(arm, r.q, T) if r.count else (np.zeros(0), np.zeros(0))
    tp, tr = (np.where(r.approximate, iik.ik.DEFAULT_OPTIONS.approximate_tol, t) for t in _TOL)
    wrong = int(np.count_nonzero((pres > tp) | (rres > tr)))
    return PoseStats(found, inside, found_in, wrong, tuple(sorted({c.kind for cs in r.continua for c in cs})))


def recovery(fam: Family, arm: Arm, opts: RecoveryOptions = RecoveryOptions()) -> RecoveryRow:
    """The recovery line of one family for one arm."""
    rng = np.random.default_rng([opts.seed, [f.name for f in FAMILIES].index(fam.name)])
    try:
        Q = fam.sample(arm, rng, opts.n)
    except FamilyEmpty as exc:
        return RecoveryRow(fam.name, 0, empty=str(exc))
    Ts = iik.fk(Q, arm)
    results = iik.solve_many(Ts, arm, within_limits=False)
    c = Counter()
    kinds, paths, examples = Counter(), Counter(r.certificate.path for r in results), []
    for i, (q, T, r) in enumerate(zip(Q, Ts, results, strict=True)):
        st = pose_stats(arm, q, T, r)
        cert = r.certificate.certified
        c.update(found=st.found, inside=st.inside, found_inside=st.found_inside, wrong=st.wrong,
                 uncert=not cert, silent=cert and not st.found)
        kinds.update(st.kinds)
        c["continua"] += bool(st.kinds)
        if cert and not st.found and len(examples) < 3:
            examples.append((i, q.tolist()))
        if opts.oracle_every and i % opts.oracle_every == 0:
            o = multistart_ik(T, arm, OracleOptions(starts=opts.starts, seed=i))
            missed = len(coverage(r, o, T, arm, _TOL).missed)
            c.update(oracle=1, oracle_sols=len(o.q), missed=missed, missed_cert=missed if cert else 0)
        if opts.reference_every and i % opts.reference_every == 0:
            ref = iik.solve(T, arm, method="reference", within_limits=False)
            c.update(ref=1, ref_diff=not agreement(r, ref, T, arm, _TOL).same)
    return RecoveryRow(
        fam.name, len(Q), c["found"], c["silent"], c["inside"], c["found_inside"], c["wrong"],
        {"any": c["continua"], **dict(kinds)}, c["uncert"], dict(paths), c["oracle"], c["oracle_sols"],
        c["missed"], c["missed_cert"], c["ref"], c["ref_diff"], "", tuple(examples),
    )


def recovery_table(arm: Arm, opts: RecoveryOptions = RecoveryOptions(), families=FAMILIES, out=None) -> list:
    """:func:`recovery` for every family (printing each line as it comes when ``out`` is given)."""
    rows = []
    for fam in families:
        rows.append(recovery(fam, arm, opts))
        if out is not None:
            print_recovery([rows[-1]], out, header=len(rows) == 1)
    if out is not None:
        for r in rows:
            for i, q in r.examples:
                print(f"silent loss: {r.family}, pose {i} of the sample (seed {opts.seed}): q* = {q}",
                      file=out)
    return rows


def _pct(a: int, b: int) -> str:
    return f"{100.0 * a / b:.2f}" if b else "-"


def print_recovery(rows, out=sys.stdout, header: bool = True) -> None:
    """The recovery table as markdown."""
    p = lambda *a: print(*a, file=out, flush=True)  # noqa: E731
    if header:
        p("| family | poses | q* found % | q* missed, certified | q* inside limits: found with limits % "
          "| solutions missed vs oracle (poses, oracle solutions) | of them on certified poses | wrong rows "
          "| continua flagged (poses; kinds) | uncertified | differs from reference (poses) | paths |")
        p("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        if r.empty:
            p(f"| {r.family} | 0 | - | - | - | - | - | - | - | - | - | empty for this arm |")
            continue
        kinds = ", ".join(f"{k} {v}" for k, v in r.continua.items() if k != "any")
        paths = ", ".join(f"{k} {v}" for k, v in sorted(r.paths.items()))
        p(f"| {r.family} | {r.poses} | {_pct(r.found, r.poses)} | {r.silent} "
          f"| {_pct(r.found_inside, r.inside)} ({r.inside}) "
          f"| {r.missed_vs_oracle} ({r.oracle_poses}, {r.oracle_solutions}) | {r.missed_vs_oracle_certified} "
          f"| {r.wrong_rows} "
          f"| {r.continua.get('any', 0)}{'; ' + kinds if kinds else ''} | {r.uncertified} "
          f"| {r.reference_differs} ({r.reference_poses}) | {paths} |")
