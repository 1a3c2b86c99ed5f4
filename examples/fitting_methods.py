"""Fit one sample by every method and compare the fits (python examples/fitting_methods.py)."""

import numpy as np
from scipy import stats

import glstat


def main():
    x = stats.gamma(5, scale=3).rvs(size=1000, random_state=np.random.default_rng(0))
    for method in ("moments", "percentiles", "lmoments", "mle", "mps", "starship"):
        f = glstat.fit(x, param="rs", method=method)
        sel = f.solutions[f.solutions.selected].iloc[0]
        print(f"{method:12s} lambdas={np.round(f.lambdas, 5)}  KS={sel.ks:.4f}  roots={len(f.solutions)}")
    print(glstat.fit_moments(0, 1, 0, 3).solutions[["lambda1", "lambda2", "lambda3", "lambda4", "selected"]])
    # ML by the compiled BFGS (default) and by Nelder-Mead from the same starts
    for optimizer in ("bfgs", "nelder-mead"):
        f = glstat.fit(x, param="fkml", method="mle", optimizer=optimizer)
        print(f"ML with {optimizer:11s}: log-likelihood {-f.statistics['neg_loglik']:.6f}")


if __name__ == "__main__":
    main()
