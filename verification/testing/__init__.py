"""Helpers for tests and benchmarks: Hypothesis strategies (Hypothesis, of the ``test`` extra, is
imported only when a strategy is built), pose families, timing, import costs, the IK benchmark."""

__all__: list[str] = []
