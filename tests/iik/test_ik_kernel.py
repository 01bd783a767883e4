"""The compiled IK kernel (method "complete") against the NumPy reference, its input
checks against the reference path's, solve / solve_many / solve_batch consistency, and the
on-disk cache (read-only package folder, invalidation by an edit of the formulas)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import iik
from iik.errors import IIKError, InvalidInputError, NotOrthonormalError
from iik.ik.compare import contains, free_joints_of

ARM = iik.THESIS_ARM
LO, HI = ARM.q_min, ARM.q_max


def family_poses(n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """q (7 n, 6) and fk(q): random, and the singular families of the recovery sweep
    (theta4 ~ 0, theta5 ~ 0, theta3 ~ +-90 deg, theta1 at +-160 deg), offsets 0 or 10^U(-12, -2)."""
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
    return q, iik.fk(q)


def agreement(T: np.ndarray) -> tuple[int, list[int]]:
    """Compare the kernel with the reference on poses T: (poses compared, indices that differ).

    Two solution sets agree if every solution of each is among the other's
    (:func:`iik.ik.compare.contains`: to 1e-9 rad, or the accuracy the pose carries near a
    singularity, or on a flagged continuum), i.e. the same sets after wrapping.
    """
    kern = iik.solve_many(T, within_limits=False)
    ref = iik.solve_many(T, within_limits=False, method="reference")
    bad = []
    for i, (a, b) in enumerate(zip(kern, ref, strict=True)):
        ok = all(contains(b.q, row, T[i], ARM, free_joints=b.free_joints) for row in a.q)
        ok &= all(contains(a.q, row, T[i], ARM, free_joints=a.free_joints) for row in b.q)
        if not ok:
            bad.append(i)
    return len(T), bad


def test_kernel_agrees_with_reference():
    """Always-run version of the 10^5-pose agreement: 7 x 300 poses (random and singular families)."""
    _q, T = family_poses(300, seed=101)
    n, bad = agreement(T)
    assert n == 2100 and bad == [], bad[:5]


@pytest.mark.slow
def test_kernel_agrees_with_reference_on_1e5_poses():
    """Issue 10 item 6: the kernel and the NumPy reference give the same solution sets on >= 10^5 poses."""
    _q, T = family_poses(15_000, seed=102)  # 105 000 poses
    n, bad = agreement(T)
    assert n >= 100_000 and bad == [], (len(bad), bad[:5])


#: The pose the recovery sweep missed (theta5 ~ 0 family, seed 20120101, index 37445): theta4 ~ -4e-4
#: and theta5 ~ -8e-10 put it near the theta3/theta6 continuum (sigma_min(J) ~ 5e-9), where F is
#: flat at its rounding level and the degree-8 root was 2.4e-5 rad off; its polish stalled in the
#: valley 4e-3 rad from q at residual 3e-11 (a curved path within the tolerance joins the two,
#: but the exact root itself was missing).
SWEEP_MISS = np.array([1.8089656803384133, -1.949406613634231, 1.3741108543885727, -0.00038877210366772275,
                       -8.382657476354402e-10, 2.5880086775654725])


def test_pose_missed_by_the_recovery_sweep_is_recovered_exactly():
    T = iik.fk(SWEEP_MISS)
    r = iik.solve(T, within_limits=False)
    d = np.max(np.abs((r.q - SWEEP_MISS + np.pi) % (2 * np.pi) - np.pi), axis=1)
    i = int(np.argmin(d))
    assert d[i] <= 1e-6 and r.position_residual[i] <= 1e-13 and r.rotation_residual[i] <= 1e-13
    assert contains(r.q, SWEEP_MISS, T, ARM, free_joints=r.free_joints)
    n, bad = agreement(T[None])
    assert bad == []


def near_continuum_poses(n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """Poses of the sweep miss's kind: |theta4| in 10^[-4.5, -2.5], |theta5| in 10^[-12, -6] (the
    near theta3/theta6 continuum, where the eliminant is flat at rounding level)."""
    rng = np.random.default_rng(seed)
    q = rng.uniform(LO, HI, size=(n, 6))
    q[:, 3] = rng.choice([-1.0, 1.0], n) * 10 ** rng.uniform(-4.5, -2.5, n)
    q[:, 4] = rng.choice([-1.0, 1.0], n) * 10 ** rng.uniform(-12, -6, n)
    return q, iik.fk(q)


def recovered(q: np.ndarray, T: np.ndarray) -> list[int]:
    """Indices whose generating q is not among the kernel's solutions."""
    b = iik.ik.solve_batch(T, within_limits=False)
    return [i for i in range(len(q)) if not contains(b.q[i, :b.count[i]], q[i], T[i], ARM,
                                                      free_joints=free_joints_of(b.free[i, :b.count[i]]))]


