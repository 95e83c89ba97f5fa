"""Trust, third round: the command line, check, the Moodle boxes, parameter sweeps and
`make test`.  Each test failed before its fix; the files of tests/data/trust3/ say in their
header what linkcli printed and what is right."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import gc
import tracemalloc
import xml.etree.ElementTree as ET

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import run  # noqa: E402
from cloze_grammar import parse as parse_cloze  # noqa: E402
from linkcli.exports import moodle  # noqa: E402
from linkcli.input.source import load_file  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data", "trust3")
MECHANISMS = os.path.join(ROOT, "mechanisms")


def data(name):
    return os.path.join(DATA, name)


def _stand_in(mech) -> bytes:
    return b"\x89PNG\r\n\x1a\n"


def _boxes(path) -> dict:
    """{quantity name: its NUMERICAL box} of the quiz of ``path`` (the file's own digit),
    read back by the independent Cloze parser; each table row is name, words, box, unit."""
    root = ET.fromstring(moodle.export(load_file(path), None, figure=_stand_in))
    text = root.find("question/questiontext/text").text
    boxes = {}
    for row in text.split("<tr>")[1:]:
        name = row.split("<td>")[1].split("</td>")[0]
        boxes[name] = parse_cloze(row.split("<td>")[3].split("</td>")[0])[0]
    return boxes


def _scores(box, response: float) -> bool:
    """Whether Moodle gives ``response`` full marks: |r - a| <= tol for an answer at 100 %
    (the 1e-14 Moodle adds does not matter at these values)."""
    return any(abs(response - a.value) <= a.tolerance + 1e-9 for a in box.correct)


# --- angles one turn off ------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["crank-angle-key.yaml", "vib-equilibrium-angle-key.yaml"])
def test_check_accepts_a_key_one_turn_off(name):
    """The headers: -320 is 40 deg (the crank), -79.10 is 280.90 (the crank angle of the
    least piston velocity), -90 is 270 (a pendulum hanging): check passes every key."""
    code, out, err = run(["check", data(name)])
    assert code == 0, out + err
    assert "0 failed" in out.splitlines()[-1]


def test_moodle_boxes_score_the_angle_one_turn_off():
    crank = _boxes(data("crank-angle-key.yaml"))
    # the crank at 40 deg (the file's driver value): 40.00 and -320.00 both score
    assert _scores(crank["theta"], 40.0) and _scores(crank["theta"], -320.0)
    # the key's -79.10 for the crank angle computed as 280.90 (header), and 280.90 itself
    assert _scores(crank["zero_acc_2"], -79.10) and _scores(crank["zero_acc_2"], 280.90)
    assert not _scores(crank["zero_acc_2"], 79.10)
    pendulum = _boxes(data("vib-equilibrium-angle-key.yaml"))
    for name in ("phi_e", "theta_e"):          # hanging: 270 deg from +x, i.e. -90
        assert _scores(pendulum[name], 270.0) and _scores(pendulum[name], -90.0)
        assert not _scores(pendulum[name], 90.0)


def test_moodle_phase_of_half_a_turn_scores_either_sign():
    """An undamped system forced above its resonance lags by half a turn: -180 and +180
    deg are the same phase (polimi-2001-02-07: Omega above both natural frequencies)."""
    boxes = _boxes(os.path.join(MECHANISMS, "polimi-2001-02-07-vibration.yaml"))
    for name in ("phTheta", "phX"):
        assert _scores(boxes[name], -180.0) and _scores(boxes[name], 180.0), name


def test_an_amplitude_is_not_compared_modulo_a_turn():
    """An amplitude measures a size: 5 deg is not -355 deg."""
    boxes = _boxes(os.path.join(MECHANISMS, "polimi-2001-02-07-vibration.yaml"))
    box = boxes["Theta"]
    value = box.correct[0].value
    assert len(box.correct) == 1 and not _scores(box, value - 360.0)


# --- -o naming a folder -------------------------------------------------------------------------
@pytest.mark.parametrize("args", [
    ["export", os.path.join(MECHANISMS, "padova-2020-02.yaml"), "--to", "moodle", "--no-figure",
     "--force"],
    ["export", os.path.join(MECHANISMS, "padova-2020-07.yaml"), "--to", "markdown"],
    ["solve", os.path.join(MECHANISMS, "padova-2020-07.yaml")],
    ["schema"],
])
def test_output_naming_a_folder_is_refused_by_name(tmp_path, args):
    code, out, err = run(args + ["-o", tmp_path])
    assert code == 2, out + err
    assert f"{tmp_path}, key '-o': the output path is a folder (give the name of a file" in err
    assert "Is a directory" not in err and "Traceback" not in err


# --- draw --method newton -----------------------------------------------------------------------
def test_draw_with_newton_draws_a_class_three_group(tmp_path):
    """The closed form refuses the triad; Newton assembles it, as with --exam."""
    triad = os.path.join(MECHANISMS, "triad-class3.yaml")
    assert run(["draw", triad, "-o", tmp_path / "closed.png"])[0] == 3
    for extra in ([], ["--exam"]):
        out = tmp_path / f"newton{len(extra)}.png"
        code, _, err = run(["draw", triad, "--method", "newton", "-o", out] + extra)
        assert code == 0, err
        assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("extra", [[], ["--exam"]])
def test_draw_with_newton_refuses_a_vibration_problem_by_name(tmp_path, extra):
    path = os.path.join(MECHANISMS, "polimi-2001-09-18-vibration.yaml")
    code, _, err = run(["draw", path, "--method", "newton", "-o", tmp_path / "v.png"] + extra)
    assert code == 2
    assert "a vibration problem is solved at its static equilibrium" in err and "--method" in err


def test_sweep_vary_with_newton_refuses_a_vibration_problem_by_name():
    """As solve, draw and explain do (it ignored --method, printing the closed form's)."""
    path = os.path.join(MECHANISMS, "polimi-2001-09-18-vibration.yaml")
    code, out, err = run(["sweep", path, "--vary", "ks=50:150:2", "--method", "newton"])
    assert code == 2 and not out
    assert "a vibration problem is solved at its static equilibrium" in err


# --- explain --method newton --------------------------------------------------------------------
def test_explain_with_newton_lists_the_equations_it_solves():
    """The triad's four moving points B, C, D, E: eight unknowns, eight equations (two per
    point: the crank's tip fixed by q, the lengths BC, CD, FD, GE and E's place on CDE)."""
    triad = os.path.join(MECHANISMS, "triad-class3.yaml")
    code, out, err = run(["explain", triad, "--method", "newton"])
    assert code == 0, err
    assert "unknowns: x and y of the 4 moving points B, C, D, E (8)" in out
    assert "all 8 solved together" in out
    listed = [line for line in out.splitlines() if line.startswith("    ") and ". " in line]
    assert len(listed) == 8
    assert "closed form: not available: the structure does not decompose" in out
    assert "Statics by virtual work" in out
    assert run(["explain", triad])[0] == 3            # the closed form still refuses it


def test_explain_with_newton_counts_a_dyad_chain_too():
    path = os.path.join(MECHANISMS, "padova-2020-07.yaml")
    code, out, _ = run(["explain", path, "--method", "newton"])
    moving = len(load_file(path).data["points"])
    assert code == 0
    assert f"({2 * moving})" in out and f"all {2 * moving} solved together" in out
    assert "2 groups solved in order" in out


@pytest.mark.parametrize("args,key", [
    (["--method", "newton", "--pseudocode"], "--method"),
])
def test_explain_pseudocode_is_the_closed_forms(args, key):
    code, _, err = run(["explain", os.path.join(MECHANISMS, "padova-2020-07.yaml")] + args)
    assert code == 2 and f"key '{key}'" in err


def test_explain_with_newton_refuses_a_vibration_problem():
    path = os.path.join(MECHANISMS, "polimi-2001-09-18-vibration.yaml")
    code, _, err = run(["explain", path, "--method", "newton"])
    assert code == 2 and "static equilibrium" in err


# --- a mechanism with two inputs ----------------------------------------------------------------
def test_two_inputs_named_with_what_works():
    """Two degrees of freedom and one driver (x of B): the message says so and sends the
    file to 'drivers:', one per input, not to 'coordinates:'."""
    code, _, err = run(["solve", data("two_inputs_pinion_between_racks.yaml")])
    assert code == 3
    assert "2 degrees of freedom, not 1 (the one driver, x of B)" in err
    assert "declare one driver per input under 'drivers:'" in err
    assert "under 'coordinates:'" not in err


def test_following_the_drivers_hint_gives_the_books_answer(tmp_path):
    """The hint followed: B at 8 ft/s and C at -4 ft/s as two drivers give omega = -20 rad/s
    (20 clockwise) and v_A = 2 ft/s, the header's answer by hand."""
    with open(data("two_inputs_pinion_between_racks.yaml"), encoding="utf-8") as handle:
        text = handle.read()
    _assert_books_answer(tmp_path, text, "driver: {x: B, value: 0, rate: 8}",
                         "drivers: {xB: {x: B, value: 0, rate: 8}, xC: {x: C, value: 0, rate: -4}}")


def _assert_books_answer(tmp_path, text, old, new):
    """The pinion's file with ``old`` replaced by ``new`` (its two drivers) solves to the
    book's omega = -20 rad/s and v_A = 2 ft/s."""
    assert old in text
    path = tmp_path / "drivers.yaml"
    path.write_text(text.replace(old, new), encoding="utf-8")
    code, out, err = run(["solve", path, "--format", "csv", "--decimals", "6"])
    assert code == 0, err
    rows = dict(line.split(",")[:2] for line in out.splitlines()[1:])
    assert [float(rows["wdot"]), float(rows["xAdot"])] == pytest.approx([-20.0, 2.0], abs=1e-6)


def test_following_the_two_input_hint_gives_the_books_answer(tmp_path):
    """The hint: hold all inputs but one in the frame, solve once per input, add the
    velocities.  B at 8 ft/s with C held, then C at -4 ft/s with B held: omega = -20 rad/s
    (20 clockwise) and v_A = 2 ft/s, the header's answer by hand."""
    with open(data("two_inputs_pinion_between_racks.yaml"), encoding="utf-8") as handle:
        text = handle.read()
    hold_c = (text.replace("frame: {O: [0, 0]}", "frame: {O: [0, 0], C: [0, 0]}")
              .replace("  C: [0, 0]\n", "", 1)
              .replace("  rackC: {point: C, guide: {y: 0}}\n", "")
              .replace("on: {line: x, side: left, body: rackC}", "on: {line: x, side: left}"))
    hold_b = (text.replace("frame: {O: [0, 0]}", "frame: {O: [0, 0], B: [0, 0.6], B2: [1, 0.6]}")
              .replace("  B: [0, 0.6]\n", "", 1)
              .replace("  rackB: {point: B, guide: {y: 0.6}}\n", "")
              .replace("on: {line: x, side: right, body: rackB}", "on: {line: [B, B2], side: right}")
              .replace("driver: {x: B, value: 0, rate: 8}", "driver: {x: C, value: 0, rate: -4}"))
    total = np.zeros(2)
    for name, body in (("hold-c.yaml", hold_c), ("hold-b.yaml", hold_b)):
        path = tmp_path / name
        path.write_text(body, encoding="utf-8")
        code, out, err = run(["solve", path, "--format", "csv", "--decimals", "6"])
        assert code == 0, err
        rows = dict(line.split(",")[:2] for line in out.splitlines()[1:])
        total += [float(rows["wdot"]), float(rows["xAdot"])]
    assert total == pytest.approx([-20.0, 2.0], abs=1e-6)


def test_two_inputs_as_coordinates_says_what_coordinates_are(tmp_path):
    """'coordinates:' is a vibration problem's: the message sends the rates to 'drivers:',
    and the file with its coordinates written as drivers gives the book's answer."""
    code, _, err = run(["solve", data("two_inputs_pinion_between_racks_coordinates.yaml")])
    assert code == 2
    assert "a file with 'coordinates:' is a vibration problem" in err
    assert "or 'drivers:' instead of 'coordinates:'" in err
    with open(data("two_inputs_pinion_between_racks_coordinates.yaml"), encoding="utf-8") as f:
        text = f.read()
    _assert_books_answer(tmp_path, text, "coordinates:\n  xb: {x: B}\n  xc: {x: C}\n",
                         "drivers:\n  xb: {x: B, value: 0, rate: 8}\n"
                         "  xc: {x: C, value: 0, rate: -4}\n")


# --- sweep --vary: memory flat, rows streamed ---------------------------------------------------
def _vary_peak(count: int) -> int:
    """The peak of Python's allocations while `sweep --vary` writes ``count`` + 1 rows (a
    crank-slider's crank length: every value assembles)."""
    from linkcli import load
    from linkcli.runs import vary as vary_mod
    mech = load(os.path.join(MECHANISMS, "polimi-crank-slider.yaml")).model
    name, values = vary_mod.parse_vary(f"a=1:1.5:{count}")
    variation = vary_mod.Variation(mech, name, values, ["c", "cdot"])
    gc.collect()
    tracemalloc.start()
    try:
        vary_mod.write(variation, "csv", None, lambda text: None)
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def _growth() -> float:
    _vary_peak(20)                         # imports and first solve out of the measure
    return _vary_peak(400) / _vary_peak(100)


def test_sweep_vary_memory_does_not_grow_with_the_values():
    """Four times the values, not four times the memory (each value's variant of the file
    and its solver were kept: 415 MB at 2e4 values).  What is left grows by the cyclic
    garbage collector's timing (a mechanism and its solver refer to each other), 1.2 to 1.6
    times here; a cache that keeps every variant gives 3.8."""
    assert _growth() < 2.0


def test_the_memory_check_catches_a_cache_that_keeps_every_variant(monkeypatch):
    """Planted: the solvers' cache keeps every mechanism it saw (as a weakly keyed cache
    whose solvers hold their mechanism did): the growth is seen."""
    from linkcli.kinematics import solvers
    monkeypatch.setattr(solvers, "KEPT", 10 ** 9)
    assert _growth() > 3.0


def test_sweep_vary_is_solved_and_printed_a_block_at_a_time():
    """The first rows come before the last values are solved."""
    from linkcli import load
    from linkcli.runs.vary import Variation
    mech = load(os.path.join(MECHANISMS, "polimi-crank-slider.yaml")).model
    variation = Variation(mech, "a", np.linspace(1.0, 1.5, 30), ["c"], block=10)
    blocks = variation.blocks()
    first = next(blocks)
    assert first.q.size == 10 and variation.solved_rows == 10
    assert sum(b.count for b in blocks) == 20


# --- make test ----------------------------------------------------------------------------------
def _fake_venv(tmp_path, tests: int, keys: int):
    """A venv whose python (the test suite) and linkcli (the answer keys) exit as given,
    each recording its call."""
    bin_dir = tmp_path / "venv" / "bin"
    bin_dir.mkdir(parents=True)
    log = tmp_path / "calls"
    for tool, status in (("python", tests), ("linkcli", keys)):
        script = bin_dir / tool
        script.write_text(f"#!/bin/sh\necho {tool} \"$@\" >> {log}\nexit {status}\n")
        script.chmod(0o755)
    (tmp_path / "venv" / ".installed-test").touch()
    return tmp_path / "venv", log


@pytest.mark.skipif(shutil.which("make") is None, reason="make is not installed")
@pytest.mark.parametrize("tests,keys", [(1, 0), (0, 1), (0, 0), (2, 1)])
def test_make_test_checks_the_keys_whatever_the_tests_give(tmp_path, tests, keys):
    venv, log = _fake_venv(tmp_path, tests, keys)
    proc = subprocess.run(["make", "-s", "-C", ROOT, "test", f"VENV={venv}"],
                          capture_output=True, text=True, timeout=60)
    calls = log.read_text().splitlines()
    assert calls == ["python -m pytest -n auto", "linkcli check mechanisms/"]
    assert (proc.returncode == 0) == (tests == 0 and keys == 0), proc.stdout + proc.stderr
    summary = proc.stdout.splitlines()[-1]
    assert ("test suite passed" if not tests else f"test suite FAILED (exit {tests})") in summary
    assert ("answer keys passed" if not keys else f"answer keys FAILED (exit {keys})") in summary


def test_ci_runs_make_test():
    with open(os.path.join(ROOT, ".ci", "run"), encoding="utf-8") as handle:
        assert "\nmake test\n" in handle.read()
