"""Issue 17 item 1: the complete IK on the adversarial families
(:mod:`verification.testing.families`), on the thesis arm and the FANUC CRX-10iA.

Per family and arm, three properties, each of which could fail:

* the kernel recovers the generating q* (within the limits too, when q* is inside them), or
  its certificate fails and says why (issue 17: never silently fewer); every row reaches the
  pose by the oracle's independent forward kinematics; the continuum families come back
  flagged;
* the kernel and the NumPy reference return the same solution sets (rows within 1e-9 rad,
  connected within the tolerance, or on each other's continua) wherever the kernel certifies
  its answer;
* on a sample, every solution of the dense multi-start Levenberg-Marquardt oracle (256
  starts, independent of the kernel) is in the kernel's answer, or the certificate fails.

How often the certificate fails, per family, is the recovery table's business
(``python benchmarks/bench_ik.py --recovery N --arm NAME``).

Sizes: a few examples per family in CI (``CI=1``, derandomised), many in the ``thorough``
profile (``HYPOTHESIS_PROFILE=thorough``: 10^5 poses per family for the kernel).
"""

import dataclasses
import os

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings

import iik
from iik import arms
from verification.oracles.multistart import OracleOptions, multistart_ik, pose_residuals_np
from verification.testing.completeness import agreement, contains, coverage
from verification.testing.families import FAMILIES, applicability, family_configurations

ARMS = ("thesis", "crx10ia")
_THOROUGH = os.environ.get("HYPOTHESIS_PROFILE") == "thorough"
#: Examples per family and arm: kernel recovery, kernel against the reference, the oracle.
RECOVERY = 100_000 if _THOROUGH else 12
REFERENCE = 5_000 if _THOROUGH else 3
ORACLE = 500 if _THOROUGH else 1
TOL = (1e-10, 1e-10)
#: Families whose every pose lies on a continuum (its row must be flagged).
CONTINUUM_FAMILIES = ("continuum", "wrist-on-axis1-theta4")
_SLOW = [HealthCheck.too_slow, HealthCheck.filter_too_much]


def _arm_and_family(arm_name, fam):
    arm = arms.get(arm_name)
    why = applicability(fam, arm)
    if why:
        pytest.skip(why)
    return arm


def _solve(T, arm, **kw):
    return iik.solve(T, arm, within_limits=False, **kw)


_CASES = [pytest.param(a, f, id=f"{a}-{f.name}") for a in ARMS for f in FAMILIES]
#: Known open (issue 17 item 3): beside the theta1 continuum (D within ~1e-9 ... 1e-4 m of the
#: joint-1 axis, theta4 = 0) the configurations within the tolerance form a band in joint 1
#: (0.09 rad wide at 3.4e-7 m), returned as up to 16 isolated rows, not flagged as a continuum;
#: the reference returns other points of the band, and oracle points in it lie farther than
#: NEAR from every row. No solution is lost: q* is recovered (the first test), and where the
#: eliminant is below its rounding the pose takes the slow path.
_BAND = pytest.mark.xfail(reason="the band beside the theta1 continuum is not flagged (issue 17 item 3)",
                          strict=False)
_SET_CASES = [pytest.param(a, f, id=f"{a}-{f.name}", marks=_BAND if f.name.startswith("near-wrist") else ())
              for a in ARMS for f in FAMILIES]


@pytest.mark.parametrize("arm_name, fam", _CASES)
def test_family_recovers_generating_q(arm_name, fam):
    arm = _arm_and_family(arm_name, fam)

    @settings(max_examples=RECOVERY, suppress_health_check=_SLOW)
    @given(family_configurations(fam, arm))
    def check(q):
        T = iik.fk(q, arm)
        r = _solve(T, arm)
        cert = r.certificate
        assert cert.certified == (cert.reason == ""), cert
        if not contains(r, q, T, arm, TOL):  # never silently fewer: only with the certificate failed
            assert not cert.certified, (q.tolist(), r.q, cert)
        pres, rres = pose_residuals_np(arm, r.q, T)
        assert np.all(pres <= TOL[0]) and np.all(rres <= TOL[1]), (q.tolist(), pres, rres)
        if fam.name in CONTINUUM_FAMILIES:
            assert r.has_continuum, (q.tolist(), r.free_joints)
        if arm.within_limits(q, tol=-1e-6) and cert.certified:
            assert contains(iik.solve(T, arm), q, T, arm, TOL), q.tolist()

    check()


@pytest.mark.parametrize("arm_name, fam", _SET_CASES)
def test_family_kernel_and_reference_agree(arm_name, fam):
    arm = _arm_and_family(arm_name, fam)

    @settings(max_examples=REFERENCE, suppress_health_check=_SLOW)
    @given(family_configurations(fam, arm))
    def check(q):
        T = iik.fk(q, arm)
        k, ref = _solve(T, arm), _solve(T, arm, method="reference")
        if not k.certificate.certified:  # the kernel says its answer may be incomplete: no set to compare
            return
        a = agreement(k, ref, T, arm, TOL)
        assert a.same, (q.tolist(), "kernel only", k.q[list(a.only_a)], "reference only",
                        ref.q[list(a.only_b)])

    check()


