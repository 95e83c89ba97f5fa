"""The textbook's questions asked directly (docs/schema.md, "quantities"): speeds and
accelerations of points, projections, relative motion, rotations of bodies, the angle
between two vectors, instant centres, joint forces and velocity ratios.

Each is checked by a second route, never by linkcli's own rates:

- speeds, tangential and normal accelerations of a crank-slider's points against its
  closed-form derivatives, and of a four-bar's coupler point against finite differences
  of positions in time (five-point stencils);
- projections and relative motion against the positions and their finite differences;
- rotations against atan2 of the positions, rolling without slip (a disc turns by
  -travel / R) and finite differences;
- the angle between two vectors against the law of cosines (the crociera's gamma, a
  four-bar's transmission angle);
- instant centres against the intersection of two points' normals to their paths;
- joint forces against the free-body balance of each body with its loads (and, with
  masses, its d'Alembert force from finite differences);
- velocity ratios against the derivative of the closed form.
"""
from __future__ import annotations

import math
import os

import numpy as np
import pytest

import linkcli
from linkcli.cli import main
from linkcli.errors import InputError, SolveError
from closure import WHEEL_ON_FLOOR

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MECH = os.path.join(ROOT, "mechanisms")

# an offset crank-slider in SI units: crank OA = r, rod AB = l, slider B on y = e
R, L, E = 0.1, 0.3, 0.02
CRANK_SLIDER = """
title: offset crank-slider
units: {length: m, angle: rad, force: N, torque: Nm}
frame: {O: [0, 0]}
points: {A: [0.08, 0.06], B: [0.36, 0.02]}
links:
  OA: {points: [O, A], length: 0.1}
  AB: {points: [A, B], length: 0.3}
sliders: {S: {point: B, guide: {y: 0.02}}}
driver: {angle: [O, A], value: 0.7, rate: 5, accel: 2}
loads:
  F: {type: force, at: B, x: -40}
  M: {type: driver, value: unknown}
quantities:
  vA: {speed: A}
  aA: {acceleration: A}
  atA: {tangential_acceleration: A}
  anA: {normal_acceleration: A}
  vB: {speed: B}
  aB: {acceleration: B}
  atB: {tangential_acceleration: B}
  anB: {normal_acceleration: B}
  phi: {rotation: AB}
  phis: {rotation: AB, signed: true}
  slide: {rotation: S}
  Ix: {instant_centre: AB, component: x}
  Iy: {instant_centre: AB, component: y}
  IS: {instant_centre: S, component: x}
  W: {velocity_ratio: xB}
  Wphi: {velocity_ratio: phi}
report:
  position: [phi]
  velocity: [vA, vB]
  acceleration: [aA, atA, anA]
"""

# a four-bar with a triangular coupler BCP, SI units
FOURBAR = """
title: four-bar with a coupler point
units: {length: m, angle: rad}
frame: {A: [0, 0], D: [0.3, 0]}
points: {B: [0.054, 0.084], C: [0.367, 0.241], P: [0.164, 0.251]}
links:
  AB: {points: [A, B], length: 0.1}
  BCP:
    points: [B, C, P]
    shape: {C: {length: 0.35}, P: {length: 0.2, angle: 0.5235987755982988}}
  DC: {points: [D, C], length: 0.25}
driver: {angle: [A, B], value: 1.0, rate: 2.0, accel: -3.0}
quantities:
  vP: {speed: P}
  aP: {acceleration: P}
  atP: {tangential_acceleration: P}
  anP: {normal_acceleration: P}
  sP: {along: [B, C], point: P}
  nP: {normal_to: [B, C], point: P}
  sD: {along: [A, D], point: P}
  rx: {relative: [B, P], component: x}
  ry: {relative: [B, P], component: y}
  vBP: {relative_speed: [B, P]}
  aBP: {relative_acceleration: [B, P]}
  cpl: {rotation: BCP}
  mu: {between: [[B, C], [D, C]]}
  mus: {between: [[D, C], [B, C]], signed: true}
  Ix: {instant_centre: BCP, component: x}
  Iy: {instant_centre: BCP, component: y}
  IP: {instant_centre_distance: [BCP, P]}
report:
  position: [mu]
"""

STEP = 1e-3


def solve(text_or_mech, names, q=None, qdot=None, qddot=None):
    mech = linkcli.loads(text_or_mech) if isinstance(text_or_mech, str) else text_or_mech
    return mech.solve(q=q, qdot=qdot, qddot=qddot, names=names).values


def positions(mech, q, points):
    """Every point of ``points`` at the driver values ``q`` (complex arrays)."""
    names = [f"{axis}{p}" for p in points for axis in "xy"]
    values = solve(mech, names, q=q)
    return {p: np.asarray(values["x" + p]) + 1j * np.asarray(values["y" + p]) for p in points}


def differences(mech, points, q0, qd, qdd, h=STEP):
    """(position, velocity, acceleration) of each point from its positions at five instants
    of the motion q(t) = q0 + qd t + qdd t^2 / 2 (display units of the driver)."""
    t = np.arange(-2, 3) * h
    z = positions(mech, q0 + qd * t + qdd * t ** 2 / 2, points)
    out = {}
    for p, w in z.items():
        v = (w[0] - 8 * w[1] + 8 * w[3] - w[4]) / (12 * h)
        a = (-w[0] + 16 * w[1] - 30 * w[2] + 16 * w[3] - w[4]) / (12 * h * h)
        out[p] = (w[2], v, a)
    return out


def scalar_differences(values):
    """(rate, second rate) of a scalar sampled at the five instants of ``differences``."""
    w = np.asarray(values)
    return ((w[0] - 8 * w[1] + 8 * w[3] - w[4]) / (12 * STEP),
            (-w[0] + 16 * w[1] - 30 * w[2] + 16 * w[3] - w[4]) / (12 * STEP * STEP))


def timeline(q0, qd, qdd):
    t = np.arange(-2, 3) * STEP
    return q0 + qd * t + qdd * t ** 2 / 2


