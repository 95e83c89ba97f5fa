"""What vibration chapters print (docs/vibrations.md, "What books ask"): periods, frequency
ratios, omega^2, the characteristic polynomial, complex parts, receptances, peaks, beats and
the largest values of a free vibration, each against a closed form or a brute-force
calculation written here, never against linkcli's own output."""
from __future__ import annotations

import math
import os

import numpy as np
import pytest

import linkcli
from linkcli.errors import SolveError
from linkcli.forces.oscillation import characteristic, largest

from cli_helpers import run

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
G = 9.81

# one mass on a vertical slider, a spring and a damper to the ground, gravity, a harmonic
# force: m x'' + c x' + k x = F cos(Omega t)
ONE = """
title: one degree of freedom
units: {length: mm, angle: deg, force: N, frequency: rad/s}
params: {m: 2, kk: 800, c: CC, F: 10, W: 16}
frame: {B: [0, 0]}
points: {P: [0, 300]}
sliders: {body: {point: P, guide: {x: 0}}}
coordinates: {y: {y: P}}
springs: {s: {between: [B, P], k: kk}}
dampers: {d: {between: [B, P], c: c}}
excitation: {frequency: W, forces: {F: {at: P, y: F}}}
dynamics: {gravity: 9.81, masses: {P: m}}
initial: INITIAL
quantities:
QUANTITIES
report:
  vibration: [NAMES]
  decimals: 6
"""


def one(quantities: dict, c=8.0, initial="{y: 0}"):
    """The values (display units) of ``quantities`` of the one-degree-of-freedom file."""
    text = ONE.replace("CC", repr(c)).replace("INITIAL", initial)
    if c == 0:
        text = text.replace("dampers: {d: {between: [B, P], c: c}}\n", "")
    text = text.replace("QUANTITIES", "\n".join(f"  {n}: {q}" for n, q in quantities.items()))
    text = text.replace("NAMES", ", ".join(quantities))
    result = linkcli.loads(text).solve()
    return result


def test_periods_ratios_and_omega_squared_of_one_degree_of_freedom():
    m, k, c, W = 2.0, 800.0, 8.0, 16.0
    wn = math.sqrt(k / m)
    zeta = c / (2 * math.sqrt(k * m))
    wd = wn * math.sqrt(1 - zeta ** 2)
    values = one({"T": "{natural_period: 1}", "Td": "{damped_period: 1, unit: ms}",
                  "r": "{frequency_ratio: 1}", "l": "{eigenvalue: 1}"}).values
    assert values["T"] == pytest.approx(2 * math.pi / wn, rel=1e-12)
    assert values["Td"] == pytest.approx(2e3 * math.pi / wd, rel=1e-10)
    assert values["r"] == pytest.approx(W / wn, rel=1e-12)
    assert values["l"] == pytest.approx(k / m, rel=1e-12)


def test_complex_parts_of_a_forced_response_closed_form():
    """X = F / (k - m W^2 + i c W); the force through the damper i c W X; mm and N."""
    m, k, c, F, W = 2.0, 800.0, 8.0, 10.0, 16.0
    X = F / (k - m * W ** 2 + 1j * c * W)
    result = one({"Xr": "{amplitude: y, part: real}", "Xi": "{amplitude: y, part: imaginary}",
                  "X": "{amplitude: y}", "Fr": "{force_amplitude: d, part: real}",
                  "Hr": "{receptance: [y, y], part: imaginary}"})
    values = result.values
    assert values["Xr"] == pytest.approx(X.real * 1e3, rel=1e-10)
    assert values["Xi"] == pytest.approx(X.imag * 1e3, rel=1e-10)
    assert values["X"] == pytest.approx(abs(X) * 1e3, rel=1e-10)
    assert values["Fr"] == pytest.approx((1j * c * W * X).real, rel=1e-10)
    assert values["Hr"] == pytest.approx((X / F).imag * 1e3, rel=1e-10)
    assert result.units["Hr"] == "mm/N"


