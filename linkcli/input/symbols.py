"""Reading a file with its parameters as symbols (``--symbolic``).

The parser reads the file as always; with a :class:`Symbolic` reading every name of
``params`` is bound to an exact number (``model.exact``) whose formula is

- the symbol of the name (in the file's units while reading), or
- the formula of its expression, when that expression uses other parameters
  (``J: M*R**2/2`` stands for M R^2/2), or
- its exact value, when the name is one of ``numbers`` (``--numbers``).

Every number the parser converts to SI is converted exactly (mm -> 1/1000,
deg -> pi/180), and the kind it is read as is recorded.  A parameter read alone
(or in a sum, times a number) as a length, a mass, a stiffness ... has that
kind; its SI symbol is then the parameter's value in SI: ``l: 800`` under
``units: {length: mm}`` is the symbol l = 0.8 m, and the file-unit symbol is
replaced by l / (1/1000) everywhere (``si``).  A parameter read as two kinds
with different factors, or never read alone, keeps the file's value as its symbol's
(``unit`` None).

The numeric twins: ``input.document.build`` reads the same file with plain numbers, and
``model.units`` holds the decimal factors these are the exact ones of.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass, field

from linkcli.model import exact


@functools.lru_cache(maxsize=1)
def exact_factors() -> dict:
    """{(kind, unit): SI factor} of the units whose factor is not the decimal it shows:
    those holding pi and the US customary ones, exact from their definitions (ft =
    0.3048 m, in = 0.0254 m, lb = 0.45359237 kg, lbf = lb 9.80665 m/s^2); every other
    factor (0.001, 1000, 1e6) is its decimal."""
    import sympy as sp
    R, pi = sp.Rational, sp.pi
    ft, inch, lb = R("0.3048"), R("0.0254"), R("0.45359237")
    lbf = lb * R("9.80665")
    slug = lbf / ft
    psi = lbf / inch ** 2
    return {
        ("angle", "deg"): pi / 180, ("angular_rate", "deg/s"): pi / 180,
        ("angular_rate", "rpm"): pi / 30, ("angular_rate", "rev/s"): 2 * pi,
        ("frequency", "Hz"): 2 * pi, ("frequency", "rpm"): pi / 30,
        ("torsional_stiffness", "Nm/deg"): 180 / pi, ("speed", "km/h"): R(5, 18),
        ("length", "ft"): ft, ("length", "in"): inch, ("speed", "ft/s"): ft,
        ("force", "lbf"): lbf, ("force", "lb"): lbf, ("force", "kip"): 1000 * lbf,
        ("mass", "lb"): lb, ("mass", "slug"): slug,
        ("torque", "lbf ft"): lbf * ft, ("torque", "lbf in"): lbf * inch,
        ("torque", "kip ft"): 1000 * lbf * ft,
        ("inertia", "slug ft^2"): slug * ft ** 2, ("inertia", "lb ft^2"): lb * ft ** 2,
        ("inertia", "lb in^2"): lb * inch ** 2,
        ("stiffness", "lbf/in"): lbf / inch, ("stiffness", "lbf/ft"): lbf / ft,
        ("stiffness", "lb/in"): lbf / inch, ("stiffness", "lb/ft"): lbf / ft,
        ("torsional_stiffness", "lbf ft/rad"): lbf * ft,
        ("torsional_stiffness", "lbf in/rad"): lbf * inch,
        ("damping", "lbf s/in"): lbf / inch, ("damping", "lbf s/ft"): lbf / ft,
        ("torsional_damping", "lbf ft s/rad"): lbf * ft,
        ("pressure", "psi"): psi, ("pressure", "lbf/in^2"): psi, ("pressure", "ksi"): 1000 * psi,
        ("area", "in^2"): inch ** 2, ("area", "ft^2"): ft ** 2,
    }


def exact_factor(units, kind):
    """The SI value of one file unit of ``kind``, exact."""
    name = units.names[kind]
    found = exact_factors().get((kind, name))
    return found if found is not None else exact.constant(units.factor(kind))

#: the SI unit of each kind, as the symbols' table prints it
SI_UNITS = {"length": "m", "angle": "rad", "angular_rate": "rad/s", "force": "N",
            "torque": "N m", "mass": "kg", "inertia": "kg m^2", "stiffness": "N/m",
            "torsional_stiffness": "N m/rad", "damping": "N s/m",
            "torsional_damping": "N m s/rad", "frequency": "rad/s", "speed": "m/s",
            "time": "s", "pressure": "Pa", "area": "m^2"}


@dataclass
class Parameter:
    """One parameter kept as a symbol: its name, the file-unit symbol used while reading,
    its value as the file writes it, the kinds it was read as."""

    name: str
    symbol: object            # sympy Dummy, in the file's unit
    value: float
    kinds: dict = field(default_factory=dict)     # kind -> exact SI factor of the file unit


@dataclass
class Symbolic:
    """The reading's state: the names given numbers and the parameters kept as symbols."""

    numbers: frozenset = frozenset()
    parameters: dict = field(default_factory=dict)     # name -> Parameter

    def param(self, name: str, number):
        """The exact number ``name`` is bound to, from its read value ``number``."""
        import sympy as sp
        if name in self.numbers:            # its number, exact from the others' numbers
            literal = {p.symbol: exact.constant(p.value) for p in self.parameters.values()}
            return exact.Exact(float(number), exact.expression(number).xreplace(literal))
        if exact.is_traced(number) and number.expr.free_symbols:
            return number                   # an expression of other parameters
        value = float(number)
        sign = {"positive": True} if value > 0 else {"negative": True} if value < 0 else \
            {"real": True}
        symbol = sp.Dummy(name, **sign)
        self.parameters[name] = Parameter(name, symbol, value)
        return exact.Exact(value, symbol)

    def convert(self, number, kind, units):
        """``number`` (file units, exact or plain) in SI, exactly; records the kind of a
        parameter read alone or in a sum."""
        if kind is None:
            return number
        factor = exact_factor(units, kind)
        value = units.angle_to_si(float(number)) if kind == "angle" else \
            float(number) * units.factor(kind)
        expr = exact.expression(number)
        self._record(expr, kind, factor)
        return exact.Exact(value, expr * factor)

    def _record(self, expr, kind, factor):
        import sympy as sp
        symbols = {p.symbol: p for p in self.parameters.values()}
        used = [s for s in expr.free_symbols if s in symbols]
        if not used:
            return
        poly = sp.Poly(expr, *used) if expr.is_polynomial(*used) else None
        if poly is None or poly.total_degree() != 1:
            return
        for s in used:
            symbols[s].kinds.setdefault(kind, factor)

    # after reading ------------------------------------------------------------------------
    def unit(self, name) -> tuple:
        """(kind, SI unit) of parameter ``name``; (None, None) when not told."""
        factors = set(self.parameters[name].kinds.values())
        kinds = self.parameters[name].kinds
        if len(factors) != 1:
            return None, None
        kind = next(iter(kinds))
        return kind, SI_UNITS.get(kind)

    def si(self) -> dict:
        """{file-unit symbol: its SI expression} for every parameter: the SI symbol of its
        name divided by the file unit's factor (1 when the kind is not told)."""
        return {p.symbol: self.si_symbol(p.name) / self.factor(p.name)
                for p in self.parameters.values()}

    def si_symbol(self, name):
        import sympy as sp
        return sp.Symbol(name, **self.parameters[name].symbol.assumptions0)

    def factor(self, name):
        """The SI value of one unit of parameter ``name`` as the file writes it (1 when its
        kind is not told)."""
        import sympy as sp
        factors = set(self.parameters[name].kinds.values())
        return next(iter(factors)) if len(factors) == 1 else sp.Integer(1)

    def values(self) -> dict:
        """{SI symbol: its value in SI} of every parameter."""
        return {self.si_symbol(p.name): float(p.value * self.factor(p.name))
                for p in self.parameters.values()}
