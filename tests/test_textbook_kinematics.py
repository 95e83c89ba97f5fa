"""Textbook kinematics problems (Khurmi & Gupta, Bevan, V. P. Singh, Hibbeler & Gupta) against
independent solutions.

Each shipped file (mechanisms/khurmi-*, bevan-*, vp-singh-*, hibbeler-*) is solved by linkcli,
and the same values are computed here from the problem's data alone: the loop closure by
Newton's method (or the law of cosines), the velocities and accelerations from the loop's
derivative equations, instant centres by intersecting lines (Kennedy), rubbing velocities as
|omega1 - omega2| times the pin's radius.  Nothing expected is taken from linkcli's output.
The models are exact, so they agree to 1e-7 relative, far inside the printed precision of
the keys; the keys themselves (with their tolerances and known problems) are checked by
`linkcli check`.  Signs: counter-clockwise positive; angles in degrees.
"""
from __future__ import annotations

import math
import os

import numpy as np
import pytest

import linkcli
from conftest import MECHANISMS
from linkcli.runs.check import check_file

RTOL = 1e-7
FT = 12.0                     # inches per foot (lengths in inches, answers in feet)
RPM = 2 * math.pi / 60        # rad/s per rpm


def e(t):
    return np.array([math.cos(t), math.sin(t)])


def k_cross(w, r):
    """w k x r for a planar vector r."""
    return np.array([-w * r[1], w * r[0]])


def newton(f, x0, tol=1e-14):
    """Root of f (R^n -> R^n) from x0, Jacobian by central differences."""
    x = np.array(x0, float)
    for _ in range(60):
        fx = f(x)
        jac = np.empty((len(fx), len(x)))
        for j in range(len(x)):
            dx = np.zeros_like(x)
            dx[j] = 1e-7
            jac[:, j] = (f(x + dx) - f(x - dx)) / 2e-7
        step = np.linalg.solve(jac, -fx)
        x = x + step
        if np.linalg.norm(step) < tol * (1 + np.linalg.norm(x)):
            break
    assert np.linalg.norm(f(x)) < 1e-10
    return x


def four_bar(d, a, b, c, th2, w2, al2, guess):
    """A at the origin, D = (d, 0); crank AB = a at th2, coupler BC = b, rocker DC = c.
    Returns B, C and, for the coupler (3) and the rocker (4), angles, omegas and alphas."""
    A, D = np.zeros(2), np.array([d, 0.0])
    B = A + a * e(th2)
    th3, th4 = newton(lambda q: B + b * e(q[0]) - D - c * e(q[1]), guess)
    C = B + b * e(th3)
    rBC, rDC = C - B, C - D
    M = np.column_stack([k_cross(1, rBC), -k_cross(1, rDC)])
    vB = k_cross(w2, B)
    w3, w4 = np.linalg.solve(M, -vB)
    aB = k_cross(al2, B) - w2 ** 2 * B
    al3, al4 = np.linalg.solve(M, -(aB - w3 ** 2 * rBC + w4 ** 2 * rDC))
    return dict(B=B, C=C, th3=th3, th4=th4, w3=w3, w4=w4, al3=al3, al4=al4, vB=vB, aB=aB)


def slider_crank(r, l, th2, w2, al2):
    """O at the origin, crank OC = r at th2, rod CP = l, P on the x axis beyond O.
    Returns C, P, the rod's angle, omega, alpha and the piston's x and its rates."""
    C = r * e(th2)
    th3, x = newton(lambda q: C + l * e(q[0]) - np.array([q[1], 0.0]),
                    [-math.asin(r * math.sin(th2) / l) * 0.9, r + l])
    P = np.array([x, 0.0])
    rCP = P - C
    M = np.column_stack([k_cross(1, rCP), [-1.0, 0.0]])
    vC = k_cross(w2, C)
    aC = k_cross(al2, C) - w2 ** 2 * C
    w3, xdot = np.linalg.solve(M, -vC)
    al3, xddot = np.linalg.solve(M, -(aC - w3 ** 2 * rCP))
    return dict(C=C, P=P, th3=th3, w3=w3, al3=al3, x=x, xdot=xdot, xddot=xddot, vC=vC, aC=aC)


def point_motion(base, v_base, a_base, w, al, point):
    """Velocity and acceleration of ``point`` of a body through ``base`` turning at w, al."""
    rel = point - base
    return v_base + k_cross(w, rel), a_base + k_cross(al, rel) - w ** 2 * rel


def meet(p1, d1, p2, d2):
    """Where the line p1 + s d1 meets the line p2 + t d2."""
    s = np.linalg.solve(np.column_stack([d1, -d2]), p2 - p1)
    return p1 + s[0] * d1


