"""Evaluate a mechanism's report: every named quantity in its display unit.

Angles of a vector ``z = P_b - P_a`` and their rates follow from
``w = z'/z``: ``phi' = Im w``, ``phi'' = Im(z''/z - w^2)``; lengths:
``r' = r Re w``, ``r'' = r (Re(z''/z - w^2) + (Re w)^2)``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from linkcli.errors import InputError, SolveError
from linkcli.kinematics.solvers import solver_for
from linkcli.model.mechanism import REPORT_SECTIONS, split_rate
from linkcli.forces.statics import unknown_load
from linkcli.model.units import ANGLE, FORCE, LENGTH, TORQUE

TWO_PI = 2 * math.pi


@dataclass
class Result:
    """Solved values of a report, in display units (floats or arrays)."""

    mechanism: object
    values: dict = field(default_factory=dict)
    units: dict = field(default_factory=dict)
    points: dict = field(default_factory=dict)       # name -> (x, y) in length units
    kinematics: object = None
    analysis: object = None                          # the vibration analysis, if any
    cautions: list = field(default_factory=list)     # warnings to print with the results

    @property
    def k(self):
        return self.mechanism.k


def needed_orders(mech, names):
    orders = {0}
    for name in names:
        base, order = split_rate(name)
        if base in mech.quantities and mech.quantities[base].kind != "load":
            orders.add(order)
        else:
            # loads need velocities (virtual work); with masses also accelerations
            orders.add(2 if mech.dynamics is not None else 1)
    return max(orders)


def report_names(mech):
    names = []
    for section in REPORT_SECTIONS:
        names += mech.report.get(section, [])
    return names


def require_driver(mech, what: str) -> None:
    """Refuse a request that varies the driver on a file declared with coordinates."""
    if mech.elements is not None or len(mech.coordinates) > 1:
        raise InputError(f"{what} varies the driver, and this file declares coordinates "
                         "(a vibration problem) instead", file=mech.file,
                         hint="use 'linkcli solve', or 'linkcli plot' with --frf, --modes or "
                         "--free")


def evaluate(mech, q=None, qdot=None, qddot=None, names=None, method="closed",
             tol=None) -> Result:
    """Solve ``mech`` at driver value(s) ``q`` (display units) and evaluate ``names``."""
    require_driver(mech, "solving at driver values")
    names = list(names) if names is not None else report_names(mech)
    solver = solver_for(mech, method, tol)
    base = "angle" if mech.driver.kind == "angle" else "length"
    units = mech.units
    q_si = mech.driver.value if q is None else np.asarray(q, float) * units.display(base, 0)[1]
    qd_si = mech.driver.rate if qdot is None else np.asarray(qdot, float) * units.display(base, 1)[1]
    qdd_si = mech.driver.accel if qddot is None else \
        np.asarray(qddot, float) * units.display(base, 2)[1]
    order = needed_orders(mech, names)
    kin = solver.positions(q_si)
    solver.check(kin, velocities=False)
    if order >= 1:
        solver.velocities(kin, qd_si)
        solver.check(kin, velocities=True)
    if order >= 2:
        solver.accelerations(kin, qdd_si)
    result = collect(mech, solver, kin, names)
    if q is None:       # the file's own position: what the figure check says of it
        from linkcli.answers.validate import figure_cautions
        result.cautions = figure_cautions(mech) if method == "closed" else []
    return result


def collect(mech, solver, kin, names) -> Result:
    """Evaluate ``names`` (display units) on kinematics ``kin`` solved as far as they need."""
    units = mech.units
    result = Result(mech, kinematics=kin)
    loads = _loads(mech, solver, kin, names)
    for name in names:
        value, unit = _value(mech, name, kin, loads)
        result.values[name] = value
        result.units[name] = unit
    l_unit, l_factor = units.display("length", 0)
    for p in mech.report.get("points", []):
        z = kin.pos[p]
        result.points[p] = (np.real(z) / l_factor + 0 * kin.q, np.imag(z) / l_factor + 0 * kin.q)
        result.units[p] = l_unit
    _require_finite(mech, result)
    return result


def _require_finite(mech, result):
    """Refuse to return NaN or infinity: overflowing data or coincident points."""
    named = list(result.values.items()) + [(p, xy) for p, xy in result.points.items()]
    for name, value in named:
        if not np.all(np.isfinite(np.asarray(value, dtype=float))):
            raise SolveError(f"'{name}' is not a finite number: the data overflow floating-point "
                             "arithmetic or the points that define it coincide",
                             file=mech.file, hint="check the magnitudes of lengths, rates and "
                             "loads, and the driver value")


def _loads(mech, solver, kin, names):
    """SI values of every load, solving the unknown one when a load is asked for."""
    wanted = any(mech.quantities.get(split_rate(n)[0]) is not None
                 and mech.quantities[split_rate(n)[0]].kind == "load" for n in names)
    if not wanted:
        return {}
    values = {n: load.value for n, load in mech.loads.items()}
    unit_kin = solver.velocities(kin.at_rest(), np.ones_like(kin.q))
    unknown = mech.unknown_load()
    extra = 0.0
    if mech.dynamics is not None:   # inertia, gravity, friction (d'Alembert)
        from linkcli.forces.balance import dynamic_power
        extra = dynamic_power(mech, kin, unit_kin)
    values[unknown.name] = unknown_load(mech, kin.pos, unit_kin.vel, extra_power=extra,
                                        q=kin.q)
    return values


def _value(mech, name, kin, loads):
    base_name, order = split_rate(name)
    quantity = mech.quantities[base_name]
    units = mech.units
    if quantity.kind == "load":
        load = mech.loads[quantity.a]
        value = loads[load.name]
        if quantity.component:
            value = value * (load.direction.real if quantity.component == "x"
                             else load.direction.imag)
        kind = mech.load_unit_kind(load)
        unit = quantity.unit or units.names[kind]
        table = FORCE if kind == "force" else TORQUE
        return value / table[unit], unit
    if quantity.kind == "q":
        value = [kin.q, kin.qd, kin.qdd][order]
        base = "angle" if mech.driver.kind == "angle" else "length"
        if order == 0 and base == "angle":
            value = wrap_angle(value)
    elif quantity.kind in ("x", "y"):
        z = [kin.pos, kin.vel, kin.acc][order].get(quantity.a, 0j)
        value = np.real(z) if quantity.kind == "x" else np.imag(z)
        base = "length"
    else:
        value, base = _vector(quantity, kin, order)
    unit, factor = units.display(base, order)
    if quantity.unit:
        unit, factor = _override(quantity.unit, base, order)
    if np.shape(value) == np.shape(kin.q):      # a fresh array; -0.0 becomes 0.0
        if factor != 1:
            return value / factor, unit
        if quantity.kind in ("angle", "length") and isinstance(value, np.ndarray) \
                and value.flags.owndata:        # computed here: normalise in place
            value += 0.0
            return value, unit
        return value + 0.0, unit
    return value / factor + 0 * kin.q, unit


def wrap_angle(value, principal=False):
    """Angle in [0, 2 pi); values within rounding (1e-12 rad) below 2 pi are 0.

    ``principal``: the value is already in [-pi, pi] (as from np.angle), so
    adding 2 pi to the negative ones is the same as the modulo, and cheaper.
    """
    if principal:
        value = value + np.where(value < 0, TWO_PI, 0.0)
    else:
        value = np.mod(value, TWO_PI)
    return np.where(value > TWO_PI - 1e-12, 0.0, value)


def _relative(rates, a, b):
    """rates[b] - rates[a], absent (fixed) points having zero rate."""
    if a in rates:
        return rates[b] - rates[a] if b in rates else -rates[a]
    return rates.get(b, 0j)


def _vector(quantity, kin, order):
    base = "angle" if quantity.kind == "angle" else "length"
    if order == 0:
        z = _rates(kin, quantity.a, quantity.b, rate=False)[0]
        value = wrap_angle(np.angle(z), principal=True) if base == "angle" else np.abs(z)
        return value, base
    z, w = _rates(kin, quantity.a, quantity.b)
    if order == 1:
        return (w.imag if base == "angle" else np.abs(z) * w.real), base
    dw = _relative(kin.acc, quantity.a, quantity.b) / z
    if base == "angle":                 # Im(z''/z - w^2)
        return dw.imag - 2.0 * w.real * w.imag, base
    dw = dw - w * w
    return np.abs(z) * (dw.real + w.real ** 2), base


def _rates(kin, a, b, rate=True):
    """z = P_b - P_a and (``rate``) w = z'/z, kept on ``kin`` for the other orders."""
    cache = kin.vectors if hasattr(kin, "vectors") else {}
    z, w = cache.get((a, b), (None, None))
    if z is None:
        z = kin.pos[b] - kin.pos[a]
    if rate and w is None:
        w = _relative(kin.vel, a, b) / z
    cache[(a, b)] = (z, w)
    return z, w


def _override(unit, base, order):
    """Display unit and SI factor for a quantity whose base unit is ``unit``."""
    factor = ANGLE[unit] if base == "angle" else LENGTH[unit]
    return unit + ["", "/s", "/s^2"][order], factor
