"""Units of answers at the edges: frequencies in expressions, `unit:` on vibration answers,
rates of names ending in 'd', critical damping, and the units part of the invariance layer
for expressions.

Each file of tests/data/trust3/ reproduces a defect; its header says what is right, and
the tests assert that (numbers from the header or a closed form written here, never from
linkcli's own output).  The invariance tests write vibration and linkage files whose
expression answers read one frequency or speed shown in rad/s, Hz and rpm, and check
that they agree in SI with factors written here, independently of linkcli's tables.
"""
from __future__ import annotations

import math
import os

import pytest

import linkcli
from tests.cli_helpers import run

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data", "trust3")
TWO_PI = 2 * math.pi
#: SI value (rad/s) of one unit, written here from the definitions, not read from linkcli:
#: one cycle is 2 pi rad, a minute 60 s, a degree pi/180 rad
SI = {"rad/s": 1.0, "Hz": TWO_PI, "rpm": TWO_PI / 60, "deg/s": math.pi / 180, "rev/s": TWO_PI,
      "1/s": 1.0}


def data(name):
    return os.path.join(DATA, name)


def printed(out: str) -> dict:
    """{name: (number, unit)} of the lines 'name = number unit' that ``solve`` prints."""
    found = {}
    for line in out.splitlines():
        name, eq, rest = line.partition("=")
        if not eq or not name.startswith("  "):
            continue
        words = rest.split()
        try:
            found[name.strip()] = (float(words[0]), " ".join(words[1:]))
        except (ValueError, IndexError):
            continue
    return found


# --- frequencies in expressions: rad/s is SI, 1 Hz = 2 pi rad/s, 1 rpm = 2 pi/60 rad/s --------
def test_expression_frequencies_in_hz_rpm_and_rad_s_are_one_frequency():
    """expr-frequency-units.yaml: w1 = 2 pi rad/s = 1 Hz = 60 rpm: w1 shown in Hz is 1,
    f1 in rad/s 6.2832, w1 - f1 = 0, w1/f1 = 1, both in rpm 60 (header, 4 decimals)."""
    code, out, err = run(["solve", data("expr-frequency-units.yaml")])
    assert code == 0, err
    v = printed(out)
    assert v["w1"] == (6.2832, "rad/s") and v["f1"] == (1.0, "Hz")
    assert v["w_in_Hz"] == (1.0, "Hz")
    assert v["f_in_rads"] == (6.2832, "rad/s")
    assert v["diff"][0] == 0 and v["diff"][1] == "rad/s"
    assert v["ratio"] == (1.0, "")
    assert v["w_rpm"] == (60.0, "rpm") and v["f_rpm"] == (60.0, "rpm")
    # one frequency: any expression of it is the same whichever way it is shown
    assert v["T"] == v["Tw"] == (round(1 / TWO_PI, 4), "s")
    assert v["two_pi_f"] == (round(TWO_PI * TWO_PI, 4), "rad/s")


def test_expression_angular_speed_of_a_crank_in_rpm_and_hz():
    """expr-rpm-linkage.yaml: qdot = 360 deg/s = 1 turn/s = 60 rpm = 1 Hz (header)."""
    code, out, err = run(["solve", data("expr-rpm-linkage.yaml")])
    assert code == 0, err
    v = printed(out)
    assert v["q_degs"] == (360.0, "deg/s")
    assert v["q_rads"] == (round(TWO_PI, 4), "rad/s")
    assert v["q_rpm"] == (60.0, "rpm")
    assert v["q_Hz"] == (1.0, "Hz")
    assert v["b_rad"] == (round(math.radians(v["b_deg"][0]), 4), "rad")


# --- the units part of the invariance layer for expressions -------------------------------
SHOWN = ("rad/s", "Hz", "rpm", "1/s")

