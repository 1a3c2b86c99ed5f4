"""contact: rough surfaces and their contact with a flat counter-face.

Turns a rough surface into a contact-pressure map and pressure samples for :mod:`glstat`:
fractal and self-affine surface generators, measured-topography I/O (npy/npz, text grids,
XYZ point lists, ISO 25178-72 X3P), ISO 25178 roughness parameters, summit detection and the
load-controlled semi-analytical asperity contact model, with an elastic boundary-element
solver (:func:`solve_bem`) as its reference.
"""

import _glstat_runtime.numba_cache  # noqa: F401  (first: numba caches outside the package)

from . import reference  # noqa: F401  (contact.reference: analytic solutions)
from ._spike_search import Spikes
from .asperity import solve, solve_displacement
from .errors import ContactWarning, TopographyFileError
from .filtering import default_s_filter, s_filter
from .generators import self_affine, weierstrass
from .io import read, write
from .like import WeierstrassParameters, self_affine_like, weierstrass_like, weierstrass_parameters
from .material import effective_modulus
from .quality import HeightSteps, height_steps
from .resample import resample
from .result import ContactResult
from .spectrum import SpectrumFit, fit_spectrum
from .spikes import despike, find_spikes
from .spots import contact_spots
from .summits import Summits, summits
from .surface import Surface
from .surface_comparison import compare_surfaces, plot_psd_comparison, psd_comparison

__all__ = [
    "BEMConvergenceWarning",
    "ContactResult",
    "ContactWarning",
    "HeightSteps",
    "SpectrumFit",
    "Spikes",
    "Summits",
    "Surface",
    "TopographyFileError",
    "WeierstrassParameters",
    "compare_models",
    "compare_surfaces",
    "contact_spots",
    "default_depths",
    "default_s_filter",
    "despike",
    "effective_modulus",
    "find_spikes",
    "fit_spectrum",
    "height_steps",
    "max_von_mises",
    "plot_psd_comparison",
    "psd_comparison",
    "read",
    "resample",
    "s_filter",
    "self_affine",
    "self_affine_like",
    "solve",
    "solve_bem",
    "solve_bem_displacement",
    "solve_displacement",
    "subsurface_stress",
    "summits",
    "weierstrass",
    "weierstrass_like",
    "weierstrass_parameters",
    "write",
]

# The boundary-element solver (numba kernels, compiled on first use), the subsurface stresses
# and the model comparison are imported on first access, so that ``import contact`` stays light.
_LAZY = {
    "BEMConvergenceWarning": "bem",
    "solve_bem": "bem",
    "solve_bem_displacement": "bem",
    "compare_models": "bem_compare",
    "default_depths": "subsurface",
    "max_von_mises": "subsurface",
    "subsurface_stress": "subsurface",
}


def __getattr__(name: str):
    """Import the boundary-element names of :data:`__all__` on first access."""
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'contact' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
