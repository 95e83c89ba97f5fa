"""`linkcli sweep`: driver values, output formats, reported ranges, no NaN rows."""
import json
import os

import numpy as np
import pytest

import linkcli
from linkcli.cli import main
from linkcli.errors import InputError
from linkcli.runs.sweep.blocks import sweep
from linkcli.runs.sweep.driver_range import driver_values

from conftest import MECHANISMS

DISPARI = os.path.join(MECHANISMS, "padova-2021-02-dispari.yaml")
LIFT = os.path.join(MECHANISMS, "padova-2020-07.yaml")


def _run(capsys, *args):
    code = main(["sweep", *args])
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    return code, out, err


# --- driver values -----------------------------------------------------------------------
def test_values_are_start_plus_i_step_never_accumulated():
    q = driver_values(10.0, 11.0, step=0.1)
    assert q.size == 11
    assert all(q[i] == 10.0 + i * 0.1 for i in range(11))
    accumulated = np.cumsum(np.r_[10.0, np.full(10, 0.1)])
    assert np.any(accumulated != q)          # the difference this rule makes


def test_steps_include_both_ends_and_reverse_ranges():
    q = driver_values(0.0, 1.0, steps=3)
    assert q.size == 4 and q[0] == 0.0 and q[-1] == 1.0 and q[1] == 1.0 / 3
    down = driver_values(360.0, 0.0, step=90)
    assert down.tolist() == [360.0, 270.0, 180.0, 90.0, 0.0]


@pytest.mark.parametrize("kwargs, key", [
    ({}, "--steps"), ({"steps": 3, "step": 1.0}, "--steps"), ({"steps": 0}, "--steps"),
    ({"step": -1.0}, "--step"), ({"step": 0.0}, "--step"), ({"step": 1e-9}, "--steps"),
])
def test_bad_ranges_are_input_errors(kwargs, key):
    with pytest.raises(InputError) as err:
        driver_values(0.0, 360.0, **kwargs)
    assert err.value.key == key


# --- output ---------------------------------------------------------------------------
def test_csv_rows_equal_single_solves(capsys):
    code, out, err = _run(capsys, LIFT, "--from", "120", "--to", "160", "--steps", "4",
                          "--names", "a1,phi2,xE,xEdot,Q")
    assert code == 0 and err == ""
    lines = out.strip().splitlines()
    assert lines[0] == "q [mm],a1 [mm],phi2 [deg],xE [mm],xEdot [mm/s],Q [N]"
    assert len(lines) == 6
    mech = linkcli.load(LIFT)
    for line in lines[1:]:
        row = [float(v) for v in line.split(",")]
        one = mech.solve(row[0], names=["a1", "phi2", "xE", "xEdot", "Q"]).values
        assert row[1:] == pytest.approx([float(one[n]) for n in ("a1", "phi2", "xE", "xEdot",
                                                                   "Q")], rel=1e-14, abs=1e-12)


def test_ranges_reported_on_stderr_and_in_json(capsys):
    code, out, err = _run(capsys, DISPARI, "--from", "0", "--to", "360", "--steps", "72",
                          "--format", "json")
    assert code == 0
    data = json.loads(out)
    assert "NaN" not in out and "Infinity" not in out
    messages = [issue["message"] for issue in data["issues"]]
    assert messages and err.strip().splitlines() == [f"linkcli: {m}" for m in messages]
    gaps = [i for i in data["issues"] if i["kind"] == "assembly"]
    assert gaps and all(i["shortfall"] > 0 and i["unit"] == "mm" for i in gaps)
    assert all("cannot assemble for q in [" in i["message"] and "links short by up to" in
               i["message"] for i in gaps)
    solved = np.array(data["q"])
    for gap in gaps:                      # no printed row inside a reported range
        assert not np.any((solved >= gap["from"]) & (solved <= gap["to"]))
    assert len(solved) + sum(i["positions"] for i in gaps) == 73
    for values in data["values"].values():
        assert len(values) == len(solved) and np.all(np.isfinite(values))


def test_table_every_and_decimals(capsys):
    code, out, _ = _run(capsys, LIFT, "--from", "120", "--to", "160", "--steps", "40",
                        "--format", "table", "--every", "10", "--decimals", "2",
                        "--names", "phi4")
    assert code == 0
    rows = out.strip().splitlines()[2:]
    assert [r.split()[0] for r in rows] == ["120.00", "130.00", "140.00", "150.00", "160.00"]


