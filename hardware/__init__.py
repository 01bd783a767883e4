"""hardware: the PowerCube CAN protocol, driver, simulated arm and executor.

Built on python-can; uses ``iik`` for limits and forward kinematics.
"""

__all__: list[str] = []
