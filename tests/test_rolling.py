"""Rolling contacts and cords: no slip at the contact in every position, rates against
differences of positions, Grübler's count with higher pairs, refusals."""
from __future__ import annotations

import math
import os

import numpy as np
import pytest

import linkcli
from linkcli.cli import main
from closure import WHEEL_ON_FLOOR

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

LINE = WHEEL_ON_FLOOR + """quantities: {th: {angle: [C, D]}}
report: {position: [th]}
"""

# a planet disc (centre C on a crank OC) rolling inside (or outside) a fixed ring of
# radius 300 about O; its marker D; the crank is the driver
CIRCLE = """
title: disc in a ring
units: {length: mm, angle: deg}
frame: {O: [0, 0]}
points: {C: [{d}, 0], D: [{d}, 50]}
links: {crank: {points: [O, C], length: {d}}, planet: {points: [C, D], length: 50}}
rolling: {ring: {disc: planet, radius: 50, on: {circle: O, radius: 300}}}
driver: {angle: [O, C], value: 20, rate: 60, accel: 10}
quantities: {th: {angle: [C, D]}}
report: {position: [th]}
"""

# a sun disc turned about O by the driver, a planet on an arm OC rolling outside it
GEARS = """
title: planet on a turning sun
units: {length: mm, angle: deg}
frame: {O: [0, 0], A: [-400, 0]}
points: {S: [0, 120], C: [200, 0], D: [200, 80]}
links:
  sun: {points: [O, S], length: 120}
  arm: {points: [O, C], length: 200}
  planet: {points: [C, D], length: 80}
rolling: {mesh: {disc: planet, radius: 80, on: {disc: sun, radius: 120}}}
coordinates: {a: {angle: [O, C]}, s: {angle: [O, S]}}
quantities: {th: {angle: [C, D]}}
report: {position: [th]}
"""

# a pulley (centre C fixed on the frame through a pin) turned by a cord to a hanging
# point P on a vertical slider: P's y is the driver
CORD = """
title: pulley and hanging block
units: {length: mm, angle: deg}
frame: {C: [0, 0]}
points: {D: [60, 0], P: [60, -400]}
links: {drum: {points: [C, D], length: 60}}
sliders: {block: {point: P, guide: {x: 60}}}
cords: {rope: {pulley: drum, radius: 60, to: P, along: -y, side: left}}
driver: {y: P, value: -400, rate: -30, accel: 5}
quantities: {th: {angle: [C, D]}}
report: {position: [th]}
"""


# a belt strand from a pulley on a vertical carriage (centre C2, y = h) down to a driven
# drum (centre C1 fixed, angle a): open belt, both tangent points on the strand's left
BELT = """
title: belt from a driven drum to a pulley on a carriage
units: {length: mm, angle: deg}
frame: {C1: [0, 0]}
points: {D1: [40, 0], C2: [-40, 500], D2: [-40, 580]}
links: {drum: {points: [C1, D1], length: 40}, pulley: {points: [C2, D2], length: 80}}
sliders: {carriage: {point: C2, guide: {x: -40}}}
cords:
  belt: {pulley: pulley, radius: 80, along: -y, side: left,
         to: {disc: drum, radius: 40, side: left}}
coordinates: {a: {angle: [C1, D1]}, h: {y: C2}}
quantities: {th: {angle: [C2, D2]}}
report: {position: [th]}
"""


def _marker_rates(text, q_values):
    """(positions, velocities, accelerations) of the marker D and the centre C."""
    mech = linkcli.loads(text)
    solver = mech.solver()
    kin = solver.positions(q_values)
    solver.check(kin, velocities=False)
    solver.velocities(kin, 1.0 if np.ndim(q_values) == 0 else np.ones_like(q_values))
    solver.accelerations(kin, 0.0 if np.ndim(q_values) == 0 else np.zeros_like(q_values))
    return mech, kin


@pytest.mark.parametrize("text, q", [
    (LINE, np.linspace(-0.3, 0.4, 15)),
    (CIRCLE.replace("{d}", "250"), np.radians(np.linspace(10, 150, 15))),   # inside
    (CIRCLE.replace("{d}", "350"), np.radians(np.linspace(10, 150, 15))),   # outside
    (CORD, np.linspace(-0.6, -0.2, 15)),
], ids=["line", "inside", "outside", "cord"])
def test_rates_match_differences_of_positions(text, q):
    mech, kin = _marker_rates(text, q)
    h = 1e-6
    plus = mech.solver().positions(q + h).pos
    minus = mech.solver().positions(q - h).pos
    for p in ("C", "D"):
        fd_v = (plus[p] - minus[p]) / (2 * h)
        fd_a = (plus[p] - 2 * kin.pos[p] + minus[p]) / h ** 2
        assert np.max(np.abs(kin.vel.get(p, 0) - fd_v)) < 1e-7, p
        assert np.max(np.abs(kin.acc.get(p, 0) - fd_a)) < 1e-3, p


