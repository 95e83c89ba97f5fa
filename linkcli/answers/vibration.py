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


def is_vibration(mech) -> bool:
    return mech.elements is not None


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
    return result


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
        j = _coordinate(mech, quantity.a)
        unit, factor = _coordinate_unit(mech, j)
        value = lin.eq.q[j] / factor
        if mech.coordinates[j].base == "angle":
            value = value % (360.0 if unit == "deg" else 2 * np.pi)
        return float(value), unit
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
        return float(np.angle(amp)) / ANGLE[angle_unit], angle_unit
    # transmissibility: |response| / |imposed amplitude|
    if not lin.imposed:
        raise InputError(f"'{quantity.name}': a transmissibility needs a support motion",
                         file=mech.file, key=f"quantities.{quantity.name}",
                         hint="for a harmonic force, ask force_amplitude of the springs and "
                         "dampers that hold the support, and divide by the force")
    return float(abs(amp) / np.max(np.abs(lin.supports))), ""
