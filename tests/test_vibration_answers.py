"""The answers of a vibration problem: in the file's units, one definition of a mode and its
damping, mode shapes only where they are defined, phases continuous in the damping.

The files in tests/data/vibration/ reproduce defects (their titles say which); every
expected value is computed here by hand or from a closed form (zeta = c / (2 sqrt(k m)),
the roots of m s^2 + c s + k), never taken from linkcli's output.
"""
from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest
import scipy.linalg as sla

import linkcli
from linkcli.cli import main
from linkcli.errors import InputError, ModeError, SolveError

sys.path.insert(0, os.path.dirname(__file__))
from vibration_cases import chain, chain_omega, pendulums, pendulums_omega  # noqa: E402

DATA = os.path.join(os.path.dirname(__file__), "data", "vibration")
# exact definitions: in = 0.0254 m, lb = 0.45359237 kg, lbf = lb * 9.80665 m/s^2, ft = 0.3048 m
INCH, LB, FT = 0.0254, 0.45359237, 0.3048
LBF = LB * 9.80665
SLUG = LBF / FT
DEG = math.pi / 180


def path(name):
    return os.path.join(DATA, name)


def text(name, *replace):
    out = open(path(name)).read()
    for old, new in replace:
        assert old in out, old
        out = out.replace(old, new)
    return out


def solved(source, names=None):
    """(values, units) of a file's report: ``source`` a file name or YAML text."""
    linkage = linkcli.load(path(source)) if source.endswith(".yaml") else linkcli.loads(source)
    result = linkage.solve(names=names)
    return {k: float(v) for k, v in result.values.items()}, result.units


def refusal(source, name) -> ModeError:
    linkage = linkcli.load(path(source)) if source.endswith(".yaml") else linkcli.loads(source)
    with pytest.raises(ModeError) as info:
        linkage.solve(names=[name])
    assert info.value.exit_code == 3
    return info.value


def sdof_roots(m, c, k):
    """The roots of m s^2 + c s + k = 0."""
    return np.roots([m, c, k])


# --- 1. units out as they came in --------------------------------------------------------
def test_a_file_in_pounds_and_inches_gets_its_answers_in_them():
    """1 lb on 10 lb/in, 1 lbf at 1 Hz, g = 9.80665 (so the block weighs 1 lbf)."""
    values, units = solved("units_lb_lbf.yaml")
    assert units == {"m_red": "lb", "k_red": "lb/in", "N": "lbf", "Ft": "lbf", "X": "in"}
    assert values["m_red"] == pytest.approx(1.0, rel=1e-12)
    assert values["k_red"] == pytest.approx(10.0, rel=1e-12)
    assert values["N"] == pytest.approx(-1.0, rel=1e-12)            # compressed by the weight
    # closed form in the file's own units: k - m Omega^2 with m in lbf s^2/in
    m = 1.0 / (9.80665 / INCH)                                       # lbf s^2 / in
    X = 1.0 / (10.0 - m * (2 * math.pi) ** 2)                        # in
    assert values["X"] == pytest.approx(X, rel=1e-12)
    assert values["Ft"] == pytest.approx(10.0 * X, rel=1e-12)        # lbf: the spring's k X


def test_a_declared_force_unit_is_used_for_forces_of_an_si_file():
    """force: kN in a file otherwise SI: the spring's static force m g in kN."""
    source = text("undamped_phase_sign.yaml", ("force: N,", "force: kN,"),
                  ("F: {at: P, y: 9}", "F: {at: P, y: 0.009}"))
    source = source.replace("  X: {amplitude: x}", "  X: {amplitude: x}\n  N: {spring_force: k}"
                            "\n  Ft: {force_amplitude: [k]}")
    values, units = solved(source, ["N", "Ft", "X"])
    assert (units["N"], units["Ft"], units["X"]) == ("kN", "kN", "mm")
    assert values["N"] == pytest.approx(-5 * 9.81 / 1000, rel=1e-12)
    X = 9.0 / abs(6000 - 5 * (2 * math.pi * 50) ** 2)                # m, from 9 N
    assert values["X"] == pytest.approx(1000 * X, rel=1e-12)
    assert values["Ft"] == pytest.approx(6000 * X / 1000, rel=1e-12)