VIBRATION = """title: "mass on a spring, one frequency shown in several units"
units: {length: m, angle: deg, stiffness: N/m, frequency: FILE}
params: {m: 2, ks: 800, fe: 3}
frame: {B: [0, 0]}
points: {P: [0, 0.3]}
sliders: {body: {point: P, guide: {x: 0}}}
coordinates: {y: {y: P}}
springs: {s: {between: [B, P], k: ks, preload: static}}
dynamics: {gravity: 9.81, masses: {P: m}}
excitation: {frequency: fe, forces: {F: {at: P, y: 1}}}
quantities:
  w_rad: {natural_frequency: 1, unit: rad/s}
  w_Hz: {natural_frequency: 1, unit: Hz}
  w_rpm: {natural_frequency: 1, unit: rpm}
  w_file: {natural_frequency: 1}
  W: {forcing_frequency: true}
EXPRESSIONS
report:
  vibration: [NAMES]
"""

LINKAGE = """title: "a crank turning at one speed, read in several units"
units: {length: m, angle: deg, angular_rate: FILE}
frame: {O: [0, 0]}
points: {A: [0.3, 0.4]}
links:
  crank: {points: [O, A], length: 0.5}
driver: {angle: [O, A], value: 53, rate: RATE}
quantities:
  turn: {rotation: crank}
EXPRESSIONS
report:
  velocity: [NAMES]
"""


def _expressions(sources) -> dict:
    """{name: (expression, unit, what it is)}: each source shown in every unit of
    :data:`SHOWN` (1: the frequency w itself), its period (-1: 2 pi/w), its ratio to each
    source (0: the number 1) and its difference from each (None: 0 rad/s)."""
    out = {}
    for i, src in enumerate(sources):
        for unit in SHOWN:
            out[f"e{i}_{unit.replace('/', '_')}"] = (src, unit, 1.0)
        out[f"T{i}"] = (f"2*pi/{src}", "s", -1.0)
        for j, other in enumerate(sources):
            out[f"r{i}_{j}"] = (f"{src}/{other}", None, 0.0)
            out[f"d{i}_{j}"] = (f"{src} - {other}", "rad/s", None)
    return out


def _file(template, expressions, **fill) -> str:
    lines = []
    for name, (text, unit, _) in expressions.items():
        lines.append(f'  {name}: {{expr: "{text}"' + (f", unit: {unit}}}" if unit else "}"))
    text = template.replace("EXPRESSIONS", "\n".join(lines))
    text = text.replace("NAMES", ", ".join(expressions))
    for key, value in fill.items():
        text = text.replace(key, str(value))
    return text


def mismatches(result, expressions, w) -> list:
    """The expressions whose value, taken to SI with the factors of :data:`SI`, is not what
    the frequency ``w`` (rad/s) makes it: w itself, the period 2 pi/w, the ratio 1 and the
    difference 0 of one frequency read in two units."""
    wrong = []
    for name, (_, unit, power) in expressions.items():
        value = float(result.values[name])
        if result.units[name] != (unit or ""):
            wrong.append((name, f"shown in {result.units[name]!r}, not {unit!r}"))
            continue
        if power is None:                               # a difference: 0
            ok = abs(value) <= 1e-9 * w
            expected = 0.0
        else:
            factor = SI.get(unit, 1.0)
            expected = w if power == 1 else (TWO_PI / w if power == -1 else 1.0)
            ok = math.isclose(value * factor, expected, rel_tol=1e-9)
        if not ok:
            wrong.append((name, f"{value} {unit or ''} is not {expected} in SI"))
    return wrong


def vibration_case(file_unit):
    """A 2 kg mass on 800 N/m (w = 20 rad/s) excited at fe = 3 of the file's frequency unit;
    expressions read the natural frequency shown in rad/s, Hz, rpm and the file's unit."""
    exprs = _expressions(["w_rad", "w_Hz", "w_rpm", "w_file"])
    forcing = {"Wr": ("W/w_rad", None, None), "WH": ("W/w_Hz", None, None)}
    text = _file(VIBRATION, {**exprs, **forcing}, FILE=file_unit)
    result = linkcli.loads(text, name="frequencies.yaml").solve()
    w = math.sqrt(800 / 2)
    ratio = 3 * SI[file_unit] / w                      # Omega / w, Omega = 3 file units
    forced = [n for n in forcing if not math.isclose(float(result.values[n]), ratio,
                                                     rel_tol=1e-9)]
    return mismatches(result, exprs, w) + forced


