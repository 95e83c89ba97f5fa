"""Vibrations: the Lagrangian terms against energies and differences, closed forms,
the forced and free responses, the nonlinear motion, and the refusals."""
from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))

import linkcli  # noqa: E402
from linkcli.cli import main  # noqa: E402
from linkcli.forces import motion, vibration as vib  # noqa: E402
from linkcli.forces.equilibrium import equilibrium  # noqa: E402
from linkcli.forces.lagrange import Lagrangian  # noqa: E402
from linkcli.kinematics.solvers import solver_for  # noqa: E402
from vibration_cases import CASES, SDOF, SUPPORT  # noqa: E402

DOUBLE = """
title: double pendulum with springs (18 Sep 2001, Es. 2)
units: {length: m, angle: deg}
params: {L: 0.5, m: 2, kk: 100}
frame: {O: [0, 0], SA1: [-L, -L], SA2: [L, -L], SB1: [-L, -2*L], SB2: [L, -2*L]}
points: {A: [0, -L], B: [0, -2*L]}
links: {OA: {points: [O, A], length: L}, AB: {points: [A, B], length: L}}
coordinates: {phi: {angle: [O, A]}, theta: {angle: [A, B]}}
springs:
  kA1: {between: [SA1, A], k: kk, along: x}
  kA2: {between: [A, SA2], k: kk, along: x}
  kB1: {between: [SB1, B], k: kk, along: x}
  kB2: {between: [B, SB2], k: kk, along: x}
dynamics: {gravity: 9.81, masses: {A: m, B: m}}
quantities: {w1: {natural_frequency: 1}}
report: {vibration: [w1]}
"""

# a leg pivoted at A, held by an actuator BC that is a spring and a damper
# (4 Jul 2001, Quesito 3): a rocker and an actuator, body masses off the axis
LEG = """
title: landing-gear leg on a spring-damper actuator
units: {length: m, angle: deg}
frame: {A: [0, 0], B: [0.3, 0.5]}
points: {C: [0.45, -0.2], W: [0.2, -1.0]}
links: {leg: {points: [A, C, W], local: {A: [0, 0], C: [0.45, -0.2], W: [0.2, -1.0]}}}
actuators: {BC: {points: [B, C]}}
coordinates: {theta: {angle: [A, W]}}
springs: {k: {between: [B, C], k: 40000, preload: static}}
dampers: {r: {between: [B, C], c: 300}}
dynamics:
  gravity: 9.81
  bodies: {leg: {mass: 25, inertia: 1.4, center: W}, BC.cylinder: {mass: 2, inertia: 0.02, center: [0.1, 0]},
           BC.rod: {mass: 1, inertia: 0.01, center: [0.1, 0]}}
quantities: {w1: {natural_frequency: 1}}
report: {vibration: [w1]}
"""

ALL = {**{k: v[0] for k, v in CASES.items()}, "double": DOUBLE,
       "sdof": SDOF.format(m=2, k=800, c=12, Omega=15, F=10),
       "support": SUPPORT.format(m=2, k=800, c=12, Omega=15, Y=0.01)}


def lagrangian(text):
    mech = linkcli.loads(text).model
    return Lagrangian(mech, solver_for(mech))


@pytest.fixture(scope="module", params=sorted(ALL) + ["leg"])
def lag(request):
    text = LEG if request.param == "leg" else ALL[request.param]
    return lagrangian(text)


def _near(lag, eq_q, rng, scale=0.05):
    """A configuration near the equilibrium (not itself one)."""
    return eq_q + scale * rng.standard_normal(lag.n)


# --- closed forms ---------------------------------------------------------------------------
@pytest.mark.parametrize("name", sorted(CASES))
def test_natural_frequencies_match_textbook_closed_forms(name):
    text, expected = CASES[name]
    values = linkcli.loads(text).solve().values
    got = [float(values[f"w{i + 1}"]) for i in range(len(expected))]
    assert np.allclose(got, expected, rtol=1e-9, atol=0), (got, expected)


