"""The data lines of the masses: gravity, each body's mass and moment of inertia with its
centre of mass, point masses, Coulomb friction on the guides, the rolling discs with their
rolling resistance, and the friction circles of the pins.

A centre of mass is stated as a point of the body where it is one, else by its
coordinates in the body's own frame (a link's base side, a slider's guide, an actuator's
line).
"""
from __future__ import annotations

import cmath
import math

from linkcli.texts.amounts import CLOSE


def mass_lines(w) -> list:
    """Gravity, the masses and inertias, friction and the rolling discs, a line each
    (``w`` a :class:`~linkcli.texts.amounts.Writer`; none without a dynamics section)."""
    dyn = w.mech.dynamics
    if dyn is None:
        return []
    out = []
    if dyn.gravity:
        g = abs(dyn.gravity)
        direction = w.w["at_angle"].format(angle=w.angle(cmath.phase(dyn.gravity) %
                                                         (2 * math.pi)))
        if abs(dyn.gravity / g + 1j) < CLOSE:
            direction = f"{w.w['down']} ({direction})"
        out.append(w.w["gravity"].format(g=f"{w.num(g)} m/s^2", direction=direction))
    for mb in dyn.bodies.values():
        out.append(_mass_body(w, mb))
    out += [w.w["point_mass"].format(m=w.amount(m, "mass"), p=p) for p, m in dyn.masses.items()]
    out += [w.w["friction"].format(name=s, mu=w.num(mu)) for s, mu in dyn.friction.items()]
    for disc in dyn.discs.values():
        text = w.w["disc"].format(name=disc.name, c=disc.center, r=w.length(disc.radius),
                                  m=w.amount(disc.mass, "mass"),
                                  J=w.amount(disc.inertia, "inertia"),
                                  side=w.w["left"] if disc.side > 0 else w.w["right"])
        if disc.resistance:
            text += ", " + w.w["resistance"].format(u=w.length(disc.resistance))
        out.append(text)
    out += [w.w["pin"].format(p=p, rho=w.length(pin.radius)) for p, pin in dyn.pins.items()]
    return out


def _mass_body(w, mb) -> str:
    mech = w.mech
    body = mech.bodies[mb.body]
    if body.kind == "link":
        owner = w.w["of_link"].format(name=body.name)
    elif body.kind == "block":
        owner = w.w["of_slider"].format(name=body.name)
    else:
        name, half = body.name.rsplit(".", 1)
        owner = w.w["of_" + half].format(name=name)
    key = "mass" if mb.mass and mb.inertia else "mass_only" if mb.mass else "inertia_only"
    return w.w[key].format(body=owner, m=w.amount(mb.mass, "mass"),
                           J=w.amount(mb.inertia, "inertia"), where=_centre(w, body, mb.center))


def _centre(w, body, centre) -> str:
    """Where G is: a point of the body, or coordinates in the body's own frame."""
    f = w.units.factor("length")
    size = max([abs(z) for z in body.local.values()] + [f])
    for p, z in body.local.items():
        if abs(z - centre) <= CLOSE * size:
            return w.w["at_point"].format(p=p)
    x, y = w.num(centre.real / f), w.num(centre.imag / f)
    unit = w.units.names["length"]
    if body.kind == "link":
        a, b = body.points[0], body.points[1]
        return w.w["in_frame"].format(x=x, y=y, a=a, b=b).replace(")", f") {unit}", 1)
    if body.kind == "block":
        return w.w["in_block"].format(x=x, y=y, p=body.points[0]).replace(")", f") {unit}", 1)
    act = w.mech.actuators[body.name.rsplit(".", 1)[0]]
    return w.w["on_actuator"].format(x=x, y=y, p=body.points[0], a=act.a,
                                     b=act.b).replace(")", f") {unit}", 1)
