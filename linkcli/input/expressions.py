"""A small, safe evaluator for parameter expressions and expression quantities.

Grammar: numbers, names (params, ``k``, ``pi``, ``deg``, quantities), ``+ - * / **``,
unary minus, parentheses and calls of a fixed set of functions.  The text is
parsed with :mod:`ast` and walked node by node; nothing reaches ``eval``,
attribute access, subscripts or imports.  Length, nesting depth and exponent
size are bounded so that no expression can hang or exhaust memory.

Every number, written or computed, must be finite with ``|x| <= 1e300``; a
final value must also be 0 or ``|x| >= 1e-300`` (unit conversion must not
round it to zero).  The text may hold only ASCII letters, digits, ``_ . , +
- * / ( )`` and blanks (:data:`ALLOWED`), the same rule the JSON Schema states.

The same walk evaluates three kinds of values, bound to the names:

- numbers (``evaluate``: the file's parameters);
- NumPy arrays (an expression quantity over a sweep: element by element);
- :class:`Rates`, a value with its first and second time derivatives, which the
  walk carries through every operation by the chain rule (the rates of an
  expression quantity: d/dt f(a, b) = f_a a' + f_b b', and the second rate likewise).

:class:`Expression` parses a text once (for a quantity evaluated many times) and
also gives its dimension from those of its names (:meth:`Expression.dimension`).
"""
from __future__ import annotations

import ast
import functools
import math
import re

import numpy as np

from linkcli.errors import ExpressionError
from linkcli.model import exact as _exact

MAX_LENGTH = 400
MAX_DEPTH = 40
MAX_EXPONENT = 1000.0
MAX_MAGNITUDE = 1e300
MIN_MAGNITUDE = 1e-300
ALLOWED = re.compile(r"[A-Za-z0-9_.,+\-*/() \t\r\n]*")

CONSTANTS = {"pi": math.pi, "deg": math.pi / 180.0}


def _sqrt_rates(x):
    r = np.sqrt(x)
    return 0.5 / r, -0.25 / (r * x)


def _tan_rates(x):
    t = np.tan(x)
    return 1 + t * t, 2 * t * (1 + t * t)


def _asin_rates(x):
    c = 1 - x * x
    return 1 / np.sqrt(c), x / c ** 1.5


def _atan_rates(x):
    c = 1 + x * x
    return 1 / c, -2 * x / (c * c)


def _abs_rates(x):
    return np.sign(x), 0 * x


#: name -> (function, arity, domain test of the arguments (True where allowed) or None,
#: (g', g'') of a function of one argument, for the rates)
FUNCTIONS = {
    "sqrt": (np.sqrt, 1, lambda x: x >= 0, _sqrt_rates),
    "sin": (np.sin, 1, None, lambda x: (np.cos(x), -np.sin(x))),
    "cos": (np.cos, 1, None, lambda x: (-np.sin(x), -np.cos(x))),
    "tan": (np.tan, 1, None, _tan_rates),
    "asin": (np.arcsin, 1, lambda x: np.abs(x) <= 1, _asin_rates),
    "acos": (np.arccos, 1, lambda x: np.abs(x) <= 1,
             lambda x: tuple(-d for d in _asin_rates(x))),
    "atan": (np.arctan, 1, None, _atan_rates),
    "atan2": (np.arctan2, 2, None, None),
    "abs": (np.abs, 1, None, _abs_rates),
    "hypot": (np.hypot, 2, None, None),
}
#: the same functions on Python floats (the parameters of a file: faster than NumPy's)
SCALAR = {"sqrt": math.sqrt, "sin": math.sin, "cos": math.cos, "tan": math.tan,
          "asin": math.asin, "acos": math.acos, "atan": math.atan, "atan2": math.atan2,
          "abs": abs, "hypot": math.hypot}

