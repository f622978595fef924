"""Shared pytest setup: hypothesis profiles and doctest namespace."""

import os

from hypothesis import HealthCheck, settings

# "ci" keeps example counts as written but never fails on slow data generation: machines are
# shared and noisy (no wall-clock limits in tests).
settings.register_profile("ci", deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("dev", deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci" if os.environ.get("CI") else "dev"))
