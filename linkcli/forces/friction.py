"""Losses: Coulomb friction at the sliders, rolling resistance of discs, friction circles.

Each loss opposes a relative motion with a force or couple proportional to a contact
force that the joint reactions carry:

- slider: T = -mu sgn(v_rel) |N| along the guide direction u, with v_rel the block's
  velocity along u relative to the guide's carrier and N the normal force on the block
  along n = i u;
- rolling disc: the ground's couple on the disc M = -u_r sgn(omega) |N|, with u_r the
  rolling resistance (the length by which N is shifted ahead of the contact), omega the
  disc's spin and N the contact's normal force;
- pin with a friction circle of radius rho: the couple on the body whose eye turns on the
  pin (``other``) M = -rho sgn(omega_other - omega_holder) |R|, with R the force of the pin
  on ``other``, and -M on the body the pin is fixed in (``holder``).

|N| = s N with the sign s of N assumed (then checked) makes T and M linear in N.  |R| is
linearised as e . R with e the direction of R of the previous iterate: exact when e is
R's direction, and in error only to second order in the change of e, so the iteration
converges quadratically.  Where a relative motion is zero, the sense of its loss is
undetermined and the joint forces are refused (a slider at rest has no friction force).
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from linkcli.errors import AtRestError
from linkcli.forces import motion as dyn_mod
from linkcli.kinematics.refusals import where_text
from linkcli.model.mechanism import FRAME

#: a relative rotation at most AT_REST times the mechanism's largest rate has no sense
AT_REST = 1e-9


def coefficients(dyn) -> dict:
    """Slider -> mu of the sliders with friction (mu > 0); none without dynamics."""
    return {} if dyn is None else {s: mu for s, mu in dyn.friction.items() if mu > 0}


def resistances(dyn) -> dict:
    """Disc slider -> rolling resistance u_r (m) of the discs that have one."""
    return {} if dyn is None else {d.slider: d for d in dyn.discs.values() if d.resistance > 0}


def friction_circles(dyn) -> dict:
    """Point -> PinFriction of the pins with a friction circle (rho > 0)."""
    return {} if dyn is None else {p: f for p, f in dyn.pins.items() if f.radius > 0}


def has_losses(dyn) -> bool:
    """Whether the joint reactions carry any loss."""
    return bool(coefficients(dyn) or resistances(dyn) or friction_circles(dyn))


def body_spin(mech, dyn, body, pos, vel):
    """Angular velocity of ``body`` (a rolling disc's slider: the disc's spin; 0 for the
    frame)."""
    if body == FRAME:
        return 0.0
    disc = dyn.disc_on(body) if dyn is not None else None
    if disc is not None:
        return dyn_mod.disc_spin(mech, disc, pos, vel)[0]
    return dyn_mod.rotation(mech, body, pos, vel)[0]


def pin_rate(mech, dyn, pin, pos, vel):
    """omega_other - omega_holder at a pin."""
    return body_spin(mech, dyn, pin.other, pos, vel) - body_spin(mech, dyn, pin.holder, pos, vel)


@dataclass
class Losses:
    """The losses at the positions of ``kin``: the senses sigma of the relative motions
    (fixed) and the iterate's assumed signs s of the normal forces and directions e of
    the pins' forces."""

    sliders: dict                                    # slider -> mu
    discs: dict                                      # disc slider -> Disc
    pins: dict                                       # point -> PinFriction
    sigma: dict = field(default_factory=dict)        # (kind, name) -> sgn of the motion
    signs: dict = field(default_factory=dict)        # (kind, name) -> assumed sgn N
    directions: dict = field(default_factory=dict)   # point -> assumed unit R (0: none yet)
    #: the fraction t of every coefficient applied (mu t, u_r t, rho t): 0 frictionless
    scale: float = 1.0

    @property
    def any(self) -> bool:
        return bool(self.sliders or self.discs or self.pins)

    def scaled(self, t: float) -> "Losses":
        """The same losses with every coefficient times ``t`` (the same signs, directions)."""
        return replace(self, scale=t)

    def slider_factor(self, name):
        """T/N = -mu t sgn(v_rel) s of a slider (0 without friction)."""
        if name not in self.sliders:
            return 0.0
        return -self.sliders[name] * self.scale * self.sigma[("slider", name)] * \
            self.signs[("slider", name)]

    def disc_factor(self, name):
        """M/N = -u_r t sgn(omega) s of a rolling disc (0 without rolling resistance)."""
        if name not in self.discs:
            return 0.0
        return -self.discs[name].resistance * self.scale * self.sigma[("disc", name)] * \
            self.signs[("disc", name)]

    def pin_factor(self, point, body, part):
        """The couple on ``other`` per unit x (part 0) or y (part 1) of the pin's force on
        it: -rho t sgn(omega_rel) e_x (e_y); None when ``body`` is not the pin's ``other``."""
        pin = self.pins.get(point)
        if pin is None or pin.other != body:
            return None
        e = self.directions[point]
        return -pin.radius * self.scale * self.sigma[("pin", point)] * \
            (np.real(e) if part == 0 else np.imag(e))

    def describe(self) -> str:
        """The losses (times ``scale`` where it is a number), for messages."""
        t = self.scale if np.ndim(self.scale) == 0 else 1.0
        parts = [f"mu = {mu * t:.6g} at slider {s}" for s, mu in self.sliders.items()]
        parts += [f"rolling resistance {d.resistance * t:.6g} m of disc {d.name}"
                  for d in self.discs.values()]
        parts += [f"friction circle {pin.radius * t:.6g} m at pin {p}"
                  for p, pin in self.pins.items()]
        return ", ".join(parts)


