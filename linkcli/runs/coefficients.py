"""A vibration problem swept over a parameter that only sets coefficients: every value at once.

Where the parameter changes nothing but springs' stiffnesses, dampers' coefficients, point
masses, bodies' masses and inertias and the forcing frequency (what the file writes with
it, evaluated over the whole array of its values), the geometry, the equilibrium's jets and
the Lagrangian's shape do not depend on it: the terms at the equilibrium are affine in
those coefficients, T(c) = T(c0) + sum_j (c_j - c_j0) dT_j, with dT_j from the file solved
once with c_j doubled (exact: each term holds one coefficient).  M, K, R of every value are
assembled at once, and the answers of the linear system solved on stacks of matrices:
generalised eigenvalues by Cholesky factors (numpy's eigh on M^-1/2 K M^-T/2), forced
responses by stacked solves.

The equilibrium must not move (|Q| within the equilibrium's tolerance at every value; a
value where it does is solved as usual), and the answers must be of the kinds this module
computes (natural frequencies and what is made of them, matrices, spring forces, mode shapes,
amplitudes, phases, transmissibilities, force amplitudes, the characteristic polynomial, and
expressions over them).  Otherwise, and where the answers at three of the values differ
from those of the file solved as usual beyond rounding (the check that nothing else
depended on the parameter), :func:`sweep` returns None and every value is solved as usual.
"""
from __future__ import annotations

import copy
import dataclasses
import math

import numpy as np

from linkcli.errors import LinkcliError
from linkcli.input.expressions import Expression

#: the kinds of answer computed here
KINDS = ("natural_frequency", "natural_period", "eigenvalue", "frequency_ratio",
         "mass_matrix", "stiffness_matrix", "damping_matrix", "equilibrium", "spring_force",
         "mode_shape", "amplitude", "phase", "transmissibility", "force_amplitude",
         "characteristic", "forcing_frequency", "receptance", "beat_period")
#: the values checked against the file solved as usual, and how close they must be
PROBES = 3
AGREE = 1e-8


def sweep(mech, name, values, names, evaluate):
    """(answers, solved, units) of ``names`` at the ``values`` of parameter ``name``, each
    answer an array over the values (NaN where ``solved`` is False: to be solved as usual),
    or None where this module does not apply."""
    from linkcli.answers.quantities.expressions import expand
    if mech.elements is None or mech.design is not None or mech.source is None:
        return None
    wanted, exprs = expand(mech, names)
    if any(mech.quantities[n].kind not in KINDS for n in wanted):
        return None
    values = np.asarray(values, dtype=float)
    coefficients = _coefficients(mech, name, values)
    if coefficients is None:
        return None
    try:
        base = evaluate(mech, names=wanted)
        linear = _Linear(mech, coefficients)
    except LinkcliError:
        return None
    answers, good = linear.answers(wanted, base)
    units = dict(base.units)
    if exprs:       # an expression's unit is known once it is worked out
        answers, good, units = _expressions(mech, names, exprs, answers, good, base)
    else:
        answers = {n: answers[n] for n in names}
    units = {n: units[n] for n in names}
    if not _agrees(mech, name, values, names, answers, good, evaluate):
        return None
    for n in answers:
        answers[n] = np.where(good, answers[n], np.nan)
    return answers, good, units


# --- what the parameter sets ------------------------------------------------------------------
def _setter(path):
    """What a written value at ``path`` sets, as (kind of coefficient, its name), or None."""
    if len(path) == 3 and path[0] == "springs" and path[2] == "k":
        return "spring", path[1]
    if len(path) == 3 and path[0] == "dampers" and path[2] == "c":
        return "damper", path[1]
    if len(path) == 3 and path[:2] == ("dynamics", "masses"):
        return "point mass", path[2]
    if len(path) == 4 and path[:2] == ("dynamics", "bodies") and path[3] in ("mass", "inertia"):
        return "body " + path[3], path[2]
    if path == ("excitation", "frequency"):
        return "frequency", None
    return None


