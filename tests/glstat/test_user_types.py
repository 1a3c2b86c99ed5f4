"""The types of glstat's results reach user code: mypy (the one installed with the project)
accepts a user script that uses ``glstat.fit(x).dist`` as a GLD, and rejects one that misuses
it, so the check sees glstat's annotations rather than ``Any``."""

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

pytest.importorskip("mypy", reason="the type check of user code needs mypy")

ROOT = Path(__file__).resolve().parents[2]

GOOD = """
    import numpy as np
    import glstat

    x = np.array([1.2, 0.7, 3.1, 2.2, 1.9, 0.4, 2.8, 1.1, 1.6, 2.4])
    f = glstat.fit(x)
    g: glstat.GLD = f.dist              # not Optional: no None check needed
    p: float = float(f.dist.cdf(1.0))
    ok: bool = f.ok
    lam: tuple[float, float, float, float] = f.dist.lambdas
    bf = glstat.bootstrap(x, n_resamples=10)
    low = bf.confidence_interval.low
    bca = bf.confidence_interval("BCa").high
    dist = bf.bootstrap_distribution
    level = glstat.return_level(f.dist, 100.0, n=10)
    dq = f.dist.density_quantile(0.5)
"""

BAD = """
    import numpy as np
    import glstat

    f = glstat.fit(np.array([1.0, 2.0, 3.0, 4.0, 5.0]))
    fifth = f.dist.lambdas[4]
    name: int = f.dist.param
"""


def _mypy(tmp_path: Path, name: str, code: str) -> subprocess.CompletedProcess:
    script = tmp_path / name
    script.write_text(textwrap.dedent(code))
    # from a folder outside the project: mypy finds glstat (and its py.typed marker) through
    # the installation, editable or not, as in a user's project
    return subprocess.run([sys.executable, "-m", "mypy", "--no-error-summary", "--follow-imports=silent",
                           "--cache-dir", str(ROOT / ".mypy_cache"), str(script)], cwd=tmp_path,
                          capture_output=True, text=True, timeout=600)


@pytest.mark.slow
def test_user_script_type_checks(tmp_path):
    res = _mypy(tmp_path, "user_good.py", GOOD)
    assert res.returncode == 0, res.stdout + res.stderr


@pytest.mark.slow
def test_misuse_is_reported(tmp_path):
    res = _mypy(tmp_path, "user_bad.py", BAD)
    assert res.returncode == 1, res.stdout + res.stderr
    assert "Tuple index out of range" in res.stdout
    assert ('Incompatible types in assignment (expression has type "str", variable has type "int")'
            in res.stdout)


def test_nan_fit_has_no_dist():
    import numpy as np

    import glstat

    f = glstat.fit([1.0, 2.0, np.nan, 4.0, 5.0, 6.0], "fkml", nan_policy="propagate")
    assert not f.ok
    with pytest.raises(glstat.FitError, match=r"NaN fit .* check fit\.ok"):
        f.dist
    with pytest.raises(ValueError, match="nan_policy='omit'"):
        f.dist
    good = glstat.fit([1.0, 2.0, 4.0, 4.5, 5.0, 6.0, 7.5], "fkml", warn=False)
    assert good.ok and good.dist == glstat.GLD(*good.lambdas, param="fkml")