def test_coupled_pendulum_modes_are_in_phase_and_opposed():
    values = linkcli.loads(CASES["coupled"][0]).solve().values
    assert float(values["u1"]) == pytest.approx(1.0, abs=1e-9)
    assert float(values["u2"]) == pytest.approx(-1.0, abs=1e-9)


def test_double_pendulum_matches_the_closed_form():
    """omega^2 = 2k/m + (2 -+ sqrt 2) g / L, shapes [1, +-sqrt 2] (18 Sep 2001, Es. 2)."""
    lin = vib.linearise(lagrangian(DOUBLE))
    modes = vib.modes(lin)
    expected = np.sqrt(2 * 100 / 2 + (2 - np.array([1, -1]) * math.sqrt(2)) * 9.81 / 0.5)
    assert np.allclose(modes.omega, expected, rtol=1e-9)
    assert np.allclose(modes.shapes[1], [math.sqrt(2), -math.sqrt(2)], rtol=1e-9)
    assert np.allclose(lin.M, [[1.0, 0.5], [0.5, 0.5]], rtol=1e-12)
    assert np.allclose(lin.K, [[119.62, 50.0], [50.0, 59.81]], rtol=1e-12)


# --- the terms against energies and finite differences ----------------------------------
def test_mass_matrix_gives_the_kinetic_energy(lag):
    """T = 1/2 q'^T M q' against T summed body by body from the solver's velocities."""
    rng = np.random.default_rng(1)
    eq = equilibrium(lag)
    for q in (eq.q, _near(lag, eq.q, rng)):
        terms = lag.terms(q)
        for _ in range(3):
            qd = rng.standard_normal(lag.n)
            kin = lag.solver.positions(q[0] if lag.n == 1 else tuple(q))
            lag.solver.velocities(kin, qd[0] if lag.n == 1 else tuple(qd))
            T = float(motion.kinetic_energy(lag.mech, lag.mech.dynamics, kin.pos, kin.vel))
            assert 0.5 * qd @ terms.M @ qd == pytest.approx(T, rel=1e-12)


def test_stiffness_is_the_hessian_of_the_potential(lag):
    """K against central differences of V (positions only), to 1e-7 relative."""
    rng = np.random.default_rng(2)
    eq = equilibrium(lag)
    for q in (eq.q, _near(lag, eq.q, rng)):
        K = lag.terms(q).K
        h = 1e-4
        fd = np.empty((lag.n, lag.n))
        E = np.eye(lag.n) * h
        for i in range(lag.n):
            for j in range(lag.n):
                fd[i, j] = (lag.potential(q + E[i] + E[j]) - lag.potential(q + E[i] - E[j])
                            - lag.potential(q - E[i] + E[j]) + lag.potential(q - E[i] - E[j])) \
                    / (4 * h * h)
        scale = np.max(np.abs(K))
        assert np.max(np.abs(K - fd)) <= 1e-7 * scale, (K, fd)


def test_generalised_forces_are_minus_the_gradient(lag):
    rng = np.random.default_rng(3)
    q = _near(lag, equilibrium(lag).q, rng)
    Q = lag.terms(q).Q
    h = 1e-6
    fd = np.array([-(lag.potential(q + e) - lag.potential(q - e)) / (2 * h)
                   for e in np.eye(lag.n) * h])
    scale = np.max(np.abs(lag.terms(q).K)) * 1e-3 + np.max(np.abs(Q))
    assert np.max(np.abs(Q - fd)) <= 1e-7 * scale


def test_second_derivatives_of_points_match_differences(lag):
    """P_ij from the rate solver against differences of the Jacobian columns."""
    rng = np.random.default_rng(4)
    q = _near(lag, equilibrium(lag).q, rng)
    jt = lag.jet(q)
    h = 1e-6
    size = lag.size
    for j in range(lag.n):
        e = np.eye(lag.n)[j] * h
        plus, minus = lag.jet(q + e, second=False), lag.jet(q - e, second=False)
        for i in range(lag.n):
            for p in jt.pos:
                fd = (plus.d1(p, i) - minus.d1(p, i)) / (2 * h)
                assert abs(jt.d2(p, i, j) - fd) <= 1e-6 * size, (p, i, j)


