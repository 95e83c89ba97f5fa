"""The power balance of inverse dynamics, in numbers and (for ``explain``) in symbols.

    dE/dt = W_motor - W_resistant - W_lost

E the kinetic energy, W_motor the power of the unknown load, W_resistant minus the
power of the known loads and gravity, W_lost >= 0 the power lost (``friction``):

    W_lost = sum mu |N| |v_rel|            sliding friction at the sliders
           + sum u_r |N| |omega_disc|      rolling resistance of the discs
           + sum rho |R| |omega_rel|       friction circles at the pins

The unknown load by virtual power with the d'Alembert forces: per unit driver
rate, sum_loads Q c_Q + P = 0 (``statics.unknown_load``) with the extra power

    P = sum m (g - a_G) . v_G,unit - J alpha omega_unit     gravity and inertia
      + sum C omega_disc,unit                               known torques on rolling discs
      + sum T v_rel,unit                                    sliding friction (T from the
                                                            joint reactions)
      + sum M omega_disc,unit + sum M omega_rel,unit        rolling resistance and friction
                                                            circles (M from the reactions)
"""
from __future__ import annotations

import numpy as np

from linkcli.forces import motion as dyn_mod
from linkcli.forces.friction import (coefficients, friction_circles, friction_power,
                                     has_losses, resistances)
from linkcli.forces.joint_forces import solve
from linkcli.kinematics.solvers import state
from linkcli.forces.statics import coefficient, unknown_load
from linkcli.model.rounding import noise_free
from linkcli.model.units import FORCE, TORQUE


def balance(mech, q=None) -> dict:
    """Terms of dE/dt = W_motor - W_resistant - W_lost (W) at driver value ``q`` (SI;
    default the file's), with the unknown load's value (SI) and E (J)."""
    dyn = mech.dynamics
    kin, unit = state(mech, q)
    value = unknown_load(mech, kin.pos, unit.vel, extra_power=dynamic_power(mech, kin, unit),
                         q=kin.q)
    rate = mech.driver.rate
    motor = value * coefficient(mech, mech.unknown_load(), kin.pos, unit.vel) * rate
    lost = -friction_power(mech, dyn, kin, kin.vel, solve(mech, kin)) \
        if has_losses(dyn) else 0.0
    resistant = -(_known_power(mech, dyn, kin, unit.vel) + dyn_mod.gravity_power(mech, dyn, kin))
    return {"dEdt": dyn_mod.energy_rate(mech, dyn, kin), "motor": motor,
            "resistant": resistant, "lost": lost,
            "unknown": value, "E": dyn_mod.kinetic_energy(mech, dyn, kin.pos, kin.vel)}


def dynamic_power(mech, kin, unit_kin, reactions=None):
    """P (W per unit driver rate) at ``kin`` (accelerations needed), 0 without dynamics;
    the losses' from ``reactions``, the joint forces at ``kin`` (solved when not given)."""
    dyn = mech.dynamics
    if dyn is None:
        return 0.0
    extra = dyn_mod.inertia_gravity_power(mech, dyn, kin, unit_kin.vel) + \
        dyn_mod.disc_torque_power(mech, dyn, kin, unit_kin.vel)
    if has_losses(dyn):
        reactions = solve(mech, kin) if reactions is None else reactions
        extra = extra + friction_power(mech, dyn, kin, unit_kin.vel, reactions)
    return extra


def _known_power(mech, dyn, kin, unit_vel):
    """Power of the known loads, sum Q c_Q qdot, torques on rolling discs included (W)."""
    rate = mech.driver.rate
    known = 0.0
    for load in mech.loads.values():
        if load.value is not None:
            known = known + load.value * coefficient(mech, load, kin.pos, unit_vel) * rate
    return known + dyn_mod.disc_torque_power(mech, dyn, kin, unit_vel) * rate


# --- the balance written out -----------------------------------------------------------
def balance_lines(mech) -> list[str]:
    """The power balance of ``explain``: symbols, then numbers at the file's position."""
    dyn = mech.dynamics
    if dyn is None:
        return []
    energy, rate, gravity = _mass_symbols(dyn)
    equations = ["  E = " + _sum(energy), "  dE/dt = " + _sum(rate)]
    if not any(ld.value is None for ld in mech.loads.values()):
        return ["Power balance (inverse dynamics): no unknown load in this file"] + equations
    return ["Power balance (inverse dynamics): dE/dt = W_motor - W_resistant - W_lost"] + \
        equations + _power_symbols(mech, dyn, gravity) + _data_lines(dyn) + _numbers(mech)


def _sum(terms) -> str:
    return " + ".join(terms) or "0"


def _mass_symbols(dyn):
    """Terms of E, of dE/dt and of the power of gravity, one per mass, in symbols."""
    terms = [t for mb in dyn.bodies.values() for t in _body_symbols(mb)]
    for disc in dyn.discs.values():
        c, n = disc.center, disc.name
        terms.append((f"1/2 m_{n} |v_{c}|^2 + 1/2 J_{n} omega_{n}^2",
                      f"m_{n} a_{c} . v_{c} + J_{n} alpha_{n} omega_{n}", f"m_{n} g . v_{c}"))
    for p in dyn.masses:
        terms.append((f"1/2 m_{p} |v_{p}|^2", f"m_{p} a_{p} . v_{p}", f"m_{p} g . v_{p}"))
    return [t[0] for t in terms], [t[1] for t in terms], [t[2] for t in terms if t[2]]


