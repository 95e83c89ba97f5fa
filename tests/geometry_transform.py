"""A mechanism file moved, turned and scaled, written from the file format (docs/schema.md,
docs/dynamics.md, docs/vibrations.md) and not from linkcli's reader: which keys are
positions, vectors in the frame's axes, lengths, absolute angles, directions, and how each
physical quantity scales.

The similarity is x -> s R(theta) x + t: ``theta`` in degrees counter-clockwise, ``t`` in the
file's length unit, ``s`` a pure number.  Under a scale the mass and the time are kept, so
every quantity scales as s to the power of its length dimension (force = kg m/s^2):

    length, coordinate, length rate and acceleration, force, linear preload      s
    torque, energy, power, inertia (kg m^2), torsional stiffness and damping      s^2
    mass, time, angle, angular rate, frequency, linear stiffness (N/m), N s/m     1
    pressure (N/m^2)                                                              1/s
    gravity's g (m/s^2)                                                           s

so loads are given times s (forces) and s^2 (torques), and g times s.  A key the
transformation does not know raises :class:`NotUnderstood` with its path: the file is
listed, never passed silently.
"""
from __future__ import annotations

import math
import re

import yaml


class NotUnderstood(Exception):
    """A key of the file this transformation does not know how to move or scale."""

    def __init__(self, path, why="unknown key"):
        super().__init__(f"{'.'.join(map(str, path))}: {why}")
        self.path = path


class _Loader(yaml.SafeLoader):
    """YAML as linkcli reads it: every mapping key kept as its text ('on' is not True)."""


def _mapping(loader, node):
    return {str(k.value): loader.construct_object(v, deep=True) for k, v in node.value}


_Loader.add_constructor("tag:yaml.org,2002:map", _mapping)


def read(path) -> dict:
    with open(path, encoding="utf-8") as f:
        return yaml.load(f, Loader=_Loader)


def write(doc: dict) -> str:
    return yaml.safe_dump(doc, sort_keys=False, allow_unicode=True, width=10_000)


AXES = {"x": 0.0, "y": 90.0, "-x": 180.0, "-y": 270.0}
TURN = {"deg": 360.0, "rad": 2 * math.pi}


#: values that are words, not numbers: a spring's preload 'static', a load 'unknown'
WORDS = {"static", "unknown"}


def _power(s, n) -> float:
    """s^n, inf where it overflows (a scale beyond the range is refused, not computed)."""
    try:
        return s ** n
    except OverflowError:
        return math.inf


def times(value, factor):
    """value * factor: a number computed, an expression (text) wrapped."""
    if factor == 1:
        return value
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise TypeError(value)
    if isinstance(value, str):
        return value if value in WORDS else f"({value})*{factor!r}"
    return value * factor


def plus(value, offset):
    if offset == 0:
        return value
    if isinstance(value, str):
        return f"({value}) + {offset!r}"
    return value + offset


