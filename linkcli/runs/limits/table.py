"""The output of ``linkcli limits``: the extremes of each quantity as a table, JSON or CSV.

One row per extreme (quantity, maximum or minimum, its driver value q or a dwell's stretch
first..last, its value, unit), a constant's row (constant, the range, its value), the
stroke, and over a full turn of a crank the time ratio with the working and return strokes
(each: its driver sweep in the q column, its time in s).  Numbers at ``decimals`` places;
JSON gives them at full precision.  What could not be solved and the quantities without an
extreme are messages, each once.
"""
from __future__ import annotations

import json

from linkcli.answers.formats import csv_text, fmt
from linkcli.runs.limits.extremes import Limits


def rows(found: Limits, decimals: int) -> list:
    """(quantity, what, q, value, unit) rows of ``found``, as text."""
    out = []
    if found.constant is not None:
        span = f"{fmt(found.start, decimals)}..{fmt(found.stop, decimals)}"
        out.append((found.name, "constant", span, fmt(found.constant, decimals), found.unit))
    for e in found.extremes:
        where = fmt(e.q, decimals) if e.span is None else \
            f"{fmt(e.span[0], decimals)}..{fmt(e.span[1], decimals)}"
        out.append((found.name, e.kind, where, fmt(e.value, decimals), found.unit))
    if found.stroke is not None:
        out.append((found.name, "stroke", "", fmt(found.stroke, decimals), found.unit))
    if found.sweeps is not None:
        out.append((found.name, "time_ratio", "", fmt(found.time_ratio, decimals), ""))
        for i, what in enumerate(("working_stroke", "return_stroke")):
            time = "" if found.times is None else fmt(found.times[i], decimals)
            out.append((found.name, what, fmt(found.sweeps[i], decimals), time,
                        "s" if time else ""))
    return out


def messages(found_list) -> list:
    """What to tell besides the rows, each once: the ranges that cannot be solved, the
    quantities without an extreme."""
    out = [f"over {found.range_text()}, {note}" for found in found_list for note in found.notes]
    out += [f"'{found.name}' has no extreme over {found.range_text()}: {found.why}"
            for found in found_list if not found.extremes and found.constant is None]
    return list(dict.fromkeys(out))


def as_dict(found: Limits) -> dict:
    return {"quantity": found.name, "unit": found.unit, "q_unit": found.q_unit,
            "from": found.start, "to": found.stop, "full_turn": found.periodic,
            "constant": found.constant,
            "extremes": [{"kind": e.kind, "q": e.q, "value": e.value,
                          "span": None if e.span is None else list(e.span)}
                         for e in found.extremes],
            "stroke": found.stroke, "time_ratio": found.time_ratio,
            "sweeps": None if found.sweeps is None else {"working": found.sweeps[0],
                                                          "return": found.sweeps[1]},
            "times": None if found.times is None else {"working": found.times[0],
                                                        "return": found.times[1]},
            "messages": messages([found])}


def render(found_list, form: str, decimals: int) -> str:
    """The limits of every quantity of ``found_list`` as a table, JSON or CSV."""
    if form == "json":
        return json.dumps([as_dict(f) for f in found_list], indent=2)
    q_unit = found_list[0].q_unit if found_list else ""
    header = ["quantity", "what", f"q [{q_unit}]", "value", "unit"]
    body = [row for found in found_list for row in rows(found, decimals)]
    if form == "csv":
        return csv_text(header, body).rstrip("\n")
    from tabulate import tabulate
    return tabulate(body, headers=header, disable_numparse=True)
