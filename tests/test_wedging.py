"""Coulomb friction with two consistent answers (wedging), and friction that locks the
mechanism, against a free-body calculation written here.

A crank OA drives a rod AB and a piston B on the guide y = 0 with friction mu.  The rod
carries no load but at its ends: its force on the piston is f u, u = (B - A)/|B - A|.  The
piston (mass m at B, gravity -y) balances f u, the load F, its weight, the guide's normal
force N along +y and the friction -mu sgn(v_B) |N| along x against m a_B; the crank needs
the torque T = (A - O) x f u.  With |N| = s N each sign s gives a 2x2 linear system, and a
consistent answer has sgn N = s.  Raising mu from 0, N = N_0 / (1 + t g s) keeps the sign of
the frictionless N_0: the answer linkcli gives.  Where the other sign is consistent too, the
rod wedges the piston and the warning names that answer with its numbers; where the
continued answer's denominator reaches 0 before t = 1, the friction locks the mechanism at
t = -1 / (g s) of the given mu.
"""
from __future__ import annotations

import math
import os
import re

import numpy as np
import pytest

import linkcli
from linkcli.cli import main
from linkcli.errors import SelfLockingError

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data")
G = 9.81

CRANK_SLIDER = """
title: wedging case
units: {{length: mm, angle: rad, force: N, torque: Nm, angular_rate: rad/s}}
frame: {{O: [{ox!r}, {oy!r}]}}
points: {{A: [{ax!r}, {ay!r}], B: [{bx!r}, 0]}}
links:
  crank: {{points: [O, A], length: {r!r}}}
  rod: {{points: [A, B], length: {L!r}}}
sliders:
  piston: {{point: B, guide: {{y: 0}}}}
driver: {{angle: [O, A], value: {q!r}, rate: {qd!r}, accel: {qdd!r}}}
loads:
  F: {{type: force, at: B, x: {F!r}}}
  T: {{type: driver, value: unknown}}
dynamics:
  gravity: {g!r}
  bodies:
    piston: {{mass: {m!r}, center: B}}
  friction: {{piston: {mu!r}}}
quantities:
  N: {{slider_force: piston, component: normal}}
report:
  statics: [T, N]
"""


def free_body(ox, oy, r, L, q, qd, qdd, F, m, mu, g=G):
    """{s: (T, N)} of the consistent answers (SI, lengths in mm in the arguments), and the
    frictionless N_0, from the piston's and the crank's free bodies."""
    ox, oy, r, L = ox / 1000, oy / 1000, r / 1000, L / 1000
    ax, ay = ox + r * math.cos(q), oy + r * math.sin(q)
    h = math.sqrt(L * L - ay * ay)
    d_ax, d_ay = -r * math.sin(q), r * math.cos(q)
    dd_ax, dd_ay = -r * math.cos(q), -r * math.sin(q)
    d_b = d_ax - ay * d_ay / h
    dd_b = dd_ax - (d_ay ** 2 + ay * dd_ay) / h - (ay * d_ay) ** 2 / h ** 3
    v, a = d_b * qd, dd_b * qd * qd + d_b * qdd
    ux, uy = h / L, -ay / L                         # B - A = (h, -ay)
    out = {}
    for s in (1.0, -1.0, 0.0):
        k = mu * math.copysign(1.0, v) * s if s else 0.0
        f, n = np.linalg.solve([[ux, -k], [uy, 1.0]], [m * a - F, m * g])
        if s == 0.0:
            n0 = n
        elif n * s >= 0:
            out[s] = ((ax - ox) * f * uy - (ay - oy) * f * ux, n)
    return out, n0


def case(ox, oy, r, L, q, qd, qdd, F, m, mu):
    ax, ay = ox + r * math.cos(q), oy + r * math.sin(q)
    bx = ax + math.sqrt(L * L - ay * ay)
    return CRANK_SLIDER.format(ox=ox, oy=oy, ax=ax, ay=ay, bx=bx, r=r, L=L, q=q, qd=qd,
                               qdd=qdd, F=F, m=m, mu=mu, g=G)


