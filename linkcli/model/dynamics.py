"""Masses, inertias, gravity, friction and rolling discs: the data of the ``dynamics:`` section.

Everything here is in SI units.  A massive body has mass ``m``, inertia ``J``
about its centre of mass G and G fixed in the body (local coordinates).  A
disc rolling without slipping has its centre on a slider of a fixed line, on
the ``side`` s = +1 (left of the line's direction) or -1 (right); its rolling
resistance is the length ``resistance`` by which the ground's normal force is
shifted ahead of the contact.  A pin with friction has a friction circle of
radius rho between the body the pin is fixed in (``holder``) and the body whose
eye turns on it (``other``).
"""
from __future__ import annotations

from dataclasses import dataclass, field

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
    resistance: float = 0.0     # rolling resistance: the normal force's shift (m)


@dataclass(frozen=True)
class PinFriction:
    """A friction circle of radius ``radius`` (m) at pin ``point``: the pin is fixed in
    ``holder`` (the frame at a fixed pivot, else a slider block or actuator half, else the
    first link of the file) and the eye of ``other`` turns on it."""

    point: str
    holder: str
    other: str
    radius: float


@dataclass
class Dynamics:
    gravity: complex = 0j                               # m/s^2
    bodies: dict = field(default_factory=dict)          # body -> MassBody
    masses: dict = field(default_factory=dict)          # point -> kg
    friction: dict = field(default_factory=dict)        # slider -> mu
    discs: dict = field(default_factory=dict)           # disc name -> Disc
    pins: dict = field(default_factory=dict)            # point -> PinFriction

    def disc_on(self, slider: str):
        return next((d for d in self.discs.values() if d.slider == slider), None)
