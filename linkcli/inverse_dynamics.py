"""The unknown load by virtual power with the d'Alembert forces.

Per unit driver rate, sum_loads Q c_Q + P = 0 (``statics.unknown_load``) with the
extra power

    P = sum m (g - a_G) . v_G,unit - J alpha omega_unit     gravity and inertia
      + sum C omega_disc,unit                               known torques on rolling discs
      + sum T v_rel,unit                                    sliding friction (T from the
                                                            joint reactions)
"""
from __future__ import annotations

from . import dynamics as dyn_mod
from .friction import coefficients, friction_power
from .joint_forces import solve


def dynamic_power(mech, kin, unit_kin):
    """P (W per unit driver rate) at ``kin`` (accelerations needed), 0 without dynamics."""
    dyn = dyn_mod.model(mech)
    if dyn is None:
        return 0.0
    extra = dyn_mod.inertia_gravity_power(mech, dyn, kin, unit_kin.vel) + \
        dyn_mod.disc_torque_power(mech, dyn, kin, unit_kin.vel)
    if coefficients(dyn):
        extra = extra + friction_power(mech, dyn, kin, unit_kin.vel, solve(mech, kin))
    return extra
