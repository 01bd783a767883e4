"""Wall-clock timing for the benchmarks: the median of repeated measurements."""

from __future__ import annotations

import statistics
import time

__all__ = ["median_seconds"]


def median_seconds(fn, reps: int = 7, *, calls: int = 1, warmup: bool = False) -> float:
    """Median over ``reps`` repetitions of the wall time [s] per call of ``fn()``, each repetition
    timing ``calls`` calls in a row; ``warmup`` calls ``fn`` once first, untimed (imports, caches)."""
    if warmup:
        fn()
    times = []
    for _ in range(reps):
        t0 = time.perf_counter()
        for _ in range(calls):
            fn()
        times.append((time.perf_counter() - t0) / calls)
    return statistics.median(times)
