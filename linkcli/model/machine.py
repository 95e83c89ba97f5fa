"""Machine dynamics data: the motor's characteristic, a load's window of the driver, and
what the integration of the motion needs (the ``motion:`` section), in SI units.

A motor is a torque M(w) on a body, w the body's angular velocity (rad/s), given as

- 'linear': M = stall (1 - w / no_load)  (the stall torque and the no-load speed);
- 'table': M interpolated linearly between (speeds[i], torques[i]), refused outside;
- 'expression': M = f(w), a function of w (rad/s) to N m built by the reader from the
  file's expression (written in the file's units).

A window ``(q1, q2)`` of the driver (rad or m) switches a load on while q, taken modulo
a turn for an angle driver, lies in [q1, q2] (through 0 when q1 > q2).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

TURN = 2 * math.pi


@dataclass(frozen=True)
class Characteristic:
    """A motor's torque-speed characteristic M(w) (N m against rad/s)."""

    kind: str                       # 'linear' | 'table' | 'expression'
    stall: float = 0.0
    no_load: float = 0.0
    speeds: tuple = ()
    torques: tuple = ()
    function: object = field(default=None, compare=False)   # (w, q, t) SI -> M (N m)
    text: str = ""                  # as the file writes it, for messages

    def torque(self, w, q=0.0, t=0.0):
        """M(w) for an array of speeds w (rad/s) (an expression may also read the driver's
        q and the time t, SI); a speed outside a table gives NaN here, which
        :meth:`outside` names before it is used."""
        w = np.asarray(w, dtype=float)
        if self.kind == "linear":
            return self.stall * (1.0 - w / self.no_load)
        if self.kind == "table":
            return np.interp(w, self.speeds, self.torques, left=np.nan, right=np.nan)
        return np.asarray(self.function(w, q, t), dtype=float) + 0.0 * w

    def scalar(self, w: float, q: float, t: float) -> float:
        """M(w) of one state, in floats (a step of the integration)."""
        if self.kind == "linear":
            return self.stall * (1.0 - w / self.no_load)
        return float(self.torque(w, q, t))

    def outside(self, w) -> float | None:
        """The first speed of ``w`` outside a table's range, None when every one is inside."""
        if self.kind != "table":
            return None
        w = np.atleast_1d(np.asarray(w, dtype=float))
        bad = (w < self.speeds[0]) | (w > self.speeds[-1])
        return float(w[np.argmax(bad)]) if bad.any() else None


def in_window(q, window, angular: bool):
    """1.0 where the driver value q lies in ``window`` (modulo a turn for an angle driver),
    0.0 elsewhere; 1.0 everywhere without a window."""
    q = np.asarray(q, dtype=float)
    if window is None:
        return np.ones_like(q)
    lo, hi = window
    if angular:
        span = (hi - lo) % TURN
        return (((q - lo) % TURN) <= span).astype(float)
    return ((q >= lo) & (q <= hi)).astype(float)


def inside(q: float, window, angular: bool) -> bool:
    """:func:`in_window` of one driver value, in floats."""
    lo, hi = window
    if angular:
        return (q - lo) % TURN <= (hi - lo) % TURN
    return lo <= q <= hi


@dataclass(frozen=True)
class MotionSpec:
    """The ``motion:`` section: the longest time the motion is integrated (s)."""

    until: float = 60.0
    #: reserved for the periodic regime and the flywheel (read by their own modules)
    extra: dict = field(default_factory=dict, compare=False)
