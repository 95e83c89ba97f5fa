"""The periodic regime of a machine file and its flywheel (docs/machines.md, "The periodic
regime and the flywheel").

The file's machine (forces.machine: J*, dJ*/dq and each load's generalised force from the
kinematics and the masses) is read once on a grid of one cycle of the driver (its value in
the file is where the cycle starts; one turn, or ``turns_per_cycle``) and handed to
forces.regime as periodic cubic splines: the speed-free loads by the energy method at the
file's mean speed, a motor's characteristic by shooting.  The flywheel is the driver's
link's own inertia (``dynamics: bodies: LINK: inertia``): the machine without it is the
cycle's J*, and forces.flywheel finds the one that keeps the coefficient asked.  A
turning-moment diagram given by its areas gives DeltaE from the areas' running sums.
Positions are driver values in [0, a cycle), in the file's unit.
"""
from __future__ import annotations

import math
import weakref

import numpy as np

from linkcli.errors import InputError, RegimeError
from linkcli.forces.flywheel import flywheel as size_flywheel
from linkcli.forces.regime import GRID, Cycle, Load, regime
from linkcli.model.regime import KINDS, regime_dimension

_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
#: the largest variation of J* over a cycle, as a fraction of its mean, that a diagram of
#: areas accepts (the areas give energies; the speeds need a constant inertia)
CONSTANT = 1e-9


def spec_of(mech):
    """The file's regime request (model.regime.RegimeSpec), None without one."""
    motion = getattr(mech, "motion", None)
    return None if motion is None else motion.extra.get("regime")


def asks_regime(mech, names) -> bool:
    return any(name in mech.quantities and mech.quantities[name].kind in KINDS
               for name in names)


def regime_values(mech, names) -> dict:
    """name -> (value in the file's units, unit) of each regime or flywheel quantity."""
    out = {}
    for name in names:
        quantity = mech.quantities[name]
        try:
            value = answer(mech, quantity)
        except RegimeError as err:
            raise err.located(mech.file) from None
        unit, factor = display(mech, quantity)
        out[name] = (value / factor, unit)
    return out


def answer(mech, quantity) -> float:
    """The SI value of a ``regime:`` or ``flywheel:`` quantity."""
    spec = _require_spec(mech, quantity)
    if quantity.kind == "flywheel":
        inertia = flywheel_answer(mech, quantity, spec)
        return inertia if quantity.radius is None else inertia / quantity.radius ** 2
    if spec.areas:
        return _areas_answer(mech, quantity, spec)
    reg = solved(mech)
    if quantity.a.startswith("at_"):
        return getattr(reg, quantity.a) % reg.cycle.period
    if quantity.a == "fluctuation":
        return reg.fluctuation
    return getattr(reg, quantity.a)


def _require_spec(mech, quantity):
    spec = spec_of(mech)
    if spec is None:
        raise InputError(f"'{quantity.name}' asks the periodic regime, which 'motion:' does "
                         "not describe", file=mech.file, key=f"quantities.{quantity.name}",
                         line=quantity.line, hint="add motion: {regime: {mean_speed: ...}}, "
                         "or a motor whose characteristic sets the speed")
    if mech.driver.kind != "angle":
        raise InputError("a periodic regime is of a driver that turns: an angle driver",
                         file=mech.file, key="driver", hint="drive the crank's angle")
    return spec


def display(mech, quantity) -> tuple:
    """(unit, SI factor) of a regime or flywheel answer: its own ``unit``, else the file's
    (the driver's rates for speeds and accelerations, its angle for positions)."""
    dim = regime_dimension(mech, quantity)
    if quantity.unit is not None:
        return mech.units.show(dim, None, quantity.unit)
    a = quantity.a
    if quantity.kind == "flywheel":
        return mech.units.show(dim, "inertia" if quantity.radius is None else "mass")
    orders = {"max_acceleration": 2, "min_acceleration": 2, "mean_speed": 1, "max_speed": 1,
              "min_speed": 1, "average_speed": 1}
    if a in orders or a.startswith("at_"):
        return mech.units.display("angle", orders.get(a, 0))
    if a == "energy_fluctuation":
        return mech.units.show(dim, "torque")
    if a == "cycle_time":
        return mech.units.show(dim, "time")
    return "", 1.0


