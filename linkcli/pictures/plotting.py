"""Pictures: quantities against the driver, the mechanism with its vector polygon, motion.

matplotlib (Agg, no display) is imported inside the functions, so the other
commands never pay for it.  Every picture is written to a temporary file in
the target folder and renamed into place: a failure leaves nothing half-written.
What a picture shows is in :mod:`linkcli.scene`, how it is drawn in
:mod:`linkcli.drawing`.
"""
from __future__ import annotations

import contextlib
import math
import os
import signal
import tempfile

import numpy as np

from linkcli.answers.quantities import angle_period, report_names, require_driver
from linkcli.answers.quantities.drive import Drive
from linkcli.runs.sweep.names import listing
from linkcli.runs.sheet import evaluate, refuse_driving
from linkcli.pictures.drawing import (COLORS, draw_elements, draw_loads, draw_masses,
                                      draw_mechanism, draw_polygon, figure)
from linkcli.pictures.drawing import set_limits
from linkcli.pictures.labels import place_labels
from linkcli.errors import InputError
from linkcli.kinematics.solvers import solver_for
from linkcli.model.mechanism import split_rate
from linkcli.pictures.scene import Scene, disc_points, disc_turns, extent

IMAGE_FORMATS = ("png", "svg", "pdf")
MAX_STEPS = 100_000
MAX_FRAMES = 2000           # an animation's frames: a GIF of 2000 frames is ~3 minutes long


# --- command-line requests -----------------------------------------------------------------
# what FROM:TO:STEPS means after each option, for its messages
SPANS = {"--sweep": "e.g. 0:360:72: driver values in the file's units, STEPS intervals",
         "--frf": "e.g. 0:60:600: forcing frequencies Omega in the file's units.frequency, "
                  "STEPS intervals",
         "--free": "e.g. 0:5:2000: times in seconds from 0, STEPS intervals"}


def parse_sweep(text: str, key: str = "--sweep") -> np.ndarray:
    """'FROM:TO:STEPS' -> STEPS + 1 values FROM + i (TO - FROM) / STEPS (display units), the
    text of option ``key``."""
    parts = str(text).split(":")
    try:
        if len(parts) != 3:
            raise ValueError
        start, stop, steps = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError:
        raise InputError(f"cannot read {key[2:]} '{text}'", key=key,
                         hint=f"write FROM:TO:STEPS, {SPANS[key]}") from None
    if not (math.isfinite(start) and math.isfinite(stop)) or not 1 <= steps <= MAX_STEPS:
        raise InputError(f"{key[2:]} '{text}': need finite FROM, TO and 1 <= STEPS <= "
                         f"{MAX_STEPS}", key=key)
    return start + np.arange(steps + 1) * ((stop - start) / steps)


def default_sweep(mech) -> str:
    """A full turn from the file's value for an angle driver; other drivers need --sweep."""
    d = mech.driver
    if d.kind != "angle":
        raise InputError("give --sweep FROM:TO:STEPS for a driver that is not an angle",
                         file=mech.file, key="--sweep",
                         hint="driver values in the file's units, inside the assembly range")
    _, unit, factor = _driver_text(mech)
    start = d.value / factor
    turn = 2 * math.pi / factor
    return f"{start}:{start + turn}:72"


def check_names(mech, names):
    """Refuse names that the file does not define (quantities, their rates, loads)."""
    if not names:
        raise InputError("give at least one quantity to plot", key="--y",
                         hint="e.g. --y " + (report_names(mech) or ["q"])[0])
    for name in names:
        base, order = split_rate(name, mech.quantities)
        quantity = mech.quantities.get(base)
        ok = quantity is not None and (order == 0 if quantity.kind == "load" else True)
        if not ok:
            shown = report_names(mech)
            raise InputError(f"'{name}' is not defined by this file", file=mech.file, key="--y",
                             hint="its report defines: " + (listing(shown) or "nothing") +
                             "; define others under 'quantities'")


