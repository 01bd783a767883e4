"""Thesis checks. Every module here is imported by ``load_checks`` and
registers its checks with ``@verification.registry.register``."""
