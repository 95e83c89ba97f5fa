"""Positions of the points as formulas of the coordinates, along the solving order.

The groups are the Assur decomposition's: ``assur.analyse`` of the model read with
``--symbolic``, whose numbers carry their formulas (``model.exact``), taken in the order the numeric
solver takes them.  Each gives its point as a formula of the coordinates q and of
the file's parameters, as the closed-form solver computes it:

    driver-angle   P = A + L (cos q, sin q)              (-L when the vector runs P -> A)
    driver-coord   x_P = q (or y_P = q) on the guide cross(C - B, P - B) = c
    place          P = K + (M - N) w                      (w complex, fixed in the body)
    roll           P = C + d (cos theta, sin theta),  theta = theta_0 - sum' c_k (mu_k - mu_k0) / c

with mu_k the measures of the contact's relation sum c_k (mu_k - mu_k0) = 0
(``kinematics.contacts``; sum' leaves out the disc's own turn, of coefficient c) and the
_0 values those of the figure.  Two groups of the dyads' kinds have one too: a point on
two lines, each a guide or a contact's relation linear in it (a cord's end on its guide:
two linear equations), and a point at a length along a guide through the length's centre
(P = A + L (C - B) / |C - B|).  A dyad (RRR, RRP, PRR, PRP, RPR, RPP) closes a loop:
its point is a root of closure equations whose solution in the parameters is no
formula worth printing, so it is refused by name (:class:`NoClosedForm`); its
closure equations in complex form are ``texts.symbolic``'s.

Points are pairs (x, y) of sympy expressions; angles of vectors are found as
rho (cos phi, sin phi) with rho free of the coordinates when the vector is one
(:func:`angle`), else atan2(y, x).

The numeric twin is ``kinematics.closed_form`` (positions along the same groups,
``kinematics.rates`` their rates; ``kinematics.jacobian`` for bodies' angles and points),
and ``kinematics.substitute`` for a coordinate the groups do not place (its closures are
written with the substitute).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from linkcli.errors import SolveError
from linkcli.kinematics.contacts import Along, Carried, Track, Turn
from linkcli.kinematics.assur import analyse, partial
from linkcli.kinematics.groups import Dist, Line
from linkcli.model import exact


class NoClosedForm(SolveError):
    """A group whose position has no formula in the parameters (a closed loop)."""

    def __init__(self, detail, *, group=None, **kw):
        super().__init__(detail, **kw)
        self.group = group


def placed(mech):
    """The solving order of ``mech`` (``assur.analyse``); NoClosedForm where the
    decomposition leaves a coordinate it does not place (a coupler's angle: the numeric
    solver reaches it through substitute coordinates, ``kinematics.substitute``, by Newton's
    method), since the points are then roots of closure equations in it."""
    pending = partial(mech).pending
    if pending:
        names = ", ".join(f"{c.name} (the angle of {c.a}->{c.b})" if c.kind == "angle" else
                          c.name for c in pending)
        raise NoClosedForm(f"{names} places no point in the solving order (a coupler's "
                           "angle): the points are roots of the closure equations in it, with "
                           "no closed form in the parameters", file=mech.file,
                           hint="the closure equations and the numeric answers are given")
    return analyse(mech)


def placing(mech):
    """``mech`` with the coordinates its decomposition does not place replaced by the first
    substitutes that it does (``kinematics.substitute``), for the closure equations; ``mech``
    itself where it places them all or no substitute does."""
    from linkcli.kinematics.substitute import substitutes
    for inner, _ in substitutes(mech):
        try:
            analyse(inner)
        except SolveError:
            continue
        return inner
    return mech


@dataclass
class Symbols:
    """The symbols of one file read with ``--symbolic``: coordinates, rates and the
    SI symbols of the parameters, with their values (for branch choices and checks)."""

    mech: object                    # the model, its numbers exact (model.exact)
    si: dict                        # file-unit symbol -> SI expression
    values: dict                    # SI symbol -> value (SI)
    gravity: object = None          # the symbol g (or its number) of gravity's magnitude
    q: list = field(default_factory=list)
    qd: list = field(default_factory=list)
    qdd: list = field(default_factory=list)
    figure: dict = field(default_factory=dict)      # q symbol -> its figure value (formula)

    @classmethod
    def of(cls, mech, si, values, gravity=None):
        out = cls(mech, si, dict(values), gravity)
        for c in mech.coordinates:
            q = sp.Symbol(c.name, real=True)
            out.q.append(q)
            out.qd.append(sp.Symbol(f"{c.name}_dot", real=True))
            out.qdd.append(sp.Symbol(f"{c.name}_ddot", real=True))
            out.figure[q] = out.num(c.value)
        return out

    def num(self, x):
        """A model number (exact or plain) as an SI formula."""
        return exact.expression(x).xreplace(self.si)

    def point(self, z) -> tuple:
        return exact.parts(self.num(z))

    def at_figure(self, expr):
        return expr.xreplace(self.figure)

    def value(self, expr) -> complex:
        """The number of ``expr`` at the parameters' values and the figure."""
        return complex(sp.N(self.at_figure(expr).xreplace(self.values), 17))


