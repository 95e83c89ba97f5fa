"""A small, safe evaluator for parameter expressions.

Grammar: numbers, names (params, ``k``, ``pi``, ``deg``), ``+ - * / **``,
unary minus, parentheses and calls of a fixed set of functions.  The text is
parsed with :mod:`ast` and walked node by node; nothing reaches ``eval``,
attribute access, subscripts or imports.  Length, nesting depth and exponent
size are bounded so that no expression can hang or exhaust memory.
"""
from __future__ import annotations

import ast
import math

from .errors import ExpressionError

MAX_LENGTH = 400
MAX_DEPTH = 40
MAX_EXPONENT = 1000.0
MAX_MAGNITUDE = 1e300

CONSTANTS = {"pi": math.pi, "deg": math.pi / 180.0}

FUNCTIONS = {
    "sqrt": (math.sqrt, 1), "sin": (math.sin, 1), "cos": (math.cos, 1), "tan": (math.tan, 1),
    "asin": (math.asin, 1), "acos": (math.acos, 1), "atan": (math.atan, 1),
    "atan2": (math.atan2, 2), "abs": (abs, 1), "hypot": (math.hypot, 2),
}

_BINARY = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
}


def evaluate(text, names: dict[str, float] | None = None) -> float:
    """Value of ``text`` (a number or an expression string) with ``names`` bound."""
    if isinstance(text, bool):
        raise ExpressionError(f"expected a number, got {text!r}")
    if isinstance(text, (int, float)):
        value = float(text)
        if not math.isfinite(value):
            raise ExpressionError(f"{text!r} is not a finite number")
        return value
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
        raise ExpressionError(f"cannot parse expression '{source}'",
                              hint="use numbers, names, + - * / ** and parentheses") from None
    scope = dict(CONSTANTS)
    scope.update(names or {})
    return _Walker(scope, source).value(tree.body, 0)


class _Walker:
    def __init__(self, scope: dict[str, float], source: str):
        self.scope = scope
        self.source = source

    def fail(self, what: str) -> ExpressionError:
        return ExpressionError(f"{what} in expression '{self.source}'")

    def value(self, node, depth: int) -> float:
        if depth > MAX_DEPTH:
            raise self.fail("nesting too deep")
        result = self._node(node, depth + 1)
        if not isinstance(result, float) or not math.isfinite(result) or abs(result) > MAX_MAGNITUDE:
            raise self.fail("result is not a finite number")
        return result

    def _node(self, node, depth: int) -> float:
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise self.fail(f"constant {node.value!r} is not a number")
            return float(node.value)
        if isinstance(node, ast.Name):
            if node.id not in self.scope:
                known = ", ".join(sorted(self.scope)) or "none"
                raise self.fail(f"unknown name '{node.id}' (known: {known})")
            return float(self.scope[node.id])
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            operand = self.value(node.operand, depth)
            return -operand if isinstance(node.op, ast.USub) else operand
        if isinstance(node, ast.BinOp):
            return self._binary(node, depth)
        if isinstance(node, ast.Call):
            return self._call(node, depth)
        raise self.fail(f"'{type(node).__name__}' is not allowed")

    def _binary(self, node: ast.BinOp, depth: int) -> float:
        left = self.value(node.left, depth)
        right = self.value(node.right, depth)
        if isinstance(node.op, ast.Pow):
            if abs(right) > MAX_EXPONENT:
                raise self.fail(f"exponent {right:g} is too large")
            try:
                result = left ** right
            except (OverflowError, ZeroDivisionError):
                raise self.fail("power overflows") from None
            if isinstance(result, complex):
                raise self.fail("power of a negative number to a fractional exponent")
            return float(result)
        op = _BINARY.get(type(node.op))
        if op is None:
            raise self.fail(f"operator '{type(node.op).__name__}' is not allowed")
        try:
            return float(op(left, right))
        except ZeroDivisionError:
            raise self.fail("division by zero") from None

    def _call(self, node: ast.Call, depth: int) -> float:
        if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
            allowed = ", ".join(sorted(FUNCTIONS))
            name = node.func.id if isinstance(node.func, ast.Name) else type(node.func).__name__
            raise self.fail(f"function '{name}' is not allowed (allowed: {allowed})")
        func, arity = FUNCTIONS[node.func.id]
        if node.keywords or len(node.args) != arity:
            raise self.fail(f"{node.func.id}() takes {arity} argument(s)")
        args = [self.value(arg, depth) for arg in node.args]
        try:
            return float(func(*args))
        except (ValueError, OverflowError):
            raise self.fail(f"{node.func.id}{tuple(args)} is out of its domain") from None
