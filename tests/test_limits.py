"""Limit positions and extremes (runs.limits), against closed forms computed here.

Crank-slider dead centres: crank and rod aligned, |OB| = l + r and l - r; an offset
slider's stroke sqrt((l + r)^2 - e^2) - sqrt((l - r)^2 - e^2) and its time ratio from the
two crank angles; a crank-rocker's limit angles from the law of cosines; the maximum piston
velocity against a fine grid of the closed-form position and finite differences; the named
quantities of the report through solve, the API and check; bad input located.
"""
from __future__ import annotations

import math
import os
import re

import numpy as np
import pytest

import linkcli
from linkcli.runs.limits import search
from linkcli.runs.check import check_file
from linkcli.cli import main
from linkcli.errors import InputError, SolveError

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REL = 1e-9


def slider_crank(r=100.0, l=300.0, e=0.0, rate=60.0, extra="", report="position: [xB]"):
    """Crank OA = r about O, rod AB = l, B on the line y = e (mm, deg, deg/s)."""
    return linkcli.loads(f"""
units: {{length: mm, angle: deg}}
frame: {{O: [0, 0]}}
points: {{A: [{r * 0.6}, {r * 0.8}], B: [{math.sqrt(l * l - (0.8 * r - e) ** 2) + 0.6 * r}, {e}]}}
links:
  OA: {{points: [O, A], length: {r}}}
  AB: {{points: [A, B], length: {l}}}
sliders:
  B: {{point: B, guide: {{y: {e}}}}}
driver: {{angle: [O, A], value: 53.13, rate: {rate}}}
quantities:
  phi: {{angle: [O, A]}}
  beta: {{angle: [A, B]}}
  vA: {{speed: A}}
  vB: {{speed: B}}
  aB: {{acceleration: B}}
{extra}
report:
  {report}
""", name="crank-slider.yaml")


def close(a, b, rel=REL):
    return abs(a - b) <= rel * max(abs(a), abs(b), 1.0)


# --- closed forms ----------------------------------------------------------------------------
def test_in_line_dead_centres_are_l_plus_and_minus_r():
    found = search.find(slider_crank().model, "xB")
    top, bottom = found.of("maximum"), found.of("minimum")
    assert len(top) == len(bottom) == 1
    assert close(top[0].value, 400.0) and close(bottom[0].value, 200.0)
    # crank and rod aligned: the crank along +x (0 deg) and against it (180 deg)
    assert abs(top[0].q - 0.0) <= 1e-9 and close(bottom[0].q, 180.0)
    assert close(found.stroke, 200.0) and close(found.time_ratio, 1.0)
    # at 60 deg/s each stroke takes half a turn: 3 s
    assert all(close(t, 3.0) for t in found.times)


@pytest.mark.parametrize("r, l, e", [(100.0, 300.0, 60.0), (80.0, 250.0, -90.0),
                                     (37.5, 112.0, 20.0)])
def test_offset_slider_stroke_and_time_ratio(r, l, e):
    found = search.find(slider_crank(r, l, e).model, "xB")
    outer, inner = math.sqrt((l + r) ** 2 - e * e), math.sqrt((l - r) ** 2 - e * e)
    # the outer dead centre: crank along O -> B; the inner: crank along B -> O
    q_out = math.degrees(math.atan2(e, outer)) % 360
    q_in = (math.degrees(math.atan2(e, inner)) + 180) % 360
    (top,), (bottom,) = found.of("maximum"), found.of("minimum")
    assert close(top.value, outer) and close(bottom.value, inner)
    assert abs(top.q - q_out) <= 1e-9 * 360 and abs(bottom.q - q_in) <= 1e-9 * 360
    assert close(found.stroke, outer - inner)
    forward = (q_out - q_in) % 360          # the crank's sweep from the inner to the outer
    ratio = max(forward, 360 - forward) / min(forward, 360 - forward)
    assert close(found.time_ratio, ratio) and ratio > 1.0
    assert close(found.sweeps[0], max(forward, 360 - forward))


