"""The periodic regime and the flywheel of machine files (runs.machine_regime): a design
question (`find:`) that asks the flywheel round-trips with the flywheel answer; the answers
of a file against the numerical layer fed by hand; refusals with their numbers; defects
planted in the reading of the file caught by the invariance layer.
"""
import math
import os

import numpy as np
import pytest

import linkcli
from linkcli.errors import RegimeError
from linkcli.forces import flywheel as fw
from linkcli.forces import regime as rg
from linkcli.runs import machine_regime as mr

from cli_helpers import run

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

CRANKSHAFT = """\
title: "a crankshaft under T = 5000 + 1500 sin 3q against a constant torque"
units: {{length: m, angle: deg, angular_rate: rpm, torque: Nm, inertia: kg m^2}}
params: {{If: {If}}}
frame: {{O: [0, 0]}}
points: {{A: [1, 0]}}
links: {{crank: {{points: [O, A], length: 1}}}}
driver: {{angle: [O, A], value: 0, rate: 300}}
loads:
  T: {{type: motor, on: crank, torque: "5000 + 1500*sin(3*q*deg)"}}
  R: {{type: brake, on: crank, value: {resisting}}}
dynamics: {{bodies: {{crank: {{inertia: If, center: O}}}}}}
motion:
  regime: {{mean_speed: 300}}
  flywheel: {{fluctuation: 0.02}}
quantities:
  CS: {{regime: fluctuation}}
  dE: {{regime: energy_fluctuation}}
  Ie: {{flywheel: exact}}
  Ia: {{flywheel: approximate}}
report: {{motion: [CS, dE, Ie, Ia]}}
{find}"""

FIND = """find:
  unknowns: {If: {between: [10, 1000]}}
  targets: {CS: 0.02}
"""


def crankshaft(If=500, resisting=5000, find=""):
    return CRANKSHAFT.format(If=If, resisting=resisting, find=find)


def values(text, name="crankshaft.yaml"):
    result = linkcli.loads(text, None, name).solve()
    return {k: float(v) for k, v in result.values.items()}


def roundtrip_gap(text):
    """|If found by find: - the exact flywheel of the file| / the exact flywheel (the find
    asks only the coefficient)."""
    asked = values(text.replace("report: {motion: [CS, dE, Ie, Ia]}", "report: {motion: [CS]}")
                   + FIND)
    own = values(text)
    return abs(asked["If"] - own["Ie"]) / own["Ie"], asked, own


def test_find_asks_the_flywheel_round_trip():
    """find: If such that delta = 0.02 is the file's exact flywheel, whatever If the file
    starts from; the books' flywheel is DeltaE / (w_m^2 delta) = (2 x 1500 / 3) / (w^2 0.02)."""
    gap, asked, own = roundtrip_gap(crankshaft())
    assert gap < 1e-7
    assert asked["CS"] == pytest.approx(0.02, rel=1e-9)
    w = 300 * math.pi / 30
    assert own["Ia"] == pytest.approx(1000 / (w * w * 0.02), rel=1e-9)
    assert values(crankshaft(If=7))["Ie"] == pytest.approx(own["Ie"], rel=1e-9)


def test_round_trip_catches_the_flywheel_counted_twice(monkeypatch):
    """A planted defect: the driver's link's own inertia left in the machine's J* (so the
    flywheel is added on top of it): the round trip sees the difference."""
    monkeypatch.setattr(mr, "own_inertia", lambda mech: 0.0)
    gap, _, _ = roundtrip_gap(crankshaft(If=20))
    assert gap > 1e-3