class Similarity:
    """x -> s R(theta) x + t applied to one file's keys."""

    def __init__(self, doc: dict, theta=0.0, t=(0.0, 0.0), s=1.0):
        self.doc, self.s = doc, float(s)
        units = doc.get("units") or {}
        angle = units.get("angle", "rad")
        if angle not in TURN:
            raise NotUnderstood(("units", "angle"), f"angle unit {angle}")
        self.turn = TURN[angle]
        self.theta_deg = float(theta)
        self.theta = self.theta_deg * self.turn / 360.0          # in the file's unit
        self.c, self.sn = math.cos(math.radians(theta)), math.sin(math.radians(theta))
        if abs(self.theta_deg % 90) < 1e-12:                       # exact quarter turns
            self.c, self.sn = round(self.c), round(self.sn)
        self.t = tuple(float(x) for x in t)
        self.turns = self.theta_deg % 360 != 0
        self.coordinates = {n: next(iter(spec)) for n, spec in
                            (doc.get("coordinates") or {}).items() if isinstance(spec, dict)}

    # the roles --------------------------------------------------------------------------
    def vector(self, v, path, power=1):
        """A vector in the frame's axes, of length dimension ``power``: s^power R v."""
        if not isinstance(v, list) or len(v) != 2:
            raise NotUnderstood(path, "expected [x, y]")
        f = _power(self.s, power)
        x, y = (times(a, f) for a in v)
        return [self._comb(self.c, x, -self.sn, y), self._comb(self.sn, x, self.c, y)]

    @staticmethod
    def _comb(a, x, b, y):
        if b == 0:
            return times(x, a)
        if a == 0:
            return times(y, b)
        if isinstance(x, str) or isinstance(y, str):
            return f"{a!r}*({x}) + {b!r}*({y})"
        return a * x + b * y

    def point(self, v, path):
        x, y = self.vector(v, path)
        return [plus(x, self.t[0]), plus(y, self.t[1])]

    def length(self, v, power=1):
        return times(v, _power(self.s, power))

    def angle(self, v):
        """An absolute angle (a direction measured from +x) in the file's unit."""
        return plus(v, self.theta)

    def axis(self, v, path):
        """A direction: x, y, -x, -y or an angle."""
        if isinstance(v, str) and v in AXES:
            return v if not self.turns else plus(AXES[v] * self.turn / 360.0, self.theta)
        if isinstance(v, (int, float, str)) and not isinstance(v, bool):
            return self.angle(v)
        raise NotUnderstood(path, "a direction")

    def no_turn(self, path, why):
        """A key tied to the frame's axes: only a translation or a scale keeps it."""
        if self.turns:
            raise NotUnderstood(path, why)

    # the file -----------------------------------------------------------------------------
    PASS = {"title", "source", "notes", "units", "k", "params", "report", "actuators",
            "statement"}
    DROP = {"keys", "quiz"}

    def apply(self) -> dict:
        out = {}
        for key, value in self.doc.items():
            if key in self.DROP:
                continue
            if key in self.PASS:
                out[key] = value
                continue
            handler = getattr(self, "sec_" + key, None)
            if handler is None:
                raise NotUnderstood((key,), "unknown section")
            out[key] = handler(value, (key,))
        return out

    def _each(self, value, path, func):
        return {n: func(v, path + (n,)) for n, v in (value or {}).items()}

    def _keys(self, spec, path, roles):
        """A mapping whose every key has a role: a function of (value, path), or None to
        keep the value."""
        if not isinstance(spec, dict):
            raise NotUnderstood(path, "expected a mapping")
        out = {}
        for key, value in spec.items():
            if key not in roles:
                raise NotUnderstood(path + (key,))
            role = roles[key]
            out[key] = value if role is None else role(value, path + (key,))
        return out

    def sec_frame(self, value, path):
        return self._each(value, path, self.point)

    sec_points = sec_frame

    def sec_links(self, value, path):
        return self._each(value, path, self.link)

    def link(self, spec, path):
        return self._keys(spec, path, {
            "points": None, "length": lambda v, p: self.length(v),
            "shape": lambda v, p: self._each(v, p, self.shape_point),
            "local": lambda v, p: self._each(v, p, lambda w, q: [self.length(a) for a in w])})

    def shape_point(self, spec, path):
        return self._keys(spec, path, {
            "length": lambda v, p: self.length(v), "angle": None, "from": None, "side": None,
            "distances": lambda v, p: {n: self.length(d) for n, d in v.items()}})

    def sec_sliders(self, value, path):
        return self._each(value, path, self.slider)

    def slider(self, spec, path):
        return self._keys(spec, path, {
            "point": None, "guide": self.guide,
            "carries": lambda v, p: self._each(v, p, self.carried)})

    def carried(self, v, path):
        if isinstance(v, list):         # [dx, dy] in the frame's axes (a fixed guide)
            return self.vector(v, path)
        if "dx" in v or "dy" in v:
            return dict(zip(("dx", "dy"), self.vector([v.get("dx", 0), v.get("dy", 0)], path)))
        return self._keys(v, path, {"along": lambda w, p: self.length(w),
                                    "normal": lambda w, p: self.length(w)})

    def guide(self, spec, path):
        """{x: c} is the line through (c, 0) along +y, {y: c} through (0, c) along +x: a
        turned one is {through, angle}; {through, angle} moves its point and turns its
        angle; {along: [B, C]} moves with its points; the offset is a length."""
        spec = dict(spec)
        offset = {"offset": self.length(spec.pop("offset"))} if "offset" in spec else {}
        if "along" in spec:
            return {"along": spec.pop("along"), **self._keys(spec, path, {}), **offset}
        if "x" in spec or "y" in spec:
            if len(spec) != 1:
                raise NotUnderstood(path, "x and y")
            (axis, c), = spec.items()
            start, direction = ([c, 0], 90.0) if axis == "x" else ([0, c], 0.0)
            if not self.turns:
                return {axis: plus(self.length(c), self.t[0 if axis == "x" else 1]), **offset}
            return {"through": self.point(start, path + (axis,)),
                    "angle": self.angle(direction * self.turn / 360.0), **offset}
        through = spec.get("through")
        moved = through if isinstance(through, str) else self.point(through, path + ("through",))
        return {**self._keys(spec, path, {"through": lambda v, p: moved,
                                          "angle": lambda v, p: self.angle(v)}), **offset}

    def sec_driver(self, spec, path):
        kind = next(k for k in ("angle", "length", "x", "y", "payout") if k in spec)
        if kind == "angle":
            value, rate = self.angle, None
        elif kind in ("length", "payout"):     # a pay-out: the cord unwound since the figure
            value = rate = lambda v: self.length(v)
        else:
            self.no_turn(path + (kind,), "a driver along the frame's axis")
            value = lambda v: plus(self.length(v), self.t[0 if kind == "x" else 1])  # noqa: E731
            rate = lambda v: self.length(v)                                           # noqa: E731
        roles = {kind: None, "value": lambda v, p: value(v)}
        for key in ("rate", "accel"):
            roles[key] = None if rate is None else (lambda v, p: rate(v))
        return self._keys(spec, path, roles)

    def sec_drivers(self, value, path):
        """Each named driver as ``driver:`` (several inputs, each driven)."""
        return {name: self.sec_driver(spec, path + (name,)) for name, spec in value.items()}

    def sec_coordinates(self, value, path):
        for name, spec in value.items():
            kind = next(iter(spec))
            if kind in ("x", "y"):
                self.no_turn(path + (name, kind), "a coordinate along the frame's axis")
            elif kind not in ("angle", "length"):
                raise NotUnderstood(path + (name, kind))
            if len(spec) != 1:
                raise NotUnderstood(path + (name,))
        return value

    def sec_loads(self, value, path):
        return self._each(value, path, self.load)

    def load(self, spec, path):
        spec = dict(spec)
        window = {"over": self.window(spec.pop("over"), path + ("over",))} \
            if "over" in spec else {}
        return {**self.load_itself(spec, path), **window}

    def window(self, v, path):
        """A load's window of the driver (machine dynamics): an angle turns with the figure,
        a length of an actuator or between points stays (scaled), an axis' coordinate is
        tied to the frame's axes."""
        kind = next(k for k in ("angle", "length", "x", "y") if k in self.doc["driver"])
        if kind == "angle":
            return [self.angle(a) for a in v]
        if kind != "length":
            self.no_turn(path, "a window along the frame's axis")
            return [plus(self.length(a), self.t[0 if kind == "x" else 1]) for a in v]
        return [self.length(a) for a in v]

    def motor_torque(self, v, path):
        """A motor's torque (s^2); an expression reads the driver q, which turns with the
        figure for an angle driver: q of the new file is q + theta."""
        if isinstance(v, str) and re.search(r"\bq\b", v):
            kind = next(k for k in ("angle", "length", "x", "y") if k in self.doc["driver"])
            if kind == "angle" and self.theta:
                v = re.sub(r"\bq\b", f"(q - {self.theta!r})", v)
            elif kind in ("x", "y"):
                self.no_turn(path, "a torque of the driver along the frame's axis")
                offset = self.t[0 if kind == "x" else 1]
                v = re.sub(r"\bq\b", f"((q - {offset!r})/{self.s!r})", v)
            elif kind == "length" and self.s != 1:
                v = re.sub(r"\bq\b", f"(q/{self.s!r})", v)
        return self.length(v, 2)

    def load_itself(self, spec, path):
        kind = spec.get("type")
        s = lambda v, p: self.length(v)                         # noqa: E731  forces: s
        if kind == "force":
            spec = dict(spec)
            xy = {}
            axis = next((a for a in ("x", "y") if spec.get(a) == "unknown"), None)
            if axis is not None and self.turns:     # the unknown along a turned axis
                if len(set(spec) & {"x", "y", "magnitude", "angle"}) != 1:
                    raise NotUnderstood(path, "an unknown with another component")
                del spec[axis]
                xy = {"magnitude": "unknown",
                      "angle": self.angle(AXES[axis] * self.turn / 360.0)}
            elif axis is not None:
                xy = {axis: spec.pop(axis)}
            elif "x" in spec or "y" in spec:
                given = [a for a in ("x", "y") if a in spec]
                x, y = self.vector([spec.pop("x", 0), spec.pop("y", 0)], path)
                xy = {"x": x, "y": y} if self.turns else \
                    {a: v for a, v in (("x", x), ("y", y)) if a in given}
            return {**self._keys(spec, path, {"type": None, "at": None, "magnitude": s,
                                              "angle": lambda v, p: self.angle(v)}), **xy}
        if kind == "torque":
            return self._keys(spec, path, {"type": None, "on": None,
                                           "value": lambda v, p: self._known(v, 2)})
        if kind == "axial":
            return self._keys(spec, path, {"type": None, "on": None,
                                           "value": lambda v, p: self._known(v, 1)})
        if kind == "driver":
            return self._keys(spec, path, {"type": None, "value": lambda v, p: self._known(v, 1)})
        if kind == "pressure":
            return self._keys(spec, path, {"type": None, "on": None,
                                           "value": lambda v, p: self._known(v, -1),
                                           "diameter": s,
                                           "area": lambda v, p: self.length(v, 2)})
        if kind == "brake":
            return self._keys(spec, path, {"type": None, "on": None,
                                           "value": lambda v, p: self.length(v, 2)})
        if kind == "motor":         # torques s^2; speeds (angular) stay
            torque = lambda v, p: self.length(v, 2)             # noqa: E731
            return self._keys(spec, path, {
                "type": None, "on": None, "stall": torque, "no_load": None, "speeds": None,
                "torques": lambda v, p: [self.length(a, 2) for a in v],
                "torque": self.motor_torque})
        raise NotUnderstood(path + ("type",), f"load type {kind}")

    def _known(self, v, power):
        return v if v == "unknown" else self.length(v, power)

    def sec_shafts(self, value, path):
        """A clutch problem's shafts (docs/machines.md): nothing is placed in the plane;
        inertias and torques scale as s^2, speeds are kept."""
        return self._each(value, path, lambda spec, p: self._keys(spec, p, {
            "inertia": lambda v, q: self.length(v, 2), "speed": None,
            "torque": lambda v, q: self.length(v, 2), "resisting": lambda v, q: self.length(v, 2),
            "motor": lambda v, q: self._keys(v, q, {"stall": lambda w, r: self.length(w, 2),
                                                    "no_load": None})}))

    def sec_clutch(self, spec, path):
        """The clutch: its torque s^2, a plate's force s and radii s (mu F r: s^2)."""
        return self._keys(spec, path, {
            "between": None, "torque": lambda v, p: self.length(v, 2),
            "plate": lambda v, p: self._keys(v, p, {
                "mu": None, "force": lambda w, q: self.length(w),
                "outer": lambda w, q: self.length(w), "inner": lambda w, q: self.length(w),
                "pairs": None, "wear": None})})

    def sec_dynamics(self, spec, path):
        return self._keys(spec, path, {
            "gravity": self.gravity,
            "bodies": lambda v, p: self._each(v, p, self.mass_body),
            "masses": lambda v, p: v,
            "friction": None,
            "discs": lambda v, p: self._each(v, p, self.disc),
            "friction_circles": lambda v, p: (self._each(v, p, lambda w, q: self.length(w))
                                              if isinstance(v, dict) else self.length(v))})

    def gravity(self, v, path):
        """A number g along -y, {g, angle} or off: g is m/s^2, times s."""
        if v in (False, "off", "false", None):
            return v
        if isinstance(v, dict):
            return self._keys(v, path, {"g": lambda w, p: self.length(w),
                                        "angle": lambda w, p: self.angle(w)})
        if not self.turns:
            return self.length(v)
        return {"g": self.length(v), "angle": self.angle(270.0 * self.turn / 360.0)}

    def mass_body(self, spec, path):
        return self._keys(spec, path, {
            "mass": None, "inertia": lambda v, p: self.length(v, 2),
            "center": lambda v, p: v if isinstance(v, str) else [self.length(a) for a in v]})

    def disc(self, spec, path):
        return self._keys(spec, path, {
            "center": None, "side": None, "mass": None, "radius": lambda v, p: self.length(v),
            "inertia": lambda v, p: self.length(v, 2),
            "rolling_resistance": lambda v, p: self.length(v)})

    def sec_rolling(self, value, path):
        return self._each(value, path, self.contact)

    def contact(self, spec, path):
        return self._keys(spec, path, {"disc": None, "radius": lambda v, p: self.length(v),
                                       "on": self.rolls_on, "gear": None})

    def rolls_on(self, spec, path):
        def line(v, p):
            return v if isinstance(v, list) else self.axis(v, p)
        return self._keys(spec, path, {"line": line, "side": None, "body": None,
                                       "circle": None, "radius": lambda v, p: self.length(v),
                                       "disc": None, "inside": None, "gear": None})

    def sec_gears(self, value, path):
        """A gear's module and addendum are lengths, its diametral pitch (teeth per unit
        of diameter) a length to the power -1; teeth and the pressure angle (between the
        line of action and the pitch circles' tangent, no direction) are kept."""
        return self._each(value, path, lambda spec, p: self._keys(spec, p, {
            "teeth": None, "module": lambda v, q: self.length(v),
            "addendum": lambda v, q: self.length(v),
            "diametral_pitch": lambda v, q: self.length(v, -1),
            "pressure_angle": None, "internal": None}))

    def sec_cords(self, value, path):
        return self._each(value, path, self.cord)

    def cord(self, spec, path):
        def to(v, p):
            if isinstance(v, str):
                return v
            return self._keys(v, p, {"disc": None, "side": None,
                                     "radius": lambda w, q: self.length(w)})
        return self._keys(spec, path, {"pulley": None, "radius": lambda v, p: self.length(v),
                                       "to": to, "along": self.axis, "side": None,
                                       "slip": None})

    def sec_springs(self, value, path):
        return self._each(value, path, lambda v, p: self.element(v, p, "k"))

    def sec_dampers(self, value, path):
        return self._each(value, path, lambda v, p: self.element(v, p, "c"))

    def element(self, spec, path, coefficient):
        """A spring or damper: between two points (linear: k, c kept, free length and
        preload times s) or two bodies (torsional: k, c, preload times s^2; its free
        length an angle, absolute where one body is the frame)."""
        torsional = "bodies" in spec
        if torsional:
            if "free_length" in spec:
                self.no_turn(path + ("free_length",), "a torsional spring's free angle")
            roles = {"bodies": None, coefficient: lambda v, p: self.length(v, 2),
                     "free_length": None, "preload": lambda v, p: self.length(v, 2)}
        else:
            roles = {"between": None, coefficient: None, "along": self.axis,
                     "free_length": lambda v, p: self.length(v),
                     "preload": lambda v, p: self.length(v)}
        return self._keys(spec, path, roles)

    def sec_excitation(self, spec, path):
        out = {}
        for key, value in spec.items():
            p = path + (key,)
            if key == "frequency":
                out[key] = value
            elif key == "forces":
                out[key] = self._each(value, p, self.excitation_force)
            elif key == "supports":
                out[key] = self._each(value, p, self.support)
            elif isinstance(value, dict) and "wavelength" in value:
                out[key] = self._keys(value, p, {
                    "coordinate": None, "amplitude": lambda v, q: self.length(v),
                    "wavelength": lambda v, q: self.length(v),
                    "speed": lambda v, q: self.length(v)})
            else:
                raise NotUnderstood(p)
        return out

    def excitation_force(self, spec, path):
        spec = dict(spec)
        x, y = self.vector([spec.pop("x", 0), spec.pop("y", 0)], path)
        return {**self._keys(spec, path, {"at": None}), "x": x, "y": y}

    def support(self, spec, path):
        kind = self.coordinates.get(spec.get("coordinate"))
        power = 0 if kind == "angle" else 1
        return self._keys(spec, path, {"coordinate": None,
                                       "amplitude": lambda v, p: self.length(v, power)})

    def sec_initial(self, spec, path):
        self.no_turn(path, "initial values of coordinates")
        out = {}
        for key, value in spec.items():
            if key in ("from", "mode"):         # a mode's number is no value
                out[key] = value
                continue
            name = key[:-4] if key.endswith("_dot") else key
            kind = self.coordinates.get(name)
            if kind is None:
                raise NotUnderstood(path + (key,))
            moved = value if key.endswith("_dot") or kind not in ("x", "y") else \
                plus(value, 0.0)        # a displacement from equilibrium: no translation
            out[key] = self.length(moved, 0 if kind == "angle" else 1)
        return out

    def sec_quantities(self, value, path):
        """Quantities are answers, kept; a flywheel's radius of gyration is a length."""
        def quantity(spec, p):
            if isinstance(spec, dict) and "flywheel" in spec and "radius" in spec:
                return dict(spec, radius=self.length(spec["radius"]))
            return spec
        return self._each(value, path, quantity)

    def sec_motion(self, spec, path):
        """The motion of a machine: times and speeds kept (time and angles are), a diagram's
        scale of torque as a torque (s^2), its angle, areas and coefficients pure numbers."""
        def regime(v, p):
            return self._keys(v, p, {
                "mean_speed": None, "areas": None,
                "scale": lambda w, q: self._keys(w, q, {"torque": lambda x, r: self.length(x, 2),
                                                        "angle": None})})
        return self._keys(spec or {}, path, {"until": None, "regime": regime, "flywheel": None,
                                             "turns_per_cycle": None})

    def sec_find(self, spec, path):
        """Unknowns are params (used where they are, so never scaled); a target scales as
        its unit's length power: the unit written with it, else its quantity's ``unit``, else
        its quantity's kind (a frequency); a rigid motion keeps a target whose answer it
        keeps."""
        out = dict(spec)
        targets = {}
        for name, value in (spec.get("targets") or {}).items():
            p = path + ("targets", name)
            if self.s == 1:
                if frame_class(self.doc, name) != "invariant":
                    raise NotUnderstood(p, "a target the motion changes")
                targets[name] = value
                continue
            number, unit = value, None
            if isinstance(value, str):
                head, _, unit = value.strip().partition(" ")
                number = float(head)
            power = None if reads_params(self.doc, name) else self.target_power(name, unit)
            if power is None:
                raise NotUnderstood(p, "a target's dimension")
            number = self.length(number, power)
            targets[name] = number if unit is None else f"{number!r} {unit}"
        out["targets"] = targets
        return out

    def target_power(self, name, unit):
        spec = (self.doc.get("quantities") or {}).get(name) or {}
        unit = unit or spec.get("unit")
        if unit is not None:
            return length_power(unit)
        kind = next((k for k in spec if k != "unit"), None)
        return KIND_POWER.get(kind)


