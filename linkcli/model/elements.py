"""Springs, dampers and harmonic excitation: the data of vibration problems.

Every element acts through a *measure* s(q) of the mechanism:

- ``distance``: s = |P_b - P_a| (a spring or damper between two points);
- ``along``: s = Re(conj(e) (P_b - P_a)), the relative displacement along a
  fixed unit direction e (a spring that "deforms only horizontally");
- ``angle``: s = theta_b - theta_a, the relative rotation of two bodies (the
  frame's angle is 0): a torsional spring or damper.

A spring stores V = 1/2 k (s - s0)^2 with s0 its free measure, so its force
(tension positive) is N = k (s - s0); a damper dissipates D = 1/2 c s'^2.
All values are SI (m, rad, N/m, N m/rad, N s/m, N m s/rad).
"""
from __future__ import annotations

from dataclasses import dataclass, field

#: how a spring's free measure is given
FREE = "free"            # s0 given (free length or angle)
PRELOAD = "preload"      # N given at the figure: s0 = s_figure - N / k
STATIC = "static"        # N chosen so that the figure is the static equilibrium
UNSTRETCHED = "unstretched"  # s0 = s_figure (the default)


@dataclass(frozen=True)
class Measure:
    """What an element stretches: see the module's docstring.  ``a``, ``b`` are
    points (distance, along) or bodies (angle; ``frame`` for the frame)."""

    kind: str              # 'distance' | 'along' | 'angle'
    a: str
    b: str
    direction: complex = 1 + 0j

    def text(self) -> str:
        if self.kind == "distance":
            return f"|{self.b} - {self.a}|"
        if self.kind == "along":
            return f"({self.b} - {self.a}) along ({self.direction.real:.4g}, " \
                f"{self.direction.imag:.4g})"
        return f"theta_{self.b} - theta_{self.a}"


@dataclass(frozen=True)
class Spring:
    """A linear spring, V = 1/2 k (s - s0)^2.  ``mode`` says how s0 is set
    (FREE, PRELOAD, STATIC, UNSTRETCHED); ``value`` is s0 (FREE) or the
    figure's force N (PRELOAD)."""

    name: str
    measure: Measure
    stiffness: float
    mode: str = UNSTRETCHED
    value: float = 0.0


@dataclass(frozen=True)
class Damper:
    """A linear viscous damper, D = 1/2 c s'^2."""

    name: str
    measure: Measure
    coefficient: float


@dataclass(frozen=True)
class Harmonic:
    """A harmonic load amplitude e^{i (Omega t + phase)}: kind 'force' at point
    ``target`` along unit ``direction``, or 'torque' on body ``target`` (N m,
    counter-clockwise)."""

    name: str
    kind: str
    target: str
    direction: complex
    amplitude: float
    phase: float = 0.0


@dataclass(frozen=True)
class Support:
    """Imposed harmonic motion of coordinate number ``coordinate`` about its figure
    value: s(t) = amplitude e^{i (Omega t + phase)} (a shaker, a moving support,
    or a road profile under a wheel).  ``road`` is (wavelength L in m, speed V in m/s) of
    a road profile, whose Omega = 2 pi V / L, as the problem states them."""

    name: str
    coordinate: int
    amplitude: float
    phase: float = 0.0
    road: tuple | None = None


@dataclass
class Elements:
    """Springs, dampers, the excitation and the settings of the vibration analysis."""

    springs: dict = field(default_factory=dict)      # name -> Spring
    dampers: dict = field(default_factory=dict)      # name -> Damper
    forces: dict = field(default_factory=dict)       # name -> Harmonic
    supports: dict = field(default_factory=dict)     # name -> Support
    frequency: float | None = None                   # Omega (rad/s) of the excitation
    initial: dict = field(default_factory=dict)      # coordinate index -> (dq0, dq'0)
    #: what the initial offsets are measured from: ('equilibrium', None), ('figure', None)
    #: or ('unstretched', spring names): where those springs have their free measures
    initial_from: tuple = ("equilibrium", None)
    #: a start in a mode: (k, j, a), released from rest in mode k (0-based) scaled so
    #: that coordinate j's offset is a (SI); None otherwise
    initial_mode: tuple | None = None
    equilibrium: str = "solve"                       # 'solve' from the figure | 'figure'

    @property
    def started(self) -> bool:
        """Whether a free vibration has a start (``initial:``) other than rest at the
        equilibrium."""
        return bool(self.initial) or self.initial_from[0] != "equilibrium" or \
            self.initial_mode is not None

    @property
    def imposed(self) -> tuple:
        """Indices of the coordinates whose motion is imposed (not degrees of freedom)."""
        return tuple(sorted({s.coordinate for s in self.supports.values()}))
