"""Velocities and accelerations agree with central finite differences in q.

Positions are solved at q - h and q + h for whole arrays of q at once.  With
h = 1e-6 (rad, or 1e-6 of the mechanism's size for a length driver) the
central difference has truncation error h^2 |P'''| / 6 ~ 1e-13 and rounding
error eps |P| / h ~ 1e-10 of the velocity scale, so a relative tolerance of
1e-6 is three orders above the method's error, and far below any real
mistake (a missing Coriolis term is O(1) relative).
"""
import numpy as np
import pytest

import linkcli

from closure import (CASE_IDS, CASES, along_first, assembled, conditioning, load_case, q_factor,
                     rates_along_first, shipped, step, sweep)

RTOL = 1e-6


def _fd_setup(mech, q):
    solver = mech.solver()
    h = step(mech)
    ones = rates_along_first(mech, np.ones_like(q))
    kin = solver.velocities(solver.positions(along_first(mech, q)), ones)
    solver.accelerations(kin, rates_along_first(mech, np.zeros_like(q)))
    plus = solver.velocities(solver.positions(along_first(mech, q + h)), ones)
    minus = solver.velocities(solver.positions(along_first(mech, q - h)), ones)
    ok = assembled(kin) & assembled(plus) & assembled(minus) & (conditioning(kin) > 0.1)
    return kin, plus, minus, h, ok


def _compare(exact, plus, minus, h, points, ok):
    """Largest error of the central difference, relative to the largest rate of
    any point at the same driver value."""
    scale = np.max([np.abs(exact[p]) for p in points], axis=0) + 1e-300
    worst = {}
    for p in points:
        fd = (plus[p] - minus[p]) / (2 * h)
        worst[p] = float(np.max((np.abs(exact[p] - fd) / scale)[ok]))
    return worst


def _cases_and_examples():
    out = [(case[0], load_case(case), sweep(load_case(case), case[3], 121)) for case in CASES]
    for path in shipped():
        mech = linkcli.load(path)
        span = 0.3 if mech.driver.kind == "angle" else 0.15 * abs(mech.driver.value)
        q = mech.driver.value + np.linspace(-span, span, 61)
        out.append((path.rsplit("/", 1)[-1], mech, q))
    return out


ALL = _cases_and_examples()
ALL_IDS = [item[0] for item in ALL]


@pytest.mark.parametrize("name, mech, q", ALL, ids=ALL_IDS)
def test_velocities_match_finite_differences(name, mech, q):
    kin, plus, minus, h, ok = _fd_setup(mech, q)
    assert ok.all() if name in CASE_IDS else ok.sum() > 10
    points = list(mech.moving)
    worst = _compare(kin.vel, plus.pos, minus.pos, h, points, ok)
    assert max(worst.values()) < RTOL, worst


@pytest.mark.parametrize("name, mech, q", ALL, ids=ALL_IDS)
def test_accelerations_match_finite_differences(name, mech, q):
    kin, plus, minus, h, ok = _fd_setup(mech, q)
    points = list(mech.moving)
    worst = _compare(kin.acc, plus.vel, minus.vel, h, points, ok)
    assert max(worst.values()) < RTOL, worst


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_rates_are_linear_in_driver_rates(case):
    """v = P'(q) qdot and a = P''(q) qdot^2 + P'(q) qddot."""
    mech = load_case(case)
    solver = mech.solver()
    q = sweep(mech, case[3], 37)
    qd = np.linspace(-3.0, 2.0, q.size)
    qdd = np.linspace(4.0, -1.5, q.size)
    unit = solver.velocities(solver.positions(q), np.ones_like(q))
    solver.accelerations(unit, np.zeros_like(q))
    kin = solver.velocities(solver.positions(q), qd)
    solver.accelerations(kin, qdd)
    for p in mech.moving:
        vscale = np.max(np.abs(unit.vel[p])) + 1e-300
        ascale = vscale + np.max(np.abs(unit.acc[p]))
        assert np.max(np.abs(kin.vel[p] - qd * unit.vel[p])) < 1e-12 * 3 * vscale, p
        expected = unit.acc[p] * qd ** 2 + unit.vel[p] * qdd
        assert np.max(np.abs(kin.acc[p] - expected)) < 1e-12 * 16 * ascale, p


def _unwrap(diff, full):
    return (diff + full / 2) % full - full / 2


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_reported_rates_match_finite_differences(case):
    """phi1dot, xEdot, sddot ... in display units are the q-derivatives of the
    reported positions (qdot = 1 display unit/s, qddot = 0)."""
    mech = load_case(case)
    base = [n for n, qu in mech.quantities.items() if qu.kind in ("angle", "length", "x", "y")]
    names = base + [n + "dot" for n in base] + [n + "ddot" for n in base]
    q = sweep(mech, case[3], 61) / q_factor(mech)
    h = step(mech) / q_factor(mech)
    ones, zeros = np.ones_like(q), np.zeros_like(q)
    mid = mech.solve(q=q, qdot=ones, qddot=zeros, names=names).values
    plus = mech.solve(q=q + h, qdot=ones, qddot=zeros, names=names).values
    minus = mech.solve(q=q - h, qdot=ones, qddot=zeros, names=names).values
    checked = 0
    for n in base:
        full = 360.0 if mech.quantities[n].kind == "angle" else np.inf
        d_pos = (plus[n] - minus[n]) if full == np.inf else _unwrap(plus[n] - minus[n], full)
        for fd, exact, of in ((d_pos / (2 * h), mid[n + "dot"], mid[n]),
                              ((plus[n + "dot"] - minus[n + "dot"]) / (2 * h), mid[n + "ddot"],
                               mid[n + "dot"])):
            # rate scale, plus the rounding floor eps |X| / h of a constant quantity
            scale = np.max(np.abs(exact)) + np.max(np.abs(mid[n + "dot"])) + \
                np.finfo(float).eps * np.max(np.abs(of)) / h / RTOL
            assert np.max(np.abs(fd - exact)) <= RTOL * scale, n
            checked += 1
    assert checked >= 4


def test_coriolis_term_matters():
    """A slider on a moving guide: dropping the 2 w x v_rel part of the
    acceleration would break the finite-difference agreement by O(1)."""
    mech = load_case(CASES[CASE_IDS.index("coupler-slider")])
    q = sweep(mech, (-60, 40), 21)
    kin, plus, minus, h, ok = _fd_setup(mech, q)
    fd = (plus.vel["E"] - minus.vel["E"]) / (2 * h)
    omega = ((kin.vel["C"] - kin.vel["B"]) / (kin.pos["C"] - kin.pos["B"])).imag
    u = (kin.pos["C"] - kin.pos["B"]) / np.abs(kin.pos["C"] - kin.pos["B"])
    # slip velocity of E along the coupler's line, relative to the coupler
    v_guide = kin.vel["B"] + 1j * omega * (kin.pos["E"] - kin.pos["B"])
    v_rel = kin.vel["E"] - v_guide
    assert np.max(np.abs((np.conj(u) * v_rel).imag)) < 1e-9 * np.max(np.abs(kin.vel["E"]))
    coriolis = 2j * omega * v_rel
    assert np.max(np.abs(kin.acc["E"] - fd)) < RTOL * np.max(np.abs(fd))
    assert np.max(np.abs(coriolis)) > 1e3 * np.max(np.abs(kin.acc["E"] - fd))
