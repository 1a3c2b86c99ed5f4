"""Table 1 of Bigerelle et al. (2019) and its consistency, computed.

Bigerelle, Plouraboué, Robache, Jourani, Fabre, "Mechanical Integrity of 3D Rough Surfaces
during Contact", Coatings 10(1):15, 2019 (doi:10.3390/coatings10010015), Table 1 gives, for each
Hurst exponent H, the moments of the contact-pressure sample (mean α1, standard deviation,
skewness α3, kurtosis α4) and the Ramberg–Schmeiser (RS) λ's fitted to them by the method of
moments; the paper's damage claims at the hardness 2050 MPa (impossible / about 1 % / certain
for H = 1 / 0.5 / 0) rest on them. The table is data (:data:`TABLE1`,
:mod:`glstat.study.paper_table`), checked with glstat's own GLD machinery (docs/method.md §11;
:mod:`glstat.study.paper_gld`, :mod:`glstat.study.paper_checks`):

- :func:`moment_fit_roots` — every RS root of the printed moments, its support end points and
  whether the hardness lies beyond the upper end point (then damage is 0 for any n);
- :func:`printed_lambda_check` — the moments of the printed λ's next to the printed moments,
  the mirror image ``λ1 → 2 α1 − λ1, λ3 ↔ λ4`` (:func:`mirror_lambdas`) and the validity of each
  row (the :class:`glstat.InvalidParameterError` text);
- :func:`damage_claims` — the damage probability ``1 − F(Pd)^n`` at the hardness from each
  reading of the table, with n = grid points in contact, and the range of n that reproduces
  each claim;
- :func:`paper_consistency` — all of it; :func:`paper_findings` — plain-English findings
  (both in this module).

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

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ..formatting import fmt_probability
from .paper_checks import FAMILIES, common_n, n_contact_for, reading_family
from .paper_checks import damage_claims as damage_claims
from .paper_checks import moment_fit_roots as moment_fit_roots
from .paper_checks import printed_lambda_check as printed_lambda_check
from .paper_gld import as_distribution as as_distribution
from .paper_gld import lambda_moments as lambda_moments
from .paper_gld import mirror_lambdas as mirror_lambdas
from .paper_table import CLAIM_RANGES as CLAIM_RANGES
from .paper_table import HARDNESS_MPA as HARDNESS_MPA
from .paper_table import PAPER_CLAIMS as PAPER_CLAIMS
from .paper_table import SCENE_N_CONTACT as SCENE_N_CONTACT
from .paper_table import TABLE1 as TABLE1
from .paper_table import TABLE1_SOURCE as TABLE1_SOURCE
from .paper_table import Table1Row as Table1Row
from .paper_table import table1 as table1
from .paper_table import table_rows

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["PaperConsistency", "paper_consistency", "paper_findings"]


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

    from _glstat_runtime.validation import positive_finite

    hardness_mpa = positive_finite(hardness_mpa, "hardness_mpa", "hardness in MPa")
    rows = table_rows(table)
    roots = moment_fit_roots(table, hardness_mpa)
    printed = printed_lambda_check(table)
    damage = damage_claims(table, n_contact, hardness_mpa, roots=roots)
    common = pd.DataFrame(common_n(damage),
                          columns=["family", "hursts", "exists", "n_low", "n_high"])
    return PaperConsistency(table=table1(table), roots=roots, printed=printed, damage=damage,
                            common_n=common, hardness_mpa=hardness_mpa,
                            n_contact={r.hurst: n_contact_for(n_contact, r.hurst) for r in rows},
                            stored_only=table is None)


# -- the findings --------------------------------------------------------------------------------
def _means_finding(c: PaperConsistency) -> str:
    """What the printed means imply with the paper's c = 0.2, E = 210 GPa, nu = 0.3."""
    from contact import effective_modulus

    t = c.table
    ce = 0.2 * effective_modulus(210e9, 0.3) / 1e6
    hs = " / ".join(f"{h:g}" for h in t["hurst"])
    return (
        "Table 1's mean contact pressures (" + " / ".join(f"{m:.0f}" for m in t["mean_mpa"])
        + f" MPa for H = {hs}) imply attack angles tan β ≈ p_m / (c E*) = "
        + " / ".join(f"{m / ce:.3f}" for m in t["mean_mpa"])
        + f" with the paper's c = 0.2 and E* = {ce / 0.2 / 1e3:.1f} GPa: rms slopes of a few "
        f"percent; the hardness {c.hardness_mpa:g} MPa is "
        + " / ".join(f"{c.hardness_mpa / m:.2f}" for m in t["mean_mpa"]) + " times these means."
    )