def near(a, b, rel=1e-7, scale=1.0):
    """a == b to ``rel`` relative, or ``rel * scale`` absolute (complex: both parts)."""
    a, b = np.asarray(a), np.asarray(b)
    if np.iscomplexobj(a) or np.iscomplexobj(b):
        near(a.real, b.real, rel, scale)
        near(a.imag, b.imag, rel, scale)
        return
    np.testing.assert_allclose(a.astype(float), b.astype(float), rtol=rel, atol=rel * scale)


def with_report(text, report):
    """``text`` with its report replaced by ``report`` (YAML lines under 'report:')."""
    return text[:text.index("report:\n")] + "report:\n" + report


# --- speeds and accelerations of points -------------------------------------------------
def crank_slider_closed_form(theta, omega, alpha):
    """v and a (complex) of A and B from x_B = r cos(theta) + sqrt(l^2 - (e - r sin)^2)."""
    a_pos = R * np.exp(1j * theta)
    v_a = 1j * omega * a_pos
    a_a = (1j * alpha - omega ** 2) * a_pos
    s = E - R * np.sin(theta)
    k = np.sqrt(L ** 2 - s ** 2)
    dx = -R * np.sin(theta) + s * R * np.cos(theta) / k
    ds = -R * np.cos(theta)
    dk = s * R * np.cos(theta) / k
    ddx = -R * np.cos(theta) + ((ds * R * np.cos(theta) - s * R * np.sin(theta)) * k
                                - s * R * np.cos(theta) * dk) / k ** 2
    return v_a, a_a, dx * omega + 0j, ddx * omega ** 2 + dx * alpha + 0j, dx


@pytest.mark.parametrize("omega, alpha", [(5.0, 2.0), (-3.0, 7.0), (0.5, -40.0)])
def test_crank_slider_speeds_and_accelerations_match_the_closed_form(omega, alpha):
    theta = np.linspace(0.1, 6.1, 13)
    v_a, a_a, v_b, a_b, _ = crank_slider_closed_form(theta, omega, alpha)
    got = solve(CRANK_SLIDER, ["vA", "aA", "atA", "anA", "vB", "aB", "atB", "anB", "vBdot"],
                q=theta, qdot=omega, qddot=alpha)
    scale = R * max(omega ** 2, abs(alpha))
    near(got["vA"], R * abs(omega))
    near(got["aA"], R * math.hypot(alpha, omega ** 2))
    near(got["atA"], R * alpha * np.sign(omega), scale=scale)      # r alpha, with omega's sign
    near(got["anA"], R * omega ** 2)                                # r omega^2 towards O
    near(got["vB"], np.abs(v_b))
    near(got["aB"], np.abs(a_b))
    near(got["atB"], a_b.real * np.sign(v_b.real), scale=scale)     # along its straight path
    near(got["vBdot"], got["atB"])                                  # a speed's rate
    near(got["anB"], 0.0, scale=scale)                              # a straight path


def test_coupler_point_speed_and_acceleration_components_match_differences():
    mech = linkcli.loads(FOURBAR)
    q0, qd, qdd = 1.0, 2.0, -3.0
    _, v, a = differences(mech, ["P"], q0, qd, qdd)["P"]
    got = solve(mech, ["vP", "vPdot", "aP", "atP", "anP"])
    near(got["vP"], abs(v))
    tangential = (np.conj(v) * a).real / abs(v)
    normal = abs((np.conj(v) * a).imag) / abs(v)
    near(got["atP"], tangential, rel=1e-6, scale=abs(a))
    near(got["vPdot"], tangential, rel=1e-6, scale=abs(a))
    near(got["anP"], normal, rel=1e-6, scale=abs(a))
    near(got["aP"], abs(a), rel=1e-6)
    near(got["atP"] ** 2 + got["anP"] ** 2, got["aP"] ** 2, rel=1e-12)
    # the speed's rate is the derivative of the speed along the motion
    t = timeline(q0, qd, qdd)
    speeds = [solve(mech, ["vP"], q=q, qdot=qd + qdd * ti)["vP"] for q, ti in
              zip(t, np.arange(-2, 3) * STEP)]
    near(scalar_differences(speeds)[0], got["vPdot"], rel=1e-6, scale=abs(a))


def test_relative_projections_are_the_textbooks_normal_and_tangential_components():
    """Of C relative to B on the coupler (B -> C its axis): along B -> C the relative
    acceleration is -omega^2 BC, normal to it alpha BC, omega and alpha the coupler's
    (from differences of its angle); the position along it is BC, its rate 0; along a
    fixed vector the pair form is the difference of the point forms."""
    text = FOURBAR.replace("quantities:\n", "quantities:\n"
                           "  rBC: {along: [B, C], point: [B, C]}\n"
                           "  tBC: {normal_to: [B, C], point: [B, C]}\n"
                           "  dBP: {along: [A, D], point: [B, P]}\n"
                           "  sB: {along: [A, D], point: B}\n"
                           "  sP2: {along: [A, D], point: P}\n")
    mech = linkcli.loads(text)
    q0, qd, qdd = 1.0, 2.0, -3.0
    got = solve(mech, ["rBC", "rBCdot", "rBCddot", "tBCddot", "dBP", "dBPddot", "sB", "sBddot",
                       "sP2", "sP2ddot"], q=q0, qdot=qd, qddot=qdd)
    angles = solve(mech, ["cpl"], q=timeline(q0, qd, qdd))["cpl"]
    omega, alpha = scalar_differences(np.unwrap(np.asarray(angles)))
    near(got["rBC"], 0.35)
    near(got["rBCdot"], 0.0, scale=0.35 * abs(omega))
    near(got["rBCddot"], -omega ** 2 * 0.35, rel=1e-6)
    near(got["tBCddot"], alpha * 0.35, rel=1e-6)
    near(got["dBP"], got["sP2"] - got["sB"], rel=1e-12)
    near(got["dBPddot"], got["sP2ddot"] - got["sBddot"], rel=1e-12)


