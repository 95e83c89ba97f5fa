"""The answers of gears by their teeth (input.gears): centre distances, contact ratios and
the fewest teeth without interference, from the teeth alone (kinematics.gearing); one value
for every position of the mechanism."""
from __future__ import annotations

import numpy as np

from linkcli.answers.quantities.geometry import override_unit
from linkcli.kinematics import gearing


def gear_value(mech, quantity, kin):
    """(value in display units, unit) of a GEARING quantity, shaped as the driver values."""
    gears = mech.gears
    first = gears[quantity.a]
    other = gears.get(quantity.b) if quantity.b else None
    if quantity.kind == "centre_distance":
        unit, factor = mech.units.display("length", 0)
        if quantity.unit:
            unit, factor = override_unit(quantity.unit, "length", 0)
        value = gearing.centre_distance(first, other) / factor
    elif quantity.kind == "contact_ratio":
        value, unit = gearing.contact_ratio(first, other), ""
    else:
        addendum = (other or first).addendum / (other or first).module
        ratio = None if other is None else other.teeth / first.teeth
        value, unit = gearing.min_teeth(addendum, first.pressure_angle, ratio), ""
    return value + 0 * np.asarray(kin.q, dtype=float), unit
