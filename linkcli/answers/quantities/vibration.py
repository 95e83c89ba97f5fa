"""The report of a vibration problem: every asked quantity in the file's units.

Each answer is computed in SI with its dimension (:class:`Answer`) and shown in the unit
``Units.show`` decides from it (model/units.py), the one place that picks display units:

- frequencies in the file's frequency unit (or the quantity's ``unit:``), damping ratios
  and mode-shape ratios of like coordinates as pure numbers;
- coordinates (equilibrium, amplitudes, free response) in the file's length or angle unit,
  phases in its angle unit (negative when the response lags the excitation, in
  [-180, 180) deg: a response in opposition is -180, the limit of a vanishing damping);
- spring forces and force amplitudes in its force unit (torque unit for torsional
  elements);
- matrix entries in its mass, inertia, stiffness or damping units where both coordinates
  are of one kind, else in a product of its units (kg mm, N/deg, Ns/deg);
- a mode shape component is the ratio of that coordinate to the reference coordinate (the
  first free one) in the mode: mm/deg for a length against an angle.

Geometric quantities of the position section are evaluated at the equilibrium.

The formulas of the same problem (``--symbolic``) are ``texts.symbolic``'s, its twin.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from linkcli.answers.quantities import collect, oscillation
from linkcli.errors import InputError, ModeError, SolveError
from linkcli.forces import vibration as vib
from linkcli.input.oscillation import OSCILLATION
from linkcli.forces.lagrange import Lagrangian
from linkcli.kinematics import jacobian as jac
from linkcli.kinematics.solvers import solver_for
from linkcli.kinematics.grubler import SEVERAL_DRIVERS
from linkcli.model.mechanism import VIBRATION, split_rate
from linkcli.model.rounding import noise_free
from linkcli.model.dimensions import FREQUENCY_DIM, coordinate_dim, generalised_force_dim, \
    matrix_dim, of_quantity
from linkcli.model.units import ANGLE_DIM, DIMENSIONS, Dimension, FORCE_DIM


@dataclass(frozen=True)
class Answer:
    """One answer in SI, its dimension, and the kind of unit it is shown in (None: decided
    from the dimension alone).  ``turn``: an angle shown within one turn, [0, 360) deg."""

    value: float
    dim: Dimension
    kind: str | None = None
    turn: bool = False


def shown(units, answer: Answer, unit: str | None = None) -> tuple[float, str]:
    """(value, unit) of ``answer`` in the file's ``units`` (``unit``: the quantity's own)."""
    name, factor = units.show(answer.dim, answer.kind, unit)
    value = answer.value / factor
    if answer.turn:
        turn = 2 * math.pi / factor
        value = value % turn
        value = 0.0 if value > turn * (1 - 1e-12) else value
    return float(value), name


@dataclass
class Analysis:
    """The linearised problem and what has been derived from it (computed on demand)."""

    mech: object
    lin: vib.Linear
    cache: dict = field(default_factory=dict)

    def modes(self) -> vib.Modes:
        if "modes" not in self.cache:
            self.cache["modes"] = vib.modes(self.lin)
        return self.cache["modes"]

    def damped(self) -> vib.Damped:
        if "damped" not in self.cache:
            # the modes first: they refuse an unstable equilibrium
            self.cache["damped"] = vib.damped(self.lin, self.modes())
        return self.cache["damped"]

    def amplitudes(self):
        """Complex amplitudes of every coordinate at the excitation frequency."""
        if "X" not in self.cache:
            lin = self.lin
            if lin.frequency is None:
                raise InputError("a steady-state response needs an excitation",
                                 file=self.mech.file, key="excitation",
                                 hint="give excitation: {frequency: ..., forces: ...} or a "
                                 "support motion")
            X = vib.response(lin, lin.frequency)
            self.cache["X"] = vib.full_amplitudes(lin, X)
        return self.cache["X"]


#: the most coordinates a vibration analysis takes: its second derivatives are n (n + 1) / 2
#: rates of the mechanism and its time grows as n^3 (benchmarks/vibration.py: a chain of 500
#: masses takes about 10 times a chain of 200)
MAX_COORDINATES = 500


def analyse(mech) -> Analysis:
    """Equilibrium and linearisation of ``mech`` (SI)."""
    count = len(mech.coordinates)
    if count > MAX_COORDINATES:
        raise InputError(f"{count} coordinates: a vibration analysis takes at most "
                         f"{MAX_COORDINATES} (its second derivatives are n (n + 1) / 2 rates "
                         "of the mechanism: its time grows as n^3)", file=mech.file,
                         key="coordinates", hint="model the system with fewer degrees of "
                         "freedom, a continuous one by its first modes")
    lag = Lagrangian(mech, solver_for(mech))
    return Analysis(mech, vib.linearise(lag))


def evaluate(mech, names, result):
    """Fill ``result`` (values, units) with ``names`` of a vibration problem."""
    for name in names:
        base, order = split_rate(name, mech.quantities)
        if order and name not in mech.quantities:
            raise InputError(f"'{name}': a file with 'coordinates:' is a vibration problem, "
                             "solved at its static equilibrium: it has no driver rates",
                             file=mech.file, key="report",
                             hint="ask for amplitudes, frequencies or the free response; a "
                             "mechanism moved at given input rates takes 'driver:' (one) "
                             "or 'drivers:' instead of 'coordinates:': " + SEVERAL_DRIVERS)
    analysis = analyse(mech)
    geometric = [n for n in names if mech.quantities[n].kind not in VIBRATION]
    if geometric or mech.report.get("points"):
        solver = solver_for(mech)
        q = analysis.lin.eq.q
        kin = solver.positions(q[0] if len(q) == 1 else tuple(q))
        solved = collect(mech, solver, kin, geometric)
        result.values.update(solved.values)
        result.units.update(solved.units)
        result.points.update(solved.points)
        result.kinematics = kin
    for name in names:
        quantity = mech.quantities[name]
        if quantity.kind in VIBRATION:
            answer = answer_of(analysis, quantity)
            if not math.isfinite(answer.value):
                raise SolveError(f"'{name}' is not a finite number: "
                                 f"{_why_not_finite(answer.value)}", file=mech.file,
                                 hint="check the magnitudes of masses, stiffnesses, lengths "
                                 "and the excitation")
            result.values[name], result.units[name] = shown(mech.units, answer, quantity.unit)
    result.analysis = analysis
    result.cautions = list(analysis.lin.eq.cautions) + road_lift_off(analysis) + \
        analysis.cache.get("cautions", [])
    return result


def _why_not_finite(value) -> str:
    if math.isnan(value):
        return "its computation is undefined (zero over zero or infinity less infinity)"
    return "it overflows floating-point arithmetic: its SI value exceeds 1.8e308"


def road_lift_off(analysis) -> list:
    """A wheel on a road (``excitation: road``) is held down by its static load only: where
    the amplitude of the dynamic force the system exerts on the road's coordinate exceeds
    the static force, the contact pulls in part of each cycle, so the wheel lifts off and the
    linear answer assumes a contact it has not."""
    mech = analysis.mech
    lin = analysis.lin
    road = mech.elements.supports.get("road") if mech.elements else None
    if road is None or lin.frequency is None:
        return []
    j = road.coordinate
    t = lin.eq.terms
    w = lin.frequency
    static = abs(float(t.Q[j]))
    X = analysis.amplitudes()
    row = t.K[j] - w ** 2 * t.M[j] + 1j * w * t.R[j]
    dynamic = abs(complex(row @ X))
    if dynamic <= static:
        return []
    from linkcli.errors import Caution
    force = generalised_force_dim(mech, j)
    text = {}
    for label, value, dim, kind in (("dynamic", dynamic, force, None),
                                    ("static", static, force, None),
                                    ("Omega", w, FREQUENCY_DIM, "frequency")):
        number, unit = shown(mech.units, Answer(value, dim, kind))
        text[label] = f"{number:.6g} {unit}"
    return [Caution("contact", f"the wheel lifts off the road: the dynamic contact force "
                    f"amplitude {text['dynamic']} exceeds the static load {text['static']} at "
                    f"Omega = {text['Omega']}; the linear response assumes a contact the "
                    "wheel does not keep", mech.file,
                    {mech.coordinates[j].name: shown(mech.units, Answer(dynamic, force))[0]})]


def _coordinate(mech, name) -> int:
    return next(j for j, c in enumerate(mech.coordinates) if c.name == name)


def _free_index(analysis, name) -> int:
    j = _coordinate(analysis.mech, name)
    if j not in analysis.lin.free:
        raise InputError(f"coordinate {name} is imposed (a support motion), not free",
                         file=analysis.mech.file, key="quantities",
                         hint="ask for a free coordinate")
    return analysis.lin.free.index(j)


def _coordinate_answer(mech, j, value, turn=False) -> Answer:
    """Coordinate j's ``value`` (SI); ``turn``: an angle shown within one turn."""
    angle = mech.coordinates[j].base == "angle"
    return Answer(float(value), coordinate_dim(mech, j), turn=turn and angle)


