"""Test-only: points in both tails of a distribution and next to its finite end points, for
the tests that compare a distribution's functions with glstat.GLD's (pytest puts
``tests/glstat`` on ``sys.path``)."""

from __future__ import annotations

import math

import numpy as np


def tail_points(gld, support, log_p) -> np.ndarray:
    """x at the tail probabilities exp(log_p) on both sides (``gld``'s quantiles, which are
    doubles: references are computed at these doubles), and 1, 4 and 64 ulps inside each finite
    end point of ``support`` (probabilities far below the double range for small shapes);
    sorted, finite and strictly inside the support."""
    a, b = support
    xs = [gld.ppf(np.exp(log_p)), gld.isf(np.exp(log_p))]
    for end, inward in ((float(a), math.inf), (float(b), -math.inf)):
        if math.isfinite(end):
            x = end
            for k in range(64):
                x = math.nextafter(x, inward)
                if k in (0, 3, 63):
                    xs.append(np.array([x]))
    x = np.unique(np.concatenate(xs))
    return x[np.isfinite(x) & (x > a) & (x < b)]