@pytest.mark.parametrize("length, angle", [("ft", "deg"), ("in", "rad"), ("mm", "deg")])
def test_a_mode_shape_mixing_a_length_and_an_angle_is_in_the_files_units(length, angle):
    """Edwards & Penney 7.4-24 data: V = 1/2 k (x + 6 th)^2 + 1/2 k (x - 4 th)^2 (ft, rad),
    M = diag(100 slug, 1000 slug ft^2); mode 1's th / x converted by hand."""
    k = 2000.0
    K = np.array([[2 * k, 2 * k], [2 * k, 52 * k]])                  # lb/ft, lb, lb ft
    w2, vectors = sla.eigh(K, np.diag([100.0, 1000.0]))
    ratio = vectors[1, 0] / vectors[0, 0]                            # rad/ft
    assert ratio == pytest.approx(-0.06023, abs=1e-5)                # the file's note
    source = text("mode_shape_mixed_units.yaml")
    if (length, angle) != ("ft", "deg"):
        scale = {"in": 12.0, "mm": 304.8}[length]
        source = source.replace("units: {length: ft, angle: deg,",
                                f"units: {{length: {length}, angle: {angle},")
        for old, new in (("A1: [6, 0], A2: [-4, 0]", f"A1: [{6 * scale}, 0], A2: [{-4 * scale}, 0]"),
                         ("G: [0, 2], S1: [6, 2], S2: [-4, 2]",
                          f"G: [0, {2 * scale}], S1: [{6 * scale}, {2 * scale}], "
                          f"S2: [{-4 * scale}, {2 * scale}]"),
                         ("local: {G: [0, 0], S1: [6, 0], S2: [-4, 0]}",
                          f"local: {{G: [0, 0], S1: [{6 * scale}, 0], S2: [{-4 * scale}, 0]}}")):
            source = source.replace(old, new)
    values, units = solved(source)
    per_angle = 1.0 if angle == "rad" else DEG                       # rad in one display unit
    per_length = {"ft": 1.0, "in": 1 / 12, "mm": 1 / 304.8}[length]  # ft in one display unit
    assert units["u1"] == f"{angle}/{length}"
    assert values["u1"] == pytest.approx(ratio * per_length / per_angle, rel=1e-9)
    assert values["w1"] == pytest.approx(math.sqrt(w2[0]), rel=1e-9)


def test_matrix_entries_of_mixed_coordinates_are_products_of_the_files_units():
    """The same car: m12 is 0 slug ft, k12 = 2k (lb/rad) in N/deg (no force unit declared),
    k22 = 52 k lb ft/rad in the default N m/rad."""
    source = text("mode_shape_mixed_units.yaml").replace(
        "  u1: {mode_shape: [1, theta]}",
        "  u1: {mode_shape: [1, theta]}\n  m11: {mass_matrix: [x, x]}\n"
        "  m22: {mass_matrix: [theta, theta]}\n  k12: {stiffness_matrix: [x, theta]}\n"
        "  k22: {stiffness_matrix: [theta, theta]}")
    values, units = solved(source, ["m11", "m22", "k12", "k22"])
    assert units == {"m11": "slug", "m22": "slug ft^2", "k12": "lbf/deg", "k22": "Nm/rad"}
    assert values["m11"] == pytest.approx(100.0, rel=1e-12)
    assert values["m22"] == pytest.approx(1000.0, rel=1e-12)
    assert values["k12"] == pytest.approx(4000.0 * DEG, rel=1e-9)    # lbf/rad -> lbf/deg
    assert values["k22"] == pytest.approx(104000.0 * LBF * FT, rel=1e-9)


def test_explain_prints_the_matrices_in_the_files_units(capsys):
    assert main(["explain", path("units_lb_lbf.yaml")]) == 0
    out = capsys.readouterr().out
    assert "M (lb) =" in out and "K (lb/in) =" in out
    assert "spring k: force N = -1 lbf" in out
    assert "m* = 1 lb, k* = 10 lb/in" in out
    assert "Omega = 1 Hz" in out


