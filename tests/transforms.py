"""Rewritings of a mechanism file that must not change its answers: the same mechanism in
other units, with its sections and entries in another order, with its points and links
renamed.  Used by tests/test_invariance_units.py and tests/test_invariance_names.py.

Everything here is written from the file format as docs/schema.md, docs/dynamics.md,
docs/vibrations.md and docs/conventions.md describe it, never from linkcli's own tables:
the unit factors below are the definitions (in = 0.0254 m, lb = 0.45359237 kg, lbf = lb g0
with g0 = 9.80665 m/s^2, one turn = 2 pi rad), and :func:`sites` knows which value of
which section is a length, an angle, a force...

Units.  Every value of the file is rewritten in the new units: a number by its factor, an
expression ``e`` of a site of kind K as ``(e')*c`` with c = (old unit of K)/(new unit of
K).  Parameters: docs/schema.md says a parameter is in the unit of the values it is written
as on its own, or a number times it (``length: a``, ``k: 2*ks``, ``[L, -L]``); an
expression that reads it (``expr:``), a ``find:`` unknown's interval without ``unit:`` and
the solved value of a design question are in that unit.  So that all of these keep their
meaning, each parameter with such a kind is converted where it is defined (``a: (def')*c``)
and holds its value in the new unit; a parameter without one keeps its number.  Inside
every expression (of a parameter or of a site) a parameter ``a`` is read back in the old
unit as ``(a/c_a)``, so an expression is evaluated on the old numbers and converted as a
whole: ``R - 100`` at a length becomes ``((R/c) - 100)*c``, which is still a multiple of
nothing, and ``2*R`` becomes ``(2*(R/c))*c``, still a multiple of R.  ``expr:`` quantities
are evaluated in SI and are kept as written.  A ``find:`` target written as a bare number
(in the answer's display unit) is written with the unit the original file displays it in
(``0.1`` -> ``"0.1 Hz"``); an interval, a start and ``nearest`` without ``unit:`` are in
the parameter's unit and converted as it is.  Answer keys, quiz tolerances and the report
are not answers and are kept (the comparison is of solved values, not of ``check``).

A numeric value at a place :func:`sites` does not know is returned in ``unknown``: the
tests count and list such files rather than rewrite them half-way.

Names.  Every point and every link gets a prefix (``B`` -> ``pB``, ``BCD`` -> ``lBCD``),
wherever it is referenced, including the derived names ``xB``, ``yBdot`` in the report,
the keys, ``find`` targets and expressions, and keys' point entries (``B: [x, y]``).  A
common prefix keeps the alphabetical order of every link's points, so each vector z_i of
the key convention (from the alphabetically first vertex to the next) runs the same way.
"""
from __future__ import annotations

import ast
import copy
import math
import random
import re

# --- units, by their definitions ---------------------------------------------------------
INCH, FOOT = 0.0254, 0.3048
POUND = 0.45359237
G0 = 9.80665
LBF = POUND * G0
TURN = 2 * math.pi

#: atom -> (SI factor, dimension (mass, length, time, angle)); an angle is a dimension of
#: its own here, so that a turn, a degree and a radian are told apart
_M, _L, _T, _A = (1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1)
_F = (1, 1, -2, 0)


def _dim(*parts):
    out = [0, 0, 0, 0]
    for part, power in parts:
        for i in range(4):
            out[i] += part[i] * power
    return tuple(out)


_FORCE_LEN = _dim((_F, 1), (_L, 1))
_FORCE_TIME = _dim((_F, 1), (_T, 1))
ATOMS = {
    "m": [(1.0, _L)], "cm": [(0.01, _L)], "mm": [(0.001, _L)], "km": [(1000.0, _L)],
    "in": [(INCH, _L)], "ft": [(FOOT, _L)], "mi": [(1609.344, _L)],
    "rad": [(1.0, _A)], "deg": [(math.pi / 180, _A)], "rev": [(TURN, _A)],
    "s": [(1.0, _T)], "ms": [(0.001, _T)], "min": [(60.0, _T)], "h": [(3600.0, _T)],
    "kg": [(1.0, _M)], "g": [(0.001, _M)], "slug": [(LBF / FOOT, _M)],
    "lb": [(POUND, _M), (LBF, _F)],          # a mass, or (books) the pound-force
    "N": [(1.0, _F)], "kN": [(1000.0, _F)], "lbf": [(LBF, _F)], "kip": [(1000 * LBF, _F)],
    "Nm": [(1.0, _FORCE_LEN)], "Nmm": [(0.001, _FORCE_LEN)], "kNm": [(1000.0, _FORCE_LEN)],
    "J": [(1.0, _FORCE_LEN)], "kJ": [(1000.0, _FORCE_LEN)],
    "W": [(1.0, _dim((_FORCE_LEN, 1), (_T, -1)))],
    "kW": [(1000.0, _dim((_FORCE_LEN, 1), (_T, -1)))],
    "Ns": [(1.0, _FORCE_TIME)], "kNs": [(1000.0, _FORCE_TIME)],
    "Nms": [(1.0, _dim((_FORCE_LEN, 1), (_T, 1)))],
    "Nmms": [(0.001, _dim((_FORCE_LEN, 1), (_T, 1)))],
    "Pa": [(1.0, _dim((_F, 1), (_L, -2)))], "kPa": [(1e3, _dim((_F, 1), (_L, -2)))],
    "MPa": [(1e6, _dim((_F, 1), (_L, -2)))], "bar": [(1e5, _dim((_F, 1), (_L, -2)))],
    "psi": [(LBF / INCH ** 2, _dim((_F, 1), (_L, -2)))],
    "ksi": [(1000 * LBF / INCH ** 2, _dim((_F, 1), (_L, -2)))],
    "Hz": [(TURN, _dim((_A, 1), (_T, -1)))], "rpm": [(TURN / 60, _dim((_A, 1), (_T, -1)))],
    "mph": [(1609.344 / 3600, _dim((_L, 1), (_T, -1)))],
    "1": [(1.0, (0, 0, 0, 0))], "%": [(0.01, (0, 0, 0, 0))],
}


def parse(unit: str) -> list:
    """Every (SI factor, dimension) the display unit ``unit`` may mean ('lb': a mass or a
    force): products of atoms with powers, one '/' and a parenthesised denominator
    (``kg m^2``, ``N/mm^2``, ``mm/deg``, ``1/(in deg)``, ``km/h``); '' is a pure number."""
    text = (unit or "").strip()
    if not text:
        return [(1.0, (0, 0, 0, 0))]
    up, _, down = text.partition("/")
    down = down.strip()
    if down.startswith("(") and down.endswith(")"):
        down = down[1:-1]
    options = [(1.0, (0, 0, 0, 0))]
    for part, sign in ((up, 1), (down, -1)):
        for token in part.split():
            base, _, power = token.partition("^")
            p = sign * (float(power) if power else 1.0)
            if base not in ATOMS:
                raise KeyError(f"unit '{unit}': unknown atom '{base}'")
            options = [(f * a ** p, tuple(d + e * p for d, e in zip(dim, adim)))
                       for f, dim in options for a, adim in ATOMS[base]]
    return options


