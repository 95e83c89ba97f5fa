"""The periodic regime and the flywheel asked of a machine file (``motion:`` and the
``regime:`` / ``flywheel:`` quantities), in SI units.

``mean_speed`` (rad/s or m/s) is the mean speed of a machine whose loads do not depend on
the speed (None where a motor's characteristic sets it); ``fluctuation`` the coefficient
delta = (w_max - w_min) / w_m a flywheel must keep (None when not asked); ``turns`` the
turns of the driver in one cycle (2 for a four-stroke engine); ``areas`` a turning-moment
diagram given as the areas between the torque curve and the mean line, taken in order
(positive above), and ``area_energy`` the energy of one unit of area (J).
"""
from __future__ import annotations

from dataclasses import dataclass

#: what ``regime:`` answers: speeds (the mean (w_max + w_min) / 2, the average over the
#: cycle's time) and where they are reached, the coefficient of
#: fluctuation, the largest fluctuation of energy, the extreme accelerations, the cycle's time
REGIME = ("mean_speed", "average_speed", "max_speed", "min_speed", "at_max_speed", "at_min_speed",
          "fluctuation", "energy_fluctuation", "max_acceleration", "at_max_acceleration",
          "min_acceleration", "at_min_acceleration", "cycle_time")
#: what ``flywheel:`` answers: the books' approximation and the exact inertia
FLYWHEEL = ("approximate", "exact")
#: the quantity kinds of the regime
KINDS = ("regime", "flywheel")


@dataclass(frozen=True)
class RegimeSpec:
    """What the file says of its periodic regime (``motion:``'s keys ``regime``,
    ``flywheel``, ``turns_per_cycle``)."""

    mean_speed: float | None = None
    fluctuation: float | None = None
    turns: float = 1.0
    areas: tuple = ()
    area_energy: float = 0.0
    #: the drawing's scales (SI): the torque and the angle of one unit of its length
    scale: tuple = ()


def regime_dimension(mech, quantity):
    """The dimension of a regime or flywheel answer (an angle driver): speeds rad/s,
    positions an angle, accelerations rad/s^2, DeltaE an energy, the cycle's time, the
    flywheel an inertia, the coefficient a pure number."""
    from linkcli.model.units import ANGLE_DIM, FORCE_DIM, LENGTH_DIM, MASS_DIM, NONE, TIME_DIM

    if quantity.kind == "flywheel":
        return MASS_DIM if quantity.radius is not None else MASS_DIM * LENGTH_DIM ** 2
    a = quantity.a
    if a in ("mean_speed", "average_speed", "max_speed", "min_speed"):
        return ANGLE_DIM / TIME_DIM
    if a.startswith("at_"):
        return ANGLE_DIM
    if a in ("max_acceleration", "min_acceleration"):
        return ANGLE_DIM / TIME_DIM ** 2
    if a == "energy_fluctuation":
        return FORCE_DIM * LENGTH_DIM
    if a == "cycle_time":
        return TIME_DIM
    return NONE
