"""The 3D web viewer (issue 13): poses, all IK solutions, interactive IK, plans and run logs.

Built on Pinocchio's visualizer interface (:class:`pinocchio.visualize.ViserVisualizer`
on the ``viser`` web viewer). The arm's body is the URDF's collision shapes; the
scene is the planner's own description (platform, floor, scenario boxes). A view
is served live on localhost (:func:`serve`) or exported as a page that opens from
disk with no server and no network (:func:`export`).

* :mod:`.session` -- serve / export any view; time slider and play/pause.
* :mod:`.bodies` -- one arm on the scene (:class:`ArmBody`).
* :mod:`.environment` -- platform, floor, boxes, ellipsoids (Eq 52-53).
* :mod:`.pose` -- a pose: every IK solution, pick one; interactive IK with a gizmo.
* :mod:`.plan_data` -- the one adapter from the planner's result (:func:`plan_scene`).
* :mod:`.plan` -- a plan played back with clearance and branch switches.
* :mod:`.attempts` -- the planner's attempt log as a table (panel, notebook) and a caption (scene).
* :mod:`.motion` -- several arms following recorded joint tracks (run logs).
* :mod:`.app` -- :func:`view`: one call from a request (pose, scenario, interactive) to a view.

Errors (:class:`ViewerError` and its subclasses) live in :mod:`iik.planning.errors`, the
layer's one errors module; they are re-exported here.
"""

from ...extras import require
from ...lazy import lazy_exports

require("viewer", __name__)

__getattr__, __dir__ = lazy_exports(__name__, {
    "..errors": ("ExportError", "OutsideLimitsError", "PortInUseError", "ViewerError", "ViewRequestError"),
    ".app": ("Shown", "ViewRequest", "show", "view"),
    ".attempts": ("attempt_table",),
    ".motion": ("Motion", "MotionView", "Track"),
    ".plan": ("PlanScene",),
    ".plan_data": ("PlanView", "frame_clearance", "least_clearance", "plan_for_view", "plan_scene"),
    ".pose": ("PoseView",),
    ".session": ("Animation", "ExportResult", "LiveView", "View", "ViewOptions", "export", "inline",
                 "present", "record", "serve"),
})

__all__ = [
    "ViewRequest",
    "Shown",
    "view",
    "show",
    "PoseView",
    "Motion",
    "MotionView",
    "Track",
    "ViewerError",
    "ViewRequestError",
    "OutsideLimitsError",
    "PortInUseError",
    "ExportError",
    "Animation",
    "View",
    "ViewOptions",
    "LiveView",
    "ExportResult",
    "serve",
    "export",
    "record",
    "inline",
    "present",
    "PlanView",
    "plan_scene",
    "plan_for_view",
    "frame_clearance",
    "least_clearance",
    "PlanScene",
    "attempt_table",
]
