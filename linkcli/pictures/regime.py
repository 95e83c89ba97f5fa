"""The periodic regime in pictures: w(q) over a cycle and the turning-moment (energy) diagram.

The diagram draws the reduced torque Q(q, w(q)) on the orbit against q: it is the books'
turning moment less the mean resisting torque, so the mean line is Q = 0.  Between two
consecutive zeros of Q lies a lobe whose area is the energy the machine gains (above) or
gives back (below): E(q_b) - E(q_a) = integral of Q dq.  The lobes from the slowest-energy
position to the fastest-energy one (in the sense of q, through the cycle's end) are the
ones that size the flywheel: their areas add up to DeltaE.  They are shaded darker and
each is labelled with its area.  matplotlib is imported inside the functions.
"""
from __future__ import annotations

import textwrap
from dataclasses import dataclass

import numpy as np

from linkcli.errors import InputError
from linkcli.forces.regime import Regime

#: samples per cycle of the curves and of each lobe's outline
SAMPLES = 1441


@dataclass(frozen=True)
class Lobe:
    """One area between Q and its mean line: q from ``start`` to ``end`` (SI, end > start,
    past the cycle's end where it wraps), its area (J, signed) and whether it sizes the
    flywheel; ``q`` and ``Q`` the outline shaded."""

    start: float
    end: float
    area: float
    sizing: bool
    q: np.ndarray
    Q: np.ndarray


def torque_on_orbit(reg: Regime, q):
    """Q(q, w(q)) along the orbit."""
    return reg.cycle.Q(q, reg.speed(q))


def zeros(reg: Regime) -> np.ndarray:
    """The zeros of Q on the orbit over one cycle, located by Brent's method between the
    samples where it changes sign (the cycle's start where there is none)."""
    from scipy.optimize import brentq

    c = reg.cycle
    q = c.q(SAMPLES - 1)
    Q = torque_on_orbit(reg, q)
    out = []
    for i in range(q.size - 1):
        if Q[i] == 0.0:
            out.append(float(q[i]))
        elif Q[i] * Q[i + 1] < 0:
            out.append(brentq(lambda x: float(torque_on_orbit(reg, np.array([x]))[0]),
                              q[i], q[i + 1], xtol=1e-12 * c.period))
    return np.array(out if out else [c.start])


def lobes(reg: Regime) -> list:
    """The lobes of the diagram over one cycle, in order from the first zero of Q; the run of
    lobes from a position of least energy to the first of most energy after it is marked
    ``sizing`` (their areas add up to DeltaE)."""
    c = reg.cycle
    z = zeros(reg)
    bounds = np.append(z, z[0] + c.period)
    spans = [(a, b) for a, b in zip(bounds[:-1], bounds[1:]) if b - a > 1e-12 * c.period]
    E = reg.energy(np.array([a for a, _ in spans] + [spans[-1][1]]))
    runs = _sizing(E, reg.energy_fluctuation)
    out = []
    for i, (a, b) in enumerate(spans):
        n = max(8, int(SAMPLES * (b - a) / c.period))
        qs = np.linspace(a, b, n + 1)
        out.append(Lobe(float(a), float(b), float(E[i + 1] - E[i]), i in runs, qs,
                        torque_on_orbit(reg, qs)))
    return out


def _sizing(E, dE):
    """The indices of the lobes from the first bound of least energy E[i] (E over the lobes'
    bounds, E[-1] the cycle's return to E[0]) to the first of most energy after it."""
    n = E.size - 1
    tol = 1e-9 * max(dE, 1e-300)
    low = int(np.flatnonzero(E[:n] <= E[:n].min() + tol)[0])
    top = E[:n].max()
    run = []
    for k in range(n):
        i = (low + k) % n
        run.append(i)
        if E[(i + 1) % n] >= top - tol:
            break
    return set(run)


def picture(reg: Regime, units, title: str = "", dpi: int = 100):
    """The figure: w(q) over a cycle above, the turning-moment diagram with its lobes below.

    ``units`` is ``(q_unit, q_factor, w_unit, w_factor, torque_unit, torque_factor)``: each
    name and the SI value of one display unit."""
    from linkcli.pictures.drawing import COLORS, figure

    q_unit, q_f, w_unit, w_f, t_unit, t_f = units
    c = reg.cycle
    q = c.q(SAMPLES - 1)
    fig = figure(8.0, 6.4, dpi)
    top, bottom = fig.subplots(2, 1, sharex=True)
    top.plot(q / q_f, reg.speed(q) / w_f, color=COLORS[0])
    top.axhline(reg.mean_speed / w_f, color="0.5", lw=0.8, ls="--")
    for at, value, label in ((reg.at_max_speed, reg.max_speed, "max"),
                             (reg.at_min_speed, reg.min_speed, "min")):
        top.plot([at / q_f], [value / w_f], "o", color=COLORS[0])
        top.annotate(f"{label} {value / w_f:.4g}", (at / q_f, value / w_f),
                     textcoords="offset points", xytext=(4, 4), fontsize=8)
    top.set_ylabel(f"w [{w_unit}]")
    head = "\n".join(textwrap.wrap(title, 80)) + "\n" if title else ""
    top.set_title(f"{head}delta = {reg.fluctuation:.4g}, "
                  f"DeltaE = {reg.energy_fluctuation:.6g} J", fontsize=10)
    bottom.plot(q / q_f, torque_on_orbit(reg, q) / t_f, color="k", lw=1.0)
    bottom.axhline(0.0, color="0.5", lw=0.8)
    for lobe in lobes(reg):
        x = c.reduce(lobe.q)
        cut = np.flatnonzero(np.diff(x) < 0)
        for part in np.split(np.arange(x.size), cut + 1):
            bottom.fill_between(x[part] / q_f, 0.0, lobe.Q[part] / t_f, lw=0,
                                color=COLORS[1] if lobe.area > 0 else COLORS[6],
                                alpha=0.75 if lobe.sizing else 0.2)
        mid = c.reduce(0.5 * (lobe.start + lobe.end))
        bottom.annotate(f"{lobe.area:+.4g}", (float(mid) / q_f, 0.0), ha="center",
                        fontsize=7, va="bottom" if lobe.area > 0 else "top")
    bottom.set_ylabel(f"Q - mean [{t_unit}]")
    bottom.set_xlabel(f"q [{q_unit}]  (darker: the areas that add up to DeltaE, in J)")
    fig.tight_layout()
    return fig


def plot_regime(mech, output: str, dpi: int = 100) -> None:
    """``linkcli plot FILE --regime -o OUT``: the picture of the file's periodic regime, in
    its units (the driver's angle and rate, its torque)."""
    from linkcli.pictures.plotting import IMAGE_FORMATS, _save_figure, check_output
    from linkcli.runs import machine_regime

    check_output(output, IMAGE_FORMATS)
    spec = machine_regime.spec_of(mech)
    if spec is None or spec.areas:
        raise InputError("the regime's picture needs the turning moment as loads on the "
                         "machine" + (", not a diagram's areas" if spec is not None else
                                      ": 'motion:' asks no periodic regime"),
                         file=mech.file, key="motion.regime", hint="give the loads, or "
                         "add motion: {regime: {mean_speed: ...}}")
    reg = machine_regime.solved(mech)
    q_unit, q_f = mech.units.display("angle", 0)
    w_unit, w_f = mech.units.display("angle", 1)
    t_unit, t_f = mech.units.names["torque"], mech.units.factor("torque")
    fig = picture(reg, (q_unit, q_f, w_unit, w_f, t_unit, t_f), mech.title, dpi)
    _save_figure(fig, output)
