"""Static equilibrium of a mechanism with springs, gravity and constant loads.

The free coordinates q_f satisfy Q_f(q) = -dV/dq_f = 0, the imposed ones stay
at their figure values.  From the figure, the roots are found by scipy's
hybrid method with the analytic Jacobian dQ/dq = -K.  Springs whose preload
is 'static' get the forces N that make the figure an equilibrium, from the
linear system sum_s N_s s_i = Q_i(other loads) (each spring's Q_i is -N s_i).

An equilibrium is accepted when every |Q_i| is below TOL times that
coordinate's load scale, the sum of the magnitudes of the terms of Q_i.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkcli.errors import SolveError
from linkcli.forces.lagrange import Lagrangian, Terms
from linkcli.model import elements as el

TOL = 1e-10


@dataclass
class Equilibrium:
    """The static equilibrium: coordinates (SI), the terms there, and how well it holds."""

    q: np.ndarray
    terms: Terms
    free: list                 # indices of the free coordinates
    residual: np.ndarray       # Q_f at q
    scale: np.ndarray          # load scale of each free coordinate
    preloads: dict             # 'static' spring -> the force chosen at the figure (N)

    @property
    def relative(self) -> float:
        return float(np.max(np.abs(self.residual) / self.scale)) if len(self.free) else 0.0


def free_coordinates(mech) -> list:
    imposed = set(mech.elements.imposed) if mech.elements is not None else set()
    return [j for j in range(len(mech.coordinates)) if j not in imposed]


def load_scale(lag: Lagrangian, terms: Terms, free) -> np.ndarray:
    """Per free coordinate, the scale of the generalised forces: the sum over the loads
    of |force| |velocity coefficient| (gravity m|g||G_i|, loads |F||P_i|) and over the
    springs of (|N| + k L) |s_i|, with L the mechanism's size (1 rad for a torsional
    spring): the force of a spring strained by the order of the mechanism."""
    n = lag.n
    scale = np.zeros(n)
    g = abs(lag.dyn.gravity) if lag.dyn is not None else 0.0
    for m in terms.masses:
        scale += m.mass * g * np.abs([m.g[1][i] for i in range(n)])
    size = lag.size
    for spring in lag.elements.springs.values():
        strain = spring.stiffness * (1.0 if spring.measure.kind == "angle" else size)
        grad = np.asarray(terms.measures[spring.name].grad, dtype=float)
        scale += (abs(terms.forces[spring.name]) + strain) * np.abs(grad)
    for load in lag.mech.loads.values():
        s = lag.load_measure(terms.jet, load)
        if s is not None and load.value is not None:
            scale += abs(load.value) * np.abs(np.asarray(s.grad, dtype=float))
    scale = scale[free]
    fallback = float(np.max(scale)) if scale.size and np.max(scale) > 0 else 1.0
    return np.where(scale > 0, scale, fallback)


def static_preloads(lag: Lagrangian, free) -> dict:
    """Solve the forces of the 'static' springs that make the figure an equilibrium and
    set their free measures; returns {spring: N}."""
    static = [s for s in lag.elements.springs.values() if s.mode == el.STATIC]
    if not static:
        return {}
    terms = lag.terms(lag.figure)      # static springs are unstretched here: N = 0
    A = np.array([[terms.measures[s.name].grad[i] for s in static] for i in free], dtype=float)
    b = terms.Q[free]
    forces, *_ = np.linalg.lstsq(A, b, rcond=None)
    rank = np.linalg.matrix_rank(A) if A.size else 0
    names = ", ".join(s.name for s in static)
    if rank < len(static):
        raise SolveError(f"the preloads of {names} are not determined by equilibrium: "
                         f"{len(static)} unknown forces, {rank} independent equations",
                         file=lag.mech.file, hint="give the other springs a free length or a "
                         "preload, and 'preload: static' to one spring per coordinate")
    residual = A @ forces - b
    scale = load_scale(lag, terms, free)
    if np.any(np.abs(residual) > 1e-9 * scale):
        worst = int(np.argmax(np.abs(residual) / scale))
        raise SolveError(f"no preload of {names} makes the figure an equilibrium: the force "
                         f"on coordinate {lag.mech.coordinates[free[worst]].name} is left at "
                         f"{residual[worst]:.6g} (SI)", file=lag.mech.file,
                         hint="let the equilibrium be solved ('equilibrium: solve'), or give "
                         "'preload: static' to a spring acting on that coordinate")
    out = {}
    for spring, force in zip(static, forces):
        lag.free[spring.name] -= float(force) / spring.stiffness
        out[spring.name] = float(force)
    return out


def equilibrium(lag: Lagrangian) -> Equilibrium:
    """The static equilibrium nearest the figure (or the figure, 'equilibrium: figure')."""
    mech = lag.mech
    free = free_coordinates(mech)
    preloads = static_preloads(lag, free)
    q = lag.figure.copy()
    mode = mech.elements.equilibrium if mech.elements is not None else "solve"
    if mode == "solve" and free:
        q = _solve(lag, q, free)
    terms = lag.terms(q)
    result = Equilibrium(q, terms, free, terms.Q[free], load_scale(lag, terms, free), preloads)
    if result.relative > (1e-9 if mode == "figure" else TOL * 1e3):
        forces = ", ".join(f"{mech.coordinates[j].name}: {terms.Q[j]:.6g}" for j in free)
        where = "the figure is not a static equilibrium" if mode == "figure" else \
            "no static equilibrium found from the figure"
        raise SolveError(f"{where}: residual generalised forces {forces} (SI; "
                         f"{result.relative:.2e} of the load scale)", file=mech.file,
                         hint="check the springs' free lengths and preloads, the masses and "
                         "gravity" + ("; or let it be solved ('equilibrium: solve')"
                                      if mode == "figure" else ""))
    return result


def _solve(lag: Lagrangian, q0, free):
    """Roots of Q_f from the figure (scipy's hybrid method, Jacobian -K_ff)."""
    from scipy.optimize import root

    cache = {}

    def terms(x):
        key = x.tobytes()
        if key not in cache:
            q = q0.copy()
            q[free] = x
            try:
                cache.clear()
                cache[key] = lag.terms(q)
            except SolveError:
                return None
        return cache[key]

    def fun(x):
        t = terms(x)
        return np.full(len(free), 1e30) if t is None else t.Q[free]

    def jac(x):
        t = terms(x)
        return np.eye(len(free)) if t is None else -t.K[np.ix_(free, free)]

    solution = root(fun, q0[free], jac=jac, method="hybr", options={"xtol": 1e-14})
    q = q0.copy()
    q[free] = solution.x
    return q