def test_near_continuum_poses_are_recovered():
    """The sweep miss's kind, 5000 poses (the kernel before the fix missed ~2 per 1000 of them)."""
    q, T = near_continuum_poses(5000, seed=106)
    assert recovered(q, T) == []


@pytest.mark.slow
def test_near_continuum_poses_are_recovered_thorough():
    q, T = near_continuum_poses(100_000, seed=107)
    assert recovered(q, T) == []


#: The wrist point on the joint-1 axis to 1e-16 m: the eliminant's double roots (where Eq 8
#: vanishes) come out as pairs of simple roots 2.4e-5 rad apart; refined on f_sigma both land
#: where Eq 8 vanishes, and there theta2 has the two Eq 11 options (one was lost once).
ON_AXIS = np.array([1.9807956984317099, -1.8113215801070661, 0.0, -0.002596077066196578, 1.4226199670433592,
                    -2.6792027325122807])


def test_wrist_point_on_the_joint1_axis():
    from verification.testing.ik_benchmark import family_joints

    q = np.concatenate([ON_AXIS[None], family_joints("wrist point on joint-1 axis", 300,
                                                       np.random.default_rng(108), ARM)])
    T = iik.fk(q)
    assert recovered(q, T) == []
    _n, bad = agreement(T)
    assert bad == []


def test_solve_many_and_solve_batch_match_solve():
    q, T = family_poses(20, seed=103)
    many = iik.solve_many(T, within_limits=False)
    batch = iik.ik.solve_batch(T, within_limits=False)
    assert np.all(batch.count == [r.count for r in many])
    for i, r in enumerate(many):
        one = iik.solve(T[i], within_limits=False)
        assert np.array_equal(one.q, r.q) and one.free_joints == r.free_joints
        assert np.array_equal(batch.q[i, :r.count], r.q)
        assert np.array_equal(batch.position_residual[i, :r.count], r.position_residual)
        assert np.all(np.isnan(batch.q[i, r.count:]))


def test_parallel_option_gives_the_same_answers():
    _q, T = family_poses(30, seed=104)
    serial = iik.ik.solve_batch(T)
    par = iik.ik.solve_batch(T, options=iik.ik.IKOptions(parallel=True))
    assert np.array_equal(serial.count, par.count)
    assert np.array_equal(np.nan_to_num(serial.q), np.nan_to_num(par.q))


def test_reported_residuals_are_those_of_fk():
    """The residuals in the result are |fk(q) - T| and rotation_angle(fk(q), R), recomputed here."""
    _q, T = family_poses(10, seed=105)
    for Ti, r in zip(T, iik.solve_many(T, within_limits=False), strict=True):
        F = iik.fk(r.q)
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
            iik.solve(bad, method=method)
        assert word in str(e.value) and e.value.argument == "T" and isinstance(e.value, IIKError)
        errors.append((type(e.value), str(e.value)))
    assert len(set(errors)) == 1, errors


def test_batch_errors_name_the_index():
    Ts = iik.fk(np.zeros((3, 6)))
    Ts[2, :3, :3] *= 1.01
    for method in ("complete", "reference"):
        with pytest.raises(NotOrthonormalError) as e:
            iik.solve_many(Ts, method=method)
        assert e.value.index == 2 and "index 2" in str(e.value) and e.value.argument == "Ts"
        assert e.value.deviation == pytest.approx(0.0201, rel=1e-3)


# ----------------------------------------------------------------------------- the on-disk cache
_PROGRAM = textwrap.dedent("""
    import numpy as np, iik
    from iik.ik import kernel
    T = iik.fk(np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0]))
    assert iik.fk(np.zeros(6)).shape == (4, 4)
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
    iik/kinematics.py (compiled into the kernel) invalidates it."""
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
        (pkg / "kinematics.py").chmod(0o644)
    with open(pkg / "kinematics.py", "a") as f:
        f.write("\n# edited\n")
    assert once() == (0, 1)  # the formulas changed: compiled again, not a stale kernel


def test_kernel_runs_as_python_under_numba_disable_jit():
    """NUMBA_DISABLE_JIT=1 (how one steps through the kernel in a debugger) gives plain Python
    functions: same solutions, no cache machinery (which needs a compiled dispatcher)."""
    code = ("import numpy as np, iik; q = np.array([0.3, -0.5, 0.7, 0.4, -0.6, 0.2]); "
            "r = iik.solve(iik.fk(q)); "
            "print(min(np.max(np.abs(np.angle(np.exp(1j * (row - q))))) for row in r.q))")
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert float(out.stdout) < 1e-9
