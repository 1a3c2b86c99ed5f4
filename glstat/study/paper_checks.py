"""The checks of Table 1 of the paper, each a DataFrame (MPa): every RS root of the printed
moments (:func:`moment_fit_roots`), the printed λ's against the printed moments and their
mirror image (:func:`printed_lambda_check`), and the paper's damage claims from every reading
of the table (:func:`damage_claims`), with the n that reproduces the three claims at once
(:func:`common_n`)."""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np

from .paper_gld import (
    as_distribution,
    claim_n_range,
    damage_at,
    gld_support,
    lambda_moments,
    mirror_lambdas,
    other_readings,
    valid_gld,
)
from .paper_table import CLAIM_RANGES, HARDNESS_MPA, PAPER_CLAIMS, SCENE_N_CONTACT, Table1Row, table_rows

if TYPE_CHECKING:  # pragma: no cover
    from ..distributions.gld import GLD

__all__ = [
    "FAMILIES",
    "common_n",
    "damage_claims",
    "moment_fit_roots",
    "n_contact_for",
    "printed_lambda_check",
    "reading_family",
]

_NAN = float("nan")

#: The families of readings of Table 1, and how the findings name them.
FAMILIES = {"printed": "the printed λ's",
            "mirror of printed": "the mirror image of the printed λ's",
            "moment fits": "the GLDs matching the printed moments (every RS root)"}

#: The ``source`` of the damage rows for each of :func:`glstat.study.paper_gld.other_readings`.
_OTHER_SOURCES = {"λ2 sign changed": "printed, λ2 sign changed",
                  "Q(U), decreasing Q": "printed, read as Q(U) with Q decreasing"}


def moment_fit_roots(table=None, hardness_mpa: float = HARDNESS_MPA):
    """Every RS root of Table 1's moments, with its support and moments.

    Parameters
    ----------
    table : optional
        Table 1 (see :func:`table1`); default :data:`TABLE1`.
    hardness_mpa : float
        Hardness Pd, MPa.

    Returns
    -------
    pandas.DataFrame
        One row per (H, root) of :func:`glstat.fit_moments` (RS): ``hurst``, ``root``,
        ``selected`` (fit_moments' choice), ``lambda1_mpa``, ``lambda2_per_mpa``, ``lambda3``,
        ``lambda4``, ``region``, ``lower_mpa``, ``upper_mpa`` (support end points),
        ``hardness_beyond_upper`` (the hardness is above the upper end point: damage 0 for
        any n), ``mean_mpa``, ``sd_mpa``, ``skewness``, ``kurtosis`` of the root (computed from
        its λ's, a check of the fit) and ``note`` (why a row has no root: moments not stored,
        or the :class:`glstat.FitError` text).

    Examples
    --------
    The moments of the standard normal (in "MPa") have four RS roots, all bounded:

    >>> from glstat.study.paper import moment_fit_roots
    >>> r = moment_fit_roots([{"hurst": 1.0, "mean_mpa": 0.0, "sd_mpa": 1.0, "skewness": 0.0,
    ...                        "kurtosis": 3.0}])
    >>> r[["selected", "lambda3", "upper_mpa"]].round(4).values.tolist()[0]
    [True, 0.1349, 5.0645]
    """
    import pandas as pd

    from ..errors import FitError
    from ..fitting import fit_moments

    out = []
    for r in table_rows(table):
        base = {"hurst": r.hurst}
        if not r.has_moments:
            out.append({**base, "note": "Table 1 moments not stored (sd, skewness, kurtosis)"})
            continue
        try:
            f = fit_moments(*r.moments, param="rs")
        except FitError as exc:
            out.append({**base, "note": f"FitError: {exc}"})
            continue
        for k, s in enumerate(f.solutions.itertuples(index=False)):
            out.append({**base, "root": k, **_root_row(s, hardness_mpa)})
    cols = ["hurst", "root", "selected", "lambda1_mpa", "lambda2_per_mpa", "lambda3", "lambda4",
            "region", "lower_mpa", "upper_mpa", "hardness_beyond_upper", "mean_mpa", "sd_mpa",
            "skewness", "kurtosis", "note"]
    return pd.DataFrame(out, columns=cols)