# --- 2. one definition of a mode and its damping -------------------------------------------
def test_overdamped_modes_have_their_own_damping_ratios():
    """Uncoupled: mode 1 m = 1, k = 1, c = 10 (zeta 5); mode 2 m = 1, k = 100, c = 40 (2)."""
    values, _ = solved("overdamped_2dof.yaml", ["w1", "w2", "z1", "z2"])
    assert values["w1"] == pytest.approx(1.0, rel=1e-12)
    assert values["w2"] == pytest.approx(10.0, rel=1e-12)
    assert values["z1"] == pytest.approx(10 / (2 * math.sqrt(1 * 1)), rel=1e-9)
    assert values["z2"] == pytest.approx(40 / (2 * math.sqrt(100 * 1)), rel=1e-9)
    for name, (m, c, k) in (("wd1", (1, 10, 1)), ("wd2", (1, 40, 100))):
        error = refusal("overdamped_2dof.yaml", name)
        assert error.reason == "overdamped" and error.mode == int(name[-1])
        rates = np.sort(-sdof_roots(m, c, k).real)
        assert np.allclose(error.values, rates, rtol=1e-9)
        assert "overdamped" in str(error)


def test_damping_is_numbered_by_mode_not_by_root_size():
    """Mode 1 (wn = 1) is lightly damped, mode 2 (wn = 10) overdamped."""
    values, _ = solved("swapped_order_2dof.yaml", ["z1", "z2", "wd1"])
    assert values["z1"] == pytest.approx(0.1 / (2 * math.sqrt(1 * 1)), rel=1e-9)
    assert values["z2"] == pytest.approx(200 / (2 * math.sqrt(100 * 1)), rel=1e-9)
    assert values["wd1"] == pytest.approx(abs(sdof_roots(1, 0.1, 1)[0].imag), rel=1e-9)
    error = refusal("swapped_order_2dof.yaml", "wd2")
    assert error.mode == 2 and error.reason == "overdamped"
    assert np.allclose(error.values, np.sort(-sdof_roots(1, 200, 100).real), rtol=1e-9)


def test_a_mass_held_by_a_damper_alone_has_no_damping_ratio():
    """m s^2 + c s = 0: s = 0 and -c/m; zeta = c / (2 sqrt(k m)) is undefined at k = 0."""
    values, _ = solved("damper_only.yaml", ["w1"])
    assert values["w1"] == 0.0
    for name in ("z1", "wd1"):
        error = refusal("damper_only.yaml", name)
        assert error.reason == "no stiffness" and error.mode == 1
        assert np.allclose(error.values, [0.0, 50 / 5], atol=1e-12)


def test_undamped_modes_have_zero_damping_and_their_natural_frequency():
    source = text("swapped_order_2dof.yaml").replace(
        "dampers:\n  r1: {between: [G1, P1], c: 0.1}\n  r2: {between: [G2, P2], c: 200}\n", "")
    values, _ = solved(source, ["z1", "z2", "wd1", "wd2"])
    assert (values["z1"], values["z2"]) == (0.0, 0.0)           # R = 0: exactly
    assert (values["wd1"], values["wd2"]) == pytest.approx((1.0, 10.0), rel=1e-12)


NON_PROPORTIONAL = """
title: two masses in a chain of three springs, a damper on the first only
units: {length: mm, angle: deg}
frame: {W0: [0, 0], W1: [300, 0]}
points: {P1: [100, 0], P2: [200, 0]}
sliders: {b1: {point: P1, guide: {y: 0}}, b2: {point: P2, guide: {y: 0}}}
coordinates: {x1: {x: P1}, x2: {x: P2}}
springs:
  s1: {between: [W0, P1], k: 400}
  s2: {between: [P1, P2], k: 100}
  s3: {between: [P2, W1], k: 900}
dampers: {r: {between: [W0, P1], c: C}}
dynamics: {masses: {P1: 1, P2: 2}}
params: {C: 0.5}
quantities:
  z1: {damping_ratio: 1}
  z2: {damping_ratio: 2}
  wd1: {damped_frequency: 1}
  wd2: {damped_frequency: 2}
report: {vibration: [z1, z2, wd1, wd2]}
"""


def _chain(c):
    M = np.diag([1.0, 2.0])
    K = np.array([[500.0, -100.0], [-100.0, 1000.0]])
    R = np.array([[c, 0.0], [0.0, 0.0]])
    return M, K, R


