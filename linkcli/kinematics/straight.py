"""A mechanism's solve written out once as straight-line Python: the per-call fast path.

A NumPy solve along the groups (``closed_form``) walks dictionaries of points, picks each
group's formula and each rate system's terms at every call: on one position that structure
costs a hundred microseconds, on a few hundred it costs more than the arithmetic.  Here the
:class:`compiled.Program` of a solver (its groups as numbers: kinds, point indices,
lengths, guides' frames, branches) and the probes asked (angles, lengths, coordinates and
their rates, each over its display factor) are turned once into the source of one Python
function with no loop, no dictionary and no branch on the mechanism: the same formulas as
``compiled._run`` (the compiled loop), with every constant folded in (a fixed point's rate
is 0, a guide along +x needs no rotation, a multiplication by 1 disappears).  Two versions
are written from the same plan: one on numbers (``math``; a single position costs a few
microseconds) and one on NumPy arrays (vectorised over the positions).

Checks are those of the compiled loop, made conservative: the function returns None,
and the caller solves by the general path (which refuses with its own words, or answers
where the case was only close), wherever a position is not clearly regular:

- a dyad's discriminant within twice the rounding bound of its toggle test (on arrays, the
  least discriminant against the bound of the largest magnitudes), coincident centres;
- a rate system whose conditioning |det| / (|G_1| |G_2|) is under twice ``SINGULAR``;
- a probe's vector of zero length (its angle's rates), a value that is not finite
  (the scalar version also on any arithmetic exception: a domain error, a division by 0).

So the fast path answers only where the general path answers, with the same numbers up to
rounding (tests/test_straight.py: 1e-12 over every shipped file), and refuses nowhere on
its own.

Why compiling generated source is safe (the project's rule is no ``eval`` of user text):
the source is built here from the program's numbers only.  Identifiers are generated
(``x3``, ``t17``), never a name from the file; every constant is written with ``repr`` of
a finite Python float (a non-finite one leaves the mechanism to the general path), and no
string of the file reaches the source.  ``compile`` and ``exec`` run that text in a
namespace holding only ``math``'s and NumPy's functions; the source is kept on the
function (``__source__``) to be read.
"""
from __future__ import annotations

import math
import re

import numpy as np

from linkcli.kinematics.compiled import ANGLE, CIRCLE_LINE, CRANK, LENGTH, LINE_DRIVER, \
    PLACE, RRR, TWO_PI, WRAP, X, Y, program_of
from linkcli.kinematics.dyads import ROUNDING, TOGGLE
from linkcli.kinematics.refusals import SINGULAR

#: the checks are this many times wider than the general path's: a position it answers
#: differently from the general one (a rounding away from a bound) is left to it
MARGIN = 2.0
#: arrays of at most this many positions are solved position by position (``Straight.short``)
SHORT = 16
#: probe kinds by the names a caller in another layer gives them
KINDS = {"angle": ANGLE, "x": X, "y": Y, "length": LENGTH}


class Straight:
    """The straight-line solve of one solver and one list of probes, to rates of ``order``.

    ``scalar(q, qd, qdd)``: a tuple of the probes' values at one position (numbers, SI
    driver values), None where a check fails; ``array(q, qd, qdd)``: a (probes x positions)
    table for a 1-D array ``q`` (``qd``, ``qdd`` numbers or arrays like it), None likewise.
    Each is written at its first call.
    """

    __slots__ = ("scalar", "array", "order", "size", "_plan")

    def __init__(self, program, rows, order):
        self.order, self.size, self._plan = order, len(rows), (program, rows)
        self.scalar = self._first_scalar
        self.array = self._first_array

    def short(self, q, w, al):
        """The table of :meth:`array` for a short 1-D array (at most :data:`SHORT` values),
        position by position by the scalar version: a NumPy operation costs about a
        microsecond whatever its length, more than the arithmetic of a few positions."""
        ws = w.tolist() if np.ndim(w) else [w] * q.size
        als = al.tolist() if np.ndim(al) else [al] * q.size
        scalar = self.scalar
        try:
            rows = [scalar(x, y, z) for x, y, z in zip(q.tolist(), ws, als)]
        except (ArithmeticError, ValueError):
            return None
        if None in rows:
            return None
        return np.array(rows).T.copy()

    def function(self, array: bool):
        """The function of the array (or the scalar) version, written now if not yet; its
        source is its ``__source__``, its constants its ``__constants__``."""
        if array:
            if self.array == self._first_array:
                self.array = self._written(True)
            return self.array
        if self.scalar == self._first_scalar:
            self.scalar = self._written(False)
        return self.scalar

    def _first_scalar(self, q, w, al):
        self.scalar = self._written(False)
        return self.scalar(q, w, al)

    def _first_array(self, q, w, al):
        self.array = self._written(True)
        return self.array(q, w, al)

    def _written(self, array):
        """The function of the version asked; one that answers None where the program
        cannot be written (a check that fails whatever the position)."""
        try:
            return _build(*self._plan, self.order, array)
        except _Unwritable:
            return _none