def linkage_case(file_unit, rate):
    """A crank at ``rate`` of the file's angular-rate unit: the expressions read its rate
    (qdot) and its rotation's (turndot), shown in rad/s, Hz, rpm and 1/s."""
    exprs = _expressions(["qdot", "turndot"])
    text = _file(LINKAGE, exprs, FILE=file_unit, RATE=rate)
    result = linkcli.loads(text, name="speeds.yaml").solve()
    return mismatches(result, exprs, rate * SI[file_unit])


@pytest.mark.parametrize("file_unit", ["rad/s", "Hz", "rpm"])
def test_vibration_expressions_read_one_frequency_in_every_unit(file_unit):
    assert vibration_case(file_unit) == []


@pytest.mark.parametrize("file_unit, rate", [("deg/s", 360), ("rpm", 120), ("rad/s", 7),
                                             ("rev/s", 2)])
def test_linkage_expressions_read_one_speed_in_every_unit(file_unit, rate):
    assert linkage_case(file_unit, rate) == []


def _counting_cycles(monkeypatch):
    """Plant the defect: in expressions a unit that counts cycles (Hz, rpm) is taken 1:1
    as radians (1 Hz read as 1 rad/s), as linkcli once did."""
    from linkcli.answers.quantities import expressions
    from linkcli.model.units import parse_unit as tables

    def planted(name, expected=None):
        found = tables(name, expected)
        if found is not None and any(c in str(name) for c in ("Hz", "rpm", "rev/s")):
            return found[0], found[1] / TWO_PI
        return found
    monkeypatch.setattr(expressions, "parse_unit", planted)


def test_the_invariance_check_catches_frequencies_read_one_to_one(monkeypatch):
    """With the defect planted, both the vibration and the linkage checks report it, on the
    expressions that read or show Hz and rpm, and not on those in rad/s alone."""
    _counting_cycles(monkeypatch)
    wrong = dict(vibration_case("rad/s"))
    assert {"e0_Hz", "e0_rpm", "e1_rad_s", "r0_1", "d0_1", "T1"} <= set(wrong)
    assert not {"e0_rad_s", "e0_1_s", "r0_0", "T0"} & set(wrong)
    moving = dict(linkage_case("rpm", 120))
    assert {"e0_rad_s", "e1_1_s", "T0", "T1"} <= set(moving)


def test_a_file_in_turns_per_second_shows_its_angular_accelerations():
    """`angular_rate: rev/s` (a unit of the tables) solves: accelerations in the file's
    deg/s^2.  A crank at 1 rev/s: its rate is 360 deg/s, shown as 1 rev/s."""
    text = open(data("expr-rpm-linkage.yaml"), encoding="utf-8").read()
    text = text.replace("angular_rate: deg/s", "angular_rate: rev/s")
    text = text.replace("rate: 360", "rate: 1")
    text = text.replace("report:\n  position:", "report:\n  acceleration: [turnddot]\n  position:")
    text = text.replace("quantities:\n", "quantities:\n  turn: {rotation: AB}\n")
    result = linkcli.loads(text, name="revs.yaml").solve()
    assert result.units["turnddot"] == "deg/s^2"
    assert float(result.values["q_degs"]) == pytest.approx(360, rel=1e-12)