def test_non_proportional_damping_pairs_each_root_with_its_mode():
    """A damper on one mass couples the modes.  Each mode's roots solve det(M s^2 + R s + K)
    = 0, and for a light damper they approach first-order perturbation theory:
    zeta_k = u_k^T R u_k / (2 omega_k) with u_k mass-normalised (error of order c^2)."""
    c = 0.5
    values, _ = solved(NON_PROPORTIONAL)
    M, K, R = _chain(c)
    w2, U = sla.eigh(K, M)
    omega = np.sqrt(w2)
    first_order = np.einsum("ik,ij,jk->k", U, R, U) / (2 * omega)
    for k in (1, 2):
        zeta, wd = values[f"z{k}"], values[f"wd{k}"]
        wn = wd / math.sqrt(1 - zeta ** 2)
        s = complex(-zeta * wn, wd)
        D = M * s ** 2 + R * s + K
        scale = np.linalg.norm(M) * abs(s) ** 2 + np.linalg.norm(K)
        assert abs(np.linalg.det(D)) < 1e-10 * scale ** 2
        assert zeta == pytest.approx(first_order[k - 1], rel=10 * (c / omega[0]) ** 2)
        assert wn == pytest.approx(omega[k - 1], rel=10 * (c / omega[0]) ** 2)


def test_explain_says_how_coupled_damping_is_paired(capsys, tmp_path):
    heavy = NON_PROPORTIONAL.replace("C: 0.5", "C: 300")
    file = tmp_path / "coupled.yaml"
    file.write_text(heavy)
    assert main(["explain", str(file)]) == 0
    out = capsys.readouterr().out
    assert "damping couples the modes" in out
    # the heavy damper makes the first mass's mode overdamped: two decay rates are named
    M, K, R = _chain(300.0)
    A = np.block([[np.zeros((2, 2)), np.eye(2)],
                  [-np.linalg.solve(M, K), -np.linalg.solve(M, R)]])
    s = np.linalg.eigvals(A)
    real = np.sort(-s[s.imag == 0].real)
    assert len(real) == 2
    assert "overdamped: decay rates" in out
    line = next(x for x in out.splitlines() if "overdamped: decay rates" in x)
    printed = [float(x) for x in line.split("rates")[1].replace("1/s", "").split("and")]
    assert np.allclose(sorted(printed), real, rtol=1e-5)


# --- 3. mode shapes only where they are defined -------------------------------------------
def test_a_shape_ratio_to_a_coordinate_that_does_not_move_is_refused():
    """Three equal masses between walls: mode 2 is (1, 0, -1) in (x1, x2, x3); the file
    lists x2 first, the reference of the shapes."""
    error = refusal("symmetric_chain_mode.yaml", "u2_x1")
    assert error.reason == "does not move" and error.mode == 2
    assert error.values[0] < 1e-12
    assert "normalised by x2" in str(error)
    values, units = solved("symmetric_chain_mode.yaml", ["w1", "w2", "w3", "u1_x1"])
    w = math.sqrt(1000.0) * np.array([math.sqrt(2 - math.sqrt(2)), math.sqrt(2),
                                      math.sqrt(2 + math.sqrt(2))])
    assert [values[f"w{k}"] for k in (1, 2, 3)] == pytest.approx(w, rel=1e-12)
    assert values["u1_x1"] == pytest.approx(1 / math.sqrt(2), rel=1e-12)
    assert units["u1_x1"] == ""


def test_with_a_moving_reference_the_same_mode_is_answered():
    source = text("symmetric_chain_mode.yaml", ("  x2: {x: P2}\n  x1: {x: P1}\n",
                                                "  x1: {x: P1}\n  x2: {x: P2}\n"))
    source = source.replace("  u1_x1: {mode_shape: [1, x1]}", "  u1_x1: {mode_shape: [1, x1]}\n"
                            "  u2_x2: {mode_shape: [2, x2]}")
    values, _ = solved(source, ["u2_x3", "u2_x2"])
    assert values["u2_x3"] == pytest.approx(-1.0, rel=1e-12)
    assert values["u2_x2"] == 0.0 and math.copysign(1, values["u2_x2"]) == 1


def test_a_shape_of_a_repeated_frequency_is_refused():
    """Two identical uncoupled oscillators: any combination is a mode."""
    source = text("swapped_order_2dof.yaml", ("k: 100}", "k: 1}")).replace(
        "dampers:\n  r1: {between: [G1, P1], c: 0.1}\n  r2: {between: [G2, P2], c: 200}\n", "")
    source = source.replace("  wd2: {damped_frequency: 2}", "  wd2: {damped_frequency: 2}\n"
                            "  u: {mode_shape: [1, x2]}")
    error = refusal(source, "u")
    assert error.reason == "repeated" and error.values == pytest.approx([1.0])