def _none(q, w, al):
    return None


def straight_of(solver, probes, order) -> Straight | None:
    """The :class:`Straight` of ``solver`` for ``probes`` = [(kind, a, b, order, factor,
    signed)] (``compiled.Program.probes``' rows, point names), None where its groups are not
    all of the compiled loop's kinds."""
    program = program_of(solver)
    if program is None:
        return None
    index = program.index
    if any(a not in index or (b is not None and b not in index) for _, a, b, *_ in probes):
        return None
    rows = [(kind, index[a], None if b is None else index[b], rate, factor, signed)
            for kind, a, b, rate, factor, signed in probes]
    return Straight(program, rows, order)


def evaluator(solver, probes, order=None):
    """:func:`straight_of` for probes named by kind: [(kind, a, b, order)] with kind one of
    'x', 'y', 'angle', 'length' (SI, angles in [0, 2 pi)); ``order`` default the highest
    probe order."""
    rows = [(KINDS[kind], a, b, rate, 1.0, False) for kind, a, b, rate in probes]
    top = max((rate for *_, rate in probes), default=0) if order is None else order
    return straight_of(solver, rows, top)


class _Unwritable(Exception):
    """A program this module does not write (a non-finite constant, a degenerate guide)."""


# --- the writer -------------------------------------------------------------------------
class _Writer:
    """Straight-line source built expression by expression.  A value is a Python float (a
    constant, folded at once) or the name of a variable; an operation met twice is written
    once (the same operands give the same variable)."""

    def __init__(self, array: bool):
        self.array = array
        self.lines: list = []
        self.memo: dict = {}
        self.count = 0
        self.constants: list = []       # the value of each c<i> of the source
        self.named: dict = {}           # repr of a constant -> its name
        self.bounds: dict = {}          # variable -> a bound of its magnitude, where known
        self.radii: dict = {}           # (x, y) -> r > 0 with x^2 + y^2 = r^2 up to rounding

    def emit(self, line: str):
        self.lines.append("    " + line)

    def let(self, expr: str) -> str:
        got = self.memo.get(expr)
        if got is None:
            got = self.memo[expr] = f"t{self.count}"
            self.count += 1
            self.emit(f"{got} = {expr}")
        return got

    def text(self, x) -> str:
        """A variable's name, or a constant as a name c<i> of its own (its value passed
        when the function is made: the source depends on the mechanism's structure only,
        and mechanisms of one structure share it)."""
        if isinstance(x, str):
            return x
        if not math.isfinite(x):
            raise _Unwritable(x)
        key = repr(float(x))
        name = self.named.get(key)
        if name is None:
            name = self.named[key] = f"c{len(self.constants)}"
            self.constants.append(float(x))
        return name

    def fresh(self, expr: str) -> str:
        """A variable of its own (changed in place after), never shared."""
        name = f"t{self.count}"
        self.count += 1
        self.emit(f"{name} = {expr}")
        return name

    def offset(self, p, a, d) -> None:
        """Record that ``p - a`` is ``d`` (computed as ``p = a + d``): the difference is not
        computed again, and is exact."""
        if isinstance(p, str) and isinstance(d, str):
            self.memo[f"{p} - {self.text(a)}"] = d

    def bound(self, x):
        """A bound of |x| known when the source is written (None: not known)."""
        return abs(x) if isinstance(x, float) else self.bounds.get(x)

    def bounded(self, x, *terms) -> None:
        """Record |x| <= the sum of ``terms`` (bounds; None where one is not known)."""
        if isinstance(x, str) and None not in terms:
            self.bounds[x] = float(sum(terms))

    def radius(self, x, y, r) -> None:
        """Record that (x, y) is a vector of the fixed length ``r`` (a link; not one of
        driven length, a string ``q``)."""
        if isinstance(r, float) and r != 0 and isinstance(x, str) and isinstance(y, str):
            self.radii[(x, y)] = abs(r)

    def add(self, a, b):
        if isinstance(a, float) and isinstance(b, float):
            return a + b
        if a == 0.0 and isinstance(a, float):
            return b
        if b == 0.0 and isinstance(b, float):
            return a
        return self.let(f"{self.text(a)} + {self.text(b)}")

    def sub(self, a, b):
        if isinstance(a, float) and isinstance(b, float):
            return a - b
        if b == 0.0 and isinstance(b, float):
            return a
        if a == 0.0 and isinstance(a, float):
            return self.neg(b)
        return self.let(f"{self.text(a)} - {self.text(b)}")

    def mul(self, a, b):
        if isinstance(a, float) and isinstance(b, float):
            return a * b
        for x, y in ((a, b), (b, a)):
            if isinstance(x, float):
                if x == 0.0:
                    return 0.0
                if x == 1.0:
                    return y
                if x == -1.0:
                    return self.neg(y)
        return self.let(f"{self.text(a)} * {self.text(b)}")

    def div(self, a, b):
        if isinstance(a, float) and isinstance(b, float):
            return a / b
        if isinstance(b, float) and b == 1.0:
            return a
        if isinstance(a, float) and a == 0.0:
            return 0.0
        return self.let(f"{self.text(a)} / {self.text(b)}")

    def neg(self, a):
        return -a if isinstance(a, float) else self.let(f"-{a}")

    def call(self, name: str, *args):
        """A function of the namespace (sqrt, cos, sin, atan2, hypot, abs) of ``args``."""
        if all(isinstance(a, float) for a in args):
            return float(_SCALAR[name](*args))
        return self.let(f"{name}({', '.join(self.text(a) for a in args)})")

    # checks: the function returns None where one fails -----------------------------------
    def low(self, x):
        """The least of ``x`` (itself on numbers)."""
        return x if not self.array or isinstance(x, float) else self.let(f"{x}.min()")

    def top(self, x):
        """The largest magnitude of ``x`` (on arrays, a bound known beforehand if any)."""
        if isinstance(x, float):
            return abs(x)
        if self.array and x in self.bounds:
            return self.bounds[x]
        return self.let(f"abs({x}).max()" if self.array else f"abs({x})")

    def require(self, lhs, rhs):
        """Go on only where ``lhs > rhs`` (``lhs``, ``rhs`` numbers: :meth:`low`, :meth:`top`)."""
        if isinstance(lhs, float) and isinstance(rhs, float):
            if not lhs > rhs:
                raise _Unwritable((lhs, rhs))
            return
        self.emit(f"if not {self.text(lhs)} > {self.text(rhs)}: return None")


