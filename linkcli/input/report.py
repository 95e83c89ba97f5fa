"""Reading of ``report:``: which named values the answer sheet prints, section by section.

    report:
      decimals: 2                 # 0-12, default 1
      position: [phi2, xB]        # quantities
      velocity: [phi2dot, vB]     # rates NAMEdot, and quantities that are speeds
      acceleration: [xBddot, aB]  # rates NAMEddot, and accelerations
      statics: [M, RAx]           # loads and joint forces
      vibration: [w1, X1]         # the answers of a vibration problem
      points: [B, C]              # the coordinates of points

:class:`ReportSection` (a mixin of the Parser) reads each name against the quantities read
before it: the section a name belongs to follows from its kind and its rate (``LEVEL``,
``EITHER``, ``FORCES`` of ``quantities``); an expression is listed where its reader wants.

Errors, each an :class:`~linkcli.errors.InputError` at the name's YAML path and line,
collected (exit 2): decimals not a whole number 0-12; a section that is not a list; a name
that is not defined, or a rate the quantity has not (an acceleration has none); a name in a
section that is not its own (the hint names its section); an unknown of 'find:'; a joint
force in a vibration problem, which has no unknown load to solve it with.  A name whose
quantity failed is skipped: its own error is reported already.
"""
from __future__ import annotations

from linkcli.model.mechanism import MACHINE, VIBRATION, split_rate
from linkcli.input.derived import EXPR
from linkcli.input.quantities import EITHER, FORCES, LEVEL, RATES, SUFFIX, kind_text

SECTIONS = ("position", "velocity", "acceleration", "statics", "vibration", "points", "motion")


#: the sections whose names are the quantities of one analysis, and what they are
#: (a clutch problem's answers are listed with the motion: docs/machines.md)
OWN_SECTIONS = {"motion": MACHINE + ("clutch",), "vibration": VIBRATION}
OWN_WORDS = {"motion": ("machine dynamics", "reduced inertias and torques and the answers of "
                        "the motion in time"),
             "vibration": ("the vibration analysis", "natural frequencies, modes, matrices, "
                           "equilibrium, amplitudes")}


def split_base(name: str, order: int) -> str:
    return name[:len(name) - len(SUFFIX[order])]


def _bases(name: str) -> list[str]:
    """Every name of which ``name`` may be a rate (or which it is)."""
    return [split_base(name, order) for order in RATES
            if name.endswith(SUFFIX[order]) and len(name) > len(SUFFIX[order])]


