"""A small, safe evaluator for parameter expressions.

Grammar: numbers, names (params, ``k``, ``pi``, ``deg``), ``+ - * / **``,
unary minus, parentheses and calls of a fixed set of functions.  The text is
parsed with :mod:`ast` and walked node by node; nothing reaches ``eval``,
attribute access, subscripts or imports.  Length, nesting depth and exponent
size are bounded so that no expression can hang or exhaust memory.

Every number, written or computed, must be finite with ``|x| <= 1e300``; a
final value must also be 0 or ``|x| >= 1e-300`` (unit conversion must not
round it to zero).  The text may hold only ASCII letters, digits, ``_ . , +
- * / ( )`` and blanks (:data:`ALLOWED`), the same rule the JSON Schema states.
"""
from __future__ import annotations

import ast
import math
import re

from linkcli.errors import ExpressionError
from linkcli.model import exact as _exact

MAX_LENGTH = 400
MAX_DEPTH = 40
MAX_EXPONENT = 1000.0
MAX_MAGNITUDE = 1e300
MIN_MAGNITUDE = 1e-300
ALLOWED = re.compile(r"[A-Za-z0-9_.,+\-*/() \t\r\n]*")

CONSTANTS = {"pi": math.pi, "deg": math.pi / 180.0}

FUNCTIONS = {
    "sqrt": (math.sqrt, 1), "sin": (math.sin, 1), "cos": (math.cos, 1), "tan": (math.tan, 1),
    "asin": (math.asin, 1), "acos": (math.acos, 1), "atan": (math.atan, 1),
    "atan2": (math.atan2, 2), "abs": (abs, 1), "hypot": (math.hypot, 2),
}

_NODE_WORDS = {"Attribute": "attribute access", "Subscript": "a subscript",
               "Tuple": "a tuple (',' outside a function call)", "Lambda": "a lambda",
               "Call": "a call", "Compare": "a comparison", "BoolOp": "and/or",
               "IfExp": "if/else", "UnaryOp": "this unary operator", "Starred": "'*' unpacking"}

_BINARY = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
}


