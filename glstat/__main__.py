"""``python -m glstat``: quantiles and tail probabilities of a GLD (the quick-start job)."""

from __future__ import annotations

import argparse
import sys

import numpy as np

from .distributions.gld import GLD
from .errors import InvalidParameterError


def main(argv: list[str] | None = None) -> int:
    """Print quantiles and tail probabilities of a GLD given in lambda notation."""
    parser = argparse.ArgumentParser(
        prog="python -m glstat",
        description="Quantiles and tail probabilities of a Generalized Lambda Distribution.",
    )
    parser.add_argument("lambdas", nargs="*", type=float, metavar="LAMBDA",
                        help="lambda1 lambda2 lambda3 lambda4 (default: the RS approximation "
                             "of N(0, 1), 0 0.197451 0.134912 0.134912)")
    parser.add_argument("--param", choices=("rs", "fkml"), default="rs")
    args = parser.parse_args(argv)
    lambdas = args.lambdas or [0.0, 0.197451, 0.134912, 0.134912]
    if len(lambdas) != 4:
        parser.error(f"give four lambdas (lambda1 lambda2 lambda3 lambda4), got {len(lambdas)}")
    try:
        l1, l2, l3, l4 = lambdas
        g = GLD(l1, l2, l3, l4, param=args.param)
    except InvalidParameterError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    lo, hi = g.support()
    print(g)
    if g.region is not None:
        print(f"RS region {g.region}")
    print(f"support  [{lo:.6g}, {hi:.6g}]")
    m, v, s, k = g.stats(moments="mvsk")
    print(f"mean {m:.6g}  variance {v:.6g}  skewness {s:.6g}  excess kurtosis {k:.6g}")
    print("\n        p        Q(p)      Q(1-p)")
    for p in (1e-300, 1e-100, 1e-12, 1e-6, 1e-3, 0.05, 0.25, 0.5):
        print(f"{p:9.3g}  {g.ppf(p):10.6g}  {g.isf(p):10.6g}")
    print("\n        x           F(x)          1-F(x)")
    for x in np.linspace(g.ppf(1e-9), g.isf(1e-9), 7):
        print(f"{x:9.5g}  {g.cdf(x):14.6e}  {g.sf(x):14.6e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
