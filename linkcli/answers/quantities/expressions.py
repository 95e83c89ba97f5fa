"""Answers computed from answers: the values of expression quantities (``expr``).

An expression is evaluated in SI: each name it reads is solved with the other answers
(in its display unit, then converted by the factor of that unit: model.units.parse_unit),
a parameter is its value in the unit the file writes it in (model.dimensions.param_unit),
and the result is shown in the expression's own unit.  The factors are the tables' and
the same for every path (display, find targets, keys): a frequency is its angular
frequency in rad/s whatever unit it is shown in (1 Hz = 2 pi rad/s, 1 rpm = 2 pi/60
rad/s), so ``w1 - f1`` is 0 for one frequency shown in rad/s and in Hz, and its period is
``2*pi/f1``.  Over a sweep every name is an
array and so is the result.  A rate of an expression (``Tdot``) is the chain rule's:
each name is bound to its value and rates (input.expressions.Rates), so
d/dt f(a, b) = f_a a' + f_b b' and likewise the second rate; a parameter's rates are 0.

:func:`expand` turns a list of names into the names to solve (those the expressions
read, at the orders of rate they need) and the expressions to work out after;
:func:`complete` works them out on a solved :class:`Result` and leaves exactly the
names asked for.
"""
from __future__ import annotations

import numpy as np

from linkcli.errors import ExpressionError, SolveError
from linkcli.input.expressions import Expression, Rates
from linkcli.model.dimensions import dimension, param_unit
from linkcli.model.mechanism import split_rate
from linkcli.model.units import parse_unit

EXPR = "expr"
SUFFIX = ("", "dot", "ddot")


def is_expression(mech, name) -> bool:
    """Whether ``name`` is an expression quantity or one of its rates."""
    q = mech.quantities.get(split_rate(name, mech.quantities)[0])
    return q is not None and q.kind == EXPR


def rate_name(name: str, order: int, names=()) -> str:
    """The name of the rate of ``order`` of the answer ``name`` (itself a rate, perhaps; of
    one of ``names``, the quantities: model.mechanism.split_rate)."""
    base, level = split_rate(name, names)
    return base + SUFFIX[level + order]


def expand(mech, names) -> tuple[list, list]:
    """(names to solve, [(expression, highest rate order asked)] in the order to work them
    out: every expression after those it reads)."""
    solve, exprs = [], {}

    def need(name, order):
        base, level = split_rate(name, mech.quantities)
        quantity = mech.quantities.get(base)
        if quantity is not None and quantity.kind == EXPR:
            order += level
            if order <= exprs.get(base, -1):
                return
            for used in Expression(quantity.a).names:
                if split_rate(used, mech.quantities)[0] in mech.quantities:
                    need(used, order)
            exprs.pop(base, None)          # after the ones it reads
            exprs[base] = order
            return
        if quantity is None and name in mech.params:
            return
        solve.extend(rate_name(name, i, mech.quantities) for i in range(order + 1))

    for name in names:
        need(name, 0)
    return list(dict.fromkeys(solve)), list(exprs.items())


def complete(mech, result, names, exprs) -> None:
    """Work out ``exprs`` (from :func:`expand`) on ``result`` (its values in display units)
    and leave in it exactly ``names``, in that order."""
    own = {}                    # expression -> its value (SI, Rates when rates are asked)
    for base, order in exprs:
        quantity = mech.quantities[base]
        expression = Expression(quantity.a)
        scope = {used: _bound(mech, result, own, used, order) for used in expression.names}
        try:
            value = expression.value(scope)
        except ExpressionError as exc:
            raise SolveError(f"'{base}' is not defined here: {exc.detail}", file=mech.file,
                             key=f"quantities.{base}", line=quantity.line,
                             hint="check the values the expression reads (solve them on "
                             "their own)") from None
        own[base] = value
        unit, factor = unit_of(quantity)
        terms = value.terms if isinstance(value, Rates) else (value,)
        for level, term in enumerate(terms):
            name = base + SUFFIX[level]
            result.values[name] = np.asarray(term, dtype=float) / factor + 0.0
            result.units[name] = rate_unit(unit, level)
    units = result.units
    result.values = {n: result.values[n] for n in names}
    result.units = {n: units[n] for n in list(names) + list(result.points) if n in units}


def unit_of(quantity) -> tuple[str, float]:
    """(unit name, SI factor) an expression is shown in: its ``unit``, or none."""
    if not quantity.unit:
        return "", 1.0
    return quantity.unit, parse_unit(quantity.unit, quantity.dimension)[1]


def rate_unit(unit: str, level: int) -> str:
    """The unit of the rate of ``level`` of a value in ``unit``: 'mm/s', '1/s^2'."""
    if not level:
        return unit
    per = "s" if level == 1 else "s^2"
    if not unit:
        return f"1/{per}"
    if "/" not in unit:
        return f"{unit}/{per}"
    up, down = unit.split("/", 1)
    return f"{up}/({down.strip('()')} {per})"


def _bound(mech, result, own, used, order):
    """The value (SI) a name read by an expression is bound to, with ``order`` rates."""
    base, level = split_rate(used, mech.quantities)
    if base in own and not level:
        value = own[base]
        return value if order == 0 or not isinstance(value, Rates) else \
            Rates(value.terms[:order + 1])
    if base in mech.quantities:
        terms = [in_si(mech, result, rate_name(used, i, mech.quantities)) for i in range(order + 1)]
        return terms[0] if order == 0 else Rates(terms)
    if used == "k":
        return float(mech.k)
    _, _, factor = param_unit(mech, used)
    return float(mech.params[used]) * (1.0 if factor is None else factor)


def in_si(mech, result, name):
    """An answer of ``result`` (display units) in SI."""
    value = np.asarray(result.values[name], dtype=float)
    unit = result.units.get(name, "")
    parsed = parse_unit(unit, dimension(mech, name))
    if parsed is None:   # pragma: no cover - every answer's unit is readable
        raise SolveError(f"the unit '{unit}' of '{name}' cannot be read", file=mech.file)
    return value * parsed[1] if value.ndim else float(value) * parsed[1]


class Derived:
    """The plan (quantities.plan.Plan) of names that hold expressions: the plan of the names
    they read, and the expressions worked out on each of its results."""

    def __init__(self, names, plan, exprs):
        self.names, self.plan, self.exprs = list(names), plan, exprs

    def order(self, mech) -> int:
        return self.plan.order(mech)

    def evaluate(self, mech, q=None, qdot=None, qddot=None):
        result = self.plan.evaluate(mech, q, qdot, qddot)
        complete(mech, result, self.names, self.exprs)
        return result

    def collect(self, mech, solver, kin):
        result = self.plan.collect(mech, solver, kin)
        complete(mech, result, self.names, self.exprs)
        return result