def test_wheel_contact_point_does_not_slip():
    """The wheel's material point at the floor has zero velocity at every position."""
    mech, kin = _marker_rates(LINE, np.linspace(-0.3, 0.4, 15))
    c, d = kin.pos["C"], kin.pos["D"]
    omega = ((kin.vel["D"] - kin.vel["C"]) / (d - c)).imag
    contact = c - 0.1j                        # below the centre, on the floor
    v_contact = kin.vel["C"] + 1j * omega * (contact - c)
    assert np.max(np.abs(v_contact)) < 1e-12
    # and the angle turned is -x / r (clockwise when rolling to +x), from the figure's 90 deg
    turned = np.angle((d - c) * np.exp(-1j * (math.pi / 2 - np.real(c) / 0.1)))
    assert np.max(np.abs(turned)) < 1e-12


@pytest.mark.parametrize("d, inside", [(250, True), (350, False)])
def test_disc_in_a_ring_does_not_slip(d, inside):
    mech, kin = _marker_rates(CIRCLE.replace("{d}", str(d)), np.radians(np.linspace(10, 150, 9)))
    c = kin.pos["C"]
    omega = ((kin.vel["D"] - kin.vel["C"]) / (kin.pos["D"] - c)).imag
    u = c / np.abs(c)
    contact = c + (0.05 if inside else -0.05) * u      # on the ring, along O -> C
    v_contact = kin.vel["C"] + 1j * omega * (contact - c)
    assert np.max(np.abs(v_contact)) < 1e-12


def test_planet_on_a_turning_sun_does_not_slip():
    mech = linkcli.loads(GEARS)
    solver = mech.solver()
    a, s = np.radians(np.linspace(0, 90, 7)), np.radians(np.linspace(90, 200, 7))
    kin = solver.positions((a, s))
    solver.velocities(kin, (np.full(7, 2.0), np.full(7, -3.0)))
    pos, vel = kin.pos, kin.vel
    w_sun = ((vel["S"] - vel.get("O", 0)) / (pos["S"] - pos["O"])).imag
    w_planet = ((vel["D"] - vel["C"]) / (pos["D"] - pos["C"])).imag
    u = pos["C"] / np.abs(pos["C"])
    contact = 0.12 * u
    v_sun = 1j * w_sun * contact
    v_planet = vel["C"] + 1j * w_planet * (contact - pos["C"])
    assert np.max(np.abs(v_sun - v_planet)) < 1e-12


def test_cord_unwinds_the_pulley():
    """The cord leaves the drum from its +x side (left, looking down along it): the block
    descending by |dy| pulls that side down and turns the drum clockwise by |dy| / r."""
    mech, kin = _marker_rates(CORD, np.linspace(-0.6, -0.2, 9))
    c, d = kin.pos["C"], kin.pos["D"]
    theta = np.unwrap(np.angle(d - c))
    y = np.real(kin.pos["P"] * -1j)
    assert np.allclose(theta - theta[0], (y - y[0]) / 0.06, atol=1e-12)


def _belt_state(rates, accels):
    mech = linkcli.loads(BELT)
    solver = mech.solver()
    q = (np.radians(np.linspace(-60, 200, 9)), np.linspace(0.3, 0.7, 9))
    kin = solver.positions(q)
    solver.velocities(kin, tuple(np.full(9, r) for r in rates))
    solver.accelerations(kin, tuple(np.full(9, a) for a in accels))
    return solver, q, kin


def _spin(kin, centre, marker, rates=True):
    pos, vel, acc = kin.pos, kin.vel, kin.acc
    z = pos[marker] - pos[centre]
    w = ((vel.get(marker, 0) - vel.get(centre, 0)) / z).imag
    if not rates:
        return w
    return w, ((acc.get(marker, 0) - acc.get(centre, 0)) / z - w * w).imag


