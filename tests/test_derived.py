"""Answers computed from answers (``expr`` quantities): values against independent
calculations, rates against finite differences, dimensions and units, refusals."""
from __future__ import annotations

import math
import os

import numpy as np
import pytest

import linkcli
from linkcli.errors import ExpressionError, InputError
from linkcli.input.expressions import Expression, Rates
from linkcli.model.dimensions import dimension
from linkcli.model.units import DIMENSIONS, Dimension, Units, parse_unit

from cli_helpers import run

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MECHANISMS = os.path.join(ROOT, "mechanisms")


# --- the evaluator: values with their rates ------------------------------------------------
def _rates(t):
    """a(t) = sin t + 2, b(t) = t^2 + 1 with their first and second rates."""
    return {"a": Rates((np.sin(t) + 2, np.cos(t), -np.sin(t))),
            "b": Rates((t * t + 1, 2 * t, 2.0))}


@pytest.mark.parametrize("text", ["a*b", "a/b", "sqrt(a*b)", "atan2(a, b)", "hypot(a, b)",
                                  "a**b", "a**2.5", "asin(a/4)", "acos(b/3)", "tan(b/3)",
                                  "abs(a - b)", "atan(a)", "2*pi/a - 3*b"])
def test_rates_are_the_chain_rule_against_differences(text):
    """The first and second rates carried through the walk agree with central differences
    of the values (h = 1e-4: truncation ~1e-8, rounding ~1e-8 for the second)."""
    expression = Expression(text)
    t, h = 0.7, 1e-4
    at = _rates(t)
    got = expression.value(at)

    def plain(s):
        return expression.value({n: r.terms[0] for n, r in _rates(s).items()})
    first = (plain(t + h) - plain(t - h)) / (2 * h)
    second = (plain(t + h) - 2 * plain(t) + plain(t - h)) / h ** 2
    scale = 1 + abs(plain(t))
    assert got.terms[0] == pytest.approx(plain(t), rel=1e-14)
    assert abs(got.terms[1] - first) <= 1e-7 * scale
    assert abs(got.terms[2] - second) <= 1e-5 * scale


def test_arrays_are_evaluated_element_by_element_and_refusals_name_the_value():
    expression = Expression("sqrt(a) / b")
    a, b = np.array([4.0, 9.0]), np.array([2.0, 3.0])
    assert np.array_equal(expression.value({"a": a, "b": b}), [1.0, 1.0])
    with pytest.raises(ExpressionError, match=r"sqrt\(-1\) is out of its domain"):
        expression.value({"a": np.array([4.0, -1.0]), "b": b})
    with pytest.raises(ExpressionError, match="division by zero"):
        expression.value({"a": a, "b": np.array([1.0, 0.0])})


def test_dimension_of_an_expression_and_what_it_refuses():
    length, time = DIMENSIONS["length"], DIMENSIONS["time"]
    omega = DIMENSIONS["frequency"]
    assert Expression("2*pi/w").dimension({"w": omega}).agrees(time)
    assert Expression("sqrt(k/m)").dimension({"k": DIMENSIONS["stiffness"],
                                               "m": DIMENSIONS["mass"]}).agrees(omega)
    assert Expression("atan2(x, y) + 1").dimension({"x": length, "y": length}).none
    for text, words in (("x + t", "adds 'x' (L) and 't' (T)"), ("sin(x)", "sin() takes"),
                        ("x**t", "not a pure number"), ("x**n", "not a number written"),
                        ("hypot(x, t)", "compares")):
        with pytest.raises(ExpressionError) as info:
            Expression(text).dimension({"x": length, "t": time, "n": Dimension()})
        assert words in str(info.value), str(info.value)


# --- units read back ----------------------------------------------------------------------
@pytest.mark.parametrize("dim", [Dimension(1, 1, 0, 0), Dimension(0, 1, -2, 0),
                                 Dimension(1, 1, -1, -1), Dimension(0, -1, 0, -1),
                                 Dimension(0, 0, -2, 0), Dimension(1, 2, -2, -1)])
def test_composed_units_read_back_to_their_dimension_and_factor(dim):
    """What Units.show writes, parse_unit reads: the same dimension and SI factor."""
    for declared in ({}, {"length": "in", "force": "lbf", "mass": "lb", "angle": "deg"}):
        units = Units(declared)
        name, factor = units.show(dim)
        read, read_factor = parse_unit(name, dim)
        assert read.agrees(dim) and read_factor == pytest.approx(factor, rel=1e-14), name


