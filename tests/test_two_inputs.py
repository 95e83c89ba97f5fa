"""Mechanisms of two degrees of freedom with both inputs driven (``drivers:``).

Positions against closure and against closed forms written here (the 2R arm's forward
kinematics and Jacobian, a five-bar's circle intersection), rates against finite
differences of the positions along the drivers' motion q_j(t) = q_j + q_j' t + q_j'' t^2 / 2,
the refusals (one driver too many, two drivers on one coordinate) with their exit status,
key and line.
"""
import os

import numpy as np
import pytest

import linkcli
from linkcli.errors import InputError
from linkcli.kinematics.closed_form import residuals, unit_rates
from linkcli.kinematics.solvers import solver_for

from cli_helpers import run

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "data", "two_inputs")


def model(name, replacements=()):
    with open(os.path.join(DATA, name), encoding="utf-8") as handle:
        text = handle.read()
    for old, new in replacements:
        assert old in text
        text = text.replace(old, new)
    return linkcli.loads(text, name=name).model


def motion(mech, t):
    """Every driver's value, rate and acceleration at time ``t`` (SI) of the constant
    acceleration motion from the file's values."""
    cs = mech.coordinates
    return (tuple(c.value + c.rate * t + 0.5 * c.accel * t * t for c in cs),
            tuple(c.rate + c.accel * t for c in cs), tuple(c.accel for c in cs))


def solved(mech, t=0.0):
    solver = solver_for(mech)
    q, qd, qdd = motion(mech, t)
    kin = solver.positions(q)
    solver.velocities(kin, qd)
    solver.accelerations(kin, qdd)
    return solver, kin


def test_grubler_gives_two_and_the_decomposition_drives_both():
    mech = model("five-bar.yaml")
    solver = solver_for(mech)
    assert solver.topology.grubler.dof == 2
    kinds = [g.kind for g in solver.groups]
    assert kinds.count("driver-angle") == 2 and "RRR" in kinds


@pytest.mark.parametrize("name", ["arm-2r.yaml", "five-bar.yaml"])
def test_rates_match_finite_differences_of_positions(name):
    """v = dP/dt and a = dv/dt by central differences along the drivers' motion."""
    mech = model(name)
    _, kin = solved(mech)
    h = 1e-5
    plus, minus = solved(mech, h)[1], solved(mech, -h)[1]
    size = max(abs(z) for z in mech.figure_points)
    for p in mech.moving:
        v = (plus.pos[p] - minus.pos[p]) / (2 * h)
        a = (plus.vel[p] - minus.vel[p]) / (2 * h)
        assert abs(kin.vel[p] - v) <= 1e-7 * size * (1 + abs(v) / size)
        assert abs(kin.acc[p] - a) <= 1e-5 * size * (1 + abs(a) / size)


def test_arm_end_point_and_jacobian_against_the_closed_form():
    """B = L1 e^{i t1} + L2 e^{i t2} (absolute angles): v_B = J q', its columns
    i L1 e^{i t1} and i L2 e^{i t2}; a_B = J q'' - L1 t1'^2 e^{i t1} - L2 t2'^2 e^{i t2}."""
    mech = model("arm-2r.yaml")
    solver, kin = solved(mech)
    t1, t2 = (c.value for c in mech.coordinates)
    w1, w2 = (c.rate for c in mech.coordinates)
    e1, e2 = (c.accel for c in mech.coordinates)
    l1 = l2 = 0.4
    assert kin.pos["B"] == pytest.approx(l1 * np.exp(1j * t1) + l2 * np.exp(1j * t2), abs=1e-12)
    jacobian = [unit_rates(solver, kin, j).vel["B"] for j in range(2)]
    assert jacobian == pytest.approx([1j * l1 * np.exp(1j * t1), 1j * l2 * np.exp(1j * t2)],
                                     abs=1e-12)
    assert kin.vel["B"] == pytest.approx(jacobian[0] * w1 + jacobian[1] * w2, abs=1e-12)
    answers = linkcli.load(os.path.join(DATA, "arm-2r.yaml")).solve(
        names=["J11", "J12", "J21", "J22"]).values          # the Jacobian as answers, m/deg
    per_deg = np.pi / 180
    assert [answers[n] for n in ("J11", "J12", "J21", "J22")] == pytest.approx(
        [jacobian[0].real * per_deg, jacobian[1].real * per_deg, jacobian[0].imag * per_deg,
         jacobian[1].imag * per_deg], abs=1e-12)
    a = (1j * e1 - w1 ** 2) * l1 * np.exp(1j * t1) + (1j * e2 - w2 ** 2) * l2 * np.exp(1j * t2)
    assert kin.acc["B"] == pytest.approx(a, abs=1e-12)


