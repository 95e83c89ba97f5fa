"""Readers of the vibration sections: ``springs``, ``dampers``, ``excitation``,
``initial`` and ``equilibrium``.

They run after the core sections, on the mechanism they built, so that every
point, body and coordinate named is checked against it.

    springs:
      k1: {between: [A, C], k: 2000}                     # unstretched in the figure
      k2: {between: [A, C], k: 2000, free_length: 150}   # file length units
      k3: {between: [A, C], k: 2000, preload: 50}        # tension in the figure (force units)
      k4: {between: [A, C], k: 2000, preload: static}    # as equilibrium in the figure needs
      kh: {between: [A, C], k: 2000, along: x}           # deforms only along x (y, or an angle)
      kt: {bodies: [frame, rod], k: 30}                  # torsional
    dampers:
      r1: {between: [A, C], c: 20}
    excitation:
      frequency: 12                                      # Omega (units.frequency)
      forces: {F: {at: A, x: 10}, C: {on: rod, torque: 2, phase: 90}}
      supports: {base: {coordinate: s, amplitude: 5}}
      road: {coordinate: s, amplitude: 10, wavelength: 5, speed: 20}
    initial: {theta: 2, theta_dot: 0}                    # offsets from the equilibrium
    equilibrium: solve | figure
"""
from __future__ import annotations

import math

from linkcli.model.exact import cis, hypot, plane, times_pi
from linkcli.model import elements as el
from linkcli.model.mechanism import FRAME


