"""The dimension of every named answer of a mechanism (model.units.Dimension).

:func:`dimension` gives it from the quantity's kind and the mechanism's data (a
coordinate's base, a load's kind, a spring's measure) before anything is solved, so that
an expression quantity's dimension is checked when the file is read.  A rate divides by
a time for each order (``phi1dot`` is an angle per second).  A parameter has the
dimension of the value it is written as on its own (``k: ks`` makes ``ks`` a stiffness;
``2*L`` a length): :func:`param_unit`.
"""
from __future__ import annotations

from linkcli.model.mechanism import MACHINE, split_rate
from linkcli.model.regime import KINDS as REGIME_KINDS, regime_dimension
from linkcli.model.units import ANGLE_DIM, DIMENSIONS, FORCE_DIM, LENGTH_DIM, MASS_DIM, NONE, \
    TIME_DIM, Dimension

FREQUENCY_DIM = DIMENSIONS["frequency"]
ENERGY_DIM = FORCE_DIM * LENGTH_DIM
#: per matrix, the dimension of an entry between two lengths; each angle coordinate brings
#: its lever arm (a length), and stiffness and damping are per radian (N/rad, Nm/rad)
MATRIX_DIMS = {"mass_matrix": MASS_DIM, "stiffness_matrix": FORCE_DIM / LENGTH_DIM,
               "damping_matrix": FORCE_DIM * TIME_DIM / LENGTH_DIM}

#: kinds of quantity that are lengths, and angles (with their rates by order)
LENGTHS = ("x", "y", "length", "along", "normal_to", "relative", "instant_centre",
           "instant_centre_distance", "least_speed_at")
ANGLES = ("angle", "rotation", "between")
SPEEDS = ("speed", "relative_speed", "least_speed")
ACCELERATIONS = ("acceleration", "tangential_acceleration", "normal_acceleration",
                 "relative_acceleration")


def base_dimension(base: str) -> Dimension:
    """The dimension of a coordinate or driver measured as an 'angle' or a 'length'."""
    return ANGLE_DIM if base == "angle" else LENGTH_DIM


def dimension(mech, name: str) -> Dimension:
    """The dimension of the answer ``name`` (a quantity, its rate, a point's coordinate, a
    load, a solved design parameter) of ``mech``; KeyError for a name it does not define."""
    base, order = split_rate(name, mech.quantities)
    quantity = mech.quantities[base]
    return of_quantity(mech, quantity) / TIME_DIM ** order


def of_quantity(mech, quantity) -> Dimension:
    """The dimension of ``quantity`` itself (no rate)."""
    kind = quantity.kind
    if kind == "q":
        return base_dimension(mech.driver.base)
    if kind in LENGTHS:
        return LENGTH_DIM
    if kind in ANGLES:
        return ANGLE_DIM
    if kind in SPEEDS:
        return LENGTH_DIM / TIME_DIM
    if kind in ACCELERATIONS:
        return LENGTH_DIM / TIME_DIM ** 2
    if kind == "load":
        return DIMENSIONS[mech.load_unit_kind(mech.loads[quantity.a])]
    if kind in ("reaction", "slider_force"):
        return FORCE_DIM
    if kind in ("ideal_load", "reverse_load"):
        return DIMENSIONS[mech.load_unit_kind(mech.loads[quantity.a])]
    if kind in ("efficiency", "self_locking"):
        return NONE
    if kind == "clutch":
        from linkcli.model.clutch import ANSWERS
        return ANSWERS[quantity.a]
    if kind == "velocity_ratio":
        per = mech.coordinates[mech.driver_index(quantity.b)] if quantity.b else mech.driver
        return dimension(mech, quantity.a) / base_dimension(per.base)
    if kind in ("maximum", "minimum", "stroke"):
        return dimension(mech, quantity.a)
    if kind in ("at_maximum", "at_minimum"):
        return base_dimension(mech.driver.base)
    if kind in ("time_ratio", "contact_ratio", "min_teeth"):
        return NONE
    if kind == "centre_distance":
        return LENGTH_DIM
    if kind == "stroke_time":
        return TIME_DIM
    if kind == "expr":
        return quantity.dimension
    if kind == "design":
        return param_unit(mech, quantity.a)[1]
    if kind in MACHINE:
        return machine_dimension(mech, quantity)
    return _vibration(mech, quantity)