@pytest.mark.parametrize("zeta", [0.02, 0.3, 0.6])
def test_peak_of_a_forced_response_closed_form(zeta):
    """|X| peaks at W = wn sqrt(1 - 2 zeta^2) with F / (2 k zeta sqrt(1 - zeta^2))."""
    m, k, F = 2.0, 800.0, 10.0
    wn = math.sqrt(k / m)
    c = 2 * zeta * math.sqrt(k * m)
    values = one({"wp": "{peak_frequency: y}", "Xp": "{peak_amplitude: y}",
                  "fp": "{peak_frequency: {y: P}, unit: Hz}"}, c=c).values
    assert values["wp"] == pytest.approx(wn * math.sqrt(1 - 2 * zeta ** 2), rel=1e-12)
    assert values["fp"] == pytest.approx(values["wp"] / (2 * math.pi), rel=1e-12)
    assert values["Xp"] == pytest.approx(F / (2 * k * zeta * math.sqrt(1 - zeta ** 2)) * 1e3,
                                         rel=1e-11)


def test_no_peak_is_an_answer_stated_as_such():
    """zeta >= 1/sqrt 2: |X| falls from the static F / k, which is the largest."""
    k, F, m = 800.0, 10.0, 2.0
    result = one({"wp": "{peak_frequency: y}", "Xp": "{peak_amplitude: y}"},
                 c=2 * 0.8 * math.sqrt(k * m))
    assert result.values["wp"] == 0.0
    assert result.values["Xp"] == pytest.approx(F / k * 1e3, rel=1e-12)
    assert any("no resonant peak" in c.detail for c in result.cautions)


def test_peaks_of_two_degrees_of_freedom_against_a_fine_scan():
    """The chain ground-k1-m1-k2-m2 with dampers, forced on m2: the maxima of |X2(W)| found
    by brute force on a fine grid of direct solutions agree with the peaks found."""
    path = os.path.join(ROOT, "docs", "examples", "two-masses.yaml")
    linkage = linkcli.load(path)
    values = linkage.solve(names=["wp1", "wp2", "Xp1", "Xp2"]).values
    M = np.diag([2.0, 1.0])
    K = np.array([[3000.0, -1000.0], [-1000.0, 1000.0]])
    R = np.array([[15.0, -5.0], [-5.0, 5.0]])
    grid = np.linspace(1.0, 80.0, 400_001)
    amp = np.array([abs(np.linalg.solve(K - w * w * M + 1j * w * R, [0, 10.0])[1])
                    for w in grid[::100]])
    coarse = grid[::100]
    tops = [i for i in range(1, len(amp) - 1) if amp[i] > amp[i - 1] and amp[i] >= amp[i + 1]]
    assert len(tops) == 2
    for i, (w, x) in zip(tops, (("wp1", "Xp1"), ("wp2", "Xp2"))):
        fine = np.linspace(coarse[i - 1], coarse[i + 1], 20001)
        a = [abs(np.linalg.solve(K - f * f * M + 1j * f * R, [0, 10.0])[1]) for f in fine]
        best = int(np.argmax(a))
        assert values[w] == pytest.approx(fine[best], abs=2 * (fine[1] - fine[0]))
        assert values[x] == pytest.approx(a[best] * 1e3, rel=1e-9)
        assert values[x] >= max(a) * 1e3 * (1 - 1e-12)     # nothing on the grid higher


def test_transmissibility_peak_of_a_moving_support_closed_form():
    """A mass on a spring and a damper whose base moves Y cos(W t): |X/Y| =
    sqrt((1 + (2 z r)^2) / ((1 - r^2)^2 + (2 z r)^2)), largest at
    r^2 = (sqrt(1 + 8 z^2) - 1) / (4 z^2)."""
    text = """
title: base excitation
units: {length: mm, angle: deg}
params: {m: 5, kk: 2000, c: 40}
frame: {G: [0, 0]}
points: {B: [0, 100], P: [0, 400]}
sliders:
  base: {point: B, guide: {x: 0}}
  body: {point: P, guide: {x: 0}}
coordinates: {s: {y: B}, y: {y: P}}
springs: {k: {between: [B, P], k: kk}}
dampers: {d: {between: [B, P], c: c}}
excitation: {frequency: 10, supports: {shaker: {coordinate: s, amplitude: 2}}}
dynamics: {masses: {P: m, B: 1}}
quantities:
  wp: {peak_frequency: y}
  Yp: {peak_amplitude: y}
report: {vibration: [wp, Yp]}
"""
    values = linkcli.loads(text).solve().values
    m, k, c = 5.0, 2000.0, 40.0
    wn, z = math.sqrt(k / m), c / (2 * math.sqrt(k * m))
    r = math.sqrt((math.sqrt(1 + 8 * z * z) - 1) / (4 * z * z))
    peak = math.sqrt((1 + (2 * z * r) ** 2) / ((1 - r * r) ** 2 + (2 * z * r) ** 2))
    assert values["wp"] == pytest.approx(r * wn, rel=1e-10)
    assert values["Yp"] == pytest.approx(2 * peak, rel=1e-10)


