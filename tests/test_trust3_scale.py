"""The geometry's range and the figure's branch: lengths a double cannot carry through the
solvers are refused by name, a regular position at any carried scale solves (a toggle is a
toggle at every scale), and the branch that closes is judged at the file's driver value.

The numbers asserted come from the files' headers or from closed forms written here."""
from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from tests.cli_helpers import run

DATA = Path(__file__).parent / "data" / "trust3"

CRANK_SLIDER = """title: "centred crank-slider at scale {s}"
units: {{length: m, angle: deg}}
params: {{s: {s}, a: 1*s, b: {b}*s}}
frame: {{O: [0, 0]}}
points: {{A: [0.7*s, 0.7*s], B: [1.9*s, 0]}}
links:
  OA: {{points: [O, A], length: a}}
  AB: {{points: [A, B], length: b}}
sliders: {{B: {{point: B, guide: {{y: 0}}}}}}
driver: {{angle: [O, A], value: 45, rate: 1}}
quantities:
  c: {{x: B}}
  r: {{expr: "c/a"}}
report:
  position: [c, r]
  velocity: [cdot]
"""


def crank_slider(tmp_path, s, b="sqrt(2)"):
    path = tmp_path / f"crank-slider-{s}.yaml"
    path.write_text(CRANK_SLIDER.format(s=s, b=b))
    return path


def solve_json(path, *options):
    code, out, err = run(["solve", path, "--format", "json", *options])
    return code, (json.loads(out) if code == 0 else None), err


# --- lengths beyond the range ---------------------------------------------------------------
def test_huge_crank_is_refused_by_name():
    """A crank of 1e200 m: its square overflows; the file is refused at the key that gives
    it, with the length, not assembled."""
    code, out, err = run(["solve", DATA / "huge-crank-assembles.yaml"])
    assert code == 2, err
    assert out == ""
    assert "links.OA.length" in err and "1e+200 m" in err
    assert "huge-crank-assembles.yaml:12" in err
    assert "1e+75 m" in err                    # the bound it exceeds


def test_huge_crank_within_range_falls_short(tmp_path):
    """The same file at a = 1e74 m is carried: the rod (sqrt 2 m) cannot reach the guide
    from A at a sin 45: the shortfall a sin 45 - sqrt 2 is named (4 digits)."""
    text = (DATA / "huge-crank-assembles.yaml").read_text().replace("a: 1e200", "a: 1e74")
    path = tmp_path / "crank-1e74.yaml"
    path.write_text(text)
    code, out, err = run(["solve", path])
    assert code == 3, err
    short = 1e74 * math.sin(math.radians(45)) - math.sqrt(2)
    assert f"the links fall short by {short:.4g} m" in err


@pytest.mark.parametrize("key, text", [
    ("points.B[0]", "points: {A: [0.7, 0.7], B: [1e76, 0]}"),
    ("sliders.B.guide.y", "sliders: {B: {point: B, guide: {y: 1e300}}}"),
])
def test_any_length_beyond_range_is_refused(tmp_path, key, text):
    """Coordinates and guides' offsets are lengths too: each beyond 1e75 m is named."""
    base = (DATA / "huge-crank-assembles.yaml").read_text().replace("a: 1e200", "a: 1")
    field = text.split(":")[0]
    lines = [text if line.startswith(field + ":") else line for line in base.splitlines()]
    path = tmp_path / "beyond.yaml"
    path.write_text("\n".join(lines) + "\n")
    code, _, err = run(["solve", path])
    assert code == 2, err
    assert f"key '{key}'" in err and "beyond the largest" in err


def test_range_in_the_files_unit(tmp_path):
    """The bound is in metres whatever the file's unit: 1e77 mm (1e74 m) is carried."""
    text = (DATA / "huge-crank-assembles.yaml").read_text().replace(
        "length: m", "length: mm").replace("a: 1e200", "a: 1e77")
    path = tmp_path / "mm.yaml"
    path.write_text(text)
    code, _, err = run(["solve", path])
    assert code == 3 and "fall short by 7.071e+76 mm" in err, err