@pytest.mark.parametrize("arm_name, fam", _SET_CASES)
def test_family_contains_every_oracle_solution(arm_name, fam):
    arm = _arm_and_family(arm_name, fam)

    @settings(max_examples=ORACLE, suppress_health_check=_SLOW)
    @given(family_configurations(fam, arm))
    def check(q):
        T = iik.fk(q, arm)
        r = _solve(T, arm)
        oracle = multistart_ik(T, arm, OracleOptions(starts=256))
        assert len(oracle.q) >= 1
        cov = coverage(r, oracle, T, arm, TOL)
        assert not cov.wrong, (q.tolist(), cov.wrong)
        if len(cov.missed):  # never silently fewer: only with the certificate failed
            assert not r.certificate.certified, (q.tolist(), cov.missed, r.certificate)

    check()


def test_reference_keeps_both_rows_beside_a_multiple_root_blob():
    """A CRX-10iA pose of split-axis6-through-b (found by the CI profile, default_rng(130)): near
    its multiple root the set within the tolerance is a thin curved blob, and the reference once
    kept three points of it as three solutions (the straight segment between them leaves the
    tolerance), hit the 16-row bound and dropped two genuine solutions, both found by the oracle.
    The blob counts once (its points are joined by a refitted path), and the sets agree."""
    arm = arms.get("crx10ia")
    q = np.array([-0.30985614618627055, -3.686893141438525, 0.4801953510974333,
                  -1.5707963267948966, 1.5908015393997852, -0.34233353551891454])
    T = iik.fk(q, arm)
    k, ref = _solve(T, arm), _solve(T, arm, method="reference")
    assert k.certificate.certified
    a = agreement(k, ref, T, arm, TOL)
    assert a.same, ("kernel only", k.q[list(a.only_a)], "reference only", ref.q[list(a.only_b)])
    oracle = multistart_ik(T, arm, OracleOptions(starts=256))
    assert len(coverage(ref, oracle, T, arm, TOL).missed) == 0


def _without(r, i):
    """The answer r without its row i (an IKResult of the other rows)."""
    keep = np.arange(r.count) != i
    return dataclasses.replace(
        r, q=r.q[keep], position_residual=r.position_residual[keep],
        rotation_residual=r.rotation_residual[keep], within_limits=r.within_limits[keep],
        approximate=r.approximate[keep], free_joints=tuple(f for k, f in enumerate(r.free_joints) if k != i),
        continua=tuple(c for k, c in enumerate(r.continua) if k != i))


@pytest.mark.parametrize("q", [
    # split-c-on-axis1 (default_rng(12345), the first pose): 14 rows, 4 per blob
    [-1.5228429309846931, -1.9389377494343343, 1.5707963267948966, 0.7321413897362867,
     -0.4523182541015658, -1.0504610719949992],
    # elbow-second (default_rng(12345), the first pose): 12 rows
    [-1.522842931050155, -1.9378769517288172, 1.660802019889576, 7.8113815147155e-17,
     -0.4523182541015658, -1.0504610719949992],
], ids=["split-c-on-axis1", "elbow-second"])
def test_a_multiple_root_blob_is_one_row_as_in_the_reference(q):
    """At a multiple root of the thesis arm the configurations within the tolerance form a thin
    curved blob (residual ~ d^4 along it); the kernel once kept up to four points of each blob,
    within 1.2e-3 rad of each other, as distinct rows (no straight segment between them stays
    within the tolerance), so such poses came back with 10-16 rows, or with "some were left out"
    at the 16-row bound. Points within CONNECTED joined along the blob (a bent path) are one row
    now, as in the reference: no row is a point of another row's blob (by the comparator's own
    path search), q* is found, and the kernel and the reference agree."""
    arm = arms.get("thesis")
    q = np.array(q)
    T = iik.fk(q, arm)
    k, ref = _solve(T, arm), _solve(T, arm, method="reference")
    assert k.certificate.certified, k.certificate
    assert contains(k, q, T, arm, TOL)
    redundant = [i for i in range(k.count) if contains(_without(k, i), k.q[i], T, arm, TOL)]
    assert redundant == [], (k.q, redundant)
    assert agreement(k, ref, T, arm, TOL).same


def test_a_pose_taken_for_degenerate_keeps_the_near_roots_of_its_eliminant():
    """A thesis-arm pose of singular-second (the 4428th of the 10^5-pose recovery run, seed
    20120101): P, Q and R of Eq 11 are small, so the eliminant is below the degenerate threshold
    on the whole circle and the kernel takes the degenerate path; it once searched the eliminant
    there for exact roots only and lost a near-double one (q* and its wrist flip), certified. It
    keeps the near roots too, as on the other paths."""
    arm = arms.get("thesis")
    q = np.array([3.7010337174830545, -1.4505542057019916, 3.1298324366784582,
                  -1.3023775359917218, 1.1825946301057206, 0.8027795600399259])
    T = iik.fk(q, arm)
    k, ref = _solve(T, arm), _solve(T, arm, method="reference")
    assert contains(k, q, T, arm, TOL), (k.certificate, k.q)
    assert agreement(k, ref, T, arm, TOL).same