def factor(unit: str) -> float:
    """The SI factor of an unambiguous unit."""
    found = {f for f, _ in parse(unit)}
    if len(found) != 1:
        raise KeyError(f"unit '{unit}' is ambiguous")
    return found.pop()


# --- a file's unit system -----------------------------------------------------------------
#: the defaults of docs/schema.md ("units")
DEFAULTS = {"length": "mm", "angle": "deg", "force": "N", "torque": "Nm", "mass": "kg",
            "inertia": "kg m^2", "stiffness": "N/m", "torsional_stiffness": "Nm/rad",
            "damping": "Ns/m", "torsional_damping": "Nms/rad", "frequency": "rad/s",
            "speed": "m/s", "time": "s"}
KINDS = tuple(DEFAULTS) + ("angular_rate", "pressure", "area")
#: the dimension of each kind of value (mass, length, time, angle)
KIND_DIMS = {
    "length": _L, "angle": _A, "force": _F, "torque": _FORCE_LEN, "mass": _M,
    "inertia": _dim((_M, 1), (_L, 2)), "stiffness": _dim((_F, 1), (_L, -1)),
    "torsional_stiffness": _dim((_FORCE_LEN, 1), (_A, -1)),
    "damping": _dim((_FORCE_TIME, 1), (_L, -1)),
    "torsional_damping": _dim((_FORCE_LEN, 1), (_T, 1), (_A, -1)),
    "frequency": _dim((_A, 1), (_T, -1)), "angular_rate": _dim((_A, 1), (_T, -1)),
    "speed": _dim((_L, 1), (_T, -1)), "time": _T, "pressure": _dim((_F, 1), (_L, -2)),
    "area": _dim((_L, 2)), "angular_accel": _dim((_A, 1), (_T, -2)),
    "length_rate": _dim((_L, 1), (_T, -1)), "length_accel": _dim((_L, 1), (_T, -2)),
    "per_length": _dim((_L, -1))}


class System:
    """The unit of every kind of value in a file that declares ``declared``; besides the
    kinds of ``units:``, the rates of a driver or coordinate (docs/conventions.md): a
    length per second (``length_rate``) and per second squared, an angular acceleration
    in the angular rate's angle unit per s^2 (the angle unit's when rates are in turns,
    rpm or rev/s)."""

    def __init__(self, declared: dict | None):
        self.declared = dict(declared or {})
        names = dict(DEFAULTS)
        names.update({k: v for k, v in self.declared.items() if k in KINDS})
        names.setdefault("angular_rate", names["angle"] + "/s")
        names.setdefault("pressure", f"{names['force']}/{names['length']}^2")
        names.setdefault("area", f"{names['length']}^2")
        rate = names["angular_rate"]
        names["angular_accel"] = (names["angle"] if rate in ("rpm", "rev/s")
                                  else rate[:-2]) + "/s^2"
        names["length_rate"] = names["length"] + "/s"
        names["length_accel"] = names["length"] + "/s^2"
        names["per_length"] = "1/" + names["length"]      # a diametral pitch (gears:)
        self.names = names
        for kind in names:          # every unit read now: a file's unknown unit fails here
            self.factor(kind)

    def factor(self, kind: str) -> float:
        """SI value of one unit of ``kind`` (of an ambiguous name, 'lb', the meaning of the
        kind's dimension: a mass, or the pound-force of a force or a stiffness)."""
        options = [f for f, d in parse(self.names[kind]) if d == KIND_DIMS[kind]]
        if len(options) != 1:
            raise KeyError(f"{kind} unit '{self.names[kind]}' is not one unit of {kind}")
        return options[0]

    def __repr__(self):
        return f"System({self.declared})"


def ratio(old: System, new: System, kind: str | None) -> float:
    """The number that turns a value of ``kind`` in ``old`` units into ``new`` units."""
    if kind is None:
        return 1.0
    return old.factor(kind) / new.factor(kind)


# --- where the values are, and of which kind ----------------------------------------------
UNKNOWN_WORD = "unknown"


