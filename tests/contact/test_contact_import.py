"""``import contact`` is light: pandas, matplotlib and the BEM solver load on first use."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

import contact

HEAVY = ("pandas", "matplotlib", "contact.bem", "contact._constrained_cg", "contact._influence",
         "contact.bem_compare")


def run(code: str) -> dict:
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, timeout=120)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_import_does_not_load_pandas_matplotlib_or_the_bem():
    got = run(
        "import json, sys\n"
        "import contact\n"
        f"heavy = [m for m in {HEAVY!r} if m in sys.modules]\n"
        "s = contact.weierstrass((32, 32), 1e-3, 0.5, rq=5e-6, rng=0)\n"
        "r = contact.solve_displacement(s, float(s.heights.max()) - 5e-6, 210e9, 0.3)\n"
        "after_solve = 'pandas' in sys.modules\n"
        "bem = contact.solve_bem\n"
        "print(json.dumps({'heavy': heavy, 'after_solve': after_solve,\n"
        "                  'bem': bem.__module__, 'all': sorted(contact.__all__),\n"
        "                  'bem_loaded': 'contact.bem' in sys.modules}))\n"
    )
    assert got["heavy"] == []
    # Building the asperity table needs pandas, the BEM name resolves on first access.
    assert got["after_solve"] is True
    assert got["bem"] == "contact.bem" and got["bem_loaded"] is True
    for name in ("solve_bem", "solve_bem_displacement", "BEMConvergenceWarning",
                 "compare_models"):
        assert name in got["all"]


def test_lazy_names_resolve_and_unknown_names_fail():
    from contact import BEMConvergenceWarning, compare_models, solve_bem_displacement
    from contact.bem import solve_bem
    from contact.bem_compare import compare_models as direct

    assert contact.solve_bem is solve_bem and compare_models is direct
    assert issubclass(BEMConvergenceWarning, Warning)
    assert callable(solve_bem_displacement)
    assert {"solve_bem", "compare_models"} <= set(dir(contact))
    with pytest.raises(AttributeError, match=r"module 'contact' has no attribute 'nonsense'"):
        _ = contact.nonsense
    for name in contact.__all__:
        assert getattr(contact, name) is not None
