"""The efficiency answers of a mechanism with friction (``forces.efficiency``): the direct
and reverse efficiencies, the unknown load without friction and in reverse motion, whether
the mechanism locks itself and the friction where it starts; series and parallel
efficiencies of given stages.  Self-locking is an answer, not an error: where the reverse
efficiency is <= 0 a note says so with its numbers."""
from __future__ import annotations

import numpy as np

from linkcli.answers.quantities.textbook import located
from linkcli.errors import Caution, EfficiencyError, InputError
from linkcli.forces import efficiency as eff
from linkcli.forces.friction import coefficients, has_losses
from linkcli.model.units import FORCE, TORQUE


def efficiency_value(quantity, kin, context):
    """(value, unit) of an efficiency question in its display unit; a refusal located at
    the quantity's key and line."""
    try:
        return _value(quantity, kin, context)
    except EfficiencyError as err:
        if err.key is None:
            err.key, err.line = f"quantities.{quantity.name}", quantity.line
        raise


def _value(quantity, kin, context):
    mech = context.mech
    kind, arg = quantity.kind, quantity.a
    if kind == "efficiency" and arg in ("series", "parallel"):
        etas = [e for e, _ in quantity.elements]
        value = eff.series(etas) if arg == "series" else \
            eff.parallel(etas, [p for _, p in quantity.elements])
        return value + 0 * np.asarray(kin.q, dtype=float), ""
    _require_losses(quantity, mech)
    unit_kin = context.unit()
    if kind in ("ideal_load", "reverse_load"):
        value = eff.ideal_load(mech, kin, unit_kin) if kind == "ideal_load" else \
            eff.reverse_load(mech, context._solver(), kin, unit_kin)
        return _load_display(mech, quantity, value)
    if kind == "efficiency":
        if arg == "direct":
            return eff.direct(mech, kin, unit_kin) + 0.0, ""
        return _reverse(quantity, kin, context) + 0.0, ""
    if arg == "locks":
        return np.where(_reverse(quantity, kin, context) <= 0, 1.0, 0.0), ""
    return _locking_friction(quantity, kin, context), ""


def _reverse(quantity, kin, context):
    """eta_r, computed once per evaluation, with the self-locking note where it is <= 0."""
    def make():
        value = eff.reverse(context.mech, context._solver(), kin, context.unit())
        if np.any(np.asarray(value) <= 0):
            worst = float(np.min(value))
            context.notes.append(Caution(
                "self-locking", f"the mechanism locks itself: its reverse efficiency is "
                f"{worst:.6g} <= 0, so the loads cannot drive it back and the unknown load "
                f"{context.mech.unknown_load().name} must push it along in reverse motion",
                context.mech.file))
        return value
    return context._once("reverse efficiency", make)


def _locking_friction(quantity, kin, context):
    """The friction coefficient of slider ``at`` (the file's only one by default) where
    self-locking starts: t* mu, every loss raised together by the fraction t*."""
    mech = context.mech
    sliders = coefficients(mech.dynamics)
    at = quantity.b
    if at is None:
        if len(sliders) != 1 or mech.dynamics.pins or any(
                d.resistance for d in mech.dynamics.discs.values()):
            raise located(quantity, mech, "the friction where self-locking starts is asked of "
                          "one slider, and this file has " + (", ".join(sliders) or "no slider")
                          + " with friction among its losses", hint="name it: {self_locking: "
                          "friction, at: SLIDER}", error=InputError)
        at = next(iter(sliders))
    if at not in sliders:
        raise located(quantity, mech, f"'{at}' is not a slider with friction",
                      hint="sliders with friction: " + (", ".join(sliders) or "none"),
                      error=InputError)
    solver = context._solver()
    if not np.shape(kin.q):
        return eff.locking_fraction(mech, solver, kin, context.unit()) * sliders[at]
    out = [eff.locking_fraction(mech, solver, *_one(solver, kin, i)) * sliders[at]
           for i in np.ndindex(np.shape(kin.q))]
    return np.reshape(out, np.shape(kin.q))


def _one(solver, kin, index):
    """(kin, unit) at the driver value ``index`` of an array, solved again alone."""
    def pick(x):
        return x[index] if np.ndim(x) else x
    one = solver.positions(pick(kin.q))
    solver.velocities(one, pick(kin.qd))
    solver.accelerations(one, pick(kin.qdd))
    return one, solver.velocities(one.at_rest(), 1.0)


def _require_losses(quantity, mech):
    if not has_losses(mech.dynamics):
        raise located(quantity, mech, f"'{quantity.name}' asks for an efficiency, and the file "
                      "has no friction: every efficiency is 1", hint="give the friction in "
                      "dynamics: friction, friction_circles or discs' rolling_resistance",
                      error=InputError)


def _load_display(mech, quantity, value):
    load = mech.loads[quantity.a]
    kind = mech.load_unit_kind(load)
    unit = quantity.unit or mech.units.names[kind]
    table = FORCE if kind == "force" else TORQUE
    return value / table[unit], unit
