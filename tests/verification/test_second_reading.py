"""verification.second_reading: the search finds the reading that reproduces a printed value (and only then
moves the slip to the input), and Row.reread grades by it."""

from __future__ import annotations

import numpy as np
import pytest

from verification.registry import Erratum, Row, Verdict
from verification.second_reading import (
    Kind,
    Reading,
    Slip,
    choices,
    digit_slips,
    moved_entries,
    numbering_slips,
    other_limits,
    search,
    sign_typos,
    signs,
    swapped,
    units,
)

_LO, _HI = -np.radians(160), np.radians(160)


def _lam(q, lo=_LO, hi=_HI):
    """Eq 58 inverted: the printed value's recipe."""
    return np.arcsin((q - (hi + lo) / 2) / ((hi - lo) / 2))


def _read(printed: float, q: float, **kw):
    stated = {"q": q, "lam": printed}
    readings = signs(stated, ["q"]) + digit_slips("lam", printed) + kw.get("extra", [])
    return search(
        stated,
        readings,
        lambda x: abs(x["lam"] - _lam(x["q"])),
        1e-3,
        printed="u0",
        stated_text="q",
        route="Eq 58",
        measure="|printed - lambda|",
    )


def test_an_input_reading_moves_the_slip_to_the_input():
    """A1's u0 = +1.0654 is Eq 58 at theta1 = +140 deg, while theta1 = -140 deg is stated."""
    sr = _read(1.0654, np.radians(-140))
    assert sr.slip is Slip.INPUT and sr.explanation.sides == {"input"}
    assert sr.as_stated.misfit > 2 and not sr.as_stated.reproduces
    assert sr.searched == len(sr.trials) - 1 > 5


def test_right_as_stated_withdraws_the_erratum_and_a_wrong_value_stays_one():
    assert _read(-1.0654, np.radians(-140)).slip is Slip.NONE
    wrong = _read(0.7, np.radians(-140))
    assert wrong.slip is Slip.RESULT and wrong.explanation is None
    assert "no reading reproduces it" in wrong.result()


def test_a_digit_slip_is_a_typo_and_combinations_are_tried_last():
    # -0.0698 printed as -0.698: a dropped zero (the printed side)
    typo = search(
        {"x": -0.698},
        digit_slips("x", -0.698),
        lambda s: abs(s["x"] + 0.0698),
        1e-6,
        printed="x",
        stated_text="-",
        route="-",
        measure="-",
    )
    assert typo.slip is Slip.TYPO and "-0.0698" in typo.explanation.text
    # an input sign and a dropped digit together (A6's N0): only searched when no single reading works
    stated = {"t": 1.0, "x": -0.698}
    both = search(
        stated,
        signs(stated, ["t"]) + digit_slips("x", -0.698),
        lambda s: abs(s["x"] - (-0.0698) * s["t"] * -1),
        1e-6,
        printed="x",
        stated_text="t",
        route="-",
        measure="-",
    )
    assert both.slip is Slip.INPUT_AND_TYPO and len(both.explanation.readings) == 2
    single = len(signs(stated, ["t"]) + digit_slips("x", -0.698))
    assert len(both.trials) > 1 + single  # the pairs were searched


