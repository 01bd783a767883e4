"""The OMPL RRT-Connect fallback on Coal checks (iik.planning.rrt)."""

import subprocess
import sys
import textwrap

import numpy as np
import pytest

from iik import THESIS_ARM
from iik.errors import InvalidInputError
from iik.planning import Box
from iik.planning.collision import SceneCollision
from iik.planning.rrt import rrt_connect


def test_rrt_connect_goes_around_a_box_with_certified_clearance():
    chk = SceneCollision([Box((0.5, 0.0, 0.1), (0.2, 0.2, 0.4), name="pillar")], arm=THESIS_ARM)
    q0 = np.array([0.8, 0.3, 0.0, 0.5, -1.0, 0.0])
    q1 = np.array([-0.8, 0.3, 0.0, 0.5, -1.0, 0.0])
    assert chk.path_clearance(np.array([q0, q1]), 0.03).minimum < 0.03  # the direct motion collides
    P = rrt_connect(q0, q1, chk, required=0.03, time_limit=5.0, seed=7, arm=THESIS_ARM)
    assert P is not None
    assert np.allclose(P[0], q0) and np.allclose(P[-1], q1)
    assert np.abs(np.diff(P, axis=0)).max() <= 0.05 + 1e-12
    assert np.all(THESIS_ARM.within_limits(P))
    pc = chk.path_clearance(P, 0.03)
    assert pc.minimum >= 0.03  # certified on the motions too


_ATTEMPT = textwrap.dedent("""
    import sys, numpy as np
    from iik import THESIS_ARM
    from iik.planning import Box
    from iik.planning.collision import SceneCollision
    from iik.planning.rrt import rrt_connect
    chk = SceneCollision([Box((0.5, 0.0, 0.1), (0.2, 0.2, 0.4), name="pillar")], arm=THESIS_ARM)
    q0, q1 = np.array([0.8, 0.3, 0.0, 0.5, -1.0, 0.0]), np.array([-0.8, 0.3, 0.0, 0.5, -1.0, 0.0])
    np.save(sys.argv[1], rrt_connect(q0, q1, chk, required=0.03, time_limit=30.0, seed=7, arm=THESIS_ARM))
""")


def test_one_seed_gives_one_path_whatever_ran_before_and_ompl_says_nothing(tmp_path, capfd):
    """Issue 20 item 10: the attempt with seed 7 in a fresh process and after other attempts in this
    one (OMPL's generators already started) is the same path, state for state, and OMPL prints no
    'Random number generation already started'."""
    fresh = subprocess.run([sys.executable, "-c", _ATTEMPT, str(tmp_path / "fresh.npy")], capture_output=True,
                           text=True, timeout=300)
    assert fresh.returncode == 0, fresh.stderr
    chk = SceneCollision([Box((0.5, 0.0, 0.1), (0.2, 0.2, 0.4), name="pillar")], arm=THESIS_ARM)
    q0, q1 = np.array([0.8, 0.3, 0.0, 0.5, -1.0, 0.0]), np.array([-0.8, 0.3, 0.0, 0.5, -1.0, 0.0])
    other = rrt_connect(q0, q1, chk, required=0.03, time_limit=30.0, seed=3, arm=THESIS_ARM)
    again = rrt_connect(q0, q1, chk, required=0.03, time_limit=30.0, seed=7, arm=THESIS_ARM)
    np.testing.assert_array_equal(again, np.load(tmp_path / "fresh.npy"))
    assert not (other.shape == again.shape and np.array_equal(other, again))  # the seed does matter
    err = capfd.readouterr().err + fresh.stderr
    assert "Random number generation already started" not in err and "Error" not in err


@pytest.mark.parametrize("seed", [0, -5, 2**32, 1.5, True])
def test_a_seed_ompl_would_ignore_or_wrap_is_refused(seed):
    chk = SceneCollision([], arm=THESIS_ARM)
    with pytest.raises(InvalidInputError) as info:
        rrt_connect(np.zeros(6), np.ones(6) * 0.1, chk, required=0.03, seed=seed, arm=THESIS_ARM)
    assert info.value.argument == "seed"