def evaluate(text, names: dict[str, float] | None = None, exact: bool = False) -> float:
    """Value of ``text`` (a number or an expression string) with ``names`` bound.

    ``exact``: the names may be ``model.exact`` numbers and the result is one where an
    operand is (pi and deg are exact too)."""
    if isinstance(text, bool):
        raise ExpressionError(f"expected a number, got {text!r}")
    if isinstance(text, (int, float)):
        return _in_range(_finite(text, _short(repr(text))), _short(repr(text)))
    if not isinstance(text, str):
        raise ExpressionError(f"expected a number or an expression, got {type(text).__name__}")
    if len(text) > MAX_LENGTH:
        raise ExpressionError(f"expression longer than {MAX_LENGTH} characters")
    source = text.strip()
    if not source:
        raise ExpressionError("empty expression")
    try:
        tree = ast.parse(source, mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        raise ExpressionError(f"cannot parse expression '{_short(source)}'",
                              hint="use numbers, names, + - * / ** and parentheses") from None
    scope = _exact.constants() if exact else dict(CONSTANTS)
    scope.update(names or {})
    value = _Walker(scope, source, exact).value(tree.body, 0)
    if not ALLOWED.fullmatch(text):   # e.g. a '# comment', or letters Python would normalise
        bad = next(c for c in text if not ALLOWED.fullmatch(c))
        raise ExpressionError(f"character {bad!r} is not allowed in expression "
                              f"'{_short(source)}'",
                              hint="use ASCII letters, digits, + - * / ** and parentheses")
    return _in_range(value, f"'{_short(source)}'")


def _short(text: str, limit: int = 60) -> str:
    return text if len(text) <= limit else text[:limit - 3] + "..."


def _finite(number, what: str) -> float:
    """``number`` as a float with ``|x| <= MAX_MAGNITUDE``, else ExpressionError."""
    try:
        value = float(number)
    except OverflowError:       # an integer beyond the float range
        value = math.inf
    if not math.isfinite(value) or abs(value) > MAX_MAGNITUDE:
        raise ExpressionError(f"{what} is not a finite number within +-{MAX_MAGNITUDE:g}")
    return value


def _in_range(value: float, what: str) -> float:
    if value != 0 and abs(value) < MIN_MAGNITUDE:
        raise ExpressionError(f"{what} is too small (0 < |x| < {MIN_MAGNITUDE:g})",
                              hint="write 0, or use a larger unit")
    return value


def _float(value) -> float:
    """``value`` as a float, keeping an exact number's formula."""
    return value if isinstance(value, _exact.Exact) else float(value)


class _Walker:
    def __init__(self, scope: dict[str, float], source: str, exact: bool = False):
        self.scope = scope
        self.source = source
        self.exact = exact          # literals as exact numbers (0.5 is 1/2)

    def fail(self, what: str) -> ExpressionError:
        return ExpressionError(f"{what} in expression '{_short(self.source)}'")

    def value(self, node, depth: int) -> float:
        if depth > MAX_DEPTH:
            raise self.fail("nesting too deep")
        result = self._node(node, depth + 1)
        if not isinstance(result, float) or not math.isfinite(result) \
                or abs(result) > MAX_MAGNITUDE:
            raise self.fail("result is not a finite number")
        return result

    def _node(self, node, depth: int) -> float:
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise self.fail(f"constant {node.value!r} is not a number")
            value = _finite(node.value, f"a number in expression '{_short(self.source)}'")
            return _exact.Exact(value, _exact.constant(node.value)) if self.exact else value
        if isinstance(node, ast.Name):
            if node.id not in self.scope:
                names = sorted(self.scope)      # at most 10: the text stays linear in the file
                known = (", ".join(names[:10]) + (f" ... and {len(names) - 10} more"
                                                  if len(names) > 10 else "")) or "none"
                raise self.fail(f"unknown name '{node.id}' (known: {known})")
            value = self.scope[node.id]
            return value if isinstance(value, _exact.Exact) else float(value)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            operand = self.value(node.operand, depth)
            return -operand if isinstance(node.op, ast.USub) else operand
        if isinstance(node, ast.BinOp):
            return self._binary(node, depth)
        if isinstance(node, ast.Call):
            return self._call(node, depth)
        kind = type(node).__name__
        what = f"{_NODE_WORDS[kind]} ({kind})" if kind in _NODE_WORDS else f"'{kind}'"
        raise self.fail(f"{what} is not allowed")

    def _binary(self, node: ast.BinOp, depth: int) -> float:
        left = self.value(node.left, depth)
        right = self.value(node.right, depth)
        if isinstance(node.op, ast.Pow):
            if abs(right) > MAX_EXPONENT:
                raise self.fail(f"exponent {right:g} is too large")
            try:
                result = left ** right
            except OverflowError:
                raise self.fail("power overflows") from None
            except ZeroDivisionError:
                raise self.fail("zero to a negative power") from None
            if isinstance(result, complex):
                raise self.fail("power of a negative number to a fractional exponent")
            return _float(result)
        op = _BINARY.get(type(node.op))
        if op is None:
            word = {"FloorDiv": "//", "Mod": "%"}.get(type(node.op).__name__,
                                                      type(node.op).__name__)
            raise self.fail(f"operator '{word}' is not allowed")
        try:
            return _float(op(left, right))
        except ZeroDivisionError:
            raise self.fail("division by zero") from None
        except OverflowError:
            raise self.fail("result is not a finite number") from None

    def _call(self, node: ast.Call, depth: int) -> float:
        if not isinstance(node.func, ast.Name):
            raise self.fail("calling anything but a named function is not allowed")
        if node.func.id not in FUNCTIONS:
            allowed = ", ".join(sorted(FUNCTIONS))
            raise self.fail(f"function '{node.func.id}' is not allowed (allowed: {allowed})")
        func, arity = FUNCTIONS[node.func.id]
        if node.keywords or len(node.args) != arity:
            raise self.fail(f"{node.func.id}() takes {arity} argument(s)")
        args = [self.value(arg, depth) for arg in node.args]
        try:
            return _exact.call(node.func.id, func, args)
        except (ValueError, OverflowError):
            shown = ", ".join(f"{a:g}" for a in args)
            raise self.fail(f"{node.func.id}({shown}) is out of its domain") from None
