"""Round trips over every shipped file with an answer key: what a course hands out
(a Moodle box, a batch row, a sweep's row) is what `linkcli solve` prints for the same
digit, driver value and parameters.

- Moodle: each box's value, as written, is solve's value at the box's decimals;
- batch: each digit's row is `solve --k K`, to the last bit (both JSON);
- sweep: the row at the file's driver value is solve's (a file with a driver);
- sweep --vary: the row at a parameter's own value is solve's, every answer.

Each comparison is a function returning the disagreements, and a permanent test plants a
defect (monkeypatch) and asserts that the comparison reports it.
"""
from __future__ import annotations

import glob
import json
import math
import os
import sys
import xml.etree.ElementTree as ET

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import run  # noqa: E402
from cloze_grammar import parse as parse_cloze  # noqa: E402
from linkcli import load  # noqa: E402
from linkcli.exports import moodle  # noqa: E402
from linkcli.input.source import load_file  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
METHOD = {"triad-class3.yaml": "newton"}      # a class-III group: the closed form refuses it
#: two values agree to rounding: |a - b| <= AGREE max(1, |a|, |b|), angles modulo a turn
AGREE = 1e-9


def _keyed(clutch=False) -> list:
    """The shipped files with an answer key (relative paths, as a user types them); a
    clutch problem (no quiz, no driver: docs/machines.md) only where ``clutch``."""
    out = []
    for path in sorted(glob.glob(os.path.join(ROOT, "mechanisms", "*.yaml"))):
        model = load(path).model
        if model.keys and (clutch or model.clutch is None):
            out.append(os.path.relpath(path, ROOT))
    return out


KEYED = _keyed()


def _path(name):
    return os.path.join(ROOT, name)


def _method(name) -> list:
    method = METHOD.get(os.path.basename(name))
    return ["--method", method] if method else []


def _json(args) -> dict:
    code, out, err = run(args)
    assert code == 0, f"{args}: {err}"
    return json.loads(out)


def _solved(name, *extra) -> dict:
    """solve's unrounded values (JSON): {name: value}, a point's x and y as xP, yP."""
    data = _json(["solve", _path(name), "--format", "json", *_method(name), *extra])
    values = dict(data["values"])
    for point, (x, y) in (data.get("points") or {}).items():
        values.setdefault("x" + point, x)
        values.setdefault("y" + point, y)
    return {"values": values, "units": data["units"]}


def _differ(a: float, b: float, unit: str = "") -> bool:
    gap = a - b
    if unit == "deg":
        gap = math.remainder(gap, 360.0)
    elif unit == "rad":
        gap = math.remainder(gap, 2 * math.pi)
    return not abs(gap) <= AGREE * max(1.0, abs(a), abs(b))


# --- Moodle ------------------------------------------------------------------------------------
def _stand_in(mech) -> bytes:
    return b"\x89PNG\r\n\x1a\n"


def moodle_mismatches(name) -> list:
    """The boxes of the file's quiz (its own digit) whose value, as written, is not solve's
    value printed at the box's decimals (`solve --format csv --decimals N`)."""
    doc = load_file(_path(name))
    places = load(_path(name)).model.report.get("decimals", 1)
    root = ET.fromstring(moodle.export(doc, None, figure=_stand_in,
                                       **({"method": METHOD[os.path.basename(name)]}
                                          if os.path.basename(name) in METHOD else {})))
    text = root.find("question/questiontext/text").text
    code, out, err = run(["solve", _path(name), "--format", "csv", "--decimals", places,
                          *_method(name)])
    assert code == 0, err
    printed = {row.split(",")[0]: row.split(",")[1] for row in out.splitlines()[1:]}
    bad = []
    for row in text.split("<tr>")[1:]:
        cells = row.split("<td>")
        quantity = cells[1].split("</td>")[0]
        box = parse_cloze(cells[3].split("</td>")[0])[0]
        written = box.correct[0].raw_text.split(":")[0]
        if quantity not in printed or float(written) != float(printed[quantity]) or \
                len(written.split(".")[-1] if "." in written else "") != places:
            bad.append(f"{name} {quantity}: box {written}, solve {printed.get(quantity)}")
    return bad


@pytest.mark.parametrize("name", KEYED)
def test_moodle_boxes_hold_what_solve_prints(name):
    assert not moodle_mismatches(name)


def test_the_moodle_round_trip_catches_a_box_off_by_its_last_decimal(monkeypatch):
    """Planted: the box's value written one unit of its last decimal high."""
    written = moodle.fmt
    monkeypatch.setattr(moodle, "fmt", lambda value, places: written(value + 10.0 ** -places,
                                                                      places))
    assert moodle_mismatches("mechanisms/padova-2020-07.yaml")


# --- batch -------------------------------------------------------------------------------------
def batch_mismatches(name, ks) -> list:
    """The values of batch's rows (JSON) that are not `solve --k K`'s, to the last bit."""
    rows = _json(["batch", _path(name), "--k", ",".join(map(str, ks)), "--format", "json"])
    bad = []
    for row in rows["rows"]:
        solved = _solved(name, "--k", row["k"])["values"]
        for column, value in row.items():
            if column != "k" and (column not in solved or value != solved[column]):
                bad.append(f"{name} k={row['k']} {column}: batch {value}, "
                           f"solve {solved.get(column)}")
    return bad


