"""The driver values of a sweep: ``q_i = start + i * delta`` for i < count.

The values are computed from their index, never accumulated, so the last one is the
same however the range is cut into blocks; with ``--steps`` the last value is ``--to``
exactly.  They are made a block at a time (:class:`DriverRange`): a 10^7-position sweep
never holds them all.  Values are in the driver's display unit (deg, mm, ...).
"""
from __future__ import annotations

import math

import numpy as np

from linkcli.errors import InputError

MAX_POSITIONS = 10 ** 7


class DriverRange:
    """The driver values ``start + i * delta`` (i < count; the last one ``last`` when given),
    made a block at a time: a 10^7-position sweep never holds them all."""

    def __init__(self, start: float, delta: float, count: int, last: float | None = None):
        self.start, self.delta, self.size, self.last = start, delta, count, last

    def __len__(self) -> int:
        return self.size

    def block(self, lo: int, hi: int) -> np.ndarray:
        q = self.start + np.arange(lo, hi) * self.delta
        if self.last is not None and hi == self.size and hi > lo:
            q[-1] = self.last
        return q

    def at(self, index) -> np.ndarray:
        """The values at the integer array ``index`` (the last one ``last`` when given)."""
        q = self.start + index * self.delta
        if self.last is not None:
            q = np.where(index == self.size - 1, self.last, q)
        return q

    def __array__(self, dtype=None, copy=None):
        q = self.block(0, self.size)
        return q if dtype is None else q.astype(dtype)


def driver_range(start: float, stop: float, steps: int | None = None,
                 step: float | None = None) -> DriverRange:
    """q_i = start + i * step; ``steps`` intervals (both ends included) or a ``step`` > 0."""
    if (steps is None) == (step is None):
        raise InputError("give either --steps N or --step S", key="--steps",
                         hint="--steps 360 splits the range into 360 intervals")
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise InputError("--from and --to must be finite numbers", key="--from")
    if steps is not None:
        if steps < 1:
            raise InputError(f"--steps must be at least 1, got {steps}", key="--steps")
        count = steps + 1
        delta = (stop - start) / steps
    else:
        if not (math.isfinite(step) and step > 0):
            raise InputError(f"--step must be a positive number, got {step}", key="--step",
                             hint="the direction follows --from and --to")
        span = abs(stop - start)
        count = int(math.floor(span / step * (1 + 1e-12))) + 1 if span / step < 1e12 else \
            MAX_POSITIONS + 1
        delta = math.copysign(step, stop - start) if stop != start else step
    if count > MAX_POSITIONS:
        raise InputError(f"{count} positions is more than the limit of {MAX_POSITIONS}",
                         key="--steps", hint="use fewer steps or split the range")
    return DriverRange(start, delta, count, stop if steps is not None else None)


def driver_values(start: float, stop: float, steps: int | None = None,
                  step: float | None = None) -> np.ndarray:
    """The values of :func:`driver_range` as one array."""
    return np.asarray(driver_range(start, stop, steps, step))


def block_of(q, lo: int, hi: int) -> np.ndarray:
    """The values ``lo`` to ``hi`` (excluded) of ``q``, a :class:`DriverRange` or an array."""
    return q.block(lo, hi) if isinstance(q, DriverRange) else q[lo:hi]


def values_at(q, index) -> np.ndarray:
    """The values of ``q`` (a :class:`DriverRange` or an array) at the integer array ``index``."""
    return q.at(index) if isinstance(q, DriverRange) else q[index]
