"""The completeness comparator (:mod:`verification.testing.completeness`): an oracle point in a
flat valley of near-solutions beside a continuum, on a sheet where a tube meets another singular
set, or in a multiple root's blob farther than NEAR from its row, is contained by the answer
(through a bent path), and a solution the answer lacks is still reported missing."""

from types import SimpleNamespace

import numpy as np
import pytest

import iik
from iik import arms
from iik.ik.angles import wrap_angle
from verification.oracles.multistart import pose_residuals_np
from verification.testing.completeness import BLOB, NEAR, contains

TOL = (1e-10, 1e-10)

#: CRX-10iA, family elbow-second (pose 23200 of the 10^5 recovery run): the pose has a collinear
#: continuum (joints 4 and 1) that meets another singular set at joint 4 = 0; the oracle's point
#: lies 1.7e-4 rad off it, in the valley where the residual grows as about 8e-4 d^2.
Q_STAR = [1.1780979579439985, 4.734709156498013e-17, 1.570796326794897, 2.2274215101582464,
          -0.05187300885723367, 3.0536666505979175]
VALLEY = [-1.0490103340682018, -8.715011126870802e-05, 1.5706218800210978, 0.00031374573180857786,
          -0.05178571219899359, 3.053666122302938]


def _pose():
    arm = arms.get("crx10ia")
    T = iik.fk(np.array(Q_STAR), arm)
    return arm, T, iik.solve(T, arm, within_limits=False)


def test_an_oracle_point_in_the_valley_beside_a_continuum_is_contained_by_it():
    arm, T, r = _pose()
    q = np.array(VALLEY)
    pres, rres = pose_residuals_np(arm, q[None], T)
    assert pres[0] <= TOL[0] and rres[0] <= TOL[1]  # the oracle's point reaches the pose
    (c,) = [c for row in r.continua for c in row]
    member = c.member(float(q[c.free_joint - 1]))
    assert np.max(np.abs(wrap_angle(member - q))) > 1e-4  # and is far from the continuum's member
    assert contains(r, q, T, arm, TOL)


def test_without_the_continuum_row_the_valley_point_is_missed():
    arm, T, r = _pose()
    keep = [i for i, row in enumerate(r.continua) if not row]
    lacking = SimpleNamespace(q=r.q[keep], continua=tuple(r.continua[i] for i in keep))
    assert not contains(lacking, np.array(VALLEY), T, arm, TOL)


def test_a_generic_solution_left_out_of_the_answer_is_missed():
    arm = arms.get("crx10ia")
    rng = np.random.default_rng(3)
    for q in rng.uniform(arm.q_min, arm.q_max, (5, 6)):
        T = iik.fk(q, arm)
        r = iik.solve(T, arm, within_limits=False)
        assert contains(r, q, T, arm, TOL)
        d = np.max(np.abs(wrap_angle(r.q - q)), axis=1)
        lacking = SimpleNamespace(q=r.q[d > 1e-7], continua=())
        assert not contains(lacking, q, T, arm, TOL)


#: Thesis arm, family near-continuum-equal (default_rng(1), the 217th pose): q* is 4e-8 rad from
#: the collinear continuum, the kernel's tube row is a numerical continuum of joint 3, and the
#: oracle's point lies at joint 3 = 90 deg, 2.6e-4 rad off the tube's member there. Stepping the
#: joint that differs most (joint 6) leaves the tolerance; stepping joint 1 the refit slides
#: along the tube (steps larger than a quarter of the distance, each within the tolerance).
TUBE = ([-1.0903859605951336, -1.9602397198866932, 2.4805366726910125, -4.3950562293041914e-08,
         6.283185333426696, 2.3563604218200993],
        [-1.090519134759254, -1.9602397304037216, 1.5707895899484718, 5.564149725443259e-05,
         -5.089657648717816e-06, 1.4464901369245822])
#: Thesis arm, near-continuum-equal pose 80800 of the 10^5 recovery run (seed 20120101): the
#: oracle's point lies at joint 3 = -90 deg + 1e-5, 7.5e-5 rad off the tube (two small singular
#: values there: 5e-6 and 2e-7, a sheet). Stepping joint 1 toward the tube, the refit reaches it
#: and then slides along it by 1.1e-2 rad (more than NEAR) in one step: the path ends before.
SHEET = ([-0.9259368357637954, -1.8609686071112546, -1.8022093327182838, 1.260571675299938e-08,
          6.283185297231939, 0.1490562877807049],
         [-0.9260068733855551, -1.8609686060504673, -1.5707852833070783, -1.0018836874091203e-05,
          -1.0017551613069706e-05, 0.3804132275211096])
#: Thesis arm, elbow-second (default_rng([3, 4]), the 10th pose): the eliminant has a triple root
#: at theta1 = 0.31173 on the singular set, where the configurations within the tolerance form a
#: blob spanning 0.027 rad of joint 3. The oracle's point lies 0.023 rad (more than NEAR) from the
#: kernel's row of that blob; stepping joint 1 from it, the refit stays within 8e-11 of the pose
#: all the way to the row.
BLOB_POINT = ([0.3117029499205457, -1.823640812065575, -0.3291874097227363, 1.0635825615916398e-16,
               0.0065952267447348945, -0.2834913609691041],
              [0.31104393883596293, -1.823667526409721, 2.835658345798096, 8.229294530664266e-05,
               -0.006600656669285776, 2.8807168251580735])


def _on_continuum(r, q):
    return [bool(row) for row in r.continua]


def _within_blob(r, q):
    dist = np.max(np.abs(wrap_angle(r.q - q)), axis=1)
    assert NEAR < dist.min() <= BLOB  # (the point is farther than NEAR from every row)
    return list(dist <= BLOB)


@pytest.mark.parametrize(
    "case, rows",
    [
        pytest.param(TUBE, _on_continuum, id="beside-a-near-continuum-tube"),
        pytest.param(SHEET, _on_continuum, id="on-the-sheet-where-a-tube-meets-joint-3-at-90-deg"),
        pytest.param(BLOB_POINT, _within_blob, id="in-a-triple-root-blob-farther-than-NEAR"),
    ],
)
def test_an_oracle_point_is_contained_by_its_rows_and_missed_without_them(case, rows):
    """The thesis arm's oracle point reaches the pose, the kernel's answer contains it, and
    without the rows that hold it (``rows``: the continuum rows, or the rows within BLOB) the
    answer does not (negative control)."""
    arm = arms.get("thesis")
    q_star, q = (np.array(x) for x in case)
    T = iik.fk(q_star, arm)
    r = iik.solve(T, arm, within_limits=False)
    pres, rres = pose_residuals_np(arm, q[None], T)
    assert pres[0] <= TOL[0] and rres[0] <= TOL[1]
    assert contains(r, q, T, arm, TOL)
    keep = [i for i, holds in enumerate(rows(r, q)) if not holds]
    lacking = SimpleNamespace(q=r.q[keep], continua=tuple(r.continua[i] for i in keep))
    assert not contains(lacking, q, T, arm, TOL)