_NODE_WORDS = {"Attribute": "attribute access", "Subscript": "a subscript",
               "Tuple": "a tuple (',' outside a function call)", "Lambda": "a lambda",
               "Call": "a call", "Compare": "a comparison", "BoolOp": "and/or",
               "IfExp": "if/else", "UnaryOp": "this unary operator", "Starred": "'*' unpacking"}


class Rates:
    """A value and its first ``len(terms) - 1`` time derivatives (floats or arrays):
    ``terms[0]`` = f, ``terms[1]`` = f', ``terms[2]`` = f''.  Arithmetic follows the
    rules of differentiation, so an expression walked over Rates gives its own rates."""

    __slots__ = ("terms",)

    def __init__(self, terms):
        self.terms = tuple(terms)

    @property
    def order(self) -> int:
        return len(self.terms) - 1

    @property
    def value(self):
        return self.terms[0]

    @staticmethod
    def lift(x, order: int) -> "Rates":
        """``x`` as Rates of ``order`` (a constant: its rates are 0)."""
        if isinstance(x, Rates):
            return x
        return Rates((x,) + (0 * x,) * order)

    def chain(self, g, rates) -> "Rates":
        """g(self) with g' and g'' from ``rates`` (a function of the value)."""
        a = self.terms
        out = [g]
        if len(a) > 1:
            d1, d2 = rates(a[0])
            out.append(d1 * a[1])
            if len(a) > 2:
                out.append(d2 * a[1] * a[1] + d1 * a[2])
        return Rates(out)


def _pair(a, b):
    """Both operands as Rates of the larger order (a number becomes a constant)."""
    order = max(x.order for x in (a, b) if isinstance(x, Rates))
    return Rates.lift(a, order).terms, Rates.lift(b, order).terms


def _add(a, b, sign=1.0):
    if not isinstance(a, Rates) and not isinstance(b, Rates):
        return a + b if sign > 0 else a - b
    x, y = _pair(a, b)
    return Rates([p + sign * q for p, q in zip(x, y)])


def _mul(a, b):
    if not isinstance(a, Rates) and not isinstance(b, Rates):
        return a * b
    x, y = _pair(a, b)
    out = [x[0] * y[0]]
    if len(x) > 1:
        out.append(x[1] * y[0] + x[0] * y[1])
    if len(x) > 2:
        out.append(x[2] * y[0] + 2 * x[1] * y[1] + x[0] * y[2])
    return Rates(out)


def _div(a, b):
    if not isinstance(a, Rates) and not isinstance(b, Rates):
        return a / b
    x, y = _pair(a, b)
    q0 = x[0] / y[0]
    out = [q0]
    if len(x) > 1:
        q1 = (x[1] - q0 * y[1]) / y[0]
        out.append(q1)
    if len(x) > 2:
        out.append((x[2] - 2 * q1 * y[1] - q0 * y[2]) / y[0])
    return Rates(out)


def _pow(a, b):
    """a ** b; with rates, for a constant exponent or a positive base."""
    if not isinstance(a, Rates) and not isinstance(b, Rates):
        return np.power(a, b)
    if not isinstance(b, Rates) or not any(np.any(t != 0) for t in b.terms[1:]):
        p = b.value if isinstance(b, Rates) else b
        base = a.value
        return a.chain(np.power(base, p), lambda x: (p * np.power(x, p - 1),
                                                     p * (p - 1) * np.power(x, p - 2)))
    x, y = _pair(a, b)          # a ** b = exp(b ln a), a > 0
    ln_a = Rates(x).chain(np.log(x[0]), lambda v: (1 / v, -1 / (v * v)))
    exponent = _mul(Rates(y), ln_a)
    return exponent.chain(np.exp(exponent.value), lambda v: (np.exp(v), np.exp(v)))


def _atan2(y, x):
    if not isinstance(y, Rates) and not isinstance(x, Rates):
        return np.arctan2(y, x)
    p, q = _pair(y, x)           # p = y, q = x
    out = [np.arctan2(p[0], q[0])]
    r2 = q[0] * q[0] + p[0] * p[0]
    if len(p) > 1:
        num = q[0] * p[1] - p[0] * q[1]
        out.append(num / r2)
    if len(p) > 2:
        num1 = q[0] * p[2] - p[0] * q[2]
        r21 = 2 * (q[0] * q[1] + p[0] * p[1])
        out.append((num1 * r2 - num * r21) / (r2 * r2))
    return Rates(out)


