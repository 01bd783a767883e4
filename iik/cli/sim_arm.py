"""``iik sim-arm``: serve simulated PowerCube modules on a CAN bus, in their own process.

Example (two terminals, no hardware)::

    iik sim-arm --interface udp_multicast --channel 239.74.163.2
    iik run --demo --interface udp_multicast --channel 239.74.163.2

Prints one ``sim-arm ready`` line when serving; stops on Ctrl-C, SIGTERM or SIGHUP, or
after ``--duration`` seconds. ``--arm`` (default thesis) sets the modules' limits, speeds and
accelerations: run the host with the same arm. Hostile options (an initial position outside the limits, a
negative duration...) are refused before a bus is opened (:class:`hardware.bus.BusConfig`). The work
is :func:`hardware.sim.serve`.
"""

from __future__ import annotations

import signal
import sys
import threading

from .arm_option import add_arm_argument, chosen_arm
from .bus_option import add_bus_arguments, bus_config

NAME = "sim-arm"
HELP = "serve simulated PowerCube modules on a python-can bus (real time, own process)"


def add_arguments(p) -> None:
    add_bus_arguments(p, interface="udp_multicast", channel="239.74.163.2", joints=None)
    add_arm_argument(p)
    p.add_argument("--lag", type=float, default=0.02, help="tracking lag of the measurement [0, 1] s")
    p.add_argument("--initial", type=float, nargs="+", default=None, metavar="RAD",
                   help="initial joint positions [rad], inside Table I (default: zeros)")
    p.add_argument("--not-homed", action="store_true", help="start with HOME_OK clear")
    p.add_argument("--duration", type=float, default=None, help="stop after this many seconds")


def run(args) -> int:
    from hardware.bus import SimConfig
    from hardware.sim import serve

    arm = chosen_arm(args)  # before any bus is opened
    config = bus_config(args, sim=SimConfig(lag=args.lag, initial=args.initial, homed=not args.not_homed))
    stop = threading.Event()
    previous = {s: signal.signal(s, lambda n, frame: stop.set()) for s in (signal.SIGTERM, signal.SIGHUP)}

    def ready(served) -> None:
        print(f"sim-arm ready: modules {list(served.module_ids)} of the arm {arm.name!r} on "
              f"{args.interface}:{args.channel}", flush=True)

    try:
        serve(config, arm=arm, duration=args.duration, stop=stop, ready=ready)
    except KeyboardInterrupt:
        pass
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
    print("sim-arm stopped", file=sys.stderr, flush=True)
    return 0
