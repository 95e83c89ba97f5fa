"""Pictures of a vibration problem: the frequency response, the modes, the time response.

- ``frf``: amplitude (log scale, one panel per unit: angles and lengths apart) and phase of
  each free coordinate against the forcing frequency Omega, the natural frequencies marked
  with their values and unit inside the panels;
- ``modes``: each mode drawn on the mechanism at its equilibrium (grey), displaced both
  ways by the mode shape, the farthest moving point by a fifth of the drawing's extent (the
  larger of its width and height; the scale is said in the legend), with the shape's
  components in the title;
- ``free``: the free response from ``initial:`` of the linear model beside the full
  nonlinear equations integrated in time (scipy's solve_ivp).

Every value is in the file's units (``answers.quantities.vibration.shown``).
"""
from __future__ import annotations

import numpy as np

from linkcli.answers.quantities.oscillation import initial_state
from linkcli.answers.quantities.vibration import FREQUENCY_DIM, Answer, analyse, \
    coordinate_dim, phase, shape_text, shown
from linkcli.errors import InputError, SolveError
from linkcli.forces import vibration as vib
from linkcli.model.units import ANGLE_DIM
from linkcli.pictures.drawing import COLORS, draw_elements, draw_mechanism, figure, set_limits
from linkcli.pictures.labels import place_labels
from linkcli.pictures.plotting import (IMAGE_FORMATS, _save_figure, _tell, _wrap, check_output,
                                       parse_sweep)
from linkcli.pictures.scene import Scene, actuators, links

#: the farthest moving point of a mode is drawn displaced by this fraction of the size
MODE_SCALE = 0.2
#: the two displaced poses of a mode, and the pose at equilibrium
PLUS, MINUS, REST = "#d62728", "#1f3a93", "0.55"
# a free response integrates at most MAX_PERIODS periods of the highest natural frequency,
# sampled at least SAMPLES_PER_PERIOD times each (fewer draw an aliased curve)
MAX_PERIODS = 200
SAMPLES_PER_PERIOD = 20


def _require_vibration(mech, what):
    if mech.elements is None:
        raise InputError(f"{what} is for vibration problems (files with coordinates)",
                         file=mech.file, hint="declare 'coordinates:', springs and masses; see "
                         "docs/vibrations.md")


def _coordinates(mech, lin, names):
    """Indices (in the free coordinates) of ``names``; all of them by default."""
    free = [mech.coordinates[j].name for j in lin.free]
    if not names:
        return list(range(len(free)))
    out = []
    for name in names:
        if name not in free:
            raise InputError(f"'{name}' is not a free coordinate of this file", file=mech.file,
                             key="--y", hint="free coordinates: " + ", ".join(free))
        out.append(free.index(name))
    return out


def _unit(mech, j):
    """(unit name, SI factor) of coordinate j in the file's units."""
    return mech.units.show(coordinate_dim(mech, j))


def frf(mech, span: str, names, output: str, dpi: int = 100, notify=None) -> list:
    """Amplitude and phase of coordinates ``names`` over the Omega values of ``span``.

    An Omega where the undamped system is at resonance (the dynamic matrix singular) is a
    break in the curves, and is named to ``notify`` (default: standard error); returns
    those messages."""
    check_output(output, IMAGE_FORMATS)
    fig, said = frf_figure(mech, span, names, dpi)
    _tell(said, notify)
    _save_figure(fig, output)
    return said


