"""The data lines of the bodies and their guides: the frame, the links with their shapes,
the actuators, the sliders with their guides, the rolling contacts, cords and belts.

A rigid body's shape is stated as the exam would: its base side (first point to second)
and every other point by its distance from a placed point and the angle from the base
direction, or by its distances from two placed points; of the ways that give the same
shape, the one with the fewest digits (an exam's round numbers).  A slider's guide is a
fixed line (horizontal, vertical or through a named point at an angle), a guide carried
by a body or an actuator's line; the pins it carries are stated in the frame's axes or the
guide's, whichever is rounder.
"""
from __future__ import annotations

import cmath
import math

from linkcli.model.mechanism import FRAME
from linkcli.texts.amounts import CLOSE, digits


def body_lines(w) -> list:
    """The frame, the links, the actuators, the sliders and the rolling contacts and cords
    of ``w``'s mechanism, a line each (``w`` a :class:`~linkcli.texts.amounts.Writer`)."""
    return _frame(w) + _links(w) + _actuators(w) + _sliders(w) + _contacts(w)


def _frame(w) -> list:
    fixed = [f"{p} = {w.point(z)}" for p, z in w.mech.fixed.items() if not p.startswith("~")]
    return [f"{w.w['frame']}: " + ", ".join(fixed)] if fixed else []


def _links(w) -> list:
    binary, bodies = [], []
    rolling = {r.disc for r in w.mech.rolling.values()}
    for body in w.mech.bodies.values():
        if body.kind != "link":
            continue
        if len(body.points) == 2:
            a, b = body.points
            text = w.w["base"].format(a=a, b=b, length=w.length(abs(body.local[b] -
                                                                    body.local[a])))
            named = body.name not in (a + b, b + a) and body.name not in rolling
            binary.append(f"{body.name} {text}" if named else text)
        else:
            bodies.append(w.w["body"].format(name=body.name) + ": " + "; ".join(_shape(w, body)))
    out = [f"{w.w['links']}: " + ", ".join(binary)] if binary else []
    return out + bodies


def _shape(w, body) -> list:
    """The base side and each further point by its roundest description."""
    p, local = body.points, body.local
    base = local[p[1]] - local[p[0]]
    parts = [w.w["base"].format(a=p[0], b=p[1], length=w.length(abs(base)))]
    for i in range(2, len(p)):
        parts.append(_place_point(w, p, i, local, base))
    return parts


def _place_point(w, p, i, local, base) -> str:
    """Point p[i] from earlier ones: by distance and angle from the base direction, or by
    two distances; the description with the fewest digits."""
    f = w.units.factor("length")
    fa = w.units.factor("angle")
    target = local[p[i]]
    options = []
    for j in range(i):                 # polar from p[j]
        z = target - local[p[j]]
        angle = math.remainder(cmath.phase(z / base), 2 * math.pi)
        cost = digits(abs(z) / f) + digits(angle / fa) + (0 if j == 0 else 0.5)
        options.append((cost, len(options), w.w["polar"].format(
            p=p[i], length=w.length(abs(z)), f=p[j], angle=w.angle(angle), a=p[0], b=p[1])))
    for j in range(i):                 # two distances from p[j], p[m]
        for m in range(j + 1, i):
            d1, d2 = abs(target - local[p[j]]), abs(target - local[p[m]])
            along = local[p[m]] - local[p[j]]
            cross = (along.conjugate() * (target - local[p[j]])).imag
            if abs(cross) <= CLOSE * abs(along) * max(d1, d2):
                continue                # on the line: the side is undefined
            side = w.w["left"] if cross > 0 else w.w["right"]
            cost = digits(d1 / f) + digits(d2 / f) + 1
            options.append((cost, len(options), w.w["two"].format(
                p=p[i], d1=w.length(d1), p1=p[j], d2=w.length(d2), p2=p[m], side=side)))
    return min(options)[2]


def _actuators(w) -> list:
    return [w.w["actuator"].format(name=a.name, a=a.a, b=a.b)
            for a in w.mech.actuators.values()]


def _sliders(w) -> list:
    out = []
    for body in w.mech.bodies.values():
        if body.kind != "block":
            continue
        g = body.guide
        text = w.w["slider"].format(name=body.name, p=body.points[0], guide=_guide(w, g))
        carried = [_carried(w, body, other) for other in body.points[1:]]
        out.append(text + ("; " + "; ".join(carried) if carried else ""))
    return out


