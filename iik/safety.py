"""The safety numbers the planner, the executor and the run analysis share (the one place they live).

The planner keeps them (:mod:`iik.planning`) and the hardware layer checks them (:mod:`hardware`), so
that running a trajectory file or the demo needs no planning layer. Units: m, rad, s.
"""

from __future__ import annotations

import math

__all__ = ["SAFETY_ZONE", "SAFETY_ZONE_PREDEFINED", "EXECUTION_MARGIN", "STEP_RESOLUTION", "MIN_STEP"]

#: Sec 3.6.2.2 / Sec 4.3.2: thickness of the safety zone around each obstacle's ellipsoid [m]; the
#: clearance a planned path keeps, and the 30 mm zone suggested for a run's motion.
SAFETY_ZONE = 0.030
#: Sec 4.3.1: the minimum safety zone chosen from the predefined paths [m]: the end-effector error
#: an ok run of a trajectory file or the demo stays within.
SAFETY_ZONE_PREDEFINED = 0.010
#: Margin inside the joint limits (Table I) [rad] that every planned sample keeps (0.5 deg): the
#: default margin of :func:`hardware.validate`, so a planned trajectory is never refused for it.
EXECUTION_MARGIN = math.radians(0.5)
#: Resolution of an executed step time [s]: FSTEP carries whole milliseconds (docs/POWERCUBE.md).
STEP_RESOLUTION = 0.001
#: Shortest executed step [s] (the default of :func:`hardware.validate`).
MIN_STEP = 0.010
