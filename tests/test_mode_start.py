"""A free vibration started in a mode (docs/vibrations.md, "What books ask"): two masses in a
chain, M = diag(2, 1) kg, K = [[3000, -1000], [-1000, 1000]] N/m, whose modes by hand are
omega^2 = 500 (u = [1, 2]) and 2000 (u = [1, -1]).  Released from rest in mode k with x2 = a,
the motion is x(t) = a u_k / u_2k cos(omega_k t): the other modal coordinate u_j^T M x stays
0, and the springs' largest forces are k times the elongations' amplitudes."""
from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

import linkcli

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import run  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FILE = os.path.join(ROOT, "docs", "examples", "two-masses-mode.yaml")
M = np.diag([2.0, 1.0])
MODES = {1: (math.sqrt(500.0), np.array([1.0, 2.0])), 2: (math.sqrt(2000.0),
                                                          np.array([1.0, -1.0]))}
TIMES = (0.0, 0.013, 0.05, 0.31)


def started(mode, amplitude, coordinate="x2"):
    text = open(FILE, encoding="utf-8").read()
    old = "initial: {mode: 2, x2: 10}"
    assert old in text
    times = "\n".join(f"  y{c}{i}: {{free_response: {c}, time: {t}}}"
                      for i, t in enumerate(TIMES) for c in ("x1", "x2"))
    text = text.replace(old, f"initial: {{mode: {mode}, {coordinate}: {amplitude}}}")
    text = text.replace("quantities:\n", "quantities:\n" + times + "\n  N1m: {largest: "
                        "{spring: s1}}\n  x2m: {largest: x2}\n")
    names = [f"y{c}{i}" for i in range(len(TIMES)) for c in ("x1", "x2")]
    return linkcli.loads(text).solve(names=names + ["N1m", "N2m", "x1m", "x2m"]).values


@pytest.mark.parametrize("mode", [1, 2])
@pytest.mark.parametrize("amplitude, coordinate", [(10, "x2"), (-4, "x1"), (7.5, "x1")])
def test_the_motion_stays_in_the_mode(mode, amplitude, coordinate):
    values = started(mode, amplitude, coordinate)
    omega, shape = MODES[mode]
    other = MODES[3 - mode][1]
    i = 0 if coordinate == "x1" else 1
    x0 = amplitude * shape / shape[i]                               # mm
    for n, t in enumerate(TIMES):
        x = np.array([float(values[f"yx1{n}"]), float(values[f"yx2{n}"])])
        assert x == pytest.approx(x0 * math.cos(omega * t), abs=1e-9 * abs(amplitude))
        assert other @ M @ x == pytest.approx(0.0, abs=1e-9 * abs(amplitude))
    # the largest offsets and spring forces: k times the elongations' amplitudes (N, mm)
    assert float(values["x1m"]) == pytest.approx(abs(x0[0]), rel=1e-9)
    assert float(values["x2m"]) == pytest.approx(abs(x0[1]), rel=1e-9)
    assert abs(float(values["N1m"])) == pytest.approx(2000 * abs(x0[0]) / 1000, rel=1e-9)
    assert abs(float(values["N2m"])) == pytest.approx(1000 * abs(x0[1] - x0[0]) / 1000,
                                                      rel=1e-9)


def test_the_shipped_example_vibrates_in_its_second_mode():
    values = linkcli.load(FILE).solve().values
    assert float(values["u2"]) == pytest.approx(-1.0, rel=1e-12)
    assert float(values["N2m"]) == pytest.approx(1000 * 0.020, rel=1e-9)   # 20 mm stretch
    assert float(values["x1t"]) == pytest.approx(-10 * math.cos(math.sqrt(2000) * 0.05),
                                                 rel=1e-9)


@pytest.mark.parametrize("start, words", [
    ("{mode: 3, x2: 10}", ["initial.mode", "numbered 1-2", "got 3"]),
    ("{mode: 2, x2_dot: 10}", ["initial", "one coordinate"]),
    ("{mode: 2, x1: 1, x2: 10}", ["initial", "one coordinate"]),
    ("{mode: 2, x2: 0}", ["initial.x2", "not 0"]),
    ("{mode: 2, x3: 10}", ["initial.x3", "undefined coordinate"])])
def test_bad_starts_are_refused_with_their_line(tmp_path, start, words):
    path = tmp_path / "mode.yaml"
    path.write_text(open(FILE, encoding="utf-8").read().replace("{mode: 2, x2: 10}", start))
    code, _, err = run(["solve", path])
    assert code == 2 and "Traceback" not in err and "mode.yaml:" in err
    for word in words:
        assert word in err, (word, err)
