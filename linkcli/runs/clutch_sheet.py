"""The answer sheet of a clutch problem (``shafts:`` and ``clutch:``): the shafts' torques
as functions of their speeds, the transient solved once (``runs.clutch``), and each answer
in its display unit.

A shaft's torque is its constant ``torque``, plus its motor's stall (1 - w / no_load), minus
its ``resisting`` torque R times the sense its speed keeps while it turns.  A shaft at rest
starts the way the clutch and its torques push it; one they push with no more than R stays
at rest, and the slip cannot end (refused, exit 3, with the numbers).  A shaft with a
resisting torque must not come to rest and turn back during the slip or after it (refused:
the constant-sense model no longer holds).
"""
from __future__ import annotations

import weakref

import numpy as np

from linkcli.errors import ClutchError, SolveError
from linkcli.forces import clutch as physics
from linkcli.model.units import parse_unit
from linkcli.runs import clutch as run

_TRANSIENTS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def transient(mech) -> run.Transient:
    """The clutch's transient of ``mech``, solved at the first call and kept."""
    found = _TRANSIENTS.get(mech)
    if found is None:
        found = _TRANSIENTS[mech] = _solve(mech)
    return found


def _solve(mech) -> run.Transient:
    problem = mech.clutch
    clutch = problem.clutch
    one = problem.shafts[clutch.driving]
    two = problem.shafts[clutch.driven] if clutch.driven is not None else None
    sense = 1.0 if one.speed >= (two.speed if two is not None else 0.0) else -1.0
    s1 = _sense(mech, one, -sense * clutch.torque)
    s2 = _sense(mech, two, sense * clutch.torque) if two is not None else 0.0
    m1, m2 = _torque(one, s1), _torque(two, s2) if two is not None else (lambda w, t: 0.0)
    shafts = physics.Shafts(one.inertia, two.inertia if two is not None else None, one.speed,
                            two.speed if two is not None else 0.0, m1(one.speed, 0.0),
                            m2(two.speed if two is not None else 0.0, 0.0), clutch.torque)
    constant = one.constant and (two is None or two.constant)
    out = run.transient(shafts, run.Torques(m1, m2, constant), mech.file)
    for shaft, s in ((one, s1), (two, s2)):
        if shaft is not None and shaft.resisting and out.speed * s < 0:
            raise ClutchError(f"shaft {shaft.name} comes to rest during the slip and would turn "
                              f"back (from {shaft.speed:.6g} rad/s to the common speed "
                              f"{out.speed:.6g} rad/s) against its resisting torque "
                              f"{shaft.resisting:.6g} N m", file=mech.file, reason="reverses",
                              hint="a resisting torque acts against one sense of turning: "
                              "give a signed 'torque' for one that keeps its sense",
                              values={"speed": out.speed})
    return out


def _sense(mech, shaft, push):
    """The sense of turning a shaft keeps while it slips: its speed's, or at rest the way
    ``push`` (the clutch's torque on it) and its torques push it."""
    if shaft.speed != 0:
        return 1.0 if shaft.speed > 0 else -1.0
    drive = push + shaft.torque + (shaft.stall or 0.0)
    if abs(drive) <= shaft.resisting:
        raise ClutchError(f"shaft {shaft.name} never starts: the clutch and its torques push it "
                          f"with {abs(drive):.6g} N m, not more than its resisting torque "
                          f"{shaft.resisting:.6g} N m, so the speeds are never equal",
                          file=mech.file, reason="never engages",
                          hint="raise the clutch torque above the load on the driven side",
                          values={"push": abs(drive), "R": shaft.resisting})
    return 1.0 if drive > 0 else -1.0


def _torque(shaft, sense):
    """M(w, t) of ``shaft`` turning in ``sense`` (N m)."""
    base = shaft.torque - shaft.resisting * sense
    if shaft.stall is None:
        return lambda w, t: base
    stall, no_load = shaft.stall, shaft.no_load
    return lambda w, t: base + stall * (1 - w / no_load)


def evaluate(mech, names, result):
    """The clutch answers ``names`` into ``result`` (values and units, display units)."""
    for name in names:
        quantity = mech.quantities[name]
        try:
            value, unit = answer(mech, quantity)
        except SolveError as err:
            if err.key is None:
                err.key, err.line = f"quantities.{name}", quantity.line
            raise
        result.values[name], result.units[name] = value, unit
    return result


def answer(mech, quantity):
    """(value, unit) of one clutch answer in its display unit."""
    tr = transient(mech)
    what = quantity.a
    if what == "torque":
        value = mech.clutch.clutch.torque
    elif what == "slip_time":
        value = tr.slip_time
    elif what == "common_speed":
        value = tr.speed
    elif what == "energy":
        value = tr.energy
    elif what == "transmitted":
        value = _transmitted(tr)
    else:
        side = mech.clutch.side(quantity.b)
        if what == "time":
            value = tr.time_to(quantity.time, side)
        else:
            state = tr.speeds_at(quantity.time)
            value = state[side - 1] if what == "speed" else state[side + 1]
    return _display(mech, quantity, value)


def _transmitted(tr):
    """The torque the clutch passes once the shafts turn together, at the engagement."""
    if tr.torques.constant:
        torque = physics.transmitted(tr.shafts)[1]
    else:
        torque = run.locked_torque(tr, tr.speed, tr.slip_time)
    if not physics.holds(tr.shafts, torque):
        raise physics.slips_again(tr.shafts, torque, tr.slip_time, tr.file)
    return torque


#: the unit kind each answer is shown in when the quantity names none
KINDS = {"slip_time": "time", "time": "time", "common_speed": "angular_rate",
         "speed": "angular_rate", "torque": "torque", "transmitted": "torque"}


def _display(mech, quantity, value):
    """``value`` (SI) in the quantity's unit, its file's unit of the kind, J for an energy
    and the angular rate's unit per second for an acceleration."""
    units = mech.units
    unit = quantity.unit
    if unit is None:
        kind = KINDS.get(quantity.a)
        if kind is not None:
            return value / units.factor(kind), units.names[kind]
        if quantity.a == "energy":
            return value, "J"
        return _acceleration(units, value)
    return value / parse_unit(unit)[1], unit


def _acceleration(units, value):
    """An angular acceleration (rad/s^2) in the angular rate's unit per time unit: rpm/s,
    deg/s^2 (a rate per second, per second); rad/s^2 where the two do not compose."""
    rate, time = units.names["angular_rate"], units.names["time"]
    base, slash, per = rate.partition("/")
    unit = f"{rate}/{time}" if not slash else f"{base}/{time}^2" if per == time else None
    if unit is None:
        return value, "rad/s^2"
    return value / (units.factor("angular_rate") / units.factor("time")), unit
