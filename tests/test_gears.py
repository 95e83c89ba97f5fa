"""Gears by their teeth (docs/schema.md, "gears"): trains against Willis's formula written
here from the tooth counts, the contact ratio against the path of contact measured on the
line of action (where it cuts the addendum circles), the fewest teeth against Khurmi's
formula as the book prints it, and the refusals of teeth that cannot be cut or do not mesh.
Nothing expected here is taken from linkcli's output."""
from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

import linkcli
from linkcli.runs.check import check_file

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import run  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHIPPED = ["gate-me-2009-epicyclic-arm.yaml", "gate-me-2014-compound-train.yaml",
           "khurmi-13-epicyclic-annulus-fixed.yaml", "shigley-13-1-diametral-pitch.yaml",
           "rack-pinion-fewest-teeth.yaml"]


def shipped(name):
    return os.path.join(ROOT, "mechanisms", name)


@pytest.mark.parametrize("name", SHIPPED)
def test_shipped_gear_problems_agree_with_their_printed_keys(name):
    report = check_file(shipped(name))
    assert report.error is None and report.count("fail") == 0 and report.count("pass") >= 1, \
        report


def test_epicyclic_arm_follows_willis_over_turns():
    """GATE ME 2009: ring fixed, (Ns - Na) / (Nr - Na) = -zr / zs, so Na = Ns zs / (zs + zr);
    the planet, (Np - Na) / (Ns - Na) = -zs / zp.  The arm's and the planet's turns are these
    rates integrated from the figure (any number of turns of the sun)."""
    zs, zp, zr = 20, 40, 100
    mech = linkcli.load(shipped("gate-me-2009-epicyclic-arm.yaml"))
    q = np.array([0.0, 250.0, 1170.0, 2160.0])           # deg of the sun
    rate = np.array([60.0, -35.0, 7.0, 120.0])           # rpm
    values = mech.solve(q=q, qdot=rate, names=["arm_turndot", "arm_turn"]).values
    na = rate * zs / (zs + zr)
    assert np.asarray(values["arm_turndot"]) == pytest.approx(na, rel=1e-10)
    turn = (90.0 + q * zs / (zs + zr)) % 360.0           # the arm drawn at 90 deg
    got = np.asarray(values["arm_turn"]) % 360.0
    assert np.minimum(abs(got - turn), 360 - abs(got - turn)) == pytest.approx(0, abs=1e-8)


def test_compound_train_speed_is_the_product_of_tooth_ratios():
    """GATE ME 2014: N5 = N2 (z2 / z3)(z4 / z5), two external meshes: the same sense."""
    mech = linkcli.load(shipped("gate-me-2014-compound-train.yaml"))
    values = mech.solve(q=np.array([0.0, 77.0]), qdot=np.array([1200.0, -90.0]),
                        names=["turn5dot", "a23", "a45"]).values
    assert np.asarray(values["turn5dot"]) == pytest.approx(
        np.array([1200.0, -90.0]) * (20 / 40) * (15 / 30), rel=1e-10)
    # centre distances from the teeth: m (z1 + z2) / 2
    assert np.asarray(values["a23"]) == pytest.approx(2 * (20 + 40) / 2, rel=1e-12)
    assert np.asarray(values["a45"]) == pytest.approx(4 * (15 + 30) / 2, rel=1e-12)


def test_annulus_train_speeds_from_willis():
    """Arm driven, annulus A fixed: (NC - Na) / (NA - Na) = -zA / zC and
    (NB - Na) / (NC - Na) = -zC / zB, zB = (zA - zC) / 2."""
    za, zc = 72, 32
    zb = (za - zc) // 2
    mech = linkcli.load(shipped("khurmi-13-epicyclic-annulus-fixed.yaml"))
    na = np.array([18.0, -5.0])
    values = mech.solve(q=np.array([90.0, 200.0]), qdot=na,
                        names=["turnCdot", "turnBdot"]).values
    nc = na * (1 + za / zc)
    nb = na - (nc - na) * zc / zb
    assert np.asarray(values["turnCdot"]) == pytest.approx(nc, rel=1e-10)
    assert np.asarray(values["turnBdot"]) == pytest.approx(nb, rel=1e-10)


