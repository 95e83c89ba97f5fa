"""The stroke of a quantity: how far it goes between its extremes over the range.

stroke = max(level of the maxima) - min(level of the minima), in the quantity's display
unit, with level the value along the motion (an angle unwrapped over its run), so that an
angle's stroke is its swing along the motion, not across 0/360.  It is >= 0.  Only a
position quantity (a coordinate, an angle, a length ...) has strokes: the extremes of a rate
or a speed give no stroke.  A position quantity constant to rounding (``runs.limits.dwell``)
has the stroke 0; one with no maximum or no minimum over the range has none.
"""
from __future__ import annotations


def stroke(found) -> None:
    """Set ``found.stroke`` from its extremes (0 for a constant position quantity)."""
    maxima, minima = found.of("maximum"), found.of("minimum")
    if found.constant is not None and found.position:
        found.stroke = 0.0
    if not maxima or not minima or not found.position:
        return
    found.stroke = max(e.level for e in maxima) - min(e.level for e in minima)
