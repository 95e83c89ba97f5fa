"""Hypothesis strategies for fuzzing: mutated mechanism files, random values and
random expressions.  Shared by tests/test_fuzz.py and tests/test_schema.py.
"""
from __future__ import annotations

import copy
import glob
import math
import os

import yaml
from hypothesis import strategies as st

from linkcli.input.source import load_file

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHIPPED = sorted(glob.glob(os.path.join(ROOT, "mechanisms", "*.yaml")))
TEMPLATE = os.path.join(ROOT, "linkcli", "input", "templates", "mechanism.yaml")
EXTRA = sorted(glob.glob(os.path.join(ROOT, "tests", "data", "*.yaml"))) + [TEMPLATE]

SPECIAL_NUMBERS = [0, -0.0, 1, -1, 0.5, -2.5, 1e-3, 360, -720, 1e6, 2 ** 53 + 1,
                   1e300, -1e300, 1.5e300, 1e308, 1e-300, -1e-300, 1e-310, 5e-324,
                   math.nan, math.inf, -math.inf, 10 ** 400, -(10 ** 400)]
SPECIAL_TEXTS = ["", " ", "unknown", "left", "right", "force", "torque", "axial", "driver",
                 "x", "y", "A", "B", "frame", "k", "pi", "deg", "nan", "inf", "-inf", "1e999",
                 "28,9", "0x1F", "1_000", "~", "null", "true", "mm", "rad", "rpm", "kN",
                 "9**9**9", "1/0", "__import__('os')", "().__class__", "a" * 500,
                 "(" * 100 + "1" + ")" * 100, "-" * 300 + "1", "A\n", "ｋ", "1 # c"]


def data_of(path: str):
    """Plain data of a mechanism file, as the loader reads it."""
    return load_file(path).data


class _Dumper(getattr(yaml, "CSafeDumper", yaml.SafeDumper)):
    def ignore_aliases(self, _data):
        return True


def to_yaml(data) -> str:
    """YAML text of ``data`` (no anchors: every repeated object is written out)."""
    return yaml.dump(data, Dumper=_Dumper, sort_keys=False, allow_unicode=True)


_NUMBERS = st.one_of(st.sampled_from(SPECIAL_NUMBERS), st.floats(),
                     st.integers(-10 ** 6, 10 ** 6), st.floats(-1e4, 1e4))


def numbers():
    return _NUMBERS


_ATOMS = st.one_of(
    st.integers(0, 10 ** 6).map(str),
    st.floats(0, 1e6).map(repr),
    st.sampled_from(["k", "pi", "deg", "r", "l", "q", "zz", "1e308", "1e-320", "1e400", "9",
                     "0", "0.0", "__import__", "True", "None", "'s'", "1j", "...", "x"]))


def _combine(children):
    ops = ["+", "-", "*", "/", "**", "//", "%", " < ", " and ", ","]
    funcs = ["sqrt", "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "abs", "hypot",
             "exp", "open", "eval", "getattr"]
    return st.one_of(
        st.tuples(children, st.sampled_from(ops), children).map(lambda t: f"({t[0]}{t[1]}{t[2]})"),
        children.map(lambda c: f"-{c}"),
        st.tuples(st.sampled_from(funcs), st.lists(children, max_size=3)).map(
            lambda t: f"{t[0]}({', '.join(t[1])})"),
        children.map(lambda c: f"{c}.real"),
        children.map(lambda c: f"{c}[0]"),
        children.map(lambda c: f"(lambda: {c})()"),
    )


_EXPRESSIONS = st.recursive(_ATOMS, _combine, max_leaves=10)
_SCALARS = st.one_of(_NUMBERS, st.sampled_from(SPECIAL_TEXTS), st.text(max_size=10),
                     _EXPRESSIONS, st.none(), st.booleans())
_VALUES = st.recursive(_SCALARS, lambda c: st.lists(c, max_size=3) | st.dictionaries(
    st.text(max_size=6), c, max_size=3), max_leaves=5)
_OPS = st.sampled_from(["delete", "replace", "number", "expression", "swap-list",
                        "swap-points", "rename", "add-key"])
_NEW_KEYS = st.sampled_from(["extra", "length", "angle", "points", "type", "value", "unknown",
                             "A\n", "x", "dynamics"]) | st.text(max_size=5)


def expressions():
    """Random expression text: mostly the allowed grammar, sometimes forbidden forms."""
    return _EXPRESSIONS


def values():
    """Any YAML value: numbers, text, expressions, null, booleans, lists, mappings."""
    return _VALUES


# --- mutations -------------------------------------------------------------------------
def paths(data, prefix=()):
    """Every path (tuple of keys and indices) below the root of ``data``."""
    if isinstance(data, dict):
        for key, value in data.items():
            yield prefix + (key,)
            yield from paths(value, prefix + (key,))
    elif isinstance(data, list):
        for index, value in enumerate(data):
            yield prefix + (index,)
            yield from paths(value, prefix + (index,))


def get(data, path):
    for part in path:
        data = data[part]
    return data


def point_names(data) -> list[str]:
    names = []
    for section in ("frame", "points"):
        if isinstance(data.get(section), dict):
            names += [n for n in data[section] if isinstance(n, str)]
    return names


def mutate(draw, data):
    """One random mutation of ``data`` (changed in place); returns its description."""
    every = list(paths(data))
    if not every:
        return "empty"
    op = draw(_OPS)
    path = draw(st.sampled_from(every))
    parent, last = get(data, path[:-1]), path[-1]
    if op == "delete":
        del parent[last]
    elif op == "replace":
        parent[last] = draw(values())
    elif op == "number":
        numeric = [p for p in every if isinstance(get(data, p), (int, float))
                   and not isinstance(get(data, p), bool)]
        if numeric:
            path = draw(st.sampled_from(numeric))
        get(data, path[:-1])[path[-1]] = draw(numbers())
    elif op == "expression":
        get(data, path[:-1])[path[-1]] = draw(expressions())
    elif op == "swap-list":
        lists = [p for p in every if isinstance(get(data, p), list) and len(get(data, p)) >= 2]
        if lists:
            items = get(data, draw(st.sampled_from(lists)))
            i, j = draw(st.sampled_from([(0, 1), (0, -1), (1, -1)]))
            items[i], items[j] = items[j], items[i]
    elif op == "swap-points":
        names = point_names(data)
        if len(names) >= 2:
            a, b = draw(st.lists(st.sampled_from(names), min_size=2, max_size=2, unique=True))
            where = {n: s for s in ("frame", "points") if isinstance(data.get(s), dict)
                     for n in data[s]}
            data[where[a]][a], data[where[b]][b] = data[where[b]][b], data[where[a]][a]
    elif op == "rename":
        names = point_names(data) + ["frame", "Z", "q"]
        refs = [p for p in every if isinstance(get(data, p), str) and get(data, p) in names]
        if refs:
            path = draw(st.sampled_from(refs))
            get(data, path[:-1])[path[-1]] = draw(st.sampled_from(names))
    else:
        holders = [()] + [p for p in every if isinstance(get(data, p), dict)]
        holder = get(data, draw(st.sampled_from(holders)))
        key = draw(_NEW_KEYS)
        holder[key] = draw(values())
    return f"{op} {path}"


@st.composite
def mutated(draw, base):
    """``base`` (plain data) after one to three random mutations: (data, description)."""
    data = copy.deepcopy(base)
    steps = [mutate(draw, data) for _ in range(draw(st.integers(1, 3)))]
    return data, "; ".join(steps)
