import contact
import glstat


def test_packages_import():
    assert glstat.__version__
    assert contact.Surface


def test_ci_runs_the_readmes_commands_as_written_and_in_order():
    """.ci/run runs the README's shell commands verbatim, in the README's order."""
    import re
    from pathlib import Path

    root = Path(__file__).resolve().parent.parent
    readme = (root / "README.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```bash\n(.*?)```", readme, flags=re.S)
    commands = [ln.strip() for b in blocks for ln in b.splitlines()
                if ln.strip() and not ln.lstrip().startswith("#")]
    assert len(commands) >= 2
    ci = [ln.strip() for ln in (root / ".ci" / "run").read_text(encoding="utf-8").splitlines()]
    positions = [ci.index(c) for c in commands]  # ValueError: a command .ci/run does not run
    assert positions == sorted(positions)
