"""Trust, third round: Newton against the closed form on discs, belts and the figure check.

Each test failed before its fix; every number asserted comes from the file's header or from
a closed form written here."""
from __future__ import annotations

import csv
import io
import math
import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import run  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data", "trust3")


def _path(name):
    return os.path.join(DATA, name)


def _rows(out):
    """The CSV rows of a sweep as dicts of floats."""
    return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(io.StringIO(out))]


def _turn_gap(a, b):
    """|a - b| in degrees, modulo a full turn."""
    return abs((a - b + 180.0) % 360.0 - 180.0)


# --- whole turns of discs -----------------------------------------------------------------
def test_differential_pulley_newton_counts_the_upper_blocks_turns():
    """The hand pulls 1200 mm (yP from -800 to -2000): the upper block turns 1200 / R (more
    than a turn), the load rises 1200 (R - r) / (2 R) = 100 mm: yL = -900.00 mm."""
    R, r = 150.0, 125.0
    expected = -1000.0 + 1200.0 * (R - r) / (2 * R)
    for method in ("closed", "newton"):
        code, out, err = run(["solve", _path("differential-pulley-newton.yaml"),
                              "--method", method])
        assert code == 0, err
        assert f"yL  = {expected:10.2f} mm" in out, (method, out)
        assert "VR    =      12.00" in out                     # 2 R / (R - r)


def _epicyclic_exact(q):
    """Arm turn q / 6 and planet turn -q / 4 from the figure (q the sun's, deg): P = C + 20
    e^{-i q/4}, C = 30 e^{i (90 + q/6)} mm."""
    ta = math.radians(90 + q / 6)
    tp = math.radians(-q / 4)
    cx, cy = 30 * math.cos(ta), 30 * math.sin(ta)
    return {"arm_turn": (90 + q / 6) % 360, "planet_turn": (-q / 4) % 360,
            "xP": cx + 20 * math.cos(tp), "yP": cy + 20 * math.sin(tp)}


def test_epicyclic_newton_keeps_the_planets_turns_over_six_turns_of_the_sun():
    code, out, err = run(["sweep", _path("epicyclic_newton_sweep_turns.yaml"), "--method",
                          "newton", "--from", 0, "--to", 2160, "--step", 90, "--decimals", 3])
    assert code == 0 and not err, err
    rows = _rows(out)
    assert len(rows) == 25
    for row in rows:
        exact = _epicyclic_exact(row["q [deg]"])
        assert _turn_gap(row["arm_turn [deg]"], exact["arm_turn"]) <= 1.5e-3, row
        assert _turn_gap(row["planet_turn [deg]"], exact["planet_turn"]) <= 1.5e-3, row
        assert row["xP [mm]"] == pytest.approx(exact["xP"], abs=1.5e-3), row
        assert row["yP [mm]"] == pytest.approx(exact["yP"], abs=1.5e-3), row
        assert row["arm_turndot [rpm]"] == pytest.approx(60 / 6, abs=1e-3)
        assert row["planet_turndot [rpm]"] == pytest.approx(-60 / 4, abs=1e-3)


def test_crossed_belt_newton_solves_every_turn():
    """A crossed belt from a 100 mm pulley to a 50 mm one: n2 = -2 q at every q (before, q in
    [135, 225] deg was dropped as 'links short by 1750 mm' in a file with no links)."""
    code, out, err = run(["sweep", _path("crossed_belt_newton_sweep.yaml"), "--method", "newton",
                          "--from", 0, "--to", 720, "--step", 15, "--names", "n2,n2dot"])
    assert code == 0 and not err, err
    rows = _rows(out)
    assert len(rows) == 49
    for row in rows:
        assert _turn_gap(row["n2 [deg]"], (-2 * row["q [deg]"]) % 360) < 1e-9, row
        assert row["n2dot [rpm]"] == pytest.approx(-200.0, rel=1e-12)


def test_newton_sweep_that_cannot_assemble_names_its_closure_error_not_links(tmp_path):
    """A crank too long to turn round (Grashof: 100 + 150 > 200 + 111.8): both methods leave
    out q in [120, 240] deg; Newton's reason is its equations' closure error."""
    path = tmp_path / "rocker.yaml"
    path.write_text("""title: a crank that cannot turn round
units: {length: mm, angle: deg}
frame: {A: [0, 0], D: [200, 0]}
points: {B: [0, 100], C: [150, 100]}
links:
  AB: {points: [A, B], length: 100}
  BC: {points: [B, C], length: 150}
  CD: {points: [C, D], length: 111.8034}
driver: {angle: [A, B], value: 90, rate: 1}
quantities: {phi: {angle: [D, C]}}
report: {position: [phi]}
""", encoding="utf-8")
    code, out, err = run(["sweep", path, "--method", "newton", "--from", 0, "--to", 360,
                          "--steps", 12])
    assert code == 0
    assert "cannot assemble for q in [120, 240] deg" in err
    assert "(Newton), no convergence, closure error up to" in err
    assert "links short" not in err


# --- the figure check -----------------------------------------------------------------------
def test_newton_warns_of_a_figure_far_from_the_solved_position():
    """The coupler's shape angle has the wrong sign: E is drawn 120 mm from where it is
    solved; Newton warns as the closed form does."""
    warnings = {}
    for method in ("closed", "newton"):
        code, out, err = run(["solve", _path("newton_far_figure_no_warning.yaml"),
                              "--method", method])
        assert code == 0
        warnings[method] = [line for line in err.splitlines() if "warning" in line]
    assert len(warnings["newton"]) == 1
    assert "far from the figure" in warnings["newton"][0]
    assert "E by 120 mm" in warnings["newton"][0]
    assert warnings["newton"] == warnings["closed"]


# --- a redundant belt strand ----------------------------------------------------------------
def test_a_repeated_belt_strand_is_named():
    path = _path("belt-two-strands.yaml")
    for method in ("closed", "newton"):
        code, out, err = run(["solve", path, "--method", method])
        assert code == 3, err
        assert "key 'cords.top'" in err
        assert "joins the discs p1 and p2 as 'bottom' does" in err
        assert "check that every link" not in err


def test_one_strand_of_the_same_belt_solves(tmp_path):
    """Equal pulleys of an open belt turn together: th2dot = 10 deg/s."""
    with open(_path("belt-two-strands.yaml"), encoding="utf-8") as f:
        text = f.read()
    one = tmp_path / "one-strand.yaml"
    one.write_text("\n".join(line for line in text.splitlines() if "top:" not in line),
                   encoding="utf-8")
    for method in ("closed", "newton"):
        code, out, err = run(["solve", one, "--method", method])
        assert code == 0, err
        assert "th2dot =       10.0 deg/s" in out, out

