"""Trust at the edges (issue 11), resources and reports: sweeps in blocks with flat memory
and the same digits, branch points between any two samples (sweeps, plots, animations),
animations streamed and capped, error texts that stay linear, `check` linear in its keys,
rates of loads refused, keys in scientific notation, plots with gaps.  Each test failed
before its fix."""
from __future__ import annotations

import io
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import linkcli
from linkcli.cli import main
from linkcli.errors import InputError

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import CODE, FOURBAR as HELPER_FOURBAR  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MECHANISMS = os.path.join(ROOT, "mechanisms")
DISPARI = os.path.join(MECHANISMS, "padova-2021-02-dispari.yaml")
LIFT = os.path.join(MECHANISMS, "padova-2020-07.yaml")
SIXBAR = os.path.join(MECHANISMS, "padova-2020-01.yaml")

FOURBAR = HELPER_FOURBAR.replace("report:", "KEYS\nreport:")   # room for answer keys

# a change-point linkage: B, C and D in line at q = 0 and 180
PARALLELOGRAM = """title: "Parallelogram four-bar (change point at q = 0 and 180)"
frame: {A: [0, 0], D: [100, 0]}
points: {B: [28.28, 28.28], C: [128.28, 28.28]}
links:
  AB: {points: [A, B], length: 40}
  BC: {points: [B, C], length: 100}
  CD: {points: [C, D], length: 40}
driver: {angle: [A, B], value: 45, rate: 10}
quantities: {phi2: {angle: [B, C]}, phi3: {angle: [D, C]}}
report:
  position: [phi2, phi3]
  velocity: [phi3dot]
"""


@pytest.fixture
def fourbar(tmp_path):
    path = tmp_path / "fourbar.yaml"
    path.write_text(FOURBAR.replace("KEYS\n", ""), encoding="utf-8")
    return str(path)


@pytest.fixture
def parallelogram(tmp_path):
    path = tmp_path / "parallelogram.yaml"
    path.write_text(PARALLELOGRAM, encoding="utf-8")
    return str(path)


def _run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err and "internal error" not in err
    return code, out, err


def _branches(text):
    return [line for line in text.splitlines() if "branch point at q = " in line]


# --- 1. (7a) sweeps in blocks: flat memory, the same digits ---------------------------------
def _peak_mb(args):
    """Peak resident memory (MB) of linkcli ``args`` in a child process; stdout discarded."""
    env = dict(os.environ, PYTHONPATH=ROOT)
    with open(os.devnull, "w") as sink:
        proc = subprocess.Popen([sys.executable, "-c", CODE, *args], stdout=sink,
                                stderr=subprocess.PIPE, env=env)
        err = proc.stderr.read()
        _, status, usage = os.wait4(proc.pid, 0)
    assert os.waitstatus_to_exitcode(status) == 0, err
    return usage.ru_maxrss / 1024


@pytest.mark.parametrize("form", ["csv", "json", "table"])
def test_sweep_memory_does_not_grow_with_the_number_of_positions(fourbar, form):
    small, large = (_peak_mb(["sweep", fourbar, "--from", "0", "--to", "360", "--steps",
                              str(n - 1), "--format", form]) for n in (10 ** 5, 10 ** 6))
    # before: 10x the positions took about 7x the memory (csv 1.0 GB, json 1.9 GB at 10^6)
    assert large - small < 0.1 * small + 10, (small, large)
    assert large < 500


def _old_render(result, form, every=1, decimals=None):
    """The one-block output as it was printed before blocks (tabulate, json.dumps)."""
    q = result.q[result.solved][::every]
    columns = [np.asarray(result.values[n])[::every] for n in result.names]
    if form == "json":
        data = {"file": result.mechanism.file, "title": result.mechanism.title,
                "k": result.mechanism.k, "method": result.method,
                "units": {"q": result.q_unit, **{n: result.units[n] for n in result.names}},
                "q": q.tolist(), "values": {n: c.tolist() for n, c in zip(result.names, columns)},
                "issues": [issue.as_dict() for issue in result.issues]}
        return json.dumps(data, indent=1)
    fmt = repr if decimals is None else (lambda v: f"{v:.{decimals}f}")
    header = [f"q [{result.q_unit}]"] + [f"{n} [{result.units[n]}]" for n in result.names]
    if form == "table":
        from tabulate import tabulate
        fmt = (lambda v: f"{v:.{4 if decimals is None else decimals}f}")
        body = [[fmt(float(v)) for v in row] for row in zip(q, *columns)]
        return tabulate(body, headers=header, disable_numparse=True, stralign="right")
    lines = [",".join(header)]
    for row in zip(q.tolist(), *(c.tolist() for c in columns)):
        lines.append(",".join(fmt(float(v)) for v in row))
    return "\n".join(lines)


