"""The evaluation plan (answers.quantities.Plan) gives the values of evaluating every name
on its own, on every shipped mechanism with a driver, at the file's position and at random
driver values; it is built once per (mechanism, names, method) and reused.

These are the plan's general path (its kernels on the solver's kinematics), bit for bit;
the straight-line path it takes first where it can (``kinematics.straight``) is held to
this one within rounding by tests/test_straight.py, and is switched off here."""
from __future__ import annotations

import glob
import math
import os

import numpy as np
import pytest

import linkcli
from linkcli.answers.quantities import plan as quantities
from linkcli.answers.quantities import TEXTBOOK, Result, plan_for, report_names
from linkcli.errors import LinkcliError, SolveError
from linkcli.kinematics.solvers import solver_for
from linkcli.model.mechanism import split_rate
from linkcli.input.source import load_file

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@pytest.fixture(autouse=True)
def general_path(monkeypatch):
    """The plan's general path: no straight-line solve (tests/test_straight.py)."""
    monkeypatch.setattr(quantities, "straight_of", lambda *args: None)


#: a clutch problem (shafts:, docs/machines.md) has no driver values to plan
SHIPPED = sorted(p for p in glob.glob(os.path.join(ROOT, "mechanisms", "*.yaml"))
                 if "shafts" not in load_file(p).data)
FOURBAR = """title: four-bar
units: {length: mm, angle: deg}
frame: {A0: [0, 0], B0: [300, 0]}
points: {A: [0, 100], B: [250, 250]}
links:
  crank: {points: [A0, A], length: 100}
  coupler: {points: [A, B], length: 280}
  rocker: {points: [B0, B], length: 260}
driver: {angle: [A0, A], value: 90, rate: 10, accel: 2}
quantities: {beta: {angle: [A, B]}, gamma: {angle: [B0, B], signed: true}, AB: {length: [A0, B]}}
report:
  position: [beta, gamma, AB, xB, yB]
  velocity: [betadot, gammadot, ABdot, xBdot]
  acceleration: [betaddot, gammaddot, ABddot, yBddot]
  points: [B]
"""


KINDS = ("q", "x", "y", "angle", "length", "load") + TEXTBOOK


def _driven(path):
    try:
        mech = linkcli.load(path).model
    except LinkcliError:
        return None
    return mech if mech.elements is None and len(mech.coordinates) == 1 else None


#: the shipped files with a driver (vibration problems have coordinates and no driver)
FILES = [p for p in SHIPPED if _driven(p) is not None]


def _names(mech):
    """The report's names of the kinds evaluated at one position (not sweeps' maxima)."""
    return [n for n in dict.fromkeys(report_names(mech))
            if mech.quantities[split_rate(n)[0]].kind in KINDS]


def _each(mech, kin, names):
    """Every name evaluated on its own by quantities.value_of (no plan), on ``kin``."""
    kin.vectors.clear()
    return quantities._collect_each(mech, solver_for(mech), kin, names, Result(mech))


def _driver_values(mech, count=12, seed=0):
    """Random driver values (display units) around the file's: a whole turn for an angle,
    +-10 % for a length."""
    base = "angle" if mech.driver.kind == "angle" else "length"
    factor = mech.units.display(base, 0)[1]
    value = mech.driver.value / factor
    rng = np.random.default_rng(seed)
    spread = 2 * math.pi / factor if base == "angle" else 0.1 * max(abs(value), 1e-9)
    return value + spread * rng.uniform(-0.5, 0.5, count)


