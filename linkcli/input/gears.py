"""Reading of ``gears:`` (gears by their teeth) and of the pair quantities they answer (a
mixin of the Parser; docs/schema.md, "gears"):

    gears:
      sun:    {teeth: 20, module: 2}                  # module in the length unit
      planet: {teeth: 40, module: 2, addendum: 2}     # addendum: one module by default
      ring:   {teeth: 100, module: 2, internal: true} # teeth cut inside: an annulus
      # pinion: {teeth: 16, diametral_pitch: 8}       # teeth per unit of pitch diameter
      # pressure_angle: 20 (in the angle unit) by default
    rolling:
      mesh: {disc: planet, on: {disc: sun}}           # radii: the pitch radii m z / 2
      rim:  {disc: planet, on: {circle: O, gear: ring}}
    quantities:
      a:  {centre_distance: [sun, planet]}
      e:  {contact_ratio: [sun, planet]}
      zm: {min_teeth: sun, with: planet}              # no 'with': against a rack

A gear's name is the name of its disc (a link whose first point is its centre) when it
turns in the mechanism; a fixed ring or a gear asked about only needs no link.

Errors, each at its key and line (exit 2): teeth that are not a whole positive number; a
module, a diametral pitch or an addendum that is not positive; neither or both of module
and diametral pitch; a pressure angle outside (0, 45) degrees; gears in mesh (a rolling
contact, a pair quantity) whose modules or pressure angles differ, each named with its
value; a radius that is not the gear's pitch radius.
"""
from __future__ import annotations

import math

from linkcli.model.dimensions import PER_LENGTH
from linkcli.model.gears import Gear
from linkcli.model.mechanism import Quantity
from linkcli.model.units import LENGTH
from linkcli.input.reader import _Skip

#: the quantities of a pair of gears, each the YAML key that asks for it
GEARING = ("centre_distance", "contact_ratio", "min_teeth")
#: relative difference under which two modules, angles or radii are the same
SAME = 1e-9
DEFAULT_PRESSURE_ANGLE = 20.0      # degrees


def module_of_pitch(pitch, unit_length):
    """m = 1 / P of a diametral pitch P in teeth per length unit of pitch diameter, the
    unit being ``unit_length`` metres: m = unit_length / P (m)."""
    return unit_length / pitch