class ElementsReader:
    def __init__(self, parser, mech, skip):
        self.p = parser
        self.mech = mech
        self.skip = skip
        self.units = mech.units
        self.coordinates = {c.name: j for j, c in enumerate(mech.coordinates)}

    def block(self, func, *args):
        try:
            return func(*args)
        except self.skip:
            return None

    def run(self, data) -> el.Elements:
        out = el.Elements()
        for name, value in self.section(data, "springs"):
            spring = self.block(self.spring, name, value, ("springs", name))
            if spring is not None:
                out.springs[name] = spring
        for name, value in self.section(data, "dampers"):
            damper = self.block(self.damper, name, value, ("dampers", name))
            if damper is not None:
                out.dampers[name] = damper
        if data.get("excitation") is not None:
            self.block(self.excitation, data["excitation"], ("excitation",), out)
        if data.get("initial") is not None:
            out.initial = self.block(self.initial, data["initial"], ("initial",), out) or {}
        mode = data.get("equilibrium", "solve")
        if mode not in ("solve", "figure"):
            self.p.error(("equilibrium",), f"equilibrium is 'solve' or 'figure', got {mode!r}",
                         hint="'solve' finds it from the figure; 'figure' checks that the "
                         "figure is one")
        else:
            out.equilibrium = mode
        clash = set(out.springs) & set(out.dampers)
        for name in sorted(clash):
            self.p.error(("dampers", name), f"'{name}' names a spring too",
                         hint="give springs and dampers different names")
        return out

    def section(self, data, key):
        value = data.get(key)
        if value is None or (not value and not isinstance(value, dict)):
            return []               # an empty section: nothing, [], 0, false or ''

        try:
            return list(self.p.mapping(value, (key,)).items())
        except self.skip:
            return []

    def turning(self) -> set:
        """The names a torsional element or a torque may act on: bodies, actuators and rolling
        discs (a torque on a disc's slider turns the disc)."""
        discs = set(self.mech.dynamics.discs) if self.mech.dynamics is not None else set()
        return set(self.mech.bodies) | set(self.mech.actuators) | discs

    # elements --------------------------------------------------------------------------
    def positive(self, value, path, kind, what):
        number = self.p.number(value, path, kind, self.units)
        if not math.isfinite(number) or number <= 0:
            shown = f"{number / self.units.factor(kind):.6g} {self.units.names[kind]}"
            if isinstance(value, str):          # an expression: its value, then as written
                shown += f" (= {value})"
            raise self.p.error(path, f"{what} must be positive, got {shown}",
                               hint=f"a {what} is a number > 0")
        return number

    def measure(self, spec, path) -> el.Measure:
        """between: [P, Q] (with along: x | y | angle) or bodies: [B1, B2]."""
        if ("between" in spec) == ("bodies" in spec):
            raise self.p.error(path, "give either between: [P, Q] (two points) or "
                               "bodies: [B1, B2] (a torsional element)")
        if "bodies" in spec:
            if "along" in spec:
                raise self.p.error(path + ("along",), "'along' is for elements between points")
            pool = {FRAME} | self.turning()
            a, b = self.p.pair(spec["bodies"], path + ("bodies",), pool, "body")
            return el.Measure("angle", a, b)
        a, b = self.p.pair(spec["between"], path + ("between",), set(self.mech.points))
        if "along" not in spec:
            return el.Measure("distance", a, b)
        along = spec["along"]
        if along in ("x", "y"):
            return el.Measure("along", a, b, 1 + 0j if along == "x" else 1j)
        angle = self.p.number(along, path + ("along",), "angle", self.units)
        return el.Measure("along", a, b, cis(angle))

    def spring(self, name, value, path) -> el.Spring:
        self.p.name(name, path, what="spring")
        spec = self.p.mapping(value, path, {"between", "bodies", "along", "k", "free_length",
                                            "free_angle", "preload"}, ("k",))
        measure = self.measure(spec, path)
        torsional = measure.kind == "angle"
        k = self.positive(spec["k"], path + ("k",),
                          "torsional_stiffness" if torsional else "stiffness", "stiffness")
        given = [key for key in ("free_length", "free_angle", "preload") if key in spec]
        if len(given) > 1:
            raise self.p.error(path, f"give one of {', '.join(given)}",
                               hint="the free length (or angle), or the preload in the figure")
        if not given:
            return el.Spring(name, measure, k)
        key = given[0]
        if key == "preload":
            if spec[key] == "static":
                return el.Spring(name, measure, k, el.STATIC)
            force = self.p.number(spec[key], path + (key,), "torque" if torsional else "force",
                                  self.units)
            return el.Spring(name, measure, k, el.PRELOAD, force)
        expected = "free_angle" if torsional else "free_length"
        if key != expected:
            raise self.p.error(path + (key,), f"a {'torsional ' if torsional else ''}spring "
                               f"takes {expected}", hint=f"rename it {expected}")
        free = self.p.number(spec[key], path + (key,), "angle" if torsional else "length",
                             self.units)
        if key == "free_length" and measure.kind == "distance" and free < 0:
            raise self.p.error(path + (key,), f"a free length cannot be negative, got {free!r}")
        return el.Spring(name, measure, k, el.FREE, free)

    def damper(self, name, value, path) -> el.Damper:
        self.p.name(name, path, what="damper")
        spec = self.p.mapping(value, path, {"between", "bodies", "along", "c"}, ("c",))
        measure = self.measure(spec, path)
        c = self.positive(spec["c"], path + ("c",), "torsional_damping"
                          if measure.kind == "angle" else "damping", "damping coefficient")
        return el.Damper(name, measure, c)

    # excitation ------------------------------------------------------------------------
    def excitation(self, value, path, out):
        spec = self.p.mapping(value, path, {"frequency", "forces", "supports", "road"})
        if "frequency" in spec:
            out.frequency = self.positive(spec["frequency"], path + ("frequency",), "frequency",
                                          "forcing frequency")
        for name, item in self.items(spec.get("forces"), path + ("forces",)):
            h = self.block(self.harmonic, name, item, path + ("forces", name))
            if h is not None:
                out.forces[name] = h
        for name, item in self.items(spec.get("supports"), path + ("supports",)):
            s = self.block(self.support, name, item, path + ("supports", name))
            if s is not None:
                out.supports[name] = s
        if "road" in spec:
            self.block(self.road, spec["road"], path + ("road",), out)
        if (out.forces or out.supports) and out.frequency is None:
            self.p.error(path, "a harmonic excitation needs its frequency",
                         hint="give excitation.frequency (Omega), or a road's speed and "
                         "wavelength")

    def items(self, value, path):
        if value is None:
            return []
        try:
            return list(self.p.mapping(value, path).items())
        except self.skip:
            return []

    def phase(self, spec, path) -> float:
        return self.p.number(spec.get("phase", 0), path + ("phase",), "angle", self.units)

    def harmonic(self, name, value, path) -> el.Harmonic:
        self.p.name(name, path, what="excitation")
        spec = self.p.mapping(value, path, {"at", "x", "y", "on", "torque", "phase"})
        if "on" in spec:
            body = self.p.name(spec["on"], path + ("on",), self.turning(), "body")
            if "torque" not in spec or "at" in spec:
                raise self.p.error(path, "a harmonic torque is {on: body, torque: amplitude}")
            amount = self.p.number(spec["torque"], path + ("torque",), "torque", self.units)
            return el.Harmonic(name, "torque", body, 1 + 0j, amount, self.phase(spec, path))
        if "at" not in spec or "torque" in spec:
            raise self.p.error(path, "a harmonic force is {at: P, x: Fx, y: Fy}, a torque "
                               "{on: body, torque: C}")
        at = self.p.name(spec["at"], path + ("at",), set(self.mech.points))
        fx = self.p.number(spec.get("x", 0), path + ("x",), "force", self.units)
        fy = self.p.number(spec.get("y", 0), path + ("y",), "force", self.units)
        amplitude = hypot(fx, fy)
        if amplitude == 0:
            raise self.p.error(path, "a harmonic force needs a non-zero x or y amplitude")
        return el.Harmonic(name, "force", at, plane(fx, fy) / amplitude, amplitude,
                           self.phase(spec, path))

    def coordinate(self, value, path) -> int:
        name = self.p.name(value, path, set(self.coordinates), "coordinate")
        return self.coordinates[name]

    def support(self, name, value, path) -> el.Support:
        self.p.name(name, path, what="support")
        spec = self.p.mapping(value, path, {"coordinate", "amplitude", "phase"},
                              ("coordinate", "amplitude"))
        j = self.coordinate(spec["coordinate"], path + ("coordinate",))
        base = self.mech.coordinates[j].base
        amplitude = self.positive(spec["amplitude"], path + ("amplitude",), base, "amplitude")
        return el.Support(name, j, amplitude, self.phase(spec, path))

    def road(self, value, path, out):
        """A profile y = A cos(2 pi x / L) travelled at speed V: Omega = 2 pi V / L."""
        spec = self.p.mapping(value, path, {"coordinate", "amplitude", "wavelength", "speed",
                                            "phase"},
                              ("coordinate", "amplitude", "wavelength", "speed"))
        j = self.coordinate(spec["coordinate"], path + ("coordinate",))
        amplitude = self.positive(spec["amplitude"], path + ("amplitude",), "length", "amplitude")
        wavelength = self.positive(spec["wavelength"], path + ("wavelength",), "length",
                                   "wavelength")
        speed = self.positive(spec["speed"], path + ("speed",), "speed", "speed")
        omega = 2 * times_pi(speed) / wavelength
        if out.frequency is not None and abs(out.frequency - omega) > 1e-12 * omega:
            raise self.p.error(path, f"the road gives Omega = 2 pi V / L = {omega:.6g} rad/s, "
                               "but excitation.frequency is given too",
                               hint="give one of them")
        out.frequency = omega
        out.supports["road"] = el.Support("road", j, amplitude, self.phase(spec, path),
                                          road=(wavelength, speed))

    # free response ---------------------------------------------------------------------
    def initial(self, value, path, elements) -> dict:
        spec = self.p.mapping(value, path)
        if "mode" in spec:
            elements.initial_mode = self.initial_mode(spec, path)
            return {}
        out = {}
        if "from" in spec:
            elements.initial_from = self.initial_from(spec["from"], path + ("from",), elements)
        for key, item in spec.items():
            if key == "from":
                continue
            name, rate = (key[:-4], True) if isinstance(key, str) and key.endswith("_dot") \
                else (key, False)
            j = self.coordinate(name, path + (key,))
            base = self.mech.coordinates[j].base
            if rate:    # in the unit of a driver's rate, a parameter written here too
                number = self.p.driver_rate(spec, path, key, base, 1, self.units)
            else:
                number = self.p.number(item, path + (key,), base, self.units)
            x0, v0 = out.get(j, (0.0, 0.0))
            out[j] = (x0, number) if rate else (number, v0)
        return out

    def initial_mode(self, spec, path) -> tuple:
        """``{mode: N, q: a}``: released from rest in mode N, its shape scaled so that the
        offset of coordinate q from the equilibrium is a (q's unit): (N - 1, j, a in SI)."""
        mode = spec["mode"]
        count = len(self.mech.coordinates)
        if isinstance(mode, bool) or not isinstance(mode, int) or not 1 <= mode <= count:
            raise self.p.error(path + ("mode",), f"a mode is numbered 1-{count} from the "
                               f"lowest frequency, got {mode!r}")
        others = [k for k in spec if k != "mode"]
        if len(others) != 1 or others[0] == "from" or str(others[0]).endswith("_dot"):
            raise self.p.error(path, "a start in a mode gives the amplitude of one coordinate "
                               f"(its offset from the equilibrium), got {others or 'none'}",
                               hint=f"initial: {{mode: {mode}, "
                               f"{self.mech.coordinates[0].name}: 10}}: released from rest "
                               "in that mode's shape")
        name = others[0]
        j = self.coordinate(name, path + (name,))
        base = self.mech.coordinates[j].base
        amplitude = self.p.number(spec[name], path + (name,), base, self.units)
        if float(amplitude) == 0:
            raise self.p.error(path + (name,), "the amplitude of a start in a mode is not 0",
                               hint="without an amplitude the system stays at rest")
        return mode - 1, j, amplitude

    def initial_from(self, value, path, elements) -> tuple:
        """``from:`` equilibrium (the default), figure, unstretched (the one spring),
        {unstretched: SPRING} or {unstretched: [SPRINGS]}: what the initial offsets are
        measured from."""
        if value in ("equilibrium", "figure"):
            return value, None
        if isinstance(value, dict):
            spec = self.p.mapping(value, path, {"unstretched"}, ("unstretched",))
            given = spec["unstretched"]
            items = given if isinstance(given, list) else [given]
            names = tuple(self.p.name(n, path + ("unstretched",) + ((i,) if isinstance(
                given, list) else ()), set(elements.springs), "spring")
                for i, n in enumerate(items))
        elif value == "unstretched":
            if len(elements.springs) != 1:
                raise self.p.error(path, f"'unstretched' names no spring: the file has "
                                   f"{len(elements.springs)}",
                                   hint="write {unstretched: NAME} or {unstretched: [NAMES]}")
            names = tuple(elements.springs)
        else:
            raise self.p.error(path, f"from is equilibrium, figure, unstretched or "
                               f"{{unstretched: SPRING}}, got {value!r}")
        return "unstretched", names
