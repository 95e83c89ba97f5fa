"""The Python API (load, solve on arrays) and the JSON output of the CLI."""
import json
import math

import numpy as np
import pytest

import linkcli
from linkcli.cli import main
from linkcli.errors import AssemblyError, LinkcliError

from closure import CASE_IDS, CASES, data_text, load_case, q_factor, sweep

K_FILE = """title: "Crank-slider, data depending on k"
k: 2
params:
  r: 40 + 2*k
  l: 3*r
frame: {A: [0, 0]}
points: {B: [30, 30], C: [150, 0]}
links:
  AB: {points: [A, B], length: r}
  BC: {points: [B, C], length: l}
sliders:
  SC: {point: C, guide: {y: 0}}
driver: {angle: [A, B], value: 30 + 5*k, rate: 60}
loads:
  F: {type: force, at: C, x: -(100 + 10*k)}
  M: {type: driver, value: unknown}
quantities:
  phi1: {angle: [A, B]}
  phi2: {angle: [B, C]}
report:
  position: [phi1, phi2, xC]
  velocity: [phi2dot, xCdot]
  statics: [M]
  points: [B, C]
"""


def _crank_slider(r, l, q_deg, qdot_deg, force):
    """Closed form of the centred crank-slider: xC, xC' and the driver torque."""
    q = math.radians(q_deg)
    s = r * math.sin(q)
    root = math.sqrt(l * l - s * s)
    x = r * math.cos(q) + root
    dx_dq = -r * math.sin(q) - s * r * math.cos(q) / root
    return x, dx_dq * math.radians(qdot_deg), -force * dx_dq * 1e-3


@pytest.mark.parametrize("k", [None, 0, 7])
def test_load_with_k(tmp_path, k):
    path = tmp_path / "k.yaml"
    path.write_text(K_FILE, encoding="utf-8")
    mech = linkcli.load(str(path), k=k)
    kk = 2 if k is None else k
    assert mech.k == kk
    values = mech.solve().values
    r, l = 40 + 2 * kk, 3 * (40 + 2 * kk)
    x, xdot, torque = _crank_slider(r, l, 30 + 5 * kk, 60, -(100 + 10 * kk))
    assert math.isclose(values["phi1"], 30 + 5 * kk, rel_tol=1e-12)
    assert math.isclose(values["xC"], x, rel_tol=1e-12)
    assert math.isclose(values["xCdot"], xdot, rel_tol=1e-10)
    assert math.isclose(values["M"], torque, rel_tol=1e-10)


def test_load_errors_name_the_file(tmp_path):
    path = tmp_path / "k.yaml"
    path.write_text(K_FILE.replace("l: 3*r", "l: 3*q"), encoding="utf-8")
    with pytest.raises(LinkcliError) as info:
        linkcli.load(str(path))
    assert str(path) in str(info.value) and "params.l" in str(info.value)


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_array_solve_matches_scalar_solves(case):
    mech = load_case(case)
    q = sweep(mech, case[3], 7) / q_factor(mech)
    qdot = np.linspace(-2.0, 3.0, q.size)
    qddot = np.linspace(1.0, -1.0, q.size)
    result = mech.solve(q=q, qdot=qdot, qddot=qddot)
    assert set(result.values) == {n for s in ("position", "velocity", "acceleration", "statics")
                                  for n in mech.report.get(s, [])}
    for i in range(q.size):
        one = mech.solve(q=float(q[i]), qdot=float(qdot[i]), qddot=float(qddot[i]))
        for name, value in result.values.items():
            assert np.shape(value) == q.shape, name
            assert np.ndim(one.values[name]) == 0, name
            assert math.isclose(value[i], float(one.values[name]), rel_tol=1e-12,
                                abs_tol=1e-12), (name, i)
        for p, (x, y) in result.points.items():
            assert math.isclose(x[i], float(np.ravel(one.points[p][0])[0]), rel_tol=1e-12,
                                abs_tol=1e-12)
            assert math.isclose(y[i], float(np.ravel(one.points[p][1])[0]), rel_tol=1e-12,
                                abs_tol=1e-12)


def test_defaults_come_from_the_file():
    mech = linkcli.loads(data_text("quick-return.yaml"))
    default = mech.solve().values
    explicit = mech.solve(q=60, qdot=30, qddot=5).values
    for name, value in default.items():
        assert math.isclose(value, explicit[name], rel_tol=1e-12, abs_tol=1e-12), name
    assert math.isclose(default["phi1"], 60.0, rel_tol=1e-12)


def test_solve_selected_names():
    mech = linkcli.loads(data_text("quick-return.yaml"))
    result = mech.solve(q=[10.0, 20.0], names=["phi3", "xDdot"])
    assert set(result.values) == {"phi3", "xDdot"}
    assert result.units["phi3"] == "deg" and result.units["xDdot"] == "mm/s"


def test_angles_reported_in_0_360():
    mech = linkcli.loads(data_text("quick-return.yaml"))
    q = np.linspace(-720, 720, 97)
    values = mech.solve(q=q, names=["phi1", "phi3", "phi4"]).values
    for name, value in values.items():
        assert np.all((value >= 0) & (value < 360)), name
        assert all(f"{v:.6f}" != "360.000000" for v in value), name   # not even when printed
    assert np.allclose(values["phi1"], np.mod(q, 360), atol=1e-9)


def test_array_solve_outside_assembly_names_the_range():
    mech = linkcli.loads(data_text("coupler-slider.yaml"), name="coupler-slider.yaml")
    with pytest.raises(AssemblyError) as info:
        mech.solve(q=np.linspace(40, 100, 61))
    exc = info.value
    assert exc.exit_code == 3 and exc.shortfall > 0
    assert "dyad RRP: E" in str(exc) and "for q in [" in str(exc) and "deg" in str(exc)
    assert "coupler-slider.yaml" in str(exc)


def _json(capsys, args):
    assert main(args) == 0
    out, err = capsys.readouterr()
    assert err == ""
    return json.loads(out)


def test_json_output(tmp_path, capsys):
    path = tmp_path / "k.yaml"
    path.write_text(K_FILE, encoding="utf-8")
    data = _json(capsys, ["solve", str(path), "--k", "7", "--format", "json"])
    assert data["title"] == "Crank-slider, data depending on k"
    assert data["k"] == 7
    api = linkcli.load(str(path), k=7).solve().values
    assert set(data["values"]) == set(api)
    for name, value in api.items():
        assert data["values"][name] == float(value), name          # unrounded, exact
        assert isinstance(data["units"][name], str)
    assert any(v != round(v, 1) for v in data["values"].values())
    assert data["units"]["phi1"] == "deg" and data["units"]["xC"] == "mm"
    assert data["units"]["xCdot"] == "mm/s" and data["units"]["M"] == "Nm"


def test_json_of_a_shipped_example(capsys):
    from closure import shipped
    path = shipped()[0]
    data = _json(capsys, ["solve", path, "--format", "json"])
    api = linkcli.load(path).solve().values
    assert data["values"] == {n: float(v) for n, v in api.items()}
    assert data["title"] == linkcli.load(path).title


def test_exam_format_rounds_to_the_decimals(tmp_path, capsys):
    path = tmp_path / "k.yaml"
    path.write_text(K_FILE, encoding="utf-8")
    assert main(["solve", str(path), "--decimals", "3"]) == 0
    out = capsys.readouterr().out
    api = linkcli.load(str(path)).solve().values
    assert f"{api['xC']:.3f}" in out and "mm" in out
    assert f"{api['M']:.3f}" in out