def frf_figure(mech, span: str, names, dpi: int = 100):
    """The figure of :func:`frf` and its messages: one amplitude panel per unit of the
    picked coordinates, then the phase, in [-180, 180) deg at the lowest Omega of each
    stretch between resonances and continuous along it."""
    _require_vibration(mech, "a frequency response")
    analysis = analyse(mech)
    lin = analysis.lin
    if not lin.forces.any() and not lin.supports.any():
        raise InputError("a frequency response needs an excitation", file=mech.file,
                         key="excitation", hint="give harmonic forces or a support motion")
    f_unit, f_factor = mech.units.show(FREQUENCY_DIM, "frequency")
    x_axis = parse_sweep(span, key="--frf")
    if x_axis.min() < 0:
        raise InputError(f"frf '{span}': a forcing frequency cannot be negative, got "
                         f"{x_axis.min():g} {f_unit}", key="--frf",
                         hint="Omega runs from 0 up, e.g. --frf 0:60:600")
    omega = x_axis * f_factor
    picked = _coordinates(mech, lin, names)
    D, singular = vib.dynamic_matrix(lin, omega)
    regular = ~singular              # an undamped resonance: a break in the curve, named
    X = np.full((omega.size, len(lin.free)), np.nan, dtype=complex)
    X[regular] = np.linalg.solve(D[regular], lin.load(omega[regular])[..., None])[..., 0]
    said = [f"{mech.file}: warning: Omega = {w:.6g} {f_unit} is an undamped resonance: the "
            "amplitude is unbounded there, a break in the curves" for w in x_axis[singular]]
    panels = {}                                  # unit -> the coordinates shown in it
    for i in picked:
        panels.setdefault(_unit(mech, lin.free[i]), []).append(i)
    fig = figure(8.0, 2.6 + 2.4 * len(panels), dpi)
    axes = fig.subplots(len(panels) + 1, 1, sharex=True, squeeze=False)[:, 0]
    colors = {i: COLORS[n % len(COLORS)] for n, i in enumerate(picked)}
    for ax, ((unit, factor), members) in zip(axes, panels.items()):
        for i in members:
            name = mech.coordinates[lin.free[i]].name
            ax.semilogy(x_axis, np.abs(X[:, i]) / factor, color=colors[i], lw=1.6,
                        label=f"|{name}|")
        ax.set_ylabel(f"amplitude [{unit}]")
        ax.legend(fontsize=8, loc="best")
        _plain_if_narrow(ax, np.abs(X[:, members]) / factor)
    phase_ax = axes[-1]
    a_unit, a_factor = mech.units.show(ANGLE_DIM, "angle")
    for i in picked:
        phase_ax.plot(x_axis, _phase(X[:, i]) / a_factor, color=colors[i], lw=1.4,
                      label=mech.coordinates[lin.free[i]].name)
    if a_unit == "deg":
        from matplotlib.ticker import MultipleLocator
        phase_ax.yaxis.set_major_locator(MultipleLocator(90))
    phase_ax.set_ylabel(f"phase [{a_unit}]")
    phase_ax.set_xlabel(f"forcing frequency Omega [{f_unit}]")
    phase_ax.legend(fontsize=8, loc="best")
    _mark_natural(analysis, axes, x_axis, f_unit, f_factor)
    for ax in axes:
        ax.grid(True, alpha=0.35)
    axes[0].set_title(_wrap(mech.title))
    fig.tight_layout()
    return fig, said


def _phase(x):
    """The phase of ``x`` (rad) by solve's convention, [-pi, pi) at the start of each
    stretch between breaks (NaN) and unwrapped along it."""
    out = np.full(x.shape, np.nan)
    rows = np.nonzero(np.isfinite(x))[0]
    for part in np.split(rows, np.nonzero(np.diff(rows) != 1)[0] + 1):
        if part.size:
            out[part] = np.unwrap(phase(x[part]))
    return out


def _plain_if_narrow(ax, values):
    """Plain numbers on a log axis that spans less than two decades (6 and 10, not 6x10^0)."""
    values = values[np.isfinite(values) & (values > 0)]
    if values.size and np.max(values) < 100 * np.min(values):
        from matplotlib.ticker import ScalarFormatter
        for axis_formatter in (ax.yaxis.set_major_formatter, ax.yaxis.set_minor_formatter):
            formatter = ScalarFormatter()
            formatter.set_scientific(False)
            axis_formatter(formatter)