def fourbar(a=40.0, b=120.0, c=90.0, d=110.0, driver="[O2, A]", value=60.0, extra=""):
    """A crank-rocker: crank O2A = a, coupler AB = b, rocker O4B = c, ground O2O4 = d."""
    qa = math.radians(value)
    A = complex(a * math.cos(qa), a * math.sin(qa))
    # B above the ground line, from the law of cosines on O4 A
    O4 = complex(d, 0)
    s = abs(A - O4)
    gamma = math.acos((c * c + s * s - b * b) / (2 * c * s))
    B = O4 + c * (A - O4) / s * complex(math.cos(-gamma), math.sin(-gamma))
    if B.imag < 0:
        B = O4 + c * (A - O4) / s * complex(math.cos(gamma), math.sin(gamma))
    return linkcli.loads(f"""
units: {{length: mm, angle: deg}}
frame: {{O2: [0, 0], O4: [{d}, 0]}}
points: {{A: [{A.real}, {A.imag}], B: [{B.real}, {B.imag}]}}
links:
  O2A: {{points: [O2, A], length: {a}}}
  AB: {{points: [A, B], length: {b}}}
  O4B: {{points: [O4, B], length: {c}}}
driver: {{angle: {driver}, value: {value}, rate: 10}}
quantities:
  psi: {{angle: [O4, B]}}
  theta: {{angle: [O2, A]}}
{extra}
report:
  position: [psi]
""", name="fourbar.yaml")


def test_crank_rocker_limit_angles_from_the_law_of_cosines():
    a, b, c, d = 40.0, 120.0, 90.0, 110.0
    found = search.find(fourbar(a, b, c, d).model, "psi")
    expected = {}
    for s, kind in ((b + a, "extended"), (b - a, "folded")):
        gamma = math.acos((d * d + c * c - s * s) / (2 * d * c))     # at O4, from O4 -> O2
        beta = math.acos((d * d + s * s - c * c) / (2 * d * s))      # at O2, of O2 -> B
        crank = beta if kind == "extended" else beta + math.pi
        expected[kind] = (math.degrees(math.pi - gamma), math.degrees(crank) % 360)
    (top,), (bottom,) = found.of("maximum"), found.of("minimum")
    # extended: B farthest from O2, the rocker leaning most towards +x ... the smaller angle
    assert close(bottom.value, expected["extended"][0]) and close(top.value, expected["folded"][0])
    assert abs(bottom.q - expected["extended"][1]) <= 1e-9 * 360
    assert abs(top.q - expected["folded"][1]) <= 1e-9 * 360
    assert close(found.stroke, expected["folded"][0] - expected["extended"][0])
    sweep = (expected["folded"][1] - expected["extended"][1]) % 360
    assert close(found.time_ratio, max(sweep, 360 - sweep) / min(sweep, 360 - sweep))


def test_max_piston_velocity_against_a_fine_grid_and_finite_differences():
    r, l, rate = 100.0, 350.0, 120.0          # mm, deg/s
    found = search.find(slider_crank(r, l, rate=rate).model, "xBdot")

    def x(theta):                               # the piston's position, closed form
        return r * np.cos(theta) + np.sqrt(l * l - (r * np.sin(theta)) ** 2)

    h = 1e-5
    theta = np.linspace(0, 2 * np.pi, 2_000_001)
    speed = (x(theta + h) - x(theta - h)) / (2 * h) * math.radians(rate)   # mm/s
    j = int(np.argmax(speed))
    (top,), (bottom,) = found.of("maximum"), found.of("minimum")
    assert close(top.value, float(speed[j]), 1e-8)
    assert abs(top.q - math.degrees(theta[j])) <= 2 * math.degrees(theta[1])
    assert close(bottom.value, float(np.min(speed)), 1e-8)
    # the piston's acceleration (finite differences of the velocity) is zero there
    t = math.radians(top.q)
    accel = (x(t + 1e-4) - 2 * x(t) + x(t - 1e-4)) / 1e-8
    assert abs(accel) <= 1e-5 * r
    # and the speed |v_B| has the same maxima, its minima 0 at the dead centres
    speeds = search.find(slider_crank(r, l, rate=rate).model, "vB")
    assert sorted(round(e.q, 6) for e in speeds.of("minimum")) == [0.0, 180.0]
    assert all(close(e.value, abs(top.value)) for e in speeds.of("maximum"))


