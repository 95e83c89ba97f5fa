"""Units: factors from the units a file declares to SI, and back for display.

Internally every quantity is SI: m, rad, N, N m, s, kg.  A file declares its
units once (``units:``); values are converted on load and results converted
back to the display unit of each reported quantity.
"""
from __future__ import annotations

import math

from linkcli.errors import InputError

# US customary units, exact by definition: ft = 0.3048 m, in = 0.0254 m,
# lb (mass) = 0.45359237 kg, lbf = lb * 9.80665 m/s^2, slug = lbf s^2 / ft.
FT = 0.3048
INCH = 0.0254
LBF = 0.45359237 * 9.80665
LB = 0.45359237
SLUG = LBF / FT
# pressure: psi = lbf / in^2 = 6894.757293168361 Pa; bar = 1e5 Pa; N/mm^2 = MPa = 1e6 Pa
PSI = LBF / INCH ** 2

LENGTH = {"m": 1.0, "cm": 0.01, "mm": 0.001, "km": 1000.0, "ft": FT, "in": INCH}
ANGLE = {"rad": 1.0, "deg": math.pi / 180.0}
ANGULAR_RATE = {"rad/s": 1.0, "deg/s": math.pi / 180.0, "rpm": 2.0 * math.pi / 60.0,
                "rev/s": 2.0 * math.pi}
# "lb" as a force is the pound-force, as books write it; as a mass it is the pound
FORCE = {"N": 1.0, "kN": 1000.0, "lbf": LBF, "lb": LBF, "kip": 1000.0 * LBF}
TORQUE = {"Nm": 1.0, "Nmm": 0.001, "kNm": 1000.0, "lbf ft": LBF * FT, "lbf in": LBF * INCH,
          "kip ft": 1000.0 * LBF * FT}
MASS = {"kg": 1.0, "g": 0.001, "lb": LB, "slug": SLUG}
INERTIA = {"kg m^2": 1.0, "kg mm^2": 1e-6, "slug ft^2": SLUG * FT ** 2,
           "lb ft^2": LB * FT ** 2, "lb in^2": LB * INCH ** 2}
STIFFNESS = {"N/m": 1.0, "N/mm": 1000.0, "kN/m": 1000.0, "lbf/in": LBF / INCH,
             "lbf/ft": LBF / FT, "lb/in": LBF / INCH, "lb/ft": LBF / FT}
TORSIONAL_STIFFNESS = {"Nm/rad": 1.0, "Nmm/rad": 0.001, "Nm/deg": 180.0 / math.pi,
                       "lbf ft/rad": LBF * FT, "lbf in/rad": LBF * INCH}
DAMPING = {"Ns/m": 1.0, "Ns/mm": 1000.0, "kNs/m": 1000.0, "lbf s/in": LBF / INCH,
           "lbf s/ft": LBF / FT}
TORSIONAL_DAMPING = {"Nms/rad": 1.0, "Nmms/rad": 0.001, "lbf ft s/rad": LBF * FT}
FREQUENCY = {"rad/s": 1.0, "Hz": 2.0 * math.pi, "rpm": 2.0 * math.pi / 60.0}
SPEED = {"m/s": 1.0, "km/h": 1.0 / 3.6, "mm/s": 0.001, "ft/s": FT, "mph": 1609.344 / 3600.0}
TIME = {"s": 1.0, "ms": 0.001}
PRESSURE = {"Pa": 1.0, "kPa": 1000.0, "MPa": 1e6, "bar": 1e5, "N/m^2": 1.0, "kN/m^2": 1000.0,
            "N/mm^2": 1e6, "psi": PSI, "lbf/in^2": PSI, "ksi": 1000.0 * PSI}
AREA = {"m^2": 1.0, "cm^2": 1e-4, "mm^2": 1e-6, "in^2": INCH ** 2, "ft^2": FT ** 2}

# one turn in each angle unit that has an exact float value; radians are not reduced
# (NumPy's sin and cos reduce a float in radians exactly)
TURN = {"deg": 360.0}
# Angles are reduced from this size on: below it the conversion to radians loses less
# than 1e-11 rad, and an angle as written (a spring's free angle of several turns, a
# driver value of 400 deg) is kept as written.
REDUCE_ABOVE = 1e6

