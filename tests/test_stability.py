"""Where methods fail: limit positions, toggles, far starts, singular rates, extreme scales.

Nothing here may produce NaN or a silently wrong row: unassemblable positions
are ranges, toggles are clean points with a dimensionless conditioning
measure, and the answers do not depend on the length unit.
"""
import json

import numpy as np
import pytest

import linkcli
from linkcli.kinematics import dyads
from linkcli.cli import main
from linkcli.errors import SingularError
from linkcli.kinematics.newton import NewtonSolver
from linkcli.runs.sweep.blocks import sweep

EPS = np.finfo(float).eps

TRIPLE_ROCKER = """title: non-Grashof four-bar (triple rocker)
frame: {A: [0, 0], D: [200, 0]}
points: {B: [106, 106], C: [205, 120]}
links:
  AB: {points: [A, B], length: 150}
  BC: {points: [B, C], length: 100}
  CD: {points: [C, D], length: 120}
driver: {angle: [A, B], value: 45, rate: 10}
quantities: {phi2: {angle: [B, C]}, phi3: {angle: [D, C]}}
report: {position: [phi2, phi3], velocity: [phi2dot, phi3dot], acceleration: [phi3ddot]}
"""

ACTUATED_ROCKER = """title: actuator AB drives the rocker CB
frame: {A: [0, 0], C: [100, 0]}
points: {B: [64, 48]}
links: {CB: {points: [C, B], length: 60}}
actuators: {AB: {points: [A, B]}}
driver: {length: [A, B], value: 80, rate: 10}
quantities: {phi: {angle: [C, B]}}
report: {position: [phi], velocity: [phidot]}
"""

PARALLELOGRAM = """title: parallelogram four-bar, a change-point linkage
frame: {A: [0, 0], D: [200, 0]}
points: {B: [70.7, 70.7], C: [270.7, 70.7]}
links:
  AB: {points: [A, B], length: 100}
  BC: {points: [B, C], length: 200}
  CD: {points: [C, D], length: 100}
driver: {angle: [A, B], value: 45, rate: 10}
quantities: {phi2: {angle: [B, C]}}
report: {position: [phi2], velocity: [phi2dot]}
"""

TOGGLE = """title: four-bar at its toggle (|DB| = BC + CD at q = 0)
units: {length: UNIT, angle: deg}
params: {s: SCALE}
frame: {A: [0, 0], D: [250*s, 0]}
points: {B: [50*s, 0], C: [170*s, 0]}
links:
  AB: {points: [A, B], length: 50*s}
  BC: {points: [B, C], length: 120*s}
  CD: {points: [C, D], length: 80*s}
driver: {angle: [A, B], value: 0, rate: 10}
quantities: {phi2: {angle: [B, C]}}
report: {position: [phi2], velocity: [phi2dot]}
"""

SCALED = """title: seed-004 four-bar, scaled
units: {length: UNIT, angle: deg}
params: {s: SCALE}
frame:
  A0: [0, 0]
  B0: [425*s*cos(7/4*pi), 425*s*sin(7/4*pi)]
points: {A: [100*s, 0], B: [345*s, 197*s]}
links:
  crank: {points: [A0, A], length: 100*s}
  coupler: {points: [A, B], length: 315*s}
  rocker: {points: [B0, B], length: 500*s}
driver: {angle: [A0, A], value: 0, rate: 900}
quantities: {beta: {angle: [A, B]}, gamma: {angle: [B0, B]}}
report:
  position: [beta, gamma]
  velocity: [betadot, gammadot]
  acceleration: [betaddot, gammaddot]
"""


def _assembly(result):
    return [i for i in result.issues if i.kind == "assembly"]


# --- limit positions ----------------------------------------------------------------------
@pytest.mark.parametrize("method", ["closed", "newton"])
def test_non_grashof_four_bar_limits_are_ranges(method):
    mech = linkcli.loads(TRIPLE_ROCKER)
    # the crank stops where coupler and rocker are stretched: |BD| = BC + CD
    limit = np.degrees(np.arccos((150 ** 2 + 200 ** 2 - 220 ** 2) / (2 * 150 * 200)))
    q = np.arange(0.0, 361.0, 1.0)
    result = sweep(mech, q, method=method)
    gaps = _assembly(result)
    assert len(gaps) == 1
    gap = gaps[0]
    assert gap.lo == np.ceil(limit) and gap.hi == np.floor(360 - limit)
    assert gap.count == gap.hi - gap.lo + 1 and gap.amount > 0
    assert np.array_equal(result.solved, (q < limit) | (q > 360 - limit))
    for values in result.values.values():
        assert values.shape == (result.solved.sum(),) and np.all(np.isfinite(values))