def test_roots_are_found_to_the_tolerance_off_the_grid():
    # an offset that puts the dead centres between grid values; the rate at them is zero
    link = slider_crank(100.0, 300.0, 37.0)
    found = search.find(link.model, "xB")
    for e in found.extremes:
        rates = link.solve(q=[e.q - 2e-10, e.q + 2e-10], names=["xBdot"])
        low, high = rates.values["xBdot"]
        assert low * high < 0           # the rate changes sign within 2e-10 deg


# --- named quantities ------------------------------------------------------------------------
NAMED = """
  top: {maximum: xB}
  bottom: {minimum: xB}
  where: {at_maximum: xB}
  travel: {stroke: xB}
  ratio: {time_ratio: xB}
  t_work: {stroke_time: xB, component: working}
  t_back: {stroke_time: xB, component: return}
  vmax: {maximum: vB}
  half: {maximum: xB, from: -90, to: 90}
"""


def test_named_limits_print_in_the_files_units_at_every_driver_value():
    r, l, e = 100.0, 300.0, 60.0
    link = slider_crank(r, l, e, extra=NAMED,
                        report="position: [top, bottom, where, travel, ratio, t_work, t_back, "
                        "half]\n  velocity: [vB, vmax]")
    model = link.model
    result = link.solve(q=[10.0, 20.0, 30.0])
    outer, inner = math.sqrt((l + r) ** 2 - e * e), math.sqrt((l - r) ** 2 - e * e)
    assert np.allclose(result.values["top"], outer, rtol=REL)
    assert np.allclose(result.values["bottom"], inner, rtol=REL)
    assert np.allclose(result.values["travel"], outer - inner, rtol=REL)
    assert np.allclose(result.values["half"], outer, rtol=REL)
    assert result.units["travel"] == "mm" and result.units["where"] == "deg"
    assert result.units["ratio"] == "" and result.units["t_work"] == "s"
    assert np.shape(result.values["ratio"]) == (3,)
    found = search.find(model, "xB")
    assert np.allclose(result.values["t_work"] + result.values["t_back"], 6.0, rtol=REL)
    assert np.allclose(result.values["ratio"], found.time_ratio, rtol=REL)
    assert result.values["vB"][0] < result.values["vmax"][0]
    # the ordinary quantities are those of the plain solve
    plain = link.solve(q=[10.0, 20.0, 30.0], names=["vB"])
    assert np.array_equal(plain.values["vB"], result.values["vB"])


def test_solve_prints_named_limits(capsys):
    path = os.path.join(ROOT, "mechanisms", "khurmi-5-2-quick-return.yaml")
    assert main(["solve", path]) == 0
    out = capsys.readouterr().out
    assert "tilt_max =     30.000 deg" in out and "stroke   =    450.000 mm" in out


@pytest.mark.parametrize("name", ["khurmi-5-2-quick-return.yaml",
                                  "khurmi-15-4-piston-extremes.yaml",
                                  "khurmi-15-3-max-piston-velocity.yaml"])
def test_textbook_keys(name):
    report = check_file(os.path.join(ROOT, "mechanisms", name))
    assert report.error is None
    assert report.outcomes and all(o.status in ("pass", "known") for o in report.outcomes)


# --- what is not an extreme ------------------------------------------------------------------
def test_constant_and_monotonic_quantities_have_no_extreme():
    """A constant quantity (to rounding) has its constant as maximum and minimum, stroke 0,
    and no extreme at any position; a monotonic one has none."""
    model = slider_crank().model
    flat = search.find(model, "yB")
    assert not flat.extremes and flat.constant == 0.0 and flat.stroke == 0.0
    speed = 100.0 * math.radians(60.0)              # the crank pin's speed r qdot, mm/s
    for name, value in (("vA", speed), ("yBdot", 0.0)):
        still = search.find(model, name)
        assert not still.extremes and still.constant == pytest.approx(value, rel=1e-12), name
    turning = search.find(model, "phi")
    assert not turning.extremes and "keeps its sign" in turning.why and "rises" in turning.why


