"""The parser's base: located errors and the readers of names, numbers and coordinates.

Every problem is recorded with its YAML path and line and parsing goes on with
the next block, so that one run reports them all (:class:`InputErrors`).
"""
from __future__ import annotations

import re

from linkcli.input import expressions
from linkcli.model.exact import plane
from linkcli.errors import ExpressionError, InputError, ScaleError
from linkcli.model.mechanism import FRAME
from linkcli.model.units import Units
from linkcli.input.source import Document, path_text

UNKNOWN = "unknown"
NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*\Z")   # \Z: no trailing newline
WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
BODIES = ("link", "slider", "actuator", "disc")   # named bodies: never the fixed one's name
#: The range of lengths (SI, m) the solvers carry in double precision.  They square lengths
#: (distances, discriminants, Newton's |g|^2), multiply a square by a length or by the
#: rounding 2.3e-13 (the bounds of "zero up to rounding"), and multiply a speed by an
#: acceleration (the tests of a rate's zero) or two energies (the vibrations' determinants):
#: products of four lengths, which must stay normal doubles.  Every length is at most
#: LARGEST_LENGTH (its fourth power 1e300, below the overflow at 1.8e308) and the file's
#: largest at least SMALLEST_SIZE (1e-300, above the subnormals that start at 2.2e-308, where
#: a product loses its digits and a regular position reads as a toggle).  A tiny length in
#: a mechanism of ordinary size is only a small number, and is kept.
LARGEST_LENGTH = 1e75
SMALLEST_SIZE = 1e-75


def reserved_parameter(name: str) -> str | None:
    """Why ``name`` cannot be a parameter (it means something in every expression), or
    None."""
    if name == "k":
        return "'k' is the last digit of the matricola (set it with 'k:' or --k)"
    if name in expressions.CONSTANTS:
        return f"'{name}' is a constant of expressions ({name} = {expressions.CONSTANTS[name]:.6g})"
    if name in expressions.FUNCTIONS:
        return f"'{name}' is a function of expressions"
    return None


class InputErrors(InputError):
    """Several input errors found in one file."""

    def __init__(self, errors: list[InputError]):
        self.errors = errors
        first = errors[0]
        super().__init__(first.detail, file=first.file, key=first.key, line=first.line,
                         hint=first.hint)

    def __str__(self) -> str:
        lines = [InputError.__str__(e) for e in self.errors]
        if len(lines) == 1:
            return lines[0]
        return f"{len(lines)} problems:\n" + "\n".join("  " + line for line in lines)


class _Skip(Exception):
    """Raised inside the parser after an error was recorded, to skip a block."""


def _kind(value) -> str:
    return {dict: "a mapping", list: "a list", str: "text", type(None): "nothing"}.get(
        type(value), type(value).__name__)