# --- `unit:` on vibration answers: any unit of their dimension ------------------------------
def test_an_amplitude_takes_a_length_unit_of_its_own():
    """vib4_amplitude_unit_hint.yaml: 5 kg on 6000 N/m, 9 N at 1 Hz, file in m; X in mm is
    F / (k - m Omega^2) = 9 / (6000 - 5 (2 pi)^2) m, Tn = 2 pi sqrt(5/6000) s in ms."""
    code, out, err = run(["solve", data("vib4_amplitude_unit_hint.yaml")])
    assert code == 0, err
    x_mm = 1000 * 9 / (6000 - 5 * TWO_PI ** 2)
    v = printed(out)
    assert v["X"] == (round(x_mm, 1), "mm")
    assert v["Tn"] == (round(1000 * TWO_PI * math.sqrt(5 / 6000), 1), "ms")
    result = linkcli.load(data("vib4_amplitude_unit_hint.yaml")).solve()
    assert float(result.values["X"]) == pytest.approx(x_mm, rel=1e-9)


@pytest.mark.parametrize("unit, si", [("N kg/m", 1.0), ("N kg/mm", 1000.0), ("kg^2/s^2", 1.0)])
def test_a_characteristic_coefficient_takes_a_unit_of_its_dimension(unit, si):
    """vib4_characteristic_unit_refused.yaml: det(K - w^2 M) = 2 w^4 - 6000 w^2 + 3e6 in
    SI, so c1 = -6000 N kg/m; in any unit of M^2 T^-2 it is -6000/factor (header)."""
    text = open(data("vib4_characteristic_unit_refused.yaml"), encoding="utf-8").read()
    text = text.replace("unit: N kg/m}", f"unit: {unit}}}")
    result = linkcli.loads(text, name="chain.yaml").solve()
    assert result.units["c1si"] == unit
    assert float(result.values["c1si"]) == pytest.approx(-6000 / si, rel=1e-9)
    code, out, err = run(["solve", data("vib4_characteristic_unit_refused.yaml")])
    assert code == 0, err
    assert printed(out)["c1si"] == (-6000.0, "N kg/m")
    assert printed(out)["c1"] == (-6.0, "N kg/mm")          # the file's mm


@pytest.mark.parametrize("file, old, new, key, fit", [
    ("vib4_amplitude_unit_hint.yaml", "unit: mm}", "unit: N}", "quantities.X.unit",
     "give one of m, cm, mm, km, ft, in"),
    ("vib4_characteristic_unit_refused.yaml", "unit: N kg/m}", "unit: N/m}",
     "quantities.c1si.unit", "give one of N kg/mm, N kg/m"),
    ("critical-damping.yaml", "z1: {damping_ratio: 1}", "z1: {damping_ratio: 1, unit: s}",
     "quantities.z1.unit", "give one of 1, %"),
])
def test_a_unit_of_another_dimension_is_refused_with_the_units_that_fit(tmp_path, file, old,
                                                                        new, key, fit):
    """Refused by validate and solve alike (exit 2): the file, the line, the key, both
    dimensions, and the units that have the answer's."""
    text = open(data(file), encoding="utf-8").read()
    assert old in text
    path = tmp_path / file
    path.write_text(text.replace(old, new), encoding="utf-8")
    line = max(i for i, row in enumerate(path.read_text().splitlines(), 1) if new in row)
    for command in ("solve", "validate"):
        code, out, err = run([command, path])
        assert code == 2
        message = out + err
        assert f"{path}:{line}, key '{key}'" in message and fit in message


# --- rates of a quantity whose name ends in 'd' -----------------------------------------------
def test_the_rate_of_a_quantity_named_wd():
    """rate_name_ending_d.yaml: 'wddot' is the rate of 'wd' (no quantity 'w'): 10 rad/s."""
    code, out, err = run(["solve", data("rate_name_ending_d.yaml")])
    assert code == 0, err
    assert printed(out)["wddot"] == (10.0, "rad/s")


