"""What ``glstat`` and ``contact`` share at run time: where compiled kernels are cached
(:mod:`_glstat_runtime.numba_cache`, registered on import, which the packages holding
kernels import before them), the validation of arguments (:mod:`_glstat_runtime.validation`)
and progress on standard error (:mod:`_glstat_runtime.progress`).

Importing this package loads none of them (nor NumPy or numba).
"""