class ReportSection:
    """``report`` (a mixin of the Parser)."""

    def report(self, data, quantities, loads, pool) -> dict:
        spec = self.mapping(self.get(data, (), "report"), ("report",), set(SECTIONS) | {"decimals"})
        report = {}
        decimals = spec.get("decimals", 1)
        if isinstance(decimals, bool) or not isinstance(decimals, int) or not 0 <= decimals <= 12:
            self.error(("report", "decimals"), f"decimals is a whole number 0-12, got {decimals!r}")
        else:
            report["decimals"] = decimals
        for section in SECTIONS:
            names = spec.get(section) or []
            path = ("report", section)
            if not isinstance(names, list):
                self.error(path, "expected a list of names")
                continue
            report[section] = []
            for i, name in enumerate(names):
                if self.block(self.report_name, section, name, path + (i,), quantities,
                              loads, pool):
                    report[section].append(name)
        return report

    def report_name(self, section, name, path, quantities, loads, pool) -> bool:
        if not isinstance(name, str):
            raise self.error(path, f"expected a name, got {name!r}")
        if section == "points":
            self.name(name, path, pool)
            return True
        if any(base in getattr(self, "failed", ()) for base in _bases(name)):
            return False            # its definition's error is reported already
        order = {"position": 0, "velocity": 1, "acceleration": 2, "statics": 0,
                 "vibration": 0, "motion": 0}[section]
        base = split_rate(name, quantities)
        if base[0] in quantities and quantities[base[0]].kind == "design":
            raise self.error(path, f"'{name}' is an unknown of 'find': it is listed in the "
                             "report's Design section by itself", hint="remove it from here")
        if base[0] in quantities and quantities[base[0]].kind == EXPR:
            self.rate_of(name, quantities[base[0]], base[1], path)
            return True             # an expression: in the section its reader expects
        for own, kinds in OWN_SECTIONS.items():
            belongs = name in quantities and quantities[name].kind in kinds
            if section == own or belongs:
                if not belongs or section != own:
                    what, lists = OWN_WORDS[own]
                    raise self.error(path, f"'{name}' is {'' if belongs else 'not '}a quantity "
                                     f"of {what}", hint=f"the '{own}' section lists {lists}")
                return True
        if section == "statics":
            if name in quantities and quantities[name].kind in FORCES:
                self.balanced(name, quantities[name], path)
                return True
            if name not in quantities or quantities[name].kind != "load":
                raise self.error(path, f"'{name}' is not a load", hint="statics lists loads")
            return True
        quantity = quantities.get(base[0]) if base is not None else None
        if quantity is not None and quantity.limit and base[1] == 0:
            return True             # one value for the range: any kinematic section
        if quantity is None or quantity.kind == "load" or (
                base[1] != order and quantity.kind not in LEVEL and quantity.kind not in EITHER
                and quantity.kind not in FORCES):
            suffix = ["", "dot", "ddot"][order]
            raise self.error(path, f"'{name}' is not a defined quantity{' rate' if order else ''}",
                             hint=f"define it under 'quantities' and name it <quantity>{suffix}")
        self.rate_of(name, quantity, base[1], path)
        kinematic = ("position", "velocity", "acceleration")
        if quantity.kind in FORCES:
            raise self.error(path, f"'{name}' is not a defined quantity of the {section} section",
                             hint="a joint force is listed under 'statics'")
        allowed = {LEVEL.get(quantity.kind, 0) + base[1]}
        if quantity.kind in EITHER:
            allowed.add(1)
        if order not in allowed:
            raise self.error(path, f"'{name}' is not a defined quantity of the {section} section",
                             hint=f"{kind_text(quantity.kind)}"
                             f"{' rate' if base[1] else ''} is listed under " +
                             " or ".join(f"'{kinematic[o]}'" for o in sorted(allowed)))
        return True

    def balanced(self, name, quantity, path) -> None:
        """Refuse a joint force in a vibration problem (a file that declares coordinates):
        statics finds it with the unknown load that balances the others, and such a file
        has none; the advice names what it has (its springs' forces at the equilibrium)."""
        if "coordinates" not in self.doc.data or quantity.kind == "load":
            return
        springs = sorted(self.vibration["springs"])
        hint = "remove it from 'statics'"
        if springs:
            hint += f"; the forces at the equilibrium it solves are its springs' " \
                f"(spring_force: {springs[0]}, under 'vibration')"
        raise self.error(path, f"'{name}' is {kind_text(quantity.kind)}, which statics "
                         "finds with the unknown load that balances the others, and a "
                         "vibration problem (coordinates, no driver) has no unknown load, so "
                         "its joint forces are not solved", hint=hint)

    def rate_of(self, name, quantity, order, path):
        """Refuse a rate the quantity has not (a speed has one, an acceleration none)."""
        if order <= quantity.rates:
            return
        has = {0: "no rates", 1: f"one rate ({quantity.name}dot)"}[quantity.rates]
        if quantity.kind == EXPR:
            raise self.error(path, f"'{name}' is not defined: the expression {quantity.name} "
                             f"has {has}, the rates that every name it reads has",
                             hint=f"ask for '{quantity.name}' itself, or read names that have "
                             "the rate (a load and a limit have none)")
        raise self.error(path, f"'{name}' is not a defined quantity rate: "
                         f"{kind_text(quantity.kind)} has {has}",
                         hint={"speed": "the rate of a speed is the tangential acceleration; "
                               "ask for tangential_acceleration and normal_acceleration"}.get(
                                   quantity.kind, f"ask for '{quantity.name}' itself"))