def test_rates_of_names_ending_in_d_everywhere():
    """'yd' = y of A on a unit crank at 30 deg, 10 rad/s, 2 rad/s^2: yddot = cos(q) w,
    ydddot = -sin(q) w^2 + cos(q) alpha, read by the report, an expression, a sweep."""
    text = open(data("rate_name_ending_d.yaml"), encoding="utf-8").read()
    text = text.replace("value: 0, rate: 10}", "value: 30, rate: 10, accel: 2}")
    text = text.replace("  wd: {rotation: crank}\n", "  wd: {rotation: crank}\n  yd: {y: A}\n"
                        '  e: {expr: "yddot/wddot", unit: m}\n')
    text = text.replace("  velocity: [wddot]", "  velocity: [wddot, yddot, e, edot]\n"
                        "  acceleration: [wdddot, ydddot]")
    result = linkcli.loads(text, name="rates.yaml").solve()
    v = {n: float(x) for n, x in result.values.items()}
    q, w, alpha = math.radians(30), 10.0, 2.0
    assert v["wddot"] == pytest.approx(w) and v["wdddot"] == pytest.approx(alpha)
    assert v["yddot"] == pytest.approx(math.cos(q) * w, rel=1e-9)
    assert v["ydddot"] == pytest.approx(-math.sin(q) * w * w + math.cos(q) * alpha, rel=1e-9)
    assert v["e"] == pytest.approx(math.cos(q), rel=1e-9)
    # d/dt (cos(q) w / w) = -sin(q) w, the chain rule through both rates
    assert v["edot"] == pytest.approx(-math.sin(q) * w, rel=1e-9)


# --- a design unknown written as the driver's rate ----------------------------------------
def test_find_the_drivers_acceleration_in_a_unit_of_its_own():
    """find_unit_driver_accel.yaml: a 2 kg block pushed by 10 N moves freely at
    a = F/m = 5 m/s^2; the unknown takes `unit:` and is printed in the file's m/s^2."""
    code, out, err = run(["solve", data("find_unit_driver_accel.yaml")])
    assert code == 0, err
    assert printed(out)["a"] == (5.0, "m/s^2")
    text = open(data("find_unit_driver_accel.yaml"), encoding="utf-8").read()
    for interval, unit in (("[-50, 50]", "m/s^2"), ("[-50000, 50000]", "mm/s^2"),
                           ("[-50, 50]", None)):
        changed = text.replace("{between: [-50, 50], unit: m/s^2}",
                               f"{{between: {interval}" + (f", unit: {unit}}}" if unit else "}"))
        result = linkcli.loads(changed, name="accel.yaml").solve()
        assert float(result.values["a"]) == pytest.approx(10 / 2, rel=1e-9)
        assert result.units["a"] == "m/s^2"


def test_a_drivers_rate_written_as_a_parameter_has_the_drivers_unit():
    """A crank's rate n = 30 rpm written as a parameter: an expression reads it in rad/s
    (30 x 2 pi/60 = pi), and a find: of it in rad/s gives 30 rpm back."""
    text = open(data("expr-rpm-linkage.yaml"), encoding="utf-8").read()
    text = text.replace("angular_rate: deg/s}", "angular_rate: rpm}")
    text = text.replace("params: {a: 1, b: sqrt(2)}", "params: {a: 1, b: sqrt(2), n: 30}")
    text = text.replace("rate: 360", "rate: n")
    text = text.replace("  q_Hz: {expr: \"qdot\", unit: Hz}",
                        "  q_Hz: {expr: \"qdot\", unit: Hz}\n  wn: {expr: \"n\", unit: rad/s}")
    text = text.replace("q_rpm, q_Hz]", "q_rpm, q_Hz, wn]")
    result = linkcli.loads(text, name="n.yaml").solve()
    assert float(result.values["wn"]) == pytest.approx(math.pi, rel=1e-12)
    assert float(result.values["q_Hz"]) == pytest.approx(0.5, rel=1e-12)
    found = text.replace("report:", "find:\n  unknowns: {n: {between: [1, 10], unit: rad/s}}\n"
                         "  targets: {q_Hz: 0.5 Hz}\nreport:")
    result = linkcli.loads(found, name="n.yaml").solve()
    assert result.units["n"] == "rpm"
    assert float(result.values["n"]) == pytest.approx(30, rel=1e-9)