def _hypot(x, y):
    if not isinstance(x, Rates) and not isinstance(y, Rates):
        return np.hypot(x, y)
    square = _add(_mul(x, x), _mul(y, y))
    return square.chain(np.hypot(Rates.lift(x, 0).value, Rates.lift(y, 0).value),
                        _sqrt_rates)


def _value(x):
    return x.value if isinstance(x, Rates) else x


def _short(text: str, limit: int = 60) -> str:
    return text if len(text) <= limit else text[:limit - 3] + "..."


def _first(mask, *values) -> str:
    """The first values where ``mask`` holds, as text ('-1', or '-1, 2' for two)."""
    index = np.unravel_index(int(np.argmax(mask)), np.shape(mask)) if np.ndim(mask) else ()
    return ", ".join(f"{float(np.asarray(v)[index] if np.ndim(v) else v):g}" for v in values)


def _finite(number, what: str) -> float:
    """``number`` as a float with ``|x| <= MAX_MAGNITUDE``, else ExpressionError."""
    try:
        value = float(number)
    except OverflowError:       # an integer beyond the float range
        value = math.inf
    if not math.isfinite(value) or abs(value) > MAX_MAGNITUDE:
        raise ExpressionError(f"{what} is not a finite number within +-{MAX_MAGNITUDE:g}")
    return value


def _in_range(value, what: str):
    """``value`` unless one of its numbers is 0 < |x| < MIN_MAGNITUDE (ExpressionError)."""
    if type(value) is float:        # a plain number: the same rule without NumPy's overhead
        if value != 0 and abs(value) < MIN_MAGNITUDE:
            raise ExpressionError(f"{what} is too small (0 < |x| < {MIN_MAGNITUDE:g})",
                                  hint="write 0, or use a larger unit")
        return value
    small = (value != 0) & (np.abs(value) < MIN_MAGNITUDE)
    if np.any(small):
        raise ExpressionError(f"{what} is too small (0 < |x| < {MIN_MAGNITUDE:g})",
                              hint="write 0, or use a larger unit")
    return value


@functools.lru_cache(maxsize=4096)
def _parse(text):
    """(source, tree) of ``text``; the length and the grammar are checked here.  Kept per
    text (a file built again for each value of a parameter parses the same texts): the tree
    is only read by the walks, never changed, and a text that fails is not kept."""
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
    return source, tree


def _characters(text, source):
    if not ALLOWED.fullmatch(text):   # e.g. a '# comment', or letters Python would normalise
        bad = next(c for c in text if not ALLOWED.fullmatch(c))
        raise ExpressionError(f"character {bad!r} is not allowed in expression "
                              f"'{_short(source)}'",
                              hint="use ASCII letters, digits, + - * / ** and parentheses")


def evaluate(text, names: dict | None = None, exact: bool = False) -> float:
    """Value of ``text`` (a number or an expression string) with ``names`` bound.

    ``exact``: the names may be ``model.exact`` numbers and the result is one where an
    operand is (pi and deg are exact too)."""
    if isinstance(text, bool):
        raise ExpressionError(f"expected a number, got {text!r}")
    if isinstance(text, (int, float)):
        return _in_range(_finite(text, _short(repr(text))), _short(repr(text)))
    if not isinstance(text, str):
        raise ExpressionError(f"expected a number or an expression, got {type(text).__name__}")
    source, tree = _parse(text)
    scope = _exact.constants() if exact else dict(CONSTANTS)
    scope.update(names or {})
    value = _Walker(scope, source, exact).value(tree.body, 0)
    _characters(text, source)
    return _float(_in_range(value, f"'{_short(source)}'"))