def test_characteristic_polynomial_against_numpys_of_the_matrices():
    """det(K - w^2 M) of the double pendulum (18 Sep 2001) against det(M) times numpy's
    polynomial of the eigenvalues of M^-1 K, with M and K as linkcli prints them."""
    path = os.path.join(ROOT, "mechanisms", "polimi-2001-09-18-vibration.yaml")
    text = open(path, encoding="utf-8").read().split("\nkeys:")[0]
    extra = "".join(f"  c{i}: {{characteristic: {i}}}\n  m{i}: {{characteristic: {i}, "
                    f"monic: true}}\n" for i in range(3))
    text = text.replace("\nquantities:\n", "\nquantities:\n" + extra, 1)
    linkage = linkcli.loads(text)
    values = linkage.solve(names=["m11", "m12", "m22", "k11", "k12", "k22"] +
                           [f"{c}{i}" for c in "cm" for i in range(3)]).values
    M = np.array([[values["m11"], values["m12"]], [values["m12"], values["m22"]]])
    K = np.array([[values["k11"], values["k12"]], [values["k12"], values["k22"]]])
    monic = np.poly(np.linalg.eigvals(np.linalg.solve(M, K)))[::-1]   # lambda^2 + ...
    for i in range(3):
        assert values[f"m{i}"] == pytest.approx(monic[i], rel=1e-10)
        assert values[f"c{i}"] == pytest.approx(monic[i] * np.linalg.det(M), rel=1e-10)
    # the 3 x 3 expansion by columns on its own, against numpy
    rng = np.random.default_rng(7)
    A = rng.normal(size=(3, 3))
    M3 = A @ A.T + 3 * np.eye(3)
    K3 = rng.normal(size=(3, 3))
    K3 = K3 @ K3.T + np.eye(3)
    expected = np.poly(np.linalg.eigvals(np.linalg.solve(M3, K3)))[::-1] * \
        np.linalg.det(M3) * (-1) ** 3
    assert characteristic(M3, K3) == pytest.approx(expected, rel=1e-10)


def test_beat_period_of_coupled_pendulums_closed_form():
    """King 4.1: w1 = sqrt(g/L), w2 = sqrt(g/L + 2k/m); the envelope's period 2 pi / dw, and
    the time the energy takes to pass to the other pendulum, half of it (11.65 s)."""
    path = os.path.join(ROOT, "mechanisms", "vib-king-4-1-coupled-pendulums.yaml")
    values = linkcli.load(path).solve(names=["Tb", "t0"]).values
    L, m, k = 0.300, 0.950, 1.50
    w1, w2 = math.sqrt(G / L), math.sqrt(G / L + 2 * k / m)
    assert values["Tb"] == pytest.approx(2 * math.pi / (w2 - w1), rel=1e-10)
    assert values["t0"] == pytest.approx(11.65, abs=0.005)


