"""The formulas of --symbolic against the numbers of the same files.

For every shipped vibration problem (every file with ``coordinates:``): the file's numbers
put into the symbolic M, K, R and F give the numeric linearisation to 1e-12 (relative to
the largest entry), the characteristic polynomial's roots are the natural frequencies, and
the JSON strings read back (sympy.sympify) to the same numbers.  The formulas are checked
once more with every literal parameter moved by a few per cent, against the numbers of
the moved file: a number that lost its formula on the way (a constant where a parameter
should be) agrees at the file's values only, and fails there.
"""
from __future__ import annotations

import glob
import json
import os

import numpy as np
import pytest
import sympy as sp

import linkcli
from conftest import MECHANISMS
from linkcli.answers.symbolic import as_dict, formulas
from linkcli.forces.lagrange import Lagrangian
from linkcli.forces.vibration import linearise, modes
from linkcli.input.document import build
from linkcli.input.source import load_file
from linkcli.input.symbols import Symbolic
from linkcli.kinematics.solvers import solver_for

FILES = sorted(os.path.basename(p) for p in glob.glob(os.path.join(MECHANISMS, "*.yaml"))
               if "coordinates:" in open(p).read())
_CACHE = {}


def of(name):
    """(formulas, numeric linearisation) of a shipped file, once per session."""
    if name not in _CACHE:
        doc = load_file(os.path.join(MECHANISMS, name))
        mech = build(doc)
        _CACHE[name] = (formulas(doc), linearise(Lagrangian(mech, solver_for(mech))))
    return _CACHE[name]


def numeric(expr, values) -> np.ndarray:
    if isinstance(expr, (list, tuple)):
        return np.array([complex(sp.N(sp.sympify(x).xreplace(values), 30)) for x in expr])
    out = sp.sympify(expr).xreplace(values)
    if isinstance(out, sp.MatrixBase):
        return np.array(out.evalf(30).tolist(), dtype=complex)
    return np.complex128(complex(sp.N(out, 30)))


def assert_relative(got, expected, tol=1e-12, what=""):
    got, expected = np.atleast_1d(got), np.atleast_1d(expected)
    scale = max(float(np.max(np.abs(expected))), 1e-300)
    assert np.max(np.abs(got - expected)) <= tol * scale, (what, got, expected)


def test_every_vibration_file_is_covered():
    assert len(FILES) >= 21
    assert all(n.startswith(("vib-", "polimi-2001-")) for n in FILES)


@pytest.mark.parametrize("name", FILES)
def test_matrices_are_the_numeric_ones(name):
    f, lin = of(name)
    assert not f.missing
    values = f.numbers
    for item, expected in (("M", lin.M), ("K", lin.K), ("R", lin.R)):
        assert_relative(numeric(f.values[item], values), expected, what=f"{name} {item}")
        assert not f.values[item].has(sp.Float), (name, item)
    if lin.frequency is not None:
        expected = lin.load(lin.frequency)
        assert_relative(numeric(f.values["F"], values), expected, what=f"{name} F")


@pytest.mark.parametrize("name", FILES)
def test_characteristic_roots_are_the_natural_frequencies(name):
    f, lin = of(name)
    w = sp.Symbol("w2")
    poly = sp.Poly(f.values["characteristic"].xreplace(
        {sp.Symbol("omega", positive=True): sp.sqrt(w)}), w)
    coefficients = [complex(sp.N(c.xreplace(f.numbers), 30)).real for c in poly.all_coeffs()]
    roots = np.sort(np.roots(coefficients).real)
    expected = modes(lin).omega
    assert np.sqrt(roots) == pytest.approx(expected, rel=1e-9)
    if f.roots is not None:                       # the printed roots, where short
        printed = np.sort([complex(sp.N(r.xreplace(f.numbers), 30)).real for r in f.roots])
        assert np.sqrt(printed) == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("name", FILES)
def test_json_strings_read_back(name):
    """Every string is sympify-able with the symbols and coordinates as local names, and
    means the same numbers."""
    f, lin = of(name)
    data = json.loads(json.dumps(as_dict(f)))
    names = set(data["symbols"]) | set(data["coordinates"]) | set(data["imposed"])
    names |= {f"{n}_dot" for n in data["coordinates"] + data["imposed"]}
    names |= {f"{n}_ddot" for n in data["coordinates"] + data["imposed"]} | {"t", "omega"}
    local = {n: sp.Symbol(n) for n in names}
    plain = {sp.Symbol(s.name): v for s, v in f.numbers.items()}
    for item in ("M", "K", "R"):
        got = sp.Matrix([[sp.sympify(x, locals=local) for x in row] for row in data[item]])
        assert_relative(numeric(got, plain), getattr(lin, item), what=f"{name} {item}")
    assert set(data) >= {"coordinates", "symbols", "T", "V", "D", "M", "K", "R", "F",
                         "equations", "stability", "characteristic"}
    for text in [data["T"], data["V"], data["D"], data["characteristic"]] + \
            data["equations"] + data["stability"] + data["F"]:
        sp.sympify(text, locals=local)
    assert set(data["symbols"]) <= set(f.mech.params) | {"g"} | \
        {f"{c}_e" for c in data["coordinates"]}


def moved(name):
    """The file's document with every literal parameter moved by 1 to 4 %."""
    doc = load_file(os.path.join(MECHANISMS, name))
    params = doc.data.get("params") or {}
    for i, (key, value) in enumerate(sorted(params.items())):
        if isinstance(value, (int, float)) and not isinstance(value, bool) and value != 0:
            params[key] = value * (1 + 0.01 * (1 + i % 4))
    return doc


@pytest.mark.parametrize("name", FILES)
def test_formulas_hold_for_other_numbers(name):
    f, _ = of(name)
    doc = moved(name)
    reading = Symbolic()
    build(doc, None, reading)
    values = dict(reading.values())
    if "g" in f.symbols:
        values[sp.Symbol("g", positive=True)] = f.numbers[sp.Symbol("g", positive=True)]
    mech = build(doc)
    lin = linearise(Lagrangian(mech, solver_for(mech)))
    for q, value in zip(f.stated, lin.eq.q[[f.mech.coordinates.index(c) for c in
                                           f.mech.coordinates if f"{c.name}_e" in
                                           {s.name for s in f.stated}]]):
        values[q] = value
    for item, expected in (("M", lin.M), ("K", lin.K), ("R", lin.R)):
        assert_relative(numeric(f.values[item], values), expected, what=f"{name} {item}")
    if lin.frequency is not None:
        assert_relative(numeric(f.values["F"], values), lin.load(lin.frequency),
                        what=f"{name} F")
