"""verification: machine checks of the thesis against Pinocchio, Coal and ground truth.

Checks live in :mod:`verification.checks` and register themselves; ``iik verify`` runs
them all and writes ``reports/verification.json`` (one record per row, see
``report.schema.json``) and ``reports/verification.md`` rendered from it;
:func:`self_test` proves that every verdict can fail, on the mistakes a person would make;
:mod:`verification.second_reading` searches the nearby readings of a printed value's inputs
before it is called wrong.
"""

from iik.extras import require
from iik.lazy import lazy_exports

require("verify", __name__)

__getattr__, __dir__ = lazy_exports(__name__, {
    ".errors": ("RegistrationError", "ReportError", "RowError", "VerificationError"),
    ".registry": ("Check", "Context", "Erratum", "Forms", "Measure", "Row", "Scope", "Section", "Slip",
                  "SlipKind", "Verdict", "epsilon", "load_checks", "register", "registered_checks",
                  "verdict_of"),
    ".report": ("CheckResult", "Verification", "read_report", "report_document", "run_checks", "summary",
                "verify", "write_report"),
    ".self_test": ("SelfTestOutcome", "run_self_test", "self_test"),
})

__all__ = [
    "Check",
    "Context",
    "Erratum",
    "Forms",
    "Slip",
    "SlipKind",
    "epsilon",
    "Measure",
    "Row",
    "Scope",
    "Verdict",
    "verdict_of",
    "register",
    "Section",
    "registered_checks",
    "load_checks",
    "CheckResult",
    "Verification",
    "verify",
    "run_checks",
    "report_document",
    "write_report",
    "read_report",
    "summary",
    "SelfTestOutcome",
    "run_self_test",
    "self_test",
    "VerificationError",
    "RegistrationError",
    "RowError",
    "ReportError",
]