class Sites:
    """The numeric places of a file: ``kinds`` path -> kind (None: a pure number), and
    ``unknown`` the numeric places the format description below does not know."""

    def __init__(self, data: dict):
        self.data = data
        self.kinds: dict = {}
        self.unknown: list = []
        driver = data.get("driver") if isinstance(data.get("driver"), dict) else None
        drivers = [d for d in (data.get("drivers") or {}).values() if isinstance(d, dict)] \
            if isinstance(data.get("drivers"), dict) else []
        if driver is None and drivers:      # several drivers: the first is q
            driver = drivers[0]
        self.driver_base = None
        if driver is not None:
            # a pay-out's q is its disc's turn (its value and rates are lengths)
            self.driver_base = "angle" if "angle" in driver or "payout" in driver else "length"
        self.bases = {}
        for name, spec in (data.get("coordinates") or {}).items():
            if isinstance(spec, dict):
                self.bases[name] = "angle" if "angle" in spec else "length"
        self.motor_expressions: list = []      # motors' torque(w, q, t): paths
        self.torsional = set()
        for section in ("springs", "dampers"):
            for name, spec in (data.get(section) or {}).items():
                if isinstance(spec, dict) and "bodies" in spec:
                    self.torsional.add(name)
        for key, value in data.items():
            reader = getattr(self, "_" + str(key), None)
            if key in IGNORED:
                continue
            if reader is None:
                self._numbers(value, (key,))
            else:
                reader(value, (key,))

    # helpers
    def items(self, value, path):
        """The entries of a section, or none (its numbers unknown) when it is no mapping."""
        if isinstance(value, dict):
            return value.items()
        self._numbers(value, path)
        return []

    def put(self, path, kind, value):
        if _is_value(value):
            self.kinds[path] = kind

    def _numbers(self, value, path):
        """Every numeric leaf below ``path``: unknown."""
        if isinstance(value, dict):
            for k, v in value.items():
                self._numbers(v, path + (k,))
        elif isinstance(value, list):
            for i, v in enumerate(value):
                self._numbers(v, path + (i,))
        elif _is_value(value) and not _is_word(value):
            self.unknown.append(path)

    def _only(self, spec, path, known: dict):
        """``known``: key -> kind (or a callable (value, path)); others are unknown."""
        if not isinstance(spec, dict):
            self._numbers(spec, path)
            return
        for key, value in spec.items():
            if key in known:
                kind = known[key]
                if callable(kind):
                    kind(value, path + (key,))
                elif kind != NAME:
                    self.put(path + (key,), kind, value)
            else:
                self._numbers(value, path + (key,))

    def xy(self, value, path):
        if isinstance(value, list):
            for i, v in enumerate(value):
                self.put(path + (i,), "length", v)
        elif not isinstance(value, str):
            self._numbers(value, path)

    # sections
    def _frame(self, value, path):
        for name, xy in self.items(value, path):
            self.xy(xy, path + (name,))

    _points = _frame

    def _links(self, value, path):
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), {"points": NAME, "length": "length",
                                               "shape": self._shape, "local": self._frame})

    def _shape(self, value, path):
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), {"length": "length", "angle": "angle",
                                               "from": NAME, "side": NAME,
                                               "distances": self._lengths})

    def _lengths(self, value, path):
        if isinstance(value, dict):
            for name, v in value.items():
                self.put(path + (name,), "length", v)
        else:
            self.put(path, "length", value)

    def _actuators(self, value, path):
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), {"points": NAME})

    def _sliders(self, value, path):
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), {"point": NAME, "guide": self._guide,
                                               "carries": self._carries})

    def _guide(self, value, path):
        self._only(value, path, {"x": "length", "y": "length", "through": self.xy,
                                 "angle": "angle", "along": NAME, "offset": "length"})

    def _carries(self, value, path):
        for name, spec in self.items(value, path):
            if isinstance(spec, list):
                self.xy(spec, path + (name,))
            else:
                self._only(spec, path + (name,), {"dx": "length", "dy": "length",
                                                   "along": "length", "normal": "length"})

    def _rolling(self, value, path):
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), {"disc": NAME, "radius": "length",
                                               "on": self._track, "gear": NAME})

    def _track(self, value, path):
        self._only(value, path, {"line": self._line, "side": NAME, "body": NAME,
                                 "circle": NAME, "radius": "length", "inside": NAME,
                                 "disc": NAME, "gear": NAME})

    def _gears(self, value, path):
        """docs/schema.md, "gears": teeth a count, the module and the addendum lengths, the
        diametral pitch teeth per unit of length, the pressure angle an angle."""
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), {"teeth": None, "module": "length",
                                               "diametral_pitch": "per_length",
                                               "addendum": "length",
                                               "pressure_angle": "angle", "internal": NAME})

    def _line(self, value, path):
        if not isinstance(value, (list, str)):
            self.put(path, "angle", value)
        elif isinstance(value, str) and value.lstrip("-") not in ("x", "y"):
            self.put(path, "angle", value)

    def _cords(self, value, path):
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), {"pulley": NAME, "radius": "length",
                                               "along": self._line, "side": NAME,
                                               "to": self._cord_end, "slip": self._slip})

    def _slip(self, value, path):
        """A belt's slip: a percentage, or two [s1, s2] (pure numbers)."""
        for i, v in enumerate(value if isinstance(value, list) else [value]):
            self.put(path + ((i,) if isinstance(value, list) else ()), None, v)

    def _cord_end(self, value, path):
        if isinstance(value, dict):
            self._only(value, path, {"disc": NAME, "radius": "length", "side": NAME})

    def _driver(self, value, path, base=None):
        base = base or self.driver_base
        if isinstance(value, dict) and "payout" in value:
            base = "length"             # the length of cord unwound
        self._only(value, path, {"angle": NAME, "length": NAME, "x": NAME, "y": NAME,
                                 "payout": NAME,
                                 "value": base,
                                 "rate": "angular_rate" if base == "angle" else "length_rate",
                                 "accel": "angular_accel" if base == "angle"
                                 else "length_accel"})

    def _drivers(self, value, path):
        """Each named driver as ``driver:``, in the unit of its own kind."""
        for name, spec in self.items(value, path):
            base = "angle" if isinstance(spec, dict) and "angle" in spec else "length"
            self._driver(spec, path + (name,), base)

    def _coordinates(self, value, path):
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), {"angle": NAME, "length": NAME, "x": NAME,
                                               "y": NAME, "value": self.bases.get(name)})

    def _loads(self, value, path):
        for name, spec in self.items(value, path):
            if not isinstance(spec, dict):
                self._numbers(spec, path + (name,))
                continue
            kind = spec.get("type")
            value_kind = {"torque": "torque", "axial": "force", "pressure": "pressure",
                          "driver": "torque" if self.driver_base == "angle" else "force",
                          "brake": "torque"}
            self._only(spec, path + (name,), {
                "type": NAME, "at": NAME, "on": NAME, "x": "force", "y": "force",
                "magnitude": "force", "angle": "angle", "diameter": "length", "area": "area",
                "value": value_kind.get(kind, NAME if kind == "force" else None),
                # machine dynamics (docs/machines.md): a motor's characteristic, a window
                "stall": "torque", "no_load": "angular_rate", "torque": "torque",
                "speeds": self._list("angular_rate"), "torques": self._list("torque"),
                "over": self._list(self.driver_base)})
            if kind == "motor" and isinstance(spec.get("torque"), str):
                self.motor_expressions.append(path + (name, "torque"))
            if kind not in value_kind and kind not in ("force", "motor"):
                self.unknown.append(path + (name, "type"))

    def _list(self, kind):
        """A list of values of ``kind``."""
        def read(value, path):
            if isinstance(value, list):
                for i, v in enumerate(value):
                    self.put(path + (i,), kind, v)
            else:
                self._numbers(value, path)
        return read

    def _when(self, value, path):
        """A machine's event: stop, or a time, a speed (the driver's rate), a distance
        travelled (the driver's unit) or a number of turns."""
        if isinstance(value, dict):
            rate = "angular_rate" if self.driver_base == "angle" else "length_rate"
            self._only(value, path, {"time": "time", "speed": rate,
                                     "turned": self.driver_base, "turns": None})

    def _quantities(self, value, path):
        limit_kind = self.driver_base
        for name, spec in self.items(value, path):
            if isinstance(spec, dict) and "clutch" in spec:     # docs/machines.md
                self._only(spec, path + (name,), {"clutch": NAME, "shaft": NAME, "unit": NAME,
                                                  "time": "time", "speed": "angular_rate"})
                continue
            known = dict.fromkeys(QUANTITY_WORDS, NAME)
            known.update({"from": limit_kind, "to": limit_kind, "time": "time",
                          "axis": self._axis, "radius": "length", "when": self._when,
                          "stages": self._pure, "powers": self._pure})
            self._only(spec, path + (name,), known)

    def _motion(self, value, path):
        """The motion of a machine (docs/machines.md): the time integrated, the periodic
        regime's mean speed (the driver's rate) and a diagram's areas (pure numbers) with
        the scales of its drawing, the coefficient of fluctuation and the turns of a cycle."""
        if value is None:
            return
        self._only(value, path, {"until": "time", "regime": self._regime,
                                 "flywheel": lambda v, p: self._only(v, p, {"fluctuation": None}),
                                 "turns_per_cycle": None})

    def _regime(self, value, path):
        rate = "angular_rate" if self.driver_base == "angle" else "length_rate"
        self._only(value, path, {
            "mean_speed": rate,
            "areas": lambda v, p: [self.put(p + (i,), None, a) for i, a in enumerate(v)]
            if isinstance(v, list) else self._numbers(v, p),
            "scale": lambda v, p: self._only(v, p, {"torque": "torque", "angle": "angle"})})

    def _pure(self, value, path):
        """A list of pure numbers (docs/machines.md: stages' efficiencies, and input powers of
        which only the ratios count): kept as written."""
        if not isinstance(value, list):
            self._numbers(value, path)
            return
        for i, v in enumerate(value):
            self.put(path + (i,), None, v)


    def _axis(self, value, path):
        if isinstance(value, dict):
            self._only(value, path, {"angle": "angle"})

    def _shafts(self, value, path):
        """A clutch problem's shafts (docs/machines.md)."""
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), {
                "inertia": "inertia", "speed": "angular_rate", "torque": "torque",
                "resisting": "torque",
                "motor": lambda v, p: self._only(v, p, {"stall": "torque",
                                                        "no_load": "angular_rate"})})

    def _clutch(self, value, path):
        self._only(value, path, {
            "between": NAME, "torque": "torque",
            "plate": lambda v, p: self._only(v, p, {
                "mu": None, "force": "force", "outer": "length", "inner": "length",
                "pairs": NAME, "wear": NAME})})

    def _dynamics(self, value, path):
        self._only(value, path, {"gravity": self._gravity, "bodies": self._bodies,
                                 "masses": self._masses, "friction": self._friction,
                                 "discs": self._discs,
                                 "friction_circles": self._lengths})

    def _gravity(self, value, path):
        if isinstance(value, dict):     # g is always m/s^2 (docs/dynamics.md)
            self._only(value, path, {"g": None, "angle": "angle"})
        else:
            self.put(path, None, value)

    def _bodies(self, value, path):
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), {"mass": "mass", "inertia": "inertia",
                                               "center": self.xy})

    def _masses(self, value, path):
        for name, v in self.items(value, path):
            self.put(path + (name,), "mass", v)

    def _friction(self, value, path):
        for name, v in self.items(value, path):
            if isinstance(v, dict):
                self._only(v, path + (name,), {"mu": None})
            else:
                self.put(path + (name,), None, v)

    def _discs(self, value, path):
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), {"center": NAME, "radius": "length",
                                               "mass": "mass", "inertia": "inertia",
                                               "side": NAME, "rolling_resistance": "length"})

    def _element(self, name, stiff, torsional_stiff):
        torsional = name in self.torsional
        return {"between": NAME, "bodies": NAME, "along": self._line,
                "k": torsional_stiff if torsional else stiff,
                "c": torsional_stiff if torsional else stiff,
                "free_length": "length", "free_angle": "angle",
                "preload": "torque" if torsional else "force"}

    def _springs(self, value, path):
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), self._element(name, "stiffness",
                                                           "torsional_stiffness"))

    def _dampers(self, value, path):
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), self._element(name, "damping",
                                                           "torsional_damping"))

    def _excitation(self, value, path):
        self._only(value, path, {"frequency": "frequency", "forces": self._harmonics,
                                 "supports": self._supports, "road": self._road})

    def _harmonics(self, value, path):
        for name, spec in self.items(value, path):
            self._only(spec, path + (name,), {"at": NAME, "on": NAME, "x": "force",
                                               "y": "force", "torque": "torque",
                                               "phase": "angle"})

    def _supports(self, value, path):
        for name, spec in self.items(value, path):
            base = self.bases.get(spec.get("coordinate")) if isinstance(spec, dict) else None
            self._only(spec, path + (name,), {"coordinate": NAME, "amplitude": base,
                                               "phase": "angle"})

    def _road(self, value, path):
        self._only(value, path, {"coordinate": NAME, "amplitude": "length",
                                 "wavelength": "length", "speed": "speed", "phase": "angle"})

    def _initial(self, value, path):
        for key, v in self.items(value, path):
            if key in ("from", "mode"):         # a mode's number is no value
                continue
            name, rate = (key[:-4], True) if str(key).endswith("_dot") else (key, False)
            base = self.bases.get(name)
            if base is None:
                self._numbers(v, path + (key,))
                continue
            kind = base if not rate else ("angular_rate" if base == "angle" else "length_rate")
            self.put(path + (key,), kind, v)

    def _find(self, value, path):
        pass        # read by :func:`rewrite_find`, which knows the parameters' kinds

    def _params(self, value, path):
        pass        # :func:`param_kinds`