def path_on_line_of_action(r1, r2, add1, add2, phi, internal=False):
    """The length of the line of action between where it cuts the two addendum circles
    (measured, not the textbook's formula): the pitch point at the origin, the line of
    action through it at phi, the centres on the y axis."""
    u = complex(math.cos(phi), math.sin(phi))
    c1 = complex(0, -r1)
    c2 = complex(0, r2) if not internal else complex(0, -r2)
    tips = (r1 + add1, r2 + add2 if not internal else r2 - add2)

    def cuts(c, rho):
        # |t u - c|^2 = rho^2: t^2 - 2 t Re(conj(u) c) + |c|^2 - rho^2 = 0
        b = (u.conjugate() * c).real
        disc = math.sqrt(b * b - abs(c) ** 2 + rho ** 2)
        return b - disc, b + disc

    ends = [cuts(c1, tips[0]), cuts(c2, tips[1])]
    # contact runs between the two circles' cuts that bracket the pitch point
    start = max(min(t for t in e if t <= 0) for e in ends) if not internal else None
    if internal:
        starts = [t for t in ends[0] if t <= 0] + [t for t in ends[1] if t <= 0]
        stops = [t for t in ends[0] if t >= 0] + [t for t in ends[1] if t >= 0]
        return min(stops) - max(starts)
    stop = min(max(t for t in e if t >= 0) for e in ends)
    return stop - start


@pytest.mark.parametrize("z1, z2, module, addendum, phi, internal", [
    (30, 80, 12.0, 10.0, 20.0, False),      # Khurmi's pair of 12 mm module, 10 mm addenda
    (20, 60, 8.0, 8.0, 20.0, False),
    (16, 40, 25.4 / 2, 25.4 / 2, 20.0, False),
    (18, 90, 5.0, 5.0, 25.0, True),         # a pinion in a ring
    (24, 60, 3.0, 3.0, 14.5, False)])
def test_contact_ratio_is_the_path_of_contact_over_the_base_pitch(z1, z2, module, addendum,
                                                                  phi, internal):
    """eps = path of contact / (pi m cos phi); the path measured on the line of action."""
    text = f"""
units: {{length: mm, angle: deg}}
gears:
  p: {{teeth: {z1}, module: {module}, addendum: {addendum}, pressure_angle: {phi}}}
  w: {{teeth: {z2}, module: {module}, addendum: {addendum}, pressure_angle: {phi},
       internal: {str(internal).lower()}}}
frame: {{O: [0, 0]}}
points: {{A: [10, 0]}}
links: {{crank: {{points: [O, A], length: 10}}}}
driver: {{angle: [O, A], value: 0, rate: 1}}
quantities:
  e: {{contact_ratio: [p, w]}}
  a: {{centre_distance: [p, w]}}
report: {{position: [e, a]}}
"""
    values = linkcli.loads(text).solve().values
    r1, r2 = module * z1 / 2, module * z2 / 2
    path = path_on_line_of_action(r1, r2, addendum, addendum, math.radians(phi), internal)
    expected = path / (math.pi * module * math.cos(math.radians(phi)))
    assert float(values["e"]) == pytest.approx(expected, rel=1e-12)
    assert float(values["a"]) == pytest.approx(r2 - r1 if internal else r1 + r2, rel=1e-12)


