"""Typed errors of the verification layer, all under the one root :class:`iik.errors.IIKError`.

* :class:`RegistrationError` -- a check is registered wrongly (a duplicate name, forms
  on a function that cannot take them, both forms and a "by construction" label, ...).
* :class:`RowError` -- a check built an inconsistent :class:`~verification.registry.Row`
  (a "not checkable" row without its reason, an erratum without a record, a bad id).
* :class:`ReportError` -- a ``verification.json`` that cannot be read back (missing
  file, not JSON, or not matching ``report.schema.json``).
* :class:`SelectionError` -- a selection of checks (``iik verify --only TEXT``) with an item
  that matches no check (bad input: nothing is run or written).
"""

from __future__ import annotations

from iik.errors import IIKError, InvalidInputError

__all__ = ["VerificationError", "RegistrationError", "RowError", "ReportError", "SelectionError"]


class VerificationError(IIKError):
    """Root of the errors the verification layer raises on purpose."""


class _AboutError(VerificationError, ValueError):
    """An error about one thing (a check, a row field, a file) and what is wrong with it.

    A subclass names the attribute that holds the thing (``about``) and how the message
    leads with it (``lead``, formatted with the thing); ``reason`` holds what is wrong.
    """

    about = ""
    lead = "{}"

    def __init__(self, subject: str, reason: str):
        setattr(self, self.about, subject)
        self.reason = reason
        super().__init__(f"{self.lead.format(subject)}: {reason}")


class RegistrationError(_AboutError):
    """A check registration is malformed.

    Attributes:
        check: The check's name (``module.function``).
        reason: What is wrong with it.
    """

    about, lead = "check", "check {!r}"
    check: str


class RowError(_AboutError):
    """A report row is inconsistent.

    Attributes:
        field: The offending field of the row (e.g. ``"reason"``).
        reason: What is wrong with it.
    """

    about, lead = "field", "row {}"
    field: str


class ReportError(_AboutError):
    """A machine-readable report cannot be read.

    Attributes:
        path: The file (as given).
        reason: What is wrong with it (for a schema mismatch: the JSON path and the rule).
    """

    about = "path"
    path: str


class SelectionError(VerificationError, InvalidInputError):
    """A selection of checks (:func:`verification.registry.selected_checks`) with items that match
    no check's name or section.

    Attributes:
        argument: ``"select"`` (``iik verify --only``).
        reason: Which items match nothing, and what there is to match.
        unmatched: Those items.
    """

    def __init__(self, unmatched, reason: str):
        self.unmatched = tuple(unmatched)
        super().__init__("select", reason)