def _mode(analysis, quantity) -> int:
    k = int(quantity.a) - 1
    count = len(analysis.lin.free)
    if k >= count:
        raise InputError(f"mode {k + 1} asked, but the problem has {count} free coordinate"
                         f"{'s' if count != 1 else ''}", file=analysis.mech.file,
                         key=f"quantities.{quantity.name}")
    return k


def answer_of(analysis: Analysis, quantity) -> Answer:
    """One vibration quantity in SI, with its dimension (:func:`dimension_of`)."""
    mech = analysis.mech
    dim, kind = dimension_of(mech, quantity)
    turn = quantity.kind == "equilibrium" and dim == ANGLE_DIM
    return Answer(si_value(analysis, quantity), dim, kind, turn)


FREQUENCIES = ("natural_frequency", "damped_frequency", "forcing_frequency")


#: the kind of unit an answer is shown in where its dimension is shared by several
SHOWN = {"natural_period": "time", "damped_period": "time", "beat_period": "time",
         "peak_frequency": "frequency", "phase": "angle",
         **{kind: "frequency" for kind in FREQUENCIES}}


def dimension_of(mech, quantity) -> tuple:
    """(Dimension, kind of unit it is shown in or None) of a vibration quantity, from the
    file alone (model.dimensions): what ``Units.show`` needs to decide its unit."""
    dim = of_quantity(mech, quantity)
    kind = SHOWN.get(quantity.kind)
    if quantity.kind in ("spring_force", "largest") and quantity.a in mech.elements.springs:
        kind = _element_force(mech.elements.springs[quantity.a])[1]
    elif quantity.kind == "force_amplitude":
        kind = _elements_force(mech, quantity)[1]
    return dim, kind


