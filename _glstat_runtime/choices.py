"""The names the arguments of the fits choose from: the GLD's parameterisations and the
fitting methods (plain tuples, importable without NumPy, e.g. by the command-line parsers;
:mod:`_glstat_runtime.validation` checks arguments against them)."""

__all__ = ["FIT_METHODS", "PARAMS"]

#: The parameterisations of the GLD.
PARAMS = ("rs", "fkml")
#: The fitting methods of :func:`glstat.fit`.
FIT_METHODS = ("moments", "percentiles", "lmoments", "tlmoments", "mle", "mps", "starship")
