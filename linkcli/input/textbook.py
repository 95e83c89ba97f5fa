"""Reading of the textbook's quantities of motion: what a point, a pair of points or a body does.

    quantities:
      vB:  {speed: B}                            # also acceleration, tangential_ and
      aBt: {tangential_acceleration: B}          #   normal_acceleration of a point
      vr:  {relative_speed: [B, C]}              # also relative (component x | y),
      pE:  {along: [A, B], point: E}             #   relative_acceleration; normal_to
      th2: {rotation: link2}                     # a body's angle turned; signed: true
      gam: {between: [[A, B], [C, D]]}           # the angle between two vectors
      I2:  {instant_centre: link2, component: x} # or [BODY, OTHER] relative to another
      d2:  {instant_centre_distance: [link2, B]}
      vmin: {least_speed: [B, C]}                # on the line B-C of one body; least_speed_at
      tau: {velocity_ratio: xE}                  # d(xE)/dq, once every quantity is read

:class:`TextbookQuantities` (a mixin of the Parser) reads one such quantity's points and
bodies, as the file declares them (:meth:`raw_bodies`: links, actuators, sliders, and the
rolling discs and cords that take a name); joint forces go to ``forces``.

Errors, each an :class:`~linkcli.errors.InputError` at the quantity's YAML path and line
(exit 2): a component the kind has not, or none where it needs one; a projection without
its 'point'; an undefined point or body; two points no one body carries; an instant centre
of a body relative to itself or of an actuator (its halves have different ones).
"""
from __future__ import annotations

from linkcli.model.mechanism import FRAME, Quantity
from linkcli.input.quantities import FORCES, PROJECTIONS

OF_POINT = ("speed", "acceleration", "tangential_acceleration", "normal_acceleration")
OF_PAIR = ("relative", "relative_speed", "relative_acceleration")
#: of the line through two points of one body: its point of least speed and that speed
ON_BODY = ("least_speed", "least_speed_at")
COMPONENTS = {"relative": ("x", "y"), "instant_centre": ("x", "y"),
              "reaction": ("x", "y", "magnitude", "along", "normal"),
              "slider_force": ("normal", "friction"), "contact_force": ("normal", "friction")}


class TextbookQuantities:
    """Speeds, accelerations, projections, rotations and instant centres (a mixin of the
    Parser)."""

    def textbook_quantity(self, name, kind, value, path, pool) -> Quantity:
        """Speeds and accelerations of points, projections, relative motion, rotations of
        bodies, the angle between two vectors, instant centres and velocity ratios (see
        docs/schema.md, 'quantities'); a joint force's own reader is :meth:`force_quantity`."""
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
        if kind in FORCES:
            return self.force_quantity(name, kind, value, path, pool)
        _, spinning = self.raw_bodies()
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