def _mark_natural(analysis, axes, x_axis, unit, factor):
    """A dashed line at each natural frequency in the range, labelled with its value and unit
    inside the top panel: to the right of the line in the left half, to its left in the
    right half, lower when it would meet the previous label."""
    try:
        natural = analysis.modes().omega / factor
    except SolveError:
        return
    if not x_axis.size:
        return
    low, high = float(x_axis[0]), float(x_axis[-1])
    last, row = None, 0
    for k, w in enumerate(natural):
        if not low <= w <= high:
            continue
        for ax in axes:
            ax.axvline(w, color="0.4", ls="--", lw=0.9)
        right = (w - low) > 0.5 * (high - low)
        row = row + 1 if last is not None and abs(w - last) < 0.25 * (high - low) else 0
        last = w
        axes[0].annotate(f"omega{k + 1} = {w:.4g} {unit}", (w, 1),
                         xycoords=("data", "axes fraction"),
                         xytext=(-4 if right else 4, -12 - 11 * (row % 3)),
                         textcoords="offset points", fontsize=8,
                         ha="right" if right else "left", annotation_clip=True,
                         bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none",
                               "alpha": 0.8})


def _positions(lag, q):
    kin = lag.solver.positions(q[0] if lag.n == 1 else tuple(q))
    lag.solver.check(kin, velocities=False)
    return kin.pos


def modes(mech, output: str, dpi: int = 100) -> None:
    """Every mode drawn on the mechanism at equilibrium and displaced both ways."""
    check_output(output, IMAGE_FORMATS)
    _save_figure(modes_figure(mech, dpi), output)


def modes_figure(mech, dpi: int = 100):
    """The figure of :func:`modes`: a panel per mode, a legend for the three poses."""
    _require_vibration(mech, "a picture of the modes")
    analysis = analyse(mech)
    lin = analysis.lin
    lag = lin.lag
    found = analysis.modes()
    count = len(found.omega)
    columns = min(count, 3)
    height = 1.6 + 4.6 * ((count + 2) // 3)              # inches: the panels, legend, title
    fig = figure(5.0 * columns, height, dpi)
    rest = Scene(mech, _positions(lag, lin.eq.q))
    target = MODE_SCALE * rest.size * rest.lf       # m: a fifth of the drawing's extent
    moved = None
    for k in range(count):
        ax = fig.add_subplot((count + 2) // 3, columns, k + 1)
        shape = np.zeros(lag.n)
        shape[lin.free] = found.shapes[:, k]
        scale = _mode_scale(lag, lin.eq.q, shape, target)
        views = [rest.p[n] for n in mech.points]
        draw_mechanism(ax, rest, mech.dynamics, labels=True)
        _pose(ax, rest, REST, "-", 5.0)
        draw_elements(ax, rest, mech.elements)
        for sign, color, style in ((1, PLUS, "-"), (-1, MINUS, "--")):
            scene = Scene(mech, _positions(lag, lin.eq.q + sign * scale * shape))
            _pose(ax, scene, color, style, 1.8)
            _moving_points(ax, scene, rest, color)
            views += [scene.p[n] for n in mech.points]
        set_limits(ax, views, rest.size)
        w, unit = shown(mech.units, Answer(float(found.omega[k]), FREQUENCY_DIM, "frequency"))
        ax.set_title(f"mode {k + 1}: omega = {w:.4g} {unit}\n{shape_text(analysis, k)}",
                     fontsize=9)
        ax.set_xlabel(f"x [{rest.l_unit}]")
        ax.set_ylabel(f"y [{rest.l_unit}]")
        ax.grid(True, alpha=0.25)
        moved = target / rest.lf
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], color=REST, lw=5.0, label="equilibrium"),
               Line2D([], [], color=PLUS, lw=1.8, label="+ mode shape"),
               Line2D([], [], color=MINUS, lw=1.8, ls="--", label="- mode shape")]
    fig.legend(handles=handles, loc="lower center", ncol=3, fontsize=9,
               title=f"displacements scaled: the farthest moving point moves {moved:.3g} "
               f"{rest.l_unit}", title_fontsize=8)
    title = _wrap(mech.title)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout(rect=(0, 0.85 / height, 1, 1 - (0.25 + 0.2 * title.count("\n")) / height))
    for ax in fig.axes:
        place_labels(ax)
    return fig


def _pose(ax, scene, color, style, width):
    """The links and actuators of ``scene`` as lines of one colour and style."""
    for pts in links(scene):
        ax.plot([z.real for z in pts + pts[:1 if len(pts) > 2 else 0]],
                [z.imag for z in pts + pts[:1 if len(pts) > 2 else 0]],
                color=color, ls=style, lw=width, zorder=5 if color != REST else 2.5,
                solid_capstyle="round")
    for a, _, b, _ in actuators(scene):
        ax.plot([a.real, b.real], [a.imag, b.imag], color=color, ls=style, lw=width, zorder=5)


