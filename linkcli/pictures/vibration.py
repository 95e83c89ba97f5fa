"""Pictures of a vibration problem: the frequency response, the modes, the time response.

- ``frf``: amplitude (log scale) and phase of each free coordinate against the
  forcing frequency Omega, the natural frequencies marked;
- ``modes``: each mode drawn on the mechanism at its equilibrium, displaced
  both ways by the mode shape (scaled to a tenth of the mechanism's size);
- ``free``: the free response from ``initial:`` of the linear model beside the
  full nonlinear equations integrated in time (scipy's solve_ivp).
"""
from __future__ import annotations

import numpy as np

from linkcli.answers.quantities.oscillation import initial_state
from linkcli.answers.quantities.vibration import analyse
from linkcli.errors import InputError, SolveError
from linkcli.forces import vibration as vib
from linkcli.model.units import ANGLE, FREQUENCY, LENGTH
from linkcli.pictures.drawing import (COLORS, draw_elements, draw_mechanism, draw_outline,
                                      figure, set_limits)
from linkcli.pictures.plotting import (IMAGE_FORMATS, _save_figure, _tell, _wrap, check_output,
                                       parse_sweep)

# a free response integrates at most MAX_PERIODS periods of the highest natural frequency,
# sampled at least SAMPLES_PER_PERIOD times each (fewer draw an aliased curve)
MAX_PERIODS = 200
SAMPLES_PER_PERIOD = 20
from linkcli.pictures.scene import Scene


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
    base = mech.coordinates[j].base
    unit = mech.units.names["angle" if base == "angle" else "length"]
    return unit, (ANGLE if base == "angle" else LENGTH)[unit]


def frf(mech, span: str, names, output: str, dpi: int = 100, notify=None) -> list:
    """Amplitude and phase of coordinates ``names`` over the Omega values of ``span``.

    An Omega where the undamped system is at resonance (the dynamic matrix singular) is a
    break in the curves, and is named to ``notify`` (default: standard error); returns
    those messages."""
    check_output(output, IMAGE_FORMATS)
    _require_vibration(mech, "a frequency response")
    analysis = analyse(mech)
    lin = analysis.lin
    if not lin.forces.any() and not lin.supports.any():
        raise InputError("a frequency response needs an excitation", file=mech.file,
                         key="excitation", hint="give harmonic forces or a support motion")
    f_unit = mech.units.names["frequency"]
    shown = parse_sweep(span, key="--frf")
    if shown.min() < 0:
        raise InputError(f"frf '{span}': a forcing frequency cannot be negative, got "
                         f"{shown.min():g} {f_unit}", key="--frf",
                         hint="Omega runs from 0 up, e.g. --frf 0:60:600")
    omega = shown * FREQUENCY[f_unit]
    picked = _coordinates(mech, lin, names)
    D, singular = vib.dynamic_matrix(lin, omega)
    regular = ~singular              # an undamped resonance: a break in the curve, named
    X = np.full((omega.size, len(lin.free)), np.nan, dtype=complex)
    X[regular] = np.linalg.solve(D[regular], lin.load(omega[regular])[..., None])[..., 0]
    x_axis = shown
    said = [f"{mech.file}: warning: Omega = {w:.6g} {f_unit} is an undamped resonance: the amplitude is unbounded "
            "there, a break in the curves" for w in shown[singular]]
    _tell(said, notify)
    fig = figure(8.0, 6.4, dpi)
    amp_ax, phase_ax = fig.subplots(2, 1, sharex=True)
    for i, color in zip(picked, COLORS * len(picked)):
        j = lin.free[i]
        unit, factor = _unit(mech, j)
        name = mech.coordinates[j].name
        amp_ax.semilogy(x_axis, np.abs(X[:, i]) / factor, color=color, lw=1.6,
                        label=f"|{name}| [{unit}]")
        phase_ax.plot(x_axis, _phase(X[:, i]), color=color, lw=1.4, label=name)
    try:
        natural = analysis.modes().omega / FREQUENCY[f_unit]
    except SolveError:
        natural = []
    for k, w in enumerate(natural):
        if x_axis.size and x_axis[0] <= w <= x_axis[-1]:
            for ax in (amp_ax, phase_ax):
                ax.axvline(w, color="0.4", ls="--", lw=0.9)
            amp_ax.annotate(f"omega{k + 1} = {w:.4g}", (w, 1), xycoords=("data", "axes fraction"),
                            xytext=(3, -12), textcoords="offset points", fontsize=8)
    amp_ax.set_ylabel("amplitude")
    amp_ax.legend(fontsize=8)
    phase_ax.set_ylabel("phase [deg]")
    phase_ax.set_xlabel(f"forcing frequency Omega [{f_unit}]")
    for ax in (amp_ax, phase_ax):
        ax.grid(True, alpha=0.35)
    amp_ax.set_title(_wrap(mech.title))
    fig.tight_layout()
    _save_figure(fig, output)
    return said


