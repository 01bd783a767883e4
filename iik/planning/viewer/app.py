"""One call per request: what to show (:class:`ViewRequest`), how (:class:`ViewOptions`) -> :class:`Shown`.

The modes of ``iik view``:

* a scenario (file or shipped name): plan it (``planning`` options) and play the plan
  (:class:`~.plan.PlanScene`); a plan that fails or times out is shown with its reason and attempt log;
* ``q``: the arm at ``q`` and every IK solution of its pose (:class:`~.pose.PoseView`); a ``q``
  outside Table I is bad input (:class:`~iik.planning.errors.OutsideLimitsError`, nothing shown
  or written) unless ``allow_outside_limits``: then it is shown, the links moved by the offending
  joints red, with one warning line;
* ``xyz`` + ``zxz``: every IK solution of that pose (position [m], Eq 42 angles [rad]);
* nothing, or ``interactive``: interactive IK with a draggable gizmo (live only).

Run logs are shown by :func:`hardware.view.view_run` (the hardware layer reads them).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import iik
from iik.arm import Arm
from iik.errors import InvalidInputError, Remedy

from ..errors import OutsideLimitsError, ViewRequestError
from ..pipeline import PlanOptions
from .attempts import plan_log
from .bodies import joints_outside_limits, outside_limits_text
from .plan import PlanScene
from .plan_data import plan_for_view
from .pose import PoseView
from .session import ExportResult, LiveView, ViewOptions, present

__all__ = ["ViewRequest", "Shown", "view", "show"]

#: Start pose of interactive IK with no pose given: tool 0.4 m ahead, 0.2 m up, gripper down.
HOME_TARGET = ((0.4, 0.0, 0.2), (0.0, np.pi, 0.0))


@dataclass(frozen=True)
class ViewRequest:
    """What to show (see the module docstring); angles in rad, positions in m.

    ``arm``: the arm shown (its FK, IK, limits and body); with a scenario None means the scenario's own
    arm (:func:`iik.planning.plan`), without one it is required.
    ``planning`` (:class:`~iik.planning.PlanOptions`, default options when None) only with a scenario;
    ``allow_outside_limits``: show a ``q`` outside the arm's limits (red, with a warning) instead of
    refusing it.
    """

    arm: Arm | None = None
    scenario: str | None = None
    planning: PlanOptions | None = None
    q: tuple[float, ...] | None = None
    xyz: tuple[float, float, float] | None = None
    zxz: tuple[float, float, float] | None = None
    previous: tuple[float, ...] | None = None
    interactive: bool = False
    allow_outside_limits: bool = False


@dataclass(frozen=True)
class Shown:
    """A served or exported view: ``result``, the view's warnings, its one-line headline and details.

    ``details``: further display lines (a plan's notes and attempt log, one line each);
    ``ok``: False when what is shown failed (a plan that failed or timed out).
    """

    result: LiveView | ExportResult
    warnings: tuple[str, ...] = ()
    headline: str = ""
    details: tuple[str, ...] = ()
    ok: bool = True


def _pose_view(req: ViewRequest) -> PoseView:
    arm = req.arm
    if not isinstance(arm, Arm):
        raise ViewRequestError("arm", "a pose is shown on an arm" if arm is None else
                               f"expected an iik.Arm, got {type(arm).__name__}",
                               Remedy("give one as {} (e.g. iik.arms.get(NAME))", "arm"))
    if (req.xyz is None) != (req.zxz is None):
        missing = "zxz" if req.zxz is None else "xyz"
        raise InvalidInputError(missing, "a pose needs both the position and the Eq 42 angles",
                                Remedy("give {} too", missing))
    if req.q is not None and req.xyz is not None:
        raise InvalidInputError("q", "a configuration and a pose were both given",
                                Remedy("give either {}", ("q", "xyz")))
    if req.q is not None:
        outside = outside_limits_text(req.q, arm)
        if outside and not req.allow_outside_limits:
            raise OutsideLimitsError("q", f"{outside}; not shown", joints_outside_limits(req.q, arm),
                                     Remedy("to show it with those links in red: {}", "allow_outside_limits",
                                            True, rerun=True))
        return PoseView(q=req.q, previous=req.previous, interactive=req.interactive, arm=arm)
    xyz, zxz = (req.xyz, req.zxz) if req.xyz is not None else HOME_TARGET
    T = iik.pose_from_euler(np.asarray(xyz, float), *np.asarray(zxz, float))
    interactive = req.interactive or req.xyz is None
    return PoseView(T, previous=req.previous, interactive=interactive, arm=arm)


def show(view, options: ViewOptions | None = None, *, headline: str = "", details: tuple[str, ...] = (),
         ok: bool = True) -> Shown:
    """Present any view (:func:`~.session.present`), refusing to export a live-only one."""
    options = options or ViewOptions()
    if options.export is not None and getattr(view, "live_only", False):
        raise ViewRequestError("export", "interactive IK needs the live server",
                               Remedy("give {} to export", ("q", "xyz", "scenario", "run")))
    result = present(view, options)
    return Shown(result=result, warnings=tuple(getattr(view, "warnings", ())), headline=headline,
                 details=tuple(details), ok=ok)


def view(request: ViewRequest, options: ViewOptions | None = None) -> Shown:
    """Build the requested view and serve it (returns at once) or export it.

    Raises:
        ScenarioError: the scenario does not exist or fails validation.
        OutsideLimitsError: ``q`` is outside Table I and ``allow_outside_limits`` is False.
        ViewRequestError: planning options without a scenario; exporting interactive IK.
        InvalidInputError: inconsistent or non-finite pose arguments.
        PortInUseError, ExportError: see :mod:`.session`.
    """
    if request.scenario is not None:
        if request.q is not None or request.xyz is not None:
            raise InvalidInputError("scenario", "a scenario and a pose were both given",
                                    Remedy("give either {}", ("scenario", "q", "xyz")))
        plan = plan_for_view(request.scenario, request.planning, arm=request.arm)
        return show(PlanScene(plan), options, headline=plan.headline, details=plan_log(plan), ok=plan.success)
    if request.planning is not None:
        raise ViewRequestError("planning", "planning options without a scenario",
                               Remedy("they need a {}", "scenario"))
    pv = _pose_view(request)
    return show(pv, options, headline=pv.summary().split("\n")[0].replace("**", ""))