def _moving_points(ax, scene, rest, color):
    """A dot at each point that moves in the mode (sliders and point masses included)."""
    size = rest.size or 1.0
    for name in scene.mech.points:
        z = scene.p[name]
        if abs(z - rest.p[name]) > 1e-6 * size:
            ax.plot(z.real, z.imag, "o", ms=4, color=color, zorder=6, gid=name)


def _mode_scale(lag, q, shape, target):
    """The factor that moves the mode's farthest point by ``target`` (m)."""
    jt = lag.jet(q, second=False)
    largest = 0.0
    for gradient in jt.grad.values():
        largest = max(largest, float(np.max(np.abs(np.tensordot(shape, gradient, 1)))))
    return target / largest if largest > 0 else 0.0


def free(mech, span: str, names, output: str, dpi: int = 100) -> None:
    """Free response from ``initial``: the linear model and the nonlinear equations."""
    check_output(output, IMAGE_FORMATS)
    _require_vibration(mech, "a time response")
    analysis = analyse(mech)
    lin = analysis.lin
    if not mech.elements.started:
        raise InputError("a time response starts from 'initial:'", file=mech.file,
                         key="initial", hint="e.g. initial: {theta: 2, theta_dot: 0}")
    t = _times(lin, span)
    x0, v0 = initial_state(analysis)
    linear = vib.free_response(lin, x0, v0, t)
    nonlinear = vib.simulate(lin, x0, v0, t)
    picked = _coordinates(mech, lin, names)
    fig = figure(8.0, 1.4 + 2.4 * len(picked), dpi)
    axes = fig.subplots(len(picked), 1, sharex=True, squeeze=False)[:, 0]
    for ax, i in zip(axes, picked):
        j = lin.free[i]
        unit, factor = _unit(mech, j)
        ax.plot(t, nonlinear[:, i] / factor, color=COLORS[0], lw=1.8, label="nonlinear")
        ax.plot(t, linear[:, i] / factor, color=COLORS[1], lw=1.1, ls="--", label="linear")
        ax.set_ylabel(f"{mech.coordinates[j].name} - equilibrium [{unit}]")
        ax.grid(True, alpha=0.35)
    axes[0].legend(fontsize=8)
    axes[-1].set_xlabel("t [s]")
    axes[0].set_title(_wrap(mech.title))
    fig.tight_layout()
    _save_figure(fig, output)


def _times(lin, span):
    """The times of ``--free 0:T:STEPS`` (s), refused where T holds more than MAX_PERIODS
    periods of the highest natural frequency omega_max = max sqrt(|eig(K, M)|) (its cost
    grows with them), or STEPS samples fewer than SAMPLES_PER_PERIOD per period."""
    from scipy.linalg import eigvals
    t = parse_sweep(span, key="--free")
    if t[0] != 0 or t[-1] <= 0:
        raise InputError(f"times '{span}' must run from 0 to a positive end", key="--free",
                         hint="e.g. --free 0:5:2000 (seconds)")
    highest = float(np.sqrt(np.max(np.abs(eigvals(lin.K, lin.M)))))
    if not highest > 0:
        return t
    period = 2 * np.pi / highest
    periods = t[-1] / period
    where = (f"the highest natural frequency, omega = {highest:.4g} rad/s, has the period "
             f"{period:.4g} s")
    if periods > MAX_PERIODS:
        raise InputError(f"free '{span}': {periods:.4g} periods is more than the limit of "
                         f"{MAX_PERIODS} ({where})", key="--free",
                         hint=f"end the time at {MAX_PERIODS * period:.4g} s or before")
    steps = t.size - 1
    if steps < SAMPLES_PER_PERIOD * periods:
        need = int(np.ceil(SAMPLES_PER_PERIOD * periods))
        raise InputError(f"free '{span}': {steps / periods:.4g} samples per period would draw "
                         f"an aliased curve ({where})", key="--free",
                         hint=f"use at least {need} STEPS, {SAMPLES_PER_PERIOD} a period: "
                         f"--free 0:{span.split(':')[1]}:{need}")
    return t
