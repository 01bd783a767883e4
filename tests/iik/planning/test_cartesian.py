"""The thesis's Cartesian path: step-points, repulsion, lifting, orientations (iik.planning.cartesian)."""

import dataclasses

import numpy as np

from iik.planning import Box, Scenario, Waypoint, build_path, ellipsoid_value, enclosing_radii, poses_of
from iik.rotations import euler_matrix, pose_from_euler
from iik.scene import THESIS_SCENE


def _scenario(**kw):
    base = dict(name="t", start=Waypoint((0.30, 0.25, -0.35), None, 0.0),
                goal=Waypoint((0.30, -0.25, -0.35), None, 0.0),
                obstacles=(Box((0.32, 0.0, -0.35), (0.12, 0.12, 0.2)),))
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
    keys = cp.key_path()
    assert keys.n == 4 and np.array_equal(keys.points, cp.points[list(cp.key_index)])
    assert keys.key_index == (0, 1, 2, 3)


def test_points_are_lifted_a_safety_zone_above_the_scene_floor():
    floor = THESIS_SCENE.floor.z
    low = _scenario(start=Waypoint((0.45, 0.25, floor + 0.01), None, 0.0),
                    goal=Waypoint((0.45, -0.25, floor + 0.01), None, 0.0), obstacles=())
    free = build_path(low)
    lifted = build_path(low, scene=THESIS_SCENE)
    inner = lifted.points[1:-1]
    assert not free.lifted.any() and lifted.lifted[1:-1].all()
    assert np.allclose(inner[:, 2], floor + low.safety_zone)  # the floor of the scene, not a constant


def test_poses_follow_the_corrected_eq42():
    cp = build_path(_scenario(obstacles=()))
    T = poses_of(cp.points, cp.euler)
    for i in (0, cp.n // 2, cp.n - 1):
        assert np.allclose(T[i], pose_from_euler(cp.points[i], *cp.euler[i]))


def test_slerp_orientation_starts_and_ends_at_the_requested_rotations():
    sc = dataclasses.replace(_scenario(obstacles=()), orientation="slerp",
                             start=Waypoint((0.30, 0.25, -0.35), 0.3, 0.2, 0.0),
                             goal=Waypoint((0.30, -0.25, -0.35), -0.5, 0.6, 0.4))
    cp = build_path(sc)
    R = np.stack([euler_matrix(*e) for e in cp.euler])
    assert np.allclose(R[0], euler_matrix(0.3, 0.2, 0.0), atol=1e-9)
    assert np.allclose(R[-1], euler_matrix(-0.5, 0.6, 0.4), atol=1e-9)
    # rotation angle between consecutive steps is nearly constant (spherical interpolation)
    ang = [np.arccos(np.clip((np.trace(R[i].T @ R[i + 1]) - 1) / 2, -1, 1)) for i in range(len(R) - 1)]
    assert max(ang) - min(ang) < 0.02