def _body_symbols(mb) -> list[tuple]:
    """(E, dE/dt, gravity power) terms of a body's mass (at G) and moment of inertia."""
    b = mb.body
    terms = []
    if mb.mass:
        terms.append((f"1/2 m_{b} |v_G({b})|^2", f"m_{b} a_G({b}) . v_G({b})",
                      f"m_{b} g . v_G({b})"))
    if mb.inertia:
        terms.append((f"1/2 J_{b} omega_{b}^2", f"J_{b} alpha_{b} omega_{b}", None))
    return terms


def _load_symbol(load) -> str:
    """A load's power in symbols: Q . v, C omega, F d|AB|/dt or Q qdot."""
    return {"force": f"{load.name} . v_{load.target}",
            "torque": f"{load.name} omega_{load.target}",
            "axial": f"{load.name} d|{load.target}|/dt",
            "driver": f"{load.name} qdot"}[load.kind]


def _power_symbols(mech, dyn, gravity) -> list[str]:
    """W_motor, W_resistant (known loads and, with g, gravity) and W_lost in symbols."""
    resistant = [_load_symbol(ld) for ld in mech.loads.values() if ld.value is not None]
    if dyn.gravity:
        resistant += gravity
    lost = [f"mu_{s} |N_{s}| |v_{s},rel|" for s in coefficients(dyn)]
    lost += [f"u_{d.name} |N_{d.name}| |omega_{d.name}|" for d in resistances(dyn).values()]
    lost += [f"rho_{p} |R_{p}| |omega_{f.other} - omega_{f.holder}|"
             for p, f in friction_circles(dyn).items()]
    return [f"  W_motor = {_load_symbol(mech.unknown_load())}   (the unknown load)",
            "  W_resistant = -(" + _sum(resistant) + ")",
            "  W_lost = " + _sum(lost)]


def _data_lines(dyn) -> list[str]:
    """The rolling discs' spin omega = -s (v_C . u)/R, the losses' data and the gravity
    vector."""
    lines = [f"  rolling disc {disc.name}: omega_{disc.name} = "
             f"{'-' if disc.side > 0 else '+'}(v_{disc.center} . u)/R, R = {disc.radius:g} m"
             for disc in dyn.discs.values()]
    lines += [f"  rolling resistance of {disc.name}: u_{disc.name} = {disc.resistance:g} m"
              for disc in resistances(dyn).values()]
    lines += [f"  friction circle at {p}: rho_{p} = {f.radius:g} m, {f.other} turning on the pin "
              f"fixed in {f.holder}" for p, f in friction_circles(dyn).items()]
    if dyn.gravity:
        g = dyn.gravity
        lines.append(f"  g = ({g.real:.6g}, {g.imag:.6g}) m/s^2")
    return lines


def _numbers(mech) -> list[str]:
    """The balance's terms (W) and the unknown load at the file's position."""
    terms = balance(mech)
    unknown = mech.unknown_load()
    value = noise_free(terms["unknown"], _unknown_scale(mech))
    value = _display_load(mech, unknown, value)
    watts = {k: f"{float(np.asarray(terms[k])) + 0.0:.6g} W"
             for k in ("dEdt", "motor", "resistant", "lost")}
    return [f"  at the file's position: dE/dt = {watts['dEdt']}, W_motor = {watts['motor']}, "
            f"W_resistant = {watts['resistant']}, W_lost = {watts['lost']}",
            f"  {unknown.name} = {value}"]


def _unknown_scale(mech) -> float:
    """The scale of the unknown load at the file's position (SI): the terms it balances per
    unit driver rate, in magnitude, over |c|, its own virtual power per unit rate,

        (sum |m (g - a_G)| |v_G,unit| + |J alpha omega_unit| + sum |Q c_Q|) / |c|,

    the magnitudes of the vectors rather than their dot products, so that the scale does
    not vanish where a lever does (an unknown that balances weights acting across the
    motion is still measured against those weights)."""
    dyn = mech.dynamics
    kin, unit = state(mech)
    actual = dyn_mod.motions(mech, dyn, kin.pos, kin.vel, kin.acc)
    moved = dyn_mod.motions(mech, dyn, kin.pos, unit.vel)
    total = sum(abs(a.mass) * abs(dyn.gravity - a.a) * abs(u.v) + abs(a.inertia * a.alpha * u.omega)
                for a, u in zip(actual, moved))
    total = total + sum(abs(ld.value * coefficient(mech, ld, kin.pos, unit.vel))
                        for ld in mech.loads.values() if ld.value is not None)
    lever = abs(coefficient(mech, mech.unknown_load(), kin.pos, unit.vel))
    if not np.all(np.asarray(lever) > 0):      # no lever: unknown_load refuses it before
        return 0.0
    return float(np.max(np.asarray(total / lever, dtype=float)))


def _display_load(mech, load, value) -> str:
    """``value`` (SI) in the file's force or torque unit, with the unit."""
    kind = mech.load_unit_kind(load)
    unit = mech.units.names[kind]
    table = FORCE if kind == "force" else TORQUE
    return f"{value / table[unit]:.6g} {unit}"
