"""Positions of every group type satisfy their closure equations to 1e-12 relative.

Three independent views: the solver's own constraint residuals
(``linkcli.kinematics.residuals``), the rigid relations of the model (link
distances and shapes, block guides and offsets, the driver coordinate), and
the dimensions written in the YAML files, checked directly.
"""
import numpy as np
import pytest

import linkcli
from linkcli.kinematics.closed_form import residuals
from linkcli.kinematics.contacts import Track
from linkcli.kinematics.groups import Coord, Dist, Line

from closure import (CASE_IDS, CASES, along_first, assembled, closure_errors, load_case, q_factor,
                     shipped, size, sweep, variant)

TOL = 1e-12
DEG = np.pi / 180
MM = 1e-3


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_decomposition_has_the_group_types(case):
    mech = load_case(case)
    kinds = {g.kind for g in mech.solver().groups}
    assert case[4] <= kinds, kinds


def _relative_residuals(solver, kin):
    """Solver residuals scaled to be dimensionless: distances by length^2,
    lines by |C - B| times the mechanism size, coordinates by the size."""
    mech = solver.mech
    L = size(mech)
    out = {}
    constraints = {}
    for index, group in enumerate(solver.groups):
        for j, c in enumerate(group.constraints):
            constraints[(index, j)] = c
    for key, value in residuals(solver, kin).items():
        c = constraints[key]
        if isinstance(c, Dist):
            length = kin.q if c.length is None else c.length
            out[key] = value / length ** 2
        elif isinstance(c, Line):
            out[key] = value / (np.abs(kin.pos[c.c] - kin.pos[c.b]) * L)
        elif isinstance(c, Track):          # a contact's relation: radians already
            out[key] = value
        else:
            assert isinstance(c, Coord)
            out[key] = value / L
    return out


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_closure_over_sweep(case):
    mech = load_case(case)
    solver = mech.solver()
    kin = solver.positions(sweep(mech, case[3]))
    assert assembled(kin).all(), "the test sweep must stay inside the assembly range"
    rel = _relative_residuals(solver, kin)
    assert rel, "no constraint residuals reported"
    worst = {key: float(np.max(np.abs(v))) for key, v in rel.items()}
    assert max(worst.values()) < TOL, worst
    direct = {key: float(np.max(np.abs(v))) for key, v in closure_errors(mech, kin).items()}
    assert max(direct.values()) < TOL, direct


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_branch_follows_figure_and_is_continuous(case):
    mech = load_case(case)
    solver = mech.solver()
    L = size(mech)
    kin = solver.positions(np.asarray(mech.driver.value))
    for p, approx in mech.moving.items():
        assert abs(complex(kin.pos[p]) - approx) < 0.1 * L, (p, kin.pos[p], approx)
    for group in solver.groups:       # the other branch lies farther from the figure
        if group.kind in ("RRR", "RRP", "PRR", "RPR"):
            group.branch = -group.branch
            other = complex(solver.positions(np.asarray(mech.driver.value)).pos[group.point])
            group.branch = -group.branch
            approx = mech.moving[group.point]
            assert abs(other - approx) > abs(complex(kin.pos[group.point]) - approx), group.point
    q = sweep(mech, case[3], 721)
    kin = solver.positions(q)
    for p in mech.moving:
        jumps = np.abs(np.diff(kin.pos[p]))
        assert jumps.max() < 0.05 * L, (p, jumps.max())


# --- the dimensions of each test file, checked directly ----------------------------------
def _cross(a, b):
    return (np.conj(a) * b).imag


def _unit(deg):
    return np.exp(1j * deg * DEG)


def _quick_return(pos, q, offset=0.0):
    O, P, A, C, D, E = (pos[n] for n in "OPACDE")
    u = (C - P) / np.abs(C - P)
    return [np.abs(A - O) - 60 * MM, np.abs(C - P) - 300 * MM,
            _cross(u, A - P) - offset * MM, D.imag - 170 * MM, np.abs(D - C) - 200 * MM,
            np.abs(E - A - (20 + 10j) * MM * u)]


def _crank_slider(pos, q):
    A, B, C, E = (pos[n] for n in "ABCE")
    return [np.abs(B - A) - 50 * MM, np.abs(C - B) - 160 * MM,
            _cross(_unit(20), C - (-20j * MM)), np.abs(E - C - 30j * MM)]


def _double_slider(pos, q):
    A, B, P = (pos[n] for n in "ABP")
    u = (B - A) / np.abs(B - A)
    return [np.abs(B - A) - 80 * MM, P.imag - 40 * MM, _cross(u, P - A) - 10 * MM,
            np.angle(np.exp(1j * (np.angle(B - A) - q)))]


