"""`linkcli check` with tolerances: a key's `tolerance`, a value's `tolerances`, and bad input.

The mechanism is the 2020_07 exam, whose printed key (mechanisms/padova-2020-07.yaml) agrees
at the printed precision: the keys below move printed values away from the published ones by
known amounts, so that whether a tolerance covers the move follows from the published key
alone (a published value is within half a unit of its last digit of the computed one).
"""
import os
import re

import pytest

from conftest import MECHANISMS
from linkcli.runs.check import agrees, check_file, within
from linkcli.cli import main
from linkcli.model.mechanism import Tolerance

EXAM = os.path.join(MECHANISMS, "padova-2020-07.yaml")


def run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    return code, out, err


def exam_with_key(tmp_path, key: str) -> str:
    """The exam with its key replaced by ``key`` (YAML lines under 'keys:')."""
    text = open(EXAM).read()
    path = tmp_path / "exam.yaml"
    path.write_text(text[:text.index("keys:")] + "keys:\n" + key)
    return str(path)


PERCENT = Tolerance(0.02, True, "2%")
ABSOLUTE = Tolerance(0.05, False, "0.05")


def test_within_is_relative_to_the_printed_value_or_absolute_in_display_units():
    assert within(1.487, 1.47, PERCENT, None)          # 1.2 % off
    assert not within(1.51, 1.47, PERCENT, None)       # 2.7 % off
    assert within(-1.49, -1.47, PERCENT, None)         # of |printed|
    assert within(1.515, 1.47, ABSOLUTE, None) and not within(1.525, 1.47, ABSOLUTE, None)
    assert within(359.98, 0.0, ABSOLUTE, 360.0)        # angles modulo a full turn
    assert not within(359.98, 0.0, ABSOLUTE, None)
    assert not within(1.47, 1.47, None, None)          # no tolerance: never widened
    assert within(0.0, 0.0, PERCENT, None) and not within(1e-3, 0.0, PERCENT, None)


def test_without_a_tolerance_agreement_stays_at_the_printed_precision(tmp_path, capsys):
    path = exam_with_key(tmp_path, "  - values: {phi2: 340.0}\n")
    code, out, _ = run(capsys, "check", path)
    assert code == 1
    fail = [line for line in out.splitlines() if line.startswith("FAIL")]
    assert len(fail) == 1 and fail[0].startswith(f"FAIL {path} k=- phi2: printed 340.0, computed")
    assert "within" not in out


def test_a_key_tolerance_passes_a_value_off_its_printed_precision_and_says_so(tmp_path, capsys):
    # published phi2 = 341.0: 340.0 is 1.0 +- 0.05 deg off, 0.29 % of 340
    path = exam_with_key(tmp_path, "  - tolerance: 0.5%\n    values: {phi1: 28.9, phi2: 340.0}\n")
    code, out, _ = run(capsys, "check", "-v", path)
    assert code == 0
    lines = out.splitlines()
    assert f"ok {path} k=- phi1: 28.9" in lines            # at the printed precision: as before
    assert any(re.fullmatch(rf"ok {re.escape(path)} k=- phi2: 340\.0 \(computed 34[01]\.\d\d, "
                            r"within 0\.5%\)", line) for line in lines), out
    assert f"{path}: 2 passed (1 within tolerance), 0 failed" in lines
    assert lines[-1] == "2 passed, 0 failed"
    (report,) = [check_file(path)]
    outcome = next(o for o in report.outcomes if o.name == "phi2")
    assert outcome.status == "pass" and outcome.within and outcome.tolerance == "0.5%"
    plain = next(o for o in report.outcomes if o.name == "phi1")
    assert plain.status == "pass" and not plain.within and plain.tolerance == "0.5%"


def test_a_value_outside_its_tolerance_fails_and_names_the_tolerance(tmp_path, capsys):
    path = exam_with_key(tmp_path, "  - tolerance: 0.2%\n    values: {phi2: 340.0}\n")
    code, out, _ = run(capsys, "check", path)
    assert code == 1
    fail = [line for line in out.splitlines() if line.startswith("FAIL")]
    assert len(fail) == 1 and fail[0].endswith("(not within 0.2%)"), fail


def test_a_value_of_its_own_overrides_the_key_tolerance(tmp_path, capsys):
    # published xE = -46.4 mm: -47.0 is 0.6 +- 0.05 mm off; phi2 as above
    key = ("  - tolerance: 0.2%\n    tolerances: {xE: 1}\n"
           "    values: {xE: -47.0, phi2: 340.0}\n")
    code, out, _ = run(capsys, "check", "-v", exam_with_key(tmp_path, key))
    assert code == 1
    assert re.search(r"ok \S+ k=- xE: -47\.0 \(computed -46\.\d\d, within 1 mm\)", out), out
    assert re.search(r"FAIL \S+ k=- phi2: printed 340\.0, computed 341\.0 \(not within 0\.2%\)",
                     out), out


