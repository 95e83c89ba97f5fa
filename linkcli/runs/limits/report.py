"""The report's limits of the motion: each one value for a range of the driver.

A limit quantity (``model.mechanism``: maximum, minimum, at_maximum, at_minimum, stroke,
time_ratio, stroke_time) of a quantity N over its range q = from..to (a full turn by
default) is found once per (N, range) from N's extremes (``runs.limits.search``) and given
at every driver value asked, the same number; the rest of the report is evaluated as usual.
A limit that is not defined (no such extreme, no full turn, a driver at rest) is a located
SolveError (exit 3) that says why; a range the mechanism only partly assembles over is a
caution naming the positions left out.
"""
from __future__ import annotations

import numpy as np

from linkcli.answers import quantities
from linkcli.errors import Caution, SolveError
from linkcli.runs.limits import dwell, limit_positions, quick_return, search
from linkcli.runs.limits.extremes import Limits
from linkcli.runs.limits.names import pointwise

#: what a limit quantity of each kind is, in messages
WORDS = {"maximum": "the maximum", "minimum": "the minimum", "at_maximum": "where the maximum is",
         "at_minimum": "where the minimum is", "stroke": "the stroke",
         "time_ratio": "the time ratio", "stroke_time": "the stroke time"}


def evaluate(mech, q=None, qdot=None, qddot=None, names=None, method="closed", tol=None):
    """The report's values (``answers.quantities.evaluate``) with its limits of the motion,
    each one value for its range, repeated at every driver value of ``q``."""
    names = list(names) if names is not None else quantities.report_names(mech)
    others = pointwise(mech, names)
    result = quantities.evaluate(mech, q, qdot, qddot, names=others, method=method, tol=tol)
    found = {}
    values, units = {}, {}
    for name in names:
        if name in others:
            values[name], units[name] = result.values[name], result.units[name]
            continue
        quantity = mech.quantities[name]
        span = quantity.span or (None, None)
        key = (quantity.a, span)
        if key not in found:
            found[key] = search.find(mech, quantity.a, *span, qdot=qdot, method=method, tol=tol,
                                     key=f"quantities.{name}", line=quantity.line)
            if not found[key].whole:
                result.cautions.append(Caution(
                    "limits", f"the limits of {quantity.a} are over the part of "
                    f"{found[key].range_text()} where the mechanism assembles: "
                    + "; ".join(found[key].notes), mech.file))
        value, unit = answer(mech, quantity, found[key])
        values[name] = np.asarray(value + 0 * np.asarray(result.kinematics.q, float)) + 0.0
        units[name] = unit
    result.values, result.units = values, dict(result.units, **units)
    return result


def answer(mech, quantity, found: Limits):
    """(value, unit) of the limit ``quantity`` from the extremes ``found``; a located
    SolveError when it is not defined (no such extreme, no full turn, no driver rate)."""
    kind, of = quantity.kind, quantity.a

    def undefined(detail, hint=None):
        return SolveError(f"'{quantity.name}' ({WORDS[kind]} of {of}) is undefined: {detail}",
                          file=mech.file, key=f"quantities.{quantity.name}", line=quantity.line,
                          hint=hint)

    if found.constant is not None:
        return dwell.of_constant(found, kind, undefined)
    if not found.extremes:
        raise undefined(f"{of} has no extreme over {found.range_text()}: {found.why}" +
                        "".join(f"; {note}" for note in found.notes),
                        hint="ask for a quantity that goes back and forth")
    limit_positions.require(found, kind, of, undefined)
    if kind in limit_positions.EXTREMES:
        return limit_positions.answer(found, kind, of, undefined)
    if kind == "stroke":
        return found.stroke, found.unit
    return quick_return.answer(found, kind, quantity.component, undefined)