def test_undefined_limits_are_located_solve_errors():
    link = slider_crank(extra="  flat: {at_maximum: yB}\n  ratio: {time_ratio: xB, from: -90, "
                        "to: 200}\n  only: {minimum: xB, from: -90, to: 90}",
                        report="position: [flat]")
    with pytest.raises(SolveError, match=r"'flat' \(where the maximum is of yB\) is undefined: "
                       r"yB is constant \(0.0000 mm\) over q = 0..360 deg, its rate 0 to rounding: "
                       "its maximum and minimum are at every position"):
        link.solve()
    with pytest.raises(SolveError, match="is not a full turn of the crank"):
        link.solve(names=["ratio"])
    with pytest.raises(SolveError, match=r"has no minimum over q = -90..90 deg, only a maximum "
                       "at q = 0 deg"):
        link.solve(names=["only"])


def test_a_rocker_driver_is_limited_to_where_it_assembles():
    # driven by the rocker O4B, the crank-rocker assembles for part of the turn only: the
    # crank's angle rises through 180 deg in one window, falls through 0 in the other
    link = fourbar(driver="[O4, B]", value=100.0,
                   extra="  ratio: {time_ratio: xA}\n  top: {maximum: xA}\n"
                   "  flat: {maximum: theta}")
    found = search.find(link.model, "xA")
    assert not found.whole and any("cannot assemble" in n for n in found.notes)
    assert [e.kind for e in found.extremes] == ["minimum", "maximum"]
    assert close(found.of("minimum")[0].value, -40.0) and close(found.stroke, 80.0)
    with pytest.raises(SolveError, match="the crank cannot make a full turn: cannot assemble"):
        link.solve(names=["ratio"])
    result = link.solve(names=["top"])
    assert close(float(result.values["top"]), 40.0)
    assert any("where the mechanism assembles" in str(c) for c in result.cautions)
    with pytest.raises(SolveError, match=r"theta has no extreme .* keeps its sign: it rises .*"
                       r"cannot assemble for q in \["):
        link.solve(names=["flat"])


# --- bad input -------------------------------------------------------------------------------
@pytest.mark.parametrize("spec, message", [
    ("{maximum: nope}", r"'nope' is not a defined quantity"),
    ("{maximum: aB}", r"the extremes of 'aB' are where its rate is zero, and 'aB' is an "
                      r"acceleration, whose rate \(the jerk\) is not computed"),
    ("{maximum: xBddot}", r"'xBddot' is an acceleration"),
    ("{stroke: xBdot}", r"a stroke is of a position quantity"),
    ("{stroke_time: xB}", r"component is working or return, got None"),
    ("{maximum: xB, component: x}", r"a maximum quantity has no component"),
    ("{maximum: xB, from: 10}", r"give both 'from' and 'to'"),
    ("{maximum: xB, from: 10, to: 5}", r"'to' \(5\) must be larger than 'from' \(10\)"),
    ("{maximum: xB, minimum: xB}", r"give exactly one kind of limit, not maximum and minimum"),
    ("{maximum: [xB]}", r"expected a quantity name"),
])
def test_bad_limit_quantities_are_located(spec, message):
    with pytest.raises(InputError, match=message) as caught:
        slider_crank(extra=f"  bad: {spec}")
    assert "quantities.bad" in str(caught.value) and "crank-slider.yaml:" in str(caught.value)


def test_a_limit_of_a_limit_is_refused():
    with pytest.raises(InputError, match="is a limit of the motion itself"):
        slider_crank(extra="  top: {maximum: xB}\n  bad: {maximum: top}")


