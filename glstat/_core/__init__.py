"""Pure numerical core of glstat (numba kernels, no scipy.stats or pandas)."""

import _glstat_runtime.numba_cache  # noqa: F401  (first: numba caches outside the package)
