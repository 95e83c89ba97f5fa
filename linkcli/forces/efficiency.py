"""Efficiency of a mechanism with friction, in direct and in reverse motion, and self-locking.

The unknown load Q drives the mechanism against the known loads (the user's), gravity and
the inertia forces.  By virtual power (``statics.unknown_load``) Q is found with the losses
(``balance.dynamic_power``) and without them (the ideal load Q0, the same state), and

    direct efficiency   eta = P_out / P_in = Q0 / Q,

since P_in = Q c q' and P_in - W_lost = Q0 c q' (c the power of a unit Q per unit q'):
the power balance Q c q' = Q0 c q' + W_lost.  It is defined where Q drives (P_in > 0).

In reverse motion the load drives and Q holds back: the same positions and accelerations
with the velocities reversed (time run backwards: q' -> -q', q'' kept), the losses opposing
the reversed relative motions.  Q_r is the unknown load found there, and

    reverse efficiency  eta_r = Q_r / Q0,

the power the former driver absorbs over what it would absorb without friction (Q0 is the
same in both senses: the inertia forces do not change when time runs backwards).  An inclined
plane of angle alpha and friction angle phi gives eta = tan(alpha) / tan(alpha + phi) and
eta_r = tan(alpha - phi) / tan(alpha).  eta_r <= 0 is self-locking: the load cannot drive the
mechanism back, the former driver must push it along.  The friction where it starts is the
fraction t of every loss (mu t, u_r t, rho t) where Q_r(t) = 0, found by Brent's method
(:func:`locking_fraction`).

Machines in series pass each one's output to the next: eta = prod eta_i.  Machines in
parallel share the input power P_i: eta = sum eta_i P_i / sum P_i (:func:`series`,
:func:`parallel`).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from linkcli.errors import EfficiencyError
from linkcli.forces import motion as dyn_mod
from linkcli.forces.balance import dynamic_power
from linkcli.forces.statics import coefficient, unknown_load
from linkcli.kinematics.refusals import where_text

#: the fraction of the losses where self-locking starts is found to this relative tolerance
LOCK_TOL = 1e-12
#: the losses are raised up to this many times their values looking for self-locking
LOCK_REACH = 1e6


def ideal_load(mech, kin, unit):
    """Q0 (SI): the unknown load without the losses, at the state ``kin`` (velocities and
    accelerations) with ``unit`` the velocities per unit driver rate."""
    dyn = mech.dynamics
    extra = 0.0
    if dyn is not None:
        extra = dyn_mod.inertia_gravity_power(mech, dyn, kin, unit.vel) + \
            dyn_mod.disc_torque_power(mech, dyn, kin, unit.vel)
    return unknown_load(mech, kin.pos, unit.vel, extra_power=extra, q=kin.q)


def actual_load(mech, kin, unit):
    """Q (SI): the unknown load with the losses at ``kin``."""
    return unknown_load(mech, kin.pos, unit.vel, extra_power=dynamic_power(mech, kin, unit),
                        q=kin.q)


def reversed_state(solver, kin):
    """The kinematics at ``kin``'s positions with the velocities reversed and the
    accelerations kept (the motion with time run backwards)."""
    back = solver.positions(kin.q)
    solver.velocities(back, -np.asarray(kin.qd))
    solver.accelerations(back, kin.qdd)
    return back


def direct(mech, kin, unit, actual=None):
    """eta = Q0 / Q, refused where Q does not drive, with the losses or without them (its
    power Q c q' <= 0 or Q0 c q' <= 0: the loads run the mechanism that way)."""
    q_loss = actual_load(mech, kin, unit) if actual is None else actual
    name = mech.unknown_load().name
    hint = "an efficiency is output over input: make the unknown load the one that drives, " \
        "or ask for the reverse efficiency of the opposite motion"
    _require_positive(mech, kin, q_loss * _lever(mech, kin, unit) * kin.qd, "no input",
                      f"the unknown load {name} does not drive the mechanism",
                      "its power is {value:.6g} W", hint)
    q0 = ideal_load(mech, kin, unit)
    _require_positive(mech, kin, q0 * _lever(mech, kin, unit) * kin.qd, "no ideal input",
                      f"without friction the unknown load {name} would not drive the "
                      "mechanism (the loads run it this way)", "its ideal power is "
                      "{value:.6g} W", hint)
    return q0 / q_loss


def reverse_load(mech, solver, kin, unit, scale=1.0):
    """Q_r (SI): the unknown load in reverse motion, every loss times ``scale``."""
    back = reversed_state(solver, kin)
    scaled = mech if scale == 1.0 else scaled_losses(mech, scale)
    return unknown_load(scaled, back.pos, unit.vel,
                        extra_power=dynamic_power(scaled, back, unit), q=kin.q)


def reverse(mech, solver, kin, unit):
    """eta_r = Q_r / Q0, refused where the load cannot drive the mechanism back even
    without friction (Q0 c q' <= 0: no power for it to give)."""
    q0 = ideal_load(mech, kin, unit)
    _require_ideal(mech, kin, unit, q0)
    return reverse_load(mech, solver, kin, unit) / q0


def _require_ideal(mech, kin, unit, q0):
    power = q0 * _lever(mech, kin, unit) * kin.qd
    _require_positive(mech, kin, power, "no ideal output",
                      "the loads do not drive the mechanism back even without friction",
                      "the unknown load's ideal power is {value:.6g} W",
                      "a reverse efficiency needs loads that would run the mechanism "
                      "backwards on their own")


def _lever(mech, kin, unit):
    return coefficient(mech, mech.unknown_load(), kin.pos, unit.vel)


def _require_positive(mech, kin, power, reason, what, why, hint):
    bad = np.asarray(power) <= 0
    if np.any(bad):
        mask = np.broadcast_to(bad, np.shape(kin.q))
        value = float(np.ravel(np.broadcast_to(power, np.shape(kin.q))[mask])[0]) + 0.0
        raise EfficiencyError(f"{what} {where_text(mech, kin.q, mask)}: " + why.format(
            value=value), file=mech.file, hint=hint, reason=reason, values={"power": value})


def scaled_losses(mech, t):
    """The mechanism with every loss times ``t``: friction coefficients, rolling
    resistances, friction circles' radii."""
    dyn = mech.dynamics
    dyn = replace(dyn, friction={s: mu * t for s, mu in dyn.friction.items()},
                  discs={n: replace(d, resistance=d.resistance * t) for n, d in dyn.discs.items()},
                  pins={p: replace(f, radius=f.radius * t) for p, f in dyn.pins.items()})
    return replace(mech, dynamics=dyn)


def locking_fraction(mech, solver, kin, unit) -> float:
    """The fraction t of the losses where the reverse efficiency reaches zero (Q_r(t) = 0):
    below it the load drives the mechanism back, from it on the mechanism locks itself.
    One driver value.  Raises EfficiencyError where no t up to LOCK_REACH locks it."""
    from scipy.optimize import brentq
    q0 = float(np.ravel(ideal_load(mech, kin, unit))[0])
    _require_ideal(mech, kin, unit, q0)

    def margin(t):
        return float(np.ravel(reverse_load(mech, solver, kin, unit, t))[0]) / q0
    hi = 1.0
    while margin(hi) > 0:
        if hi >= LOCK_REACH:
            raise EfficiencyError(
                f"the mechanism never locks itself {where_text(mech, kin.q, True)}: with "
                f"{hi:.3g} times the losses the reverse efficiency is still "
                f"{margin(hi):.6g} > 0", file=mech.file, reason="never locks",
                values={"reach": hi}, hint="ask for the reverse efficiency instead")
        hi *= 4.0
    return float(brentq(margin, 0.0, hi, xtol=LOCK_TOL * hi, rtol=LOCK_TOL))


def series(stages) -> float:
    """The efficiency of machines in series: the product of the stages' efficiencies."""
    return float(np.prod(np.asarray(stages, dtype=float)))


def parallel(stages, powers) -> float:
    """The efficiency of machines in parallel sharing the input powers ``powers``:
    sum eta_i P_i / sum P_i."""
    stages, powers = np.asarray(stages, dtype=float), np.asarray(powers, dtype=float)
    return float(np.sum(stages * powers) / np.sum(powers))