def test_ranges_and_names_on_the_command_line(capsys):
    path = os.path.join(ROOT, "mechanisms", "khurmi-5-2-quick-return.yaml")
    assert main(["limits", path, "--of", "nope"]) == 2
    assert "'nope' is not a quantity of this file" in capsys.readouterr().err
    assert main(["limits", path, "--of", "xP", "--from", "10"]) == 2
    assert "give both ends of the range" in capsys.readouterr().err
    assert main(["limits", path, "--of", "xP", "--from", "10", "--to", "500"]) == 2
    assert "is longer than a turn" in capsys.readouterr().err
    assert main(["limits", path, "--of", "xP", "--from", "200", "--to", "340",
                 "--format", "csv"]) == 0
    out = capsys.readouterr().out
    assert "xP,minimum,210.000,-225.000,mm" in out and "xP,maximum,330.000,225.000,mm" in out
    assert "time_ratio" not in out          # not a full turn
    # a sweep lists what depends on the driver, and refuses a limit
    assert main(["sweep", path, "--from", "0", "--to", "10", "--steps", "1"]) == 0
    assert main(["sweep", path, "--names", "ratio", "--from", "0", "--to", "10",
                 "--steps", "1"]) == 2
    assert "'ratio' is a limit of the motion" in capsys.readouterr().err
    assert main(["plot", path, "--sweep", "0:360:4", "--y", "ratio", "-o", "never.png"]) == 2
    assert "key '--y': 'ratio' is a limit of the motion" in capsys.readouterr().err
    assert not os.path.exists("never.png")


def test_a_length_driver_needs_a_range():
    model = linkcli.load(os.path.join(ROOT, "mechanisms", "padova-2020-07.yaml")).model
    with pytest.raises(InputError, match="the driver is a length, which has no natural range"):
        search.find(model, "phi3")


# --- constant up to rounding, dwells and toggles inside the range ---------------------------
DATA = os.path.join(ROOT, "tests", "data")


def test_a_constant_rate_has_its_constant_as_maximum_and_no_position(capsys):
    """A parallelogram's rocker turns with the crank: phi3dot = qdot = 10 deg/s exactly.  Its
    sampled rate is rounding (1e-14), whose signs listed hundreds of extremes and an
    at_maximum that rounding picked (20.489 deg)."""
    path = os.path.join(DATA, "parallelogram_atmax.yaml")
    link = linkcli.load(path)
    assert link.solve(names=["wmax"]).values["wmax"] == pytest.approx(10.0, rel=1e-12)
    with pytest.raises(SolveError, match="phi3dot is constant .* at every position"):
        link.solve(names=["wmax_at"])
    assert main(["solve", path]) == 3
    assert main(["limits", path, "--of", "phi3dot", "--from", "10", "--to", "170",
                 "--format", "json"]) == 0
    import json
    found = json.loads(capsys.readouterr().out)[0]
    assert found["extremes"] == [] and found["constant"] == pytest.approx(10.0, rel=1e-12)


def _crossed_phi2_maximum():
    """The largest angle of BC on the parallelogram's crossed branch (q in 180..360 deg, C
    the intersection of the circles about B and D that is not B + 100, the parallelogram's),
    from a fine grid refined by golden sections: an independent closed form."""
    def phi2(q):
        b = 40 * np.exp(1j * np.radians(q))
        d = 100.0
        dist = abs(d - b)
        along = (100 ** 2 - 40 ** 2 + dist ** 2) / (2 * dist)
        across = np.sqrt(100 ** 2 - along ** 2)
        u = (d - b) / dist
        both = np.array([b + u * (along + 1j * across), b + u * (along - 1j * across)])
        c = np.where(abs(both[0] - b - 100) > abs(both[1] - b - 100), both[0], both[1])
        return np.degrees(np.angle(c - b))
    q = np.linspace(180.5, 359.5, 20001)
    values = phi2(q)
    i = int(np.argmax(values))
    a, b = q[i - 1], q[i + 1]
    g = (math.sqrt(5) - 1) / 2
    for _ in range(80):
        c, d = b - g * (b - a), a + g * (b - a)
        if phi2(c) > phi2(d):
            b = d
        else:
            a = c
    return (a + b) / 2, float(phi2((a + b) / 2))


