"""A file's answers as a function of the driver, made once: the per-call path of the Python
API (``Linkage.evaluator``) for a caller that solves one mechanism at many positions (an
integration of its motion, an optimisation, a plot redrawn live).

:class:`Evaluator` works out once what a call of ``Linkage.solve`` works out at every call
(the design question's solution, the names' route, the plan, the solver, the straight-line
solve of ``kinematics.straight``); a call then converts the driver's values from display
units and runs the straight-line function: a tuple of numbers for one position, a
(names x positions) array for a 1-D array of them.  Where the straight-line solve cannot
express the names (a speed, a load, an expression, a limit of the motion, a group it does
not write) or leaves a position to the general path (one not clearly regular), the call is
``Linkage.solve``'s, with its answers and its refusals (the same errors with the same
fields): the values are the same within rounding either way.
"""
from __future__ import annotations

import numpy as np

from linkcli.answers.memory import LONG, keep_freed_memory
from linkcli.answers.quantities import plan_for, require_driver
from linkcli.answers.quantities.plan import BLOCK, as_number
from linkcli.kinematics.solvers import solver_for
from linkcli.kinematics.straight import SHORT
from linkcli.runs import design
from linkcli.runs.sheet import evaluate, route


class Evaluator:
    """``evaluator(q, qdot=None, qddot=None)``: the answers ``names`` (default: the report's)
    at driver value(s) ``q`` with rates ``qdot``, ``qddot`` (display units; the file's where
    not given), in the order of ``names``: a tuple of numbers for one position, an array
    (names x positions) for a 1-D array of positions.  ``units``: each name's display unit,
    where known before a call."""

    def __init__(self, mech, names=None, method="closed", tol=None):
        require_driver(mech, "an evaluator")
        if design.unsolved(mech):
            mech = design.resolved(mech, evaluate, method, tol)
        self.mech, self.method, self.tol = mech, method, tol
        names, solve, exprs, solved, limits = route(mech, names)
        self.names = tuple(names)
        self._straight = None
        plan = plan_for(mech, solve, method, tol)
        self.units = tuple(getattr(plan, "units", {}).get(n) for n in self.names)
        if not (exprs or solved or limits) and list(plan.names) == list(self.names) and \
                len(mech.coordinates) == 1:     # several drivers: solve's path
            self._straight = plan._straight_of(solver_for(mech, method, tol),
                                               plan.order(mech), now=True)
            self._factors = plan.q_factors
            self._count = len(self.names)
            self._points = bool(plan.points)

    def __repr__(self) -> str:
        return f"Evaluator({self.mech.title!r}, names={list(self.names)})"

    def __call__(self, q=None, qdot=None, qddot=None):
        fast = self._straight
        if fast is not None:
            values = self._fast(fast, q, qdot, qddot)
            if values is not None:
                return values
        result = evaluate(self.mech, q, qdot, qddot, names=list(self.names),
                          method=self.method, tol=self.tol)
        if np.ndim(q) == 0:
            return tuple(float(result.values[n]) for n in self.names)
        return np.array([np.broadcast_to(result.values[n], np.shape(q)) for n in self.names])

    def _fast(self, fast, q, qdot, qddot):
        """The straight-line answer, None where the general path is to answer."""
        driver = self.mech.driver
        f0, f1, f2 = self._factors
        try:
            qs = driver.value if q is None else as_number(q, f0)
            w = driver.rate if qdot is None else as_number(qdot, f1)
            al = driver.accel if qddot is None else as_number(qddot, f2)
            if qs is not None and w is not None and al is not None:
                values = fast.scalar(qs, w, al)
                return values[:self._count] if self._points and values is not None \
                    else values
        except (ArithmeticError, ValueError, TypeError):
            return None
        qs = np.asarray(q, float) * f0
        w = driver.rate if qdot is None else np.asarray(qdot, float) * f1
        al = driver.accel if qddot is None else np.asarray(qddot, float) * f2
        if qs.ndim != 1 or not 0 < qs.size <= BLOCK or w is None or al is None or \
                any(np.ndim(x) and np.shape(x) != qs.shape for x in (w, al)):
            return None
        if qs.size >= LONG:
            keep_freed_memory()
        table = fast.short(qs, w, al) if qs.size <= SHORT else fast.array(qs, w, al)
        return table[:self._count] if self._points and table is not None else table
