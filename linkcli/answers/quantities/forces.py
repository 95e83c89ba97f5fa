"""Loads and joint forces as answers: the unknown load by virtual work (with d'Alembert's
inertia, gravity and friction where the file has masses), the force of a pin on a body and a
slider's normal and friction forces from the Newton-Euler joint forces (N).  A pin's force F
is given by its x and y, its magnitude, or its components F . u along and F . (i u) normal
(left) to an axis u (a body's, a vector's or a fixed direction)."""
from __future__ import annotations

import numpy as np

from linkcli.answers.quantities.textbook import located
from linkcli.errors import InputError
from linkcli.forces import motion
from linkcli.kinematics.closed_form import unit_rates
from linkcli.kinematics.refusals import where_text
from linkcli.forces.statics import unknown_load
from linkcli.model.mechanism import split_rate
from linkcli.model.units import FORCE


def loads_at(mech, solver, kin, names, context=None):
    """SI values of every load, solving the unknown one when a load is asked for (with
    losses, from the joint forces of ``context``, solved once for every answer); a
    vibration problem's loads are all known."""
    bases = [mech.quantities.get(split_rate(n, mech.quantities)[0]) for n in names]
    wanted = any(q is not None and q.kind == "load" for q in bases)
    if not wanted:
        return {}
    values = {n: load.value for n, load in mech.loads.items()}
    if mech.elements is not None or None not in values.values():
        return values               # every load known: a vibration problem, a machine's motion
    if len(mech.coordinates) > 1:   # one unknown per driver, by each driver's motion
        values.update(_unknowns_of_drivers(mech, solver, kin))
        return values
    unit_kin = unit_rates(solver, kin)
    unknown = mech.unknown_load()
    extra = 0.0
    if mech.dynamics is not None:   # inertia, gravity, friction (d'Alembert)
        from linkcli.forces.balance import dynamic_power
        from linkcli.forces.friction import has_losses
        reactions = context.reactions() if context is not None and \
            has_losses(mech.dynamics) else None
        extra = dynamic_power(mech, kin, unit_kin, reactions)
    values[unknown.name] = unknown_load(mech, kin.pos, unit_kin.vel, extra_power=extra,
                                        q=kin.q)
    return values


#: the kinds of quantity that are joint forces
JOINT_FORCES = ("reaction", "slider_force", "tension", "contact_force")


def force_value(quantity, kin, context):
    """(value, unit) of a joint force (:func:`joint_force`) in its display unit."""
    unit = quantity.unit or context.mech.units.names["force"]
    return joint_force(quantity, context) / FORCE[unit] + 0 * kin.q, unit


def joint_force(quantity, context):
    """The force of the pin on the body (a component or its magnitude), or a slider's N or
    T, in N, from the Newton-Euler joint forces."""
    reactions = context.reactions()
    mech = context.mech
    if quantity.kind in ("tension", "contact_force"):
        return contact_force(quantity, reactions)
    if quantity.kind == "slider_force":
        pair = reactions.pairs[quantity.a]
        return np.asarray(pair.normal if quantity.component == "normal" else pair.friction,
                          dtype=float)
    point, body = quantity.a, quantity.b
    keys = [(point, body)] if quantity.of != "actuator" else \
        [(point, body + ".cylinder"), (point, body + ".rod")]
    key = next((k for k in keys if k in reactions.pins), None)
    if key is None:
        raise located(quantity, mech, f"no pin at {point} acts on {body}",
                       hint="pins: " + ", ".join(f"{p} on {b}" for p, b in reactions.pins),
                       error=InputError)
    force = reactions.pins[key]
    if quantity.component == "x":
        return np.real(force)
    if quantity.component == "y":
        return np.imag(force)
    if quantity.component in ("along", "normal"):
        u = axis_direction(mech, quantity.axis, reactions.kin.pos, key[1])
        if quantity.component == "normal":
            u = 1j * u
        return (np.conj(u) * force).real
    return np.abs(force)


def contact_force(quantity, reactions):
    """A cord's tension, or a rolling contact's friction T (along the line, or the track's
    tangent) or normal force N (from what it rolls on towards the centre), in N.  A slack
    cord (T < 0) or a disc that lifts off (N < 0) is refused with its value: the contact
    the answer assumes is not there."""
    from linkcli.forces.joint_forces import contact_normal
    mech, kin = reactions.mech, reactions.kin
    name = quantity.a
    if quantity.component == "normal":
        value = contact_normal(reactions, name)
        if value is None:
            r = mech.rolling[name]
            raise located(quantity, mech, f"the normal force of {name} is not determined: no "
                          f"slider keeps the centre {r.center} on the parallel of the line "
                          "it rolls on, so the links that hold the centre carry it",
                          hint="ask for the friction, or the reactions of the pins at "
                          f"{r.center}")
    else:
        value = np.asarray(reactions.contacts[name], dtype=float)
    if quantity.kind == "tension" or quantity.component == "normal":
        bad = value < 0
        if np.any(bad):
            worst = float(np.min(value))
            where = where_text(mech, kin.q, np.broadcast_to(bad, np.shape(kin.q)))
            what = f"cord {name} is slack: its tension would be {worst:.6g} N {where}, and a " \
                "cord cannot push" if quantity.kind == "tension" else \
                f"the disc lifts off at {name}: its normal force would be {worst:.6g} N " \
                f"{where}, and what it rolls on can only push"
            raise located(quantity, mech, what, hint="the motion there is not the one the "
                          "contact imposes: check the loads, the masses and the driver's rates")
    return value


def axis_direction(mech, axis, pos, body):
    """The unit vector u a joint force is projected on (``Quantity.axis``): a body's axis
    (a link's first -> second point, a slider's guide, an actuator's a -> b), the vector
    P -> Q, or a fixed direction; ``body`` is the pin's body, for an actuator named whole."""
    kind = axis[0]
    if kind == "angle":
        return np.exp(1j * axis[1])
    if kind == "points":
        z = pos[axis[2]] - pos[axis[1]]
    else:
        name = axis[1]
        if name in mech.actuators:
            name = body if body.startswith(name + ".") else name + ".cylinder"
        z = motion.axis_vector(mech, name, pos)
    return z / np.abs(z)


def _unknowns_of_drivers(mech, solver, kin) -> dict:
    """The unknown loads of several drivers (``forces.inputs``): each driver's unit motion,
    with the d'Alembert forces' power where the file has masses (no friction losses)."""
    from linkcli.forces.inputs import unknown_loads
    units = [unit_rates(solver, kin, j) for j in range(len(mech.coordinates))]
    extra = None
    if mech.dynamics is not None:
        from linkcli.forces.balance import dynamic_power
        from linkcli.forces.friction import has_losses
        if has_losses(mech.dynamics):
            raise InputError("friction losses with several drivers are not solved: the "
                             "friction's iteration on the joint forces finds one unknown "
                             "load", file=mech.file, key="dynamics",
                             hint="leave friction out, or drive one input")
        extra = [dynamic_power(mech, kin, unit) for unit in units]
    return unknown_loads(mech, kin.pos, [u.vel for u in units], extra, q=tuple(kin.coords))