def _coefficients(mech, name, values) -> dict | None:
    """{(kind, element): SI values over ``values``} of every coefficient the parameter sets,
    or None where it sets anything else (a length, a position, an amplitude...)."""
    source = mech.source
    params = source.doc.data.get("params") or {}
    scope = {"k": float(mech.k)} if mech.k is not None else {}
    given = dict(source.params)
    varied = set()
    try:
        for key, text in params.items():
            if key == name:
                scope[key] = values
            elif key in given:
                scope[key] = float(given[key])
            else:
                scope[key] = Expression(text).value(scope) if isinstance(text, str) \
                    else float(text)
            if isinstance(scope[key], np.ndarray):
                varied.add(key)
    except LinkcliError:
        return None
    out = {}
    for path, (text, kind) in source.written.items():
        if path[0] == "params":
            continue
        expression = Expression(text)
        if not set(expression.names) & varied:
            continue
        what = _setter(path)
        if what is None or kind is None:
            return None
        try:
            value = np.broadcast_to(expression.value(scope), values.shape) * \
                mech.units.factor(kind)
        except LinkcliError:
            return None
        out[what] = np.asarray(value, dtype=float)
    return out or None


def _with(mech, changes: dict):
    """A copy of ``mech`` with these coefficients (one value each), for the Lagrangian."""
    out = copy.copy(mech)
    elements = out.elements = dataclasses.replace(
        mech.elements, springs=dict(mech.elements.springs), dampers=dict(mech.elements.dampers))
    dyn = None
    if mech.dynamics is not None:
        dyn = out.dynamics = dataclasses.replace(mech.dynamics, bodies=dict(mech.dynamics.bodies),
                                                 masses=dict(mech.dynamics.masses))
    for (kind, element), value in changes.items():
        if kind == "spring":
            elements.springs[element] = dataclasses.replace(elements.springs[element],
                                                            stiffness=value)
        elif kind == "damper":
            elements.dampers[element] = dataclasses.replace(elements.dampers[element],
                                                            coefficient=value)
        elif kind == "point mass":
            dyn.masses[element] = value
        elif kind.startswith("body "):
            dyn.bodies[element] = dataclasses.replace(dyn.bodies[element],
                                                      **{kind[5:]: value})
        elif kind == "frequency":
            elements.frequency = value
    return out


def _base(mech, what):
    kind, element = what
    if kind == "spring":
        return mech.elements.springs[element].stiffness
    if kind == "damper":
        return mech.elements.dampers[element].coefficient
    if kind == "point mass":
        return mech.dynamics.masses[element]
    if kind == "frequency":
        return mech.elements.frequency
    return getattr(mech.dynamics.bodies[element], kind[5:])


