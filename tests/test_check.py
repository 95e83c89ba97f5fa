"""`linkcli check` and `linkcli batch`: answer keys, known key problems, one row per k."""
import csv
import io
import os

import pytest

from conftest import MECHANISMS
from linkcli.runs.check import agrees
from linkcli.cli import main
from linkcli.input.source import load_file

EXAM = os.path.join(MECHANISMS, "padova-2020-02.yaml")


def run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    return code, out, err


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def with_key(values: str, wrong: str = "") -> str:
    """The 2020_07 exam with its key replaced by ``values`` (and ``wrong``)."""
    text = open(os.path.join(MECHANISMS, "padova-2020-07.yaml")).read()
    head = text[:text.index("keys:")]
    return head + "keys:\n  - values:\n" + values + ("    wrong:\n" + wrong if wrong else "")


def test_agreement_is_at_the_printed_precision():
    assert agrees(28.949, 28.9, 1, None)
    assert not agrees(28.951, 28.9, 1, None)
    assert agrees(2.34, 2.3, 1, None) and not agrees(2.36, 2.3, 1, None)
    assert agrees(0.3324, 0.332, 3, None) and not agrees(0.3326, 0.332, 3, None)
    assert agrees(359.97, 0.0, 1, 360.0)          # angles modulo a full turn
    assert agrees(-30.0, 330.0, 1, 360.0)
    assert not agrees(359.97, 0.0, 1, None)


def test_every_shipped_key_passes_and_the_count_is_over_200(capsys):
    code, out, _ = run(capsys, "check", MECHANISMS)
    assert code == 0
    last = out.strip().splitlines()[-1]
    passed, failed = (int(part.split()[0]) for part in last.split(", "))
    assert failed == 0 and passed > 200, last
    assert "files without key" in out and "known key problems" in out


def test_a_wrong_value_fails_with_file_k_quantity_printed_and_computed(tmp_path, capsys):
    path = write(tmp_path, "exam.yaml", with_key("      phi1: 28.9\n      phi2: 341.2\n"))
    code, out, _ = run(capsys, "check", path)
    assert code == 1
    fail = [line for line in out.splitlines() if line.startswith("FAIL")]
    assert fail == [f"FAIL {path} k=- phi2: printed 341.2, computed 341.0"]
    assert out.strip().splitlines()[-1] == "1 passed, 1 failed"


def test_check_as_json_lists_every_value_and_the_totals_of_the_text(tmp_path, capsys):
    import json
    bad = write(tmp_path, "exam.yaml", with_key("      phi1: 28.9\n      phi2: 341.2\n"))
    known = write(tmp_path, "known.yaml", with_key("      phi1: 28.9\n      phi2: 161.0\n",
                                                   "      phi2: 'the angle of C to B'\n"))
    code, out, _ = run(capsys, "check", bad, known, "--format", "json")
    assert code == 1
    data = json.loads(out)
    values = {(f["file"], v["name"]): v for f in data["files"] for v in f["values"]}
    assert values[(bad, "phi2")]["status"] == "fail"
    assert values[(bad, "phi2")]["printed"] == "341.2"
    assert values[(bad, "phi2")]["computed"] == "341.0"
    assert values[(known, "phi2")]["status"] == "known"
    assert values[(known, "phi2")]["reason"] == "the angle of C to B"
    assert (data["passed"], data["failed"], data["known"], data["ok"]) == (2, 1, 1, False)
    code, text, _ = run(capsys, "check", bad, known)
    assert text.strip().splitlines()[-1] == "2 passed, 1 failed"
    code, out, _ = run(capsys, "check", known, "--format", "json")
    assert code == 0 and json.loads(out)["ok"] is True


def test_a_known_key_problem_is_counted_apart_and_never_fails(tmp_path, capsys):
    path = write(tmp_path, "exam.yaml", with_key("      phi1: 28.9\n      phi2: 161.0\n",
                                                 "      phi2: 'the angle of C to B'\n"))
    code, out, _ = run(capsys, "check", path)
    assert code == 0
    assert "KNOWN" in out and "printed 161.0, computed 341.0 (the angle of C to B)" in out
    assert "1 known key problems" in out
    assert out.strip().splitlines()[-1] == "1 passed, 0 failed"


