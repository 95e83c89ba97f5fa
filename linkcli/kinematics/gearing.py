"""The geometry of a pair of involute gears (model.gears.Gear), as the course states it.

- centre distance: a = r1 + r2 for two external gears, a = r2 - r1 when gear 2 is
  internal (a ring about the pinion);
- contact ratio: the length of the path of contact over the base pitch,
  eps = (sqrt(ra1^2 - rb1^2) +/- sqrt(ra2^2 - rb2^2) -/+ a sin(phi)) / (pi m cos(phi)),
  with rb = r cos(phi) the base radii and ra the addendum radii (r + a; r - a for an
  internal gear, whose terms take the lower signs), which is the arc of contact
  (path / cos(phi)) over the circular pitch pi m;
- the fewest teeth a pinion may have without interference (undercut) when it meshes
  with a wheel of G times its teeth whose addendum is A_w modules:
  z_min = 2 A_w / (sqrt(G^2 + (1 + 2 G) sin^2(phi)) - G)  (Khurmi, "Theory of Machines",
  12.23: t = 2 A_W / (G (sqrt(1 + (1/G)(1/G + 2) sin^2 phi) - 1)), the same), which tends
  to 2 A / sin^2(phi) for a rack (G -> infinity): 17.1 for 20 degrees.
"""
from __future__ import annotations

import math


def centre_distance(pinion, wheel) -> float:
    """a = r1 + r2, or the difference of the radii when one gear is internal (m)."""
    if pinion.internal or wheel.internal:
        return abs(wheel.radius - pinion.radius)
    return pinion.radius + wheel.radius


def contact_ratio(pinion, wheel) -> float:
    """The path of contact over the base pitch pi m cos(phi) (module docstring), worked
    out in modules (the pitch radii z / 2), so that no square of a length under- or
    overflows."""
    phi = pinion.pressure_angle
    m = pinion.module
    ring = pinion if pinion.internal else wheel if wheel.internal else None
    inner = wheel if ring is pinion else pinion
    a = centre_distance(pinion, wheel) / m

    def reach(gear, sign) -> float:
        r = gear.teeth / 2
        tip = r + sign * gear.addendum / m
        return math.sqrt(max(tip ** 2 - (r * math.cos(phi)) ** 2, 0.0))

    if ring is None:
        path = reach(pinion, 1) + reach(wheel, 1) - a * math.sin(phi)
    else:
        path = reach(inner, 1) - reach(ring, -1) + a * math.sin(phi)
    return path / (math.pi * math.cos(phi))


def min_teeth(addendum: float, phi: float, ratio: float | None) -> float:
    """The fewest teeth of a pinion without interference: ``addendum`` A_w in modules of
    the gear it meshes with, ``ratio`` G its teeth over the pinion's (None: a rack)."""
    s2 = math.sin(phi) ** 2
    if ratio is None:
        return 2 * addendum / s2
    return 2 * addendum / (math.sqrt(ratio ** 2 + (1 + 2 * ratio) * s2) - ratio)