_SCALAR = {"sqrt": math.sqrt, "cos": math.cos, "sin": math.sin, "atan2": math.atan2,
           "hypot": math.hypot, "abs": abs, "max": max}
_ARRAY = {"sqrt": np.sqrt, "cos": np.cos, "sin": np.sin, "atan2": np.arctan2,
          "hypot": np.hypot, "abs": np.abs, "max": max}


def _build(program, probes, order, array):
    """The function (q, w, al) -> values of ``program`` and ``probes`` (see the module)."""
    out = _Writer(array)
    m = len(program.index)
    pos = [[float(program.x0[i]), float(program.y0[i])] for i in range(m)]
    vel = [[0.0, 0.0] for _ in range(m)]
    acc = [[0.0, 0.0] for _ in range(m)]
    state = (pos, vel, acc)
    for op, par in zip(program.ops.tolist(), program.par.tolist()):
        _GROUPS[op[0]](out, op, par, state, order)
    values = [_probe(out, probe, state) for probe in probes]
    if array:
        out.emit(f"table = empty(({len(values)},) + q.shape)")
        for k, v in enumerate(values):      # -0.0 is 0.0, as the general path writes
            out.emit(f"add({out.text(v)}, 0.0, out=table[{k}])")
        out.emit("if not isfinite(table.sum()): return None")
        out.emit("return table")
    else:
        texts = [out.text(v) for v in values]
        out.emit(f"values = ({''.join(t + ' + 0.0, ' for t in texts)})")
        out.emit(f"if not isfinite({' + '.join(texts) or '0.0'}): return None")
        out.emit("return values")
    lines = _live(out.lines)
    lines = _freed(lines) if array else lines
    names = ", ".join(f"c{i}" for i in range(len(out.constants)))
    source = f"def make({names}):\n    def solve(q, w, al):\n" + \
        "\n".join("    " + line for line in lines) + "\n    return solve\n"
    make = _MADE.get((source, array))
    if make is None:
        namespace = dict(_ARRAY if array else _SCALAR)
        namespace.update(isfinite=math.isfinite, empty=np.empty, TWO_PI=TWO_PI, WRAP=WRAP,
                         pi=math.pi, copyto=np.copyto, add=np.add, subtract=np.subtract)
        exec(compile(source, "<linkcli straight-line solve>", "exec"), namespace)  # noqa: S102
        make = namespace["make"]
        make.__source__ = source
        if len(_MADE) >= KEPT:
            _MADE.pop(next(iter(_MADE)))
        _MADE[(source, array)] = make
    function = make(*out.constants)
    function.__source__ = make.__source__
    function.__constants__ = tuple(out.constants)
    return function