def check_output(path: str, formats) -> str:
    """The picture format from the output path's extension; refuse others early."""
    ext = os.path.splitext(str(path))[1].lower().lstrip(".")
    if ext not in formats:
        raise InputError(f"cannot write {'.' + ext if ext else 'files without an extension'} "
                         "here", file=path, key="-o", hint="use " + ", ".join("." + f for f in
                                                                               formats))
    if os.path.isdir(path):
        raise InputError("the output path is a folder", file=path, key="-o")
    return ext


def _driver_text(mech) -> tuple[str, str, float]:
    """(what q is, its display unit, SI value of one display unit)."""
    d = mech.driver
    base = "angle" if d.kind == "angle" else "length"
    unit, factor = mech.units.display(base, 0)
    what = {"angle": f"angle of {d.a}->{d.b}", "length": f"length {d.a}{d.b}",
            "x": f"x of {d.a}", "y": f"y of {d.a}"}[d.kind]
    return what, unit, factor


# --- atomic writing --------------------------------------------------------------------------
def _save(path: str, write, formats) -> None:
    """Write a picture through ``write(tmp_path, ext)`` to a temporary file, then rename.

    Any exception on the way removes the temporary file, interruptions too (the command
    line turns SIGINT and SIGTERM into exceptions); they are held back while the file is
    created, so that it never exists without this function knowing its name."""
    ext = check_output(path, formats)
    folder = os.path.dirname(os.path.abspath(path))
    tmp = None
    try:
        with _signals_held():   # a signal held here is raised on leaving, with tmp known
            handle, tmp = tempfile.mkstemp(prefix=".linkcli-", suffix="." + ext, dir=folder)
        os.close(handle)
        write(tmp, ext)
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)
        os.replace(tmp, path)
    except OSError as exc:
        if tmp is not None:
            _remove(tmp)
        raise _write_error(path, exc) from None
    except BaseException:
        if tmp is not None:
            _remove(tmp)
        raise


@contextlib.contextmanager
def _signals_held():
    """SIGINT and SIGTERM are delivered after the block, not inside it (where possible).

    Around matplotlib's drawing too: its compiled code calls back into Python, and an
    exception the command line's handler raises there can come out as an error of its
    own (a ValueError 'Invalid bounding box'), the signal lost."""
    held = {signal.SIGINT, signal.SIGTERM}
    try:
        previous = signal.pthread_sigmask(signal.SIG_BLOCK, held)
    except (AttributeError, OSError, ValueError):     # pragma: no cover - not POSIX
        yield
        return
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def _write_error(path, exc) -> InputError:
    return InputError(f"cannot write output file: {exc.strerror}", file=path, key="-o",
                      hint="check the folder exists and is writable")


def _remove(path):
    try:
        os.remove(path)
    except OSError:
        pass


def _save_figure(fig, path) -> None:
    def write(tmp, ext):
        with _signals_held():
            fig.savefig(tmp, format=ext)

    _save(path, write, IMAGE_FORMATS)


# --- plot ------------------------------------------------------------------------------------
def plot(mech, sweep: str, names, output: str, dpi: int = 100, notify=None) -> list:
    """Quantities ``names`` against the driver over ``sweep``, one panel each.

    Driver values that cannot be solved are left blank, and what the sweep reports (ranges
    that cannot be assembled, rows left out at a toggle, branch points) goes to ``notify``
    (default: standard error, after 'linkcli: '); returns those reports."""
    from linkcli.runs.sweep.blocks import sweep as solve_sweep
    check_output(output, IMAGE_FORMATS)
    require_driver(mech, "a plot against the driver")
    check_names(mech, names)
    q = parse_sweep(sweep)
    result = solve_sweep(mech, q, names=list(dict.fromkeys(names)))
    _tell(result.issues, notify)
    what, q_unit, _ = _driver_text(mech)
    fig = figure(8.0, 1.2 + 2.4 * len(names), dpi)
    axes = fig.subplots(len(names), 1, sharex=True, squeeze=False)[:, 0]
    for ax, name, color in zip(axes, names, COLORS * len(names)):
        _panel(ax, mech, q, result, name, color)
    axes[-1].set_xlabel(f"q = {what} [{q_unit}]")
    axes[0].set_title(_wrap(mech.title))
    fig.tight_layout()
    _save_figure(fig, output)
    return result.issues