def _same(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return a.shape == b.shape and np.array_equal(a, b)


@pytest.mark.parametrize("path", FILES, ids=os.path.basename)
def test_plan_gives_the_values_of_each_name_on_its_own(path):
    mech = _driven(path)
    names = _names(mech)
    try:
        quantities.evaluate(mech, names=names)
    except LinkcliError:
        pytest.skip("not solved by the closed form at the file's own position")
    points = [None] + list(_driver_values(mech))
    solved = 0
    for q in points:
        try:
            planned = quantities.evaluate(mech, q, names=names)
        except LinkcliError:
            continue                       # unassembled or singular there: refused by both
        try:
            direct = _each(mech, planned.kinematics, names)
        except SolveError:
            continue
        solved += 1
        assert list(planned.values) == list(direct.values)
        for name, value in direct.values.items():
            assert _same(planned.values[name], value), (name, q, planned.values[name], value)
            assert planned.units[name] == direct.units[name], name
        for p, xy in direct.points.items():
            assert all(_same(u, v) for u, v in zip(planned.points[p], xy)), p
    assert solved, "not even the file's own position solved"


@pytest.mark.parametrize("path", FILES, ids=os.path.basename)
def test_plan_on_an_array_gives_each_position_as_alone(path):
    """One position and many take the same path: an array of driver values gives, row by
    row, the values of each driver value solved alone."""
    mech = _driven(path)
    alone = {}
    names = _names(mech)
    for q in _driver_values(mech, 8, seed=1):
        try:
            alone[q] = quantities.evaluate(mech, q, names=names).values
        except LinkcliError:
            continue
    if not alone:
        pytest.skip("no random driver value assembles")
    many = quantities.evaluate(mech, np.array(list(alone)), names=names).values
    for i, values in enumerate(alone.values()):
        for name, value in values.items():
            assert np.isclose(many[name][i], value, rtol=1e-12, atol=1e-12), (name, i)


def test_plan_is_built_once_and_reused(monkeypatch):
    mech = linkcli.loads(FOURBAR).model
    built = []
    init = quantities.Plan.__init__

    def counting(self, *args, **kw):
        built.append(args[1])
        init(self, *args, **kw)
    monkeypatch.setattr(quantities.Plan, "__init__", counting)
    first = plan_for(mech)
    for q in (80.0, np.linspace(0, 90, 7), 10.0):
        quantities.evaluate(mech, q)
        quantities.evaluate(mech, q, names=["beta", "gammadot"])
    assert plan_for(mech) is first
    assert len(built) == 2, built                   # the report's names, and the two asked
    assert plan_for(mech, ["beta", "gammadot"]) is plan_for(mech, ("beta", "gammadot"))
    assert plan_for(mech, method="newton") is not first


def test_plan_values_against_the_definitions():
    """beta = arg(B - A) in [0, 360), gamma signed in (-180, 180], AB = |B - A0|, and their
    rates against central differences of the positions."""
    mech = linkcli.loads(FOURBAR).model
    q = np.linspace(40, 140, 11)
    res = quantities.evaluate(mech, q)
    pos = res.kinematics.pos
    z = (pos["B"] - pos["A"]) / 1e-3
    assert np.allclose(res.values["beta"], np.degrees(np.angle(z)) % 360, atol=1e-12)
    gamma = np.degrees(np.angle(pos["B"] - pos["B0"]))
    assert np.allclose(res.values["gamma"], gamma, atol=1e-12)
    assert np.all((res.values["gamma"] > -180) & (res.values["gamma"] <= 180))
    assert np.allclose(res.values["AB"], np.abs(pos["B"] - pos["A0"]) / 1e-3, rtol=1e-14)
    h = 1e-4
    up, dn = quantities.evaluate(mech, q + h), quantities.evaluate(mech, q - h)
    rate = 10.0           # deg/s
    for name in ("beta", "gamma", "AB"):
        d1 = (up.values[name] - dn.values[name]) / (2 * h) * rate
        scale = np.max(np.abs(res.values[name + "dot"]))
        assert np.allclose(res.values[name + "dot"], d1, atol=1e-7 * scale), name


def test_a_non_finite_value_is_named_not_returned(monkeypatch):
    """One finiteness check for the whole table still names the first bad quantity."""
    mech = linkcli.loads(FOURBAR).model
    kin = quantities.evaluate(mech, 80.0).kinematics
    kin.vectors.clear()
    kin.pos["B"] = kin.pos["B"] * np.nan
    with pytest.raises(SolveError, match="'beta' is not a finite number"), \
            np.errstate(all="ignore"):
        plan_for(mech).collect(mech, solver_for(mech), kin)


@pytest.mark.parametrize("source", ["four-bar", "crank-slider"])
def test_a_long_array_in_blocks_gives_the_whole_array_values_bit_for_bit(source, monkeypatch):
    """Above BLOCK driver values the plan solves BLOCK at a time: the same numbers, to the
    last bit in the whole blocks, as one pass over the whole array (NumPy's loops may round
    the last bit of a short tail block otherwise), and the same kinematics when read."""
    import sys
    sys.path.insert(0, os.path.join(ROOT, "benchmarks"))
    from speed_accuracy import CRANK_SLIDER, FOURBAR as BENCH_FOURBAR
    mech = linkcli.loads(BENCH_FOURBAR if source == "four-bar" else CRANK_SLIDER).model
    names = report_names(mech)
    block = quantities.BLOCK
    q = np.linspace(0.0, 360.0, 2 * block + 7)
    blocks = quantities.evaluate(mech, q, names=names)
    monkeypatch.setattr(quantities, "BLOCK", 10 ** 9)
    whole = quantities.evaluate(mech, q, names=names)
    full = 2 * block
    for name in names:
        got, expected = blocks.values[name], whole.values[name]
        assert np.array_equal(got[:full], expected[:full]), name
        assert np.allclose(got[full:], expected[full:], rtol=1e-14,
                           atol=1e-14 * np.max(np.abs(expected))), name
    for p in mech.moving:
        assert np.array_equal(blocks.kinematics.pos[p], whole.kinematics.pos[p]), p


SCATTERED = FOURBAR.replace(
    "quantities: {beta: {angle: [A, B]}, gamma: {angle: [B0, B], signed: true}, "
    "AB: {length: [A0, B]}}",
    "quantities: {beta: {angle: [A, B]}, gamma: {angle: [B0, B], signed: true}, "
    "AB: {length: [A0, B]}, theta: {angle: [A0, A], unit: rad}, "
    "back: {angle: [B, A], signed: true}}")


@pytest.mark.parametrize("q", [80.0, np.linspace(-170.0, 190.0, 37)])
def test_angles_in_any_order_units_and_signs_are_each_names_value(q, monkeypatch):
    """The angles are evaluated stacked (quantities.Angles): names scattered among others,
    in several units (deg and an override in rad), signed and not, the same vector asked
    twice and its reverse, give each name's own value, at one position and at many (by
    NumPy, also where LINKCLI_JIT=1 would take the compiled loop)."""
    from linkcli.kinematics import compiled
    monkeypatch.setitem(compiled._state, "kernel", None)
    mech = linkcli.loads(SCATTERED).model
    names = ["thetaddot", "xB", "gamma", "backdot", "AB", "beta", "thetadot", "gammaddot",
             "theta", "back", "betadot", "yBddot", "betaddot", "gammadot", "backddot"]
    planned = quantities.evaluate(mech, q, names=names)
    direct = _each(mech, planned.kinematics, names)
    assert list(planned.values) == names
    for name in names:
        assert _same(planned.values[name], direct.values[name]), name
        assert planned.units[name] == direct.units[name], name
    assert planned.units["thetadot"] == "rad/s" and planned.units["betadot"] == "deg/s"
    assert np.all(np.asarray(planned.values["back"]) <= 180)


@pytest.mark.parametrize("path", FILES, ids=os.path.basename)
def test_conditioning_from_constant_gradient_norms_is_the_computed_one(path):
    """A dyad of fixed-length links and fixed guides divides its determinant by the
    gradients' constant norms (rates.constant_norms: 2 L, |C - B|, 1): the same
    sine of the angle between the constraint normals as |det| / (|G_1| |G_2|) computed
    from the solved positions, and the same rates as a system solved from those."""
    from linkcli.kinematics.rates import DyadRates
    mech = _driven(path)
    try:
        solver = solver_for(mech)
        kin = solver.positions(solver._coords(mech.driver.value, "q"))
        solver.velocities(kin, mech.driver.rate)
    except LinkcliError:
        pytest.skip("not solved at the file's own position")
    checked = 0
    for _, step in solver._rates:
        if not isinstance(step, DyadRates) or step.norms is None:
            continue
        _, _, g1, g2 = kin.linear[step.index]
        det = (np.conj(g1) * g2).imag
        computed = np.abs(det) / (np.abs(g1) * np.abs(g2))
        assert np.allclose(kin.measure[step.index], computed, rtol=1e-12, atol=1e-15)
        checked += 1
    if not checked:
        pytest.skip("no dyad with constant gradient norms")


def test_a_refused_position_in_a_later_block_is_named_as_in_one_pass(monkeypatch):
    """Blocks solved on several threads: a driver value that cannot be assembled in the
    second block makes the whole array refused, naming that value, as one pass does."""
    import sys
    sys.path.insert(0, os.path.join(ROOT, "benchmarks"))
    from speed_accuracy import SIXBAR
    from linkcli.errors import AssemblyError
    mech = linkcli.loads(SIXBAR).model
    block = quantities.BLOCK
    q = np.linspace(0.12, 0.20, 2 * block + 7)
    q[block + 5] = 0.5                      # the actuator far too long for the rocker
    monkeypatch.setattr(quantities, "WORKERS", 2)
    with pytest.raises(AssemblyError) as threads:
        quantities.evaluate(mech, q)
    monkeypatch.setattr(quantities, "BLOCK", 10 ** 9)
    with pytest.raises(AssemblyError) as whole:
        quantities.evaluate(mech, q)
    assert str(threads.value) == str(whole.value)
    assert "0.5 m" in str(threads.value), str(threads.value)


@pytest.mark.parametrize("workers", [2, 3])
def test_blocks_on_any_number_of_threads_give_the_same_values(workers, monkeypatch):
    import sys
    sys.path.insert(0, os.path.join(ROOT, "benchmarks"))
    from speed_accuracy import SIXBAR
    mech = linkcli.loads(SIXBAR).model
    q = np.linspace(0.12, 0.20, 3 * quantities.BLOCK + 11)
    monkeypatch.setattr(quantities, "WORKERS", 1)
    one = quantities.evaluate(mech, q).values
    monkeypatch.setattr(quantities, "WORKERS", workers)
    many = quantities.evaluate(mech, q).values
    for name, value in one.items():
        assert np.array_equal(many[name], value), name


@pytest.mark.parametrize("key", ["four-bar", "crank-slider"])
def test_the_benchmarks_straight_line_replicas_are_linkcli_bit_for_bit(key):
    """benchmarks/overhead.py times linkcli's algorithm written straight-line to split a
    call's cost into its operations and its structure: that holds only while the replica
    does linkcli's operations exactly, so the values must agree to the last bit."""
    import sys
    sys.path.insert(0, os.path.join(ROOT, "benchmarks"))
    from overhead import STRAIGHT
    from speed import case
    c = case(key)
    for q in (c.grid(360), c.grid(7) + 0.1):
        mine, straight = c.solve(q), STRAIGHT[key](q, c.qd, c.qdd)
        assert set(mine) == set(straight)
        for name, value in mine.items():
            assert np.array_equal(value, straight[name]), name