def machine_dimension(mech, quantity) -> Dimension:
    """J* (an inertia for an angle driver, a mass for a length one), dJ*/dq, the reduced
    torque (a torque or a force), and the motion's answers (the driver's unit, its rates,
    turns, a time); the periodic regime's and the flywheel's (model.regime)."""
    if quantity.kind in REGIME_KINDS:
        return regime_dimension(mech, quantity)
    base = base_dimension(mech.driver.base)
    angular = mech.driver.base == "angle"
    inertia = MASS_DIM * LENGTH_DIM ** 2 if angular else MASS_DIM
    if quantity.kind == "reduced_inertia":
        return inertia
    if quantity.kind == "reduced_inertia_slope":
        return inertia / base
    if quantity.kind == "reduced_torque":
        return FORCE_DIM * LENGTH_DIM if angular else FORCE_DIM
    return {"speed": base / TIME_DIM, "acceleration": base / TIME_DIM ** 2, "turned": base,
            "turns": NONE, "time": TIME_DIM}[quantity.a]


def coordinate_dimension(mech, name: str) -> Dimension:
    """The dimension of the coordinate ``name`` of a vibration problem."""
    coordinate = next(c for c in mech.coordinates if c.name == name)
    return base_dimension(coordinate.base)


def coordinate_dim(mech, j: int) -> Dimension:
    """The dimension of coordinate number j: an angle or a length."""
    return base_dimension(mech.coordinates[j].base)


def generalised_force_dim(mech, j: int) -> Dimension:
    """The dimension of the generalised force of coordinate j: a torque for an angle (the
    work per radian), a force for a length."""
    return ENERGY_DIM if mech.coordinates[j].base == "angle" else FORCE_DIM


def matrix_dim(kind: str, mech, i: int, j: int) -> Dimension:
    """The dimension of entry (i, j) of the mass, stiffness or damping matrix."""
    angles = [mech.coordinates[c].base for c in (i, j)].count("angle")
    dim = MATRIX_DIMS[kind] * LENGTH_DIM ** angles
    return dim / ANGLE_DIM if angles and kind != "mass_matrix" else dim


def free_indices(mech) -> list:
    """The free coordinates of a vibration problem (not imposed by a support), in order."""
    imposed = set(mech.elements.imposed) if mech.elements is not None else set()
    return [j for j in range(len(mech.coordinates)) if j not in imposed]


def element_dimension(mech, names) -> Dimension:
    """The dimension of the force of springs and dampers ``names``: a torque when they are
    all torsional, else a force."""
    elements = mech.elements
    measures = [(elements.springs.get(n) or elements.dampers[n]).measure for n in names]
    return ENERGY_DIM if all(m.kind == "angle" for m in measures) else FORCE_DIM


def free_dimensions(mech) -> list:
    """The dimensions of the free coordinates of a vibration problem, in order."""
    return [coordinate_dim(mech, j) for j in free_indices(mech)]