#: the functions made from each source (mechanisms of one structure share theirs), the
#: KEPT last written
_MADE: dict = {}
KEPT = 256


def _live(lines) -> list:
    """``lines`` without the assignments no later line reads (a rate system's second
    column where its right-hand side is 0), and without a check written twice; one pass
    from the end (each variable is assigned once)."""
    read, kept = set(), []
    for line in reversed(list(dict.fromkeys(lines))):     # a repeated check: once
        match = _ASSIGN.match(line)
        if match is not None:
            if match.group(1) not in read:
                continue
            line_reads = line.split(" = ", 1)[1]
        else:
            line_reads = line
        read.update(_NAME.findall(line_reads))
        kept.append(line)
    return kept[::-1]


def _freed(lines) -> list:
    """``lines`` with each array dropped (``del``) after the line that reads it last: the
    temporaries of a long array do not all stay alive to the end."""
    last = {}
    for i, line in enumerate(lines):
        for name in _NAME.findall(line.split(" = ", 1)[1] if _ASSIGN.match(line) else line):
            last[name] = i
    dead: dict = {}
    for name, i in last.items():
        dead.setdefault(i, []).append(name)
    out = []
    for i, line in enumerate(lines):
        out.append(line)
        if i in dead and "return" not in line:
            out.append("    del " + ", ".join(sorted(dead[i])))
    return out


_NAME = re.compile(r"\bt\d+\b")
_ASSIGN = re.compile(r"^    (t\d+) = ")


def _crank(out, op, par, state, order):
    """P = A + L e^{i q}; P' = A' + i q' (P - A); P'' = A'' + (i q'' - q'^2)(P - A)."""
    pos, vel, acc = state
    p, a, length = op[1], op[2], par[0]
    rx, ry = out.mul(length, out.call("cos", "q")), out.mul(length, out.call("sin", "q"))
    pos[p] = [out.add(pos[a][0], rx), out.add(pos[a][1], ry)]
    for i, d in enumerate((rx, ry)):
        out.offset(pos[p][i], pos[a][i], d)
        out.bounded(pos[p][i], out.bound(pos[a][i]), abs(length))
    out.radius(rx, ry, length)
    if order >= 1:
        vel[p] = [out.add(vel[a][0], out.mul(ry, out.neg("w"))),
                  out.add(vel[a][1], out.mul(rx, "w"))]
    if order >= 2:
        w2 = out.neg(out.mul("w", "w"))
        acc[p] = [out.add(acc[a][0], out.add(out.mul(rx, w2), out.mul(ry, out.neg("al")))),
                  out.add(acc[a][1], out.add(out.mul(rx, "al"), out.mul(ry, w2)))]