# --- the cycle of the file -----------------------------------------------------------------

def solved(mech):
    """The regime of ``mech`` (solved once and kept, keyed by the model)."""
    store = _CACHE.setdefault(mech, {})
    if "regime" not in store:
        spec = spec_of(mech)
        cycle = cycle_of(mech, spec)
        store["regime"] = regime(cycle, None if cycle.speed_dependent else
                                 _mean_speed(mech, spec, cycle))
    return store["regime"]


def _mean_speed(mech, spec, cycle):
    if spec.mean_speed is None:
        raise InputError("the loads do not depend on the speed, so the regime needs its mean "
                         "speed", file=mech.file, key="motion.regime",
                         hint="add mean_speed (the driver's rate unit)")
    return spec.mean_speed


def cycle_of(mech, spec, grid: int = GRID) -> Cycle:
    """The reduced equation of ``mech`` over one cycle from the driver's value: J* without
    the driver's link's own inertia (that is the flywheel), dJ*/dq, and each load."""
    from scipy.interpolate import CubicSpline

    from linkcli.answers.quantities.machine import machine_for
    from linkcli.model.machine import in_window

    machine = machine_for(mech)
    period = 2 * math.pi * (spec.turns if spec is not None else 1.0)
    q = mech.driver.value + period * np.arange(grid + 1) / grid
    c = machine.coefficients(q)
    jt = machine.jet(q)
    own = own_inertia(mech)

    def periodic(values):
        y = np.array(values, dtype=float)
        y[-1] = y[0]
        return CubicSpline(q, y, bc_type="periodic")

    J, dJ = periodic(c.J - own), periodic(c.dJ)
    loads, known = [], np.zeros(q.shape)
    for load in mech.loads.values():
        lever = machine.lever(jt, load)
        spline = periodic(lever)
        if load.kind == "motor":
            loads.append(_motor(load, spline, q))
        elif load.kind == "brake":
            loads.append(Load(load.name, lambda x, w, s=spline, v=load.value: -v * s(x)))
        elif load.window is not None:
            loads.append(Load(load.name, lambda x, w, s=spline, ld=load: ld.value * s(x) *
                              in_window(x, ld.window, True)))
        else:
            known = known + load.value * lever
            loads.append(Load(load.name, lambda x, w, s=periodic(load.value * lever): s(x)))
    rest = c.smooth - known
    if np.any(np.abs(rest) > 1e-12 * max(1.0, float(np.abs(c.smooth).max()))):
        loads.append(Load("gravity and springs", lambda x, w, s=periodic(rest): s(x)))
    return Cycle(float(q[0]), period, J, dJ, tuple(loads), flywheel=own, grid=grid)


def _motor(load, lever, q) -> Load:
    """A motor's M(theta_q w, q) theta_q; speed-dependent unless its torque is the same at
    two speeds over the whole cycle (a turning moment written as a function of q)."""
    def torque(x, w):
        c = lever(x)
        return load.motor.torque(c * np.asarray(w, dtype=float), x, 0.0) * c

    slow, fast = torque(q, np.full(q.shape, 1.0)), torque(q, np.full(q.shape, 2.0))
    same = np.allclose(slow, fast, rtol=1e-13, atol=1e-13 * float(np.abs(slow).max() or 1))
    return Load(load.name, torque, speed=not same)


def own_inertia(mech) -> float:
    """The inertia (about its centre) the file gives the driver's link: the flywheel."""
    link = driver_link(mech)
    dyn = mech.dynamics
    if link is None or dyn is None or link not in dyn.bodies:
        return 0.0
    return float(dyn.bodies[link].inertia)


def driver_link(mech):
    """The link whose angle the driver is (it holds both of the driver's points)."""
    d = mech.driver
    for name, body in mech.bodies.items():
        if body.kind == "link" and d.a in body.points and d.b in body.points:
            return name
    return None


# --- the flywheel --------------------------------------------------------------------------

