"""`iik solve` command line."""

import json

import numpy as np
import pytest

import iik
from iik.cli import main


def test_solve_json_round_trip(capsys):
    q = np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0])
    T = iik.fk(q)
    a, b, g = iik.zxz_from_matrix(T[:3, :3])
    x, y, z = T[:3, 3]
    rc = main(["solve", "--xyz", str(x), str(y), str(z), "--zxz", *(str(float(v)) for v in (a, b, g)),
               "--previous", *(str(float(v)) for v in q), "--json"])
    assert rc == 0
    out = json.loads(capsys.readouterr().out)
    sols = np.array([s["q"] for s in out["solutions"]])
    assert out["count"] == len(sols) >= 1
    assert np.min(np.max(np.abs(sols - q), axis=1)) <= 1e-8
    sel = out["solutions"][out["selected"]]
    assert np.allclose(sel["q"], q, atol=1e-8) and sel["effort_index"] <= 1e-8
    assert all(s["position_residual_m"] <= 1e-10 for s in out["solutions"])


def test_solve_degrees_and_unreachable(capsys):
    assert main(["solve", "--xyz", "0.3", "0.2", "0.5", "--zxz", "30", "120", "0", "--deg"]) == 0
    assert "solution" in capsys.readouterr().out
    assert main(["solve", "--xyz", "3", "0", "0", "--zxz", "0", "0", "0", "--json"]) == 1  # nothing found
    out = json.loads(capsys.readouterr().out)
    assert out["count"] == 0 and "unreachable" in out["reason"]
    assert main(["solve", "--xyz", "3", "0", "0", "--zxz", "0", "0", "0"]) == 1
    assert capsys.readouterr().out.startswith("no solution: unreachable")


def test_angles_that_look_like_degrees_get_a_warning(capsys):
    argv = ["solve", "--xyz", "0.4", "0.3", "0.2", "--zxz", "180", "120", "0"]
    main(argv)
    err = capsys.readouterr().err
    assert "warning: --zxz 180 120 0 look like degrees" in err and "add --deg" in err
    assert main([*argv, "--deg"]) == 0
    assert "warning" not in capsys.readouterr().err
    main(["solve", *"--xyz 0.4 0.3 0.2 --zxz 3 2 0 --previous 0 90 0 0 0 0".split()])
    assert "warning: --previous 0 90 0 0 0 0 look like degrees" in capsys.readouterr().err


def test_absurd_positions_are_unreachable_without_internal_warnings(capfd):
    assert main(["solve", "--xyz", "1e308", "0", "0", "--zxz", "0", "0", "0"]) == 1
    out, err = capfd.readouterr()
    assert out.startswith("no solution: unreachable") and err == ""


@pytest.mark.parametrize(("argv", "named"), [
    (["--xyz", "nan", "0", "0", "--zxz", "0", "0", "0"], "--xyz: "),
    (["--xyz", "0.4", "0.3", "0.2", "--zxz", "0", "inf", "0"], "--zxz: "),
    (["--xyz", "0.4", "0.3", "0.2", "--zxz", "0", "0", "0", "--previous", "nan", "0", "0", "0", "0", "0"],
     "--previous: "),
])
def test_errors_name_the_option_as_typed(argv, named, capsys):
    assert main(["solve", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("iik solve: error: InvalidInputError: " + named), err