def _missing_findings(t: pd.DataFrame) -> list[str]:
    """Which checks the copy of Table 1 ``t`` does not allow (none when it is complete)."""
    def lacking(cols: list[str]) -> list[str]:
        present = t[cols].notna().all(axis=1)
        return [f"{h:g}" for h, ok in zip(t["hurst"], present, strict=True) if not ok]

    missing_m = lacking(["sd_mpa", "skewness", "kurtosis"])
    missing_l = lacking(["lambda1_mpa", "lambda2_per_mpa", "lambda3", "lambda4"])
    if not (missing_m or missing_l):
        return []
    return [
        "Not checked: the copy of Table 1 used here lacks "
        + ("the standard deviation, skewness and kurtosis" if missing_m else "")
        + (" and " if missing_m and missing_l else "")
        + ("the printed λ's" if missing_l else "")
        + f" for H = {', '.join(sorted(set(missing_m + missing_l)))}; the moment-fit roots, "
        "the sign of the skewness, the validity of the printed rows and the damage claims "
        "need them (glstat study --paper-table FILE.csv, or "
        "glstat.study.paper.paper_consistency(table=...), with the printed values)."
    ]


def _printed_findings(p: pd.DataFrame) -> list[str]:
    """The printed λ's against the printed moments, and the rows that are not a valid GLD."""
    if not (len(p) and "sign_flip" in p):
        return []
    out = []
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
    return out


def _root_findings(roots: pd.DataFrame, hardness_mpa: float) -> list[str]:
    """Per H, the upper end points of the moment-fit roots against the hardness."""
    out: list[str] = []
    if not (len(roots) and roots["upper_mpa"].notna().any()):
        return out
    for h in roots["hurst"].unique():
        sub = roots[(roots["hurst"] == h) & roots["upper_mpa"].notna()]
        if not len(sub):
            continue
        ends = ", ".join(f"{u:.0f}" for u in sub["upper_mpa"])
        beyond = sub["hardness_beyond_upper"].astype(bool)
        txt = (f"H = {h:g}: Table 1's moments have {len(sub)} RS root(s) with upper end "
               f"point(s) {ends} MPa")
        if beyond.all():
            txt += (f", all below the hardness {hardness_mpa:g} MPa: a GLD matching these "
                    "moments gives damage 0 for any number of points — a statement about "
                    "the fitted family's finite end point, not about the surfaces")
        elif beyond.any():
            txt += (f"; {int(beyond.sum())} of them end below the hardness "
                    f"{hardness_mpa:g} MPa (damage 0 for any n)")
        out.append(txt + ".")
    return out


def _damage_findings(c: PaperConsistency) -> list[str]:
    """The damage from each family of readings, and whether one n reproduces the claims."""
    d = c.damage
    out: list[str] = []
    if not len(d):
        return out
    for fam in FAMILIES:
        sub = d[d["source"].map(reading_family) == fam]
        if not len(sub):
            continue
        parts = []
        for h in sorted(sub["hurst"].unique(), reverse=True):
            s = sub[sub["hurst"] == h]
            vals = ", ".join(fmt_probability(v) for v in s["damage"])
            parts.append(f"H = {h:g}: {vals} (claim: {s['claim'].iloc[0]})")
        nn = ", ".join(f"{c.n_contact[h]:.3g}" for h in sorted(c.n_contact, reverse=True))
        out.append(f"Damage at {c.hardness_mpa:g} MPa from {FAMILIES[fam]} with n = {nn} points in "
                   "contact: " + "; ".join(parts) + ".")
    for r in c.common_n.itertuples():
        if r.exists:
            out.append(f"One n reproduces the three claims with {FAMILIES[r.family]}: "
                       f"n from {r.n_low:.3g} to {r.n_high:.3g}.")
        else:
            out.append(f"No single n reproduces the three claims with {FAMILIES[r.family]}.")
    return out


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
    c = consistency if consistency is not None else paper_consistency(**kwargs)
    return [_means_finding(c), *_missing_findings(c.table), *_printed_findings(c.printed),
            *_root_findings(c.roots, c.hardness_mpa), *_damage_findings(c)]
