"""Numbers that remember their formula: the model read with its parameters as symbols.

``Exact`` (a float) and ``ExactComplex`` (a complex) are the values every solver
uses, and carry beside them ``expr``, the sympy expression of the same value in the
file's parameters.  Arithmetic on them (``+ - * / **``, ``abs``, ``conjugate``,
``.real``, ``.imag``) computes both, so that the one parser and the one topology
that build the numeric model also build its formulas: a length ``R - r`` becomes the
number 0.4 and the expression R - r, a link's local point ``complex(length, 0)``
keeps it, a topology ratio of two local vectors is the ratio of their expressions.

An absolute value or an angle is taken on the side the value is: |R - r| is R - r
where R > r in the file, the angle of a vector (0, -L) is -pi/2; the formulas are
those of the figure's configuration, valid near the file's numbers.

A plain number meeting an exact one becomes exact when it is what it looks like: an
integer, or a float whose shortest decimal form has at most ``DIGITS`` significant
digits (0.5 -> 1/2, 0.001 -> 1/1000, 9.81 -> 981/100); any other float (the
rounded result of a computation, 0.8660254037844386) stays a sympy Float, which
marks every formula it enters as numeric (``is_exact``).

Only a file read with ``--symbolic`` holds these numbers, and sympy is imported the
first time one is made: the numeric path never imports it.  The helpers ``plane``,
``cis``, ``phase``, ``sqrt``, ``hypot`` and ``times_pi`` are what the parser calls in
place of ``complex(x, y)``, ``cmath.exp(1j a)``, ``cmath.phase``, ``math.sqrt``,
``math.hypot`` and ``math.pi * x``: on plain numbers they return exactly what those
return.

Its twin is every plain float and complex of the numeric model: ``Exact`` is one, with the
formula beside it.
"""
from __future__ import annotations

import cmath
import math

#: a float with at most this many significant digits in its shortest form is read as
#: the decimal it shows
DIGITS = 15


def _sympy():
    import sympy
    return sympy


def constant(x):
    """The sympy number of a plain ``x``: exact where ``x`` is what it shows (see module)."""
    sp = _sympy()
    if isinstance(x, (Exact, ExactComplex)):
        return x.expr
    if isinstance(x, bool):
        raise TypeError("a bool is not a number")
    if isinstance(x, complex):
        return constant(x.real) + sp.I * constant(x.imag)
    if isinstance(x, int):
        return sp.Integer(x)
    x = float(x)
    if not math.isfinite(x):
        return sp.Float(x)
    if x == int(x) and abs(x) < 1e15:
        return sp.Integer(int(x))
    text = repr(x)
    mantissa = text.split("e")[0].replace("-", "").replace(".", "").lstrip("0")
    if len(mantissa) <= DIGITS:
        return sp.Rational(text)
    return sp.Float(x)


def expression(x):
    """The sympy expression of ``x``, exact or plain."""
    return x.expr if isinstance(x, (Exact, ExactComplex)) else constant(x)


def is_traced(*values) -> bool:
    return any(isinstance(v, (Exact, ExactComplex)) for v in values)


def is_exact(expr) -> bool:
    """Whether a sympy expression holds no Float (no rounded number)."""
    sp = _sympy()
    return not expr.has(sp.Float)


def make(value, expr):
    """An Exact or ExactComplex of ``value`` (plain) and ``expr``."""
    if isinstance(value, complex):
        return ExactComplex(value, expr)
    return Exact(value, expr)


def _plain(x):
    if isinstance(x, Exact):
        return float(x)
    if isinstance(x, ExactComplex):
        return complex(x)
    return x


def _operate(plain, symbolic):
    """The binary operator of both numbers: ``plain`` on values, ``symbolic`` on
    expressions; NotImplemented for anything but numbers."""
    def apply(a, b, other):
        if not isinstance(other, (int, float, complex)) or isinstance(other, bool):
            return NotImplemented
        value = plain(_plain(a), _plain(b))
        if not isinstance(value, (int, float, complex)):
            return value
        return make(value, symbolic(expression(a), expression(b)))

    def forward(self, other):
        return apply(self, other, other)

    def backward(self, other):
        return apply(other, self, other)
    return forward, backward


def _add(a, b):
    return a + b


def _sub(a, b):
    return a - b


def _mul(a, b):
    return a * b


def _div(a, b):
    return a / b


def _pow(a, b):
    return a ** b


class _Traced:
    """The arithmetic shared by Exact and ExactComplex; ``base`` is float or complex."""

    base = float

    def __new__(cls, value, expr):
        self = cls.base.__new__(cls, value)
        self.expr = expr
        return self

    def __repr__(self):
        return f"{type(self).__name__}({self.base(self)!r}, {self.expr})"

    __add__, __radd__ = _operate(_add, _add)
    __sub__, __rsub__ = _operate(_sub, _sub)
    __mul__, __rmul__ = _operate(_mul, _mul)
    __truediv__, __rtruediv__ = _operate(_div, _div)
    __pow__, __rpow__ = _operate(_pow, _pow)

    def __neg__(self):
        return make(-_plain(self), -self.expr)

    def __pos__(self):
        return self

    def __reduce__(self):
        return (make, (_plain(self), self.expr))


