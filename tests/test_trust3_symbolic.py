"""--symbolic answers or refuses by name within its bound, and never fails where the numbers
answer (files in tests/data/trust3/; each file's title says what linkcli did).

Every expected number comes from the test's own computation: the chain's natural
frequencies from NumPy's eigenvalues of the M and K written here, the inclined springs'
equilibrium and stiffness from the potential energy written here (scipy's root and finite
differences), the carried link's frequency and the coupler coordinate's stiffness from
their velocity ratios at the figure.
"""
from __future__ import annotations

import math
import os
import time

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import fsolve

from linkcli.texts import budget as budget_module
from linkcli.texts.symbolic import ITEMS, as_dict, formulas, to_text
from linkcli.cli import main
from linkcli.forces import symbolic as fs
from linkcli.input.source import load_file

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "trust3")


def path(name):
    return os.path.join(DATA, name)


def of(name, **kw):
    return formulas(load_file(path(name)), **kw)


def value(expr, f, extra=None):
    values = dict(f.numbers)
    values.update(extra or {})
    return complex(sp.N(sp.sympify(expr).xreplace(values), 30))


def omegas(f):
    """The natural frequencies from the written characteristic polynomial at the numbers."""
    w = sp.Symbol("w2")
    poly = sp.Poly(f.values["characteristic"].xreplace(
        {sp.Symbol("omega", positive=True): sp.sqrt(w)}), w)
    coefficients = [value(c, f).real for c in poly.all_coeffs()]
    return np.sqrt(np.sort(np.roots(coefficients).real))


def test_six_masses_in_a_chain_are_written_whole_within_the_bound():
    """Was > 300 s (det by sympy's Bareiss with simplification); the determinant by minors
    in a polynomial ring takes a fraction of a second."""
    start = time.process_time()
    f = of("chain6-symbolic.yaml")
    assert time.process_time() - start < budget_module.SECONDS
    assert not f.missing
    m = np.array([1.1, 1.2, 1.3, 1.4, 1.5, 1.6])
    k = np.array([110.0, 120, 130, 140, 150, 160])
    K = np.diag(k + np.append(k[1:], 0)) - np.diag(k[1:], 1) - np.diag(k[1:], -1)
    expected = np.sqrt(np.sort(np.linalg.eigvals(np.linalg.solve(np.diag(m), K)).real))
    assert omegas(f) == pytest.approx(expected, rel=1e-9)


def test_inclined_springs_and_a_load_give_the_numeric_equilibrium_and_its_stiffness():
    """Never ended (the characteristic polynomial's roots expanded from coefficients of
    thousands of operations); now the equilibrium is the numeric one, said so, K holds it,
    and the characteristic polynomial is refused by its size."""
    f = of("vib4_symbolic_no_end_inclined_springs_load.yaml")
    kk, h, F = 3000.0, 0.1, 100.0
    A, B = np.array([-0.5, h]), np.array([0.8, h])

    def potential(x):
        p1, p2 = np.array([x[0], 0.0]), np.array([x[1], h])
        free = (np.hypot(0.5, h), np.hypot(0.3, h), 0.5)     # free in the figure
        stretch = (np.linalg.norm(p1 - A) - free[0], np.linalg.norm(p2 - p1) - free[1],
                   np.linalg.norm(B - p2) - free[2])
        return 0.5 * kk * sum(s * s for s in stretch) - F * x[0]

    def gradient(x, d=1e-6):
        return np.array([(potential(x + e) - potential(x - e)) / (2 * d)
                         for e in np.eye(2) * d])
    q = fsolve(gradient, [0.0, 0.3], xtol=1e-13)
    assert f.how == "numeric"
    stated = {s.name: v for s, v in f.stated.items()}
    assert stated["x1_e"] == pytest.approx(q[0], rel=1e-6)
    assert stated["x2_e"] == pytest.approx(q[1], rel=1e-6)
    assert round(stated["x1_e"], 3) == 0.023                # the printed x1s = 0.023 m
    d = 1e-4
    hessian = np.array([[(gradient(q + d * e)[i] - gradient(q - d * e)[i]) / (2 * d)
                         for e in np.eye(2)] for i in range(2)])
    K = np.array([[value(x, f).real for x in row] for row in f.values["K"].tolist()])
    assert K == pytest.approx(hessian, rel=1e-5)
    assert "characteristic" in f.missing and "operations" in f.missing["characteristic"]
    assert set(f.missing) == {"characteristic"}


