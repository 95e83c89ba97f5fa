"""The validated mechanism, in SI units, as plain immutable data.

Positions are complex numbers ``x + iy`` (m).  Angles are radians,
counter-clockwise from +x.  One model serves every later stage: topology reads
its bodies and pairs, the solver its geometry, the reporter its quantities.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from linkcli.errors import InputError
from linkcli.model.dynamics import Dynamics
from linkcli.model.elements import Elements

FRAME = "frame"


@dataclass(frozen=True)
class Guide:
    """A straight line along which a slider block translates.

    The line is the set of points ``P`` with ``cross(C - B, P - B) = c``, where
    ``B`` and ``C`` are two points of the ``carrier`` body (virtual fixed
    points for a line of the frame) and ``c`` is constant because the carrier
    is rigid.  Its direction is from ``B`` to ``C``.

    The carrier is the frame, a link, another slider's block (a slot cut in the
    block, as in a Scotch yoke) or an actuator's cylinder (``NAME.cylinder``: the
    line through the actuator's two points, whose distance changes, so its
    offset is 0 and its block carries no other point).
    """

    carrier: str          # body name, FRAME for a fixed line
    b: str
    c: str
    offset: float         # signed distance of the line to the left of B->C (m)
    text: str             # how the file wrote it, for messages


@dataclass(frozen=True)
class Body:
    """A rigid body: a link, a triangular link, a slider block, an actuator half.

    ``local`` gives each point's coordinates in the body's own frame (complex,
    m); for a block they are offsets from its guide point in the guide's axes
    (along, left normal).
    """

    name: str
    kind: str             # 'link' | 'block' | 'cylinder' | 'rod'
    points: tuple
    local: dict = field(default_factory=dict)
    guide: Guide | None = None


@dataclass(frozen=True)
class Actuator:
    """A linear actuator between two points: a cylinder and a rod sliding in it."""

    name: str
    a: str
    b: str


@dataclass(frozen=True)
class Rolling:
    """A disc that rolls without slipping, or a pulley that a taut cord turns.

    The disc is the link ``disc`` whose first point ``center`` is its centre;
    ``radius`` its rolling radius.  What it rolls on (``kind``):

    - 'line': a line of unit direction ``direction`` (in the figure); ``side`` is -1 when
      the centre is on the line's left (looking along u), +1 on its right:
      omega = side (v_C . u) / r on a fixed line; a line of the body ``carrier`` (a link or
      slider, FRAME for a fixed line) turns and moves with it, and the disc rolls on it
      as on a fixed line in the carrier's own frame;
    - 'cord': a straight cord leaving the pulley along ``direction`` towards
      ``point`` P, from its ``side``: the cord is a line moving with P,
      omega = side ((v_C - v_P) . u) / r;
    - 'circle': a fixed circle of centre ``track`` and radius ``track_radius``,
      ``inside`` or outside: omega = -(R - r)/r psi' inside, (R + r)/r psi' outside,
      psi the angle of C about the centre;
    - 'disc': the disc ``other`` (its first point its centre) of radius
      ``track_radius``: as the circle, plus -/+ (R / r) omega_other (outside/inside);
    - 'belt': a straight strand of a taut cord or belt leaving the pulley along
      ``direction`` towards the disc ``other`` (centre ``track``, radius
      ``track_radius``), which it meets on its ``other_side`` (+1 left, -1 right, looking
      along the strand): the strand's speed along u at the other disc is
      v_D . u - other_side r_D omega_D, so
      omega = side ((v_C - v_D) . u + other_side r_D omega_D) / r; a belt that slips by the
      fraction ``slip`` turns the pulley (the follower) at (1 - slip) of that:
      omega = (1 - slip) side (...) / r.

    Each contact takes one degree of freedom (a higher pair in Grübler's count); a disc
    may have any number of them (a pulley with several cords).
    """

    name: str
    disc: str
    center: str
    radius: float
    kind: str
    direction: complex = 1 + 0j
    side: int = 1
    point: str | None = None
    track: str | None = None
    track_radius: float = 0.0
    inside: bool = False
    other: str | None = None
    other_side: int = 1
    carrier: str = FRAME
    slip: float = 0.0


@dataclass(frozen=True)
class Driver:
    """An independent coordinate: the driver q of a 1-DOF file, one of ``drivers`` (a
    mechanism of several degrees of freedom, each input driven) or one of ``coordinates``.

    kind 'angle': q is the angle of the vector a->b; 'length': q = |b - a|;
    'x' / 'y': q is that coordinate of point ``a``.  ``value`` is the
    figure's; ``rate`` and ``accel`` are the driver's (0 for coordinates); ``name`` is 'q'
    for ``driver:``, the file's name of it otherwise.  ``payout`` names the cord whose
    pay-out the file drives: q is then the angle of its disc's vector a->b, which the
    pay-out s turns (theta = theta_0 - side s / r, ``input.contacts``).
    """

    kind: str
    a: str
    b: str | None
    value: float
    rate: float
    accel: float
    name: str = "q"
    payout: str | None = None

    @property
    def base(self) -> str:
        """'angle' or 'length': the kind of unit q is measured in."""
        return "angle" if self.kind == "angle" else "length"

    @property
    def words(self) -> str:
        """What it drives, in words: 'angle of A->B', 'length AB', 'x of B'."""
        if self.payout is not None:
            return f"angle of {self.a}->{self.b} (the pay-out of cord {self.payout})"
        return {"angle": f"angle of {self.a}->{self.b}", "length": f"length {self.a}{self.b}",
                "x": f"x of {self.a}", "y": f"y of {self.a}"}[self.kind]

    def same_coordinate(self, other: "Driver") -> bool:
        """Whether ``other`` measures the same coordinate: the same kind of the same point,
        or of the same two points (either way round)."""
        if self.kind != other.kind:
            return False
        return self.a == other.a if self.b is None else {self.a, self.b} == {other.a, other.b}


@dataclass(frozen=True)
class Load:
    """An external load.  ``value`` is None for the one unknown load (one per driver with
    several drivers).

    kind 'force': at point ``target`` along unit direction ``direction``
    (complex), magnitude ``value`` (N); 'torque': on body ``target`` (N m,
    counter-clockwise); 'axial': on actuator ``target`` (N, > 0 pushes the
    ends apart); 'driver': generalised force on q (N or N m), with several drivers on
    the driver named ``target``; 'motor': a torque on body ``target`` given by its
    characteristic ``motor`` of the body's speed; 'brake': a torque ``value`` >= 0 on body
    ``target`` against its turning.  A pressure load is
    the force or axial load p A, with ``pressure`` = (p in Pa, A in m^2, the bore D
    in m or None) as the problem states them.
    """

    name: str
    kind: str
    target: str | None
    direction: complex
    value: float | None
    pressure: tuple | None = None
    #: machine dynamics (model.machine): the driver's window (q1, q2) it acts in, None:
    #: always; a motor's Characteristic ('motor' loads); a brake's torque is ``value``
    window: tuple | None = None
    motor: object = None


@dataclass(frozen=True)
class Quantity:
    """A reported quantity.

    Geometry: kind 'angle' (of vector a->b), 'length' (|b - a|), 'x' / 'y' (of
    point a), 'q' (the driver), 'load' (a load's value or one of its components).
    Vibrations (kinds in VIBRATION): ``a`` names the mode (1-based, as text), the
    coordinate or the element, ``b`` the second coordinate of a matrix entry or
    of a mode shape, ``component`` the axis of a point's amplitude, ``elements``
    the springs and dampers of a force amplitude, ``time`` the instant of a free
    response (s).

    The textbook's questions (docs/schema.md, "quantities"):

    - 'speed', 'acceleration', 'tangential_acceleration', 'normal_acceleration' of
      point ``a``;
    - 'along' / 'normal_to': point ``c``'s position component along the unit vector
      of a->b (or its left normal); with ``d``, that of the vector from c to d;
    - 'relative' (``component`` x or y of b - a), 'relative_speed',
      'relative_acceleration' (|v_b - v_a|, |a_b - a_a|);
    - 'rotation': the angle of body ``a`` (``of`` says what the name is: 'link',
      'slider', 'actuator', 'rolling' (a contact's or cord's disc) or 'disc' (of
      ``dynamics: discs:``));
    - 'between': the angle from vector a->b to vector c->d;
    - 'instant_centre' (``component`` x or y) of body ``a`` (relative to body ``b`` when
      it is given, ``c`` then saying what b is, as ``of`` does for a), and
      'instant_centre_distance' from it to point ``b``;
    - 'reaction': the force of the pin at point ``a`` on body ``b`` (``of``: its kind,
      'cylinder' or 'rod' for an actuator's half, or 'frame'), ``component`` x, y,
      magnitude, or along / normal (left) to ``axis``: ('body', NAME) a body's axis,
      ('points', P, Q) the vector P -> Q, ('angle', radians) a fixed direction (None: the
      axis of body ``b``); 'slider_force' of slider ``a``, ``component`` normal or friction;
    - 'velocity_ratio': d(a)/dq of the quantity named ``a`` (with several drivers, d(a)/dq_b
      of the driver named ``b``, the others at rest: a column of the Jacobian);
    - 'least_speed', 'least_speed_at': of the line through points ``a`` and ``b`` of one
      body, the least speed of its points and where it is (distance from a along a->b);
    - the limits of the motion (kinds in LIMITS) of the quantity named ``a`` over the
      driver range ``span``.

    ``signed`` prints an angle in (-180, 180] instead of [0, 360); ``line`` is where
    the file defines the quantity, for errors found when it is evaluated.
    """

    name: str
    kind: str
    a: str | None = None
    b: str | None = None
    component: str | None = None
    unit: str | None = None
    elements: tuple = ()
    time: float = 0.0
    c: str | None = None
    d: str | None = None
    of: str | None = None
    signed: bool = False
    line: int | None = field(default=None, compare=False)
    span: tuple | None = None      # a limit's driver range (from, to), display units
    #: an expression quantity's (kind 'expr', the text in ``a``): the Dimension of its unit
    #: (model.units), and the rates it has (those every name it reads has)
    dimension: object = None
    derived: int | None = None
    #: of a complex vibration answer, its 'real' or 'imaginary' part (None: its magnitude);
    #: of the characteristic polynomial's coefficient, 'monic' (divided by the leading one)
    form: str | None = None
    axis: tuple | None = None      # a joint force's direction of projection (see above)
    #: a flywheel's radius of gyration (m): the answer is then its mass (model.regime)
    radius: float | None = None

    @property
    def rates(self) -> int:
        """How many rates the quantity has: 2 (NAMEdot and NAMEddot), 1 or 0."""
        if self.derived is not None:
            return self.derived
        if self.kind in ("q", "x", "y", "angle", "length", "along", "normal_to", "relative",
                         "rotation", "between"):
            return 2
        return 1 if self.kind in ("speed", "relative_speed") else 0

    @property
    def limit(self) -> bool:
        """Whether it is a limit of the motion (LIMITS): one value for a range of the driver."""
        return self.kind in LIMITS

    @property
    def angular(self) -> bool:
        """Whether the quantity is an angle (compared modulo a turn, unless signed)."""
        return self.kind in ("angle", "rotation", "between")


#: quantity kinds of the limits of the motion (runs.limits): one value for a range of the
#: driver, of the quantity named ``a`` (a name or a rate's name, e.g. xB or xBdot); ``component``
#: is 'working' or 'return' for a stroke time, ``span`` the range (None: the default one)
LIMITS = ("maximum", "minimum", "at_maximum", "at_minimum", "stroke", "time_ratio",
          "stroke_time")

#: the report's sections of named quantities, in the order of the answer sheet
REPORT_SECTIONS = ("design", "position", "velocity", "acceleration", "statics", "vibration",
                   "motion")

#: quantity kinds of machine dynamics (input.machine): one value at the driver's state, or
#: of the motion in time (kind 'motion': ``a`` the answer, ``b`` the event, ``time`` its
#: value in SI)
MACHINE = ("reduced_inertia", "reduced_inertia_slope", "reduced_torque", "motion", "regime",
           "flywheel")

#: quantity kinds of the vibration analysis (each is also the YAML key that asks for it)
VIBRATION = ("natural_frequency", "damped_frequency", "damping_ratio", "mode_shape",
             "mass_matrix", "stiffness_matrix", "damping_matrix", "equilibrium",
             "spring_force", "amplitude", "phase", "transmissibility", "force_amplitude",
             "free_response", "forcing_frequency",
             # what vibration chapters print besides (input.oscillation)
             "natural_period", "damped_period", "frequency_ratio", "eigenvalue",
             "characteristic", "receptance", "peak_frequency", "peak_amplitude",
             "beat_period", "largest")


@dataclass(frozen=True)
class Tolerance:
    """How far a computed value may lie from a printed one and still agree with it:
    ``|computed - printed| <= value`` in the value's display unit, or, ``relative``,
    ``<= value |printed|`` (``value`` a fraction: 0.02 for '2%'); ``text`` as written."""

    value: float
    relative: bool
    text: str


@dataclass(frozen=True)
class KeyEntry:
    """One printed answer key value."""

    name: str
    printed: str          # as printed (text), for display
    value: float | tuple  # parsed number, or (x, y) for a point
    decimals: int
    wrong: str | None = None   # reason, when the printed value is a known key problem
    line: int | None = None
    tolerance: Tolerance | None = None   # None: agreement at the printed precision only


@dataclass(frozen=True)
class AnswerKey:
    k: int | None
    entries: tuple


@dataclass(frozen=True)
class Quiz:
    """How a Moodle quiz scores the file: ``points`` per report section (the exams'
    9/9/2; None: one point per answer box), the answers' absolute ``tolerance`` in
    display units (None: half a unit of the last printed decimal), whether it asks the
    values the question gives (``ask_given``; false as ``export --no-given``) and the
    report's names it does not ask (``not_asked``: printed by solve and checked against
    the key, but not asked by the statement)."""

    points: dict | None = None
    tolerance: float | None = None
    ask_given: bool = True
    not_asked: tuple = ()


@dataclass(eq=False)
class Mechanism:
    """A mechanism definition for one value of k (SI units).

    Plain data, filled once at load time; equality is identity, so solvers may
    be cached per mechanism by the layers above.
    """

    title: str
    file: str
    k: int | None
    units: object
    fixed: dict            # point -> complex, includes virtual guide points
    moving: dict           # point -> approximate complex position
    bodies: dict           # name -> Body (frame not included)
    actuators: dict        # name -> Actuator
    driver: Driver
    loads: dict            # name -> Load
    quantities: dict       # name -> Quantity
    report: dict           # section -> list of names
    keys: tuple = ()
    dynamics: Dynamics | None = None   # the ``dynamics:`` section, None when absent
    coordinates: tuple = ()            # every independent coordinate; (driver,) for 1 DOF
    rolling: dict = field(default_factory=dict)   # name -> Rolling (contacts and cords)
    as_drawn: bool = True              # built for the digit k the figure draws
    statement: str = ""                # the exam's statement text, for exports
    quiz: Quiz = field(default_factory=Quiz)
    params: dict = field(default_factory=dict)    # the file's named numbers for this k
    elements: Elements | None = None   # springs, dampers, forcing: None when absent
    #: the unit kind of each parameter written on its own as a value of one kind (k: ks)
    param_kinds: dict = field(default_factory=dict)
    #: what it was built from, to build it again with other parameters (input.document.Source)
    source: object = None
    #: a design question (``find:``, model.design.Design), None when absent
    design: object = None
    #: the ``motion:`` section of machine dynamics (model.machine.MotionSpec), None when absent
    motion: object = None
    #: name -> model.gears.Gear: the gears given by their teeth (``gears:``)
    gears: dict = field(default_factory=dict)
    #: a clutch problem's shafts and clutch (``shafts:``, model.clutch.ClutchProblem): then
    #: there is no linkage, and no driver
    clutch: object = None

    def __post_init__(self):
        if not self.coordinates and self.driver is not None:    # a clutch problem has none
            self.coordinates = (self.driver,)

    @property
    def points(self) -> list:
        return [p for p in self.fixed if not p.startswith("~")] + list(self.moving)

    @property
    def figure_points(self) -> list:
        """The figure's positions of the named points (m): not the virtual ones (a fixed
        guide's second point, drawn at least 1 m away to give its direction, is no part of
        the mechanism's size)."""
        figure = {**self.fixed, **self.moving}
        return [figure[p] for p in self.points]

    @property
    def inputs(self) -> tuple:
        """(values, rates, accelerations) of the file's own position as the solvers take
        them: numbers for one driver (or coordinate), tuples over them for several."""
        cs = self.coordinates
        if len(cs) == 1:
            return cs[0].value, cs[0].rate, cs[0].accel
        return tuple(tuple(getattr(c, a) for c in cs) for a in ("value", "rate", "accel"))

    def unknown_load(self) -> Load:
        load = next((load for load in self.loads.values() if load.value is None), None)
        if load is None:
            raise InputError("no load is 'unknown', so there is nothing to balance",
                             file=self.file, key="loads",
                             hint="give one load, usually the driver's, the value 'unknown'")
        return load

    def driver_index(self, name: str | None) -> int:
        """The place of the driver ``name`` among the coordinates (None: the first, q)."""
        return 0 if name is None else [c.name for c in self.coordinates].index(name)

    def unknown_loads(self) -> list:
        """The unknown loads, one per driver of a mechanism of several drivers; refused
        when their number is not the drivers' (nothing, or not everything, to balance)."""
        unknown = [load for load in self.loads.values() if load.value is None]
        if len(unknown) != len(self.coordinates):
            names = ", ".join(c.name for c in self.coordinates)
            which = ", ".join(load.name for load in unknown) or "none"
            raise InputError(f"the statics needs one unknown load per driver "
                             f"({len(self.coordinates)}: {names}), found {len(unknown)} "
                             f"({which})",
                             file=self.file, key="loads",
                             hint="give one load per driver, usually each driver's, the "
                                  "value 'unknown'")
        return unknown

    def load_unit_kind(self, load: Load) -> str:
        """'torque' for a torque (a motor's, a brake's) or the driver load of an angle driver
        (the driver it acts on, ``target``, with several drivers), else 'force'."""
        driver = next((c for c in self.coordinates if c.name == load.target), self.driver) \
            if load.kind == "driver" else None
        if load.kind in ("torque", "motor", "brake") or driver is not None and \
                driver.kind == "angle":
            return "torque"
        return "force"


def split_rate(name: str, names=()):
    """'phi1ddot' -> ('phi1', 2); 'phi1dot' -> ('phi1', 1); 'phi1' -> ('phi1', 0).

    A name ending in 'ddot' reads two ways ('wddot': the second rate of 'w' or the first of
    'wd'); the reading whose base is one of ``names`` (the file's quantities) is taken, and
    the second rate where none or both are (both defined is refused when the file is read:
    input.quantities)."""
    if not name.endswith("dot"):        # no reading as a rate
        return name, 0
    if name.endswith("ddot") and len(name) > 4:
        if name[:-4] in names or name[:-3] not in names:
            return name[:-4], 2
        return name[:-3], 1
    return (name[:-3], 1) if len(name) > 3 else (name, 0)


def limit_refusal(name: str, quantity: Quantity, order: int) -> str | None:
    """Why the extremes of ``name`` (``quantity``'s rate of ``order``) cannot be found from a
    zero of its rate, or None when they can: it needs a rate the solver computes."""
    if order < quantity.rates:
        return None
    if quantity.limit:
        what = "a limit of the motion itself (one value for the whole range)"
    elif order == 2 or quantity.kind in ("acceleration", "tangential_acceleration",
                                         "normal_acceleration", "relative_acceleration") \
            or (order == 1 and quantity.kind in ("speed", "relative_speed")):
        what = "an acceleration, whose rate (the jerk) is not computed"
    else:
        words = quantity.kind.replace("_", " ")
        what = ("an " if words[0] in "aeiou" else "a ") + words + ", which has no rate"
    return f"the extremes of '{name}' are where its rate is zero, and '{name}' is {what}"
