"""Numbers and their units in words, as an exam writes them.

A number is written with up to ten significant digits (:data:`SIGNIFICANT`) and the
decimal separator of the language (a comma in Italian, where the two coordinates of a
point are then separated by a semicolon), never with an exponent between 1e-6 and 1e12.
:func:`digits` measures how round a number is (how many significant digits it needs), so
that of two ways of stating a datum the one with the fewest digits is chosen.  A
:class:`Writer` writes the amounts of one mechanism in its file's display units (lengths,
angles in degrees with '°', points, directions, axes) in one language; :data:`CLOSE` is
the relative agreement of a stated number with the model's.
"""
from __future__ import annotations

import math
from decimal import Decimal

from linkcli.texts.phrases import WORDS

SIGNIFICANT = 10        # digits of a stated number
CLOSE = 1e-9            # relative agreement of a stated number with the model's


def number(value: float, lang: str = "en") -> str:
    """``value`` with up to ten significant digits, without exponent between 1e-6 and 1e12,
    with the language's decimal separator; never '-0'."""
    value = float(value)
    if value == 0 or not math.isfinite(value):
        return "0" if value == 0 else str(value)
    text = f"{value:.{SIGNIFICANT}g}"
    if 1e-6 <= abs(value) < 1e12:
        text = format(Decimal(text), "f")
        if "." in text:
            text = text.rstrip("0").rstrip(".")
    if text in ("-0", "0"):
        text = "0"
    return text.replace(".", ",") if lang == "it" else text


def digits(value: float) -> int:
    """How many significant digits ``value`` needs (a measure of roundness: 90 needs 1,
    228.035 needs 6); SIGNIFICANT + 1 when ten are not enough."""
    value = float(value)
    if value == 0:
        return 1
    for n in range(1, SIGNIFICANT + 1):
        if abs(float(f"{value:.{n}g}") - value) <= CLOSE * abs(value):
            return n
    return SIGNIFICANT + 1


class Writer:
    """Numbers of one mechanism in its display units, in one language."""

    def __init__(self, mech, lang="en"):
        self.mech, self.lang, self.units = mech, lang, mech.units
        self.w = WORDS[lang]

    def num(self, value) -> str:
        return number(value, self.lang)

    def amount(self, si: float, kind: str) -> str:
        """An SI value in the file's unit of ``kind``, with the unit."""
        return f"{self.num(si / self.units.factor(kind))} {self.units.names[kind]}"

    def length(self, si: float) -> str:
        return self.amount(si, "length")

    def angle(self, si: float) -> str:
        value = si / self.units.factor("angle")
        unit = self.units.names["angle"]
        return f"{self.num(value)}°" if unit == "deg" else f"{self.num(value)} {unit}"

    def signed_angle(self, si: float) -> str:
        """An angle in (-half turn, half turn]."""
        return self.angle(math.remainder(si, 2 * math.pi))

    def pair(self, a: float, b: float) -> str:
        sep = "; " if self.lang == "it" else ", "
        return f"({self.num(a)}{sep}{self.num(b)})"

    def point(self, z: complex) -> str:
        f = self.units.factor("length")
        return f"{self.pair(z.real / f, z.imag / f)} {self.units.names['length']}"

    def direction(self, u: complex) -> str:
        """'along x', 'along y' or 'at 205° from +x' for a unit vector (its sense signed by
        the value it multiplies)."""
        if abs(u - 1) < CLOSE:
            return self.w["along_x"]
        if abs(u - 1j) < CLOSE:
            return self.w["along_y"]
        return self.w["at_angle"].format(angle=self.angle(math.atan2(u.imag, u.real) %
                                                          (2 * math.pi)))

    def axis(self, u: complex) -> str:
        """+x, -x, +y, -y or an angle, for a direction along which something runs."""
        for name, v in (("+x", 1), ("-x", -1), ("+y", 1j), ("-y", -1j)):
            if abs(u - v) < CLOSE:
                return name
        return self.angle(math.atan2(u.imag, u.real) % (2 * math.pi))
