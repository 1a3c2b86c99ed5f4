"""docs/api.md is the API reference generated from the docstrings; it must be current."""

import importlib.util
from pathlib import Path

DOCS = Path(__file__).resolve().parents[1] / "docs"


def test_api_reference_is_up_to_date():
    spec = importlib.util.spec_from_file_location("make_api", DOCS / "make_api.py")
    make_api = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(make_api)
    expected = make_api.render()
    current = (DOCS / "api.md").read_text(encoding="utf-8")
    assert current == expected, "docs/api.md is stale: run `python docs/make_api.py`"
    for name in ("glstat.GLD", "glstat.fit", "glstat.bootstrap", "glstat.maximum",
                 "glstat.damage_probability", "glstat.gof_report", "contact.solve",
                 "contact.solve_bem", "glstat.study.run_campaign"):
        assert f"### `{name}`" in current