def five_bar_b(p1, p2):
    """The five-bar's coupler point B by hand: A = O + 0.1 e^{i p1}, C = D + 0.1 e^{i p2},
    B on |B - A| = 0.17 and |B - C| = 0.14, on the left of A -> C (the figure's branch)."""
    a = 0.1 * np.exp(1j * p1)
    c = 0.2 + 0.1 * np.exp(1j * p2)
    d = np.abs(c - a)
    along = (0.17 ** 2 - 0.14 ** 2 + d ** 2) / (2 * d)
    height = np.sqrt(0.17 ** 2 - along ** 2)
    u = (c - a) / d
    return a + u * (along + 1j * height)


def test_five_bar_against_a_closed_form_over_both_drivers():
    mech = model("five-bar.yaml")
    solver = solver_for(mech)
    p1, p2 = np.meshgrid(np.radians(np.linspace(75, 105, 7)), np.radians(np.linspace(45, 75, 7)))
    kin = solver.positions((p1, p2))
    solver.check(kin, velocities=False)
    assert kin.pos["B"] == pytest.approx(five_bar_b(p1, p2), abs=1e-12)
    for value in residuals(solver, kin).values():
        assert np.max(np.abs(value)) <= 1e-12


def test_solve_reports_driver_rates_and_the_first_driver_as_q():
    code, out, err = run(["solve", os.path.join(DATA, "arm-2r.yaml"), "--format", "csv",
                          "--decimals", "6"])
    assert code == 0, err
    rows = dict(line.split(",")[:2] for line in out.splitlines()[1:])
    assert float(rows["theta1dot"]) == 1.5 and float(rows["theta2dot"]) == -0.5


def test_explain_says_two_degrees_of_freedom_each_driven():
    code, out, err = run(["explain", os.path.join(DATA, "five-bar.yaml")])
    assert code == 0, err
    assert "= 2" in out and "phi1 = angle of O->A" in out and "phi2 = angle of D->C" in out


# --- refusals -------------------------------------------------------------------------------
FOURBAR = """title: four-bar
frame: {O: [0, 0], D: [4, 0]}
points: {A: [0, 1], B: [3, 2]}
links: {crank: {points: [O, A], length: 1}, coupler: {points: [A, B], length: 3.1623},
        rocker: {points: [D, B], length: 2.2361}}
drivers:
  phi: {angle: [O, A], value: 90, rate: 1}
  psi: {angle: [D, B], value: 116.57, rate: 1}
report: {position: [xB]}
"""


def test_two_drivers_on_one_degree_of_freedom_are_named_with_the_count(tmp_path):
    path = tmp_path / "fourbar.yaml"
    path.write_text(FOURBAR, encoding="utf-8")
    code, _, err = run(["solve", str(path)])
    assert code == 3
    assert "the mechanism has 1 degree of freedom, not 2 (the drivers phi: angle of O->A, " \
        "psi: angle of D->B)" in err
    assert "n = 3(m - 1) - 2R - 2P = 3(4 - 1) - 2*4 - 2*0 = 1" in err
    assert "drive 1 of the coordinates" in err