def on_line(b, c, value, axis, q) -> tuple:
    """P with x_P = q (``axis`` 'x', else y_P = q) on the guide cross(C - B, P - B) = value."""
    d = sub(c, b)
    if axis == "x":
        return (q, b[1] + (value + d[1] * (q - b[0])) / d[0])
    return (b[0] + (d[0] * (q - b[1]) - value) / d[1], q)


def add(a, b):
    return (a[0] + b[0], a[1] + b[1])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def times(a, w):
    """a w of two plane vectors as complex numbers."""
    return (a[0] * w[0] - a[1] * w[1], a[0] * w[1] + a[1] * w[0])


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def length(z, s: Symbols):
    """|z| of a vector z = (x, y): sqrt(x^2 + y^2), a square's root taken with the sign
    its base has at the figure (|z - s| is z - s where the figure has z > s)."""
    square = sp.factor(sp.trigsimp(sp.expand(z[0] ** 2 + z[1] ** 2)))
    root = sp.sqrt(square)
    return root.replace(lambda e: isinstance(e, sp.Abs),
                        lambda e: e.args[0] * (1 if s.value(e.args[0]).real >= 0 else -1))


def angle(z, s: Symbols, coords=()):
    """The angle of the vector z = (x, y): phi where z = rho (cos phi, sin phi) with rho
    free of the coordinates and phi one of the angles z's cosines and sines hold (within
    a quarter turn), on the branch of atan2 at the figure; else atan2(y, x)."""
    x, y = (sp.sympify(c) for c in z)
    target = s.value(sp.atan2(y, x)).real
    rho2 = sp.trigsimp(sp.expand(x ** 2 + y ** 2), method="fu")
    phi = None
    if not rho2.free_symbols & set(coords):
        rho = sp.sqrt(rho2)
        if not (x.free_symbols | y.free_symbols) & set(coords):
            phi = _constant_angle(x, y, s)
        else:
            phi = _match(x, y, rho)
    if phi is None:
        return sp.atan2(y, x)
    turns = round((target - s.value(phi).real) / (2 * sp.pi.evalf()))
    return phi + 2 * sp.pi * turns


def _constant_angle(x, y, s):
    """The angle of a constant vector: along an axis exactly, else atan2."""
    if x == 0:
        return sp.pi / 2 if s.value(y).real > 0 else -sp.pi / 2
    if y == 0:
        return sp.Integer(0) if s.value(x).real > 0 else sp.pi
    return sp.atan2(y, x)


