"""Benchmark of the IK methods, per pose family: the compiled kernel against the NumPy
reference, the thesis IIK, Newton and damped least squares, in one run.

    python benchmarks/bench_ik.py                       # default sizes
    python benchmarks/bench_ik.py --n 500 --single 200  # quick
    python benchmarks/bench_ik.py --recovery 100000     # plus the near-singular recovery sweep
    python benchmarks/bench_ik.py --cold-start          # plus first-call times in new processes

It lives in the package (not only in ``benchmarks/``) so that ``iik verify`` can time the
thesis's claim that the IIK costs less than Newton per solution from any install.

Poses are ``fk(q)`` for q drawn uniformly within Table I (seeded), so every pose is
reachable and its generating q is known; besides random q, each singular family of issue
10 puts one joint combination at or near its singular value (offset 0 with probability
0.2, else +-10^U(-12, -2) rad): theta4 ~ 0, theta5 ~ 0, theta4 + theta5 ~ 0 or pi,
theta3 ~ +-90 deg, theta1 at +-160 deg, and the wrist point on the joint-1 axis.

Per family and method: completeness (% of poses whose generating q is among the
solutions, :func:`iik.ik.compare.contains`), mean solutions per pose, the median / p90 /
p99 wall time of a single-pose call from Python (validation and result object included)
per pose and per solution, and the batch throughput (``solve_many``, and ``solve_batch``
for the kernel; Newton and DLS in a loop; the best of three runs). Newton (pseudo-inverse,
Pinocchio, tolerance 1e-6 deg) and DLS start from the generating q perturbed by
N(0, 0.1 rad), the favourable "previous step" guess of a path (Sec 4.2.1). Ratios are to
the kernel in the same run. This is a benchmark, not a test: numbers depend on the machine
and its load.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

from iik import THESIS_ARM
from iik.ik.angles import angle_distance

METHODS = ("kernel", "reference", "thesis", "newton", "dls")
FAMILIES = ("generic", "theta4 ~ 0", "theta5 ~ 0", "theta4 + theta5 ~ 0", "theta4 + theta5 ~ pi",
            "theta3 ~ +-90 deg", "theta1 at +-160 deg", "wrist point on joint-1 axis")


def _pct(x, p):
    return float(np.percentile(np.asarray(x), p)) if len(x) else float("nan")


def _offsets(rng, n):
    return np.where(rng.random(n) < 0.2, 0.0, 10 ** rng.uniform(-12, -2, n)) * rng.choice([-1.0, 1.0], n)


def _wrist_on_axis(rng, n, arm):
    """q with theta3 = 0 and theta2 solved so that the wrist point (joint 5) is on the joint-1 axis."""
    from scipy.optimize import brentq

    import iik

    out = []
    while len(out) < n:
        q = rng.uniform(arm.q_min, arm.q_max)
        q[2] = 0.0

        def radial(t2, q=q):
            qq = q.copy()
            qq[1] = t2
            D = iik.joint_frames(qq, arm)[4, :3, 3]
            return D[0] * np.cos(q[0]) + D[1] * np.sin(q[0])

        grid = np.linspace(arm.q_min[1], arm.q_max[1], 41)
        vals = [radial(t) for t in grid]
        k = next((i for i in range(40) if vals[i] * vals[i + 1] < 0), None)
        if k is None:
            continue
        q[1] = brentq(radial, grid[k], grid[k + 1], xtol=1e-15, rtol=1e-15)
        out.append(q)
    q = np.array(out)
    q[:, 1] += _offsets(rng, n)
    return np.clip(q, arm.q_min, arm.q_max)


def family_joints(name: str, n: int, rng, arm) -> np.ndarray:
    """Generating q (n, 6) of a pose family (see the module docstring)."""
    q = rng.uniform(arm.q_min, arm.q_max, size=(n, 6))
    off = _offsets(rng, n)
    if name == "theta4 ~ 0":
        q[:, 3] = off
    elif name == "theta5 ~ 0":
        q[:, 4] = off
    elif name == "theta4 + theta5 ~ 0":
        q[:, 4] = -q[:, 3] + off
    elif name == "theta4 + theta5 ~ pi":
        q[:, 3] = rng.uniform(np.pi - arm.q_max[4], arm.q_max[3], n)
        q[:, 4] = np.pi - q[:, 3] + off
    elif name == "theta3 ~ +-90 deg":
        q[:, 2] = rng.choice([-1.0, 1.0], n) * np.pi / 2 + off
    elif name == "theta1 at +-160 deg":
        side = rng.choice([0, 1], n)
        q[:, 0] = np.where(side, arm.q_max[0] - np.abs(off), arm.q_min[0] + np.abs(off))
    elif name == "wrist point on joint-1 axis":
        q = _wrist_on_axis(rng, n, arm)
    return np.clip(q, arm.q_min, arm.q_max)


def _solver(method: str):
    import iik
    from verification.oracles.baselines import damped_least_squares, newton_pinv

    if method in ("kernel", "reference", "thesis"):
        m = "complete" if method == "kernel" else method
        return (lambda T, q0: iik.solve(T, THESIS_ARM, method=m, within_limits=False),
                lambda Ts, Q0: iik.solve_many(Ts, THESIS_ARM, method=m, within_limits=False))
    fn = newton_pinv if method == "newton" else damped_least_squares
    return (lambda T, q0: fn(T, q0), lambda Ts, Q0: [fn(T, q0) for T, q0 in zip(Ts, Q0, strict=True)])


def _recovered(method, res, q, T, arm) -> bool:
    from verification.testing.completeness import contains

    if method in ("newton", "dls"):
        return bool(res.converged and angle_distance(res.q, q) <= 1e-6)
    if method == "thesis":  # the thesis's 1e-6 deg bisection: its rows are that accurate
        return bool(len(res.q)) and float(np.min(angle_distance(res.q, q))) <= 1e-6
    return contains(res, q, T, arm)


def _best_time(fn, repeats: int) -> float:
    """Least wall time of ``repeats`` runs [s] (throughput on a shared machine: the least disturbed run)."""
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def measure(method: str, q: np.ndarray, T: np.ndarray, q0: np.ndarray, n_single: int, arm) -> dict:
    """Timings and completeness of one method on poses T generated by q."""
    one, many = _solver(method)
    one(T[0], q0[0])  # warm-up (and compile)
    times, counts, hits = [], [], 0
    for i in range(min(n_single, len(T))):
        t0 = time.perf_counter()
        res = one(T[i], q0[i])
        times.append(time.perf_counter() - t0)
        counts.append(1 if method in ("newton", "dls") else res.count)
        hits += _recovered(method, res, q[i], T[i], arm)
    times = np.array(times) * 1e6
    per_sol = times / np.maximum(counts, 1)
    batch = len(T) / _best_time(lambda: many(T, q0), 1 if method in ("reference", "thesis") else 3)
    return {"completeness_pct": 100.0 * hits / len(times), "mean_solutions": float(np.mean(counts)),
            "median_us": float(np.median(times)), "p90_us": _pct(times, 90), "p99_us": _pct(times, 99),
            "median_per_solution_us": float(np.median(per_sol)), "p90_per_solution_us": _pct(per_sol, 90),
            "p99_per_solution_us": _pct(per_sol, 99), "batch_poses_per_s": batch, "n_single": len(times),
            "n_batch": len(T)}


def run(n: int = 2000, n_single: int = 500, n_newton: int = 200, seed: int = 20120101, out=sys.stdout,
        families=FAMILIES, methods=METHODS) -> dict:
    """Run the benchmark; ``rows[family][method]`` -> figures (see :func:`measure`), printed as tables."""
    import iik

    arm = iik.THESIS_ARM
    rows: dict = {}
    for fam in families:
        rng = np.random.default_rng([seed, FAMILIES.index(fam)])
        q = family_joints(fam, n, rng, arm)
        T = iik.fk(q, THESIS_ARM)
        q0 = q + rng.normal(0.0, 0.1, q.shape)
        rows[fam] = {}
        for m in methods:
            k = n_newton if m in ("newton", "dls") else n
            ks = min(n_single, k)
            rows[fam][m] = measure(m, q[:k], T[:k], q0[:k], ks, arm)
        if "kernel" in methods:
            best = _best_time(lambda T=T: iik.ik.solve_batch(T, THESIS_ARM, within_limits=False), 3)
            rows[fam]["kernel"]["solve_batch_poses_per_s"] = n / best
    _print(rows, n, n_single, n_newton, out)
    return rows


def _print(rows, n, n_single, n_newton, out):
    p = lambda *a: print(*a, file=out)
    p(f"IK benchmark (pid {os.getpid()}): {n} poses fk(q) per family (Newton/DLS: {n_newton}); "
      f"single-pose calls on the first {n_single}; times in us, wall clock, one thread.")
    gen = rows.get("generic", {}).get("kernel")
    for fam, r in rows.items():
        k = r.get("kernel")
        p("")
        p(f"### {fam}")
        p("")
        p("| method | found q % | sols/pose | median us/pose | p90 | p99 | median us/sol | p90 | p99 "
          "| batch poses/s | median vs kernel | batch vs kernel |")
        p("|---|---|---|---|---|---|---|---|---|---|---|---|")
        for m, x in r.items():
            rm = x["median_us"] / k["median_us"] if k else float("nan")
            rb = x["batch_poses_per_s"] / k["batch_poses_per_s"] if k else float("nan")
            p(f"| {m} | {x['completeness_pct']:.2f} | {x['mean_solutions']:.2f} | {x['median_us']:.1f} "
              f"| {x['p90_us']:.1f} | {x['p99_us']:.1f} | {x['median_per_solution_us']:.2f} "
              f"| {x['p90_per_solution_us']:.2f} | {x['p99_per_solution_us']:.2f} "
              f"| {x['batch_poses_per_s']:.0f} | {rm:.2f} | {rb:.3f} |")
        if k and "solve_batch_poses_per_s" in k:
            p(f"kernel as arrays (iik.ik.solve_batch): {k['solve_batch_poses_per_s']:.0f} poses/s")
        if k and gen:
            p(f"kernel p99 / generic median = {k['p99_us'] / gen['median_us']:.2f}")
    if gen and "thesis" in rows["generic"] and "newton" in rows["generic"]:
        t, nw = rows["generic"]["thesis"], rows["generic"]["newton"]
        holds = t["median_per_solution_us"] < nw["median_per_solution_us"]
        p("")
        p(f"thesis claim 'IIK costs less than Newton per solution' (Sec 4.2.1, 5.2): "
          f"{'holds' if holds else 'does not hold'} here for the thesis IIK "
          f"({t['median_per_solution_us']:.1f} vs {nw['median_per_solution_us']:.1f} us/solution); "
          f"kernel: {gen['median_per_solution_us']:.2f} us/solution")


def kinematics_timings(n: int = 20000, out=sys.stdout) -> dict:
    """fk / jacobian / position_jacobian of one q, and fk of a batch: median us per call."""
    import iik

    q = np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0])
    Q = np.random.default_rng(0).uniform(iik.THESIS_ARM.q_min, iik.THESIS_ARM.q_max, size=(10000, 6))
    res = {}
    for name, f in (("fk(q)", lambda: iik.fk(q, THESIS_ARM)),
                    ("jacobian(q)", lambda: iik.jacobian(q, THESIS_ARM)),
                    ("position_jacobian(q)", lambda: iik.position_jacobian(q, THESIS_ARM))):
        f()
        ts = []
        for _ in range(n // 100):
            t0 = time.perf_counter()
            for _ in range(100):
                f()
            ts.append((time.perf_counter() - t0) / 100)
        res[name] = 1e6 * float(np.median(ts))
    iik.fk(Q, THESIS_ARM)
    t0 = time.perf_counter()
    iik.fk(Q, THESIS_ARM)
    res["fk batch, per q"] = 1e6 * (time.perf_counter() - t0) / len(Q)
    print("| kinematics | median us |\n|---|---|", file=out)
    for k, v in res.items():
        print(f"| {k} | {v:.2f} |", file=out)
    return res


_COLD = r"""
import time, json
t0 = time.perf_counter()
import numpy as np, iik
t1 = time.perf_counter()
T = iik.fk(np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0]))
t2 = time.perf_counter()
iik.solve(T)
t3 = time.perf_counter()
iik.solve(T)
t4 = time.perf_counter()
print(json.dumps({"import_s": t1 - t0, "first_fk_s": t2 - t1, "first_solve_s": t3 - t2,
                  "second_solve_s": t4 - t3}))
