"""The bus options of ``iik run`` and ``iik sim-arm`` (this module is no command: it has no ``NAME``).

``--interface --channel --bitrate --port --modules`` (and ``--timeout`` for the host) become one
:class:`hardware.BusConfig`, validated there; its errors name ``module_ids`` as ``--modules``.
"""

from __future__ import annotations

__all__ = ["add_bus_arguments", "bus_config"]


def add_bus_arguments(p, *, interface: str | None, channel: str | None, joints: int | None) -> None:
    """The bus options; ``interface``/``channel``: their defaults (``interface`` None: the arm simulated
    in-process); ``joints``: how many ``--modules`` ids (None: one or more)."""
    where = interface or "the arm simulated in-process, on a private virtual channel"
    p.add_argument("--interface", default=interface, help=f"python-can interface (default: {where})")
    p.add_argument("--channel", default=channel, help="bus channel (e.g. can0, 239.74.163.2)"
                   + (f"; default {channel}" if channel else ""))
    p.add_argument("--bitrate", type=int, default=None,
                   help="bit rate [bit/s] where the interface needs it: 125000, 250000, 500000 or 1000000")
    p.add_argument("--port", type=int, default=None, help="UDP port (udp_multicast only)")
    p.add_argument("--modules", type=int, nargs=joints or "+", default=[1, 2, 3, 4, 5, 6], metavar="ID",
                   help="the module ids in joint order (default: 1..6)")
    p.spelling.update(module_ids="--modules")  # the library's name as typed


def bus_config(args, *, timeout: float | None = None, sim=None):
    """The :class:`hardware.BusConfig` of the options; with ``sim`` (a :class:`hardware.SimConfig`) and no
    ``--interface`` the modules are simulated in this process on a private ``virtual`` channel (``--channel``
    is for a bus)."""
    from hardware.bus import BusConfig

    interface, channel = ("virtual", None) if args.interface is None else (args.interface, args.channel)
    return BusConfig(interface, channel, args.bitrate, args.port, tuple(args.modules), timeout, sim=sim)
