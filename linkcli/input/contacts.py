"""Parsing of rolling contacts and cords: ``rolling`` and ``cords`` (a mixin of the Parser).

    rolling:
      r1: {disc: wheel, radius: 100, on: {line: x, side: left}}     # on a fixed line along x
      r4: {disc: wheel, radius: 100, on: {line: x, side: left, body: cart}}   # cart's floor
      r5: {disc: wheel, radius: 100, on: {line: [F1, F2], body: cart}}  # through F1, F2 of cart
      r2: {disc: wheel, radius: 100, on: {circle: O, radius: 500}}  # inside or outside a track
      r3: {disc: planet, radius: 50, on: {disc: sun, radius: 150}}  # on another disc
    cords:
      c1: {pulley: drum, radius: 80, to: P, along: -y, side: left}  # a taut cord from drum to P
      b1: {pulley: drum, radius: 80, along: x, side: right,         # a belt strand from drum
           to: {disc: wheel, radius: 40, side: right}}              # to the disc wheel

The disc (or pulley) is a link whose first point is its centre; it may have any number of
contacts and cords.  A line belongs to the frame unless ``body`` names the link or slider
that carries it; a line through points of a moving body, or under a centre that rides on a
moving body's guide (and on no fixed guide along the line), must name its body
(``body: frame`` for the ground).  Whether a disc is
inside or outside a circle is read from the figure unless ``inside`` is given; a cord must
be taut and tangent in the figure, a line through two points tangent to the disc.
"""
from __future__ import annotations

import dataclasses

from linkcli.model.exact import cis, phase
from linkcli.model.mechanism import FRAME, Driver, Rolling

SIDES = {"left": 1, "right": -1}
#: relative tolerance of the figure checks (the figure is approximate)
FIGURE_TOL = 0.02


#: the kind of unit a pay-out's value, rate and accel are written in: a length of cord
PAYOUT_KIND = "length"


def turn_per_payout(cord) -> float:
    """d theta / d s = -side / r: the disc's turn per length of ``cord`` paid out
    (``ContactsSection.payout``)."""
    return -cord.side / cord.radius


