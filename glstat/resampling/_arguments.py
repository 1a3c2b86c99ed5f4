"""The arguments of :func:`glstat.bootstrap`: their checks, the groups of a cluster bootstrap
and the seeds of the resamples.

Every resample r has its own generator, ``numpy.random.default_rng(child_r)`` with
``child_r`` the r-th child of one ``numpy.random.SeedSequence`` whose entropy is drawn from
the user's ``rng``; the children after the B resamples seed the later random streams of the
result (the jackknife partition of BCa, the random maxima).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from _glstat_runtime.validation import check_level, check_n_resamples, real_values

from .._fit_engine.aliases import resolve_method, resolve_param

__all__ = ["COMPILED", "KINDS", "Arguments", "Groups", "check_arguments", "draw_entropy",
           "group_choices", "resample_seeds", "stream_seed"]

#: The kinds of resample.
KINDS = ("nonparametric", "parametric")
#: The fitting methods whose resample statistics are computed in one compiled pass.
COMPILED = ("moments", "percentiles", "lmoments")


class Groups(NamedTuple):
    """The groups of a cluster bootstrap over the sorted finite data.

    Attributes
    ----------
    members : ndarray of int
        Indices into the sorted data, group after group.
    offsets : ndarray of int, shape (G + 1,)
        Where each group starts in ``members`` (and where the last one ends).
    sizes : ndarray of int, shape (G,)
        Number of values of each group.
    """

    members: np.ndarray
    offsets: np.ndarray
    sizes: np.ndarray


class Arguments(NamedTuple):
    """The checked arguments of a bootstrap."""

    n_resamples: int
    confidence_level: float
    param: str
    groups: Groups | None
    method: str = "moments"


def check_arguments(data, param, method, n_resamples, confidence_level, kind, nan_policy,
                    groups) -> Arguments:
    """Check the arguments of :func:`glstat.bootstrap` (in the order of its documentation)
    and lay out the groups.

    Raises
    ------
    TypeError, ValueError
        As documented by :func:`glstat.bootstrap`; the data themselves are checked by the fit.
    """
    n = check_n_resamples(n_resamples)
    level = check_level(confidence_level)
    if kind not in KINDS:
        raise ValueError(f"kind must be 'nonparametric' or 'parametric', got {kind!r}")
    method = resolve_method(method)
    param = resolve_param(param)
    layout = None
    if groups is not None:
        if kind != "nonparametric":
            raise ValueError("groups resample whole groups of the data: use kind='nonparametric'")
        if nan_policy == "propagate":
            raise ValueError("groups need finite data: use nan_policy='raise' or 'omit'")
        layout = group_layout(data, groups)
    return Arguments(n, level, param, layout, method)


def group_layout(data, groups) -> Groups:
    """The groups of ``groups`` (one label per data value) over the sorted finite data."""
    values, unmasked = real_values(data)
    labels = np.asarray(groups).ravel()
    if labels.size != values.size:
        raise ValueError(f"groups must give one label per data value: {labels.size} labels for "
                         f"{values.size} values")
    keep = np.isfinite(values) if unmasked is None else np.isfinite(values) & unmasked
    values, labels = values[keep], labels[keep]
    order = np.argsort(values, kind="stable")
    _, inverse = np.unique(labels[order], return_inverse=True)
    sizes = np.bincount(inverse)
    if sizes.size < 2:
        raise ValueError("groups: at least two groups are needed to resample them")
    members = np.argsort(inverse, kind="stable")
    offsets = np.concatenate(([0], np.cumsum(sizes)))
    return Groups(members, offsets, sizes)


def draw_entropy(rng) -> tuple[int, ...]:
    """The entropy of the bootstrap's seed sequence, drawn from ``rng`` (seed or generator)."""
    return tuple(int(v) for v in np.random.default_rng(rng).integers(0, 2**63, size=4))


def resample_seeds(entropy: tuple[int, ...], n_resamples: int) -> list[np.random.SeedSequence]:
    """The seed of every resample: the first ``n_resamples`` children of the seed sequence."""
    return [np.random.SeedSequence(list(entropy), spawn_key=(r,)) for r in range(n_resamples)]


def stream_seed(entropy: tuple[int, ...], n_resamples: int, key: int) -> np.random.SeedSequence:
    """The seed of stream ``key`` after the resamples (0: the jackknife partition, 1: the
    random maxima)."""
    return np.random.SeedSequence(list(entropy), spawn_key=(n_resamples + key,))


def group_choices(seeds, n_groups: int) -> np.ndarray:
    """The groups every resample draws, shape (B, G): the first draw of its generator."""
    return np.stack([np.random.default_rng(sd).integers(0, n_groups, size=n_groups, dtype=np.int64)
                     for sd in seeds])