KENNEDY = """
title: four-bar ABCD (Khurmi 6.1's data)
units: {length: mm, angle: deg, angular_rate: rad/s}
frame: {A: [0, 0], D: [600, 0]}
points: {B: [150, 259.8], C: [499.6, 345.7]}
links:
  AB: {points: [A, B], length: 300}
  BC: {points: [B, C], length: 360}
  CD: {points: [D, C], length: LCD}
driver: {angle: [A, B], value: 60, rate: -10.47}
quantities:
  I13x: {instant_centre: BC, component: x}
  I13y: {instant_centre: BC, component: y}
  I24x: {instant_centre: [AB, CD], component: x}
  I24y: {instant_centre: [AB, CD], component: y}
  I42x: {instant_centre: [CD, AB], component: x}
  I13fx: {instant_centre: [BC, frame], component: x}
report:
  position: [I13x]
"""


def _meet(p1, p2, p3, p4):
    """Where the line p1 p2 meets the line p3 p4 (complex points)."""
    d1, d2 = p2 - p1, p4 - p3
    t = ((p3 - p1).conjugate() * d2).imag / ((d1.conjugate() * d2).imag)
    return p1 + t * d1


def test_relative_instant_centres_follow_kennedys_theorem():
    """I24 (AB relative to CD) lies on A D and on B C, I13 on A B and on D C (Kennedy's
    three-centre theorem); the points of AB and of CD at I24 move alike; relative to the
    frame a centre is the absolute one; I42 = I24."""
    mech = linkcli.loads(KENNEDY.replace("LCD", "360"))
    q = np.linspace(30.0, 100.0, 6)
    got = solve(mech, ["I13x", "I13y", "I24x", "I24y", "I42x", "I13fx", "xB", "yB", "xC", "yC"],
                q=q)
    A, D = 0j, 600 + 0j
    B, C = got["xB"] + 1j * got["yB"], got["xC"] + 1j * got["yC"]
    near(got["I24x"] + 1j * got["I24y"], _meet(A, D, B, C), rel=1e-9, scale=600)
    near(got["I13x"] + 1j * got["I13y"], _meet(A, B, D, C), rel=1e-9, scale=600)
    near(got["I42x"], got["I24x"], rel=1e-12, scale=600)
    near(got["I13fx"], got["I13x"], rel=1e-12, scale=600)
    # velocities of the two bodies' points at I24 (m, rad/s from the positions' rates)
    state = mech.solver().velocities(mech.solver().positions(np.radians(q)), np.ones_like(q))
    w_ab = (state.vel["B"] / state.pos["B"]).imag
    w_cd = (state.vel["C"] / (state.pos["C"] - 0.6)).imag
    i24 = (got["I24x"] + 1j * got["I24y"]) / 1000
    near(1j * w_ab * i24, 1j * w_cd * (i24 - 0.6), rel=1e-9, scale=1.0)


def test_a_relative_centre_of_bodies_turning_alike_is_refused(tmp_path, capsys):
    """A parallelogram (AB and CD equal and parallel) turns AB and CD alike: no I24."""
    text = KENNEDY.replace("LCD", "300").replace("C: [499.6, 345.7]", "C: [750, 259.8]") \
        .replace("BC: {points: [B, C], length: 360}", "BC: {points: [B, C], length: 600}") \
        .replace("  position: [I13x]", "  position: [I24x]")
    path = tmp_path / "parallelogram.yaml"
    path.write_text(text)
    assert main(["solve", str(path)]) == 3
    err = capsys.readouterr().err
    assert "'I24x' is undefined at q = 60 deg: body AB relative to CD does not turn" in err
    bad = KENNEDY.replace("LCD", "360").replace("[AB, CD], component: x", "[AB, AB], component: x")
    path.write_text(bad)
    assert main(["solve", str(path)]) == 2
    assert "a body has no instant centre relative to itself" in capsys.readouterr().err


def test_the_point_of_least_speed_on_a_line_of_a_body_is_the_sampled_minimum():
    """least_speed_at / least_speed of the coupler's line B -> C: the minimum of |v| over
    points B + t u sampled finely (rigid-body velocities from v_B and omega)."""
    text = FOURBAR.replace("quantities:\n", "quantities:\n"
                           "  G: {least_speed_at: [B, C]}\n  vG: {least_speed: [B, C]}\n")
    mech = linkcli.loads(text)
    for q in (0.6, 1.0, 1.7):
        got = solve(mech, ["G", "vG", "xB", "yB", "xC", "yC"], q=q, qdot=2.0)
        state = mech.solver().velocities(mech.solver().positions(q), 2.0)
        B, C = state.pos["B"], state.pos["C"]
        vb = state.vel["B"]
        omega = ((state.vel["C"] - vb) / (C - B)).imag
        u = (C - B) / abs(C - B)
        t = np.linspace(-5.0, 5.0, 2_000_001)
        speeds = np.abs(vb + 1j * omega * t * u)
        best = int(np.argmin(speeds))
        near(got["G"], t[best], rel=1e-5)           # the grid's step is 5e-6 m
        near(got["vG"], speeds[best], rel=1e-9)


def test_the_point_of_least_speed_of_a_translating_body_is_refused(tmp_path, capsys):
    text = KENNEDY.replace("LCD", "300").replace("C: [499.6, 345.7]", "C: [750, 259.8]") \
        .replace("BC: {points: [B, C], length: 360}", "BC: {points: [B, C], length: 600}") \
        .replace("  position: [I13x]", "  velocity: [G, vG]") \
        .replace("quantities:\n", "quantities:\n  G: {least_speed_at: [B, C]}\n"
                 "  vG: {least_speed: [B, C]}\n")
    mech = linkcli.loads(text)
    v = solve(mech, ["vG"], q=60.0)
    near(v["vG"], 300 * 10.47, rel=1e-9)         # mm/s: every point moves as B, AB omega
    path = tmp_path / "parallelogram.yaml"
    path.write_text(text)
    assert main(["solve", str(path)]) == 3
    assert "'G' is undefined at q = 60 deg: the body of B and C does not turn there" in \
        capsys.readouterr().err
    path.write_text(text.replace("least_speed_at: [B, C]", "least_speed_at: [A, C]"))
    assert main(["solve", str(path)]) == 2
    assert "no body carries both A and C" in capsys.readouterr().err


