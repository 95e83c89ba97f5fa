"""Sweeps over a parameter (``sweep --vary``, ``plot --vary``, ``Linkage.vary``): the answers
at each value against closed forms, the values without answers reported, the refusals."""
from __future__ import annotations

import json
import math
import os

import numpy as np
import pytest

import linkcli
from linkcli.errors import AssemblyError, InputError

from cli_helpers import run

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CRANK = os.path.join(ROOT, "mechanisms", "polimi-crank-slider.yaml")
PENDULUM = os.path.join(ROOT, "mechanisms", "polimi-2001-09-18-vibration.yaml")
G = 9.81


def test_frequencies_against_a_stiffness_closed_form():
    """The double pendulum with springs: omega^2 = 2 ks / m + (2 -+ sqrt 2) g / L."""
    ks = np.linspace(20.0, 400.0, 9)
    varied = linkcli.load(PENDULUM).vary("ks", ks, names=["w1", "w2"])
    assert varied.solved.all() and not varied.issues
    m, L = 2.0, 0.5
    for s, name in ((1, "w1"), (-1, "w2")):
        expected = np.sqrt(2 * ks / m + (2 - s * math.sqrt(2)) * G / L)
        assert varied.values[name] == pytest.approx(expected, rel=1e-10)


def test_a_crank_length_and_the_values_that_do_not_assemble():
    """c = a cos(45) + sqrt(b^2 - a^2 sin^2(45)) where it assembles (a sin 45 < b = sqrt 2);
    the toggle (a = 2) and the values that do not assemble are reported, not printed."""
    a = np.array([0.5, 1.0, 1.5, 2.0, 2.5, 3.0])
    varied = linkcli.load(CRANK).vary("a", a, names=["c"])
    assert varied.solved.tolist() == [True, True, True, True, False, False]
    ok = a[varied.solved]
    s = math.sin(math.radians(45))
    expected = ok * s + np.sqrt(2 - (ok * s) ** 2)
    assert varied.values["c"][:3] == pytest.approx(expected[:3], rel=1e-12)
    # at the toggle the square root of a rounding-size difference: sqrt(eps) relative
    assert varied.values["c"][3] == pytest.approx(expected[3], rel=4 * math.sqrt(2.2e-16))
    assert len(varied.issues) == 1 and varied.issues[0].count == 2
    assert "cannot assemble" in varied.issues[0].text()


def test_no_value_with_answers_is_the_error_of_the_first():
    with pytest.raises(AssemblyError):
        linkcli.load(CRANK).vary("a", [3.0, 4.0], names=["c"])


def test_with_params_is_the_file_with_other_values():
    linkage = linkcli.load(PENDULUM)
    other = linkage.with_params(ks=200)
    assert other.solve(names=["k11"]).values["k11"] == pytest.approx(
        4 * 200 * 0.25 + 2 * 2 * G * 0.5, rel=1e-12)      # 4 k L^2 + 2 m g L
    assert linkage.solve(names=["k11"]).values["k11"] == pytest.approx(
        4 * 100 * 0.25 + 2 * 2 * G * 0.5, rel=1e-12)


def test_cli_formats_and_the_parameters_column():
    code, out, err = run(["sweep", PENDULUM, "--vary", "ks=50:150:2", "--names", "w1",
                          "--format", "csv"])
    assert code == 0 and not err
    lines = out.splitlines()
    assert lines[0] == "ks [N/m],w1 [rad/s]" and len(lines) == 4
    assert float(lines[2].split(",")[1]) == pytest.approx(
        math.sqrt(2 * 100 / 2 + (2 - math.sqrt(2)) * G / 0.5), rel=1e-12)
    code, out, err = run(["sweep", CRANK, "--vary", "a=1:3:2", "--names", "c",
                          "--format", "json"])
    data = json.loads(out)
    assert code == 0 and data["a"] == [1.0, 2.0] and data["units"]["a"] == "m"
    assert data["issues"][0]["from"] == 3.0 and "cannot assemble" in err


@pytest.mark.parametrize("args, words", [
    (["--vary", "kk=1:2:1"], "'kk' is not a parameter of this file"),
    (["--vary", "k=0:9:9"], "the digit k is not varied here"),
    (["--vary", "ks=1:2"], "cannot read 'ks=1:2'"),
    (["--vary", "ks=1:2:0"], "1 <= STEPS"),
    (["--vary", "ks=1:2:1", "--steps", "3"], "--vary takes the place of --steps"),
    (["--vary", "ks=1:2:1", "--names", "nope"], "'nope' is not a quantity"),
])
def test_refusals(args, words):
    code, _, err = run(["sweep", PENDULUM] + args)
    assert code == 2 and words in err, err


def test_plot_against_a_parameter(tmp_path):
    out = tmp_path / "w.png"
    code, _, err = run(["plot", PENDULUM, "--vary", "ks=50:150:4", "--y", "w1", "-o", out])
    assert code == 0 and out.stat().st_size > 1000, err
    with pytest.raises(InputError):
        linkcli.load(PENDULUM).vary("nope", [1.0])
