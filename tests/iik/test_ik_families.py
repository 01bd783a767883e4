"""Issue 17 item 1: the complete IK on the adversarial families
(:mod:`verification.testing.families`), on the thesis arm and the FANUC CRX-10iA.

Per family and arm, three properties, each of which could fail:

* the kernel recovers the generating q* (within the limits too, when q* is inside them), or
  its certificate fails and says why (issue 17: never silently fewer); every row reaches the
  pose by the oracle's independent forward kinematics; the continuum families come back
  flagged;
* wherever the kernel certifies its answer, it and the NumPy reference's are the same set
  (issue 17 item 4): every row of each is in the other (within 1e-9 rad, connected within the
  tolerance, or on one of its continua);
* on a sample, every solution of the dense multi-start Levenberg-Marquardt oracle (256
  starts, independent of the kernel) is in the kernel's answer, or the certificate fails.

How often the certificate fails, per family, is the recovery table's business
(``python benchmarks/bench_ik.py --recovery N --arm NAME``).

Sizes: a few examples per family in CI (``CI=1``, derandomised), many in the ``thorough``
profile (``HYPOTHESIS_PROFILE=thorough``: 10^5 poses per family for the kernel).
"""

import os

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings

import iik
from iik import arms
from iik.ik import layout as L
from iik.ik.angles import angle_distance
from iik.ik.members import RESOLUTION, STEP, along, follow
from verification.oracles.multistart import OracleOptions, multistart_ik, pose_residuals_np
from verification.testing.completeness import agreement, contains, coverage
from verification.testing.families import FAMILIES, applicability, family_configurations

ARMS = ("thesis", "crx10ia")
_THOROUGH = os.environ.get("HYPOTHESIS_PROFILE") == "thorough"
#: Examples per family and arm: kernel recovery, kernel against the reference, the oracle.
RECOVERY = 100_000 if _THOROUGH else 12
REFERENCE = 5_000 if _THOROUGH else 3
ORACLE = 500 if _THOROUGH else 1
BATCH = 2_000 if _THOROUGH else 8
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
#: Beside the theta1 continuum (D within ~1e-9 ... 1e-3 m of the joint-1 axis, theta4 = 0 or pi)
#: the configurations within the tolerance form a band of joint 1 on each wrist branch; each
#: band comes back as one row flagged as a numerical continuum of joint 1 (issue 17 item 3). The
#: NumPy reference returns isolated points of a band instead (the kernel's band row is often
#: farther than NEAR from all of them: 6 of 94 certified poses of 150, default_rng(5)); band
#: answers are not certified, so the set test skips them. On some poses the oracle itself finds nothing (7
#: of 40, theta4 = 0 and pi both: its Levenberg-Marquardt starts stall at 1e-8 ... 1e-10 in the
#: valley beside the band, with 1000 iterations too, and Gauss-Newton polishing does not get them
#: lower), so such a pose cannot be checked against it and another is drawn (hypothesis.assume).
BANDS = "near-wrist-on-axis1-theta4"


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


#: The continuum code (iik.ik.layout FREE_*) of each kind of row.
_CODES = {"collinear": L.FREE_Q3, "theta1": L.FREE_Q1, "theta2": L.FREE_Q2, "numerical": L.FREE_NUMERICAL}


def _code(row_continua) -> int:
    if not row_continua:
        return L.FREE_NONE
    c = row_continua[0]
    return L.FREE_BAND if c.band else _CODES[c.kind]


@pytest.mark.parametrize("within", [True, False], ids=["within", "all"])
@pytest.mark.parametrize("arm_name, fam", _CASES)
def test_solve_batch_is_solve_many_as_arrays(arm_name, fam, within):
    """solve_batch returns solve_many's answer as padded arrays on every family: the same rows,
    residuals, flags, continuum codes and certificate (it used to return the kernel's raw rows
    where solve_many sorts them: theta1 continua and bands, continuum rows outside the limits)."""
    arm = _arm_and_family(arm_name, fam)
    T = iik.fk(fam.sample(arm, np.random.default_rng(7), BATCH), arm)
    many = iik.solve_many(T, arm, within_limits=within)
    b = iik.ik.solve_batch(T, arm, within_limits=within)
    for i, r in enumerate(many):
        k = r.count
        assert b.count[i] == k, (i, T[i].tolist())
        assert np.array_equal(b.q[i, :k], r.q) and np.all(np.isnan(b.q[i, k:]))
        pairs = ((b.position_residual, r.position_residual), (b.rotation_residual, r.rotation_residual),
                 (b.within_limits, r.within_limits), (b.approximate, r.approximate))
        for got, want in pairs:
            assert np.array_equal(got[i, :k], want), i
        assert b.free[i, :k].tolist() == [_code(c) for c in r.continua], i
        assert b.certified[i] == r.certificate.certified, (i, r.certificate)


