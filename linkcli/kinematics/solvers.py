"""The one place that picks a kinematic solver by method, and the state for force analysis.

``closed``: the closed form along the Assur decomposition; ``newton``:
Newton-Raphson on every constraint equation, with a tolerance relative to the
mechanism's size.  Solvers are built once per mechanism (and tolerance) and
kept in a cache keyed by the mechanism object, which stays plain data: the
solvers of the KEPT mechanisms solved last.  (A solver refers to its
mechanism, so a cache keyed weakly would keep every mechanism alive: a sweep
over a parameter builds one per value, and its memory grew with the values.)
"""
from __future__ import annotations

from collections import OrderedDict

import numpy as np

from linkcli.errors import InputError, StructureError
from linkcli.kinematics.closed_form import Solver, unit_rates

METHODS = ("closed", "newton")
KEPT = 64
_CACHE: OrderedDict = OrderedDict()     # mechanism -> {key: solver}, the last used at the end


def solver_for(mech, method="closed", tol=None):
    """The solver of ``mech`` for ``method`` ('closed' or 'newton', relative tolerance ``tol``)."""
    if method not in METHODS:
        raise InputError(f"unknown method {method!r}", key="method", hint="closed or newton")
    if getattr(mech, "clutch", None) is not None:
        raise InputError("a clutch problem (shafts and a clutch) has no linkage to solve",
                         file=mech.file, key="shafts", hint="solve(), batch and check answer "
                         "it (runs.sheet), without positions")
    cache = _solvers(mech)
    if method == "closed":
        key = ("closed",)
        if key not in cache:
            cache[key] = _closed(mech)
        return cache[key]
    from linkcli.kinematics.newton import DEFAULT_TOL, NewtonSolver
    key = ("newton", DEFAULT_TOL if tol is None else float(tol))
    if key not in cache:
        cache[key] = NewtonSolver(mech, key[1])
    return cache[key]


def _solvers(mech) -> dict:
    """The solvers kept for ``mech`` (made the last used); the least recently used
    mechanism's are dropped beyond KEPT."""
    cache = _CACHE.get(mech)
    if cache is not None:
        _CACHE.move_to_end(mech)
        return cache
    cache = _CACHE[mech] = {}
    while len(_CACHE) > KEPT:
        _CACHE.popitem(last=False)
    return cache


def _closed(mech):
    """The closed-form solver; with declared coordinates that the decomposition cannot place
    (a coupler's angle), the solver through substitute coordinates that it can."""
    try:
        return Solver(mech)
    except StructureError:
        if mech.elements is None:       # a driver: its rates are the file's, not converted
            raise
        from linkcli.kinematics.substitute import substitute_solver
        solver = substitute_solver(mech)
        if solver is None:
            raise
        return solver


def state(mech, q=None, method="closed", tol=None):
    """(kin, unit) at driver value(s) ``q`` (SI; default the file's): ``kin`` solved to the
    accelerations with the file's qdot and qddot, ``unit`` the velocities for qdot = 1 (the
    virtual-power coefficients; with several drivers, ``q`` is the first's and ``unit`` its
    unit rate, the others at rest)."""
    solver = solver_for(mech, method, tol)
    own, rate, accel = mech.inputs
    if q is None:
        q = own
    elif len(mech.coordinates) > 1:   # several drivers: q the first's, the others the file's
        q = (q,) + tuple(c.value + 0 * np.asarray(q, float) for c in mech.coordinates[1:])
    kin = solver.positions(q)
    solver.check(kin, velocities=False)
    solver.velocities(kin, rate)
    solver.check(kin, velocities=True)
    solver.accelerations(kin, accel)
    unit = unit_rates(solver, kin)
    return kin, unit


def figure_cautions(mech, method="closed", tol=None) -> list:
    """What the figure check found: the figure far from the solved position, an ambiguous or
    forced branch, a figure that cannot be assembled (the branch is then undetermined);
    with ``method`` newton, the points Newton solves far from the figure."""
    from linkcli.errors import Caution
    solver = solver_for(mech, method, tol)
    out = list(solver.cautions)
    if solver.undetermined:
        out.insert(0, Caution("unassembled", solver.undetermined, mech.file))
    return out