def test_a_coordinate_driven_twice_is_refused_at_its_line(tmp_path):
    path = tmp_path / "twice.yaml"
    path.write_text(FOURBAR.replace("psi: {angle: [D, B]", "psi: {angle: [A, O]"),
                    encoding="utf-8")
    code, _, err = run(["solve", str(path)])
    assert code == 2
    assert "twice.yaml:8, key 'drivers.psi': driver 'psi' drives the angle of A->O, which " \
        "driver 'phi' already fixes" in err


def test_driver_and_drivers_together_are_refused(tmp_path):
    path = tmp_path / "both.yaml"
    path.write_text(FOURBAR + "driver: {angle: [O, A], value: 90}\n", encoding="utf-8")
    code, _, err = run(["solve", str(path)])
    # the second of the two in the file's order is refused, at its own line
    assert code == 2 and "both.yaml:10, key 'driver'" in err
    assert "not both 'drivers' and 'driver'" in err


# --- sweeps over one driver ---------------------------------------------------------------
def _csv(args):
    code, out, err = run(args + ["--format", "csv", "--decimals", "9"])
    assert code == 0, err
    lines = out.splitlines()
    names = [h.split(" [")[0] for h in lines[0].split(",")]
    return [dict(zip(names, map(float, line.split(",")))) for line in lines[1:]]


def test_a_tied_sweep_row_is_the_file_solved_with_the_tie_written_in(tmp_path):
    """phi2 = 150 - phi1: at phi1 = 80 deg the row is the file with phi2 = 70 deg, its rate
    -phi1' = -10 rad/s and its acceleration -phi1'' = 0 (the chain rule)."""
    path = os.path.join(DATA, "five-bar.yaml")
    names = "xB,yB,theta3dot,xBddot"
    row = _csv(["sweep", path, "--from", "80", "--to", "80", "--steps", "1", "--names", names,
                "--tie", "phi2=150-phi1"])[0]
    with open(path, encoding="utf-8") as handle:
        text = handle.read()
    old = "phi1: {angle: [O, A], value: 90, rate: 10, accel: 0}\n  phi2: {angle: [D, C], " \
        "value: 60, rate: -5, accel: 3}"
    assert old in text
    tied = tmp_path / "tied.yaml"
    tied.write_text(text.replace(old, "phi1: {angle: [O, A], value: 80, rate: 10, accel: 0}\n"
                                      "  phi2: {angle: [D, C], value: 70, rate: -10, accel: 0}"),
                    encoding="utf-8")
    code, out, err = run(["solve", str(tied), "--format", "csv", "--decimals", "9"])
    assert code == 0, err
    solved = {line.split(",")[0]: float(line.split(",")[1]) for line in out.splitlines()[1:]}
    for name in names.split(","):
        assert row[name] == pytest.approx(solved[name], rel=1e-9, abs=1e-9)


def test_the_python_sweep_takes_ties_as_the_command_does():
    path = os.path.join(DATA, "five-bar.yaml")
    rows = _csv(["sweep", path, "--from", "80", "--to", "90", "--steps", "1", "--names",
                 "yBdot", "--tie", "phi2=150-phi1"])
    swept = linkcli.load(path).sweep(np.array([80.0, 90.0]), names=["yBdot"],
                                     ties={"phi2": "150-phi1"})
    assert list(swept.values["yBdot"]) == pytest.approx([r["yBdot"] for r in rows], rel=1e-9)


def test_a_sweep_over_the_second_driver_passes_the_files_position():
    path = os.path.join(DATA, "five-bar.yaml")
    rows = _csv(["sweep", path, "--from", "50", "--to", "70", "--steps", "2", "--driver",
                 "phi2", "--names", "xB,yBdot"])
    code, out, err = run(["solve", path, "--format", "csv", "--decimals", "9"])
    solved = {line.split(",")[0]: float(line.split(",")[1]) for line in out.splitlines()[1:]}
    assert [r["q"] for r in rows] == [50, 60, 70]
    assert rows[1]["xB"] == pytest.approx(solved["xB"], rel=1e-9)
    assert rows[1]["yBdot"] == pytest.approx(solved["yBdot"], rel=1e-9)
    assert rows[0]["xB"] != pytest.approx(rows[2]["xB"])      # the second driver moves B


