"""The machine's reduced quantities at a state of the driver (forces.machine): J*(q),
dJ*/dq and the reduced torque Q(q, q', t = 0), in the file's units (docs/machines.md).

A :class:`~linkcli.forces.machine.Machine` is built once per mechanism and kept, keyed by
the mechanism object like its solvers.
"""
from __future__ import annotations

import weakref

import numpy as np

from linkcli.errors import InputError
from linkcli.forces.machine import Machine, require_known
from linkcli.kinematics.solvers import solver_for
from linkcli.model.dimensions import machine_dimension

_MACHINES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
#: the file's unit kind of each reduced quantity, for an angle driver and a length driver
KINDS = {"reduced_inertia": ("inertia", "mass"), "reduced_torque": ("torque", "force"),
         "reduced_inertia_slope": (None, None)}


def machine_for(mech, method="closed", tol=None) -> Machine:
    """The machine of ``mech`` (built at the first call and kept)."""
    machines = _MACHINES.setdefault(mech, {})
    key = (method, tol)
    if key not in machines:
        machines[key] = Machine(mech, solver_for(mech, method, tol))
    return machines[key]


def display(mech, quantity) -> tuple:
    """(unit, SI factor) of a machine quantity in the file's units."""
    dim = machine_dimension(mech, quantity)
    if quantity.unit is not None:
        return mech.units.show(dim, None, quantity.unit)
    if quantity.kind == "reduced_inertia_slope":     # the inertia unit per driver unit
        inertia = mech.units.show(machine_dimension_of(mech, "reduced_inertia"),
                                  KINDS["reduced_inertia"][0 if angular(mech) else 1])
        base = mech.units.display(mech.driver.base, 0)
        return f"{inertia[0]}/{base[0]}", inertia[1] / base[1]
    if quantity.kind in KINDS:
        kind = KINDS[quantity.kind][0 if mech.driver.base == "angle" else 1]
        return mech.units.show(dim, kind, quantity.unit)
    if quantity.a in ("speed", "acceleration", "turned"):
        order = {"turned": 0, "speed": 1, "acceleration": 2}[quantity.a]
        return mech.units.display(mech.driver.base, order)
    if quantity.a == "time":
        return mech.units.show(dim, "time", quantity.unit)
    return "", 1.0


def angular(mech) -> bool:
    return mech.driver.base == "angle"


def machine_dimension_of(mech, kind):
    from linkcli.model.mechanism import Quantity
    return machine_dimension(mech, Quantity("_", kind, "q"))


def reduced_value(mech, quantity, kin) -> tuple:
    """(value in display units, unit) of J*, dJ*/dq or Q at the solved state ``kin``."""
    if quantity.kind not in KINDS:      # the whole motion's answers are the runs'
        raise InputError(f"'{quantity.name}' is an answer of the machine's whole motion, one "
                         "value: an expression or a sweep over the driver cannot read it",
                         file=mech.file, key=f"quantities.{quantity.name}", line=quantity.line,
                         hint="print it with 'linkcli solve'")
    machine = machine_for(mech)
    q = np.atleast_1d(np.asarray(kin.q, dtype=float))
    c = machine.coefficients(q.ravel())
    if quantity.kind == "reduced_inertia":
        value = c.J
    elif quantity.kind == "reduced_inertia_slope":
        value = c.dJ
    else:
        require_known(mech)
        w = np.broadcast_to(np.asarray(kin.qd, dtype=float), np.shape(kin.q)).ravel()
        value = c.smooth + machine.windowed_torque(c.q, c.levers) + \
            machine.turning_torque(c.q, w, 0.0, c.levers)
    unit, factor = display(mech, quantity)
    value = np.reshape(value, np.shape(kin.q)) / factor
    return (float(value) if np.ndim(value) == 0 else value), unit