def test_unit_names_of_answers_and_of_files():
    assert parse_unit("mm/s^2") == (Dimension(0, 1, -2), pytest.approx(1e-3))
    assert parse_unit("N s/m")[0].agrees(DIMENSIONS["damping"])
    assert parse_unit("Ns/rad")[0].agrees(DIMENSIONS["damping"] * DIMENSIONS["length"])
    assert parse_unit("lb", DIMENSIONS["mass"]) == (DIMENSIONS["mass"], 0.45359237)
    assert parse_unit("lb")[0] == DIMENSIONS["force"]
    assert parse_unit("furlong") is None and parse_unit("m/s/s") is None


@pytest.mark.parametrize("path", ["khurmi-8-1-slider-crank-accelerations.yaml",
                                  "docs/examples/textbook-quantities.yaml",
                                  "khurmi-5-2-quick-return.yaml", "padova-2020-07.yaml",
                                  "polimi-2001-02-07-vibration.yaml",
                                  "polimi-2001-07-04-vibration.yaml"])
def test_every_answers_unit_has_the_dimension_the_model_gives(path):
    """The display unit of each answer, read back, has the dimension model.dimensions
    gives it before solving: expressions convert answers to SI by that unit."""
    path = path if path.startswith("docs") else os.path.join(MECHANISMS, path)
    linkage = linkcli.load(os.path.join(ROOT, path))
    result = linkage.solve()
    for name, unit in result.units.items():
        if name in result.points:
            continue
        expected = dimension(linkage.model, name)
        parsed = parse_unit(unit, expected)
        assert parsed is not None and parsed[0].agrees(expected), (name, unit, expected)


# --- in files --------------------------------------------------------------------------------
CRANK = os.path.join(MECHANISMS, "polimi-crank-slider.yaml")


def _with(path, quantities, report):
    """The text of ``path`` with ``quantities`` added and ``report`` as its report."""
    text = open(path, encoding="utf-8").read().split("\nkeys:")[0]
    head, _, _ = text.partition("\nreport:")
    head = head.replace("\nquantities:\n", "\nquantities:\n" + quantities, 1)
    return head + "\nreport:\n" + report + "\n"


def test_expressions_and_their_rates_on_a_crank_slider():
    """p = c sin(beta) (c = OB, beta the rod's angle) and its rates against the closed form
    of the centred crank-slider (a = 1, b = sqrt 2) differentiated by hand, over a sweep."""
    text = _with(CRANK, '  p: {expr: "c*sin(beta)", unit: mm}\n',
                 "  position: [p]\n  velocity: [pdot]\n  acceleration: [pddot]")
    linkage = linkcli.loads(text)
    alpha = np.radians(np.array([20.0, 45.0, 100.0]))
    w, e = 0.5, 1.0                                  # the file's rate and acceleration
    result = linkage.solve(np.degrees(alpha), names=["p", "pdot", "pddot"])
    a, b = 1.0, math.sqrt(2.0)
    sb = -a * np.sin(alpha) / b                      # sin(beta)
    cb = np.sqrt(1 - sb ** 2)
    c = a * np.cos(alpha) + b * cb
    # d/dalpha by hand: beta' = -a cos(alpha) / (b cos beta), c' = -a sin(alpha) - b sin(beta) beta'
    bp = -a * np.cos(alpha) / (b * cb)
    cp = -a * np.sin(alpha) - b * sb * bp
    p_alpha = cp * sb + c * cb * bp
    p = c * sb
    assert result.values["p"] == pytest.approx(p * 1e3, rel=1e-12)
    assert result.values["pdot"] == pytest.approx(p_alpha * w * 1e3, rel=1e-12)
    assert result.units["pdot"] == "mm/s" and result.units["pddot"] == "mm/s^2"
    # the second rate: p'' = p_aa w^2 + p_a e, p_aa by central differences of p_alpha
    h = 1e-5

    def p_a(x):
        s = -a * np.sin(x) / b
        co = np.sqrt(1 - s ** 2)
        bq = -a * np.cos(x) / (b * co)
        cq = -a * np.sin(x) - b * s * bq
        return cq * s + (a * np.cos(x) + b * co) * co * bq
    p_aa = (p_a(alpha + h) - p_a(alpha - h)) / (2 * h)
    assert result.values["pddot"] == pytest.approx((p_aa * w * w + p_alpha * e) * 1e3,
                                                   rel=1e-8)