def si_value(analysis: Analysis, quantity) -> float:
    """One vibration quantity in SI (rad/s, m, rad, N, kg ...)."""
    kind = quantity.kind
    if kind in OSCILLATION or quantity.form is not None:
        return oscillation.si_value(analysis, quantity)
    if kind in FREQUENCIES:
        return _frequency(analysis, quantity)
    if kind == "damping_ratio":
        k = _mode(analysis, quantity)
        _require_stiffness(analysis, quantity, k, "its damping ratio c / (2 sqrt(k m))")
        return float(analysis.damped().zeta[k])
    if kind == "mode_shape":
        return _mode_shape(analysis, quantity)
    mech = analysis.mech
    lin = analysis.lin
    if kind.endswith("_matrix"):
        i, j = _coordinate(mech, quantity.a), _coordinate(mech, quantity.b)
        matrix = {"mass_matrix": lin.eq.terms.M, "stiffness_matrix": lin.eq.terms.K,
                  "damping_matrix": lin.eq.terms.R}[kind]
        return float(matrix[i, j])
    if kind == "equilibrium":
        return float(lin.eq.q[_coordinate(mech, quantity.a)])
    if kind == "spring_force":
        return float(lin.eq.terms.forces[quantity.a])
    if kind == "free_response":
        j = _free_index(analysis, quantity.a)
        x0, v0 = oscillation.initial_state(analysis)
        return float(vib.free_response(lin, x0, v0, [quantity.time])[0, j])
    return _steady(analysis, quantity)


