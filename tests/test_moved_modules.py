"""Module paths of the previous release keep working for one release, with a warning that names
the new home; the package's public names are untouched by them."""

from __future__ import annotations

import importlib
import subprocess
import sys

import pytest

import glstat

MOVED = {
    "glstat.gld": ("glstat.distributions.gld", "GLD"),
    "glstat.generalized_lambda": ("glstat.distributions.generalized_lambda", "GeneralizedLambda"),
    "glstat.counts": ("glstat.extremes.counts", "PoissonCount"),
    "glstat.damage": ("glstat.extremes.damage", "damage_probability"),
    "glstat.pot": ("glstat.extremes.peaks_over_threshold", "predict_maximum_pot"),
    "glstat.checks": ("glstat.gof.binomial_check", "outcomes_needed"),
    "glstat.bootstrap": ("glstat.resampling", "BootstrapFit"),
    "glstat.bootstrap_maximum": ("glstat.resampling.maxima", "resample_maximum"),
    "glstat.fitting.core": ("glstat.fitting.fit_functions", "fit"),
    "glstat.cli_input": ("glstat.cli.sample_files", "read_sample"),
    "glstat.cli_fit": ("glstat.cli.fit", "run"),
}


@pytest.mark.parametrize("old", sorted(MOVED))
def test_an_old_path_gives_the_new_object_with_a_warning(old):
    new, name = MOVED[old]
    module = importlib.import_module(old)
    with pytest.warns(DeprecationWarning, match=f"{old} moved to {new}"):
        value = getattr(module, name)
    assert value is getattr(importlib.import_module(new), name)


def test_a_name_the_new_module_lacks_is_an_attribute_error():
    module = importlib.import_module("glstat.damage")
    with pytest.warns(DeprecationWarning), pytest.raises(AttributeError):
        module.no_such_name


def test_the_public_names_stay_functions():
    import glstat.bootstrap as gb  # the function, as before the move

    assert gb is glstat.bootstrap and callable(gb)
    assert glstat.damage_probability.__module__ == "glstat.extremes.damage"


def test_importing_glstat_warns_of_nothing():
    proc = subprocess.run([sys.executable, "-W", "error::DeprecationWarning", "-c",
                           "import glstat, glstat.study, glstat.cli"], capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr
