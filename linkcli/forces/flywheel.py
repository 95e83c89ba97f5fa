"""The flywheel that keeps a machine's speed within a coefficient of fluctuation.

A flywheel is a constant inertia J_f added to the reduced inertia J*(q) on the driver's
shaft.  Two answers for a coefficient delta = (w_max - w_min) / w_m:

- the books' approximation: the whole inertia DeltaE / (w_m^2 delta), DeltaE the largest
  fluctuation of energy read off the turning-moment diagram at the mean speed w_m, less
  the machine's own inertia (its mean over the cycle; none in the books' crankshafts); it
  takes J* as constant and w_m as (w_max + w_min) / 2 (exact for a constant inertia then,
  since DeltaE = 1/2 J (w_max^2 - w_min^2));
- the exact one, the J_f whose regime (the same mean speed where the loads do not depend on
  the speed, the motor's balance where they do) has exactly delta on the true orbit, found
  by Brent's method: delta falls as J_f grows.

The two agree to O(delta) in relative terms (the variation of J* and of the speed in Q
against J_f, which grows as 1 / delta), and to O(delta^2) for a constant J* and loads
independent of the speed (only the two means differ: J_exact / J_approx = w_m / w_a).
"""
from __future__ import annotations

import math

import numpy as np
from dataclasses import dataclass, replace

from linkcli.errors import RegimeError
from linkcli.forces.regime import (Cycle, Load, Regime, at_speed, balance_speed,
                                    check_balance, extreme, regime, work)

#: the relative tolerance of the exact flywheel's coefficient: the energy method's, and the
#: shooting's (above its noise, about 1e-8 / delta)
XTOL = 1e-11
SHOT_XTOL = 1e-7


@dataclass(frozen=True)
class Flywheel:
    """The flywheel for the coefficient ``fluctuation``: ``approximate`` (the books'
    formula; <= 0 where by it the machine's own inertia is enough) and ``exact`` (kg m^2),
    and the regime the exact one gives."""

    fluctuation: float
    approximate: float
    exact: float
    regime: Regime


def approximate(cycle: Cycle, fluctuation: float, mean_speed: float | None = None):
    """(J_f, DeltaE, w_m): J_f = DeltaE / (w_m^2 delta) - mean J*, DeltaE the largest
    fluctuation of the work of Q over a cycle at the constant speed w_m (the mean speed
    given, or the motor's balance where the loads depend on the speed), as the books read it
    off the turning-moment diagram; the machine's own inertia (its mean over the cycle, zero
    for the books' crankshafts) is part of the inertia the formula asks for."""
    _check_asked(fluctuation)
    w = balance_speed(cycle) if cycle.speed_dependent else mean_speed
    if not cycle.speed_dependent:
        check_balance(cycle)
    diagram = books_diagram(cycle, w)
    W = work(diagram)
    q = cycle.q()

    def torque(x):
        return diagram.Q(x, np.full(np.shape(x), w))

    dE = extreme(cycle, W, W(q), +1, torque)[1] - extreme(cycle, W, W(q), -1, torque)[1]
    own = float(np.mean(cycle.with_flywheel(0.0).J(q[:-1])))
    return dE / (w * w * fluctuation) - own, dE, w


def books_diagram(cycle: Cycle, w: float) -> Cycle:
    """The turning-moment diagram at the constant speed w, as the books draw it: every load
    at w and the inertia torque of the varying J*, -1/2 dJ*/dq w^2 (the reciprocating
    masses' inertia forces)."""
    loads = tuple(Load(ld.name, at_speed(ld.torque, w)) for ld in cycle.loads)
    inertia = Load("inertia", lambda q, _w: -0.5 * cycle.dJ(q) * w * w)
    return replace(cycle, loads=loads + (inertia,))


def flywheel(cycle: Cycle, fluctuation: float, mean_speed: float | None = None) -> Flywheel:
    """Both flywheels for the coefficient ``fluctuation``; the cycle's own flywheel is
    replaced by the one sought.  Refused where no flywheel gives it: the machine alone
    fluctuates less (a negative flywheel would be needed)."""
    guess, dE, w = approximate(cycle, fluctuation, mean_speed)
    bare = cycle.with_flywheel(0.0)
    alone = _machine_alone(bare, mean_speed)
    if alone is not None and alone.fluctuation <= fluctuation:
        raise RegimeError(f"no flywheel gives a coefficient of fluctuation of {fluctuation:.6g}: "
                          f"the machine alone gives {alone.fluctuation:.6g}, and a flywheel "
                          "only lowers it", reason="no flywheel",
                          values=(fluctuation, alone.fluctuation))
    exact, reg = _solve(bare, fluctuation, mean_speed,
                        max(guess, 0.1 * dE / (w * w * fluctuation)))
    return Flywheel(fluctuation, guess, exact, reg)


def _check_asked(fluctuation: float) -> None:
    if not (isinstance(fluctuation, (int, float)) and math.isfinite(fluctuation)
            and fluctuation > 0):
        raise RegimeError(f"a coefficient of fluctuation of {fluctuation!r} is given by no "
                          "flywheel: it must be a positive number", reason="no flywheel",
                          values=(fluctuation,) if isinstance(fluctuation, float) else ())


def _machine_alone(bare: Cycle, mean_speed):
    """The regime without a flywheel, or None where the machine has no inertia of its own
    (any coefficient is then reachable)."""
    if float(bare.J(bare.q()).min()) <= 0.0:
        return None
    try:
        return regime(bare, mean_speed)
    except RegimeError as err:
        if err.reason in ("stops",):
            return None
        raise


def _solve(bare: Cycle, fluctuation: float, mean_speed, guess: float):
    """log delta against log J_f is nearly a straight line of slope -1: the secant method
    from the books' flywheel, Brent's method between a flywheel too light and one heavy
    enough where the secant does not settle."""
    from scipy.optimize import brentq

    found = {}

    def gap(log_j):
        reg = regime(bare.with_flywheel(math.exp(log_j)), mean_speed)
        found[log_j] = reg
        return math.log(reg.fluctuation / fluctuation)

    tol = SHOT_XTOL if bare.speed_dependent else XTOL
    root = _secant(gap, math.log(max(guess, 1e-300)), tol)
    if root is None:
        high = math.log(max(guess, 1e-300)) + 0.5
        while gap(high) > 0:
            high += 1.0
        low = high - 1.0
        while _gap_or_stop(gap, low) < 0:
            low -= 1.0
        root = brentq(gap, low, high, xtol=tol, rtol=tol)
    reg = found.get(root) or regime(bare.with_flywheel(math.exp(root)), mean_speed)
    return math.exp(root), reg


def _secant(gap, x0, tol, steps=12):
    """The root of gap from x0 and x0 -+ 0.05 by the secant method (|gap| within ``tol``),
    or None."""
    try:
        x1, g1 = x0, gap(x0)
        x2, g2 = x0 - 0.05 if g1 < 0 else x0 + 0.05, None
        g2 = gap(x2)
        for _ in range(steps):
            if abs(g2) <= tol or g2 == g1 or abs(x2 - x1) <= tol:
                return x2 if abs(g2) <= 10 * tol else None
            x1, g1, x2 = x2, g2, x2 - g2 * (x2 - x1) / (g2 - g1)
            g2 = gap(x2)
    except RegimeError:
        return None
    return None


def _gap_or_stop(gap, log_j):
    """The gap, +inf where a flywheel this light lets the machine stop (too light)."""
    try:
        return gap(log_j)
    except RegimeError as err:
        if err.reason == "stops":
            return math.inf
        raise
