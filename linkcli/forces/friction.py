"""Coulomb friction at the sliders: T = -mu sgn(v_rel) |N| along the guide direction u.

v_rel is the block's velocity along u relative to the guide's carrier and N the normal
force on the block along n = i u.  Writing |N| = s N (s = sgn N, assumed then checked)
makes T linear in N: T = (-mu sgn(v_rel) s) N.
"""
from __future__ import annotations

import numpy as np

from linkcli.forces import motion as dyn_mod


def coefficients(dyn) -> dict:
    """Slider -> mu of the sliders with friction (mu > 0); none without dynamics."""
    return {} if dyn is None else {s: mu for s, mu in dyn.friction.items() if mu > 0}


def sliding_signs(mech, kin, friction) -> dict:
    """Slider -> sgn(v_rel) at every driver value."""
    return {s: np.sign(dyn_mod.sliding_velocity(mech, s, kin.pos, kin.vel)) for s in friction}


def normal_factors(friction, sigma, signs) -> dict:
    """Slider -> T/N = -mu sgn(v_rel) s for the assumed signs s of N."""
    return {s: -friction[s] * sigma[s] * signs[s] for s in friction}


def friction_force(mu, sigma, normal):
    """T = -mu sgn(v_rel) |N| (N)."""
    return -mu * sigma * np.abs(normal)


def friction_power(mech, dyn, kin, unit_vel, reactions):
    """Power per unit driver rate of the friction forces: sum T v_rel,unit (T from
    ``reactions``)."""
    total = 0.0
    for slider in coefficients(dyn):
        v = dyn_mod.sliding_velocity(mech, slider, kin.pos, unit_vel)
        total = total + reactions.pairs[slider].friction * v
    return total
