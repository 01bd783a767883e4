"""A second reading: before a printed number or formula is called wrong, search the nearby readings
of its inputs and conventions for one that reproduces it.

The guide's rule: *if a nearby reading of the inputs reproduces the printed values, the slip is in
the input, not in the result.* A check that finds a printed value wrong re-derives it with
:func:`search`: the same printed value, recomputed from its stated inputs by a route of its own
(not the code that found the discrepancy), under every :class:`Reading` of a small catalogue:

* the sign of a stated angle or offset (:func:`signs`), the other joint limit (:func:`other_limits`),
  degrees for radians and back (:func:`units`), two inputs swapped (:func:`swapped`), and named
  alternatives (:func:`choices`: the other Euler convention, row vs column vectors, which frame,
  which point, which singular set);
* on the *printed* side, dropped or misplaced digits of a printed number (:func:`digit_slips`), a
  printed entry moved to a neighbouring place (:func:`moved_entries`), a printed entry with its sign
  dropped or added (:func:`sign_typos`) and a citation one number or letter off
  (:func:`numbering_slips`): these are typos of the result.

A reading of the inputs must also keep what the same passage prints from them: a check passes the
passage's other printed values into the misfit (e.g. A1's N0 beside its u0), so an input reading that
reproduces one number but breaks another that holds as stated does not explain the slip; a typo of the
printed number does.

:class:`SecondReading` records every reading searched with its misfit and says where the slip is
(:class:`Slip`): nowhere (the value is right as stated: the erratum does not survive), in the stated
input (a reading of the inputs reproduces it: :attr:`~verification.registry.Verdict.INPUT_SLIP`), a
typo of the printed result, or the printed result itself. Combinations of one input reading with one
printed-side reading are searched only when no single reading reproduces the value.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from enum import Enum
from typing import Any

import numpy as np

__all__ = [
    "Kind",
    "Reading",
    "AS_STATED",
    "Trial",
    "Slip",
    "SecondReading",
    "search",
    "signs",
    "other_limits",
    "units",
    "swapped",
    "choices",
    "digit_slips",
    "moved_entries",
    "sign_typos",
    "numbering_slips",
]


class Kind(str, Enum):
    """The kinds of nearby reading the search tries."""

    AS_STATED = "as stated"
    SIGN = "sign of an angle or offset"
    LIMIT = "the other joint limit"
    UNIT = "degrees vs radians"
    SWAP = "swapped or transposed indices"
    CONVENTION = "the other convention (Euler, row vs column, frame)"
    WHICH = "which angle, point or set"
    DIGITS = "dropped or misplaced digits (printed side)"
    MOVED = "an entry printed in the wrong place (printed side)"
    PRINTED_SIGN = "a sign dropped or added in a printed entry (printed side)"
    NUMBERING = "a citation one number or letter off (printed side)"


_PRINT_SIDE = (Kind.DIGITS, Kind.MOVED, Kind.PRINTED_SIGN, Kind.NUMBERING)


@dataclass(frozen=True)
class Reading:
    """One reading of the stated inputs (or of the printed value).

    Attributes:
        kind: Which kind of nearby reading.
        text: The reading in words, e.g. ``"theta1 = +7 pi/9 (sign)"``.
        change: Overrides of the stated inputs (input side) or of the printed values (printed side);
            the misfit function receives the stated inputs updated with it.
    """

    kind: Kind
    text: str
    change: Mapping[str, Any] = field(default_factory=dict)

    @property
    def side(self) -> str:
        """``"as stated"``, ``"input"`` or ``"printed"``."""
        if self.kind is Kind.AS_STATED:
            return "as stated"
        return "printed" if self.kind in _PRINT_SIDE else "input"

    def applied(self, stated: Mapping[str, Any]) -> dict:
        """The stated inputs with this reading's changes."""
        return {**stated, **self.change}


#: The stated inputs, read as stated.
AS_STATED = Reading(Kind.AS_STATED, "as stated")


@dataclass(frozen=True)
class Trial:
    """One reading searched.

    Attributes:
        readings: The reading, or an input reading and a printed-side one together.
        misfit: The measured misfit of the printed value under it (inf if it cannot be evaluated).
        reproduces: True if the misfit is within the tolerance.
    """

    readings: tuple[Reading, ...]
    misfit: float
    reproduces: bool

    @property
    def text(self) -> str:
        return " and ".join(r.text for r in self.readings)

    @property
    def sides(self) -> frozenset[str]:
        return frozenset(r.side for r in self.readings)


