"""Answers computed from answers: expression quantities (a mixin of the Parser).

    quantities:
      T: {expr: "2*pi/wd1", unit: s}          # over quantities, their rates, params and k
      r: {expr: "w_forcing/w1"}               # a pure number needs no unit

An expression reads quantities of the file (``wd1``), their rates (``phi1dot``), points'
coordinates (``xB``), loads, other expressions, the file's parameters and ``k``.  Checked
when the file is read: every name is defined, no expression reads itself through others
(a cycle), and the expression's dimension (from its names': model.dimensions) is that of
its unit.  Its rates (``Tdot``, ``Tddot``) are those every name it reads has: the chain
rule gives them (input.expressions.Rates).
"""
from __future__ import annotations

import dataclasses

from linkcli.errors import ExpressionError
from linkcli.input.expressions import Expression
from linkcli.model.dimensions import dimension, param_unit
from linkcli.model.mechanism import split_rate
from linkcli.model.units import DIMENSIONS, NONE, SHOWN_AS, parse_unit, unit_dimension

EXPR = "expr"


def words(dim, unit=None) -> str:
    """A dimension in words: 'a time (T)', 'a pure number', 'of dimension M L^2'; that of
    the kind of ``unit`` when it is a unit of the tables ('Hz': a frequency)."""
    if dim.none and not dim.angle:
        return "a pure number"
    named = unit_dimension(unit) if isinstance(unit, str) else None
    kind = (named[0] if named else None) or SHOWN_AS.get(dim) or \
        next((k for k, d in DIMENSIONS.items() if d.agrees(dim)), None)
    if kind is None:
        return f"of dimension {dim.text()}"
    kind = kind.replace("_", " ")
    return f"{'an' if kind[0] in 'aeiou' else 'a'} {kind} ({dim.text()})"


class DerivedSection:
    """``expr`` quantities: read with the others (:meth:`expression_quantity`), their names
    and cycles checked once all are read (:meth:`expression_names`), their dimensions once
    the mechanism is built (:meth:`expression_dimensions`)."""

    def expression_quantity(self, name, value, path):
        """{expr: TEXT, unit: UNIT}: the text parsed, the unit read (its dimension kept)."""
        value = self.mapping(value, path, {EXPR, "unit"})
        try:
            expression = Expression(value[EXPR])
        except ExpressionError as exc:
            raise self.error(path + (EXPR,), exc.detail, exc.hint) from None
        unit = value.get("unit")
        dim = NONE
        if unit is not None:
            parsed = parse_unit(unit) if isinstance(unit, str) else None
            if parsed is None:
                raise self.error(path + ("unit",), f"unknown unit {unit!r}",
                                 hint="a unit of the tables (mm, deg, N/mm, Hz, s ...) or a "
                                 "product of them: 'N s/m', 'mm/s^2', '1/s'")
            dim = parsed[0]
        from linkcli.model.mechanism import Quantity
        return Quantity(name, EXPR, expression.source, unit=unit, line=self.doc.line(path),
                        dimension=dim)

    def expression_names(self, quantities) -> None:
        """Every expression's names defined, no cycle; each one's rates set (those of all
        its names).  A failed expression is dropped from ``quantities``."""
        order = {}
        for name, q in list(quantities.items()):
            if q.kind == EXPR and self.block(self._visit, name, quantities, order, ()) is None:
                quantities.pop(name, None)
                self.failed.add(name)

    def _visit(self, name, quantities, order, stack) -> int:
        """The rates expression ``name`` has, its names checked first (depth first)."""
        if name in order:
            return order[name]
        q = quantities[name]
        path = ("quantities", name, EXPR)
        if name in stack:
            cycle = " -> ".join(stack[stack.index(name):] + (name,))
            raise self.error(path, f"the expression reads itself: {cycle}",
                             hint="an expression may read other expressions, never back")
        rates = 2
        for used in Expression(q.a).names:
            base, level = split_rate(used, quantities)
            if used in self.names and used not in quantities:      # a parameter, or k
                continue
            if base in getattr(self, "failed", ()):
                raise self.error(path, f"'{used}' is not defined (its definition failed)")
            if used not in quantities and (base not in quantities or not level):
                known = sorted(set(quantities) | set(self.names))
                raise self.error(path, f"'{used}' is not a quantity, a quantity's rate, a "
                                 "parameter or k of this file",
                                 hint="defined: " + ", ".join(known[:10]) +
                                 (f" ... and {len(known) - 10} more" if len(known) > 10 else ""))
            if used in quantities:
                base, level = used, 0
            other = quantities[base]
            has = self._visit(base, quantities, order, stack + (name,)) if other.kind == EXPR \
                else other.rates
            if level > has:
                raise self.error(path, f"'{used}' is not defined: '{base}' has "
                                 f"{has or 'no'} rate{'' if has == 1 else 's'}")
            rates = min(rates, has - level)
        quantities[name] = dataclasses.replace(q, derived=rates)
        order[name] = rates
        return rates

    def expression_dimensions(self, mech) -> None:
        """Each expression's dimension, from its names', is that of its unit (a pure number
        without one): else a located error naming both."""
        for name, q in list(mech.quantities.items()):
            if q.kind == EXPR:
                self.block(self._dimension_of, mech, q)

    def _dimension_of(self, mech, q):
        path = ("quantities", q.name)
        dims = {}
        for used in Expression(q.a).names:
            if split_rate(used, mech.quantities)[0] in mech.quantities:
                try:
                    dims[used] = dimension(mech, used)
                except (KeyError, AttributeError, StopIteration):
                    return          # a section it reads failed: reported already
                continue
            if used == "k":
                dims[used] = NONE
                continue
            kind, dim, _ = param_unit(mech, used)
            if dim is None:
                raise self.error(path + (EXPR,), f"parameter '{used}' has no unit: the file "
                                 "never writes it on its own as a value of one kind (a length, "
                                 "a stiffness ...), so its value in SI is unknown",
                                 hint="use it as such a value (k: ks), or write the number "
                                 "in the expression")
            dims[used] = dim
        try:
            found = Expression(q.a).dimension(dims)
        except ExpressionError as exc:
            raise self.error(path + (EXPR,), exc.detail, exc.hint) from None
        if not found.agrees(q.dimension):
            from linkcli.model.units import show
            suggested = show(mech.units, found)[0]
            if q.unit is None:
                raise self.error(path + (EXPR,), f"the expression is {words(found)}, and "
                                 "without a unit it must be a pure number",
                                 hint=f"give its unit, e.g. unit: {suggested!r}" if suggested
                                 else None)
            raise self.error(path + ("unit",), f"the expression is {words(found)} and its "
                             f"unit '{q.unit}' is {words(q.dimension, q.unit)}",
                             hint=f"give a unit of its dimension, e.g. {suggested!r}"
                             if suggested else "a pure number has no unit: remove 'unit'")