NAME = object()     # a place that holds a name or a word, not a number
#: the keys of a quantity that hold names, words, mode numbers and powers (no values)
QUANTITY_WORDS = (
    "acceleration", "along", "angle", "between", "component", "contact_force", "driver",
    "instant_centre", "instant_centre_distance", "least_speed", "least_speed_at", "length",
    "load", "normal_acceleration", "normal_to", "point", "reaction", "relative",
    "relative_acceleration", "relative_speed", "rotation", "signed", "slider_force", "speed",
    "tangential_acceleration", "tension", "unit", "velocity_ratio", "x", "y",
    "at_maximum", "at_minimum", "maximum", "minimum", "stroke", "stroke_time", "time_ratio",
    "beat_period", "characteristic", "damped_period", "eigenvalue", "frequency_ratio",
    "largest", "monic", "natural_period", "part", "peak", "peak_amplitude", "peak_frequency",
    "receptance", "amplitude", "damped_frequency", "damping_matrix", "damping_ratio",
    "equilibrium", "force_amplitude", "forcing_frequency", "free_response", "mass_matrix",
    "mode_shape", "natural_frequency", "phase", "spring_force", "stiffness_matrix",
    "transmissibility", "expr", "centre_distance", "contact_ratio", "min_teeth", "with",
    "regime", "flywheel", "reduced_inertia", "reduced_inertia_slope", "reduced_torque",
    "motion",
    # efficiency questions (docs/machines.md): words, a load's or a slider's name
    "efficiency", "ideal_load", "reverse_load", "self_locking", "at")
IGNORED = {"title", "source", "notes", "statement", "units", "k", "report", "keys", "quiz",
           "equilibrium"}


def _is_word(value) -> bool:
    return isinstance(value, str) and value.strip() in (UNKNOWN_WORD, "static")


def _is_value(value) -> bool:
    """A number or an expression (text) at a numeric place."""
    if isinstance(value, bool) or value is None:
        return False
    return isinstance(value, (int, float, str)) and not _is_word(value)


# --- expressions -----------------------------------------------------------------------
def names_in(text) -> list:
    """The names an expression reads (functions and constants included)."""
    try:
        tree = ast.parse(str(text).strip(), mode="eval")
    except SyntaxError:
        return []
    return [n.id for n in ast.walk(tree) if isinstance(n, ast.Name)]


def scaled_name(text):
    """The one name ``text`` is a multiple of (``L``, ``-L``, ``2*L``, ``L/2``), or None:
    a parameter written so takes the unit of the place (docs/schema.md)."""
    try:
        node = ast.parse(str(text).strip(), mode="eval").body
    except SyntaxError:
        return None

    def number(n):
        return isinstance(n, ast.Constant) and isinstance(n.value, (int, float)) or (
            isinstance(n, ast.UnaryOp) and number(n.operand)) or (
            isinstance(n, ast.BinOp) and isinstance(n.op, (ast.Mult, ast.Div))
            and number(n.left) and number(n.right))
    while True:
        if isinstance(node, ast.Name):
            return None if node.id in ("pi", "deg") else node.id
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            node = node.operand
        elif isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult) and number(node.left):
            node = node.right
        elif isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Mult, ast.Div)) \
                and number(node.right):
            node = node.left
        else:
            return None


