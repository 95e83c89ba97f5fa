"""Unit invariance: every shipped file (mechanisms/, docs/examples/), rewritten in other units
by tests/transforms.py, gives the same answers.

For each file, each digit k it is solved for (its own and its keys'), and each unit system of
:data:`SYSTEMS`, the file and its rewriting are solved through the Python API
(``linkcli.loads(...).solve()``, Newton's method where the closed form cannot decompose the
mechanism) and compared in SI with the unit factors of tests/transforms.py (written from the
units' definitions, not from linkcli's tables), angles modulo a turn, to 1e-9; an answer
whose quantity names its own ``unit:`` is also compared as displayed.  A file linkcli refuses
must be refused with the same exit code and error type.  Design questions (``find:``) are
solved again in the new units, and their solved parameters compared like every answer.

Files whose values the rewriter does not know where to place are listed in
:data:`NOT_REWRITTEN` with the reason, and the listing is checked, so none passes silently.
The planted defects at the end (a wrong Hz, inch or rpm factor in linkcli/model/units.py)
show that the comparison reports a wrong conversion.  ``make explore`` draws random unit
systems (:func:`test_random_systems`).
"""
from __future__ import annotations

import functools
import glob
import os
import random
import warnings

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import transforms as T
from linkcli.input.source import load_file
from linkcli.model import units as linkcli_units

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXPLORE = bool(os.environ.get("LINKCLI_EXPLORE"))


def _shipped() -> list:
    """The shipped files that read as a mapping (the others are examples of YAML errors)."""
    out = []
    for path in sorted(glob.glob(os.path.join(ROOT, "mechanisms", "*.yaml"))
                       + glob.glob(os.path.join(ROOT, "docs", "examples", "*.yaml"))):
        try:
            data = load_file(path).data
        except Exception:       # noqa: BLE001 - a file of the YAML errors' examples
            continue
        if isinstance(data, dict):
            out.append(os.path.relpath(path, ROOT))
    return out


FILES = _shipped()

#: unit systems every file is rewritten in (a kind not named takes its default)
SYSTEMS = {
    "si": {"length": "m", "angle": "rad", "force": "kN", "torque": "kNm", "mass": "kg",
           "inertia": "kg mm^2", "stiffness": "kN/m", "torsional_stiffness": "Nmm/rad",
           "damping": "kNs/m", "torsional_damping": "Nmms/rad", "frequency": "Hz",
           "angular_rate": "rpm", "speed": "km/h", "time": "ms", "pressure": "bar",
           "area": "cm^2"},
    "us": {"length": "in", "angle": "deg", "force": "lbf", "torque": "lbf in", "mass": "lb",
           "inertia": "lb in^2", "stiffness": "lbf/in", "torsional_stiffness": "lbf in/rad",
           "damping": "lbf s/in", "frequency": "rpm", "speed": "mph", "time": "s"},
    "bare": {"length": "m", "angle": "rad"},
    "turns": {"length": "cm", "angle": "deg", "angular_rate": "rev/s", "force": "N",
              "mass": "g", "frequency": "rad/s", "time": "ms", "stiffness": "N/mm",
              "torque": "Nmm"},
}

#: files the rewriter leaves alone, and why (each an example of an invalid file)
NOT_REWRITTEN = {
    "docs/examples/bad-bodies.yaml": "a misspelt key (lenght)",
    "docs/examples/bad-expressions.yaml": "a parameter written as a list",
    "docs/examples/bad-find.yaml": "a bare target of a quantity the file does not define",
    "docs/examples/bad-loads.yaml": "a load of an unknown type",
    "docs/examples/bad-losses.yaml": "a unit of another kind (pressure: N)",
    "docs/examples/bad-sections.yaml": "a unit the format does not have (inch)",
    "docs/examples/many-problems.yaml": "an unknown key (driver.spin)",
    "docs/examples/no-frame.yaml": "a section that is not a mapping (links)",
    "docs/examples/astronomical.yaml": "lengths of 1e299 km: out of range in m or in",
}


@functools.lru_cache(maxsize=None)
def data_of(path: str) -> dict:
    return load_file(os.path.join(ROOT, path)).data


@functools.lru_cache(maxsize=None)
def baseline(path: str, k) -> T.Outcome:
    """The file's own answers."""
    with open(os.path.join(ROOT, path), encoding="utf-8") as f, warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)      # astronomical.yaml's squares
        return T.solve(f.read(), k, path)