def plot_vary(mech, vary: str, names, output: str, dpi: int = 100, notify=None) -> list:
    """Answers ``names`` against one of the file's parameters over ``vary``
    ('NAME=FROM:TO:STEPS'), one panel each; values without answers are left blank and
    reported to ``notify``."""
    from linkcli.runs.vary import parse_vary, vary as solve_vary
    check_output(output, IMAGE_FORMATS)
    check_names(mech, names)
    name, values = parse_vary(vary)
    result = solve_vary(mech, name, values, list(dict.fromkeys(names)))
    _tell(result.issues, notify)
    fig = figure(8.0, 1.2 + 2.4 * len(names), dpi)
    axes = fig.subplots(len(names), 1, sharex=True, squeeze=False)[:, 0]
    for ax, answer, color in zip(axes, names, COLORS * len(names)):
        _panel(ax, mech, values, result, answer, color)
    axes[-1].set_xlabel(f"{name} [{result.unit}]" if result.unit else name)
    axes[0].set_title(_wrap(mech.title))
    fig.tight_layout()
    _save_figure(fig, output)
    return result.issues


def _tell(issues, notify=None):
    """Each report's text to ``notify``, by default to standard error as 'linkcli: ...'."""
    if notify is None:
        import sys

        def notify(text):
            try:
                print(f"linkcli: {text}", file=sys.stderr, flush=True)
            except (OSError, ValueError):
                pass
    for issue in issues:
        notify(issue if isinstance(issue, str) else issue.text())


def _panel(ax, mech, q, result, name, color):
    """One quantity's curve against q: a line through each range of solved values, blank
    between them (a lone solved value is a dot)."""
    rows = np.nonzero(result.solved)[0]
    y = np.broadcast_to(np.asarray(result.values[name], dtype=float), rows.shape)
    y = _continuous(mech, name, y, result.units[name])
    cuts = np.nonzero(np.diff(rows) != 1)[0] + 1
    for part, values in zip(np.split(rows, cuts), np.split(y, cuts)):
        ax.plot(q[part], values, color=color, lw=1.8, marker="." if part.size == 1 else None)
    ax.set_ylabel(f"{name} [{result.units[name]}]")
    ax.grid(True, alpha=0.35)
    if q[0] != q[-1]:
        ax.set_xlim(min(q[0], q[-1]), max(q[0], q[-1]))


def _continuous(mech, name, y, unit):
    """Angles without the jumps of [0, 360): unwrapped, then shifted to a mean in [-180, 180)."""
    period = angle_period(mech, name, unit)
    if period is None or y.size < 2:
        return y
    y = np.unwrap(y, period=period)
    return y - period * np.floor(np.mean(y) / period + 0.5)


def _wrap(text, width=80):
    """The file's title on at most three lines, as text: a '$' is not mathtext's."""
    import textwrap
    return "\n".join(textwrap.wrap(str(text), width)[:3]).replace("$", r"\$")


# --- draw and animate ------------------------------------------------------------------------
def _positions(mech, q, method="closed"):
    """Positions at driver values ``q`` (SI) by ``method``; an error where the mechanism
    cannot assemble; a vibration problem takes the closed form only."""
    refuse_driving(mech, method=method)
    solver = solver_for(mech, method)
    if len(mech.coordinates) > 1 and mech.elements is None and np.ndim(q):
        q = Drive(mech)(q, 0.0, 0.0)[0]        # several drivers: the others the file's
    kin = solver.positions(q)
    solver.check(kin, velocities=False)
    return kin