def test_largest_values_of_a_free_vibration_of_one_degree_of_freedom():
    """Undamped: X = sqrt(x0^2 + (v0/wn)^2); the spring's force k (delta_st + X) when released
    from rest where it is unstretched (X = delta_st): 2 m g; damped: against a fine scan of
    the closed-form response."""
    m, k = 2.0, 800.0
    wn = math.sqrt(k / m)
    values = one({"ym": "{largest: y}", "Pm": "{largest: {y: P}}"}, c=0.0,
                 initial="{y: 4, y_dot: 300}").values
    assert values["ym"] == pytest.approx(math.hypot(4.0, 300.0 / wn), rel=1e-12)
    assert values["Pm"] == pytest.approx(values["ym"], rel=1e-12)
    values = one({"Nm": "{largest: {spring: s}}", "ym": "{largest: y}"}, c=0.0,
                 initial="{y: 0, from: unstretched}").values
    assert values["Nm"] == pytest.approx(-2 * m * G, rel=1e-10)      # compression
    assert values["ym"] == pytest.approx(m * G / k * 1e3, rel=1e-10)
    c = 12.0
    zeta = c / (2 * math.sqrt(k * m))
    wd = wn * math.sqrt(1 - zeta ** 2)
    x0, v0 = 4e-3, -0.5
    t = np.linspace(0, 2, 2_000_001)
    x = np.exp(-zeta * wn * t) * (x0 * np.cos(wd * t) + (v0 + zeta * wn * x0) / wd *
                                 np.sin(wd * t))
    values = one({"ym": "{largest: y}"}, c=c, initial="{y: 4, y_dot: -500}").values
    assert values["ym"] == pytest.approx(np.max(np.abs(x)) * 1e3, rel=1e-9)


def test_largest_value_of_two_modes_by_superposition():
    """Undamped two degrees of freedom from x0: the sum of the modal amplitudes (computed
    here from scipy's eigh), which a long time scan approaches from below."""
    from scipy.linalg import eigh
    M = np.diag([2.0, 1.0])
    K = np.array([[3000.0, -1000.0], [-1000.0, 1000.0]])
    x0 = np.array([5e-3, 0.0])
    found = largest(M, K, np.zeros((2, 2)), [0.0, 1.0], x0, [0.0, 0.0])
    values, vectors = eigh(K, M)
    a = vectors.T @ M @ x0
    expected = sum(abs(vectors[1, k] * a[k]) for k in range(2))
    assert found.value == pytest.approx(expected, rel=1e-12)
    t = np.linspace(0, 200, 2_000_001)
    x2 = sum(vectors[1, k] * a[k] * np.cos(np.sqrt(values[k]) * t) for k in range(2))
    assert np.max(np.abs(x2)) <= found.value * (1 + 1e-12)
    assert np.max(np.abs(x2)) >= found.value * 0.99


def test_initial_offsets_from_the_figure():
    """from: figure with y: 0 starts where the figure draws the mass (300 mm), above the
    equilibrium by m g / k: the free response's largest offset is that."""
    m, k = 2.0, 800.0
    values = one({"ym": "{largest: y}", "y0": "{free_response: y, time: 0}"}, c=0.0,
                 initial="{y: 0, from: figure}").values
    assert values["ym"] == pytest.approx(m * G / k * 1e3, rel=1e-10)
    assert values["y0"] == pytest.approx(m * G / k * 1e3, rel=1e-10)


@pytest.mark.parametrize("quantity, words, code", [
    ("{natural_frequency: 1, part: real}", "'part' is of a complex answer", 2),
    ("{beat_period: [1, 1]}", "must differ", 2),
    ("{characteristic: 2}", "i = 0-1", 2),
    ("{natural_period: 1, unit: mm}", "is a time (T) and the unit 'mm' is a length", 2),
    ("{largest: {spring: nope}}", "undefined spring 'nope'", 2),
    ("{peak_frequency: y, peak: 2}", "has 1 peak (at Omega =", 3),
    ("{receptance: [y]}", "a receptance is [response coordinate, forced coordinate]", 2),
])
def test_refusals(quantity, words, code):
    text = ONE.replace("CC", "8.0").replace("INITIAL", "{y: 0}")
    text = text.replace("QUANTITIES", f"  z: {quantity}").replace("NAMES", "z")
    status, out, err = run(["solve", "-"], stdin=text)
    assert status == code and words in err, err


def test_peaks_of_an_undamped_system_are_refused():
    with pytest.raises(SolveError) as info:
        one({"wp": "{peak_frequency: y}"}, c=0.0)
    assert "without damping" in str(info.value) and info.value.exit_code == 3