def _match(x, y, rho):
    """phi with x = rho cos phi and y = rho sin phi, among the angles of x's and y's
    cosines and sines turned by a quarter turn; a candidate that fails at a sample point
    is dropped, one that passes is proved (the differences simplify to 0)."""
    args = {a.args[0] for a in (x.atoms(sp.cos) | x.atoms(sp.sin) | y.atoms(sp.cos)
                                | y.atoms(sp.sin))}
    sample = {v: sp.Rational(7 + 3 * i, 11 + i) for i, v in
              enumerate(sorted(x.free_symbols | y.free_symbols, key=sp.default_sort_key))}
    for arg in sorted(args, key=sp.default_sort_key):
        for shift in (0, sp.pi, sp.pi / 2, -sp.pi / 2):
            phi = arg + shift
            dx, dy = x - rho * sp.cos(phi), y - rho * sp.sin(phi)
            if abs(complex(sp.N(dx.xreplace(sample)))) > 1e-9 or \
                    abs(complex(sp.N(dy.xreplace(sample)))) > 1e-9:
                continue
            if all(_zero(d) for d in (dx, dy)):
                return phi
    return None


def _zero(expr) -> bool:
    """Whether ``expr`` simplifies to 0 (the cheap ways first)."""
    expr = sp.expand(sp.expand_trig(expr))
    return expr == 0 or sp.trigsimp(expr, method="fu") == 0 or sp.simplify(expr) == 0


