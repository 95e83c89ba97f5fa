"""Angles, lengths and coordinates of the kinematics and their rates, in SI.

The angle of a vector ``z = P_b - P_a`` and its rates follow from ``w = z'/z``:
``phi' = Im w``, ``phi'' = Im(z''/z - w^2)``; its length: ``r' = r Re w``,
``r'' = r (Re(z''/z - w^2) + (Re w)^2)``.  Angles are in [0, 2 pi) (``signed``: (-pi, pi]).
"""
from __future__ import annotations

import math

import numpy as np

from linkcli.model.mechanism import split_rate
from linkcli.model.units import ANGLE, LENGTH

TWO_PI = 2 * math.pi


def wrap_angle(value, principal=False):
    """Angle in [0, 2 pi); values within rounding (1e-12 rad) below 2 pi are 0.

    ``principal``: the value is already in [-pi, pi] (as from np.angle), so
    adding 2 pi to the negative ones is the same as the modulo, and cheaper.
    """
    if principal:
        return _wrap_principal(np.array(value, dtype=float))
    value = np.mod(value, TWO_PI)
    return np.where(value > TWO_PI - 1e-12, 0.0, value)


def _wrap_principal(out):
    """:func:`wrap_angle` of angles in (-pi, pi], in place: those <= 0 gain 2 pi (-0 and 0
    become 2 pi), those within 1e-12 rad of 2 pi are 0."""
    np.add(out, TWO_PI, out=out, where=out <= 0)
    np.copyto(out, 0.0, where=out > TWO_PI - 1e-12)
    return out


def signed_angle(value):
    """An angle of [0, 2 pi) in (-pi, pi]."""
    return np.where(value > math.pi, value - TWO_PI, value)


def relative(rates, a, b):
    """rates[b] - rates[a], absent (fixed) points having zero rate."""
    if a in rates:
        return rates[b] - rates[a] if b in rates else -rates[a]
    return rates.get(b, 0j)


def vector(quantity, kin, order):
    base = "angle" if quantity.kind == "angle" else "length"
    if order == 0:
        z = vector_rates(kin, quantity.a, quantity.b, rate=False)[0]
        value = wrap_angle(np.angle(z), principal=True) if base == "angle" else np.abs(z)
        return value, base
    return vector_rate(kin, quantity.a, quantity.b, order, base == "angle"), base


def vector_rate(kin, a, b, order, angle):
    """The rate of ``order`` (1 or 2) of the angle (``angle``) or length of P_b - P_a."""
    z, w = vector_rates(kin, a, b)
    if order == 1:
        return w.imag if angle else np.abs(z) * w.real
    dw = relative(kin.acc, a, b) / z
    if angle:                           # Im(z''/z - w^2)
        return dw.imag - 2.0 * w.real * w.imag
    dw = dw - w * w
    return np.abs(z) * (dw.real + w.real ** 2)


def vector_rates(kin, a, b, rate=True):
    """z = P_b - P_a and (``rate``) w = z'/z, kept on ``kin`` for the other orders."""
    cache = kin.vectors if hasattr(kin, "vectors") else {}
    z, w = cache.get((a, b), (None, None))
    if z is None:
        z = kin.pos[b] - kin.pos[a]
    if rate and w is None:
        w = relative(kin.vel, a, b) / z
    cache[(a, b)] = (z, w)
    return z, w


def override_unit(unit, base, order):
    """Display unit and SI factor for a quantity whose base unit is ``unit``."""
    factor = ANGLE[unit] if base == "angle" else LENGTH[unit]
    return unit + ["", "/s", "/s^2"][order], factor


def angle_period(mech, name: str, unit: str) -> float | None:
    """The turn (360 in deg, 2 pi in rad) of a quantity that is a direction, compared and
    plotted modulo a turn (:func:`is_direction`); None for any other quantity and for every
    rate."""
    base, order = split_rate(name, mech.quantities)
    if order or not is_direction(mech, mech.quantities[base]):
        return None
    return 360.0 if unit == "deg" else 2 * math.pi


def is_direction(mech, quantity) -> bool:
    """Whether ``quantity`` is an angle that names a direction, the same one turn off: an
    angle, a rotation, the angle between two vectors, an angle driver, the driver value of
    an extreme when the driver is an angle, the extreme of a direction, the equilibrium of
    an angle coordinate and a phase (-180 and 180 deg alike).  A swing (a stroke), an
    amplitude or a largest excursion measures an angle's size instead, and is not one."""
    kind = quantity.kind
    if quantity.angular or kind == "phase":
        return True
    if kind in ("q", "at_maximum", "at_minimum"):
        return mech.driver is not None and mech.driver.kind == "angle"
    if kind in ("maximum", "minimum"):
        base, order = split_rate(quantity.a, mech.quantities)
        return not order and base in mech.quantities and \
            is_direction(mech, mech.quantities[base])
    if kind == "equilibrium":
        return any(c.name == quantity.a and c.base == "angle" for c in mech.coordinates)
    return False
