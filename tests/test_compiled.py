"""The compiled loop (kinematics.compiled): the same values as NumPy wherever it answers,
and a refusal wherever NumPy refuses.

The loop is plain Python that numba compiles when the ``jit`` extra is installed and
``LINKCLI_JIT=1``; here it runs as Python (``compiled._run``), so its logic is tested on a
machine without numba; with numba installed the compiled function is compared with it.
"""
from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

import linkcli
from linkcli.answers.quantities import plan as quantities
from linkcli.answers.quantities import Later, plan_for, report_names
from linkcli.errors import LinkcliError
from linkcli.kinematics import compiled
from linkcli.kinematics.solvers import solver_for
from linkcli.model.mechanism import split_rate
from test_plan import FILES, FOURBAR, _driven, _driver_values

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PROBED = ("angle", "length", "x", "y")


@pytest.fixture(autouse=True)
def no_straight(monkeypatch):
    """The general NumPy path, not the straight-line one (tests/test_straight.py), is what
    the loop is compared with and falls back to."""
    monkeypatch.setattr(quantities, "straight_of", lambda *args: None)


@pytest.fixture
def loop(monkeypatch):
    """Evaluations run the compiled loop as Python."""
    monkeypatch.setitem(compiled._state, "kernel", compiled._run)
    return compiled._run


def _probed_names(mech):
    """The report's names that are probes (angles, lengths, coordinates, their rates)."""
    return [n for n in dict.fromkeys(report_names(mech))
            if mech.quantities[split_rate(n)[0]].kind in PROBED]


def _close(name, got, expected, mech):
    """Within rounding: angles as angles (1e-9 deg near the wrap at 0 and 360), others
    relative to the row's largest magnitude."""
    got, expected = np.asarray(got), np.asarray(expected)
    scale = max(float(np.max(np.abs(expected))), 1e-300)
    base, order = split_rate(name)
    if mech.quantities[base].kind == "angle" and order == 0:
        period = 360.0 if np.max(np.abs(expected)) > 2 * np.pi + 1e-9 else 2 * np.pi
        diff = np.abs((got - expected + period / 2) % period - period / 2)
        return float(np.max(diff)) <= 1e-11 * period
    return float(np.max(np.abs(got - expected))) <= 1e-11 * scale


def _numpy(mech, q, names):
    try:
        return quantities.evaluate(mech, q, names=names)
    except LinkcliError as error:
        return error