def test_convective_terms_match_the_solvers_accelerations(lag):
    """c_i from the Hessians against sum m Re(conj(G_i) a_G) with a_G from the solver at q'' = 0."""
    rng = np.random.default_rng(5)
    q = _near(lag, equilibrium(lag).q, rng)
    qd = rng.standard_normal(lag.n)
    terms = lag.terms(q)
    c = lag.convective(terms, qd)
    solver = lag.solver
    kin = solver.positions(q[0] if lag.n == 1 else tuple(q))
    solver.velocities(kin, qd[0] if lag.n == 1 else tuple(qd))
    solver.accelerations(kin, 0.0 if lag.n == 1 else tuple(np.zeros(lag.n)))
    dyn = lag.mech.dynamics
    moving = motion.motions(lag.mech, dyn, kin.pos, kin.vel, kin.acc)
    by_name = {m.name: m for m in moving}
    expected = np.zeros(lag.n)
    for m in terms.masses:
        actual = by_name[m.name]
        for i in range(lag.n):
            expected[i] += m.mass * np.real(np.conj(m.g[1][i]) * actual.a)
            if m.theta is not None:
                expected[i] += m.inertia * m.theta.grad[i] * float(actual.alpha)
    scale = np.max(np.abs(terms.M)) * np.max(np.abs(qd)) ** 2 + 1e-300
    assert np.max(np.abs(c - expected)) <= 1e-10 * scale


def test_equilibrium_residual_is_below_the_load_scale(lag):
    eq = equilibrium(lag)
    assert eq.relative < 1e-10


# --- responses --------------------------------------------------------------------------
@pytest.mark.parametrize("m, k, c, Omega, F", [(2, 800, 12, 15, 10), (5, 2e4, 100, 80, 3),
                                               (1, 100, 1, 10, 1)])
def test_forced_sdof_matches_the_closed_form(m, k, c, Omega, F):
    values = linkcli.loads(SDOF.format(m=m, k=k, c=c, Omega=Omega, F=F)).solve().values
    wn = math.sqrt(k / m)
    zeta = c / (2 * math.sqrt(k * m))
    X = F / math.hypot(k - m * Omega ** 2, c * Omega)
    assert float(values["w1"]) == pytest.approx(wn, rel=1e-12)
    assert float(values["z1"]) == pytest.approx(zeta, rel=1e-12)
    assert float(values["wd"]) == pytest.approx(wn * math.sqrt(1 - zeta ** 2), rel=1e-12)
    assert float(values["X"]) == pytest.approx(X, rel=1e-12)
    phase = -math.degrees(math.atan2(c * Omega, k - m * Omega ** 2))
    assert float(values["ph"]) == pytest.approx(phase, rel=1e-12)
    assert float(values["Ft"]) == pytest.approx(X * math.hypot(k, c * Omega), rel=1e-12)
    assert float(values["ye"]) == pytest.approx(0.5 - m * 9.81 / k, rel=1e-12)
    assert float(values["N"]) == pytest.approx(-m * 9.81, rel=1e-12)   # compressed


@pytest.mark.parametrize("ratio", [0.3, 1.0, 1.7, 3.0])
def test_base_excitation_transmissibility(ratio):
    m, k, c, Y = 2.0, 800.0, 12.0, 0.01
    wn = math.sqrt(k / m)
    values = linkcli.loads(SUPPORT.format(m=m, k=k, c=c, Omega=ratio * wn, Y=Y)).solve().values
    zeta = c / (2 * math.sqrt(k * m))
    T = math.hypot(1, 2 * zeta * ratio) / math.hypot(1 - ratio ** 2, 2 * zeta * ratio)
    assert float(values["T"]) == pytest.approx(T, rel=1e-12)
    assert float(values["X"]) == pytest.approx(T * Y, rel=1e-12)


