"""Shipped problems that ask design questions and answers computed from answers
(mechanisms/vib-*.yaml with find:, expr, and the vibration chapters' quantities), each
against the closed form of its statement, written here from the textbook formulas."""
from __future__ import annotations

import math
import os

import pytest

import linkcli
from linkcli.runs.check import check_file

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
G = 9.81


def solved(name, names=None):
    linkage = linkcli.load(os.path.join(ROOT, "mechanisms", name))
    return linkage.solve(names=names).values


@pytest.mark.parametrize("name", [
    "vib-gate-me-2015-critical-damping.yaml", "vib-gate-me-2013-impulse.yaml",
    "vib-tspgecet-static-deflection.yaml", "vib-quantumstudy-spring-period.yaml",
    "vib-cdquestions-spring-mass.yaml", "vib-ques10-refrigerator-isolation.yaml",
    "vib-king-4-1-coupled-pendulums.yaml", "vib-rao-rough-road-100kmh.yaml"])
def test_printed_keys(name):
    report = check_file(os.path.join(ROOT, "mechanisms", name))
    assert report.error is None and report.outcomes
    assert all(o.status != "fail" for o in report.outcomes), report.outcomes


def test_critical_damping_design():
    """2 sqrt(k m) = 0.1 with m = 1 kg: k = 0.0025 N/m; 2 sqrt(8k 2m) = 0.4 kg/s."""
    v = solved("vib-gate-me-2015-critical-damping.yaml", ["ks", "cc1", "cc2"])
    assert v["ks"] == pytest.approx(0.0025, rel=1e-9)
    assert v["cc2"] == pytest.approx(4 * v["cc1"], rel=1e-12)


def test_impulse_amplitude():
    """v0 = J/m = 0.5 m/s, omega = sqrt(10000/1) = 100 rad/s: x = v0/omega = 5 mm."""
    assert solved("vib-gate-me-2013-impulse.yaml", ["A"])["A"] == pytest.approx(5.0, rel=1e-10)


@pytest.mark.parametrize("name, delta, m", [("vib-tspgecet-static-deflection.yaml", 0.01, 10),
                                            ("vib-quantumstudy-spring-period.yaml", 0.2, 1)])
def test_stiffness_from_a_static_deflection(name, delta, m):
    """k = m g / delta, omega = sqrt(g / delta)."""
    v = solved(name)
    assert v["ks"] == pytest.approx(m * G / delta, rel=1e-9)
    if "fn" in v:
        assert v["fn"] == pytest.approx(math.sqrt(G / delta) / (2 * math.pi), rel=1e-9)
    else:
        assert v["T"] == pytest.approx(2 * math.pi * math.sqrt(delta / G), rel=1e-9)


def test_refrigerator_stiffness_for_a_tenth_of_the_force():
    """Undamped above resonance TR = 1/(r^2 - 1) = 0.1: r^2 = 11, 3 K = m Omega^2 / 11."""
    omega = 2 * math.pi * 580 / 60
    v = solved("vib-ques10-refrigerator-isolation.yaml", ["K", "TR", "R"])
    assert v["K"] == pytest.approx(30 * omega ** 2 / 33, rel=1e-9)
    assert v["R"] == pytest.approx(math.sqrt(11), rel=1e-9)


def test_beat_time_of_coupled_pendulums():
    w1, w2 = math.sqrt(G / 0.3), math.sqrt(G / 0.3 + 2 * 1.5 / 0.95)
    v = solved("vib-king-4-1-coupled-pendulums.yaml", ["t0"])
    assert v["t0"] == pytest.approx(math.pi / (w2 - w1), rel=1e-10)
