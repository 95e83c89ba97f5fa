"""The names of the limits of the motion: the quantity asked, the range of the driver, and
which of the report's names are limits.

A name is a quantity N of the file or the rate of one, ``N`` + ``dot`` (``split_rate``): its
extremes are the zeros of dN/dq, so N must have a rate the solver gives (a position or a
velocity quantity, ``model.mechanism.limit_refusal``).  The range q = start..stop is in the
driver's display unit, start < stop: a full turn 0..360 deg (0..2 pi rad) of an angle driver
when none is given, never longer than a turn (the motion repeats); a length driver has no
natural range and needs both ends.  The range is ``periodic`` when it is one turn, to 1e-12
of the turn.  A limit quantity of the report (maximum, at_maximum, stroke, time_ratio ...:
``model.mechanism``) is one value for a range of the driver, not a function of q: a sweep
lists the report without them and refuses one asked by name.
"""
from __future__ import annotations

import math

from linkcli.answers import quantities
from linkcli.model.regime import KINDS as REGIME_KINDS
from linkcli.errors import InputError
from linkcli.model.mechanism import limit_refusal, split_rate
from linkcli.runs.limits.extremes import num
from linkcli.runs.sweep.names import listing


def target(mech, name, key="--of", line=None):
    """(quantity, order) of ``name``, whose extremes are asked; refused when the file does
    not define it or it has no rate to find them from."""
    if not isinstance(name, str) or not name:
        raise InputError(f"expected a quantity name, got {name!r}", file=mech.file, key=key,
                         line=line)
    base, order = split_rate(name, mech.quantities)
    quantity = mech.quantities.get(base)
    if quantity is None:
        raise InputError(f"'{name}' is not a quantity of this file", file=mech.file, key=key,
                         line=line, hint="defined: " + listing(sorted(mech.quantities)))
    refusal = limit_refusal(name, quantity, order)
    if refusal:
        raise InputError(refusal, file=mech.file, key=key, line=line,
                         hint="ask for a position or velocity quantity: a coordinate, an "
                         "angle, a speed, or the rate of one, e.g. xBdot")
    return quantity, order


def driver_span(mech, start=None, stop=None, key="--from", line=None):
    """(start, stop, periodic) in the driver's display unit: a full turn of an angle driver
    when no range is given; ``periodic`` when the range is one turn."""
    units = mech.units
    q_unit, q_factor = units.display(mech.driver.base, 0)
    turn = 2 * math.pi / q_factor if mech.driver.base == "angle" else None

    def refuse(detail, hint=None):
        return InputError(detail, file=mech.file, key=key, line=line, hint=hint)

    if start is None and stop is None:
        if turn is None:
            raise refuse("the driver is a length, which has no natural range: give the range "
                         "of q", hint="--from A --to B, or from: and to: in the quantity, in "
                         f"{q_unit}")
        return 0.0, turn, True
    if start is None or stop is None:
        raise refuse("give both ends of the range of q", hint="--from A --to B")
    if not (math.isfinite(start) and math.isfinite(stop)) or not start < stop:
        raise refuse(f"the range of q goes from a smaller to a larger value, got "
                     f"{num(start)}..{num(stop)} {q_unit}", hint="e.g. --from 0 --to 360")
    if turn is not None and stop - start > turn * (1 + 1e-12):
        raise refuse(f"the range {num(start)}..{num(stop)} {q_unit} is longer than a turn "
                     f"({num(turn)} {q_unit}): the motion repeats", hint="give one turn at most")
    periodic = turn is not None and abs(stop - start - turn) <= 1e-12 * turn
    return start, stop, periodic


def is_limit(mech, name) -> bool:
    return getattr(mech.quantities.get(name), "limit", False)


#: kinds of answers that are one value for the whole motion of a machine (runs.machine_motion,
#: runs.machine_regime), not a function of the driver: a sweep leaves them out, as a limit
WHOLE = ("motion",) + REGIME_KINDS


def is_whole(mech, name) -> bool:
    return getattr(mech.quantities.get(name), "kind", None) in WHOLE


def pointwise(mech, names):
    """``names`` without the limits of the motion and the answers of a machine's whole motion
    (one value, not a function of the driver): what a sweep can list."""
    return [n for n in names if not is_limit(mech, n) and not is_whole(mech, n)]


def sweep_names(mech, names, key="--names"):
    """The names a sweep lists: ``names`` (None: the report's) without the limits of the
    motion, which are one value for a range; asking a sweep for one is refused."""
    if names is None:
        report = quantities.report_names(mech)
        if not any(is_limit(mech, n) or is_whole(mech, n) for n in report):
            return None
        return pointwise(mech, report) or ["q"]
    for name in names:
        if is_whole(mech, name):
            raise InputError(f"'{name}' is an answer of the machine's whole motion, one value, "
                             "not a function of the driver", file=mech.file, key=key,
                             hint="print it with 'linkcli solve'")
        if is_limit(mech, name):
            raise InputError(f"'{name}' is a limit of the motion, one value for the whole range "
                             "of the driver, not a function of it", file=mech.file, key=key,
                             hint=f"print it with 'linkcli solve' or 'linkcli limits --of "
                             f"{mech.quantities[name].a}'")
    return names


def default_names(mech) -> list:
    """What ``linkcli limits`` looks at without --of: the quantities the report's limits are
    of, else the report's position and velocity quantities that have a rate (the driver's own
    angle left out)."""
    report = quantities.report_names(mech)
    asked = [mech.quantities[n].a for n in report if is_limit(mech, n)]
    if asked:
        return list(dict.fromkeys(asked))
    driver = mech.driver
    names = []
    for name in report:
        base, order = split_rate(name, mech.quantities)
        quantity = mech.quantities.get(base)
        if quantity is None or limit_refusal(name, quantity, order) or quantity.kind == "q" or (
                quantity.kind == "angle" and (quantity.a, quantity.b) == (driver.a, driver.b)):
            continue
        names.append(name)
    if not names:
        raise InputError("the report has no quantity to find the extremes of", file=mech.file,
                         key="--of", hint="name one: --of xB")
    return names