def test_belt_strand_runs_at_one_speed_on_both_discs():
    """The strand's material speed along u = -y at the drum's tangent point (C1 + 40) and at
    the pulley's (C2 + 80): v_C . u - side r omega on each, equal for any rates."""
    for rates in ((2.0, 0.0), (0.0, 0.5), (-3.0, 0.25)):
        _, _, kin = _belt_state(rates, (0.0, 0.0))
        w1, w2 = _spin(kin, "C1", "D1", False), _spin(kin, "C2", "D2", False)
        u = -1j
        s1 = (np.conj(u) * kin.vel.get("C1", 0)).real - 0.04 * w1
        s2 = (np.conj(u) * kin.vel["C2"]).real - 0.08 * w2
        assert np.max(np.abs(s1 - s2)) < 1e-12
        if rates[1] == 0:
            assert np.allclose(w2, w1 * 0.04 / 0.08, rtol=1e-12)   # the open belt's ratio


def test_belt_rates_match_differences_of_positions():
    rates, accels = (1.5, -0.2), (0.0, 0.0)
    solver, (a, h), kin = _belt_state(rates, accels)
    step = 1e-5
    plus = solver.positions((a + step * rates[0], h + step * rates[1])).pos
    minus = solver.positions((a - step * rates[0], h - step * rates[1])).pos
    for p in ("C2", "D2"):
        fd_v = (plus[p] - minus[p]) / (2 * step)
        fd_a = (plus[p] - 2 * kin.pos[p] + minus[p]) / step ** 2
        assert np.max(np.abs(kin.vel[p] - fd_v)) < 1e-8, p
        assert np.max(np.abs(kin.acc[p] - fd_a)) < 1e-4, p


@pytest.mark.parametrize("old, new, message", [
    ("side: left}}", "side: right}}", "the cord is not tangent in the figure: disc drum"),
    ("along: -y", "along: y", "the cord is not taut in the figure: disc drum"),
    ("to: {disc: drum,", "to: {disc: pulley,", "a belt cannot run from a pulley to itself"),
    ("to: {disc: drum,", "to: {disc: wheel,", "undefined link 'wheel'"),
    ("to: {disc: drum, radius: 40, side: left}", "to: [drum]",
     "expected a point name or a disc, got ['drum']"),
])
def test_bad_belts_are_located(tmp_path, capsys, old, new, message):
    assert old in BELT
    path = tmp_path / "belt.yaml"
    path.write_text(BELT.replace(old, new))
    assert main(["solve", str(path)]) == 2
    err = capsys.readouterr().err
    assert message in err and "key 'cords.belt.to" in err, err


def test_gruebler_counts_the_rolling_contact(capsys):
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "w.yaml")
        open(path, "w").write(LINE)
        assert main(["explain", path]) == 0
    out = capsys.readouterr().out
    assert "higher pairs H = 1: floor (wheel, rolling)" in out
    assert "n = 3(m - 1) - 2R - 2P - H = 3(3 - 1) - 2*1 - 2*1 - 1 = 1" in out
    assert "wheel turned by floor (rolling on a fixed line)" in out


@pytest.mark.parametrize("old, new, message", [
    ("to: P, along: -y", "to: P, along: y", "the cord is not taut in the figure"),
    ("P: [60, -400]", "P: [90, -400]", "the cord is not tangent in the figure"),
    ("pulley: drum", "pulley: drumm", "undefined link 'drumm'"),
    ("radius: 60, to", "radius: -60, to", "must be positive"),
])
def test_bad_cords_are_located(tmp_path, capsys, old, new, message):
    text = CORD
    if old == "P: [60, -400]":
        text = text.replace("sliders: {block: {point: P, guide: {x: 60}}}",
                            "sliders: {block: {point: P, guide: {x: 90}}}")
    assert old in text
    path = tmp_path / "c.yaml"
    path.write_text(text.replace(old, new))
    assert main(["solve", str(path)]) == 2
    err = capsys.readouterr().err
    assert message in err and "key 'cords." in err


def test_disc_that_does_not_fit_the_ring(tmp_path, capsys):
    path = tmp_path / "r.yaml"
    path.write_text(CIRCLE.replace("{d}", "250").replace("on: {circle: O, radius: 300}",
                                                         "on: {circle: O, radius: 400}"))
    assert main(["solve", str(path)]) == 2
    assert "in the figure the centres are 250 mm apart" in capsys.readouterr().err