@pytest.mark.parametrize("option, words", [
    (["--tie", "phi1=2*phi1"], "a tie sets a driver other than the first"),
    (["--tie", "phi2=2*x"], "reads x; a tie is an expression of the swept driver phi1"),
    (["--tie", "phi2"], "expected NAME=EXPR"),
    (["--driver", "psi"], "--driver psi: not a driver of this file; its drivers: phi1, phi2"),
])
def test_sweep_options_of_several_drivers_refused_by_name(option, words):
    code, _, err = run(["sweep", os.path.join(DATA, "five-bar.yaml"), "--from", "80", "--to",
                        "90", "--steps", "1"] + option)
    assert code == 2 and words in err


def test_a_ties_rates_are_its_derivatives_along_the_motion():
    """q2 = f(q1) with f nonlinear: the tied driver's rate and acceleration against central
    differences of its value along q1(t) = q1 + q1' t + q1'' t^2 / 2 (SI)."""
    from linkcli.answers.quantities.drive import Drive
    mech = model("five-bar.yaml")
    drive = Drive(mech, {"phi2": "60 + 0.01*(phi1 - 90)**2 + 5*sin(phi1*deg)"})
    q0, w, a = np.radians(85.0), 7.0, -3.0

    def at(t):
        return drive(q0 + w * t + 0.5 * a * t * t, w + a * t, a)

    h = 1e-5
    (_, q2), (_, r2), (_, a2) = at(0.0)
    plus, minus = at(h), at(-h)
    assert r2 == pytest.approx((plus[0][1] - minus[0][1]) / (2 * h), rel=1e-7)
    assert a2 == pytest.approx((plus[1][1] - minus[1][1]) / (2 * h), rel=1e-6)
    expected = np.radians(60 + 0.01 * (85 - 90) ** 2 + 5 * np.sin(np.radians(85)))
    assert q2 == pytest.approx(expected, rel=1e-12)


# --- statics and inverse dynamics: one unknown load per driver ----------------------------
def _loads(text, name="arm.yaml"):
    """The model and the drivers' torques M1, M2 (SI) of the arm's file ``text``."""
    linkage = linkcli.loads(text, name=name)
    result = linkage.solve(names=["M1", "M2"])
    return linkage.model, [result.values["M1"], result.values["M2"]]


def _arm_text():
    with open(os.path.join(DATA, "arm-2r-loads.yaml"), encoding="utf-8") as handle:
        return handle.read()


def test_arm_statics_is_the_jacobians_transpose():
    """M_j = -F . J_j, J_j = i L e^{i theta_j} (B's velocity per unit rate of driver j)."""
    mech, (m1, m2) = _loads(_arm_text())
    t1, t2 = (c.value for c in mech.coordinates)
    force = 10 - 20j
    j1, j2 = 0.4j * np.exp(1j * t1), 0.4j * np.exp(1j * t2)
    assert [m1, m2] == pytest.approx([-(np.conj(force) * j1).real, -(np.conj(force) * j2).real],
                                     rel=1e-12)