def check(path: str, system: dict) -> list:
    """The differences between ``path`` and its rewriting in ``system``, for every digit;
    None when the rewriter cannot rewrite it."""
    data = data_of(path)
    out = []
    for k in T.digits(data):
        base = baseline(path, k)
        rewrite = T.UnitRewrite(data, system, base.units)
        new = rewrite.run()
        if rewrite.unknown:
            return None
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            outcome = T.solve(T.to_yaml(new), k, path)
        lengths = (rewrite.old.factor("length"), rewrite.new.factor("length"))
        out += [f"k={k}: {d}" for d in T.differences(base, outcome, T.own_units(data),
                                                      lengths=lengths, same_keys=True)]
    return out


@pytest.mark.parametrize("path, system", [pytest.param(p, s, id=f"{p}-{s}")
                                          for p in FILES for s in SYSTEMS])
def test_same_answers_in_other_units(path, system, invariance_counter):
    differences = check(path, SYSTEMS[system])
    if differences is None:
        assert path in NOT_REWRITTEN, f"{path}: values the rewriter cannot place"
        invariance_counter["units: not rewritten"] += 1
        pytest.skip(f"not rewritten: {NOT_REWRITTEN[path]}")
    invariance_counter["units"] += len(T.digits(data_of(path)))
    assert not differences, f"{path} in {SYSTEMS[system]}:\n" + "\n".join(differences)


def test_files_not_rewritten_are_listed():
    """Exactly the files of :data:`NOT_REWRITTEN` hold values the rewriter cannot place,
    each listed with the places; every other file is rewritten in full."""
    found = {}
    for path in FILES:
        data = data_of(path)
        for k in T.digits(data):
            rewrite = T.UnitRewrite(data, SYSTEMS["bare"], baseline(path, k).units)
            rewrite.run()
            if rewrite.unknown:
                found[path] = rewrite.unknown
    assert set(found) == set(NOT_REWRITTEN), found
    assert len(NOT_REWRITTEN) < len(FILES) / 10


# --- the rewriter itself ------------------------------------------------------------------
def test_unit_factors_are_the_definitions():
    """The comparison's own factors: 1 in = 0.0254 m, 1 lbf = 0.45359237 kg x 9.80665 m/s^2,
    1 Hz = one turn per second, 1 rpm = one turn per minute."""
    assert T.factor("in") == 0.0254
    assert T.factor("lbf") == pytest.approx(4.4482216152605)
    assert T.factor("Hz") == pytest.approx(6.283185307179586)
    assert T.factor("rpm") == pytest.approx(0.10471975511965977)
    assert T.factor("kg mm^2") == pytest.approx(1e-6)
    assert T.factor("1/(in deg)") == pytest.approx(1 / (0.0254 * 0.017453292519943295))
    assert sorted(f for f, _ in T.parse("lb/in")) == pytest.approx(
        [0.45359237 / 0.0254, 4.4482216152605 / 0.0254])          # a mass, or a force
    system = T.System({"angle": "deg", "angular_rate": "rpm"})
    assert system.names["angular_accel"] == "deg/s^2"
    assert T.System({"angle": "rad"}).names["angular_accel"] == "rad/s^2"
    assert T.System({"force": "lbf", "length": "in"}).names["pressure"] == "lbf/in^2"


def test_parameters_keep_their_meaning():
    """A parameter written on its own as a length holds its value in the new unit; an
    expression reads it back in the old one and is converted as a whole."""
    data = {"units": {"length": "mm"}, "params": {"a": 100, "b": "a + 50"},
            "frame": {"A": [0, "b - 10"]}, "points": {"B": ["a", 0]},
            "links": {"AB": {"points": ["A", "B"], "length": "2*a"}}}
    rewrite = T.UnitRewrite(data, {"length": "m"})
    new = rewrite.run()
    assert rewrite.kinds == {"a": "length"}
    assert new["params"]["a"] == pytest.approx(0.1)
    assert new["params"]["b"] == "a / 0.001 + 50"            # b has no unit: kept in mm
    assert new["frame"]["A"][1] == "(b - 10)*0.001"           # so b - 10 is in mm
    assert new["points"]["B"][0] == "(a / 0.001)*0.001"
    assert T.scaled_name(new["links"]["AB"]["length"]) == "a"  # still a multiple of a