@pytest.mark.parametrize("text, q", [
    (LINE, np.linspace(-0.3, 0.4, 15)),
    (CIRCLE.replace("{d}", "250"), np.radians(np.linspace(10, 150, 15))),
    (CORD, np.linspace(-0.6, -0.2, 15)),
], ids=["line", "inside", "cord"])
def test_newton_solves_contacts_as_the_closed_form(text, q):
    """Newton's rows of the contacts (one a contact) give the closed form's positions and
    rates, the disc turning more than half a turn over the range."""
    mech = linkcli.loads(text)
    ref = _marker_rates(text, q)[1]
    newton = mech.solver("newton")
    kin = newton.positions(q)
    newton.velocities(kin, np.ones_like(q))
    newton.accelerations(kin, np.zeros_like(q))
    for p in ("C", "D"):
        assert np.max(np.abs(kin.pos[p] - ref.pos[p])) < 1e-9
        assert np.max(np.abs(kin.vel.get(p, 0) - ref.vel.get(p, 0))) < 1e-9
        assert np.max(np.abs(kin.acc.get(p, 0) - ref.acc.get(p, 0))) < 1e-8


def test_seed_24_january_disc_in_a_guide_with_a_pendulum():
    """24 Jan 2001, Es. 2 (numbers chosen): the corrected M and K of the seed, written in
    the coordinates alpha (disc rotation) and beta; the file uses psi = A alpha (A = r/(R-r))
    for the disc's centre, which leaves the frequencies unchanged."""
    from scipy.linalg import eigh
    Md, r, J, R, m, L, j, K, g = 10, 0.1, 0.05, 0.5, 2, 0.6, 0.0025, 2000, 9.81
    M = np.array([[J + r ** 2 * (Md + m), m * r * L], [m * r * L, j + m * L ** 2]])
    Kk = np.array([[2 * K * r ** 2 + (Md + m) * g * r ** 2 / (R - r), K * r * L],
                   [K * r * L, K * L ** 2 / 2 + m * g * L]])
    omega = np.sqrt(eigh(Kk, M, eigvals_only=True))
    values = linkcli.load(os.path.join(ROOT, "mechanisms",
                                       "polimi-2001-01-24-vibration.yaml")).solve().values
    assert float(values["w1"]) == pytest.approx(omega[0], rel=1e-9)
    assert float(values["w2"]) == pytest.approx(omega[1], rel=1e-9)
    # the seed's own final K (l.417: no gravity, K22 = L^2/2) gives no real frequencies
    seed_K = np.array([[2 * K * (r / (R - r)) ** 2 * (R - r) ** 2, K * r * L],
                       [K * r * L, L ** 2 / 2]])
    assert np.min(eigh(seed_K, M, eigvals_only=True)) < 0


def _belt_chain(n):
    """n discs in a row, each turned by an open belt from the one before (radii 100 and 50
    mm in turn, every strand along y = 0 under them): the last one turns at r_0 / r_last
    times the first one's rate, in the same sense."""
    radius = [100 if i % 2 == 0 else 50 for i in range(n)]
    lines = ['title: "belt chain"', "units: {length: mm, angle: deg}", "frame:"]
    lines += [f"  C{i}: [{300 * i}, {radius[i]}]" for i in range(n)]
    lines += ["points:"] + [f"  M{i}: [{300 * i}, {2 * radius[i]}]" for i in range(n)]
    lines += ["links:"] + [f"  d{i}: {{points: [C{i}, M{i}], length: {radius[i]}}}"
                           for i in range(n)]
    lines += ["cords:"] + [f"  b{i}: {{pulley: d{i + 1}, radius: {radius[i + 1]}, along: -x, "
                           f"side: left, to: {{disc: d{i}, radius: {radius[i]}, side: left}}}}"
                           for i in range(n - 1)]
    lines += ["driver: {angle: [C0, M0], value: 90, rate: 10}",
              f"quantities: {{w: {{angle: [C{n - 1}, M{n - 1}]}}}}",
              "report: {position: [w], velocity: [wdot]}"]
    return "\n".join(lines) + "\n", radius[0] / radius[-1]


def test_a_thousand_chained_belt_strands_are_solved():
    """The branch search walked the groups by recursion, one level per group: 1000 strands
    ended in an internal error (RecursionError, exit 70)."""
    text, ratio = _belt_chain(1000)
    got = linkcli.loads(text).solve(q=np.array([100.0, 110.0])).values
    assert np.allclose(got["w"], 90 + np.array([10.0, 20.0]) * ratio, rtol=0, atol=1e-9)
    assert np.allclose(got["wdot"], 10 * ratio, rtol=0, atol=1e-9)