# --- advice that fits the file -------------------------------------------------------------
def test_a_tension_in_a_vibration_file_is_refused_with_advice_that_fits_it(tmp_path):
    """vib4_tension_in_vibration_file.yaml: the file has coordinates and no driver, so the
    refusal (exit 2, validate and solve, with its line) names neither a driver's load nor
    an unknown to give, and its advice is followed: the spring's force at the equilibrium
    is k x0 = 20 g - 4 g = 156.96 N (header: 196.2 N = 4 g + k x0)."""
    path = data("vib4_tension_in_vibration_file.yaml")
    line = next(i for i, row in enumerate(open(path, encoding="utf-8"), 1)
                if row.startswith("  statics:"))
    for command in ("validate", "solve"):
        code, out, err = run([command, path])
        message = out + err
        assert code == 2
        assert f"{path}:{line}, key 'report.statics[0]': 'T1' is a tension" in message
        assert "vibration problem" in message and "spring_force: ks" in message
        assert "driver's" not in message and "value 'unknown'" not in message
    text = open(path, encoding="utf-8").read().replace(
        "  T1: {tension: left}\n  T2: {tension: right}\n", "  Nk: {spring_force: ks}\n")
    text = text.replace("  statics: [T1, T2]\n", "").replace("vibration: [x0]",
                                                             "vibration: [x0, Nk]")
    fixed = tmp_path / "advice.yaml"
    fixed.write_text(text, encoding="utf-8")
    result = linkcli.load(str(fixed)).solve()
    assert float(result.values["Nk"]) == pytest.approx((20 - 4) * 9.81, rel=1e-6)


# --- critical damping is a case of its own ---------------------------------------------------
def test_critical_damping_is_not_called_overdamped():
    """critical-damping.yaml: m = 1, k = 1, c = 2: zeta = c / (2 sqrt(k m)) = 1, the double
    root s = -1 1/s: critically damped (exit 3 for its damped frequency, at its line)."""
    path = data("critical-damping.yaml")
    code, out, err = run(["solve", path])
    assert code == 3
    assert f"{path}:16, key 'quantities.wd1': 'wd1': mode 1 is critically damped (zeta = 1)" \
        in err and "decay rate 1 1/s" in err
    assert "overdamped" not in err
    text = open(path, encoding="utf-8").read().replace("[w1, z1, wd1]", "[w1, z1]")
    result = linkcli.loads(text, name="critical.yaml").solve()
    assert float(result.values["w1"]) == pytest.approx(1, rel=1e-12)
    assert round(float(result.values["z1"]), 6) == 1.0
    code, out, _ = run(["explain", path])
    assert "zeta = 1, critically damped: decay rate 1 1/s" in out and "overdamped" not in out


@pytest.mark.parametrize("ks, cc, case", [
    (3, "2*sqrt(3)", "critically damped"),            # zeta = 1 to the rounding of sqrt(3)
    (1, 2.0002, "overdamped"),                        # zeta = 1.0001
    (1, 1.9998, None),                                # zeta = 0.9999: it oscillates
])
def test_critical_damping_is_decided_with_a_dimensionless_tolerance(ks, cc, case):
    """Near zeta = 1 the mode is critically damped only within the rounding of a double
    root; a damping ratio 1e-4 away is overdamped, or oscillates at
    omega_d = omega_n sqrt(1 - zeta^2)."""
    text = open(data("critical-damping.yaml"), encoding="utf-8").read()
    text = text.replace("params: {m: 1, ks: 1, cc: 2}", f"params: {{m: 1, ks: {ks}, cc: {cc}}}")
    linkage = linkcli.loads(text, name="near.yaml")
    if case is None:
        zeta = 1.9998 / 2
        values = linkage.solve().values
        assert float(values["wd1"]) == pytest.approx(math.sqrt(1 - zeta ** 2), rel=1e-6)
        return
    with pytest.raises(linkcli.LinkcliError) as caught:
        linkage.solve()
    assert f"is {case}" in str(caught.value)
    assert caught.value.reason == case


