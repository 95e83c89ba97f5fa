"""Motion of the massive bodies: centres of mass, spins, energies and the power terms.

G is placed with the body's rigid transform from two of its known points,

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

from dataclasses import dataclass

import numpy as np

from linkcli.model.mechanism import FRAME



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