def _float(value) -> float:
    """``value`` as a float, keeping an exact number's formula."""
    return value if isinstance(value, _exact.Exact) else float(value)


class Expression:
    """An expression parsed once: its free ``names`` (those not constants), its value for
    names bound to numbers, arrays or :class:`Rates` (:meth:`value`), and its dimension
    from theirs (:meth:`dimension`)."""

    def __init__(self, text):
        if isinstance(text, bool) or not isinstance(text, (str, int, float)):
            raise ExpressionError(f"expected an expression, got {text!r}")
        text = str(text)
        self.source, self.tree = _parse(text)
        _characters(text, self.source)
        calls = {id(node.func) for node in ast.walk(self.tree) if isinstance(node, ast.Call)}
        self.names = tuple(dict.fromkeys(
            node.id for node in ast.walk(self.tree) if isinstance(node, ast.Name)
            and id(node) not in calls and node.id not in CONSTANTS))

    def __repr__(self):
        return f"Expression({self.source!r})"

    def value(self, names: dict):
        """The value with ``names`` bound (numbers, arrays or Rates); ExpressionError where
        it is not defined (a division by zero, a square root of a negative number ...)."""
        scope = dict(CONSTANTS)
        scope.update(names)
        return _Walker(scope, self.source).value(self.tree.body, 0)

    def dimension(self, dims: dict):
        """The dimension of the value from those of the names (``dims``: name ->
        model.units.Dimension); ExpressionError naming the terms whose dimensions do not
        add up (a sum of a length and a time, the sine of a length)."""
        return _Dimensions(dims, self.source).of(self.tree.body, 0)


class _Visit:
    """A walk over an expression's tree: its errors name the expression."""

    def __init__(self, source: str):
        self.source = source

    def fail(self, what: str) -> ExpressionError:
        return ExpressionError(f"{what} in expression '{_short(self.source)}'")

    def refuse(self, node) -> ExpressionError:
        kind = type(node).__name__
        what = f"{_NODE_WORDS[kind]} ({kind})" if kind in _NODE_WORDS else f"'{kind}'"
        return self.fail(f"{what} is not allowed")


