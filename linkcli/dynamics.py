"""Mass properties, gravity, Coulomb friction and rolling discs: the ``dynamics:`` section.

Everything here is in SI units.  A massive body has mass ``m``, inertia ``J``
about its centre of mass G and G fixed in the body.  G is placed with the
body's rigid transform from two of its known points,

    G = K + (M - K) w,   w = (g - k) / (m - k)   (local coordinates g, k, m),

so ``v_G`` and ``a_G`` follow linearly from the points' velocities and
accelerations.  The body's angular velocity and acceleration come from any
vector z fixed in it: ``omega = Im(z'/z)``, ``alpha = Im(z''/z - (z'/z)^2)``.

A disc rolling without slipping has its centre C on a slider of a fixed
line (direction u); with the centre on the ``side`` s = +1 (left of u) or
-1 (right) of the ground line, the contact point is ``H = C - R s i u`` and
no slip gives ``omega = -s (v_C . u) / R``, ``alpha = -s (a_C . u) / R``.

Inverse dynamics by virtual power (d'Alembert), per unit driver rate:

    sum(loads) + sum_b [ m_b (g - a_Gb) . v_Gb + (-J_b alpha_b) omega_b ] + friction = 0,

equivalently ``dE/dt = W_motor - W_resistant - W_lost``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .model import FRAME

STANDARD_SIDE = {"left": 1, "right": -1}


@dataclass(frozen=True)
class MassBody:
    """Mass ``mass`` (kg) and inertia ``inertia`` (kg m^2, about G) of one body;
    ``center`` is G in the body's local coordinates (m)."""

    body: str
    mass: float
    inertia: float
    center: complex


@dataclass(frozen=True)
class Disc:
    """A disc rolling without slipping; its centre is the point of slider ``slider``."""

    name: str
    slider: str
    center: str
    radius: float
    side: int
    mass: float
    inertia: float


@dataclass
class Dynamics:
    gravity: complex = 0j                               # m/s^2
    bodies: dict = field(default_factory=dict)          # body -> MassBody
    masses: dict = field(default_factory=dict)          # point -> kg
    friction: dict = field(default_factory=dict)        # slider -> mu
    discs: dict = field(default_factory=dict)           # disc name -> Disc

    def disc_on(self, slider: str):
        return next((d for d in self.discs.values() if d.slider == slider), None)


# --- parsing --------------------------------------------------------------------
def model(mech) -> Dynamics | None:
    """The parsed ``dynamics:`` section of ``mech`` (cached), None when absent."""
    extras = mech.extras
    if extras.get("dynamics") is None:
        return None
    if "dynamics_model" not in extras:
        extras["dynamics_model"] = parse(mech)
    return extras["dynamics_model"]


def parse(mech) -> Dynamics:
    """Validate the raw section; every problem is reported with its key and line."""
    from .parsing import InputErrors, Parser, _Skip
    doc = mech.extras.get("doc")
    parser = Parser(doc, None)
    parser.names = dict(mech.extras.get("names") or {})
    reader = _Reader(parser, mech, _Skip)
    dyn = reader.run(mech.extras["dynamics"])
    if parser.errors:
        raise InputErrors(parser.errors)
    return dyn


class _Reader:
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
                                               "discs"}) if spec is not None else {}
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
        """off/false/0: none; a number g (m/s^2, along -y); or {g, angle}."""
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
        spec = self.p.mapping(value, path, {"center", "radius", "mass", "inertia", "side"},
                              ("center", "radius"))
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
        return Disc(name, block.name, center, radius, STANDARD_SIDE[side], mass, inertia)


# --- motion of bodies -----------------------------------------------------------------
def guide_axis(mech, guide, pos):
    """Direction vector C - B of a guide (its length is constant)."""
    return pos[guide.c] - pos[guide.b]


def _get(d, name):
    return d.get(name, 0.0) if d is not None else None


def axis_vector(mech, name, d):
    """A vector fixed in body ``name``, from the position/velocity/acceleration map ``d``."""
    body = mech.bodies[name]
    if body.kind == "link":
        return _get(d, body.points[1]) - _get(d, body.points[0])
    if body.kind == "block":
        return _get(d, body.guide.c) - _get(d, body.guide.b)
    act = mech.actuators[name.rsplit(".", 1)[0]]
    return _get(d, act.b) - _get(d, act.a)


def rotation(mech, name, pos, vel, acc=None):
    """(omega, alpha) of body ``name``: omega = Im(z'/z), alpha = Im(z''/z - (z'/z)^2)."""
    z = axis_vector(mech, name, pos)
    w = axis_vector(mech, name, vel) / z
    omega = w.imag
    if acc is None:
        return omega, None
    return omega, (axis_vector(mech, name, acc) / z - w * w).imag


