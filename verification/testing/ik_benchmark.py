"""Benchmark of the IK methods on one fixed set of reachable random poses.

    python benchmarks/bench_ik.py            # 10 000 poses (default)
    python benchmarks/bench_ik.py --n 500    # quick

It lives in the package (not only in ``benchmarks/``) so that ``iik verify`` can time
the thesis's claim that the IIK costs less than Newton per solution from any install.

Poses are ``fk(q)`` for q drawn uniformly within Table I (seeded), so every pose
is reachable and its generating q is known. Per method it reports completeness
(% of poses whose generating q is among the returned solutions), mean
solutions per pose, median and p99 wall time per pose and per solution
(single-pose calls from Python), and batch throughput; plus the ratios to the
thesis method and to Newton measured in the same run. Newton (pseudo-inverse,
Pinocchio, tolerance 1e-6 deg) starts from the generating q perturbed by
N(0, 0.1 rad), i.e. the favourable "previous step" guess of a path (Sec 4.2.1).
This is a benchmark, not a test: numbers depend on the machine and its load.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from dataclasses import dataclass

import numpy as np

__all__ = ["run", "recovery_sweep", "main", "CostComparison", "ThesisSolver", "compare_cost"]


def _pct(x, p):
    return float(np.percentile(np.asarray(x), p)) if len(x) else float("nan")


def run(
    n: int = 10_000, n_single: int = 1000, n_newton: int = 500, seed: int = 20120101, out=sys.stdout
) -> dict:
    import iik
    from iik.ik.complete import contains, solve_arrays
    from iik.ik.thesis import solve_thesis_arrays

    arm = iik.THESIS_ARM
    rng = np.random.default_rng(seed)
    q = rng.uniform(arm.q_min, arm.q_max, size=(n, 6))
    T = iik.fk(q)
    rows = {}

    def completeness(Q, V, F, tol):
        hit = 0
        for i in range(n):
            sol = Q[i][V[i]]
            fj = [() if f == 0 else ((3, 6) if f == 2 else (1, 6)) for f in F[i][V[i]]]
            hit += contains(sol, q[i], T[i], arm, tol=tol, free_joints=fj)
        return 100.0 * hit / n

    for name, fn, tol in (
        ("complete", lambda Ts: solve_arrays(Ts, arm), 1e-9),
        ("thesis", lambda Ts: solve_thesis_arrays(Ts, arm), 1e-6),
    ):
        fn(T[:10])  # warm-up
        t0 = time.perf_counter()
        Q, V, F, _P, _R = fn(T)
        batch = time.perf_counter() - t0
        counts = V.sum(1)
        single = []
        for i in range(min(n_single, n)):
            t1 = time.perf_counter()
            iik.solve(T[i], method=name, within_limits=False)
            single.append(time.perf_counter() - t1)
        single = np.array(single)
        per_sol = single / np.maximum(counts[: len(single)], 1)
        rows[name] = {
            "completeness_pct": completeness(Q, V, F, tol),
            "mean_solutions": float(counts.mean()),
            "median_us": 1e6 * np.median(single),
            "p99_us": 1e6 * _pct(single, 99),
            "median_per_solution_us": 1e6 * np.median(per_sol),
            "p99_per_solution_us": 1e6 * _pct(per_sol, 99),
            "batch_poses_per_s": n / batch,
            "counts": np.bincount(counts, minlength=17).tolist(),
        }

    from verification.oracles.baselines import newton_pinv

    times, ok, its = [], 0, []
    m = min(n_newton, n)
    for i in range(m):
        q0 = q[i] + rng.normal(0.0, 0.1, 6)
        t1 = time.perf_counter()
        r = newton_pinv(T[i], q0)
        times.append(time.perf_counter() - t1)
        its.append(r.iterations)
        ok += bool(r.converged and np.max(np.abs((r.q - q[i] + np.pi) % (2 * np.pi) - np.pi)) <= 1e-6)
    times = np.array(times)
    rows["newton"] = {
        "completeness_pct": 100.0 * ok / m,
        "mean_solutions": 1.0,
        "median_us": 1e6 * np.median(times),
        "p99_us": 1e6 * _pct(times, 99),
        "median_per_solution_us": 1e6 * np.median(times),
        "p99_per_solution_us": 1e6 * _pct(times, 99),
        "batch_poses_per_s": m / times.sum(),
        "counts": [],
        "iterations": float(np.mean(its)),
        "n": m,
    }
    _print(rows, n, n_single, m, out)
    return rows


def _print(rows, n, n_single, m, out):
    p = lambda *a: print(*a, file=out)
    p(
        f"IK benchmark: {n} poses fk(q), q uniform in Table I; single-pose timings on the first "
        f"{min(n_single, n)}; Newton on the first {m} (pid {os.getpid()})."
    )
    p("")
    p(
        "| method | completeness % | mean sols/pose | median us/pose | p99 us/pose "
        "| median us/solution | p99 us/solution | batch poses/s |"
    )
    p("|---|---|---|---|---|---|---|---|")
    for k, r in rows.items():
        p(
            f"| {k} | {r['completeness_pct']:.4f} | {r['mean_solutions']:.2f} | {r['median_us']:.0f} "
            f"| {r['p99_us']:.0f} | {r['median_per_solution_us']:.1f} | {r['p99_per_solution_us']:.1f} "
            f"| {r['batch_poses_per_s']:.0f} |"
        )
    c, t, nw = rows["complete"], rows["thesis"], rows["newton"]
    p("")
    p(
        f"ratios (median per solution): complete/thesis = "
        f"{c['median_per_solution_us'] / t['median_per_solution_us']:.3f}, complete/Newton = "
        f"{c['median_per_solution_us'] / nw['median_per_solution_us']:.3f}, thesis/Newton = "
        f"{t['median_per_solution_us'] / nw['median_per_solution_us']:.3f}"
    )
    p(f"batch throughput: complete/thesis = {c['batch_poses_per_s'] / t['batch_poses_per_s']:.2f}")
    holds = t["median_per_solution_us"] < nw["median_per_solution_us"]
    p(
        f"thesis claim 'IIK costs less than Newton per solution' (Sec 4.2.1, 5.2): "
        f"{'holds' if holds else 'does not hold'} here for the thesis IIK "
        f"({t['median_per_solution_us']:.1f} vs {nw['median_per_solution_us']:.1f} us/solution); "
        f"complete: {c['median_per_solution_us']:.1f} us/solution"
    )
    p(f"solution-count distribution (complete, index = count): {c['counts']}")
    p(f"solution-count distribution (thesis): {t['counts']}")


@dataclass(frozen=True)
class ThesisSolver:
    """The thesis IIK as the cost comparison calls it: one pose, or a batch; returns solution counts.

    Attributes:
        n_grid: theta1 grid cells over a full turn (the thesis scan: 72, i.e. 5 deg).
    """

    n_grid: int = 72

    def single(self, T: np.ndarray) -> int:
        import iik
        from iik.ik.thesis import solve_thesis_arrays

        return int(solve_thesis_arrays(T[None], iik.THESIS_ARM, n_grid=self.n_grid)[1].sum())

    def batch(self, Ts: np.ndarray) -> int:
        import iik
        from iik.ik.thesis import solve_thesis_arrays

        return int(solve_thesis_arrays(Ts, iik.THESIS_ARM, n_grid=self.n_grid)[1].sum())


@dataclass(frozen=True)
class CostComparison:
    """IIK vs pseudo-inverse Newton, cost per solution, measured ``repeats`` times, interleaved.

    Ratios are IIK / Newton time per solution (below 1: the IIK is cheaper). Single: the median
    over poses of one-pose calls, each IIK call next to a Newton call on the same pose (order
    alternating). Batch: one vectorised call over all poses each (order alternating).

    Attributes:
        single_ratio, batch_ratio: One ratio per repeat.
        single_us, batch_us: (IIK, Newton) median time per solution over the repeats [us].
        solutions_per_pose: Mean IIK solutions per pose.
        newton_converged: Share of Newton runs that converged (batch).
        n_single, n_batch, repeats: Sizes.
    """

    single_ratio: tuple[float, ...]
    batch_ratio: tuple[float, ...]
    single_us: tuple[float, float]
    batch_us: tuple[float, float]
    solutions_per_pose: float
    newton_converged: float
    n_single: int
    n_batch: int
    repeats: int


def compare_cost(
    T: np.ndarray, q: np.ndarray, solver, *, n_single: int, repeats: int = 5, seed: int = 20120101
) -> CostComparison:
    """Time ``solver`` (``.single(T) -> count``, ``.batch(Ts) -> count``) against Newton on poses ``T``
    (n, 4, 4) generated by ``q`` (n, 6); Newton starts from q + N(0, 0.1 rad) (the "previous step")."""
    from verification.oracles.baselines import newton_pinv, newton_pinv_batch

    rng = np.random.default_rng([seed, 11])
    q0 = q + rng.normal(0.0, 0.1, q.shape)
    solver.single(T[0])  # warm-up
    newton_pinv(T[0], q0[0])
    newton_pinv_batch(T[:2], q0[:2])
    s_ratio, b_ratio, s_us, b_us = [], [], [], []
    counts, conv = 0, 1.0
    for r in range(repeats):
        ti, tn = [], []
        for i in rng.permutation(min(n_single, len(T))):
            pair = [
                ("iik", lambda i=i: solver.single(T[i])),
                ("newton", lambda i=i: newton_pinv(T[i], q0[i])),
            ]
            for name, call in pair if (i + r) % 2 == 0 else pair[::-1]:
                t0 = time.perf_counter()
                out = call()
                dt = time.perf_counter() - t0
                (ti if name == "iik" else tn).append(dt / max(int(out), 1) if name == "iik" else dt)
        s_us.append((1e6 * np.median(ti), 1e6 * np.median(tn)))
        s_ratio.append(float(np.median(ti) / np.median(tn)))
        times = {}
        for name in ("iik", "newton") if r % 2 == 0 else ("newton", "iik"):
            t0 = time.perf_counter()
            if name == "iik":
                counts = solver.batch(T)
            else:
                res = newton_pinv_batch(T, q0)
                conv = float(np.mean(res.converged))
            times[name] = time.perf_counter() - t0
        per_iik = times["iik"] / max(counts, 1)
        per_newton = times["newton"] / len(T)
        b_us.append((1e6 * per_iik, 1e6 * per_newton))
        b_ratio.append(float(per_iik / per_newton))
    return CostComparison(
        tuple(s_ratio),
        tuple(b_ratio),
        tuple(np.median(s_us, axis=0)),
        tuple(np.median(b_us, axis=0)),
        counts / len(T),
        conv,
        min(n_single, len(T)),
        len(T),
        repeats,
    )


def recovery_sweep(n: int, seed: int = 20120101, out=sys.stdout) -> dict:
    """Generating-q recovery of the complete solver on random and near-singular poses.

    Strategies (q otherwise uniform in Table I): theta4 ~ 0, theta5 ~ 0, theta3 ~ +-90 deg,
    theta1 at either limit; the offset is 0 with probability 0.2, else +-10^U(-12, -2) rad.
    Recovered = :func:`iik.ik.complete.contains` (1e-9 rad, or the accuracy the pose
    carries near a singularity, or on a flagged continuum).
    """
    import iik
    from iik.ik.complete import contains, solve_arrays

    arm = iik.THESIS_ARM
    rng = np.random.default_rng([seed, 7])
    res = {}
    strategies = [
        ("random", None, 0.0),
        ("theta4 ~ 0", 3, 0.0),
        ("theta5 ~ 0", 4, 0.0),
        ("theta3 ~ +90 deg", 2, np.pi / 2),
        ("theta3 ~ -90 deg", 2, -np.pi / 2),
        ("theta1 ~ +160 deg", 0, arm.q_max[0]),
        ("theta1 ~ -160 deg", 0, arm.q_min[0]),
    ]
    for name, j, centre in strategies:
        q = rng.uniform(arm.q_min, arm.q_max, size=(n, 6))
        if j is not None:
            off = np.where(rng.random(n) < 0.2, 0.0, 10 ** rng.uniform(-12, -2, n))
            sign = -np.sign(centre) if j == 0 else rng.choice([-1.0, 1.0], n)
            q[:, j] = centre + sign * off
        T = iik.fk(q)
        Q, V, F, P, R = solve_arrays(T, arm)
        hit = 0
        for i in range(n):
            fj = [() if f == 0 else ((3, 6) if f == 2 else (1, 6)) for f in F[i][V[i]]]
            hit += contains(Q[i][V[i]], q[i], T[i], arm, free_joints=fj)
        res[name] = (hit, n, float(np.nanmax(P)), float(np.nanmax(R)))
    print(
        "| poses | n | generating q recovered | max position residual [m] | max rotation residual [rad] |",
        file=out,
    )
    print("|---|---|---|---|---|", file=out)
    for k, (h, m, pm, rm) in res.items():
        print(f"| {k} | {m} | {100 * h / m:.4f} % ({m - h} missed) | {pm:.1e} | {rm:.1e} |", file=out)
    return res


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=10_000, help="number of poses (default 10000)")
    ap.add_argument("--single", type=int, default=1000, help="poses timed one at a time")
    ap.add_argument("--newton", type=int, default=500, help="poses solved by Newton")
    ap.add_argument("--seed", type=int, default=20120101)
    ap.add_argument(
        "--recovery",
        type=int,
        default=0,
        metavar="N",
        help="also run the random/near-singular recovery sweep with N poses per strategy",
    )
    a = ap.parse_args(argv)
    run(a.n, a.single, a.newton, a.seed)
    if a.recovery:
        print()
        recovery_sweep(a.recovery, a.seed)
    return 0


if __name__ == "__main__":
    sys.exit(main())
