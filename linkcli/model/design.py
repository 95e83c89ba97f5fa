"""A design question (``find:``): parameters of the file that are unknown, and the answers
they must give.

    find:
      unknowns:
        ks: {between: [100, 10000]}      # a search interval, as the file writes ks
        m: {start: 2}                    # or a start value
      targets: {f1: 1 Hz, T: 0.5 s}      # as many as unknowns: an answer and its value
      choose: smallest                   # largest, or {nearest: V}: one of several roots
                                         # (V in the interval's unit, or '900 mm')

Values of unknowns are in the unit the file writes the parameter in (``unit:`` gives the
interval in another of its dimension, converted); a target's value is in its ``unit``, or
in the answer's display unit when it has none.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Unknown:
    """A parameter to solve for: in [lo, hi] (both given) or from ``start``."""

    name: str
    lo: float | None = None
    hi: float | None = None
    start: float | None = None
    unit: str | None = None        # as written, before it is converted (input.find)
    line: int | None = None

    @property
    def interval(self) -> bool:
        return self.lo is not None


@dataclass(frozen=True)
class Target:
    """An answer of the file (a quantity or its rate) and the value it must have: ``value``
    in ``unit`` (None: in the answer's display unit); ``text`` as written."""

    name: str
    value: float
    unit: str | None
    text: str
    line: int | None = None


@dataclass(frozen=True)
class Design:
    """The unknowns, the targets, the rule that picks one of several roots (('smallest',),
    ('largest',) or ('nearest', value), the value as the file writes the unknown once
    input.find has converted it; None: several roots are refused), and whether the
    unknowns were given values (``fixed``: the mechanism is a trial of the search, or the
    solution)."""

    unknowns: tuple
    targets: tuple
    choose: tuple | None = None
    fixed: bool = False

    @property
    def names(self) -> list:
        return [u.name for u in self.unknowns]