def _frequency(analysis, quantity) -> float:
    """A natural or damped frequency of a mode, or the forcing frequency (rad/s)."""
    lin = analysis.lin
    kind = quantity.kind
    if kind == "natural_frequency":
        return float(analysis.modes().omega[_mode(analysis, quantity)])
    if kind == "forcing_frequency":
        if lin.frequency is None:
            raise InputError("no excitation frequency in this file", file=analysis.mech.file,
                             key=f"quantities.{quantity.name}")
        return float(lin.frequency)
    k = _mode(analysis, quantity)
    _require_stiffness(analysis, quantity, k, "it has no damped frequency")
    damped = analysis.damped()
    if not damped.oscillates[k]:
        rates = _rates(analysis, damped.decay(k))
        critical = bool(damped.critical[k])
        how = (f"critically damped (zeta = 1): it returns without oscillating, at the decay "
               f"rate {rates[0]}") if critical else \
            (f"overdamped (zeta = {zeta_text(damped.zeta[k])}): it returns without "
             f"oscillating, as the sum of two decays at the rates {rates[0]} and {rates[1]}")
        raise ModeError(f"'{quantity.name}': mode {k + 1} is {how}, so it has no damped "
                        "frequency", file=analysis.mech.file, key=f"quantities.{quantity.name}",
                        line=quantity.line, mode=k + 1,
                        reason="critically damped" if critical else "overdamped",
                        values=damped.decay(k),
                        hint="ask its damping_ratio; a damped frequency needs zeta < 1")
    return float(damped.omega_d[k])


def zeta_text(zeta) -> str:
    """A damping ratio to 6 digits, or to all of them where those would read 1 (an
    overdamped or underdamped mode next to critical damping)."""
    text = f"{float(zeta):.6g}"
    return repr(float(zeta)) if text == "1" else text


def _rates(analysis, values) -> list:
    """Decay rates (1/s) as text in the file's units."""
    out = []
    for value in values:
        number, unit = shown(analysis.mech.units, Answer(float(value), Dimension(time=-1)))
        out.append(f"{number:.6g} {unit}")
    return out


def _require_stiffness(analysis, quantity, k, what) -> None:
    """Refuse a damping answer of a mode that nothing holds (natural frequency 0)."""
    if analysis.modes().omega[k] > 0:
        return
    roots = ", ".join(f"{-r:.6g}" if r else "0" for r in analysis.damped().decay(k))
    unit = shown(analysis.mech.units, Answer(1.0, Dimension(time=-1)))[1]
    raise ModeError(f"'{quantity.name}': mode {k + 1} has no stiffness (natural frequency 0: "
                    f"no spring or gravity holds it at the equilibrium), so {what} is "
                    f"undefined; its roots are s = {roots} {unit}", file=analysis.mech.file,
                    key=f"quantities.{quantity.name}", line=quantity.line, mode=k + 1,
                    reason="no stiffness", values=analysis.damped().decay(k),
                    hint="add a spring or gravity that holds the mode, or ask only for its "
                    "natural frequency")


def _mode_shape(analysis, quantity) -> float:
    """Coordinate q of mode k over the reference coordinate (the first free one)."""
    mech = analysis.mech
    lin = analysis.lin
    k = _mode(analysis, quantity)
    i = _free_index(analysis, quantity.b)
    found = analysis.modes()
    ref = vib.REFERENCE
    names = lin.names
    if found.repeated[k]:
        others = " and ".join(str(j + 1) for j in [k] + found.repeated[k])
        number, unit = shown(mech.units, Answer(float(found.omega[k]), FREQUENCY_DIM,
                                                "frequency"))
        raise ModeError(f"'{quantity.name}': modes {others} share the natural frequency "
                        f"{number:.6g} {unit}, so their shapes are any combination of theirs: "
                        "a component of one of them is not defined", file=mech.file,
                        key=f"quantities.{quantity.name}", line=quantity.line, mode=k + 1,
                        reason="repeated", values=(found.omega[k],),
                        hint="make a mass or a spring slightly different to break the "
                        "symmetry, or ask for the frequency only")
    if not found.moves(ref, k):
        largest = names[int(np.argmax(found.size[:, k] >= 1 - 1e-6))]    # the first of ties
        raise ModeError(f"'{quantity.name}': the mode shapes are normalised by {names[ref]} "
                        f"(the first free coordinate), and {names[ref]} does not move in mode "
                        f"{k + 1}: it moves less than {found.still[k]:.1e} of the largest "
                        f"component ({largest}'s, in energy), zero within the eigenvector's "
                        f"accuracy, so the ratio {names[i]}/{names[ref]} is undefined",
                        file=mech.file, key=f"quantities.{quantity.name}", line=quantity.line,
                        mode=k + 1, reason="does not move",
                        values=(found.size[ref, k],),
                        hint=f"list first under 'coordinates:' a coordinate that moves in "
                        f"mode {k + 1}, such as {largest}: the shapes are normalised by the "
                        "first")
    return float(found.shapes[i, k])