@pytest.mark.parametrize("arm_name, fam", _CASES)
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
        only = ("kernel only", k.q[list(a.only_a)], "reference only", ref.q[list(a.only_b)])
        assert a.same, (q.tolist(), *only)

    check()


@pytest.mark.parametrize("arm_name, fam", _CASES)
def test_family_contains_every_oracle_solution(arm_name, fam):
    arm = _arm_and_family(arm_name, fam)

    @settings(max_examples=ORACLE, suppress_health_check=_SLOW)
    @given(family_configurations(fam, arm))
    def check(q):
        T = iik.fk(q, arm)
        r = _solve(T, arm)
        oracle = multistart_ik(T, arm, OracleOptions(starts=256))
        if fam.name == BANDS:
            assume(len(oracle.q) >= 1)  # the oracle stalls beside the band: nothing to check against
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
    return r.rows(np.arange(r.count) != i)


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
        for c in (cs[0] for cs in r.continua if cs):  # only bands of joint 1 are flagged here
            assert (c.kind, c.free_joint, c.coupled_joint) == ("numerical", 1, None), c
        pres, rres = pose_residuals_np(arm, r.q, T)  # (the kernel's approximate candidates are left out)
        assert np.all(pres <= TOL[0]) and np.all(rres <= TOL[1]), (pres, rres)


def test_the_reference_joins_the_points_of_a_tube_beside_the_collinear_continuum():
    """A thesis-arm pose of split-both (default_rng(235722)) 1e-3 rad from the collinear continuum
    (theta4 ~ 1e-3, theta5 ~ pi): the reference's rows along the tube there lie up to 7e-3 rad
    apart. Its straight-segment test (to 1e-3 rad) did not join them: they filled its 16 rows and
    the two isolated solutions at theta1 = 2.46 (found by the oracle, and by the kernel, certified)
    were cut. Bent paths (each joint held in turn, to 1e-2 rad) join them: the two answers are
    one set, which holds every oracle solution."""
    arm = arms.get("thesis")
    q = np.array([-0.6830519685746785, 1.9389377494343343, -1.5707963267948968, -0.0010571446595228906,
                  3.142289875470784, -0.7675823061163234])
    T = iik.fk(q, arm)
    k, ref = _solve(T, arm), _solve(T, arm, method="reference")
    assert ref.count < L.MAX_SOLUTIONS and ref.certificate.reason == "", ref.certificate
    assert k.certificate.certified and contains(k, q, T, arm, TOL) and contains(ref, q, T, arm, TOL)
    assert agreement(k, ref, T, arm, TOL).same
    oracle = multistart_ik(T, arm, OracleOptions(starts=256))
    assert len(coverage(k, oracle, T, arm, TOL).missed) == 0 == len(coverage(ref, oracle, T, arm, TOL).missed)


@pytest.mark.parametrize("method", ["reference", "thesis"])
def test_a_numpy_method_says_when_it_left_rows_out(monkeypatch, method):
    """With room for fewer rows than a pose has solutions (MAX_SOLUTIONS set to 2 for a generic
    pose with 4), the NumPy methods keep 2 of their solutions and their certificate says rows
    were left out; with room for all, it does not."""
    arm = arms.get("thesis")
    T = iik.fk(np.array([0.3, -0.7, 1.1, 0.4, 0.9, -0.5]), arm)
    full = _solve(T, arm, method=method)
    assert full.count > 2 and full.certificate.reason == ""
    monkeypatch.setattr(L, "MAX_SOLUTIONS", 2)
    r = _solve(T, arm, method=method)
    assert r.count == 2 and r.certificate.reason == L.CERT_NAMES[L.CERT_ROWS_DROPPED], r.certificate
    assert all(np.min(angle_distance(full.q, row), initial=np.inf) <= 1e-12 for row in r.q)