# --- planted defects ----------------------------------------------------------------------
PLANTED = [
    ("frequency Hz = 1 rad/s", "FREQUENCY", "Hz", 1.0,
     "mechanisms/polimi-2001-07-17-vibration.yaml", "si"),
    # a wrong length factor alone scales the whole mechanism, which a torque, a mass or an
    # inertia given in their own units then tells
    ("length in = 0.025 m", "LENGTH", "in", 0.025, "mechanisms/fourbar-inverse-dynamics.yaml",
     "us"),
    ("angular rate rpm = 2 pi rad/s", "ANGULAR_RATE", "rpm", 6.283185307179586,
     "mechanisms/khurmi-8-1-slider-crank-accelerations.yaml", "si"),
]


@pytest.mark.parametrize("what, table, unit, value, path, system", PLANTED,
                         ids=[p[0] for p in PLANTED])
def test_a_wrong_factor_is_caught(monkeypatch, what, table, unit, value, path, system):
    """A wrong factor planted in linkcli's table of units: the rewritten file disagrees."""
    found = caught(lambda: check(path, SYSTEMS[system]),
                   lambda: monkeypatch.setitem(getattr(linkcli_units, table), unit, value))
    assert found, f"planted '{what}' not caught"


def test_a_diametral_pitch_read_per_metre_is_caught(monkeypatch):
    """A diametral pitch read per metre whatever the file's length unit (P teeth per inch
    taken as P per metre): the file rewritten in millimetres gives other radii, so another
    contact ratio and centre distance."""
    from linkcli.input import gears
    found = caught(lambda: check("mechanisms/shigley-13-1-diametral-pitch.yaml", SYSTEMS["si"]),
                   lambda: monkeypatch.setattr(gears, "module_of_pitch",
                                               lambda pitch, unit_length: 1.0 / pitch))
    assert found, "planted 'diametral pitch per metre' not caught"


def test_a_payout_read_as_an_angle_is_caught(monkeypatch):
    """A cord's pay-out (value and rates) read in the file's angle units instead of its
    length units: the spool rewritten in radians turns otherwise."""
    from linkcli.input import contacts
    found = caught(lambda: check("docs/examples/spool-payout.yaml", SYSTEMS["si"]),
                   lambda: monkeypatch.setattr(contacts, "PAYOUT_KIND", "angle"))
    assert found, "planted 'pay-out in angle units' not caught"


def test_a_motor_speed_read_in_rad_per_s_is_caught(monkeypatch):
    """A motor's no-load speed read in rad/s whatever the file's angular rate (1500 rpm taken
    as 1500 rad/s): the press rewritten in deg/s starts up otherwise."""
    from linkcli.input import machine
    found = caught(lambda: check("docs/examples/machine-press.yaml", SYSTEMS["us"]),
                   lambda: monkeypatch.setattr(machine, "rate_factor", lambda units: 1.0))
    assert found, "planted 'motor speed in rad/s' not caught"


def caught(compare, plant) -> list:
    """What ``compare()`` finds once ``plant()`` has put a defect in (the files' own answers
    solved again with it), having found nothing before."""
    assert compare() == []
    baseline.cache_clear()
    try:
        plant()
        return compare()
    finally:
        baseline.cache_clear()


# --- random unit systems (make explore draws new ones) ------------------------------------
RANDOM = settings(derandomize=not EXPLORE, max_examples=300 if EXPLORE else 25,
                  deadline=None, database=None, suppress_health_check=list(HealthCheck))
REWRITTEN = [p for p in FILES if p not in NOT_REWRITTEN]


@RANDOM
@given(path=st.sampled_from(REWRITTEN), seed=st.integers(0, 2 ** 32 - 1))
def test_random_systems(path, seed, invariance_counter):
    system = T.random_system(random.Random(seed))
    invariance_counter["units: random"] += 1
    differences = check(path, system)
    assert differences == [], f"{path} in {system}:\n" + "\n".join(differences)


def test_rates_in_turns_per_second():
    """A crank's rates in rev/s: its acceleration in the angle unit per s^2 (as with rpm),
    where reading the file stopped on an internal error; the tip of a crank of 100 mm at
    30 deg turning 0.5 rev/s (pi rad/s) moves at -r w sin(30 deg) along x."""
    import math

    import linkcli
    text = """
units: {length: mm, angle: deg, angular_rate: rev/s}
frame: {A: [0, 0]}
points: {B: [87, 50]}
links: {AB: {points: [A, B], length: 100}}
driver: {angle: [A, B], value: 30, rate: 0.5, accel: 2}
quantities: {phi: {angle: [A, B]}}
report: {velocity: [phidot, xBdot], acceleration: [phiddot]}
"""
    result = linkcli.loads(text).solve()
    assert result.units["phidot"] == "rev/s" and result.values["phidot"] == pytest.approx(0.5)
    assert result.units["phiddot"] == "deg/s^2"
    assert result.values["phiddot"] == pytest.approx(2)
    assert result.values["xBdot"] == pytest.approx(-100 * math.pi * 0.5)


