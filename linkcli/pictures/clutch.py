"""The picture of a clutch problem: the two shafts' speeds in time, through the slip to the
common speed and after it (the locked shafts), the engagement marked with its time and
speed.  Speeds in the file's angular rate unit, times in its time unit."""
from __future__ import annotations

import numpy as np

from linkcli.pictures.drawing import COLORS, figure
from linkcli.pictures.plotting import IMAGE_FORMATS, _save_figure, _wrap, check_output
from linkcli.runs import clutch_sheet

#: the picture runs to this many times the slip time (the motion after it shown too)
SPAN = 1.6
SAMPLES = 400


def speeds(mech, output: str, dpi: int = 100) -> None:
    """The two speeds in time, written to ``output`` (.png, .svg, .pdf)."""
    check_output(output, IMAGE_FORMATS)
    _save_figure(speeds_figure(mech, dpi), output)


def samples(mech):
    """(t, w1, w2) in SI from 0 to SPAN times the slip time; w2 of a brake is the frame's 0.
    After the engagement a clutch that slips again is refused (runs.clutch)."""
    tr = clutch_sheet.transient(mech)
    end = SPAN * tr.slip_time if tr.slip_time > 0 else 1.0
    t = np.linspace(0.0, end, SAMPLES)
    state = np.array([tr.speeds_at(float(x))[:2] for x in t])
    return t, state[:, 0], state[:, 1]


def speeds_figure(mech, dpi: int = 100):
    """The figure of :func:`speeds`."""
    tr = clutch_sheet.transient(mech)
    units = mech.units
    rate, time = units.names["angular_rate"], units.names["time"]
    f_rate, f_time = units.factor("angular_rate"), units.factor("time")
    t, w1, w2 = samples(mech)
    clutch = mech.clutch.clutch
    fig = figure(8.0, 4.6, dpi)
    ax = fig.subplots()
    ax.plot(t / f_time, w1 / f_rate, color=COLORS[0], lw=1.8, label=clutch.driving)
    ax.plot(t / f_time, w2 / f_rate, color=COLORS[1], lw=1.8,
            label=clutch.driven or "frame (brake)")
    ax.axvline(tr.slip_time / f_time, color="0.5", lw=0.8, ls="--")
    ax.plot([tr.slip_time / f_time], [tr.speed / f_rate], "o", color="k", ms=4)
    ax.annotate(f"engaged: t = {tr.slip_time / f_time:.4g} {time}, "
                f"w = {tr.speed / f_rate:.4g} {rate}", (tr.slip_time / f_time, tr.speed / f_rate),
                textcoords="offset points", xytext=(8, 8), fontsize=8)
    ax.set_xlabel(f"t [{time}]")
    ax.set_ylabel(f"speed [{rate}]")
    ax.grid(True, alpha=0.35)
    ax.legend(fontsize=8)
    ax.set_title(_wrap(mech.title))
    fig.tight_layout()
    return fig