def _root_row(s, hardness_mpa: float) -> dict:
    """The columns of :func:`moment_fit_roots` of one root ``s`` of ``fit_moments``."""
    from ..distributions.gld import GLD

    lam = (float(s.lambda1), float(s.lambda2), float(s.lambda3), float(s.lambda4))
    row = {"selected": bool(s.selected), "lambda1_mpa": lam[0], "lambda2_per_mpa": lam[1],
           "lambda3": lam[2], "lambda4": lam[3], "region": s.region, "note": ""}
    if not bool(s.valid):
        row["note"] = "root not a valid RS GLD"
        return row
    lo, hi = gld_support(GLD(*lam))
    m = lambda_moments(*lam)
    row.update(lower_mpa=lo, upper_mpa=hi, hardness_beyond_upper=bool(hardness_mpa >= hi),
               mean_mpa=m[0], sd_mpa=m[1], skewness=m[2], kurtosis=m[3])
    return row


def printed_lambda_check(table=None):
    """The printed λ's against the printed moments, and their mirror image.

    Parameters
    ----------
    table : optional
        Table 1 (see :func:`table1`); default :data:`TABLE1`.

    Returns
    -------
    pandas.DataFrame
        One row per H: ``hurst``; the printed moments ``printed_mean_mpa``,
        ``printed_sd_mpa``, ``printed_skewness``, ``printed_kurtosis``; the printed λ's;
        ``valid`` and ``error`` (the :class:`glstat.InvalidParameterError` text of the printed
        λ's, ``""`` when valid), ``reading``, ``read_lambdas`` and ``region`` (how an invalid
        row was read, :func:`as_distribution`); the moments of the printed λ's so read
        (``mean_mpa``, ``sd_mpa``, ``skewness``, ``kurtosis``, :func:`lambda_moments`) and of
        their mirror image about the printed mean (``mirrored_*``, :func:`mirror_lambdas`);
        ``mean_rel_diff``, ``sd_rel_diff``, ``kurtosis_rel_diff`` (printed λ's vs printed
        moments, relative), ``skewness_diff`` and ``mirrored_skewness_diff`` (absolute), and
        ``sign_flip`` (the printed λ's give a skewness of the opposite sign to the printed
        one while the mirror's is closer to it).

    Examples
    --------
    >>> from glstat.study.paper import printed_lambda_check
    >>> p = printed_lambda_check([{"hurst": 1.0, "mean_mpa": 1100.0, "sd_mpa": 150.0,
    ...     "skewness": 0.5, "kurtosis": 3.2, "lambda1_mpa": 1050.0, "lambda2_per_mpa": 0.001,
    ...     "lambda3": 0.1, "lambda4": 0.05}])
    >>> p[["mean_mpa", "skewness", "mirrored_skewness", "valid"]].round(3).values.tolist()
    [[1006.71, -0.475, 0.475, True]]
    """
    import pandas as pd

    out = []
    for r in table_rows(table):
        row = {"hurst": r.hurst, "printed_mean_mpa": r.mean_mpa, "printed_sd_mpa": r.sd_mpa,
               "printed_skewness": r.skewness, "printed_kurtosis": r.kurtosis,
               "lambda1_mpa": r.lambda1_mpa, "lambda2_per_mpa": r.lambda2_per_mpa,
               "lambda3": r.lambda3, "lambda4": r.lambda4}
        if r.has_lambdas:
            row.update(_printed_row(r))
        else:
            row.update(valid=None, error="", reading="", region=None,
                       note="Table 1 λ's not stored")
        out.append(row)
    return pd.DataFrame(out)


