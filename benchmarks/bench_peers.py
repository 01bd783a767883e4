"""Peer IK solvers against our kernel, on the same poses, in the same run (issue 18, item 5).

    pip install -e ".[bench]"                  # ssik, ikdh, EAIK, ik-geo: benchmark-only extras
    python benchmarks/bench_peers.py           # 200 poses per arm
    python benchmarks/bench_peers.py --n 1000 --arms thesis crx10ia --peers iik ikdh

Arms: the thesis arm and the FANUC CRX-10iA (``iik.arms``). Poses: ``fk(q)`` for q uniform in
the joint limits (seeded), so every pose is reachable and its generating q is known. Uniform
poses are the easy case (no continua, no clusters); completeness on the hard families is
``verification.testing.families``' business, not this table's.

Each peer gets the arm the way its API takes one, built from the same :class:`iik.Arm`:

* product-of-exponentials axes ``(H, P)``: the arm's joint axis lines at q = 0 (``Arm.joint_axes``)
  with the tool rotation at q = 0 moved into the target (``ssik.Manipulator.from_axes``,
  ``eaik.IK_HP.HPRobot``, ``ik_geo.Robot``; for IK-Geo's "two intersecting" the points of axes 5
  and 6 at their intersection, as its decomposition needs);
* a standard DH table with the arm's base and tool as fixed transforms around it (``ikdh``);
* ssik's prebuilt FANUC CRX-10iA artifact (``ssik.prebuilt.fanuc.crx10ia_ik``), after checking
  that its forward kinematics is ours up to a constant tool rotation.

Each peer's model is checked against our FK before it is timed. Every configuration a solver
returns is checked by *our* FK (:func:`iik.fk`): a solution counts when it reaches the pose within
1e-6 m and 1e-6 rad; distinct solutions differ by more than 1e-6 rad in some joint (angles
compared modulo 2 pi). Columns:

* ``sol/pose``: mean distinct solutions that reach the pose; ``ret/pose``: mean returned;
* ``recovery``: poses whose generating q is among the solutions (within 1e-6 rad);
* ``missed``: solutions of our kernel the peer does not return, summed over the poses;
  ``extra``: the peer's solutions our kernel does not return (a nonzero ``extra`` would be a
  miss of ours). For these three, each counted solution is first moved onto the pose by five
  Gauss-Newton steps of our FK (a peer's solution within the tolerance can sit ~1e-6 rad from
  the exact one, e.g. IK-Geo's 1D search); the counts and residuals are of the peer's own output;
* ``worst res``: the largest position [m] / rotation [rad] residual of any returned configuration;
* ``median``, ``p99``: wall time of one call per pose [us] (the call only, after one warm-up
  call); ``x iik``: median over our kernel's median for the same arm in this run.

A peer that does not install, or refuses the arm, gets a row saying so with its message. ssik's
general-6R path derives per-arm algebra on first use (minutes, cached on disk in
``~/.cache/ssik``); that setup is timed separately and listed under the table. This is a
benchmark, not a test: the numbers depend on the machine and its load.
"""

from __future__ import annotations

import argparse
import importlib.metadata
import math
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

import iik
import iik.arms
from iik.ik.angles import angle_distance

TOL = 1e-6  # [m] and [rad]: a configuration reaches the pose; two configurations are distinct


@dataclass(frozen=True)
class Peer:
    """One solver set up for one arm: ``solve(T) -> configurations (k, 6)`` in our joint angles
    [rad], or a refusal (``solve`` None, ``note`` the reason)."""

    name: str
    solve: Callable[[np.ndarray], np.ndarray] | None
    note: str = ""
    setup_s: float = 0.0


@dataclass(frozen=True)
class Row:
    """One line of the table (see the module docstring for the columns)."""

    peer: str
    arm: str
    sol: float = math.nan
    ret: float = math.nan
    recovery: str = ""
    missed: int = 0
    extra: int = 0
    worst: tuple[float, float] = (math.nan, math.nan)
    median_us: float = math.nan
    p99_us: float = math.nan
    note: str = ""