class Slip(str, Enum):
    """Where a second reading puts the slip."""

    NONE = "nowhere: the printed value is right as stated"
    INPUT = "in the stated input: a nearby reading of it reproduces the printed value"
    TYPO = "a typo of the printed result"
    INPUT_AND_TYPO = "in the stated input and a typo of the printed result"
    RESULT = "in the printed result: no nearby reading reproduces it"


@dataclass(frozen=True)
class SecondReading:
    """The second reading of one printed value.

    Attributes:
        printed: The printed value in words.
        stated: Its stated inputs in words.
        route: How the value is re-derived (a route of its own, not the check's).
        measure: What the misfit measures, with its unit.
        tolerance: Misfits up to this reproduce the printed value.
        trials: Every reading searched, the stated one first.
        before: The verdict the row had before this reading (set by ``Row.reread``).
    """

    printed: str
    stated: str
    route: str
    measure: str
    tolerance: float
    trials: tuple[Trial, ...]
    before: str = ""

    @property
    def as_stated(self) -> Trial:
        return self.trials[0]

    @property
    def reproducing(self) -> tuple[Trial, ...]:
        """The readings (other than as stated) that reproduce the printed value."""
        return tuple(t for t in self.trials[1:] if t.reproduces)

    @property
    def slip(self) -> Slip:
        if self.as_stated.reproduces:
            return Slip.NONE
        sides = [t.sides for t in self.reproducing]
        if frozenset({"input"}) in sides:
            return Slip.INPUT
        if frozenset({"printed"}) in sides:
            return Slip.TYPO
        if sides:
            return Slip.INPUT_AND_TYPO
        return Slip.RESULT

    @property
    def explanation(self) -> Trial | None:
        """The reproducing reading that decides :attr:`slip` (input readings first, then printed-side ones,
        then pairs; within each, the first in the search's order: a check lists its readings most plausible
        first, and misfits within the tolerance are all reproductions), if any."""
        order = {frozenset({"input"}): 0, frozenset({"printed"}): 1}
        found = sorted(self.reproducing, key=lambda t: order.get(t.sides, 2))
        return found[0] if found else None

    @property
    def searched(self) -> int:
        """How many readings were searched besides the stated one."""
        return len(self.trials) - 1

    def result(self) -> str:
        """One line: what reproduces the printed value, if anything."""
        if self.slip is Slip.NONE:
            return f"reproduced as stated ({self.measure} = {self.as_stated.misfit:.3g})"
        best = self.explanation
        if best is None:
            closest = min(self.trials[1:], key=lambda t: t.misfit, default=None)
            near = f"; closest: {closest.text} ({closest.misfit:.3g})" if closest else ""
            return f"no reading reproduces it (as stated {self.as_stated.misfit:.3g}{near})"
        others = len(self.reproducing) - 1
        return (
            f"reproduced by {best.text} ({self.measure} = {best.misfit:.3g}; as stated "
            f"{self.as_stated.misfit:.3g})" + (f"; {others} other reading(s) too" if others > 0 else "")
        )

    def kinds(self) -> list[str]:
        """The kinds of reading searched (for the report)."""
        seen = dict.fromkeys(r.kind.value for t in self.trials[1:] for r in t.readings)
        return list(seen)


def _misfit(f: Callable[[dict], float], inputs: dict) -> float:
    try:
        v = float(f(inputs))
    except (ArithmeticError, ValueError, np.linalg.LinAlgError):
        return float("inf")
    return v if v == v else float("inf")