def _wedging_cases(count, seed=20240611):
    """Random crank-sliders whose rod is steep enough (mu > cot beta) for both signs of N to
    be consistent: (parameters, free-body answers, N_0)."""
    rng = np.random.default_rng(seed)
    found = []
    while len(found) < count:
        beta = rng.uniform(math.radians(55), math.radians(80))
        mu = rng.uniform(1.1, 2.0) / math.tan(beta)
        r, L = rng.uniform(20, 60), rng.uniform(80, 200)
        q = rng.uniform(-math.pi, math.pi)
        ax, ay = 100 - L * math.cos(beta), L * math.sin(beta)
        params = dict(ox=ax - r * math.cos(q), oy=ay - r * math.sin(q), r=r, L=L, q=q,
                      qd=float(rng.choice([-1, 1]) * rng.uniform(0.5, 5)),
                      qdd=rng.uniform(-10, 10), F=float(rng.choice([-1, 1]) * rng.uniform(50, 500)),
                      m=rng.uniform(0.5, 3), mu=mu)
        answers, n0 = free_body(**params)
        if len(answers) == 2 and abs(n0) > 1e-6:
            found.append((params, answers, n0))
    return found


def _warned_torque(result) -> float:
    """The unknown load T of the other answer the warning names (N m)."""
    (caution,) = [c for c in result.cautions if c.kind == "friction"]
    return float(re.search(r"consistent with the friction .*?: T = (\S+) Nm", caution.detail)[1])


def test_the_repro_gives_the_answer_raised_from_no_friction_and_names_the_wedged_one(capsys):
    """wedge-two-solutions.yaml: the sign search started with N > 0 and returned the wedged
    answer (T = -21.0 N m, N = 710.8 N) without a word."""
    path = os.path.join(DATA, "wedge-two-solutions.yaml")
    o, a = (35.79798566743312, 93.96926207859084), (65.79798566743312, 93.96926207859084)
    answers, n0 = free_body(*o, 30, 100, 0.0, -1.0, 0.0, 100.0, 1.0, 0.5)
    assert set(answers) == {1.0, -1.0} and n0 < 0 and a[0] - o[0] == pytest.approx(30)
    result = linkcli.load(path).solve()
    (t_given, n_given), (t_other, _) = answers[-1.0], answers[1.0]
    assert result.values["T"] == pytest.approx(t_given, rel=1e-9)
    assert result.values["N"] == pytest.approx(n_given, rel=1e-9)
    assert _warned_torque(result) == pytest.approx(t_other, rel=1e-5)
    assert main(["solve", path]) == 0
    err = capsys.readouterr().err
    assert "warning: another set of joint forces is consistent with the friction" in err


def test_random_wedging_cases_against_the_free_bodies():
    for params, answers, n0 in _wedging_cases(4):
        result = linkcli.loads(case(**params)).solve()
        given, other = answers[math.copysign(1.0, n0)], answers[-math.copysign(1.0, n0)]
        assert result.values["T"] == pytest.approx(given[0], rel=1e-8, abs=1e-9), params
        assert result.values["N"] == pytest.approx(given[1], rel=1e-8, abs=1e-9), params
        assert _warned_torque(result) == pytest.approx(other[0], rel=1e-5, abs=1e-6), params


def test_friction_that_locks_the_mechanism_is_refused_with_the_coefficient_where_it_locks():
    """With the load against the motion the answer raised from mu = 0 grows without bound at
    mu = cot(beta) (the rod's angle beta = 70 deg below the guide): self-locking, at 72.79 %
    of mu = 0.5; no other sign is consistent either."""
    o = (35.79798566743312, 93.96926207859084)
    answers, _ = free_body(*o, 30, 100, 0.0, -1.0, 0.0, -100.0, 1.0, 0.5)
    assert answers == {}
    text = open(os.path.join(DATA, "wedge-two-solutions.yaml")).read().replace("x: 100}",
                                                                                "x: -100}")
    with pytest.raises(SelfLockingError) as caught:
        linkcli.loads(text).solve()
    cot = 1 / math.tan(math.radians(70))
    assert caught.value.reached == pytest.approx(cot / 0.5, abs=2e-6)
    assert f"mu = {cot:.6g} at slider piston" in str(caught.value)


def test_a_normal_force_of_zero_names_no_other_answer():
    """A disc pushed along a floor with rolling resistance and no gravity: N = 0, so either
    sign of N is consistent and both give F = (m + J/R^2) a, one answer (the warning named
    'another' set of joint forces equal to the one given)."""
    path = os.path.join(DATA, "trust", "gravity-off-quoted.yaml")
    result = linkcli.load(path).solve()
    assert result.values["F"] == pytest.approx((20 + 0.9 / 0.3 ** 2) * 1.5, rel=1e-12)
    assert [c for c in result.cautions if c.kind == "friction"] == []
