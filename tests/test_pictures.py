"""Pictures: plot, draw and animate write real images, refuse bad requests cleanly and never
leave a half-written file."""
import os

import numpy as np
import pytest

PIL = pytest.importorskip("PIL.Image")
pytest.importorskip("matplotlib")

import linkcli
from closure import SEED000_CRANK_SLIDER  # noqa: E402
from linkcli.pictures import plotting  # noqa: E402
from linkcli.cli import main  # noqa: E402
from linkcli.errors import InputError  # noqa: E402
from linkcli.pictures.scene import polygon_vectors  # noqa: E402

from conftest import MECHANISMS  # noqa: E402

FOURBAR = os.path.join(MECHANISMS, "fourbar-inverse-dynamics.yaml")
LIFT = os.path.join(MECHANISMS, "padova-2020-07.yaml")
SHIPPED_CRANK_SLIDER = os.path.join(MECHANISMS, "polimi-crank-slider.yaml")
CRANK_SLIDER = """
title: crank-slider of seed 000 (test copy)
""" + SEED000_CRANK_SLIDER + """quantities: {alpha: {angle: [O, A]}, beta: {angle: [A, B]}, c: {x: B}}
report:
  position: [alpha, beta, c]
  velocity: [alphadot, betadot, cdot]
  acceleration: [alphaddot, betaddot, cddot]
"""


@pytest.fixture
def crank_slider(tmp_path):
    """The shipped seed-000 file when it exists, else the copy above."""
    if os.path.exists(SHIPPED_CRANK_SLIDER):
        return SHIPPED_CRANK_SLIDER
    path = tmp_path / "crank-slider.yaml"
    path.write_text(CRANK_SLIDER, encoding="utf-8")
    return str(path)


def _pixels(path):
    image = PIL.open(path).convert("RGB")
    return image.size, np.asarray(image, dtype=int)


def _count(rgb, color, tol=40):
    return int(np.sum(np.all(np.abs(rgb - np.array(color)) <= tol, axis=-1)))


def _non_white(rgb):
    return float(np.mean(np.any(rgb < 235, axis=-1)))


@pytest.mark.parametrize("names", [("c", "beta"), ("cdot", "betadot"), ("cddot", "betaddot")],
                         ids=["position", "velocity", "acceleration"])
def test_plot_seed000_figures(tmp_path, crank_slider, names):
    out = tmp_path / f"{names[0]}.png"
    args = ["plot", crank_slider, "--sweep", "0:360:90", "-o", str(out)]
    for name in names:
        args += ["--y", name]
    assert main(args) == 0
    size, rgb = _pixels(out)
    assert size == (800, 600)
    assert 0.02 < _non_white(rgb) < 0.6
    assert _count(rgb, (31, 119, 180)) > 200        # the first panel's curve
    assert _count(rgb, (44, 160, 44)) > 200         # the second panel's curve


def test_plot_driving_torque_over_a_turn(tmp_path):
    out = tmp_path / "mm.png"
    assert main(["plot", FOURBAR, "--sweep", "0:360:180", "--y", "Mm", "-o", str(out)]) == 0
    size, rgb = _pixels(out)
    assert size == (800, 360)
    assert _count(rgb, (31, 119, 180)) > 200


def test_plot_svg_and_pdf(tmp_path, crank_slider):
    svg, pdf = tmp_path / "c.svg", tmp_path / "c.pdf"
    assert main(["plot", crank_slider, "--sweep", "0:180:10", "--y", "c", "-o", str(svg)]) == 0
    assert main(["plot", crank_slider, "--sweep", "0:180:10", "--y", "c", "-o", str(pdf)]) == 0
    assert "<svg" in svg.read_text(encoding="utf-8")[:2000]
    assert pdf.read_bytes()[:5] == b"%PDF-"


def test_plotted_angles_are_continuous():
    mech = linkcli.loads(CRANK_SLIDER)
    q = np.linspace(0, 360, 73)
    raw = np.asarray(mech.solve(q=q, names=["beta"]).values["beta"])
    assert np.max(np.abs(np.diff(raw))) > 300                  # [0, 360) jumps at beta = 0
    smooth = plotting._continuous(mech, "beta", raw, "deg")
    assert np.max(np.abs(np.diff(smooth))) < 10
    assert np.allclose(np.mod(smooth, 360), np.mod(raw, 360))
    assert np.max(np.abs(smooth)) < 46                        # beta = asin(-sin(alpha)/sqrt 2)


