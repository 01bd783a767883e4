"""Whole-arm collision checking with Coal: the URDF's collision shapes against the scene.

The arm's collision shapes are the body of the arm in use,
:func:`iik.planning.robot_model.arm_model`: its own URDF's shapes (the shipped
``urdf/thesis_arm.urdf`` for the thesis arm, ``urdf/crx10ia.urdf`` for the CRX-10iA),
the PowerCube shapes for another arm of the thesis's form, or cylinders generated
along the links of any other arm; the environment is the scenario's boxes (obstacles and supports),
the mobile platform and the floor of the scene (default
:data:`iik.scene.THESIS_SCENE`; the floor is a half-space). Distances are exact Coal
(GJK/EPA) distances between the shapes; a negative value is a penetration.

Motion between two configurations is checked *continuously* by certified
bisection: a point of the arm moves at most ``B = sum_j R_j |dq_j|`` along the
joint-space straight line, where ``R_j`` bounds the distance of every
downstream collision shape from joint ``j``'s axis (triangle inequality over
the URDF joint offsets plus each shape's bounding radius). So the clearance on
the segment is at least ``(d0 + d1 - B) / 2``; segments whose bound is below
the required clearance are bisected until the bound holds or ``B`` is below
``resolution`` (then the sampled minimum minus ``B / 2`` is reported).

Excluded pairs: the arm's root link (``base_link``) against the platform (it is bolted onto it).
Self-collisions between non-adjacent links are checked separately
(:meth:`SceneCollision.self_distance`) with no safety zone. On a segment that
violates ``required`` the bisection stops at the first sample below it, so the
reported motion value is then an upper bound of the true minimum (it proves
the violation, not its depth).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import coal
import numpy as np
import pinocchio as pin

from iik.arm import Arm
from iik.errors import InvalidInputError
from iik.scene import THESIS_SCENE, Box, Scene
from iik.validation import as_joints

from .budget import Budget
from .robot_model import arm_model, collision_link

__all__ = ["SceneCollision", "PathClearance", "Nearest"]


@dataclass(frozen=True)
class Nearest:
    """The closest arm-environment pair at one configuration (Coal distance; base frame 0, m): the
    project's one nearest-pair result (:meth:`SceneCollision.nearest`; the viewer's per-frame
    clearance, :func:`iik.planning.viewer.frame_clearance`, is one per frame).

    Attributes:
        distance: Distance between the pair [m]; negative: penetration depth.
        link: URDF link of the nearest arm shape, e.g. ``"link4"``.
        object: The environment object: a scenario box's name, ``"platform"`` or ``"floor"``.
        on_link: (3,) nearest point on the link's shape [m].
        on_object: (3,) nearest point on the object [m] (``|on_link - on_object| = |distance|``).
    """

    distance: float
    link: str
    object: str
    on_link: np.ndarray
    on_object: np.ndarray


@dataclass(frozen=True)
class PathClearance:
    """Whole-arm clearance along a joint path.

    Attributes:
        step: (n,) minimum arm-to-environment distance at each configuration [m].
        step_link: (n,) name of the link attaining it.
        step_object: (n,) name of the environment object attaining it.
        motion: (n-1,) certified lower bound of the clearance on each motion between steps [m].
        self_min: Smallest self-distance (non-adjacent links) over the steps [m].
        checks: Number of configurations evaluated (steps + bisection samples).
    """

    step: np.ndarray
    step_link: np.ndarray
    step_object: np.ndarray
    motion: np.ndarray
    self_min: float
    checks: int

    @property
    def minimum(self) -> float:
        """Smallest clearance over the steps and the motions between them [m]: a certified lower
        bound (a motion's bound is refined only until it clears the required distance)."""
        return float(min(self.step.min(), self.motion.min() if len(self.motion) else np.inf))

    @property
    def closest_link(self) -> str:
        """The link nearest to the scene at the step of smallest clearance."""
        return str(self.step_link[int(np.argmin(self.step))])

    @property
    def closest_object(self) -> str:
        """The scene object nearest to the arm at the step of smallest clearance."""
        return str(self.step_object[int(np.argmin(self.step))])

    def keeps(self, required: float) -> bool:
        """The acceptance rule of a path: clearance ``>= required`` [m] everywhere, no self-contact."""
        return self.minimum >= required and self.self_min > 0


class SceneCollision:
    """Coal distance queries between an arm and a scene.

    Args:
        boxes: Scenario boxes (:class:`iik.scene.Box`), base frame.
        arm: The arm (its body, :func:`~iik.planning.robot_model.arm_model`, placed by its kinematics).
        scene: Platform and floor (default :data:`iik.scene.THESIS_SCENE`).
        platform, floor: Include them.
    """

    def __init__(self, boxes: Sequence[Box] = (), *, arm: Arm, scene: Scene = THESIS_SCENE,
                 platform: bool = True, floor: bool = True):
        tm = arm_model(arm)
        self.arm = arm
        self.geometry = tm.geometry
        self.model = tm.model
        self.data = self.model.createData()
        src = tm.collision_model
        gm = pin.GeometryModel()
        for obj in src.geometryObjects:
            gm.addGeometryObject(obj.copy() if hasattr(obj, "copy") else obj)
        self.n_arm = len(src.geometryObjects)
        self.arm_link = np.array([collision_link(self.model, o) for o in src.geometryObjects])
        root = [o.parentJoint == 0 for o in src.geometryObjects]  # shapes of the root link
        env: list[tuple[str, object, np.ndarray]] = []
        for b in boxes:
            env.append((b.name, coal.Box(*b.size), np.asarray(b.center, float)))
        if platform:
            p = scene.platform
            env.append(("platform", coal.Box(*p.size), np.asarray(p.center, float)))
        if floor:
            env.append(("floor", coal.Halfspace(np.array([0.0, 0.0, 1.0]), float(scene.floor.z)),
                        np.zeros(3)))
        self.env_names = np.array([e[0] for e in env])
        for name, shape, c in env:
            obj = pin.GeometryObject(f"env:{name}", 0, 0, pin.SE3(np.eye(3), c), shape)
            gm.addGeometryObject(obj)
        self.pairs: list[tuple[int, int]] = []
        for i in range(self.n_arm):
            for k, (name, _s, _c) in enumerate(env):
                if name == "platform" and root[i]:
                    continue  # bolted onto the platform
                j = self.n_arm + k
                gm.addCollisionPair(pin.CollisionPair(i, j))
                self.pairs.append((i, k))
        self.n_env_pairs = len(self.pairs)
        self.geom_model = gm
        self.geom_data = pin.GeometryData(gm)
        self.self_model = src  # non-adjacent link pairs, registered by arm_model()
        self.self_data = pin.GeometryData(src)
        self._pair_arm = np.array([p[0] for p in self.pairs], int)
        self._pair_env = np.array([p[1] for p in self.pairs], int)
        self.radius_bound = self._radius_bounds(tm)

    def _radius_bounds(self, tm) -> np.ndarray:
        """R_j: bound on the distance of any downstream shape point from joint j [m]."""
        model = self.model
        nj = model.njoints - 1
        R = np.zeros(nj)
        for obj in tm.collision_model.geometryObjects:
            g = obj.geometry
            g.computeLocalAABB()
            r_obj = float(np.linalg.norm(obj.placement.translation)) + float(g.aabb_radius)
            k = obj.parentJoint
            for j in range(1, k + 1):
                chain = sum(float(np.linalg.norm(model.jointPlacements[m].translation))
                            for m in range(j + 1, k + 1))
                R[j - 1] = max(R[j - 1], chain + r_obj)
        return R

    def _update(self, q: np.ndarray) -> int:
        pin.forwardKinematics(self.model, self.data, q)
        pin.updateGeometryPlacements(self.model, self.data, self.geom_model, self.geom_data)
        return int(pin.computeDistances(self.geom_model, self.geom_data))

    def _closest(self, q: np.ndarray) -> tuple[float, int]:
        """(distance [m], pair index) of the closest arm-environment pair at a (6,) float array."""
        k = self._update(q)
        return float(self.geom_data.distanceResults[k].min_distance), k

    def distances(self, q) -> np.ndarray:
        """Distances [m] of every (arm shape, environment object) pair at one ``q`` [rad]."""
        qb, _ = as_joints(q, "q")
        self._update(qb[0])
        return np.array([self.geom_data.distanceResults[i].min_distance
                         for i in range(self.n_env_pairs)])

    def nearest(self, q) -> Nearest:
        """The closest arm-environment pair at ``q`` (6,) [rad]: distance, link, object, nearest points."""
        qb, batched = as_joints(q, "q")
        if batched:
            raise InvalidInputError("q", f"expected one configuration (6,), got shape {np.shape(q)}")
        d, i = self._closest(qb[0])
        res = self.geom_data.distanceResults[i]  # pair i: (arm shape, environment object), in that order
        return Nearest(distance=d, link=str(self.arm_link[self._pair_arm[i]]),
                       object=str(self.env_names[self._pair_env[i]]),
                       on_link=np.array(res.getNearestPoint1(), float),
                       on_object=np.array(res.getNearestPoint2(), float))

    def keeps(self, q, required: float) -> bool:
        """Does the whole arm at ``q`` [rad] stay ``required`` [m] from the scene, with no self-contact?

        The acceptance test of a single configuration: arm-environment clearance
        ``>= required`` and a positive distance between every pair of non-adjacent links.
        """
        qb, _ = as_joints(q, "q")
        return self._closest(qb[0])[0] >= required and self._self(qb[0]) > 0.0

    def link_clearances(self, q) -> dict[str, float]:
        """Minimum distance [m] of each link to the environment at ``q``."""
        d = self.distances(q)
        out: dict[str, float] = {}
        for v, a in zip(d, self._pair_arm, strict=True):
            ln = str(self.arm_link[a])
            out[ln] = min(out.get(ln, np.inf), float(v))
        return out

    def self_distance(self, q) -> float:
        """Smallest distance [m] between shapes of non-adjacent links at ``q`` [rad]."""
        qb, _ = as_joints(q, "q")
        return self._self(qb[0])

    def _self(self, q: np.ndarray) -> float:
        if len(self.self_model.collisionPairs) == 0:
            return np.inf
        pin.forwardKinematics(self.model, self.data, q)
        pin.updateGeometryPlacements(self.model, self.data, self.self_model, self.self_data)
        k = int(pin.computeDistances(self.self_model, self.self_data))
        return float(self.self_data.distanceResults[k].min_distance)

    def motion_bound(self, q0, q1) -> float:
        """Largest displacement [m] of any arm point on the straight joint motion q0 -> q1."""
        return float(self.radius_bound @ np.abs(np.asarray(q1, float) - np.asarray(q0, float)))

    def path_clearance(self, qs, required: float = 0.0, *, resolution: float = 0.002,
                       check_self: bool = True, budget: Budget | None = None) -> PathClearance:
        """Clearance at every configuration and a certified bound on every motion between them.

        Args:
            qs: (n, 6) joint path [rad].
            required: Clearance the motions must keep [m] (bisection stops once certified).
            resolution: Stop bisecting when the motion bound is below this [m].
            check_self: Also compute the self-distance at the steps.
            budget: Time budget and progress (:class:`~iik.planning.Budget`), ticked at
                every configuration and bisection sample; default: none.
        """
        budget = budget or Budget()
        Q, _ = as_joints(qs, "qs")
        n = len(Q)
        step = np.empty(n)
        link = np.empty(n, dtype=object)
        obj = np.empty(n, dtype=object)
        self_min = np.inf
        for i, q in enumerate(Q):
            budget.tick("whole-arm Coal check", i, n)
            step[i], k = self._closest(q)
            link[i], obj[i] = self.arm_link[self._pair_arm[k]], self.env_names[self._pair_env[k]]
            if check_self:
                self_min = min(self_min, self._self(q))
        checks = n
        motion = np.empty(max(n - 1, 0))
        for i in range(n - 1):
            budget.tick("whole-arm Coal check of the motions", i, n - 1)
            lb, c = self._segment(Q[i], Q[i + 1], step[i], step[i + 1], required, resolution, 0, budget)
            motion[i] = lb
            checks += c
        return PathClearance(step=step, step_link=link.astype(str), step_object=obj.astype(str),
                             motion=motion, self_min=float(self_min), checks=checks)

    def _segment(self, q0, q1, d0, d1, required, resolution, depth, budget: Budget) -> tuple[float, int]:
        B = self.motion_bound(q0, q1)
        lb = min(d0, d1) if B <= abs(d0 - d1) else (d0 + d1 - B) / 2
        if lb >= required or B <= resolution or depth > 20:
            return lb, 0
        budget.tick("whole-arm Coal check of the motions (bisection)", depth, 20)
        qm = 0.5 * (q0 + q1)
        dm, _ = self._closest(qm)
        if dm < required:  # a violation is established (a sampled distance); stop refining
            return dm, 1
        a, ca = self._segment(q0, qm, d0, dm, required, resolution, depth + 1, budget)
        b, cb = self._segment(qm, q1, dm, d1, required, resolution, depth + 1, budget)
        return min(a, b), ca + cb + 1