def norm(v):
    return float(np.linalg.norm(v))


# --- the independent solutions, by file --------------------------------------------------

def khurmi_7_1():
    s = four_bar(150, 40, 150, 80, math.radians(60), -120 * RPM, 0, [0.3, 1.4])
    return {"thCD": math.degrees(s["th4"]), "thCDdot": s["w4"], "xC": s["C"][0],
            "yC": s["C"][1]}


def khurmi_6_1():
    s = four_bar(600, 300, 360, 360, math.radians(60), -100 * RPM, 0, [0.3, 1.7])
    I13 = meet(np.zeros(2), s["B"], np.array([600.0, 0.0]), s["C"] - np.array([600.0, 0.0]))
    return {"thBCdot": s["w3"], "I13x": I13[0], "I13y": I13[1], "I13B": norm(I13 - s["B"]),
            "vB": 100 * RPM * 0.3}


def khurmi_8_4():
    s = four_bar(200, 62.5, 175, 112.5, math.radians(60), -10, 0, [0.3, 1.6])
    return {"vRQ": abs(s["w3"]) * 0.175, "vR": abs(s["w4"]) * 0.1125, "thQRdot": s["w3"],
            "thRSdot": s["w4"], "thQRddot": s["al3"], "thRSddot": s["al4"],
            "atRQddot": s["al3"] * 0.175, "atRSddot": s["al4"] * 0.1125}


def bevan_3_5():
    w2 = -100 * RPM
    s = four_bar(8, 2.5, 7, 4.5, math.radians(60), w2, 0, [0.3, 1.4])
    return {"vB": abs(w2) * 2.5 / FT, "vC": abs(s["w4"]) * 4.5 / FT,
            "vCB": abs(s["w3"]) * 7 / FT, "anB": w2 ** 2 * 2.5 / FT,
            "anC": s["w4"] ** 2 * 4.5 / FT, "thBCdot": s["w3"], "thCDdot": s["w4"],
            "thBCddot": s["al3"], "thCDddot": s["al4"],
            "btCBddot": s["w3"] ** 2 * 7 / FT}           # C's radial acceleration about B


def khurmi_7_2():
    w2 = -180 * RPM
    s = slider_crank(0.5, 2.0, math.radians(-45), w2, 0)
    E = s["C"] + 0.5 * e(s["th3"])
    vE, _ = point_motion(s["C"], s["vC"], s["aC"], s["w3"], s["al3"], E)
    # the rod's instant centre: OB produced meets the normal to P's path (Kennedy); G is the
    # foot of the perpendicular from it on the rod, the rod's point of least velocity
    centre = meet(np.zeros(2), s["C"], s["P"], np.array([0.0, 1.0]))
    u = (s["P"] - s["C"]) / norm(s["P"] - s["C"])
    arm = centre - s["C"]
    return {"vP": abs(s["xdot"]), "thBPdot": s["w3"], "vE": norm(vE),
            "vRo": abs(w2) * 0.025, "vRc": abs(s["w3"] - w2) * 0.030,
            "vRp": abs(s["w3"]) * 0.015, "BG": float(arm @ u),
            "vG": abs(s["w3"]) * abs(arm[0] * u[1] - arm[1] * u[0])}


def khurmi_8_1():
    s = slider_crank(150, 600, math.radians(-45), -300 * RPM, 0)
    D = (s["C"] + s["P"]) / 2
    vD, aD = point_motion(s["C"], s["vC"], s["aC"], s["w3"], s["al3"], D)
    return {"vD": norm(vD) / 1000, "aD": norm(aD) / 1000, "vAB": abs(s["w3"]) * 0.6,
            "thABdot": s["w3"], "thABddot": s["al3"], "atABddot": -s["al3"] * 0.6}


def bevan_3_3():
    s = slider_crank(6, 24, math.radians(45), 240 * RPM, 0)
    C, P = s["C"], s["P"]
    I = meet(np.zeros(2), C, P, np.array([0.0, 1.0]))   # OC produced, normal to the stroke

    def located(dc, dp, side):                           # law of cosines in the rod's frame
        u = (P - C) / 24
        along = (dc ** 2 - dp ** 2 + 24 ** 2) / (2 * 24)
        return C + along * u + side * math.sqrt(dc ** 2 - along ** 2) * np.array([-u[1], u[0]])

    X, Y = located(6, 19, +1), located(9, 32, -1)
    out = {"vC": norm(s["vC"]) / FT, "vP": abs(s["xdot"]) / FT, "Ix": I[0], "Iy": I[1]}
    for name, point in (("C", C), ("P", P), ("X", X), ("Y", Y)):
        out[name + "I"] = norm(point - I) / FT
    for name, point in (("X", X), ("Y", Y)):
        out["v" + name] = norm(point_motion(C, s["vC"], s["aC"], s["w3"], s["al3"], point)[0]) / FT
    return out