def test_normal_acceleration_is_speed_squared_over_the_radius_of_curvature():
    """The crank pin's path is a circle of radius r: a_n = |v|^2 / r at any rates."""
    got = solve(CRANK_SLIDER, ["vA", "anA"], q=np.linspace(0, 6, 7), qdot=-4.0, qddot=9.0)
    near(got["anA"], got["vA"] ** 2 / R)


def test_directions_of_motion_are_refused_where_a_point_is_at_rest():
    mech = linkcli.loads(CRANK_SLIDER)
    for name in ("atA", "anA", "vAdot"):
        with pytest.raises(SolveError) as err:
            solve(mech, [name], qdot=0.0)
        text = str(err.value)
        assert f"'{name}' is undefined at q = 0.7 rad" in text and "point A is at rest" in text
        assert err.value.line is not None and err.value.key.startswith("quantities.")
    # the slider at rest at the outer dead centre: O, A and B aligned, |OB| = r + l
    theta = math.asin(E / (R + L))
    with pytest.raises(SolveError, match=r"'anB' is undefined at q = 0\.05002\d* rad: point B "
                                         r"is at rest"):
        solve(mech, ["anB"], q=[0.1, theta])
    assert solve(mech, ["vA"], qdot=0.0)["vA"] == 0.0      # a speed itself is defined


# --- projections and relative motion -----------------------------------------------------
def test_projections_are_position_components_with_the_textbook_rates():
    mech = linkcli.loads(FOURBAR)
    q0, qd, qdd = 1.0, 2.0, -3.0
    motion = differences(mech, ["B", "C", "P"], q0, qd, qdd)
    (b, _, _), (c, _, _), (p, v, a) = motion["B"], motion["C"], motion["P"]
    u = (c - b) / abs(c - b)
    got = solve(mech, ["sP", "sPdot", "sPddot", "nP", "nPdot", "nPddot", "sD", "sDdot",
                       "sDddot"])
    near(got["sP"], (np.conj(u) * p).real)
    near(got["nP"], (np.conj(1j * u) * p).real)
    # the rates are the components of v_P and a_P along the current direction
    near(got["sPdot"], (np.conj(u) * v).real, rel=1e-6, scale=abs(v))
    near(got["nPdot"], (np.conj(1j * u) * v).real, rel=1e-6, scale=abs(v))
    near(got["sPddot"], (np.conj(u) * a).real, rel=1e-6, scale=abs(a))
    near(got["nPddot"], (np.conj(1j * u) * a).real, rel=1e-6, scale=abs(a))
    # ... which are not the derivatives of the projection when B -> C turns
    series = [solve(mech, ["sP"], q=q)["sP"] for q in timeline(q0, qd, qdd)]
    assert abs(scalar_differences(series)[0] - got["sPdot"]) > 1e-3 * abs(v)
    # along a fixed direction (the frame's A -> D, the x axis) they are
    series = [solve(mech, ["sD"], q=q)["sD"] for q in timeline(q0, qd, qdd)]
    rate, second = scalar_differences(series)
    near(got["sD"], p.real)
    near(got["sDdot"], rate, rel=1e-6, scale=abs(v))
    near(got["sDddot"], second, rel=1e-5, scale=abs(a))


def test_relative_motion_against_differences():
    mech = linkcli.loads(FOURBAR)
    q0, qd, qdd = 1.0, 2.0, -3.0
    motion = differences(mech, ["B", "P"], q0, qd, qdd)
    (b, vb, ab), (p, vp, ap) = motion["B"], motion["P"]
    got = solve(mech, ["rx", "ry", "rxdot", "rydot", "rxddot", "ryddot", "vBP", "vBPdot",
                       "aBP"])
    near(got["rx"] + 1j * got["ry"], p - b)
    near(got["rxdot"] + 1j * got["rydot"], vp - vb, rel=1e-6, scale=abs(vp))
    near(got["rxddot"] + 1j * got["ryddot"], ap - ab, rel=1e-6, scale=abs(ap))
    near(got["vBP"], abs(vp - vb), rel=1e-6)
    near(got["aBP"], abs(ap - ab), rel=1e-6)
    # P and B are points of one body: |v_P - v_B| = |omega| |P - B|
    omega = solve(mech, ["cpldot"])["cpldot"]
    near(got["vBP"], abs(omega) * abs(p - b))
    near(got["vBPdot"], (np.conj(vp - vb) * (ap - ab)).real / abs(vp - vb), rel=1e-6,
         scale=abs(ap - ab))


# --- rotations ---------------------------------------------------------------------------
def test_rotation_of_a_link_is_its_angle_with_omega_and_alpha_from_differences():
    mech = linkcli.loads(FOURBAR)
    q0, qd, qdd = 1.0, 2.0, -3.0
    t = timeline(q0, qd, qdd)
    z = positions(mech, t, ["B", "C"])
    angles = np.unwrap(np.angle(z["C"] - z["B"]))
    got = solve(mech, ["cpl", "cpldot", "cplddot"])
    near(got["cpl"], angles[2] % (2 * math.pi))
    rate, second = scalar_differences(angles)
    near(got["cpldot"], rate, rel=1e-6)
    near(got["cplddot"], second, rel=1e-5, scale=abs(second) + abs(rate))


def test_rotation_of_a_crank_slider_rod_a_slider_and_signed_angles():
    theta = np.linspace(0.2, 6.2, 9)
    got = solve(CRANK_SLIDER, ["phi", "phis", "slide", "slidedot", "slideddot"], q=theta)
    s = E - R * np.sin(theta)
    phi = np.arctan2(s, np.sqrt(L ** 2 - s ** 2))        # the angle of A -> B
    near(got["phis"], phi)
    near(got["phi"], np.mod(phi, 2 * math.pi))
    assert np.all((got["phis"] > -math.pi) & (got["phis"] <= math.pi))
    near(got["slide"], 0.0)                            # the guide's direction: +x
    near(got["slidedot"], 0.0)
    near(got["slideddot"], 0.0)


def test_rotation_of_an_actuator_is_the_angle_of_its_axis():
    text = open(os.path.join(MECH, "padova-2020-07.yaml"), encoding="utf-8").read()
    text = text.replace("quantities:\n", "quantities:\n  rot: {rotation: AB}\n", 1)
    got = solve(text, ["rot", "phi1", "rotdot", "phi1dot"], q=[120, 130, 140])
    near(got["rot"], got["phi1"])
    near(got["rotdot"], got["phi1dot"])