class _Walker(_Visit):
    def __init__(self, scope: dict, source: str, exact: bool = False):
        super().__init__(source)
        self.scope = scope
        self.exact = exact          # literals as exact numbers (0.5 is 1/2)

    def value(self, node, depth: int):
        if depth > MAX_DEPTH:
            raise self.fail("nesting too deep")
        result = self._node(node, depth + 1)
        if isinstance(result, float):       # the parameters' case, kept fast
            if not math.isfinite(result) or abs(result) > MAX_MAGNITUDE:
                raise self.fail("result is not a finite number")
            return result
        terms = result.terms if isinstance(result, Rates) else (result,)
        for term in terms:
            if not np.all(np.isfinite(term)) or np.any(np.abs(term) > MAX_MAGNITUDE):
                which = "result" if term is terms[0] else "its rate"
                raise self.fail(f"{which} is not a finite number")
        return result

    def _node(self, node, depth: int):
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
            return value if isinstance(value, (Rates, np.ndarray, _exact.Exact)) \
                else float(value)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            operand = self.value(node.operand, depth)
            if isinstance(node.op, ast.UAdd):
                return operand
            return -operand if isinstance(operand, float) else _mul(-1.0, operand)
        if isinstance(node, ast.BinOp):
            return self._binary(node, depth)
        if isinstance(node, ast.Call):
            return self._call(node, depth)
        raise self.refuse(node)

    def _binary(self, node: ast.BinOp, depth: int):
        left = self.value(node.left, depth)
        right = self.value(node.right, depth)
        if isinstance(left, float) and isinstance(right, float):
            return self._scalar(node.op, left, right)
        a, b = _value(left), _value(right)
        if isinstance(node.op, ast.Pow):
            if np.any(np.abs(b) > MAX_EXPONENT):
                raise self.fail(f"exponent {_first(np.abs(b) > MAX_EXPONENT, b)} is too large")
            if np.any((a == 0) & (b < 0)):
                raise self.fail("zero to a negative power")
            if np.any((a < 0) & (b != np.round(b))):
                raise self.fail("power of a negative number to a fractional exponent")
            if isinstance(right, Rates) and any(np.any(t != 0) for t in right.terms[1:]) \
                    and np.any(a <= 0):
                raise self.fail("a power whose exponent changes has no rate where the base "
                                "is not positive")
            try:
                with np.errstate(over="raise"):
                    return _pow(left, right)
            except FloatingPointError:
                raise self.fail("power overflows") from None
        if isinstance(node.op, ast.Div):
            if np.any(b == 0):
                raise self.fail("division by zero")
            return _div(left, right)
        if isinstance(node.op, (ast.Add, ast.Sub)):
            return _add(left, right, 1.0 if isinstance(node.op, ast.Add) else -1.0)
        if isinstance(node.op, ast.Mult):
            return _mul(left, right)
        raise self.fail(_operator(node.op))

    def _scalar(self, op, left: float, right: float) -> float:
        """A binary operation on two numbers."""
        if isinstance(op, ast.Pow):
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
        operation = _BINARY.get(type(op))
        if operation is None:
            raise self.fail(_operator(op))
        try:
            return _float(operation(left, right))
        except ZeroDivisionError:
            raise self.fail("division by zero") from None
        except OverflowError:
            raise self.fail("result is not a finite number") from None

    def _call(self, node: ast.Call, depth: int):
        name, (func, arity, domain, rates) = _function(node, self.fail)
        args = [self.value(arg, depth) for arg in node.args]
        if all(isinstance(a, float) for a in args):
            try:
                return _exact.call(name, SCALAR[name], args)
            except (ValueError, OverflowError):
                shown = ", ".join(f"{a:g}" for a in args)
                raise self.fail(f"{name}({shown}) is out of its domain") from None
        values = [_value(a) for a in args]
        if domain is not None and not np.all(domain(*values)):
            bad = _first(~np.asarray(domain(*values)), *values)
            raise self.fail(f"{name}({bad}) is out of its domain")
        if not any(isinstance(a, Rates) for a in args):
            return func(*values)
        if name == "atan2":
            return _atan2(*args)
        if name == "hypot":
            return _hypot(*args)
        if name == "abs" and np.any(values[0] == 0) and args[0].order:
            raise self.fail("abs() has no rate where its argument is 0")
        return args[0].chain(func(values[0]), rates)


_BINARY = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
}


def _operator(op) -> str:
    word = {"FloorDiv": "//", "Mod": "%"}.get(type(op).__name__, type(op).__name__)
    return f"operator '{word}' is not allowed"


def _function(node: ast.Call, fail):
    """(name, FUNCTIONS entry) of a call, refusing any other function and a wrong arity."""
    if not isinstance(node.func, ast.Name):
        raise fail("calling anything but a named function is not allowed")
    if node.func.id not in FUNCTIONS:
        allowed = ", ".join(sorted(FUNCTIONS))
        raise fail(f"function '{node.func.id}' is not allowed (allowed: {allowed})")
    entry = FUNCTIONS[node.func.id]
    if node.keywords or len(node.args) != entry[1]:
        raise fail(f"{node.func.id}() takes {entry[1]} argument(s)")
    return node.func.id, entry