def test_an_unreadable_printed_value_marked_wrong_is_kept_as_printed(tmp_path, capsys):
    path = write(tmp_path, "exam.yaml", with_key("      phi1: 28.9\n      phi2: '341,0 (garbled)'\n",
                                                 "      phi2: 'garbled line'\n"))
    code, out, _ = run(capsys, "check", path)
    assert code == 0 and "printed 341,0 (garbled), computed 341.0" in out


def test_an_unreadable_printed_value_not_marked_is_invalid_input(tmp_path, capsys):
    path = write(tmp_path, "exam.yaml", with_key("      phi1: 28.9x\n"))
    code, out, err = run(capsys, "solve", path)
    assert code == 2 and "keys[0].values.phi1" in err and "cannot read printed value" in err


def test_a_key_for_an_undefined_quantity_is_invalid_input(tmp_path, capsys):
    path = write(tmp_path, "exam.yaml", with_key("      phi9: 28.9\n"))
    code, _, err = run(capsys, "solve", path)
    assert code == 2 and "'phi9'" in err and "does not define" in err


def test_a_file_without_key_is_reported_as_no_key_not_passed(tmp_path, capsys):
    text = open(os.path.join(MECHANISMS, "padova-2020-07.yaml")).read()
    path = write(tmp_path, "nokey.yaml", text[:text.index("keys:")])
    code, out, _ = run(capsys, "check", path)
    assert f"{path}: no key" in out
    assert out.strip().splitlines()[-1] == "0 passed, 0 failed"
    assert "1 files without key" in out


def test_a_key_with_k_outside_0_9_is_refused(tmp_path, capsys):
    path = write(tmp_path, "exam.yaml", with_key("      phi1: 28.9\n").replace(
        "  - values:", "  - k: 12\n    values:"))
    code, _, err = run(capsys, "check", path)
    assert code == 1 and "k must be a digit 0-9" in _ + err


@pytest.mark.parametrize("ks, expected", [("0-9", list(range(10))), ("1,3,5", [1, 3, 5]),
                                          ("7", [7]), ("0-2,8", [0, 1, 2, 8])])
def test_batch_prints_one_row_per_digit(capsys, ks, expected):
    code, out, _ = run(capsys, "batch", EXAM, "--k", ks, "--format", "csv")
    assert code == 0
    rows = list(csv.reader(io.StringIO(out)))
    assert [int(r[0]) for r in rows[1:]] == expected


def test_batch_row_of_the_printed_digit_equals_the_printed_key(capsys):
    """The k = 5 row against the key printed in the exam (stored in the file)."""
    code, out, _ = run(capsys, "batch", EXAM, "--k", "0-9", "--format", "csv")
    assert code == 0
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == 10
    row = next(r for r in rows if r["k"] == "5")
    doc = load_file(EXAM)
    key = next(k for k in doc.data["keys"] if k.get("k") == 5)
    compared = 0
    for name, printed in key["values"].items():
        column = next((c for c in row if c.split(" [")[0] == name), None)
        if column is None or isinstance(printed, list):
            continue
        assert agrees(float(row[column]), float(printed), 1, 360.0 if "phi" in name and
                      "dot" not in name else None), (name, row[column], printed)
        compared += 1
    assert compared >= 10


def test_batch_data_follow_k(capsys):
    """q = 200 + 10k and Fx = -(200 + 50k) (the exam's formulas)."""
    code, out, _ = run(capsys, "batch", EXAM, "--k", "0-9", "--format", "csv")
    assert code == 0
    for row in csv.DictReader(io.StringIO(out)):
        k = int(row["k"])
        assert float(row["a1 [mm]"]) == pytest.approx(200 + 10 * k)
        assert float(row["Fx [N]"]) == pytest.approx(-(200 + 50 * k))


@pytest.mark.parametrize("ks", ["10", "0-12", "a-b", "-1", "5-3"])
def test_batch_refuses_digits_outside_0_9(capsys, ks):
    code, _, err = run(capsys, "batch", EXAM, "--k", ks)
    assert code == 2 and "--k" in err
