"""Where a report came from: commit, package versions, seeds and machine (the report header)."""

from __future__ import annotations

import datetime as _dt
import os
import platform
import subprocess
import sys
from dataclasses import asdict, dataclass, field
from importlib import metadata
from pathlib import Path

__all__ = ["Provenance", "provenance", "PACKAGES"]

#: Distributions whose versions a verdict can depend on.
PACKAGES = (
    "iik",
    "numpy",
    "scipy",
    "pin",
    "coal",
    "example-robot-data",
    "python-can",
    "toppra",
    "ompl",
    "ruckig",
    "matplotlib",
    "hypothesis",
)


@dataclass(frozen=True)
class Provenance:
    """The report header.

    Attributes:
        commit: ``git rev-parse HEAD`` of the checkout the package was imported from, or
            ``"unknown (not a git checkout)"``.
        dirty: Uncommitted changes in that checkout (None if unknown).
        versions: Installed version per distribution of :data:`PACKAGES`.
        seed: The seed every check's random samples derive from.
        quick: Quick mode (small samples).
        python: Python version.
        machine: Platform, processor and logical CPU count.
        created: UTC time the report was written (ISO 8601).
    """

    commit: str
    dirty: bool | None
    versions: dict = field(default_factory=dict)
    seed: int = 0
    quick: bool = False
    python: str = ""
    machine: dict = field(default_factory=dict)
    created: str = ""

    def as_dict(self) -> dict:
        return asdict(self)


def _git(args: list[str], cwd: Path) -> str | None:
    try:
        out = subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip() if out.returncode == 0 else None


def _version(dist: str) -> str:
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return "not installed"


def provenance(seed: int, quick: bool) -> Provenance:
    """Collect the header for a run with ``seed`` and ``quick``."""
    root = Path(__file__).resolve().parent.parent
    commit = _git(["rev-parse", "HEAD"], root)
    status = _git(["status", "--porcelain", "--untracked-files=no"], root) if commit else None
    return Provenance(
        commit=commit or "unknown (not a git checkout)",
        dirty=None if status is None else bool(status),
        versions={p: _version(p) for p in PACKAGES},
        seed=int(seed),
        quick=bool(quick),
        python=sys.version.split()[0],
        machine={
            "platform": platform.platform(),
            "processor": platform.processor() or platform.machine(),
            "cpus": os.cpu_count(),
        },
        created=_dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
    )
