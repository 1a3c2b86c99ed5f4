"""What ``glstat`` and ``contact`` share at run time: where compiled kernels are cached
(:mod:`_glstat_runtime.numba_cache`, registered on import), the validation of arguments
(:mod:`_glstat_runtime.validation`) and progress on standard error
(:mod:`_glstat_runtime.progress`)."""

from . import numba_cache  # noqa: F401  (registers the cache locator before any kernel loads)
