"""Trust at the edges, in the solver: dead centres of an unknown load, branches chosen once
as in the figure (with backtracking), figures that cannot be assembled or are far from the
solution.  Each test reproduces a defect that printed a number without a word."""
from __future__ import annotations

import math

import numpy as np
import pytest

import linkcli
from linkcli.kinematics.solvers import figure_cautions
from linkcli.cli import main
from linkcli.errors import NoWorkError

CRANK_SLIDER = """
title: crank-slider at a dead centre
units: {{length: mm, angle: deg}}
frame: {{A: [0, 0]}}
points: {{B: [-40, 0.5], C: [100, 0]}}
links: {{AB: {{points: [A, B], length: 40}}, BC: {{points: [B, C], length: 140}}}}
sliders: {{C: {{point: C, guide: {{y: 0}}}}}}
driver: {{angle: [A, B], value: {q}, rate: 10}}
loads:
  M: {{type: torque, on: AB, value: 5}}
  P: {{type: force, at: C, x: unknown}}
report: {{statics: [P]}}
"""


@pytest.mark.parametrize("q", [180, -180, 0, 360, 540])
def test_unknown_load_at_a_dead_centre_is_refused(tmp_path, capsys, q):
    path = tmp_path / "cs.yaml"
    path.write_text(CRANK_SLIDER.format(q=q))
    assert main(["solve", str(path)]) == 3
    err = capsys.readouterr().err
    assert "the unknown load P does no work at q =" in err and "dead centre" in err


@pytest.mark.parametrize("q", [179.999, 179.9, 150.0, 0.01, -30.0])
def test_unknown_load_near_a_dead_centre_is_answered(q):
    """P c_P + M = 0 with c_P = dx_C/dq = -r sin q (1 + r cos q / sqrt(l^2 - r^2 sin^2 q))."""
    r, l, m = 0.04, 0.14, 5.0
    a = math.radians(q)
    c = -r * math.sin(a) * (1 + r * math.cos(a) / math.sqrt(l * l - (r * math.sin(a)) ** 2))
    got = float(linkcli.loads(CRANK_SLIDER.format(q=q)).solve().values["P"])
    assert got == pytest.approx(-m / c, rel=1e-7)


def test_no_work_error_marks_the_rows():
    mech = linkcli.loads(CRANK_SLIDER.format(q=0))
    with pytest.raises(NoWorkError) as caught:
        mech.solve(q=np.array([170.0, 180.0, 190.0]))
    assert list(np.ravel(caught.value.rows)) == [False, True, False]


# --- branches --------------------------------------------------------------------------------
DRAGLINK = """
title: drag-link, the crank angle from k
k: 0
frame: {A: [0, 0], D: [20, 0]}
points: {B: [100, 0], C: [80, -70]}
links: {AB: {points: [A, B], length: 100}, BC: {points: [B, C], length: 60},
        CD: {points: [C, D], length: 90}}
driver: {angle: [A, B], value: 36*k, rate: 10}
quantities: {phi2: {angle: [B, C]}, phi3: {angle: [D, C]}}
report: {position: [phi2, phi3]}
"""


def test_batch_keeps_the_figures_branch_for_every_digit():
    """Every digit on the branch the figure draws: the same as a sweep from the figure."""
    sweep = linkcli.loads(DRAGLINK).solve(q=np.arange(10) * 36.0)
    for k in range(10):
        row = linkcli.loads(DRAGLINK, k=k).solve()
        for name in ("phi2", "phi3"):
            assert float(row.values[name]) == pytest.approx(float(sweep.values[name][k]),
                                                            abs=1e-9), (k, name)


def test_figure_drawn_at_another_angle_keeps_its_assembly():
    """The file asks q = 200 deg, the figure draws q = 0 on the lower branch: q = 200 is
    solved on the lower assembly mode, continued from the figure (C below the line B-D)."""
    text = DRAGLINK.replace("value: 36*k", "value: 200")
    pos = linkcli.loads(text).solver().positions(math.radians(200)).pos
    b, c, d = pos["B"], pos["C"], pos["D"]
    figure_side = np.sign(((100 - 20) * (-70 - 0) - (0 - 0) * (80 - 20)))
    side = np.sign(((d - b).conjugate() * (c - b)).imag)
    assert side == -figure_side or side == figure_side   # a sign, never a tie
    sweep = linkcli.loads(text).solve(q=np.linspace(0, 200, 201))
    assert float(np.ravel(sweep.values["phi3"])[-1]) == pytest.approx(
        float(linkcli.loads(text).solve().values["phi3"]), abs=1e-9)