def _element_force(element) -> tuple:
    """(dimension, kind) of the force of a spring or damper: a torque for a torsional one."""
    if element.measure.kind == "angle":
        return DIMENSIONS["torque"], "torque"
    return FORCE_DIM, "force"


def _steady(analysis, quantity) -> float:
    """Amplitude, phase, transmissibility of a coordinate or a point's x or y, or the
    amplitude of the force through springs and dampers, at the excitation frequency."""
    mech = analysis.mech
    lin = analysis.lin
    kind = quantity.kind
    X = analysis.amplitudes()
    if kind == "force_amplitude":
        return _force_amplitude(analysis, quantity, X)
    if quantity.component is not None:        # a point's coordinate
        jt = lin.eq.terms.jet
        direction = 1 + 0j if quantity.component == "x" else 1j
        s = jac.along(jt, None, quantity.a, direction)
        amp = np.dot(np.asarray(s.grad, dtype=float), X)
    else:
        amp = X[_coordinate(mech, quantity.a)]
    if kind == "amplitude":
        return float(abs(amp))
    if kind == "phase":
        return float(phase(amp))
    # transmissibility: |response| / |imposed amplitude|
    if not lin.imposed:
        raise InputError(f"'{quantity.name}': a transmissibility needs a support motion",
                         file=mech.file, key=f"quantities.{quantity.name}",
                         hint="for a harmonic force, ask force_amplitude of the springs and "
                         "dampers that hold the support, and divide by the force")
    return float(abs(amp) / np.max(np.abs(lin.supports)))


def phase(amplitude):
    """The phase of complex amplitudes against the excitation (rad), in [-pi, pi): negative
    when the response lags.  A response in opposition is -pi whatever the sign of its zero
    imaginary part, the limit of a vanishing damping (the response of one degree of
    freedom lags by 0 to 180 deg); 0 is never -0."""
    value = np.angle(amplitude)
    return np.where(value >= math.pi * (1 - 1e-12), value - 2 * math.pi, value) + 0.0


def _elements_force(mech, quantity) -> tuple:
    """(dimension, kind) of the sum of the forces of a force amplitude's elements: torques
    or forces, not both."""
    elements = {**mech.elements.springs, **mech.elements.dampers}
    kinds = {_element_force(elements[n]) for n in quantity.elements}
    if len(kinds) > 1:
        raise InputError(f"'{quantity.name}': force_amplitude adds the forces of "
                         f"{', '.join(quantity.elements)}, and some are torsional (torques) "
                         "and some not (forces)", file=mech.file,
                         key=f"quantities.{quantity.name}",
                         hint="ask the torsional and the other elements apart")
    return kinds.pop()


def _force_amplitude(analysis, quantity, X) -> float:
    """|sum of k s' + i Omega c s'| over the elements (s' the amplitude of their measure)."""
    mech = analysis.mech
    lin = analysis.lin
    total = 0j
    for name in quantity.elements:
        s = lin.eq.terms.measures[name]
        ds = np.dot(np.asarray(s.grad, dtype=float), X)
        spring = mech.elements.springs.get(name)
        gain = spring.stiffness if spring is not None else \
            1j * lin.frequency * mech.elements.dampers[name].coefficient
        total += gain * ds
    return float(abs(total))


# --- explain ---------------------------------------------------------------------------
def _force_scales(lag, forces) -> dict:
    """Each spring's force scale (N, or N m for a torsional spring): the largest, over the
    springs of its kind, of |N| + k L, the force of a spring strained by the order of the
    mechanism (L its size, 1 rad for a torsional spring), as in the equilibrium's load
    scale; a force under NOISE of it is the rounding noise of a zero."""
    def kind(spring):
        return spring.measure.kind == "angle"

    springs = lag.elements.springs
    own = {name: abs(forces[name]) + s.stiffness * (1.0 if kind(s) else lag.size)
           for name, s in springs.items() if name in forces}
    return {name: max(v for other, v in own.items() if kind(springs[other]) == kind(springs[name]))
            for name in own}


