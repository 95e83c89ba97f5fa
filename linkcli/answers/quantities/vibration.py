"""The report of a vibration problem: every asked quantity in its display unit.

Frequencies are in the file's frequency unit (rad/s by default) unless the
quantity says otherwise; equilibrium values and amplitudes of coordinates in
the coordinate's unit (the file's angle or length unit), phases in the angle
unit (the response lags the excitation when negative); matrix entries, spring
forces and force amplitudes in SI (kg, kg m, kg m^2; N/m, N/rad, N m/rad;
N s/m ...; N or N m).  A mode shape component is the ratio of that
coordinate to the first one in the mode (SI units: m/rad for a length against
an angle).  Geometric quantities of the position section are evaluated at the
equilibrium.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from linkcli.answers.quantities import collect
from linkcli.errors import InputError, SolveError
from linkcli.forces import vibration as vib
from linkcli.forces.lagrange import Lagrangian
from linkcli.kinematics import jacobian as jac
from linkcli.kinematics.solvers import solver_for
from linkcli.model.mechanism import VIBRATION, split_rate
from linkcli.model.units import ANGLE, FREQUENCY, LENGTH

#: SI unit names of matrix entries, by (base of row, base of column)
MATRIX_UNITS = {
    "mass_matrix": {("length", "length"): "kg", ("angle", "angle"): "kg m^2",
                    ("length", "angle"): "kg m", ("angle", "length"): "kg m"},
    "stiffness_matrix": {("length", "length"): "N/m", ("angle", "angle"): "Nm/rad",
                         ("length", "angle"): "N/rad", ("angle", "length"): "N/rad"},
    "damping_matrix": {("length", "length"): "Ns/m", ("angle", "angle"): "Nms/rad",
                       ("length", "angle"): "Ns/rad", ("angle", "length"): "Ns/rad"},
}


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
            self.modes()                 # refuses an unstable equilibrium first
            self.cache["damped"] = vib.damped(self.lin)
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


def analyse(mech) -> Analysis:
    """Equilibrium and linearisation of ``mech`` (SI)."""
    lag = Lagrangian(mech, solver_for(mech))
    return Analysis(mech, vib.linearise(lag))


def evaluate(mech, names, result):
    """Fill ``result`` (values, units) with ``names`` of a vibration problem."""
    for name in names:
        base, order = split_rate(name)
        if order and name not in mech.quantities:
            raise InputError(f"'{name}': a vibration problem has no driver rates",
                             file=mech.file, key="report",
                             hint="ask for amplitudes, frequencies or the free response")
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
            value, unit = value_of(analysis, quantity)
            if not np.isfinite(value):
                raise SolveError(f"'{name}' is not a finite number", file=mech.file)
            result.values[name] = value
            result.units[name] = unit
    result.analysis = analysis
    result.cautions = list(analysis.lin.eq.cautions) + road_lift_off(analysis)
    return result


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
    return [Caution("contact", f"the wheel lifts off the road: the dynamic contact force "
                    f"amplitude {dynamic:.6g} N exceeds the static load {static:.6g} N at "
                    f"Omega = {w:.6g} rad/s; the linear response assumes a contact the wheel "
                    "does not keep", mech.file, {mech.coordinates[j].name: dynamic})]


def _coordinate(mech, name) -> int:
    return next(j for j, c in enumerate(mech.coordinates) if c.name == name)


def _free_index(analysis, name) -> int:
    j = _coordinate(analysis.mech, name)
    if j not in analysis.lin.free:
        raise InputError(f"coordinate {name} is imposed (a support motion), not free",
                         file=analysis.mech.file, key="quantities",
                         hint="ask for a free coordinate")
    return analysis.lin.free.index(j)


def _coordinate_unit(mech, j):
    base = mech.coordinates[j].base
    unit = mech.units.names["angle" if base == "angle" else "length"]
    return unit, (ANGLE if base == "angle" else LENGTH)[unit]


def _coordinate_value(mech, j, q):
    """(value, unit) of coordinate j of ``q`` (SI) in its display unit; angles in [0, 360)."""
    unit, factor = _coordinate_unit(mech, j)
    value = q[j] / factor
    if mech.coordinates[j].base == "angle":
        value = value % (360.0 if unit == "deg" else 2 * np.pi)
    return float(value), unit


def _mode(analysis, quantity) -> int:
    k = int(quantity.a) - 1
    count = len(analysis.lin.free)
    if k >= count:
        raise InputError(f"mode {k + 1} asked, but the problem has {count} free coordinate"
                         f"{'s' if count != 1 else ''}", file=analysis.mech.file,
                         key=f"quantities.{quantity.name}")
    return k


def value_of(analysis: Analysis, quantity):
    """(value, unit) of one vibration quantity."""
    mech = analysis.mech
    lin = analysis.lin
    kind = quantity.kind
    if kind in ("natural_frequency", "damped_frequency", "forcing_frequency"):
        unit = quantity.unit or mech.units.names["frequency"]
        if kind == "natural_frequency":
            omega = analysis.modes().omega[_mode(analysis, quantity)]
        elif kind == "damped_frequency":
            omega = analysis.damped().omega_d[_mode(analysis, quantity)]
        else:
            if lin.frequency is None:
                raise InputError("no excitation frequency in this file", file=mech.file,
                                 key=f"quantities.{quantity.name}")
            omega = lin.frequency
        return float(omega) / FREQUENCY[unit], unit
    if kind == "damping_ratio":
        return float(analysis.damped().zeta[_mode(analysis, quantity)]), ""
    if kind == "mode_shape":
        shapes = analysis.modes().shapes
        return float(shapes[_free_index(analysis, quantity.b), _mode(analysis, quantity)]), ""
    if kind.endswith("_matrix"):
        i, j = _coordinate(mech, quantity.a), _coordinate(mech, quantity.b)
        matrix = {"mass_matrix": lin.eq.terms.M, "stiffness_matrix": lin.eq.terms.K,
                  "damping_matrix": lin.eq.terms.R}[kind]
        bases = (mech.coordinates[i].base, mech.coordinates[j].base)
        return float(matrix[i, j]), MATRIX_UNITS[kind][bases]
    if kind == "equilibrium":
        return _coordinate_value(mech, _coordinate(mech, quantity.a), lin.eq.q)
    if kind == "spring_force":
        spring = mech.elements.springs[quantity.a]
        return float(lin.eq.terms.forces[quantity.a]), \
            "Nm" if spring.measure.kind == "angle" else "N"
    if kind == "free_response":
        j = _free_index(analysis, quantity.a)
        x0 = np.zeros(len(lin.free))
        v0 = np.zeros(len(lin.free))
        for c, (dx, dv) in mech.elements.initial.items():
            if c in lin.free:
                x0[lin.free.index(c)], v0[lin.free.index(c)] = dx, dv
        x = vib.free_response(lin, x0, v0, [quantity.time])[0, j]
        unit, factor = _coordinate_unit(mech, lin.free[j])
        return float(x) / factor, unit
    # steady-state response
    X = analysis.amplitudes()
    if kind == "force_amplitude":
        omega = lin.frequency
        total = 0j
        for name in quantity.elements:
            s = lin.eq.terms.measures[name]
            ds = np.dot(np.asarray(s.grad, dtype=float), X)
            spring = mech.elements.springs.get(name)
            gain = spring.stiffness if spring is not None else \
                1j * omega * mech.elements.dampers[name].coefficient
            total += gain * ds
        elements = {**mech.elements.springs, **mech.elements.dampers}
        torsional = all(elements[n].measure.kind == "angle" for n in quantity.elements)
        return float(abs(total)), "Nm" if torsional else "N"
    if quantity.component is not None:        # a point's coordinate
        jt = lin.eq.terms.jet
        direction = 1 + 0j if quantity.component == "x" else 1j
        s = jac.along(jt, None, quantity.a, direction)
        amp = np.dot(np.asarray(s.grad, dtype=float), X)
        unit = mech.units.names["length"]
        factor = LENGTH[unit]
    else:
        j = _coordinate(mech, quantity.a)
        amp = X[j]
        unit, factor = _coordinate_unit(mech, j)
    if kind == "amplitude":
        return float(abs(amp)) / factor, unit
    if kind == "phase":
        angle_unit = mech.units.names["angle"]
        phase = float(np.angle(amp))
        if phase <= -np.pi + 1e-12:        # in (-180, 180]: opposition is +180, whatever 0's sign
            phase += 2 * np.pi
        return phase / ANGLE[angle_unit], angle_unit
    # transmissibility: |response| / |imposed amplitude|
    if not lin.imposed:
        raise InputError(f"'{quantity.name}': a transmissibility needs a support motion",
                         file=mech.file, key=f"quantities.{quantity.name}",
                         hint="for a harmonic force, ask force_amplitude of the springs and "
                         "dampers that hold the support, and divide by the force")
    return float(abs(amp) / np.max(np.abs(lin.supports))), ""


# --- explain ---------------------------------------------------------------------------
def _matrix(name, matrix, names, unit) -> list:
    width = max(len(n) for n in names)
    rows = [f"  {name} ({unit}) =" if unit else f"  {name} ="]
    for label, row in zip(names, matrix):
        rows.append(f"    {label:<{width}} [" + "  ".join(f"{v:>12.6g}" for v in row) + " ]")
    return rows


def _units_of(mech, free, kind):
    bases = {mech.coordinates[j].base for j in free}
    return MATRIX_UNITS[kind][(bases.pop(),) * 2] if len(bases) == 1 else "SI"


def explain_lines(mech) -> list:
    """Energies, Lagrange's equations, the equilibrium and the linearised system, with
    the numbers (SI), as the worked solutions write them."""
    analysis = analyse(mech)
    lin = analysis.lin
    lag = lin.lag
    names = [c.name for c in mech.coordinates]
    dyn = mech.dynamics
    el = mech.elements
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
        value, unit = _coordinate_value(mech, j, eq.q)
        state = "imposed" if j in lin.imposed else "free"
        lines.append(f"  {c.name} = {value:.6g} {unit} ({state})")
    for name, force in eq.terms.forces.items():
        chosen = " (chosen so that the figure is an equilibrium)" if name in eq.preloads else ""
        lines.append(f"  spring {name}: force N = {force:.6g}{chosen}")
    lines.append(f"  residual |Q| = {eq.relative:.2e} of the load scale")
    free_names = [names[j] for j in lin.free]
    lines += ["", "Linearised about the equilibrium: M x'' + R x' + K x = F e^{i Omega t}"]
    lines += _matrix("M", lin.M, free_names, _units_of(mech, lin.free, "mass_matrix"))
    lines += _matrix("K", lin.K, free_names, _units_of(mech, lin.free, "stiffness_matrix"))
    if len(lin.free) == 1:
        lines.append(f"  one degree of freedom: m* = {lin.M[0, 0]:.6g}, k* = {lin.K[0, 0]:.6g}"
                     + (f", r* = {lin.R[0, 0]:.6g}" if el.dampers else "")
                     + " (reduced mass or inertia, stiffness, damping)")
    if el.dampers:
        lines += _matrix("R", lin.R, free_names, _units_of(mech, lin.free, "damping_matrix"))
    if lin.frequency is not None:
        amps = lin.load(lin.frequency)
        lines.append(f"  Omega = {lin.frequency:.6g} rad/s, F = [" +
                     ", ".join(f"{abs(a):.6g} at {np.degrees(np.angle(a)):.4g} deg"
                               for a in amps) + "]")
    try:
        modes = analysis.modes()
    except SolveError as exc:
        return lines + ["", f"  {exc.detail}"]
    lines += ["", "Natural frequencies and modes (K u = omega^2 M u)"]
    for k, w in enumerate(modes.omega):
        shape = ", ".join(f"{free_names[i]} {modes.shapes[i, k]:.6g}" for i in range(len(free_names)))
        lines.append(f"  mode {k + 1}: omega = {w:.6g} rad/s = {w / (2 * np.pi):.6g} Hz; "
                     f"shape {shape}")
    if el.dampers:
        d = analysis.damped()
        for k in range(len(d.zeta)):
            lines.append(f"  damped {k + 1}: zeta = {d.zeta[k]:.6g}, "
                         f"omega_d = {d.omega_d[k]:.6g} rad/s")
    return lines
