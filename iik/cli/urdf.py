"""``iik urdf``: write the thesis arm's URDF (generated from Table II) to a file."""

from __future__ import annotations

import sys
from pathlib import Path

NAME = "urdf"
HELP = "write the thesis arm's URDF (generated from Table I/II by iik.urdf) to a file or stdout"


def add_arguments(p) -> None:
    p.add_argument("--out", type=Path, default=None,
                   help="output file (default: urdf/thesis_arm.urdf of the source checkout; "
                        "'-' for stdout)")
    p.add_argument("--check", action="store_true",
                   help="do not write; exit 1 if the file (default: the shipped URDF) differs from "
                        "the generator output")


def _default_out() -> Path:
    """``urdf/thesis_arm.urdf`` of the source checkout this package runs from."""
    from iik.errors import InvalidInputError

    root = Path(__file__).resolve().parents[2]
    if not (root / "pyproject.toml").exists():
        raise InvalidInputError("--out", "not running from a source checkout; give --out PATH (or '-')")
    return root / "urdf" / "thesis_arm.urdf"


def run(args) -> int:
    from iik.urdf import thesis_urdf

    text = thesis_urdf()
    if args.out is not None and str(args.out) == "-":
        sys.stdout.write(text)
        return 0
    if args.check:
        from iik.resources import urdf_path

        out = args.out or urdf_path()  # the shipped file (works in a wheel too)
        same = out.exists() and out.read_text(encoding="utf-8") == text
        print(f"{out}: {'up to date' if same else 'DIFFERS from the generator output'}")
        return 0 if same else 1
    out = args.out or _default_out()
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(text, encoding="utf-8")
    print(f"wrote {out} ({len(text)} bytes)")
    return 0