def _place(out, op, par, state, order):
    """P = K + (M - N) w, the same for its rates."""
    k, m, n, wx, wy = op[2], op[3], op[5], par[0], par[1]
    for level, points in enumerate(state[:order + 1]):
        dx, dy = out.sub(points[m][0], points[n][0]), out.sub(points[m][1], points[n][1])
        points[op[1]] = [out.add(points[k][0], out.sub(out.mul(dx, wx), out.mul(dy, wy))),
                         out.add(points[k][1], out.add(out.mul(dx, wy), out.mul(dy, wx)))]
        if level == 0:
            span = [out.bound(points[m][i]) is not None and out.bound(points[n][i]) is not None
                    and out.bound(points[m][i]) + out.bound(points[n][i]) for i in (0, 1)]
            if all(x is not False for x in span):
                reach = span[0] * (abs(wx) + abs(wy)) + span[1] * (abs(wx) + abs(wy))
                for i in (0, 1):
                    out.bounded(points[op[1]][i], out.bound(points[k][i]), reach)


def _circles(out, op, par, state, order):
    """RRR: P = A + (B - A)(t + i branch s), as ``compiled._circles``."""
    pos = state[0]
    p, a, b, branch = op[1], op[2], op[3], op[4]
    d1, d2 = par[3] > 0, par[4] > 0
    r1, r2 = ("q" if d1 else par[0]), ("q" if d2 else par[1])
    (ax, ay), (bx, by) = pos[a], pos[b]
    dx, dy = out.sub(bx, ax), out.sub(by, ay)
    dd = out.add(out.mul(dx, dx), out.mul(dy, dy))
    least = out.low(dd)
    out.require(least, 0.0)
    r11 = out.mul(r1, r1)
    t = out.div(out.add(out.sub(r11, out.mul(r2, r2)), dd), out.mul(2.0, dd))
    across2, along2 = out.div(r11, dd), out.mul(t, t)
    e = out.sub(across2, along2)
    reach = out.div(out.add(out.add(out.top(ax), out.top(ay)), out.add(out.top(bx), out.top(by))),
                    out.call("sqrt", least))
    # the general path's scale is max(across2, along2): across2 wherever e > 0, which the
    # check asks of every position
    scale = out.div(out.mul(out.top(r1), out.top(r1)), least) if out.array else across2
    out.require(out.low(e), out.mul(MARGIN * TOGGLE, out.mul(scale, out.add(1.0, reach))))
    s = out.call("sqrt", e)
    if branch <= 0:
        s = out.neg(s)
    offset = [out.sub(out.mul(dx, t), out.mul(dy, s)), out.add(out.mul(dx, s), out.mul(dy, t))]
    pos[p] = [out.add(ax, offset[0]), out.add(ay, offset[1])]
    for i in (0, 1):
        out.offset(pos[p][i], pos[a][i], offset[i])
        out.bounded(pos[p][i], out.bound(pos[a][i]), None if d1 else abs(r1))
    out.radius(*offset, r1)
    out.radius(out.sub(pos[p][0], bx), out.sub(pos[p][1], by), r2)
    if order < 1:
        return
    g1 = [out.sub(pos[p][i], pos[a][i]) for i in (0, 1)]    # half the gradients, G / 2
    g2 = [out.sub(pos[p][i], pos[b][i]) for i in (0, 1)]
    _rates(out, p, (g1, a, d1), (g2, b, d2), par[2] / 4.0, state, order)


