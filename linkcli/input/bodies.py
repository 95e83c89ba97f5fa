"""Parsing of the bodies: links and rigid shapes, actuators, slider blocks and guides."""
from __future__ import annotations

from linkcli.model.exact import cis, plane, sqrt
from linkcli.model.mechanism import FRAME, Actuator, Body, Guide
from linkcli.input.reader import _Skip


class BodiesSection:
    """``links``, ``actuators`` and ``sliders`` (a mixin of the Parser)."""

    def links(self, data, units, pool, bodies):
        links = self.mapping(self.get(data, (), "links", required=False, default={}) or {},
                             ("links",))
        for name, spec in links.items():
            self.block(self.link, name, spec, units, pool, bodies)

    def link(self, name, spec, units, pool, bodies):
        path = ("links", name)
        self.name(name, path, what="link")
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
            local = {points[0]: 0j, points[1]: plane(length, 0)}
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
        local[points[1]] = plane(self.positive(base["length"], path + (points[1], "length"),
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
            return a + plane(along, sign * sqrt(h2)) * (b - a) / base
        length = self.positive(self.get(spec, path, "length"), path + ("length",), units)
        angle = self.number(spec.get("angle", 0), path + ("angle",), "angle", units)
        origin = spec.get("from")
        start = local[next(iter(local))] if origin is None else local[
            self.name(origin, path + ("from",), local)]
        return start + length * cis(angle)

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
        # every block's points first: a guide may run on a block listed after its slider
        self.block_points = {name: _listed_points(value) for name, value in spec.items()}
        self.figure = None                # the figure's points, read when a guide moves
        for name, value in spec.items():
            self.block(self.slider, name, value, units, pool, bodies, fixed, data)
        self.block(self.guide_cycles, bodies)

    def slider(self, name, value, units, pool, bodies, fixed, data=None):
        path = ("sliders", name)
        self.name(name, path, what="slider")
        value = self.mapping(value, path, {"point", "guide", "carries"}, ("point", "guide"))
        point = self.name(value["point"], path + ("point",), pool)
        guide = self.guide(value["guide"], path + ("guide",), units, pool, bodies, fixed, name)
        local = {point: 0j}
        carries = self.mapping(value.get("carries") or {}, path + ("carries",))
        if carries and guide.carrier.endswith(".cylinder"):
            raise self.error(path + ("carries",), f"a block on the line of actuator "
                             f"{guide.carrier[:-len('.cylinder')]} carries no other points",
                             hint="pin a link to the block's point to carry them")
        for other, offset in carries.items():
            opath = path + ("carries", other)
            self.name(other, opath, pool)
            local[other] = self.offset(offset, opath, units, guide, fixed)
        if name in bodies:
            raise self.error(path, f"name '{name}' is already used by a link or actuator")
        if guide.carrier != FRAME and data is not None:
            self.on_slot(path, point, guide, data, units, fixed)
        bodies[name] = Body(name, "block", tuple(local), local, guide)

    def on_slot(self, path, point, guide: Guide, data, units, fixed):
        """Refuse a moving guide that does not pass where the figure puts the block's point.

        The figure's distance of P from the line cross(C - B, P - B) = |C - B| e must be
        at most SLOT_FIGURE times the mechanism's size (the diagonal of the box around the
        figure's points): the figure picks the assembly, so it must draw the pin
        in its slot, if only approximately.
        """
        figure = self.figure
        if figure is None:
            figure = self.figure = self.figure_points(data, units, fixed)
        if not {point, guide.b, guide.c} <= set(figure):
            return
        b, c, p = figure[guide.b], figure[guide.c], figure[point]
        axis = c - b
        if abs(axis) == 0:
            return                        # no direction drawn: the solver's figure check
        off = (axis.conjugate() * (p - b)).imag / abs(axis) - guide.offset
        xs, ys = [z.real for z in figure.values()], [z.imag for z in figure.values()]
        size = abs(complex(max(xs) - min(xs), max(ys) - min(ys)))
        if abs(off) > SLOT_FIGURE * size:
            unit, f = units.display("length", 0)
            raise self.error(path + ("guide",), f"the figure puts {point} {abs(off) / f:.4g} "
                             f"{unit} {'left' if off > 0 else 'right'} of the guide "
                             f"{guide.text}, which should pass through it",
                             hint=f"check the guide's points and offset, or {point}'s "
                             "position in 'points'")

    def figure_points(self, data, units, fixed) -> dict:
        """The figure's points (frame and moving) that read without errors."""
        figure = {n: z for n, z in fixed.items() if not n.startswith("~")}
        points = data.get("points")
        if not isinstance(points, dict):
            return figure
        before = len(self.errors)
        for name, value in points.items():
            if isinstance(name, str) and name not in figure:
                try:
                    figure[name] = self.xy(value, ("points", name), units)
                except _Skip:
                    pass
        del self.errors[before:]          # reported where the points are read
        return figure

    def guide_cycles(self, bodies):
        """Refuse blocks whose guides run on each other (no block of the cycle is placed)."""
        for body in bodies.values():
            seen = [body.name]
            carrier = body.guide.carrier if body.kind == "block" else FRAME
            while carrier in bodies and bodies[carrier].kind == "block":
                if carrier == body.name:
                    raise self.error(("sliders", body.name, "guide"), "the guides of sliders "
                                     f"{', '.join(seen)} run on each other in a ring",
                                     hint="one of them must run on the frame or on a link")
                if carrier in seen:
                    break
                seen.append(carrier)
                carrier = bodies[carrier].guide.carrier

    def carrier(self, b, c, path, bodies, slider) -> str:
        """The body a moving guide along [b, c] belongs to: a link with both points, a
        slider block carrying both (listed in any order) or an actuator between them (its
        cylinder)."""
        link = next((body.name for body in bodies.values() if body.kind == "link"
                     and b in body.points and c in body.points), None)
        if link is not None:
            return link
        points = getattr(self, "block_points", {})
        if {b, c} <= points.get(slider, set()):
            raise self.error(path, f"slider {slider} cannot run on a guide of its own points "
                             f"{b} and {c}", hint="a slot belongs to another block or a link")
        block = next((name for name, own in points.items() if name != slider
                      and {b, c} <= own), None)
        if block is not None:
            return block
        actuator = next((body.name for body in bodies.values() if body.kind == "cylinder"
                         and {b, c} == {body.points[0], bodies[body.name[:-len("cylinder")]
                                                             + "rod"].points[0]}), None)
        if actuator is not None:
            return actuator
        raise self.error(path, f"no link, slider block or actuator carries both {b} and {c}",
                         hint="a moving guide runs along two points of one link or block, or "
                         "along an actuator's two points")

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
            world = plane(self.number(value.get("dx", 0), path + ("dx",), "length", units),
                            self.number(value.get("dy", 0), path + ("dy",), "length", units))
            return world * to_guide
        return plane(self.number(value.get("along", 0), path + ("along",), "length", units),
                       self.number(value.get("normal", 0), path + ("normal",), "length", units))

    def guide(self, value, path, units, pool, bodies, fixed, slider) -> Guide:
        """A line: {x: c}, {y: c}, {through: P or [x, y], angle: a} or {along: [B, C], offset: e}."""
        value = self.mapping(value, path, {"x", "y", "through", "angle", "along", "offset"})
        text = ", ".join(f"{k}: [{', '.join(map(str, v))}]" if isinstance(v, list) else
                         f"{k}: {v}" for k, v in value.items())
        offset = self.number(value.get("offset", 0), path + ("offset",), "length", units)
        if "along" in value:
            b, c = self.pair(value["along"], path + ("along",), pool)
            carrier = FRAME if b in fixed and c in fixed else \
                self.carrier(b, c, path + ("along",), bodies, slider)
            if carrier.endswith(".cylinder") and offset != 0:
                raise self.error(path + ("offset",), "a guide along an actuator is its line: "
                                 "its offset must be 0", hint="run the guide along two points "
                                 "of a link for a line beside it")
            return Guide(carrier, b, c, offset, text)
        if "x" in value or "y" in value:
            if len(value) != 1 + ("offset" in value):
                raise self.error(path, "give only one of x or y for an axis-parallel guide")
            if "x" in value:
                origin = plane(self.number(value["x"], path + ("x",), "length", units), 0)
                direction = 1j
            else:
                origin = plane(0, self.number(value["y"], path + ("y",), "length", units))
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
            direction = cis(angle)
        b, c = f"~{slider}.0", f"~{slider}.1"
        # a direction vector of at least unit length (SI): never underflows when squared
        scale = max(abs(origin), max((abs(p) for p in fixed.values()), default=0.0), 1.0)
        fixed[b] = origin
        fixed[c] = origin + direction * scale
        return Guide(FRAME, b, c, offset, text)


#: a moving guide may miss its point in the figure by this fraction of the mechanism's size
SLOT_FIGURE = 0.1


def _listed_points(value) -> set:
    """The point names a slider's entry lists (its point and carried points), unchecked."""
    if not isinstance(value, dict):
        return set()
    names = [value.get("point")]
    carries = value.get("carries")
    if isinstance(carries, dict):
        names += list(carries)
    return {n for n in names if isinstance(n, str)}