def test_rotation_of_a_rolling_disc_of_dynamics_follows_rolling_without_slip():
    """Curami's disc (centre D on y = -100, on the floor R = 80 below it, 'left' of +x)
    turns by -(x_D - x_D0) / R: 0 at the file's driver value, counter-clockwise when it
    rolls to -x.  Before, a quantity could not name the disc at all."""
    path = os.path.join(MECH, "curami-2001-07-17-disc.yaml")
    text = open(path, encoding="utf-8").read().replace(
        "quantities:\n", "quantities:\n  theta: {rotation: disc}\n  thetas: {rotation: disc, "
        "signed: true}\n  ID: {instant_centre: disc, component: y}\n", 1)
    mech = linkcli.loads(text)
    radius = 80.0
    x0 = solve(mech, ["xD"])["xD"]
    q = np.array([30.0, 60.0, 120.0, 200.0, 300.0])
    got = solve(mech, ["theta", "thetas", "thetadot", "thetaddot", "xD", "xDdot", "xDddot",
                       "ID"], q=q)
    turned = np.degrees(-(got["xD"] - x0) / radius)
    near(got["theta"], np.mod(turned, 360.0), scale=360)
    near(got["thetas"], (turned + 180.0) % 360.0 - 180.0, scale=360)
    near(got["thetadot"], -got["xDdot"] / radius)           # rad/s: the file's angular rate
    near(got["thetaddot"], -np.radians(got["xDddot"] / radius) * 180 / math.pi,
         scale=np.max(np.abs(got["xDddot"])) / radius)
    near(got["ID"], -100.0 - radius)                         # the contact with the floor
    near(solve(mech, ["theta"])["theta"], 0.0, scale=360)


WHEEL = WHEEL_ON_FLOOR + """quantities:
  th: {rotation: floor}
  tw: {rotation: wheel}
  Ix: {instant_centre: floor, component: x}
  Iy: {instant_centre: wheel, component: y}
  IC: {instant_centre_distance: [floor, C]}
report: {position: [th]}
"""


def test_rotation_and_instant_centre_of_a_rolling_contacts_disc():
    x = np.array([-150.0, 0.0, 40.0, 400.0])
    got = solve(WHEEL, ["th", "tw", "thdot", "Ix", "Iy", "IC"], q=x)
    near(got["th"], np.mod(90.0 - np.degrees(x / 100.0), 360.0), scale=360)
    near(got["tw"], got["th"])
    near(got["thdot"], -np.degrees(40.0 / 100.0))
    near(got["Ix"], x, scale=100)         # the wheel turns about its contact point
    near(got["Iy"], 0.0, scale=100)
    near(got["IC"], 100.0)


# --- the angle between two vectors ------------------------------------------------------
def test_crociera_gamma_is_the_law_of_cosines_angle():
    """Seed 002's crociera: gamma = acos((r^2 + a6^2 - a5^2) / (2 a6 r)) = 0.776 rad, with
    r = |OC|, a6 = OE = 0.4 and a5 = EC = 0.7."""
    mech = linkcli.load(os.path.join(MECH, "padova-crociera.yaml"))
    got = solve(mech, ["gamma", "xC", "yC"])
    r = math.hypot(got["xC"], got["yC"])
    gamma = math.acos((r ** 2 + 0.4 ** 2 - 0.7 ** 2) / (2 * 0.4 * r))
    near(got["gamma"], gamma)
    assert f"{got['gamma']:.3f}" == "0.776"


def test_transmission_angle_of_a_four_bar_by_the_law_of_cosines():
    mech = linkcli.loads(FOURBAR)
    theta = np.linspace(0.0, 6.0, 9)
    got = solve(mech, ["mu", "mus"], q=theta)
    # |BD|^2 = r^2 + d^2 - 2 r d cos(theta) = b^2 + c^2 - 2 b c cos(mu)
    bd2 = 0.1 ** 2 + 0.3 ** 2 - 2 * 0.1 * 0.3 * np.cos(theta)
    mu = np.arccos((0.35 ** 2 + 0.25 ** 2 - bd2) / (2 * 0.35 * 0.25))
    # from B -> C to D -> C: the angle between the two vectors, on the assembled branch
    near(np.minimum(got["mu"], 2 * math.pi - got["mu"]), mu)
    near(got["mus"], -np.where(got["mu"] > math.pi, got["mu"] - 2 * math.pi, got["mu"]))


def test_rates_of_the_angle_between_two_vectors_against_differences():
    mech = linkcli.loads(FOURBAR)
    q0, qd, qdd = 1.0, 2.0, -3.0
    series = np.unwrap([solve(mech, ["mu"], q=q)["mu"] for q in timeline(q0, qd, qdd)])
    rate, second = scalar_differences(series)
    got = solve(mech, ["mudot", "muddot", "musdot"])
    near(got["mudot"], rate, rel=1e-6)
    near(got["muddot"], second, rel=1e-5, scale=abs(second) + abs(rate))
    near(got["musdot"], -got["mudot"])


# --- instant centres ---------------------------------------------------------------------
def intersection(p1, d1, p2, d2):
    """The point where the line through p1 along d1 meets the line through p2 along d2."""
    t = ((np.conj(d2) * (p2 - p1)).imag) / ((np.conj(d2) * d1).imag)
    return p1 + t * d1


def test_instant_centre_of_a_coupler_is_where_the_point_normals_meet():
    mech = linkcli.loads(FOURBAR)
    theta = np.linspace(0.3, 5.9, 8)
    z = positions(mech, theta, ["B", "C", "P"])
    a, d = 0j, 0.3 + 0j
    # B moves normal to AB, C normal to DC: the normals are the lines AB and DC
    centre = intersection(a, z["B"] - a, d, z["C"] - d)
    got = solve(mech, ["Ix", "Iy", "IP", "vP", "cpldot"], q=theta)
    near(got["Ix"] + 1j * got["Iy"], centre, rel=1e-9)
    near(got["IP"], np.abs(z["P"] - centre), rel=1e-9)
    near(got["vP"], np.abs(got["cpldot"]) * got["IP"], rel=1e-9)   # |v_P| = |omega| IP