def flywheel_answer(mech, quantity, spec) -> float:
    """The driver's link's inertia for the coefficient of ``motion: flywheel:``."""
    if spec.fluctuation is None:
        raise InputError(f"'{quantity.name}' asks a flywheel, and 'motion:' gives no "
                         "coefficient of fluctuation", file=mech.file,
                         key=f"quantities.{quantity.name}", line=quantity.line,
                         hint="add motion: {flywheel: {fluctuation: 0.02}}")
    if driver_link(mech) is None:
        raise InputError("a flywheel turns with the driver's link, and the driver is not "
                         "the angle of a link", file=mech.file, key="driver")
    store = _CACHE.setdefault(mech, {})
    if spec.areas:
        return _areas_flywheel(mech, quantity, spec)
    if "flywheel" not in store:
        cycle = cycle_of(mech, spec)
        mean = None if cycle.speed_dependent else _mean_speed(mech, spec, cycle)
        store["flywheel"] = size_flywheel(cycle, spec.fluctuation, mean)
    fly = store["flywheel"]
    return fly.exact if quantity.a == "exact" else _books(mech, fly.approximate, spec)


def _books(mech, value, spec) -> float:
    """The books' flywheel, refused where their formula finds the machine's own inertia
    enough (a flywheel of no or negative inertia is no answer)."""
    if value <= 0:
        raise RegimeError(f"by the books' formula DeltaE / (w_m^2 delta) the machine's own "
                          f"inertia already keeps the coefficient of fluctuation below "
                          f"{spec.fluctuation:.6g}: no flywheel is needed (the formula's "
                          f"flywheel is {value:.6g} kg m^2)", reason="no flywheel",
                          values=(spec.fluctuation, value), file=mech.file)
    return value


# --- a diagram of areas --------------------------------------------------------------------

def diagram(mech, spec):
    """(DeltaE, J*) of a diagram of areas: DeltaE the span of the running sums of the areas
    (times the energy of one unit of area), J* the machine's inertia with its flywheel,
    which must be constant over the cycle."""
    energies = np.concatenate([[0.0], np.cumsum(spec.areas)]) * spec.area_energy
    dE = float(energies.max() - energies.min())
    cycle = cycle_of(mech, spec, grid=360)
    J = cycle.J(cycle.q())
    if float(J.max() - J.min()) > CONSTANT * float(J.mean()):
        raise RegimeError(f"a diagram of areas gives energies, and the machine's inertia "
                          f"varies from {J.min():.6g} to {J.max():.6g} over the cycle: the "
                          "speeds need a constant one", reason="varying inertia",
                          values=(float(J.min()), float(J.max())), file=mech.file)
    return dE, float(J.mean()), float(J.mean()) - cycle.flywheel


def _areas_answer(mech, quantity, spec) -> float:
    """The answers of a diagram of areas: DeltaE; with a constant J and the mean speed
    w_m = (w_max + w_min) / 2, DeltaE = 1/2 J (w_max^2 - w_min^2) = J w_m^2 delta exactly,
    which gives delta and the speeds w_m (1 +- delta / 2)."""
    dE, J, _ = diagram(mech, spec)
    w = spec.mean_speed
    if J <= 0:
        raise RegimeError("the machine has no inertia: give the flywheel's", file=mech.file,
                          reason="no inertia", values=(J,))
    delta = dE / (J * w * w)
    values = {"energy_fluctuation": dE, "fluctuation": delta, "mean_speed": w,
              "max_speed": w * (1 + delta / 2), "min_speed": w * (1 - delta / 2)}
    if quantity.a not in values:
        raise RegimeError(f"'{quantity.name}' ({quantity.a}) is not given by a diagram of "
                          "areas, which tells the energies only: ask "
                          + ", ".join(values), reason="areas", file=mech.file)
    return values[quantity.a]


def _areas_flywheel(mech, quantity, spec) -> float:
    if quantity.a == "exact":
        raise RegimeError(f"'{quantity.name}': a diagram of areas gives the books' flywheel "
                          "only (the exact one needs the shape of the curve)",
                          reason="areas", file=mech.file)
    dE, _, machine = diagram(mech, spec)
    w = spec.mean_speed
    return _books(mech, dE / (w * w * spec.fluctuation) - machine, spec)
