"""Reader of the ``dynamics:`` section: gravity, masses and inertias, friction, rolling discs,
friction circles.

It runs after the core sections, on the mechanism they built, so that every
name it meets is checked against the mechanism's points, bodies and loads.
"""
from __future__ import annotations

import math

from ..model.dynamics import STANDARD_SIDE, Disc, Dynamics, MassBody, PinFriction
from ..model.mechanism import FRAME

# the words YAML 1.1 reads as booleans when unquoted, for a gravity written quoted
YAML_BOOLEANS = {"off": False, "no": False, "false": False, "on": True, "yes": True,
                 "true": True}


class DynamicsReader:
    def __init__(self, parser, mech, skip):
        self.p = parser
        self.mech = mech
        self.skip = skip
        self.units = mech.units

    def block(self, func, *args):
        try:
            return func(*args)
        except self.skip:
            return None

    def amount(self, value, path, kind, allow_zero=True, what=None):
        number = self.p.number(value, path, kind, self.units)
        if not math.isfinite(number):
            raise self.p.error(path, f"must be a finite number, got {value!r}")
        if number < 0 or (number == 0 and not allow_zero):
            what = what or {"mass": "a mass", "inertia": "a moment of inertia"}[kind]
            bound = "> 0" if not allow_zero else ">= 0"
            raise self.p.error(path, f"{what} cannot be {'negative' if number < 0 else 'zero'}, "
                               f"got {value!r}", hint=f"it must be {bound}")
        return number

    def run(self, spec) -> Dynamics:
        path = ("dynamics",)
        dyn = Dynamics()
        try:
            spec = self.p.mapping(spec, path, {"gravity", "bodies", "masses", "friction",
                                               "discs", "friction_circles"}) \
                if spec is not None else {}
        except self.skip:
            return dyn
        dyn.gravity = self.block(self.gravity, spec.get("gravity"), path + ("gravity",)) or 0j
        for name, value in self.section(spec, "bodies"):
            body = self.block(self.body, name, value, path + ("bodies", name))
            if body is not None:
                dyn.bodies[name] = body
        for name, value in self.section(spec, "masses"):
            p = path + ("masses", name)
            if self.block(self.p.name, name, p, set(self.mech.points)) is not None:
                mass = self.block(self.amount, value, p, "mass")
                if mass is not None:
                    dyn.masses[name] = mass
        for name, value in self.section(spec, "friction"):
            mu = self.block(self.friction, name, value, path + ("friction", name))
            if mu is not None:
                dyn.friction[name] = mu
        for name, value in self.section(spec, "discs"):
            disc = self.block(self.disc, name, value, path + ("discs", name), dyn)
            if disc is not None:
                dyn.discs[name] = disc
        if spec.get("friction_circles") is not None:
            dyn.pins = self.block(self.friction_circles, spec["friction_circles"],
                                  path + ("friction_circles",)) or {}
        for disc in dyn.discs.values():
            where = path + ("discs", disc.name, "center")
            if disc.slider in dyn.bodies:
                self.p.error(where, f"slider {disc.slider} is the disc {disc.name}: give its mass "
                             "under 'discs' only", hint=f"remove bodies.{disc.slider}")
            if disc.slider in dyn.friction:
                self.p.error(where, f"a disc rolling without slipping has no sliding friction "
                             f"(friction.{disc.slider})", hint="remove the friction entry")
        return dyn

    def section(self, spec, key):
        value = spec.get(key)
        if value is None:
            return []
        try:
            return list(self.p.mapping(value, ("dynamics", key)).items())
        except self.skip:
            return []

    def gravity(self, value, path) -> complex:
        """off/false/0: none; a number g (m/s^2, along -y); or {g, angle}.  'off' quoted (as
        YAML writers quote it) is off as unquoted, and so are the other booleans."""
        if isinstance(value, str) and value.strip().lower() in YAML_BOOLEANS:
            value = YAML_BOOLEANS[value.strip().lower()]
        if value is None or value is False:
            return 0j
        if value is True:
            raise self.p.error(path, "give gravity's value g in m/s^2, e.g. 'gravity: 9.81'")
        angle = -math.pi / 2
        if isinstance(value, dict):
            spec = self.p.mapping(value, path, {"g", "angle"}, ("g",))
            g = self.amount(spec["g"], path + ("g",), None, what="gravity's g")
            if "angle" in spec:
                angle = self.p.number(spec["angle"], path + ("angle",), "angle", self.units)
        else:
            g = self.amount(value, path, None, what="gravity's g")
        x, y = math.cos(angle), math.sin(angle)     # exact zeros along the axes
        return g * complex(0.0 if abs(x) < 1e-15 else x, 0.0 if abs(y) < 1e-15 else y)

    def body(self, name, value, path) -> MassBody:
        bodies = self.mech.bodies
        if not isinstance(name, str) or name not in bodies or name == FRAME:
            known = ", ".join(sorted(bodies)) or "none"
            raise self.p.error(path, f"undefined body '{name}'",
                               hint=f"links, sliders and actuator halves: {known}")
        spec = self.p.mapping(value, path, {"mass", "inertia", "center"})
        mass = self.block(self.amount, spec.get("mass", 0), path + ("mass",), "mass")
        inertia = self.block(self.amount, spec.get("inertia", 0), path + ("inertia",), "inertia")
        if mass is None or inertia is None:
            raise self.skip()
        if "center" not in spec:
            if mass > 0:
                raise self.p.error(path, "a body with mass needs its centre of mass 'center'",
                                   hint="a point of the body, or [x, y] in its local coordinates")
            return MassBody(name, mass, inertia, 0j)
        return MassBody(name, mass, inertia, self.center(bodies[name], spec["center"],
                                                         path + ("center",)))

    def center(self, body, value, path) -> complex:
        if isinstance(value, str):
            self.p.name(value, path, set(self.mech.points))
            if value not in body.points:
                raise self.p.error(path, f"'{value}' is not a point of {body.name}",
                                   hint=f"its points: {', '.join(body.points)}; or give "
                                   "[x, y] in its local coordinates")
            return body.local[value]
        return self.p.xy(value, path, self.units)

    def friction(self, name, value, path) -> float:
        blocks = {n for n, b in self.mech.bodies.items() if b.kind == "block"}
        self.p.name(name, path, blocks, "slider")
        if isinstance(value, dict):
            value = self.p.mapping(value, path, {"mu"}, ("mu",))["mu"]
            path = path + ("mu",)
        mu = self.p.number(value, path)
        if not math.isfinite(mu) or mu < 0:
            raise self.p.error(path, f"a friction coefficient cannot be negative, got {value!r}",
                               hint="mu >= 0; 0 means no friction")
        return mu

    def disc(self, name, value, path, dyn) -> Disc:
        self.p.name(name, path, what="disc")
        spec = self.p.mapping(value, path, {"center", "radius", "mass", "inertia", "side",
                                            "rolling_resistance"}, ("center", "radius"))
        center = self.p.name(spec["center"], path + ("center",), set(self.mech.points))
        block = next((b for b in self.mech.bodies.values()
                      if b.kind == "block" and b.points[0] == center), None)
        if block is None or block.guide.carrier != FRAME:
            where = "is not on a line" if block is None else \
                f"runs on a guide carried by {block.guide.carrier}, not on a fixed line"
            raise self.p.error(path + ("center",), f"rolling disc {name}: centre {center} {where}",
                               hint=f"make {center} the point of a slider on a fixed guide: "
                               "the line the centre runs on, parallel to the ground")
        if len(block.points) > 1:
            raise self.p.error(path + ("center",), f"slider {block.name} carries "
                               f"{', '.join(block.points[1:])}; as a rolling disc it spins, so "
                               "it can carry only its centre")
        if any(d.slider == block.name for d in dyn.discs.values()):
            raise self.p.error(path + ("center",), f"slider {block.name} already is a disc")
        radius = self.amount(spec["radius"], path + ("radius",), "length", allow_zero=False,
                             what="a disc's radius")
        mass = self.amount(spec.get("mass", 0), path + ("mass",), "mass")
        inertia = self.amount(spec.get("inertia", 0), path + ("inertia",), "inertia")
        side = spec.get("side", "left")
        if side not in STANDARD_SIDE:
            raise self.p.error(path + ("side",), f"side is 'left' or 'right', got {side!r}",
                               hint="the side of the ground line the centre is on, looking "
                               "along the guide (left = above a floor run along +x)")
        for load in self.mech.loads.values():
            if load.kind == "torque" and load.target == block.name and load.value is None:
                self.p.error(("loads", load.name), "the unknown load cannot be a torque on the "
                             f"rolling disc {name}", hint="make a force or the driver unknown")
        resistance = self.amount(spec.get("rolling_resistance", 0), path + ("rolling_resistance",),
                                 "length", what="a rolling resistance")
        return Disc(name, block.name, center, radius, STANDARD_SIDE[side], mass, inertia,
                    resistance)

    # --- friction circles at the pins -------------------------------------------------
    def friction_circles(self, value, path) -> dict:
        """A radius rho (length unit, >= 0) for every pin, or {PIN: rho}; a pin of exactly
        two bodies (the frame counts at a fixed pivot)."""
        pins = self.pins()
        if isinstance(value, dict):
            spec = self.p.mapping(value, path)
            out = {}
            for point, radius in spec.items():
                where = path + (point,)
                if self.block(self.p.name, point, where, set(pins), "pin") is None:
                    continue
                pin = self.block(self.pin_friction, point, pins[point], radius, where)
                if pin is not None:
                    out[point] = pin
            return out
        radius = self.amount(value, path, "length", what="a friction circle's radius")
        return {point: self.pin_friction(point, bodies, value, path, radius)
                for point, bodies in pins.items()}

    def pins(self) -> dict:
        """Point -> the bodies that meet there, the frame first at a fixed pivot, for every
        point of two or more bodies."""
        out = {}
        for body in self.mech.bodies.values():
            for point in body.points:
                out.setdefault(point, []).append(body.name)
        return {p: ([FRAME] if p in self.mech.fixed else []) + bodies
                for p, bodies in out.items() if len(bodies) + (p in self.mech.fixed) >= 2}

    def pin_friction(self, point, bodies, value, path, radius=None) -> PinFriction:
        if len(bodies) != 2:
            hint = f"leave {point} out" if radius is None else \
                "give the radius of each two-body pin: {A: 2, B: 2}"
            raise self.p.error(path, f"pin {point} joins {len(bodies)} bodies "
                               f"({', '.join(bodies)}): a friction circle acts between two",
                               hint=hint)
        if radius is None:
            radius = self.amount(value, path, "length", what="a friction circle's radius")
        kinds = {b: ("frame" if b == FRAME else self.mech.bodies[b].kind) for b in bodies}
        holder = next((b for b in bodies if kinds[b] != "link"), bodies[0])
        other = next(b for b in bodies if b != holder)
        return PinFriction(point, holder, other, radius)
