"""The compiled IK kernel: the certified root isolation (Bernstein subdivision, double-double
arithmetic) on polynomials with known roots, solve / solve_many / solve_batch consistency, the
kernel's input checks against the NumPy methods', and the on-disk cache (read-only package
folder, invalidation by an edit of the compiled sources)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import textwrap
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import iik
from iik import THESIS_ARM
from iik.errors import IIKError, InvalidInputError, NotOrthonormalError
from iik.ik import bernstein as bz
from iik.ik import ddarith as dd

ARM = iik.THESIS_ARM
LO, HI = ARM.q_min, ARM.q_max


def family_poses(n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """q (7 n, 6) and fk(q): random, and near the easy singular values (theta4 ~ 0, theta5 ~ 0,
    theta3 ~ +-90 deg, theta1 at +-160 deg), offsets 0 or 10^U(-12, -2)."""
    rng = np.random.default_rng(seed)
    blocks = []
    families = ((None, 0.0), (3, 0.0), (4, 0.0), (2, np.pi / 2), (2, -np.pi / 2), (0, HI[0]), (0, LO[0]))
    for j, centre in families:
        q = rng.uniform(LO, HI, size=(n, 6))
        if j is not None:
            off = np.where(rng.random(n) < 0.2, 0.0, 10 ** rng.uniform(-12, -2, n))
            sign = -np.sign(centre) if j == 0 else rng.choice([-1.0, 1.0], n)
            q[:, j] = centre + sign * off
        blocks.append(q)
    q = np.concatenate(blocks)
    return q, iik.fk(q, THESIS_ARM)


# ----------------------------------------------------------------------------- certified isolation
def _bernstein_of_roots(roots, lead):
    """Bernstein coefficients (9,) on [0, 1] of lead * prod (u - r) * (u^2 + 1)^(8 - len)/2... exactly:
    the power coefficients by Fractions, then the exact power-to-Bernstein map."""
    from math import comb

    poly = [Fraction(lead)]
    for r in roots:
        fr = Fraction(r)
        poly = [(poly[i - 1] if i > 0 else 0) - fr * (poly[i] if i < len(poly) else 0)
                for i in range(len(poly) + 1)]
    while len(poly) < 9:  # times (u^2 + 1): no real root
        poly = [(poly[i - 2] if i >= 2 else 0) + (poly[i] if i < len(poly) else 0)
                for i in range(len(poly) + 2)]
    b = [sum(Fraction(comb(j, i), comb(8, i)) * poly[i] for i in range(j + 1)) for j in range(9)]
    return np.array([float(x) for x in b])


@given(st.lists(st.floats(0.01, 0.99), min_size=0, max_size=8, unique=True), st.sampled_from([1.0, -3.0]))
def test_every_simple_root_is_in_its_own_root_leaf(roots, lead):
    """Random polynomials with known simple roots in (0, 1): each root lies in a root leaf or a
    cluster (never in an excluded piece); a root leaf holds exactly one of them and its refined
    root is within 1e-6 of it (clustered roots are only as accurate as their separation allows)."""
    roots = sorted(roots)
    if len(roots) % 2 == 1 and len(roots) < 8:  # degree 8 with a quadratic factor of no real root
        roots = roots[:-1]
    b = _bernstein_of_roots(roots, lead)
    out = np.zeros((bz.N_LEAF, bz.LEAF_WIDTH))
    n = bz.isolate(b, 1e-15 * np.abs(b).max(), 0.0, out, np.zeros((96, 12)))
    assert n >= 0
    leaves = out[:n]
    for r in roots:
        holding = [lf for lf in leaves if lf[1] <= r <= lf[2] and lf[0] != bz.LEAF_NEAR]
        assert holding, (r, leaves[:, :3])
    for lf in leaves[leaves[:, 0] == bz.LEAF_ROOT]:
        assert sum(lf[1] < r < lf[2] for r in roots) == 1
        s = lf[1] + bz.refine_root(lf[4:], lf[3]) * (lf[2] - lf[1])
        assert min(abs(s - r) for r in roots) <= 1e-6
    assert sum(lf[0] == bz.LEAF_ROOT for lf in leaves) <= len(roots)


def test_two_roots_closer_than_double_precision_separates_are_a_cluster_not_a_loss():
    """Roots 1e-13 apart: double precision cannot tell them apart; the piece holding them is a
    cluster (sent to the extended path), never excluded."""
    r = 0.3
    b = _bernstein_of_roots([r, r + 1e-13, 0.7, 0.8], 1.0)
    out = np.zeros((bz.N_LEAF, bz.LEAF_WIDTH))
    n = bz.isolate(b, 64 * 2.2e-16 * np.abs(b).max(), 0.0, out, np.zeros((96, 12)))
    kinds = {int(lf[0]) for lf in out[:n] if lf[1] <= r <= lf[2]}
    assert kinds == {bz.LEAF_CLUSTER}


_NORMAL = st.one_of(st.just(0.0), st.floats(1e-140, 1e10), st.floats(-1e10, -1e-140))


@given(_NORMAL, _NORMAL)
def test_double_double_products_and_sums_are_exact(a, b):
    """two_prod and two_sum are error-free (compared with exact rationals), away from underflow."""
    p, e = dd.two_prod(a, b)
    assert Fraction(p) + Fraction(e) == Fraction(a) * Fraction(b)
    s, e = dd.two_sum(a, b)
    assert Fraction(s) + Fraction(e) == Fraction(a) + Fraction(b)


def test_double_double_resolves_what_double_cannot():
    """(1 + 2^-30)^2 - 1 - 2^-29 = 2^-60: 0 in double precision, exact in double-double."""
    x = 1.0 + 2.0 ** -30
    h, lo = dd.dd_mul(x, 0.0, x, 0.0)
    h, lo = dd.dd_add(h, lo, -1.0, 0.0)
    h, lo = dd.dd_add(h, lo, -(2.0 ** -29), 0.0)
    assert x * x - 1.0 - 2.0 ** -29 == 0.0
    assert h + lo == 2.0 ** -60


# ----------------------------------------------------------------------------- consistency
def test_solve_many_and_solve_batch_match_solve():
    q, T = family_poses(20, seed=103)
    many = iik.solve_many(T, THESIS_ARM, within_limits=False)
    batch = iik.ik.solve_batch(T, THESIS_ARM, within_limits=False)
    assert np.all(batch.count == [r.count for r in many])
    for i, r in enumerate(many):
        one = iik.solve(T[i], THESIS_ARM, within_limits=False)
        assert np.array_equal(one.q, r.q) and one.free_joints == r.free_joints
        assert np.array_equal(batch.q[i, :r.count], r.q)
        assert np.array_equal(batch.position_residual[i, :r.count], r.position_residual)
        assert np.all(np.isnan(batch.q[i, r.count:]))


def test_parallel_option_gives_the_same_answers():
    _q, T = family_poses(30, seed=104)
    serial = iik.ik.solve_batch(T, THESIS_ARM)
    par = iik.ik.solve_batch(T, THESIS_ARM, options=iik.ik.IKOptions(parallel=True))
    assert np.array_equal(serial.count, par.count)
    assert np.array_equal(np.nan_to_num(serial.q), np.nan_to_num(par.q))


def test_reported_residuals_are_those_of_fk():
    """The residuals in the result are |fk(q) - T| and rotation_angle(fk(q), R), recomputed here."""
    _q, T = family_poses(10, seed=105)
    for Ti, r in zip(T, iik.solve_many(T, THESIS_ARM, within_limits=False), strict=True):
        F = iik.fk(r.q, THESIS_ARM)
        assert np.allclose(r.position_residual, np.linalg.norm(F[:, :3, 3] - Ti[:3, 3], axis=1), atol=1e-16)
        assert np.allclose(r.rotation_residual, iik.rotation_angle(F[:, :3, :3], Ti[:3, :3]), atol=1e-15)
        assert np.array_equal(r.within_limits, ARM.within_limits(r.q))  # the one limit test


BAD_POSES = [
    (np.full((4, 4), np.nan), "NaN"),
    (np.eye(4) + np.diag([0, 0, 0, np.inf]), "NaN or inf"),
    (np.eye(3), "shape"),
    (np.zeros((2, 2, 4, 4)), "shape"),
    (np.diag([1.0, 2.0, 1.0, 1.0]), "orthonormal"),
    (np.diag([1.0, 1.0, -1.0, 1.0]), "det"),
    (np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0.5, 0, 0, 1.0]]), "bottom row"),
    ("pose", "numbers"),
    ([[1, 0], [0, 1, 2]], "array"),
    (np.eye(4, dtype=complex), "complex"),
]


@pytest.mark.parametrize("bad, word", BAD_POSES)
def test_fast_path_and_reference_give_the_same_typed_errors(bad, word):
    errors = []
    for method in ("complete", "reference", "thesis"):
        with pytest.raises(InvalidInputError) as e:
            iik.solve(bad, THESIS_ARM, method=method)
        assert word in str(e.value) and e.value.argument == "T" and isinstance(e.value, IIKError)
        errors.append((type(e.value), str(e.value)))
    assert len(set(errors)) == 1, errors


def test_batch_errors_name_the_index():
    Ts = iik.fk(np.zeros((3, 6)), THESIS_ARM)
    Ts[2, :3, :3] *= 1.01
    for method in ("complete", "reference"):
        with pytest.raises(NotOrthonormalError) as e:
            iik.solve_many(Ts, THESIS_ARM, method=method)
        assert e.value.index == 2 and "index 2" in str(e.value) and e.value.argument == "Ts"
        assert e.value.deviation == pytest.approx(0.0201, rel=1e-3)


# ----------------------------------------------------------------------------- the on-disk cache
_PROGRAM = textwrap.dedent("""
    import numpy as np, iik
    from iik.ik import kernel
    T = iik.fk(np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0]), iik.THESIS_ARM)
    assert iik.fk(np.zeros(6), iik.THESIS_ARM).shape == (4, 4)
    s = kernel.fk_many.stats
    print(sum(s.cache_hits.values()), sum(s.cache_misses.values()), kernel.__file__)