def test_generators():
    s = {"a": 0.5, "b": 0.0, "lim": np.radians(-160)}
    assert [r.change["a"] for r in signs(s, ["a", "b"])] == [-0.5]  # zero has no sign to flip
    (lim,) = other_limits(s, "lim", np.radians(-160), np.radians(160))
    assert lim.kind is Kind.LIMIT and lim.change["lim"] == pytest.approx(np.radians(160))
    assert sorted(r.change["a"] for r in units(s, ["a"])) == pytest.approx([np.radians(0.5), np.degrees(0.5)])
    assert swapped(s, [("a", "b")])[0].change == {"a": 0.0, "b": 0.5}
    assert choices(Kind.CONVENTION, "c", {"other": 2})[0].change == {"c": 2}
    m = moved_entries("M", np.array([[1.0, 2.0], [3.0, 4.0]]))
    assert [r.change["M"].tolist() for r in m] == [[[3.0, 2.0], [1.0, 4.0]], [[1.0, 4.0], [3.0, 2.0]]]
    assert [r.change["c"] for r in numbering_slips("c", 19)] == [18, 20]
    assert [r.change["c"] for r in numbering_slips("c", "ABC")] == ["@AB", "BCD"]
    assert [r.change["c"] for r in numbering_slips("c", "9b")] == ["9a", "9c"]
    assert all(r.side == "printed" for r in m + digit_slips("x", 1.25) + numbering_slips("c", 2))
    assert Reading(Kind.SIGN, "t").side == "input"


def test_sign_typos_flip_one_printed_entry_and_lose_to_an_input_reading():
    v = sign_typos("u", [1.0654, 0.0, -0.5])
    assert [r.change["u"].tolist() for r in v] == [[-1.0654, 0.0, -0.5], [1.0654, 0.0, 0.5]]  # zeros skipped
    m = sign_typos("P", np.array([[[1.0, 0.0], [2.0, 3.0]]] * 4))  # matrices sampled over 4 inputs
    where = ((1, 1), (2, 1), (2, 2))
    assert [r.text for r in m] == [f"P({i},{j}) printed with its sign flipped" for i, j in where]
    assert all(r.side == "printed" and r.change["P"][:, 1, 0].tolist() == [-2.0] * 4 for r in m[1:2])
    # alone, theta1 = +140 deg explains u0 as an input slip (test above); when a value printed beside it pins
    # theta1 (the misfit counts it), the dropped minus sign is the explanation: a typo, the erratum stays
    pinned = search({"q": np.radians(-140), "lam": 1.0654},
                    signs({"q": np.radians(-140)}, ["q"]) + sign_typos("lam", np.array([1.0654])),
                    lambda x: max(float(np.abs(x["lam"] - _lam(x["q"])).max()),
                                  abs(x["q"] - np.radians(-140))),
                    1e-3, printed="u0", stated_text="q", route="Eq 58", measure="-")
    assert pinned.slip is Slip.TYPO


def test_undefined_readings_count_as_not_reproducing():
    def misfit(x):
        if x["q"] < 0:
            raise np.linalg.LinAlgError("singular")
        return float("nan") if x["q"] == 2 else 0.0

    sr = search(
        {"q": 1.0},
        [Reading(Kind.SIGN, "-1", {"q": -1.0}), Reading(Kind.SIGN, "2", {"q": 2.0})],
        misfit,
        0.0,
        printed="-",
        stated_text="-",
        route="-",
        measure="-",
    )
    assert [t.misfit for t in sr.trials] == [0.0, float("inf"), float("inf")]


def test_reread_grades_an_erratum_by_its_second_reading():
    e = Erratum("Eq 1", "p", "c", "x")
    row = Row("c", "Eq 1", "m", "n", Verdict.ERRATUM, errata=(e,))
    slip = row.reread(_read(1.0654, np.radians(-140)))
    assert (
        slip.verdict is Verdict.INPUT_SLIP and slip.errata == (e,) and slip.second_reading.before == "erratum"
    )
    withdrawn = row.reread(_read(-1.0654, np.radians(-140)))
    assert withdrawn.verdict is Verdict.HOLDS and withdrawn.errata == ()
    stays = row.reread(_read(0.7, np.radians(-140)))
    assert stays.verdict is Verdict.ERRATUM and stays.second_reading is not None
    held = Row("c", "Eq 1", "m", "n", Verdict.DOES_NOT_HOLD).reread(_read(1.0654, np.radians(-140)))
    assert held.verdict is Verdict.DOES_NOT_HOLD  # only errata are re-graded; the record is kept