@pytest.mark.parametrize("path, start, stop, steps, method", [
    (DISPARI, 0, 360, 360, "closed"), (DISPARI, 360, 0, 250, "closed"),
    (LIFT, 100, 200, 300, "closed"), (SIXBAR, 0, 360, 200, "closed"),
    (DISPARI, 0, 360, 200, "newton"), (LIFT, 100, 200, 150, "newton")])
def test_blocks_print_the_same_digits_and_reports_as_one_block(path, start, stop, steps,
                                                               method):
    from linkcli.runs.sweep.blocks import sweep, Sweeper
    from linkcli.runs.sweep.driver_range import driver_range, driver_values
    from linkcli.runs.sweep.output import write
    whole = sweep(linkcli.load(path).model, driver_values(start, stop, steps),
                  method=method, block=10 ** 9)
    assert whole.issues or path == SIXBAR   # ranges that cannot be assembled, toggles
    for form, every, decimals in (("csv", 1, None), ("json", 1, None), ("table", 1, None),
                                  ("csv", 4, 3), ("table", 7, 2), ("json", 3, None)):
        want = _old_render(whole, form, every, decimals) + "\n"
        for block in (3, 64) if method == "newton" else (1, 7, 64):
            sweeper = Sweeper(linkcli.load(path).model, driver_range(start, stop, steps),
                              method=method, block=block)
            text = io.StringIO()
            issues = write(sweeper, form, every, decimals, text)
            assert [i.text() for i in issues] == [i.text() for i in whole.issues]
            if method == "newton" and form == "csv" and decimals is None:
                _same_but_substeps(text.getvalue(), want)
            elif method != "newton" or decimals is not None:
                assert text.getvalue() == want, (form, every, decimals, block)


def _same_but_substeps(got, want):
    """Newton's rows: the same digits, but for rows that the continuation reaches by
    sub-steps from an anchor (near a fold), chained through those of the block only: they
    agree to the tolerance."""
    a, b = (np.array([[float(v) for v in line.split(",")] for line in text.splitlines()[1:]])
            for text in (got, want))
    assert a.shape == b.shape
    same = np.all(a == b, axis=1)
    assert np.sum(~same) <= 2, a[~same, 0]
    assert np.allclose(a, b, rtol=1e-11, atol=1e-11)


def test_singular_rows_and_ranges_across_block_boundaries(parallelogram):
    from linkcli.runs.sweep.blocks import sweep
    mech = linkcli.load(parallelogram).model
    q = np.arange(-90.0, 271.0, 5.0)          # exact toggles at 0 and 180: rows left out
    whole = sweep(mech, q, block=10 ** 9)
    texts = [i.text() for i in whole.issues]
    assert sum("velocities undefined at q = 180 deg" in t for t in texts) == 1
    assert sum("branch point at q = 180 deg" in t for t in texts) == 1
    for block in range(1, 40):                # the toggle at every place in a block
        got = sweep(linkcli.load(parallelogram).model, q, block=block)
        assert [i.text() for i in got.issues] == texts, block
        assert np.array_equal(got.solved, whole.solved)
        assert np.array_equal(got.values["phi3dot"], whole.values["phi3dot"])
    gaps = sweep(linkcli.load(DISPARI).model, np.arange(0.0, 361.0, 1.0), block=10 ** 9)
    for block in (1, 2, 3, 16, 100):          # assembly ranges joined across blocks
        got = sweep(linkcli.load(DISPARI).model, np.arange(0.0, 361.0, 1.0), block=block)
        assert [i.as_dict() for i in got.issues] == [i.as_dict() for i in gaps.issues]


