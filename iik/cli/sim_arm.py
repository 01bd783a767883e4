"""``iik sim-arm``: serve simulated PowerCube modules on a CAN bus, in their own process.

Example (two terminals, no hardware)::

    iik sim-arm --interface udp_multicast --channel 239.74.163.2
    iik run --demo --interface udp_multicast --channel 239.74.163.2

Prints one ``sim-arm ready`` line when serving; stops on Ctrl-C, SIGTERM or SIGHUP, or
after ``--duration`` seconds. ``--arm`` (default thesis) sets the modules' limits, speeds and
accelerations: run the host with the same arm. Hostile options (an initial position outside the limits, a
negative duration...) are refused before a bus is opened. The work is :func:`hardware.sim.serve`.
"""

from __future__ import annotations

import signal
import sys
import threading

from .arm_option import add_arm_argument, chosen_arm

NAME = "sim-arm"
HELP = "serve simulated PowerCube modules on a python-can bus (real time, own process)"


def add_arguments(p) -> None:
    p.add_argument("--interface", default="udp_multicast",
                   help="python-can interface (default: udp_multicast)")
    p.add_argument("--channel", default="239.74.163.2", help="bus channel (default: 239.74.163.2)")
    p.add_argument("--port", type=int, default=None, help="UDP port (udp_multicast only)")
    p.add_argument("--bitrate", type=int, default=None,
                   help="bit rate [bit/s] where the interface needs it: 125000, 250000, 500000 or 1000000")
    add_arm_argument(p)
    p.add_argument("--modules", type=int, nargs="+", default=[1, 2, 3, 4, 5, 6], metavar="ID",
                   help="module ids in joint order (default: 1..6)")
    p.add_argument("--lag", type=float, default=0.02, help="tracking lag of the measurement [0, 1] s")
    p.add_argument("--initial", type=float, nargs="+", default=None, metavar="RAD",
                   help="initial joint positions [rad], inside Table I (default: zeros)")
    p.add_argument("--not-homed", action="store_true", help="start with HOME_OK clear")
    p.add_argument("--duration", type=float, default=None, help="stop after this many seconds")
    p.spelling.update(module_ids="--modules")  # the library's name as typed


def run(args) -> int:
    from hardware.sim import serve

    arm = chosen_arm(args)  # before any bus is opened
    stop = threading.Event()
    previous = {s: signal.signal(s, lambda n, frame: stop.set()) for s in (signal.SIGTERM, signal.SIGHUP)}

    def ready(sim) -> None:
        print(f"sim-arm ready: modules {list(sim.module_ids)} of the arm {arm.name!r} on "
              f"{args.interface}:{args.channel}", flush=True)

    try:
        serve(args.interface, args.channel, args.modules, arm=arm, bitrate=args.bitrate, port=args.port,
              lag=args.lag,
              initial=args.initial, homed=not args.not_homed, duration=args.duration, stop=stop, ready=ready)
    except KeyboardInterrupt:
        pass
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
    print("sim-arm stopped", file=sys.stderr, flush=True)
    return 0