def test_expressions_on_a_vibration_problem_closed_form():
    """Periods and their ratio on the double pendulum with springs (18 Sep 2001):
    omega^2 = 2k/m + (2 -+ sqrt 2) g / L (the file's notes), k = 100, m = 2, L = 0.5."""
    path = os.path.join(MECHANISMS, "polimi-2001-09-18-vibration.yaml")
    text = _with(path, '  T1: {expr: "2*pi/w1", unit: s}\n  T2: {expr: "2*pi/w2", unit: ms}\n'
                 '  r: {expr: "w2/w1"}\n  kk: {expr: "2*ks", unit: N/mm}\n',
                 "  vibration: [T1, T2, r, kk]\n  decimals: 4")
    values = linkcli.loads(text).solve().values
    g, L, k, m = 9.81, 0.5, 100.0, 2.0
    w1, w2 = (math.sqrt(2 * k / m + (2 - s * math.sqrt(2)) * g / L) for s in (1, -1))
    assert values["T1"] == pytest.approx(2 * math.pi / w1, rel=1e-10)
    assert values["T2"] == pytest.approx(2e3 * math.pi / w2, rel=1e-10)
    assert values["r"] == pytest.approx(w2 / w1, rel=1e-10)
    assert values["kk"] == pytest.approx(0.2, rel=1e-14)   # 2 ks, ks in N/m, shown in N/mm


@pytest.mark.parametrize("quantity, report, key, words", [
    ('s: {expr: "c - zz", unit: mm}', "[s]", "quantities.s.expr", ["'zz' is not a quantity"]),
    ('s: {expr: "t + 1", unit: mm}\n  t: {expr: "s*2", unit: m}', "[s]", "quantities.s.expr",
     ["reads itself: s -> t -> s"]),
    ('s: {expr: "c + betadot", unit: mm}', "[s]", "quantities.s.expr",
     ["adds 'c' (L) and 'betadot' (T^-1 A)"]),
    ('s: {expr: "2*c"}', "[s]", "quantities.s.expr", ["a length (L)", "unit: 'm'"]),
    ('s: {expr: "c", unit: Hz}', "[s]", "quantities.s.unit",
     ["a length (L)", "'Hz' is a frequency"]),
    ('s: {expr: "c", unit: furlong}', "[s]", "quantities.s.unit", ["unknown unit"]),
    ('s: {expr: "c*b", unit: mm}', "[s]", "quantities.s.expr", []),
])
def test_refusals_name_the_file_line_and_key(quantity, report, key, words):
    text = _with(CRANK, f"  {quantity}\n", f"  position: {report}")
    if not words:           # b is a parameter written as a length: c b is an area
        with pytest.raises(InputError) as info:
            linkcli.loads(text, name="m.yaml")
        assert "an area (L^2)" in str(info.value)
        return
    code, out, err = run(["solve", "-"], stdin=text)
    assert code == 2 and f"key '{key}'" in err and "<stdin>:" in err, err
    for word in words:
        assert word in err, err


def test_rates_refused_where_a_name_has_none():
    """A rate of an expression over a limit (one value: no rate) is refused with its line."""
    path = os.path.join(MECHANISMS, "khurmi-5-2-quick-return.yaml")
    text = open(path, encoding="utf-8").read().split("\nkeys:")[0]
    text = text.replace("\nquantities:\n", '\nquantities:\n  half: {expr: "stroke/2", '
                        'unit: mm}\n', 1).replace("  position: [", "  position: [half, ", 1)
    assert linkcli.loads(text).solve().values["half"] == pytest.approx(225.0, abs=1e-6)
    text = text.replace("  velocity: [", "  velocity: [halfdot, ", 1) if "velocity:" in text \
        else text.replace("  position: [", "  velocity: [halfdot]\n  position: [", 1)
    code, _, err = run(["solve", "-"], stdin=text)
    assert code == 2 and "the expression half has no rates" in err, err


def test_a_parameter_without_a_unit_is_refused_in_an_expression():
    text = _with(CRANK, '  s: {expr: "c*r", unit: mm}\n', "  position: [s]")
    text = text.replace("params:\n", "params:\n  r: 2\n", 1)
    with pytest.raises(InputError) as info:
        linkcli.loads(text)
    assert "parameter 'r' has no unit" in str(info.value)
