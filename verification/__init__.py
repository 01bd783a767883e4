"""verification: machine checks of the thesis against Pinocchio and Coal.

Checks live in :mod:`verification.checks` and register themselves;
:func:`verify` (behind ``iik verify``) runs them all and writes ``verification.md``.
"""

from .registry import Context, Erratum, Row, Verdict, load_checks, register, registered_checks
from .report import CheckResult, Verification, run_checks, summary, verify, write_report

__all__ = [
    "Context",
    "Erratum",
    "Row",
    "Verdict",
    "register",
    "registered_checks",
    "load_checks",
    "CheckResult",
    "Verification",
    "verify",
    "run_checks",
    "summary",
    "write_report",
]
