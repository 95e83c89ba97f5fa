"""Units: factors from the units a file declares to SI, and back for display.

Internally every quantity is SI: m, rad, N, N m, s, kg.  A file declares its
units once (``units:``); values are converted on load and results converted
back to the display unit of each reported quantity.

``input.symbols.exact_factors`` is the twin of these factors for ``--symbolic``: the same
units, exact (deg -> pi/180, in -> 0.0254 m).
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

    def show(self, dim, kind: str | None = None, unit: str | None = None) -> tuple[str, float]:
        """(unit name, SI factor) of a value of Dimension ``dim`` in this file's units
        (:func:`show`): the one place an answer's display unit is decided.  ``unit``: the
        unit a quantity names for itself (``unit: Hz``), which must be of ``dim``."""
        return show(self, dim, kind, unit)

    # display units of derived quantities -------------------------------------
    def display(self, base: str, order: int) -> tuple[str, float]:
        """Display unit and SI factor of the ``order``-th time derivative of a
        quantity of kind ``base`` ('length' or 'angle')."""
        if base == "angle":
            if order == 0:
                return self.names["angle"], self.factor("angle")
            if order == 1:
                return self.names["angular_rate"], self.factor("angular_rate")
            # an angular acceleration in the angle unit of the rate (deg/s: deg/s^2), or of
            # the file where the rate counts turns (rpm, rev/s: the file's deg/s^2)
            name = self.names["angular_rate"][:-2]
            if name not in ANGLE:
                name = self.names["angle"]
            return f"{name}/s^2", ANGLE[name]
        unit = self.names["length"]
        factor = self.factor("length")
        suffix = ["", "/s", "/s^2"][order]
        return unit + suffix, factor


# --- dimensions ---------------------------------------------------------------------------
class Dimension(tuple):
    """A physical dimension as exponents of mass, length, time and angle (M, L, T, A).

    Angles are kept apart for display (a mode shape in mm/deg, a stiffness in Nm/rad) and
    ignored in comparisons (:meth:`agrees`), as SI does: the radian is 1, so a period
    2 pi / omega (omega in rad/s) is a time.  Exponents are integers or halves (a square
    root of a stiffness over a mass is a frequency)."""

    __slots__ = ()
    NAMES = ("mass", "length", "time", "angle")

    def __new__(cls, mass=0, length=0, time=0, angle=0):
        return super().__new__(cls, tuple(_exponent(e) for e in (mass, length, time, angle)))

    mass = property(lambda self: self[0])
    length = property(lambda self: self[1])
    time = property(lambda self: self[2])
    angle = property(lambda self: self[3])

    def __mul__(self, other):
        return Dimension(*(a + b for a, b in zip(self, other)))

    def __truediv__(self, other):
        return Dimension(*(a - b for a, b in zip(self, other)))

    def __pow__(self, power):
        return Dimension(*(a * power for a in self))

    def agrees(self, other) -> bool:
        """The same dimension in SI (angles apart)."""
        return self[:3] == other[:3]

    @property
    def none(self) -> bool:
        """Dimensionless (a ratio, an angle's radians aside)."""
        return not any(self[:3])

    def text(self) -> str:
        """``M L^2 T^-2`` and the like; '1' for a pure number."""
        parts = [f"{s}" + ("" if e == 1 else f"^{_exp_text(e)}")
                 for s, e in zip("MLTA", self) if e]
        return " ".join(parts) or "1"

    def __repr__(self):
        return f"Dimension({self.text()})"


def _exponent(value):
    """An exponent as an int, or a float that is a whole number of halves."""
    twice = round(2 * value)
    if abs(2 * value - twice) > 1e-9:
        raise InputError(f"a dimension's exponent must be a whole number of halves, got {value}")
    return twice // 2 if twice % 2 == 0 else twice / 2


def _exp_text(e) -> str:
    return str(int(e)) if float(e).is_integer() else str(e)


NONE = Dimension()
MASS_DIM, LENGTH_DIM, TIME_DIM, ANGLE_DIM = (Dimension(1), Dimension(0, 1), Dimension(0, 0, 1),
                                             Dimension(0, 0, 0, 1))
FORCE_DIM = Dimension(1, 1, -2)

#: the dimension of each kind of unit
DIMENSIONS = {
    "length": LENGTH_DIM,
    "angle": ANGLE_DIM,
    "angular_rate": ANGLE_DIM / TIME_DIM,
    "force": FORCE_DIM,
    "torque": FORCE_DIM * LENGTH_DIM,
    "mass": MASS_DIM,
    "inertia": MASS_DIM * LENGTH_DIM ** 2,
    "stiffness": FORCE_DIM / LENGTH_DIM,
    "torsional_stiffness": FORCE_DIM * LENGTH_DIM / ANGLE_DIM,
    "damping": FORCE_DIM / LENGTH_DIM * TIME_DIM,
    "torsional_damping": FORCE_DIM * LENGTH_DIM * TIME_DIM / ANGLE_DIM,
    "frequency": ANGLE_DIM / TIME_DIM,
    "speed": LENGTH_DIM / TIME_DIM,
    "time": TIME_DIM,
    "pressure": FORCE_DIM / LENGTH_DIM ** 2,
    "area": LENGTH_DIM ** 2,
}
#: the kind a dimension is shown in when a quantity names none (frequencies and angular
#: rates share a dimension: a rate of an angle is shown as an angular rate unless asked)
SHOWN_AS = {}
for _kind in ("length", "angle", "angular_rate", "force", "torque", "mass", "inertia",
              "stiffness", "torsional_stiffness", "damping", "torsional_damping", "speed",
              "time", "pressure", "area"):
    SHOWN_AS.setdefault(DIMENSIONS[_kind], _kind)
#: pure numbers
RATIOS = {"": 1.0, "1": 1.0, "%": 0.01}


def unit_dimension(name: str):
    """(kind, Dimension, SI factor) of a unit ``name`` of the tables ('' or '1': a pure
    number, '%': a hundredth); None for a name no table has.  A name shared by two kinds
    ('lb': a mass and a force; 'rpm': a frequency and an angular rate) is the first kind
    of :data:`KINDS` that has it, except where ``prefer`` below says otherwise."""
    if name in RATIOS:
        return None, NONE, RATIOS[name]
    for kind, table in KINDS.items():
        if name in table:
            return kind, DIMENSIONS[kind], table[name]
    return None


def show(units, dim, kind=None, unit=None) -> tuple[str, float]:
    """(unit name, SI factor) of a value of dimension ``dim`` in the file's units: the
    quantity's own ``unit`` when it names one (any unit :func:`parse_unit` reads whose
    dimension agrees with ``dim``, angles aside: N kg/m for M^2 T^-2, 1/s for rad/s); else
    the file's unit of ``kind`` (or of the kind the dimension is shown as); else a product
    of the file's named units (a force, a length, a mass, a time, an angle) with the fewest
    factors, written as ``N/rad``, ``kg mm``, ``mm/deg``; a pure number has no unit."""
    if unit is not None:
        named = parse_unit(unit, dim)
        if kind is not None and unit in KINDS[kind]:
            named = (DIMENSIONS[kind], KINDS[kind][unit])
        if named is None or not named[0].agrees(dim):
            raise InputError(f"unit '{unit}' is not a unit of {dim.text()}",
                             hint="give one of " + ", ".join(fitting(units, dim)))
        return unit, named[1]
    if kind is not None and DIMENSIONS[kind] == dim:
        return units.names[kind], units.factor(kind)
    named = SHOWN_AS.get(dim)
    if named is not None:
        return units.names[named], units.factor(named)
    if dim == NONE:
        return "", 1.0
    return _composed(units, dim)


#: the kinds a composed unit is made of, in the order they are tried and written
_BASES = ("force", "mass", "length", "time", "angle")


def _composed(units, dim) -> tuple[str, float]:
    """``dim`` as a product of the file's units of :data:`_BASES` with the fewest factors
    (a force counts once): force^f length^l mass^m time^t angle^a."""
    best = None
    for f in range(-2, 3):
        rest = dim / FORCE_DIM ** f
        powers = {"force": f, "mass": rest.mass, "length": rest.length, "time": rest.time,
                  "angle": rest.angle}
        cost = sum(abs(p) for p in powers.values())
        if best is None or cost < best[0]:
            best = (cost, powers)
    powers = best[1]
    up, down, factor = [], [], 1.0
    for kind in _BASES:
        p = powers[kind]
        if not p:
            continue
        name = units.names[kind]
        factor *= units.factor(kind) ** p
        word = name if abs(p) == 1 else f"{name}^{_exp_text(abs(p))}"
        (up if p > 0 else down).append(word)
    text = " ".join(up) or "1"
    if down:
        text += "/" + (down[0] if len(down) == 1 else "(" + " ".join(down) + ")")
    return text, factor


def fitting(units, dim) -> list:
    """The names of the units of dimension ``dim``: those of the tables and of energy and
    power that have it; else the file's product of units for it, the same product in SI
    ('N kg/mm', 'N kg/m') and the units that have it angles aside ('mm/deg', 'mm/rad',
    'mm' ...); '1' and '%' for a pure number."""
    if dim.none and not dim.angle:
        return list(RATIOS)[1:]
    named = [(name, DIMENSIONS[kind]) for kind, table in KINDS.items() for name in table]
    named += [(name, d) for name, (d, _) in _GLUED.items()]
    exact = list(dict.fromkeys(name for name, d in named if d == dim))
    if exact:
        return exact
    si = Units({"length": "m", "force": "N", "mass": "kg", "time": "s", "angle": "rad"})
    names = [_composed(units, dim)[0], _composed(si, dim)[0]]
    return list(dict.fromkeys(names + [name for name, d in named if d.agrees(dim)]))


#: units written glued (N s, N m s) and the units of energy and power
_GLUED = {"Ns": (FORCE_DIM * TIME_DIM, 1.0), "Nms": (FORCE_DIM * LENGTH_DIM * TIME_DIM, 1.0),
          "Nmm": (FORCE_DIM * LENGTH_DIM, 1e-3), "Nmms": (FORCE_DIM * LENGTH_DIM * TIME_DIM, 1e-3),
          # energy and power, which no kind of the file's units holds
          "J": (FORCE_DIM * LENGTH_DIM, 1.0), "kJ": (FORCE_DIM * LENGTH_DIM, 1e3),
          "W": (FORCE_DIM * LENGTH_DIM / TIME_DIM, 1.0),
          "kW": (FORCE_DIM * LENGTH_DIM / TIME_DIM, 1e3)}


def _unit_candidates(name: str) -> list:
    """Every (Dimension, SI factor) a unit name of the tables may mean ('lb': a mass or a
    force), the glued N s and N m s, '1' and '%' as pure numbers."""
    if name in RATIOS:
        return [(NONE, RATIOS[name])]
    found = [(DIMENSIONS[kind], table[name]) for kind, table in KINDS.items() if name in table]
    if name in _GLUED:
        found.append(_GLUED[name])
    return list(dict.fromkeys(found))


def _token_candidates(token: str) -> list:
    """The meanings of one factor of a composed unit: a unit name, with ``^p`` a power."""
    base, _, power = token.partition("^")
    try:
        p = float(power) if power else 1
    except ValueError:
        return []
    try:
        return [(dim ** p, factor ** p) for dim, factor in _unit_candidates(base)]
    except InputError:          # a power that is not a whole number of halves
        return []


def parse_unit(name, expected=None):
    """(Dimension, SI factor) of a unit written with the tables' names, alone or as products
    and quotients of them, as :func:`show` writes composed units (``kg m``, ``mm/s^2``,
    ``N s/rad``, ``1/(in deg)``) and files write units of their own; None for a name it
    cannot read.  Where a name means two things ('lb' a mass or a force), the meaning
    whose dimension agrees with ``expected`` (a Dimension) is taken."""
    import itertools
    if not isinstance(name, str) or len(name) > 80:
        return None
    text = name.strip()
    whole = _unit_candidates(text)
    if not whole:
        up, slash, down = text.partition("/")
        if slash and down.startswith("(") and down.endswith(")"):
            down = down[1:-1]
        if "/" in down or "(" in up or "(" in down or not up.strip() \
                or (slash and not down.strip()):
            return None
        factors = [(t, 1) for t in up.split() if t != "1"] + \
            [(t, -1) for t in down.split()]
        options = []
        for token, sign in factors:
            found = _token_candidates(token)
            if not found:
                return None
            options.append([(dim ** sign, factor ** sign) for dim, factor in found])
        whole = []
        for combination in itertools.product(*options):
            dim, factor = NONE, 1.0
            for d, f in combination:
                dim, factor = dim * d, factor * f
            whole.append((dim, factor))
    if expected is not None:
        agreeing = [w for w in whole if w[0].agrees(expected)]
        if agreeing:
            return agreeing[0]
    return whole[0] if whole else None
