"""Several drivers moved from one: the first driver's values (a sweep's, or ``solve``'s q)
give every driver's value, rate and acceleration.

A mechanism of several drivers (``drivers:``) is solved at a value q of its first driver
with each other driver either held at the file's value and rates, or tied to the first by
an expression of it, q_j = f(q) (``sweep --tie NAME=EXPR``), written in display units: its
rates follow by the chain rule, q_j' = f'(q) q', q_j'' = f''(q) q'^2 + f'(q) q''.
A file of one driver is left as it is: (q, q', q'').
"""
from __future__ import annotations

import copy

import numpy as np

from linkcli.errors import ExpressionError, InputError
from linkcli.input.expressions import Expression, Rates


def led_by(mech, name: str | None):
    """``mech`` with the driver ``name`` first (the one a sweep runs over and ``q`` names),
    the others after it in the file's order; ``mech`` itself when it is first already."""
    drivers = [c.name for c in mech.coordinates]
    if name is None or name == drivers[0] and mech.elements is None:
        return mech
    if mech.elements is not None or name not in drivers:
        raise InputError(f"--driver {name}: not a driver of this file; its drivers: "
                         + (", ".join(drivers) if mech.elements is None else "none"),
                         file=mech.file, key="--driver",
                         hint="name one of 'drivers:', or leave --driver out (the first)")
    lead = copy.copy(mech)
    first = mech.coordinates[drivers.index(name)]
    lead.coordinates = (first,) + tuple(c for c in mech.coordinates if c is not first)
    lead.driver = first
    return lead


class Drive:
    """Every driver's (values, rates, accelerations) in SI from the first driver's."""

    def __init__(self, mech, ties=None):
        self.mech = mech
        self.ties = {}              # index of a tied driver -> its Expression of the first's
        for name, text in (ties or {}).items():
            index = self._tied(name)
            self.ties[index] = self._expression(name, text)

    @property
    def several(self) -> bool:
        return len(self.mech.coordinates) > 1

    def _tied(self, name) -> int:
        drivers = [c.name for c in self.mech.coordinates]
        if self.mech.elements is not None or name not in drivers[1:]:
            words = "another driver than the first, " + ", ".join(drivers[1:]) \
                if len(drivers) > 1 and self.mech.elements is None else "none (one driver)"
            raise InputError(f"--tie {name}: a tie sets a driver other than the first, the "
                             f"one swept; this file's: {words}", file=self.mech.file,
                             key="--tie", hint="write --tie NAME=EXPR with NAME a driver "
                             f"and EXPR an expression of {drivers[0]}")
        return drivers.index(name)

    def _expression(self, name, text) -> Expression:
        first = self.mech.coordinates[0].name
        try:
            expr = Expression(text)
        except ExpressionError as exc:
            raise InputError(f"--tie {name}: {exc.detail}", file=self.mech.file,
                             key="--tie") from None
        other = [n for n in expr.names if n not in (first, "q")]
        if other:
            raise InputError(f"--tie {name}={text}: reads {', '.join(other)}; a tie is an "
                             f"expression of the swept driver {first} alone",
                             file=self.mech.file, key="--tie",
                             hint=f"write it with {first} (in its display unit) and numbers")
        return expr

    def __call__(self, q, qd, qdd, held=True) -> tuple:
        """(values, rates, accelerations): each a tuple over the drivers (one driver: the
        three as given).  ``held`` False: the drivers not tied keep their values and stand
        still (rates 0), the motion along a sweep's path of q."""
        if not self.several:
            return q, qd, qdd
        q, qd, qdd = (np.asarray(x, dtype=float) for x in (q, qd, qdd))
        zero = 0 * (q + qd + qdd)
        out = [[q + zero], [qd + zero], [qdd + zero]]
        for j, c in enumerate(self.mech.coordinates[1:], start=1):
            terms = self._tie(j, q, qd, qdd) if j in self.ties else \
                (c.value, c.rate, c.accel) if held else (c.value, 0.0, 0.0)
            for row, term in zip(out, terms):
                row.append(term + zero)
        return tuple(tuple(row) for row in out)

    def _tie(self, j, q, qd, qdd) -> tuple:
        """q_j and its rates (SI) from its expression of the first driver, evaluated in the
        display units of both (their angle or length unit; rates per second)."""
        first, tied = self.mech.coordinates[0], self.mech.coordinates[j]
        f0 = self.mech.units.display(first.base, 0)[1]
        fj = self.mech.units.display(tied.base, 0)[1]
        arg = Rates((q / f0, qd / f0, qdd / f0))
        value = Rates.lift(self.ties[j].value({first.name: arg, "q": arg}), 2)
        return tuple(np.asarray(t, dtype=float) * fj for t in value.terms)


class Path:
    """A solver of several drivers seen along a sweep's path of its first driver: positions
    at the first driver's values q, velocities per its rate (the others held still or
    moving with their ties), for what locates toggles between a sweep's samples."""

    def __init__(self, solver, drive: Drive):
        self._solver, self._drive = solver, drive

    def __getattr__(self, name):
        return getattr(self._solver, name)

    def positions(self, q):
        return self._solver.positions(self._drive(q, 0.0, 0.0, held=False)[0])

    def velocities(self, kin, qd):
        return self._solver.velocities(kin, self._drive(kin.q, qd, 0.0, held=False)[1])
