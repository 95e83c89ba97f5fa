"""Newton-Raphson on the whole mechanism: cross-check with the closed form, the
class-III example, branches, tolerances, rates against finite differences."""
import os
import sys

import numpy as np
import pytest

import linkcli
from linkcli.cli import main
from linkcli.errors import AssemblyError, InputError, StructureError
from linkcli.kinematics.newton import NewtonSolver
from linkcli.answers.quantities import report_names

from conftest import MECHANISMS

sys.path.insert(0, os.path.dirname(__file__))
from closure import along_first, rates_along_first, shipped  # noqa: E402

TRIAD = os.path.join(MECHANISMS, "triad-class3.yaml")
DEG = np.pi / 180

FOURBAR = """title: four-bar of seed 004
units: {length: mm, angle: deg}
params: {d: 425, delta: 7/4*pi}
frame:
  A0: [0, 0]
  B0: [d*cos(delta), d*sin(delta)]
points:
  A: [100, 0]
  B: [345, 197]
links:
  crank: {points: [A0, A], length: 100}
  coupler: {points: [A, B], length: 315}
  rocker: {points: [B0, B], length: 500}
driver: {angle: [A0, A], value: 0, rate: 900}
quantities:
  beta: {angle: [A, B]}
  gamma: {angle: [B0, B]}
report:
  position: [beta, gamma]
  velocity: [betadot, gammadot]
  acceleration: [betaddot, gammaddot]
"""


def _closed_form_files():
    """Files with a driver that the closed form solves (vibration problems have none),
    rolling contacts and cords included (a row each for Newton)."""
    return list(shipped())


def _sweep_around(mech):
    """Driver values near the file's one where every group is well conditioned."""
    solver = mech.solver()
    q0 = mech.driver.value
    span = 10 * DEG if mech.driver.kind == "angle" else 0.05 * abs(q0)
    q = q0 + np.linspace(-span, span, 9)
    kin = solver.velocities(solver.positions(along_first(mech, q)),
                            rates_along_first(mech, np.ones_like(q)))
    ok = np.ones(q.shape, bool)
    for short in kin.short.values():
        ok &= ~(np.broadcast_to(short, q.shape) > 0)
    for measure in kin.measure.values():
        ok &= np.broadcast_to(measure, q.shape) > 1e-2
    return q[ok]


@pytest.mark.parametrize("path", _closed_form_files(), ids=os.path.basename)
def test_newton_agrees_with_closed_form(path):
    mech = linkcli.load(path)
    if len(mech.model.coordinates) > 1:     # several drivers: Newton refuses them by name
        with pytest.raises(InputError, match="one driver; this one has"):
            mech.solve(names=report_names(mech), method="newton")
        return
    q_si = _sweep_around(mech)
    assert q_si.size >= 3
    factor = mech.units.display("angle" if mech.driver.kind == "angle" else "length", 0)[1]
    names = report_names(mech)
    closed = mech.solve(q_si / factor, names=names)
    newton = mech.solve(q_si / factor, names=names, method="newton", tol=1e-13)
    largest = {}                # per unit: a value zero throughout (a free motion's load)
    for name in names:           # is compared at the size of its unit's other values
        unit = closed.units[name]
        largest[unit] = max(largest.get(unit, 0.0), float(np.max(np.abs(closed.values[name]))))
    for name in names:
        a = np.asarray(closed.values[name], float)
        b = np.asarray(newton.values[name], float)
        scale = max(float(np.max(np.abs(a))), largest[closed.units[name]] * 1e-3, 1e-300)
        assert np.max(np.abs(a - b)) <= 1e-10 * scale, (name, a, b)
    for p, (x, y) in closed.points.items():
        nx, ny = newton.points[p]
        size = max(float(np.max(np.abs(x))), float(np.max(np.abs(y))), 1.0)
        assert np.max(np.abs(x - nx)) + np.max(np.abs(y - ny)) <= 1e-10 * size, p


# --- the class-III example ---------------------------------------------------------------
def test_triad_refused_by_closed_form_with_reason(capsys):
    mech = linkcli.load(TRIAD)
    with pytest.raises(StructureError) as err:
        mech.solve()
    assert "class-III" in str(err.value) and "C, D, E" in str(err.value)
    code = main(["solve", TRIAD])
    out, err_text = capsys.readouterr()
    assert code == 3 and "does not decompose into dyads" in err_text
    assert "Traceback" not in err_text


def _triad_residuals(pos, q):
    """Closure of the triad from its YAML dimensions, written out independently."""
    A, F, G = 60e-3 + 0j, 240e-3 + 110e-3j, 20e-3 + 200e-3j
    B, C, D, E = (pos[n] for n in "BCDE")
    return [np.abs(B - A) - 20e-3, np.angle((B - A) * np.exp(-1j * q)),
            np.abs(C - B) - 82e-3, np.abs(D - C) - 100e-3,
            np.abs(E - C - 100e-3 * np.exp(1j * np.pi / 3) * (D - C) / np.abs(D - C)),
            np.abs(D - F) - 82e-3, np.abs(E - G) - 93e-3]


