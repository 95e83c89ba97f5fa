"""Limit positions: the greatest maximum and least minimum of a quantity and where they are.

The maximum asked of N is the greatest of its maxima, max(level), the minimum the least of
its minima, min(level) (level: the value along the motion, an angle unwrapped); of several
equal to 1e-9 of the largest |level|, the first in driver order (a speed's two equal maxima
over a turn).  at_maximum (at_minimum) is that extreme's driver value q, in the driver's
display unit: for the slider of a slider-crank the crank angles of the dead centres.  A
dwell holds its extreme over a stretch of q, so its position is refused, not picked.  A
limit needs the extremes it is made of: a maximum (minimum) and where it is need one; a
stroke or a time ratio needs both.
"""
from __future__ import annotations

from linkcli.answers.formats import fmt
from linkcli.runs.limits.extremes import Extreme, num

#: the limits that are one extreme or its position
EXTREMES = ("maximum", "minimum", "at_maximum", "at_minimum")


def require(found, kind: str, of: str, undefined) -> None:
    """Refuse (``undefined(detail, hint)``) a limit ``kind`` of ``of`` whose maximum or
    minimum ``found`` lacks over its range."""
    for wanted in ("maximum", "minimum"):
        if not found.of(wanted) and (kind in (wanted, "at_" + wanted) or kind not in EXTREMES):
            other = "minimum" if wanted == "maximum" else "maximum"
            raise undefined(f"{of} has no {wanted} over {found.range_text()}, only a {other}"
                            f" at q = {', '.join(num(e.q) for e in found.of(other))} "
                            f"{found.q_unit}")


def answer(found, kind: str, of: str, undefined):
    """(value, unit) of the maximum, minimum or where one is (``kind`` in EXTREMES)."""
    wanted = kind.replace("at_", "")
    pick = first_extreme(found.of(wanted), wanted)
    if kind.startswith("at_"):
        if pick.span is not None:
            raise undefined(f"{of} holds its {wanted} ({fmt(pick.value, 4)} {found.unit}) "
                            f"over q = {pick.where()} {found.q_unit} (its rate is 0 to "
                            "rounding there), not at one position",
                            hint=f"ask for the {wanted} itself")
        return pick.q, found.q_unit
    return pick.value, found.unit


def first_extreme(some: list, wanted: str) -> Extreme:
    """The greatest maximum (least minimum); of several equal to rounding (1e-9 of the
    largest value), the first in driver order (a speed's two equal maxima)."""
    sign = 1.0 if wanted == "maximum" else -1.0
    best = max(sign * e.level for e in some)
    size = max(abs(e.level) for e in some)
    return next(e for e in some if sign * e.level >= best - 1e-9 * size)