@pytest.mark.parametrize("path", FILES, ids=os.path.basename)
def test_the_loop_gives_numpys_values_or_refuses_where_numpy_does(path, monkeypatch):
    """Every shipped file the loop can express, at its own driver value and random ones,
    one at a time and all at once: where NumPy refuses (unassembled, singular) the loop
    refuses too; where the loop answers, NumPy's values to rounding."""
    mech = _driven(path)
    names = _probed_names(mech)
    if not names:
        pytest.skip("no angle, length or coordinate in the report")
    try:
        program = compiled.program_of(solver_for(mech))
    except LinkcliError:
        pytest.skip("not solved by the closed form")
    if program is None:
        pytest.skip("a group the loop does not express")
    values = np.concatenate([[mech.driver.value / mech.units.display(
        "angle" if mech.driver.kind == "angle" else "length", 0)[1]], _driver_values(mech, 24)])
    answered, good = 0, []
    for q in values:
        expected = _numpy(mech, np.array([q]), names)
        monkeypatch.setitem(compiled._state, "kernel", compiled._run)
        got = _numpy(mech, np.array([q]), names)
        monkeypatch.setitem(compiled._state, "kernel", None)
        if isinstance(expected, LinkcliError):
            assert isinstance(got, LinkcliError) and str(got) == str(expected), q
            continue
        good.append(q)
        if isinstance(got.kinematics, Later):       # the loop answered
            answered += 1
            for name in names:
                assert _close(name, got.values[name], expected.values[name], mech), (name, q)
    assert answered >= max(1, len(good) // 2), (answered, len(good))
    if len(good) > 1:
        monkeypatch.setitem(compiled._state, "kernel", compiled._run)
        many = quantities.evaluate(mech, np.array(good), names=names)
        monkeypatch.setitem(compiled._state, "kernel", None)
        whole = quantities.evaluate(mech, np.array(good), names=names)
        for name in names:
            assert _close(name, many.values[name], whole.values[name], mech), name


def test_most_shipped_files_are_expressed_by_the_loop():
    """The loop covers the common groups: most driven files are programs."""
    count = 0
    for path in FILES:
        try:
            count += compiled.program_of(solver_for(_driven(path))) is not None
        except LinkcliError:
            pass
    assert count >= len(FILES) // 2, (count, len(FILES))


CRANK_SLIDER = """title: crank-slider
units: {length: mm, angle: deg}
frame: {O: [0, 0]}
points: {A: [0, 50], B: [190, 0]}
links:
  crank: {points: [O, A], length: 50}
  rod: {points: [A, B], length: 200}
sliders:
  piston: {point: B, guide: {y: 0}}
driver: {angle: [O, A], value: 90, rate: 10, accel: 1}
quantities: {beta: {angle: [A, B]}}
report:
  position: [beta, xB]
  velocity: [betadot, xBdot]
  acceleration: [betaddot, xBddot]
"""


@pytest.mark.parametrize("q", [90.0, 270.0])
def test_a_toggle_is_refused_as_numpy_refuses_it(q, loop):
    """A rod as long as the crank stands across the guide at q = 90 and 270 deg: the dyad's
    rate system is singular there; the loop refuses and the error is NumPy's, with its
    numbers."""
    mech = linkcli.loads(CRANK_SLIDER.replace("length: 200", "length: 50")
                         .replace("B: [190, 0]", "B: [90, 0]")).model
    names = report_names(mech)
    with pytest.raises(LinkcliError) as error:
        quantities.evaluate(mech, np.array([10.0, q, 30.0]), names=names)
    assert "singular" in str(error.value) and f"q = {q:g}" in str(error.value)
    fine = quantities.evaluate(mech, np.array([10.0, 30.0]), names=names)
    assert isinstance(fine.kinematics, Later)


def test_an_unassemblable_position_is_refused_with_numpys_error(loop):
    mech = linkcli.loads(FOURBAR.replace("length: 280", "length: 60")).model
    names = ["beta", "betadot"]
    with pytest.raises(LinkcliError) as error:
        quantities.evaluate(mech, np.linspace(0, 350, 36), names=names)
    assert "cannot assemble" in str(error.value)


def test_a_long_array_is_left_to_numpy(loop, monkeypatch):
    """Above COMPILED_MOST driver values NumPy's whole-array loops are the faster: it
    solves them, with the loop's values to rounding."""
    mech = linkcli.loads(FOURBAR).model
    names = ["beta", "gamma", "betadot", "gammaddot", "xB", "yBddot"]
    q = np.linspace(-170.0, 190.0, 53)
    short = quantities.evaluate(mech, q, names=names)
    assert isinstance(short.kinematics, Later)
    monkeypatch.setattr(quantities, "COMPILED_MOST", 52)
    long = quantities.evaluate(mech, q, names=names)
    assert not isinstance(long.kinematics, Later)
    for name in names:
        assert _close(name, short.values[name], long.values[name], mech), name


def test_a_name_the_loop_does_not_probe_leaves_numpy_to_it(loop):
    """A speed is not a probe: the plan has no program, and NumPy answers."""
    mech = linkcli.loads(FOURBAR.replace("AB: {length: [A0, B]}}",
                                         "AB: {length: [A0, B]}, vB: {speed: B}}")).model
    assert plan_for(mech, ["beta", "vB"]).probes is None
    result = quantities.evaluate(mech, np.linspace(0, 90, 5), names=["beta", "vB"])
    assert not isinstance(result.kinematics, Later)


def test_lengths_and_their_rates_are_probes(loop):
    """|P_b - P_a| and its rates by the loop: NumPy's values to rounding."""
    mech = linkcli.loads(FOURBAR).model
    names = ["AB", "ABdot", "ABddot", "beta"]
    q = np.linspace(-170.0, 190.0, 37)
    got = quantities.evaluate(mech, q, names=names)
    assert isinstance(got.kinematics, Later)
    expected = quantities.collect(mech, solver_for(mech), got.kinematics, names)
    for name in names:
        assert _close(name, got.values[name], expected.values[name], mech), name


def test_the_later_kinematics_are_the_solved_ones(loop):
    mech = linkcli.loads(FOURBAR).model
    q = np.linspace(0, 90, 5)
    result = quantities.evaluate(mech, q, names=["gamma", "gammadot"])
    kin = result.kinematics
    z = kin.pos["B"] - mech.fixed["B0"]
    angle = np.degrees(np.angle(z)) % 360
    assert np.allclose(angle, result.values["gamma"], atol=1e-10)


def test_without_the_setting_nothing_is_imported():
    """Off by default: a solve does not import numba (start-up unchanged)."""
    code = ("import sys, numpy as np, linkcli\n"
            f"m = linkcli.loads({FOURBAR!r})\n"
            "m.solve(np.linspace(0, 90, 360), names=['beta', 'betadot'])\n"
            "print('numba' in sys.modules)\n")
    env = {k: v for k, v in os.environ.items() if k != "LINKCLI_JIT"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env=env, cwd=ROOT, check=True)
    assert out.stdout.strip() == "False"


def test_the_setting_without_numba_solves_with_numpy():
    """LINKCLI_JIT=1 where numba is not installed (or cannot compile): the same values,
    by NumPy."""
    code = ("import sys, numpy as np, linkcli\n"
            "from linkcli.kinematics import compiled\n"
            "sys.modules['numba'] = None\n"          # as if not installed
            f"m = linkcli.loads({FOURBAR!r})\n"
            "v = m.solve(np.linspace(0, 90, 4), names=['beta']).values['beta']\n"
            "print(compiled.compiled() is None, ' '.join(f'{x:.12f}' for x in v))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env={**os.environ, "LINKCLI_JIT": "1"}, cwd=ROOT, check=True)
    flag, *values = out.stdout.split()
    mech = linkcli.loads(FOURBAR).model
    expected = quantities.evaluate(mech, np.linspace(0, 90, 4), names=["beta"]).values["beta"]
    assert flag == "True"
    assert np.allclose([float(v) for v in values], expected, atol=1e-11)


@pytest.mark.parametrize("path", FILES[::3], ids=os.path.basename)
def test_numbas_loop_is_the_python_loop(path):
    """With numba installed: the compiled function gives the Python function's values."""
    pytest.importorskip("numba")
    kernel = compiled._compile()
    assert kernel is not None
    mech = _driven(path)
    names = _probed_names(mech)
    try:
        solver = solver_for(mech)
    except LinkcliError:
        pytest.skip("not solved by the closed form")
    plan = plan_for(mech, names)
    program = plan._compiled_program(solver)
    if not names or program is None:
        pytest.skip("not a program")
    base = "angle" if mech.driver.kind == "angle" else "length"
    q = _driver_values(mech, 40) * mech.units.display(base, 0)[1]
    tables = []
    for run in (compiled._run, kernel):
        table = np.zeros((len(plan.probes), q.size))
        tables.append((program[0].run(program[1], q, mech.driver.rate, mech.driver.accel,
                                      plan.order(mech), table, kernel=run), table))
    (ok1, t1), (ok2, t2) = tables
    assert ok1 == ok2
    if ok1:
        assert np.allclose(t1, t2, rtol=1e-12, atol=1e-12 * np.max(np.abs(t1)))


@pytest.mark.parametrize("path", FILES, ids=os.path.basename)
def test_the_loops_points_are_the_solvers(path):
    """Every point of every file the loop expresses, its velocity and acceleration (x and y
    probes), at random driver values: NumPy's solver's to rounding where the loop answers,
    and a refusal wherever the solver refuses."""
    mech = _driven(path)
    try:
        solver = solver_for(mech)
    except LinkcliError:
        pytest.skip("not solved by the closed form")
    program = compiled.program_of(solver)
    if program is None:
        pytest.skip("a group the loop does not express")
    moving = [p for p in program.index if p not in solver.fixed]
    rows = [(axis, p, None, order, 1.0, False) for order in (0, 1, 2) for p in moving
            for axis in (compiled.X, compiled.Y)]
    probes = program.probes(rows)
    base = "angle" if mech.driver.kind == "angle" else "length"
    rate, accel = mech.driver.rate, mech.driver.accel
    solvable = answered = 0
    for q in _driver_values(mech, 24, seed=2) * mech.units.display(base, 0)[1]:
        try:
            kin = quantities.solved(solver, 2, np.array([q]), rate, accel)
        except LinkcliError:
            kin = None
        table = np.zeros((len(rows), 1))
        ok = program.run(probes, np.array([q]), rate, accel, 2, table, kernel=compiled._run)
        if kin is None:
            assert not ok, q
            continue
        solvable += 1
        if not ok:
            continue
        answered += 1
        for order, points in enumerate((kin.pos, kin.vel, kin.acc)):
            expected = np.array([complex(np.ravel(points.get(p, 0j))[0]) for p in moving])
            got = table[2 * len(moving) * order:2 * len(moving) * (order + 1), 0]
            scale = max(float(np.max(np.abs(expected))), 1e-300)
            assert np.allclose(got[0::2], expected.real, rtol=0, atol=1e-12 * scale), order
            assert np.allclose(got[1::2], expected.imag, rtol=0, atol=1e-12 * scale), order
    assert answered >= max(1, solvable // 2), (answered, solvable)


def test_the_api_switches_the_loop_on_where_numba_is_installed(monkeypatch):
    """linkcli.jit(): on where numba is installed (then arrays are solved by the loop), off
    again with jit(False)."""
    import importlib.util
    monkeypatch.setitem(compiled._state, "kernel", None)
    installed = importlib.util.find_spec("numba") is not None
    assert linkcli.jit(True) is installed
    result = linkcli.loads(FOURBAR).solve(np.linspace(0, 90, 10), names=["beta", "betadot"])
    assert isinstance(result.kinematics, Later) is installed
    assert linkcli.jit(False) is False
    result = linkcli.loads(FOURBAR).solve(np.linspace(0, 90, 10), names=["beta", "betadot"])
    assert not isinstance(result.kinematics, Later)