def rigid_point(mech, name, local, pos, vel=None, acc=None):
    """Position (and velocity, acceleration) of the point of body ``name`` at ``local``."""
    body = mech.bodies[name]
    if body.kind in ("link", "block"):
        k = body.points[0]
        if body.kind == "link":
            m, n = body.points[1], k
            w = (local - body.local[k]) / (body.local[m] - body.local[k])
        else:
            m, n = body.guide.c, body.guide.b
            w = (local - body.local[k]) / np.abs(pos[m] - pos[n])
        out = [pos[k] + (pos[m] - pos[n]) * w]
        for d in (vel, acc):
            out.append(None if d is None else _get(d, k) + (_get(d, m) - _get(d, n)) * w)
        return tuple(out)
    act = mech.actuators[name.rsplit(".", 1)[0]]
    k = act.a if body.kind == "cylinder" else act.b
    z = pos[act.b] - pos[act.a]
    arm = z / np.abs(z) * local
    out = [pos[k] + arm]
    if vel is None:
        return out[0], None, None
    omega, alpha = rotation(mech, name, pos, vel, acc)
    out.append(_get(vel, k) + 1j * omega * arm)
    out.append(None if acc is None else _get(acc, k) + (1j * alpha - omega ** 2) * arm)
    return tuple(out)


def disc_spin(mech, disc, pos, vel, acc=None):
    """(omega, alpha) of a rolling disc: omega = -s (v_C . u) / R."""
    guide = mech.bodies[disc.slider].guide
    z = guide_axis(mech, guide, pos)
    u = z / np.abs(z)
    scale = -disc.side / disc.radius
    omega = scale * (np.conj(u) * _get(vel, disc.center)).real
    alpha = None if acc is None else scale * (np.conj(u) * _get(acc, disc.center)).real
    return omega, alpha


@dataclass
class Motion:
    """Centre of mass position, velocity, acceleration and the spin of one mass."""

    name: str
    mass: float
    inertia: float
    g: object
    v: object
    a: object
    omega: object
    alpha: object


def motions(mech, dyn, pos, vel, acc=None) -> list[Motion]:
    """Every mass of the mechanism (bodies, discs, point masses) in motion."""
    out = []
    for mb in dyn.bodies.values():
        g, v, a = rigid_point(mech, mb.body, mb.center, pos, vel, acc)
        omega, alpha = rotation(mech, mb.body, pos, vel, acc)
        out.append(Motion(mb.body, mb.mass, mb.inertia, g, v, a, omega, alpha))
    for disc in dyn.discs.values():
        omega, alpha = disc_spin(mech, disc, pos, vel, acc)
        out.append(Motion(disc.name, disc.mass, disc.inertia, pos[disc.center],
                          _get(vel, disc.center), _get(acc, disc.center), omega, alpha))
    for point, mass in dyn.masses.items():
        out.append(Motion(point, mass, 0.0, pos[point], _get(vel, point), _get(acc, point),
                          0.0, 0.0 if acc is not None else None))
    return out


def dot(a, b):
    """Scalar product of two plane vectors given as complex numbers."""
    return (np.conj(a) * b).real


# --- power terms ----------------------------------------------------------------------
def inertia_gravity_power(mech, dyn, kin, unit_vel):
    """Power of gravity and of the inertia forces and torques per unit driver rate:

        sum m (g - a_G) . v_G,unit - J alpha omega_unit
    """
    actual = motions(mech, dyn, kin.pos, kin.vel, kin.acc)
    unit = motions(mech, dyn, kin.pos, unit_vel)
    total = 0.0
    for m_act, m_unit in zip(actual, unit):
        total = total + m_act.mass * dot(dyn.gravity - m_act.a, m_unit.v) \
            - m_act.inertia * m_act.alpha * m_unit.omega
    return total


def disc_torque_power(mech, dyn, kin, unit_vel):
    """Power per unit rate of known torques on rolling discs (their spin is not the block's)."""
    total = 0.0
    for disc in dyn.discs.values():
        omega, _ = disc_spin(mech, disc, kin.pos, unit_vel)
        for load in mech.loads.values():
            if load.kind == "torque" and load.target == disc.slider and load.value is not None:
                total = total + load.value * omega
    return total


def kinetic_energy(mech, dyn, pos, vel):
    """E = sum 1/2 m |v_G|^2 + 1/2 J omega^2 (J)."""
    total = 0.0
    for m in motions(mech, dyn, pos, vel):
        total = total + 0.5 * m.mass * np.abs(m.v) ** 2 + 0.5 * m.inertia * m.omega ** 2
    return total


def energy_rate(mech, dyn, kin):
    """dE/dt = sum m a_G . v_G + J alpha omega (W)."""
    total = 0.0
    for m in motions(mech, dyn, kin.pos, kin.vel, kin.acc):
        total = total + m.mass * dot(m.a, m.v) + m.inertia * m.alpha * m.omega
    return total


def gravity_power(mech, dyn, kin):
    """sum m g . v_G (W)."""
    total = 0.0
    for m in motions(mech, dyn, kin.pos, kin.vel):
        total = total + m.mass * dot(dyn.gravity, m.v)
    return total


def sliding_velocity(mech, slider, pos, vel):
    """Velocity of a slider along its guide, relative to the guide's carrier (m/s)."""
    block = mech.bodies[slider]
    guide = block.guide
    z = guide_axis(mech, guide, pos)
    u = z / np.abs(z)
    p = block.points[0]
    v = _get(vel, p)
    if guide.carrier != FRAME:
        omega, _ = rotation(mech, guide.carrier, pos, vel)
        v = v - (_get(vel, guide.b) + 1j * omega * (pos[p] - pos[guide.b]))
    return dot(u, v)