#: the length power of the answers of quantity kinds that have one whatever their unit
KIND_POWER = {"natural_frequency": 0, "natural_period": 0, "damped_frequency": 0,
              "damping_ratio": 0, "transmissibility": 0, "frequency_ratio": 0, "length": 1}


# --- how an answer changes ------------------------------------------------------------------
#: kinds of an answer about another (NAME): a rigid motion leaves it alone where it leaves
#: NAME alone or turns it (an angle's swing, the crank's sweep between its extremes)
OF_ANOTHER = {"stroke", "stroke_time", "time_ratio"}
#: machine dynamics' quantity kinds (docs/machines.md)
MACHINE = {"reduced_inertia", "reduced_inertia_slope", "reduced_torque", "motion"}
#: quantity kinds whose answers a rigid motion of the figure leaves alone
INVARIANT = {
    "length", "speed", "acceleration", "relative_speed", "relative_acceleration",
    "normal_acceleration", "instant_centre_distance", "least_speed", "tension", "spring_force", "force_amplitude",
    "natural_frequency", "natural_period", "damping_ratio", "damped_frequency",
    "mass_matrix", "stiffness_matrix", "damping_matrix", "mode_shape", "phase",
    "forcing_frequency", "frequency_ratio", "beat_period", "eigenvalue", "transmissibility",
    "characteristic", "receptance", "peak_frequency", "period",
    "centre_distance", "contact_ratio", "min_teeth"}
