"""Reading of the joint forces a report asks for: reactions, slider forces, tensions, contact forces.

    quantities:
      RAx: {reaction: [A, link2], component: x}     # x, y, magnitude, along, normal
      RAn: {reaction: [A, frame], component: normal, axis: link2}   # axis: [P, Q] or
                                                                    # {angle: A} too
      RC:  {reaction: [C, act.rod], component: magnitude}   # an actuator's half
      Fn:  {slider_force: slider4, component: normal}       # normal | friction
      T1:  {tension: c1}                                    # a cord of 'cords:'
      N1:  {contact_force: r1, component: normal}           # a contact of 'rolling:'

:class:`ForceQuantities` (a mixin of the Parser) reads the point, the body (a link, slider
or actuator, an actuator's half NAME.cylinder or NAME.rod, or the frame), the contact and
the axis of a projected component; statics finds the force with the unknown load.

Errors, each an :class:`~linkcli.errors.InputError` at the quantity's YAML path and line
(exit 2): an undefined body or half, a point that is not on the body, a slider force of a
body that is not a slider, a tension or contact force of a name that is not a cord or a
rolling contact, a projected component on the frame without its axis.
"""
from __future__ import annotations

from linkcli.model.mechanism import FRAME, Quantity
from linkcli.input.quantities import PROJECTED


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


class ForceQuantities:
    """Joint forces (a mixin of the Parser)."""

    def force_quantity(self, name, kind, value, path, pool) -> Quantity:
        """A joint force: the tension of a cord, the force of a rolling contact, the force
        of a slider's guide on it, or the reaction of a pin at POINT on BODY
        (``reaction: [POINT, BODY]``), by the component asked."""
        where = path + (kind,)
        arg = value[kind]
        component = value.get("component")
        if kind in ("tension", "contact_force"):
            return Quantity(name, kind, self.contact(arg, where, kind), component=component)
        bodies, _ = self.raw_bodies()
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
