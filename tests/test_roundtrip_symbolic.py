"""Round trip of --symbolic: the formulas with the file's numbers put in are the numbers.

For every shipped file (mechanisms/ and docs/examples/) where the numbers answer:

- a vibration problem: M, K, R and F, the static equilibrium and the natural frequencies
  (omega^2: the roots of the written characteristic polynomial, the eigenvalues of M^-1 K) at the file's numbers equal the
  numeric linearisation (``forces.vibration``) to a relative 1e-9; an item the formulas
  name as not available is skipped, and only those of a file whose positions are roots of
  closure equations may be (its closures are then checked as a linkage's);
- a linkage: at the file's driver value, the solver's positions, velocities and
  accelerations satisfy every written closure and both its rate systems to 1e-9 of the
  terms' size (those whose symbols all measure an angle, a length, a guide's abscissa or a
  coordinate: a slot's abscissa has no measure recorded).

The two planted defects at the end show that the checks bite: the numeric stiffness
matrix without its coupling terms, and the closures' rate systems with their right side's
sign turned, are each reported.
"""
from __future__ import annotations

import glob
import os

import numpy as np
import pytest
import sympy as sp

from linkcli.runs.sheet import evaluate
from linkcli.texts.symbolic import ITEMS, formulas
from linkcli.errors import LinkcliError
from linkcli.forces import lagrange
from linkcli.forces.vibration import linearise
from linkcli.input.document import build
from linkcli.input.source import load_file
from linkcli.kinematics import symbolic as ks
from linkcli.kinematics.solvers import solver_for

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FILES = sorted(os.path.relpath(p, ROOT) for p in
               glob.glob(os.path.join(ROOT, "mechanisms", "*.yaml")) +
               glob.glob(os.path.join(ROOT, "docs", "examples", "*.yaml")))
TOL = 1e-9
#: seconds enough for every shipped file on a loaded machine: a formula not reached would
#: leave an item unchecked
SECONDS = 120.0


def numeric(expr, values):
    out = sp.sympify(expr).xreplace(values)
    if isinstance(out, sp.MatrixBase):
        return np.array(out.evalf(30).tolist(), dtype=complex)
    return complex(sp.N(out, 30))


def close(got, expected, scale, what):
    got, expected = np.atleast_1d(got), np.atleast_1d(expected)
    assert got.shape == expected.shape, (what, got, expected)
    assert np.max(np.abs(got - expected)) <= TOL * scale, (what, got, expected)


def model(name):
    """(numeric model, formulas) of a shipped file; None where the numbers do not answer."""
    try:
        doc = load_file(os.path.join(ROOT, name))
        mech = build(doc)
        evaluate(mech)                        # what `linkcli solve` answers
    except LinkcliError:
        return None
    if mech.clutch is not None:         # shafts and a clutch: no formulas (docs/machines.md)
        return None
    return mech, formulas(doc, seconds=SECONDS)


def check_vibration(mech, f):
    """M, K, R, F, the equilibrium and the natural frequencies against the numbers."""
    lin = linearise(lagrange.Lagrangian(mech, solver_for(mech)))
    if f.missing:
        assert f.loop is not None and set(f.missing) == set(ITEMS), f.missing
        return 0
    values = f.numbers
    for item, expected in (("M", lin.M), ("K", lin.K), ("R", lin.R)):
        close(numeric(f.values[item], values), expected, max(np.max(np.abs(expected)), 1e-300),
              item)
    if lin.frequency is not None:
        expected = lin.load(lin.frequency)
        close(numeric(sp.Matrix(f.values["F"]), values).ravel(), expected,
              max(np.max(np.abs(expected)), 1e-300), "F")
    points = np.array([complex(z) for z in list(mech.fixed.values()) +
                       list(mech.moving.values())])
    size = float(np.max(np.abs(points - points.mean()))) or 1.0
    for j, c in enumerate(mech.coordinates):
        if c.name in f.values["equilibrium"]:
            scale = 1.0 if c.base == "angle" else size
            close(numeric(f.values["equilibrium"][c.name], values).real, lin.eq.q[j], scale,
                  f"equilibrium {c.name}")
    w = sp.Symbol("w2")
    poly = sp.Poly(f.values["characteristic"].xreplace(
        {sp.Symbol("omega", positive=True): sp.sqrt(w)}), w)
    found = np.sort(np.roots([numeric(c, values).real for c in poly.all_coeffs()]).real)
    expected = np.sort(np.linalg.eigvals(np.linalg.solve(lin.M, lin.K)).real)   # omega^2
    close(found, expected, np.max(np.abs(expected)), "natural frequencies (omega^2)")
    return 1


def _measured(meaning, kin, values):
    """(value, rate, acceleration) of what a closure's symbol measures, from the solver."""
    def at(d, p):
        return complex(np.ravel(d.get(p, 0.0))[0])
    pos, vel, acc = kin.pos, kin.vel, kin.acc
    kind = meaning[0]
    if kind in ("angle", "length"):
        z, v, a = (at(d, meaning[2]) - at(d, meaning[1]) for d in (pos, vel, acc))
        if kind == "angle":
            rate = v / z
            return np.angle(z), rate.imag, (a / z - rate ** 2).imag
        r = abs(z)
        rate = (v * z.conjugate()).real / r
        return r, rate, ((a * z.conjugate()).real + abs(v) ** 2 - rate ** 2) / r
    if kind == "coordinate":
        part = (lambda z: z.real) if meaning[2] == "x" else (lambda z: z.imag)
        return tuple(part(at(d, meaning[1])) for d in (pos, vel, acc))
    _, p, g, gamma = meaning
    turn = np.exp(-1j * numeric(gamma, values).real)
    return (((at(pos, p) - numeric(g, values)) * turn).real, (at(vel, p) * turn).real,
            (at(acc, p) * turn).real)