# --- the linear system at every value ------------------------------------------------------------
class _Linear:
    """M, K, R, Q and the springs' forces at the equilibrium for every value of the
    coefficients, and the answers of the linear system they make."""

    def __init__(self, mech, coefficients):
        from linkcli.answers.quantities.vibration import analyse
        from linkcli.forces.equilibrium import TOL, static_preloads
        from linkcli.forces.lagrange import Lagrangian
        self.mech = mech
        self.coefficients = coefficients
        analysis = analyse(mech)
        lin = self.lin = analysis.lin
        q = lin.eq.q
        solver = lin.lag.solver

        def terms(changes):
            lag = Lagrangian(_with(mech, changes), solver)
            static_preloads(lag, lin.eq.free)
            return lag.terms(q)
        t0 = terms({})
        size = next(iter(coefficients.values())).shape
        self.omega = np.full(size, lin.frequency if lin.frequency is not None else np.nan)
        parts = {"M": t0.M, "K": t0.K, "R": t0.R, "Q": t0.Q,
                 "N": np.array(list(t0.forces.values()), dtype=float)}
        self.springs = list(t0.forces)
        stacks = {key: np.broadcast_to(value, size + value.shape).copy()
                  for key, value in parts.items()}
        for what, c in coefficients.items():
            if what[0] == "frequency":
                self.omega = c
                continue
            c0 = _base(mech, what)
            step = c0 if c0 else 1.0
            tj = terms({what: c0 + step})
            change = (c - c0)[..., None, None] / step
            for key, value in (("M", tj.M), ("K", tj.K), ("R", tj.R)):
                stacks[key] += change * (value - parts[key])
            stacks["Q"] += change[..., 0] * (tj.Q - t0.Q)
            stacks["N"] += change[..., 0] * (np.array(list(tj.forces.values())) - parts["N"])
        self.M, self.K, self.R, self.Q, self.N = (stacks[k] for k in "MKRQN")
        free = lin.free
        scale = lin.eq.scale * (1 + max(float(np.max(np.abs(c / (_base(mech, w) or 1.0))))
                                        for w, c in coefficients.items()))
        self.good = np.all(np.abs(self.Q[..., free]) <= TOL * 1e3 * scale, axis=-1)
        ix = np.ix_(free, free)
        self.Mf, self.Kf, self.Rf = (a[..., ix[0], ix[1]] for a in (self.M, self.K, self.R))
        self._modes = None

    def coefficient(self, kind, name):
        """A spring's stiffness or a damper's coefficient at every value."""
        if (kind, name) in self.coefficients:
            return self.coefficients[(kind, name)]
        return _base(self.mech, (kind, name))

    def modes(self):
        """(omega^2, mass-normalised vectors) of every value: K u = omega^2 M u by the
        Cholesky factor L of M, eigh of L^-1 K L^-T."""
        if self._modes is None:
            L = np.linalg.cholesky(self.Mf)
            Linv = np.linalg.inv(L)
            A = Linv @ self.Kf @ np.swapaxes(Linv, -1, -2)
            values, vectors = np.linalg.eigh(0.5 * (A + np.swapaxes(A, -1, -2)))
            vectors = np.swapaxes(Linv, -1, -2) @ vectors
            top = np.max(np.abs(values), axis=-1, keepdims=True)
            self.good &= np.all(values >= -1e-9 * top, axis=-1)
            self._modes = (np.where(values < 0, 0.0, values), vectors)
        return self._modes

    def response(self):
        """The complex amplitudes of every coordinate at each value's forcing frequency."""
        lin = self.lin
        w = self.omega[..., None, None]
        D = self.Kf - w ** 2 * self.Mf + 1j * w * self.Rf
        F = np.broadcast_to(np.asarray(lin.forces, dtype=complex), D.shape[:-1]).copy()
        if lin.imposed:
            fs = np.ix_(lin.free, lin.imposed)
            C = self.K[..., fs[0], fs[1]] - w ** 2 * self.M[..., fs[0], fs[1]] + \
                1j * w * self.R[..., fs[0], fs[1]]
            F = F - C @ lin.supports
        X = np.linalg.solve(D, F[..., None])[..., 0]
        out = np.zeros(X.shape[:-1] + (lin.lag.n,), dtype=complex)
        out[..., lin.free] = X
        if lin.imposed:
            out[..., lin.imposed] = lin.supports
        return out

    def answers(self, names, base):
        """{name: SI answers / display factor} over the values, and the mask of the good
        values."""
        from linkcli.model.dimensions import dimension
        from linkcli.model.units import parse_unit
        out = {}
        for name in names:
            quantity = self.mech.quantities[name]
            if quantity.kind == "equilibrium":
                out[name] = np.full(self.omega.shape, float(base.values[name]))
                continue
            si = self._si(quantity)
            factor = parse_unit(base.units[name], dimension(self.mech, name))[1]
            out[name] = np.real(si) / factor
        return out, self.good & np.all([np.isfinite(v) for v in out.values()], axis=0)

    def _si(self, quantity):
        mech, lin, kind = self.mech, self.lin, quantity.kind
        index = {c.name: j for j, c in enumerate(mech.coordinates)}
        if kind.endswith("_matrix"):
            matrix = {"mass_matrix": self.M, "stiffness_matrix": self.K,
                      "damping_matrix": self.R}[kind]
            return matrix[..., index[quantity.a], index[quantity.b]]
        if kind == "spring_force":
            return self.N[..., self.springs.index(quantity.a)]
        if kind == "forcing_frequency":
            return self.omega
        if kind == "characteristic":
            from linkcli.forces.oscillation import characteristic
            c = characteristic(self.Mf, self.Kf)
            i = int(quantity.a)
            return c[..., i] / c[..., -1] if quantity.form == "monic" else c[..., i]
        if kind == "receptance":
            w = self.omega[..., None, None]
            H = np.linalg.inv(self.Kf - w ** 2 * self.Mf + 1j * w * self.Rf)
            i, j = (lin.free.index(index[c]) for c in (quantity.a, quantity.b))
            return _part(H[..., i, j], quantity.form)
        values, vectors = self.modes()
        if kind in ("natural_frequency", "natural_period", "eigenvalue", "frequency_ratio"):
            k = int(quantity.a) - 1
            omega = np.sqrt(values[..., k])
            return {"natural_frequency": omega, "eigenvalue": values[..., k],
                    "natural_period": 2 * np.pi / np.where(omega > 0, omega, np.nan),
                    "frequency_ratio": self.omega / np.where(omega > 0, omega, np.nan)}[kind]
        if kind == "beat_period":
            a, b = (np.sqrt(values[..., int(m) - 1]) for m in (quantity.a, quantity.b))
            gap = np.abs(b - a)
            return 2 * np.pi / np.where(gap > 0, gap, np.nan)
        if kind == "mode_shape":
            k = int(quantity.a) - 1
            i = lin.free.index(index[quantity.b])
            column = vectors[..., :, k]
            weight = np.abs(column) * np.sqrt(np.diagonal(self.Mf, axis1=-2, axis2=-1))
            moves = weight[..., 0] > 1e-6 * np.max(weight, axis=-1)
            self.good &= moves
            return column[..., i] / np.where(moves, column[..., 0], np.nan)
        X = self.response()
        return _steady(self, quantity, X, index)