def test_file_against_the_numerical_layer():
    """The file's answers are those of forces.regime fed by hand with T and the inertia."""
    own = values(crankshaft(If=500))
    cyc = rg.Cycle(0.0, 2 * math.pi, lambda q: np.zeros(np.shape(q)),
                   lambda q: np.zeros(np.shape(q)),
                   (rg.Load("T", lambda q, w: 5000 + 1500 * np.sin(3 * q)),
                    rg.Load("R", lambda q, w: np.full(np.shape(q), -5000.0))), flywheel=500.0)
    reg = rg.regime(cyc, 10 * math.pi)
    assert own["CS"] == pytest.approx(reg.fluctuation, rel=1e-8)
    assert own["dE"] == pytest.approx(1000.0, rel=1e-9)
    assert own["Ie"] == pytest.approx(fw.flywheel(cyc, 0.02, 10 * math.pi).exact, rel=1e-8)


def test_unbalanced_file_refused_with_its_means(tmp_path):
    """A resisting torque that is not the mean of T: exit 3, both means named."""
    path = tmp_path / "unbalanced.yaml"
    path.write_text(crankshaft(resisting=4900))
    code, out, err = run(["solve", str(path)])
    assert code == 3 and out == ""
    assert "T 5000, R -4900" in err and "runs away" in err and "nan" not in err.lower()


def test_areas_flywheel_exact_refused(tmp_path):
    src = open(os.path.join(ROOT, "mechanisms/khurmi-16-5-multicylinder-areas.yaml")).read()
    path = tmp_path / "areas.yaml"
    path.write_text(src.replace("m: {flywheel: approximate, radius: 500}",
                                "m: {flywheel: exact, radius: 500}"))
    code, _, err = run(["solve", str(path)])
    assert code == 3 and "books' flywheel only" in err


def test_units_invariance_catches_a_diagram_angle_read_without_its_unit(monkeypatch):
    """A planted defect: the angle of a diagram's scale taken as radians whatever the file's
    angle unit: the file rewritten in other units disagrees."""
    from linkcli.input.regime import RegimeSection
    from test_invariance_units import SYSTEMS, caught, check

    good = RegimeSection.diagram

    def planted(self, regime, path, units, mean):
        areas, energy, scale = good(self, regime, path, units, mean)
        return areas, energy / units.factor("angle"), scale

    found = caught(lambda: check("mechanisms/khurmi-16-4-petrol-engine-areas.yaml",
                                 SYSTEMS["si"]),
                   lambda: monkeypatch.setattr(RegimeSection, "diagram", planted))
    assert found


def test_regime_error_is_a_solve_error():
    with pytest.raises(RegimeError) as err:
        values(crankshaft(resisting=5100))
    assert err.value.exit_code == 3 and err.value.reason == "unbalanced"


def test_schema_states_the_regimes_tables():
    import json

    from linkcli.input.regime import MOTION_KEYS
    from linkcli.model.regime import FLYWHEEL, REGIME
    schema = json.load(open(os.path.join(ROOT, "linkcli/input/schema.json")))
    defs = schema["$defs"]
    assert defs["regimeQuantity"]["properties"]["regime"]["enum"] == list(REGIME)
    assert defs["flywheelQuantity"]["properties"]["flywheel"]["enum"] == list(FLYWHEEL)
    motion = next(a for a in schema["properties"]["motion"]["anyOf"] if "properties" in a)
    assert MOTION_KEYS <= set(motion["properties"])


def test_turns_per_cycle():
    """A torque 1500 sin(1.5 q) repeats every two turns: over two turns DeltaE = 2 x 1500 /
    1.5; over one (the default) its mean is not zero and the regime is refused."""
    text = crankshaft().replace("sin(3*q*deg)", "sin(1.5*q*deg)")
    two = text.replace("  flywheel: {{fluctuation: 0.02}}".replace("{{", "{").replace("}}", "}"),
                       "  flywheel: {fluctuation: 0.02}\n  turns_per_cycle: 2")
    assert values(two)["dE"] == pytest.approx(2 * 1500 / 1.5, rel=1e-9)
    with pytest.raises(RegimeError) as err:
        values(text)
    assert err.value.reason == "unbalanced"