def test_out_of_memory_is_a_clean_error(fourbar, capsys, monkeypatch):
    from linkcli.answers import quantities

    def exhausted(*args, **kwargs):
        raise MemoryError()

    monkeypatch.setattr(quantities.Plan, "collect", exhausted)
    code, out, err = _run(capsys, "sweep", fourbar, "--from", "0", "--to", "360",
                          "--steps", "100")
    assert code == 3 and out == ""
    assert "not enough memory" in err and "use fewer steps" in err


# --- 2. (3c) branch points between any two samples ---------------------------------------
@pytest.mark.parametrize("method", ["closed", "newton"])
@pytest.mark.parametrize("start, stop, steps", [(150, 210, 1), (175, 265, 9), (100, 260, 2),
                                                (265, 175, 9)])
def test_a_branch_point_between_two_samples_is_reported(parallelogram, capsys, method, start,
                                                        stop, steps):
    code, out, err = _run(capsys, "sweep", parallelogram, "--from", str(start), "--to",
                          str(stop), "--steps", str(steps), "--method", method)
    assert code == 0
    found = _branches(err)
    assert len(found) == 1 and "branch point at q = 180 deg" in found[0], err


#: docs/errors.md: a branch point is located to within 1e-6 rad of the toggle, either method
BRANCH_ACCURACY = math.degrees(1e-6)


@pytest.mark.parametrize("method", ["closed", "newton"])
@pytest.mark.parametrize("start, stop, steps", [(0, 360, 7), (171.3, 262.9, 7), (179, 181.3, 3),
                                                (265, 175, 9)])
def test_a_branch_point_is_located_to_the_stated_accuracy(parallelogram, method, start, stop,
                                                          steps):
    """The parallelogram's change points are exactly at 0 and 180 deg (B, C, D in line).  The
    located value must not depend on the path the solver took to the samples (Newton's
    continuation may leave a change point on either branch, as rounding decides): it is
    found on the conditioning, whose two branches mirror each other."""
    from linkcli.runs.sweep.blocks import sweep
    from linkcli.runs.sweep.driver_range import driver_values
    got = sweep(linkcli.load(parallelogram).model, driver_values(start, stop, steps),
                method=method)
    found = [i.lo for i in got.issues if i.kind == "branch"]
    exact = [t for t in (0.0, 180.0, 360.0) if min(start, stop) <= t <= max(start, stop)]
    assert len(found) == len(exact), got.issues
    for q, t in zip(sorted(found), exact):
        assert abs(q - t) <= BRANCH_ACCURACY, (q, t)


def test_branch_points_across_block_boundaries(parallelogram):
    from linkcli.runs.sweep.blocks import sweep
    for q in (np.linspace(100.0, 260.0, 17), np.linspace(101.0, 259.0, 9),
              np.array([150.0, 210.0])):
        whole = [i.text() for i in sweep(linkcli.load(parallelogram).model, q,
                                         block=10 ** 9).issues]
        assert sum("branch point" in t for t in whole) == 1, whole
        for block in (1, 2, 3, 4):
            got = sweep(linkcli.load(parallelogram).model, q, block=block)
            assert [i.text() for i in got.issues] == whole, (q, block)


@pytest.mark.parametrize("steps", [2, 3, 4, 6, 36])
def test_no_branch_point_where_there_is_none(fourbar, steps):
    from linkcli.runs.sweep.blocks import sweep
    from linkcli.runs.sweep.driver_range import driver_values
    for path in (fourbar, SIXBAR, os.path.join(MECHANISMS, "polimi-crank-slider.yaml")):
        mech = linkcli.load(path).model
        unit, factor = mech.units.display("angle", 0)
        start = mech.driver.value / factor
        got = sweep(mech, driver_values(start - 180, start + 180, steps))
        assert not [i for i in got.issues if i.kind == "branch"], (path, steps, got.issues)