def _circle_guide(out, op, par, state, order):
    """RRP, PRR: |P - A| = r on a guide through fixed points, as ``compiled._circle_guide``."""
    pos = state[0]
    p, a, branch, first = op[1], op[2], op[4], op[5] == 1
    driven = par[9] > 0
    r = "q" if driven else par[0]
    bx, by, ux, uy, e, gx, gy, norms, reach = par[1:9] + [par[10]]
    ax, ay = pos[a]
    rx, ry = out.sub(ax, bx), out.sub(ay, by)
    relx = out.add(out.mul(rx, ux), out.mul(ry, uy))
    dist = out.sub(out.sub(out.mul(ry, ux), out.mul(rx, uy)), e)
    disc = out.sub(out.mul(r, r), out.mul(dist, dist))
    top_r = out.top(r)
    bound = out.add(out.mul(top_r, top_r),
                    out.mul(top_r, out.add(out.add(out.top(ax), out.top(ay)),
                                           out.add(reach, top_r))))
    out.require(out.low(disc), out.mul(MARGIN * TOGGLE, bound))
    root = out.call("sqrt", disc)
    along = out.add(relx, root) if branch > 0 else out.sub(relx, root)
    pos[p] = [out.add(bx, out.sub(out.mul(along, ux), e * uy)),
              out.add(by, out.add(out.mul(along, uy), e * ux))]
    for i in (0, 1):
        out.bounded(pos[p][i], out.bound(pos[a][i]), None if driven else abs(r))
    out.radius(out.sub(pos[p][0], ax), out.sub(pos[p][1], ay), r)
    if order < 1:
        return
    circle = ([out.sub(pos[p][i], pos[a][i]) for i in (0, 1)], a, driven)     # G / 2
    guide = ([gx, gy], None, False)
    pair = (guide, circle) if first else (circle, guide)
    _rates(out, p, *pair, norms / 2.0, state, order)


def _slide(out, op, par, state, order):
    """A point on a guide through fixed points with its x (or y) the coordinate q."""
    pos = state[0]
    p, axis = op[1], op[5]
    bx, by, ux, uy, e, gx, gy, norms = par[:8]
    sx, sy = bx - e * uy, by + e * ux
    along = ux if axis == 0 else uy
    if not abs(along) >= ROUNDING:
        raise _Unwritable(along)
    t = out.div(out.sub("q", sx if axis == 0 else sy), along)
    pos[p] = [out.add(sx, out.mul(t, ux)), out.add(sy, out.mul(t, uy))]
    if order >= 1:
        _rates(out, p, ([gx, gy], None, False), ([1.0, 0.0] if axis == 0 else [0.0, 1.0],
                                                   "coordinate", False), norms, state, order)


def _rates(out, p, first, second, norms, state, order):
    """P' and P'' of a dyad from Re(conj(G_i) P^(k)) = r_i, each constraint (G, centre,
    driven): a circle about point ``centre`` (an index), a fixed guide (None: r = 0), the
    coordinate itself ('coordinate': r = q', q'')."""
    pos, vel, acc = state
    (x1, y1), (x2, y2) = first[0], second[0]
    if norms == 0:          # a driven length: the gradients' own norms
        norms = out.mul(out.call("hypot", x1, y1), out.call("hypot", x2, y2))
        out.require(out.low(norms), 0.0)
    det = out.sub(out.mul(x1, y2), out.mul(y1, x2))
    if isinstance(norms, float):
        out.require(out.low(out.call("abs", det)), MARGIN * SINGULAR * norms)
    else:
        out.require(out.low(out.div(out.call("abs", det), norms)), MARGIN * SINGULAR)
    inv = out.div(1.0, det)

    def minus(x):           # -x inv
        return out.mul(-x, inv) if isinstance(x, float) else out.mul(x, out.neg(inv))
    k1 = [out.mul(y2, inv), minus(x2)]
    k2 = [minus(y1), out.mul(x1, inv)]
    r1 = _rhs(out, first, pos[p], vel, None, "w")
    r2 = _rhs(out, second, pos[p], vel, None, "w")
    vel[p] = [out.add(out.mul(r1, k1[i]), out.mul(r2, k2[i])) for i in (0, 1)]
    if order < 2:
        return
    r1 = _rhs(out, first, vel[p], acc, vel, "al")
    r2 = _rhs(out, second, vel[p], acc, vel, "al")
    acc[p] = [out.add(out.mul(r1, k1[i]), out.mul(r2, k2[i])) for i in (0, 1)]


