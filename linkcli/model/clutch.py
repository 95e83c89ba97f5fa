"""A clutch problem's data (``shafts:`` and ``clutch:``): two shafts, or one shaft and the
frame (a brake), coupled by a friction clutch.  SI units; nothing here solves
(``forces.clutch``, ``runs.clutch``)."""
from __future__ import annotations

from dataclasses import dataclass, field

from linkcli.model.units import DIMENSIONS, TIME_DIM

#: the answers of ``{clutch: ...}`` (input.clutch) and the dimension of each (an energy,
#: J = N m, has a torque's)
ANSWERS = {"slip_time": TIME_DIM, "common_speed": DIMENSIONS["angular_rate"],
           "energy": DIMENSIONS["torque"], "torque": DIMENSIONS["torque"],
           "transmitted": DIMENSIONS["torque"], "speed": DIMENSIONS["angular_rate"],
           "acceleration": DIMENSIONS["angular_rate"] / TIME_DIM, "time": TIME_DIM}


@dataclass(frozen=True)
class Shaft:
    """A shaft: its inertia J (kg m^2) about its axis, its speed at t = 0 (rad/s), and the
    torques on it (N m, counter-clockwise positive along the common axis): a constant
    ``torque``, a ``resisting`` torque >= 0 against its turning (it holds the shaft at rest
    up to its value), a motor's linear characteristic M = stall (1 - w / no_load)."""

    name: str
    inertia: float
    speed: float
    torque: float = 0.0
    resisting: float = 0.0
    stall: float | None = None
    no_load: float | None = None

    @property
    def constant(self) -> bool:
        """Whether its torque does not depend on its speed."""
        return self.stall is None


@dataclass(frozen=True)
class Plate:
    """A plate clutch as the problem states it (SI): friction coefficient, axial force (N),
    outer and inner radii (m), pairs of surfaces, 'uniform' wear or 'pressure'."""

    mu: float
    force: float
    outer: float
    inner: float
    pairs: int = 1
    wear: str = "uniform"

    @property
    def torque(self) -> float:
        """The friction torque (N m) of n pairs of surfaces pressed by F:
        uniform wear n mu F (r_o + r_i) / 2, uniform pressure
        n mu F (2/3) (r_o^3 - r_i^3) / (r_o^2 - r_i^2)."""
        if self.wear == "uniform":
            radius = (self.outer + self.inner) / 2
        else:
            radius = 2 / 3 * (self.outer ** 3 - self.inner ** 3) / \
                (self.outer ** 2 - self.inner ** 2)
        return self.pairs * self.mu * self.force * radius


@dataclass(frozen=True)
class Clutch:
    """The clutch between shaft ``driving`` and shaft ``driven`` (None: the frame, a brake):
    the friction torque it passes while they slip (N m), from ``plate`` where given."""

    driving: str
    driven: str | None
    torque: float
    plate: Plate | None = None


@dataclass
class ClutchProblem:
    """The shafts by name and their clutch."""

    shafts: dict = field(default_factory=dict)
    clutch: Clutch | None = None

    def side(self, name):
        """1 for the driving shaft, 2 for the driven one."""
        return 1 if name == self.clutch.driving else 2