def test_instant_centre_of_a_crank_slider_rod():
    theta = np.array([0.3, 1.0, 2.5, 4.0])
    got = solve(CRANK_SLIDER, ["Ix", "Iy", "xB"], q=theta)
    # the line OA meets the normal to B's straight path, the vertical through B
    near(got["Ix"], got["xB"])
    near(got["Iy"], got["xB"] * np.tan(theta))


def test_instant_centres_are_refused_where_the_body_translates():
    mech = linkcli.loads(CRANK_SLIDER)
    # the rod translates where v_A is along AB: at cos(theta) = 0, where omega_AB = 0
    with pytest.raises(SolveError) as err:
        solve(mech, ["Ix"], q=[1.0, math.pi / 2])
    text = str(err.value)
    assert "'Ix' is undefined at q = 1.5708 rad" in text and "body AB does not turn" in text
    assert err.value.key == "quantities.Ix" and err.value.line is not None
    with pytest.raises(SolveError, match="body S does not turn"):
        solve(mech, ["IS"])                         # a slider on a fixed guide, always
    with pytest.raises(SolveError, match="body AB does not turn"):
        solve(mech, ["Iy"], qdot=0.0)               # a mechanism at rest


# --- joint forces ------------------------------------------------------------------------
def cross(a, b):
    return (np.conj(a) * b).imag


DISPARI_FORCES = """quantities:
  RA_AB_x: {reaction: [A, AB], component: x}
  RA_AB_y: {reaction: [A, AB], component: y}
  RB_AB_x: {reaction: [B, AB], component: x}
  RB_AB_y: {reaction: [B, AB], component: y}
  RB_AB: {reaction: [B, AB], component: magnitude}
  RC_CE_x: {reaction: [C, CE], component: x}
  RC_CE_y: {reaction: [C, CE], component: y}
  RE_CE_x: {reaction: [E, CE], component: x}
  RE_CE_y: {reaction: [E, CE], component: y}
  RC_BC_x: {reaction: [C, BC], component: x}
  RC_BC_y: {reaction: [C, BC], component: y}
  RC_CD_x: {reaction: [C, CD], component: x}
  RC_CD_y: {reaction: [C, CD], component: y}
  RE_F_x: {reaction: [E, F], component: x}
  RE_F_y: {reaction: [E, F], component: y}
  RF_F_x: {reaction: [F, F], component: x}
  RF_F_y: {reaction: [F, F], component: y}
  RD_x: {reaction: [D, frame], component: x}
  RD_CD_x: {reaction: [D, CD], component: x}
  NF: {slider_force: F, component: normal}
  TF: {slider_force: F, component: friction}
"""


def test_reactions_balance_every_body_with_its_loads():
    """Padova 2021_01_dispari: MA = 12 Nm on AB, XB = 99 N at B, YF (unknown) at F."""
    path = os.path.join(MECH, "padova-2021-01-dispari.yaml")
    text = open(path, encoding="utf-8").read().replace("quantities:\n", DISPARI_FORCES, 1)
    mech = linkcli.loads(text)
    names = [n for n in mech.quantities if n[0] in "RNT"]
    got = solve(mech, names + ["YF", "xA", "yA", "xB", "yB", "xC", "yC", "xE", "yE"], q=[110, 123])
    f = {n[:-2]: got[n] + 1j * got[n[:-2] + "_y"] for n in names
         if n.endswith("_x") and n[:-2] + "_y" in got}
    pos = {p: (got["x" + p] + 1j * got["y" + p]) / 1000 for p in "ABCE"}   # m
    scale = np.max(np.abs(f["RB_AB"]))
    # AB: two pin forces and the torque MA = 12 Nm: sum F = 0, moments about A = 0
    near(f["RA_AB"] + f["RB_AB"], 0, scale=scale)
    near(cross(pos["B"] - pos["A"], f["RB_AB"]) + 12.0, 0, scale=scale * 0.1)
    near(got["RB_AB"], np.abs(f["RB_AB"]))
    # CE: a two-force member: equal and opposite forces along C -> E
    near(f["RC_CE"] + f["RE_CE"], 0, scale=scale)
    near(cross(pos["E"] - pos["C"], f["RE_CE"]), 0, scale=scale * 0.1)
    # pin C (no load there): the forces of the pin on its three bodies sum to zero
    near(f["RC_BC"] + f["RC_CD"] + f["RC_CE"], 0, scale=scale)
    # pin D: the force on the frame is the opposite of the force on CD
    near(got["RD_x"], -got["RD_CD_x"], scale=scale)
    # slider F: pins E and F and the guide (normal N along the left normal -x of its +y
    # direction, friction T along +y) balance; pin F carries the load YF
    near(f["RF_F"], 1j * got["YF"], scale=scale)
    guide = got["NF"] * (-1 + 0j) + got["TF"] * 1j
    near(f["RE_F"] + f["RF_F"] + guide, 0, scale=scale)
    near(got["TF"], 0.0, scale=scale)                    # no friction in the file