class Reader:
    """Reads values at YAML paths, recording located errors."""

    def __init__(self, doc: Document, k: int | None, symbolic=None):
        self.doc = doc
        self.symbolic = symbolic        # an input.symbols.Symbolic: params as symbols
        self.errors: list[InputError] = []
        self.k_override = k
        self.names: dict[str, float] = {}
        self.k: int | None = None
        #: name -> the unit kinds of the values written as a multiple of it (k: 2*ks)
        self.uses: dict[str, set] = {}
        #: parameters given other values than the file's (input.document.build)
        self.overrides: dict = {}
        #: path -> (text, unit kind) of every value written as an expression: what depends
        #: on the parameters (runs.coefficients evaluates them over arrays)
        self.written: dict = {}
        #: (|value| in m, path) of the largest length read so far
        self.largest: tuple = (0.0, ())

    def error(self, path, detail: str, hint: str | None = None):
        self.errors.append(InputError(detail, file=self.doc.name, key=path_text(path) or None,
                                      line=self.doc.line(path), hint=hint))
        return _Skip()

    def get(self, mapping: dict, path, key: str, required=True, default=None):
        if key not in mapping:
            if required:
                raise self.error(path, f"missing key '{key}'")
            return default
        return mapping[key]

    def mapping(self, value, path, allowed=None, required=()) -> dict:
        if not isinstance(value, dict):
            raise self.error(path, f"expected a mapping, got {_kind(value)}")
        if allowed is not None:
            for key in value:
                if key not in allowed:
                    raise self.error(path + (key,), f"unknown key '{key}'",
                                     hint="allowed here: " + ", ".join(sorted(allowed)))
        for key in required:
            if key not in value:
                raise self.error(path, f"missing key '{key}'")
        return value

    def number(self, value, path, kind: str | None = None, units: Units | None = None) -> float:
        try:
            number = expressions.evaluate(value, self.names, self.symbolic is not None)
        except ExpressionError as exc:
            raise self.error(path, exc.detail, exc.hint) from None
        if isinstance(value, str):
            self.written[tuple(path)] = (value, kind)
            if kind is not None:
                self.note_use(value, kind)
        if self.symbolic is not None:
            return self.symbolic.convert(number, kind, units)
        if kind == "angle":
            return units.angle_to_si(number)
        if kind is not None:
            number *= units.factor(kind)
        if kind == "length" and isinstance(number, (int, float)):
            self.in_range(number, path, units)
        return number

    def in_range(self, length: float, path, units: Units):
        """Refuse a length beyond LARGEST_LENGTH (recorded: the reading goes on, so that what
        names the value is not reported undefined); keep the largest one read, which
        :meth:`large_enough` compares with SMALLEST_SIZE."""
        size = abs(length)
        if size > LARGEST_LENGTH:
            self.scale_error(path, size, LARGEST_LENGTH, "large", units)
        elif size > self.largest[0]:
            self.largest = (size, tuple(path))

    def large_enough(self, units: Units):
        """Refuse a file whose largest length is below SMALLEST_SIZE (none read: no scale)."""
        size, path = self.largest
        if 0 < size < SMALLEST_SIZE:
            self.scale_error(path, size, SMALLEST_SIZE, "small", units)

    def scale_error(self, path, size, bound, side, units: Units):
        """Record the :class:`ScaleError` of a length ``size`` (m) beyond ``bound``."""
        unit, f = units.display("length", 0)
        if side == "large":
            detail = (f"the length {size / f:.4g} {unit} is beyond the largest the solvers "
                      f"carry ({bound / f:.4g} {unit}): its square and the products of the "
                      "closed forms and Newton's method overflow a double")
        else:
            detail = (f"the mechanism's largest length is {size / f:.4g} {unit}, below the "
                      f"smallest size the solvers carry ({bound / f:.4g} {unit}): its square "
                      "and the products of the closed forms underflow a double, and regular "
                      "positions would read as toggles")
        self.errors.append(ScaleError(detail, file=self.doc.name, key=path_text(path) or None,
                                      line=self.doc.line(path), value=size, bound=bound,
                                      side=side, hint="write the mechanism in lengths between "
                                      f"{SMALLEST_SIZE:g} m and {LARGEST_LENGTH:g} m: a "
                                      "scale factor changes no angle or ratio"))

    def note_use(self, text: str, kind: str):
        """Record that ``text``, a multiple of one name (``ks``, ``2*L``), is a value of unit
        ``kind``: a parameter so written is in that unit (model.dimensions.param_unit)."""
        words = [w for w in WORD.findall(text) if w in self.names]
        if len(words) == 1:
            used = expressions.scaled_name(text)
            if used is not None:
                self.uses.setdefault(used, set()).add(kind)

    def param_kinds(self) -> dict:
        """name -> the one unit kind of the places where the parameter is written on its own
        or as a multiple (note_use); a parameter so written at places of two kinds, or never,
        has none."""
        return {name: kinds.pop() for name, kinds in self.uses.items()
                if len(kinds) == 1 and name in self.names and name != "k"}

    def name(self, value, path, pool=None, what="point") -> str:
        if not isinstance(value, str) or not NAME.match(value):
            raise self.error(path, f"expected a {what} name, got {value!r}")
        if pool is None and what in BODIES and value == FRAME:
            raise self.error(path, f"'{FRAME}' is the name of the fixed body, so it cannot "
                             f"name a {what}", hint=f"rename the {what}, e.g. '{what}1'")
        if pool is not None and value not in pool:
            names = sorted(pool)        # at most 10: the text stays linear in the file
            known = (", ".join(names[:10]) + (f" ... and {len(names) - 10} more"
                                              if len(names) > 10 else "")) or "none"
            raise self.error(path, f"undefined {what} '{value}'", hint=f"defined: {known}")
        return value

    def pair(self, value, path, pool, what="point") -> tuple[str, str]:
        if not isinstance(value, list) or len(value) != 2:
            raise self.error(path, f"expected two {what} names [first, second], got {value!r}")
        a = self.name(value[0], path + (0,), pool, what)
        b = self.name(value[1], path + (1,), pool, what)
        if a == b:
            raise self.error(path, f"the two {what}s must differ")
        return a, b

    def xy(self, value, path, units: Units) -> complex:
        if not isinstance(value, list) or len(value) != 2:
            raise self.error(path, f"expected coordinates [x, y], got {value!r}")
        x = self.number(value[0], path + (0,), "length", units)
        y = self.number(value[1], path + (1,), "length", units)
        return plane(x, y)

    def block(self, func, *args):
        """Run one parsing step; on error keep going with the next."""
        try:
            return func(*args)
        except _Skip:
            return None

    def positive(self, value, path, units, kind="length") -> float:
        number = self.number(value, path, kind, units)
        if number <= 0:
            raise self.error(path, f"must be positive, got {value!r}")
        return number