def _printed_row(r: Table1Row) -> dict:
    """The columns of :func:`printed_lambda_check` computed from the printed λ's of ``r``."""
    g, reading, err = as_distribution(*r.lambdas)
    lam = r.lambdas if g is None else g.lambdas
    m = lambda_moments(*lam)
    mm = lambda_moments(*mirror_lambdas(lam, r.mean_mpa))
    row = dict(valid=err == "", error=err, reading=reading,
               read_lambdas=tuple(float(v) for v in lam),
               region=None if g is None else g.region, note="",
               mean_mpa=m[0], sd_mpa=m[1], skewness=m[2], kurtosis=m[3],
               mirrored_mean_mpa=mm[0], mirrored_sd_mpa=mm[1], mirrored_skewness=mm[2],
               mirrored_kurtosis=mm[3],
               mean_rel_diff=m[0] / r.mean_mpa - 1, sd_rel_diff=m[1] / r.sd_mpa - 1,
               kurtosis_rel_diff=m[3] / r.kurtosis - 1,
               skewness_diff=m[2] - r.skewness, mirrored_skewness_diff=mm[2] - r.skewness)
    row["sign_flip"] = bool(np.sign(m[2]) == -np.sign(r.skewness) and r.skewness != 0
                            and abs(mm[2] - r.skewness) < abs(m[2] - r.skewness))
    return row


def n_contact_for(n_contact, hurst: float) -> float:
    """n, the grid points in contact for the exponent ``hurst``, from ``n_contact`` (one
    number, ``{H: n}`` or None; see :func:`damage_claims`)."""
    if n_contact is None:
        n_contact = SCENE_N_CONTACT
    if isinstance(n_contact, Mapping):
        counts = {float(k): v for k, v in n_contact.items()}
        if float(hurst) in counts:
            n = counts[float(hurst)]
        elif float(hurst) in SCENE_N_CONTACT:  # e.g. a campaign without this H
            n = SCENE_N_CONTACT[float(hurst)]
        else:
            raise ValueError(f"n_contact has no count for H = {hurst:g} (keys {list(n_contact)})")
    else:
        n = n_contact
    n = float(n)
    if not (math.isfinite(n) and n >= 1):
        raise ValueError(f"n_contact must be finite and >= 1, got {n!r} for H = {hurst:g}")
    return n


def _readings(r: Table1Row, roots) -> list[tuple[str, GLD, tuple[float, ...]]]:
    """(source, GLD, λ's) of every reading of one row: the printed λ's (or, when they are not
    a valid GLD, each valid one of their other readings) and their mirror image, and every
    valid moment-fit root."""
    from ..distributions.gld import GLD

    out: list[tuple[str, GLD, tuple[float, ...]]] = []
    if r.has_lambdas:
        g = valid_gld(r.lambdas)
        if g is not None:
            read = [("printed", g)]
        else:
            read = [(_OTHER_SOURCES[name], gl) for name, lam in other_readings(*r.lambdas)
                    if (gl := valid_gld(lam)) is not None]
        for label, gl in read:
            out.append((label, gl, gl.lambdas))
            gm = GLD(*mirror_lambdas(gl.lambdas, r.mean_mpa))
            out.append(("mirror of " + label, gm, gm.lambdas))
    if roots is not None:
        sub = roots[(roots["hurst"] == r.hurst) & roots["upper_mpa"].notna()]
        for s in sub.itertuples(index=False):
            lam = (s.lambda1_mpa, s.lambda2_per_mpa, s.lambda3, s.lambda4)
            tag = " (selected)" if s.selected else ""
            out.append((f"moment fit root {int(s.root)}{tag}", GLD(*lam), lam))
    return out


