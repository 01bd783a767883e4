"""Helpers for tests and benchmarks: Hypothesis strategies and the IK benchmark."""

__all__: list[str] = []