def test_reactions_with_masses_balance_the_dalembert_forces():
    """Seed 004's four-bar: the coupler (2 kg, J = 0.016 kg m^2, G at mid length) under
    its two pin forces, gravity and its inertia, a_G and alpha from differences."""
    path = os.path.join(MECH, "fourbar-inverse-dynamics.yaml")
    text = open(path, encoding="utf-8").read().replace("quantities:\n", """quantities:
  RAx: {reaction: [A, coupler], component: x}
  RAy: {reaction: [A, coupler], component: y}
  RBx: {reaction: [B, coupler], component: x}
  RBy: {reaction: [B, coupler], component: y}
""", 1)
    mech = linkcli.loads(text)
    q0 = 50.0                                        # deg; 150 rpm, constant
    qd = 150 * 360 / 60                              # deg/s
    h = 1e-4
    t = np.arange(-2, 3) * h
    z = positions(mech, q0 + qd * t, ["A", "B"])
    g_path = (z["A"] + z["B"]) / 2 / 1000            # m
    a_g = (-g_path[0] + 16 * g_path[1] - 30 * g_path[2] + 16 * g_path[3] - g_path[4]) / (
        12 * h * h)
    angle = np.unwrap(np.angle(z["B"] - z["A"]))
    alpha = (-angle[0] + 16 * angle[1] - 30 * angle[2] + 16 * angle[3] - angle[4]) / (
        12 * h * h)
    got = solve(mech, ["RAx", "RAy", "RBx", "RBy"], q=q0)
    ra, rb = got["RAx"] + 1j * got["RAy"], got["RBx"] + 1j * got["RBy"]
    gravity = -9.81j
    near(ra + rb + 2.0 * (gravity - a_g), 0, rel=1e-5, scale=abs(ra))
    a, b, g = z["A"][2] / 1000, z["B"][2] / 1000, g_path[2]
    moment = cross(a - g, ra) + cross(b - g, rb) - 0.016 * alpha
    near(moment, 0, rel=1e-5, scale=abs(ra) * 0.315)


# --- velocity ratios ---------------------------------------------------------------------
def test_velocity_ratio_is_the_derivative_of_the_closed_form():
    theta = np.linspace(0.2, 6.0, 7)
    _, _, _, _, dx = crank_slider_closed_form(theta, 1.0, 0.0)
    mech = linkcli.loads(CRANK_SLIDER)
    got = mech.solve(q=theta, qdot=0.0, names=["W", "Wphi", "phidot"])   # at rest: d/dq
    near(got.values["W"], dx)
    assert got.units["W"] == "m/rad" and got.units["Wphi"] == "rad/rad"
    at_unit_rate = solve(mech, ["phidot"], q=theta, qdot=1.0)["phidot"]
    near(got.values["Wphi"], at_unit_rate)
    # in mm per degree
    text = CRANK_SLIDER.replace("units: {length: m, angle: rad, force: N, torque: Nm}",
                                "units: {length: mm, angle: deg, force: N, torque: Nm}")
    text = text.replace("{O: [0, 0]}", "{O: [0, 0]}").replace(
        "points: {A: [0.08, 0.06], B: [0.36, 0.02]}", "points: {A: [80, 60], B: [360, 20]}")
    text = text.replace("length: 0.1}", "length: 100}").replace("length: 0.3}", "length: 300}")
    text = text.replace("guide: {y: 0.02}", "guide: {y: 20}").replace("value: 0.7,", "value: 40,")
    got = linkcli.loads(text).solve(q=np.degrees(theta), names=["W"])
    near(got.values["W"], dx * 1000 * math.pi / 180)
    assert got.units["W"] == "mm/deg"


# --- where they are used: report, keys, check, sweep, plot ---------------------------------
def test_report_sections_keys_and_check(tmp_path, capsys):
    text = with_report(CRANK_SLIDER, """  decimals: 4
  position: [phi, Ix, W]
  velocity: [vA, vB]
  acceleration: [aA, atA, anA]
  statics: [M]
""") + """keys:
  - values: {vA: 0.5000, anA: 2.5000, atA: 0.2000, phi: 6.13, W: -0.08}
"""
    path = tmp_path / "cs.yaml"
    path.write_text(text)
    assert main(["solve", str(path)]) == 0
    out = capsys.readouterr().out
    lines = [" ".join(line.split()) for line in out.splitlines()]
    assert "vA = 0.5000 m/s" in lines and "anA = 2.5000 m/s^2" in lines
    assert "Ix = 0.3732 m" in lines and "W = -0.0759 m/rad" in lines
    assert main(["check", str(path)]) == 0
    assert "5 passed, 0 failed" in capsys.readouterr().out


@pytest.mark.parametrize("section, name, message", [
    ("velocity", "aA", "'aA' is not a defined quantity of the velocity section"),
    ("position", "vA", "'vA' is not a defined quantity of the position section"),
    ("acceleration", "vAddot", "'vAddot' is not a defined quantity rate: a speed has one rate"),
    ("acceleration", "aAdot", "'aAdot' is not a defined quantity rate: an acceleration has no "
                              "rates"),
    ("position", "phi", None),
    ("velocity", "Ix", None),
])
def test_report_sections_of_the_new_quantities(tmp_path, capsys, section, name, message):
    text = with_report(CRANK_SLIDER, f"  {section}: [{name}]\n")
    if message is None:
        linkcli.loads(text)
        return
    with pytest.raises(InputError) as err:
        linkcli.loads(text)
    assert message in str(err.value)


def test_rates_a_quantity_has_not_are_refused_with_the_line_of_its_definition(capsys):
    mech = linkcli.loads(CRANK_SLIDER)
    for name, what in [("aAdot", "an acceleration, which has no rates"),
                       ("vAddot", "a speed, which has only one rate, vAdot"),
                       ("Ixdot", "an instant centre, which has no rates"),
                       ("Wdot", "a velocity ratio, which has no rates")]:
        with pytest.raises(InputError) as err:
            solve(mech, [name])
        assert what in str(err.value) and err.value.line is not None
    text = CRANK_SLIDER + "keys:\n  - values: {aAdot: 1.0}\n"
    with pytest.raises(InputError, match="'aAdot', which the file does not define: 'aA' has "
                                         "no rates"):
        linkcli.loads(text)


def test_sweep_and_plot_take_the_new_quantities(tmp_path, capsys):
    path = tmp_path / "fb.yaml"
    path.write_text(FOURBAR)
    names = "vP,atP,anP,sPdot,mu,Ix,IP"
    assert main(["sweep", str(path), "--from", "0.5", "--to", "1.5", "--steps", "4",
                 "--names", names]) == 0
    rows = [line.split(",") for line in capsys.readouterr().out.strip().splitlines()]
    assert rows[0][1:] == ["vP [m/s]", "atP [m/s^2]", "anP [m/s^2]", "sPdot [m/s]",
                           "mu [rad]", "Ix [m]", "IP [m]"]
    q = np.array([float(r[0]) for r in rows[1:]])
    got = solve(FOURBAR, names.split(","), q=q)
    for j, name in enumerate(names.split(","), 1):
        near([float(r[j]) for r in rows[1:]], got[name], rel=1e-12)
    pytest.importorskip("matplotlib")
    out = tmp_path / "p.png"
    assert main(["plot", str(path), "--sweep", "0:6:30", "--y", "mu", "--y", "vP",
                 "-o", str(out)]) == 0
    assert out.stat().st_size > 0


