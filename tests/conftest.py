"""Shared pytest configuration: hypothesis profiles.

Two profiles, chosen by the environment variable ``UWML_HYPOTHESIS_PROFILE``:

* ``fast`` (default): 200 examples per property, for every commit; the whole suite stays
  well under a minute on two cores.
* ``slow``: 2000 examples per property, for nightly or pre-release runs.

Tests whose single example is expensive (a batch of thousands of states held against the
numpy reference) take a fixed fraction of the profile's ``max_examples`` (see ``scaled`` in
``test_hydro.py``), so the profile still scales them. No example database is kept
(``database=None``); hypothesis may still write a ``.hypothesis/`` cache, which is gitignored.
"""

import os

from hypothesis import HealthCheck, settings

settings.register_profile(
    "fast",
    max_examples=200,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile(
    "slow",
    max_examples=2000,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow],
)

_PROFILE = os.environ.get("UWML_HYPOTHESIS_PROFILE", "fast")
if _PROFILE not in ("fast", "slow"):
    raise ValueError(f"UWML_HYPOTHESIS_PROFILE must be 'fast' or 'slow', got {_PROFILE!r}")
settings.load_profile(_PROFILE)


def pytest_configure(config) -> None:
    # When a property fails, hypothesis's pytest plugin imports its patch writer, which imports a
    # package that warns about mypy_extensions.TypedDict; with filterwarnings = ["error"] that
    # turns the failure report into an INTERNALERROR. Ignore that one third-party warning.
    config.addinivalue_line("filterwarnings", "ignore:mypy_extensions.TypedDict is deprecated:DeprecationWarning")
