"""Belts that slip (docs/schema.md, "rolling and cords"): the follower turns at (1 - s/100)
of the speed the belt gives it, N2/N1 = d1/d2 (1 - s/100), written here from the diameters;
per pulley s = s1 + s2 as the books combine them; slips outside [0, 100) % and forces asked
of a slipping belt are refused with their line.  Nothing expected is taken from linkcli."""
from __future__ import annotations

import os
import sys

import numpy as np
import pytest

import linkcli
from linkcli.runs.check import check_file

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import run  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SARTHAKS = os.path.join(ROOT, "mechanisms", "sarthaks-belt-slip-dynamo.yaml")
KHURMI = os.path.join(ROOT, "mechanisms", "khurmi-11-1-belt-slip.yaml")


def text_with(path, old, new):
    text = open(path, encoding="utf-8").read()
    assert old in text
    return text.replace(old, new)


def test_keys_as_printed():
    """sarthaks: 1901.25 rpm agrees; Khurmi's 1440 (150 x 9.6, the ratio rounded first) is
    a known key problem, the formula giving 1440.6."""
    report = check_file(SARTHAKS)
    assert report.error is None and report.count("pass") == 1 and report.count("fail") == 0
    report = check_file(KHURMI)
    assert report.error is None and report.count("known") == 1 and report.count("fail") == 0
    n4 = float(linkcli.load(KHURMI).solve(names=["N4dot"]).values["N4dot"])
    assert n4 == pytest.approx(150 * 750 * 900 / (450 * 150) * 0.98 ** 2, rel=1e-12)


@pytest.mark.parametrize("path, n1, d", [(SARTHAKS, 200, (80, 40, 100, 20)),
                                         (KHURMI, 150, (750, 450, 900, 150))])
@pytest.mark.parametrize("s", [0, 2, 7.5, 40])
def test_follower_speed_is_reduced_by_the_slip(path, n1, d, s):
    """N4 = N1 (d1 d3)/(d2 d4) (1 - s/100)^2 (the same slip at each drive); without slip
    the printed 2000 and 1500 rpm."""
    text = text_with(path, "s: 2", f"s: {s}")
    if "s: 2.5" in open(path).read():
        text = text_with(path, "s: 2.5}", f"s: {s}}}")
    mech = linkcli.loads(text)
    q = np.array([0.0, 30.0, 400.0])
    values = mech.solve(q=q, qdot=np.full(3, float(n1)), names=["N4dot", "N4"]).values
    d1, d2, d3, d4 = d
    ratio = d1 * d3 / (d2 * d4) * (1 - s / 100) ** 2
    assert np.asarray(values["N4dot"]) == pytest.approx(n1 * ratio, rel=1e-12)
    if s == 0:
        assert n1 * ratio == {200: 2000, 150: 1500}[n1]
    # the positions follow the same ratio: the dynamo turns ratio x the engine's turn
    turn = np.asarray(values["N4"]) - float(np.asarray(values["N4"])[0])
    expected = (q - q[0]) * ratio
    gap = (turn - expected + 180) % 360 - 180
    assert np.abs(gap) == pytest.approx(0, abs=1e-7)


def test_slip_per_pulley_adds_as_the_books_add_it():
    """s1 between driver and belt, s2 between belt and follower: N2/N1 = d1/d2 (1 - s/100)
    with s = s1 + s2."""
    text = text_with(SARTHAKS, "slip: s,\n          to: {disc: engine", "slip: [1, 3],\n"
                     "          to: {disc: engine")
    values = linkcli.loads(text).solve(names=["N4dot"]).values
    assert float(values["N4dot"]) == pytest.approx(200 * 2 * 5 * (1 - 0.04) * (1 - 0.025),
                                                   rel=1e-12)


def test_newton_gives_the_same_speeds():
    mech = linkcli.load(SARTHAKS)
    closed = mech.solve(q=np.array([10.0, 250.0]), names=["N4dot", "N4"]).values
    newton = mech.solve(q=np.array([10.0, 250.0]), names=["N4dot", "N4"],
                        method="newton").values
    for name in ("N4dot", "N4"):
        assert np.asarray(newton[name]) == pytest.approx(np.asarray(closed[name]), abs=1e-8)


@pytest.mark.parametrize("old, new, words", [
    ("s: 2.5}", "s: 100}", ["cords.first.slip", "[0, 100)", "got 100"]),
    ("s: 2.5}", "s: -0.5}", ["cords.first.slip", "got -0.5"]),
    ("slip: s,\n          to: {disc: engine", "slip: [60, 45],\n          to: {disc: engine",
     ["cords.first.slip", "add up to 105 %"]),
    ("report:", "loads: {M: {type: driver, value: unknown}}\nreport:",
     ["cords.first.slip", "slips", "loads (M)"])])
def test_bad_slips_are_refused_with_their_line(tmp_path, old, new, words):
    path = tmp_path / "belt.yaml"
    path.write_text(text_with(SARTHAKS, old, new))
    code, _, err = run(["solve", path])
    assert code == 2 and "Traceback" not in err and "belt.yaml:" in err
    for word in words:
        assert word in err, (word, err)