def damage_claims(table=None, n_contact=None, hardness_mpa: float = HARDNESS_MPA, roots=None):
    """The paper's damage claims, reproduced (or not) from every reading of Table 1.

    Parameters
    ----------
    table : optional
        Table 1 (see :func:`table1`); default :data:`TABLE1`.
    n_contact : float, mapping or None
        n, the grid points in contact per surface: one number for every H, or ``{H: n}``
        (e.g. a campaign's mean ``n_contact`` per H; an H of the table missing from it takes
        its :data:`SCENE_N_CONTACT` value). Default :data:`SCENE_N_CONTACT`, measured at the
        study's default scene (1.3–2.0 × 10⁴).
    hardness_mpa : float
        Hardness Pd, MPa.
    roots : DataFrame, optional
        Output of :func:`moment_fit_roots` (computed when omitted).

    Returns
    -------
    pandas.DataFrame
        One row per (H, source): ``hurst``, ``source`` (``printed``, its other readings for an
        invalid row, ``mirror of printed``, ``moment fit root k``), the λ's of the
        distribution used, ``upper_mpa`` (its upper end point), ``n_contact``, ``damage``
        (``1 − F(Pd)^n``), ``claim`` (the paper's), ``reproduced`` (damage inside
        :data:`CLAIM_RANGES` of the claim), ``n_low``, ``n_high`` (the n ≥ 1 for which the
        claim is reproduced; NaN when no n is).

    Examples
    --------
    A region-3 GLD ends at λ1 + 1/λ2 = 1500 MPa: no point exceeds 2050 MPa, whatever n —
    "impossible" for every n ≥ 1:

    >>> from glstat.study.paper import damage_claims
    >>> d = damage_claims([{"hurst": 1.0, "mean_mpa": 1000.0, "lambda1_mpa": 1000.0,
    ...                     "lambda2_per_mpa": 0.002, "lambda3": 0.1, "lambda4": 0.1}],
    ...                   n_contact=2e4)
    >>> d[["source", "upper_mpa", "damage", "reproduced", "n_high"]].values.tolist()[0]
    ['printed', 1500.0, 0.0, True, inf]
    """
    import pandas as pd

    if roots is None:
        roots = moment_fit_roots(table, hardness_mpa)
    out = []
    for r in table_rows(table):
        claim = PAPER_CLAIMS.get(float(r.hurst))
        n = n_contact_for(n_contact, r.hurst)
        for source, g, lam in _readings(r, roots):
            d = damage_at(g, hardness_mpa, n)
            row = {"hurst": r.hurst, "source": source, "lambda1_mpa": lam[0],
                   "lambda2_per_mpa": lam[1], "lambda3": lam[2], "lambda4": lam[3],
                   "upper_mpa": gld_support(g)[1], "n_contact": n, "damage": d, "claim": claim}
            if claim is not None:
                a, b = CLAIM_RANGES[claim]
                row["reproduced"] = bool(a <= d <= b)
                row["n_low"], row["n_high"] = claim_n_range(g, hardness_mpa, claim)
            out.append(row)
    cols = ["hurst", "source", "lambda1_mpa", "lambda2_per_mpa", "lambda3", "lambda4",
            "upper_mpa", "n_contact", "damage", "claim", "reproduced", "n_low", "n_high"]
    return pd.DataFrame(out, columns=cols)


def reading_family(source: str) -> str:
    """The family (a key of :data:`FAMILIES`) of a ``source`` of :func:`damage_claims`."""
    if source.startswith("moment fit"):
        return "moment fits"
    if source.startswith("mirror"):
        return "mirror of printed"
    return "printed"


def common_n(damage) -> list[dict]:
    """Per family of readings, the n reproducing every H's claim at once (the best choice of
    reading per H within the family).

    Parameters
    ----------
    damage : pandas.DataFrame
        :func:`damage_claims`.

    Returns
    -------
    list of dict
        ``family``, ``hursts``, ``exists``, ``n_low``, ``n_high`` (NaN when no n does), for
        each family with a reading of every H that has a claim.
    """
    out: list[dict] = []
    have = damage[damage["claim"].notna()] if len(damage) else damage
    if not len(have):
        return out
    hs = sorted(have["hurst"].unique())
    for fam in FAMILIES:
        sub = have[have["source"].map(reading_family) == fam]
        if set(sub["hurst"].unique()) != set(hs):
            continue
        per_h = [[(s.n_low, s.n_high) for s in sub[sub["hurst"] == h].itertuples()] for h in hs]
        best = _widest_common_range(per_h)
        out.append({"family": fam, "hursts": tuple(hs), "exists": best is not None,
                    "n_low": best[0] if best else _NAN, "n_high": best[1] if best else _NAN})
    return out


def _widest_common_range(per_h: list[list[tuple[float, float]]]) -> tuple[float, float] | None:
    """Over one (n_low, n_high) per H chosen from ``per_h``, the widest (by ratio) common
    range of n; None when no choice has one."""
    best = None
    for combo in itertools.product(*per_h):
        if any(not math.isfinite(a) for a, _ in combo):
            continue
        lo = max(a for a, _ in combo)
        hi = min(b for _, b in combo)
        if hi >= lo and (best is None or hi / lo > best[1] / best[0]):
            best = (lo, hi)
    return best
