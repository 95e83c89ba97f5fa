"""A design question, ``find:`` (a mixin of the Parser; model.design, docs/schema.md "find").

The unknowns are parameters of the file, each with a search interval ``between: [a, b]``
(a < b, in the unit the file writes it in, or in ``unit:``) or a ``start`` value; the
targets are answers of the file (any quantity, its rates, expressions, limits) with the
value each must have, a number in the answer's display unit or ``NUMBER UNIT`` ("1 Hz");
as many targets as unknowns.  ``choose`` picks one of several roots of one unknown.  Each
unknown becomes an answer of its own (a quantity of kind 'design', listed in the report's
``design`` section), so that keys can be written on it.
"""
from __future__ import annotations

from linkcli.errors import ExpressionError
from linkcli.input import expressions
from linkcli.model.design import Design, Target, Unknown
from linkcli.model.mechanism import Quantity, split_rate
from linkcli.model.units import parse_unit

CHOICES = ("smallest", "largest")


class FindSection:
    """``find``: read with the quantities (:meth:`find`), its units checked once the
    mechanism is built (:meth:`find_units`)."""

    def find(self, data, quantities) -> Design | None:
        spec = data.get("find")
        if spec is None:
            return None
        path = ("find",)
        spec = self.mapping(spec, path, {"unknowns", "targets", "choose"},
                            ("unknowns", "targets"))
        params = data.get("params") if isinstance(data.get("params"), dict) else {}
        unknowns = []
        for name, value in self.mapping(spec["unknowns"], path + ("unknowns",)).items():
            unknown = self.block(self.unknown, name, value, path + ("unknowns", name), params,
                                 quantities)
            if unknown is not None:
                unknowns.append(unknown)
        targets = []
        for name, value in self.mapping(spec["targets"], path + ("targets",)).items():
            target = self.block(self.target, name, value, path + ("targets", name), quantities)
            if target is not None:
                targets.append(target)
        given = len(self.mapping(spec["unknowns"], path + ("unknowns",)))
        asked = len(self.mapping(spec["targets"], path + ("targets",)))
        if given != asked:
            raise self.error(path, f"{given} unknown{'s' if given != 1 else ''} and {asked} "
                             f"target{'s' if asked != 1 else ''}: a design question needs as "
                             "many targets (answers with their values) as unknowns",
                             hint="add a target, or make an unknown a parameter again")
        choose = self.choose(spec, path, unknowns) if "choose" in spec else None
        overridden = set(self.overrides)
        fixed = bool(unknowns) and all(u.name in overridden for u in unknowns)
        for u in unknowns:
            quantities[u.name] = Quantity(u.name, "design", u.name, line=u.line)
        return Design(tuple(unknowns), tuple(targets), choose, fixed)

    def unknown(self, name, value, path, params, quantities) -> Unknown:
        if name not in params:
            known = ", ".join(sorted(map(str, params))[:10]) or "none"
            raise self.error(path, f"'{name}' is not a parameter of this file, so it cannot be "
                             f"an unknown (params: {known})",
                             hint="an unknown is one of 'params', with its value there as "
                             "the file's figure")
        if name in quantities:
            raise self.error(path, f"'{name}' is also a quantity of the file",
                             hint="rename the quantity: a solved parameter is an answer of "
                             "its own name")
        spec = self.mapping(value, path, {"between", "start", "unit"})
        if ("between" in spec) == ("start" in spec):
            raise self.error(path, "give either between: [a, b] (a search interval) or "
                             "start: v (a start value)")
        unit = spec.get("unit")
        if unit is not None and (not isinstance(unit, str) or parse_unit(unit) is None):
            raise self.error(path + ("unit",), f"unknown unit {unit!r}")
        line = self.doc.line(path)
        if "start" in spec:
            return Unknown(name, start=self.number(spec["start"], path + ("start",)),
                           unit=unit, line=line)
        ends = spec["between"]
        if not isinstance(ends, list) or len(ends) != 2:
            raise self.error(path + ("between",), f"an interval is [a, b], got {ends!r}")
        lo, hi = (self.number(e, path + ("between", i)) for i, e in enumerate(ends))
        if not lo < hi:
            raise self.error(path + ("between",), f"the interval goes up: b ({hi:g}) must be "
                             f"larger than a ({lo:g})", hint="write between: [smaller, larger]")
        return Unknown(name, lo, hi, unit=unit, line=line)

    def target(self, name, value, path, quantities) -> Target:
        base, order = split_rate(name, quantities)
        if base not in quantities or order > quantities[base].rates:
            raise self.error(path, f"the target '{name}' is not an answer of this file",
                             hint="a target is a quantity (or its rate) of 'quantities'")
        text = str(self.doc.raw.get(path, value))
        number, unit = self.number_and_unit(value, path)
        return Target(name, number, unit, text, self.doc.line(path))

    def number_and_unit(self, value, path):
        """A target's value (or a root's to choose): a number or expression, perhaps
        followed by a unit ('1 Hz')."""
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return self.number(value, path), None
        if not isinstance(value, str):
            raise self.error(path, f"a value is a number, or a number and a unit ('1 Hz'), "
                             f"got {value!r}")
        words = value.split()
        for cut in range(len(words), 0, -1):
            head, tail = " ".join(words[:cut]), " ".join(words[cut:])
            if tail and parse_unit(tail) is None:
                continue
            try:
                number = expressions.evaluate(head, self.names)
            except ExpressionError:
                continue
            return number, (tail or None)
        raise self.error(path, f"cannot read the value {value!r}",
                         hint="write a number, or a number and a unit: 1 Hz, 450 mm, 0.5 s")

    def choose(self, spec, path, unknowns):
        """``choose``: smallest, largest or {nearest: V} (one unknown with an interval): V
        in the unit of the interval, or a number and a unit ('900 mm'), converted with the
        interval by :meth:`find_units`."""
        value = spec["choose"]
        where = path + ("choose",)
        if len(unknowns) != 1 or not unknowns[0].interval:
            raise self.error(where, "'choose' picks one of several roots of one unknown "
                             "searched in an interval")
        if value in CHOICES:
            return (value,)
        if isinstance(value, dict):
            near = self.mapping(value, where, {"nearest"}, ("nearest",))
            return ("nearest",) + self.number_and_unit(near["nearest"], where + ("nearest",))
        raise self.error(where, f"choose is smallest, largest or {{nearest: V}}, got {value!r}")

    def find_units(self, mech) -> None:
        """Each target's unit is of its answer's dimension; an unknown given in a ``unit`` is
        converted to the unit the file writes it in, which must be of its dimension, and so
        is the value of ``choose: {nearest: V}`` (in its own unit, else in the interval's)."""
        import dataclasses
        from linkcli.input.derived import words
        from linkcli.model.dimensions import dimension
        design = mech.design
        if design is None:
            return
        unknowns = []
        for u in design.unknowns:
            scale = self.to_file_unit(mech, u.name, u.unit, ("find", "unknowns", u.name, "unit"))
            if scale is None:
                continue
            unknowns.append(dataclasses.replace(u, unit=None, **{
                f: getattr(u, f) * scale for f in ("lo", "hi", "start")
                if getattr(u, f) is not None}))
        choose = design.choose
        if choose is not None and choose[0] == "nearest":
            _, value, unit = choose
            u = design.unknowns[0]
            scale = (self.to_file_unit(mech, u.name, unit, ("find", "choose", "nearest"))
                     if unit is not None else
                     self.to_file_unit(mech, u.name, u.unit, ("find", "unknowns", u.name,
                                                             "unit"), report=False))
            choose = ("nearest", value * (scale or 1.0))
        mech.design = dataclasses.replace(design, unknowns=tuple(unknowns), choose=choose)
        for target in design.targets:
            if target.unit is None:
                continue
            try:
                dim = dimension(mech, target.name)
            except (KeyError, AttributeError, StopIteration):
                continue            # its definition failed: reported already
            given = parse_unit(target.unit, dim)[0]
            if not given.agrees(dim):
                self.error(("find", "targets", target.name), f"'{target.name}' is {words(dim)} "
                           f"and the target's unit '{target.unit}' is "
                           f"{words(given, target.unit)}")

    def to_file_unit(self, mech, name, unit, path, report=True) -> float | None:
        """The factor from ``unit`` (None: the file's own) to the unit the file writes the
        parameter ``name`` in; None where it does not fit (reported, unless ``report`` is
        False)."""
        from linkcli.input.derived import words
        from linkcli.model.dimensions import param_unit
        if unit is None:
            return 1.0
        kind, dim, factor = param_unit(mech, name)
        if dim is None:
            if report:
                self.error(path, f"the values of '{name}' are given in {unit}, but the file "
                           f"never writes '{name}' on its own as a value of one kind, so its "
                           "own unit is unknown", hint="give them without a unit, as the file "
                           "writes it")
            return None
        given, to_si = parse_unit(unit, dim)
        if not given.agrees(dim):
            if report:
                self.error(path, f"'{name}' is {words(dim)} and the unit '{unit}' is "
                           f"{words(given, unit)}")
            return None
        return to_si / factor
