"""Table 1 of Bigerelle et al. (2019) as data: its rows (:data:`TABLE1`, :class:`Table1Row`),
the paper's damage claims at the hardness 2050 MPa (:data:`PAPER_CLAIMS`, with the probability
ranges that count as reproducing them, :data:`CLAIM_RANGES`), the grid points in contact
measured at the study's default scene (:data:`SCENE_N_CONTACT`), and the table as a DataFrame
(:func:`table1`) from the stored copy or from a table with the printed values.

Pressures are in MPa, as printed in the paper (columns say so: ``mean_mpa``, ``lambda1_mpa``,
``lambda2_per_mpa``); skewness and kurtosis (Pearson's, 3 for the normal) are dimensionless.

**What is stored.** :data:`TABLE1` holds the mean contact pressures of Table 1 (1724 / 1369 /
1108 MPa for H = 0 / 0.5 / 1). Its standard deviations, skewnesses, kurtoses and λ's are not
stored in this package yet (NaN); every check of :mod:`glstat.study.paper` takes ``table=``
with the printed values (:func:`table1` lists the columns).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

__all__ = [
    "CLAIM_RANGES",
    "COLUMNS",
    "HARDNESS_MPA",
    "PAPER_CLAIMS",
    "SCENE_N_CONTACT",
    "TABLE1",
    "TABLE1_SOURCE",
    "Table1Row",
    "read_table1",
    "rows_not_run",
    "table1",
    "table_rows",
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
#: with 9.1 / 6.1 / 5.0 asperities in contact. The default n of
#: :func:`glstat.study.paper.damage_claims`.
SCENE_N_CONTACT: dict[float, float] = {0.0: 12928.3, 0.5: 14142.65, 1.0: 20099.0}

#: The columns of Table 1 (:class:`Table1Row`'s fields).
COLUMNS = ("hurst", "mean_mpa", "sd_mpa", "skewness", "kurtosis", "lambda1_mpa",
           "lambda2_per_mpa", "lambda3", "lambda4")


def table_rows(table) -> list[Table1Row]:
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
        unknown = set(r) - set(COLUMNS)
        if unknown:
            raise ValueError(f"unknown Table 1 column(s) {sorted(unknown)}; expected {COLUMNS}")
        if "hurst" not in r or "mean_mpa" not in r:
            raise ValueError("every Table 1 row needs 'hurst' and 'mean_mpa'")
        rows.append(Table1Row(**{k: float(v) for k, v in r.items()}))
    if not rows:
        raise ValueError("Table 1 has no rows")
    for row in rows:
        _check_row(row)
    hs = [r.hurst for r in rows]
    if len(set(hs)) != len(hs):
        raise ValueError(f"Table 1 must hold one row per H, got H = {sorted(hs)}")
    return rows


#: Largest Table 1 a user may give (rows).
MAX_ROWS = 100


def _check_row(row: Table1Row) -> None:
    """The values of one Table 1 row, in the table's units (MPa, 1/MPa): a Hurst exponent in
    [0, 1], a finite mean contact pressure below 1e6 MPa in magnitude (a value given in Pa is
    refused),
    a positive standard deviation, a kurtosis (non-excess) of at least 1, and finite lambdas
    where given (moments no distribution has, kurtosis below 1 + skewness², are reported by the
    moment fits, not refused here)."""
    h = f"H = {row.hurst:g}"
    if not 0.0 <= row.hurst <= 1.0:
        raise ValueError(f"Table 1: hurst must lie in [0, 1], got {row.hurst!r}")
    if not (math.isfinite(row.mean_mpa) and abs(row.mean_mpa) < 1e6):
        raise ValueError(f"Table 1, {h}: mean_mpa = {row.mean_mpa!r} is not a contact pressure in "
                         f"MPa (finite, below 1e6 in magnitude; a value in Pa must be divided by "
                         f"1e6)")
    if not math.isnan(row.sd_mpa) and not (0.0 < row.sd_mpa < 1e6):
        raise ValueError(f"Table 1, {h}: sd_mpa = {row.sd_mpa!r} must be a positive standard "
                         f"deviation in MPa (below 1e6)")
    if not math.isnan(row.kurtosis) and row.kurtosis < 1.0:
        raise ValueError(f"Table 1, {h}: kurtosis {row.kurtosis:g} is below 1, which no "
                         f"distribution has (the kurtosis is the non-excess one: a normal "
                         f"distribution has 3)")
    for name in ("lambda1_mpa", "lambda2_per_mpa", "lambda3", "lambda4"):
        v = getattr(row, name)
        if math.isinf(v):
            raise ValueError(f"Table 1, {h}: {name} must be finite, got {v!r}")
    if not math.isnan(row.lambda1_mpa) and abs(row.lambda1_mpa) >= 1e6:
        raise ValueError(f"Table 1, {h}: lambda1_mpa = {row.lambda1_mpa:g} is not in MPa (a value "
                         f"in Pa must be divided by 1e6)")


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

    rows = table_rows(table)
    df = pd.DataFrame([{c: getattr(r, c) for c in COLUMNS} for r in rows])
    df["source"] = TABLE1_SOURCE if table is None else "given table"
    return df


def read_table1(path) -> list[Table1Row]:
    """Table 1 with its printed values from a CSV file (``glstat study --paper-table``).

    Parameters
    ----------
    path : str or os.PathLike
        A CSV file with a header row naming the columns of :data:`COLUMNS` it holds
        (``hurst`` and ``mean_mpa`` at least; pressures in MPa, λ2 in 1/MPa) and one row per H.

    Returns
    -------
    list of Table1Row

    Raises
    ------
    ValueError
        A file that cannot be read, an unknown or missing column, or a value that is not a
        number (the message names the file and the fix).
    """
    import os

    import pandas as pd

    try:
        size = os.path.getsize(path)
    except OSError as exc:
        raise ValueError(f"--paper-table {path}: cannot read it ({exc})") from None
    if size > 1 << 20:
        raise ValueError(f"--paper-table {path}: {size / 2**20:.1f} MiB is no Table 1 (one row "
                         f"per H, at most {MAX_ROWS} rows); give the paper's table")
    try:
        frame = pd.read_csv(path, nrows=MAX_ROWS + 1)
    except (OSError, ValueError, pd.errors.ParserError) as exc:
        raise ValueError(f"--paper-table {path}: cannot read it as CSV ({exc})") from None
    unknown = [c for c in frame.columns if c not in COLUMNS]
    if unknown:
        raise ValueError(f"--paper-table {path}: unknown column(s) {', '.join(map(str, unknown))}; "
                         f"the columns are {', '.join(COLUMNS)}")
    for need in ("hurst", "mean_mpa"):
        if need not in frame.columns:
            raise ValueError(f"--paper-table {path}: the column {need} is missing")
    if len(frame) > MAX_ROWS:
        raise ValueError(f"--paper-table {path}: more than {MAX_ROWS} rows; Table 1 has one row "
                         f"per H")
    try:
        frame = frame.astype(float)
    except (TypeError, ValueError):
        raise ValueError(f"--paper-table {path}: every value must be a number (MPa for "
                         "pressures, 1/MPa for lambda2_per_mpa)") from None
    if frame[["hurst", "mean_mpa"]].isna().any().any():
        raise ValueError(f"--paper-table {path}: a row without hurst or mean_mpa; every row needs "
                         f"both")
    try:
        return table_rows(frame)
    except ValueError as exc:
        raise ValueError(f"--paper-table {path}: {exc}") from None


def rows_not_run(rows, hursts, option: str = "--paper-table",
                 add: str = "add --hurst {h}") -> str | None:
    """What becomes of the Table 1 ``rows`` whose H the run (exponents ``hursts``) does not
    simulate: a note when the paper's own contact counts check them (None when every row is
    run); a :class:`ValueError` naming ``option`` and the fix ``add`` (``{h}``: the exponents)
    when the paper's scene has no such H either."""
    run = {float(h) for h in hursts}
    extra = sorted(float(r.hurst) for r in rows if float(r.hurst) not in run)
    if not extra:
        return None
    unknown = [h for h in extra if h not in SCENE_N_CONTACT]
    listed = ", ".join(f"{h:g}" for h in (unknown or extra))
    ran = ", ".join(f"{h:g}" for h in sorted(run))
    if unknown:
        raise ValueError(f"{option} has rows for H = {listed}, which this run does not simulate "
                         f"(H = {ran}) and the paper's scene does not have; "
                         f"{add.format(h=listed)} or remove those rows")
    return (f"{option} rows for H = {listed} are not in this run (H = {ran}): they are checked "
            "with the paper's own contact counts, not with this run's")
