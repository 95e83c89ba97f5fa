"""The answer sheet of a mechanism file: its report evaluated by the path it needs.

A file with a driver is solved at driver value(s) q (``answers.quantities``);
a vibration problem, declared with coordinates, at its static equilibrium
(``answers.quantities.vibration``).
"""
from __future__ import annotations

from linkcli.answers import quantities
from linkcli.answers.quantities import Result, expressions
from linkcli.errors import InputError


def evaluate(mech, q=None, qdot=None, qddot=None, names=None, method="closed",
             tol=None) -> Result:
    """Every name of ``names`` (default: the report's) in its display unit; expression
    quantities worked out from the answers they read (``quantities.expressions``)."""
    names = list(names) if names is not None else quantities.report_names(mech)
    solve, exprs = expressions.expand(mech, names)
    if not exprs:
        return _evaluate(mech, q, qdot, qddot, names, method, tol)
    result = _evaluate(mech, q, qdot, qddot, solve, method, tol)
    expressions.complete(mech, result, names, exprs)
    return result


def _evaluate(mech, q, qdot, qddot, names, method, tol) -> Result:
    """``names`` (none an expression) by the path they need."""
    if mech.elements is None:       # a file with a driver: no vibration modules to import
        if _asks_limits(mech, names):   # maxima, strokes ...: answers.limits
            from linkcli.answers import limits
            return limits.evaluate(mech, q, qdot, qddot, names=names, method=method, tol=tol)
        return quantities.evaluate(mech, q, qdot, qddot, names=names, method=method, tol=tol)
    from linkcli.answers.quantities import vibration
    if q is not None or qdot is not None or qddot is not None or method != "closed":
        raise InputError("a vibration problem is solved at its static equilibrium: it takes no "
                         "driver values, rates or method", file=mech.file,
                         hint="drop q, qdot, qddot and --method")
    return vibration.evaluate(mech, list(names), Result(mech))


def _asks_limits(mech, names) -> bool:
    """Whether ``names`` (default: the report's) hold a limit of the motion."""
    names = quantities.report_names(mech) if names is None else names
    return any(getattr(mech.quantities.get(n), "limit", False) for n in names)
