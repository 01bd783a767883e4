"""Independent references the thesis checks compare against.

* :mod:`.pinocchio_model` -- Pinocchio tool poses and Jacobians of the shipped URDF.
* :mod:`.reachability` -- ground-truth position reachability by sampling (Sec 3.4).
* :mod:`.abdel_malek` -- the App. E boundary quantities from Pinocchio.
* :mod:`.baselines` -- Newton and damped-least-squares IK on Pinocchio.
* :mod:`.ur5`, :mod:`.panda` -- other robots, to check the URDF generator
  (:mod:`.example_robots`: their reference URDFs and FK).
"""

__all__: list[str] = []