RATE = re.compile(r"^(.*?)(ddot|dot)$")
POINT = re.compile(r"^([xy])(.+)$")


def split_rate(name):
    """(base name, order of the rate): 'phi2ddot' -> ('phi2', 2)."""
    m = RATE.match(name)
    if m and m.group(1):
        return m.group(1), 2 if m.group(2) == "ddot" else 1
    return name, 0


def point_names(doc) -> set:
    return set(doc.get("frame") or {}) | set(doc.get("points") or {})


def frame_class(doc, name, seen=()):
    """How the answer ``name`` changes under a rigid motion: 'invariant', 'angle' (an
    absolute direction: + theta), ('component', axis, point) (a point's coordinate or its
    rates: R p + t), 'driver' (the driver's value: an angle turns, a length stays), or None
    (not known: the answer is listed, not compared)."""
    base, order = split_rate(name)
    quantities = doc.get("quantities") or {}
    spec = quantities.get(base)
    points = point_names(doc)
    if spec is None:
        m = POINT.match(base)
        if m and m.group(2) in points:
            return ("component", m.group(1), m.group(2))
        if base == "q":
            return "driver"
        driver = (doc.get("drivers") or {}).get(base)
        if isinstance(driver, dict):        # a driver's own coordinate, by its name
            kind = next(k for k in ("angle", "length", "x", "y") if k in driver)
            if kind in ("x", "y"):
                return ("component", kind, driver[kind])
            return "angle" if kind == "angle" and not order else "invariant"
        loads = doc.get("loads") or {}
        if base in loads and loads[base].get("type") in ("driver", "torque", "axial"):
            return "invariant"
        unknowns = ((doc.get("find") or {}).get("unknowns") or {})
        if base in unknowns:
            return "invariant"
        return None
    if not isinstance(spec, dict):
        return None
    kinds = [k for k in spec if k not in ("unit", "signed", "decimals", "radius")]
    if not kinds:
        return None
    kind = kinds[0]
    if kind in MACHINE:             # J*, Q, the motion in time: none sees the frame's axes
        return "invariant"
    if kind in ("angle", "rotation"):
        return "invariant" if order else "angle"
    if kind == "regime":                    # positions are the driver's angle, turned
        return "angle" if str(spec[kind]).startswith("at_") else "invariant"
    if kind == "flywheel":
        return "invariant"
    if kind in OF_ANOTHER and name not in seen:
        inner = frame_class(doc, spec[kind], seen + (name,))
        return "invariant" if inner in ("invariant", "angle") else None
    if kind in ("x", "y") and isinstance(spec[kind], str):
        return ("component", kind, spec[kind])
    if kind in INVARIANT and len(kinds) == 1:
        return "invariant"
    if kind in ("along", "normal_to") and isinstance(spec.get("point"), list):
        return "invariant"                  # a relative position or rate along a body's line
    if kind in ("slider_force", "reaction") and spec.get("component") in (
            "magnitude", "normal", "tangential") and (spec.get("component") != "normal"
                                                      or kind == "slider_force" or "axis" in spec):
        return "invariant"
    if kind == "amplitude" and isinstance(spec[kind], str):
        return "invariant"
    if kind == "maximum" and name not in seen:
        inner = frame_class(doc, spec[kind], seen + (name,))
        return inner if inner in ("invariant", "angle") else None
    if kind == "equilibrium":
        coordinate = (doc.get("coordinates") or {}).get(spec[kind]) or {}
        ckind = next(iter(coordinate), None)
        if ckind == "angle":
            return "angle"
        if ckind in ("x", "y"):
            return ("component", ckind, coordinate[ckind])
        return "invariant" if ckind == "length" else None
    if kind == "expr":                  # params and constants stay; answers as they change
        words = set(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", str(spec[kind])))
        read = [w for w in words if w in quantities or w in (doc.get("loads") or {}) or
                (POINT.match(w) and POINT.match(w).group(2) in points)]
        if any(w in seen for w in read):
            return None
        classes = [frame_class(doc, w, seen + (name,)) for w in read]
        return "invariant" if all(c == "invariant" for c in classes) else None
    return None


def reads_params(doc, name) -> bool:
    """Whether the answer ``name`` is an expression that reads a parameter (which the
    scaling leaves alone where it is declared: the expression does not scale as its unit)."""
    spec = (doc.get("quantities") or {}).get(split_rate(name)[0])
    if not isinstance(spec, dict) or "expr" not in spec:
        return False
    words = set(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", str(spec["expr"])))
    return bool(words & (set(doc.get("params") or {}) | {"k"}))


# --- units: their length power ------------------------------------------------------------
LENGTH_POWER = {
    **dict.fromkeys(("m", "mm", "cm", "km", "in", "ft", "mi", "um"), 1),
    **dict.fromkeys(("N", "kN", "MN", "lbf", "kgf"), 1),
    **dict.fromkeys(("Nm", "kNm", "Nmm", "J", "kJ", "W", "kW", "hp"), 2),
    **dict.fromkeys(("Pa", "kPa", "MPa", "bar", "psi"), -1),
    **dict.fromkeys(("kg", "g", "t", "lb", "s", "min", "h", "ms", "rad", "deg", "rev", "turn",
                     "Hz", "rpm", "cpm", "1", "%"), 0),
}


def has_lengths(doc) -> bool:
    """Whether a file writes lengths: a mechanism's frame, or a clutch problem's plate."""
    return "frame" in doc or "plate" in (doc.get("clutch") or {})


def length_power(unit: str):
    """The length dimension of a unit as linkcli prints it ('kg m^2' -> 2, 'N/deg' -> 1,
    'mm/s^2' -> 1); None for a unit this table does not know."""
    if unit in ("", None):
        return 0
    total, sign = 0, 1
    for token in re.findall(r"[^\s*/]+|/", unit):
        if token == "/":
            sign = -1
            continue
        base, _, exp = token.partition("^")
        power = LENGTH_POWER.get(base)
        if power is None:
            return None
        total += sign * power * (int(exp) if exp else 1)
    return total