class Positions:
    """Every point of the mechanism as formulas of the coordinates, group by group."""

    def __init__(self, s: Symbols, check=None):
        self.s = s
        mech = s.mech
        self.mech = mech
        self.groups = placed(mech).groups
        self.pos = {name: s.point(z) for name, z in mech.fixed.items()}
        self._angles = {}
        for group in self.groups:
            if check is not None:
                check()
            if group.point is not None:
                self.pos[group.point] = self._position(group)

    def _position(self, group):
        s, pos, kind = self.s, self.pos, group.kind
        if kind == "driver-angle":
            pivot, length, reverse = group.constraints
            q = s.q[group.coord]
            arm = s.num(length) * (-1 if reverse else 1)
            return add(pos[pivot], (arm * sp.cos(q), arm * sp.sin(q)))
        if kind == "driver-coord":
            line, coord = group.constraints
            return self._on_line(line, coord, s.q[coord.coord])
        if kind == "place":
            k, m, n, w = group.place
            return add(pos[k], times(sub(pos[m], pos[n]), s.point(w)))
        if kind == "roll":
            return self._roll(group)
        if kind in ("PRP", "RPP") and all(self._linear(c, group.point)
                                          for c in group.constraints):
            return self._on_lines(group)
        if kind in ("RRP", "PRR"):
            along = self._along_guide(group)
            if along is not None:
                return along
        raise NoClosedForm(f"{group.describe()} closes a loop: its position is a root of its "
                           "closure equations, with no closed form in the parameters",
                           group=group, file=self.mech.file,
                           hint="the closure equations and the numeric answers are given")

    def _on_line(self, line, coord, q):
        return on_line(self.pos[line.b], self.pos[line.c], self.s.num(line.value), coord.axis, q)

    def _linear(self, c, p) -> bool:
        """Whether constraint ``c`` is a line in ``p`` whose other points are placed: a guide
        cross(C - B, P - B) = value or a contact's relation linear in P (``Track``)."""
        if isinstance(c, Track):
            known = set(self.pos)
            return all(term.linear(x, known) if x in c.rigid else x in known
                       for term, _, _ in c.relation.terms for x in term.points)
        return isinstance(c, Line) and c.p == p and c.b in self.pos and c.c in self.pos

    def _along_guide(self, group):
        """P at |P - A| = L on a guide through A (A one of the guide's points, the guide's
        value 0): P = A + sign L (C - B) / |C - B|, the sign the figure's; None for a
        circle that is not centred on its line (two crossings, no formula printed)."""
        dist, line = group.constraints if isinstance(group.constraints[0], Dist) else \
            group.constraints[::-1]
        if not isinstance(line, Line) or line.p != group.point or dist.a not in (line.b, line.c) \
                or not {line.b, line.c} <= set(self.pos) or self.s.num(line.value) != 0:
            return None
        s = self.s
        direction = sub(self.pos[line.c], self.pos[line.b])
        unit = length(direction, s)
        size = s.q[dist.coord] if dist.length is None else s.num(dist.length)
        drawn = s.point(self.mech.moving[group.point])
        figure_a = tuple(s.at_figure(v) for v in self.pos[dist.a])
        sign = 1 if s.value(dot(sub(drawn, figure_a),
                                tuple(s.at_figure(v) for v in direction))).real >= 0 else -1
        return add(self.pos[dist.a], (sign * size * direction[0] / unit,
                                      sign * size * direction[1] / unit))

    def _on_lines(self, group):
        """P on two lines, each a guide or a contact's relation sum c_k (mu_k - mu_k0) = 0
        linear in P (its slider's points moving with it): the two linear equations in
        (x_P, y_P) solved."""
        p = group.point
        xy = (sp.Dummy("x"), sp.Dummy("y"))
        drawn = self.s.point(self.mech.moving[p])
        equations = []
        for c in group.constraints:
            if isinstance(c, Line):
                b, cc = self.pos[c.b], self.pos[c.c]
                equations.append(cross(sub(cc, b), sub(xy, b)) - self.s.num(c.value))
                continue
            moved, figure = dict(self.pos), {k: tuple(self.s.at_figure(v) for v in z)
                                             for k, z in self.pos.items()}
            for x, offset in c.rigid.items():
                moved[x] = add(xy, self.s.point(offset))
                figure[x] = add(drawn, self.s.point(offset))
            total = 0
            for term, k, _ in c.relation.terms:
                mu = self.measure(term, moved)
                total = total + self.s.num(k) * (mu - self.s.at_figure(self.measure(term, figure)))
            equations.append(total)
        solved = sp.solve(equations, xy, dict=True, rational=False)
        if len(solved) != 1:
            raise NoClosedForm(f"{group.describe()}: its two lines have no single crossing in "
                               "the parameters", group=group, file=self.mech.file)
        return tuple(sp.simplify(solved[0][v]) for v in xy)

    # rolling ---------------------------------------------------------------------------
    def measure(self, term, pos=None):
        """A contact's measure mu (``kinematics.contacts``): Re(conj(u) (P_a - P_b)), the
        carried Re(conj(rho Z) (P_a - P_o)) / |Z|, or the angle of P_b - P_a (a
        coordinate's own where the turn is one)."""
        pos = self.pos if pos is None else pos
        if isinstance(term, Along):
            z = pos[term.a] if term.b is None else sub(pos[term.a], pos[term.b])
            return dot(self.s.point(term.u), z)
        if isinstance(term, Carried):
            z = times(self.s.point(term.rho), sub(pos[term.c], pos[term.b]))
            return dot(z, sub(pos[term.a], pos[term.o])) / self.s.num(term.length)
        assert isinstance(term, Turn)
        if term.coord is not None:
            return self.s.q[term.coord]
        return self.angle_of(sub(pos[term.b], pos[term.a]))

    def angle_of(self, z):
        return angle(z, self.s, self.s.q)

    def _roll(self, group):
        """The second point M = C + |M - C| (cos theta, sin theta) of a disc its contact
        turns: theta - theta_0 = -(sum of the other terms c_k (mu_k - mu_k0)) / c."""
        s = self.s
        rel, turn = group.constraints
        body = self.mech.bodies[group.bodies[0]]
        arm = s.num(abs(body.local[turn.b] - body.local[turn.a]))
        figure = {p: tuple(s.at_figure(c) for c in xy) for p, xy in self.pos.items()}
        drawn = s.point(self.mech.moving.get(turn.b, self.mech.fixed.get(turn.b, 0j)))
        theta = angle(sub(drawn, figure[turn.a]), s)
        rest = 0
        for term, c, _ in rel.terms:
            if term is not turn:
                mu = self.measure(term)
                rest = rest + s.num(c) * (mu - s.at_figure(mu))
        theta = theta - rest / s.num(rel.coefficient(turn))
        return add(self.pos[turn.a], (arm * sp.cos(theta), arm * sp.sin(theta)))

    # bodies -----------------------------------------------------------------------------
    def body_angle(self, name):
        """theta of body ``name`` as ``jacobian.body_angle`` measures it: the angle of its
        axis vector less that vector's local angle (the frame's is 0)."""
        if name in self._angles:
            return self._angles[name]
        from linkcli.kinematics.jacobian import body_axis
        axis = body_axis(self.mech, name)
        if axis is None:
            theta = sp.Integer(0)
        else:
            _, (a, b), local = axis
            theta = self.angle_of(sub(self.pos[b], self.pos[a])) - self.s.num(local)
        self._angles[name] = theta
        return theta

    def body_point(self, name, local):
        """The point at ``local`` of body ``name`` (``jacobian.body_point``): its origin
        point plus the offset turned by the body's angle; on a link, from two of its points
        (G = K + (M - K) w), which needs no angle."""
        body = self.mech.bodies.get(name)
        if body is not None and body.kind == "link":
            k, m = body.points[0], body.points[1]
            w = (local - body.local[k]) / (body.local[m] - body.local[k])
            return add(self.pos[k], times(sub(self.pos[m], self.pos[k]), self.s.point(w)))
        from linkcli.kinematics.jacobian import body_axis
        origin, _, _ = body_axis(self.mech, name)
        offset = local - (body.local[origin] if body is not None and body.kind == "block"
                          else 0.0)
        theta = self.body_angle(name)
        turned = times(self.s.point(offset), (sp.cos(theta), sp.sin(theta)))
        return add(self.pos[origin], turned)


