"""``iik urdf``: the thesis arm's URDF (generated from Tables I and II by :func:`iik.urdf.thesis_urdf`).

Works the same from any install: prints the URDF, or writes it where ``--out`` says;
``--check FILE`` compares a given file with the generator's output (exit 1 if it differs).
In a source checkout: ``iik urdf --out urdf/thesis_arm.urdf`` regenerates the committed file.
"""

from __future__ import annotations

import sys
from pathlib import Path

NAME = "urdf"
HELP = "the thesis arm's URDF (generated from Tables I/II): print it, write it (--out) or --check a file"


def add_arguments(p) -> None:
    p.add_argument("--out", type=Path, default=None, help="write the URDF to this file (default: stdout)")
    p.add_argument("--check", nargs="?", type=Path, const=True, default=None, metavar="FILE",
                   help="do not write; exit 1 if FILE (or the --out file) differs from the generator output")


def run(args) -> int:
    from iik.errors import InvalidInputError
    from iik.urdf import thesis_urdf

    text = thesis_urdf()
    if args.check is not None:
        path = args.out if args.check is True else args.check
        if path is None:
            raise InvalidInputError("--check", "name the file to compare, e.g. iik urdf --check "
                                               "urdf/thesis_arm.urdf")
        try:
            same = path.read_text(encoding="utf-8") == text
        except OSError as exc:
            raise InvalidInputError("--check", f"cannot read {path}: {exc.strerror}") from None
        print(f"{path}: {'up to date' if same else 'DIFFERS from the generator output'}")
        return 0 if same else 1
    if args.out is None or str(args.out) == "-":
        sys.stdout.write(text)
        return 0
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(text, encoding="utf-8")
    print(f"wrote {args.out} ({len(text)} bytes)")
    return 0
