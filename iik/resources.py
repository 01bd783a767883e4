"""Locate the data files shipped with the package (URDF, scenarios).

In a wheel they live in ``iik/data/``; in a source checkout or editable install
they are the top-level ``urdf/`` and ``scenarios/`` folders next to the
package. Either way they are found relative to the package, never the
working directory. This module only builds paths; it reads nothing.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["data_path", "urdf_path", "scenarios_dir"]

_PKG = Path(__file__).resolve().parent


def data_path(*parts: str) -> Path:
    """Path of a shipped data file, e.g. ``data_path("urdf", "thesis_arm.urdf")``."""
    for base in (_PKG / "data", _PKG.parent):
        p = base.joinpath(*parts)
        if p.exists():
            return p
    raise FileNotFoundError(f"package data {'/'.join(parts)} not found under {_PKG}")


def urdf_path(name: str = "thesis_arm.urdf") -> Path:
    """Path of a URDF from the top-level ``urdf/`` folder."""
    return data_path("urdf", name)


def scenarios_dir() -> Path:
    """Folder holding the thesis scenarios (``*.toml``)."""
    return data_path("scenarios")