def test_three_free_coordinates_answer_within_the_bound_or_name_what_is_not_reached(capsys):
    """Took minutes; now the answers come with the formulas reached, each missing one named,
    within the bound and its grace."""
    start = time.process_time()
    assert main(["solve", path("symbolic-three-coordinates-no-answer.yaml"), "--symbolic"]) == 0
    spent = time.process_time() - start
    out = capsys.readouterr().out
    assert spent < budget_module.SECONDS + budget_module.GRACE + 8    # + parsing, numbers
    assert "m_00" in out and "eq_xY" in out                          # the numbers
    assert "characteristic: not available" in out or "characteristic" not in out


def test_a_bound_of_zero_names_every_formula_and_prints_the_numbers(capsys):
    assert main(["solve", path("chain6-symbolic.yaml"), "--symbolic", "--seconds", "0"]) == 0
    out = capsys.readouterr().out
    assert "w1 =" in out
    assert ", ".join(ITEMS) + ": not available" in out
    assert "not reached within the 0 s of processor time the formulas may take" in out
    data = as_dict(of("chain6-symbolic.yaml", seconds=0))
    assert set(data["missing"]) == set(ITEMS) and "M" not in data


def test_a_step_that_never_checks_is_left_after_the_bound_and_its_grace(monkeypatch):
    """The guard that bites where a step of the algebra does not return to a check: the
    caller stops waiting at the bound plus GRACE and names what was not reached."""
    def spin(K):
        end = time.process_time() + 30
        while time.process_time() < end:
            pass
        return []
    monkeypatch.setattr(fs, "stability", spin)
    monkeypatch.setattr(budget_module, "GRACE", 0.5)
    start = time.monotonic()
    f = of("chain6-symbolic.yaml", seconds=1.0)
    assert time.monotonic() - start < 20           # not the 30 s of the step
    assert "M" in f.values and "K" in f.values
    assert {"stability", "characteristic", "equations"} <= set(f.missing)
    assert "not reached" in f.missing["stability"]
    text = to_text(f)
    assert "[K] = " in text


def test_a_slider_carrying_the_start_of_a_link_writes_its_closures(capsys):
    """Was KeyError 'A' (exit 70): the slider's driver placed no point for the closures."""
    assert main(["solve", path("vib4_symbolic_carried_point_keyerror.yaml"), "--symbolic"]) == 0
    out = capsys.readouterr().out
    b, e = 0.2, 0.02
    M = 3 + 1.2 / 4 + 1.2 * b ** 2 / 12 / b ** 2     # collar; the link's centre; its spin
    assert f"wn = {math.sqrt(1500 / M):10.1f} rad/s" in out.replace("  ", " ") or \
        f"{math.sqrt(1500 / M):.1f} rad/s" in out
    assert "closes a loop" in out
    f = of("vib4_symbolic_carried_point_keyerror.yaml")
    closure = f.loop.closures[-1]
    y, theta, xB = sp.symbols("y theta_AB xB", real=True)
    at = {sp.Symbol("b", positive=True): b, sp.Symbol("e", positive=True): e,
          y: 0.0, theta: 0.0, xB: e + b, sp.Symbol("gamma_roll", real=True): 0.0}
    residual = (closure.left - closure.right).xreplace(at)
    assert abs(complex(sp.N(residual))) < 1e-12
    assert f.loop.closures[0].text.startswith("driver: slider collar")


def test_a_coupler_angle_coordinate_is_named_and_its_closures_written(capsys):
    """Was exit 3 (the driving vector A->B must join a fixed pivot); the numbers answer, so
    --symbolic names what it cannot give and writes the loop with the crank's angle."""
    assert main(["solve", path("symbolic-coupler-angle-coordinate.yaml"), "--symbolic"]) == 0
    out = capsys.readouterr().out
    O, A, B, D = 0j, 0.1j, 0.35 + 0.2j, 0.3 + 0j
    # velocity ratio at the figure: i w2 (A - O) + i w3 (B - A) = i w4 (B - D)
    a, b, c = A - O, B - A, B - D
    w2_over_w3 = ((b * c.conjugate()).imag / (a * c.conjugate()).imag) * -1
    k = 10.0 * w2_over_w3 ** 2                     # V = kt theta2^2 / 2, theta2' = r chi'
    assert f"k = {k:10.1f} Nm/rad" in out or f"{k:.1f} Nm/rad" in out
    assert "chi (the angle of A->B) places no point in the solving order" in out
    assert "in place of chi" in out
    f = of("symbolic-coupler-angle-coordinate.yaml")
    closure = f.loop.closures[-1]
    chi, t2, t4 = (sp.Symbol(n, real=True) for n in ("chi", "theta_OA", "theta_DB"))
    at = {chi: np.angle(b), t2: np.angle(a), t4: np.angle(c)}
    at.update({sym: float(v) for sym, v in f.loop.values.items()})
    residual = (closure.left - closure.right).xreplace(at)
    assert abs(complex(sp.N(residual))) < 1e-12
