"""The planning layer's errors under the one root (iik.planning.errors)."""

import pytest

from iik.errors import IIKError, InvalidInputError
from iik.planning import (
    PlanningError,
    PlanningFailed,
    PlanOptions,
    SamplingError,
    ScenarioError,
    TimingError,
    plan,
)
from iik.planning.errors import ExportError, OutsideLimitsError, PortInUseError, ViewerError, ViewRequestError


@pytest.mark.parametrize("cls,builtin", [(ScenarioError, InvalidInputError), (PlanningFailed, RuntimeError),
                                         (TimingError, RuntimeError), (SamplingError, RuntimeError),
                                         (ViewRequestError, InvalidInputError),
                                         (OutsideLimitsError, InvalidInputError), (PortInUseError, OSError),
                                         (ExportError, OSError)])
def test_one_root_and_the_matching_builtin(cls, builtin):
    assert issubclass(cls, PlanningError) and issubclass(cls, IIKError) and issubclass(cls, builtin)


@pytest.mark.parametrize("cls", [ViewRequestError, OutsideLimitsError, PortInUseError, ExportError])
def test_the_viewer_errors_share_one_root(cls):
    assert issubclass(cls, ViewerError) and issubclass(ViewerError, PlanningError)


def test_viewer_errors_carry_their_data():
    e = OutsideLimitsError("q", "q4 = 2.5 rad is outside Table I", (3,))
    assert (e.argument, e.joints, str(e)) == ("q", (3,), "q: q4 = 2.5 rad is outside Table I")
    p = PortInUseError("127.0.0.1", 8080, "address in use")
    assert (p.host, p.port) == ("127.0.0.1", 8080) and "port 8080" in str(p)
    assert p.remedy.arguments == ("port",) and str(p).endswith("; choose another port")  # library terms
    x = ExportError("out", "folder is not empty")
    assert x.path.name == "out" and str(x) == "out: folder is not empty"


def test_scenario_error_names_the_field():
    e = ScenarioError("goal.position", "inside the platform")
    assert (e.field, e.reason) == ("goal.position", "inside the platform")
    assert str(e) == "goal.position: inside the platform"


def test_planning_failed_carries_the_result():
    r = plan("a", PlanOptions(fallbacks=False, timing=False))
    e = PlanningFailed(r)
    assert e.result is r and "'a'" in str(e) and r.reason in str(e)