def test_free_response_of_a_damped_sdof():
    """x(t) = x0 e^{-zeta wn t} (cos wd t + zeta wn / wd sin wd t)."""
    lin = vib.linearise(lagrangian(SDOF.format(m=2, k=800, c=12, Omega=15, F=10)))
    wn, zeta = 20.0, 0.15
    wd = wn * math.sqrt(1 - zeta ** 2)
    t = np.linspace(0, 0.8, 9)
    x = vib.free_response(lin, [0.01], [0.0], t)[:, 0]
    exact = 0.01 * np.exp(-zeta * wn * t) * (np.cos(wd * t) + zeta * wn / wd * np.sin(wd * t))
    assert np.allclose(x, exact, rtol=1e-10, atol=1e-14)


def test_frequency_response_is_vectorised():
    lin = vib.linearise(lagrangian(SDOF.format(m=2, k=800, c=12, Omega=15, F=10)))
    omega = np.linspace(1, 60, 1000)
    X = vib.response(lin, omega)[:, 0]
    exact = 10 / np.hypot(800 - 2 * omega ** 2, 12 * omega)
    assert np.allclose(np.abs(X), exact, rtol=1e-12)


def test_undamped_resonance_is_refused():
    text = SDOF.format(m=2, k=800, c=12, Omega=20, F=10).replace(
        "dampers: {r: {between: [B, P], c: c}}", "").replace("Ft: {force_amplitude: [k, r]}",
                                                            "Ft: {force_amplitude: [k]}")
    with pytest.raises(linkcli.LinkcliError, match="resonance"):
        linkcli.loads(text).solve(names=["X"])


# --- the nonlinear motion ---------------------------------------------------------------
def _period(t, x):
    """Mean period from the upward zero crossings (linear interpolation)."""
    s = np.sign(x)
    idx = np.where((s[:-1] < 0) & (s[1:] >= 0))[0]
    crossings = t[idx] - x[idx] * (t[idx + 1] - t[idx]) / (x[idx + 1] - x[idx])
    return (crossings[-1] - crossings[0]) / (len(crossings) - 1)


@pytest.mark.parametrize("name", ["pendulum", "disc"])
def test_small_nonlinear_oscillation_has_the_linear_frequency(name):
    lin = vib.linearise(lagrangian(CASES[name][0]))
    omega = vib.modes(lin).omega[0]
    period = 2 * math.pi / omega
    t = np.linspace(0, 6 * period, 6000)
    amplitude = 1e-3 if name == "pendulum" else 1e-4
    x = vib.simulate(lin, [amplitude], [0.0], t)[:, 0]
    assert _period(t, -x) == pytest.approx(period, rel=1e-4)


def test_nonlinear_and_linear_free_responses_agree_at_small_amplitude():
    lin = vib.linearise(lagrangian(DOUBLE))
    t = np.linspace(0, 2, 201)
    x0 = [1e-4, -2e-4]
    nonlinear = vib.simulate(lin, x0, [0, 0], t)
    linear = vib.free_response(lin, np.array(x0), np.zeros(2), t)
    assert np.max(np.abs(nonlinear - linear)) < 1e-3 * 2e-4


# --- refusals ---------------------------------------------------------------------------
def _run(tmp_path, text, *args):
    path = tmp_path / "v.yaml"
    path.write_text(text)
    return path, main(["solve", str(path), *args])


def test_unstable_equilibrium_is_named_with_its_eigenvalue(tmp_path, capsys):
    """Gravity pointing up and the pendulum drawn hanging: the figure is an equilibrium, a
    maximum of V, and it is kept and named as unstable (not left for the upright one)."""
    inverted = CASES["pendulum"][0].replace("gravity: 9.81", "gravity: {g: 9.81, angle: 90}") \
        .replace("points: {A: [0.3, -1.16]}", "points: {A: [0, -1.2]}")
    path, code = _run(tmp_path, inverted)
    err = capsys.readouterr().err
    assert code == 3
    assert "unstable (a maximum of the potential energy)" in err
    assert "negative eigenvalue" in err and "Traceback" not in err


