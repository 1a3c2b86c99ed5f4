"""The ``glstat`` command and its streams: a closed pipe on standard output."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from glstat.cli import commands


def _csv(tmp_path, n: int = 300):
    data = tmp_path / "x.csv"
    np.savetxt(data, np.random.default_rng(0).gamma(3.0, 1.0, n), header="pressure", comments="")
    return data


#: ``glstat study`` with its computation replaced by lines of output (a real study takes minutes).
STUDY_PRINTING = ("import sys; from glstat.cli import commands; "
                  "commands.study_main = lambda rest: [print('line') for _ in range(10**5)] and 0; "
                  "sys.exit(commands.main(['study']))")


@pytest.mark.parametrize("command", ["fit", "demo", "study"])
def test_a_closed_pipe_ends_quietly_with_the_sigpipe_status(tmp_path, command):
    argv = {"fit": ["-m", "glstat.cli", "fit", str(_csv(tmp_path)), "--bootstrap", "0", "--out",
                    str(tmp_path / "out")],
            "demo": ["-m", "glstat.cli", "demo"], "study": ["-c", STUDY_PRINTING]}[command]
    proc = subprocess.Popen([sys.executable, *argv], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    assert proc.stdout is not None and proc.stderr is not None
    proc.stdout.close()  # the reader goes away before the command writes, as `| head -0`
    err = proc.stderr.read()
    status = proc.wait(timeout=300)
    assert "Traceback" not in err and "BrokenPipeError" not in err, err
    assert status == commands.CLOSED_PIPE_STATUS
    if sys.platform != "win32":
        assert status == 141


def test_a_broken_pipe_that_is_not_stdout_is_an_error(monkeypatch, capfd):
    def broken(cmd, rest, **options):
        raise BrokenPipeError("a worker's pipe")

    monkeypatch.setattr(commands, "_dispatch", broken)
    with pytest.raises(BrokenPipeError, match="worker"):
        commands.main(["fit", "x.csv"])


def test_quiet_writes_nothing_on_stderr(tmp_path):
    """-q: no phase notices, no progress bars, no warnings; the report still on stdout. The
    sample is large enough that the goodness of fit and the cross-validation last more than
    the two seconds after which a phase announces itself."""
    data = tmp_path / "x.csv"
    np.savetxt(data, np.random.default_rng(1).gamma(3.0, 1.0, 100_000), header="pressure",
               comments="")
    argv = [sys.executable, "-m", "glstat.cli", "fit", str(data), "--bootstrap", "100",
            "--gof-resamples", "40", "--hardness", "40", "--out", str(tmp_path / "out"), "--seed", "1"]
    loud = subprocess.run(argv, capture_output=True, text=True, timeout=600)
    quiet = subprocess.run([*argv, "-q"], capture_output=True, text=True, timeout=600)
    assert loud.returncode == quiet.returncode == 0
    assert "glstat fit: goodness of fit" in loud.stderr  # the phases do announce themselves
    assert quiet.stderr == ""
    assert "damage probability" in quiet.stdout.lower()


def test_quiet_still_reports_errors(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "glstat.cli", "-q", "fit",
                           str(tmp_path / "missing.csv")], capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 2
    assert proc.stderr.startswith("glstat fit: error: file not found")


def _piped(tmp_path, data: bytes, *options: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "glstat.cli", "fit", "-", "--bootstrap", "0",
                           "--gof-resamples", "0", "--out", str(tmp_path / "out"), *options],
                          input=data, capture_output=True, timeout=300)


def test_a_dash_reads_a_csv_from_standard_input(tmp_path):
    x = np.random.default_rng(2).gamma(3.0, 1.0, 400)
    table = "load,pressure\n" + "".join(f"{i},{float(v)!r}\n" for i, v in enumerate(x))
    proc = _piped(tmp_path, table.encode(), "--column", "pressure")
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout.decode()
    assert out.startswith("glstat fit: standard input (csv), column 'pressure': 400 values used")
    import json

    saved = json.loads((tmp_path / "out" / "fit.json").read_text())
    assert saved["input"]["file"] == "-"
    assert saved["input"]["n_entries"] == 400
    # the same answer as the same data read from a file
    data = tmp_path / "x.csv"
    data.write_text(table)
    lam = [line for line in out.splitlines() if "lambda" in line][:4]
    from_file = subprocess.run([sys.executable, "-m", "glstat.cli", "fit", str(data), "--column",
                                "pressure", "--bootstrap", "0", "--gof-resamples", "0", "--out",
                                str(tmp_path / "out2")], capture_output=True, text=True, timeout=300)
    assert [line for line in from_file.stdout.splitlines() if "lambda" in line][:4] == lam


def test_standard_input_is_sniffed_compressed_and_binary(tmp_path):
    import gzip
    import io

    x = np.random.default_rng(3).gamma(3.0, 1.0, 300)
    text = "\t".join(["a", "b"]) + "\n" + "".join(f"{float(v)!r}\tx\n" for v in x)
    proc = _piped(tmp_path, gzip.compress(text.encode()))
    assert proc.returncode == 0, proc.stderr
    assert b"standard input (text), column 'a': 300 values" in proc.stdout
    buf = io.BytesIO()
    np.save(buf, x)
    proc = _piped(tmp_path, buf.getvalue())
    assert proc.returncode == 0, proc.stderr
    assert b"standard input (npy), column '1': 300 values" in proc.stdout


def test_standard_input_errors_name_it(tmp_path):
    empty = _piped(tmp_path, b"")
    assert empty.returncode == 2
    assert empty.stderr.decode().strip() == ("glstat fit: error: standard input is empty (0 "
                                             "bytes); give a file with the values to fit")
    binary = _piped(tmp_path, b"1\n2\x00\n")
    assert binary.returncode == 2
    err = binary.stderr.decode()
    assert "standard input is not a text file (a NUL byte at byte 3)" in err
    assert "glstat-stdin" not in err  # no temporary file name
    assert not (tmp_path / "out").exists()


def test_a_dash_on_a_terminal_is_refused(monkeypatch):
    from glstat.cli.sample_files import InputError, read_sample

    class Terminal:
        buffer = None

        def isatty(self):
            return True

    monkeypatch.setattr(sys, "stdin", Terminal())
    with pytest.raises(InputError, match="standard input is a terminal"):
        read_sample("-")


def test_json_prints_fit_json_and_nothing_else_on_stdout(tmp_path):
    import json

    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "glstat.cli", "fit", str(_csv(tmp_path)),
                           "--bootstrap", "30", "--hardness", "12", "--n-max", "300", "--seed", "1",
                           "--json", "--out", str(out)], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)  # the whole of stdout is one document
    assert proc.stdout == (out / "fit.json").read_text(encoding="utf-8")
    assert doc["input"]["n_used"] == 300 and doc["settings"]["seed"] == 1
    assert len(doc["fit"]["lambdas"]) == 4
    assert doc["damage"]["hardness"] == 12 and 0 <= doc["damage"]["estimate"][0] <= 1
    assert doc["maximum"]["low"] <= doc["maximum"]["median"] <= doc["maximum"]["high"]
    assert "fit.json" in doc["files"]
    assert "NaN" not in proc.stdout and "Infinity" not in proc.stdout  # strict JSON


def test_json_of_a_failing_run_prints_nothing_on_stdout(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "glstat.cli", "fit", str(tmp_path / "no.csv"),
                           "--json"], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 2 and proc.stdout == ""
    assert "file not found" in proc.stderr
