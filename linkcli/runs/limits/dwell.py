"""Dwell: a quantity held, to rounding, over a stretch of the driver or over the whole range.

A sampled rate dN/dq has no sign where it is within the rounding it carries
(``runs.limits.search``).  Two or more such samples between a rising and a falling part are
a dwell: an extreme held over that stretch, whose value is the median of its samples
(0 where that median is itself rounding: TOGGLE of the quantity's size S over m^(level + 1),
m the least conditioning of the stretch, level 0 for a position quantity and 1 for a rate or
a speed), never a position that rounding picked.  A quantity whose every run is held, all at
one value to 1e-9 of it (an angle compared modulo its period), is constant: its maximum and
minimum are that value, its stroke 0, and where they are (at_maximum, at_minimum) and its
time ratio are refused.
"""
from __future__ import annotations

import numpy as np

from linkcli.answers.formats import fmt
from linkcli.kinematics import toggles


def held(probe, shown, level, natural, conditioning) -> float:
    """The value a run constant to rounding holds: the middle of its samples, 0 where that
    is itself rounding (TOGGLE of the quantity's size over m^(level + 1), the rounding of
    a value of that order next to a toggle), so noise such as 1e-10 is never a value."""
    value = float(np.median(shown))
    size = max(float(np.max(np.abs(level))), natural)
    least = max(float(np.min(conditioning)), toggles.EPS)
    return 0.0 if toggles.negligible(value, size / least ** (probe.level + 1)) else value


def constant(scales, period) -> float | None:
    """The value of a quantity constant (to rounding) over every run of the range, when all
    the runs hold the same value to 1e-9 of it; None otherwise."""
    values = [value for *_, value in scales]
    if not values or any(value is None for value in values):
        return None
    gap = np.abs(np.array(values) - values[0])
    if period is not None:
        gap = np.minimum(gap, period - gap % period)
    size = max(float(np.max(np.abs(values))), 1e-300)
    return values[0] if float(np.max(gap)) <= 1e-9 * size else None


def of_constant(found, kind: str, undefined):
    """(value, unit) of a limit of a quantity constant to rounding: its maximum and minimum
    are the constant, its stroke 0; where they are, or a time ratio, is refused
    (``undefined(detail, hint)``: the located error)."""
    value = f"{fmt(found.constant, 4)} {found.unit}".rstrip()
    if kind in ("maximum", "minimum"):
        return found.constant, found.unit
    if kind == "stroke" and found.stroke is not None:
        return found.stroke, found.unit
    what = "its maximum and minimum are at every position" if kind.startswith("at_") else \
        "it has no strokes"
    raise undefined(f"{found.name} is constant ({value}) over {found.range_text()}, its rate "
                    f"0 to rounding: {what}", hint="ask for the maximum or minimum itself")
