"""From a YAML document to a validated :class:`~linkcli.model.Mechanism`.

Every problem found is collected with its YAML path and line, so that
``linkcli validate`` can report them all at once; loading raises the first
batch as one :class:`InputErrors`.
"""
from __future__ import annotations

import cmath
import math
import re

from . import expressions
from .errors import ExpressionError, InputError
from .model import (FRAME, Actuator, AnswerKey, Body, Driver, Guide, KeyEntry, Load,
                    Mechanism, Quantity)
from .units import ANGLE, FORCE, LENGTH, TORQUE, Units
from .yamlsource import Document, path_text

TOP_KEYS = {"title", "source", "notes", "units", "k", "params", "frame", "points", "links",
            "actuators", "sliders", "driver", "loads", "quantities", "report", "keys",
            "dynamics"}
SECTIONS = ("position", "velocity", "acceleration", "statics", "points")
UNKNOWN = "unknown"
NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*\Z")   # \Z: no trailing newline


class InputErrors(InputError):
    """Several input errors found in one file."""

    def __init__(self, errors: list[InputError]):
        self.errors = errors
        first = errors[0]
        super().__init__(first.detail, file=first.file, key=first.key, line=first.line,
                         hint=first.hint)

    def __str__(self) -> str:
        lines = [InputError.__str__(e) for e in self.errors]
        if len(lines) == 1:
            return lines[0]
        return f"{len(lines)} problems:\n" + "\n".join("  " + line for line in lines)


class _Skip(Exception):
    """Raised inside the parser after an error was recorded, to skip a block."""