# ----------------------------------------------------------------------------- the arm, in each form
def hp_model(arm: iik.Arm, intersect_56: bool = False):
    """Axes ``H`` (6, 3), offsets ``P`` (7, 3) [m] and the tool rotation at q = 0 (3, 3): FK is
    ``prod_i Trans(P_i) Rot(H_i, q_i) . Trans(P_6)`` with the rotation ``R(q) R0^-1``."""
    pts, dirs = arm.joint_axes()
    pts = pts.copy()
    if intersect_56:  # both reference points at the intersection of axes 5 and 6
        A = np.array([dirs[4], -dirs[5]]).T
        t = np.linalg.lstsq(A, pts[5] - pts[4], rcond=None)[0]
        pts[4] = pts[5] = pts[4] + t[0] * dirs[4]
    T0 = iik.fk(np.zeros(6), arm)
    P = np.vstack([pts[0], np.diff(pts, axis=0), T0[:3, 3] - pts[-1]])
    return dirs.copy(), P, T0[:3, :3]


def _hp_target(T: np.ndarray, R0: np.ndarray) -> np.ndarray:
    X = T.copy()
    X[:3, :3] = T[:3, :3] @ R0.T
    return X


def _rot(axis: str, a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    R = np.eye(4)
    i, j = (1, 2) if axis == "x" else (0, 1)
    R[i, i], R[i, j], R[j, i], R[j, j] = c, -s, s, c
    return R


def standard_dh(arm: iik.Arm):
    """The arm's modified-DH rows as standard DH ``(a, d, alpha, theta offset)`` lists [m, rad] and
    the fixed transforms around them: ``fk = pre . standard(q) . post``."""
    rows = arm.dh.rows
    a = [rows[i + 1].a if i < 5 else 0.0 for i in range(6)]
    alpha = [rows[i + 1].alpha if i < 5 else 0.0 for i in range(6)]
    shift = np.eye(4)
    shift[0, 3] = rows[0].a
    pre = np.array(arm.base) @ _rot("x", rows[0].alpha) @ shift
    return a, [r.d for r in rows], alpha, [r.offset for r in rows], pre, np.array(arm.tool)


def _check_model(name: str, fk: Callable[[np.ndarray], np.ndarray], arm: iik.Arm) -> None:
    """Raise if a peer's model of the arm is not ours (FK at a few q, to 1e-9 m / 1e-9)."""
    for q in np.random.default_rng(7).uniform(arm.q_min, arm.q_max, (5, 6)):
        err = np.abs(fk(q) - iik.fk(q, arm)).max()
        if err > 1e-9:
            raise RuntimeError(f"{name}'s model of {arm.name} differs from ours by {err:.3g}")


# ----------------------------------------------------------------------------- the peers
def _version(dist: str) -> str:
    try:
        return importlib.metadata.version(dist)
    except importlib.metadata.PackageNotFoundError:
        return "not installed"


def _iik(arm: iik.Arm) -> Peer:
    return Peer(f"iik {_version('iik')} (kernel)", lambda T: iik.solve(T, arm=arm, within_limits=False).q)


def _ssik_live(arm: iik.Arm) -> Peer:
    import ssik

    H, P, R0 = hp_model(arm)
    t = time.perf_counter()
    m = ssik.Manipulator.from_axes(H, P)
    m.prepare()  # the per-arm derivation (cached on disk after the first run)
    m.solve(_hp_target(iik.fk(np.full(6, 0.3), arm), R0), respect_limits=False)
    setup = time.perf_counter() - t
    _check_model("ssik", lambda q: _hp_target(m.fk(q), R0.T), arm)
    solve = lambda T: np.array([s.q for s in m.solve(_hp_target(T, R0), respect_limits=False)])  # noqa: E731
    return Peer(f"ssik {_version('ssik')} ({m.solver_name})", solve, setup_s=setup)


def _ssik_prebuilt(arm: iik.Arm) -> Peer:
    from ssik.prebuilt.fanuc import crx10ia_ik as m

    R_off = m.fk(np.zeros(6))[:3, :3].T @ iik.fk(np.zeros(6), arm)[:3, :3]  # ours = theirs . R_off
    _check_model("ssik's CRX-10iA artifact", lambda q: _hp_target(m.fk(q), R_off.T), arm)
    solve = lambda T: np.array([s.q for s in m.solve(_hp_target(T, R_off), respect_limits=False)])  # noqa: E731
    return Peer(f"ssik {_version('ssik')} (prebuilt crx10ia_ik)", solve)


def _ikdh(arm: iik.Arm) -> Peer:
    import ikdh

    a, d, alpha, theta, pre, post = standard_dh(arm)
    dh = ikdh.DHTable(a, d, alpha, theta)
    solver = ikdh.Solver(dh)
    pre_inv, post_inv = np.linalg.inv(pre), np.linalg.inv(post)
    _check_model("ikdh", lambda q: pre @ ikdh.forward_kin(dh, np.degrees(q)) @ post, arm)
    solve = lambda T: np.radians(np.array(solver.solve(pre_inv @ T @ post_inv)))  # noqa: E731 (deg out)
    return Peer(f"ikdh {_version('ikdh')} (Husty-Pfurner)", solve)


def _eaik(arm: iik.Arm) -> Peer:
    from eaik.IK_HP import HPRobot

    H, P, R0 = hp_model(arm)
    bot = HPRobot(H, P)
    if not bot.hasKnownDecomposition():
        try:
            bot.IK(_hp_target(iik.fk(np.zeros(6), arm), R0))
            message = "no error"
        except Exception as exc:  # its refusal, verbatim
            message = f"{type(exc).__name__}: {exc}"
        family = bot.getKinematicFamily()
        return Peer(f"EAIK {_version('EAIK')}", None, f"refuses the arm ({family}): {message}")
    return Peer(f"EAIK {_version('EAIK')}", lambda T: np.array(bot.IK(_hp_target(T, R0)).Q))


def _ik_geo(arm: iik.Arm, decomposition: str) -> Peer:
    from ik_geo import Robot

    H, P, R0 = hp_model(arm, intersect_56=decomposition == "two_intersecting")
    bot = getattr(Robot, decomposition)(H, P)

    def fk(q):  # its rotations come (and go, in get_ik) transposed: column-major
        R, p = bot.forward_kinematics(q)
        T = np.eye(4)
        T[:3, :3], T[:3, 3] = np.array(R).T, p
        return _hp_target(T, R0.T)

    _check_model("IK-Geo", fk, arm)
    solve = lambda T: np.array([s[0] for s in bot.get_ik(_hp_target(T, R0)[:3, :3].T, T[:3, 3])])  # noqa: E731
    return Peer(f"ik-geo {_version('ik-geo')} ({decomposition})", solve)


def _lines_meet(p1, d1, p2, d2) -> bool:
    n = np.cross(d1, d2)
    return bool(np.linalg.norm(n) > 1e-12 and abs((p2 - p1) @ n) / np.linalg.norm(n) <= 1e-9)


def _decompositions(arm: iik.Arm) -> list[str]:
    """IK-Geo's decompositions whose axis conditions the arm meets, read from the base (its
    closed-form ones need a spherical wrist or three parallel axes: none of the class has them)."""
    pts, dirs = arm.joint_axes()
    out = ["two_intersecting"] if _lines_meet(pts[4], dirs[4], pts[5], dirs[5]) else []
    if np.linalg.norm(np.cross(dirs[1], dirs[2])) <= 1e-12:
        out.append("two_parallel")  # axes 2 and 3 parallel (the CRX read from the base)
    return out + ["gen_six_dof"]


def peers_for(arm_name: str, arm: iik.Arm, chosen: set[str]) -> list[Peer]:
    makers: list[tuple[str, str, Callable[[], Peer]]] = [("iik", "iik", lambda: _iik(arm))]
    makers.append(("ssik", "ssik (general 6R)", lambda: _ssik_live(arm)))
    if arm_name == "crx10ia":
        makers.append(("ssik", "ssik (prebuilt crx10ia_ik)", lambda: _ssik_prebuilt(arm)))
    makers += [("ikdh", "ikdh", lambda: _ikdh(arm)), ("eaik", "EAIK", lambda: _eaik(arm))]
    makers += [("ik-geo", f"ik-geo ({d})", lambda d=d: _ik_geo(arm, d)) for d in _decompositions(arm)]
    out = []
    for key, label, make in makers:
        if key not in chosen:
            continue
        try:
            out.append(make())
        except Exception as exc:  # not installed, or cannot take the arm: the row says so
            out.append(Peer(label, None, f"{type(exc).__name__}: {exc}"))
    return out


# ----------------------------------------------------------------------------- measuring
def _wrapped(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """max |a - b| over the joints, modulo 2 pi: (len(a), len(b))."""
    return angle_distance(a[:, None, :], b[None, :, :])


def _residuals(qs: np.ndarray, T: np.ndarray, arm: iik.Arm) -> np.ndarray:
    """(k, 2): position [m] and rotation [rad] residual of each configuration, by our FK."""
    if len(qs) == 0:
        return np.zeros((0, 2))
    F = iik.fk(qs, arm).reshape(-1, 4, 4)
    pos = np.linalg.norm(F[:, :3, 3] - T[:3, 3], axis=1)
    rot = np.array([iik.rotation_angle(f[:3, :3], T[:3, :3]) for f in F])
    return np.stack([pos, rot], axis=1)


def _polished(qs: np.ndarray, T: np.ndarray, arm: iik.Arm, steps: int = 5) -> np.ndarray:
    """Configurations moved by a few Gauss-Newton steps onto the pose (our FK), for matching
    only: a solution within the 1e-6 tolerance can sit ~1e-6 rad from the exact one."""
    from scipy.spatial.transform import Rotation

    out = qs.copy()
    for q in out:
        for _ in range(steps):
            F = iik.fk(q, arm)
            turn = Rotation.from_matrix(T[:3, :3] @ F[:3, :3].T).as_rotvec()
            e = np.concatenate([T[:3, 3] - F[:3, 3], turn])
            q += np.linalg.lstsq(iik.jacobian(q, arm), e, rcond=None)[0]
    return out


def _distinct(qs: np.ndarray) -> np.ndarray:
    keep: list[int] = []
    for i in range(len(qs)):
        if not keep or _wrapped(qs[i : i + 1], qs[keep]).min() > TOL:
            keep.append(i)
    return qs[keep]


def measure(peer: Peer, arm_name: str, arm: iik.Arm, qs: np.ndarray, Ts: np.ndarray, ours) -> Row:
    """Run ``peer`` on every pose; ``ours`` are our kernel's solutions per pose (or None)."""
    if peer.solve is None:
        return Row(peer.name, arm_name, note=peer.note)
    peer.solve(iik.fk(np.full(6, 0.2), arm))  # warm-up (imports, JIT, caches)
    times, found = np.empty(len(Ts)), []
    for i, T in enumerate(Ts):
        t = time.perf_counter()
        out = peer.solve(T)
        times[i] = time.perf_counter() - t
        found.append(np.asarray(out, dtype=float).reshape(-1, 6))
    sol = ret = recovered = missed = extra = 0
    worst = np.full(2, np.nan)  # stays "-" if the peer never returns a configuration
    for i, (q, T, got) in enumerate(zip(qs, Ts, found, strict=True)):
        res = _residuals(got, T, arm)
        ret += len(got)
        if len(got):
            worst = np.fmax(worst, res.max(axis=0))
        good = _distinct(got[np.all(res <= TOL, axis=1)])
        sol += len(good)
        good = _polished(good, T, arm)
        recovered += bool(len(good) and _wrapped(q[None], good).min() <= TOL)
        if ours is not None and len(ours[i]):
            missed += int(np.sum(_wrapped(ours[i], good).min(axis=1) > TOL)) if len(good) else len(ours[i])
            extra += int(np.sum(_wrapped(good, ours[i]).min(axis=1) > TOL)) if len(good) else 0
    n = len(Ts)
    note = f"setup {peer.setup_s:.1f} s" if peer.setup_s > 1 else peer.note
    return Row(peer.name, arm_name, sol / n, ret / n, f"{recovered}/{n}", missed, extra, tuple(worst),
               float(np.median(times) * 1e6), float(np.percentile(times, 99) * 1e6), note)


# ----------------------------------------------------------------------------- the table
def _fmt(x: float, spec: str) -> str:
    return "-" if not np.isfinite(x) else format(x, spec)


def print_table(rows: list[Row], base: dict[str, float]) -> None:
    head = ("solver", "arm", "sol/pose", "ret/pose", "recovery", "missed", "extra", "worst res m / rad",
            "median us", "p99 us", "x iik")
    lines = [head]
    notes = []
    for r in rows:
        if not np.isfinite(r.median_us):
            lines.append((r.peer, r.arm, "-", "-", "-", "-", "-", "-", "-", "-", "-"))
            notes.append(f"{r.peer} on {r.arm}: {r.note}")
            continue
        ratio = r.median_us / base[r.arm] if r.arm in base else math.nan
        worst = f"{_fmt(r.worst[0], '.1e')} / {_fmt(r.worst[1], '.1e')}"
        lines.append((r.peer, r.arm, _fmt(r.sol, ".2f"), _fmt(r.ret, ".2f"), r.recovery, str(r.missed),
                      str(r.extra), worst, _fmt(r.median_us, ".0f"), _fmt(r.p99_us, ".0f"),
                      _fmt(ratio, ".1f")))
        if r.note:
            notes.append(f"{r.peer} on {r.arm}: {r.note}")
    widths = [max(len(line[k]) for line in lines) for k in range(len(head))]
    for k, line in enumerate(lines):
        cells = zip(line, widths, strict=True)
        print("  ".join(c.ljust(w) if j < 2 else c.rjust(w) for j, (c, w) in enumerate(cells)))
        if k == 0:
            print("  ".join("-" * w for w in widths))
    for n in notes:
        print(f"* {n}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200, help="poses per arm (default 200)")
    ap.add_argument("--seed", type=int, default=18, help="seed of the generating configurations")
    ap.add_argument("--arms", nargs="+", default=["thesis", "crx10ia"], choices=iik.arms.NAMES)
    ap.add_argument("--peers", nargs="+", default=["iik", "ssik", "ikdh", "eaik", "ik-geo"],
                    choices=["iik", "ssik", "ikdh", "eaik", "ik-geo"])
    args = ap.parse_args(argv)
    if args.n < 1:
        ap.error("--n must be at least 1")
    rng = np.random.default_rng(args.seed)
    rows, base = [], {}
    print(f"{args.n} poses per arm, fk(q) with q uniform in the joint limits (seed {args.seed}); "
          f"numpy {np.__version__}, python {sys.version.split()[0]}\n")
    for name in args.arms:
        arm = iik.arms.get(name)
        qs = rng.uniform(arm.q_min, arm.q_max, (args.n, 6))
        Ts = iik.fk(qs, arm)
        ours = [iik.solve(T, arm=arm, within_limits=False).q for T in Ts]
        for peer in peers_for(name, arm, set(args.peers) | {"iik"}):
            row = measure(peer, name, arm, qs, Ts, None if peer.name.startswith("iik") else ours)
            if peer.name.startswith("iik"):
                base[name] = row.median_us
            rows.append(row)
    print_table(rows, base)
    return 0


if __name__ == "__main__":
    sys.exit(main())