class _Substitute(ast.NodeTransformer):
    def __init__(self, table):
        self.table = table

    def visit_Call(self, node):
        node.args = [self.visit(a) for a in node.args]
        return node

    def visit_Name(self, node):
        if node.id in self.table:
            return ast.parse(self.table[node.id], mode="eval").body
        return node


def substitute(text, table: dict) -> str:
    """``text`` with each name of ``table`` replaced by the expression it maps to."""
    tree = ast.parse(str(text).strip(), mode="eval")
    return ast.unparse(_Substitute(table).visit(tree))


# --- parameters ---------------------------------------------------------------------------
def param_kinds(data: dict, sites: Sites) -> dict:
    """name -> the one kind of the places where the parameter is written on its own or as a
    number times it; parameters written so at places of two kinds, or never, have none."""
    params = data.get("params") or {}
    uses: dict = {}
    for path, kind in sites.kinds.items():
        value = at(data, path)
        if isinstance(value, str) and kind is not None:
            used = scaled_name(value)
            if used in params and used != "k":
                uses.setdefault(used, set()).add(kind)
    return {name: kinds.pop() for name, kinds in uses.items() if len(kinds) == 1}


def at(data, path):
    for part in path:
        data = data[part]
    return data


def _set(data, path, value):
    for part in path[:-1]:
        data = data[part]
    data[path[-1]] = value


def _num(x: float) -> float:
    return float(repr(float(x))) if math.isfinite(x) else x


class UnitRewrite:
    """One file rewritten from its units into ``new`` (a ``units:`` mapping)."""

    def __init__(self, data: dict, new_units: dict, display: dict | None = None):
        self.data = data
        self.unknown = []
        try:
            self.old = System(data.get("units"))
        except (KeyError, TypeError, AttributeError):     # units the format does not have
            self.old = System({})
            self.unknown.append(("units",))
        self.new = System(new_units)
        self.sites = Sites(data)
        self.unknown += self.sites.unknown
        self.kinds = param_kinds(data, self.sites)
        #: a parameter read in the old unit, inside any expression
        self.back = {p: f"({p}/{_num(ratio(self.old, self.new, k))!r})"
                     for p, k in self.kinds.items()}
        self.display = display or {}

    def value(self, value, kind):
        """``value`` (a number or an expression) of ``kind`` in the new units."""
        c = _num(ratio(self.old, self.new, kind))
        if literal(value):             # a number YAML reads as text (1e-300)
            value = float(value)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return value * c if c != 1.0 else value
        text = substitute(value, self.back) if self.back else str(value)
        return text if c == 1.0 else f"({text})*{c!r}"

    def motor(self, text):
        """A motor's torque, an expression of w (the speed, in the angular rate's unit), q
        (the driver's unit) and t (the time unit) besides the params: each read back in
        the old unit, the whole converted as a torque (docs/machines.md)."""
        back = dict(self.back)
        for name, kind in (("w", "angular_rate"), ("q", self.sites.driver_base),
                           ("t", "time")):
            back[name] = f"({name}/{_num(ratio(self.old, self.new, kind))!r})"
        c = _num(ratio(self.old, self.new, "torque"))
        return f"({substitute(text, back)})*{c!r}"

    def run(self) -> dict:
        out = copy.deepcopy(self.data)
        out["units"] = dict(self.new.declared)
        for path, kind in self.sites.kinds.items():
            value = literal(at(self.data, path))
            if value and not 1e-300 <= abs(value * ratio(self.old, self.new, kind)) <= 1e300:
                self.unknown.append(path + ("out of range in the new units",))
        for path, kind in self.sites.kinds.items():
            _set(out, path, self.value(at(self.data, path), kind))
        for path in self.sites.motor_expressions:
            _set(out, path, self.motor(at(self.data, path)))
        params = self.data.get("params") or {}
        for name, value in params.items():
            if isinstance(value, list):
                self.unknown.append(("params", name))
                continue
            out["params"][name] = self.value(value, self.kinds.get(name))
        if "find" in self.data:
            out["find"] = self.find(self.data["find"])
            for name, item in ((out["find"] or {}).get("unknowns") or {}).items():
                ends = item.get("between") if isinstance(item, dict) else None
                if any(literal(e) and not 1e-300 <= abs(literal(e)) <= 1e300
                       for e in ends or []):
                    self.unknown.append(("find", "unknowns", name,
                                         "out of range in the new units"))
        return out

    def find(self, spec):
        """Unknowns' intervals, starts and ``nearest`` without ``unit:`` in the parameter's
        (new) unit; bare targets written with the unit the original displays them in."""
        spec = copy.deepcopy(spec)
        if not isinstance(spec, dict):
            return spec
        unknowns = spec.get("unknowns") or {}
        for name, item in unknowns.items():
            if not isinstance(item, dict) or "unit" in item:
                continue
            c = _num(ratio(self.old, self.new, self.kinds.get(name)))
            if "between" in item and isinstance(item["between"], list):
                item["between"] = [_scale(v, c) for v in item["between"]]
            if "start" in item:
                item["start"] = _scale(item["start"], c)
        choose = spec.get("choose")
        if isinstance(choose, dict) and "nearest" in choose and len(unknowns) == 1:
            (name, item), = unknowns.items()
            if not (isinstance(item, dict) and "unit" in item):
                c = _num(ratio(self.old, self.new, self.kinds.get(name)))
                choose["nearest"] = _scale(choose["nearest"], c)
        for name, target in (spec.get("targets") or {}).items():
            if isinstance(target, (int, float)) and not isinstance(target, bool):
                unit = self.display.get(name)
                if unit is None:
                    unit = target_unit(self.data, name)
                if unit is None:
                    self.unknown.append(("find", "targets", name))
                elif unit:
                    spec["targets"][name] = f"{target!r} {unit}"
        return spec


def target_unit(data: dict, name: str):
    """The unit the file displays the answer ``name`` in, from the file without its design
    question (which a file that refuses the design still answers); None where not."""
    import linkcli
    plain = {k: v for k, v in data.items() if k != "find"}
    try:
        return linkcli.loads(to_yaml(plain)).solve(names=[name]).units[name]
    except (linkcli.LinkcliError, KeyError):
        return None


def literal(value) -> float:
    """The number a value writes (YAML reads 1e-300 as text), 0 for an expression."""
    try:
        return float(value) if not isinstance(value, bool) else 0.0
    except (TypeError, ValueError):
        return 0.0


def _scale(value, c):
    if literal(value):
        value = float(value)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return value * c
    return f"({value})*{c!r}"


# --- order and names ----------------------------------------------------------------------
#: sections whose entries may come in any order, and mappings inside sections
ENTRIES = ("frame", "points", "links", "loads", "quantities", "actuators", "sliders",
           "springs", "dampers", "rolling", "cords", "gears")
