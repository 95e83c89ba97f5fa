"""Parsing of what the answer sheet asks: quantities, the report and the answer keys."""
from __future__ import annotations

import dataclasses
import math
import re

from linkcli.model.mechanism import (FRAME, LIMITS, VIBRATION, AnswerKey, KeyEntry, Quantity,
                                      limit_refusal, split_rate)
from linkcli.model.mechanism import Tolerance
from linkcli.model.units import ANGLE, FORCE, LENGTH, TORQUE
from linkcli.input.derived import EXPR
from linkcli.input.oscillation import OSCILLATION

SECTIONS = ("position", "velocity", "acceleration", "statics", "vibration", "points")
#: the kinds of a geometric quantity, each the YAML key that asks for it
GEOMETRY = ("angle", "length", "x", "y", "load", "speed", "acceleration",
            "tangential_acceleration", "normal_acceleration", "along", "normal_to", "relative",
            "relative_speed", "relative_acceleration", "rotation", "between", "instant_centre",
            "instant_centre_distance", "reaction", "slider_force", "velocity_ratio",
            "least_speed", "least_speed_at", "tension", "contact_force")
OF_POINT = ("speed", "acceleration", "tangential_acceleration", "normal_acceleration")
OF_PAIR = ("relative", "relative_speed", "relative_acceleration")
#: of the line through two points of one body: its point of least speed and that speed
ON_BODY = ("least_speed", "least_speed_at")
PROJECTIONS = ("along", "normal_to")
ANGULAR = ("angle", "rotation", "between")
COMPONENTS = {"relative": ("x", "y"), "instant_centre": ("x", "y"),
              "reaction": ("x", "y", "magnitude", "along", "normal"),
              "slider_force": ("normal", "friction"), "contact_force": ("normal", "friction")}
#: the components of a joint force that are projections on an axis (``axis:``)
PROJECTED = ("along", "normal")
#: quantities whose value is itself a rate: a speed is listed with the velocities (its
#: rate with the accelerations), an acceleration with the accelerations
LEVEL = {"speed": 1, "relative_speed": 1, "acceleration": 2, "tangential_acceleration": 2,
         "normal_acceleration": 2, "relative_acceleration": 2, "least_speed": 1}
#: quantities of the position alone, listed with the positions or the velocities
EITHER = ("instant_centre", "instant_centre_distance", "velocity_ratio", "least_speed_at")
#: the limits of the motion that are of a position quantity (its dead centres)
STROKES = ("stroke", "time_ratio", "stroke_time")
#: forces, listed with the statics
FORCES = ("load", "reaction", "slider_force", "tension", "contact_force")
#: the quantities a velocity ratio may be of: those whose rate is linear in the velocities
RATIO_OF = ("q", "x", "y", "angle", "length", "along", "normal_to", "relative", "rotation",
            "between")
RATES = (0, 1, 2)
SUFFIX = ("", "dot", "ddot")
#: a relative tolerance as written: a percentage of at most 6 + 6 digits ('2%', '0.5 %')
TOLERANCE_PERCENT = re.compile(r"^([0-9]{1,6}(\.[0-9]{1,6})?) ?%$")


class _Names:
    """Every name a file defines or makes (q, xP and yP, loads, quantities) and the names of
    their rates (NAMEdot, NAMEddot): a name must mean one thing, so that 'dddot' is not
    both the rate of 'dd' and the second rate of 'd'."""

    def __init__(self):
        self.taken: dict[str, tuple] = {}    # name -> (base, order, whose, what)

    def claim(self, base: str, orders, whose: str, what: str):
        """Take ``base`` and its rates for ``whose`` (a description; ``what`` names it in a
        hint); return the clash (name, base, order, other's entry) when one is taken."""
        for order in orders:
            name = base + SUFFIX[order]
            if name in self.taken and self.taken[name][2] != whose:
                return name, base, order, self.taken[name]
        for order in orders:
            self.taken.setdefault(base + SUFFIX[order], (base, order, whose, what))
        return None


def split_base(name: str, order: int) -> str:
    return name[:len(name) - len(SUFFIX[order])]


def _bases(name: str) -> list[str]:
    """Every name of which ``name`` may be a rate (or which it is)."""
    return [split_base(name, order) for order in RATES
            if name.endswith(SUFFIX[order]) and len(name) > len(SUFFIX[order])]


def _halves(bodies: dict) -> dict:
    """The halves of each actuator as bodies a pin acts on: NAME.cylinder holds the
    actuator's first point, NAME.rod its second (``bodies`` as :meth:`raw_bodies`)."""
    out = {}
    for name, (kind, points) in bodies.items():
        if kind == "actuator":
            ends = points if points is not None and len(points) == 2 else (None, None)
            out[name + ".cylinder"] = ("cylinder", None if ends[0] is None else (ends[0],))
            out[name + ".rod"] = ("rod", None if ends[1] is None else (ends[1],))
    return out