# --- the smallest scale ----------------------------------------------------------------------
def test_tiny_scale_is_refused_by_name_not_called_a_toggle():
    code, out, err = run(["solve", DATA / "tiny-scale-singular.yaml"])
    assert code == 2, err
    assert "singular position" not in err and "toggle or dead point" not in err
    assert "1.9e-200 m" in err and "below the smallest size" in err
    assert "key 'points.B[0]'" in err           # the largest length the file gives


@pytest.mark.parametrize("s", ["1e-74", "1e-40", "1e-3", "1", "1e40", "1e74"])
@pytest.mark.parametrize("method", ["closed", "newton"])
def test_regular_position_solves_at_every_carried_scale(tmp_path, s, method):
    """c/a = cos 45 + sqrt(2 - sin^2 45) = 1.9319 at every scale the solvers carry, and
    c' = -a (sin 45 + sin 45 cos 45 / sqrt(2 - sin^2 45)) per unit rate (rad/s)."""
    code, sheet, err = solve_json(crank_slider(tmp_path, s), "--method", method)
    assert code == 0, err
    h = math.sin(math.radians(45))
    ratio = math.cos(math.radians(45)) + math.sqrt(2 - h * h)
    rate = -float(s) * (h + h * math.cos(math.radians(45)) / math.sqrt(2 - h * h))
    values = sheet["values"]
    assert values["r"] == pytest.approx(ratio, rel=1e-9)
    assert values["cdot"] == pytest.approx(rate * math.pi / 180, rel=1e-9)


@pytest.mark.parametrize("s", ["1e-74", "1", "1e74"])
def test_toggle_is_a_toggle_at_every_scale(tmp_path, s):
    """The rod b = a sin 45 reaches the guide perpendicularly at 45 deg: a toggle at every
    scale (the test of zero is relative to the mechanism's size, not in metres)."""
    code, _, err = run(["solve", crank_slider(tmp_path, s, b="sqrt(2)/2")])
    assert code == 3, err
    assert "singular position" in err


def test_planted_absolute_threshold_is_caught(tmp_path, monkeypatch):
    """A test of zero in metres (a discriminant compared with a fixed 1e-24 m^2) calls the
    regular position at scale 1e-20 a toggle: the scale test above would fail."""
    from linkcli.kinematics import dyads
    original, clear = dyads.negligible, dyads._clear
    monkeypatch.setattr(dyads, "_clear", lambda lowest, bound: False)
    monkeypatch.setattr(dyads, "negligible", lambda value, scale: abs(value) < 1e-24)
    code, _, err = run(["solve", crank_slider(tmp_path, "1e-20")])
    assert code == 3 and "singular position" in err
    monkeypatch.setattr(dyads, "negligible", original)
    monkeypatch.setattr(dyads, "_clear", clear)
    code, _, err = run(["solve", crank_slider(tmp_path, "1e-20")])
    assert code == 0, err


# --- the branch judged at the file's driver value --------------------------------------------
def test_branch_judged_at_the_files_driver_value():
    """The header: at the file's driver value the nearer B closes; Q = 4.9817 kN (an
    independent solver and Newton), not -0.13 kN, and no warning of a forced branch."""
    path = DATA / "branch-decided-at-the-figures-driver.yaml"
    for method in ("closed", "newton"):
        code, sheet, err = solve_json(path, "--method", method)
        assert code == 0, err
        assert round(sheet["values"]["Q"], 4) == 4.9817
        assert "farther from the figure" not in err


def test_branch_still_forced_where_the_nearer_cannot_close(tmp_path):
    """At the figure's own driver value (|AB| = 0.053651 m measured on the sketch, the
    header) the nearer B cannot close E: the farther branch is taken and said so."""
    path = DATA / "branch-decided-at-the-figures-driver.yaml"
    text = path.read_text().replace("value: 0.05097189596724092", "value: 0.053651")
    moved = tmp_path / "at-figure.yaml"
    moved.write_text(text)
    code, _, err = run(["solve", moved])
    assert code == 0, err
    assert "farther from the figure" in err
