"""The time ratio of a quick return: a crank making full turns at constant speed.

Over one whole turn T of the crank (the range periodic, every position assembled), a
position quantity with one maximum at q_max and one minimum at q_min, neither a dwell,
splits the turn into the driver's sweeps d1 = (q_max - q_min) mod T (the rise) and
d2 = T - d1.  The longer sweep is the working stroke: sweeps = (max(d1, d2), min(d1, d2)),
the time ratio max(d1, d2) / min(d1, d2) >= 1, and each stroke's time d / |qdot| (s) with d
in radians (or metres of a length driver) and qdot the driver's rate in SI.  Asked otherwise
(not a full turn, a crank that does not make one, a dwell, more extremes than one maximum
and one minimum, a driver at rest) the ratio is undefined and the refusal says which.
"""
from __future__ import annotations


def sweeps(found, q_factor: float, qdot_si: float) -> None:
    """Set ``found.sweeps`` (working, return) and ``found.times`` where the extremes split a
    whole turn into two strokes; ``q_factor``: SI per display unit of the driver."""
    maxima, minima = found.of("maximum"), found.of("minimum")
    if not maxima or not minima or not found.position:
        return
    if not (found.periodic and found.whole and len(maxima) == 1 and len(minima) == 1) or \
            maxima[0].span is not None or minima[0].span is not None:
        return
    rise = (maxima[0].q - minima[0].q) % found.turn
    ordered = sorted([rise, found.turn - rise], reverse=True)
    found.sweeps = tuple(ordered)
    if qdot_si != 0:
        found.times = tuple(s * q_factor / abs(qdot_si) for s in ordered)


def answer(found, kind: str, component: str, undefined):
    """(value, unit) of the time ratio or of a stroke's time (``component``: 'working' or
    'return'); ``undefined(detail, hint)``: the located error where it is not defined."""
    if found.sweeps is None:
        raise undefined(no_ratio(found), hint="the time ratio is of a crank making full turns")
    if kind == "time_ratio":
        return found.time_ratio, ""
    if found.times is None:
        raise undefined("the driver's rate is 0", hint="give the driver a rate (driver: rate:)")
    return found.times[0 if component == "working" else 1], "s"


def no_ratio(found) -> str:
    """Why ``found`` has no time ratio."""
    if not found.periodic:
        return f"the range {found.range_text()} is not a full turn of the crank"
    if not found.whole:
        return ("the crank cannot make a full turn: " + "; ".join(found.notes))
    held = [e for e in found.extremes if e.span is not None]
    if held and len(found.extremes) == 2:
        return (f"{found.name} holds its {held[0].kind} over q = {held[0].where()} "
                f"{found.q_unit}: the strokes have no single start")
    return (f"{found.name} has {len(found.extremes)} extremes over the turn (at q = "
            f"{', '.join(e.where() for e in found.extremes)} {found.q_unit}), not one maximum "
            "and one minimum")
