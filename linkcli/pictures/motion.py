"""The motion of a machine in time: the driver's speed w(t) from its start state (at rest,
at a speed) under the file's loads, and its position q(t) turned from the start, as
``plot --motion 0:T:STEPS`` draws them.  Speeds in the driver's rate unit (counter-clockwise
positive for an angle), times in the file's time unit.  The samples are the integration's
own states at those times (runs.machine_motion), never an interpolation of them.
"""
from __future__ import annotations

import numpy as np

from linkcli.errors import InputError
from linkcli.pictures.drawing import COLORS, figure
from linkcli.pictures.plotting import (IMAGE_FORMATS, _save_figure, _wrap, check_output,
                                      parse_sweep)
from linkcli.runs.machine_motion import integrate


#: the most samples one picture takes (each one a state the integration stops at)
MOST = 20000


def motion(mech, span: str, output: str, dpi: int = 100) -> None:
    """w(t) and q(t) - q(0) over the times of ``span`` (0:T:STEPS), written to ``output``."""
    check_output(output, IMAGE_FORMATS)
    _save_figure(motion_figure(mech, span, dpi), output)


def times(mech, span: str) -> np.ndarray:
    """The times of ``--motion 0:T:STEPS`` in SI: from 0 to a positive end, at most MOST."""
    factor = mech.units.factor("time")
    t = parse_sweep(span, key="--motion") * factor
    if t[0] != 0 or not t[-1] > 0 or np.any(np.diff(t) <= 0):
        raise InputError(f"times '{span}' must run from 0 up to a positive end", key="--motion",
                         file=mech.file, hint="e.g. --motion 0:5:500 (in the file's time unit)")
    if t.size > MOST:
        raise InputError(f"times '{span}': {t.size} samples is more than {MOST}",
                         key="--motion", file=mech.file, hint=f"take at most {MOST - 1} steps")
    return t


def samples(mech, span: str) -> tuple:
    """(t, q - q0, w) in SI at the times of ``span``."""
    t = times(mech, span)
    found = integrate(mech, times=tuple(float(x) for x in t))
    states = np.array([found.state(float(x))[:2] for x in t])
    return t, states[:, 0] - found.q0, states[:, 1]


def motion_figure(mech, span: str, dpi: int = 100):
    """The figure of :func:`motion`: the speed above, the motion from the start below."""
    t, moved, w = samples(mech, span)
    units, base = mech.units, mech.driver.base
    rate, f_rate = units.display(base, 1)
    place, f_place = units.display(base, 0)
    time, f_time = units.names["time"], units.factor("time")
    fig = figure(8.0, 6.0, dpi)
    top, bottom = fig.subplots(2, 1, sharex=True)
    top.plot(t / f_time, w / f_rate, color=COLORS[0], lw=1.6)
    top.set_ylabel(f"q' [{rate}]")
    bottom.plot(t / f_time, moved / f_place, color=COLORS[1], lw=1.6)
    bottom.set_ylabel(f"q - q(0) [{place}]")
    bottom.set_xlabel(f"t [{time}]")
    for ax in (top, bottom):
        ax.grid(True, alpha=0.35)
    top.set_title(_wrap(mech.title))
    fig.tight_layout()
    return fig
