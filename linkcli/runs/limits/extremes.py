"""The extremes of a quantity over a range of the driver, as found: the data of the limits.

An extreme is a driver value q (display unit of the driver) where the quantity N(q) is
stationary, dN/dq = 0, its rate changing sign: a maximum where dN/dq goes from + to - as q
grows, a minimum from - to +.  Its ``level`` is N along the motion (an angle unwrapped, so
that a swing through 0 is not read as a turn); a dwell (``span``) is an extreme held, to
rounding, over a stretch of the driver (``runs.limits.dwell``).  ``Limits`` holds every
extreme of one quantity over the range start..stop with what follows from them: the stroke
(``runs.limits.strokes``) and, over a full turn of a crank, the sweeps and times of a quick
return (``runs.limits.quick_return``).
"""
from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Extreme:
    """A stationary point of a quantity: driver value and value, display units."""

    q: float
    value: float
    kind: str                   # 'maximum' | 'minimum'
    level: float = field(default=0.0, compare=False)   # the value along the motion (unwrapped)
    #: (first, last) driver value of a dwell: the value held, to rounding, over that stretch
    span: tuple | None = field(default=None, compare=False)

    def where(self) -> str:
        """Its driver value, or the stretch of a dwell."""
        return num(self.q) if self.span is None else f"{num(self.span[0])}..{num(self.span[1])}"


@dataclass
class Limits:
    """The extremes of the quantity ``name`` over the driver range ``start``..``stop``."""

    name: str
    unit: str
    q_unit: str
    start: float
    stop: float
    periodic: bool                                   # the range is one full turn
    turn: float | None = None                        # one turn, display units (angle driver)
    extremes: list = field(default_factory=list)     # [Extreme], by driver value
    stroke: float | None = None                      # greatest maximum - least minimum
    sweeps: tuple | None = None                      # (working, return) driver sweeps
    times: tuple | None = None                       # (working, return) strokes' times, s
    notes: list = field(default_factory=list)        # what could not be solved, with where
    why: str = ""                                    # why there is no extreme, when none
    whole: bool = True                               # every grid value assembled
    position: bool = True                            # a position quantity: it has strokes
    constant: float | None = None                    # the value, where constant to rounding

    @property
    def time_ratio(self) -> float | None:
        return None if self.sweeps is None else self.sweeps[0] / self.sweeps[1]

    def range_text(self) -> str:
        return f"q = {num(self.start)}..{num(self.stop)} {self.q_unit}"

    def of(self, kind: str) -> list:
        return [e for e in self.extremes if e.kind == kind]


def num(x: float) -> str:
    """A driver value or a value in messages: ten significant digits."""
    return f"{x:.10g}"