# --- validation --------------------------------------------------------------------------
@pytest.mark.parametrize("definition, key, message", [
    ("{speed: Z}", "quantities.bad.speed", "undefined point 'Z'"),
    ("{rotation: Q}", "quantities.bad.rotation", "undefined body 'Q'"),
    ("{rotation: S, signed: 1}", "quantities.bad.signed", "signed is true or false"),
    ("{speed: A, signed: true}", "quantities.bad.signed", "'signed' is for angles"),
    ("{instant_centre: AB}", "quantities.bad.component", "component is x or y, got None"),
    ("{instant_centre: AB, component: z}", "quantities.bad.component", "component is x or y"),
    ("{relative: [A, B], component: along}", "quantities.bad.component", "component is x or y"),
    ("{relative: [A, A], component: x}", "quantities.bad.relative", "the two points must differ"),
    ("{reaction: [B, OA], component: x}", "quantities.bad.reaction[0]",
     "undefined point 'B' on body 'OA'"),
    ("{reaction: [B, frame], component: x}", "quantities.bad.reaction[0]",
     "undefined point 'B' on body 'frame'"),
    ("{reaction: [A, Q], component: x}", "quantities.bad.reaction[1]", "undefined body 'Q'"),
    ("{reaction: [A, AB], component: tangent}", "quantities.bad.component",
     "component is x, y, magnitude, along or normal"),
    ("{reaction: A, component: x}", "quantities.bad.reaction", "expected two names"),
    ("{slider_force: AB, component: normal}", "quantities.bad.slider_force",
     "undefined body 'AB' for a slider force"),
    ("{slider_force: S, component: x}", "quantities.bad.component",
     "component is normal or friction"),
    ("{along: [O, A]}", "quantities.bad", "missing key 'point'"),
    ("{along: [O, A], point: Z}", "quantities.bad.point", "undefined point 'Z'"),
    ("{speed: A, point: B}", "quantities.bad.point", "'point' is for along and normal_to"),
    ("{speed: A, component: x}", "quantities.bad.component", "a speed quantity has no component"),
    ("{between: [[A, B]]}", "quantities.bad.between", "between takes two vectors"),
    ("{between: [[A, B], [C, D]]}", "quantities.bad.between[1][0]", "undefined point 'C'"),
    ("{instant_centre_distance: [AB, Z]}", "quantities.bad.instant_centre_distance[1]",
     "undefined point 'Z'"),
    ("{velocity_ratio: nope}", "quantities.bad.velocity_ratio", "'nope' is not a defined"),
    ("{velocity_ratio: vA}", "quantities.bad.velocity_ratio",
     "the velocity ratio of 'vA' (a speed) is not defined"),
    ("{velocity_ratio: xB, unit: mm}", "quantities.bad.unit", "a velocity ratio is in its"),
    ("{rotation: AB, unit: mm}", "quantities.bad.unit", "unknown unit 'mm' for a rotation"),
    ("{reaction: [A, AB], component: x, unit: Nm}", "quantities.bad.unit",
     "unknown unit 'Nm' for a reaction"),
    ("{speed: A, rotation: AB}", "quantities.bad",
     "give exactly one kind of quantity, not speed and rotation"),
])
def test_definitions_are_validated_with_located_messages(definition, key, message):
    text = CRANK_SLIDER.replace("quantities:\n", f"quantities:\n  bad: {definition}\n", 1)
    with pytest.raises(InputError) as err:
        linkcli.loads(text)
    errors = getattr(err.value, "errors", [err.value])
    found = [e for e in errors if e.key == key]
    assert found, [str(e) for e in errors]
    assert message in found[0].detail, found[0].detail
    assert found[0].line == text.splitlines().index(f"  bad: {definition}") + 1


def test_an_actuator_has_no_single_instant_centre():
    text = open(os.path.join(MECH, "padova-2020-07.yaml"), encoding="utf-8").read()
    text = text.replace("quantities:\n", "quantities:\n  I: {instant_centre: AB, component: x}\n",
                        1)
    with pytest.raises(InputError, match="the cylinder and the rod of an actuator"):
        linkcli.loads(text)


def test_joint_forces_with_a_rolling_contact_from_the_wheels_free_body():
    """A wheel with inertia J only, its centre driven at a_x: the floor's friction T turns
    it, r T = J alpha with alpha = -a_x / r, and the pin at C holds it back, R_x = -T."""
    text = WHEEL.replace("quantities:\n", "loads: {F: {type: driver, value: unknown}}\n"
                         "dynamics: {bodies: {wheel: {inertia: 0.01, center: C}}}\n"
                         "quantities:\n  R: {reaction: [C, wheel], component: x}\n"
                         "  T: {contact_force: floor, component: friction}\n", 1)
    got = solve(text, ["R", "T"])
    alpha = 15e-3 / 0.1                     # accel -15 mm/s^2, r = 100 mm
    near(got["T"], 0.01 * alpha / 0.1)
    near(got["R"], -0.01 * alpha / 0.1)


# --- the keys of the seeds -----------------------------------------------------------------
def test_the_crociera_key_checks_gamma_and_reports_the_lost_sign_of_phi2dot(capsys):
    assert main(["check", os.path.join(MECH, "padova-crociera.yaml"), "-v"]) == 0
    out = capsys.readouterr().out
    assert "ok " in out and "gamma: 0.776" in out
    assert "KNOWN" in out and "phi2dot: printed 0.3, computed -0.3 (lost minus" in out


def test_the_dispari_key_checks_the_driver_value_and_rate(capsys):
    assert main(["check", os.path.join(MECH, "padova-2021-01-dispari.yaml"), "-v"]) == 0
    out = capsys.readouterr().out
    assert "yF: 123.0" in out and "yFdot: -85.0" in out