def test_arm_inverse_dynamics_balances_the_power_of_any_motion():
    """With a point mass at B under gravity, the drivers' torques balance the d'Alembert
    forces: for the file's motion M1 w1 + M2 w2 = m (a_B - g) . v_B (an energy check on
    the actual velocities, both drivers moving)."""
    text = _arm_text().replace("report:", "dynamics:\n  gravity: 9.81\n  masses: {B: 3}\n"
                               "report:")
    text = text.replace("rate: 1.5}", "rate: 1.5, accel: 2}")
    mech, (m1, m2) = _loads(text)
    solver, kin = solved(mech)
    v, a = kin.vel["B"], kin.acc["B"]
    inertia = 3 * (a - (-9.81j))
    power = (np.conj(inertia) * v).real - (np.conj(10 - 20j) * v).real
    w1, w2 = (c.rate for c in mech.coordinates)
    assert m1 * w1 + m2 * w2 == pytest.approx(power, rel=1e-12)
    j2 = unit_rates(solver, kin, 1).vel["B"]            # and each driver's own balance
    assert m2 == pytest.approx((np.conj(inertia) * j2).real - (np.conj(10 - 20j) * j2).real,
                               rel=1e-12)


@pytest.mark.parametrize("old, new, words", [
    ("M2: {type: driver, on: theta2, value: unknown}", "M2: {type: driver, on: theta2, value: 1}",
     "one load per driver must be unknown (2: theta1, theta2), found 1 (M1)"),
    ("M2: {type: driver, on: theta2, value: unknown}", "M2: {type: driver, value: unknown}",
     "key 'loads.M2': missing key 'on'"),
    ("M2: {type: driver, on: theta2, value: unknown}", "M2: {type: driver, on: phi, value: unknown}",
     "key 'loads.M2.on': undefined driver 'phi'"),
])
def test_loads_of_several_drivers_refused_at_their_line(tmp_path, old, new, words):
    path = tmp_path / "arm.yaml"
    text = _arm_text()
    assert old in text
    path.write_text(text.replace(old, new), encoding="utf-8")
    code, _, err = run(["solve", str(path)])
    assert code == 2 and words in err


@pytest.mark.parametrize("masses", [False, True])
def test_joint_forces_agree_with_virtual_work_and_each_body_balances(masses):
    """Newton-Euler with a column per unknown load gives the drivers' torques of the virtual
    work (a free-body check of another method), and the fore arm's moments about A add up:
    M2 + (B - A) x (P - m (a_B - g)) = 0."""
    from linkcli.forces.joint_forces import solve
    from linkcli.kinematics.solvers import state
    text = _arm_text()
    if masses:
        text = text.replace("report:", "dynamics:\n  gravity: 9.81\n  masses: {B: 3}\n"
                            "report:").replace("rate: 1.5}", "rate: 1.5, accel: 2}")
    mech, (m1, m2) = _loads(text)
    kin, _ = state(mech)
    reactions = solve(mech, kin)
    assert [reactions.loads["M1"], reactions.loads["M2"]] == pytest.approx([m1, m2], rel=1e-9)
    a, b = kin.pos["A"], kin.pos["B"]
    inertia = 3 * (kin.acc["B"] + 9.81j) if masses else 0
    net = (10 - 20j) - inertia
    assert m2 + (np.conj(b - a) * net).imag == pytest.approx(0, abs=1e-9)


def test_unknown_loads_that_do_the_same_work_are_refused():
    """Two unknown forces at B along x: the drivers' motions cannot tell them apart."""
    text = _arm_text().replace("M1: {type: driver, on: theta1, value: unknown}",
                               "M1: {type: force, at: B, x: unknown}") \
        .replace("M2: {type: driver, on: theta2, value: unknown}",
                 "M2: {type: force, at: B, x: unknown}")
    with pytest.raises(linkcli.LinkcliError) as caught:
        linkcli.loads(text, name="same.yaml").solve(names=["M1"])
    assert "cannot be found together" in str(caught.value)


