"""Deprecated: the asperity model is :mod:`contact.asperity`, the contact modulus
:mod:`contact.material`.

Reading ``solve``, ``solve_displacement`` or ``effective_modulus`` from this module gives
the function of its new module and issues a :class:`DeprecationWarning`; all three are
also in :mod:`contact` itself.
"""

from __future__ import annotations

import warnings

from . import asperity, material

_MOVED = {"solve": asperity, "solve_displacement": asperity, "effective_modulus": material}

__all__ = sorted(_MOVED)


def __getattr__(name: str):
    """The moved function ``name``, with a :class:`DeprecationWarning`."""
    module = _MOVED.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    warnings.warn(
        f"contact.solver is deprecated: use contact.{name} (defined in {module.__name__})",
        DeprecationWarning,
        stacklevel=2,
    )
    return getattr(module, name)