def test_draw_mechanism_with_polygon_and_loads(tmp_path):
    out = tmp_path / "lift.png"
    assert main(["draw", LIFT, "-o", str(out)]) == 0
    size, rgb = _pixels(out)
    assert size == (800, 650)
    assert 0.02 < _non_white(rgb) < 0.6
    assert _count(rgb, (178, 34, 34), tol=30) > 100           # the vectors z_i
    assert _count(rgb, (26, 127, 55), tol=30) > 30            # the known force
    assert _count(rgb, (199, 21, 133), tol=30) > 30           # the unknown load


def test_draw_dynamics_examples(tmp_path):
    for name in ("fourbar-inverse-dynamics", "curami-2001-07-17-disc",
                 "curami-2001-02-07-friction"):
        out = tmp_path / f"{name}.png"
        assert main(["draw", os.path.join(MECHANISMS, name + ".yaml"), "-o", str(out)]) == 0
        size, rgb = _pixels(out)
        assert size == (800, 650) and _non_white(rgb) > 0.02


def test_polygon_vectors_follow_the_exam_convention():
    mech = linkcli.load(LIFT)
    vectors = [(label, tail, head) for label, _, tail, head in polygon_vectors(mech)]
    assert vectors == [("z1", "A", "B"), ("z2", "B", "C"), ("z3", "B", "D"), ("z4", "D", "E")]
    bare = linkcli.loads(CRANK_SLIDER.replace(
        "quantities: {alpha: {angle: [O, A]}, beta: {angle: [A, B]}, c: {x: B}}",
        "quantities: {c: {x: B}}").replace("position: [alpha, beta, c]", "position: [c]")
        .replace("velocity: [alphadot, betadot, cdot]", "velocity: [cdot]")
        .replace("acceleration: [alphaddot, betaddot, cddot]", "acceleration: [cddot]"))
    # alphabetical: the crank OA gives the vector from A to O
    assert [(t, h) for _, _, t, h in polygon_vectors(bare)] == [("A", "O"), ("A", "B")]


def test_animate_gif_frames(tmp_path, crank_slider):
    out = tmp_path / "motion.gif"
    assert main(["animate", crank_slider, "--sweep", "0:100:5", "-o", str(out)]) == 0
    image = PIL.open(out)
    assert image.format == "GIF" and image.size == (512, 384)
    assert image.n_frames == 6
    image.seek(0)
    first = np.asarray(image.convert("RGB"), dtype=int)
    image.seek(5)
    last = np.asarray(image.convert("RGB"), dtype=int)
    assert _non_white(first) > 0.02
    assert np.sum(np.any(first != last, axis=-1)) > 500       # the mechanism moved


def test_animate_default_is_a_full_turn():
    mech = linkcli.loads(CRANK_SLIDER)
    q = plotting.parse_sweep(plotting.default_sweep(mech))[:-1]
    assert q.size == 72 and q[0] == pytest.approx(45) and q[-1] == pytest.approx(45 + 355)


# --- bad requests -----------------------------------------------------------------------------
def _fails(args, capsys, code, message):
    assert main(args) == code
    err = capsys.readouterr().err
    assert message in err, err
    assert "Traceback" not in err
    return err


def test_refuses_undefined_quantities(tmp_path, capsys, crank_slider):
    out = tmp_path / "x.png"
    err = _fails(["plot", crank_slider, "--sweep", "0:360:10", "--y", "c", "--y", "Q", "-o",
                  str(out)], capsys, 2, "'Q' is not defined by this file")
    assert "key '--y'" in err and "cddot" in err
    _fails(["plot", FOURBAR, "--sweep", "0:360:10", "--y", "Mmdot", "-o", str(out)], capsys, 2,
           "'Mmdot' is not defined")
    assert not out.exists()


