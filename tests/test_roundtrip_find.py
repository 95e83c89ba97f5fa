"""Round trip of every design question (``find:``) the project ships or documents: the file
is solved, built forward at the parameters found (as ``params`` of the file, no search), and
every target must hold there: within half a unit of the last digit the target is written
with, and with a dimensionless residual |answer - target| / scale below RESIDUAL (scale:
|target|; a turn for an angle's target 0).  A file that refuses its question must refuse it
as documented.  Planted defects (a root polish that returns its bracket's end, a solver of
several unknowns that stops where it starts) with the library's own root check switched
off are caught by the round trip."""
from __future__ import annotations

import glob
import math
import os
import re
from decimal import Decimal, InvalidOperation

import numpy as np
import pytest

from linkcli.runs import design
from linkcli.answers.quantities import angle_period
from linkcli.runs.sheet import evaluate
from linkcli.errors import LinkcliError
from linkcli.input.document import build
from linkcli.input.source import load_file
from linkcli.model.dimensions import dimension
from linkcli.model.units import parse_unit

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FILES = sorted(p for p in glob.glob(os.path.join(ROOT, "mechanisms", "*.yaml")) +
               glob.glob(os.path.join(ROOT, "docs", "examples", "*.yaml"))
               if re.search(rb"^find:", open(p, "rb").read(), re.M))
#: documented refusals (docs/errors.md, "Design questions"): file -> exit status
REFUSED = {"bad-find.yaml": 2, "design-no-root.yaml": 3, "design-ambiguous.yaml": 3,
           "design-singular.yaml": 3, "design-wrap.yaml": 3}
#: files whose trials only Newton's method solves (a class-III group)
METHOD = {"design-triad.yaml": "newton"}
#: the largest dimensionless residual of a target at the solution
RESIDUAL = 1e-6


def written_tolerance(text: str) -> float | None:
    """Half a unit of the last digit of the target's number as written ('1.9' -> 0.05,
    '0.10' -> 0.005, '100 cm' -> 0.5); None for an expression."""
    try:
        exponent = Decimal(text.split()[0]).as_tuple().exponent
    except (InvalidOperation, IndexError):
        return None
    return 0.5 * 10.0 ** exponent


def roundtrip(path) -> list:
    """What fails in the round trip of ``path``: [] when every target holds."""
    doc = load_file(path)
    method = METHOD.get(os.path.basename(path), "closed")
    asked = build(doc)
    found = design.solve(asked, evaluate, method)
    forward = build(doc, None, found.values)      # the file at the parameters found
    assert forward.design.fixed                   # no search: the parameters are given
    targets = asked.design.targets
    result = evaluate(forward, names=[t.name for t in targets], method=method)
    problems = []
    for t in targets:
        value, unit = float(np.ravel(result.values[t.name])[0]), result.units[t.name]
        goal = t.value
        if t.unit is not None:
            dim = dimension(forward, t.name)
            goal *= parse_unit(t.unit, dim)[1] / parse_unit(unit, dim)[1]
        diff = value - goal
        period = angle_period(forward, t.name, unit)
        if period:
            diff = math.remainder(diff, period)
        scale = abs(goal) or period or 1.0
        written = written_tolerance(t.text)
        if written is not None and abs(diff) > written * (abs(goal) / abs(t.value)
                                                          if t.value else 1.0):
            problems.append(f"{t.name} = {value:.6g} {unit}: the target {t.text} misses by "
                            f"more than its written precision")
        if abs(diff) / scale > RESIDUAL:
            problems.append(f"{t.name} = {value:.10g} {unit}: residual "
                            f"{abs(diff) / scale:.2e} of the target {t.text}")
    return problems


@pytest.mark.parametrize("path", FILES, ids=os.path.basename)
def test_every_find_file_round_trips(path):
    name = os.path.basename(path)
    if name in REFUSED:
        with pytest.raises(LinkcliError) as info:
            design.solve(build(load_file(path)), evaluate)
        assert info.value.exit_code == REFUSED[name], str(info.value)
        return
    assert roundtrip(path) == []


def test_the_files_are_found():
    names = {os.path.basename(p) for p in FILES}
    assert {"design-crank.yaml", "design-spring.yaml", "design-triad.yaml",
            "vib-ques10-refrigerator-isolation.yaml"} <= names and len(names) >= 10
    assert set(REFUSED) <= names