def _same(q: Quantity, automatic: Quantity) -> bool:
    """Whether ``q`` defines the automatic quantity again (a file may, to give it a unit)."""
    return dataclasses.replace(q, unit=None) == automatic


class QuantitiesSection:
    """``quantities``, ``report`` and ``keys`` (a mixin of the Parser)."""

    def quantities(self, data, pool, loads, driver) -> dict:
        spec = self.mapping(self.get(data, (), "quantities", required=False, default={}) or {},
                            ("quantities",))
        quantities = {"q": Quantity("q", "q")}
        names = _Names()
        names.claim("q", RATES, "the driver's coordinate", "q")
        for p in sorted(pool, key=lambda p: (len(p), p)):   # 'B' before 'Bd'
            path = next(((s, p) for s in ("frame", "points") if (s, p) in self.doc.lines),
                        ("points",))
            for axis in "xy":
                whose = f"the {axis} coordinate of point {p}"
                clash = names.claim(axis + p, RATES, whose, f"point '{p}'")
                if clash:
                    self.block(self.name_clash, path, whose, f"point '{p}'", clash)
                    break
            quantities["x" + p] = Quantity("x" + p, "x", p)
            quantities["y" + p] = Quantity("y" + p, "y", p)
        for name, load in loads.items():
            clash = names.claim(name, (0,), f"the load {name}", f"load '{name}'")
            if clash:
                self.block(self.name_clash, ("loads", name), f"the load {name}",
                           f"load '{name}'", clash)
            quantities[name] = Quantity(name, "load", name)
        self.failed = set()
        for name, value in spec.items():
            q = self.block(self.quantity, name, value, pool, loads, driver)
            if q is not None and not (name in quantities and _same(q, quantities[name])):
                # defining an automatic quantity again (to give it a unit) is allowed
                clash = names.claim(name, tuple(range(q.rates + 1)),   # the rates it has
                                    f"the quantity {name}", f"quantity '{name}'")
                if clash:
                    q = self.block(self.name_clash, ("quantities", name),
                                   f"the quantity {name}", f"quantity '{name}'", clash)
            if q is not None:
                quantities[name] = q
            else:
                self.failed.add(name)
        for name, q in list(quantities.items()):
            if q.kind == "velocity_ratio" and not self.block(self.ratio_of, q, quantities):
                del quantities[name]
                self.failed.add(name)
        for name, q in list(quantities.items()):
            if q.limit and not self.block(self.limit_of, q, quantities):
                del quantities[name]
                self.failed.add(name)
        self.expression_names(quantities)
        return quantities

    def limit_quantity(self, name, value, path) -> Quantity:
        """A limit of the motion of a quantity over a range of the driver (runs.limits):
        {maximum: NAME}, minimum, at_maximum, at_minimum, stroke, time_ratio, or
        {stroke_time: NAME, component: working | return}; from: and to: give the range."""
        value = self.mapping(value, path, set(LIMITS) | {"component", "from", "to"})
        kinds = [k for k in LIMITS if k in value]
        if len(kinds) != 1:
            raise self.error(path, f"give exactly one kind of limit, not {' and '.join(kinds)}",
                             hint="see docs/schema.md, 'Limits of the motion'")
        kind = kinds[0]
        if self.vibration.get("coordinates"):
            raise self.error(path, f"{kind} needs a driver: a vibration problem has "
                             "coordinates instead")
        of = self.name(value[kind], path + (kind,), what="quantity")
        component = value.get("component")
        if kind == "stroke_time":
            if component not in ("working", "return"):
                raise self.error(path + ("component",), "component is working or return, got "
                                 f"{component!r}", hint="the working stroke is the longer one")
        elif "component" in value:
            raise self.error(path + ("component",), f"a {kind} quantity has no component")
        span = None
        if "from" in value or "to" in value:
            if not ("from" in value and "to" in value):
                raise self.error(path, "give both 'from' and 'to' (the range of the driver)")
            span = (self.number(value["from"], path + ("from",)),
                    self.number(value["to"], path + ("to",)))
            if not span[0] < span[1]:
                raise self.error(path + ("to",), f"the range goes up: 'to' ({span[1]:g}) must "
                                 f"be larger than 'from' ({span[0]:g})")
        return Quantity(name, kind, of, component=component, span=span,
                        line=self.doc.line(path))

    def limit_of(self, q, quantities) -> bool:
        """Whether the quantity a limit is of is defined and has a rate (its definition's
        own error is reported already when it failed)."""
        path = ("quantities", q.name, q.kind)
        base, order = split_rate(q.a, quantities)
        if base in self.failed:
            return False
        if base not in quantities:
            raise self.error(path, f"'{q.a}' is not a defined quantity",
                             hint="a limit is of a quantity NAME of the file or its rate "
                             "NAMEdot, e.g. xB or xBdot")
        refusal = limit_refusal(q.a, quantities[base], order)
        if refusal:
            raise self.error(path, refusal, hint="ask for a position or velocity quantity: a "
                             "coordinate, an angle, a speed, or the rate of one, e.g. xBdot")
        if q.kind in STROKES and (order or quantities[base].kind in LEVEL):
            raise self.error(path, f"a {q.kind.replace('_', ' ')} is of a position quantity "
                             f"(a coordinate, an angle, a length), and '{q.a}' is a velocity",
                             hint=f"ask for its maximum and minimum: {{maximum: {q.a}}}")
        return True

    def ratio_of(self, q, quantities) -> bool:
        """Whether the quantity a velocity ratio is of is one whose rate is linear in the
        velocities (its definition's own error is reported already when it failed)."""
        path = ("quantities", q.name, "velocity_ratio")
        if q.a in self.failed:
            return False
        if q.a not in quantities:
            raise self.error(path, f"'{q.a}' is not a defined quantity",
                             hint="a velocity ratio is d(NAME)/dq of a quantity NAME of the file, "
                             "e.g. xE or phi2")
        kind = quantities[q.a].kind
        if kind not in RATIO_OF:
            raise self.error(path, f"the velocity ratio of '{q.a}' ({_kind_text(kind)}) "
                             "is not defined: it is d(NAME)/dq of a position quantity",
                             hint="give an angle, length, coordinate, projection, relative "
                             "coordinate, rotation or angle between vectors")
        return True

    def name_clash(self, path, whose, what, clash):
        """Refuse a name that is already taken, or whose rates' names are (see _Names)."""
        name, base, order, (other, theirs, other_whose, other_what) = clash
        if order == theirs == 0:
            raise self.error(path, f"the name '{name}' is already {other_whose}",
                             hint=f"rename the {what.split()[0]}: a name means one thing")

        def role(b, o, w):
            told = "" if w == f"the quantity {b}" else f" ({w})"
            return f"{('the name of', 'the rate of', 'the second rate of')[o]} {b}{told}"

        raise self.error(path, f"'{name}' would be both {role(base, order, whose)} and "
                         f"{role(other, theirs, other_whose)}",
                         hint=f"rename {what} or {other_what}: rates are named NAMEdot and "
                         "NAMEddot, so names ending in 'd' or 'dot' collide")

    def quantity(self, name, value, pool, loads, driver=None) -> Quantity:
        path = ("quantities", name)
        self.name(name, path, what="quantity")
        if name.endswith("dot"):
            raise self.error(path, "quantity names must not end in 'dot'",
                             hint="rates are named automatically: phi1 -> phi1dot, phi1ddot")
        if isinstance(value, dict) and any(k in value for k in OSCILLATION):
            return self.oscillation_quantity(name, value, path, pool)
        if isinstance(value, dict) and any(k in value for k in VIBRATION):
            return self.with_part(name, value, path, pool)
        if isinstance(value, dict) and any(k in value for k in LIMITS):
            return self.limit_quantity(name, value, path)
        if isinstance(value, dict) and EXPR in value:
            return self.expression_quantity(name, value, path)
        value = self.mapping(value, path, set(GEOMETRY) | {"component", "unit", "point",
                                                           "signed", "axis"})
        kinds = [k for k in GEOMETRY if k in value]
        if len(kinds) != 1:
            if len(kinds) > 1 and set(kinds) <= set(GEOMETRY[:5]):
                raise self.error(path, "give exactly one of angle, length, x, y, load")
            raise self.error(path, "give exactly one of " + ", ".join(GEOMETRY) if not kinds
                             else f"give exactly one kind of quantity, not {' and '.join(kinds)}",
                             hint="see docs/schema.md, 'quantities'")
        kind = kinds[0]
        unit = value.get("unit")
        if unit is not None and not isinstance(unit, str):
            raise self.error(path + ("unit",), f"unit is a unit name, got {unit!r}")
        table = {"angle": ANGLE, "rotation": ANGLE, "between": ANGLE, "load": None,
                 "reaction": FORCE, "slider_force": FORCE, "tension": FORCE,
                 "contact_force": FORCE}.get(kind, LENGTH)
        if kind == "load" and isinstance(value["load"], str) and value["load"] in loads:
            load = loads[value["load"]]   # the unit the results use for this load
            torque = load.kind == "torque" or load.kind == "driver" and (
                driver is None or driver.kind == "angle")
            table = TORQUE if torque else FORCE
        if kind == "velocity_ratio" and unit is not None:
            raise self.error(path + ("unit",), "a velocity ratio is in its quantity's unit per "
                             "driver unit", hint="give the unit to the quantity it is of")
        if unit is not None and table is not None and unit not in table:
            raise self.error(path + ("unit",), f"unknown unit {unit!r} for a {kind} quantity",
                             hint="use one of " + ", ".join(table))
        if "signed" in value:
            if kind not in ANGULAR:
                raise self.error(path + ("signed",), "'signed' is for angles (angle, rotation, "
                                 "between)")
            if not isinstance(value["signed"], bool):
                raise self.error(path + ("signed",), f"signed is true or false, got "
                                 f"{value['signed']!r}")
        if "point" in value and kind not in PROJECTIONS:
            raise self.error(path + ("point",), "'point' is for along and normal_to")
        if "axis" in value and not (kind == "reaction" and value.get("component") in PROJECTED):
            raise self.error(path + ("axis",), "'axis' is for the along and normal components "
                             "of a reaction", hint="{reaction: [P, BODY], component: normal, "
                             "axis: OTHER}")
        if kind in GEOMETRY[5:]:
            line = self.doc.line(path)
            return dataclasses.replace(self.textbook_quantity(name, kind, value, path, pool),
                                       unit=unit, signed=value.get("signed", False), line=line)
        if kind in ("angle", "length"):
            a, b = self.pair(value[kind], path + (kind,), pool)
            return Quantity(name, kind, a, b, unit=unit, signed=value.get("signed", False))
        if kind in ("x", "y"):
            return Quantity(name, kind, self.name(value[kind], path + (kind,), pool), unit=unit)
        load = self.name(value["load"], path + ("load",), loads, "load")
        component = value.get("component")
        if component not in (None, "x", "y"):
            raise self.error(path + ("component",), "component is x or y")
        if component and loads[load].kind != "force":
            raise self.error(path + ("component",), "only forces have x and y components")
        return Quantity(name, "load", load, component=component, unit=unit)

    def textbook_quantity(self, name, kind, value, path, pool) -> Quantity:
        """Speeds and accelerations of points, projections, relative motion, rotations of
        bodies, the angle between two vectors, instant centres, joint forces and velocity
        ratios (see docs/schema.md, 'quantities')."""
        where = path + (kind,)
        arg = value[kind]
        component = value.get("component")
        if kind in COMPONENTS:
            if component not in COMPONENTS[kind]:
                *first, last = COMPONENTS[kind]
                raise self.error(path + ("component",), f"component is {', '.join(first)} or "
                                 f"{last}, got {component!r}")
        elif "component" in value:
            raise self.error(path + ("component",), f"a {kind} quantity has no component")
        if kind in PROJECTIONS and "point" not in value:
            raise self.error(path, "missing key 'point' (the point projected "
                             f"{kind.replace('_', ' ')} the vector)",
                             hint=f"e.g. {{{kind}: [A, B], point: P}}")
        if kind in OF_POINT:
            return Quantity(name, kind, self.name(arg, where, pool))
        if kind in PROJECTIONS or kind in OF_PAIR:
            a, b = self.pair(arg, where, pool)
            point, other = None, None
            if kind in PROJECTIONS and isinstance(value["point"], list):
                point, other = self.pair(value["point"], path + ("point",), pool)
            elif kind in PROJECTIONS:
                point = self.name(value["point"], path + ("point",), pool)
            return Quantity(name, kind, a, b, component=component, c=point, d=other)
        if kind == "between":
            if not isinstance(arg, list) or len(arg) != 2:
                raise self.error(where, f"between takes two vectors [[A, B], [C, D]], got {arg!r}")
            a, b = self.pair(arg[0], where + (0,), pool)
            c, d = self.pair(arg[1], where + (1,), pool)
            return Quantity(name, kind, a, b, c=c, d=d)
        if kind in ON_BODY:
            a, b = self.pair(arg, where, pool)
            bodies, _ = self.raw_bodies()
            if not any({a, b} <= set(points) for _, points in bodies.values()):
                raise self.error(where, f"no body carries both {a} and {b}: {kind} is of the "
                                 "line through two points of one body",
                                 hint="name two points of one link or slider")
            return Quantity(name, kind, a, b)
        if kind == "velocity_ratio":       # its quantity is looked up once all are read
            return Quantity(name, kind, self.name(arg, where, what="quantity"))
        bodies, spinning = self.raw_bodies()
        if kind == "instant_centre" and isinstance(arg, list):   # relative to another body
            body, other = self.two_names(arg, where, "[BODY, OTHER]")
            self.body(body, where + (0,), spinning, kind)
            if other != FRAME:
                self.body(other, where + (1,), spinning, kind)
            if other == body:
                raise self.error(where, f"a body has no instant centre relative to itself, "
                                 f"got {arg!r}", hint="name two bodies, or the frame")
            return Quantity(name, kind, body, other, component=component,
                            of=spinning[body][0],
                            c=spinning[other][0] if other != FRAME else None)
        if kind in ("rotation", "instant_centre"):
            return Quantity(name, kind, self.body(arg, where, spinning, kind), component=component,
                            of=spinning[arg][0])
        if kind == "instant_centre_distance":
            body, point = self.two_names(arg, where, "[BODY, P]")
            self.body(body, where + (0,), spinning, kind)
            return Quantity(name, kind, body, self.name(point, where + (1,), pool),
                            of=spinning[body][0])
        if kind in ("tension", "contact_force"):
            return Quantity(name, kind, self.contact(arg, where, kind), component=component)
        if kind == "slider_force":
            sliders = sorted(n for n, (what, _) in bodies.items() if what == "slider")
            self.name(arg, where, what="slider")
            if arg not in sliders:
                raise self.error(where, f"undefined body '{arg}' for a slider force: it is not "
                                 "a slider", hint="sliders: " + (", ".join(sliders) or "none"))
            return Quantity(name, kind, arg, component=component, of="slider")
        point, body = self.two_names(arg, where, "[POINT, BODY]")
        point = self.name(point, where + (0,), pool)
        fixed = set(self.doc.data.get("frame") or {}) if isinstance(
            self.doc.data.get("frame"), dict) else set()
        pins = dict(bodies, **_halves(bodies), **{FRAME: ("frame", tuple(sorted(fixed)))})
        body = self.body_name(body, where + (1,), pins)
        points = pins[body][1]
        if points is not None and point not in points:
            raise self.error(where + (0,), f"undefined point '{point}' on body '{body}'",
                             hint=f"{'its points' if body != FRAME else 'fixed points'}: "
                             + (", ".join(points) or "none"))
        axis = None
        if component in PROJECTED:
            axis = self.axis(value.get("axis"), path + ("axis",), pins, pool, body)
        return Quantity(name, kind, point, body, component=component, of=pins[body][0],
                        axis=axis)

    def body_name(self, value, path, pins) -> str:
        """A body a pin acts on: a link, slider or actuator, an actuator's half
        (NAME.cylinder, NAME.rod) or the frame."""
        if isinstance(value, str) and value in pins:
            return value
        if isinstance(value, str) and "." in value:
            halves = sorted(n for n in pins if "." in n)
            raise self.error(path, f"undefined body '{value}'", hint="an actuator's halves are "
                             "NAME.cylinder and NAME.rod: " + (", ".join(halves) or "none"))
        return self.name(value, path, {n for n in pins if "." not in n}, "body")

    def axis(self, value, path, pins, pool, body) -> tuple:
        """The direction a joint force is projected on: ('body', NAME) the axis of a body
        (``axis: NAME``; by default the body the force acts on), ('points', P, Q) the vector
        P -> Q (``axis: [P, Q]``) or ('angle', radians) a fixed direction
        (``axis: {angle: A}``, counter-clockwise from +x)."""
        if value is None:
            if body == FRAME:
                raise self.error(path[:-1], "the frame has no axis of its own: give the "
                                 "direction of the component", hint="axis: BODY, axis: [P, Q] "
                                 "or axis: {angle: A}")
            return ("body", body)
        if isinstance(value, list):
            return ("points",) + self.pair(value, path, pool)
        if isinstance(value, dict):
            spec = self.mapping(value, path, {"angle"}, ("angle",))
            return ("angle", self.number(spec["angle"], path + ("angle",), "angle",
                                         self.file_units))
        name = self.body_name(value, path, {n: v for n, v in pins.items() if n != FRAME})
        return ("body", name)

    def contact(self, arg, where, kind) -> str:
        """A cord of ``cords:`` (a tension) or a rolling contact of ``rolling:``."""
        data = self.doc.data if isinstance(self.doc.data, dict) else {}
        key = "cords" if kind == "tension" else "rolling"
        names = set(data.get(key) or {}) if isinstance(data.get(key), dict) else set()
        self.name(arg, where, what="contact")
        if arg not in names:
            what = "cord" if kind == "tension" else "rolling contact"
            raise self.error(where, f"'{arg}' is not a {what} of '{key}:'",
                             hint=f"{key}: " + (", ".join(sorted(names)) or "none"))
        return arg

    def two_names(self, arg, where, form):
        if not isinstance(arg, list) or len(arg) != 2:
            raise self.error(where, f"expected two names {form}, got {arg!r}")
        return arg

    def body(self, value, where, spinning, kind) -> str:
        """A body's name for a rotation or an instant centre."""
        name = self.name(value, where, spinning, "body")
        if kind != "rotation" and spinning[name][0] == "actuator":
            raise self.error(where, f"undefined body '{name}' for an instant centre: the "
                             "cylinder and the rod of an actuator turn together but have "
                             "different instant centres", hint="ask for the instant centre "
                             "of a link")
        return name

    def raw_bodies(self) -> tuple[dict, dict]:
        """(bodies, spinning) as the file declares them (those sections are read before the
        quantities, and report their own errors): ``bodies`` maps each link, slider and
        actuator to (kind, its points or None); ``spinning`` adds the rolling contacts and
        cords (their disc) and the discs of ``dynamics: discs:``, which take their name."""
        data = self.doc.data if isinstance(self.doc.data, dict) else {}

        def section(*keys):
            spec = data
            for key in keys:
                spec = spec.get(key) if isinstance(spec, dict) else None
            return spec if isinstance(spec, dict) else {}

        def names(items):
            return tuple(items) if isinstance(items, (list, dict)) and all(
                isinstance(p, str) for p in items) else None

        bodies = {}
        for name, spec in section("links").items():
            bodies.setdefault(name, ("link", names(spec.get("points"))
                                     if isinstance(spec, dict) else None))
        for name, spec in section("actuators").items():
            bodies.setdefault(name, ("actuator", names(spec.get("points"))
                                     if isinstance(spec, dict) else None))
        for name, spec in section("sliders").items():
            points = None
            if isinstance(spec, dict) and isinstance(spec.get("point"), str):
                carried = names(spec.get("carries") or {})
                points = None if carried is None else (spec["point"],) + carried
            bodies.setdefault(name, ("slider", points))
        spinning = dict(bodies)
        for key in ("rolling", "cords"):
            for name in section(key):
                spinning.setdefault(name, ("rolling", None))
        for name in section("dynamics", "discs"):
            spinning[name] = ("disc", None)
        return bodies, spinning

    def one_kind(self, value, path, kinds):
        """(kind, its path, its argument) of a quantity written with exactly one of the
        keys ``kinds``."""
        found = [k for k in kinds if k in value]
        if len(found) != 1:
            raise self.error(path, "give exactly one of " + ", ".join(found))
        return found[0], path + (found[0],), value[found[0]]

    def vibration_quantity(self, name, value, path, pool) -> Quantity:
        """A quantity of the vibration analysis (see docs/vibrations.md)."""
        value = self.mapping(value, path, set(VIBRATION) - set(OSCILLATION) | {"unit", "time"})
        kind, where, arg = self.one_kind(value, path, VIBRATION)
        coords = self.vibration.get("coordinates", [])
        unit = self.answer_unit(value, path)        # its dimension: answer_units
        if "time" in value and kind != "free_response":
            raise self.error(path + ("time",), "'time' is for free_response")
        if not coords:
            raise self.error(path, f"{kind} needs a vibration problem: declare its "
                             "coordinates under 'coordinates:'")
        quantity = self.vibration_kind(name, kind, value, path, where, arg, pool)
        return dataclasses.replace(quantity, unit=unit, line=self.doc.line(path))

    def vibration_kind(self, name, kind, value, path, where, arg, pool) -> Quantity:
        """The quantity of ``kind`` (a key of :data:`VIBRATION`) with its argument ``arg``."""
        coords = self.vibration["coordinates"]
        if kind in ("natural_frequency", "damped_frequency", "damping_ratio"):
            return Quantity(name, kind, str(self.mode(arg, where, len(coords))))
        if kind == "forcing_frequency":
            if arg is not True:
                raise self.error(where, "write 'forcing_frequency: true'")
            return Quantity(name, kind)
        if kind == "mode_shape":
            if not isinstance(arg, list) or len(arg) != 2:
                raise self.error(where, "a mode shape component is [mode, coordinate]")
            mode = self.mode(arg[0], where + (0,), len(coords))
            return Quantity(name, kind, str(mode), self.name(arg[1], where + (1,), coords,
                                                             "coordinate"))
        if kind.endswith("_matrix"):
            a, b = self.pair(arg, where, coords, "coordinate") if not (
                isinstance(arg, list) and len(arg) == 2 and arg[0] == arg[1]) else \
                (self.name(arg[0], where + (0,), coords, "coordinate"),) * 2
            return Quantity(name, kind, a, b)
        if kind == "equilibrium":
            return Quantity(name, kind, self.name(arg, where, coords, "coordinate"))
        if kind == "spring_force":
            return Quantity(name, kind, self.name(arg, where, self.vibration["springs"],
                                                  "spring"))
        if kind == "force_amplitude":
            items = arg if isinstance(arg, list) else [arg]
            pool_e = self.vibration["springs"] | self.vibration["dampers"]
            names = tuple(self.name(e, where + (i,), pool_e, "spring or damper")
                          for i, e in enumerate(items))
            return Quantity(name, kind, elements=names)
        if kind == "free_response":
            time = self.number(value.get("time", 0), path + ("time",), "time", self.file_units)
            if time < 0:
                raise self.error(path + ("time",), f"time must be >= 0, got {time!r}")
            return Quantity(name, kind, self.name(arg, where, coords, "coordinate"), time=time)
        # amplitude, phase, transmissibility: of a coordinate, or {x: P} / {y: P}
        if isinstance(arg, dict):
            spec = self.mapping(arg, where, {"x", "y"})
            if len(spec) != 1:
                raise self.error(where, "give one axis: {x: P} or {y: P}")
            axis = next(iter(spec))
            return Quantity(name, kind, self.name(spec[axis], where + (axis,), pool),
                            component=axis)
        return Quantity(name, kind, self.name(arg, where, coords, "coordinate"))

    def mode(self, value, path, count) -> int:
        if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= count:
            raise self.error(path, f"a mode is numbered 1-{count} (from the lowest frequency), "
                             f"got {value!r}")
        return value

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
        if any(base in getattr(self, "failed", ()) for base in _bases(name)):
            return False            # its definition's error is reported already
        order = {"position": 0, "velocity": 1, "acceleration": 2, "statics": 0,
                 "vibration": 0}[section]
        base = split_rate(name, quantities)
        if base[0] in quantities and quantities[base[0]].kind == "design":
            raise self.error(path, f"'{name}' is an unknown of 'find': it is listed in the "
                             "report's Design section by itself", hint="remove it from here")
        if base[0] in quantities and quantities[base[0]].kind == EXPR:
            self.rate_of(name, quantities[base[0]], base[1], path)
            return True             # an expression: in the section its reader expects
        vibration = name in quantities and quantities[name].kind in VIBRATION
        if section == "vibration" or vibration:
            if not vibration or section != "vibration":
                raise self.error(path, f"'{name}' is {'' if vibration else 'not '}a quantity of "
                                 "the vibration analysis", hint="the 'vibration' section lists "
                                 "natural frequencies, modes, matrices, equilibrium, amplitudes")
            return True
        if section == "statics":
            if name in quantities and quantities[name].kind in FORCES:
                self.balanced(name, quantities[name], path)
                return True
            if name not in quantities or quantities[name].kind != "load":
                raise self.error(path, f"'{name}' is not a load", hint="statics lists loads")
            return True
        quantity = quantities.get(base[0]) if base is not None else None
        if quantity is not None and quantity.limit and base[1] == 0:
            return True             # one value for the range: any kinematic section
        if quantity is None or quantity.kind == "load" or (
                base[1] != order and quantity.kind not in LEVEL and quantity.kind not in EITHER
                and quantity.kind not in FORCES):
            suffix = ["", "dot", "ddot"][order]
            raise self.error(path, f"'{name}' is not a defined quantity{' rate' if order else ''}",
                             hint=f"define it under 'quantities' and name it <quantity>{suffix}")
        self.rate_of(name, quantity, base[1], path)
        kinematic = ("position", "velocity", "acceleration")
        if quantity.kind in FORCES:
            raise self.error(path, f"'{name}' is not a defined quantity of the {section} section",
                             hint="a joint force is listed under 'statics'")
        allowed = {LEVEL.get(quantity.kind, 0) + base[1]}
        if quantity.kind in EITHER:
            allowed.add(1)
        if order not in allowed:
            raise self.error(path, f"'{name}' is not a defined quantity of the {section} section",
                             hint=f"{_kind_text(quantity.kind)}"
                             f"{' rate' if base[1] else ''} is listed under " +
                             " or ".join(f"'{kinematic[o]}'" for o in sorted(allowed)))
        return True

    def balanced(self, name, quantity, path) -> None:
        """Refuse a joint force in a vibration problem (a file that declares coordinates):
        statics finds it with the unknown load that balances the others, and such a file
        has none; the advice names what it has (its springs' forces at the equilibrium)."""
        if "coordinates" not in self.doc.data or quantity.kind == "load":
            return
        springs = sorted(self.vibration["springs"])
        hint = "remove it from 'statics'"
        if springs:
            hint += f"; the forces at the equilibrium it solves are its springs' " \
                f"(spring_force: {springs[0]}, under 'vibration')"
        raise self.error(path, f"'{name}' is {_kind_text(quantity.kind)}, which statics "
                         "finds with the unknown load that balances the others, and a "
                         "vibration problem (coordinates, no driver) has no unknown load, so "
                         "its joint forces are not solved", hint=hint)

    def rate_of(self, name, quantity, order, path):
        """Refuse a rate the quantity has not (a speed has one, an acceleration none)."""
        if order <= quantity.rates:
            return
        has = {0: "no rates", 1: f"one rate ({quantity.name}dot)"}[quantity.rates]
        if quantity.kind == EXPR:
            raise self.error(path, f"'{name}' is not defined: the expression {quantity.name} "
                             f"has {has}, the rates that every name it reads has",
                             hint=f"ask for '{quantity.name}' itself, or read names that have "
                             "the rate (a load and a limit have none)")
        raise self.error(path, f"'{name}' is not a defined quantity rate: "
                         f"{_kind_text(quantity.kind)} has {has}",
                         hint={"speed": "the rate of a speed is the tangential acceleration; "
                               "ask for tangential_acceleration and normal_acceleration"}.get(
                                   quantity.kind, f"ask for '{quantity.name}' itself"))

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
        item = self.mapping(item, path, {"k", "values", "wrong", "source", "tolerance",
                                         "tolerances"}, ("values",))
        k = item.get("k")
        if k is not None and (isinstance(k, bool) or not isinstance(k, int) or not 0 <= k <= 9):
            raise self.error(path + ("k",), f"k must be a digit 0-9, got {k!r}")
        values = self.mapping(item["values"], path + ("values",))
        wrong = self.mapping(item.get("wrong") or {}, path + ("wrong",))
        for name in wrong:
            if name not in values:
                self.error(path + ("wrong", name), f"'{name}' has no printed value in this key")
        tolerances = self.key_tolerances(item, path, values)
        entries = []
        for name, printed in values.items():
            vpath = path + ("values", name)
            entry = self.block(self.key_entry, name, printed, vpath, quantities, pool,
                               wrong.get(name))
            if entry is not None:
                entries.append(dataclasses.replace(entry, tolerance=tolerances.get(name)))
        return AnswerKey(k, tuple(entries))

    def key_tolerances(self, item, path, values) -> dict:
        """Each printed value's tolerance: its own under ``tolerances``, else the key's
        ``tolerance`` (for every value of the key), else none."""
        default = None
        if "tolerance" in item:
            default = self.block(self.tolerance, item["tolerance"], path + ("tolerance",))
        own = self.block(self.mapping, item.get("tolerances") or {}, path + ("tolerances",))
        result = {name: default for name in values}
        for name, value in (own or {}).items():
            if name not in values:
                self.error(path + ("tolerances", name),
                           f"'{name}' has no printed value in this key")
                continue
            result[name] = self.block(self.tolerance, value, path + ("tolerances", name))
        return result

    def tolerance(self, value, path) -> Tolerance:
        """A tolerance: a number >= 0 (absolute, in the value's display unit) or a
        percentage of the printed value ('2%', '0.5 %')."""
        match = TOLERANCE_PERCENT.search(value) if isinstance(value, str) else None
        if match:
            return Tolerance(float(match.group(1)) / 100.0, True, match.group(1) + "%")
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.error(path, f"a tolerance is a number (absolute, in the value's display "
                             f"unit) or a percentage, got {value!r}",
                             hint="write e.g. 'tolerance: 2%' or 'tolerance: 0.05'")
        number = self.number(value, path)
        if number < 0:
            raise self.error(path, f"a tolerance is at least 0, got {value!r}")
        return Tolerance(number, False, str(self.doc.raw.get(path, value)))

    def key_entry(self, name, printed, path, quantities, pool, wrong) -> KeyEntry:
        line = self.doc.line(path)
        is_point = name in pool and (isinstance(printed, list) or name not in quantities)
        if not is_point:
            base = split_rate(name, quantities)
            if base is None or base[0] not in quantities:
                raise self.error(path, f"the key names '{name}', which the file does not define",
                                 hint="define it under 'quantities' or fix the name")
            if base[1] > quantities[base[0]].rates and quantities[base[0]].kind != "load" \
                    and quantities[base[0]].kind not in VIBRATION:
                raise self.error(path, f"the key names '{name}', which the file does not define: "
                                 f"'{base[0]}' has {quantities[base[0]].rates or 'no'} rate"
                                 f"{'' if quantities[base[0]].rates == 1 else 's'}",
                                 hint=f"compare '{base[0]}' itself")
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


def _kind_text(kind: str) -> str:
    """'a speed', 'an instant centre': a quantity's kind in words."""
    words = kind.replace("_", " ")
    return ("an " if words[0] in "aeiou" else "a ") + words


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
