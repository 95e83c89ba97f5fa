"""The parser's base: located errors and the readers of names, numbers and coordinates.

Every problem is recorded with its YAML path and line and parsing goes on with
the next block, so that one run reports them all (:class:`InputErrors`).
"""
from __future__ import annotations

import re

from linkcli.input import expressions
from linkcli.model.exact import plane
from linkcli.errors import ExpressionError, InputError
from linkcli.model.mechanism import FRAME
from linkcli.model.units import Units
from linkcli.input.source import Document, path_text

UNKNOWN = "unknown"
NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*\Z")   # \Z: no trailing newline
WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
BODIES = ("link", "slider", "actuator", "disc")   # named bodies: never the fixed one's name


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
        return number

    def note_use(self, text: str, kind: str):
        """Record that ``text``, a multiple of one name (``ks``, ``2*L``), is a value of unit
        ``kind``: a parameter so written is in that unit (model.dimensions.param_unit)."""
        words = [w for w in WORD.findall(text) if w in self.names]
        if len(words) == 1:
            used = expressions.scaled_name(text)
            if used is not None:
                self.uses.setdefault(used, set()).add(kind)

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