def test_the_written_tolerance():
    assert written_tolerance("1.9") == pytest.approx(0.05)
    assert written_tolerance("0.10 kg/s") == pytest.approx(0.005)
    assert written_tolerance("100 cm") == pytest.approx(0.5)
    assert written_tolerance("sqrt(2)") is None


# --- planted defects ----------------------------------------------------------------------------
CRANK = os.path.join(ROOT, "docs", "examples", "design-crank.yaml")
SPRING = os.path.join(ROOT, "docs", "examples", "design-spring.yaml")


def _bracket_end(residuals, a, b):
    return a


def test_a_root_polish_that_returns_the_bracket_end_is_refused(monkeypatch):
    """The library's own check: the answer at the 'root' is not its target."""
    monkeypatch.setattr(design, "_polish", _bracket_end)
    with pytest.raises(LinkcliError) as info:
        roundtrip(CRANK)
    assert info.value.reason == "no root", str(info.value)


def test_the_round_trip_catches_a_wrong_root(monkeypatch):
    """The same defect with the library's root check switched off: the round trip finds
    c away from 1.9 m at the parameter returned."""
    monkeypatch.setattr(design, "_polish", _bracket_end)
    monkeypatch.setattr(design, "ROOT", math.inf)
    problems = roundtrip(CRANK)
    assert problems and problems[0].startswith("c = "), problems


def test_the_round_trip_catches_a_search_that_stops_at_its_start(monkeypatch):
    """Several unknowns: a solver that returns its start values, the residual check of the
    library switched off."""
    import scipy.optimize

    class Stopped:
        def __init__(self, x):
            self.x = np.asarray(x, dtype=float)

    monkeypatch.setattr(scipy.optimize, "root", lambda f, x0, **kw: Stopped(x0))
    monkeypatch.setattr(scipy.optimize, "least_squares",
                        lambda f, x0, **kw: Stopped(x0))
    monkeypatch.setattr(design, "RESIDUAL", math.inf)
    problems = roundtrip(SPRING)
    assert len(problems) >= 2, problems


# --- the question as the documents state it --------------------------------------------------
def _started_at(doc, factor):
    """``doc`` with each unknown's value in ``params`` (the figure's) times ``factor``: the
    same question drawn at other values."""
    import copy
    from linkcli.input.source import Document
    data = copy.deepcopy(doc.data)
    for name in data["find"]["unknowns"]:
        data["params"][name] = f"({data['params'][name]}) * {factor}"
    return Document(doc.name, data, doc.lines, doc.raw)


def stated(doc, lang="en"):
    """What the documents state of the question: the data lines and the exam figure's
    texts (a figure's geometry apart)."""
    from linkcli.texts.data import data_lines
    from linkcli.pictures.exam import exam_figure
    mech = build(doc)
    method = METHOD.get(os.path.basename(doc.name), "closed")
    texts = [t.get_text() for ax in exam_figure(mech, lang, method).axes for t in ax.texts]
    return data_lines(mech, lang), sorted(texts)


ASKED = [p for p in FILES if os.path.basename(p) not in REFUSED]


@pytest.mark.parametrize("path", ASKED, ids=os.path.basename)
def test_the_statement_does_not_give_the_figures_value_of_an_unknown(path):
    """The data and the exam figure of a design question are the same whatever value the
    file gives its unknowns for the figure: none of them is stated (it is the answer)."""
    doc = load_file(path)
    assert stated(doc) == stated(_started_at(doc, 1.0625))


def test_the_statement_check_catches_an_unknown_stated_at_its_value(monkeypatch):
    """Planted: the data and the figure state every datum at the file's value."""
    from linkcli.texts import data, unknowns
    monkeypatch.setattr(data, "_unknowns_stated", lambda mech, lines, lang: lines)
    monkeypatch.setattr(unknowns, "unknown_datum", lambda *a, **k: None)
    import linkcli.pictures.exam as exam
    monkeypatch.setattr(exam, "unknown_datum", lambda *a, **k: None)
    doc = load_file(CRANK)
    assert stated(doc) != stated(_started_at(doc, 1.0625))