"""


def cold_start(out=sys.stdout) -> dict:
    """First calls in new processes: with an empty kernel cache (a fresh install) and then with
    the cache it left (every later process). The cache goes to a temporary NUMBA_CACHE_DIR so
    the installed one is not touched."""
    res = {}
    with tempfile.TemporaryDirectory() as d:
        env = {**os.environ, "NUMBA_CACHE_DIR": d}
        for label in ("fresh install (empty cache)", "new process, warm cache"):
            t0 = time.perf_counter()
            o = subprocess.run([sys.executable, "-c", _COLD], env=env, capture_output=True, text=True,
                               check=True)
            wall = time.perf_counter() - t0
            res[label] = {**json.loads(o.stdout.strip().splitlines()[-1]), "process_s": wall}
    print("| cold start | process [s] | import iik [s] | first fk [s] | first solve [s] "
          "| second solve [us] |", file=out)
    print("|---|---|---|---|---|---|", file=out)
    for k, v in res.items():
        print(f"| {k} | {v['process_s']:.2f} | {v['import_s']:.2f} | {v['first_fk_s']:.2f} | "
              f"{v['first_solve_s']:.2f} | {1e6 * v['second_solve_s']:.0f} |", file=out)
    return res


def recovery_sweep(n: int, seed: int = 20120101, out=sys.stdout) -> dict:
    """Generating-q recovery of the kernel on random and near-singular poses (n per family of the
    recovery sweep: random, theta4 ~ 0, theta5 ~ 0, theta3 ~ +-90 deg, theta1 at +-160 deg).

    Recovered = :func:`iik.ik.compare.contains` (1e-9 rad, or the accuracy the pose carries near a
    singularity, or on a flagged continuum).
    """
    import iik
    from verification.testing.completeness import contains

    arm = iik.THESIS_ARM
    rng = np.random.default_rng([seed, 7])
    res = {}
    strategies = [("random", None, 0.0), ("theta4 ~ 0", 3, 0.0), ("theta5 ~ 0", 4, 0.0),
                  ("theta3 ~ +90 deg", 2, np.pi / 2), ("theta3 ~ -90 deg", 2, -np.pi / 2),
                  ("theta1 ~ +160 deg", 0, arm.q_max[0]), ("theta1 ~ -160 deg", 0, arm.q_min[0])]
    for name, j, centre in strategies:
        q = rng.uniform(arm.q_min, arm.q_max, size=(n, 6))
        if j is not None:
            off = np.where(rng.random(n) < 0.2, 0.0, 10 ** rng.uniform(-12, -2, n))
            sign = -np.sign(centre) if j == 0 else rng.choice([-1.0, 1.0], n)
            q[:, j] = centre + sign * off
        T = iik.fk(q, THESIS_ARM)
        results = iik.solve_many(T, arm, within_limits=False)
        hit = sum(contains(r, q[i], T[i], arm) for i, r in enumerate(results))
        res[name] = (hit, n, max(float(np.max(r.position_residual, initial=0.0)) for r in results),
                     max(float(np.max(r.rotation_residual, initial=0.0)) for r in results))
    print("| poses | n | generating q recovered | max position residual [m] | max rotation residual [rad] |",
          file=out)
    print("|---|---|---|---|---|", file=out)
    for k, (h, m, pm, rm) in res.items():
        print(f"| {k} | {m} | {100 * h / m:.4f} % ({m - h} missed) | {pm:.1e} | {rm:.1e} |", file=out)
    return res


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=2000, help="poses per family (default 2000)")
    ap.add_argument("--single", type=int, default=500, help="poses timed one at a time per family")
    ap.add_argument("--newton", type=int, default=200, help="poses per family for Newton and DLS")
    ap.add_argument("--seed", type=int, default=20120101)
    ap.add_argument("--families", default="all", help="comma-separated family names, or 'all'")
    ap.add_argument("--recovery", type=int, default=0, metavar="N",
                    help="also run the random/near-singular recovery sweep with N poses per family")
    ap.add_argument("--cold-start", action="store_true", help="also time first calls in new processes")
    a = ap.parse_args(argv)
    fams = FAMILIES if a.families == "all" else tuple(f.strip() for f in a.families.split(","))
    kinematics_timings()
    print()
    run(a.n, a.single, a.newton, a.seed, families=fams)
    if a.recovery:
        print()
        recovery_sweep(a.recovery, a.seed)
    if a.cold_start:
        print()
        cold_start()
    return 0


if __name__ == "__main__":
    sys.exit(main())