def _rhs(out, constraint, mine, rates, vel, rate):
    """The right-hand side of one constraint (see :func:`_rates`) with half its gradient,
    G / 2 = P - A for a circle about A: Re(conj(G / 2) A^(k)) (+ L L^(k) where L = q is
    driven), and for accelerations - |P' - A'|^2 (+ L'^2); ``mine`` is P' (accelerations)
    or P.  (Halving both sides of every equation of the system leaves its solution.)"""
    (gx, gy), centre, driven = constraint
    if centre is None:
        return 0.0
    if centre == "coordinate":
        return rate
    cx, cy = rates[centre]
    r = out.add(out.mul(gx, cx), out.mul(gy, cy))
    if driven:
        r = out.add(r, out.mul("q", rate))
    if vel is not None:
        dx, dy = out.sub(mine[0], vel[centre][0]), out.sub(mine[1], vel[centre][1])
        r = out.sub(r, out.add(out.mul(dx, dx), out.mul(dy, dy)))
        if driven:
            r = out.add(r, out.mul("w", "w"))
    return r


_GROUPS = {CRANK: _crank, PLACE: _place, RRR: _circles, CIRCLE_LINE: _circle_guide,
           LINE_DRIVER: _slide}


def _probe(out, probe, state):
    """The value of one probe (kind, a, b, rate, factor, signed) over its factor."""
    kind, a, b, rate, factor, signed = probe
    if kind in (X, Y):
        value = state[rate][a][0 if kind == X else 1]
    else:
        z, dz, ddz = ([out.sub(points[b][i], points[a][i]) for i in (0, 1)]
                      for points in state)
        if kind == ANGLE and rate == 0:
            value = _angle(out, z, signed)
        elif kind == LENGTH and rate == 0:
            value = out.call("hypot", *z)
        else:
            value = _vector_rate(out, kind, rate, z, dz, ddz)
    return out.div(value, float(factor))


def _angle(out, z, signed):
    """The angle of z in [0, 2 pi), within WRAP of 2 pi being 0 (``signed``: (-pi, pi])."""
    if isinstance(z[0], float) and isinstance(z[1], float):
        value = math.atan2(z[1], z[0])
        value = value + TWO_PI if value <= 0 else value
        value = 0.0 if value > TWO_PI - WRAP else value
        return value - TWO_PI if signed and value > math.pi else value
    name = out.fresh(f"atan2({out.text(z[1])}, {out.text(z[0])})")   # changed in place
    if out.array:
        out.emit(f"add({name}, TWO_PI, out={name}, where={name} <= 0)")
        out.emit(f"copyto({name}, 0.0, where={name} > TWO_PI - WRAP)")
        if signed:
            out.emit(f"subtract({name}, TWO_PI, out={name}, where={name} > pi)")
    else:
        out.emit(f"if {name} <= 0: {name} += TWO_PI")
        out.emit(f"if {name} > TWO_PI - WRAP: {name} = 0.0")
        if signed:
            out.emit(f"if {name} > pi: {name} -= TWO_PI")
    return name


def _vector_rate(out, kind, rate, z, dz, ddz):
    """Rates of the angle (Im w, Im(z''/z) - 2 Re w Im w) or of the length (|z| Re w,
    |z| (Re(z''/z - w^2) + (Re w)^2)) of z, with w = z'/z; refused where z = 0.  For a
    link's fixed length r (``_Writer.radius``), |z|^2 = r^2."""
    zx, zy = z
    radius = out.radii.get((zx, zy))
    if radius is not None:      # a link of fixed length: |z|^2 is its square
        n2 = radius * radius
    else:
        n2 = out.add(out.mul(zx, zx), out.mul(zy, zy))
        out.require(out.low(n2), 0.0)
    wr = out.div(out.add(out.mul(zx, dz[0]), out.mul(zy, dz[1])), n2)
    wi = out.div(out.sub(out.mul(zx, dz[1]), out.mul(zy, dz[0])), n2)
    if kind == ANGLE:
        if rate == 1:
            return wi
        si = out.div(out.sub(out.mul(zx, ddz[1]), out.mul(zy, ddz[0])), n2)
        if radius is not None:  # Re w = z.z' / |z|^2 = 0 where |z| is fixed: its rounding
            return si           # only, which the general path carries and this leaves out
        return out.sub(si, out.mul(2.0, out.mul(wr, wi)))
    length = out.call("hypot", zx, zy)
    if rate == 1:
        return out.mul(length, wr)
    sr = out.div(out.add(out.mul(zx, ddz[0]), out.mul(zy, ddz[1])), n2)
    return out.mul(length, out.add(out.sub(sr, out.sub(out.mul(wr, wr), out.mul(wi, wi))),
                                   out.mul(wr, wr)))