NESTED = (("dynamics",), ("dynamics", "bodies"), ("dynamics", "masses"),
          ("dynamics", "discs"), ("dynamics", "friction"), ("dynamics", "friction_circles"),
          ("excitation", "forces"), ("excitation", "supports"), ("report",))


def reorder(data: dict, order) -> dict:
    """The sections, the entries of :data:`ENTRIES` and the mappings of :data:`NESTED` put
    in the order ``order(list)`` gives (a report's lists too: their order is the printing's)."""
    out = {}
    for key in order(list(data)):
        value = copy.deepcopy(data[key])
        if key in ENTRIES and isinstance(value, dict):
            value = {k: value[k] for k in order(list(value))}
        out[key] = value
    for path in NESTED:
        parent, inner = None, out
        for part in path:
            parent, inner = inner, inner.get(part) if isinstance(inner, dict) else None
        if isinstance(inner, dict):
            parent[path[-1]] = {k: inner[k] for k in order(list(inner))}
    for section, names in (out.get("report") or {}).items():
        if isinstance(names, list):
            out["report"][section] = order(list(names))
    return out


def permute(data: dict, rng: random.Random) -> dict:
    """The sections and their entries in a random order (:func:`reorder`)."""
    def shuffled(items):
        rng.shuffle(items)
        return items
    return reorder(data, shuffled)


def reverse(data: dict) -> dict:
    """The sections and their entries in the reverse order (:func:`reorder`)."""
    return reorder(data, lambda items: items[::-1])


class Rename:
    """Every point P renamed ``point(P)`` and every link L ``link(L)``, wherever they are
    referenced (the places are those of the format: docs/schema.md, dynamics.md,
    vibrations.md)."""

    def __init__(self, data: dict, point_prefix="p", link_prefix="l"):
        self.data = data
        self.points = {n: point_prefix + n for sec in ("frame", "points")
                       for n in (data.get(sec) or {}) if isinstance(n, str)}
        self.links = {n: link_prefix + n for n in (data.get("links") or {})
                      if isinstance(n, str)}
        self.unknown: list = []
        self.check()

    def check(self):
        """Refuse new names that a parameter, a quantity, a load or another section's entry
        already has (with a point's derived names ``xP``, ``yP``)."""
        taken = set()
        for section in ("params", "quantities", "loads", "sliders", "actuators", "springs",
                        "dampers", "rolling", "cords", "coordinates", "drivers"):
            if isinstance(self.data.get(section), dict):
                taken |= set(self.data[section])
        new = set(self.points.values()) | set(self.links.values())
        new |= {a + p for p in self.points.values() for a in "xy"}
        clash = taken & new
        if clash:
            raise ValueError(f"renaming clashes with {sorted(clash)}")

    def point(self, name):
        return self.points.get(name, name) if isinstance(name, str) else name

    def body(self, name):
        """A body: a link (renamed), a slider, an actuator or its half, the frame."""
        return self.links.get(name, name) if isinstance(name, str) else name

    def either(self, name):
        if isinstance(name, str) and name in self.points:
            return self.points[name]
        return self.body(name)

    def answer(self, name):
        """A name of an answer: ``xB``, ``yBddot`` of a point renamed with it; others kept."""
        if not isinstance(name, str) or name in (self.data.get("quantities") or {}) \
                or name in (self.data.get("loads") or {}) \
                or name in (self.data.get("drivers") or {}) \
                or name in (self.data.get("params") or {}):
            return name
        m = re.fullmatch(r"([xy])(.+?)((?:d)?dot)?", name)
        if m and m.group(2) in self.points:
            return m.group(1) + self.points[m.group(2)] + (m.group(3) or "")
        return name

    def key_name(self, name, value):
        """A key's entry: a point's [x, y] (a load may share the point's name), or an
        answer's value."""
        answers = set(self.data.get("loads") or {}) | set(self.data.get("quantities") or {})
        if name in self.points and (isinstance(value, list) or name not in answers):
            return self.points[name]
        return self.answer(name)

    def expression(self, text):
        if not isinstance(text, str):
            return text
        table = {n: self.answer(n) for n in names_in(text) if self.answer(n) != n}
        return substitute(text, table) if table else text

    def keys_of(self, mapping, fn):
        return {fn(k): v for k, v in mapping.items()}

    def run(self) -> dict:
        d = copy.deepcopy(self.data)
        P, B = self.point, self.body
        for sec in ("frame", "points"):
            if isinstance(d.get(sec), dict):
                d[sec] = self.keys_of(d[sec], P)
        for name, spec in list((d.get("links") or {}).items()):
            if isinstance(spec, dict):
                if isinstance(spec.get("points"), list):
                    spec["points"] = [P(p) for p in spec["points"]]
                if isinstance(spec.get("shape"), dict):
                    shape = {}
                    for p, s in spec["shape"].items():
                        if isinstance(s, dict):
                            if "from" in s:
                                s["from"] = P(s["from"])
                            if isinstance(s.get("distances"), dict):
                                s["distances"] = self.keys_of(s["distances"], P)
                        shape[P(p)] = s
                    spec["shape"] = shape
                if isinstance(spec.get("local"), dict):
                    spec["local"] = self.keys_of(spec["local"], P)
        if isinstance(d.get("links"), dict):
            d["links"] = self.keys_of(d["links"], B)
        for spec in (d.get("actuators") or {}).values():
            spec["points"] = [P(p) for p in spec["points"]]
        for spec in (d.get("sliders") or {}).values():
            spec["point"] = P(spec.get("point"))
            guide = spec.get("guide") or {}
            if isinstance(guide.get("through"), str):
                guide["through"] = P(guide["through"])
            if isinstance(guide.get("along"), list):
                guide["along"] = [P(p) for p in guide["along"]]
            if isinstance(spec.get("carries"), dict):
                spec["carries"] = self.keys_of(spec["carries"], P)
        if isinstance(d.get("gears"), dict):
            d["gears"] = self.keys_of(d["gears"], self.gear)
        for spec in (d.get("rolling") or {}).values():
            spec["disc"] = B(spec.get("disc"))
            on = spec.get("on") or {}
            for where in (spec, on):
                if "gear" in where:
                    where["gear"] = self.gear(where["gear"])
            if isinstance(on.get("line"), list):
                on["line"] = [P(p) for p in on["line"]]
            if "circle" in on:
                on["circle"] = P(on["circle"])
            for key in ("body", "disc"):
                if key in on:
                    on[key] = B(on[key])
        for spec in (d.get("cords") or {}).values():
            spec["pulley"] = B(spec.get("pulley"))
            to = spec.get("to")
            if isinstance(to, dict):
                to["disc"] = B(to.get("disc"))
            else:
                spec["to"] = P(to)
        for section in ("driver",):
            spec = d.get(section)
            if isinstance(spec, dict):
                self.coordinate(spec)
        for section in ("coordinates", "drivers"):
            for spec in (d.get(section) or {}).values():
                self.coordinate(spec)
        for spec in (d.get("loads") or {}).values():
            if "at" in spec:
                spec["at"] = P(spec["at"])
            if "on" in spec:
                spec["on"] = B(spec["on"])
        for name, spec in (d.get("quantities") or {}).items():
            self.quantity(spec)
        if isinstance(d.get("report"), dict):
            for section, names in d["report"].items():
                if isinstance(names, list):
                    fn = P if section == "points" else self.answer
                    d["report"][section] = [fn(n) for n in names]
        quiz = d.get("quiz")
        if isinstance(quiz, dict) and isinstance(quiz.get("not_asked"), list):
            quiz["not_asked"] = [self.answer(n) for n in quiz["not_asked"]]   # report names
        for key in d.get("keys") or []:
            for part in ("values", "wrong", "tolerances"):
                if isinstance(key.get(part), dict):
                    key[part] = {self.key_name(n, v): v for n, v in key[part].items()}
        self.dynamics(d.get("dynamics"))
        for section in ("springs", "dampers"):
            for spec in (d.get(section) or {}).values():
                if "between" in spec:
                    spec["between"] = [P(p) for p in spec["between"]]
                if "bodies" in spec:
                    spec["bodies"] = [B(b) for b in spec["bodies"]]
        excitation = d.get("excitation") or {}
        for spec in (excitation.get("forces") or {}).values():
            if "at" in spec:
                spec["at"] = P(spec["at"])
            if "on" in spec:
                spec["on"] = B(spec["on"])
        find = d.get("find")
        if isinstance(find, dict) and isinstance(find.get("targets"), dict):
            find["targets"] = self.keys_of(find["targets"], self.answer)
        return d

    def coordinate(self, spec):
        for key in ("angle", "length"):
            if isinstance(spec.get(key), list):
                spec[key] = [self.point(p) for p in spec[key]]
        for key in ("x", "y"):
            if key in spec:
                spec[key] = self.point(spec[key])

    #: quantity keys whose value is a point, a pair of points, a body, [point, body] ...
    QUANTITY_POINTS = ("speed", "acceleration", "tangential_acceleration",
                       "normal_acceleration", "x", "y")
    QUANTITY_PAIRS = ("angle", "length", "along", "normal_to", "relative", "relative_speed",
                      "relative_acceleration", "least_speed", "least_speed_at")

    def quantity(self, spec):
        if not isinstance(spec, dict):
            return
        P, B = self.point, self.body
        for key in self.QUANTITY_POINTS:
            if isinstance(spec.get(key), str):
                spec[key] = P(spec[key])
        for key in self.QUANTITY_PAIRS:
            if isinstance(spec.get(key), list):
                spec[key] = [P(p) for p in spec[key]]
        if "point" in spec:
            spec["point"] = [P(p) for p in spec["point"]] if isinstance(spec["point"], list) \
                else P(spec["point"])
        if isinstance(spec.get("between"), list):
            spec["between"] = [[P(p) for p in pair] if isinstance(pair, list) else pair
                               for pair in spec["between"]]
        if "rotation" in spec:
            spec["rotation"] = B(spec["rotation"])
        if "instant_centre" in spec:
            ic = spec["instant_centre"]
            spec["instant_centre"] = [B(b) for b in ic] if isinstance(ic, list) else B(ic)
        if isinstance(spec.get("instant_centre_distance"), list):
            body, point = spec["instant_centre_distance"]
            spec["instant_centre_distance"] = [B(body), P(point)]
        if isinstance(spec.get("reaction"), list):
            point, body = spec["reaction"]
            spec["reaction"] = [P(point), B(body)]
        if "axis" in spec:
            axis = spec["axis"]
            spec["axis"] = [P(p) for p in axis] if isinstance(axis, list) else (
                B(axis) if isinstance(axis, str) else axis)
        for key in ("amplitude", "phase", "largest", "peak_frequency", "peak_amplitude"):
            if isinstance(spec.get(key), dict):
                spec[key] = {k: P(v) if k in ("x", "y") else v for k, v in spec[key].items()}
        for key in ("maximum", "minimum", "at_maximum", "at_minimum", "stroke", "time_ratio",
                    "stroke_time", "velocity_ratio"):
            if isinstance(spec.get(key), str):
                spec[key] = self.answer(spec[key])
        if "expr" in spec:
            spec["expr"] = self.expression(spec["expr"])
        for key in ("centre_distance", "contact_ratio"):
            if isinstance(spec.get(key), list):
                spec[key] = [self.gear(g) for g in spec[key]]
        for key in ("min_teeth", "with"):
            if key in spec:
                spec[key] = self.gear(spec[key])

    def gear(self, name):
        """A gear of ``gears:``: one named as a link is that link's (docs/schema.md,
        "gears"), renamed with it; the others keep their names."""
        if isinstance(name, str) and name in (self.data.get("gears") or {}):
            return self.body(name)
        return name

    def dynamics(self, spec):
        if not isinstance(spec, dict):
            return
        P, B = self.point, self.body
        if isinstance(spec.get("bodies"), dict):
            bodies = {}
            for name, body in spec["bodies"].items():
                if isinstance(body, dict) and isinstance(body.get("center"), str):
                    body["center"] = P(body["center"])
                head, dot, tail = str(name).partition(".")
                bodies[B(head) + dot + tail if not dot else name] = body
            spec["bodies"] = bodies
        if isinstance(spec.get("masses"), dict):
            spec["masses"] = self.keys_of(spec["masses"], P)
        for disc in (spec.get("discs") or {}).values():
            if "center" in disc:
                disc["center"] = P(disc["center"])
        if isinstance(spec.get("friction_circles"), dict):
            spec["friction_circles"] = self.keys_of(spec["friction_circles"], P)