class GearsSection:
    """``gears:`` and the quantities of :data:`GEARING` (a mixin of the Parser)."""

    def gears(self, data, units) -> dict:
        spec = self.mapping(self.get(data, (), "gears", required=False, default={}) or {},
                            ("gears",))
        out = {}
        self.gears_failed = set()
        for name, value in spec.items():
            gear = self.block(self.gear, name, value, ("gears", name), units)
            if gear is not None:
                out[name] = gear
            else:
                self.gears_failed.add(name)
        return out

    def known_gear(self, name, path) -> str:
        """``name`` as a gear of ``gears:``; a gear whose own entry failed is skipped (its
        error is reported already)."""
        if name in getattr(self, "gears_failed", ()):
            raise _Skip()
        return self.name(name, path, set(self.gear_table), "gear")

    def gear(self, name, value, path, units) -> Gear:
        self.name(name, path, what="gear")
        spec = self.mapping(value, path, {"teeth", "module", "diametral_pitch", "addendum",
                                          "pressure_angle", "internal"}, ("teeth",))
        teeth = float(self.number(spec["teeth"], path + ("teeth",)))
        if teeth != round(teeth) or teeth <= 0:
            raise self.error(path + ("teeth",), "a number of teeth is a whole number above 0, "
                             f"got {teeth:g}", hint="count the teeth of the gear")
        given = [k for k in ("module", "diametral_pitch") if k in spec]
        if len(given) != 1:
            raise self.error(path, "give the tooth size: either module (a length) or "
                             "diametral_pitch (teeth per unit of pitch diameter)" +
                             (", not both" if given else ""))
        key = given[0]
        length = units.names["length"]
        shown = self.number(spec[key], path + (key,))
        if float(shown) <= 0:
            raise self.error(path + (key,), f"must be positive, got {spec[key]!r}")
        if key == "module":
            module = self.positive(spec[key], path + (key,), units)
            pitch = (key, float(shown), length)
        else:
            per = units.factor("length") if self.symbolic is None else \
                self.symbolic.convert(1, "length", units)
            module = module_of_pitch(shown, per)    # a length read, as any other
            self.in_range(float(module), path + (key,), units)
            pitch = (key, float(shown), f"1/{length}")
            if isinstance(spec[key], str):
                self.note_use(spec[key], PER_LENGTH)
        addendum = module if "addendum" not in spec else \
            self.positive(spec["addendum"], path + ("addendum",), units)
        phi = math.radians(DEFAULT_PRESSURE_ANGLE) if "pressure_angle" not in spec else \
            self.number(spec["pressure_angle"], path + ("pressure_angle",), "angle", units)
        if not 0 < float(phi) < math.pi / 4:
            raise self.error(path + ("pressure_angle",), "a pressure angle lies between 0 and "
                             f"45 degrees, got {spec.get('pressure_angle')!r}",
                             hint="14.5, 20 and 25 degrees are the usual ones")
        internal = spec.get("internal", False)
        if not isinstance(internal, bool):
            raise self.error(path + ("internal",), f"internal is true or false, got "
                             f"{internal!r}")
        return Gear(name, int(round(teeth)), module, phi, addendum, internal, pitch,
                    self.doc.line(path))

    def gear_of(self, spec, path, disc):
        """The gear ``spec`` names (``gear:``, one of several on a shaft), else the disc's
        own gear when one has its name (None: no gear)."""
        if "gear" in spec:
            return self.known_gear(spec["gear"], path + ("gear",))
        if disc in getattr(self, "gears_failed", ()):
            raise _Skip()
        return disc if disc in self.gear_table else None

    def pitch_radius(self, spec, path, units, gear_name, what="disc"):
        """The radius of ``spec`` (a rolling contact or its track): the one given, which
        must then be the pitch radius of ``gear_name`` when that names a gear, or that
        pitch radius when none is given."""
        gear = self.gear_table.get(gear_name) if gear_name else None
        if "radius" not in spec:
            if gear is None:
                raise self.error(path, "missing key 'radius'",
                                 hint=f"give the {what}'s radius, or name its gear ('gear:', "
                                 "a gear of 'gears:' with its teeth and module)")
            return gear.radius
        radius = self.positive(spec["radius"], path + ("radius",), units)
        if gear is not None and abs(float(radius) - gear.radius) > SAME * gear.radius:
            unit, f = self.length_unit
            raise self.error(path + ("radius",), f"the radius {float(radius) / f:.6g} {unit} "
                             f"is not the pitch radius of gear {gear_name}, m z / 2 = "
                             f"{gear.radius / f:.6g} {unit} ({gear.pitch_text()}, "
                             f"{gear.teeth} teeth)", hint="leave out the radius: the teeth "
                             "give it")
        return radius

    def meshing(self, path, first, second):
        """Refuse two gears in mesh whose teeth differ in size or in pressure angle."""
        a, b = (self.gear_table.get(g) if g else None for g in (first, second))
        if a is None or b is None:
            return
        if abs(a.module - b.module) > SAME * max(a.module, b.module):
            if a.pitch[0] == b.pitch[0]:
                what = {"module": "modules", "diametral_pitch": "diametral pitches"}[a.pitch[0]]
                hint = "give both gears one"
            else:
                unit, f = self.length_unit
                what = "modules"
                hint = (f"their modules are {a.module / f:.6g} and {b.module / f:.6g} {unit}: "
                        "give both gears one")
            raise self.error(path, f"gears {first} ({a.pitch_text()}) and {second} "
                             f"({b.pitch_text()}) do not mesh: teeth in mesh have equal "
                             f"{what}", hint=hint + f" {a.pitch[0].replace('_', ' ')}")
        if abs(a.pressure_angle - b.pressure_angle) > SAME:
            raise self.error(path, f"gears {first} and {second} do not mesh: their pressure "
                             f"angles are {math.degrees(a.pressure_angle):.6g} and "
                             f"{math.degrees(b.pressure_angle):.6g} deg",
                             hint="teeth in mesh have one pressure angle")

    def gear_quantity(self, name, value, path) -> Quantity:
        """centre_distance, contact_ratio: [GEAR, GEAR]; min_teeth: GEAR (with: GEAR)."""
        value = self.mapping(value, path, set(GEARING) | {"with", "unit"})
        kind, where, arg = self.one_kind(value, path, GEARING)
        gears = set(self.gear_table)
        if not gears:
            raise self.error(where, f"{kind.replace('_', ' ')} is of gears: give their teeth "
                             "under 'gears:'", hint="gears: {pinion: {teeth: 20, module: 2}}")
        if "with" in value and kind != "min_teeth":
            raise self.error(path + ("with",), "'with' is for min_teeth")
        if "unit" in value and kind != "centre_distance":
            raise self.error(path + ("unit",), f"{kind.replace('_', ' ')} is a pure number")
        unit = value.get("unit")
        if unit is not None and unit not in LENGTH:
            raise self.error(path + ("unit",), f"unknown unit {unit!r} for a length",
                             hint="use one of " + ", ".join(LENGTH))
        line = self.doc.line(path)
        if kind == "min_teeth":
            a = self.known_gear(arg, where)
            b = None
            if "with" in value:
                b = self.known_gear(value["with"], path + ("with",))
                if a == b:
                    raise self.error(path + ("with",), "a gear meshes with another gear")
                self.meshing(path, a, b)
            return Quantity(name, kind, a, b, line=line)
        if isinstance(arg, list) and any(g in self.gears_failed for g in arg):
            raise _Skip()
        a, b = self.pair(arg, where, gears, "gear")
        self.meshing(where, a, b)
        if self.gear_table[a].internal and self.gear_table[b].internal:
            raise self.error(where, f"gears {a} and {b} are both internal: a ring meshes with "
                             "an external gear")
        return Quantity(name, kind, a, b, unit=unit, line=line)
