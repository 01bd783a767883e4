"""Inverse kinematics of the thesis arm (Sec 3.3): complete solver, thesis IIK, selection.

* :func:`solve` / :func:`solve_many` / :func:`solve_batch`: all solutions of a pose
  (``method="complete"``: the compiled elimination, the default; ``"reference"``: the same
  in NumPy; ``"thesis"``: Sec 3.3 with errata fixed), with :class:`IKOptions`.
* :func:`select` (least Eq 54 effort within Table I), :func:`follow_path`.
"""

from ..lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(__name__, {
    ".nearest": ("Candidates",),
    ".options": ("DEFAULT_OPTIONS", "ORTHONORMAL_TOL", "IKOptions"),
    ".result": ("Continuum", "IKBatch", "IKResult"),
    ".selection": ("branch_signature", "follow_path", "select", "select_index"),
    ".solve": ("COMPILE_MESSAGE", "METHODS", "compile_clock", "compile_notice", "solve", "solve_batch",
               "solve_many"),
})

__all__ = [
    "IKResult",
    "IKBatch",
    "Continuum",
    "IKOptions",
    "DEFAULT_OPTIONS",
    "ORTHONORMAL_TOL",
    "METHODS",
    "solve",
    "solve_many",
    "solve_batch",
    "compile_notice",
    "compile_clock",
    "COMPILE_MESSAGE",
    "select",
    "select_index",
    "Candidates",
    "follow_path",
    "branch_signature",
]