def test_a_root_whose_configuration_slid_to_its_neighbour_is_not_certified_as_found():
    """A thesis-arm pose of theta3-band (the 69674th of the 10^5-pose recovery run, seed
    20120101): two roots of the eliminant 4.7e-4 rad apart in joint 1, with the eliminant below
    1e-14 between them. The refinement of q*'s root slid to its neighbour's solution, so q* and
    its wrist flip were lost while the certificate held (every root had *a* configuration). A
    root is now accounted for only by a configuration nearer to it than to any other root; the
    retry finds q*."""
    arm = arms.get("thesis")
    q = np.array([-0.974794838788603, 0.943595896699505, 6.283185318677922, -1.7028367913485023,
                  -0.7836071918919687, 2.970992770483112])
    T = iik.fk(q, arm)
    k, ref = _solve(T, arm), _solve(T, arm, method="reference")
    assert contains(k, q, T, arm, TOL), (k.certificate, k.q)
    assert agreement(k, ref, T, arm, TOL).same


def test_a_degenerate_pose_without_a_theta1_continuum_takes_the_slow_path():
    """Beside the theta1 continuum (near-wrist-on-axis1-theta4: D 4.9e-8 m off the joint-1 axis)
    the eliminant is below its rounding on the whole circle, so the kernel takes the degenerate
    path; no theta1 continuum reaches the pose, and the eliminant's isolated roots cannot be told
    from the rounding: q* was lost, certified. Such a pose's rows are now merged with the NumPy
    reference's (each reaching the pose within the tolerances), and the result says it is not
    certified and why."""
    arm = arms.get("thesis")
    lost = [0.6823775460153216, 1.8104376142146257, -1.5900161816248128, 2.7475096607363555e-17,
            0.46747641876249624, -2.8654968747988607]
    approximate = [-1.0854611518269244, -1.8104375088005231, 0.9864462887468304, 1.2130328826340872e-16,
                   -2.05937232528557, -0.5073489651351157]  # (once returned rows 1.7e-9 m off)
    for q in map(np.array, (lost, approximate)):
        T = iik.fk(q, arm)
        r = _solve(T, arm)
        assert r.certificate.path == "reference" and not r.certificate.certified and r.reason
        assert contains(r, q, T, arm, TOL), r.q
        assert not r.has_continuum
        pres, rres = pose_residuals_np(arm, r.q, T)  # (the kernel's approximate candidates are left out)
        assert np.all(pres <= TOL[0]) and np.all(rres <= TOL[1]), (pres, rres)


def test_a_slow_path_pose_whose_rows_all_miss_the_tolerances_returns_them_flagged_approximate():
    """A near-wrist-on-axis1-theta4 pose (the benchmark's pose 10 of 1000) where neither the
    kernel's rows nor the reference's reach the pose within the tolerances (the kernel's 16 miss
    its position by 3e-10 ... 2.5e-9 m): the slow path had dropped them all and answered
    "unreachable within the joint limits" with the limits off. Now the kernel's rows come back
    flagged approximate, within approximate_tol, and the reason says no exact row was found (q*
    itself, at 4e-16, is still missed: an open case of issue 17, docs/IK_CLASS.md section 6)."""
    arm = arms.get("thesis")
    q = np.array([2.240928731349585, -1.8104375063602773, -0.46671679532235855, -1.9817871048231255e-17,
                  0.037236730500666226, 1.5539680801674205])
    T = iik.fk(q, arm)
    r = _solve(T, arm)
    assert r.certificate.path == "reference" and not r.certificate.certified
    assert r.count and r.approximate.all() and "approximate" in r.reason and "joint limits" not in r.reason
    pres, rres = pose_residuals_np(arm, r.q, T)
    tol = iik.ik.IKOptions().approximate_tol
    assert np.all(pres <= tol) and np.all(rres <= tol), (pres, rres)
    assert np.any((pres > TOL[0]) | (rres > TOL[1]))  # (the rows do miss the tolerances)


def test_a_theta1_continuum_outside_the_limits_does_not_take_the_slow_path():
    """With the limits applied, a theta1 continuum whose members all lie outside them leaves no
    continuum row, but the pose has one: it keeps the kernel's certificate (the slow path is for
    poses where no continuum reaches the pose at all)."""
    arm = arms.get("thesis")
    Q = FAMILIES[[f.name for f in FAMILIES].index("wrist-on-axis1-theta4")].sample(
        arm, np.random.default_rng(5), 20)
    seen = 0
    for q in Q:
        T = iik.fk(q, arm)
        free = _solve(T, arm)
        if not free.certificate.certified or not free.has_continuum:
            continue
        limited = iik.solve(T, arm)
        seen += not limited.has_continuum
        assert limited.certificate.path == "degenerate", limited.certificate
    assert seen, "no pose with its continuum outside the limits among the 20"
