"""Shorthand of the checks' transcriptions: the thesis's ``c1 = cos(theta1)``, ``s1 = sin(theta1)``,
``ca = cos(alpha)``, ..., angle differences wrapped to one turn (:func:`iik.ik.angles.wrap_angle`), and
printed expressions evaluated as they read (:func:`evaluate`, :func:`matrix`): the report's printed text
is then the transcription itself."""

from __future__ import annotations

import re
from functools import cache

import numpy as np

from iik.ik.angles import wrap_angle

__all__ = ["cos_sin", "wrap", "evaluate", "matrix"]


def cos_sin(*angles) -> tuple:
    """``(cos a, sin a, cos b, sin b, ...)`` of the given angles [rad] (floats or arrays), in order."""
    return tuple(f(a) for a in angles for f in (np.cos, np.sin))


#: Angles [rad] (floats or arrays) wrapped to (-pi, pi]: how far apart two joint angles are. The
#: project's one wrap, :func:`iik.ik.angles.wrap_angle`, under the checks' short name.
wrap = wrap_angle


_TOKEN = re.compile(r"\s*(\w+(?:\.\d*)?|[-+*/()])")


@cache
def _code(text: str):
    """``text`` compiled, with a ``*`` between juxtaposed factors (``"l3 s1 c2"``, ``"(a + b)(c)"``)."""
    tokens, pos = [], 0
    while pos < len(text.rstrip()):
        m = _TOKEN.match(text, pos)
        if m is None:
            raise ValueError(f"cannot read {text[pos:]!r} in the printed expression {text!r}")
        tokens.append(m.group(1))
        pos = m.end()
    ends, starts = (lambda t: t == ")" or t[-1].isalnum()), (lambda t: t == "(" or t[0].isalnum())
    out = [("*" if k and ends(tokens[k - 1]) and starts(t) else "") + t for k, t in enumerate(tokens)]
    return compile("".join(out), text, "eval")


def evaluate(text: str, symbols: dict):
    """The printed expression ``text`` with ``symbols`` (name -> float or array): names, numbers,
    ``+ - * /`` and parentheses, a product written as it is printed, by juxtaposition
    (``"-l2 s1 + (l5 s45 + l4 s4)(c1 s3)"``). An unknown name raises NameError."""
    return eval(_code(text), {"__builtins__": {}}, dict(symbols))


def matrix(text, symbols: dict) -> np.ndarray:
    """The printed matrix ``text`` -> (..., rows, columns), broadcast over array symbols: either
    ``"[c1 -s1 0; s1 c1 0]"`` (rows split by ``;``, entries by spaces; text around the brackets is
    ignored) or rows of :func:`evaluate` expressions (``(("c1", "-s1"), ("s1", "c1"))``)."""
    if isinstance(text, str):
        text = [r.split() for r in text[text.index("[") + 1 : text.index("]")].split(";")]
    vals = np.broadcast_arrays(*(np.asarray(evaluate(e, symbols), float) for r in text for e in r))
    return np.stack(vals, -1).reshape(vals[0].shape + (len(text), len(text[0])))
