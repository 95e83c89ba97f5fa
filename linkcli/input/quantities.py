"""Reading of ``quantities:``: the named values a report and a key may ask for.

Every file has the driver's coordinate ``q``, the coordinates ``xP`` and ``yP`` of each
point and its loads by name; ``quantities:`` defines the others, each of exactly one kind
(docs/schema.md, 'quantities').  :class:`QuantitiesSection` (a mixin of the Parser) reads
the section, claims every name and the names of its rates (NAMEdot, NAMEddot), reads the
geometric kinds itself (angle, length, x, y, load: their points, load and unit) and sends
the others to their readers: speeds, accelerations and the like (``textbook``), joint
forces (``forces``), limits of the motion (``limits``), the answers of a vibration problem
(``vibration``, ``oscillation``) and expressions (``derived``).  The tables of kinds here
(``LEVEL``, ``EITHER``, ``FORCES``) say where the report lists each kind.

Errors, each an :class:`~linkcli.errors.InputError` at the quantity's YAML path and line,
collected and raised together (exit 2): a name already taken, or one whose rates' names are
(a name ending in 'd' or 'dot'); a name ending in 'dot'; not exactly one kind; a unit
unknown for the kind, or given to a velocity ratio; 'signed', 'point', 'axis' or
'component' where the kind has none; a velocity ratio of an undefined quantity or of one
that is not a position quantity.
"""
from __future__ import annotations

import dataclasses

from linkcli.model.mechanism import LIMITS, VIBRATION, Quantity
from linkcli.model.units import ANGLE, FORCE, LENGTH, TORQUE
from linkcli.input.derived import EXPR
from linkcli.input.gears import GEARING
from linkcli.input.oscillation import OSCILLATION
from linkcli.input.efficiency import EFFICIENCY
from linkcli.input.machine import MACHINE

#: the kinds of a geometric quantity, each the YAML key that asks for it
GEOMETRY = ("angle", "length", "x", "y", "load", "speed", "acceleration",
            "tangential_acceleration", "normal_acceleration", "along", "normal_to", "relative",
            "relative_speed", "relative_acceleration", "rotation", "between", "instant_centre",
            "instant_centre_distance", "reaction", "slider_force", "velocity_ratio",
            "least_speed", "least_speed_at", "tension", "contact_force")
PROJECTIONS = ("along", "normal_to")
ANGULAR = ("angle", "rotation", "between")
#: the components of a joint force that are projections on an axis (``axis:``)
PROJECTED = ("along", "normal")
#: quantities whose value is itself a rate: a speed is listed with the velocities (its
#: rate with the accelerations), an acceleration with the accelerations
LEVEL = {"speed": 1, "relative_speed": 1, "acceleration": 2, "tangential_acceleration": 2,
         "normal_acceleration": 2, "relative_acceleration": 2, "least_speed": 1}
#: quantities of the position alone, listed with the positions or the velocities
EITHER = ("instant_centre", "instant_centre_distance", "velocity_ratio", "least_speed_at")
#: forces, listed with the statics
FORCES = ("load", "reaction", "slider_force", "tension", "contact_force") + EFFICIENCY
#: the quantities a velocity ratio may be of: those whose rate is linear in the velocities
RATIO_OF = ("q", "x", "y", "angle", "length", "along", "normal_to", "relative", "rotation",
            "between")
RATES = (0, 1, 2)
SUFFIX = ("", "dot", "ddot")


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


def _same(q: Quantity, automatic: Quantity) -> bool:
    """Whether ``q`` defines the automatic quantity again (a file may, to give it a unit)."""
    return dataclasses.replace(q, unit=None) == automatic

def kind_text(kind: str) -> str:
    """'a speed', 'an instant centre': a quantity's kind in words."""
    words = kind.replace("_", " ")
    return ("an " if words[0] in "aeiou" else "a ") + words