def test_a_pendulum_let_go_below_an_upward_gravity_settles_upright(tmp_path):
    """Drawn off the hanging position with gravity pointing up, the pendulum is not in
    equilibrium: let go, it swings up to the stable upright position, theta = 90 deg, with
    omega^2 = m g (L/2) / (m L^2 / 3) as hanging under the usual gravity."""
    inverted = CASES["pendulum"][0].replace("gravity: 9.81", "gravity: {g: 9.81, angle: 90}")
    values = linkcli.loads(inverted).solve().values
    assert float(values["th"]) == pytest.approx(90.0, abs=1e-9)
    assert float(values["w1"]) == pytest.approx(CASES["pendulum"][1][0], rel=1e-9)


def test_coordinate_without_mass_is_named(tmp_path, capsys):
    text = CASES["coupled"][0].replace("masses: {A1: m, A2: m}", "masses: {A1: m}")
    path, code = _run(tmp_path, text)
    err = capsys.readouterr().err
    assert code == 3
    assert "coordinate t2 carries no mass" in err


def test_no_equilibrium_is_reported_with_the_residual(tmp_path, capsys):
    text = CASES["disc"][0].replace("springs: {k: {between: [W, C], k: kk, free_length: 1.05}}",
                                    "springs: {k: {between: [W, C], k: kk, along: y}}") \
        .replace("dynamics:", "loads: {push: {type: force, at: C, x: 10}}\ndynamics:")
    path, code = _run(tmp_path, text)
    err = capsys.readouterr().err
    assert code == 3      # nothing holds x against the push: V falls without bound along x
    assert "no static equilibrium within" in err and "keeps falling along x" in err


def test_figure_that_is_not_an_equilibrium_is_refused(tmp_path, capsys):
    text = CASES["pendulum"][0] + "equilibrium: figure\n"
    path, code = _run(tmp_path, text)
    err = capsys.readouterr().err
    assert code == 3
    assert "the figure is not a static equilibrium" in err


@pytest.mark.parametrize("old, new, key, message", [
    ("k: kk, free_length: 1.05", "k: -5, free_length: 1.05", "springs.k.k",
     "stiffness must be positive"),
    ("k: kk, free_length: 1.05", "k: 0, free_length: 1.05", "springs.k.k",
     "stiffness must be positive"),
    ("between: [W, C]", "between: [W, Z]", "springs.k.between[1]", "undefined point 'Z'"),
    ("k: kk, free_length: 1.05", "k: kk, free_length: 1, preload: 3", "springs.k",
     "give one of free_length, preload"),
    ("coordinates: {x: {x: C}}", "coordinates: {x: {x: C}}\ndriver: {x: C, value: 0}", "driver",
     "not both 'coordinates' and 'driver'"),
])
def test_bad_elements_are_located(tmp_path, capsys, old, new, key, message):
    text = CASES["disc"][0]
    assert old in text
    path, code = _run(tmp_path, text.replace(old, new, 1))
    err = capsys.readouterr().err
    assert code == 2
    assert f"key '{key}'" in err and message in err


def test_damper_with_non_positive_coefficient(tmp_path, capsys):
    text = SDOF.format(m=2, k=800, c=-1, Omega=15, F=10)
    path, code = _run(tmp_path, text)
    err = capsys.readouterr().err
    assert code == 2 and "key 'dampers.r.c'" in err and "must be positive" in err


def test_gruebler_count_against_declared_coordinates(tmp_path, capsys):
    text = CASES["coupled"][0].replace("coordinates: {t1: {angle: [O1, A1]}, t2: {angle: [O2, A2]}}",
                                       "coordinates: {t1: {angle: [O1, A1]}}")
    text = text[:text.index("quantities:")] + "quantities: {w1: {natural_frequency: 1}}\n" \
        "report: {vibration: [w1]}\n"
    path, code = _run(tmp_path, text)
    err = capsys.readouterr().err
    assert code == 3
    assert "the mechanism has 2 degrees of freedom, not 1" in err and "n = 3(m - 1)" in err


def test_springs_without_coordinates_say_how(tmp_path, capsys):
    text = """
title: t
frame: {A: [0, 0], D: [100, 0]}
points: {B: [0, 50]}
links: {AB: {points: [A, B], length: 50}}
driver: {angle: [A, B], value: 90}
springs: {k: {between: [B, D], k: 100}}
report: {position: [q]}
"""
    path, code = _run(tmp_path, text)
    err = capsys.readouterr().err
    assert code == 2 and "key 'springs'" in err and "coordinates" in err


