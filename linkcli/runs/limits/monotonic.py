"""Why a quantity has no extreme, in words: over each run of the range it only rises or falls.

Each run is a stretch of consecutive solved driver values q0..qn (``runs.limits.search``);
over it the rate dN/dq keeps its sign, so N is monotonic: it rises where
level(qn) > level(q0) (the value along the motion, an angle unwrapped) and falls otherwise,
by |level(qn) - level(q0)|.  A run held to rounding is told as constant at its value
(``runs.limits.dwell``).  A run carried across the end of a full turn names its end a turn
back, ``(through stop)``; one past the end of a shorter range is cut at its last value
inside it.
"""
from __future__ import annotations

import numpy as np

from linkcli.answers.formats import fmt
from linkcli.runs.limits.extremes import num


def why(found, scales) -> str:
    """Why ``found`` has no extreme: the quantity is constant, or it only rises or falls.
    ``scales``: (q, shown, level, held) of every run, held None where it is not constant."""
    if not scales:
        return "the mechanism cannot be assembled anywhere in the range"
    parts = []
    for qs, shown, level, held in scales:
        if held is not None:
            parts.append(f"it is constant ({fmt(held, 4)} {found.unit}) for q in "
                         f"{num(qs[0])}..{num(qs[-1])} {found.q_unit}")
            continue
        parts.append(_trend(found, qs, shown, level))
    return "; ".join(parts)


def _trend(found, qs, shown, level) -> str:
    """The run ``qs`` in words: N rises (falls) from its first to its last value."""
    last = qs.size - 1
    end = num(qs[last])
    if qs[last] > found.stop and found.periodic:     # a run across the turn's end
        end = f"{num(qs[last] - found.turn)} (through {num(found.stop)})"
    elif qs[last] > found.stop:
        inside = qs <= found.stop
        last = int(np.nonzero(inside)[0][-1]) if inside.any() else last
        end = num(qs[last])
    trend = "rises" if level[last] > level[0] else "falls"
    return (f"its rate d({found.name})/dq keeps its sign: it {trend} from "
            f"{fmt(shown[0], 4)} to {fmt(shown[last], 4)} {found.unit} (by "
            f"{fmt(abs(level[last] - level[0]), 4)}) as q goes from {num(qs[0])} to "
            f"{end} {found.q_unit}")