@pytest.mark.parametrize("method", ["closed", "newton"])
def test_actuator_driven_rocker_limits(method, capsys):
    """Reach 40 ... 160 mm: beyond, ranges; at the ends a clean toggle, never NaN."""
    mech = linkcli.loads(ACTUATED_ROCKER)
    q = np.arange(20.0, 201.0, 5.0)
    result = sweep(mech, q, method=method)
    gaps = [(g.lo, g.hi) for g in _assembly(result)]
    assert gaps == [(20.0, 35.0), (165.0, 200.0)]
    solved = q[result.solved]
    assert solved.min() >= 40 and solved.max() <= 160 and 45 in solved and 155 in solved
    for end in (40.0, 160.0):            # toggles: left out of the rates, said so
        assert end in solved or any(i.kind == "singular" and i.lo <= end <= i.hi
                                    for i in result.issues)
    assert all(np.all(np.isfinite(v)) for v in result.values.values())


def test_cli_sweep_through_limits_prints_no_nan(tmp_path, capsys):
    path = tmp_path / "rocker.yaml"
    path.write_text(TRIPLE_ROCKER, encoding="utf-8")
    code = main(["sweep", str(path), "--from", "0", "--to", "360", "--steps", "360",
                 "--format", "json"])
    out, err = capsys.readouterr()
    assert code == 0 and "NaN" not in out and "Traceback" not in err
    assert "cannot assemble for q in [77, 283] deg" in err
    assert len(json.loads(out)["q"]) == 361 - (283 - 77 + 1)


# --- toggles ------------------------------------------------------------------------------
def test_circle_circle_exact_and_near_toggle():
    a, b = 0j, np.array(0.1 + 0.2 + 0j)          # |AB| = 0.30000000000000004
    p, short = dyads.circle_circle(a, 0.1, b, 0.2, 1)
    assert short == 0 and np.isfinite(p) and p.imag == 0 and abs(p - 0.1) < 1e-16
    r2 = 0.2 * (1 + np.arange(-8, 9) * EPS)       # within rounding of the toggle
    p, short = dyads.circle_circle(a, 0.1, b, r2, -1)
    assert np.all(np.isfinite(p)) and np.all(short == 0)
    assert np.max(np.abs(p - 0.1)) < 1e-8         # h = sqrt(rounding) at most
    gap = 0.2 * (1 - 1e-9)                        # a real gap: reported, still finite
    p, short = dyads.circle_circle(a, 0.1, b, np.array([gap]), 1)
    assert np.isfinite(p[0]) and abs(short[0] - 0.2e-9) < 1e-6 * 0.2e-9


def test_circle_line_and_slotted_at_toggle():
    p, short = dyads.circle_line(0j, 0.1, 0.1j, 1 + 0.1j, 0.0, 1)     # tangent line
    assert short == 0 and p == 0.1j
    p, short = dyads.circle_line(0j, 0.1 * (1 - 4 * EPS), 0.1j, 1 + 0.1j, 0.0, -1)
    assert short == 0 and np.isfinite(p) and abs(p - 0.1j) < 1e-8
    c, short = dyads.slotted(0j, 0.05, np.array(0.2 + 0j), 0.05 * 0.2, 1)   # |sin| = 1
    assert short == 0 and np.isfinite(c) and abs(abs(c) - 0.05) < 1e-17