class QuantitiesSection:
    """``quantities`` (a mixin of the Parser)."""

    def quantities(self, data, pool, loads, driver, drivers=()) -> dict:
        """Every quantity of the file: q (the first driver), xP and yP of each point, each
        load, each of ``drivers`` (its coordinate: an angle, a length, an x or y) by its
        name, then the file's ``quantities:``."""
        spec = self.mapping(self.get(data, (), "quantities", required=False, default={}) or {},
                            ("quantities",))
        quantities = {"q": Quantity("q", "q")}
        self.ratio_drivers = drivers
        names = _Names()
        names.claim("q", RATES, "the driver's coordinate", "q")
        for d in drivers:
            if d.kind in "xy" and d.name == d.kind + d.a:
                continue            # the automatic xP itself
            if names.claim(d.name, RATES, f"the driver {d.name}", f"driver '{d.name}'"):
                self.error(("drivers", d.name), f"the driver's name '{d.name}' is taken by the "
                           "first driver's coordinate 'q' or its rates",
                           hint="call it another name")
            quantities[d.name] = Quantity(d.name, d.kind, d.a, d.b)
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

    def quantity(self, name, value, pool, loads, driver=None) -> Quantity:
        path = ("quantities", name)
        self.name(name, path, what="quantity")
        if name.endswith("dot"):
            raise self.error(path, "quantity names must not end in 'dot'",
                             hint="rates are named automatically: phi1 -> phi1dot, phi1ddot")
        if isinstance(value, dict) and any(k in value for k in MACHINE):
            return self.machine_quantity(name, value, path)
        if isinstance(value, dict) and any(k in value for k in OSCILLATION):
            return self.oscillation_quantity(name, value, path, pool)
        if isinstance(value, dict) and any(k in value for k in VIBRATION):
            return self.with_part(name, value, path, pool)
        if isinstance(value, dict) and any(k in value for k in LIMITS):
            return self.limit_quantity(name, value, path)
        if isinstance(value, dict) and EXPR in value:
            return self.expression_quantity(name, value, path)
        if isinstance(value, dict) and "clutch" in value:
            return self.clutch_quantity(name, value, path)
        if isinstance(value, dict) and any(k in value for k in EFFICIENCY):
            return self.efficiency_quantity(name, value, path, loads)
        if isinstance(value, dict) and any(k in value for k in GEARING):
            return self.gear_quantity(name, value, path)
        value = self.mapping(value, path, set(GEOMETRY) | {"component", "unit", "point",
                                                           "signed", "axis", "driver"})
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
        if "driver" in value:
            self.ratio_driver(value["driver"], kind, path + ("driver",))
        if "point" in value and kind not in PROJECTIONS:
            raise self.error(path + ("point",), "'point' is for along and normal_to")
        if "axis" in value and not (kind == "reaction" and value.get("component") in PROJECTED):
            raise self.error(path + ("axis",), "'axis' is for the along and normal components "
                             "of a reaction", hint="{reaction: [P, BODY], component: normal, "
                             "axis: OTHER}")
        if kind in GEOMETRY[5:]:
            line = self.doc.line(path)
            q = dataclasses.replace(self.textbook_quantity(name, kind, value, path, pool),
                                    unit=unit, signed=value.get("signed", False), line=line)
            return dataclasses.replace(q, b=value["driver"]) if "driver" in value else q
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

    def ratio_driver(self, name, kind, path) -> None:
        """``driver:`` of a velocity ratio: one of ``drivers:`` (the ratio per its rate)."""
        if kind != "velocity_ratio":
            raise self.error(path, "'driver' is for a velocity ratio (of several drivers)")
        drivers = [d.name for d in self.ratio_drivers]
        if len(drivers) < 2:
            raise self.error(path, "'driver' picks one of several drivers ('drivers:'); this "
                             "file has one", hint="leave it out: the ratio is per q")
        self.name(name, path, set(drivers), "driver")

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
            raise self.error(path, f"the velocity ratio of '{q.a}' ({kind_text(kind)}) "
                             "is not defined: it is d(NAME)/dq of a position quantity",
                             hint="give an angle, length, coordinate, projection, relative "
                             "coordinate, rotation or angle between vectors")
        return True