# --- closure equations of a linkage ------------------------------------------------------
@dataclass
class Closure:
    """One group's closure in complex form, ``left = right`` (sympy, e^{i angle} kept as
    exp), its unknowns and its rate systems A u' = b (velocity) and A u'' = c
    (acceleration); ``text`` says what the group is, ``missing`` why a group has none."""

    text: str
    left: object = None
    right: object = None
    unknowns: list = field(default_factory=list)
    matrix: object = None
    velocity: object = None
    acceleration: object = None
    missing: str = ""
    point: str = ""             # the point a driver places (left: its position)


class Closures:
    """The closure equations of a linkage's groups in the solving order, with symbols
    for its lengths and angles (the seed's a e^{i alpha} + b e^{i beta} = c e^{i gamma}).

    A link's length is its formula where the file gives one in parameters, else the
    symbol l_XY; a vector's angle is named by the report's quantity of that angle (else
    theta_XY), a slider's abscissa along its guide by the report's x or y of the point
    when the guide runs along that axis (else s_P), a fixed guide's angle gamma (gamma_S
    with several).  The rate systems come from d/dt (right - left) = 0, its real and
    imaginary parts, the unknown rates on the left: the seed's matrix
    [[cos gamma, b sin beta], [sin gamma, -b cos beta]] [c', beta']^T = ...
    """

    def __init__(self, s: Symbols, check=None, write=True):
        self.s = s
        self.mech = placing(s.mech)
        self.named = s.mech.coordinates     # the file's, which name the angles they measure
        self.groups = analyse(self.mech).groups
        self.pos = {n: self._fixed(z) for n, z in self.mech.fixed.items()}
        self.varying = []          # symbols that move: the driver's, then each unknown
        self.values = {}           # symbol -> its formula or number (SI)
        self.meaning = {}          # symbol -> ('angle', a, b) | ('abscissa', P, G, gamma)
        #                            | ('length', a, b): what it measures, for checks
        guides = [b for b in self.mech.bodies.values() if b.kind == "block"
                  and b.guide.carrier == "frame"]
        self.one_guide = len({(g.guide.b, g.guide.c) for g in guides}) == 1
        self.closures = []
        if write:
            self.write(check)

    def write(self, check=None):
        """Each group's closure, appended to ``closures`` as it is written; ``check`` is
        called before each."""
        for g in self.groups[len(self.closures):]:
            if check is not None:
                check()
            self.closures.append(self._group(g))

    def _fixed(self, z):
        x, y = self.s.point(z)
        return x + sp.I * y

    # names --------------------------------------------------------------------------------
    def _quantities(self):
        """The report's quantities, those the report lists first."""
        listed = [n for names in self.mech.report.values() if isinstance(names, list)
                  for n in names]
        return sorted(self.mech.quantities.values(),
                      key=lambda q: listed.index(q.name) if q.name in listed else len(listed))

    def _angle_symbol(self, a, b):
        """(symbol, sign): the coordinate's or the report's angle of a->b (sign 1) or of
        b->a (-1), else theta_ab."""
        symbol, sign = self._named_angle(a, b)
        self.meaning[symbol] = ("angle", a, b) if sign == 1 else ("angle", b, a)
        return symbol, sign

    def _named_angle(self, a, b):
        for c in self.named:
            if c.kind == "angle" and (c.a, c.b) in ((a, b), (b, a)) and len(
                    self.named) + (self.mech.elements is not None) > 1:
                return sp.Symbol(c.name, real=True), 1 if (c.a, c.b) == (a, b) else -1
        for q in self._quantities():
            if q.kind == "angle" and (q.a, q.b) == (a, b):
                return sp.Symbol(q.name, real=True), 1
            if q.kind == "angle" and (q.a, q.b) == (b, a):
                return sp.Symbol(q.name, real=True), -1
        return sp.Symbol(f"theta_{a}{b}", real=True), 1

    def _length(self, body, a, b):
        local = self.mech.bodies[body].local
        value = self.s.num(abs(local[b] - local[a]))
        if value.free_symbols:
            return value
        symbol = sp.Symbol(f"l_{a}{b}", positive=True)
        self.values[symbol] = value
        return symbol

    def _guide(self, line):
        """(point G, angle symbol gamma, offset e) of a fixed guide cross(C - B, P - B) = c:
        P = G + s e^{i gamma} + i e e^{i gamma}."""
        block = self.mech.bodies[line.body]
        name = "gamma" if self.one_guide else f"gamma_{block.name}"
        gamma = sp.Symbol(name, real=True)
        b, c = self.pos[line.b], self.pos[line.c]
        d = sp.expand(c - b)
        self.values[gamma] = angle(exact.parts(d), self.s)
        e = sp.simplify(self.s.num(line.value) / sp.sqrt(sp.expand(d * sp.conjugate(d))))
        return b, gamma, e

    def _abscissa(self, point, gamma_value):
        axis = {0: "x", sp.pi / 2: "y"}.get(gamma_value)
        for q in self._quantities():
            if axis and q.kind == axis and q.a == point:
                return sp.Symbol(q.name, real=True)
        return sp.Symbol(f"s_{point}", real=True)

    # groups -------------------------------------------------------------------------------
    def _group(self, group) -> Closure:
        kind = group.kind
        text = group.describe()
        if kind == "driver-angle":
            pivot, length, reverse = group.constraints
            crank = group.bodies[0]
            d = self.mech.coordinates[group.coord]
            if d not in self.named:
                text += " (in place of " + ", ".join(
                    c.name for c in self.named if c not in self.mech.coordinates) + \
                    ", which places no point)"
            if pivot not in self.pos:   # a pivot that a contact's relation placed
                return Closure(text, missing=f"its pivot {pivot} is placed by a contact's "
                               "relation, whose closure is not written (see its numbers)")
            q, sign = self._angle_symbol(d.a, d.b)
            L = self._length(crank, d.a, d.b)
            other = d.b if pivot == d.a else d.a
            step = sign * L * sp.exp(sp.I * q)
            self.pos[other] = self.pos[pivot] + (step if pivot == d.a else -step)
            self.varying.append(q)
            return Closure(text, self.pos[other], None, point=other)
        if kind == "driver-coord":
            return self._slider_driver(group, text)
        if kind == "place":
            k, m, n, w = group.place
            if not {k, m, n} <= set(self.pos):
                return Closure(text, missing="its body's points follow from a group with no "
                               "closure equation written: see its numbers in the worked "
                               "solution")
            self.pos[group.point] = self.pos[k] + (self.pos[m] - self.pos[n]) * \
                self._fixed(w)
            return Closure(text)
        if kind in ("RRR", "RRP", "PRR", "PRP", "RPR-actuator"):
            return self._dyad(group, text)
        if kind == "RPR" and not group.point.startswith("~"):
            return self._slotted(group, text)
        return Closure(text, missing="no closure equation is written for this group "
                       f"({kind}): see its numbers in the worked solution")

    def _slider_driver(self, group, text) -> Closure:
        """A slider's point set by its x (or y), the coordinate q, on its fixed guide:
        P = x + i y with the other of x, y from the guide's line (``on_line``)."""
        line, coord = group.constraints
        d = self.mech.coordinates[coord.coord]
        q = sp.Symbol(d.name, real=True)
        self.meaning[q] = ("coordinate", coord.p, coord.axis)
        self.varying.append(q)
        b, c = (exact.parts(self.pos[x]) for x in (line.b, line.c))
        x, y = on_line(b, c, self.s.num(line.value), coord.axis, q)
        self.pos[group.point] = x + sp.I * y
        return Closure(text, self.pos[group.point], None, point=group.point)

    def _arm(self, dist):
        """(vector A -> P as length e^{i angle}, the angle symbol) of a Dist constraint."""
        symbol, sign = self._angle_symbol(dist.a, dist.p)
        if dist.length is None:                 # a driven length: the driver
            length = self._driven(dist.a, dist.p)
        else:
            length = self._length(dist.body, dist.a, dist.p)
        return sign * length * sp.exp(sp.I * symbol), symbol

    def _driven(self, a, b):
        """The symbol of a driving length |b - a|: the report's, else l_ab; it varies."""
        found = next((q.name for q in self._quantities() if q.kind == "length"
                      and {q.a, q.b} == {a, b}), f"l_{a}{b}")
        symbol = sp.Symbol(found, positive=True)
        self.meaning[symbol] = ("length", a, b)
        if symbol not in self.varying:
            self.varying.insert(0, symbol)
        return symbol

    def _slide(self, line):
        if line.b not in self.mech.fixed or line.c not in self.mech.fixed:
            return None
        g, gamma, e = self._guide(line)
        s = self._abscissa(line.p, self.values[gamma])
        self.meaning[s] = ("abscissa", line.p, g, self.values[gamma])
        return g + (s + sp.I * e) * sp.exp(sp.I * gamma), s

    def _dyad(self, group, text) -> Closure:
        kind = group.kind
        if kind == "RPR-actuator":
            act = self.mech.actuators[group.bodies[0]]
            d = sp.Symbol(f"l_{act.a}{act.b}", positive=True)
            self.meaning[d] = ("length", act.a, act.b)
            theta, _ = self._angle_symbol(act.a, act.b)
            return self._close(text, self.pos[act.b] - self.pos[act.a], d * sp.exp(sp.I * theta),
                               [d, theta], None)
        c1, c2 = group.constraints
        if not all(isinstance(c, (Dist, Line)) for c in (c1, c2)):
            return Closure(text, missing="a contact's relation (a cord, a rolling disc) places "
                           "it: its closure is not written (see its numbers)")
        if kind == "RRR":
            (v1, t1), (v2, t2) = self._arm(c1), self._arm(c2)
            left, right = self.pos[c1.a] + v1, self.pos[c2.a] + v2
            return self._close(text, left, right, [t1, t2], (group.point, left))
        if kind in ("RRP", "PRR"):
            dist, line = (c1, c2) if kind == "RRP" else (c2, c1)
            slide = self._slide(line)
            if slide is None:
                return Closure(text, missing="the guide moves: its closure is not written")
            v, t = self._arm(dist)
            left = self.pos[dist.a] + v
            return self._close(text, left, slide[0], [slide[1], t], (group.point, left))
        one, two = self._slide(c1), self._slide(c2)
        if one is None or two is None:
            return Closure(text, missing="a guide moves: its closure is not written")
        return self._close(text, one[0], two[0], [one[1], two[1]], (group.point, one[0]))

    def _slotted(self, group, text) -> Closure:
        """A link pivoted at B with a slot along B -> C, a known pin A in it:
        A = B + (s + i e) e^{i theta}, s the pin's abscissa along the slot."""
        dist, line = group.constraints
        theta, sign = self._angle_symbol(dist.a, dist.p)
        length = self._length(dist.body, dist.a, dist.p)
        s = sp.Symbol(f"s_{line.p}", real=True)
        e = sp.simplify(self.s.num(line.value) / length)
        pivot = self.pos[dist.a]
        turn = sign * sp.exp(sp.I * theta)
        closure = self._close(text, self.pos[line.p], pivot + (s + sp.I * e) * turn, [s, theta],
                              (dist.p, pivot + length * turn))
        return closure

    def _close(self, text, left, right, unknowns, placed) -> Closure:
        """The closure left = right and its rate systems in ``unknowns``."""
        if placed is not None:
            self.pos[placed[0]] = placed[1]
        zero = right - left
        rates = self._rates(zero, 1, unknowns)
        A = sp.Matrix(2, 2, lambda i, j: sp.diff(_part(rates, i), _dot(unknowns[j], 1)))
        velocity = sp.Matrix([-(_part(rates, i) - sum(A[i, j] * _dot(unknowns[j], 1)
                                                      for j in range(2))) for i in range(2)])
        second = self._rates(zero, 2, unknowns)
        acceleration = sp.Matrix([-(_part(second, i) - sum(A[i, j] * _dot(unknowns[j], 2)
                                                           for j in range(2)))
                                  for i in range(2)])
        closure = Closure(text, left, right, list(unknowns), A.applyfunc(sp.expand),
                          velocity.applyfunc(_tidy), acceleration.applyfunc(_tidy))
        self.varying += list(unknowns)
        return closure

    def _rates(self, expr, order, unknowns=()):
        """d/dt of ``expr`` (order 1), or d2/dt2 (order 2), the varying symbols' rates as
        symbols NAME_dot and NAME_ddot."""
        varying = self.varying + list(unknowns)
        out = expr
        for _ in range(order):
            out = sum((sp.diff(out, v) * _dot(v, 1) + sp.diff(out, _dot(v, 1)) * _dot(v, 2)
                       for v in varying), sp.Integer(0))
        return out


def _dot(symbol, order):
    return sp.Symbol(f"{symbol.name}_{'d' * order}ot", real=True)


def _part(expr, i):
    """Real (0) or imaginary (1) part of an expression in real symbols."""
    return sp.expand_complex(expr).as_real_imag()[i]


def _tidy(expr):
    """A rate system's right side expanded and collected in the rates: each term a length
    times the sines and cosines of the angles (sympy's simplify, which would fold a sum into
    sqrt(2) cos(phi + pi/4), costs ten times the rest of the closures)."""
    return sp.collect(sp.expand(expr), [s for s in expr.free_symbols
                                        if s.name.endswith("dot")])
