"""Reading of the limits of the motion a report asks for, over a range of the driver.

    quantities:
      xmax: {maximum: xB}                        # also minimum, at_maximum, at_minimum
      vmax: {maximum: xBdot, from: 0, to: 180}   # of a rate; over part of the range
      s:    {stroke: xB}                         # and time_ratio: of a position quantity
      tw:   {stroke_time: xB, component: working}   # working | return

:class:`LimitsSection` (a mixin of the Parser) reads the kind, the quantity it is of and the
range; once every quantity is read, :meth:`limit_of` checks that quantity (``runs.limits``
finds the values).

Errors, each an :class:`~linkcli.errors.InputError` at the quantity's YAML path and line
(exit 2): not exactly one kind of limit; a limit in a vibration problem (it has no driver);
a component other than working or return for stroke_time, or one for another kind; 'from'
without 'to' or a range that does not go up; a limit of an undefined quantity, of one
whose limits are not defined (an acceleration), or a stroke of a velocity.
"""
from __future__ import annotations

from linkcli.model.mechanism import LIMITS, Quantity, limit_refusal, split_rate
from linkcli.input.quantities import LEVEL

#: the limits of the motion that are of a position quantity (its dead centres)
STROKES = ("stroke", "time_ratio", "stroke_time")


class LimitsSection:
    """Limits of the motion (a mixin of the Parser)."""

    def limit_quantity(self, name, value, path) -> Quantity:
        """A limit of the motion of a quantity over a range of the driver (runs.limits):
        {maximum: NAME}, minimum, at_maximum, at_minimum, stroke, time_ratio, or
        {stroke_time: NAME, component: working | return}; from: and to: give the range."""
        value = self.mapping(value, path, set(LIMITS) | {"component", "from", "to"})
        kinds = [k for k in LIMITS if k in value]
        if len(kinds) != 1:
            raise self.error(path, f"give exactly one kind of limit, not {' and '.join(kinds)}",
                             hint="see docs/schema.md, 'Limits of the motion'")
        kind = kinds[0]
        if self.vibration.get("coordinates"):
            raise self.error(path, f"{kind} needs a driver: a vibration problem has "
                             "coordinates instead")
        of = self.name(value[kind], path + (kind,), what="quantity")
        component = value.get("component")
        if kind == "stroke_time":
            if component not in ("working", "return"):
                raise self.error(path + ("component",), "component is working or return, got "
                                 f"{component!r}", hint="the working stroke is the longer one")
        elif "component" in value:
            raise self.error(path + ("component",), f"a {kind} quantity has no component")
        span = None
        if "from" in value or "to" in value:
            if not ("from" in value and "to" in value):
                raise self.error(path, "give both 'from' and 'to' (the range of the driver)")
            span = (self.number(value["from"], path + ("from",)),
                    self.number(value["to"], path + ("to",)))
            if not span[0] < span[1]:
                raise self.error(path + ("to",), f"the range goes up: 'to' ({span[1]:g}) must "
                                 f"be larger than 'from' ({span[0]:g})")
        return Quantity(name, kind, of, component=component, span=span,
                        line=self.doc.line(path))

    def limit_of(self, q, quantities) -> bool:
        """Whether the quantity a limit is of is defined and has a rate (its definition's
        own error is reported already when it failed)."""
        path = ("quantities", q.name, q.kind)
        base, order = split_rate(q.a, quantities)
        if base in self.failed:
            return False
        if base not in quantities:
            raise self.error(path, f"'{q.a}' is not a defined quantity",
                             hint="a limit is of a quantity NAME of the file or its rate "
                             "NAMEdot, e.g. xB or xBdot")
        refusal = limit_refusal(q.a, quantities[base], order)
        if refusal:
            raise self.error(path, refusal, hint="ask for a position or velocity quantity: a "
                             "coordinate, an angle, a speed, or the rate of one, e.g. xBdot")
        if q.kind in STROKES and (order or quantities[base].kind in LEVEL):
            raise self.error(path, f"a {q.kind.replace('_', ' ')} is of a position quantity "
                             f"(a coordinate, an angle, a length), and '{q.a}' is a velocity",
                             hint=f"ask for its maximum and minimum: {{maximum: {q.a}}}")
        return True
