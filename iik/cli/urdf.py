"""``iik urdf``: an arm's URDF as the project generates it (:func:`iik.urdf.arm_urdf`): for the thesis arm
(the default) from Tables I and II with the PowerCube shapes (:func:`iik.urdf.thesis_urdf`); for
another arm (``--arm``) from its DH chain, with cylinders along its links unless of the thesis's form.

Works the same from any install: prints the URDF, or writes it where ``--out`` says;
``--check FILE`` compares a given file with the generator's output (exit 1 if it differs).
In a source checkout: ``iik urdf --out urdf/thesis_arm.urdf`` regenerates the committed file.
"""

from __future__ import annotations

import sys
from pathlib import Path

from .arm_option import add_arm_argument, chosen_arm

NAME = "urdf"
HELP = "an arm's generated URDF (thesis: Tables I/II): print it, write it (--out) or --check a file"


def add_arguments(p) -> None:
    add_arm_argument(p)
    p.add_argument("--out", type=Path, default=None, help="write the URDF to this file (default: stdout)")
    p.add_argument("--check", nargs="?", type=Path, const=True, default=None, metavar="FILE",
                   help="do not write; exit 1 if FILE (or the --out file) differs from the generator output")


def run(args) -> int:
    from iik.errors import InvalidInputError
    from iik.files import read_text, write_text
    from iik.urdf import MAX_URDF_BYTES, arm_urdf

    text = arm_urdf(chosen_arm(args))
    if args.check is not None:
        path = args.out if args.check is True else args.check
        if path is None:
            raise InvalidInputError("--check", "name the file to compare, e.g. iik urdf --check "
                                               "urdf/thesis_arm.urdf")
        same = read_text(path, "--check", limit=MAX_URDF_BYTES, what="a URDF file") == text
        print(f"{path}: {'up to date' if same else 'DIFFERS from the generator output'}")
        return 0 if same else 1
    if args.out is None or str(args.out) == "-":
        sys.stdout.write(text)
        return 0
    write_text(args.out, "--out", text)  # whole or not at all
    print(f"wrote {args.out} ({len(text)} bytes)")
    return 0
