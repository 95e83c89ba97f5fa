"""Gears by their teeth: the ``gears:`` section's data (docs/schema.md, "gears").

A gear is a number of teeth z cut at a module m (SI: metres of pitch diameter per tooth),
or at a diametral pitch P (teeth per unit of pitch diameter, m = 1 / P): its pitch radius
is r = m z / 2.  Its involute teeth have a pressure angle phi and an addendum a (the
height of a tooth above the pitch circle, m by default).  An ``internal`` gear (a ring,
an annulus) has its teeth cut inside its pitch circle: its addendum circle is r - a.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Gear:
    """One gear: ``teeth`` z, ``module`` m (m), ``pressure_angle`` phi (rad), ``addendum``
    a (m), ``internal`` for teeth cut inside the rim.  ``pitch`` says how the file gave the
    tooth size, for messages: ('module', value, unit) or ('diametral_pitch', value, unit)
    in the file's own units."""

    name: str
    teeth: int
    module: float
    pressure_angle: float
    addendum: float
    internal: bool = False
    pitch: tuple = ()
    line: int | None = None

    @property
    def radius(self) -> float:
        """The pitch radius r = m z / 2 (m)."""
        return self.module * self.teeth / 2

    def pitch_text(self) -> str:
        """'module 2 mm' or 'diametral pitch 8 1/in', as the file gave it."""
        key, value, unit = self.pitch
        return f"{key.replace('_', ' ')} {value:g} {unit}"