def _axes_text(ax, scene, title, fontsize):
    ax.set_title(title, fontsize=fontsize)
    ax.set_xlabel(f"x [{scene.l_unit}]")
    ax.grid(True, alpha=0.25)


def draw(mech, output: str, dpi: int = 100, method: str = "closed") -> None:
    """The mechanism at the file's driver value, with its vector polygon and loads, its
    positions and loads solved by ``method`` ('closed' or 'newton')."""
    check_output(output, IMAGE_FORMATS)
    _save_figure(drawn(mech, dpi, method), output)


def drawn(mech, dpi: int = 100, method: str = "closed"):
    """The figure of ``draw``, its labels apart."""
    dyn = mech.dynamics
    kin = _positions(mech, figure_coordinates(mech), method)
    scene = Scene(mech, kin.pos)
    values, units_text = _load_values(mech, method)
    fig = figure(8.0, 6.5, dpi)
    ax = fig.add_subplot(1, 1, 1)
    view = [scene.p[n] for n in mech.points] + disc_points(mech, dyn, scene)
    set_limits(ax, view, scene.size)
    draw_mechanism(ax, scene, dyn)
    draw_polygon(ax, scene)
    draw_loads(ax, scene, values, units_text)
    draw_masses(ax, scene, dyn, kin.pos)
    draw_elements(ax, scene, mech.elements)
    what, q_unit, q_factor = _driver_text(mech)
    subtitle = f"q = {what} = {mech.driver.value / q_factor:.4g} {q_unit}" \
        if len(mech.coordinates) == 1 and mech.elements is None else "as in the figure"
    _axes_text(ax, scene, _wrap(mech.title) + "\n" + subtitle, 10)
    ax.set_ylabel(f"y [{scene.l_unit}]")
    fig.tight_layout()
    place_labels(ax)
    return fig


def figure_coordinates(mech):
    """The coordinates' figure values, as the solver takes them (SI)."""
    values = [c.value for c in mech.coordinates]
    return values[0] if len(values) == 1 else tuple(values)


def _load_values(mech, method="closed"):
    """({load: value}, {load: unit}) at the file's position, for the loads that are solved
    (by ``method``)."""
    values, units_text = {}, {}
    if mech.loads and mech.elements is None:
        result = evaluate(mech, names=list(mech.loads), method=method)
        for name in mech.loads:
            if name in result.values:
                values[name] = float(np.asarray(result.values[name]).reshape(-1)[0])
                units_text[name] = result.units[name]
    return values, units_text


def animate(mech, output: str, sweep: str | None = None, fps: int = 12, dpi: int = 80,
            notify=None) -> int:
    """The motion over ``sweep`` as an animated GIF, at most MAX_FRAMES frames, each written
    to the file as soon as it is drawn; branch points of the motion go to ``notify`` (as
    for :func:`plot`).  Returns the frame count."""
    from linkcli.runs.sweep.blocks import Sweeper
    check_output(output, ("gif",))
    require_driver(mech, "an animation")
    dyn = mech.dynamics
    if sweep is None:
        q = parse_sweep(default_sweep(mech))[:-1]       # a full turn: the last frame is the first
    else:
        q = parse_sweep(sweep)
    what, q_unit, q_factor = _driver_text(mech)
    if q.size > MAX_FRAMES:
        step = abs(q[-1] - q[0]) / (MAX_FRAMES - 1)
        raise InputError(f"{q.size} frames is more than the limit of {MAX_FRAMES}",
                         key="--sweep", hint=f"use at most {MAX_FRAMES - 1} STEPS in --sweep "
                         f"FROM:TO:STEPS, here a frame every {step:.3g} {q_unit} or more; at "
                         f"{fps} fps, {MAX_FRAMES} frames play for {MAX_FRAMES / fps:.0f} s")
    kin = _positions(mech, q * q_factor)
    branches = Sweeper(mech, q, quantities=False)
    for _ in branches.blocks():
        pass
    _tell([i for i in branches.issues if i.kind == "branch"], notify)
    spins = disc_turns(mech, dyn, kin)
    scenes = [Scene(mech, kin.pos, i) for i in range(q.size)]
    every = _common_view(mech, dyn, scenes)
    titles = [f"q = {what} = {value:.4g} {q_unit}" for value in q]
    fig = figure(6.4, 4.8, dpi)
    ax = fig.add_subplot(1, 1, 1)

    def write(tmp, ext):
        _write_gif(fig, tmp, fps, dpi, _frames(ax, dyn, scenes, every, spins, titles))

    _save(output, write, ("gif",))
    return int(q.size)