FORCED = """
title: six-bar whose second dyad closes only on the first dyad's far branch
frame: {A: [0, 0], D: [100, 0], F: [50, -150]}
points: {B: [0, 50], C: [60, 60], E: [20, -90]}
links: {AB: {points: [A, B], length: 50}, BC: {points: [B, C], length: 80},
        CD: {points: [C, D], length: 80}, CE: {points: [C, E], length: 60},
        EF: {points: [E, F], length: 70}}
driver: {angle: [A, B], value: 90, rate: 10}
quantities: {phi: {angle: [B, C]}}
report: {position: [phi]}
"""


def test_a_later_dyad_forces_the_earlier_branch():
    mech = linkcli.loads(FORCED)
    solver = mech.solver()
    kin = solver.positions(math.radians(90))
    solver.check(kin, velocities=False)               # it assembles
    assert any(c.kind == "branch" and "farther from the figure" in c.detail
               for c in solver.cautions)


UNASSEMBLED = """
title: four-bar whose driver value cannot be assembled
frame: {A: [0, 0], D: [100, 0]}
points: {B: [20, 34.64], C: [70, -30]}
links: {AB: {points: [A, B], length: 40}, BC: {points: [B, C], length: 80},
        CD: {points: [C, D], length: 40}}
driver: {angle: [A, B], value: 180, rate: 10}
quantities: {phi: {angle: [B, C]}}
report: {position: [phi]}
"""


def test_validate_says_the_files_own_position_cannot_be_assembled(tmp_path, capsys):
    path = tmp_path / "u.yaml"
    path.write_text(UNASSEMBLED)
    assert main(["validate", str(path)]) == 3
    out = capsys.readouterr().out
    assert "the file's own position cannot be assembled" in out and "falls short by" in out


def test_figure_that_cannot_be_assembled_leaves_the_branch_undetermined(tmp_path, capsys):
    text = UNASSEMBLED.replace("points: {B: [20, 34.64], C: [70, -30]}",
                               "points: {B: [-40, 0], C: [70, -30]}")
    path = tmp_path / "n.yaml"
    path.write_text(text)
    assert main(["explain", str(path)]) == 0
    out = capsys.readouterr().out
    assert "not determined by the figure" in out
    assert "the figure's position cannot be assembled" in out


# --- figures far from the answer -----------------------------------------------------------
SHAPE = """
title: four-bar with a coupler point
frame: {A: [0, 0], D: [200, 0]}
points: {B: [30, 51.96], C: [196.7, 119.95], E: [103.6, 146.8]}
links:
  AB: {points: [A, B], length: 60}
  BCE: {points: [B, C, E], shape: {C: {length: 180}, E: {length: 120, angle: 30}}}
  CD: {points: [C, D], length: 120}
driver: {angle: [A, B], value: 60, rate: 1}
quantities: {phi: {angle: [B, C]}}
report: {position: [phi]}
"""


@pytest.mark.parametrize("old, new, point", [
    ("angle: 30}", "angle: -30}", "E"),                     # a shape angle of the wrong sign
    ("CD: {points: [C, D], length: 120}", "CD: {points: [C, D], length: 150}", "C"),
    ("angle: [A, B], value: 60", "angle: [B, A], value: 60", "B"),      # the vector reversed
])
def test_solution_far_from_the_figure_is_reported(tmp_path, capsys, old, new, point):
    assert figure_cautions(linkcli.loads(SHAPE).model) == []
    text = SHAPE.replace(old, new)
    cautions = figure_cautions(linkcli.loads(text).model)
    assert any(c.kind == "figure" and point in c.points for c in cautions), cautions
    path = tmp_path / "f.yaml"
    path.write_text(text)
    assert main(["validate", str(path)]) == 0
    out = capsys.readouterr().out
    assert "warning: the solved position is far from the figure" in out


