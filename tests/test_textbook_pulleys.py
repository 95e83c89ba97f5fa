"""Pulley and rolling-disc vibration problems (mechanisms/vib-*.yaml) against independent
solutions: problems 1, 11 and 12 of /work/scratch/vibbook/problems.md (check_1.py,
check_11.py, check_12.py), re-written here as closed forms from the energies of each system.
Nothing expected here is taken from linkcli's output; the models are exact about the
equilibrium, so the comparison is to rtol 1e-9.  Matrix entries and spring forces are SI; the
other values are in the files' display units.

Extra quantities that a file does not report are added to a copy of the file's data before it
is loaded, so the shipped files stay as the problems ask them.
"""
from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

import linkcli
from linkcli.runs.check import check_file

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vibration_cases import close, keys_agree, shipped, solve_file  # noqa: E402

G = 9.81

FILES = {
    "block": "vib-gate-me-2016-pulley-block.yaml",          # problem 1
    "atwood": "vib-smii-07-q9-q10-pulley.yaml",             # problem 11
    "disc": "vib-smii-07-q3-q4-rolling-disc.yaml",          # problem 12
}


def path_of(key):
    return shipped(FILES[key])


def solve(key, extra=None, params=None, report=None, **sections):
    """Values of the file ``key`` (see ``vibration_cases.solve_file``)."""
    return solve_file(path_of(key), extra, params, report, **sections)


# --- every file: its printed keys at their printed precision ----------------------------------
@pytest.mark.parametrize("key", sorted(FILES))
def test_file_reproduces_its_printed_keys(key):
    report = keys_agree(path_of(key))
    assert [o for o in report.outcomes if o.status == "pass"]


def test_known_key_problems_are_the_sheet_mistakes():
    known = {}
    for key in FILES:
        for o in check_file(path_of(key)).outcomes:
            if o.status == "known":
                known[(key, o.name)] = (o.printed, o.computed)
    assert known == {("atwood", "w9"): ("5.71", "5.72"),
                     ("atwood", "w10"): ("5.34", "5.37"),
                     ("disc", "w4"): ("16.09", "4.01"),
                     ("disc", "A"): ("0.019", "0.076")}


# --- problem 1: GATE ME 2016 set 2 ------------------------------------------------------------
def block_on_pulley(m=5.0, M=20.0, k=1500.0, r=0.2):
    """The block falls by x, the pulley turns by x / r, the spring's strand rises by x:
    T = 1/2 (m + (M r^2/2) / r^2) x'^2, V = 1/2 k x^2 about the equilibrium."""
    m_star = m + (M * r ** 2 / 2) / r ** 2
    return m_star, k, math.sqrt(k / m_star)


@pytest.mark.parametrize("r", [0.2, 0.05, 0.5])
def test_block_on_a_heavy_pulley(r):
    m_star, k_star, wn = block_on_pulley(r=r)
    v = solve("block", {"N": {"spring_force": "k"}, "y0": {"equilibrium": "y"}},
              params={"r": r})
    close(v["m_star"], m_star)
    close(v["m_star"], 15.0)
    close(v["k_star"], k_star)
    close(v["wn"], wn)
    close(v["wn"], 10.0)
    close(v["N"], 5.0 * G)                        # the spring holds the block's weight
    close(v["y0"], -1.0)                          # the figure is the equilibrium


def test_block_on_a_heavy_pulley_free_response():
    """From rest 1 cm below the equilibrium: y = -0.01 cos(wn t)."""
    _, _, wn = block_on_pulley()
    times = [0.0, 0.05, 0.2, 0.7]
    extra = {f"y{i}": {"free_response": "y", "time": t} for i, t in enumerate(times)}
    v = solve("block", extra, report=list(extra), initial={"y": -0.01})
    for i, t in enumerate(times):
        close(v[f"y{i}"], -0.01 * math.cos(wn * t), atol=1e-12)


# --- problem 11: SMII tutorial sheet 7, Q9 and Q10 --------------------------------------------
def atwood(I, m1=4.0, m2=20.0, k=785.0, R=0.125):
    """x up for the 4 kg block, down for the 20 kg one, the pulley turns by x / R:
    T = 1/2 (m1 + m2 + I/R^2) x'^2, V = 1/2 k x^2 + (m1 - m2) g x."""
    m_star = m1 + m2 + I / R ** 2
    x0 = (m2 - m1) * G / k
    return m_star, k, x0, math.sqrt(k / m_star)