def test_an_answer_with_bands_of_joint_1_is_not_certified():
    """The 59043rd pose of near-wrist-on-axis1-theta4 in the 10^5-pose recovery run (seed
    20120101; theta4 = -pi, the wrist point just off the joint-1 axis): the extended path's near
    roots fall along bands of joint 1 and come back as two band rows, which do not contain q*
    (the reference's rows and the oracle's do); the answer was certified. Bands are found by
    restarts, not proven complete, as on the degenerate path: the certificate says so."""
    arm = arms.get("thesis")
    q = np.array([-1.9957743997539352, 2.40968760491771, -2.5876024105265767, -3.141592653589793,
                  0.018838010138340522, -1.4147018580037187])
    T = iik.fk(q, arm)
    r = _solve(T, arm)
    assert any(cs and cs[0].band for cs in r.continua), r.continua
    assert not r.certificate.certified and "bands of joint 1" in r.certificate.reason, r.certificate
    assert contains(_solve(T, arm, method="reference"), q, T, arm, TOL)
    assert not iik.ik.solve_batch(T[None], arm, within_limits=False).certified[0]


def test_a_degenerate_pose_with_no_row_inside_the_limits_takes_the_slow_path_too():
    """A near-wrist-on-axis1-theta4 pose (default_rng(11), the 60th) on the degenerate path whose
    two solutions (bands of joint 1) both have joint 2 outside Table I. With the limits off it
    takes the slow path, uncertified; with them on, the kernel kept no row and the answer was
    empty and *certified*, solve_batch's not. Both now take the slow path, and the reason counts
    the solutions outside the limits (it said configurations within approximate_tol exist)."""
    arm = arms.get("thesis")
    T = np.array([[-0.6510158508580123, 0.2163699840688653, -0.7275729461199457, 0.19280683064164394],
                  [-0.3378712595159934, -0.9409233036764776, 0.022502190818225243, -0.00596308127213642],
                  [-0.6797215414599529, 0.26047527059700426, 0.6856611841738767, 0.22789905547432326],
                  [0.0, 0.0, 0.0, 1.0]])
    every, inside = _solve(T, arm), iik.solve(T, arm)
    assert every.count == 2 and not arm.within_limits(every.q).any()
    for r in (every, inside):
        assert r.certificate.path == "reference" and not r.certificate.certified, r.certificate
    assert inside.count == 0 and inside.reason == "2 solution(s) exist but none within the joint limits"
    batch = iik.ik.solve_batch(T[None], arm)
    assert batch.count[0] == 0 and not batch.certified[0] and batch.path[0] == L.PATH_REFERENCE


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


def _member_at(r, q):
    """The continuum member of result r nearest q (6,) at q's value of each free joint."""
    members = [c.member(float(q[c.free_joint - 1])) for cs in r.continua for c in cs]
    return min(members, key=lambda m: float(angle_distance(m, q)), default=None)


def test_the_wrist_flip_of_a_band_beside_the_theta1_continuum_is_returned():
    """A thesis-arm pose of near-wrist-on-axis1-theta4 (one of 7 certified misses of the 10^5-pose
    recovery run): the wrist point just off the joint-1 axis, so the configurations within the
    tolerance form a band of joint 1 (1.93 ... 2.12 rad) on each of two wrist branches (joint 3
    turned by pi, joint 5 negated, joint 6 turned by pi). The kernel's only exact rows came from
    the tube restarts of one wrist branch, so only that branch came back, flagged a theta1
    continuum and certified; q* (3 rad away in joint 3) was lost. Now both branches come back,
    q* is the member at its joint 1, and the certificate says the band is not proven complete."""
    arm = arms.get("thesis")
    q = np.array([2.0892141898825627, -1.8104374472579947, -2.2258776810259655, 4.7e-17,
                  -0.009284016978601706, 2.204080270915197])
    T = iik.fk(q, arm)
    r = iik.solve(T, arm)
    assert arm.within_limits(q)
    m = _member_at(r, q)
    assert m is not None and float(angle_distance(m, q)) <= 1e-7, (r.q, m)
    pres, rres = pose_residuals_np(arm, m[None], T)
    assert pres[0] <= TOL[0] and rres[0] <= TOL[1]
    assert contains(r, q, T, arm, TOL)
    assert not r.certificate.certified and r.certificate.reason