def bevan_3_4(al2):
    s = slider_crank(9, 36, math.radians(40), 240 * RPM, al2)
    C, P = s["C"], s["P"]
    X = C + 12 * (P - C) / 36
    _, aX = point_motion(C, s["vC"], s["aC"], s["w3"], s["al3"], X)
    _, aP_rel = point_motion(C, 0 * C, 0 * C, s["w3"], s["al3"], P)
    return {"anC": (240 * RPM) ** 2 * 9 / FT, "aC": norm(s["aC"]) / FT,
            "aPC": norm(aP_rel) / FT, "aX": norm(aX) / FT, "thCPddot": s["al3"],
            "atPCddot": s["al3"] * 36 / FT}


def vp_singh_13_3():
    r, l, d = 0.15, 0.60, 0.15 + 0.60 - 0.08
    # the crank angle t (clockwise from O -> P) at which the rod reaches P = (d, 0)
    (t,) = newton(lambda q: np.array([norm(np.array([d, 0.0]) - r * e(-q[0])) - l]), [1.0])
    s = slider_crank(r, l, -t, -240 * RPM, 0)
    assert abs(s["x"] - d) < 1e-12
    return {"th": math.degrees(t), "vP": abs(s["xdot"]), "aP": abs(s["xddot"]),
            "thBPdot": s["w3"]}


def hibbeler_16_9():
    w2 = -30.0
    B = 0.2 * e(math.radians(60))
    C = B + np.array([0.2, 0.0])                       # BC horizontal: C at B's height
    vB = k_cross(w2, B)
    # vB + w3 k x (C - B) = (vC, 0): the wheel's centre moves along the floor
    w3, vC = np.linalg.solve(np.column_stack([k_cross(1, C - B), [-1.0, 0.0]]), -vB)
    return {"vC": abs(vC), "thBCdot": w3, "thDdot": -vC / 0.1}


CASES = {
    "khurmi-7-1-fourbar.yaml": (khurmi_7_1, ()),
    "khurmi-6-1-instant-centres.yaml": (khurmi_6_1, ()),
    "khurmi-8-4-fourbar-accelerations.yaml": (khurmi_8_4, ()),
    "bevan-3-5-fourbar-imperial.yaml": (bevan_3_5, ()),
    "khurmi-7-2-rubbing-velocities.yaml": (khurmi_7_2, ("BG", "vP")),
    "khurmi-8-1-slider-crank-accelerations.yaml": (khurmi_8_1, ("vD",)),
    "bevan-3-3-slider-crank-instant-centre.yaml": (bevan_3_3, ()),
    "bevan-3-4a-slider-crank-accelerations.yaml": (lambda: bevan_3_4(0.0), ()),
    "bevan-3-4b-slider-crank-accelerating.yaml": (lambda: bevan_3_4(100.0), ()),
    "vp-singh-13-3-slider-crank-travel.yaml": (vp_singh_13_3, ()),
    "hibbeler-16-9-linkage-wheel.yaml": (hibbeler_16_9, ()),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_values_equal_the_independent_solution(name):
    solution, _ = CASES[name]
    expected = solution()
    path = os.path.join(MECHANISMS, name)
    mech = linkcli.load(path)
    names = [n for n in expected if n in mech.model.quantities or
             n.removesuffix("ddot").removesuffix("dot") in mech.model.quantities]
    assert len(names) >= 3, names
    values = mech.solve(names=names).values
    for n in names:
        assert float(values[n]) == pytest.approx(expected[n], rel=RTOL, abs=1e-9), n


@pytest.mark.parametrize("name", sorted(CASES))
def test_every_printed_value_is_keyed_and_checked(name):
    """Every value of the key is computed independently above, the file names its source,
    and its key passes; the values marked wrong are exactly the documented ones."""
    solution, known = CASES[name]
    path = os.path.join(MECHANISMS, name)
    report = check_file(path)
    assert report.error is None, report.error
    assert report.count("fail") == 0
    assert sorted(o.name for o in report.outcomes if o.status == "known") == sorted(known)
    expected = solution()
    assert {o.name for o in report.outcomes} <= set(expected)
    text = open(path, encoding="utf-8").read()
    assert text.startswith("title:") and "\nsource:" in text and "\nnotes:" in text
