"""Published two-mass problems started in a mode (mechanisms/vib-uark-*.yaml and
vib-holooly-13-4-1-*.yaml) against a hand-written eigen-solution.

Each file is a chain wall - k1 - m1 - k2 - m2 - k3 - wall: M = diag(m1, m2),
K = [[k1 + k2, -k2], [-k2, k2 + k3]], K u = omega^2 M u.  Released from rest in mode n
with coordinate q at a, x(t) = a u_n / u_qn cos(omega_n t): the largest offsets are
|a u_n / u_qn| and the middle spring's largest force is k2 |x1 - x2| (a tension, > 0,
with no preload).  Nothing expected here comes from linkcli's output.
"""
from __future__ import annotations

import os

import numpy as np
import pytest
import scipy.linalg as sla

import linkcli

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

#: file: (m1, m2, k1, k2, k3 in kg and N/m, mode, start coordinate, start, length unit in m)
CASES = {
    "vib-uark-coupled-masses-second-mode.yaml": (1, 2, 1, 2, 2, 2, 1, 1.0, 1.0),
    "vib-holooly-13-4-1-two-masses-modes.yaml": (1, 1, 100, 200, 100, 2, 0, 10.0, 1e-3),
}
REPORTED = {"vib-uark-coupled-masses-second-mode.yaml": "x1m",
            "vib-holooly-13-4-1-two-masses-modes.yaml": "x2m"}


def by_hand(m1, m2, k1, k2, k3, mode, q, a, unit):
    """omega_n (rad/s), both shapes x2/x1, both amplitudes (file units), k2's force (N)."""
    M = np.diag([m1, m2]).astype(float)
    K = np.array([[k1 + k2, -k2], [-k2, k2 + k3]], dtype=float)
    w2, U = sla.eigh(K, M)
    shapes = [U[1, j] / U[0, j] for j in range(2)]
    x = a * U[:, mode - 1] / U[q, mode - 1]
    return np.sqrt(w2), shapes, np.abs(x), k2 * abs(x[0] - x[1]) * unit


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_mode_started_problem_matches_its_eigen_solution(name):
    omegas, shapes, amplitudes, force = by_hand(*CASES[name])
    values = linkcli.load(os.path.join(ROOT, "mechanisms", name)).solve().values
    assert [float(values["w1"]), float(values["w2"])] == pytest.approx(omegas, rel=1e-9)
    assert [float(values["u1"]), float(values["u2"])] == pytest.approx(shapes, rel=1e-9)
    reported = REPORTED[name]
    assert float(values[reported]) == pytest.approx(amplitudes[0 if reported == "x1m" else 1],
                                                    rel=1e-9)
    assert float(values["N2m"]) == pytest.approx(force, rel=1e-9)
    assert float(values["N2m"]) > 0                     # no preload: given as a tension


def test_check_reports_a_start_scaled_by_the_wrong_coordinate(monkeypatch):
    """A defect planted on purpose: the start scaled by the first coordinate instead of
    the one the file names (x2 = 1 m read as x1 = 1 m) halves mass 1's amplitude, and
    ``check`` fails the printed "twice the amplitude of the second" (x1m = 2)."""
    from linkcli.answers.quantities import oscillation
    from linkcli.runs.check import check_file
    right = oscillation.mode_start

    def first_coordinate(analysis):
        x0 = right(analysis)
        return x0 / x0[0] * analysis.mech.elements.initial_mode[2]

    path = os.path.join(ROOT, "mechanisms", "vib-uark-coupled-masses-second-mode.yaml")
    assert not [o for o in check_file(path).outcomes if o.status == "fail"]
    monkeypatch.setattr(oscillation, "mode_start", first_coordinate)
    failed = [o.name for o in check_file(path).outcomes if o.status == "fail"]
    assert failed == ["x1m"], failed