def test_a_band_of_joint_1_on_the_extended_path_comes_back_as_one_flagged_row_per_band():
    """A thesis-arm pose of near-wrist-on-axis1-theta4 (the CI profile's oracle example,
    default_rng(430595)): D farther from the joint-1 axis than the degenerate path reaches, so the
    eliminant's near roots fall along two bands of joint 1 (one per wrist branch): ten isolated
    rows came back, none flagged, and the oracle found a point of a band 0.034 rad beyond them.
    Each band is now one row flagged as a numerical continuum of joint 1 whose members reach
    the pose over its interval (checked by the oracle's own forward kinematics), and the oracle's
    solutions are all in the answer."""
    arm = arms.get("thesis")
    q = np.array([-0.8170401360576565, -1.8104374182194671, -2.3896215974600126, 1.0491683545722488e-16,
                  1.9962914265410103, -2.600105367539886])
    T = iik.fk(q, arm)
    r = _solve(T, arm)
    assert r.count >= 1 and all(cs for cs in r.continua), (r.q, r.free_joints)
    for cs in r.continua:
        c = cs[0]
        assert (c.kind, c.free_joint, c.coupled_joint) == ("numerical", 1, None)
        lo, hi = c.interval
        assert hi - lo > 1e-3, (lo, hi)
        # the ends are known to RESOLUTION (members there sit at the tolerance, and a member
        # marched from the representative can land 1e-15 m beyond the one the bisection found)
        xs = np.r_[lo + RESOLUTION, np.linspace(lo, hi, 7)[1:-1], hi - RESOLUTION]
        pres, rres = pose_residuals_np(arm, np.array([c.member(x) for x in xs]), T)  # (the oracle's FK)
        assert np.all(pres <= TOL[0]) and np.all(rres <= TOL[1]), (pres, rres)
    for i, a in enumerate(r.continua):  # one row per band: no row lies on another row's band
        for j in range(r.count):
            if j != i:
                assert float(angle_distance(a[0].member(float(r.q[j, 0])), r.q[j])) > 1e-3
    assert contains(r, q, T, arm, TOL)
    oracle = multistart_ik(T, arm, OracleOptions(starts=256))
    assert len(oracle.q) >= 1
    assert len(coverage(r, oracle, T, arm, TOL).missed) == 0


def test_a_theta1_continuum_is_followed_through_a_near_wrist_singularity():
    """The 15072nd pose of wrist-on-axis1 in the 10^5-pose recovery run (seed 20120101; theta4 = 0,
    q* inside Table I): its two theta1 continua (one per sign of theta5) pass within 5e-3 rad of
    theta5 = 0 near theta1 = 0.08, where joints 3 and 6 swing by ~pi within 0.02 rad of joint 1. A
    whole march step (0.05 rad) landed on the other branch there, so a member depended on where
    the march began: with the limits on (representatives moved into Table I) both continua's
    members at q*'s joint 1 were one configuration, and q* was lost from a certified answer. The
    march halves its steps where a member jumps: each continuum stays on its branch (theta5 keeps
    its sign, the two are pi apart), and its members are the same from either representative."""
    arm = arms.get("thesis")
    q = np.array([1.7588670851618784, -1.8104375170509364, -2.387011352223242, 2.6627679061888805e-17,
                  0.3588719523073025, -2.987480354833726])
    T = iik.fk(q, arm)
    grid = np.linspace(-np.pi, np.pi, 145)
    members = {}
    for within in (True, False):
        r = iik.solve(T, arm, within_limits=within)
        assert r.certificate.certified and contains(r, q, T, arm, TOL), (within, r.certificate)
        (a, ra), (b, rb) = (follow(cs[0], grid) for cs in r.continua)
        assert np.all(ra <= TOL) and np.all(rb <= TOL)
        assert len(set(np.sign(a[:, 4]))) == len(set(np.sign(b[:, 4]))) == 1
        assert np.all(angle_distance(a, b) > 3.0)
        members[within] = (a, b)
    (a, b), (c, d) = members[True], members[False]
    same = np.minimum(np.maximum(angle_distance(a, c), angle_distance(b, d)),
                      np.maximum(angle_distance(a, d), angle_distance(b, c)))
    assert np.all(same <= 1e-9)