class ContactsSection:
    def contacts(self, data, units, pool, bodies, fixed, moving) -> dict:
        out = {}
        figure = {**fixed, **moving}
        self.fixed_points = set(fixed)
        self.length_unit = (units.names["length"], units.factor("length"))
        for key, reader in (("rolling", self.rolling_entry), ("cords", self.cord_entry)):
            spec = self.mapping(self.get(data, (), key, required=False, default={}) or {},
                                (key,))
            for name, value in spec.items():
                path = (key, name)
                if name in out:
                    self.error(path, f"'{name}' names a rolling contact already")
                    continue
                entry = self.block(reader, name, value, path, units, bodies, figure)
                if entry is not None:
                    out[name] = entry
        self.contact_table = (out, bodies, figure)
        return out

    def payout(self, spec, path, units, name) -> Driver:
        """A cord's pay-out s as the driver: the length of cord unwound from its disc,
        measured relative to the disc (0 on the figure).  The cord leaves the disc along a
        fixed direction u from the tangent point T = C + side r i u, which moves with the
        centre C; the disc's point at T moves at v_C + i omega (T - C) = v_C - side r omega u,
        the cord's with it (it does not slip), so the cord passes T relative to the disc at
        s' = -side r omega: the pay-out drives the disc's turn, theta = theta_0 - side s / r,
        omega = -side s' / r (q is that angle, the disc's vector C -> M)."""
        where = path + ("payout",)
        table, bodies, figure = getattr(self, "contact_table", ({}, {}, {}))
        if "angle" in spec or "length" in spec or "x" in spec or "y" in spec:
            raise self.error(path, "give exactly one of angle: [P, Q], length: [P, Q], x: P, "
                             "y: P, payout: CORD")
        cords = {n for n, r in table.items() if r.kind in ("cord", "belt")}
        cord = spec["payout"]
        if isinstance(cord, str) and cord in table and cord not in cords:
            raise self.error(where, f"'{cord}' is a rolling contact, not a cord: a pay-out is "
                             "the length of a cord unwound from its disc",
                             hint=f"name a cord of 'cords:' ({', '.join(sorted(cords)) or 'none'})")
        cord = self.name(cord, where, cords, "cord")
        r = table[cord]
        disc = bodies[r.disc]
        mark = disc.points[1]
        theta0 = phase(figure[mark] - figure[r.center])
        s = self.number(spec["value"], path + ("value",), PAYOUT_KIND, units)
        rate, accel = (self.driver_rate(spec, path, key, PAYOUT_KIND, order, units)
                       for order, key in ((1, "rate"), (2, "accel")))
        k = turn_per_payout(r)
        return Driver("angle", r.center, mark, theta0 + k * s, k * rate, k * accel, name,
                      payout=cord)

    def disc_body(self, value, path, bodies):
        if isinstance(value, str) and value in bodies and bodies[value].kind == "link":
            return value, bodies[value].points[0]       # (no set of every link per contact)
        links = {n for n, b in bodies.items() if b.kind == "link"}
        name = self.name(value, path, links, "link")
        return name, bodies[name].points[0]

    def direction(self, value, path, units) -> complex:
        """x, -x, y, -y or an angle (counter-clockwise from +x)."""
        axes = {"x": 1 + 0j, "-x": -1 + 0j, "y": 1j, "-y": -1j}
        if isinstance(value, str) and value in axes:
            return axes[value]
        return cis(self.number(value, path, "angle", units))

    def side(self, spec, path) -> int:
        side = spec.get("side", "left")
        if not isinstance(side, str) or side not in SIDES:
            raise self.error(path + ("side",), f"side is 'left' or 'right', got {side!r}")
        return SIDES[side]

    def rolling_entry(self, name, value, path, units, bodies, figure) -> Rolling:
        self.name(name, path, what="rolling contact")
        spec = self.mapping(value, path, {"disc", "radius", "on", "gear"}, ("disc", "on"))
        disc, center = self.disc_body(spec["disc"], path + ("disc",), bodies)
        gear = self.gear_of(spec, path, disc)
        radius = self.pitch_radius(spec, path, units, gear)
        on = self.mapping(spec["on"], path + ("on",))
        kinds = [k for k in ("line", "circle", "disc") if k in on]
        if len(kinds) != 1:
            raise self.error(path + ("on",), "give one of line, circle, disc")
        where = path + ("on",)
        if kinds[0] == "line":
            self.mapping(on, where, {"line", "side", "body"})
            carrier = self.line_body(on, where, bodies, disc)
            side = self.side(on, where)
            if isinstance(on["line"], list):
                if carrier is None:
                    carrier = self.owner(self.pair(on["line"], where + ("line",), set(figure)),
                                         where, bodies)
                u = self.line_through(on["line"], where, bodies, figure, carrier,
                                      (figure[center], radius, side))
            else:
                u = self.direction(on["line"], where + ("line",), units)
            if carrier is None:
                carrier = self.ground(center, where, bodies, u, figure)
            # the centre is on `side` of the line: the contact is on the other side
            return Rolling(name, disc, center, radius, "line", u, -side, carrier=carrier)
        self.mapping(on, where, {"circle", "disc", "radius", "inside", "gear"})
        if kinds[0] == "circle":
            track = self.name(on["circle"], where + ("circle",),
                              {p for p in figure if p in self.fixed_points}, "fixed point")
            other = None
        else:
            other, track = self.disc_body(on["disc"], where + ("disc",), bodies)
            if other == disc:
                raise self.error(where + ("disc",), "a disc cannot roll on itself")
        ring = self.gear_of(on, where, other)
        track_radius = self.pitch_radius(on, where, units, ring, "track")
        self.meshing(path, gear, ring)
        inside = self.inside(on, where, figure[center], figure[track], radius, track_radius)
        return Rolling(name, disc, center, radius, kinds[0], track=track,
                       track_radius=track_radius, inside=inside, other=other)

    def line_body(self, on, where, bodies, disc):
        """The body ``body:`` names as the line's (FRAME for the ground), None when absent."""
        if "body" not in on:
            return None
        carriers = {n for n, b in bodies.items() if b.kind in ("link", "block")} - {disc}
        name = on["body"]
        if name == FRAME:
            return FRAME
        if name == disc:
            raise self.error(where + ("body",), "a disc cannot roll on itself")
        return self.name(name, where + ("body",), carriers, "link or slider")

    def line_through(self, ends, where, bodies, figure, carrier, disc) -> complex:
        """The direction P -> Q of a line through two points, which must be the named
        body's (fixed points for the frame) and tangent to the disc in the figure."""
        p, q = self.pair(ends, where + ("line",), set(figure))
        if carrier is not None:
            own = self.fixed_points if carrier == FRAME else set(bodies[carrier].points)
            for i, x in enumerate((p, q)):
                if x not in own:
                    raise self.error(where + ("line", i), f"point {x} is not a point of "
                                     f"{'the frame' if carrier == FRAME else carrier}",
                                     hint=f"a line of {carrier} passes through its own points")
        z = figure[q] - figure[p]
        u = z / abs(z)
        centre, radius, side = disc
        height = ((centre - figure[p]) * u.conjugate()).imag * side
        if abs(height - radius) > FIGURE_TOL * max(radius, abs(z)):
            unit, f = self.length_unit
            raise self.error(where, f"the disc does not touch the line {p}{q} in the figure: "
                             f"its centre is {height / f:.6g} {unit} from it on the "
                             f"{'left' if side > 0 else 'right'}, the radius is "
                             f"{radius / f:.6g} {unit}", hint="check 'side', the radius and the "
                             "figure's positions")
        return u

    def owner(self, ends, where, bodies) -> str:
        """The frame, for a line through two fixed points; else the line moves with a body
        it passes through, which the file must name."""
        p, q = ends
        if p in self.fixed_points and q in self.fixed_points:
            return FRAME
        movers = sorted(n for n, b in bodies.items() if {p, q} & set(b.points))
        raise self.error(where, f"the line {p}{q} moves with "
                         f"{' or '.join(movers) or 'the moving points'}: say which body it "
                         "belongs to", hint=f"body: {movers[0] if movers else 'NAME'} for "
                         "a line of that body; a disc rolls on the ground only on a line of "
                         "fixed points")

    def ground(self, center, where, bodies, u, figure) -> str:
        """FRAME for a line given by its direction ``u``, unless the disc's centre rides on a
        guide carried by a moving body and on no fixed guide along u: then the line may be
        that body's floor, and the file must say which."""
        blocks = [b for b in bodies.values() if b.kind == "block" and center in b.points]
        for b in blocks:
            if b.guide.carrier != FRAME:
                continue
            axis = figure[b.guide.c] - figure[b.guide.b]
            if abs((axis / abs(axis) * u.conjugate()).imag) < FIGURE_TOL:
                return FRAME        # the centre runs on the ground's parallel: the ground
        for b in blocks:
            if b.guide.carrier != FRAME:
                carrier = b.guide.carrier.split(".")[0]
                raise self.error(where, f"the centre {center} rides on a guide of {carrier} "
                                 f"(slider {b.name}): does the disc roll on {carrier} or on "
                                 "the ground?", hint=f"body: {carrier} for a line of "
                                 f"{carrier} (its floor), body: frame for the ground")
        return FRAME

    def inside(self, on, path, c, o, r, big) -> bool:
        """Inside or outside the track: given, or the figure's distance |C - O| nearer
        R - r or R + r (and within FIGURE_TOL of it)."""
        d = abs(c - o)
        unit, f = self.length_unit
        if "inside" in on:
            inside = on["inside"]
            if not isinstance(inside, bool):
                raise self.error(path + ("inside",), f"inside is true or false, got {inside!r}")
        else:
            inside = abs(d - (big - r)) < abs(d - (big + r))
        expected = big - r if inside else big + r
        if inside and big <= r:
            raise self.error(path + ("radius",), f"a disc of radius {r / f:.6g} {unit} does not "
                             f"fit inside a track of radius {big / f:.6g} {unit}")
        if abs(d - expected) > FIGURE_TOL * big:
            raise self.error(path, f"in the figure the centres are {d / f:.6g} {unit} apart, but "
                             f"a disc rolling {'inside' if inside else 'outside'} is at "
                             f"{expected / f:.6g} {unit} (R {'-' if inside else '+'} r)",
                             hint="check the radii and the figure's positions")
        return inside

    def cord_entry(self, name, value, path, units, bodies, figure) -> Rolling:
        """A taut cord from a pulley to a point P (``to: P``), or a belt strand from the
        pulley to another disc (``to: {disc: D, radius: r, side: left}``)."""
        self.name(name, path, what="cord")
        spec = self.mapping(value, path, {"pulley", "radius", "to", "along", "side", "slip"},
                            ("pulley", "radius", "to", "along"))
        disc, center = self.disc_body(spec["pulley"], path + ("pulley",), bodies)
        radius = self.positive(spec["radius"], path + ("radius",), units)
        u = self.direction(spec["along"], path + ("along",), units)
        side = self.side(spec, path)
        tangent = figure[center] + side * radius * 1j * u
        if isinstance(spec["to"], dict):
            belt = self.belt_entry(name, spec["to"], path + ("to",), units, bodies, figure,
                                   (disc, center, radius, u, side, tangent))
            return dataclasses.replace(belt, slip=self.slip(spec, path))
        if "slip" in spec:
            raise self.error(path + ("slip",), "a slip is of a belt between two pulleys, and "
                             "this cord runs to a point", hint="to: {disc: D, radius: r, side: "
                             "left} for a belt strand")
        if not isinstance(spec["to"], str):
            raise self.error(path + ("to",), f"expected a point name or a disc, got "
                             f"{spec['to']!r}", hint="to: P, or to: {disc: D, radius: r, "
                             "side: left} for a belt strand")
        point = self.name(spec["to"], path + ("to",), set(figure))
        self.taut(path + ("to",), figure[point] - tangent, u, radius, side, point)
        return Rolling(name, disc, center, radius, "cord", u, side, point=point)

    def slip(self, spec, path) -> float:
        """A belt's slip as a fraction: ``slip: s`` (per cent), or ``[s1, s2]`` between the
        driver and the belt and between the belt and the follower, combined as the books
        combine them, s = s1 + s2 (N2/N1 = d1/d2 (1 - s/100), the product s1 s2 / 100^2
        neglected); each, and s, in [0, 100)."""
        if "slip" not in spec:
            return 0.0
        where = path + ("slip",)
        value = spec["slip"]
        parts = value if isinstance(value, list) else [value]
        if not 1 <= len(parts) <= 2:
            raise self.error(where, f"a slip is a percentage or two [s1, s2], got {value!r}")
        total = 0.0
        for i, part in enumerate(parts):
            s = float(self.number(part, where + ((i,) if isinstance(value, list) else ())))
            if not 0 <= s < 100:
                raise self.error(where, f"a slip is a percentage in [0, 100), got {s:g}",
                                 hint="2.5 for '2.5 % slip'; 100 % would leave the follower "
                                 "at rest")
            total += s
        if total >= 100:
            raise self.error(where, f"the slips add up to {total:g} %, not under 100 %")
        return total / 100

    def belt_entry(self, name, to, path, units, bodies, figure, pulley) -> Rolling:
        """The strand runs from the pulley's tangent point to the other disc's, whose
        tangent point is D + side_D r_D i u (on its ``side`` looking along the strand)."""
        disc, center, radius, u, side, tangent = pulley
        to = self.mapping(to, path, {"disc", "radius", "side"}, ("disc", "radius"))
        other, track = self.disc_body(to["disc"], path + ("disc",), bodies)
        if other == disc:
            raise self.error(path + ("disc",), "a belt cannot run from a pulley to itself")
        r_other = self.positive(to["radius"], path + ("radius",), units)
        other_side = self.side(to, path)
        far = figure[track] + other_side * r_other * 1j * u
        self.taut(path, far - tangent, u, max(radius, r_other), side, f"disc {other}")
        return Rolling(name, disc, center, radius, "belt", u, side, track=track,
                       track_radius=r_other, other=other, other_side=other_side)

    def taut(self, path, z, u, radius, side, what):
        """The strand z from the pulley's tangent point runs ahead along u, on the tangent."""
        run = (z * u.conjugate()).real
        size = max(abs(z), radius)
        if run <= 0:
            raise self.error(path, f"the cord is not taut in the figure: {what} is not "
                             f"ahead of the pulley along the cord's direction",
                             hint="'along' is the direction from the pulley to the point")
        if abs((z * u.conjugate()).imag) > FIGURE_TOL * size:
            unit, f = self.length_unit
            raise self.error(path, f"the cord is not tangent in the figure: {what} is "
                             f"{abs((z * u.conjugate()).imag) / f:.4g} {unit} off the tangent line "
                             "from the "
                             f"{'left' if side > 0 else 'right'} of the pulley",
                             hint="check 'side', 'along' and the radius")
