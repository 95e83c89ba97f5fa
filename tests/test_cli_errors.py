"""Every bad input of issue 2 gives a short message naming the file, the key
(and line), exit code 2 for invalid input or 3 for an unsolvable mechanism,
and never a traceback."""
import math
import os
import subprocess
import sys

import pytest

from linkcli.cli import main

from closure import data_text

BASE = data_text("crank-slider-inclined.yaml")

TOGGLE = """title: four-bar at its toggle
frame:
  A: [0, 0]
  D: [250, 0]
points:
  B: [50, 0]
  C: [170, 0]
links:
  AB: {points: [A, B], length: 50}
  BC: {points: [B, C], length: 120}
  CD: {points: [C, D], length: 80}     # |DB| = 200 = BC + CD at q = 0
driver: {angle: [A, B], value: 0, rate: 10}
loads:
  M: {type: torque, on: AB, value: unknown}
  MC: {type: torque, on: CD, value: 1}
quantities:
  phi2: {angle: [B, C]}
report:
  position: [phi2]
  velocity: [phi2dot]
"""

DEAD = """title: crank-slider driven by the slider, at its dead point
frame:
  A: [0, 0]
points:
  B: [50, 0]
  S: [200, 0]
links:
  AB: {points: [A, B], length: 50}
  SB: {points: [S, B], length: 150}
sliders:
  SS: {point: S, guide: {y: 0}}
driver: {x: S, value: 200, rate: 10}
loads:
  Q: {type: driver, value: unknown}
  M: {type: torque, on: AB, value: 1}
report:
  statics: [Q]
"""


def _edit(text, old, new):
    assert old in text, old
    return text.replace(old, new)


def _run(tmp_path, capsys, text, name="mech.yaml", extra=()):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    code = main(["solve", str(path), *extra])
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    assert str(path) in err, err            # the message names the file
    assert err.startswith("linkcli: error:"), err
    assert len(err.strip().splitlines()) <= 4, err   # short
    return code, err


def _line_of(text, fragment):
    return next(i for i, line in enumerate(text.splitlines(), 1) if fragment in line)


@pytest.mark.parametrize("old, new", [
    ("  BC: {points: [B, C], length: 160}", "  BC: {points: [B, C], length: 160}}"),
    ("  BC: {points: [B, C], length: 160}", "   BC: {points: [B, C], length: 160}"),
])
def test_yaml_syntax_error(tmp_path, capsys, old, new):
    text = _edit(BASE, old, new)
    code, err = _run(tmp_path, capsys, text)
    assert code == 2
    assert f"mech.yaml:{_line_of(text, 'BC: {points')}: YAML syntax error" in err, err


def test_unknown_key(tmp_path, capsys):
    text = _edit(BASE, "AB: {points: [A, B], length: 50}", "AB: {points: [A, B], lenght: 50}")
    code, err = _run(tmp_path, capsys, text)
    assert code == 2
    assert f"mech.yaml:{_line_of(text, 'lenght')}, key 'links.AB.lenght'" in err, err
    assert "unknown key 'lenght'" in err and "length" in err   # the hint lists allowed keys


def test_unknown_section(tmp_path, capsys):
    text = BASE + "extra: 1\n"
    code, err = _run(tmp_path, capsys, text)
    assert code == 2
    assert f"mech.yaml:{_line_of(text, 'extra:')}, key 'extra'" in err, err


def test_missing_key(tmp_path, capsys):
    text = _edit(BASE, "driver: {angle: [A, B], value: 40,", "driver: {angle: [A, B],")
    code, err = _run(tmp_path, capsys, text)
    assert code == 2
    assert f"mech.yaml:{_line_of(text, 'driver:')}, key 'driver'" in err, err
    assert "missing key 'value'" in err


def test_missing_section(tmp_path, capsys):
    text = _edit(BASE, "driver: {angle: [A, B], value: 40, rate: -20, accel: 4}\n", "")
    code, err = _run(tmp_path, capsys, text)
    assert code == 2
    assert "missing key 'driver'" in err, err


def test_undefined_point(tmp_path, capsys):
    text = _edit(BASE, "BC: {points: [B, C], length: 160}", "BC: {points: [B, X], length: 160}")
    code, err = _run(tmp_path, capsys, text)
    assert code == 2
    assert f"mech.yaml:{_line_of(text, '[B, X]')}, key 'links.BC.points[1]'" in err, err
    assert "undefined point 'X'" in err


def test_undefined_link(tmp_path, capsys):
    text = _edit(BASE, "MA: {type: torque, on: AB, value: 5}",
                 "MA: {type: torque, on: XY, value: 5}")
    code, err = _run(tmp_path, capsys, text)
    assert code == 2
    assert f"mech.yaml:{_line_of(text, 'on: XY')}, key 'loads.MA.on'" in err, err
    assert "undefined link 'XY'" in err


@pytest.mark.parametrize("expr, word", [
    ("\"__import__('os')\"", "__import__"),
    ("\"__import__('os').system('touch PWNED')\"", "not allowed"),
    ("\"k.real\"", "Attribute"),
    ("\"radius * 2\"", "unknown name 'radius'"),
    ("\"9**9**9\"", "too large"),
])
def test_unsafe_or_malformed_expression(tmp_path, capsys, expr, word):
    text = _edit(BASE, "BC: {points: [B, C], length: 160}",
                 f"BC: {{points: [B, C], length: {expr}}}")
    text = text.replace("PWNED", str(tmp_path / "pwned"))
    code, err = _run(tmp_path, capsys, "k: 1\n" + text)
    assert code == 2
    assert not (tmp_path / "pwned").exists()
    line = _line_of("k: 1\n" + text, "BC: {points")
    assert f"mech.yaml:{line}, key 'links.BC.length'" in err, err
    assert word in err