def test_the_feasible_interval_of_a_theta1_continuum_runs_through_its_swing():
    """The continuum through q* of the pose above, with the limits on: its feasible interval
    contains q*'s joint 1, every member across it is inside Table I and reaches the pose, and it
    ends at joint 1's limit or where a member leaves the limits. It used to end at theta1 = 0.063,
    2.5 rad short, where the curve swings (a jump between march steps was taken for a lost curve),
    and the members the selection samples (:func:`iik.ik.members.along`) stopped there too."""
    arm = arms.get("thesis")
    q = np.array([1.7588670851618784, -1.8104375170509364, -2.387011352223242, 2.6627679061888805e-17,
                  0.3588719523073025, -2.987480354833726])
    T = iik.fk(q, arm)
    (c,) = [cs[0] for cs in iik.solve(T, arm).continua if angle_distance(cs[0].member(q[0]), q) <= 1e-9]
    lo, hi = c.interval
    assert lo <= q[0] <= hi
    m, res = follow(c, np.linspace(lo, hi, 201))
    assert np.all(res <= TOL) and all(arm.within_limits(x) for x in m)
    for end, out in ((lo, -1e-4), (hi, 1e-4)):
        if arm.q_min[0] + 1e-9 < end < arm.q_max[0] - 1e-9:
            beyond = follow(c, [end + out])[0][0]
            assert not arm.within_limits(beyond), (end, beyond)
    th, _ = along(c)  # the members the selection samples run from limit to limit of joint 1 too
    assert th[0] == arm.q_min[0] and th[-1] == arm.q_max[0] and np.max(np.diff(th)) <= STEP + 1e-12


@pytest.mark.parametrize(
    "arm_name, q",
    [
        pytest.param("thesis", [-1.9939614126443936, -1.937814267126225, -1.6684914522999492,
                                -1.4712672120374102, -0.7363358381934075, -2.24099615329877],
                     id="thesis-near-double-root"),
        pytest.param("crx10ia", [3.6202928038922595, -2.2712799078594097, -1.5695946974153314,
                                 -3.274124122353042, 0.8496694631858704, 0.40495896950284166],
                     id="crx10ia-cluster"),
        pytest.param("crx10ia", [0.4760137856182406, 0.8433177597867076, 4.712333172586383,
                                 -0.24506781207461112, -0.7623049419992953, 1.9835036629825866],
                     id="crx10ia-two-pairs"),
    ],
)
def test_the_reference_keeps_every_solution_of_a_cluster_of_roots(arm_name, q):
    """Two off-singular poses (default_rng([3, 8]), the 20th on the thesis arm, the 39th on the
    CRX-10iA). Thesis: two solutions 1.2e-3 rad apart (a near-double root, a barrier of 1.6e-9 m
    between them); the reference's bent path held a joint in which they agree (joint 5, 3e-12
    apart), its points slid to either end, and the two were merged. CRX-10iA: three solutions
    whose joint 6 (solver joint 1) lie 1.4e-4 rad apart, on branches of joint 2 radians apart; the
    companion eigenvalues err by ~1e-4 there and every candidate polished onto the middle one,
    until the cluster's roots were found again in extended precision. CRX-10iA two pairs (the
    thorough profile, fam.sample(arm, default_rng(3852), 1)): four solutions whose joint 6 lie
    within 1.7e-5 rad, in two pairs 1e-7 apart; F keeps one sign on every grid over the cluster
    (it is positive only between the two roots of a pair), and the reference returned 8 of the
    kernel's 16 rows until it found the crossings of the two conditions' curves
    (:mod:`iik.ik.crossings`). The reference now returns the kernel's set."""
    arm = arms.get(arm_name)
    T = iik.fk(np.array(q), arm)
    k, ref = _solve(T, arm), _solve(T, arm, method="reference")
    assert k.certificate.certified and ref.count == k.count
    a = agreement(k, ref, T, arm, TOL)
    assert a.same, ("kernel only", k.q[list(a.only_a)], "reference only", ref.q[list(a.only_b)])