@pytest.mark.parametrize("phi", [14.5, 20.0, 25.0])
@pytest.mark.parametrize("ratio", [None, 1, 3, 4.5])
def test_fewest_teeth_against_khurmi(phi, ratio):
    """Khurmi, 12.23: t = 2 A_W / (G (sqrt(1 + (1/G)(1/G + 2) sin^2 phi) - 1)); with a rack
    t = 2 A_R / sin^2 phi.  The pinion's own teeth (12 here) do not enter; G is the wheel's
    teeth over 12."""
    s2 = math.sin(math.radians(phi)) ** 2
    wheel = "" if ratio is None else \
        f"  w: {{teeth: {12 * ratio:g}, module: 2, pressure_angle: {phi}}}\n"
    text = f"""
units: {{length: mm, angle: deg}}
gears:
  p: {{teeth: 12, module: 2, pressure_angle: {phi}}}
{wheel}frame: {{O: [0, 0]}}
points: {{A: [10, 0]}}
links: {{crank: {{points: [O, A], length: 10}}}}
driver: {{angle: [O, A], value: 0, rate: 1}}
quantities:
  z: {{min_teeth: p{'' if ratio is None else ', with: w'}}}
report: {{position: [z]}}
"""
    got = float(linkcli.loads(text).solve().values["z"])
    expected = 2 / s2 if ratio is None else \
        2 / (ratio * (math.sqrt(1 + (1 / ratio) * (1 / ratio + 2) * s2) - 1))
    assert got == pytest.approx(expected, rel=1e-12)
    if ratio is None:
        assert phi != 20.0 or math.ceil(got) == 18          # the books' 18 teeth


def test_diametral_pitch_is_the_module_in_the_other_way():
    """P teeth per inch of diameter is a module of 1/P in: the same radii, the same answers,
    whichever the file gives (other units: tests/test_invariance_units.py)."""
    text = open(shipped("shigley-13-1-diametral-pitch.yaml"), encoding="utf-8").read()
    metric = text.replace("diametral_pitch: P", "module: 1/P")
    assert metric.count("module: 1/P") == 2
    imperial = linkcli.loads(text).solve().values
    values = linkcli.loads(metric).solve().values
    assert float(values["C"]) == pytest.approx(float(imperial["C"]), rel=1e-12)
    assert float(values["eps"]) == pytest.approx(float(imperial["eps"]), rel=1e-12)
    assert float(imperial["C"]) == pytest.approx((16 + 40) / (2 * 2), rel=1e-12)   # in


def _bad(tmp_path, name, old, new):
    text = open(shipped(name), encoding="utf-8").read()
    assert old in text
    path = tmp_path / name
    path.write_text(text.replace(old, new))
    return run(["solve", path])


@pytest.mark.parametrize("old, new, words", [
    ("g3: {teeth: 40, module: m23}", "g3: {teeth: 40, module: 2.5}",
     ["rolling.mesh23", "g3 (module 2.5 mm)", "g2 (module 2 mm)", "do not mesh"]),
    ("g3: {teeth: 40, module: m23}", "g3: {teeth: 40.5, module: m23}",
     ["gears.g3.teeth", "whole number", "40.5"]),
    ("g2: {teeth: 20, module: m23}", "g2: {teeth: 0, module: m23}",
     ["gears.g2.teeth", "whole number above 0"]),
    ("g4: {teeth: 15, module: m45}", "g4: {teeth: 15, module: m45, diametral_pitch: 2}",
     ["gears.g4", "not both"]),
    ("g5: {teeth: 30, module: m45}", "g5: {teeth: 30}", ["gears.g5", "module"]),
    ("mesh45: {disc: g5, on:", "mesh45: {disc: g5, radius: 61, on:",
     ["rolling.mesh45.radius", "not the pitch radius of gear g5", "60 mm"])])
def test_teeth_that_cannot_be_cut_or_do_not_mesh_are_refused(tmp_path, old, new, words):
    code, out, err = _bad(tmp_path, "gate-me-2014-compound-train.yaml", old, new)
    assert code == 2 and "Traceback" not in err
    assert "gate-me-2014-compound-train.yaml:" in err          # file and line
    for word in words:
        assert word in err, (word, err)
    # the failed gear's own error only: no echo of it where it is used
    assert err.count("undefined gear") == 0


def test_diametral_pitches_that_differ_are_named_with_both_values(tmp_path):
    code, _, err = _bad(tmp_path, "shigley-13-1-diametral-pitch.yaml",
                        "gear: {teeth: 40, diametral_pitch: P", "gear: {teeth: 40, "
                        "diametral_pitch: 3")
    assert code == 2
    assert "diametral pitch 3 1/in" in err and "diametral pitch 2 1/in" in err
    assert "quantities.C.centre_distance" in err and "keys" not in err