def _write_gif(fig, path, fps, dpi, frames) -> None:
    """One GIF frame of ``fig`` for each item of ``frames`` (which draws it), written to
    ``path`` as soon as the next one is drawn: memory stays that of two frames.

    Each frame has its own palette (Pillow's adaptive one) and holds only the box that
    changed since the previous frame; a frame equal to the previous one lengthens it.
    ``path`` is the temporary file of :func:`_save`, removed when drawing fails or is
    interrupted, so a partial GIF is never left in place."""
    import io

    import matplotlib as mpl
    from PIL import Image, ImageChops
    from PIL.GifImagePlugin import getdata, getheader

    duration = int(1000 / fps)
    width, height = (int(v * dpi) for v in fig.get_size_inches())    # as matplotlib's writers
    with open(path, "wb") as fp, mpl.rc_context({"savefig.bbox": None}):
        pending, previous = None, None            # [image, offset, duration], last RGB frame

        def flush(frame, first):
            image, offset, length = frame
            if first:
                header, _ = getheader(image, info={"loop": 0, "duration": length})
                fp.write(b"".join(header))
                fp.write(b"".join(getdata(image, offset, duration=length)))
            else:
                fp.write(b"".join(getdata(image, offset, duration=length,
                                          include_color_table=True)))

        written, end = 0, object()
        frames = iter(frames)
        while True:
            with _signals_held():                 # a signal is taken between frames
                if next(frames, end) is end:
                    break
                buf = io.BytesIO()
                fig.savefig(buf, format="rgba", dpi=dpi)
                rgb = Image.frombuffer("RGBA", (width, height), buf.getbuffer(), "raw", "RGBA",
                                       0, 1).convert("RGB")
                box = (0, 0, width, height) if previous is None else \
                    ImageChops.difference(previous, rgb).getbbox()
                if box is None:                   # the same picture: shown longer
                    pending[2] += duration
                    continue
                if pending is not None:
                    flush(pending, written == 0)
                    fp.flush()
                    written += 1
                part = rgb if box == (0, 0, width, height) else rgb.crop(box)
                pending = [part.convert("P", palette=Image.Palette.ADAPTIVE), box[:2],
                           duration]
                previous = rgb
        if pending is not None:
            flush(pending, written == 0)
        fp.write(b";")


def _frames(ax, dyn, scenes, every, spins, titles):
    """Draw each scene in turn on ``ax``, discs turned by ``spins``; yield after each."""
    for i, (scene, title) in enumerate(zip(scenes, titles)):
        ax.clear()
        set_limits(ax, every, scene.size, margin=0.08)
        draw_mechanism(ax, scene, dyn, labels=True,
                       spins={n: float(v[i]) for n, v in spins.items()})
        _axes_text(ax, scene, title, 9)
        yield


def _common_view(mech, dyn, scenes) -> list:
    """Every point the frames show; each scene takes their size, so the scale stays put."""
    every = [z for scene in scenes
             for z in [scene.p[n] for n in mech.points] + disc_points(mech, dyn, scene)]
    size = extent(every)
    for scene in scenes:
        scene.size = size
    return every