def test_newton_sweep_matches_closed_form(capsys):
    args = [LIFT, "--from", "100", "--to", "200", "--steps", "20", "--names", "phi2,phi4,xEdot"]
    _, closed, closed_err = _run(capsys, *args)
    _, newton, newton_err = _run(capsys, *args, "--method", "newton", "--tol", "1e-13")
    a = np.array([[float(v) for v in line.split(",")] for line in closed.splitlines()[1:]])
    b = np.array([[float(v) for v in line.split(",")] for line in newton.splitlines()[1:]])
    assert a.shape == b.shape and a.shape[0] > 10
    assert np.max(np.abs(a - b)) < 1e-9
    assert "cannot assemble" in closed_err and "cannot assemble" in newton_err


def test_bad_names_and_empty_sweeps(capsys):
    code, _, err = _run(capsys, LIFT, "--from", "120", "--to", "130", "--steps", "2",
                        "--names", "phi9")
    assert code == 2 and "--names" in err and "phi9" in err
    code, _, err = _run(capsys, LIFT, "--from", "10", "--to", "20", "--steps", "2")
    assert code == 3 and "cannot assemble" in err
    code, _, err = _run(capsys, LIFT, "--from", "120", "--to", "130")
    assert code == 2 and "--steps" in err


def test_api_sweep_keeps_rows_and_reports():
    mech = linkcli.load(DISPARI)
    result = sweep(mech, np.arange(0, 361, 5.0))
    assert result.solved.sum() == len(next(iter(result.values.values())))
    assert result.solved.sum() < 73 and result.issues
    assert all(np.all(np.isfinite(v)) for v in result.values.values())


# --- rows where the friction locks the mechanism ----------------------------------------------
SELF_LOCKING = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data",
                            "sweep-selflocking.yaml")


def test_a_sweep_leaves_out_the_rows_where_the_friction_locks_the_mechanism(capsys):
    """The friction locks this slider-rocker for q = 75..95 mm: the sweep exited 3 with no
    row at all, though 60-70 and 100-110 solve one by one; those rows are printed (the
    values each gives alone) and the others named, as at-rest rows are."""
    code, out, err = _run(capsys, SELF_LOCKING, "--names", "Mu", "--from", "60", "--to", "110",
                          "--steps", "10")
    assert code == 0
    rows = [line.split(",") for line in out.splitlines()[1:]]
    assert [float(q) for q, _ in rows] == [60, 65, 70, 100, 105, 110]
    link = linkcli.load(SELF_LOCKING)
    for q, value in rows:
        alone = link.solve(q=float(q), names=["Mu"]).values["Mu"]
        assert float(value) == pytest.approx(float(alone), rel=1e-12, abs=1e-12)
    assert "the friction locks the mechanism for q in [75, 95] mm (self-locking" in err
    assert "rows left out" in err
    code, out, _ = _run(capsys, SELF_LOCKING, "--names", "Mu", "--from", "60", "--to", "110",
                        "--steps", "10", "--format", "json")
    (issue,) = [i for i in json.loads(out)["issues"] if i["kind"] == "self-locking"]
    assert code == 0 and (issue["from"], issue["to"], issue["positions"]) == (75, 95, 5)


def test_the_api_sweep_gives_the_rows_that_solve_and_names_the_others():
    """Linkage.solve refuses a whole array when some driver values lock; Linkage.sweep keeps
    the others, with the failures as structured issues (never NaN)."""
    from linkcli.errors import SelfLockingError
    link = linkcli.load(SELF_LOCKING)
    q = np.linspace(60, 110, 11)
    with pytest.raises(SelfLockingError) as caught:
        link.solve(q=q, names=["Mu"])
    assert np.array_equal(np.nonzero(caught.value.rows)[0], np.arange(3, 8))
    got = link.sweep(q, names=["Mu"])
    assert np.array_equal(got.solved, ~caught.value.rows)
    assert np.all(np.isfinite(got.values["Mu"])) and got.values["Mu"].size == 6
    assert got.units["Mu"] == "Nm"
    (issue,) = [i for i in got.issues if i.kind != "branch"]
    assert (issue.kind, issue.lo, issue.hi, issue.count) == ("self-locking", 75.0, 95.0, 5)
    assert np.allclose(got.values["Mu"], link.solve(q=q[got.solved], names=["Mu"]).values["Mu"],
                       rtol=1e-12, atol=0)
