"""``export --to moodle --no-given`` leaves out exactly the boxes whose value the question
states as data, and the count line says how many there are.

The data are taken here from the file's driver and loads (the driver's value, rate and
acceleration in display units, each known load and its components), the boxes from the
exported questions' tables; nothing is taken from moodle.py's own choice of boxes."""
from __future__ import annotations

import math
import os
import re
import sys

import pytest

sys.path.insert(0, os.path.dirname(__file__))

from quizzes import SHIPPED, Parts, export, html_of, names, questions  # noqa: E402
import xml.etree.ElementTree as ET  # noqa: E402
from cli_helpers import run  # noqa: E402
from linkcli.exports import moodle  # noqa: E402
from linkcli.input.document import build  # noqa: E402
from linkcli.input.source import load_file  # noqa: E402

KEYED = [p for p in SHIPPED if build(load_file(p), None).keys]
FIRST = re.compile(r"\{(\d+):NUMERICAL:=([^:~}]+):")


def _rate(name, quantities):
    """(base, order) of a report name: NAMEddot, NAMEdot or NAME of a defined quantity."""
    for suffix, order in (("ddot", 2), ("dot", 1)):
        if name.endswith(suffix) and name[:-len(suffix)] in quantities:
            return name[:-len(suffix)], order
    return name, 0


def data_of(mech) -> dict:
    """{report name: the datum the statement gives for it (display units)}: the driver's
    value, rate and (when the statement words it) acceleration for a quantity measuring the
    driver; a known load's value or component for a load quantity."""
    d, out = mech.driver, {}
    stated_accel = bool(d.accel or mech.report.get("acceleration") or mech.dynamics)
    for name in names(mech):
        base, order = _rate(name, mech.quantities)
        q = mech.quantities.get(base)
        if q is None:
            continue
        if q.kind == "load":
            load = mech.loads[q.a]
            if load.value is None:
                continue
            unit = q.unit or mech.units.names[mech.load_unit_kind(load)]
            scale = {"x": load.direction.real, "y": load.direction.imag}.get(q.component, 1)
            out[name] = (load.value * scale, mech.load_unit_kind(load), unit)
            continue
        driver = mech.elements is None and (q.kind == "q" or q.kind == d.kind and (
            {q.a, q.b} == {d.a, d.b} if d.kind == "length"
            else q.a == d.a and (d.kind != "angle" or q.b == d.b)))
        if driver and (order < 2 or stated_accel):
            out[name] = ([d.value, d.rate, d.accel][order], d.base, order)
    return out


def rows(question) -> dict:
    """{box name: (weight, first answer as written)} of a question's table."""
    out = {}
    for row in Parts(html_of(question)).rows:
        found = FIRST.search(row[2])
        out[row[0]] = (int(found.group(1)), found.group(2))
    return out


def displayed(mech, datum) -> tuple:
    """(value in display units, period or None) of a datum of :func:`data_of`."""
    value, kind, third = datum
    if isinstance(third, str):                      # a load in its unit
        from linkcli.model.units import FORCE, TORQUE
        return value / (FORCE if kind == "force" else TORQUE)[third], None
    unit, factor = mech.units.display(kind, third)
    period = (360.0 if unit == "deg" else 2 * math.pi) if kind == "angle" and not third \
        else None
    return value / factor, period


def same(a: float, b: float, places: int, period) -> bool:
    diff = abs(a - b) if period is None else min(abs(a - b) % period,
                                                 period - abs(a - b) % period)
    return diff <= 0.5 * 10 ** -places + 1e-9 * max(1.0, abs(b))


@pytest.fixture(scope="module")
def exported():
    """{path: (questions without the option, with it)}."""
    return {p: (questions(ET.fromstring(export(p))),
                questions(ET.fromstring(export(p, no_given=True)))) for p in KEYED}


@pytest.mark.parametrize("path", KEYED, ids=os.path.basename)
def test_no_given_leaves_out_exactly_the_data(exported, path):
    check(path, *exported[path])


def check(path, before, after) -> None:
    """Each question with --no-given (``after``) against the same without (``before``)."""
    doc = load_file(path)
    assert len(before) == len(after)
    for full, cut in zip(before, after):
        mech = build(doc, _digit(full))
        data = data_of(mech)
        places = mech.report.get("decimals", 1)
        all_rows, kept = rows(full), rows(cut)
        # a given box printed without the option is the datum the statement gives
        for name in data:
            value, period = displayed(mech, data[name])
            assert same(float(all_rows[name][1]), value, places, period), (path, name)
        # with it: no datum asked back, every other box kept with its value
        assert set(kept) == set(all_rows) - set(data), path
        for name, (_, value) in kept.items():
            assert not any(same(float(value), *displayed(mech, d)[:1], places,
                                displayed(mech, d)[1]) for d in data.values()), (path, name)
        for name, (weight, value) in kept.items():
            assert value == all_rows[name][1], (path, name)
        # the mark is the sum of the remaining boxes' weights
        assert int(cut.find("defaultgrade").text) == sum(w for w, _ in kept.values())
        if not mech.quiz.points:
            assert all(w == 1 for w, _ in kept.values())


def _digit(question):
    found = re.search(r"-k(\d)$", question.find("idnumber").text)
    return int(found.group(1)) if found else None


@pytest.mark.parametrize("path", KEYED, ids=os.path.basename)
def test_count_line(path, tmp_path):
    mech = build(load_file(path), None)
    count, total = len(data_of(mech)), len(names(mech))
    for option in ([], ["--no-given"]):
        extra = ["--method", "newton"] if os.path.basename(path) == "triad-class3.yaml" else []
        code, out, err = run(["export", path, "--to", "moodle", "--no-figure", *option,
                              *extra, "-o", str(tmp_path / f"q{len(option)}.xml")])
        assert code == 0, err
        line = [s for s in err.splitlines() if " box" in s]
        assert len(line) == 1, err
        assert line[0].startswith(f"{os.path.basename(path)}: {count} of {total} box"), line


def test_an_empty_given_set_is_caught(monkeypatch):
    """A planted defect: nothing counted as given; the check above must fail."""
    path = next(p for p in KEYED if os.path.basename(p) == "padova-2020-02.yaml")
    assert set(data_of(build(load_file(path), None))) == {"a1", "a1dot", "Fx"}
    before = questions(ET.fromstring(export(path)))
    monkeypatch.setattr(moodle, "given", lambda mech: set())
    after = questions(ET.fromstring(export(path, no_given=True)))
    with pytest.raises(AssertionError):
        check(path, before, after)
