"""A sweep over a coefficient solved all at once (runs.coefficients) gives the answers of
the file solved again at each value, and steps aside where it does not apply."""
from __future__ import annotations

import os

import numpy as np
import pytest

import linkcli
from linkcli.runs import coefficients
from linkcli.runs.sheet import evaluate

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def usual(linkage, name, values, names):
    """The answers of the file built and solved at each value (no shortcut)."""
    from linkcli.input.document import rebuild
    rows = [evaluate(rebuild(linkage.model, {name: float(v)}), names=names) for v in values]
    return {n: np.array([float(r.values[n]) for r in rows]) for n in names}


@pytest.mark.parametrize("path, name, values, names", [
    ("mechanisms/polimi-2001-09-18-vibration.yaml", "ks", [20.0, 77.0, 400.0],
     ["w1", "w2", "f1", "u1", "u2", "k11", "k12", "phi_e"]),
    ("docs/examples/two-masses.yaml", "c2", [1.0, 5.0, 40.0],
     ["w1", "T1", "c0m", "X2r", "H12", "r1"]),
    ("docs/examples/two-masses.yaml", "m1", [0.5, 2.0, 7.0], ["w1", "w2", "l2", "c1m", "Tb"]),
    ("mechanisms/polimi-2001-06-20-vibration.yaml", "r", [50.0, 500.0, 5000.0],
     ["z_e", "N", "m_red", "r_red", "wn", "W", "Z", "phZ", "T", "Ft"]),
])
def test_at_once_is_the_file_solved_at_each_value(path, name, values, names):
    linkage = linkcli.load(os.path.join(ROOT, path))
    fast = coefficients.sweep(linkage.model, name, np.array(values), names, evaluate)
    assert fast is not None
    answers, solved, _ = fast
    assert solved.all()
    expected = usual(linkage, name, values, names)
    for n in names:
        assert answers[n] == pytest.approx(expected[n], rel=1e-9, abs=1e-12), n


def test_it_steps_aside_where_the_parameter_sets_more_than_coefficients():
    """L sets lengths (the geometry moves): every value solved as usual, same answers."""
    linkage = linkcli.load(os.path.join(ROOT, "mechanisms", "polimi-2001-09-18-vibration.yaml"))
    assert coefficients.sweep(linkage.model, "L", np.array([0.4, 0.5]), ["w1"], evaluate) \
        is None
    varied = linkage.vary("L", [0.4, 0.6], names=["w1"])
    g, k, m = 9.81, 100.0, 2.0
    assert varied.values["w1"] == pytest.approx(
        np.sqrt(2 * k / m + (2 - np.sqrt(2)) * g / np.array([0.4, 0.6])), rel=1e-10)


def test_values_where_the_equilibrium_moves_are_solved_as_usual():
    """A mass hanging on a spring unstretched in the figure: its equilibrium moves with the
    stiffness, so no value is answered at once, and the sweep is the usual one."""
    text = """
title: hanging mass
units: {length: m, angle: deg}
params: {m: 2, ks: 800}
frame: {B: [0, 1]}
points: {P: [0, 0]}
sliders: {body: {point: P, guide: {x: 0}}}
coordinates: {y: {y: P}}
springs: {s: {between: [B, P], k: ks}}
dynamics: {gravity: 9.81, masses: {P: m}}
quantities:
  w: {natural_frequency: 1}
  ye: {equilibrium: y}
report: {vibration: [w, ye]}
"""
    linkage = linkcli.loads(text)
    fast = coefficients.sweep(linkage.model, "ks", np.array([400.0, 1600.0]), ["w", "ye"],
                              evaluate)
    assert fast is None or not fast[1].any()
    varied = linkage.vary("ks", [400.0, 1600.0])
    assert varied.values["ye"] == pytest.approx(-2 * 9.81 / np.array([400.0, 1600.0]),
                                                rel=1e-9)


def test_an_expression_keeps_its_own_unit():
    """An expression among the answers (the static deflection, in m) swept over a spring's
    stiffness: its unit was looked up among the answers it reads (KeyError, exit 70).  The
    deflection of 4 kg is M g / ks, the period 2 pi sqrt(M / ks)."""
    linkage = linkcli.load(os.path.join(ROOT, "mechanisms/vib-cdquestions-spring-mass.yaml"))
    ks = np.array([900.0, 1000.0, 1100.0])
    _, _, units = coefficients.sweep(linkage.model, "ks", ks, ["delta", "T"], evaluate)
    assert units == {"delta": "m", "T": "s"}
    varied = linkage.vary("ks", ks)
    assert varied.solved.all()
    assert varied.values["delta"] == pytest.approx(4 * 9.81 / ks, rel=1e-9)
    assert varied.values["T"] == pytest.approx(2 * np.pi * np.sqrt(4 / ks), rel=1e-9)