@pytest.mark.parametrize("name", KEYED)
def test_batch_rows_are_solve_for_each_digit(name):
    """Every digit of a file that sets k; one digit of the others (the file's data)."""
    ks = list(range(10)) if load_file(_path(name)).data.get("k") is not None else [0]
    if METHOD.get(os.path.basename(name)):
        pytest.skip("batch solves by the closed form, which refuses a class-III group")
    assert not batch_mismatches(name, ks)


def test_the_batch_round_trip_catches_a_row_of_another_digit(monkeypatch):
    """Planted: each row built for the next digit."""
    from linkcli.runs import batch
    built = batch.build
    monkeypatch.setattr(batch, "build", lambda doc, k: built(doc, (k + 1) % 10))
    assert batch_mismatches("mechanisms/padova-2020-02.yaml", [3, 4])


# --- sweep over the driver ---------------------------------------------------------------------
def _driver_value(name):
    """The file's driver value in its display unit, as the file writes it."""
    mech = load(_path(name)).model
    base = "angle" if mech.driver.kind == "angle" else "length"
    return mech.driver.value / mech.units.display(base, 0)[1]


def sweep_mismatches(name) -> list:
    """The answers of the sweep's row at the file's driver value that are not solve's."""
    q0 = _driver_value(name)
    step = 1e-3 * max(abs(q0), 1.0)
    swept = _json(["sweep", _path(name), "--from", repr(q0), "--to", repr(q0 + step),
                   "--steps", "1", "--format", "json", *_method(name)])
    solved = _solved(name)
    assert swept["q"][0] == q0
    bad = []
    for quantity, values in swept["values"].items():
        expected = q0 if quantity == "q" else solved["values"].get(quantity)
        if expected is None or _differ(values[0], expected, swept["units"][quantity]):
            bad.append(f"{name} {quantity}: sweep {values[0]}, solve {expected}")
    return bad


DRIVEN = [n for n in KEYED if load(_path(n)).model.elements is None
          and load(_path(n)).model.design is None]


@pytest.mark.parametrize("name", DRIVEN)
def test_a_sweeps_row_at_the_drivers_value_is_solve(name):
    assert not sweep_mismatches(name)


def test_the_sweep_round_trip_catches_a_driver_value_off(monkeypatch):
    """Planted: the sweep solves each row at q (1 + 1e-6), printing q."""
    from linkcli.runs.sweep.blocks import Sweeper
    made = Sweeper.__init__

    def shifted(self, *args, **kwargs):
        made(self, *args, **kwargs)
        self.q_factor *= 1 + 1e-6
    monkeypatch.setattr(Sweeper, "__init__", shifted)
    assert sweep_mismatches("mechanisms/padova-2020-07.yaml")


# --- sweep --vary ------------------------------------------------------------------------------
def _parameter(name):
    """(the file's first parameter that can be varied, its value as the file writes it)."""
    mech = load(_path(name)).model
    declared = load_file(_path(name)).data.get("params") or {}
    unknowns = mech.design.names if mech.design is not None else ()
    for param in declared:
        if param != "k" and param not in unknowns:
            return param, float(mech.params[param])
    return None, None


def vary_mismatches(name) -> list:
    """The answers of `sweep --vary` at the parameter's own value that are not solve's."""
    param, value = _parameter(name)
    other = value * 1.001 if value else 1e-3
    varied = _json(["sweep", _path(name), "--vary", f"{param}={value!r}:{other!r}:1",
                    "--format", "json", *_method(name)])
    solved = _solved(name)
    assert varied[param][0] == value
    bad = []
    for quantity, values in varied["values"].items():
        expected = solved["values"].get(quantity)
        if expected is None or _differ(values[0], expected, varied["units"][quantity]):
            bad.append(f"{name} {param}={value} {quantity}: vary {values[0]}, solve {expected}")
    return bad


PARAMETRIC = [n for n in _keyed(clutch=True) if _parameter(n)[0] is not None]


@pytest.mark.parametrize("name", PARAMETRIC)
def test_a_parameter_sweeps_row_at_its_value_is_solve(name):
    assert not vary_mismatches(name)


@pytest.mark.parametrize("name", ["mechanisms/padova-2020-02.yaml",
                                  "mechanisms/polimi-2001-09-18-vibration.yaml"])
def test_the_vary_round_trip_catches_a_parameter_off(monkeypatch, name):
    """Planted: each value's file rebuilt with the parameter 0.1 % off (a linkage, and a
    vibration problem, whose coefficients are swept all at once)."""
    from linkcli.input import document
    rebuilt = document.rebuild
    monkeypatch.setattr(document, "rebuild", lambda mech, params: rebuilt(
        mech, {n: v * 1.001 for n, v in params.items()}))
    assert vary_mismatches(name)
