"""verification.oracles.example_robots: reference URDFs of example-robot-data."""

from __future__ import annotations

import pytest

from verification.oracles.example_robots import example_robot_urdf


def test_example_robot_urdf_finds_a_shipped_file_and_names_a_missing_one():
    assert example_robot_urdf("ur_description/urdf/ur5_robot.urdf").is_file()
    with pytest.raises(FileNotFoundError, match="none.urdf"):
        example_robot_urdf("nothing_description/urdf/none.urdf")