def test_figure_point_equidistant_from_both_assemblies():
    text = """
title: C drawn on the line B-D
frame: {A: [0, 0], D: [100, 0]}
points: {B: [51.96152422706632, 30], C: [75.98076211353316, 15]}
links: {AB: {points: [A, B], length: 60}, BC: {points: [B, C], length: 40},
        CD: {points: [C, D], length: 50}}
driver: {angle: [A, B], value: 30, rate: 10}
quantities: {phi: {angle: [B, C]}}
report: {position: [phi]}
"""
    cautions = figure_cautions(linkcli.loads(text).model)
    assert any(c.kind == "ambiguous" and "nearly as far from both assemblies" in c.detail
               for c in cautions)


def test_every_shipped_file_matches_its_figure():
    import glob
    import os
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    for path in sorted(glob.glob(os.path.join(root, "mechanisms", "*.yaml"))):
        mech = linkcli.load(path).model
        try:
            cautions = figure_cautions(mech)
        except linkcli.LinkcliError:
            continue                         # the class-III file: Newton only
        assert cautions == [], (path, [str(c) for c in cautions])


# --- contacts that lift off --------------------------------------------------------------
def _root():
    import os
    return os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def test_rolling_contact_that_pulls_is_reported():
    """With gravity the floor pushes (no warning); with gravity reversed it would have to pull."""
    import os
    from linkcli.forces.joint_forces import solve
    from linkcli.kinematics.solvers import state
    path = os.path.join(_root(), "mechanisms", "curami-2001-07-17-disc.yaml")
    text = open(path).read()
    mech = linkcli.loads(text).model
    kin, _ = state(mech)
    assert solve(mech, kin).cautions == []
    upside = linkcli.loads(text.replace("gravity: 9.81", "gravity: {g: 9.81, angle: 90}")).model
    kin, _ = state(upside)
    cautions = solve(upside, kin).cautions
    assert len(cautions) == 1 and cautions[0].kind == "contact"
    assert "the rolling contact of D pulls (N = -" in cautions[0].detail
    assert cautions[0].points["D"] == pytest.approx(-6 * 9.81, rel=0.2)


@pytest.mark.parametrize("speed, lifts", [(5, False), (8.5, False), (8.7, True), (12, True)])
def test_wheel_on_a_road_lifts_off_above_its_speed(speed, lifts):
    """20 Jun 2001: the contact force amplitude k Z_rel + r Z_rel' reaches m g at 8.58 m/s
    (damped, the chosen numbers): above it the wheel leaves the runway."""
    import os
    path = os.path.join(_root(), "mechanisms", "polimi-2001-06-20-vibration.yaml")
    text = open(path).read().replace("  V: 5                # m/s, taxi speed", f"  V: {speed}")
    result = linkcli.loads(text).solve()
    contact = [c for c in result.cautions if c.kind == "contact"]
    assert bool(contact) == lifts
    if lifts:
        assert "the wheel lifts off the road" in contact[0].detail
        assert float(result.values["Ft"]) > 6 * 9.81 * 50 / 6   # above m g = 490.5 N


def test_sweep_leaves_out_the_dead_centre_rows(tmp_path, capsys):
    path = tmp_path / "cs.yaml"
    path.write_text(CRANK_SLIDER.format(q=0))
    assert main(["sweep", str(path), "--from", "170", "--to", "190", "--steps", "4",
                 "--format", "csv"]) == 0
    out, err = capsys.readouterr()
    rows = [line.split(",")[0] for line in out.splitlines()[1:]]
    assert rows == ["170.0", "175.0", "185.0", "190.0"]
    assert "the unknown load P does no work at q = 180 deg" in err and "rows left out" in err


def test_rates_of_loads_are_refused_by_the_api():
    mech = linkcli.loads(CRANK_SLIDER.format(q=30))
    with pytest.raises(linkcli.LinkcliError, match="a load has no rates"):
        mech.solve(names=["Pdot"])