def shuffle_names(data: dict, rng: random.Random) -> Rename:
    """A renaming of every point to ``N0``, ``N1`` ... and every link to ``b0``, ``b1`` ...,
    the numbers assigned in a random order: the alphabetical order of the points changes,
    which only the figure's vector labels (z_i) follow, never an answer."""
    renamer = Rename(data)
    orders = []
    for table in (renamer.points, renamer.links):
        numbers = list(range(len(table)))
        rng.shuffle(numbers)
        orders.append(numbers)
    for prefixes in (("N", "b"), ("Nq", "bq"), ("Nz_", "bz_")):    # the first free ones
        for table, prefix, numbers in zip((renamer.points, renamer.links), prefixes, orders):
            for name, i in zip(list(table), numbers):
                table[name] = f"{prefix}{i}"
        try:
            renamer.check()
            return renamer
        except ValueError:
            continue
    raise ValueError("no free names")


# --- solving and comparing ----------------------------------------------------------------
def to_yaml(data) -> str:
    import yaml

    class Dumper(getattr(yaml, "CSafeDumper", yaml.SafeDumper)):
        def ignore_aliases(self, _data):
            return True
    return yaml.dump(data, Dumper=Dumper, sort_keys=False, allow_unicode=True)


class Outcome:
    """The answers of a file (name -> (value, display unit), points), or its refusal."""

    def __init__(self, values=None, units=None, points=None, error=None, key=None):
        self.values = values or {}
        self.units = units or {}
        self.points = points or {}
        self.error = error
        self.key = key          # the key a refusal names

    def __repr__(self):
        return f"Outcome(error={self.error!r})" if self.error else f"Outcome({self.values})"