def test_triad_solved_by_newton_over_a_full_turn():
    mech = linkcli.load(TRIAD)
    solver = NewtonSolver(mech, 1e-13)
    q = np.linspace(0, 2 * np.pi, 121)
    kin = solver.positions(q)
    assert np.all(kin.short[0] == 0)
    worst = max(float(np.max(np.abs(r))) for r in _triad_residuals(kin.pos, q))
    assert worst < 1e-14
    for p in "CDE":       # continuous: no branch jump between neighbouring positions
        assert np.max(np.abs(np.diff(kin.pos[p]))) < 0.02
        assert abs(kin.pos[p][0] - kin.pos[p][-1]) < 1e-12   # back where it started


def test_triad_rates_match_finite_differences():
    mech = linkcli.load(TRIAD)
    solver = NewtonSolver(mech, 1e-14)
    q = np.linspace(0.1, 6.2, 13)
    h = 1e-5
    kin = solver.accelerations(solver.velocities(solver.positions(q), 1.0), 0.0)
    plus, minus = solver.positions(q + h), solver.positions(q - h)
    for p in "BCDE":
        fd_v = (plus.pos[p] - minus.pos[p]) / (2 * h)
        fd_a = (plus.pos[p] - 2 * kin.pos[p] + minus.pos[p]) / h ** 2
        assert np.max(np.abs(kin.vel[p] - fd_v)) < 1e-8 * np.max(np.abs(fd_v)), p
        assert np.max(np.abs(kin.acc[p] - fd_a)) < 1e-4 * np.max(np.abs(fd_a)), p


def test_triad_statics_by_finite_differences():
    """Only FE and M do work: M qdot + FE xE' = 0, with xE' by finite differences."""
    mech = linkcli.load(TRIAD)
    q = 30 * DEG
    h = 1e-6
    solver = NewtonSolver(mech, 1e-14)
    xe = [solver.positions(np.array([q + s])).pos["E"][0].real for s in (h, -h)]
    expected = 50.0 * (xe[0] - xe[1]) / (2 * h)        # FE = -50 N along x
    got = mech.solve(names=["M"], method="newton").values["M"]
    assert abs(float(got) - expected) < 1e-6 * abs(expected)


def test_triad_cli_with_newton(capsys):
    assert main(["solve", TRIAD, "--method", "newton", "--format", "json"]) == 0
    out = capsys.readouterr().out
    assert '"phi3"' in out and "NaN" not in out


# --- branches, starts, tolerances -------------------------------------------------------
def test_figure_picks_the_branch_like_the_closed_form():
    """A figure with the coupler-rocker pin mirrored gives the other assembly."""
    mirrored = FOURBAR.replace("B: [345, 197]", "B: [-83, -414]")
    for text in (FOURBAR, mirrored):
        mech = linkcli.loads(text)
        q = np.linspace(0, 2 * np.pi, 37)
        closed = mech.solver().positions(q)
        newton = NewtonSolver(mech, 1e-13).positions(q)
        assert np.max(np.abs(closed.pos["B"] - newton.pos["B"])) < 1e-14
    a = linkcli.loads(FOURBAR).solver().positions(np.array(0.0)).pos["B"]
    b = linkcli.loads(mirrored).solver().positions(np.array(0.0)).pos["B"]
    assert abs(a - b) > 0.1          # the two assemblies really differ


def test_large_steps_are_substepped_without_a_branch_jump():
    mech = linkcli.loads(FOURBAR)
    closed = mech.solver()
    for q in (np.array([np.pi]), np.linspace(0, 2 * np.pi, 5), np.array([3.0, -3.0, 6.0])):
        newton = NewtonSolver(mech, 1e-13)
        got = newton.positions(q).pos["B"]
        assert np.max(np.abs(got - closed.positions(q).pos["B"])) < 1e-14


def test_far_start_converges_to_an_assembly():
    """Every moving point 40 % of the shortest link away from the figure."""
    far = FOURBAR.replace("A: [100, 0]", "A: [60, 45]").replace("B: [345, 197]",
                                                                  "B: [300, 240]")
    mech = linkcli.loads(far)
    newton = NewtonSolver(mech, 1e-13)
    kin = newton.positions(np.array([0.0, 1.0]))
    A0, B0 = 0j, 0.425 * np.exp(1j * 7 / 4 * np.pi)
    A, B = kin.pos["A"], kin.pos["B"]
    assert np.max(np.abs(np.abs(A - A0) - 0.1)) < 1e-15
    assert np.max(np.abs(np.abs(B - A) - 0.315)) < 1e-15
    assert np.max(np.abs(np.abs(B - B0) - 0.5)) < 1e-15
    assert np.max(np.abs(np.angle(A / np.exp(1j * np.array([0.0, 1.0]))))) < 1e-15


def test_tolerance_controls_the_work():
    mech = linkcli.loads(FOURBAR)
    q = np.linspace(0, 2 * np.pi, 50)
    exact = mech.solver().positions(q).pos["B"]
    loose, tight = NewtonSolver(mech, 1e-3), NewtonSolver(mech, 1e-14)
    loose.iterations = tight.iterations = 0
    err_loose = np.max(np.abs(loose.positions(q).pos["B"] - exact))
    err_tight = np.max(np.abs(tight.positions(q).pos["B"] - exact))
    assert loose.iterations < tight.iterations
    assert err_loose < 1e-3 * tight.size and err_tight < 1e-14


def test_unreachable_position_is_an_assembly_error():
    mech = linkcli.loads(FOURBAR.replace("length: 315", "length: 30"))
    with pytest.raises(AssemblyError) as err:
        NewtonSolver(mech)
    assert "Newton cannot assemble" in str(err.value)