def losses_at(mech, kin) -> Losses:
    """The losses of ``mech`` with the senses of the relative motions at ``kin``
    (velocities needed when there are any); s = +1 and e = 0 to start."""
    dyn = mech.dynamics
    out = Losses(coefficients(dyn), resistances(dyn), friction_circles(dyn))
    if not out.any:
        return out
    shape = np.shape(kin.q)
    scale, size = _largest_rate(mech, dyn, kin)
    for s in out.sliders:
        v = dyn_mod.sliding_velocity(mech, s, kin.pos, kin.vel)
        _require_motion(mech, kin, v / size, scale, f"the friction at slider {s}",
                        "it does not slide there (v = {value:.3g} of the mechanism's size "
                        "per second)")
        out.sigma[("slider", s)] = np.sign(v)
        out.signs[("slider", s)] = np.ones(shape)
    for s, disc in out.discs.items():
        omega = dyn_mod.disc_spin(mech, disc, kin.pos, kin.vel)[0]
        _require_motion(mech, kin, omega, scale, f"the rolling resistance of disc {disc.name}",
                        "the disc does not roll there (omega = {value:.3g} rad/s)")
        out.sigma[("disc", s)] = np.sign(omega)
        out.signs[("disc", s)] = np.ones(shape)
    for p, pin in out.pins.items():
        omega = pin_rate(mech, dyn, pin, kin.pos, kin.vel)
        _require_motion(mech, kin, omega, scale, f"the friction couple at pin {p}",
                        f"{pin.other} does not turn relative to {pin.holder} there "
                        "(omega_rel = {value:.3g} rad/s)")
        out.sigma[("pin", p)] = np.sign(omega)
        out.directions[p] = np.zeros(shape, dtype=complex)
    return out


def _largest_rate(mech, dyn, kin):
    """(the mechanism's largest rate (1/s): its bodies' and discs' angular velocities and
    its largest speed over its size, at each position; its size)."""
    pos, vel = kin.pos, kin.vel
    first = pos[mech.points[0]]
    size = max(float(np.max(np.abs(np.asarray(pos[p] - first)))) for p in mech.points) or 1.0
    top = 0.0
    for p in mech.points:
        top = np.maximum(top, np.abs(vel.get(p, 0.0)) / size)
    for name in mech.bodies:
        top = np.maximum(top, np.abs(body_spin(mech, dyn, name, pos, vel)))
    return top, size


def _require_motion(mech, kin, omega, scale, what, why):
    """Refuse where |omega| <= AT_REST times the largest rate: the loss has no sense."""
    still = np.abs(omega) <= AT_REST * scale
    if np.any(still):
        mask = np.broadcast_to(still, np.shape(kin.q))
        value = float(np.ravel(np.broadcast_to(omega, np.shape(kin.q))[mask])[0]) + 0.0
        ratio = abs(value) / float(np.max(scale)) if np.max(scale) > 0 else 0.0
        raise AtRestError(f"{what} is undetermined {where_text(mech, kin.q, mask)}: "
                          + why.format(value=value) + f", {ratio:.1e} of the mechanism's "
                          "largest rate, so the sense of the loss is unknown", file=mech.file,
                          hint="move the driver away from that position, or give the driver "
                          "a rate: its sign says which way the mechanism moves",
                          what=what, rows=mask, measure=ratio, q=kin.q)


def update(losses, normals, forces):
    """The next iterate's signs s = sgn N (``normals``: (kind, name) -> N) and directions
    e = R / |R| (``forces``: point -> R on ``other``; 0 where R = 0).  Returns the new
    Losses and whether every sign was kept."""
    signs = {k: np.where(np.asarray(normals[k]) < 0, -1.0, 1.0) for k in losses.signs}
    kept = all(np.array_equal(signs[k], losses.signs[k]) for k in signs)
    directions = {}
    for p, r in forces.items():
        size = np.abs(r)
        directions[p] = np.where(size > 0, r / np.where(size > 0, size, 1.0), 0.0)
    return replace(losses, signs=signs, directions=directions), kept


def friction_force(mu, sigma, normal):
    """T = -mu sgn(v_rel) |N| (N)."""
    return -mu * sigma * np.abs(normal)


def couple(radius, sigma, force):
    """M = -rho sgn(omega_rel) |R| (N m): a friction circle's or a rolling resistance's."""
    return -radius * sigma * np.abs(force)


def friction_power(mech, dyn, kin, unit_vel, reactions):
    """Power per unit driver rate (or, with ``unit_vel`` the actual velocities, the power)
    of the losses, from ``reactions``: sum T v_rel + sum M omega_disc + sum M omega_rel
    (<= 0 with the actual velocities)."""
    total = 0.0
    for slider in coefficients(dyn):
        v = dyn_mod.sliding_velocity(mech, slider, kin.pos, unit_vel)
        total = total + reactions.pairs[slider].friction * v
    for slider, disc in resistances(dyn).items():
        omega = dyn_mod.disc_spin(mech, disc, kin.pos, unit_vel)[0]
        total = total + reactions.resistances[slider] * omega
    for point, pin in friction_circles(dyn).items():
        total = total + reactions.pin_couples[point] * pin_rate(mech, dyn, pin, kin.pos,
                                                                 unit_vel)
    return total