def test_an_absolute_tolerance_is_in_the_display_unit_and_fails_with_it(tmp_path, capsys):
    key = "  - values: {xE: -47.0}\n    tolerances: {xE: 0.5}\n"
    code, out, _ = run(capsys, "check", exam_with_key(tmp_path, key))
    assert code == 1 and "(not within 0.5 mm)" in out


def test_an_angle_within_its_tolerance_modulo_a_turn(tmp_path, capsys):
    # published phi2 = 341.0 deg, printed here as -18.0 (= 342.0)
    key = "  - values: {phi2: -18.0}\n    tolerance: 1.5\n"
    code, out, _ = run(capsys, "check", "-v", exam_with_key(tmp_path, key))
    assert code == 0 and "within 1.5 deg)" in out


@pytest.mark.parametrize("tolerance, ok", [("1%", True), ("0.5%", False)])
def test_a_point_uses_the_tolerance_on_each_coordinate(tmp_path, capsys, tolerance, ok):
    # published D = (136.6, 129.0): x moved by 1.0 +- 0.05 mm (0.73 % of 137.6)
    key = f"  - values: {{D: [137.6, 129.0], B: [113.8, 62.8]}}\n    tolerance: {tolerance}\n"
    code, out, _ = run(capsys, "check", "-v", exam_with_key(tmp_path, key))
    assert code == (0 if ok else 1)
    if ok:
        assert re.search(r"ok \S+ k=- D: \(137\.6, 129\.0\) \(computed \(136\.\d\d, 12[89]\.\d\d\), "
                         r"within 1%\)", out), out
        assert re.search(r"ok \S+ k=- B: \(113\.8, 62\.8\)$", out, re.M), out
    else:
        assert re.search(r"FAIL \S+ k=- D: printed \(137\.6, 129\.0\), computed \(136\.\d, "
                         r"12[89]\.\d\) \(not within 0\.5%\)", out), out


def test_a_known_key_problem_stays_known_whatever_the_tolerance(tmp_path, capsys):
    key = ("  - tolerance: 50%\n    values: {phi2: 161.0}\n"
           "    wrong: {phi2: 'the angle of C to B'}\n")
    code, out, _ = run(capsys, "check", exam_with_key(tmp_path, key))
    assert code == 0 and "KNOWN" in out and "1 known key problems" in out
    assert out.strip().splitlines()[-1] == "0 passed, 0 failed"


def test_a_percentage_may_be_written_with_a_space(tmp_path):
    report = check_file(exam_with_key(tmp_path, "  - tolerance: 0.5 %\n    values: {phi2: 340.0}\n"))
    assert report.error is None and report.outcomes[0].tolerance == "0.5%"


@pytest.mark.parametrize("line, message", [
    ("    tolerance: two percent\n", "keys[0].tolerance': a tolerance is a number (absolute, in "
     "the value's display unit) or a percentage, got 'two percent' (write e.g. 'tolerance: 2%'"),
    ("    tolerance: -2%\n", "keys[0].tolerance': a tolerance is a number"),
    ("    tolerance: 2e1%\n", "keys[0].tolerance': a tolerance is a number"),
    ("    tolerance: true\n", "keys[0].tolerance': a tolerance is a number"),
    ("    tolerance: [2]\n", "keys[0].tolerance': a tolerance is a number"),
    ("    tolerance: -0.5\n", "keys[0].tolerance': a tolerance is at least 0, got -0.5"),
    ("    tolerance: .inf\n", "keys[0].tolerance'"),
    ("    tolerances: {zz: 2%}\n", "keys[0].tolerances.zz': 'zz' has no printed value in this key"),
    ("    tolerances: {phi2: 2 percent}\n", "keys[0].tolerances.phi2': a tolerance is a number"),
    ("    tolerances: [2%]\n", "keys[0].tolerances': expected a mapping"),
])
def test_a_bad_tolerance_is_invalid_input_with_file_line_and_key(tmp_path, capsys, line, message):
    path = exam_with_key(tmp_path, "  - values: {phi2: 341.0}\n" + line)
    code, _, err = run(capsys, "solve", path)
    assert code == 2
    assert f"{path}:" in err and message in err, err
    code, out, _ = run(capsys, "validate", path)
    assert code == 2 and message in out


def test_the_printed_precision_rule_is_unchanged():
    assert agrees(1.474, 1.47, 2, None) and not agrees(1.476, 1.47, 2, None)