""")


def _read_only_runner(pkg: Path):
    """A command prefix under which ``pkg`` is read-only: file modes for a normal user, a
    read-only bind mount in a private mount namespace for root (who ignores modes)."""
    if os.geteuid() != 0:
        for p in [pkg, *pkg.rglob("*")]:
            p.chmod(p.stat().st_mode & ~0o222)
        return lambda cmd: cmd
    if shutil.which("unshare") is None:
        pytest.skip("running as root without unshare: cannot make a read-only folder")
    probe = subprocess.run(["unshare", "-m", "true"], capture_output=True)
    if probe.returncode != 0:
        pytest.skip("running as root and unshare -m is not permitted: cannot make a read-only folder")
    mount = f"mount --bind {pkg} {pkg} && mount -o remount,ro,bind {pkg} {pkg} && exec \"$@\""
    return lambda cmd: ["unshare", "-m", "sh", "-c", mount, "sh", *cmd]


def test_cache_in_user_folder_when_package_is_read_only_and_keyed_on_all_sources(tmp_path):
    """Issue 10 item 7: with the installed package read-only the compiled kernel is cached in
    the user cache folder and loaded from there by the next process; an edit of
    iik/ik/chain.py (compiled into the kernel) invalidates it."""
    src = Path(iik.__file__).parent
    pkg = tmp_path / "site" / "iik"
    shutil.copytree(src, pkg, ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc"))
    run = _read_only_runner(pkg)
    env = {**os.environ, "PYTHONPATH": str(tmp_path / "site"), "XDG_CACHE_HOME": str(tmp_path / "cache"),
           "HOME": str(tmp_path)}
    env.pop("NUMBA_CACHE_DIR", None)

    def once():
        out = subprocess.run(run([sys.executable, "-c", _PROGRAM]), env=env, cwd=tmp_path,
                             capture_output=True, text=True, timeout=600)
        assert out.returncode == 0, out.stderr
        hits, misses, where = out.stdout.split()
        assert Path(where).parent == pkg / "ik"  # the copy ran, not the worktree
        return int(hits), int(misses)

    assert once() == (0, 1)  # first process compiles ...
    cached = list((tmp_path / "cache").rglob("kernel.fk_many*.nbi"))
    assert cached, "no index in the user cache folder"
    assert not list(pkg.rglob("*.nbi")), "wrote into the read-only package"
    assert once() == (1, 0)  # ... the next one loads it
    if os.geteuid() != 0:
        (pkg / "ik" / "chain.py").chmod(0o644)
    with open(pkg / "ik" / "chain.py", "a") as f:
        f.write("\n# edited\n")
    assert once() == (0, 1)  # the formulas changed: compiled again, not a stale kernel


def test_kernel_runs_as_python_under_numba_disable_jit():
    """NUMBA_DISABLE_JIT=1 (how one steps through the kernel in a debugger) gives plain Python
    functions: same solutions, no cache machinery (which needs a compiled dispatcher)."""
    code = ("import numpy as np, iik; q = np.array([0.3, -0.5, 0.7, 0.4, -0.6, 0.2]); "
            "r = iik.solve(iik.fk(q, iik.THESIS_ARM), iik.THESIS_ARM); "
            "print(min(np.max(np.abs(np.angle(np.exp(1j * (row - q))))) for row in r.q))")
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert float(out.stdout) < 1e-9
