"""One call per request: what to show (:class:`ViewRequest`), how (:class:`ViewOptions`) -> :class:`Shown`.

The modes of ``iik view``:

* a scenario (file or shipped name): plan it and play the plan (:class:`~.plan.PlanScene`);
* ``q``: the arm at ``q`` and every IK solution of its pose (:class:`~.pose.PoseView`);
* ``xyz`` + ``zxz``: every IK solution of that pose (position [m], Eq 42 angles [rad]);
* nothing, or ``interactive``: interactive IK with a draggable gizmo (live only).

Run logs are shown by :func:`hardware.view.view_run` (the hardware layer reads them).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import iik
from iik.errors import InvalidInputError

from ..errors import ViewRequestError
from .plan import PlanScene
from .plan_data import plan_for_view
from .pose import PoseView
from .session import ExportResult, LiveView, ViewOptions, present

__all__ = ["ViewRequest", "Shown", "view", "show"]

#: Start pose of interactive IK with no pose given: tool 0.4 m ahead, 0.2 m up, gripper down.
HOME_TARGET = ((0.4, 0.0, 0.2), (0.0, np.pi, 0.0))


@dataclass(frozen=True)
class ViewRequest:
    """What to show (see the module docstring); angles in rad, positions in m."""

    scenario: str | None = None
    q: tuple[float, ...] | None = None
    xyz: tuple[float, float, float] | None = None
    zxz: tuple[float, float, float] | None = None
    previous: tuple[float, ...] | None = None
    interactive: bool = False


@dataclass(frozen=True)
class Shown:
    """A served or exported view: ``result``, the view's warnings and its one-line headline."""

    result: LiveView | ExportResult
    warnings: tuple[str, ...] = ()
    headline: str = ""


def _pose_view(req: ViewRequest) -> PoseView:
    if (req.xyz is None) != (req.zxz is None):
        raise InvalidInputError("--xyz/--zxz", "give both the position and the Eq 42 angles")
    if req.q is not None and req.xyz is not None:
        raise InvalidInputError("--q", "give either --q or --xyz/--zxz, not both")
    if req.q is not None:
        return PoseView(q=req.q, previous=req.previous, interactive=req.interactive)
    xyz, zxz = (req.xyz, req.zxz) if req.xyz is not None else HOME_TARGET
    T = iik.pose_from_zxz(np.asarray(xyz, float), *np.asarray(zxz, float))
    interactive = req.interactive or req.xyz is None
    return PoseView(T, previous=req.previous, interactive=interactive)


def show(view, options: ViewOptions | None = None, *, headline: str = "") -> Shown:
    """Present any view (:func:`~.session.present`), refusing to export a live-only one."""
    options = options or ViewOptions()
    if options.export is not None and getattr(view, "live_only", False):
        raise ViewRequestError("export", "interactive IK needs the live server; give a pose (--q or "
                                         "--xyz/--zxz), a scenario or a run log to export")
    result = present(view, options)
    return Shown(result=result, warnings=tuple(getattr(view, "warnings", ())), headline=headline)


def view(request: ViewRequest, options: ViewOptions | None = None) -> Shown:
    """Build the requested view and serve it (returns at once) or export it.

    Raises:
        ScenarioError: the scenario does not exist or fails validation.
        InvalidInputError: inconsistent or non-finite pose arguments.
        PortInUseError, ExportError: see :mod:`.session`.
    """
    if request.scenario is not None:
        if request.q is not None or request.xyz is not None:
            raise InvalidInputError("SCENARIO", "give a scenario or a pose, not both")
        plan = plan_for_view(request.scenario)
        return show(PlanScene(plan), options, headline=plan.headline)
    pv = _pose_view(request)
    return show(pv, options, headline=pv.summary().split("\n")[0].replace("**", ""))