def _text(units, answer: Answer) -> str:
    """An answer as '12.3 unit' in the file's units."""
    value, unit = shown(units, answer)
    return f"{value:.6g} {unit}".rstrip()


def _matrix(mech, name, kind, matrix, free) -> list:
    """``matrix`` (SI) in the file's units: one unit for it where every entry has the same,
    else each row followed by its entries' units."""
    names = [mech.coordinates[j].name for j in free]
    width = max(len(n) for n in names)
    shown_rows = [[shown(mech.units, Answer(float(matrix[a, b]), matrix_dim(kind, mech, i, j)))
                   for b, j in enumerate(free)] for a, i in enumerate(free)]
    units = {unit for row in shown_rows for _, unit in row}
    one = len(units) == 1
    rows = [f"  {name} ({units.pop()}) =" if one else f"  {name} ="]
    for label, row in zip(names, shown_rows):
        text = f"    {label:<{width}} [" + "  ".join(f"{v:>12.6g}" for v, _ in row) + " ]"
        rows.append(text if one else text + "  " + ", ".join(u for _, u in row))
    return rows


def explain_lines(mech) -> list:
    """Energies (SI), Lagrange's equations, the equilibrium and the linearised system, with
    the numbers in the file's units, as the worked solutions write them."""
    analysis = analyse(mech)
    lin = analysis.lin
    lag = lin.lag
    dyn = mech.dynamics
    el = mech.elements
    units = mech.units
    lines = ["Energies (SI units; s is each element's measure, s0 its free value)"]
    kinetic = []
    for m in lin.eq.terms.masses:
        term = f"1/2 {m.mass:.6g} |v_{m.name}|^2"
        if m.theta is not None and m.inertia:
            term += f" + 1/2 {m.inertia:.6g} omega_{m.name}^2"
        kinetic.append(term)
    lines.append("  T = " + (" + ".join(kinetic) or "0"))
    potential = [f"1/2 {s.stiffness:.6g} ({s.measure.text()} - {lag.free[s.name]:.6g})^2"
                 for s in el.springs.values()]
    if dyn is not None and dyn.gravity:
        g = dyn.gravity
        potential += [f"- {m.mass:.6g} ({g.real:.6g}, {g.imag:.6g}) . G_{m.name}"
                      for m in lin.eq.terms.masses]
    potential += [f"- {load.name} (work of the constant load)" for load in mech.loads.values()]
    lines.append("  V = " + (" ".join(("+ " + p) if not p.startswith("-") else p
                                       for p in potential).lstrip("+ ") or "0"))
    lines.append("  D = " + (" + ".join(f"1/2 {d.coefficient:.6g} (d/dt {d.measure.text()})^2"
                                       for d in el.dampers.values()) or "0"))
    lines += ["", "Lagrange's equations, one per coordinate q_i:",
              "  d/dt dT/dq_i' - dT/dq_i + dD/dq_i' + dV/dq_i = F_i(t)",
              "  i.e. M(q) q'' + c(q, q') + R(q) q' = Q(q) + F(t),  Q = -dV/dq"]
    eq = lin.eq
    lines += ["", "Static equilibrium (" + ("the figure" if el.equilibrium == "figure"
                                            else "solved from the figure") + ")"]
    for j, c in enumerate(mech.coordinates):
        state = "imposed" if j in lin.imposed else "free"
        value = _text(units, _coordinate_answer(mech, j, eq.q[j], turn=True))
        lines.append(f"  {c.name} = {value} ({state})")
    scales = _force_scales(lin.lag, eq.terms.forces)
    for name, force in eq.terms.forces.items():
        chosen = " (chosen so that the figure is an equilibrium)" if name in eq.preloads else ""
        force = noise_free(force, scales[name])
        value = _text(units, Answer(force, *_element_force(el.springs[name])))
        lines.append(f"  spring {name}: force N = {value}{chosen}")
    lines.append(f"  residual |Q| = {eq.relative:.2e} of the load scale")
    lines += ["", "Linearised about the equilibrium: M x'' + R x' + K x = F e^{i Omega t}"]
    lines += _matrix(mech, "M", "mass_matrix", lin.M, lin.free)
    lines += _matrix(mech, "K", "stiffness_matrix", lin.K, lin.free)
    if len(lin.free) == 1:
        j = lin.free[0]
        reduced = [f"{label} = " + _text(units, Answer(matrix[0, 0], matrix_dim(kind, mech, j, j)))
                   for label, kind, matrix in (("m*", "mass_matrix", lin.M),
                                               ("k*", "stiffness_matrix", lin.K),
                                               ("r*", "damping_matrix", lin.R))
                   if el.dampers or label != "r*"]
        lines.append("  one degree of freedom: " + ", ".join(reduced)
                     + " (reduced mass or inertia, stiffness, damping)")
    if el.dampers:
        lines += _matrix(mech, "R", "damping_matrix", lin.R, lin.free)
    if lin.frequency is not None:
        amps = lin.load(lin.frequency)
        forces = [f"{_text(units, Answer(abs(a), generalised_force_dim(mech, j)))} at "
                  f"{_text(units, Answer(float(np.angle(a)), ANGLE_DIM, 'angle'))}"
                  for a, j in zip(amps, lin.free)]
        lines.append(f"  Omega = {_text(units, Answer(lin.frequency, FREQUENCY_DIM, 'frequency'))}"
                     f", F = [" + ", ".join(forces) + "]")
    try:
        found = analysis.modes()
    except SolveError as exc:
        return lines + ["", f"  {exc.detail}"]
    return lines + _mode_lines(analysis, found) + oscillation.explain_lines(analysis)


