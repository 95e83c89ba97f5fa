"""Trust, second round: the command line's bounds and messages, the exports' text, the
display of numbers and the drawings' labels.  Each test failed before its fix."""
from __future__ import annotations

import os
import subprocess
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import CODE, FOURBAR, run  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data")


@pytest.fixture
def fourbar(tmp_path):
    path = tmp_path / "fourbar.yaml"
    path.write_text(FOURBAR, encoding="utf-8")
    return path


# --- -o never writes onto the input, --force or not -----------------------------------------
@pytest.mark.parametrize("link", ["none", "symbolic", "hard"])
@pytest.mark.parametrize("target", ["moodle", "markdown"])
def test_export_force_never_replaces_the_input(fourbar, tmp_path, link, target):
    output = fourbar
    if link == "symbolic":
        output = tmp_path / "link.xml"
        os.symlink(fourbar, output)
    elif link == "hard":
        output = tmp_path / "same.xml"
        os.link(fourbar, output)
    code, out, err = run(["export", fourbar, "--to", target, "--no-figure", "--force",
                          "-o", output])
    assert code == 2, out + err
    assert "key '-o'" in err and f"is the input file {fourbar}" in err
    assert fourbar.read_text(encoding="utf-8") == FOURBAR


def test_dash_o_onto_the_file_read_on_standard_input_is_refused(fourbar):
    with open(fourbar, "rb") as stdin:
        proc = subprocess.run([sys.executable, "-c", CODE, "solve", "-", "-o", str(fourbar)],
                              stdin=stdin, capture_output=True, cwd=ROOT,
                              env=dict(os.environ, PYTHONPATH=ROOT), timeout=120)
    assert proc.returncode == 2, proc.stderr
    assert b"the file read on standard input" in proc.stderr
    assert fourbar.read_text(encoding="utf-8") == FOURBAR