class Parser:
    def __init__(self, doc: Document, k: int | None):
        self.doc = doc
        self.errors: list[InputError] = []
        self.k_override = k
        self.names: dict[str, float] = {}
        self.k: int | None = None

    # error helpers -------------------------------------------------------------
    def error(self, path, detail: str, hint: str | None = None):
        self.errors.append(InputError(detail, file=self.doc.name, key=path_text(path) or None,
                                      line=self.doc.line(path), hint=hint))
        return _Skip()

    def get(self, mapping: dict, path, key: str, required=True, default=None):
        if key not in mapping:
            if required:
                raise self.error(path, f"missing key '{key}'")
            return default
        return mapping[key]

    def mapping(self, value, path, allowed=None, required=()) -> dict:
        if not isinstance(value, dict):
            raise self.error(path, f"expected a mapping, got {_kind(value)}")
        if allowed is not None:
            for key in value:
                if key not in allowed:
                    raise self.error(path + (key,), f"unknown key '{key}'",
                                     hint="allowed here: " + ", ".join(sorted(allowed)))
        for key in required:
            if key not in value:
                raise self.error(path, f"missing key '{key}'")
        return value

    def number(self, value, path, kind: str | None = None, units: Units | None = None) -> float:
        try:
            number = expressions.evaluate(value, self.names)
        except ExpressionError as exc:
            raise self.error(path, exc.detail, exc.hint) from None
        if kind is not None:
            number *= units.factor(kind)
        return number

    def name(self, value, path, pool=None, what="point") -> str:
        if not isinstance(value, str) or not NAME.match(value):
            raise self.error(path, f"expected a {what} name, got {value!r}")
        if pool is not None and value not in pool:
            known = ", ".join(sorted(pool)) or "none"
            raise self.error(path, f"undefined {what} '{value}'", hint=f"defined: {known}")
        return value

    def pair(self, value, path, pool, what="point") -> tuple[str, str]:
        if not isinstance(value, list) or len(value) != 2:
            raise self.error(path, f"expected two {what} names [first, second], got {value!r}")
        a = self.name(value[0], path + (0,), pool, what)
        b = self.name(value[1], path + (1,), pool, what)
        if a == b:
            raise self.error(path, f"the two {what}s must differ")
        return a, b

    def xy(self, value, path, units: Units) -> complex:
        if not isinstance(value, list) or len(value) != 2:
            raise self.error(path, f"expected coordinates [x, y], got {value!r}")
        x = self.number(value[0], path + (0,), "length", units)
        y = self.number(value[1], path + (1,), "length", units)
        return complex(x, y)

    def block(self, func, *args):
        """Run one parsing step; on error keep going with the next."""
        try:
            return func(*args)
        except _Skip:
            return None

    # the document --------------------------------------------------------------
    def parse(self) -> Mechanism:
        data = self.doc.data
        if not isinstance(data, dict):
            self.error((), f"a mechanism file is a mapping of sections, got {_kind(data)}")
            raise InputErrors(self.errors)
        for key in data:
            if key not in TOP_KEYS:
                self.error((key,), f"unknown section '{key}'",
                           hint="sections: " + ", ".join(sorted(TOP_KEYS)))
        units = self.block(self.units, data.get("units")) or Units()
        self.block(self.params, data)
        fixed = self.block(self.frame, data, units) or {}
        moving = self.block(self.moving, data, units, fixed) or {}
        pool = set(fixed) | set(moving)
        bodies: dict[str, Body] = {}
        self.block(self.links, data, units, pool, bodies)
        actuators = self.block(self.actuators, data, pool, bodies) or {}
        self.block(self.sliders, data, units, pool, bodies, fixed)
        driver = self.block(self.driver, data, units, pool, actuators)
        loads = self.block(self.loads, data, units, pool, bodies, actuators, driver) or {}
        quantities = self.block(self.quantities, data, pool, loads, driver) or {}
        report = self.block(self.report, data, quantities, loads, pool) or {}
        keys = self.block(self.keys, data, quantities, loads, pool, report) or ()
        self.check_points_used(pool, bodies, actuators, fixed)
        if self.errors:
            raise InputErrors(self.errors)
        title = str(data.get("title", self.doc.name))
        return Mechanism(title=title, file=self.doc.name, k=self.k, units=units,
                         fixed=fixed, moving=moving, bodies=bodies, actuators=actuators,
                         driver=driver, loads=loads, quantities=quantities, report=report,
                         keys=keys, extras={"dynamics": data.get("dynamics"), "doc": self.doc,
                                            "names": dict(self.names)})

    def units(self, value) -> Units:
        if value is None:
            return Units()
        self.mapping(value, ("units",))
        try:
            return Units(value)
        except InputError as exc:
            raise self.error(("units", exc.key.split(".")[-1]) if exc.key else ("units",),
                             exc.detail, exc.hint) from None

    def params(self, data):
        k = data.get("k")
        if self.k_override is not None:
            k = self.k_override
        if k is not None:
            if isinstance(k, bool) or not isinstance(k, int) or not 0 <= k <= 9:
                raise self.error(("k",), f"k must be a digit 0-9, got {k!r}",
                                 hint="k is the last digit of the matricola")
            self.names["k"] = float(k)
            self.k = k
        params = data.get("params") or {}
        self.mapping(params, ("params",))
        for key, value in params.items():
            if not isinstance(key, str) or not NAME.match(key) or key in expressions.CONSTANTS \
                    or key in expressions.FUNCTIONS or key == "k":
                self.error(("params", key), f"'{key}' cannot be a parameter name")
                continue
            try:
                self.names[key] = self.number(value, ("params", key))
            except _Skip:
                continue

    def frame(self, data, units) -> dict:
        frame = self.mapping(self.get(data, (), "frame"), ("frame",))
        fixed = {}
        for name, value in frame.items():
            path = ("frame", name)
            if self.block(self.name, name, path) is None:
                continue
            xy = self.block(self.xy, value, path, units)
            if xy is not None:
                fixed[name] = xy
        if not fixed:
            raise self.error(("frame",), "the frame needs at least one fixed point")
        return fixed

    def moving(self, data, units, fixed) -> dict:
        points = self.mapping(self.get(data, (), "points"), ("points",))
        moving = {}
        for name, value in points.items():
            path = ("points", name)
            if self.block(self.name, name, path) is None:
                continue
            if name in fixed:
                self.error(path, f"point '{name}' is both fixed (frame) and moving")
                continue
            xy = self.block(self.xy, value, path, units)
            if xy is not None:
                moving[name] = xy
        return moving

    # bodies --------------------------------------------------------------------
    def links(self, data, units, pool, bodies):
        links = self.mapping(self.get(data, (), "links", required=False, default={}) or {},
                             ("links",))
        for name, spec in links.items():
            self.block(self.link, name, spec, units, pool, bodies)

    def link(self, name, spec, units, pool, bodies):
        path = ("links", name)
        self.name(name, path, what="link")
        if name == FRAME:
            raise self.error(path, "'frame' is reserved for the fixed body")
        spec = self.mapping(spec, path, {"points", "length", "shape", "local"}, ("points",))
        points = spec["points"]
        if not isinstance(points, list) or len(points) < 2:
            raise self.error(path + ("points",), "a link needs a list of at least two points")
        points = tuple(self.name(p, path + ("points", i), pool) for i, p in enumerate(points))
        if len(set(points)) != len(points):
            raise self.error(path + ("points",), "a point is listed twice")
        given = [key for key in ("length", "shape", "local") if key in spec]
        if len(given) != 1:
            raise self.error(path, "give exactly one of 'length' (two points), 'shape' or 'local'")
        if given[0] == "length":
            if len(points) != 2:
                raise self.error(path + ("length",), "'length' is for a link of two points; "
                                 "use 'shape' or 'local' for three or more")
            length = self.positive(spec["length"], path + ("length",), units)
            local = {points[0]: 0j, points[1]: complex(length, 0)}
        elif given[0] == "local":
            local = self.local(spec["local"], path + ("local",), points, units)
        else:
            local = self.shape(spec["shape"], path + ("shape",), points, units)
        size = max(abs(z) for z in local.values())
        for i, a in enumerate(points):     # coincident points (relative to the body's size)
            b = next((b for b in points[i + 1:] if abs(local[b] - local[a]) <= 1e-12 * size), None)
            if b is not None:
                raise self.error(path, f"points {a} and {b} of the link coincide",
                                 hint="check its lengths and angles")
        bodies[name] = Body(name, "link", points, local)

    def positive(self, value, path, units, kind="length") -> float:
        number = self.number(value, path, kind, units)
        if number <= 0:
            raise self.error(path, f"must be positive, got {value!r}")
        return number

    def local(self, spec, path, points, units) -> dict:
        spec = self.mapping(spec, path, set(points), points)
        local = {p: self.xy(spec[p], path + (p,), units) for p in points}
        if abs(local[points[1]] - local[points[0]]) == 0:
            raise self.error(path, "the first two points coincide")
        return local

    def shape(self, spec, path, points, units) -> dict:
        """Local coordinates from the exam's description.

        The first point is the origin, the second lies on +x at distance
        ``length``; every other point is placed ``length`` from ``from`` (default
        the first point) at ``angle`` counter-clockwise from the direction
        first -> second, or by two ``distances`` and the ``side`` it opens to.
        """
        spec = self.mapping(spec, path, set(points[1:]), points[1:])
        local = {points[0]: 0j}
        base = self.mapping(spec[points[1]], path + (points[1],), {"length"}, ("length",))
        local[points[1]] = complex(self.positive(base["length"], path + (points[1], "length"),
                                                 units), 0)
        for p in points[2:]:
            local[p] = self.shape_point(spec[p], path + (p,), local, units)
        return local

    def shape_point(self, spec, path, local, units) -> complex:
        spec = self.mapping(spec, path, {"length", "angle", "from", "distances", "side"})
        if "distances" in spec:
            dist = self.mapping(spec["distances"], path + ("distances",))
            if len(dist) != 2:
                raise self.error(path + ("distances",), "give distances to two placed points")
            (p1, d1), (p2, d2) = dist.items()
            for p in (p1, p2):
                self.name(p, path + ("distances", p), local)
            d1 = self.positive(d1, path + ("distances", p1), units)
            d2 = self.positive(d2, path + ("distances", p2), units)
            side = self.get(spec, path, "side")
            if side not in ("left", "right"):
                raise self.error(path + ("side",), "side is 'left' or 'right' of first -> second")
            a, b = local[p1], local[p2]
            base = abs(b - a)
            along = (d1 * d1 - d2 * d2 + base * base) / (2 * base)
            h2 = d1 * d1 - along * along
            if h2 < 0:
                raise self.error(path + ("distances",), "these distances do not close a triangle")
            sign = 1 if side == "left" else -1
            return a + (along + 1j * sign * math.sqrt(h2)) * (b - a) / base
        length = self.positive(self.get(spec, path, "length"), path + ("length",), units)
        angle = self.number(spec.get("angle", 0), path + ("angle",), "angle", units)
        origin = spec.get("from")
        start = local[next(iter(local))] if origin is None else local[
            self.name(origin, path + ("from",), local)]
        return start + length * cmath.exp(1j * angle)

    def actuators(self, data, pool, bodies) -> dict:
        spec = self.mapping(self.get(data, (), "actuators", required=False, default={}) or {},
                            ("actuators",))
        actuators = {}
        for name, value in spec.items():
            path = ("actuators", name)
            try:
                self.name(name, path, what="actuator")
                value = self.mapping(value, path, {"points"}, ("points",))
                a, b = self.pair(value["points"], path + ("points",), pool)
            except _Skip:
                continue
            if name in bodies:
                self.error(path, f"name '{name}' is already a link")
                continue
            actuators[name] = Actuator(name, a, b)
            bodies[name + ".cylinder"] = Body(name + ".cylinder", "cylinder", (a,), {a: 0j})
            bodies[name + ".rod"] = Body(name + ".rod", "rod", (b,), {b: 0j})
        return actuators

    def sliders(self, data, units, pool, bodies, fixed):
        spec = self.mapping(self.get(data, (), "sliders", required=False, default={}) or {},
                            ("sliders",))
        for name, value in spec.items():
            self.block(self.slider, name, value, units, pool, bodies, fixed)

    def slider(self, name, value, units, pool, bodies, fixed):
        path = ("sliders", name)
        self.name(name, path, what="slider")
        value = self.mapping(value, path, {"point", "guide", "carries"}, ("point", "guide"))
        point = self.name(value["point"], path + ("point",), pool)
        guide = self.guide(value["guide"], path + ("guide",), units, pool, bodies, fixed, name)
        local = {point: 0j}
        carries = self.mapping(value.get("carries") or {}, path + ("carries",))
        for other, offset in carries.items():
            opath = path + ("carries", other)
            self.name(other, opath, pool)
            local[other] = self.offset(offset, opath, units, guide, fixed)
        if name in bodies:
            raise self.error(path, f"name '{name}' is already used by a link or actuator")
        bodies[name] = Body(name, "block", tuple(local), local, guide)

    def offset(self, value, path, units, guide: Guide, fixed) -> complex:
        """Offset of a carried point in the guide's axes (along, left normal).

        On a fixed guide the offset may be given in the frame's axes (``[dx,
        dy]`` or ``{dx, dy}``): the block translates, so it never changes.
        """
        if guide.carrier == FRAME:
            axis = fixed[guide.c] - fixed[guide.b]
            to_guide = (axis / abs(axis)).conjugate()
        if isinstance(value, list):
            if guide.carrier != FRAME:
                raise self.error(path, "on a moving guide give {along: .., normal: ..}")
            return self.xy(value, path, units) * to_guide
        value = self.mapping(value, path, {"dx", "dy", "along", "normal"})
        if "dx" in value or "dy" in value:
            if guide.carrier != FRAME:
                raise self.error(path, "on a moving guide give {along: .., normal: ..}")
            world = complex(self.number(value.get("dx", 0), path + ("dx",), "length", units),
                            self.number(value.get("dy", 0), path + ("dy",), "length", units))
            return world * to_guide
        return complex(self.number(value.get("along", 0), path + ("along",), "length", units),
                       self.number(value.get("normal", 0), path + ("normal",), "length", units))

    def guide(self, value, path, units, pool, bodies, fixed, slider) -> Guide:
        """A line: {x: c}, {y: c}, {through: P or [x, y], angle: a} or {along: [B, C], offset: e}."""
        value = self.mapping(value, path, {"x", "y", "through", "angle", "along", "offset"})
        text = ", ".join(f"{k}: {v}" for k, v in value.items())
        offset = self.number(value.get("offset", 0), path + ("offset",), "length", units)
        if "along" in value:
            b, c = self.pair(value["along"], path + ("along",), pool)
            if b in fixed and c in fixed:
                carrier = FRAME
            else:
                carrier = next((body.name for body in bodies.values() if body.kind == "link"
                                and b in body.points and c in body.points), None)
                if carrier is None:
                    raise self.error(path + ("along",), f"no link carries both {b} and {c}",
                                     hint="a moving guide runs along two points of one link")
            return Guide(carrier, b, c, offset, text)
        if "x" in value or "y" in value:
            if len(value) != 1 + ("offset" in value):
                raise self.error(path, "give only one of x or y for an axis-parallel guide")
            if "x" in value:
                origin = complex(self.number(value["x"], path + ("x",), "length", units), 0)
                direction = 1j
            else:
                origin = complex(0, self.number(value["y"], path + ("y",), "length", units))
                direction = 1
        else:
            through = self.get(value, path, "through")
            if isinstance(through, str):
                origin = fixed.get(self.name(through, path + ("through",), pool))
                if origin is None:
                    raise self.error(path + ("through",), f"'{through}' is not a fixed point")
            else:
                origin = self.xy(through, path + ("through",), units)
            angle = self.number(self.get(value, path, "angle"), path + ("angle",), "angle", units)
            direction = cmath.exp(1j * angle)
        b, c = f"~{slider}.0", f"~{slider}.1"
        # a direction vector of at least unit length (SI): never underflows when squared
        scale = max(abs(origin), max((abs(p) for p in fixed.values()), default=0.0), 1.0)
        fixed[b] = origin
        fixed[c] = origin + direction * scale
        return Guide(FRAME, b, c, offset, text)

    # driver, loads -------------------------------------------------------------
    def driver(self, data, units, pool, actuators) -> Driver:
        path = ("driver",)
        spec = self.mapping(self.get(data, (), "driver"), path,
                            {"angle", "length", "x", "y", "value", "rate", "accel"},
                            ("value",))
        kinds = [k for k in ("angle", "length", "x", "y") if k in spec]
        if len(kinds) != 1:
            raise self.error(path, "give exactly one of angle: [P, Q], length: [P, Q], x: P, y: P")
        kind = kinds[0]
        if kind in ("angle", "length"):
            a, b = self.pair(spec[kind], path + (kind,), pool)
        else:
            a, b = self.name(spec[kind], path + (kind,), pool), None
        base = "angle" if kind == "angle" else "length"
        value = self.number(spec["value"], path + ("value",), base, units)
        rate_factor = units.factor("angular_rate") if base == "angle" else units.factor("length")
        rate = self.number(spec.get("rate", 0), path + ("rate",)) * rate_factor
        accel_factor = units.display(base, 2)[1]
        accel = self.number(spec.get("accel", 0), path + ("accel",)) * accel_factor
        if kind == "length" and value <= 0:
            raise self.error(path + ("value",), "a driving length must be positive")
        return Driver(kind, a, b, value, rate, accel)

    def loads(self, data, units, pool, bodies, actuators, driver) -> dict:
        spec = self.mapping(self.get(data, (), "loads", required=False, default={}) or {},
                            ("loads",))
        loads = {}
        for name, value in spec.items():
            load = self.block(self.load, name, value, units, pool, bodies, actuators, driver)
            if load is not None:
                loads[name] = load
        unknown = [n for n, load in loads.items() if load.value is None]
        if loads and len(unknown) != 1 and len(loads) == len(spec):
            which = ", ".join(unknown) if unknown else "none"
            self.error(("loads",), f"exactly one load must be unknown, found {len(unknown)} ({which})",
                       hint="write 'unknown' as the value the statics must find")
        return loads

    def load(self, name, value, units, pool, bodies, actuators, driver) -> Load:
        path = ("loads", name)
        self.name(name, path, what="load")
        value = self.mapping(value, path, {"type", "at", "on", "x", "y", "magnitude", "angle",
                                           "value"}, ("type",))
        kind = value["type"]
        if kind == "force":
            return self.force(name, value, path, units, pool)
        if kind not in ("torque", "axial", "driver"):
            raise self.error(path + ("type",), f"unknown load type {kind!r}",
                             hint="force, torque, axial or driver")
        for key in ("at", "x", "y", "magnitude", "angle"):
            if key in value:
                raise self.error(path + (key,), f"'{key}' is for forces")
        target = None
        if kind == "torque":
            pool_b = {n for n, b in bodies.items() if b.kind in ("link", "block")} | set(actuators)
            target = self.name(self.get(value, path, "on"), path + ("on",), pool_b, "link")
        elif kind == "axial":
            target = self.name(self.get(value, path, "on"), path + ("on",), actuators, "actuator")
        elif "on" in value:
            raise self.error(path + ("on",), "the driver load acts on the driver coordinate")
        driver_unit = "torque" if driver is None or driver.kind == "angle" else "force"
        unit = {"torque": "torque", "axial": "force", "driver": driver_unit}[kind]
        amount = self.amount(self.get(value, path, "value"), path + ("value",), unit, units)
        return Load(name, kind, target, 1, amount)

    def amount(self, value, path, kind, units):
        if value == UNKNOWN:
            return None
        return self.number(value, path, kind, units)

    def force(self, name, value, path, units, pool) -> Load:
        at = self.name(self.get(value, path, "at"), path + ("at",), pool)
        if "on" in value or "value" in value:
            raise self.error(path, "a force takes x/y components or magnitude and angle")
        if "magnitude" in value:
            angle = self.number(self.get(value, path, "angle"), path + ("angle",), "angle", units)
            amount = self.amount(value["magnitude"], path + ("magnitude",), "force", units)
            return Load(name, "force", at, cmath.exp(1j * angle), amount)
        comps = {c: value[c] for c in ("x", "y") if c in value}
        if not comps:
            raise self.error(path, "a force needs x and/or y components, or magnitude and angle")
        unknown = [c for c, v in comps.items() if v == UNKNOWN]
        if unknown:
            if len(comps) != 1:
                raise self.error(path, "an unknown force has one direction: give only x or y")
            return Load(name, "force", at, 1 if unknown[0] == "x" else 1j, None)
        fx = self.number(comps.get("x", 0), path + ("x",), "force", units)
        fy = self.number(comps.get("y", 0), path + ("y",), "force", units)
        if len(comps) == 1:   # a force along one axis keeps its sign as its value
            return Load(name, "force", at, 1 if "x" in comps else 1j, fx if "x" in comps else fy)
        magnitude = math.hypot(fx, fy)
        direction = complex(fx, fy) / magnitude if magnitude else 1
        return Load(name, "force", at, direction, magnitude)

    # quantities and report -----------------------------------------------------
    def quantities(self, data, pool, loads, driver) -> dict:
        spec = self.mapping(self.get(data, (), "quantities", required=False, default={}) or {},
                            ("quantities",))
        quantities = {"q": Quantity("q", "q")}
        for p in pool:
            quantities["x" + p] = Quantity("x" + p, "x", p)
            quantities["y" + p] = Quantity("y" + p, "y", p)
        for name, load in loads.items():
            quantities[name] = Quantity(name, "load", name)
        for name, value in spec.items():
            q = self.block(self.quantity, name, value, pool, loads, driver)
            if q is not None:
                quantities[name] = q
        return quantities

    def quantity(self, name, value, pool, loads, driver=None) -> Quantity:
        path = ("quantities", name)
        self.name(name, path, what="quantity")
        if name.endswith("dot"):
            raise self.error(path, "quantity names must not end in 'dot'",
                             hint="rates are named automatically: phi1 -> phi1dot, phi1ddot")
        value = self.mapping(value, path, {"angle", "length", "x", "y", "load", "component",
                                           "unit"})
        kinds = [k for k in ("angle", "length", "x", "y", "load") if k in value]
        if len(kinds) != 1:
            raise self.error(path, "give exactly one of angle, length, x, y, load")
        kind = kinds[0]
        unit = value.get("unit")
        if unit is not None and not isinstance(unit, str):
            raise self.error(path + ("unit",), f"unit is a unit name, got {unit!r}")
        table = {"angle": ANGLE, "load": None}.get(kind, LENGTH)
        if kind == "load" and isinstance(value["load"], str) and value["load"] in loads:
            load = loads[value["load"]]   # the unit the results use for this load
            torque = load.kind == "torque" or load.kind == "driver" and (
                driver is None or driver.kind == "angle")
            table = TORQUE if torque else FORCE
        if unit is not None and table is not None and unit not in table:
            raise self.error(path + ("unit",), f"unknown unit {unit!r} for a {kind} quantity",
                             hint="use one of " + ", ".join(table))
        if kind in ("angle", "length"):
            a, b = self.pair(value[kind], path + (kind,), pool)
            return Quantity(name, kind, a, b, unit=unit)
        if kind in ("x", "y"):
            return Quantity(name, kind, self.name(value[kind], path + (kind,), pool), unit=unit)
        load = self.name(value["load"], path + ("load",), loads, "load")
        component = value.get("component")
        if component not in (None, "x", "y"):
            raise self.error(path + ("component",), "component is x or y")
        if component and loads[load].kind != "force":
            raise self.error(path + ("component",), "only forces have x and y components")
        return Quantity(name, "load", load, component=component, unit=unit)

    def report(self, data, quantities, loads, pool) -> dict:
        spec = self.mapping(self.get(data, (), "report"), ("report",), set(SECTIONS) | {"decimals"})
        report = {}
        decimals = spec.get("decimals", 1)
        if isinstance(decimals, bool) or not isinstance(decimals, int) or not 0 <= decimals <= 12:
            self.error(("report", "decimals"), f"decimals is a whole number 0-12, got {decimals!r}")
        else:
            report["decimals"] = decimals
        for section in SECTIONS:
            names = spec.get(section) or []
            path = ("report", section)
            if not isinstance(names, list):
                self.error(path, "expected a list of names")
                continue
            report[section] = []
            for i, name in enumerate(names):
                if self.block(self.report_name, section, name, path + (i,), quantities,
                              loads, pool):
                    report[section].append(name)
        return report

    def report_name(self, section, name, path, quantities, loads, pool) -> bool:
        if not isinstance(name, str):
            raise self.error(path, f"expected a name, got {name!r}")
        if section == "points":
            self.name(name, path, pool)
            return True
        order = {"position": 0, "velocity": 1, "acceleration": 2, "statics": 0}[section]
        base = split_rate(name)
        if section == "statics":
            if name not in quantities or quantities[name].kind != "load":
                raise self.error(path, f"'{name}' is not a load", hint="statics lists loads")
            return True
        if base is None or base[1] != order or base[0] not in quantities \
                or quantities[base[0]].kind == "load":
            suffix = ["", "dot", "ddot"][order]
            raise self.error(path, f"'{name}' is not a defined quantity{' rate' if order else ''}",
                             hint=f"define it under 'quantities' and name it <quantity>{suffix}")
        return True

    def keys(self, data, quantities, loads, pool, report) -> tuple:
        spec = data.get("keys")
        if spec is None:
            return ()
        if not isinstance(spec, list):
            raise self.error(("keys",), "expected a list of answer keys")
        keys = []
        for i, item in enumerate(spec):
            key = self.block(self.key, item, ("keys", i), quantities, pool)
            if key is not None:
                keys.append(key)
        return tuple(keys)

    def key(self, item, path, quantities, pool) -> AnswerKey:
        item = self.mapping(item, path, {"k", "values", "wrong", "source"}, ("values",))
        k = item.get("k")
        if k is not None and (isinstance(k, bool) or not isinstance(k, int) or not 0 <= k <= 9):
            raise self.error(path + ("k",), f"k must be a digit 0-9, got {k!r}")
        values = self.mapping(item["values"], path + ("values",))
        wrong = self.mapping(item.get("wrong") or {}, path + ("wrong",))
        for name in wrong:
            if name not in values:
                self.error(path + ("wrong", name), f"'{name}' has no printed value in this key")
        entries = []
        for name, printed in values.items():
            vpath = path + ("values", name)
            entry = self.block(self.key_entry, name, printed, vpath, quantities, pool,
                               wrong.get(name))
            if entry is not None:
                entries.append(entry)
        return AnswerKey(k, tuple(entries))

    def key_entry(self, name, printed, path, quantities, pool, wrong) -> KeyEntry:
        line = self.doc.line(path)
        is_point = name in pool and (isinstance(printed, list) or name not in quantities)
        if not is_point:
            base = split_rate(name)
            if base is None or base[0] not in quantities:
                raise self.error(path, f"the key names '{name}', which the file does not define",
                                 hint="define it under 'quantities' or fix the name")
        if wrong and not _readable(printed, is_point):
            # a garbled printed value: kept as printed, reported, never compared
            return KeyEntry(name, str(self.doc.raw.get(path, printed)), None, 0, wrong, line)
        if is_point:
            if not isinstance(printed, list) or len(printed) != 2:
                raise self.error(path, f"a point's key is [x, y], got {printed!r}")
            texts = [self.doc.raw.get(path + (i,), str(v)) for i, v in enumerate(printed)]
            nums = tuple(self.printed_number(t, path + (i,)) for i, t in enumerate(texts))
            return KeyEntry(name, f"({texts[0]}, {texts[1]})", nums,
                            min(_decimals(t) for t in texts), wrong, line)
        text = self.doc.raw.get(path, str(printed))
        return KeyEntry(name, text, self.printed_number(text, path), _decimals(text), wrong, line)

    def printed_number(self, text, path) -> float:
        try:
            value = float(str(text).replace(",", "."))
        except ValueError:
            raise self.error(path, f"cannot read printed value {text!r} as a number") from None
        if not math.isfinite(value):
            raise self.error(path, f"printed value {text!r} is not finite")
        return value

    def check_points_used(self, pool, bodies, actuators, fixed):
        if any((e.key or "").startswith(("links", "actuators", "sliders")) for e in self.errors):
            return   # a body that failed to parse would make its points look unused
        used = {p for body in bodies.values() for p in body.points}
        for point in sorted(pool - used - set(fixed)):
            self.error(("points", point), f"moving point '{point}' belongs to no link, slider or "
                       "actuator", hint="add it to a link or remove it")


def split_rate(name: str):
    """'phi1ddot' -> ('phi1', 2); 'phi1dot' -> ('phi1', 1); 'phi1' -> ('phi1', 0)."""
    if name.endswith("ddot") and len(name) > 4:
        return name[:-4], 2
    if name.endswith("dot") and len(name) > 3:
        return name[:-3], 1
    return name, 0


def _readable(printed, is_point: bool) -> bool:
    """Whether a printed key value can be read as a number (or [x, y] for a point)."""
    values = printed if is_point and isinstance(printed, list) and len(printed) == 2 else (
        None if is_point else [printed])
    if values is None:
        return False
    try:
        return all(math.isfinite(float(str(v).replace(",", "."))) for v in values)
    except ValueError:
        return False


def _decimals(text: str) -> int:
    text = str(text).strip().replace(",", ".")
    return len(text.split(".")[1]) if "." in text else 0


def _kind(value) -> str:
    return {dict: "a mapping", list: "a list", str: "text", type(None): "nothing"}.get(
        type(value), type(value).__name__)


def parse(doc: Document, k: int | None = None) -> Mechanism:
    return Parser(doc, k).parse()