# --- 4. phases continuous in the damping ---------------------------------------------------
@pytest.mark.parametrize("c", [0.0, 1e-3, 1.0, 200.0])
def test_the_phase_above_resonance_is_a_lag_continuous_in_the_damping(c):
    """5 kg on 6000 N/m, 9 N at 50 Hz: phase = -atan2(c Omega, k - m Omega^2), which tends
    to -180 deg as c -> 0 above resonance."""
    source = text("undamped_phase_sign.yaml")
    if c:
        source = source.replace("dynamics:", f"dampers: {{r: {{between: [O, P], c: {c}}}}}\n"
                                "dynamics:")
    values, units = solved(source)
    W = 2 * math.pi * 50
    expected = -math.degrees(math.atan2(c * W, 6000 - 5 * W ** 2))
    assert units["ph"] == "deg"
    assert values["ph"] == pytest.approx(expected, abs=1e-9)
    assert values["ph"] <= -179 if c <= 1.0 else values["ph"] < 0


def test_the_phase_below_resonance_is_zero_not_minus_zero():
    values, _ = solved(text("undamped_phase_sign.yaml", ("frequency: 50", "frequency: 1")))
    assert values["ph"] == 0.0 and math.copysign(1, values["ph"]) == 1


# --- 5. messages -------------------------------------------------------------------------
def test_resonance_is_named_in_the_files_frequency_unit():
    wn = math.sqrt(6000 / 5) / (2 * math.pi)                          # Hz
    source = text("undamped_phase_sign.yaml", ("frequency: 50", f"frequency: {wn!r}"))
    with pytest.raises(SolveError) as info:
        linkcli.loads(source).solve()
    assert f"Omega = {wn:.6g} Hz" in str(info.value)


def test_a_value_that_overflows_is_refused_with_the_reason():
    source = text("undamped_phase_sign.yaml", ("k: 6000, preload: static", "k: 1e-200"),
                  ("masses: {P: 5}", "masses: {P: 1e-200}"), ("y: 9}", "y: 1e300}"),
                  ("gravity: 9.81", "gravity: 0"), ("frequency: 50", "frequency: 0.05"))
    with pytest.raises(SolveError) as info:
        linkcli.loads(source).solve(names=["X"])
    assert "'X' is not a finite number" in str(info.value)
    assert "overflows" in str(info.value)


def test_a_refused_stiffness_shows_its_value_and_its_expression(tmp_path, capsys):
    file = tmp_path / "negative.yaml"
    file.write_text(text("damper_only.yaml", ("params: {m: 5, c: 50}", "params: {m: 5, c: 50, kk: 3}"))
                    .replace("dampers:", "springs:\n  s: {between: [B, P], k: kk - 5}\ndampers:"))
    assert main(["solve", str(file)]) == 2
    err = capsys.readouterr().err
    assert "springs.s.k" in err and "-2 N/m (= kk - 5)" in err


# --- 6. size ----------------------------------------------------------------------------
def test_a_long_chain_matches_its_closed_form():
    """40 masses between walls: omega_j = 2 sqrt(k/m) sin(j pi / (2 (n + 1))); each point's
    second derivatives are kept where they are not zero (none here)."""
    values, _ = solved(chain(40))
    assert [values["w1"], values["wn"]] == pytest.approx(chain_omega(40), rel=1e-9)


def test_pendulums_end_to_end_match_their_linearised_matrices():
    """8 rods hanging end to end: every pair of coordinates moves the last mass."""
    values, _ = solved(pendulums(8))
    assert [values["w1"], values["wn"]] == pytest.approx(pendulums_omega(8), rel=1e-9)


def test_more_coordinates_than_the_bound_are_refused(monkeypatch):
    from linkcli.answers.quantities import vibration
    monkeypatch.setattr(vibration, "MAX_COORDINATES", 3)
    with pytest.raises(InputError) as info:
        linkcli.loads(chain(4)).solve()
    assert info.value.key == "coordinates" and "at most 3" in str(info.value)