@pytest.mark.parametrize("sweep", ["0:360", "a:b:c", "0:360:0", "0:360:-4", "0:inf:4"])
def test_refuses_bad_sweeps(tmp_path, capsys, crank_slider, sweep):
    out = tmp_path / "x.png"
    _fails(["plot", crank_slider, "--sweep", sweep, "--y", "c", "-o", str(out)], capsys, 2,
           "key '--sweep'")
    assert not out.exists()


def test_refuses_paths_that_cannot_be_written(tmp_path, capsys, crank_slider):
    missing = tmp_path / "no" / "such" / "folder" / "x.png"
    _fails(["plot", crank_slider, "--sweep", "0:90:3", "--y", "c", "-o", str(missing)], capsys,
           2, "cannot write output file")
    _fails(["draw", LIFT, "-o", str(tmp_path)], capsys, 2, "")
    _fails(["draw", LIFT, "-o", str(tmp_path / "x.jpg")], capsys, 2, "use .png, .svg, .pdf")
    _fails(["animate", LIFT, "--sweep", "120:140:4", "-o", str(tmp_path / "x.png")], capsys, 2,
           "use .gif")
    assert not missing.parent.exists()
    assert os.listdir(tmp_path) == []


def test_cannot_assemble_leaves_nothing(tmp_path, capsys):
    out = tmp_path / "lift.gif"
    _fails(["animate", LIFT, "--sweep", "100:400:4", "-o", str(out)], capsys, 3,
           "cannot assemble")
    assert os.listdir(tmp_path) == []


def test_animate_needs_a_sweep_for_a_length_driver(tmp_path, capsys):
    _fails(["animate", LIFT, "-o", str(tmp_path / "x.gif")], capsys, 2, "give --sweep")


def test_failed_write_keeps_the_old_file_and_no_temporary(tmp_path):
    target = tmp_path / "picture.png"
    target.write_bytes(b"old picture")

    def broken(tmp, ext):
        with open(tmp, "wb") as handle:
            handle.write(b"half a png")
        raise OSError(28, "No space left on device")

    with pytest.raises(InputError, match="No space left on device"):
        plotting._save(str(target), broken, plotting.IMAGE_FORMATS)
    assert target.read_bytes() == b"old picture"
    assert os.listdir(tmp_path) == ["picture.png"]

    def interrupted(tmp, ext):
        with open(tmp, "wb") as handle:
            handle.write(b"half")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        plotting._save(str(target), interrupted, plotting.IMAGE_FORMATS)
    assert target.read_bytes() == b"old picture"
    assert os.listdir(tmp_path) == ["picture.png"]


def test_written_pictures_are_readable_by_others(tmp_path, crank_slider):
    out = tmp_path / "c.png"
    assert main(["plot", crank_slider, "--sweep", "0:90:3", "--y", "c", "-o", str(out)]) == 0
    mask = os.umask(0)
    os.umask(mask)
    assert os.stat(out).st_mode & 0o777 == 0o666 & ~mask


def test_discs_pulleys_and_strands_are_drawn_where_they_touch():
    """The contact shapes of the 4 Sep 2001 file: disc 1 touches its anchored strand (a line
    at distance r from its centre, parallel to u); the belt strand leaves both discs at
    tangent points (at distance r from each centre, normal to the radius there)."""
    from linkcli.kinematics.solvers import solver_for
    from linkcli.pictures.scene import Scene, contacts
    mech = linkcli.load(os.path.join(MECHANISMS, "polimi-2001-09-04-vibration.yaml")).model
    kin = solver_for(mech).positions(plotting.figure_coordinates(mech))
    shapes = contacts(Scene(mech, kin.pos))
    assert len(shapes) == 2
    line, belt = shapes
    a, b = line.ground
    u = (b - a) / abs(b - a)
    assert abs(((line.centre - a) * u.conjugate()).imag) == pytest.approx(line.radius, rel=1e-12)
    t2, t1 = belt.strand
    d = (t1 - t2) / abs(t1 - t2)
    assert abs(t2 - belt.centre) == pytest.approx(belt.radius, rel=1e-12)
    assert abs(((t2 - belt.centre) * d.conjugate()).real) < 1e-12        # radius normal to it
    assert abs(t1 - line.centre) == pytest.approx(line.radius, rel=1e-12)
    assert abs(((t1 - line.centre) * d.conjugate()).real) < 1e-12
