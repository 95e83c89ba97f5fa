"""The JSON Schema (linkcli/input/schema.json) and the loader agree.

* every shipped example, test mechanism and the template validates;
* the schema states the loader's own tables (sections, units, names, bounds);
* on mutated files: whatever the loader accepts the schema accepts, and
  whatever the loader rejects for a rule the schema can express, the schema
  rejects too.  Rules that need the rest of the file are the loader's alone:
  ``loader_only`` lists them (docs/cli.md repeats the list).

The ``dynamics`` section is open in the schema (an object) and validated by the
dynamics model; it is left out of the comparison.
"""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import zlib

import jsonschema
import pytest
from hypothesis import HealthCheck, given, seed, settings

from linkcli.input import expressions
from linkcli.input import document as parsing
from linkcli.model import units
from linkcli.errors import InputError, ScaleError
from linkcli.input.document import build as parse
from linkcli.input.source import load_text, path_text

from mutations import EXTRA, ROOT, SHIPPED, data_of, mutated, paths, to_yaml

SCHEMA_PATH = os.path.join(ROOT, "linkcli", "input", "schema.json")
SCHEMA = json.load(open(SCHEMA_PATH, encoding="utf-8"))
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA)
DEFS = SCHEMA["$defs"]
CASES_PER_FILE = max(25, 400 // max(1, len(SHIPPED)))


def test_schema_is_a_valid_json_schema():
    jsonschema.Draft202012Validator.check_schema(SCHEMA)


@pytest.mark.parametrize("path", SHIPPED + EXTRA, ids=os.path.basename)
def test_every_example_validates(path):
    errors = [f"{path_text(tuple(e.absolute_path))}: {e.message}"
              for e in VALIDATOR.iter_errors(data_of(path))]
    assert not errors, errors


def test_schema_states_the_loaders_tables():
    props = SCHEMA["properties"]
    assert set(props) == parsing.TOP_KEYS
    unit_props = props["units"]["anyOf"][1]["properties"]
    assert set(unit_props) == set(units.KINDS)
    for kind, table in units.KINDS.items():
        assert set(unit_props[kind]["enum"]) == set(table), kind
    report = props["report"]["properties"]
    assert set(report) == set(parsing.SECTIONS) | {"decimals"}
    from linkcli.model.mechanism import VIBRATION
    from linkcli.input.oscillation import OSCILLATION
    assert set(DEFS["vibrationQuantity"]["properties"]) == \
        set(VIBRATION) - set(OSCILLATION) | {"unit", "time", "part"}
    assert set(DEFS["oscillationQuantity"]["properties"]) == \
        set(OSCILLATION) | {"unit", "part", "monic", "peak"}
    # a vibration answer's own unit is any unit of its dimension, as parse_unit reads them
    for kind in ("vibrationQuantity", "oscillationQuantity"):
        unit = DEFS[kind]["properties"]["unit"]
        assert unit["type"] == "string" and unit["maxLength"] == 80
        assert units.parse_unit("x" * 81) is None and units.parse_unit("kg " * 26 + "m")
    reserved = props["params"]["anyOf"][1]["propertyNames"]["allOf"][1]["not"]["enum"]
    assert set(reserved) == set(expressions.CONSTANTS) | set(expressions.FUNCTIONS) | {"k"}
    assert DEFS["name"]["pattern"].replace("$", r"\Z") == parsing.NAME.pattern
    assert DEFS["expression"]["maxLength"] == expressions.MAX_LENGTH
    assert DEFS["number"]["maximum"] == expressions.MAX_MAGNITUDE
    assert DEFS["number"]["minimum"] == -expressions.MAX_MAGNITUDE
    tiny = DEFS["number"]["not"]["anyOf"][1]
    assert tiny["exclusiveMaximum"] == expressions.MIN_MAGNITUDE


@pytest.mark.parametrize("text, ok", [
    ("2*k + 1", True), ("  sqrt(a**2 + b**2) ", True), ("atan2(1, 2)/deg", True),
    ("", False), ("   ", False), ("1 # comment", False), ("a[0]", False), ("'s'", False),
    ("ｓｉｎ(1)", False), ("x" * 401, False),
])
def test_expression_pattern_is_the_evaluators_character_rule(text, ok):
    in_schema = VALIDATOR.evolve(schema={**DEFS["expression"]}).is_valid(text)
    assert in_schema == ok
    in_evaluator = bool(text.strip()) and len(text) <= expressions.MAX_LENGTH and \
        expressions.ALLOWED.fullmatch(text) is not None
    assert in_evaluator == ok


@pytest.mark.parametrize("value, ok", [
    (0, True), (-0.0, True), (1e300, True), (-1e300, True), (1e-300, True), (2.5, True),
    (float("nan"), False), (float("inf"), False), (float("-inf"), False), (1e301, False),
    (1e-301, False), (5e-324, False), (10 ** 400, False), (True, False), ("1", False),
])
def test_number_rule_is_the_evaluators_range(value, ok):
    assert VALIDATOR.evolve(schema={**DEFS["number"]}).is_valid(value) == ok
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        try:
            expressions.evaluate(value)
            accepted = True
        except InputError:
            accepted = False
        assert accepted == ok


# --- which loader errors the schema cannot express -----------------------------------------
_SHAPE_POINT_KEYS = {"angle", "from", "distances", "side"}
_ALWAYS_LOADER = [           # messages of rules that need the rest of the file
    r"^undefined (point|link|actuator|load|coordinate|spring|damper|spring or damper|body|gear|fixed point) ",
    r"do not mesh: ", r"is not the pitch radius of gear", r"are both internal: a ring",
    r"is of gears: give their teeth", r"^a pressure angle lies between",
    r"^a mode is numbered",
    r"a quantity of the vibration analysis",
    r"needs a vibration problem",
    r"belongs to a vibration problem",
    r"^a 'driver' load needs a driver",
    r"^a vibration problem has no unknown load",
    r"^a file has one of 'driver'",
    r"^the driver load acts on the driver coordinate",   # 'on' names a driver of 'drivers:'
    r"^one load per driver must be unknown",
    r"^'driver' is for a velocity ratio",
    r"^'driver' picks one of several drivers",
    r"already fixes: one coordinate takes one driver",
    r"^the driver's name .* is taken by",
    r"^a harmonic excitation needs its frequency",
    r"^the cord is not (taut|tangent) in the figure",
    r"^in the figure the centres are",
    r"does not fit inside a track",
    r"already rolls",
    r"names a rolling contact already",
    r"^a disc cannot roll on itself",
    r"^a belt cannot run from a pulley to itself",
    r"^no body carries both .*: least_speed",
    r"section to score",
    r"^a harmonic force needs a non-zero",
    r"^a harmonic (force|torque) is",
    r"^the road gives Omega",
    r"is both fixed \(frame\) and moving",
    r"belongs to no link, slider or actuator",
    r"^name '.*' is already",
    r"is not a fixed point",
    r"^no link carries both",
    r"^no link, slider block or actuator carries both",
    r"^the figure puts .* which should pass through it$",
    r"cannot run on a guide of its own points",
    r"run on each other in a ring$",
    r"^a guide along an actuator is its line",
    r"^a block on the line of actuator .* carries no other points$",
    r"^the frame needs at least one fixed point",   # when its only point does not read
    r"^on a moving guide give",
    r"^exactly one load must be unknown",
    r"^only forces have x and y components",
    r"is not a load$",
    r"is not a defined quantity",
    r"has no printed value in this key",
    r"which the file does not define",
    r"^a point's key is \[x, y\]",
    r"^cannot read printed value",
    r"^these distances do not close a triangle",
    r"^points .* of the link coincide",
    r"^the first two points coincide",
    r"runs on a guide carried by .*: a pressure acts on a piston",
    r"^the force p A is not a finite number",
    r"^the extremes of '.*' are where its rate is zero",
    r"is of a position quantity",
    r"needs a driver: a vibration problem has coordinates",
    r"^the range goes up",
    # expressions (input.derived): names, cycles and dimensions
    r"is not defined \(its definition failed\)$",
    r"is not a quantity, a quantity's rate, a parameter or k",
    r"^the expression reads itself",
    r"^the expression is ",
    r"^it (adds|subtracts|compares) '",
    r"takes a pure number or an angle",
    r"^parameter '.*' has no unit",
    r"^'.*' is not defined: the expression",
    r"^'.*' is not defined: '.*' has",
    # design questions (input.find) and the vibration chapters' quantities
    r"is not a parameter of this file, so it cannot be an unknown",
    r"is also a quantity of the file$",
    r"unknowns? and \d+ targets?: a design question",
    r"^the target '.*' is not an answer",
    r"^the interval goes up",
    r"^cannot read the target",
    r"^'choose' picks one of several roots",
    r"is an unknown of 'find'",
    r"' is (a|an|of dimension) .* and the (target's |interval's )?unit '",
    r"^the values of '.*' are given in",
    r"^the two modes of a beat period must differ",
    r"^'unstretched' names no spring",
    # the periodic regime (input.regime): a sum of the areas, a cycle of an angle driver
    r"^the areas add up to ",
    r"turns of an angle driver",
    # a unit written as a product of the tables' units ('N s/m', 'mm/s^2') is free text in the
    # schema: only the loader can tell a product of units from an unknown word
    r"^unknown unit '[^']*'$",
]
_VALUE_RULES = [             # loader-only when the value is an expression (text)
    r"in expression '", r"^cannot parse expression", r"^'.*' is too small",
    r"^must be positive", r"^a driving length must be positive", r"must be positive, got",
    r"^printed value .* is not finite",
]


def loader_only(error: InputError, data) -> bool:
    """Whether ``error`` enforces a rule the JSON Schema cannot state."""
    detail, key = error.detail, error.key or ""
    if isinstance(error, ScaleError):   # a range in metres: the file's unit decides the number
        return True
    if any(re.search(p, detail) for p in _ALWAYS_LOADER):
        return True
    value = _value_at(data, key)
    if isinstance(value, str) and any(re.search(p, detail) for p in _VALUE_RULES):
        return True
    parts = key.split(".")
    # the keys of 'shape' and 'local' are the link's own points; its second point has
    # only a length
    if len(parts) >= 3 and parts[0] == "links" and parts[2] in ("shape", "local"):
        if detail.startswith("missing key") and len(parts) == 3:
            return True
        if detail.startswith("unknown key"):
            return len(parts) == 4 or (len(parts) == 5 and parts[4] in _SHAPE_POINT_KEYS)
    # a load quantity's unit depends on the kind of load (force or torque)
    if re.match(r"^unknown unit '(N|kN|lbf|lb|kip|Nm|Nmm|kNm|lbf ft|lbf in|kip ft)' for a load "
                r"quantity", detail):
        return True
    # a disc's radius may be left out where 'gears:' gives its teeth
    if detail == "missing key 'radius'" and parts[0] == "rolling":
        return True
    # a whole number written with a decimal point (5.0): JSON Schema calls it an integer
    if re.search(r"(digit 0-9|whole number 0-12), got -?\d+\.0$", detail):
        return True
    return False


def _value_at(data, key: str):
    for path in paths(data):
        if path_text(path) == key:
            value = data
            for part in path:
                value = value[part]
            return value
    return None


def compare(data, counter, what=""):
    """Loader and schema verdicts on ``data``; asserts they agree."""
    data.pop("dynamics", None) if isinstance(data, dict) else None
    text = to_yaml(data)
    try:
        doc = load_text(text, "fuzz.yaml")
    except InputError:
        counter["refused by the YAML reader"] += 1
        return
    schema_ok = VALIDATOR.is_valid(doc.data)
    try:
        parse(doc)
        loader_errors = []
    except InputError as exc:
        loader_errors = getattr(exc, "errors", [exc])
    counter["cases"] += 1
    context = f"\nmutation: {what}\nfile:\n{text}"
    if not loader_errors:
        counter["accepted by both"] += 1
        if not schema_ok:
            errors = [f"{path_text(tuple(e.absolute_path))}: {e.message}"[:300]
                      for e in VALIDATOR.iter_errors(doc.data)]
            pytest.fail(f"the loader accepts, the schema refuses: {errors}" + context)
        return
    expressible = [e for e in loader_errors if not loader_only(e, doc.data)]
    if expressible:
        counter["refused by both"] += 1
        assert not schema_ok, "the loader refuses, the schema accepts: " + "; ".join(
            str(e) for e in expressible) + context
    else:
        counter["refused by loader-only rules"] += 1


@pytest.mark.parametrize("path", SHIPPED + EXTRA, ids=os.path.basename)
def test_schema_and_loader_agree_on_mutated_files(path, fuzz_counter):
    base = data_of(path)
    examples = CASES_PER_FILE if path in SHIPPED else CASES_PER_FILE // 2

    @seed(zlib.crc32(b"schema " + os.path.basename(path).encode()))
    @settings(max_examples=examples, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    @given(case=mutated(base))
    def agree(case):
        data, what = case
        compare(data, fuzz_counter["schema vs loader"], what)

    agree()


def test_solve_does_not_import_jsonschema():
    code = ("import sys; from linkcli.cli import main; "
            "main(['solve', 'mechanisms/padova-2020-07.yaml']); "
            "sys.exit(3 if 'jsonschema' in sys.modules else 0)")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True)
    assert done.returncode == 0, done.stderr.decode()