def search(
    stated: Mapping[str, Any],
    readings: Iterable[Reading],
    misfit: Callable[[dict], float],
    tolerance: float,
    *,
    printed: str,
    stated_text: str,
    route: str,
    measure: str,
) -> SecondReading:
    """Search the nearby readings of ``stated`` for one under which the printed value is right.

    Args:
        stated: The stated inputs (and, under their own names, the printed values), by name.
        readings: The readings to try (input and printed side).
        misfit: ``misfit(inputs) -> float``: how far the printed value (under ``inputs``'s printed-side
            entries) is from the value re-derived from ``inputs``; >= 0, inf if undefined.
        tolerance: A misfit up to this reproduces the printed value.
        printed, stated_text, route, measure: Words for the report (:class:`SecondReading`).

    Returns:
        The record of every reading tried, the stated one first. Pairs of one input reading and one
        printed-side reading are tried only if no single reading reproduces the value.
    """
    readings = tuple(readings)
    trials = []
    for r in (AS_STATED, *readings):
        m = _misfit(misfit, r.applied(stated))
        trials.append(Trial((r,), m, m <= tolerance))
    if not any(t.reproduces for t in trials):
        inputs = [r for r in readings if r.side == "input"]
        prints = [r for r in readings if r.side == "printed"]
        for a, b in itertools.product(inputs, prints):
            m = _misfit(misfit, {**a.applied(stated), **b.change})
            trials.append(Trial((a, b), m, m <= tolerance))
    return SecondReading(printed, stated_text, route, measure, float(tolerance), tuple(trials))


# ----------------------------------------------------------------------------- reading generators
def _fmt(v) -> str:
    if isinstance(v, float | int | np.floating):
        return f"{float(v):.6g}"
    return str(v)


def signs(
    stated: Mapping[str, Any], names: Iterable[str], *, label: Callable[[str], str] = str
) -> list[Reading]:
    """The sign of each named (non-zero) stated value flipped."""
    out = []
    for n in names:
        v = stated[n]
        if np.any(np.asarray(v) != 0):
            out.append(
                Reading(
                    Kind.SIGN,
                    f"{label(n)} = {_fmt(-np.asarray(v) if np.ndim(v) else -v)}",
                    {n: -np.asarray(v) if np.ndim(v) else -v},
                )
            )
    return out


def other_limits(
    stated: Mapping[str, Any], name: str, lower: float, upper: float, *, what: str = ""
) -> list[Reading]:
    """If the named value sits at a joint limit: the other limit."""
    v = float(stated[name])
    out = []
    for at, other, word in ((lower, upper, "upper"), (upper, lower, "lower")):
        if abs(v - at) <= 1e-9:
            out.append(
                Reading(
                    Kind.LIMIT,
                    f"{what or name} at its {word} limit ({np.degrees(other):.0f} deg)",
                    {name: other},
                )
            )
    return out


def units(stated: Mapping[str, Any], names: Iterable[str]) -> list[Reading]:
    """Each named angle [rad] read as degrees, and a degree value typed as radians."""
    out = []
    for n in names:
        v = float(stated[n])
        if v == 0:
            continue
        out.append(
            Reading(
                Kind.UNIT,
                f"{n} = {v:.6g} taken as degrees ({np.radians(v):.4g} rad)",
                {n: float(np.radians(v))},
            )
        )
        out.append(
            Reading(Kind.UNIT, f"{n} = {np.degrees(v):.6g} deg typed as rad", {n: float(np.degrees(v))})
        )
    return out


def swapped(stated: Mapping[str, Any], pairs: Iterable[tuple[str, str]]) -> list[Reading]:
    """The values of two named inputs exchanged."""
    return [Reading(Kind.SWAP, f"{a} and {b} swapped", {a: stated[b], b: stated[a]}) for a, b in pairs]


def choices(kind: Kind, name: str, options: Mapping[str, Any]) -> list[Reading]:
    """Named alternatives for one input: ``{text: value}`` (e.g. the other Euler convention)."""
    return [Reading(kind, text, {name: value}) for text, value in options.items()]


def _digit_variants(text: str) -> list[str]:
    """Numbers one digit slip away from ``text`` (a printed decimal): a dropped zero after the point, a
    digit too many, two adjacent digits swapped, the decimal point one place off."""
    sign = "-" if text.startswith("-") else ""
    body = text.lstrip("-")
    if "." not in body:
        body += "."
    out = set()
    i = body.index(".")
    digits = body.replace(".", "")
    for k in range(i + 1, len(body) + 1):  # a zero dropped right after the point (0.0698 printed 0.698)
        out.add(body[:k] + "0" + body[k:])
    for k in range(len(body)):  # one digit too many
        if body[k] != ".":
            out.add(body[:k] + body[k + 1 :])
    for k in range(len(body) - 1):  # adjacent digits swapped
        if "." not in body[k : k + 2]:
            out.add(body[:k] + body[k + 1] + body[k] + body[k + 2 :])
    for j in (i - 1, i + 1):  # the point one place off
        if 0 <= j <= len(digits):
            out.add(digits[:j] + "." + digits[j:])
    res = []
    for s in out:
        s = s.strip(".")
        if not s or s == ".":
            continue
        try:
            float(s)
        except ValueError:
            continue
        if float(s) != float(body.rstrip(".") or 0):
            res.append(sign + s)
    return sorted(set(res), key=lambda s: (abs(float(s)), s))