def check_linkage(mech, loop):
    """Every closure and its two rate systems at the solver's motion; the closures checked."""
    if mech.driver is None or mech.elements is not None:
        return 0
    solver = solver_for(mech)
    drivers = mech.coordinates                  # one driver, or several each driven
    value, rate, accel = ((tuple(getattr(c, a) for c in drivers) if len(drivers) > 1
                           else getattr(drivers[0], a)) for a in ("value", "rate", "accel"))
    kin = solver.positions(value)
    solver.velocities(kin, rate)
    solver.accelerations(kin, accel)
    values = dict(loop.numbers)
    values.update({k: float(v) for k, v in loop.values.items()})
    for symbol, meaning in loop.meaning.items():
        x, v, a = _measured(meaning, kin, values)
        values.update({symbol: x, sp.Symbol(f"{symbol.name}_dot", real=True): v,
                       sp.Symbol(f"{symbol.name}_ddot", real=True): a})
    checked = 0
    for c in loop.closures:
        if c.matrix is None:
            continue
        symbols = (c.left - c.right).free_symbols | c.matrix.free_symbols | \
            c.velocity.free_symbols | c.acceleration.free_symbols
        if not symbols <= set(values):
            continue                        # a slot's abscissa: no measure to compare
        scale = max(abs(numeric(c.left, values)), 1e-3)
        close(numeric(c.left - c.right, values), 0, scale, c.text)
        for order, rhs in ((1, c.velocity), (2, c.acceleration)):
            u = sp.Matrix([sp.Symbol(f"{x.name}_{'d' * order}ot", real=True)
                           for x in c.unknowns])
            size = max(float(np.max(np.abs(numeric(rhs, values)))), 1.0)
            close(numeric(c.matrix * u - rhs, values).ravel(), np.zeros(2), size,
                  f"{c.text} rates of order {order}")
        checked += 1
    return checked


def closures_of(name):
    """The closures of a linkage with their meanings (``kinematics.symbolic.Closures``)."""
    from linkcli.input.symbols import Symbolic
    reading = Symbolic()
    traced = build(load_file(os.path.join(ROOT, name)), None, symbolic=reading)
    found = ks.Closures(ks.Symbols(traced, reading.si(), reading.values()))
    found.numbers = reading.values()
    return found


_CACHE = {}


def answered(name):
    if name not in _CACHE:
        _CACHE[name] = model(name)
    return _CACHE[name]


@pytest.mark.parametrize("name", FILES)
def test_formulas_with_the_numbers_put_in_are_the_numbers(name):
    found = answered(name)
    if found is None:
        pytest.skip("the numbers do not answer this file")
    mech, f = found
    if mech.elements is not None:
        check_vibration(mech, f)
        return
    check_linkage(mech, closures_of(name))


def test_the_round_trip_covers_the_shipped_files():
    vibrations = [n for n in FILES if answered(n) is not None and
                  answered(n)[0].elements is not None]
    linkages = [n for n in FILES if answered(n) is not None and answered(n)[0].elements is None]
    assert len(vibrations) >= 30 and len(linkages) >= 50
    written = sum(check_vibration(*answered(n)) for n in vibrations)
    assert written >= len(vibrations) - 3          # closed loops give their closures only
    closed = sum(1 for n in linkages if check_linkage(answered(n)[0], closures_of(n)))
    assert closed >= 40


def test_a_numeric_stiffness_without_its_coupling_is_caught(monkeypatch):
    """Planted defect: the numeric K loses its off-diagonal terms (a coupling spring's)."""
    name = "mechanisms/polimi-2001-09-18-vibration.yaml"
    mech, f = answered(name)
    check_vibration(mech, f)
    terms = lagrange.Lagrangian.terms

    def planted(self, q):
        t = terms(self, q)
        t.K = np.diag(np.diag(t.K))
        return t
    monkeypatch.setattr(lagrange.Lagrangian, "terms", planted)
    with pytest.raises(AssertionError, match="K"):
        check_vibration(mech, f)


def test_a_rate_formula_with_its_sign_turned_is_caught(monkeypatch):
    """Planted defect: the rate systems' right sides written with the opposite sign."""
    name = "mechanisms/polimi-crank-slider.yaml"
    mech, _ = answered(name)
    assert check_linkage(mech, closures_of(name)) >= 1
    tidy = ks._tidy
    monkeypatch.setattr(ks, "_tidy", lambda expr: -tidy(expr))
    with pytest.raises(AssertionError, match="rates of order 1"):
        check_linkage(mech, closures_of(name))


TWINS = [("linkcli.kinematics.symbolic", "linkcli.kinematics.closed_form"),
         ("linkcli.forces.symbolic", "linkcli.forces.lagrange"),
         ("linkcli.forces.symbolic", "linkcli.forces.oscillation"),
         ("linkcli.texts.symbolic", "linkcli.answers.quantities.vibration"),
         ("linkcli.input.symbols", "linkcli.input.document")]


@pytest.mark.parametrize("formulas_module, numbers_module", TWINS)
def test_each_symbolic_module_and_its_numeric_twin_name_each_other(formulas_module,
                                                                    numbers_module):
    import importlib
    a, b = (importlib.import_module(m) for m in (formulas_module, numbers_module))
    assert numbers_module.removeprefix("linkcli.") in a.__doc__
    assert formulas_module.removeprefix("linkcli.") in b.__doc__