def test_exact_toggle_is_singular_with_dimensionless_measure(tmp_path, capsys):
    """|DB| = BC + CD at q = 0: velocities undefined, said with the same measure at any scale."""
    measures = []
    for unit, scale in (("mm", "1"), ("mm", "1e-5"), ("km", "0.04")):   # D at 2.5 um, 10 km
        text = TOGGLE.replace("UNIT", unit).replace("SCALE", scale)
        mech = linkcli.loads(text)
        with pytest.raises(SingularError) as err:
            mech.solve()
        assert "conditioning" in str(err.value)
        measures.append(err.value.measure)
        with pytest.raises(SingularError) as err:      # Newton says the same, in its measure
            mech.solve(method="newton")
        assert "conditioning" in str(err.value) and err.value.measure < 1e-7
        positions = mech.solve(names=["phi2"]).values           # positions alone are fine
        assert float(positions["phi2"]) == 0.0
    assert max(measures) < 1e-9 and max(measures) - min(measures) < 1e-15
    path = tmp_path / "toggle.yaml"
    path.write_text(TOGGLE.replace("UNIT", "mm").replace("SCALE", "1"), encoding="utf-8")
    assert main(["solve", str(path)]) == 3
    assert "sine of the angle between its constraint directions" in capsys.readouterr().err


def test_branch_point_of_a_change_point_linkage():
    mech = linkcli.loads(PARALLELOGRAM)
    hit = sweep(mech, np.arange(-40.0, 41.0, 5.0))             # samples q = 0 exactly
    kinds = {i.kind for i in hit.issues}
    assert kinds == {"branch", "singular"}
    branch = next(i for i in hit.issues if i.kind == "branch")
    assert abs(branch.lo) < 1e-6 and "dyad RRR: C" in branch.group
    assert not hit.solved[8] and hit.solved.sum() == 16        # the toggle row left out
    missed = sweep(mech, np.linspace(-40.0, 40.0, 16))         # q = 0 between samples
    branch = [i for i in missed.issues if i.kind == "branch"]
    assert len(branch) == 1 and abs(branch[0].lo) < 0.5 and missed.solved.all()
    smooth = sweep(mech, np.arange(10.0, 80.0, 5.0))           # no toggle, nothing said
    assert smooth.issues == []


# --- Newton: far starts and branches ---------------------------------------------------------
def test_newton_far_start_and_across_a_branch():
    base = SCALED.replace("UNIT", "mm").replace("SCALE", "1")
    closed = linkcli.loads(base).solver().positions(np.linspace(0, 6, 7)).pos["B"]
    far = base.replace("B: [345*s, 197*s]", "B: [250*s, 300*s]").replace("A: [100*s, 0]",
                                                                           "A: [40*s, 60*s]")
    got = NewtonSolver(linkcli.loads(far), 1e-13).positions(np.linspace(0, 6, 7)).pos["B"]
    assert np.max(np.abs(got - closed)) < 1e-14
    other = base.replace("B: [345*s, 197*s]", "B: [-83*s, -414*s]")   # the mirrored figure
    mech = linkcli.loads(other)
    got = NewtonSolver(mech, 1e-13).positions(np.linspace(0, 6, 7)).pos["B"]
    assert np.max(np.abs(got - mech.solver().positions(np.linspace(0, 6, 7)).pos["B"])) < 1e-14
    assert np.min(np.abs(got - closed)) > 0.1


# --- scale ---------------------------------------------------------------------------------
@pytest.mark.parametrize("method", ["closed", "newton"])
def test_tiny_and_huge_scales_give_the_same_angles(method):
    reference = linkcli.loads(SCALED.replace("UNIT", "mm").replace("SCALE", "1"))
    tiny = linkcli.loads(SCALED.replace("UNIT", "mm").replace("SCALE", "1e-5"))  # crank 0.001 mm
    huge = linkcli.loads(SCALED.replace("UNIT", "km").replace("SCALE", "10/425"))  # frame 10 km
    q = np.linspace(0, 360, 73)
    ref = reference.solve(q, method=method).values
    for mech in (tiny, huge):
        got = mech.solve(q, method=method).values
        for name, value in ref.items():
            scale = max(float(np.max(np.abs(value))), 1.0)
            assert np.max(np.abs(got[name] - value)) < 1e-11 * scale, name
    measures = []
    for mech in (reference, tiny, huge):
        solver = mech.solver()
        kin = solver.velocities(solver.positions(np.radians(q)), 1.0)
        measures.append(np.concatenate([np.ravel(m) for m in kin.measure.values()]))
    assert np.max(np.abs(measures[1] - measures[0])) < 1e-13
    assert np.max(np.abs(measures[2] - measures[0])) < 1e-13