class _Dimensions(_Visit):
    """The dimension of an expression from those of its names (model.units.Dimension):
    sums and differences of agreeing dimensions, products, quotients, powers by a number,
    square roots; the arguments of sin, cos, tan, asin, acos and atan are pure numbers
    (angles included), those of atan2 and hypot agree with each other."""

    def __init__(self, dims: dict, source: str):
        super().__init__(source)
        self.dims = dims

    def of(self, node, depth: int):
        from linkcli.model.units import Dimension, NONE
        if depth > MAX_DEPTH:
            raise self.fail("nesting too deep")
        if isinstance(node, ast.Constant):
            return NONE
        if isinstance(node, ast.Name):
            if node.id in CONSTANTS:
                return NONE
            if node.id not in self.dims:
                raise self.fail(f"unknown name '{node.id}'")
            return self.dims[node.id]
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            return self.of(node.operand, depth + 1)
        if isinstance(node, ast.BinOp):
            left, right = self.of(node.left, depth + 1), self.of(node.right, depth + 1)
            if isinstance(node.op, (ast.Add, ast.Sub)):
                self.same(left, right, node, "adds" if isinstance(node.op, ast.Add)
                          else "subtracts")
                return left if left == right else Dimension(*left[:3])
            if isinstance(node.op, ast.Mult):
                return left * right
            if isinstance(node.op, ast.Div):
                return left / right
            if isinstance(node.op, ast.Pow):
                if not right.none:
                    raise self.fail(f"the exponent '{_segment(self.source, node.right)}' is "
                                    f"not a pure number ({right.text()})")
                if left.none:
                    return left
                power = _constant(node.right)
                if power is None:
                    raise self.fail(f"'{_segment(self.source, node.right)}' raises a quantity "
                                    f"of dimension {left.text()} to a power that is not a "
                                    "number written in the expression")
                try:
                    return left ** power
                except Exception:       # noqa: BLE001 - not a whole number of halves
                    raise self.fail(f"{left.text()} to the power {power:g} is not a "
                                    "dimension") from None
            raise self.fail(f"operator '{type(node.op).__name__}' is not allowed")
        if isinstance(node, ast.Call):
            name, _ = _function(node, self.fail)
            args = [self.of(arg, depth + 1) for arg in node.args]
            if name == "sqrt":
                return args[0] ** 0.5
            if name == "abs":
                return args[0]
            if name in ("atan2", "hypot"):
                self.same(args[0], args[1], node, "compares")
                return Dimension(angle=1) if name == "atan2" else args[0]
            if not args[0].none:
                raise self.fail(f"{name}() takes a pure number or an angle, and "
                                f"'{_segment(self.source, node.args[0])}' is of dimension "
                                f"{args[0].text()}")
            return Dimension(angle=1) if name in ("asin", "acos", "atan") else NONE
        raise self.refuse(node)

    def same(self, left, right, node, verb):
        if not left.agrees(right):
            a, b = (_segment(self.source, n) for n in
                    ((node.left, node.right) if isinstance(node, ast.BinOp) else node.args))
            raise self.fail(f"it {verb} '{a}' ({left.text()}) and '{b}' ({right.text()}), "
                            "of different dimensions")


def _constant(node):
    """The number a node writes (a constant, or its negative), else None."""
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) \
            and not isinstance(node.value, bool):
        return float(node.value)
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        inner = _constant(node.operand)
        return None if inner is None else (-inner if isinstance(node.op, ast.USub) else inner)
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Div, ast.Mult)):
        a, b = _constant(node.left), _constant(node.right)
        if a is not None and b is not None and (b != 0 or isinstance(node.op, ast.Mult)):
            return a / b if isinstance(node.op, ast.Div) else a * b
    return None


def _segment(source: str, node) -> str:
    return _short(ast.get_source_segment(source, node) or "?", 40)


def scaled_name(text) -> str | None:
    """The one name an expression is a multiple of (``L``, ``-L``, ``2*kk``, ``ks/2``), or
    None: a parameter written so takes the unit of the value it gives."""
    if not isinstance(text, str) or len(text) > MAX_LENGTH:
        return None
    try:
        node = ast.parse(text.strip(), mode="eval").body
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return None
    while True:
        if isinstance(node, ast.Name):
            return None if node.id in CONSTANTS else node.id
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            node = node.operand
        elif isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult) \
                and _constant(node.left) is not None:
            node = node.right
        elif isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Mult, ast.Div)) \
                and _constant(node.right) is not None:
            node = node.left
        else:
            return None
