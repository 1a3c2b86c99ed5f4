"""Table 1 of Bigerelle et al. (2019) and its consistency, computed.

Bigerelle, Plouraboué, Robache, Jourani, Fabre, "Mechanical Integrity of 3D Rough Surfaces
during Contact", Coatings 10(1):15, 2019 (doi:10.3390/coatings10010015), Table 1 gives, for each
Hurst exponent H, the moments of the contact-pressure sample (mean α1, standard deviation,
skewness α3, kurtosis α4) and the Ramberg–Schmeiser (RS) λ's fitted to them by the method of
moments; the paper's damage claims at the hardness 2050 MPa (impossible / about 1 % / certain
for H = 1 / 0.5 / 0) rest on them. This module holds the table as data (:data:`TABLE1`) and
checks it with glstat's own GLD machinery (docs/method.md §11):

- :func:`moment_fit_roots` — every RS root of the printed moments, its support end points and
  whether the hardness lies beyond the upper end point (then damage is 0 for any n);
- :func:`printed_lambda_check` — the moments of the printed λ's next to the printed moments,
  the mirror image ``λ1 → 2 α1 − λ1, λ3 ↔ λ4`` (:func:`mirror_lambdas`) and the validity of each
  row (the :class:`glstat.InvalidParameterError` text);
- :func:`damage_claims` — the damage probability ``1 − F(Pd)^n`` at the hardness from each
  reading of the table, with n = grid points in contact, and the range of n that reproduces
  each claim;
- :func:`paper_consistency` — all of it; :func:`paper_findings` — plain-English findings.

Pressures in these tables are in MPa, as printed in the paper (columns say so: ``mean_mpa``,
``lambda1_mpa``, ``lambda2_per_mpa``); skewness and kurtosis (Pearson's, 3 for the normal) are
dimensionless.

**What is stored.** :data:`TABLE1` holds the mean contact pressures of Table 1 (1724 / 1369 /
1108 MPa for H = 0 / 0.5 / 1). Its standard deviations, skewnesses, kurtoses and λ's are not
stored in this package yet (NaN); every function takes ``table=`` with the printed values
(:func:`table1` lists the columns), and computes the checks that need them only from such a
table. The findings say which checks the stored copy allows.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

    from ..gld import GLD

__all__ = [
    "CLAIM_RANGES",
    "PAPER_CLAIMS",
    "SCENE_N_CONTACT",
    "TABLE1",
    "TABLE1_SOURCE",
    "PaperConsistency",
    "Table1Row",
    "as_distribution",
    "damage_claims",
    "lambda_moments",
    "mirror_lambdas",
    "moment_fit_roots",
    "paper_consistency",
    "paper_findings",
    "printed_lambda_check",
    "table1",
]

#: Where :data:`TABLE1` comes from.
TABLE1_SOURCE = ("Bigerelle M., Plouraboué F., Robache F., Jourani A., Fabre A., Mechanical "
                 "Integrity of 3D Rough Surfaces during Contact, Coatings 10(1):15, 2019, Table 1")

#: Hardness of the paper's damage claims, MPa.
HARDNESS_MPA = 2050.0

_NAN = float("nan")


@dataclass(frozen=True)
class Table1Row:
    """One row of Table 1 (pressures in MPa; NaN where the value is not stored).

    Attributes
    ----------
    hurst : float
        Hurst exponent H.
    mean_mpa, sd_mpa : float
        Mean α1 and standard deviation of the contact-pressure sample, MPa.
    skewness, kurtosis : float
        α3 and α4 (Pearson's kurtosis, 3 for the normal), dimensionless.
    lambda1_mpa, lambda2_per_mpa, lambda3, lambda4 : float
        The printed RS λ's: λ1 in MPa, λ2 in 1/MPa, λ3 and λ4 dimensionless.
    """

    hurst: float
    mean_mpa: float
    sd_mpa: float = _NAN
    skewness: float = _NAN
    kurtosis: float = _NAN
    lambda1_mpa: float = _NAN
    lambda2_per_mpa: float = _NAN
    lambda3: float = _NAN
    lambda4: float = _NAN

    @property
    def moments(self) -> tuple[float, float, float, float]:
        """(mean MPa, sd MPa, skewness, kurtosis)."""
        return (self.mean_mpa, self.sd_mpa, self.skewness, self.kurtosis)

    @property
    def lambdas(self) -> tuple[float, float, float, float]:
        """The printed (λ1 MPa, λ2 1/MPa, λ3, λ4)."""
        return (self.lambda1_mpa, self.lambda2_per_mpa, self.lambda3, self.lambda4)

    @property
    def has_moments(self) -> bool:
        return all(math.isfinite(v) for v in self.moments)

    @property
    def has_lambdas(self) -> bool:
        return all(math.isfinite(v) for v in self.lambdas)


#: Table 1 of the paper (:data:`TABLE1_SOURCE`), as stored in this package: the mean contact
#: pressures per H (MPa); the other columns are not stored (NaN) — see the module docstring.
TABLE1: tuple[Table1Row, ...] = (
    Table1Row(hurst=0.0, mean_mpa=1724.0),
    Table1Row(hurst=0.5, mean_mpa=1369.0),
    Table1Row(hurst=1.0, mean_mpa=1108.0),
)

#: The paper's damage claims at 2050 MPa, per H.
PAPER_CLAIMS: dict[float, str] = {0.0: "certain", 0.5: "about 1 %", 1.0: "impossible"}

#: Damage probabilities that count as reproducing each claim: [low, high].
CLAIM_RANGES: dict[str, tuple[float, float]] = {
    "impossible": (0.0, 1e-6),
    "about 1 %": (0.005, 0.02),
    "certain": (0.99, 1.0),
}

#: Stored reference measurement, not recomputed: mean number of grid points in contact per
#: surface, per H, at the study's default scene (``CampaignSettings()``: 1024², 1 mm²,
#: Rq = 1.6 µm, 6 Weierstrass terms per axis, γ = 1.5, 20 MPa, E = 210 GPa, ν = 0.3, c = 0.2,
#: seed 2019), surfaces 0–19 of each H at the first load (glstat.study.simulate_surface).
#: Their mean contact pressures were 1702 / 1546 / 1140 MPa (standard errors 90 / 72 / 83)
#: with 9.1 / 6.1 / 5.0 asperities in contact. The default n of :func:`damage_claims`.
SCENE_N_CONTACT: dict[float, float] = {0.0: 12928.3, 0.5: 14142.65, 1.0: 20099.0}

_COLUMNS = ("hurst", "mean_mpa", "sd_mpa", "skewness", "kurtosis", "lambda1_mpa",
            "lambda2_per_mpa", "lambda3", "lambda4")


# -- the table -----------------------------------------------------------------------------------
def _rows(table) -> list[Table1Row]:
    """Table 1 rows from None (the stored copy), Table1Row objects, mappings or a DataFrame."""
    if table is None:
        return list(TABLE1)
    if hasattr(table, "to_dict") and hasattr(table, "columns"):
        table = table.to_dict("records")
    rows = []
    for r in table:
        if isinstance(r, Table1Row):
            rows.append(r)
            continue
        if not isinstance(r, Mapping):
            raise TypeError(f"a Table 1 row must be a Table1Row or a mapping, got {type(r).__name__}")
        unknown = set(r) - set(_COLUMNS)
        if unknown:
            raise ValueError(f"unknown Table 1 column(s) {sorted(unknown)}; expected {_COLUMNS}")
        if "hurst" not in r or "mean_mpa" not in r:
            raise ValueError("every Table 1 row needs 'hurst' and 'mean_mpa'")
        rows.append(Table1Row(**{k: float(v) for k, v in r.items()}))
    if not rows:
        raise ValueError("Table 1 has no rows")
    return rows


def table1(table=None):
    """Table 1 as a pandas DataFrame (MPa).

    Parameters
    ----------
    table : DataFrame, sequence of Table1Row or of mappings, optional
        The table to use (columns ``hurst, mean_mpa, sd_mpa, skewness, kurtosis, lambda1_mpa,
        lambda2_per_mpa, lambda3, lambda4``; missing ones are NaN). Default :data:`TABLE1`.

    Returns
    -------
    pandas.DataFrame
        One row per H with those columns and ``source``.

    Examples
    --------
    >>> from glstat.study.paper import table1
    >>> table1()[["hurst", "mean_mpa"]].values.tolist()
    [[0.0, 1724.0], [0.5, 1369.0], [1.0, 1108.0]]
    """
    import pandas as pd

    rows = _rows(table)
    df = pd.DataFrame([{c: getattr(r, c) for c in _COLUMNS} for r in rows])
    df["source"] = TABLE1_SOURCE if table is None else "given table"
    return df


# -- GLD helpers -----------------------------------------------------------------------------------
def lambda_moments(l1: float, l2: float, l3: float, l4: float) -> tuple[float, float, float, float]:
    """Mean, standard deviation, skewness and kurtosis of ``Q(U)``, U uniform on (0, 1).

    ``Q(u) = λ1 + (u^λ3 − (1 − u)^λ4) / λ2`` (RS). ``Q(U)`` is a random variable for any λ's,
    whether or not ``Q`` is increasing (a valid quantile function), so this also gives the
    moments of a printed row that is not a valid GLD. Computed from the raw moments of
    ``Z = U^λ3 − (1 − U)^λ4``, ``E Z^k = Σ_j C(k, j) (−1)^j B(λ3 (k − j) + 1, λ4 j + 1)``, in
    50-digit arithmetic (mpmath), so the differences of beta functions do not cancel.

    Parameters
    ----------
    l1, l2, l3, l4 : float
        λ1 (units of x), λ2 (1 / units of x), λ3, λ4; the 4th moment needs
        ``min(λ3, λ4) > −1/4``.

    Returns
    -------
    (mean, sd, skewness, kurtosis)
        In the units of λ1 (mean, sd); skewness and Pearson's kurtosis dimensionless. NaN
        where a moment does not exist.

    Examples
    --------
    >>> from glstat.study.paper import lambda_moments
    >>> [round(v, 3) for v in lambda_moments(0, 0.197451, 0.134912, 0.134912)]  # ~ N(0, 1)
    [0.0, 1.0, 0.0, 3.0]
    """
    import mpmath as mp

    if not (l2 != 0 and all(math.isfinite(v) for v in (l1, l2, l3, l4))):
        return (_NAN,) * 4
    if min(l3, l4) <= -0.25:
        return (_NAN,) * 4
    with mp.workdps(50):
        a, b = mp.mpf(l3), mp.mpf(l4)
        ez = []
        for k in range(1, 5):
            ez.append(mp.fsum(mp.binomial(k, j) * (-1) ** j * mp.beta(a * (k - j) + 1, b * j + 1)
                              for j in range(k + 1)))
        m1, m2, m3, m4 = ez
        v = m2 - m1 ** 2
        mu3 = m3 - 3 * m1 * m2 + 2 * m1 ** 3
        mu4 = m4 - 4 * m1 * m3 + 6 * m1 ** 2 * m2 - 3 * m1 ** 4
        mean = mp.mpf(l1) + m1 / mp.mpf(l2)
        sd = mp.sqrt(v) / abs(mp.mpf(l2))
        skew = mu3 / v ** mp.mpf(1.5) * (1 if l2 > 0 else -1)
        kurt = mu4 / v ** 2
        return (float(mean), float(sd), float(skew), float(kurt))


def mirror_lambdas(lambdas: Sequence[float], mean: float) -> tuple[float, float, float, float]:
    """λ's of the mirror image ``2 α1 − X`` of the RS GLD X about its mean α1.

    ``2 α1 − Q(1 − u) = (2 α1 − λ1) + (u^λ4 − (1 − u)^λ3) / λ2``: the mirror has
    ``(2 α1 − λ1, λ2, λ4, λ3)`` — the same mean, standard deviation and kurtosis and the
    opposite skewness.

    Parameters
    ----------
    lambdas : (λ1, λ2, λ3, λ4)
        RS λ's (λ1 in the units of x, λ2 in 1 / units).
    mean : float
        α1, the mean of X (units of x).

    Returns
    -------
    tuple of float

    Examples
    --------
    >>> from glstat.study.paper import mirror_lambdas
    >>> mirror_lambdas((1000.0, 0.002, 0.1, 0.3), 1070.0)
    (1140.0, 0.002, 0.3, 0.1)
    """
    l1, l2, l3, l4 = (float(v) for v in lambdas)
    return (2.0 * float(mean) - l1, l2, l4, l3)


def as_distribution(l1: float, l2: float, l3: float, l4: float):
    """The distribution printed RS λ's stand for, and how they were read.

    Readings, in this order, the first valid one wins: the λ's as printed; with the sign of
    λ2 changed (tables often print |λ2| where the region needs λ2 < 0, as the
    :class:`glstat.InvalidParameterError` message says); the random variable ``Q(U)`` for a
    decreasing ``Q`` (e.g. λ2 > 0 with λ3, λ4 < 0), whose quantile function is ``Q(1 − u)``, the
    RS GLD ``(λ1, −λ2, λ4, λ3)``.

    Parameters
    ----------
    l1, l2, l3, l4 : float
        RS λ's as printed.

    Returns
    -------
    (GLD or None, str, str)
        The distribution, the reading (``"as printed"``, ``"λ2 sign changed"``,
        ``"Q(U), decreasing Q"``, or ``""`` when none is valid) and the
        :class:`glstat.InvalidParameterError` text of the λ's as printed (``""`` when valid).

    Examples
    --------
    >>> from glstat.study.paper import as_distribution
    >>> g, reading, err = as_distribution(1700.0, 0.002, -0.1, -0.05)
    >>> reading, g.lambdas
    ('λ2 sign changed', (1700.0, -0.002, -0.1, -0.05))
    """
    from ..errors import InvalidParameterError
    from ..gld import GLD

    try:
        return GLD(l1, l2, l3, l4), "as printed", ""
    except InvalidParameterError as exc:
        err = str(exc)
    for lam, reading in (((l1, -l2, l3, l4), "λ2 sign changed"),
                         ((l1, -l2, l4, l3), "Q(U), decreasing Q")):
        try:
            return GLD(*lam), reading, err
        except InvalidParameterError:
            pass
    return None, "", err


def _support(g) -> tuple[float, float]:
    lo, hi = g.support()
    return float(lo), float(hi)


def _damage(g, hardness: float, n: float) -> float:
    from ..damage import damage_probability

    return float(damage_probability(g, hardness, n, outside_support="limit"))


def _claim_n_range(g, hardness: float, claim: str) -> tuple[float, float]:
    """[n_low, n_high] (n >= 1) over which 1 − F(Pd)^n lies in CLAIM_RANGES[claim]; (nan, nan)
    when no n >= 1 does."""
    lo_p, hi_p = CLAIM_RANGES[claim]
    lo_s, hi_s = _support(g)
    if hardness >= hi_s:
        log_f = 0.0
    elif hardness <= lo_s:
        log_f = -math.inf
    else:
        log_f = float(g.logcdf(hardness))
    if log_f == 0.0:  # never damaged
        return (1.0, math.inf) if lo_p == 0.0 else (_NAN, _NAN)
    if log_f == -math.inf:  # always damaged
        return (1.0, math.inf) if hi_p >= 1.0 else (_NAN, _NAN)
    # D(n) = 1 - exp(n log F) increases with n: lo_p <= D <= hi_p  <=>  n in [n_lo, n_hi]
    n_lo = math.log1p(-lo_p) / log_f if lo_p > 0 else 0.0
    n_hi = math.log1p(-hi_p) / log_f if hi_p < 1 else math.inf
    n_lo = max(n_lo, 1.0)
    return (n_lo, n_hi) if n_hi >= n_lo else (_NAN, _NAN)


# -- the checks ----------------------------------------------------------------------------------
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
    from ..gld import GLD

    out = []
    for r in _rows(table):
        base = {"hurst": r.hurst}
        if not r.has_moments:
            out.append({**base, "note": "Table 1 moments not stored (sd, skewness, kurtosis)"})
            continue
        try:
            f = fit_moments(*r.moments, param="rs")
        except FitError as exc:
            out.append({**base, "note": f"FitError: {exc}"})
            continue
        sol = f.solutions
        for k, s in enumerate(sol.itertuples(index=False)):
            lam = (float(s.lambda1), float(s.lambda2), float(s.lambda3), float(s.lambda4))
            row = {**base, "root": k, "selected": bool(s.selected), "lambda1_mpa": lam[0],
                   "lambda2_per_mpa": lam[1], "lambda3": lam[2], "lambda4": lam[3],
                   "region": s.region, "note": ""}
            if bool(s.valid):
                g = GLD(*lam)
                lo, hi = _support(g)
                m = lambda_moments(*lam)
                row.update(lower_mpa=lo, upper_mpa=hi, hardness_beyond_upper=bool(hardness_mpa >= hi),
                           mean_mpa=m[0], sd_mpa=m[1], skewness=m[2], kurtosis=m[3])
            else:
                row["note"] = "root not a valid RS GLD"
            out.append(row)
    cols = ["hurst", "root", "selected", "lambda1_mpa", "lambda2_per_mpa", "lambda3", "lambda4",
            "region", "lower_mpa", "upper_mpa", "hardness_beyond_upper", "mean_mpa", "sd_mpa",
            "skewness", "kurtosis", "note"]
    return pd.DataFrame(out, columns=cols)


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
    for r in _rows(table):
        row = {"hurst": r.hurst, "printed_mean_mpa": r.mean_mpa, "printed_sd_mpa": r.sd_mpa,
               "printed_skewness": r.skewness, "printed_kurtosis": r.kurtosis,
               "lambda1_mpa": r.lambda1_mpa, "lambda2_per_mpa": r.lambda2_per_mpa,
               "lambda3": r.lambda3, "lambda4": r.lambda4}
        if not r.has_lambdas:
            row.update(valid=None, error="", reading="", region=None,
                       note="Table 1 λ's not stored")
            out.append(row)
            continue
        g, reading, err = as_distribution(*r.lambdas)
        lam = r.lambdas if g is None else g.lambdas
        m = lambda_moments(*lam)
        mm = lambda_moments(*mirror_lambdas(lam, r.mean_mpa))
        row.update(valid=err == "", error=err, reading=reading,
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
        out.append(row)
    return pd.DataFrame(out)


def _n_for(n_contact, hurst: float) -> float:
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
    """(source, GLD, λ's) of every reading of one row: the printed λ's, their mirror image,
    and every valid moment-fit root."""
    from ..gld import GLD

    out: list[tuple[str, GLD, tuple[float, ...]]] = []
    if r.has_lambdas:
        from ..errors import InvalidParameterError

        cands = [("printed", (r.lambda1_mpa, r.lambda2_per_mpa, r.lambda3, r.lambda4)),
                 ("printed, λ2 sign changed",
                  (r.lambda1_mpa, -r.lambda2_per_mpa, r.lambda3, r.lambda4)),
                 ("printed, read as Q(U) with Q decreasing",
                  (r.lambda1_mpa, -r.lambda2_per_mpa, r.lambda4, r.lambda3))]
        valid_printed = False
        for label, lam in cands:
            if label != "printed" and valid_printed:
                break
            try:
                g = GLD(*lam)
            except InvalidParameterError:
                continue
            valid_printed |= label == "printed"
            out.append((label, g, g.lambdas))
            gm = GLD(*mirror_lambdas(g.lambdas, r.mean_mpa))
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
    for r in _rows(table):
        claim = PAPER_CLAIMS.get(float(r.hurst))
        n = _n_for(n_contact, r.hurst)
        for source, g, lam in _readings(r, roots):
            d = _damage(g, hardness_mpa, n)
            hi = _support(g)[1]
            row = {"hurst": r.hurst, "source": source, "lambda1_mpa": lam[0],
                   "lambda2_per_mpa": lam[1], "lambda3": lam[2], "lambda4": lam[3],
                   "upper_mpa": hi, "n_contact": n, "damage": d, "claim": claim}
            if claim is not None:
                a, b = CLAIM_RANGES[claim]
                row["reproduced"] = bool(a <= d <= b)
                row["n_low"], row["n_high"] = _claim_n_range(g, hardness_mpa, claim)
            out.append(row)
    cols = ["hurst", "source", "lambda1_mpa", "lambda2_per_mpa", "lambda3", "lambda4",
            "upper_mpa", "n_contact", "damage", "claim", "reproduced", "n_low", "n_high"]
    return pd.DataFrame(out, columns=cols)


_FAMILIES = {"printed": "the printed λ's",
             "mirror of printed": "the mirror image of the printed λ's",
             "moment fits": "the GLDs matching the printed moments (every RS root)"}


def _family(source: str) -> str:
    if source.startswith("moment fit"):
        return "moment fits"
    if source.startswith("mirror"):
        return "mirror of printed"
    return "printed"


def _common_n(damage) -> list[dict]:
    """Per family of readings, the n reproducing every H's claim at once (the best choice of
    reading per H within the family)."""
    out: list[dict] = []
    have = damage[damage["claim"].notna()] if len(damage) else damage
    if not len(have):
        return out
    hs = sorted(have["hurst"].unique())
    for fam in ("printed", "mirror of printed", "moment fits"):
        sub = have[have["source"].map(_family) == fam]
        if set(sub["hurst"].unique()) != set(hs):
            continue
        per_h = [[(s.n_low, s.n_high) for s in sub[sub["hurst"] == h].itertuples()] for h in hs]
        best = None
        for combo in itertools.product(*per_h):
            if any(not math.isfinite(a) for a, _ in combo):
                continue
            lo = max(a for a, _ in combo)
            hi = min(b for _, b in combo)
            if hi >= lo and (best is None or hi / lo > best[1] / best[0]):
                best = (lo, hi)
        out.append({"family": fam, "hursts": tuple(hs), "exists": best is not None,
                    "n_low": best[0] if best else _NAN, "n_high": best[1] if best else _NAN})
    return out


@dataclass
class PaperConsistency:
    """Everything :func:`paper_consistency` computed (tables in MPa).

    Attributes
    ----------
    table : pandas.DataFrame
        Table 1 as used (:func:`table1`).
    roots : pandas.DataFrame
        :func:`moment_fit_roots`.
    printed : pandas.DataFrame
        :func:`printed_lambda_check`.
    damage : pandas.DataFrame
        :func:`damage_claims`.
    common_n : pandas.DataFrame
        Per family of readings (``printed``, ``mirror of printed``, ``moment fits``): whether
        one n reproduces the three claims at once, and its range ``n_low``–``n_high``.
    hardness_mpa : float
    n_contact : dict
        ``{H: n}`` used.
    stored_only : bool
        True when the stored :data:`TABLE1` (means only) was used.
    """

    table: pd.DataFrame
    roots: pd.DataFrame
    printed: pd.DataFrame
    damage: pd.DataFrame
    common_n: pd.DataFrame
    hardness_mpa: float
    n_contact: dict = field(default_factory=dict)
    stored_only: bool = True

    def findings(self) -> list[str]:
        """Plain-English findings (:func:`paper_findings`)."""
        return paper_findings(self)


def paper_consistency(n_contact=None, *, table=None,
                      hardness_mpa: float = HARDNESS_MPA) -> PaperConsistency:
    """Check Table 1 of the paper: moment-fit roots, printed λ's, mirror, validity, damage.

    Parameters
    ----------
    n_contact : float, mapping or None
        Grid points in contact per surface (one number, or ``{H: n}``, e.g. a campaign's mean
        count per H); default :data:`SCENE_N_CONTACT`.
    table : optional
        Table 1 with the printed values (see :func:`table1`); default :data:`TABLE1`, which
        holds the means only, so the checks needing the other columns come out empty.
    hardness_mpa : float
        Hardness Pd, MPa (the paper's 2050).

    Returns
    -------
    PaperConsistency

    Examples
    --------
    >>> from glstat.study.paper import paper_consistency
    >>> c = paper_consistency()
    >>> c.table["mean_mpa"].tolist()
    [1724.0, 1369.0, 1108.0]
    >>> len(c.findings()) >= 2
    True
    """
    import pandas as pd

    if not (isinstance(hardness_mpa, int | float) and math.isfinite(hardness_mpa)
            and hardness_mpa > 0):
        raise ValueError(f"hardness_mpa must be positive and finite (MPa), got {hardness_mpa!r}")
    rows = _rows(table)
    roots = moment_fit_roots(table, hardness_mpa)
    printed = printed_lambda_check(table)
    damage = damage_claims(table, n_contact, hardness_mpa, roots=roots)
    common = pd.DataFrame(_common_n(damage),
                          columns=["family", "hursts", "exists", "n_low", "n_high"])
    return PaperConsistency(table=table1(table), roots=roots, printed=printed, damage=damage,
                            common_n=common, hardness_mpa=float(hardness_mpa),
                            n_contact={r.hurst: _n_for(n_contact, r.hurst) for r in rows},
                            stored_only=table is None)


def _fmt_p(d: float) -> str:
    if d == 0:
        return "0"
    if d >= 0.995:
        return f"{d:.3f}"
    if d >= 1e-3:
        return f"{100 * d:.3g} %"
    return f"{d:.2g}"


def paper_findings(consistency: PaperConsistency | None = None, **kwargs) -> list[str]:
    """Plain-English findings on Table 1, computed from :func:`paper_consistency`.

    Parameters
    ----------
    consistency : PaperConsistency, optional
        A result of :func:`paper_consistency` (computed with ``**kwargs`` when omitted).
    **kwargs
        Passed to :func:`paper_consistency`.

    Returns
    -------
    list of str
        One sentence or short paragraph per finding, for a report section "Consistency with
        the paper".

    Examples
    --------
    >>> from glstat.study.paper import paper_findings
    >>> paper_findings()[0][:60]
    "Table 1's mean contact pressures (1724 / 1369 / 1108 MPa for"
    """
    from contact import effective_modulus

    c = consistency if consistency is not None else paper_consistency(**kwargs)
    t, out = c.table, []
    # what the means imply, with the paper's c = 0.2, E = 210 GPa, nu = 0.3
    ce = 0.2 * effective_modulus(210e9, 0.3) / 1e6
    hs = " / ".join(f"{h:g}" for h in t["hurst"])
    out.append(
        "Table 1's mean contact pressures (" + " / ".join(f"{m:.0f}" for m in t["mean_mpa"])
        + f" MPa for H = {hs}) imply attack angles tan β ≈ p_m / (c E*) = "
        + " / ".join(f"{m / ce:.3f}" for m in t["mean_mpa"])
        + f" with the paper's c = 0.2 and E* = {ce / 0.2 / 1e3:.1f} GPa: rms slopes of a few "
        f"percent; the hardness {c.hardness_mpa:g} MPa is "
        + " / ".join(f"{c.hardness_mpa / m:.2f}" for m in t["mean_mpa"]) + " times these means."
    )
    missing_m = [f"{h:g}" for h, ok in zip(t["hurst"], t[["sd_mpa", "skewness", "kurtosis"]]
                                           .notna().all(axis=1), strict=True) if not ok]
    missing_l = [f"{h:g}" for h, ok in zip(t["hurst"], t[["lambda1_mpa", "lambda2_per_mpa",
                                                          "lambda3", "lambda4"]]
                                           .notna().all(axis=1), strict=True) if not ok]
    if missing_m or missing_l:
        out.append(
            "Not checked: the copy of Table 1 used here lacks "
            + ("the standard deviation, skewness and kurtosis" if missing_m else "")
            + (" and " if missing_m and missing_l else "")
            + ("the printed λ's" if missing_l else "")
            + f" for H = {', '.join(sorted(set(missing_m + missing_l)))}; the moment-fit roots, "
            "the sign of the skewness, the validity of the printed rows and the damage claims "
            "need them (glstat.study.paper.paper_consistency(table=...) with the printed values)."
        )
    p = c.printed
    if len(p) and "sign_flip" in p:
        full = p[p["valid"].notna()]
        for r in full.itertuples():
            close = (abs(r.mean_rel_diff) < 0.01 and abs(r.sd_rel_diff) < 0.02
                     and abs(r.kurtosis_rel_diff) < 0.02)
            out.append(
                f"H = {r.hurst:g}: the printed λ's give mean {r.mean_mpa:.0f} MPa, sd "
                f"{r.sd_mpa:.0f} MPa, skewness {r.skewness:+.3f}, kurtosis {r.kurtosis:.3f} "
                f"against the printed {r.printed_mean_mpa:g} MPa, {r.printed_sd_mpa:g} MPa, "
                f"{r.printed_skewness:+g}, {r.printed_kurtosis:g}"
                + (" — mean, sd and kurtosis agree" if close else "")
                + ("; the skewness has the opposite sign, and the mirror image "
                   "(λ1 → 2α1 − λ1, λ3 ↔ λ4) gives " + f"{r.mirrored_skewness:+.3f}"
                   if r.sign_flip else "")
                + "."
            )
        bad = full[full["valid"] == False]  # noqa: E712 (pandas column of bools / None)
        for r in bad.itertuples():
            out.append(f"H = {r.hurst:g}: the printed λ's are not a valid RS GLD — {r.error}"
                       + (f" Read with {r.reading} they are an RS GLD of region {r.region}; "
                          "the moments above are of that reading." if r.region is not None
                          else ""))
    roots = c.roots
    if len(roots) and roots["upper_mpa"].notna().any():
        for h in roots["hurst"].unique():
            sub = roots[(roots["hurst"] == h) & roots["upper_mpa"].notna()]
            if not len(sub):
                continue
            ends = ", ".join(f"{u:.0f}" for u in sub["upper_mpa"])
            beyond = sub["hardness_beyond_upper"].astype(bool)
            txt = (f"H = {h:g}: Table 1's moments have {len(sub)} RS root(s) with upper end "
                   f"point(s) {ends} MPa")
            if beyond.all():
                txt += (f", all below the hardness {c.hardness_mpa:g} MPa: a GLD matching these "
                        "moments gives damage 0 for any number of points — a statement about "
                        "the fitted family's finite end point, not about the surfaces")
            elif beyond.any():
                txt += (f"; {int(beyond.sum())} of them end below the hardness "
                        f"{c.hardness_mpa:g} MPa (damage 0 for any n)")
            out.append(txt + ".")
    d = c.damage
    if len(d):
        for fam in ("printed", "mirror of printed", "moment fits"):
            sub = d[d["source"].map(_family) == fam]
            if not len(sub):
                continue
            parts = []
            for h in sorted(sub["hurst"].unique(), reverse=True):
                s = sub[sub["hurst"] == h]
                vals = ", ".join(_fmt_p(v) for v in s["damage"])
                parts.append(f"H = {h:g}: {vals} (claim: {s['claim'].iloc[0]})")
            nn = ", ".join(f"{c.n_contact[h]:.3g}" for h in sorted(c.n_contact, reverse=True))
            out.append(f"Damage at {c.hardness_mpa:g} MPa from {_FAMILIES[fam]} with n = {nn} points in "
                       "contact: " + "; ".join(parts) + ".")
        for r in c.common_n.itertuples():
            if r.exists:
                out.append(f"One n reproduces the three claims with {_FAMILIES[r.family]}: "
                           f"n from {r.n_low:.3g} to {r.n_high:.3g}.")
            else:
                out.append(f"No single n reproduces the three claims with {_FAMILIES[r.family]}.")
    return out
