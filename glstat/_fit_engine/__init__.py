"""The engine of the GLD fits: compiled shape equations and objectives, their solvers, the
candidate solutions and the sample statistics they match (no public names; the public fits are
in :mod:`glstat.fitting`)."""

import _glstat_runtime.numba_cache  # noqa: F401  (first: numba caches outside the package)