def _vibration(mech, quantity) -> Dimension:
    """The answers of a vibration problem (docs/vibrations.md)."""
    kind = quantity.kind
    if kind in ("natural_frequency", "damped_frequency", "forcing_frequency",
                "peak_frequency"):
        return FREQUENCY_DIM
    if kind in ("natural_period", "damped_period", "beat_period"):
        return TIME_DIM
    if kind == "frequency_ratio":
        return NONE
    if kind == "eigenvalue":
        return TIME_DIM ** -2
    if kind == "characteristic":
        # det(K - omega^2 M): a product of one stiffness per free coordinate, and each
        # omega^2 a mass over a stiffness (T^2); divided by the leading one when monic.
        # Radians are 1 here (a product of N m/rad^2 shown in N m)
        dims = free_dimensions(mech)
        power = int(quantity.a)
        if quantity.form == "monic":
            return TIME_DIM ** (2 * (power - len(dims)))
        det = NONE
        for d in dims:
            d = Dimension(d.mass, d.length, d.time)
            det = det * ENERGY_DIM / (d * d)
        return det * TIME_DIM ** (2 * power)
    if kind == "receptance":
        return coordinate_dimension(mech, quantity.a) * coordinate_dimension(mech, quantity.b) \
            / ENERGY_DIM
    if kind in ("peak_amplitude", "largest"):
        if quantity.of == "spring":
            return element_dimension(mech, (quantity.a,))
        return LENGTH_DIM if quantity.of == "point" else coordinate_dimension(mech, quantity.a)
    if kind == "damping_ratio":
        return NONE
    if kind == "transmissibility":
        # the response over the largest support motion: mm/mm, or deg/mm for a rotation
        # driven by a moving ground
        dim = LENGTH_DIM if quantity.component else coordinate_dimension(mech, quantity.a)
        supports = mech.elements.supports.values()
        if supports:
            support = max(supports, key=lambda item: abs(item.amplitude))
            dim = dim / coordinate_dim(mech, support.coordinate)
        return dim
    if kind == "mode_shape":
        # a component over the reference coordinate, the first free one
        return coordinate_dimension(mech, quantity.b) / \
            coordinate_dim(mech, free_indices(mech)[0])
    if kind.endswith("_matrix"):
        names = [c.name for c in mech.coordinates]
        return matrix_dim(kind, mech, names.index(quantity.a), names.index(quantity.b))
    if kind in ("equilibrium", "free_response"):
        return coordinate_dimension(mech, quantity.a)
    if kind == "spring_force":
        return element_dimension(mech, (quantity.a,))
    if kind == "force_amplitude":
        return element_dimension(mech, quantity.elements)
    if kind == "phase":
        return ANGLE_DIM
    if kind == "amplitude":
        return LENGTH_DIM if quantity.component else coordinate_dimension(mech, quantity.a)
    raise KeyError(kind)


#: the kinds of value a parameter may be written as that no unit kind of the tables is: a
#: length driver's rate (the file's length per second) and a driver's second rate, each
#: (the driver's base, the order of the rate): model.units.Units.display names its unit
DRIVER_RATES = {"length_rate": ("length", 1), "length_accel": ("length", 2),
                "angular_accel": ("angle", 2)}


def driver_rate_kind(base: str, order: int) -> str:
    """The kind of value of the driver's rate of ``order`` (1 or 2), its base 'angle' or
    'length': 'angular_rate' (a unit kind of the tables) or one of :data:`DRIVER_RATES`."""
    if (base, order) == ("angle", 1):
        return "angular_rate"
    return next(kind for kind, rate in DRIVER_RATES.items() if rate == (base, order))


#: the kind of a diametral pitch (gears: teeth per length unit of pitch diameter), which
#: ``units:`` does not name: it is one over the file's length unit
PER_LENGTH = "per_length"


def param_unit(mech, name: str) -> tuple:
    """(kind, Dimension, SI factor) of the parameter ``name``: the unit kind it is written in
    where the file uses it on its own as a value of one kind (``k: ks``, ``[L, -2*L]``,
    ``driver: accel: a``), else (None, None, None)."""
    kind = mech.param_kinds.get(name)
    if kind is None:
        return None, None, None
    if kind in DRIVER_RATES:
        base, order = DRIVER_RATES[kind]
        return kind, base_dimension(base) / TIME_DIM ** order, mech.units.display(base, order)[1]
    if kind == PER_LENGTH:
        return kind, LENGTH_DIM ** -1, 1.0 / mech.units.factor("length")
    return kind, DIMENSIONS[kind], mech.units.factor(kind)


def param_unit_name(mech, name: str) -> str:
    """The name of the unit the file writes parameter ``name`` in ('' where it does not
    tell)."""
    kind = mech.param_kinds.get(name)
    if kind in DRIVER_RATES:
        return mech.units.display(*DRIVER_RATES[kind])[0]
    if kind == PER_LENGTH:
        return "1/" + mech.units.names["length"]
    return mech.units.names[kind] if kind else ""
