"""IK along the path by the effort index (Eq 54) and the orientation search (iik.planning.tracking)."""


import numpy as np
import pytest

import iik
from iik import THESIS_ARM
from iik.arm import thesis_arm
from iik.planning import (
    LIMIT_MARGIN,
    Scenario,
    Tracking,
    Waypoint,
    build_path,
    poses_of,
    track_branches,
    track_dp,
)


@pytest.fixture(scope="module")
def line():
    return build_path(Scenario(name="t", start=Waypoint((0.30, 0.25, -0.35), None, 0.0),
                               goal=Waypoint((0.30, -0.25, -0.35), None, 0.0)))


def test_branches_follow_the_poses_and_report_eq54_effort(line):
    tr = track_branches(line, adapt_orientation=False, arm=THESIS_ARM)
    assert isinstance(tr, Tracking) and tr.complete and tr.failed_steps == ()
    b = tr.branches[0]
    T = iik.fk(b.q, THESIS_ARM)
    P = poses_of(line.points, line.euler)
    assert np.abs(T[:, :3, 3] - P[:, :3, 3]).max() < 1e-8
    assert np.abs(T[:, :3, :3] - P[:, :3, :3]).max() < 1e-6
    eff = np.abs(np.diff(b.q, axis=0)).sum(1) / 6  # Eq 54
    assert np.allclose(b.effort[1:], eff)
    assert np.all(iik.THESIS_ARM.within_limits(b.q, tol=-LIMIT_MARGIN))
    assert np.array_equal(b.counts, tr.solutions_per_step) and np.all(tr.solutions_per_step > 0)
    # the least-effort branch is listed first among complete ones without switches
    same = [x for x in tr.branches if x.complete and len(x.switches) == len(b.switches)]
    assert b.total_effort <= min(x.total_effort for x in same) + 1e-12


def test_each_step_takes_the_least_effort_candidate(line):
    b = track_branches(line, adapt_orientation=False, arm=THESIS_ARM).branches[0]
    for i in range(1, line.n):
        r = iik.solve(poses_of(line.points[i:i + 1], line.euler[i:i + 1])[0], THESIS_ARM)
        cands = r.q[r.within_limits]
        cands = cands[iik.THESIS_ARM.within_limits(cands, tol=-LIMIT_MARGIN)]
        assert b.effort[i] == pytest.approx(iik.effort_index(b.q[i - 1], cands).min(), abs=1e-12)


def test_dynamic_programme_reaches_every_step_within_limits():
    sc = Scenario(name="t", start=Waypoint((0.30, -0.27, 0.45), None, np.radians(45)),
                  goal=Waypoint((0.30, 0.27, 0.45), None, np.radians(45)))
    cp = build_path(sc)
    tr = track_dp(cp, arm=THESIS_ARM)
    assert tr.orientation_search and tr.branches
    b = tr.branches[0]
    assert np.all(iik.THESIS_ARM.within_limits(b.q, tol=-LIMIT_MARGIN))
    assert np.abs(iik.fk(b.q, THESIS_ARM)[:, :3, 3] - cp.points).max() < 1e-8  # position always exact
    assert tr.beta_changed_steps == b.changed_steps("beta")
    assert tr.alpha_changed_steps == b.changed_steps("alpha")
    assert np.allclose(b.effort[1:], np.abs(np.diff(b.q, axis=0)).sum(1) / 6)  # Eq 54


def test_the_arm_sets_the_ik_and_the_joint_limits(line):
    a = iik.THESIS_ARM
    lo, hi = np.array(a.lower), np.array(a.upper)
    free = track_branches(line, adapt_orientation=False, arm=THESIS_ARM)
    q1 = np.concatenate([b.q[:, 0] for b in free.complete])
    narrow = a.with_limits(lower=tuple(np.r_[q1.min() + 0.05, lo[1:]]), upper=tuple(hi))
    assert not all(np.all(narrow.within_limits(b.q, tol=-LIMIT_MARGIN)) for b in free.complete)
    tr = track_branches(line, arm=narrow, adapt_orientation=False)
    assert tr.branches
    for b in tr.branches:  # only the narrower arm's usable solutions are offered
        assert np.all(narrow.within_limits(b.q[b.ok], tol=-LIMIT_MARGIN))
    longer = thesis_arm(a.l1, a.l2, a.l3 * 1.1, a.l4 * 1.1, a.l5)
    b = track_branches(line, arm=longer, adapt_orientation=False).complete[0]
    assert np.abs(iik.fk(b.q, longer)[:, :3, 3] - line.points).max() < 1e-8
    assert np.abs(iik.fk(b.q, THESIS_ARM)[:, :3, 3] - line.points).max() > 0.01  # a different arm's solutions


def _path_of(qs, arm):
    """A CartesianPath through fk(qs) (tool points and Z-Y-Z angles of each configuration)."""
    from iik.planning.cartesian import CartesianPath

    T = iik.fk(qs, arm)
    n = len(qs)
    return CartesianPath(points=T[:, :3, 3], euler=np.array([iik.euler_from_matrix(t[:3, :3]) for t in T]),
                         segment=np.zeros(n, int), key_index=(0, n - 1), via_points=np.zeros((0, 3)),
                         via_numbers=(), routes=("line",), repelled=np.zeros(n, bool),
                         lifted=np.zeros(n, bool), min_ellipsoid_value=np.inf)


def test_tracking_stays_on_a_continuum_instead_of_switching():
    """Issue 20 item 1 in the planner: only theta5 moves, through theta4 = theta5 = 0 (joints 3
    and 6 collinear). The branch that starts at q keeps q's theta3 and theta6: no switch."""
    arm = iik.THESIS_ARM
    qs = np.tile([0.3, -0.5, 0.7, 0.0, 0.0, -0.4], (15, 1))
    qs[:, 4] = np.linspace(-0.3, 0.3, 15)
    cp = _path_of(qs, arm)
    tr = track_branches(cp, arm=arm, adapt_orientation=False)
    b = min(tr.branches, key=lambda b: np.abs(b.q[0] - qs[0]).max())
    assert np.abs(b.q - qs).max() <= 1e-6 and b.switches == ()
    dp = track_dp(cp, arm=arm, offsets=((0.0, 0.0),), half_turn=False)
    best = min(dp.branches, key=lambda b: np.abs(b.q[0] - qs[0]).max())
    assert np.abs(best.q - qs).max() <= 1e-6 and best.switches == ()