# --- pictures ---------------------------------------------------------------------------
@pytest.mark.parametrize("args", [["--modes"], ["--frf", "1:60:300"], ["--free", "0:1:100"],
                                  ["--frf", "1:60:300", "--y", "y"]])
def test_vibration_pictures_are_written(tmp_path, args):
    pytest.importorskip("matplotlib")
    path = tmp_path / "sdof.yaml"
    path.write_text(SDOF.format(m=2, k=800, c=12, Omega=15, F=10) + "initial: {y: 0.01}\n")
    out = tmp_path / "out.png"
    assert main(["plot", str(path), *args, "-o", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not [p for p in os.listdir(tmp_path) if p.startswith(".linkcli-")]


@pytest.mark.parametrize("args, message", [
    (["--modes", "--frf", "1:2:3"], "give one of --sweep, --frf, --modes, --free"),
    (["--free", "0:1:10"], "a time response starts from 'initial:'"),
    (["--frf", "1:60:10", "--y", "nope"], "'nope' is not a free coordinate"),
])
def test_vibration_picture_requests_are_checked(tmp_path, capsys, args, message):
    path = tmp_path / "sdof.yaml"
    path.write_text(SDOF.format(m=2, k=800, c=12, Omega=15, F=10))
    assert main(["plot", str(path), *args, "-o", str(tmp_path / "o.png")]) == 2
    assert message in capsys.readouterr().err


def test_frf_of_a_file_without_coordinates_is_refused(tmp_path, capsys):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    code = main(["plot", os.path.join(root, "mechanisms", "padova-2020-07.yaml"), "--frf", "1:2:3",
                 "-o", str(tmp_path / "o.png")])
    assert code == 2 and "vibration problems" in capsys.readouterr().err


def test_forced_nonlinear_motion_settles_on_the_linear_amplitude():
    """A linear system (spring along its guide): after the transient, the integrated motion
    oscillates with the steady-state amplitude of the frequency response."""
    lin = vib.linearise(lagrangian(SDOF.format(m=2, k=800, c=40, Omega=15, F=10)))
    t = np.linspace(0, 6, 6001)
    x = vib.simulate(lin, [0.0], [0.0], t, forced=True)[:, 0]
    late = x[t > 4.5]
    X = abs(vib.response(lin, 15.0)[0])
    assert 0.5 * (late.max() - late.min()) == pytest.approx(X, rel=1e-4)


def test_explain_writes_the_energies_and_the_linearised_system(capsys):
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "d.yaml")
        open(path, "w").write(DOUBLE)
        assert main(["explain", path]) == 0
    out = capsys.readouterr().out
    for text in ("coordinate phi = angle of O->A", "T = 1/2 2 |v_A|^2 + 1/2 2 |v_B|^2",
                 "Lagrange's equations", "phi = 270 deg (free)", "M (kg m^2) =",
                 "mode 1: omega = 10.559 rad/s"):
        assert text in out, text


def test_resonance_reached_in_floating_point_is_refused():
    """Omega = sqrt(k/m) rounded: K - Omega^2 M cancels to rounding, never a huge amplitude."""
    text = SDOF.format(m=3, k=1000, c=12, Omega=math.sqrt(1000 / 3), F=10).replace(
        "dampers: {r: {between: [B, P], c: c}}", "").replace("Ft: {force_amplitude: [k, r]}",
                                                             "Ft: {force_amplitude: [k]}")
    with pytest.raises(linkcli.LinkcliError, match="at resonance at Omega = 18.2574"):
        linkcli.loads(text).solve(names=["X"])
    # slightly off resonance it is answered, with the closed-form amplitude
    off = text.replace(f"frequency: {math.sqrt(1000 / 3)}", "frequency: 18.2")
    X = float(linkcli.loads(off).solve(names=["X"]).values["X"])
    assert X == pytest.approx(10 / abs(1000 - 3 * 18.2 ** 2), rel=1e-12)
