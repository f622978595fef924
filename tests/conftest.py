"""Shared pytest setup: hypothesis profiles, and the ``fast_cases`` marker of the fast tier."""

import os
import signal
from collections import Counter

import pytest
from hypothesis import HealthCheck, settings

# "ci" keeps example counts as written but never fails on slow data generation: machines are
# shared and noisy (no wall-clock limits in tests).
settings.register_profile("ci", deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("dev", deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci" if os.environ.get("CI") else "dev"))

# A shell starts background jobs with SIGINT ignored, and Python then keeps it ignored (and so do
# the console scripts the tests start, since an ignored signal survives exec). The Ctrl-C tests
# would wait forever for an interrupt that never arrives; give the suite the usual handler.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(items):
    """``@pytest.mark.fast_cases(n)`` on a parametrized test: its first ``n`` cases stay in the
    fast tier, the others are marked ``slow``. Runs before ``-m`` selects."""
    seen = Counter()
    for item in items:
        mark = item.get_closest_marker("fast_cases")
        if mark is not None:
            key = (item.parent.nodeid, getattr(item, "originalname", item.name))
            seen[key] += 1
            if seen[key] > mark.args[0]:
                item.add_marker(pytest.mark.slow)
