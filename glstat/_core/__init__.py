"""Pure numerical core of glstat (numba kernels, no scipy.stats or pandas)."""