class Exact(_Traced, float):
    """A float with the sympy expression of its value."""

    base = float
    __hash__ = float.__hash__
    __eq__ = float.__eq__

    def conjugate(self):
        return self

    @property
    def real(self):
        return self

    @property
    def imag(self):
        return Exact(0.0, _sympy().Integer(0))

    def __abs__(self):
        return Exact(abs(_plain(self)), signed(self.expr, _plain(self)))


class ExactComplex(_Traced, complex):
    """A complex number with the sympy expression of its value (real symbols)."""

    base = complex
    __hash__ = complex.__hash__
    __eq__ = complex.__eq__

    def conjugate(self):
        return ExactComplex(complex(self).conjugate(), _sympy().conjugate(self.expr))

    @property
    def real(self):
        return Exact(complex(self).real, parts(self.expr)[0])

    @property
    def imag(self):
        return Exact(complex(self).imag, parts(self.expr)[1])

    def __abs__(self):
        x, y = parts(self.expr)
        value = complex(self)
        if y == 0:
            return Exact(abs(value), signed(x, value.real))
        if x == 0:
            return Exact(abs(value), signed(y, value.imag))
        return Exact(abs(value), _sympy().sqrt(x ** 2 + y ** 2))


def signed(expr, value):
    """|expr| where expr is ``value``: expr or -expr by the sign it has there (the
    figure's: a length R - r drawn positive stays R - r); Abs(expr) at 0."""
    if value > 0:
        return expr
    if value < 0:
        return -expr
    return _sympy().Abs(expr)


def parts(expr) -> tuple:
    """(real part, imaginary part) of an expression in real symbols."""
    return expr.as_real_imag()


# --- the parser's helpers: plain numbers in, the same plain numbers out ------------------
def plane(x, y) -> complex:
    """complex(x, y)."""
    if not is_traced(x, y):
        return complex(x, y)
    sp = _sympy()
    return ExactComplex(complex(_plain(x), _plain(y)), expression(x) + sp.I * expression(y))


def cis(angle) -> complex:
    """e^{i angle} (cmath.exp(1j * angle))."""
    value = cmath.exp(1j * _plain(angle))
    if not is_traced(angle):
        return value
    sp = _sympy()
    a = angle.expr
    return ExactComplex(value, sp.cos(a) + sp.I * sp.sin(a))


def phase(z) -> float:
    """arg z in (-pi, pi] (cmath.phase).  Along an axis (a part identically zero) the
    angle is the axis's, on the side the value is: a pendulum drawn hanging is at
    -pi/2 exactly, whatever its length."""
    value = cmath.phase(_plain(z))
    if not is_traced(z):
        return value
    sp = _sympy()
    x, y = parts(expression(z))
    if x == 0 and value != 0:
        return Exact(value, sp.pi / 2 if value > 0 else -sp.pi / 2)
    if y == 0:
        return Exact(value, sp.Integer(0) if abs(value) < 1 else sp.pi)
    return Exact(value, sp.atan2(y, x))


def sqrt(x) -> float:
    value = math.sqrt(_plain(x))
    return Exact(value, _sympy().sqrt(x.expr)) if is_traced(x) else value


def hypot(x, y) -> float:
    value = math.hypot(_plain(x), _plain(y))
    if not is_traced(x, y):
        return value
    return Exact(value, _sympy().sqrt(expression(x) ** 2 + expression(y) ** 2))


def times_pi(x) -> float:
    """pi x (math.pi * x)."""
    value = math.pi * _plain(x)
    return Exact(value, _sympy().pi * x.expr) if is_traced(x) else value


#: the evaluator's functions by name, for exact arguments
_FUNCTIONS = {"sqrt": "sqrt", "sin": "sin", "cos": "cos", "tan": "tan", "asin": "asin",
              "acos": "acos", "atan": "atan", "atan2": "atan2", "abs": "Abs"}


def call(name, func, args):
    """``func(*args)`` of the expression evaluator, exact when an argument is."""
    value = float(func(*(_plain(a) for a in args)))
    if not is_traced(*args):
        return value
    sp = _sympy()
    exprs = [expression(a) for a in args]
    if name == "hypot":
        return Exact(value, sp.sqrt(exprs[0] ** 2 + exprs[1] ** 2))
    return Exact(value, getattr(sp, _FUNCTIONS[name])(*exprs))


def constants() -> dict:
    """The evaluator's constants, exact."""
    sp = _sympy()
    return {"pi": Exact(math.pi, sp.pi), "deg": Exact(math.pi / 180.0, sp.pi / 180)}