def test_two_blocks_over_a_pulley():
    m9, k9, x9, w9 = atwood(0.0)
    m10, k10, x10, w10 = atwood(0.05)
    v = solve("atwood", {"N9": {"spring_force": "k9"}, "N10": {"spring_force": "k10"},
                         "c": {"mass_matrix": ["x9", "x10"]},
                         "kc": {"stiffness_matrix": ["x9", "x10"]}})
    close(v["m9"], m9)
    close(v["m9"], 24.0)
    close(v["k9"], k9)
    close(v["x0_9"], x9)
    close(v["w9"], w9)
    close(v["m10"], m10)
    close(v["m10"], 27.2)
    close(v["k10s"], k10)
    close(v["x0_10"], x10)
    close(v["w10"], w10)
    close(v["N9"], 16 * G)                      # the spring carries the difference of weights
    close(v["N10"], 16 * G)
    close(v["c"], 0.0, atol=1e-12)              # the two questions are uncoupled
    close(v["kc"], 0.0, atol=1e-9)
    # the sheet's numbers: omega truncated (Q9), and from the rounded 0.43 (Q10)
    assert round(w9, 2) == 5.72 and math.floor(w9 * 100) / 100 == 5.71
    assert round(0.125 ** 2 * m10, 3) == 0.425 and round(785 * 0.125 ** 2, 2) == 12.27
    assert round(math.sqrt(12.27 / 0.43), 2) == 5.34 and round(w10, 2) == 5.37


@pytest.mark.parametrize("q, I", [("x9", 0.0), ("x10", 0.05)])
def test_released_from_rest_with_the_spring_unstretched(q, I):
    """The sheet's x = -x0 cos(omega t) + x0: from x = 0, i.e. -x0 from the equilibrium."""
    _, _, x0, w = atwood(I)
    times = [0.0, 0.1, 0.4, 1.3]
    extra = {f"x{i}": {"free_response": q, "time": t} for i, t in enumerate(times)}
    v = solve("atwood", extra, report=list(extra), initial={q: -x0})
    for i, t in enumerate(times):
        close(v[f"x{i}"], -x0 * math.cos(w * t), atol=1e-12)


# --- problem 12: SMII tutorial sheet 7, Q3 and Q4 ---------------------------------------------
def rolling_disc(k, W=89.0, R=0.1524):
    """Centre x, the disc turns by -x / R: T = 1/2 (m + (m R^2/2)/R^2) x'^2, V = 1/2 k x^2."""
    m = W / G
    m_star = 1.5 * m
    return m, m_star, math.sqrt(k / m_star)


def test_disc_stiffness_for_one_hertz():
    m, m_star, _ = rolling_disc(1.0)
    k3 = (2 * math.pi) ** 2 * m_star               # f = sqrt(k / m*) / 2 pi = 1 Hz
    assert round(k3) == 537 and round(k3, 2) == 537.24
    v = solve("disc", {"m3": {"mass_matrix": ["x3", "x3"]},
                       "w3": {"natural_frequency": 2}})
    close(v["k_3"], k3)
    close(v["m3"], m_star)
    close(v["f3"], 1.0)
    close(v["w3"], 2 * math.pi)
    # the sheet's '89/0.81' typo would give a stiffness twelve times larger
    assert round((2 * math.pi) ** 2 * 1.5 * 89 / 0.81) == 6507


def test_disc_amplitude_after_a_clockwise_spin():
    R, k4 = 0.1524, 218.9
    m, m_star, w4 = rolling_disc(k4)
    v0 = 2.0 * R                                     # clockwise: the centre rolls to +x
    v = solve("disc", {"c": {"mass_matrix": ["x3", "x4"]}})
    close(v["m4"], m_star)
    close(v["k_4"], k4)
    close(v["w4"], w4)
    close(v["A"], v0 / w4)
    close(v["c"], 0.0, atol=1e-12)
    assert round(v0 / w4, 4) == 0.0760 and round(m_star, 2) == 13.61
    # the sheet's 16.09 is omega^2, and 0.019 divides by it
    assert round(k4 / m_star, 2) == 16.09 and round(0.305 / 16.09, 3) == 0.019


def test_disc_free_response_is_a_sine():
    R, k4 = 0.1524, 218.9
    _, _, w4 = rolling_disc(k4)
    times = [0.0, 0.15, 0.5, 2.0]
    extra = {f"x{i}": {"free_response": "x4", "time": t} for i, t in enumerate(times)}
    v = solve("disc", extra, report=list(extra))
    for i, t in enumerate(times):
        close(v[f"x{i}"], 2 * R / w4 * math.sin(w4 * t), atol=1e-12)


def test_disc_rolls_clockwise_to_the_right():
    """The file's initial velocity v0 = +2R reads the spin as clockwise: the disc's mark B4
    (on top of the rim) moves at 2 v0 to +x when the centre moves at v0."""
    mech = linkcli.load(path_of("disc"))
    solver = mech.solver()
    kin = solver.positions((0.0, 1.0))
    solver.velocities(kin, (0.0, 1.0))
    vb, va = complex(np.asarray(kin.vel["B4"])), complex(np.asarray(kin.vel["A4"]))
    omega = ((vb - va) / (0.1524j)).imag
    assert va == pytest.approx(1.0) and vb == pytest.approx(2.0)
    assert omega == pytest.approx(-1 / 0.1524)       # clockwise for +x