KINDS = {
    "length": LENGTH,
    "angle": ANGLE,
    "angular_rate": ANGULAR_RATE,
    "force": FORCE,
    "torque": TORQUE,
    "mass": MASS,
    "inertia": INERTIA,
    "stiffness": STIFFNESS,
    "torsional_stiffness": TORSIONAL_STIFFNESS,
    "damping": DAMPING,
    "torsional_damping": TORSIONAL_DAMPING,
    "frequency": FREQUENCY,
    "speed": SPEED,
    "time": TIME,
    "pressure": PRESSURE,
    "area": AREA,
}

DEFAULTS = {"length": "mm", "angle": "deg", "force": "N", "torque": "Nm",
            "mass": "kg", "inertia": "kg m^2", "stiffness": "N/m",
            "torsional_stiffness": "Nm/rad", "damping": "Ns/m", "torsional_damping": "Nms/rad",
            "frequency": "rad/s", "speed": "m/s", "time": "s"}
# without a declaration, a pressure is in force per length squared and an area in length
# squared of the file's own units (N and mm: N/mm^2 and mm^2)
DERIVED = {"pressure": ("force", "length", 2), "area": (None, "length", 2)}


def _other_kind(name, kind) -> str:
    """': that is a unit of force, not of pressure' when ``name`` is another kind's unit."""
    others = [k for k, table in KINDS.items() if k != kind and isinstance(name, str)
              and name in table]
    if not others:
        return ""
    what = " or ".join(o.replace("_", " ") for o in others)
    return f": that is a unit of {what}, not of {kind.replace('_', ' ')}"


class Units:
    """The unit system of one mechanism file."""

    def __init__(self, declared: dict | None = None):
        declared = dict(declared or {})
        self.names = dict(DEFAULTS)
        for kind, name in declared.items():
            table = KINDS.get(kind)
            if table is None:
                raise InputError(f"unknown unit kind '{kind}'", key=f"units.{kind}",
                                 hint="use one of " + ", ".join(KINDS))
            if not isinstance(name, str) or name not in table:
                raise InputError(f"unknown {kind} unit '{name}'{_other_kind(name, kind)}",
                                 key=f"units.{kind}", hint="use one of " + ", ".join(table))
            self.names[kind] = name
        self.names.setdefault("angular_rate", self.names["angle"] + "/s")
        self.derived = {}
        for kind, (over, base, power) in DERIVED.items():
            if kind not in self.names:
                self._derive(kind, over, base, power)

    def _derive(self, kind, over, base, power):
        """The default unit of ``kind``: the file's ``over`` unit per (or, without ``over``,
        times) its ``base`` unit to ``power``, by name from the table when listed there."""
        name = f"{self.names[base]}^{power}"
        factor = KINDS[base][self.names[base]] ** power
        if over is not None:
            name = f"{self.names[over]}/{name}"
            factor = KINDS[over][self.names[over]] / factor
        self.names[kind] = name
        if name not in KINDS[kind]:
            self.derived[kind] = factor

    def factor(self, kind: str) -> float:
        """SI value of one file unit of ``kind``."""
        name = self.names[kind]
        table = KINDS[kind]
        return table[name] if name in table else self.derived[kind]

    def angle_to_si(self, value: float) -> float:
        """An angle in the file's unit, in radians.  A huge angle in degrees is first
        reduced to one turn exactly (``math.fmod`` is exact), so that 1e17 deg is the
        angle of ``int(1e17) % 360`` and not what is left after rounding 1e17 * pi / 180."""
        turn = TURN.get(self.names["angle"])
        if turn is not None and abs(value) >= REDUCE_ABOVE:
            value = math.fmod(value, turn)
        return value * self.factor("angle")

    # display units of derived quantities -------------------------------------
    def display(self, base: str, order: int) -> tuple[str, float]:
        """Display unit and SI factor of the ``order``-th time derivative of a
        quantity of kind ``base`` ('length' or 'angle')."""
        if base == "angle":
            if order == 0:
                return self.names["angle"], self.factor("angle")
            if order == 1:
                return self.names["angular_rate"], self.factor("angular_rate")
            name = self.names["angle"] if self.names["angular_rate"] == "rpm" else self.names["angular_rate"][:-2]
            return f"{name}/s^2", ANGLE[name]
        unit = self.names["length"]
        factor = self.factor("length")
        suffix = ["", "/s", "/s^2"][order]
        return unit + suffix, factor