def test_parameter_units_are_those_of_the_format():
    """Every parameter has the unit the format gives it: the kind of the values it is written
    as on its own (tests/transforms.py).  An initial velocity of a length coordinate made its
    parameter a length (so ``{expr: v0, unit: m/s}`` was refused as a length, and ``unit:
    mm`` showed 500 mm for 500 mm/s)."""
    import linkcli
    for path in REWRITTEN:
        data = data_of(path)
        try:
            mech = linkcli.load(os.path.join(ROOT, path)).model
        except linkcli.LinkcliError:
            continue
        assert mech.param_kinds == T.param_kinds(data, T.Sites(data)), path
    text = """
units: {length: mm, stiffness: N/m}
params: {m: 2, ks: 200, v0: 500}
frame: {A: [0, 0]}
points: {P: [100, 0]}
sliders: {block: {point: P, guide: {y: 0}}}
coordinates: {x: {x: P}}
springs: {s: {between: [A, P], k: ks}}
dynamics: {masses: {P: m}}
initial: {x: 0, x_dot: v0}
quantities: {X: {largest: x}, v: {expr: v0, unit: m/s}}
report: {vibration: [X, v]}
"""
    values = linkcli.loads(text).solve().values
    # released at 0.5 m/s from equilibrium, w = sqrt(200/2) = 10 rad/s: X = v0/w = 50 mm
    assert values["X"] == pytest.approx(50.0)
    assert values["v"] == pytest.approx(0.5)


@pytest.mark.parametrize("path, name", [
    ("mechanisms/polimi-2001-07-04-vibration.yaml", "ka"),       # a coefficient: at once
    ("mechanisms/vib-cdquestions-spring-mass.yaml", "ks"),       # ... with an expression
    ("mechanisms/polimi-2001-09-18-vibration.yaml", "L"),        # a length: rebuilt
    ("mechanisms/padova-2020-02.yaml", "Fx"),                    # a load of a linkage
    ("docs/examples/design-spring.yaml", "m"),                   # a design at each value
])
def test_a_parameter_varied_in_other_units(path, name, invariance_counter):
    """``Linkage.vary`` over a parameter's values as the file writes them: the rewritten
    file, given the same values in the parameter's new unit, answers the same in SI."""
    import linkcli
    import numpy as np
    data = data_of(path)
    rewrite = T.UnitRewrite(data, SYSTEMS["us"], baseline(path, data.get("k")).units)
    new = rewrite.run()
    old_linkage = linkcli.load(os.path.join(ROOT, path))
    new_linkage = linkcli.loads(T.to_yaml(new), None, path)
    values = float(old_linkage.model.params[name]) * np.array([0.9, 1.0, 1.2])
    a = old_linkage.vary(name, values)
    b = new_linkage.vary(name, values * T.ratio(rewrite.old, rewrite.new, rewrite.kinds.get(name)))
    assert a.solved.all() and b.solved.all()
    for i in range(len(values)):
        row = [T.Outcome({n: float(v[i]) for n, v in r.values.items()}, dict(r.units))
               for r in (a, b)]
        assert T.differences(*row, T.own_units(data)) == [], (path, name, values[i])
    invariance_counter["units: varied parameters"] += len(values)


def test_the_rewriting_changes_the_numbers():
    """The rewritten files are not the files: in m, rad, kN or in, deg, lbf, every file with a
    length, an angle or a force written in it has other numbers there."""
    changed = 0
    for path in REWRITTEN:
        data = data_of(path)
        moved = []
        for system in ("si", "us"):
            rewrite = T.UnitRewrite(data, SYSTEMS[system])
            new = rewrite.run()
            sites = [p for p, kind in rewrite.sites.kinds.items()
                     if kind in ("length", "angle", "force") and T.literal(T.at(data, p))]
            moved += [T.at(new, p) != T.at(data, p) for p in sites]
        if moved:
            assert any(moved), path
            changed += 1
    assert changed > 0.8 * len(REWRITTEN)
