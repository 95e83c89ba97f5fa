"""The safe evaluator: the exam's arithmetic works, everything else is refused."""
import math
import time

import pytest

import linkcli
from linkcli.errors import ExpressionError, InputError
from linkcli.input.expressions import evaluate


@pytest.mark.parametrize("text, names, expected", [
    ("200 + 10*k", {"k": 5.0}, 250.0),
    ("-(200 + 50*k)", {"k": 5.0}, -450.0),
    ("2**10", {}, 1024.0),
    ("sqrt(a**2 + b**2)", {"a": 3.0, "b": 4.0}, 5.0),
    ("atan2(1, 1) / deg", {}, 45.0),
    ("sin(30*deg) + cos(pi)", {}, 0.5 - 1.0),
    ("asin(1) - pi/2", {}, 0.0),
    ("acos(0.5)/deg", {}, 60.0),
    ("tan(45*deg)", {}, 1.0),
    ("(1 + 2) * (3 - 4) / 2", {}, -1.5),
    ("+k", {"k": 0.0}, 0.0),
    (12, {}, 12.0),
    (2.5, {}, 2.5),
])
def test_valid_expressions(text, names, expected):
    assert math.isclose(evaluate(text, names), expected, rel_tol=1e-12, abs_tol=1e-12)


@pytest.mark.parametrize("text, words", [
    ("__import__('os')", ["__import__", "not allowed"]),
    ("__import__('os').system('ls')", ["not allowed"]),
    ("pi.real", ["Attribute", "not allowed"]),
    ("a.__class__", ["Attribute", "not allowed"]),
    ("k[0]", ["Subscript", "not allowed"]),
    ("(lambda: 1)()", ["not allowed"]),
    ("lambda x: x", ["Lambda", "not allowed"]),
    ("foo + 1", ["unknown name 'foo'"]),
    ("open('x')", ["open", "not allowed"]),
    ("'abc'", ["not a number"]),
    ("1 < 2", ["Compare", "not allowed"]),
    ("1 if k else 2", ["not allowed"]),
    ("[1, 2]", ["not allowed"]),
    ("k % 2", ["not allowed"]),
    ("1 +", ["cannot parse"]),
    ("", ["empty"]),
    ("1/0", ["division by zero"]),
    ("sqrt(-1)", ["domain"]),
    ("sqrt(1, 2)", ["argument"]),
    ("(-8)**(1/3)", ["negative"]),
    ("1e308*10", ["not a finite number"]),
    (True, ["expected a number"]),
    (None, ["expected a number"]),
])
def test_refused_expressions(text, words):
    with pytest.raises(ExpressionError) as info:
        evaluate(text, {"k": 3.0, "a": 1.0})
    assert isinstance(info.value, InputError)
    message = str(info.value)
    for word in words:
        assert word in message, message


def test_huge_power_is_refused_quickly():
    start = time.process_time()
    for text in ("9**9**9", "(9**9)**(9**9)", "10**10**10", "2**100000"):
        with pytest.raises(ExpressionError) as info:
            evaluate(text)
        assert "too large" in str(info.value) or "overflow" in str(info.value)
    assert time.process_time() - start < 0.5


@pytest.mark.parametrize("text", [
    "1" + "+1" * 300,                 # long (and left-deep)
    "-" * 300 + "1",                  # deeply nested unary minus
    "(1+" * 90 + "1" + ")" * 90,      # right-deep sums in parentheses
    "sqrt(" * 60 + "1" + ")" * 60,    # nested calls
    "1" * 5000,                       # very long input
])
def test_long_or_deep_input_is_refused(text):
    start = time.process_time()
    with pytest.raises(ExpressionError) as info:
        evaluate(text)
    assert time.process_time() - start < 0.5
    message = str(info.value)
    assert any(w in message for w in ("longer than", "too deep", "cannot parse")), message


def test_moderate_nesting_is_fine():
    assert evaluate("((((1 + 2) * 3) - 4) / 5)") == 1.0
    assert evaluate("sqrt(sqrt(sqrt(256)))") == 2.0


MECH = """
title: params
k: 3
params:
  r: 40 + 2*k
  l: 3*r
  alpha: atan2(1, 1) / deg
frame: {A: [0, 0]}
points: {B: [40, 10], C: [150, 0]}
links:
  AB: {points: [A, B], length: r}
  BC: {points: [B, C], length: l}
sliders:
  SC: {point: C, guide: {y: 0}}
driver: {angle: [A, B], value: alpha, rate: 10}
loads:
  F: {type: force, at: C, x: -(100 + k)}
  M: {type: torque, on: AB, value: unknown}
report:
  position: [xC]
"""


def test_params_and_k_in_a_file():
    mech = linkcli.loads(MECH)
    assert mech.k == 3
    assert math.isclose(mech.driver.value, math.radians(45.0), rel_tol=1e-12)
    assert math.isclose(abs(mech.bodies["AB"].local["B"]), 0.046, rel_tol=1e-12)
    assert math.isclose(abs(mech.bodies["BC"].local["C"]), 0.138, rel_tol=1e-12)
    assert mech.loads["F"].value * mech.loads["F"].direction.real == pytest.approx(-103.0)
    other = linkcli.loads(MECH, k=7)
    assert math.isclose(abs(other.bodies["AB"].local["B"]), 0.054, rel_tol=1e-12)
    xc = other.solve().values["xC"]
    assert math.isclose(xc, 54 * math.cos(math.radians(45)) + math.sqrt(162 ** 2 - (54 * math.sin(
        math.radians(45))) ** 2), rel_tol=1e-12)


@pytest.mark.parametrize("old, new, key, words", [
    ("length: r}", "length: \"__import__('os')\"}", "links.AB.length", ["__import__"]),
    ("l: 3*r", "l: 3*s", "params.l", ["unknown name 's'"]),
    ("alpha: atan2(1, 1) / deg", "alpha: r.real", "params.alpha", ["Attribute"]),
    ("x: -(100 + k)", "x: 9**9**9", "loads.F.x", ["too large"]),
])
def test_expression_errors_in_a_file_name_the_key(old, new, key, words):
    with pytest.raises(InputError) as info:
        linkcli.loads(MECH.replace(old, new), name="m.yaml")
    message = str(info.value)
    assert "m.yaml:" in message and f"key '{key}'" in message, message
    for word in words:
        assert word in message, message
    assert info.value.exit_code == 2