def test_blocks_compute_as_the_full_arrays():
    """Sums, products, in-place sums into an array and products with vectors of blocks
    against the same operations on the full arrays."""
    from linkcli.kinematics.jacobian import Block
    rng = np.random.default_rng(7)
    a = Block([1, 4], rng.standard_normal((2, 2)) + 1j * rng.standard_normal((2, 2)), 6)
    b = Block([0, 4, 5], rng.standard_normal((3, 3)), 6)
    A, B = np.asarray(a), np.asarray(b)
    v = rng.standard_normal(6)
    assert np.array_equal(np.asarray(a + b), A + B)
    assert np.array_equal(np.asarray(a - b), A - B)
    assert np.array_equal(np.asarray(np.float64(2.5) * a), 2.5 * A)
    assert np.array_equal(np.asarray(np.real(np.conj(2j) * a)), np.real(-2j * A))
    assert np.allclose(a @ v, A @ v, rtol=1e-15) and np.allclose(v @ a, v @ A, rtol=1e-15)
    K = rng.standard_normal((6, 6))
    expected = K - B
    K -= b
    assert np.array_equal(K, expected)
    assert a[4, 1] == A[4, 1] and a[2, 3] == 0 and a[4][1] == A[4, 1]


# --- 7. pictures -------------------------------------------------------------------------
def _inside(fig, artist, ax) -> bool:
    """Whether ``artist``'s drawn box lies within ``ax``'s (in pixels)."""
    renderer = fig.canvas.get_renderer()
    box, frame = artist.get_window_extent(renderer), ax.get_window_extent(renderer)
    return (box.x0 >= frame.x0 - 1 and box.x1 <= frame.x1 + 1
            and box.y0 >= frame.y0 - 1 and box.y1 <= frame.y1 + 1)


def test_the_frequency_response_has_an_axis_per_unit_and_labelled_markers():
    """A pendulum (deg) and a slider (mm), marked natural frequencies near both ends."""
    pytest.importorskip("matplotlib")
    from linkcli.pictures.vibration import frf_figure
    mech = linkcli.load(os.path.join(os.path.dirname(DATA), "..", "..", "mechanisms",
                                     "polimi-2001-02-07-vibration.yaml")).model
    fig, _ = frf_figure(mech, "1:50.5:120", None)
    fig.canvas.draw()
    amp_deg, amp_mm, phase_ax = fig.axes
    assert amp_deg.get_ylabel() == "amplitude [deg]" and amp_mm.get_ylabel() == "amplitude [mm]"
    assert phase_ax.get_ylabel() == "phase [deg]"
    assert [t.get_text() for t in amp_deg.get_legend().get_texts()] == ["|theta|"]
    assert [t.get_text() for t in amp_mm.get_legend().get_texts()] == ["|x|"]
    marks = [t for t in amp_deg.texts if t.get_text().startswith("omega")]
    assert [t.get_text() for t in marks] == ["omega1 = 1.562 rad/s", "omega2 = 49.94 rad/s"]
    assert all(_inside(fig, t, amp_deg) for t in marks)
    # undamped, past both resonances: x in opposition (-180), as solve's phase says
    x_phase = phase_ax.get_lines()[1].get_ydata()
    assert x_phase[-1] == pytest.approx(-180.0)


def test_the_modes_have_a_legend_axis_labels_and_a_visible_displacement():
    pytest.importorskip("matplotlib")
    from linkcli.pictures import vibration as pictures
    mech = linkcli.load(path("symmetric_chain_mode.yaml")).model
    fig = pictures.modes_figure(mech)
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert labels == ["equilibrium", "+ mode shape", "- mode shape"]
    assert "displacements scaled" in fig.legends[0].get_title().get_text()
    rest = {"P1": 100.0, "P2": 200.0, "P3": 300.0}
    dots = []
    for k, ax in enumerate(fig.axes):
        assert ax.get_xlabel() == "x [mm]" and ax.get_ylabel() == "y [mm]"
        assert ax.get_title().startswith(f"mode {k + 1}: omega = ")
        # the '+' pose's dots: the farthest moved by a fifth of the drawing's extent (the
        # walls 400 mm apart), so 80 mm, not a hairline
        dots.append({line.get_gid(): float(line.get_xdata()[0]) - rest[line.get_gid()]
                     for line in ax.get_lines() if line.get_color() == pictures.PLUS
                     and line.get_marker() == "o"})
        assert max(map(abs, dots[k].values())) == pytest.approx(
            pictures.MODE_SCALE * 400.0, rel=1e-9)
    # mode 2 is (1, 0, -1) in (x1, x2, x3): the middle mass has no dot, the others opposed
    assert sorted(dots[1]) == ["P1", "P3"]
    assert dots[1]["P1"] == pytest.approx(-dots[1]["P3"], rel=1e-9)
    assert "x2 does not move" in fig.axes[1].get_title()
