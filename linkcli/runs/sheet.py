"""The answer sheet of a mechanism file: its report evaluated by the path it needs.

A file with a driver is solved at driver value(s) q (``answers.quantities``);
a vibration problem, declared with coordinates, at its static equilibrium
(``answers.quantities.vibration``).
"""
from __future__ import annotations

import weakref

import numpy as np

from linkcli.answers import quantities
from linkcli.runs import design
from linkcli.answers.quantities import Result, expressions
from linkcli.errors import InputError
from linkcli.model.mechanism import MACHINE
from linkcli.model.regime import KINDS as REGIME_KINDS


def evaluate(mech, q=None, qdot=None, qddot=None, names=None, method="closed",
             tol=None) -> Result:
    """Every name of ``names`` (default: the report's) in its display unit; a design
    question answered first (``design``: the file built with its unknowns' solution),
    expression quantities worked out from the answers they read (``quantities.expressions``)."""
    refuse_driving(mech, q, qdot, qddot, method)
    if design.unsolved(mech):       # each trial by the method asked
        mech = design.resolved(mech, evaluate, method, tol)
    names, solve, exprs, solved, limits = route(mech, names)
    if not (exprs or solved or limits) and mech.elements is None and mech.design is None \
            and mech.clutch is None:
        # the names themselves, by the driver's path (quantities.evaluate's, its plan kept)
        return quantities.plan_for(mech, solve, method, tol).evaluate(mech, q, qdot, qddot)
    result = _evaluate(mech, q, qdot, qddot, solve, method, tol, limits)
    for name in solved:         # a solved parameter: the value the file was built with
        value, result.units[name] = design.answer(mech, name)
        shape = np.shape(getattr(result.kinematics, "q", None)) if q is not None else ()
        result.values[name] = np.full(shape, value) if shape else value
    if exprs or solved:
        expressions.complete(mech, result, names, exprs)
    if mech.design is not None:     # the figure is drawn for the parameters' start values
        result.cautions = [c for c in result.cautions if c.kind != "figure"]
    return result


_ROUTES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def route(mech, names) -> tuple:
    """(names, the names to solve, the expressions, the solved design parameters, whether a
    limit of the motion or an answer of a machine's whole motion is asked) of ``names``
    (default: the report's) on ``mech``, worked out at the first call and kept with the
    mechanism, like its plans."""
    key = None if names is None else tuple(names)
    routes = _ROUTES.get(mech)
    if routes is None:
        routes = _ROUTES[mech] = {}
    route = routes.get(key)
    if route is None:
        names = list(names) if names is not None else quantities.report_names(mech)
        solve, exprs = expressions.expand(mech, names)
        solved = [n for n in solve if _kind(mech, n) == "design"]
        solve = [n for n in solve if n not in solved]
        # a limit of the motion, or an answer of a machine's whole motion: not the plan's path
        limits = mech.elements is None and (_asks_limits(mech, solve) or
                                            _machine_run(mech, solve) is not None)
        route = routes[key] = (names, solve, exprs, solved, limits)
    return route


def _kind(mech, name):
    quantity = mech.quantities.get(name)
    return quantity.kind if quantity is not None else None


def _evaluate(mech, q, qdot, qddot, names, method, tol, limits) -> Result:
    """``names`` (none an expression) by the path they need (``limits``: one is a limit of
    the motion, or an answer of a machine's whole motion)."""
    if mech.clutch is not None:     # shafts and a clutch: their transient
        from linkcli.runs import clutch_sheet
        return clutch_sheet.evaluate(mech, list(names), Result(mech))
    if mech.elements is None:       # a file with a driver: no vibration modules to import
        run = _machine_run(mech, names)
        if run is not None:             # the motion in time, the periodic regime
            return _with_run(mech, q, qdot, qddot, names, method, tol, limits, *run)
        if limits:                      # maxima, strokes ...: runs.limits
            from linkcli.runs.limits import report as limit_report
            return limit_report.evaluate(mech, q, qdot, qddot, names=names, method=method, tol=tol)
        return quantities.evaluate(mech, q, qdot, qddot, names=names, method=method, tol=tol)
    from linkcli.answers.quantities import vibration
    return vibration.evaluate(mech, list(names), Result(mech))


def _machine_run(mech, names):
    """(the kinds, the run that answers them) of the first run of a machine's whole motion
    that ``names`` ask: runs.machine_motion (the motion in time), runs.machine_regime (the
    periodic regime and the flywheel); None when they ask neither."""
    kinds = {_kind(mech, n) for n in names}
    if not kinds & set(MACHINE):
        return None
    from linkcli.runs import machine_motion, machine_regime
    if "motion" in kinds:
        return ("motion",), machine_motion.motion_values
    if kinds & set(REGIME_KINDS):
        return REGIME_KINDS, machine_regime.regime_values
    return None


def _with_run(mech, q, qdot, qddot, names, method, tol, limits, kinds, run) -> Result:
    """The answers of a run of the whole motion (``run(mech, names)``: one value each of the
    ``kinds`` it answers, repeated at every driver value of ``q``) with the others by their
    own path."""
    others = [n for n in names if _kind(mech, n) not in kinds]
    result = _evaluate(mech, q, qdot, qddot, others, method, tol, _asks_limits(mech, others))
    found = run(mech, [n for n in names if n not in others])
    shape = np.shape(getattr(result.kinematics, "q", None)) if q is not None else ()
    values = {}
    for name in names:
        if name in found:
            value, result.units[name] = found[name]
            values[name] = np.full(shape, value) if shape else value
        else:
            values[name] = result.values[name]
    result.values = values
    return result


def refuse_driving(mech, q=None, qdot=None, qddot=None, method="closed") -> None:
    """A vibration problem (``elements``) is solved at its static equilibrium, by the closed
    form: driver values, rates or another method are refused by name (before a design
    question's trials are solved, and by the commands that draw or sweep one)."""
    if mech.clutch is not None and (q is not None or qdot is not None or qddot is not None
                                    or method != "closed"):
        raise InputError("a clutch problem is solved in time from its shafts' speeds: it takes "
                         "no driver values, rates or method", file=mech.file,
                         key="--method" if method != "closed" else None,
                         hint="drop q, qdot, qddot and --method")
    if mech.elements is None:
        return
    if q is not None or qdot is not None or qddot is not None or method != "closed":
        raise InputError("a vibration problem is solved at its static equilibrium: it takes no "
                         "driver values, rates or method", file=mech.file,
                         key="--method" if method != "closed" else None,
                         hint="drop q, qdot, qddot and --method")


def _asks_limits(mech, names) -> bool:
    """Whether ``names`` (default: the report's) hold a limit of the motion."""
    names = quantities.report_names(mech) if names is None else names
    return any(getattr(mech.quantities.get(n), "limit", False) for n in names)