# --- the invariance and round-trip layers bite on files of several drivers -----------------
def test_units_invariance_catches_a_second_drivers_rate_read_without_its_unit(monkeypatch):
    """Planted: the rates of every driver but the first taken as SI numbers, whatever the
    file's units: the collar's file rewritten in inches disagrees with itself."""
    from linkcli.input.loads import LoadsSection
    from test_invariance_units import SYSTEMS, caught, check
    read = LoadsSection.driver_rate

    def raw(self, spec, path, key, base, order, units):
        if path[0] == "drivers" and path[1] != next(iter(self.doc.data["drivers"])):
            return float(self.number(spec.get(key, 0), path + (key,)))
        return read(self, spec, path, key, base, order, units)

    path = "mechanisms/hibbeler-gupta-16-19-collar-on-rotating-rod.yaml"
    found = caught(lambda: check(path, SYSTEMS["us"]),
                   lambda: monkeypatch.setattr(LoadsSection, "driver_rate", raw))
    assert any("cxdot" in line for line in found), found


def test_sweep_round_trip_catches_the_other_drivers_standing_still(monkeypatch):
    """Planted: a sweep's rows solved with the drivers it does not sweep at rest (their
    rates 0): the pinion's row at the file's value is no longer solve's."""
    from linkcli.runs.sweep.blocks import Sweeper
    from test_roundtrip_exports import sweep_mismatches
    name = "mechanisms/hibbeler-16-65-pinion-between-racks.yaml"
    assert not sweep_mismatches(name)

    def still(self, q_si):
        qs, rates, accels = self.drive(q_si, self.qd, self.qdd, held=False)
        kin = self.solver.positions(qs)
        kin.rates, kin.accels = rates, accels
        return kin

    monkeypatch.setattr(Sweeper, "_positions", still)
    assert any("xAdot" in line for line in sweep_mismatches(name))


def test_a_planetary_differential_against_willis():
    """Sun (r_s = 30 mm) and ring (r_r = 90 mm) driven, the planet (r_p = 30 mm) between
    them: the arm turns at (w_s r_s + w_r r_r) / (r_s + r_r) and the planet at
    (w_r r_r - w_s r_s) / (2 r_p), from the contact points' speeds (Willis's formula)."""
    linkage = linkcli.load(os.path.join(DATA, "planetary-differential.yaml"))
    sun, ring = (c.rate for c in linkage.model.coordinates)
    values = linkage.solve(names=["arm_angledot", "planet_angledot"]).values
    rpm = 2 * np.pi / 60
    assert values["arm_angledot"] * rpm == pytest.approx((sun * 30 + ring * 90) / 120, rel=1e-9)
    assert values["planet_angledot"] * rpm == pytest.approx((ring * 90 - sun * 30) / 60,
                                                            rel=1e-9)


# --- the Python API: each driver by name -------------------------------------------------
def _rewritten(replacements):
    with open(os.path.join(DATA, "five-bar.yaml"), encoding="utf-8") as handle:
        text = handle.read()
    for old, new in replacements:
        assert old in text
        text = text.replace(old, new)
    return linkcli.loads(text, name="five-bar.yaml").solve().values


def test_api_sets_each_driver_by_name_as_the_file_would():
    linkage = linkcli.load(os.path.join(DATA, "five-bar.yaml"))
    got = linkage.solve({"phi1": 30, "phi2": 100}, {"phi2": -2}, {"phi1": 1.5}).values
    want = _rewritten([("value: 90, rate: 10, accel: 0", "value: 30, rate: 10, accel: 1.5"),
                       ("value: 60, rate: -5", "value: 100, rate: -2")])
    assert set(got) == set(want)
    for name in want:
        assert got[name] == pytest.approx(want[name], rel=1e-12, abs=1e-9), name


@pytest.mark.parametrize("q, words", [((30.0, 100.0), "a list or tuple would read"),
                                      ({"phi3": 1}, "phi3: not a driver"),
                                      ({"phi2": [1, 2]}, "takes one value per call")])
def test_api_refuses_driver_values_it_would_misread(q, words):
    linkage = linkcli.load(os.path.join(DATA, "five-bar.yaml"))
    with pytest.raises(InputError, match=words):
        linkage.solve(q)
