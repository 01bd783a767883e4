"""`iik solve` command line."""

import json

import numpy as np
import pytest

import iik
from iik import THESIS_ARM
from iik.cli import main


def test_solve_json_round_trip(capsys):
    q = np.array([0.3, -0.5, 0.7, 1.0, -0.4, 2.0])
    T = iik.fk(q, THESIS_ARM)
    a, b, g = iik.euler_from_matrix(T[:3, :3])
    x, y, z = T[:3, 3]
    rc = main(["solve", "--xyz", str(x), str(y), str(z), "--zyz", *(str(float(v)) for v in (a, b, g)),
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
    assert main(["solve", "--xyz", "0.3", "0.2", "0.5", "--zyz", "30", "120", "0", "--deg"]) == 0
    assert "solution" in capsys.readouterr().out
    assert main(["solve", "--xyz", "3", "0", "0", "--zyz", "0", "0", "0", "--json"]) == 1  # nothing found
    out = json.loads(capsys.readouterr().out)
    assert out["count"] == 0 and "unreachable" in out["reason"]
    assert main(["solve", "--xyz", "3", "0", "0", "--zyz", "0", "0", "0"]) == 1
    assert capsys.readouterr().out.startswith("no solution: unreachable")


def test_angles_that_look_like_degrees_get_a_warning(capsys):
    argv = ["solve", "--xyz", "0.4", "0.3", "0.2", "--zyz", "180", "120", "0"]
    main(argv)
    err = capsys.readouterr().err
    assert "warning: --zyz 180 120 0 look like degrees" in err and "add --deg" in err
    assert main([*argv, "--deg"]) == 0
    assert "warning" not in capsys.readouterr().err
    main(["solve", *"--xyz 0.4 0.3 0.2 --zyz 3 2 0 --previous 0 90 0 0 0 0".split()])
    assert "warning: --previous 0 90 0 0 0 0 look like degrees" in capsys.readouterr().err


def test_absurd_positions_are_unreachable_without_internal_warnings(capfd):
    assert main(["solve", "--xyz", "1e308", "0", "0", "--zyz", "0", "0", "0"]) == 1
    out, err = capfd.readouterr()
    assert out.startswith("no solution: unreachable") and err == ""


@pytest.mark.parametrize(("argv", "named"), [
    (["--xyz", "nan", "0", "0", "--zyz", "0", "0", "0"], "--xyz: "),
    (["--xyz", "0.4", "0.3", "0.2", "--zyz", "0", "inf", "0"], "--zyz: "),
    (["--xyz", "0.4", "0.3", "0.2", "--zyz", "0", "0", "0", "--previous", "nan", "0", "0", "0", "0", "0"],
     "--previous: "),
])
def test_errors_name_the_option_as_typed(argv, named, capsys):
    assert main(["solve", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("iik solve: error: InvalidInputError: " + named), err


def test_zxz_is_a_deprecated_alias_of_zyz_said_in_help(capsys):
    """The corrected Eq 42 is Z-Y-Z: `--zyz`; the old `--zxz` gives the same pose with a warning, and an
    error names it as typed."""
    argv = ["solve", "--xyz", "0.4", "0.3", "0.2", "--deg", "--json"]
    assert main([*argv, "--zyz", "180", "120", "0"]) == 0
    new, err = capsys.readouterr()
    assert err == ""
    assert main([*argv, "--zxz", "180", "120", "0"]) == 0
    old, err = capsys.readouterr()
    assert json.loads(old)["solutions"] == json.loads(new)["solutions"]
    assert json.loads(new)["pose"]["zyz"] == [180.0, 120.0, 0.0]
    assert err.strip() == ("iik solve: warning: --zxz is deprecated: the angles are Z-Y-Z (the corrected "
                           "Eq 42, which the thesis calls Z-X-Z); use --zyz (same angles, same pose)")
    assert main(["solve", "--xyz", "0.4", "0.3", "0.2", "--zxz", "0", "inf", "0"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.endswith("iik solve: error: InvalidInputError: --zxz: contains NaN or inf")
    with pytest.raises(SystemExit):
        main(["solve", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "--zyz A B G, --zxz A B G" in text and "Z-Y-Z" in text and "--zxz is a deprecated alias" in text
    assert "--method {complete,thesis} complete: the compiled elimination" in text


def test_millimetres_typed_as_metres_get_a_hint(capsys):
    assert main(["solve", "--xyz", "400", "300", "200", "--zyz", "0", "0", "0"]) == 1
    out, err = capsys.readouterr()
    assert out.startswith("no solution: unreachable")
    assert "warning: --xyz 400 300 200 is 538.5 m from the base, farther than the arm reaches" in err
    assert "millimetres typed as metres?" in err and "--xyz 0.4 0.3 0.2" in err


@pytest.mark.parametrize(("previous", "deg", "typed"), [
    ("999", True, "q1 = 999 deg is outside the joint limits [-160, 160] deg (Table I)"),
    ("1e300", True, "q1 = 1e+300 deg is outside the joint limits [-160, 160] deg (Table I)"),
    ("4", False, "q1 = 4 rad is outside the joint limits [-2.793, 2.793] rad (Table I)"),
])
def test_a_previous_configuration_outside_table_i_is_an_error(capsys, previous, deg, typed):
    argv = ["solve", "--xyz", "0.4", "0.3", "0.2", "--zyz", "3", "2", "0", "--previous", previous, *"00000"]
    assert main([*argv, *(["--deg"] if deg else [])]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1] == f"iik solve: error: InvalidInputError: --previous: {typed}", err