def fixed_line(mech, g):
    """(a point of the line, its unit direction) of guide ``g`` of the frame (SI)."""
    b, c = mech.fixed[g.b], mech.fixed[g.c]
    u = (c - b) / abs(c - b)
    return b + g.offset * 1j * u, u


def _guide(w, g) -> str:
    if g.carrier == FRAME:
        p0, u = fixed_line(w.mech, g)
        f = w.units.factor("length")
        if abs(u - 1) < CLOSE:
            return w.w["fixed_y"].format(y=w.length(p0.imag))
        if abs(u - 1j) < CLOSE:
            return w.w["fixed_x"].format(x=w.length(p0.real))
        named = [p for p, z in w.mech.fixed.items() if not p.startswith("~")
                 and abs(((z - p0) * u.conjugate()).imag) <= CLOSE * max(abs(z), abs(p0), f)]
        point = named[0] if named else w.point(p0)
        return w.w["fixed_line"].format(point=point, angle=w.angle(cmath.phase(u) %
                                                                    (2 * math.pi)))
    if g.carrier.endswith(".cylinder"):
        return w.w["actuator_line"].format(name=g.carrier[:-len(".cylinder")], b=g.b, c=g.c)
    carrier = g.carrier
    if g.offset == 0:
        return w.w["slot_on"].format(carrier=carrier, b=g.b, c=g.c)
    return w.w["slot"].format(carrier=carrier, b=g.b, c=g.c, offset=w.length(g.offset))


def _carried(w, body, other) -> str:
    """A pin on a block: in the frame's axes on a fixed guide when rounder, else in the
    guide's (along, left normal)."""
    f = w.units.factor("length")
    local = body.local[other] - body.local[body.points[0]]
    axes = w.w["guide_axes"]
    u, v = local.real, local.imag
    if body.guide.carrier == FRAME:
        _, direction = fixed_line(w.mech, body.guide)
        frame = local * direction
        if digits(frame.real / f) + digits(frame.imag / f) <= digits(u / f) + digits(v / f):
            u, v, axes = frame.real, frame.imag, w.w["frame_axes"]
    pair = f"{w.pair(u / f, v / f)} {w.units.names['length']}"
    return w.w["carries"].format(p=other, pair=pair, o=body.points[0], axes=axes)


def _contacts(w) -> list:
    out = []
    for r in w.mech.rolling.values():
        common = dict(disc=r.disc, c=r.center, r=w.length(r.radius))
        side = w.w["left"] if r.side > 0 else w.w["right"]
        if r.kind == "line":            # the contact's side: the centre is on the other
            side = w.w["left"] if r.side < 0 else w.w["right"]
            out.append(w.w["rolls_line"].format(dir=w.axis(r.direction), side=side, **common))
        elif r.kind == "circle":
            out.append(w.w["rolls_circle"].format(
                where=w.w["inside" if r.inside else "outside"], t=r.track,
                R=w.length(r.track_radius), **common))
        elif r.kind == "disc":
            out.append(w.w["rolls_disc"].format(
                where=w.w["inside" if r.inside else "outside"], other=r.other, t=r.track,
                R=w.length(r.track_radius), **common))
        elif r.kind == "cord":
            out.append(w.w["cord"].format(side=side, dir=w.axis(r.direction), p=r.point,
                                          **common))
        else:
            out.append(w.w["belt"].format(
                side=side, dir=w.axis(r.direction), other=r.other, t=r.track,
                R=w.length(r.track_radius),
                oside=w.w["left"] if r.other_side > 0 else w.w["right"], **common))
            if r.slip:
                out[-1] += "; " + w.w["belt_slip"].format(
                    s=w.num(100 * r.slip), disc=r.disc, kept=w.num(1 - r.slip))
    return out + _gears(w)


def _gears(w) -> list:
    """Each gear of ``gears:`` as the file gives it: teeth, module or diametral pitch."""
    out = []
    for g in w.mech.gears.values():
        key, value, unit = g.pitch
        pitch = f"{key.replace('_', ' ')} {w.num(value)} {unit}"
        out.append(w.w["gear"].format(name=g.name, z=g.teeth, pitch=pitch,
                                      r=w.length(g.radius), phi=w.angle(g.pressure_angle),
                                      a=w.length(g.addendum),
                                      internal=w.w["gear_internal"] if g.internal else ""))
    return out
