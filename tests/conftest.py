"""Hypothesis profiles for the property-based tests (tests/fuzz).

- `ci` (the default): few examples, derandomized (the same examples every run, so a failure
  is reproducible and the suite stays deterministic), no deadline (a loaded machine is slow,
  not wrong), no example database written.
- `nightly`: many random examples; run with `HYPOTHESIS_PROFILE=nightly` (DEVELOPERS.md).
"""

from __future__ import annotations

import os

from hypothesis import HealthCheck, settings

settings.register_profile("ci", max_examples=25, derandomize=True, deadline=None, database=None,
                          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
settings.register_profile("nightly", max_examples=2000, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
