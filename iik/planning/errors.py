"""Errors of the planning layer, under the project's one root :class:`iik.errors.IIKError`.

* :class:`PlanningError` -- root of every error :mod:`iik.planning` raises on purpose;
* :class:`ScenarioError` -- a scenario (file or object) is malformed or impossible;
* :class:`PlanningFailed` -- no attempt kept the safety zone (carries the result);
* :class:`TimingError` -- TOPP-RA found no time parameterisation (wraps its failure);
* :class:`SamplingError` -- OMPL failed while sampling (wraps its exception);
* :class:`PlanningTimeout` -- a stage ran past the plan's time budget
  (:func:`~iik.planning.plan` turns it into a result with ``timed_out`` set);
* :class:`ViewerError` -- root of the 3D viewer's errors (:mod:`iik.planning.viewer`):
  :class:`ViewRequestError` (a view that cannot be shown as asked, naming the option),
  :class:`OutsideLimitsError` (a configuration outside Table I, not allowed to be shown),
  :class:`PortInUseError` (the viewer cannot listen there), :class:`ExportError` (an
  offline export cannot be written).

Subclasses also inherit the matching built-in (``ValueError`` for bad input, via
:class:`iik.errors.InvalidInputError`; ``RuntimeError`` for a failed computation,
``TimeoutError`` for a time budget, ``OSError`` for a port or folder) so generic
handlers keep working.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import IIKError, InvalidInputError, Remedy

if TYPE_CHECKING:  # pragma: no cover
    from .pipeline import PlanResult

__all__ = ["PlanningError", "ScenarioError", "PlanningFailed", "TimingError", "SamplingError",
           "PlanningTimeout", "ViewerError", "ViewRequestError", "OutsideLimitsError", "PortInUseError",
           "ExportError"]


class PlanningError(IIKError):
    """Root of the planning layer's errors."""


class ScenarioError(PlanningError, InvalidInputError):
    """A scenario file is malformed or describes an impossible task (bad input naming its field).

    Attributes:
        field: Dotted name of the offending field as written in the file, e.g. ``"goal.position"``
            (also :attr:`argument`).
        reason: Human-readable reason.
    """

    @property
    def field(self) -> str:
        return self.argument


class PlanningFailed(PlanningError, RuntimeError):
    """No attempt produced a path that keeps the safety zone.

    Attributes:
        result: The failed :class:`~iik.planning.PlanResult` (its ``attempts`` say why).
    """

    def __init__(self, result: PlanResult):
        self.result = result
        super().__init__(f"scenario {result.scenario.name!r}: {result.reason}")


class TimingError(PlanningError, RuntimeError):
    """TOPP-RA could not time a joint path (the library's own failure is the ``__cause__``)."""


class SamplingError(PlanningError, RuntimeError):
    """OMPL raised while planning (the library's exception is the ``__cause__``)."""


class PlanningTimeout(PlanningError, TimeoutError):
    """A planning stage ran past its time budget (:class:`~iik.planning.Budget`).

    :func:`~iik.planning.plan` never lets it escape: it returns the best result so
    far with ``timed_out`` set. Stages called directly with a budget raise it.

    Attributes:
        stage: What was running, e.g. ``"IK along the path: 1200/4000 steps"``.
        elapsed: Time since the budget started [s].
        timeout: The budget [s].
    """

    def __init__(self, stage: str, elapsed: float, timeout: float):
        self.stage, self.elapsed, self.timeout = stage, elapsed, timeout
        super().__init__(f"timed out after {elapsed:.1f} s (budget {timeout:g} s) during {stage}")


class ViewerError(PlanningError):
    """Root of the errors the 3D viewer (:mod:`iik.planning.viewer`) raises on purpose."""


class ViewRequestError(ViewerError, InvalidInputError):
    """A view that cannot be shown as asked (bad input naming the option, e.g. ``"export"``).

    Attributes:
        argument: The option, by its library name (the CLI shows it as typed, e.g. ``--export``).
        reason: Why.
    """


class OutsideLimitsError(ViewRequestError):
    """A configuration to show is outside the arm's joint limits (Table I) and was not allowed.

    Attributes:
        joints: 0-based indices of the joints outside the limits (joint ``q{j + 1}``).
    """

    def __init__(self, argument: str, reason: str, joints: tuple[int, ...], remedy: Remedy | None = None):
        self.joints = tuple(joints)
        super().__init__(argument, reason, remedy)


class PortInUseError(ViewerError, OSError):
    """The viewer cannot listen on the requested address.

    Attributes:
        host: The interface asked for.
        port: The TCP port asked for.
    """

    def __init__(self, host: str, port: int, detail: str = ""):
        self.host = host
        self.port = port
        super().__init__(f"port {port} on {host} is in use or not available"
                         + (f" ({detail})" if detail else ""))
        self.remedy = Remedy("choose another {}", "port")


class ExportError(ViewerError, OSError):
    """An offline export cannot be written (nothing is left half-written).

    Attributes:
        path: The export folder as given.
        reason: Why.
    """

    def __init__(self, path: Path | str, reason: str, remedy: Remedy | None = None):
        self.path = Path(path)
        self.reason = reason
        self.remedy = remedy
        super().__init__(f"{path}: {reason}")
