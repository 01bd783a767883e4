"""The thesis planner: step-points, repulsion, IK along the path (iik.planning.planner)."""

import numpy as np

import iik
from iik.planning import Obstacle, Scenario, Waypoint, build_path, track_branches
from iik.planning.obstacles import ellipsoid_value, enclosing_radii
from iik.planning.planner import poses_of, track_dp


def _scenario(**kw):
    base = dict(name="t", start=Waypoint((0.30, 0.25, -0.35), None, 0.0),
                goal=Waypoint((0.30, -0.25, -0.35), None, 0.0),
                obstacles=(Obstacle((0.32, 0.0, -0.35), (0.12, 0.12, 0.2)),))
    base.update(kw)
    return Scenario(**base)


def test_step_points_keep_out_of_padded_ellipsoids_and_30mm_steps():
    sc = _scenario()
    cp = build_path(sc)
    b = sc.obstacles[0]
    v = ellipsoid_value(cp.points[1:-1], b.center, enclosing_radii(b) + sc.safety_zone)
    assert v.min() >= 1 - 1e-9
    assert cp.repelled.any()
    assert np.linalg.norm(np.diff(cp.points, axis=0), axis=1).max() <= sc.max_step + 1e-9
    assert np.allclose(cp.points[0], sc.start.position) and np.allclose(cp.points[-1], sc.goal.position)


def test_table_iv_via_points_are_inserted():
    sc = _scenario(start=Waypoint((-0.33, 0.38, -0.30), None, 0.0),
                   goal=Waypoint((0.35, -0.1, -0.35), None, 0.0),
                   obstacles=())
    cp = build_path(sc)
    assert cp.via_numbers == (1, 2)
    for k in cp.key_index[1:-1]:
        assert np.min(np.linalg.norm(cp.via_points - cp.points[k], axis=1)) < 1e-12


def test_branches_follow_the_poses_and_report_eq54_effort():
    cp = build_path(_scenario(obstacles=()))
    branches, info = track_branches(cp, adapt_orientation=False)
    assert branches and branches[0].complete
    b = branches[0]
    T = iik.fk(b.q)
    P = poses_of(cp.points, cp.euler)
    assert np.abs(T[:, :3, 3] - P[:, :3, 3]).max() < 1e-8
    assert np.abs(T[:, :3, :3] - P[:, :3, :3]).max() < 1e-6
    eff = np.abs(np.diff(b.q, axis=0)).sum(1) / 6  # Eq 54
    assert np.allclose(b.effort[1:], eff)
    assert np.all(iik.THESIS_ARM.within_limits(b.q))
    # the least-effort branch is listed first among complete ones without switches
    same = [x for x in branches if x.complete and len(x.switches) == len(b.switches)]
    assert b.total_effort <= min(x.total_effort for x in same) + 1e-12


def test_dynamic_programme_reaches_every_step_within_limits():
    sc = _scenario(start=Waypoint((0.30, -0.27, 0.45), None, np.radians(45)),
                   goal=Waypoint((0.30, 0.27, 0.45), None, np.radians(45)), obstacles=())
    cp = build_path(sc)
    branches, info = track_dp(cp)
    assert branches
    b = branches[0]
    assert np.all(iik.THESIS_ARM.within_limits(b.q))
    assert np.abs(iik.fk(b.q)[:, :3, 3] - cp.points).max() < 1e-8  # position always exact


def test_slerp_orientation_starts_and_ends_at_the_requested_rotations():
    import dataclasses

    from iik.rotations import zxz_matrix

    sc = dataclasses.replace(_scenario(obstacles=()), orientation="slerp",
                             start=Waypoint((0.30, 0.25, -0.35), 0.3, 0.2, 0.0),
                             goal=Waypoint((0.30, -0.25, -0.35), -0.5, 0.6, 0.4))
    cp = build_path(sc)
    R = np.stack([zxz_matrix(*e) for e in cp.euler])
    assert np.allclose(R[0], zxz_matrix(0.3, 0.2, 0.0), atol=1e-9)
    assert np.allclose(R[-1], zxz_matrix(-0.5, 0.6, 0.4), atol=1e-9)
    # rotation angle between consecutive steps is nearly constant (spherical interpolation)
    ang = [np.arccos(np.clip((np.trace(R[i].T @ R[i + 1]) - 1) / 2, -1, 1)) for i in range(len(R) - 1)]
    assert max(ang) - min(ang) < 0.02