def test_limits_over_a_change_point_list_the_extremes_only(capsys):
    """Over a whole turn the parallelogram passes its change points (0 and 180 deg) and the
    closed form goes on along the crossed branch: phi2 is 0 up to rounding on the first
    half and has one maximum on the second; limits was an internal error (exit 70)."""
    path = os.path.join(DATA, "parallelogram.yaml")
    assert main(["limits", path, "--format", "json"]) == 0
    import json
    found = {f["quantity"]: f for f in json.loads(capsys.readouterr().out)}
    q_max, phi2_max = _crossed_phi2_maximum()
    assert [e["kind"] for e in found["phi2"]["extremes"]] == ["maximum"]
    extreme = found["phi2"]["extremes"][0]
    assert extreme["q"] == pytest.approx(q_max, abs=1e-6)
    assert extreme["value"] == pytest.approx(phi2_max, abs=1e-9)
    assert found["phi3"]["extremes"] == [] and found["phi3dot"]["extremes"] == []
    assert any("constant (10.0000 deg/s) for q in 0.1..179.9" in m
               for m in found["phi3dot"]["messages"])


def test_limits_over_a_toggle_inside_the_range(capsys):
    """docs/examples/toggle.yaml: crank and rod of equal length, so C stays at the crank's
    pivot from 90 to 270 deg on the branch the closed form keeps (x_C = 50 cos q +
    50 |cos q| mm).  limits was an internal error (exit 70, the rows left out at the
    toggles lost the driver's rates); the stretch where x_C is 0 to rounding is one held
    minimum, never noise."""
    path = os.path.join(ROOT, "docs", "examples", "toggle.yaml")
    assert main(["limits", path, "--format", "json"]) == 0
    import json
    found = {f["quantity"]: f for f in json.loads(capsys.readouterr().out)}
    assert found["xC"]["extremes"] == [{"kind": "maximum", "q": 0.0, "value": 100.0,
                                        "span": None}]
    assert found["xCdot"]["extremes"] == []
    dwell = search.find(linkcli.load(path).model, "xC", 0.05, 359.95)
    assert [e.kind for e in dwell.extremes] == ["minimum"]
    (held,) = dwell.extremes
    step = (359.95 - 0.05) / search.GRID
    assert held.value == 0.0 and abs(held.span[0] - 90) < step and abs(held.span[1] - 270) < step
    link = linkcli.loads(open(path).read().replace(
        "report:", "quantities:\n  low: {at_minimum: xC, from: 0.05, to: 359.95}\nreport:"))
    with pytest.raises(SolveError, match=r"xC holds its minimum \(0.0000 mm\) over q = "
                       r"90\.\d+..26\d\.\d+ deg"):
        link.solve(names=["low"])


def test_a_run_across_the_turns_end_is_described_to_its_end():
    """docs/examples/toggle.yaml: x_C = 100 cos q mm outside 90..270 deg, so its rate
    xCdot = -100 sin q qdot (qdot = 10 deg/s in rad/s) falls from the toggle at 270 deg
    through 360 to the toggle at 90 deg (no extreme: it jumps at the toggles).  The reason
    stopped at 360 deg, at 0 mm/s, as if the rate fell to 0 only."""
    path = os.path.join(ROOT, "docs", "examples", "toggle.yaml")
    found = search.find(linkcli.load(path).model, "xCdot", None, None)
    assert not found.extremes
    match = re.search(r"it falls from (\S+) to (\S+) mm/s \(by \S+\) as q goes from (\S+) to "
                      r"(\S+) \(through 360\) deg", found.why)
    assert match, found.why
    start, end = float(match[3]), float(match[4])
    assert 270 < start < 271 and 89 < end < 90
    for value, q in ((match[1], start), (match[2], end)):
        assert float(value) == pytest.approx(-100 * math.sin(math.radians(q)) * math.radians(10),
                                             abs=1e-4)