def _coupler_slider(pos, q):
    A, B, C, D, E, F, G = (pos[n] for n in "ABCDEFG")
    u = (C - B) / np.abs(C - B)
    return [np.abs(B - A) - 60 * MM, np.abs(C - B) - 180 * MM, np.abs(C - D) - 120 * MM,
            np.abs(E - F) - 165 * MM, _cross(u, E - B) - 5 * MM,
            np.abs(G - E - (15 - 10j) * MM * u)]


def _actuator_slide(pos, q):
    A, B, C, D = (pos[n] for n in "ABCD")
    return [np.abs(B - A) - q, B.imag - 50 * MM, np.abs(C - B) - 100 * MM,
            np.abs(C - D) - 80 * MM]


def _slider_driven(pos, q, axis="x"):
    A, B, S = (pos[n] for n in "ABS")
    coord = S.real if axis == "x" else S.imag
    return [coord - q, _cross(_unit(10), S - (-30j * MM)), np.abs(B - A) - 60 * MM,
            np.abs(S - B) - 100 * MM]


DIRECT = {
    "quick-return": _quick_return,
    "quick-return-offset": lambda pos, q: _quick_return(pos, q, 8.0),
    "quick-return-reversed": _quick_return,
    "crank-slider-inclined": _crank_slider,
    "crank-slider-reversed": _crank_slider,
    "double-slider": _double_slider,
    "coupler-slider": _coupler_slider,
    "actuator-slide": _actuator_slide,
    "slider-driven-x": _slider_driven,
    "slider-driven-y": lambda pos, q: _slider_driven(pos, q, "y"),
}


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_file_dimensions_hold(case):
    mech = load_case(case)
    q = sweep(mech, case[3])
    kin = mech.solver().positions(q)
    errors = DIRECT[case[0]](kin.pos, q)
    L = size(mech)
    worst = [float(np.max(np.abs(e))) / (1.0 if i == 3 and case[0] == "double-slider" else L)
             for i, e in enumerate(errors)]
    assert max(worst) < TOL, worst


@pytest.mark.parametrize("name, forward, backward", [
    ("quick-return.yaml", "angle: [O, A], value: 60", "angle: [A, O], value: 240"),
    ("crank-slider-inclined.yaml", "angle: [A, B], value: 40", "angle: [B, A], value: 220"),
])
def test_angle_driver_in_either_direction(name, forward, backward):
    """The angle of B->A is the angle of A->B plus 180 deg: the same positions."""
    mech_f = variant(name)
    mech_b = variant(name, [(forward, backward)])
    q = np.linspace(0, 2 * np.pi, 73)
    kin_f = mech_f.solver().positions(q)
    kin_b = mech_b.solver().positions(q + np.pi)
    for p in mech_f.moving:
        assert np.max(np.abs(kin_f.pos[p] - kin_b.pos[p])) < TOL * size(mech_f), p


def test_coordinate_drivers_agree():
    """x and y drivers on the same inclined guide give the same positions."""
    mech_x = variant("slider-driven.yaml")
    mech_y = variant("slider-driven.yaml", [("driver: {x: S, value: 120,",
                                             "driver: {y: S, value: -8.84,")])
    x = np.linspace(60, 150, 31) * MM
    y = -30 * MM + x * np.tan(10 * DEG)
    kin_x = mech_x.solver().positions(x)
    kin_y = mech_y.solver().positions(y)
    for p in ("S", "B"):
        assert np.max(np.abs(kin_x.pos[p] - kin_y.pos[p])) < TOL * size(mech_x), p


@pytest.mark.parametrize("path", shipped(), ids=lambda p: p.rsplit("/", 1)[-1])
def test_shipped_examples_closure(path):
    """Shipped examples around their driver value (the assembled part of the sweep)."""
    mech = linkcli.load(path)
    solver = mech.solver()
    q0 = mech.driver.value
    span = 20 * DEG if mech.driver.kind == "angle" else 0.15 * abs(q0) + 0.02 * size(mech)
    q = q0 + np.linspace(-span, span, 101)
    kin = solver.positions(along_first(mech, q))
    ok = assembled(kin)
    assert ok[50], "the file's own driver value must assemble"
    assert ok.sum() > 10
    rel = _relative_residuals(solver, kin)
    # a train of discs alone (gears, belts) has no loop to close: nothing to compare
    worst = max((float(np.max(np.abs(v[ok] if np.ndim(v) else v))) for v in rel.values()),
                default=0.0)
    assert worst < TOL
    direct = closure_errors(mech, kin)
    worst = {k: float(np.max(np.abs(np.broadcast_to(v, q.shape)[ok]))) for k, v in direct.items()}
    assert max(worst.values(), default=0.0) < TOL, worst
    assert q_factor(mech) > 0