def _steady(linear, quantity, X, index):
    """Amplitude, phase, transmissibility of a coordinate or point, a force amplitude."""
    from linkcli.kinematics import jacobian as jac
    mech, lin = linear.mech, linear.lin
    if quantity.kind == "force_amplitude":
        total = 0
        for name in quantity.elements:
            g = np.asarray(lin.eq.terms.measures[name].grad, dtype=float)
            if name in mech.elements.springs:
                total = total + linear.coefficient("spring", name) * (X @ g)
            else:
                total = total + 1j * linear.omega * linear.coefficient("damper", name) * \
                    (X @ g)
        return _part(total, quantity.form)
    if quantity.component is not None:
        direction = 1 + 0j if quantity.component == "x" else 1j
        g = np.asarray(jac.along(lin.eq.terms.jet, None, quantity.a, direction).grad, float)
        amp = X @ g
    else:
        amp = X[..., index[quantity.a]]
    if quantity.kind == "amplitude":
        return _part(amp, quantity.form)
    if quantity.kind == "phase":
        phase = np.angle(amp)
        return np.where(phase <= -np.pi + 1e-12, phase + 2 * np.pi, phase)
    return np.abs(amp) / np.max(np.abs(lin.supports))


def _part(value, form):
    """The real or imaginary part of complex answers, or their magnitude."""
    return np.real(value) if form == "real" else np.imag(value) if form == "imaginary" \
        else np.abs(value)


# --- expressions and the check ----------------------------------------------------------------
def _expressions(mech, names, exprs, answers, good, base):
    from linkcli.answers.quantities import Result
    from linkcli.answers.quantities.expressions import complete
    result = Result(mech, values=dict(answers), units=dict(base.units))
    complete(mech, result, names, exprs)
    values = {n: np.asarray(v, dtype=float) for n, v in result.values.items()}
    return values, good & np.all([np.isfinite(v) for v in values.values()], axis=0), \
        dict(result.units)


def _agrees(mech, name, values, names, answers, good, evaluate) -> bool:
    """Whether the answers at PROBES good values are those of the file solved as usual."""
    from linkcli.answers.quantities import angle_period
    from linkcli.input.document import rebuild
    rows = np.nonzero(good)[0]
    if not rows.size:
        return True
    for row in rows[np.unique(np.linspace(0, rows.size - 1, PROBES).astype(int))]:
        try:
            usual = evaluate(rebuild(mech, {name: float(values[row])}), names=names)
        except LinkcliError:
            return False
        for n in names:
            expected = float(np.asarray(usual.values[n]))
            gap = answers[n][row] - expected
            period = angle_period(mech, n, usual.units[n])
            if period:
                gap = math.remainder(gap, period)
            scale = max(abs(expected), float(np.max(np.abs(answers[n][rows]))) * 1e-6)
            if not abs(gap) <= AGREE * scale + 1e-300:
                return False
    return True
