"""``import glstat`` is light: statsmodels, matplotlib and pandas load only when a function
that needs them runs."""

from __future__ import annotations

import json
import subprocess
import sys

HEAVY = ("statsmodels", "matplotlib", "pandas")


def _loaded(code: str) -> dict:
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         timeout=300)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_import_glstat_loads_neither_statsmodels_nor_matplotlib_nor_pandas():
    subprocess.run([sys.executable, "-c", "import glstat, sys; assert 'statsmodels' not in sys.modules"],
                   check=True, timeout=300)
    got = _loaded(
        "import json, sys\n"
        "import glstat, glstat.gof, glstat.plot, glstat.fitting, glstat.bootstrap, glstat.resampling.maxima\n"
        f"print(json.dumps([m for m in {HEAVY!r} if m in sys.modules]))\n"
    )
    assert got == []


def test_statsmodels_loads_when_a_function_needs_it():
    got = _loaded(
        "import json, sys\n"
        "import numpy as np, glstat\n"
        "x = np.random.default_rng(0).gamma(5.0, 3.0, size=200)\n"
        "glstat.fit(x, 'rs', 'mle', warn=False)\n"
        "glstat.edf_statistics(x, glstat.GLD(15.0, 0.05, 0.1, 0.2))\n"
        "fitted = 'statsmodels' in sys.modules\n"
        "from glstat.gof import adjust_pvalues\n"
        "adjust_pvalues([0.01, 0.2])\n"
        "print(json.dumps({'after_fit': fitted, 'after_adjust': 'statsmodels' in sys.modules}))\n"
    )
    assert got == {"after_fit": False, "after_adjust": True}