def test_mobility_two(tmp_path, capsys):
    text = _edit(BASE, "  BC: {points: [B, C], length: 160}\n",
                 "  BC: {points: [B, C], length: 160}\n  CX: {points: [C, X], length: 50}\n")
    text = _edit(text, "  E: [197, 82]\n", "  E: [197, 82]\n  X: [200, 100]\n")
    code, err = _run(tmp_path, capsys, text)
    assert code == 3
    # bodies: frame, AB, BC, CX, SC; revolutes A, B, C (BC-CX, BC-SC: 2), E-free: 4; prismatic 1
    assert "2 degrees of freedom" in err
    assert "3(5 - 1) - 2*4 - 2*1 = 2" in err, err


def test_mobility_zero(tmp_path, capsys):
    text = _edit(BASE, "  A: [0, 0]\n", "  A: [0, 0]\n  F: [150, 150]\n")
    text = _edit(text, "  BC: {points: [B, C], length: 160}\n",
                 "  BC: {points: [B, C], length: 160}\n  CF: {points: [C, F], length: 120}\n")
    code, err = _run(tmp_path, capsys, text)
    assert code == 3
    assert "0 degrees of freedom" in err
    assert "3(5 - 1) - 2*5 - 2*1 = 0" in err, err


def test_cannot_assemble(tmp_path, capsys):
    text = _edit(BASE, "BC: {points: [B, C], length: 160}", "BC: {points: [B, C], length: 10}")
    code, err = _run(tmp_path, capsys, text)
    assert code == 3
    assert "cannot assemble" in err and "RRP" in err and "C from B" in err, err
    assert "q = 40 deg" in err
    # shortfall: distance of B from the guide line minus the rod length (mm)
    bx, by = 50 * math.cos(math.radians(40)), 50 * math.sin(math.radians(40))
    u = (math.cos(math.radians(20)), math.sin(math.radians(20)))
    dist = abs(u[0] * (by + 20) - u[1] * bx)
    assert f"fall short by {dist - 10:.4g} mm" in err, err


def test_singular_toggle(tmp_path, capsys):
    code, err = _run(tmp_path, capsys, TOGGLE)
    assert code == 3
    assert "singular" in err and "dyad RRR: C" in err and "q = 0 deg" in err, err
    assert "conditioning 0.00e+00" in err


def test_singular_dead_point(tmp_path, capsys):
    code, err = _run(tmp_path, capsys, DEAD)
    assert code == 3
    assert "singular" in err and "dyad RRR: B" in err and "q = 200 mm" in err, err
    assert "conditioning" in err


def test_no_unknown_load(tmp_path, capsys):
    text = _edit(BASE, "magnitude: unknown", "magnitude: 10")
    code, err = _run(tmp_path, capsys, text)
    assert code == 2
    assert f"mech.yaml:{_line_of(text, 'loads:')}, key 'loads'" in err, err
    assert "found 0" in err


def test_two_unknown_loads(tmp_path, capsys):
    text = _edit(BASE, "MA: {type: torque, on: AB, value: 5}",
                 "MA: {type: torque, on: AB, value: unknown}")
    code, err = _run(tmp_path, capsys, text)
    assert code == 2
    assert f"mech.yaml:{_line_of(text, 'loads:')}, key 'loads'" in err, err
    assert "found 2 (MA, FC)" in err


def test_file_not_found(tmp_path, capsys):
    path = str(tmp_path / "missing.yaml")
    code = main(["solve", path])
    out, err = capsys.readouterr()
    assert code == 2
    assert path in err and "cannot read file" in err
    assert "Traceback" not in out + err


@pytest.mark.parametrize("k", ["12", "-1", "10"])
def test_k_option_out_of_range(tmp_path, capsys, k):
    """One error, blamed on the option (not on the file, which is not read)."""
    path = tmp_path / "mech.yaml"
    path.write_text(BASE, encoding="utf-8")
    assert main(["solve", str(path), "--k", k]) == 2
    out, err = capsys.readouterr()
    assert (out, err) == ("", f"linkcli: error: key '--k': k must be a digit 0-9, got {k} "
                              "(k is the last digit of the matricola)\n")


def test_k_in_file_out_of_range(tmp_path, capsys):
    text = "k: 11\n" + BASE
    code, err = _run(tmp_path, capsys, text)
    assert code == 2
    assert "mech.yaml:1, key 'k'" in err and "0-9" in err, err


def test_valid_file_exits_zero(tmp_path, capsys):
    path = tmp_path / "ok.yaml"
    path.write_text(BASE, encoding="utf-8")
    assert main(["solve", str(path)]) == 0
    out, err = capsys.readouterr()
    assert err == "" and "FC" in out


def test_console_script_exit_code(tmp_path):
    """The installed entry point returns the same code, with no traceback."""
    path = tmp_path / "bad.yaml"
    path.write_text(TOGGLE, encoding="utf-8")
    proc = subprocess.run([sys.executable, "-c", "import sys; from linkcli.cli import entry; "
                           "sys.argv[0] = 'linkcli'; entry()", "solve", str(path)],
                          capture_output=True, text=True, timeout=60,
                          cwd=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    assert proc.returncode == 3
    assert "Traceback" not in proc.stderr and str(path) in proc.stderr