# --- a largest value reached at the start --------------------------------------------------
def test_explain_says_reached_for_a_largest_value_at_the_start():
    """vib4_largest_reached_said_approached.yaml: released from rest at th1 = 2 deg, th2 = 0,
    th1(t) = 1 deg (cos w1 t + cos w2 t) is largest, 2 deg, at t = 0; the spring's force
    k L (th1 - th2) = 1.5 x 0.3 x 2 deg cos(w2 t) is mode 2 alone: both reached."""
    path = data("vib4_largest_reached_said_approached.yaml")
    code, out, err = run(["solve", path])
    assert code == 0, err
    v = printed(out)
    assert v["th1m"] == (2.0, "deg")
    assert v["Nk"] == (round(1.5 * 0.3 * math.radians(2), 6), "N")
    code, out, err = run(["explain", path])
    assert code == 0, err
    assert f"  th1m: {math.radians(2):.6g} (SI; reached)" in out
    assert f"  Nk: {1.5 * 0.3 * math.radians(2):.6g} (SI; reached)" in out
    assert "(SI; approached" not in out


def test_a_start_out_of_phase_is_still_only_approached():
    """Released at th1 = 2 deg with a rate: the modes do not start in phase, and their
    frequencies (sqrt(g/L) and sqrt(g/L + 2 k/m)) are incommensurate: approached."""
    text = open(data("vib4_largest_reached_said_approached.yaml"), encoding="utf-8").read()
    text = text.replace("th1_dot: 0, th2: 0", "th1_dot: 5, th2: 0")
    linkage = linkcli.loads(text, name="phase.yaml")
    from linkcli.answers.quantities import oscillation, vibration
    analysis = vibration.analyse(linkage.model)
    found = oscillation.largest(analysis, linkage.model.quantities["th1m"])
    assert not found.reached and found.time is None


# --- the documentation's tables -------------------------------------------------------------
def _cells(row: str) -> int:
    """The cells of a table row: its pipes not escaped (\\|), less one."""
    import re
    return len(re.findall(r"(?<!\\)\|", row)) - 1


def table_problems(path) -> list:
    """Rows of a markdown file that do not render in a table: a run of rows starting with
    '|' (outside code blocks, not continuing a paragraph) without the header's delimiter row
    under its first row, or a row with another number of cells than its header."""
    import re
    lines = open(path, encoding="utf-8").read().split("\n")
    problems, fence, i = [], False, 0
    while i < len(lines):
        line = lines[i]
        if line.lstrip().startswith("```"):
            fence = not fence
        if fence or not line.startswith("|"):
            i += 1
            continue
        j = i
        while j < len(lines) and lines[j].startswith("|"):
            j += 1
        block, before = lines[i:j], lines[i - 1].strip() if i else ""
        if before and not before.endswith("-->"):       # a paragraph's text goes on
            i = j
            continue
        if len(block) < 2 or not re.fullmatch(r"\|(\s*:?-+:?\s*\|)+", block[1].strip()):
            problems.append((i + 1, "a row outside a table (no header and delimiter row)"))
        else:
            problems += [(i + k + 1, f"{_cells(row)} cells, the header has {_cells(block[0])}")
                         for k, row in enumerate(block) if _cells(row) != _cells(block[0])]
        i = j
    return problems


def test_the_vibrations_page_tables_render_as_tables(tmp_path):
    """docs/vibrations.md: every row belongs to a table with its header and as many cells
    (its refusals' table ended with two rows after a blank line, printed as text; a cell
    held an unescaped |Im s|).  The check itself finds both defects, planted in a copy."""
    page = os.path.join(ROOT, "docs", "vibrations.md")
    assert table_problems(page) == []
    text = open(page, encoding="utf-8").read()
    stray = "| more than 500 coordinates | 2 |"
    assert stray in text
    planted = tmp_path / "planted.md"
    planted.write_text(text.replace(stray, "\n" + stray).replace("\\|Im s\\|", "|Im s|"),
                       encoding="utf-8")
    found = table_problems(planted)
    assert [p[1] for p in found] == ["4 cells, the header has 2",
                                     "a row outside a table (no header and delimiter row)"]


