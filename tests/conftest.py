"""Hypothesis profiles: ``ci`` (bounded, derandomized; chosen when ``CI`` is set), ``dev``
(default locally) and ``thorough`` (``HYPOTHESIS_PROFILE=thorough``); and the name of each test
marked ``slow`` shown as it starts, so a quiet run's long tail says what it is waiting for."""

from __future__ import annotations

import os

import pytest
from hypothesis import HealthCheck, settings

settings.register_profile(
    "ci",
    max_examples=25,
    derandomize=True,
    deadline=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile("dev", max_examples=50, deadline=None)
settings.register_profile("thorough", max_examples=1000, deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci" if os.environ.get("CI") else "dev"))


class _SlowTestNames:
    """Names each test marked ``slow`` on its own line as it starts, in a run that names none."""

    def __init__(self, config: pytest.Config) -> None:
        self.config = config
        self.slow: set[str] = set()

    def pytest_collection_modifyitems(self, items: list[pytest.Item]) -> None:
        self.slow = {item.nodeid for item in items if item.get_closest_marker("slow")}

    def pytest_runtest_logstart(self, nodeid: str) -> None:
        reporter = self.config.pluginmanager.get_plugin("terminalreporter")
        if reporter is not None and self.config.get_verbosity() <= 0 and nodeid in self.slow:
            reporter.write("\n")  # off the line of dots (-q tracks no current file to end)
            reporter.write_line(f"slow test running: {nodeid}")


def pytest_configure(config: pytest.Config) -> None:
    """Register the slow-test names (a run with ``-v`` names every test anyway)."""
    config.pluginmanager.register(_SlowTestNames(config), "trackcert-slow-test-names")