def test_plot_and_animate_report_branch_points(parallelogram, tmp_path, capsys):
    code, _, err = _run(capsys, "plot", parallelogram, "--sweep", "0:360:72", "--y", "phi2",
                        "--y", "phi3", "-o", str(tmp_path / "p.png"))
    assert code == 0 and (tmp_path / "p.png").exists()
    assert any("branch point at q = 180 deg" in line for line in _branches(err)), err
    code, _, err = _run(capsys, "animate", parallelogram, "--sweep", "150:210:2", "-o",
                        str(tmp_path / "a.gif"))
    assert code == 0 and (tmp_path / "a.gif").exists()
    assert len(_branches(err)) == 1 and "branch point at q = 180 deg" in err, err


# --- 3. (7b) animations: frames streamed, their number capped ---------------------------------
def test_animation_frames_are_written_as_they_are_drawn(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    from matplotlib.figure import Figure
    from PIL import Image
    from linkcli.pictures import plotting
    fig = Figure(figsize=(2, 1.5), dpi=50)
    ax = fig.add_subplot(1, 1, 1)
    path = tmp_path / "a.gif"
    sizes = []

    def frames():
        for i in range(12):
            ax.clear()
            ax.plot([0, 1], [0, (i % 4) / 3])
            if path.exists():
                sizes.append(path.stat().st_size)
            yield

    plotting._write_gif(fig, str(path), 10, 50, frames())
    assert sizes[0] == 0 and 0 < sizes[3] < sizes[-1]    # it grows while frames are drawn
    image = Image.open(path)
    assert image.n_frames == 12 and image.size == (100, 75)


def test_animation_frames_are_capped(fourbar, tmp_path, capsys, monkeypatch):
    from linkcli.pictures import plotting
    out = tmp_path / "a.gif"
    with monkeypatch.context() as patch:        # (before: 100000 frames drawn, ~4 hours)
        patch.setattr(plotting, "MAX_FRAMES", 5, raising=False)
        code, _, err = _run(capsys, "animate", fourbar, "--sweep", "0:360:10", "-o", str(out))
        assert code == 2 and "11 frames is more than the limit of 5" in err
    code, _, err = _run(capsys, "animate", fourbar, "--sweep", "0:360:100000", "-o", str(out))
    assert code == 2 and "100001 frames is more than the limit of 2000" in err
    assert "--sweep FROM:TO:STEPS" in err and not out.exists()
    assert plotting.MAX_FRAMES == 2000
    code, _, err = _run(capsys, "animate", fourbar, "--sweep", "0:360:2000", "-o", str(out))
    assert code == 2 and "2001 frames" in err and not out.exists()


# --- 4. (7c) error text linear in the file ------------------------------------------------------
def test_lists_of_names_in_messages_are_capped(tmp_path, capsys):
    many = "".join(f"  P{i}: [{i}, 0]\n" for i in range(300))
    path = tmp_path / "many.yaml"
    path.write_text(FOURBAR.replace("KEYS\n", "").replace("  D: [200, 0]\n",
                                                          "  D: [200, 0]\n" + many)
                    .replace("points: [C, D], length: 120", "points: [C, X], length: 120"),
                    encoding="utf-8")
    code, out, _ = _run(capsys, "validate", str(path))
    assert code == 2 and "undefined point 'X'" in out
    line = next(line for line in out.splitlines() if "undefined point 'X'" in line)
    assert "... and 295 more" in line and len(line) < 300
    quantities = "".join(f"  a{i}: {{angle: [A, B]}}\n" for i in range(200))
    path.write_text(FOURBAR.replace("KEYS\n", "").replace("quantities:\n",
                                                          "quantities:\n" + quantities),
                    encoding="utf-8")
    code, _, err = _run(capsys, "sweep", str(path), "--from", "0", "--to", "10", "--steps",
                        "1", "--names", "nosuch")
    assert code == 2 and "'nosuch' is not a quantity" in err and "more" in err
    assert len(err) < 400


# --- 5. (7d) check: linear in the number of keys ------------------------------------------
def test_check_builds_each_digit_once(tmp_path, monkeypatch):
    from linkcli.runs import check
    keys = "keys:\n" + "".join(f"  - {{k: {j % 10}, values: {{phi2: 22.2}}}}\n"
                               for j in range(300))
    path = tmp_path / "keys.yaml"
    path.write_text("k: 0\nparams: {L: 180+k-k}\n" + FOURBAR.replace("KEYS\n", keys)
                    .replace("C: {length: 180}", "C: {length: L}"), encoding="utf-8")
    builds, solves = [], []
    real_build, real_evaluate = check.build, check.evaluate
    monkeypatch.setattr(check, "build", lambda doc, k=None: builds.append(k) or
                        real_build(doc, k))
    monkeypatch.setattr(check, "evaluate", lambda mech, **kw: solves.append(mech.k) or
                        real_evaluate(mech, **kw))
    report = check.check_file(str(path))
    assert report.error is None and len(report.outcomes) == 300
    assert report.count("pass") == 300
    assert len(builds) <= 11 and len(solves) <= 10, (len(builds), len(solves))


# --- 6. (8) rates of loads, scientific notation, plots with gaps -------------------------------
def test_rates_of_loads_are_refused(fourbar, tmp_path, capsys):
    code, out, err = _run(capsys, "sweep", fourbar, "--from", "0", "--to", "20", "--steps",
                          "2", "--names", "M,Mdot,Mddot")
    assert code == 2 and out == ""
    assert "key '--names'" in err and "'Mdot' is a rate of the load 'M'" in err
    from linkcli.runs.sweep.blocks import sweep
    with pytest.raises(InputError) as caught:
        sweep(linkcli.load(fourbar).model, [0.0, 10.0], ["Mddot"])
    assert "rate of the load 'M'" in str(caught.value)
    keyed = tmp_path / "key.yaml"
    text = FOURBAR.replace("KEYS\n", "keys:\n  - values: {Mdot: 3.4}\n")
    keyed.write_text(text, encoding="utf-8")
    line = text.splitlines().index("  - values: {Mdot: 3.4}") + 1
    code, out, _ = _run(capsys, "check", str(keyed))
    assert code == 1
    assert f"{keyed}:{line}, key 'keys.values.Mdot': 'Mdot' is a rate of the load 'M'" in out
    assert "0 passed, 1 failed" in out


def test_keys_in_scientific_notation_are_compared_at_their_precision(tmp_path, capsys):
    mech = linkcli.loads(FOURBAR.replace("KEYS\n", ""))
    xE = float(mech.solve(names=["xE"]).values["xE"])       # about 117.6 mm
    tens = round(xE, -1)
    keys = ("keys:\n  - values: {yA: 4e-1, phi2: 2.22e1, xE: %.1fe2}\n"
            "  - values: {xE: %.1fe2}\n" % (tens / 100, (tens + 10) / 100))
    path = tmp_path / "sci.yaml"
    path.write_text(FOURBAR.replace("KEYS\n", keys), encoding="utf-8")
    code, out, _ = _run(capsys, "check", "-v", str(path))
    assert code == 1
    assert "FAIL" in out and "yA: printed 4e-1, computed 0.0" in out      # 0 is not 0.4
    assert f"ok {path} k=- phi2: 2.22e1" in out                           # 22.19 is 22.2
    assert f"ok {path} k=- xE: {tens / 100:.1f}e2" in out                 # to tens
    assert f"FAIL {path} k=- xE: printed {(tens + 10) / 100:.1f}e2" in out
    assert "2 passed, 2 failed" in out


def test_plot_leaves_gaps_blank_and_names_the_ranges(tmp_path, capsys):
    out = tmp_path / "gaps.png"
    code, _, err = _run(capsys, "plot", DISPARI, "--sweep", "0:360:360", "--y", "phi2",
                        "--y", "phi2dot", "-o", str(out))
    assert code == 0 and out.exists()
    assert "cannot assemble for q in [0, 15] deg" in err
    assert "cannot assemble for q in [115, 360] deg" in err
    assert "[0, 360]" not in err
    code, _, err = _run(capsys, "plot", DISPARI, "--sweep", "200:300:10", "--y", "phi2",
                        "-o", str(tmp_path / "none.png"))
    assert code == 3 and "cannot assemble for q in [200, 300] deg" in err
    assert not (tmp_path / "none.png").exists()