@pytest.mark.parametrize("page", sorted(os.listdir(os.path.join(ROOT, "docs"))))
def test_every_docs_table_renders_as_a_table(page):
    if page.endswith(".md"):
        assert table_problems(os.path.join(ROOT, "docs", page)) == []


def _design(target: str) -> float:
    """The stiffness ks (N/m) that the target gives the 2 kg mass of :data:`VIBRATION`."""
    exprs = _expressions(["w_rad", "w_Hz", "w_rpm"])
    text = _file(VIBRATION, exprs, FILE="rad/s").replace(
        "report:", f"find:\n  unknowns: {{ks: {{between: [10, 100000]}}}}\n  targets: "
        f"{{{target}}}\nreport:")
    return float(linkcli.loads(text, name="target.yaml").solve().values["ks"])


@pytest.mark.parametrize("target", [
    "w_rad: 3 Hz", "w_Hz: 3", "w_Hz: 180 rpm", "e0_Hz: 3", "e1_rpm: 180",
    "e2_rad_s: 18.8495559215 rad/s", "e0_1_s: 3 Hz", "T1: 0.333333333333 s", "e2_Hz: 180 rpm",
])
def test_find_targets_on_expressions_read_one_frequency_in_every_unit(target):
    """3 Hz = 180 rpm = 6 pi rad/s: every target, on a frequency or an expression of it shown
    in any unit and given in any unit, gives ks = m (6 pi)^2 (m = 2 kg)."""
    expected = 2 * (3 * TWO_PI) ** 2
    assert _design(target) == pytest.approx(expected, rel=1e-8)


def test_keys_of_expressions_in_every_unit(tmp_path):
    """`check` passes keys written in each unit from the factors of this test (w = 20 rad/s,
    its period 2 pi/20 s) and fails one written 1:1 in rad/s."""
    exprs = _expressions(["w_rad", "w_Hz", "w_rpm"])
    text = _file(VIBRATION, exprs, FILE="rad/s")
    w = 20.0
    values = {n: round(w / SI[u], 4) for n, (_, u, p) in exprs.items() if p == 1}
    values.update({n: round(TWO_PI / w, 4) for n, (_, u, p) in exprs.items() if p == -1})
    keys = "keys:\n  - values: {" + ", ".join(f"{n}: {v}" for n, v in values.items()) + "}\n"
    path = tmp_path / "keys.yaml"
    path.write_text(text + "  decimals: 4\n" + keys, encoding="utf-8")
    code, out, err = run(["check", path])
    assert code == 0, out + err
    wrong = dict(values, e0_Hz=w)                            # 20 rad/s read as 20 Hz
    keys = "keys:\n  - values: {" + ", ".join(f"{n}: {v}" for n, v in wrong.items()) + "}\n"
    path.write_text(text + "  decimals: 4\n" + keys, encoding="utf-8")
    code, out, err = run(["check", path])
    assert code == 1 and "e0_Hz" in out + err


def test_a_known_load_in_a_vibration_file_is_its_value():
    """A 5 N force on a 2 kg mass on a 100 N/m spring (free at the figure's 0.3 m, no
    gravity), listed under statics: its value (it was refused with advice to make the
    driver's load unknown); the equilibrium moves by F/k = 0.05 m."""
    text = """title: "mass on a spring with a constant force"
units: {length: m, angle: deg, stiffness: N/m}
frame: {B: [0, 0]}
points: {P: [0, 0.3]}
sliders: {body: {point: P, guide: {x: 0}}}
coordinates: {y: {y: P}}
springs: {s: {between: [B, P], k: 100}}
loads:
  F: {type: force, at: P, y: 5}
dynamics: {masses: {P: 2}}
quantities:
  y0: {equilibrium: y}
report:
  statics: [F]
  vibration: [y0]
  decimals: 4
"""
    code, out, err = run(["solve", "-"], stdin=text)
    assert code == 0, err
    v = printed(out)
    assert v["F"] == (5.0, "N") and v["y0"] == (round(0.3 + 5 / 100, 4), "m")
