"""Typed errors of the verification layer, all under the one root :class:`iik.errors.IIKError`.

* :class:`RegistrationError` -- a check is registered wrongly (a duplicate name, forms
  on a function that cannot take them, both forms and a "by construction" label, ...).
* :class:`RowError` -- a check built an inconsistent :class:`~verification.registry.Row`
  (a "not checkable" row without its reason, an erratum without a record, a bad id).
* :class:`ReportError` -- a ``verification.json`` that cannot be read back (missing
  file, not JSON, or not matching ``report.schema.json``).
"""

from __future__ import annotations

from iik.errors import IIKError

__all__ = ["VerificationError", "RegistrationError", "RowError", "ReportError"]


class VerificationError(IIKError):
    """Root of the errors the verification layer raises on purpose."""


class RegistrationError(VerificationError, ValueError):
    """A check registration is malformed.

    Attributes:
        check: The check's name (``module.function``).
        reason: What is wrong with it.
    """

    def __init__(self, check: str, reason: str):
        self.check = check
        self.reason = reason
        super().__init__(f"check {check!r}: {reason}")


class RowError(VerificationError, ValueError):
    """A report row is inconsistent.

    Attributes:
        field: The offending field of the row (e.g. ``"reason"``).
        reason: What is wrong with it.
    """

    def __init__(self, field: str, reason: str):
        self.field = field
        self.reason = reason
        super().__init__(f"row {field}: {reason}")


class ReportError(VerificationError, ValueError):
    """A machine-readable report cannot be read.

    Attributes:
        path: The file (as given).
        reason: What is wrong with it (for a schema mismatch: the JSON path and the rule).
    """

    def __init__(self, path: str, reason: str):
        self.path = path
        self.reason = reason
        super().__init__(f"{path}: {reason}")