def shape_text(analysis, k) -> str:
    """Mode k's shape as 'x1 1, theta 0.0602 deg/mm' in the file's units (each coordinate
    over the reference, the first free one), and a note where the reference does not move
    (the shape is then scaled to its largest component)."""
    mech = analysis.mech
    lin = analysis.lin
    found = analysis.modes()
    names = lin.names
    ref = vib.REFERENCE
    ref_dim = coordinate_dim(mech, lin.free[ref])
    parts = [f"{names[i]} " + _text(mech.units, Answer(
        float(found.shapes[i, k]), coordinate_dim(mech, lin.free[i]) / ref_dim))
        for i in range(len(names))]
    note = "" if found.moves(ref, k) else f" ({names[ref]} does not move: scaled to the largest)"
    return ", ".join(parts) + note


def _mode_lines(analysis, found) -> list:
    """The natural frequencies and mode shapes, and the damping of each mode."""
    mech = analysis.mech
    lin = analysis.lin
    units = mech.units
    free_names = lin.names
    ref = vib.REFERENCE
    lines = ["", f"Natural frequencies and modes (K u = omega^2 M u; shapes normalised by "
             f"{free_names[ref]} = 1)"]
    for k, w in enumerate(found.omega):
        freq = _text(units, Answer(float(w), FREQUENCY_DIM, "frequency"))
        if units.names["frequency"] != "Hz":
            freq += f" = {w / (2 * np.pi):.6g} Hz"
        lines.append(f"  mode {k + 1}: omega = {freq}; shape {shape_text(analysis, k)}")
    if not mech.elements.dampers:
        return lines
    d = analysis.damped()
    for k in range(len(found.omega)):
        if found.omega[k] == 0:
            roots = ", ".join(f"{-r:.6g}" if r else "0" for r in d.decay(k))
            lines.append(f"  damped {k + 1}: no stiffness, roots s = {roots} "
                         f"{shown(units, Answer(1.0, Dimension(time=-1)))[1]}")
        elif d.oscillates[k]:
            wd = _text(units, Answer(float(d.omega_d[k]), FREQUENCY_DIM, "frequency"))
            lines.append(f"  damped {k + 1}: zeta = {zeta_text(d.zeta[k])}, omega_d = {wd}")
        elif d.critical[k]:
            lines.append(f"  damped {k + 1}: zeta = 1, critically damped: decay rate "
                         f"{_rates(analysis, d.decay(k))[0]}")
        else:
            rates = " and ".join(_rates(analysis, d.decay(k)))
            lines.append(f"  damped {k + 1}: zeta = {zeta_text(d.zeta[k])}, overdamped: decay "
                         f"rates {rates}")
    if np.any(d.share < 1 - 1e-6):
        lines.append("  (damping couples the modes: each pair of roots is the undamped mode "
                     "its motion is most made of; shares " +
                     ", ".join(f"{x:.3g}" for x in d.share) + ")")
    return lines
