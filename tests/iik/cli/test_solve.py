"""`iik solve` command line."""

import json

import numpy as np

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
    assert main(["solve", "--xyz", "3", "0", "0", "--zxz", "0", "0", "0", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["count"] == 0 and "unreachable" in out["reason"]
