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


@pytest.mark.parametrize("cls,builtin", [(ScenarioError, InvalidInputError), (PlanningFailed, RuntimeError),
                                         (TimingError, RuntimeError), (SamplingError, RuntimeError)])
def test_one_root_and_the_matching_builtin(cls, builtin):
    assert issubclass(cls, PlanningError) and issubclass(cls, IIKError) and issubclass(cls, builtin)


def test_scenario_error_names_the_field():
    e = ScenarioError("goal.position", "inside the platform")
    assert (e.field, e.reason) == ("goal.position", "inside the platform")
    assert str(e) == "goal.position: inside the platform"


def test_planning_failed_carries_the_result():
    r = plan("a", PlanOptions(fallbacks=False, timing=False))
    e = PlanningFailed(r)
    assert e.result is r and "'a'" in str(e) and r.reason in str(e)
