"""Parsing of the driver and the loads (exactly one of them unknown).

A pressure load is a known pressure p on an area A (or a bore of diameter D,
A = pi D^2 / 4): on a slider of a fixed guide (a piston) it is the force p A at the
slider's point along the guide's direction u (p > 0 pushes along u, p < 0 against
it); on an actuator it is the axial load p A (p > 0 pushes the ends apart).
"""
from __future__ import annotations

import dataclasses
import math

from linkcli.model.exact import cis, hypot, phase, plane
from linkcli.model.dimensions import driver_rate_kind
from linkcli.model.mechanism import FRAME, Driver, Load
from linkcli.input.reader import UNKNOWN
from linkcli.input.machine import MOTOR_KEYS


class LoadsSection:
    """``driver`` and ``loads`` (a mixin of the Parser)."""

    def driver(self, data, units, pool, actuators) -> Driver:
        return self.driven(self.get(data, (), "driver"), ("driver",), units, pool)

    def driven(self, value, path, units, pool, name="q") -> Driver:
        """A driver's coordinate, its value (the figure's) and its rate and accel (0 when
        not given), in SI."""
        spec = self.mapping(value, path, {"angle", "length", "x", "y", "payout", "value", "rate",
                                          "accel"}, ("value",))
        if "payout" in spec:
            return self.payout(spec, path, units, name)
        kind, a, b = self.coordinate_kind(spec, path, pool)
        base = "angle" if kind == "angle" else "length"
        value = self.number(spec["value"], path + ("value",), base, units)
        rate, accel = (self.driver_rate(spec, path, key, base, order, units)
                       for order, key in ((1, "rate"), (2, "accel")))
        if kind == "length" and value <= 0:
            raise self.error(path + ("value",), "a driving length must be positive")
        return Driver(kind, a, b, value, rate, accel, name)

    def drivers(self, data, units, pool) -> tuple:
        """``drivers``: every input of a mechanism of several degrees of freedom, each named
        and driven as ``driver:`` is (its value, rate and accel); the first is also ``q``."""
        path = ("drivers",)
        spec = self.mapping(data["drivers"], path)
        if not spec:
            raise self.error(path, "give at least one driver, e.g. drivers: {theta1: {angle: "
                             "[O, A], value: 30, rate: 10}}")
        out = []
        for name, value in spec.items():
            d = self.block(self.named_driver, name, value, path + (name,), units, pool)
            if d is None:
                continue
            twin = next((o for o in out if o.same_coordinate(d)), None)
            if twin is not None:
                self.error(path + (name,), f"driver '{name}' drives the {d.words}, "
                           f"which driver '{twin.name}' already fixes: one coordinate takes "
                           "one driver", hint=f"drive another coordinate, or remove '{name}'")
                continue
            out.append(d)
        return tuple(out)

    def named_driver(self, name, value, path, units, pool) -> Driver:
        self.name(name, path, what="driver")
        return self.driven(value, path, units, pool, name)

    def driver_rate(self, spec, path, key, base, order, units) -> float:
        """The driver's rate of ``order`` (``key``: rate or accel) in SI, from the file's
        unit of it (units.display); a parameter written as it is a value of that kind."""
        written = spec.get(key, 0)
        value = self.number(written, path + (key,)) * units.display(base, order)[1]
        if isinstance(written, str):
            self.note_use(written, driver_rate_kind(base, order))
        return value

    def coordinates(self, data, units, pool, fixed, moving) -> tuple:
        """``coordinates``: the independent coordinates of a mechanism with several degrees
        of freedom (or of a vibration problem), each measured on the figure unless a
        ``value`` is given."""
        path = ("coordinates",)
        spec = self.mapping(data["coordinates"], path)
        if not spec:
            raise self.error(path, "give at least one coordinate, e.g. theta: {angle: [O, A]}")
        figure = {**fixed, **moving}
        out = []
        for name, value in spec.items():
            c = self.block(self.coordinate, name, value, path + (name,), units, pool, figure)
            if c is not None:
                out.append(c)
        return tuple(out)

    def coordinate_kind(self, spec, path, pool) -> tuple:
        """(kind, a, b) of a driver or coordinate: angle or length of a -> b, x or y of a."""
        kinds = [k for k in ("angle", "length", "x", "y", "payout") if k in spec]
        if len(kinds) != 1:
            raise self.error(path, "give exactly one of angle: [P, Q], length: [P, Q], x: P, y: P"
                             + (", payout: CORD" if "payout" in spec else ""))
        kind = kinds[0]
        if kind in ("angle", "length"):
            return (kind,) + self.pair(spec[kind], path + (kind,), pool)
        return kind, self.name(spec[kind], path + (kind,), pool), None

    def coordinate(self, name, value, path, units, pool, figure) -> Driver:
        self.name(name, path, what="coordinate")
        spec = self.mapping(value, path, {"angle", "length", "x", "y", "value"})
        kind, a, b = self.coordinate_kind(spec, path, pool)
        if b is not None:
            z = figure.get(b, 0j) - figure.get(a, 0j)
            measured = phase(z) if kind == "angle" else abs(z)
        else:
            z = figure.get(a, 0j)
            measured = z.real if kind == "x" else z.imag
        if "value" in spec:
            base = "angle" if kind == "angle" else "length"
            measured = self.number(spec["value"], path + ("value",), base, units)
        return Driver(kind, a, b, measured, 0.0, 0.0, name)

    def loads(self, data, units, pool, bodies, actuators, driver, unknown_needed=True,
              drivers=()) -> dict:
        """``loads``: one unknown (one per driver with several drivers, ``drivers``)."""
        spec = self.mapping(self.get(data, (), "loads", required=False, default={}) or {},
                            ("loads",))
        loads = {}
        for name, value in spec.items():
            load = self.block(self.load, name, value, units, pool, bodies, actuators, driver,
                              data, drivers)
            if load is not None:
                loads[name] = load
        unknown = [n for n, load in loads.items() if load.value is None]
        wanted = max(1, len(drivers))
        if not unknown_needed:
            for n in unknown:
                if getattr(self, "machine", False):
                    self.error(("loads", n), "the motion under given loads needs every load "
                               "known: none is 'unknown'", hint="give its value; the driving "
                               "torque of a prescribed motion is asked in a file of its own")
                else:
                    self.error(("loads", n), "a vibration problem has no unknown load: every "
                               "load is known and acts in the equilibrium", hint="give its value")
        elif loads and len(unknown) != wanted and len(loads) == len(spec):
            which = ", ".join(unknown) if unknown else "none"
            exactly = "exactly one load must be unknown" if wanted == 1 else \
                f"one load per driver must be unknown ({wanted}: " + \
                ", ".join(d.name for d in drivers) + ")"
            self.error(("loads",), f"{exactly}, found {len(unknown)} ({which})",
                       hint="write 'unknown' as the value the statics must find")
        return loads

    def load(self, name, value, units, pool, bodies, actuators, driver, data=None,
             drivers=()) -> Load:
        path = ("loads", name)
        self.name(name, path, what="load")
        value = self.mapping(value, path, {"type", "at", "on", "x", "y", "magnitude", "angle",
                                           "value", "area", "diameter", "over"} | MOTOR_KEYS,
                             ("type",))
        kind = value["type"]
        window = self.window(value, path, units, driver)
        load = self.known_load(name, value, path, kind, units, pool, bodies, actuators, driver,
                               data, drivers)
        if window is not None:
            if not getattr(self, "machine", False):
                raise self.error(path + ("over",), "'over' switches a load on over a window of "
                                 "the driver in the motion under given loads (machine dynamics)",
                                 hint="ask for the motion (docs/machines.md) or remove it")
            if load.value is None:
                raise self.error(path + ("over",), "an unknown load has no window")
            load = dataclasses.replace(load, window=window)
        return load

    def known_load(self, name, value, path, kind, units, pool, bodies, actuators, driver,
                   data, drivers=()) -> Load:
        """The load of type ``kind`` without its window."""
        for key in MOTOR_KEYS:
            if key in value and kind != "motor":
                raise self.error(path + (key,), f"'{key}' is a motor's characteristic")
        if kind in ("motor", "brake"):
            return self.turning_load(name, value, path, kind, units, bodies, actuators, driver)
        if kind == "pressure":
            return self.pressure(name, value, path, units, bodies, actuators, data)
        for key in ("area", "diameter"):
            if key in value:
                raise self.error(path + (key,), f"'{key}' is for pressure loads",
                                 hint="type: pressure, with value (the pressure) and area or "
                                 "diameter")
        if kind == "force":
            return self.force(name, value, path, units, pool)
        if kind not in ("torque", "axial", "driver"):
            raise self.error(path + ("type",), f"unknown load type {kind!r}",
                             hint="force, torque, axial, driver, pressure, motor or brake")
        for key in ("at", "x", "y", "magnitude", "angle"):
            if key in value:
                raise self.error(path + (key,), f"'{key}' is for forces")
        target = None
        if kind == "torque":
            pool_b = {n for n, b in bodies.items() if b.kind in ("link", "block")} | set(actuators)
            target = self.name(self.get(value, path, "on"), path + ("on",), pool_b, "link")
        elif kind == "axial":
            target = self.name(self.get(value, path, "on"), path + ("on",), actuators, "actuator")
        elif drivers:                     # several drivers: the one it acts on
            names = {d.name: d for d in drivers}
            target = self.name(self.get(value, path, "on"), path + ("on",), set(names),
                               "driver")
            driver = names[target]
        elif "on" in value:
            raise self.error(path + ("on",), "the driver load acts on the driver coordinate")
        driver_unit = "torque" if driver is None or driver.kind == "angle" else "force"
        unit = {"torque": "torque", "axial": "force", "driver": driver_unit}[kind]
        amount = self.amount(self.get(value, path, "value"), path + ("value",), unit, units)
        return Load(name, kind, target, 1, amount)

    def turning_load(self, name, value, path, kind, units, bodies, actuators, driver) -> Load:
        """A motor (its characteristic) or a brake (a torque >= 0 against the turning) on a
        body of the mechanism."""
        for key in ("at", "x", "y", "magnitude", "angle", "area", "diameter"):
            if key in value:
                raise self.error(path + (key,), f"'{key}' is not a key of a {kind}")
        pool_b = {n for n, b in bodies.items() if b.kind in ("link", "block")} | set(actuators)
        target = self.name(self.get(value, path, "on"), path + ("on",), pool_b, "link")
        if kind == "motor":
            if "value" in value:
                raise self.error(path + ("value",), "a motor's torque is its characteristic",
                                 hint="stall and no_load, speeds and torques, or torque")
            return Load(name, "motor", target, 1, 0.0, motor=self.motor(value, path, units,
                                                                        driver))
        amount = self.number(self.get(value, path, "value"), path + ("value",), "torque", units)
        if not amount >= 0:
            raise self.error(path + ("value",), f"a brake's torque opposes the motion: give its "
                             f"size (>= 0), got {value['value']!r}")
        return Load(name, "brake", target, 1, amount)

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
            return Load(name, "force", at, cis(angle), amount)
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
        magnitude = hypot(fx, fy)
        direction = plane(fx, fy) / magnitude if magnitude else 1
        return Load(name, "force", at, direction, magnitude)

    # --- pressure on a piston or in an actuator ---------------------------------------
    def pressure(self, name, value, path, units, bodies, actuators, data) -> Load:
        """p A as a force along a fixed guide at the slider's point, or as an axial load."""
        for key in ("at", "x", "y", "magnitude", "angle"):
            if key in value:
                raise self.error(path + (key,), f"'{key}' is for forces: a pressure acts along "
                                 "the slider's guide or the actuator")
        sliders = {n for n, b in bodies.items() if b.kind == "block"}
        target = self.name(self.get(value, path, "on"), path + ("on",),
                           sliders | set(actuators), "body")
        raw = self.get(value, path, "value")
        if raw == UNKNOWN:
            raise self.error(path + ("value",), "a pressure load is known: give the pressure",
                             hint="to find the force on the piston, make a force along the "
                             "guide or the driver's load unknown")
        area, bore = self.area(value, path, units)
        pressure = self.number(raw, path + ("value",), "pressure", units)
        force = pressure * area
        stated = (pressure, area, bore)
        if not math.isfinite(force):
            raise self.error(path + ("value",), f"the force p A is not a finite number "
                             f"(p = {raw!r})", hint="check the pressure and the area's units")
        if target in actuators:
            return Load(name, "axial", target, 1, force, stated)
        block = bodies[target]
        if block.guide.carrier != FRAME:
            raise self.error(path + ("on",), f"slider {target} runs on a guide carried by "
                             f"{block.guide.carrier}: a pressure acts on a piston in a fixed "
                             "cylinder", hint="put the pressure on an actuator for a moving "
                             "cylinder")
        direction = self.fixed_guide_direction(data, target, units)
        return Load(name, "force", block.points[0], direction, force, stated)

    def area(self, value, path, units) -> tuple:
        """(A in m^2, the bore D in m or None) from ``area`` (area unit) or ``diameter``
        (length unit): A = pi D^2 / 4."""
        given = [k for k in ("area", "diameter") if k in value]
        if len(given) != 1:
            raise self.error(path, "a pressure load needs exactly one of 'area' or 'diameter'",
                             hint="the piston's area, or its bore: e.g. diameter: 500")
        key = given[0]
        size = self.number(value[key], path + (key,), "area" if key == "area" else "length",
                           units)
        if not size > 0:
            raise self.error(path + (key,), f"a piston's {key} must be positive, got "
                             f"{value[key]!r}")
        return (size, None) if key == "area" else (math.pi * size * size / 4.0, size)

    def fixed_guide_direction(self, data, slider, units) -> complex:
        """The unit direction of slider ``slider``'s fixed guide as its file wrote it: +y for
        {x: c}, +x for {y: c}, the angle of {through, angle}, P -> Q of {along: [P, Q]}."""
        spec = data["sliders"][slider]["guide"]
        path = ("sliders", slider, "guide")
        if "x" in spec:
            return 1j
        if "y" in spec:
            return 1
        if "angle" in spec:
            return cis(self.number(spec["angle"], path + ("angle",), "angle", units))
        p, q = spec["along"]
        frame = data["frame"]
        z = self.xy(frame[q], ("frame", q), units) - self.xy(frame[p], ("frame", p), units)
        return z / abs(z)