def _phase(x):
    """The phase of ``x`` in degrees, unwrapped along each stretch between breaks (NaN)."""
    out = np.full(x.shape, np.nan)
    rows = np.nonzero(np.isfinite(x))[0]
    for part in np.split(rows, np.nonzero(np.diff(rows) != 1)[0] + 1):
        out[part] = np.degrees(np.unwrap(np.angle(x[part])))
    return out


def _positions(lag, q):
    kin = lag.solver.positions(q[0] if lag.n == 1 else tuple(q))
    lag.solver.check(kin, velocities=False)
    return kin.pos


def modes(mech, output: str, dpi: int = 100) -> None:
    """Every mode drawn on the mechanism at equilibrium (grey) and displaced both ways."""
    check_output(output, IMAGE_FORMATS)
    _require_vibration(mech, "a picture of the modes")
    analysis = analyse(mech)
    lin = analysis.lin
    lag = lin.lag
    found = analysis.modes()
    count = len(found.omega)
    fig = figure(5.0 * min(count, 3), 4.6 * ((count + 2) // 3), dpi)
    f_unit = mech.units.names["frequency"]
    rest = _positions(lag, lin.eq.q)
    size = lag.size
    for k in range(count):
        ax = fig.add_subplot((count + 2) // 3, min(count, 3), k + 1)
        shape = np.zeros(lag.n)
        shape[lin.free] = found.shapes[:, k]
        scale = _mode_scale(lag, lin.eq.q, shape, 0.1 * size)
        views = []
        for sign, color in ((1, COLORS[0]), (-1, COLORS[6])):
            scene = Scene(mech, _positions(lag, lin.eq.q + sign * scale * shape))
            draw_outline(ax, scene, color)
            views += [scene.p[n] for n in mech.points]
        scene = Scene(mech, rest)
        draw_mechanism(ax, scene, mech.dynamics, labels=True)
        draw_elements(ax, scene, mech.elements)
        views += [scene.p[n] for n in mech.points]
        set_limits(ax, views, scene.size)
        w = found.omega[k] / FREQUENCY[f_unit]
        ax.set_title(f"mode {k + 1}: {w:.4g} {f_unit}", fontsize=10)
        ax.set_xlabel(f"x [{scene.l_unit}]")
        ax.grid(True, alpha=0.25)
    fig.suptitle(_wrap(mech.title), fontsize=10)
    fig.tight_layout()
    _save_figure(fig, output)


def _mode_scale(lag, q, shape, target):
    """The factor that moves the mode's farthest point by about ``target`` (m)."""
    jt = lag.jet(q, second=False)
    largest = 0.0
    for p in jt.pos:
        moved = abs(sum(jt.d1(p, j) * shape[j] for j in range(lag.n)))
        largest = max(largest, float(np.max(moved)))
    return target / largest if largest > 0 else 0.0


def free(mech, span: str, names, output: str, dpi: int = 100) -> None:
    """Free response from ``initial``: the linear model and the nonlinear equations."""
    check_output(output, IMAGE_FORMATS)
    _require_vibration(mech, "a time response")
    analysis = analyse(mech)
    lin = analysis.lin
    if not mech.elements.initial and mech.elements.initial_from[0] == "equilibrium":
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