def solve(text: str, k=None, name="<text>") -> Outcome:
    """The file ``text`` solved through the Python API at its own driver value (Newton's
    method where the closed form cannot decompose it)."""
    import linkcli
    from linkcli.errors import StructureError
    try:
        linkage = linkcli.loads(text, k, name)
        try:
            result = linkage.solve()
        except StructureError:
            result = linkage.solve(method="newton")
    except linkcli.LinkcliError as exc:
        return Outcome(error=(exc.exit_code, type(exc).__name__), key=_keys(exc))
    except Exception as exc:        # noqa: BLE001 - an internal error is an outcome too
        return Outcome(error=(70, type(exc).__name__))
    values = {n: float(v) for n, v in result.values.items()}
    points = {n: tuple(float(c) for c in xy) for n, xy in (result.points or {}).items()}
    return Outcome(values, dict(result.units), points)


def _si(value, unit, dim=None):
    """(SI value, dimension) of ``value`` shown in ``unit``; of the meanings of an ambiguous
    unit, the one of dimension ``dim``."""
    options = parse(unit)
    if dim is not None:
        options = [o for o in options if o[1] == dim] or options
    f, d = options[0]
    return value * f, d


def _keys(exc):
    """The keys a refusal names (each of a batch of input errors)."""
    inner = getattr(exc, "errors", None)
    return tuple(e.key for e in inner) if inner else (exc.key,)


def differences(a: Outcome, b: Outcome, own_units=(), rename=lambda n: n, rtol=1e-9,
                lengths=(1.0, 1.0), point=lambda n: n, same_keys=False) -> list:
    """What differs between the answers ``a`` and ``b`` (``b``'s names are ``rename`` of
    ``a``'s, its points ``point`` of ``a``'s): each in SI, angles modulo a turn; names in
    ``own_units`` (a quantity's own ``unit:``) also in their display unit; the report's points
    in SI by the files' length units ``lengths`` (m per unit).  Refusals: the same exit code
    and type (and, with ``same_keys``, the same keys named)."""
    if a.error or b.error:
        if a.error == b.error and (not same_keys or a.key == b.key):
            return []
        return [f"outcome {a.error or 'solved'} {a.key or ''} != {b.error or 'solved'} "
                f"{b.key or ''}"]
    out = _points(a, b, lengths, point, rtol)
    if {rename(n) for n in a.values} != set(b.values):
        out.append(f"names {sorted(a.values)} != {sorted(b.values)}")
        return out
    si = {}
    for name, value in a.values.items():
        options = parse(a.units[name])
        si[name] = [(value * f, d) for f, d in options]
    scale = {}
    for name, options in si.items():
        for v, d in options:
            scale[d] = max(scale.get(d, 0.0), abs(v))
    for name, value in a.values.items():
        other, unit = b.values[rename(name)], b.units[rename(name)]
        if name in own_units or _base(name) in own_units:
            if unit != a.units[name]:
                out.append(f"{name}: own unit {a.units[name]!r} shown as {unit!r}")
            elif not _close(value, other, rtol, 0.0, False):
                out.append(f"{name}: {value!r} != {other!r} {unit} (display)")
            continue
        pairs = [(va, d) for va, d in si[name] if any(d == e for _, e in parse(unit))]
        if not pairs:
            out.append(f"{name}: unit {a.units[name]!r} != {unit!r} in dimension")
            continue
        va, d = pairs[0]
        vb, _ = _si(other, unit, d)
        angle = d == (0, 0, 0, 1)
        atol = 1e-9 * (scale.get(d) or 1.0) if not angle else 1e-9
        if not _close(va, vb, rtol, atol, angle):
            out.append(f"{name}: {value!r} {a.units[name]} = {va!r} SI != {other!r} {unit} = "
                       f"{vb!r} SI")
    return out


def _points(a, b, lengths, point, rtol) -> list:
    """The report's points of ``a`` and ``b`` in SI."""
    if {point(n) for n in a.points} != set(b.points):
        return [f"points {sorted(a.points)} != {sorted(b.points)}"]
    size = max((abs(c) * lengths[0] for xy in a.points.values() for c in xy), default=1.0)
    out = []
    for name, xy in a.points.items():
        for axis, u, v in zip("xy", xy, b.points[point(name)]):
            if not _close(u * lengths[0], v * lengths[1], rtol, 1e-9 * size, False):
                out.append(f"point {name}: {axis} {u!r} != {v!r} (file units)")
    return out


def _base(name: str) -> str:
    for suffix in ("ddot", "dot"):
        if name.endswith(suffix):
            return name[: -len(suffix)]
    return name


def _close(a, b, rtol, atol, angle) -> bool:
    diff = abs(a - b)
    if angle:
        diff = min(diff % TURN, TURN - diff % TURN)
    return diff <= rtol * max(abs(a), abs(b)) + atol


def own_units(data) -> set:
    """The quantities that name their own display unit."""
    return {n for n, q in (data.get("quantities") or {}).items()
            if isinstance(q, dict) and "unit" in q}


def digits(data) -> list:
    """The digits k a file is solved for: its own and those of its keys (None: none)."""
    ks = {data.get("k")}
    for key in data.get("keys") or []:
        if isinstance(key, dict) and "k" in key:
            ks.add(key["k"])
    return sorted(ks, key=lambda k: (k is None, k if isinstance(k, int) else -1))


#: the units a random system draws from, per kind (docs/schema.md's table)
CHOICES = {
    "length": ["mm", "m", "in", "cm", "ft"], "angle": ["deg", "rad"],
    "angular_rate": [None, "rad/s", "deg/s", "rpm", "rev/s"],
    "force": ["N", "kN", "lbf", "kip"], "torque": ["Nm", "Nmm", "kNm", "lbf ft", "lbf in"],
    "mass": ["kg", "lb", "g", "slug"], "inertia": ["kg m^2", "kg mm^2", "lb in^2", "slug ft^2"],
    "stiffness": ["N/m", "N/mm", "kN/m", "lbf/in", "lb/ft"],
    "torsional_stiffness": ["Nm/rad", "Nmm/rad", "Nm/deg", "lbf ft/rad"],
    "damping": ["Ns/m", "Ns/mm", "kNs/m", "lbf s/in"],
    "torsional_damping": ["Nms/rad", "Nmms/rad", "lbf ft s/rad"],
    "frequency": ["rad/s", "Hz", "rpm"], "speed": ["m/s", "km/h", "mm/s", "mph", "ft/s"],
    "time": ["s", "ms"], "pressure": [None, "Pa", "MPa", "bar", "psi", "N/mm^2"],
    "area": [None, "m^2", "mm^2", "in^2"],
}


def random_system(rng: random.Random) -> dict:
    """A ``units:`` mapping drawn from :data:`CHOICES`; a kind left out at random (None, or
    one time in four) takes its default."""
    out = {}
    for kind, names in CHOICES.items():
        name = rng.choice(names)
        if name is not None and rng.random() > 0.25:
            out[kind] = name
    return out
