"""The optional parts of the distribution and the check that one is installed.

``pip install iik`` installs the core, :mod:`iik` (NumPy, SciPy, Numba, and Pinocchio). Each
package above it needs an extra of ``pyproject.toml`` and says so where it is imported:

==========  ==========================  =====================================================
extra       package                     adds
==========  ==========================  =====================================================
planning    ``iik.planning``            Coal, OMPL, TOPP-RA, matplotlib
viewer      ``iik.planning.viewer``     planning, viser, trimesh
hardware    ``hardware``                python-can (and msgpack for udp_multicast), ruckig, matplotlib
verify      ``verification``            planning, viewer, hardware, example-robot-data
test        the test suite              everything, Hypothesis, pytest, ...
all         everything above but test
==========  ==========================  =====================================================

:func:`require`, called at the top of each such package's ``__init__``, raises
:class:`~iik.errors.MissingExtraError` (an ``ImportError``) naming the extra to install, as one line.
It looks the modules up without importing them, so the check costs no import time.
"""

from __future__ import annotations

import importlib.util
import sys

from .errors import MissingExtraError

__all__ = ["EXTRAS", "require", "missing_modules"]

_TOML = ("tomli",) if sys.version_info < (3, 11) else ()  # scenario files, before Python 3.11's tomllib
_PLANNING = ("pinocchio", "coal", "ompl", "toppra", "matplotlib", *_TOML)
_VIEWER = ("viser", "trimesh")
_HARDWARE = ("can", "msgpack", "ruckig")

#: extra -> the top-level modules that show it is installed (example-robot-data ships no module:
#: the checks that use its URDF files say so when they are missing).
EXTRAS: dict[str, tuple[str, ...]] = {
    "planning": _PLANNING,
    "viewer": _PLANNING + _VIEWER,
    "hardware": _HARDWARE + ("matplotlib",),  # a scenario run also needs planning (hardware.sources)
    "verify": _PLANNING + _VIEWER + _HARDWARE,
    "test": ("hypothesis",),
}


def missing_modules(extra: str) -> tuple[str, ...]:
    """The modules of ``extra`` (a key of :data:`EXTRAS`) that cannot be imported here."""
    return tuple(m for m in EXTRAS[extra] if importlib.util.find_spec(m) is None)


def require(extra: str, package: str) -> None:
    """Raise :class:`~iik.errors.MissingExtraError` if ``package`` (the importing package's name)
    is used without ``extra`` installed."""
    missing = missing_modules(extra)
    if missing:
        raise MissingExtraError(package, extra, missing)