def digit_slips(name: str, printed) -> list[Reading]:
    """Printed-side readings of the number(s) ``printed`` (the values as typed: floats whose ``repr``
    shows the printed digits): each entry in turn read one digit slip away."""
    arr = np.asarray(printed, float)
    flat = arr.ravel()
    out = []
    for i, v in enumerate(flat):
        if v == 0:
            continue
        for s in _digit_variants(repr(float(v))):
            new = flat.copy()
            new[i] = float(s)
            where = f"{name}[{i + 1}]" if flat.size > 1 else name
            out.append(
                Reading(
                    Kind.DIGITS, f"{where} = {repr(float(v))} read as {s}", {name: new.reshape(arr.shape)}
                )
            )
    return out


def moved_entries(name: str, printed, *, within: str = "column") -> list[Reading]:
    """Printed-side readings of a printed matrix: one entry moved to the neighbouring row of its column
    (``within="column"``) or to the neighbouring column of its row, the two places exchanged."""
    a = np.asarray(printed, float)
    out = []
    r, c = a.shape[-2:]
    for i in range(r):
        for j in range(c):
            k, m = (i + 1, j) if within == "column" else (i, j + 1)
            if k >= r or m >= c or np.array_equal(a[..., i, j], a[..., k, m]):
                continue
            b = a.copy()
            b[..., i, j], b[..., k, m] = a[..., k, m], a[..., i, j]
            out.append(
                Reading(Kind.MOVED, f"{name}({i + 1},{j + 1}) and ({k + 1},{m + 1}) exchanged", {name: b})
            )
    return out


def sign_typos(name: str, printed, *, label: Callable[[tuple], str] | None = None) -> list[Reading]:
    """Printed-side readings of ``printed`` (a vector, a matrix, or matrices sampled over inputs: shape
    (..., r, c)): each entry that is not zero everywhere read with its sign flipped (a dropped or extra
    minus).
    ``label(index)`` words an entry (default ``name[i]`` or ``name(i,j)``, 1-based)."""
    a = np.asarray(printed, float)
    out = []
    shape = a.shape if a.ndim == 1 else a.shape[-2:]
    for idx in np.ndindex(*shape):
        entry = a[idx] if a.ndim == 1 else a[(..., *idx)]
        if not np.any(entry != 0):
            continue
        b = a.copy()
        if a.ndim == 1:
            b[idx] = -a[idx]
        else:
            b[(..., *idx)] = -a[(..., *idx)]
        where = label(idx) if label else (f"{name}[{idx[0] + 1}]" if a.ndim == 1
                                          else f"{name}({idx[0] + 1},{idx[1] + 1})")
        out.append(Reading(Kind.PRINTED_SIGN, f"{where} printed with its sign flipped", {name: b}))
    return out


def numbering_slips(name: str, printed, label: str = "") -> list[Reading]:
    """Printed-side readings of a citation ``printed`` (the input ``name``; ``label`` words it): an int one
    off (n - 1, n + 1), a run of letters shifted by one ("ABC" -> "BCD"), a pair of names swapped
    (("s(2)", "s(3)") -> ("s(3)", "s(2)"))."""
    word = label or name
    out = []
    if isinstance(printed, int):
        for v in (printed - 1, printed + 1):
            out.append(Reading(Kind.NUMBERING, f"{word} {printed} read as {v}", {name: v}))
    elif isinstance(printed, str) and any(c.isalpha() for c in printed):
        for d in (-1, 1):
            v = "".join(chr(ord(c) + d) if c.isalpha() else c for c in printed)
            out.append(Reading(Kind.NUMBERING, f"{word} {printed} read as {v}", {name: v}))
    elif isinstance(printed, tuple) and len(printed) == 2:
        out.append(
            Reading(
                Kind.NUMBERING,
                f"{word} {printed[0]} and {printed[1]} swapped",
                {name: (printed[1], printed[0])},
            )
        )
    return out
