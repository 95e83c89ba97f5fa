"""The energies of a vibration problem as formulas, and its linearised system.

The terms are those of ``forces.lagrange``, from the same model (its numbers exact,
``model.exact``) and the positions of ``kinematics.symbolic`` (the same solving
order), with q' the coordinates' rates:

    T = sum_b 1/2 m_b |G_b'|^2 + 1/2 J_b theta_b'^2,   G' = sum_j dG/dq_j q_j'
    V = sum_springs 1/2 k (s - s0)^2 - sum_b m_b g.G_b - sum_loads L s_L
    D = sum_dampers 1/2 c s'^2

g is the symbol g times gravity's direction.  Lagrange's equations of the free
coordinates, nonlinear, with the harmonic loads' generalised forces f(q):

    d/dt dT/dq_i' - dT/dq_i + dV/dq_i + dD/dq_i' = Re(f_i(q) e^{i Omega t})

The static equilibrium q_e is the figure where the figure is one (Q = -dV/dq = 0
there, simplified to 0), else the root of Q_f = 0 when Q_f is linear in the free
coordinates; otherwise it has no closed form and the numeric one is used, kept as
the symbols q_e whose values are stated.  'static' preloads are the exact solution of
the linear system of ``forces.equilibrium``.  About q_e, with _f the free and _s the
imposed coordinates,

    M = d2T/dq'_f dq'_f,  K = d2V/dq_f dq_f,  R = d2D/dq'_f dq'_f   (at q_e)
    F = f_f - (K_fs - Omega^2 M_fs + i Omega R_fs) S

the stability conditions are the leading principal minors of K (all > 0), and the
natural frequencies the roots of det(K - omega^2 M) = 0, a polynomial in omega^2.

The numeric twins: ``forces.lagrange`` (T, V, D, M, K, R), ``forces.equilibrium`` (q_e),
``forces.vibration`` (the linearisation, F) and ``forces.oscillation`` (the characteristic
polynomial).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from linkcli.errors import FormulaLimit, SolveError
from linkcli.kinematics.symbolic import Positions, Symbols, dot, length, sub
from linkcli.model import elements as el

#: the frequency symbol of the characteristic equation
OMEGA = sp.Symbol("omega", positive=True)
#: time, in the forcing terms of the nonlinear equations
TIME = sp.Symbol("t", real=True)
#: a root of the characteristic polynomial is printed when it is at most this long
SHORT = 160
#: a polynomial of more terms is not tried factored (it would not be short)
MANY = 16
#: a formula with roots of at most this many operations is simplified whole
BRIEF = 40
#: a formula of more operations is written as it is built: simplifying it costs more than
#: its length, and no exam prints one so long
LONG = 400
#: the characteristic polynomial is not written where a minor of det(K - omega^2 M) passes
#: this many terms (an exam's has tens), or where written out it has more operations
TERMS = 2000
OPERATIONS = 5000


@dataclass
class Equilibrium:
    """q_e of every coordinate (formulas), and how it was found."""

    values: dict                  # q symbol -> formula (or its symbol q_e when numeric)
    how: str                      # 'figure' | 'solved' | 'numeric'
    stated: dict = field(default_factory=dict)    # q_e symbol -> value, when numeric
    preloads: dict = field(default_factory=dict)  # 'static' spring -> N formula


@dataclass
class Linear:
    """The formulas of the linearised system of the free coordinates."""

    names: list
    M: sp.Matrix
    K: sp.Matrix
    R: sp.Matrix
    F: list
    stability: list
    characteristic: object        # det(K - omega^2 M), expanded
    roots: list | None            # omega^2 roots, None when not short


class Lagrangian:
    """T, V, D and the generalised harmonic forces of ``s.mech`` as formulas."""

    def __init__(self, s: Symbols, check=None):
        self.s = s
        self.mech = s.mech
        #: called between steps; raises where the formulas' time has run out
        self.check = check if check is not None else (lambda: None)
        self.positions = Positions(s, self.check)
        self.elements = self.mech.elements or el.Elements()
        self.dyn = self.mech.dynamics
        imposed = set(self.elements.imposed)
        self.free = [j for j in range(len(s.q)) if j not in imposed]
        self.imposed = sorted(imposed)
        self.g = self._gravity()
        self.free_measures = {}
        self.preloads = {}
        self.T = self._kinetic()
        self.D = self._dissipation()
        self.V = self._potential()

    # helpers ----------------------------------------------------------------------------
    def rate(self, expr):
        """d expr / dt = sum_j d expr/dq_j q_j'."""
        return sum((sp.diff(expr, q) * qd for q, qd in zip(self.s.q, self.s.qd)),
                   sp.Integer(0))

    def gradient(self, expr, indices=None):
        indices = range(len(self.s.q)) if indices is None else indices
        return [sp.diff(expr, self.s.q[j]) for j in indices]

    def _gravity(self):
        """(g_x, g_y): the symbol g along gravity's direction."""
        if self.dyn is None or self.dyn.gravity == 0:
            return (sp.Integer(0), sp.Integer(0))
        given = self.s.num(self.dyn.gravity)
        size = sp.sqrt(sum(c ** 2 for c in sp.Tuple(*given.as_real_imag())))
        if size.free_symbols:           # gravity given by parameters: their formula
            return given.as_real_imag()
        x, y = (given / size).as_real_imag()
        symbol = self.s.gravity if self.s.gravity is not None else size
        return (symbol * x, symbol * y)

    # the masses -------------------------------------------------------------------------
    def masses(self) -> list:
        """[(name, m, J, G, theta)] of every massive body, disc and point mass."""
        s, pos, out = self.s, self.positions.pos, []
        if self.dyn is None:
            return out
        for mb in self.dyn.bodies.values():
            G = self.positions.body_point(mb.body, mb.center)
            theta = self.positions.body_angle(mb.body) if mb.inertia != 0 else None
            out.append((mb.body, s.num(mb.mass), s.num(mb.inertia), G, theta))
        for disc in self.dyn.discs.values():
            out.append((disc.name, s.num(disc.mass), s.num(disc.inertia), pos[disc.center],
                        self.spin(disc)))
        for p, mass in self.dyn.masses.items():
            out.append((p, s.num(mass), sp.Integer(0), pos[p], None))
        return out

    def _kinetic(self):
        """T = 1/2 q'^T M(q) q' with M_ij = sum m (G_i . G_j) + J theta_i theta_j, as
        ``forces.lagrange`` builds it; each entry simplified on its own."""
        n = len(self.s.q)
        M = sp.zeros(n, n)
        for _, m, J, G, theta in self.masses():
            self.check()
            Gx, Gy = self.gradient(G[0]), self.gradient(G[1])
            spin = self.gradient(theta) if theta is not None and J != 0 else None
            for i in range(n):
                for j in range(i, n):
                    M[i, j] += m * (Gx[i] * Gx[j] + Gy[i] * Gy[j])
                    if spin is not None:
                        M[i, j] += J * spin[i] * spin[j]
        for i in range(n):
            for j in range(i, n):
                self.check()
                M[i, j] = M[j, i] = tidy(M[i, j])
        self.Mq = M
        return quadratic(M, self.s.qd)

    # the elements -----------------------------------------------------------------------
    def spin(self, disc):
        """A rolling disc's rotation theta = -s (x_C - x_C,figure) / R, x_C its centre along
        the floor's direction u (``forces.lagrange``: 0 in the figure)."""
        s = self.s
        guide = self.mech.bodies[disc.slider].guide
        u = sub(s.point(self.mech.fixed[guide.c]), s.point(self.mech.fixed[guide.b]))
        roll = dot(u, self.positions.pos[disc.center]) / sp.sqrt(sp.simplify(dot(u, u)))
        return -disc.side * (roll - s.at_figure(roll)) / s.num(disc.radius)

    def rotation(self, name, torque=False):
        """The rotation of body ``name`` as ``forces.lagrange`` measures it: a disc's spin
        (for the disc, and for its slider under a ``torque``), else the body's angle."""
        discs = self.dyn.discs if self.dyn is not None else {}
        disc = discs.get(name)
        if disc is None and torque and self.dyn is not None:
            disc = self.dyn.disc_on(name)
        return self.spin(disc) if disc is not None else self.positions.body_angle(name)

    def measure(self, m: el.Measure):
        """s(q) of an element: |P_b - P_a|, Re(conj(e) (P_b - P_a)) or theta_b - theta_a."""
        pos = self.positions.pos
        if m.kind == "angle":
            return self.rotation(m.b) - self.rotation(m.a)
        z = sub(pos[m.b], pos[m.a])
        if m.kind == "along":
            return dot(self.s.point(m.direction), z)
        return length(z, self.s)

    def _dissipation(self):
        """D = sum 1/2 c s'^2, s' = sum_j s_j q_j', and R_ij = sum c s_i s_j."""
        n = len(self.s.q)
        R = sp.zeros(n, n)
        D = sp.Integer(0)
        for damper in self.elements.dampers.values():
            self.check()
            grad = [tidy(x) for x in self.gradient(self.measure(damper.measure))]
            c = self.s.num(damper.coefficient)
            D += c * sum((g * qd for g, qd in zip(grad, self.s.qd)), sp.Integer(0)) ** 2 / 2
            for i in range(n):
                for j in range(i, n):
                    R[i, j] += c * grad[i] * grad[j]
        for i in range(n):
            for j in range(i, n):
                R[i, j] = R[j, i] = tidy(R[i, j])
        self.Rq = R
        return D

    def _potential(self):
        s = self.s
        terms = []
        for _, m, _, G, _ in self.masses():
            terms.append(-m * dot(self.g, G))
        for load in self.mech.loads.values():
            measure = self.load_measure(load)
            if measure is not None and load.value is not None:
                terms.append(-s.num(load.value) * measure)
        V = sum(terms, sp.Integer(0))
        springs = {}
        for spring in self.elements.springs.values():
            self.check()
            measure = self.measure(spring.measure)
            k = s.num(spring.stiffness)
            figure = s.at_figure(measure)
            if spring.mode == el.FREE:
                free = s.num(spring.value) + self._turns(spring, figure)
            elif spring.mode == el.PRELOAD:
                free = figure - s.num(spring.value) / k
            else:
                free = figure
            springs[spring.name] = (spring, measure, k, free)
        static = [n for n, (spring, *_) in springs.items() if spring.mode == el.STATIC]
        if static:
            base = V + sum((k * (m - f) ** 2 / 2 for n, (_, m, k, f) in springs.items()
                            if n not in static), sp.Integer(0))
            forces = self._static_preloads(base, [springs[n][1] for n in static], static)
            for n in static:
                spring, measure, k, free = springs[n]
                springs[n] = (spring, measure, k, free - forces[n] / k)
                self.preloads[n] = forces[n]
        terms = [tidy(t) for t in terms]
        for name, (_, measure, k, free) in springs.items():
            self.check()
            self.free_measures[name] = free
            terms.append(k * tidy(measure - free) ** 2 / 2)
        self.gradV = [sum((tidy(sp.diff(t, q)) for t in terms), sp.Integer(0)) for q in self.s.q]
        return sum(terms, sp.Integer(0))

    def _turns(self, spring, figure):
        """A torsional spring's free angle names a direction: the whole turns that put the
        figure's deflection in [-pi, pi] (``forces.lagrange``); none on a disc."""
        m = spring.measure
        discs = self.dyn.discs if self.dyn is not None else {}
        if m.kind != "angle" or m.a in discs or m.b in discs:
            return sp.Integer(0)
        value = self.s.value(figure - self.s.num(spring.value)).real
        return 2 * sp.pi * round(value / (2 * float(sp.pi)))

    def _static_preloads(self, V, measures, names) -> dict:
        """The forces N of the 'static' springs that make the figure an equilibrium:
        sum_s N_s ds/dq_i = Q_i = -dV/dq_i of the other terms, at the figure (free i)."""
        s = self.s
        unknown = sp.symbols(f"N0:{len(names)}")
        equations = []
        for i in self.free:
            q = s.q[i]
            lhs = sum((n * s.at_figure(sp.diff(m, q)) for n, m in zip(unknown, measures)),
                      sp.Integer(0))
            equations.append(sp.simplify(lhs + s.at_figure(sp.diff(V, q))))
        solutions = sp.linsolve(equations, unknown)
        if not solutions:
            raise SolveError("no preload of " + ", ".join(names) + " makes the figure an "
                             "equilibrium in symbols", file=self.mech.file)
        solution = next(iter(solutions))
        if any(x.free_symbols & set(unknown) for x in solution):
            raise SolveError("the preloads of " + ", ".join(names) + " are not determined by "
                             "equilibrium", file=self.mech.file)
        return {n: sp.simplify(x) for n, x in zip(names, solution)}

    def load_measure(self, load):
        pos = self.positions.pos
        if load.kind == "force":
            return dot(self.s.point(load.direction), pos[load.target])
        if load.kind == "torque":
            return self.rotation(load.target, torque=True)
        if load.kind == "axial":
            act = self.mech.actuators[load.target]
            return length(sub(pos[act.b], pos[act.a]), self.s)
        return None

    def forcing(self) -> list:
        """f_j(q): complex amplitudes of the generalised harmonic forces, sum A e^{i phase}
        d(Re(conj(d) P))/dq_j for a force, A e^{i phase} dtheta/dq_j for a torque."""
        s = self.s
        f = [sp.Integer(0)] * len(s.q)
        for h in self.elements.forces.values():
            if h.kind == "force":
                measure = dot(s.point(h.direction), self.positions.pos[h.target])
            else:
                measure = self.rotation(h.target, torque=True)
            phase = s.num(h.phase)
            amplitude = s.num(h.amplitude) * (sp.cos(phase) + sp.I * sp.sin(phase))
            f = [a + amplitude * g for a, g in zip(f, self.gradient(measure))]
        return f

    def frequency(self):
        value = self.elements.frequency
        return None if value is None else self.s.num(value)

    def supports(self) -> list:
        """S: complex amplitudes of the imposed coordinates."""
        s = self.s
        out = [sp.Integer(0)] * len(self.imposed)
        for sup in self.elements.supports.values():
            phase = s.num(sup.phase)
            out[self.imposed.index(sup.coordinate)] += \
                s.num(sup.amplitude) * (sp.cos(phase) + sp.I * sp.sin(phase))
        return out

    # equations of motion ----------------------------------------------------------------
    def equations(self) -> list:
        """Lagrange's equations of the free coordinates, each as its left side less its
        right side (= 0): sum_j M_ij q_j'' + sum_jk (dM_ij/dq_k - 1/2 dM_jk/dq_i) q_j' q_k'
        + dV/dq_i + sum_j R_ij q_j' - Re(f_i e^{i Omega t})."""
        s = self.s
        n = len(s.q)
        omega = self.frequency()
        forcing = self.forcing()
        M, R = self.Mq, self.Rq
        out = []
        for i in self.free:
            e = sum((M[i, j] * s.qdd[j] for j in range(n)), sp.Integer(0))
            for j in range(n):
                for k in range(n):
                    self.check()
                    c = tidy(sp.diff(M[i, j], s.q[k]) - sp.diff(M[j, k], s.q[i]) / 2)
                    e += c * s.qd[j] * s.qd[k]
            e += sum((R[i, j] * s.qd[j] for j in range(n)), sp.Integer(0)) + self.gradV[i]
            if forcing[i] != 0 and omega is not None:
                e -= tidy(sp.re(sp.expand_complex(forcing[i] * sp.exp(sp.I * omega * TIME))))
            out.append(e)
        return out

    # equilibrium and linearisation ------------------------------------------------------
    def equilibrium(self, numeric) -> Equilibrium:
        """q_e (module docstring); ``numeric`` the coordinates of the numeric equilibrium
        (SI), to choose a root and to stand for one without a formula."""
        s = self.s
        figure = dict(s.figure)
        mode = self.elements.equilibrium
        Q = [self.gradV[i] for i in self.free]
        if mode == "figure" or all(sp.simplify(s.at_figure(x)) == 0 for x in Q):
            return Equilibrium(figure, "figure", preloads=dict(self.preloads))
        unknowns = [s.q[i] for i in self.free]
        if all(sp.Poly(sp.expand(x), *unknowns).total_degree() <= 1
               for x in Q if x.is_polynomial(*unknowns)) and \
                all(x.is_polynomial(*unknowns) for x in Q):
            fixed = {q: v for q, v in figure.items() if q not in unknowns}
            solution = sp.linsolve([x.xreplace(fixed) for x in Q], unknowns)
            if solution:
                values = dict(fixed)
                values.update({q: sp.simplify(v) for q, v in
                               zip(unknowns, next(iter(solution)))})
                if all(abs(s.value(values[q]) - numeric[j]) <= 1e-9 * (1 + abs(numeric[j]))
                       for j, q in enumerate(s.q)):
                    return Equilibrium(values, "solved", preloads=dict(self.preloads))
        values, stated = dict(figure), {}
        for i in self.free:
            q = s.q[i]
            symbol = sp.Symbol(f"{q.name}_e", real=True)
            values[q] = symbol
            stated[symbol] = float(numeric[i])
        return Equilibrium(values, "numeric", stated, dict(self.preloads))

    def matrices(self, eq: Equilibrium) -> tuple:
        """(M, K, R) of the free coordinates at q_e; K = d2V/dq dq is kept whole (the
        imposed coordinates' columns enter F)."""
        s, at, free = self.s, eq.values, self.free
        n = len(s.q)
        hessian = sp.zeros(n, n)
        for i in range(n):
            for j in range(i, n):
                self.check()
                hessian[i, j] = hessian[j, i] = sp.diff(self.gradV[i], s.q[j])
        self.hessian = hessian
        return tuple(self._block(A, free, free, at) for A in (self.Mq, hessian, self.Rq))

    def _block(self, A, rows, cols, at):
        out = sp.zeros(len(rows), len(cols))
        for a in range(len(rows)):
            for b in range(len(cols)):
                self.check()
                out[a, b] = tidy(A[rows[a], cols[b]].xreplace(at))
        return out

    def load(self, eq: Equilibrium) -> list:
        """{F} = f_f - (K_fs - Omega^2 M_fs + i Omega R_fs) S at q_e (after ``matrices``)."""
        at, free, imposed = eq.values, self.free, self.imposed
        f = [tidy(x.xreplace(at)) for x in self.forcing()]
        F = [f[i] for i in free]
        if not imposed:
            return F
        omega = self.frequency() or sp.Integer(0)
        S = self.supports()
        Ks, Ms, Rs = (self._block(A, free, imposed, at) for A in (self.hessian, self.Mq,
                                                                  self.Rq))
        coupling = Ks - omega ** 2 * Ms + sp.I * omega * Rs
        return [tidy(F[a] - sum((coupling[a, b] * S[b] for b in range(len(imposed))),
                                sp.Integer(0))) for a in range(len(free))]

    def linear(self, eq: Equilibrium) -> Linear:
        """Every formula of the linearised system at once (``matrices``, ``load``,
        ``stability``, ``characteristic``)."""
        M, K, R = self.matrices(eq)
        F = self.load(eq)
        written, found = characteristic(K, M, self.check)
        return Linear([self.s.q[i].name for i in self.free], M, K, R, F, stability(K), written,
                      found)


def stability(K) -> list:
    """The leading principal minors of K, each written out (``minor``)."""
    return [minor(K[:n, :n]) for n in range(1, K.shape[0] + 1)]


def characteristic(K, M, check=None) -> tuple:
    """(det(K - omega^2 M) as a polynomial in omega^2, each coefficient tidied, its roots where
    short or None); ``forces.oscillation.characteristic`` is the numeric twin.  The
    determinant is expanded by minors in a ring of polynomials (:func:`determinant`), never
    simplified whole: the cost is that of the products.  FormulaLimit (reason 'terms') where
    it passes TERMS terms, or OPERATIONS operations once its generators are written out."""
    w2 = sp.Symbol("w2")
    det, ring = determinant(K - w2 * M, check)
    size = _operations(det, ring)
    if size > OPERATIONS:
        raise FormulaLimit(f"the characteristic polynomial is not written: it has {size} "
                           f"operations (at most {OPERATIONS} are written)", reason="terms",
                           limit=OPERATIONS, size=size, items=("characteristic",))
    coefficients = _powers_of(det, ring, w2)
    written = sum(((tidy(c) if sp.count_ops(c) <= LONG else c) * OMEGA ** (2 * p)
                   for p, c in coefficients.items()), sp.Integer(0))
    return written, roots(coefficients)


def _operations(poly, ring) -> int:
    """The operations of a ring polynomial written out: per term, one per factor and those
    of each generator (a root or a quotient is as long as its formula)."""
    cost = [1 + sp.count_ops(g) for g in ring.symbols]
    return sum(1 + sum(e * c for e, c in zip(monom, cost)) for monom in poly.keys())


def _powers_of(poly, ring, x) -> dict:
    """{p: coefficient of x^p} of a ring polynomial, as formulas."""
    gens = list(ring.symbols)
    i = gens.index(x) if x in gens else None
    parts = {}
    for monom, c in poly.terms():
        p = monom[i] if i is not None else 0
        rest = monom[:i] + (0,) + monom[i + 1:] if i is not None else monom
        parts.setdefault(p, []).append((rest, c))
    return {p: ring.to_sympy(ring.ring.from_dict(dict(terms))) for p, terms in sorted(parts.items())}


def determinant(A, check=None) -> tuple:
    """(det A, its ring) of a square matrix of formulas, expanded: its entries read as
    polynomials in their symbols and in the functions, roots and reciprocals they hold
    (sympy's generators), and

        det A = sum_j (-1)^j A_{k,j} det A[rows < k, columns S minus j]

    the minors of the first k rows on each set S of k columns computed once (sum_k C(n, k) k
    products of polynomials, no division, no simplification).  FormulaLimit (reason 'terms')
    where a minor passes TERMS terms; ``check`` is called before each product."""
    n = A.shape[0]
    polys, info = sp.parallel_poly_from_expr(list(A) or [sp.Integer(1)], expand=True)
    ring = info["domain"].poly_ring(*info["gens"])
    rows = [[ring(dict(p.as_dict())) for p in polys[i * n:(i + 1) * n]] for i in range(n)]
    minors = {(): ring.one}
    for k in range(n):
        found = {}
        for columns, below in minors.items():
            for j in range(n):
                if j in columns or not rows[k][j]:
                    continue
                if check is not None:
                    check()
                key = tuple(sorted(columns + (j,)))
                sign = -1 if sum(1 for c in columns if c > j) % 2 else 1
                term = rows[k][j] * below
                found[key] = found.get(key, ring.zero) + (term if sign > 0 else -term)
                if len(found[key]) > TERMS:
                    raise FormulaLimit(
                        f"the characteristic polynomial is not written: its expansion passes "
                        f"{TERMS} terms (a minor of {k + 1} rows)", reason="terms",
                        limit=TERMS, size=len(found[key]), items=("characteristic",))
        minors = found
    return minors.get(tuple(range(n)), ring.zero), ring


def roots(coefficients) -> list | None:
    """The roots omega^2 of the characteristic polynomial ``coefficients`` ({power: formula})
    of degree 1 or 2, where each is at most SHORT characters; None otherwise (a cubic's roots
    are not what an exam prints, nor those of coefficients longer than SHORT operations)."""
    degree = max(coefficients, default=0)
    if degree not in (1, 2) or any(sp.count_ops(c) > SHORT for c in coefficients.values()):
        return None
    a, b, c = (coefficients.get(p, sp.Integer(0)) for p in (2, 1, 0))
    if degree == 1:
        found = [tidy(-c / b)]
    else:
        discriminant = sp.expand(b ** 2 - 4 * a * c)
        if len(str(discriminant)) > 4 * SHORT:      # no short root will come of it
            return None
        root = sp.sqrt(shortest(discriminant))
        found = [sp.factor_terms(sp.together((-b + sign * root) / (2 * a))) for sign in (-1, 1)]
    return found if all(len(str(r)) <= SHORT for r in found) else None


def minor(A):
    """det A by Laplace's expansion along the first row, written out, not expanded: the
    stability condition as the exam writes it, (4kL^2 + 2mgL)(2kL^2 + mgL) - (2kL^2)^2."""
    n = A.shape[0]
    if n == 1:
        return A[0, 0]
    return sum(((-1) ** j * A[0, j] * minor(A.minor_submatrix(0, j)) for j in range(n)
                if A[0, j] != 0), sp.Integer(0))


def quadratic(A, x):
    """1/2 x^T A x, term by term."""
    n = len(x)
    return sum((A[i, j] * x[i] * x[j] * (sp.Rational(1, 2) if i == j else 1)
                for i in range(n) for j in range(i, n)), sp.Integer(0))


def tidy(expr):
    """A formula as the exam writes it: a polynomial in the parameters expanded (sums of
    products), anything with functions or roots simplified."""
    expr = sp.sympify(expr)
    if expr.has(sp.Float) or sp.count_ops(expr) > LONG:
        return expr
    if expr.is_number:
        return sp.nsimplify(expr)
    if expr.has(sp.sin, sp.cos, sp.tan):
        expr = sp.trigsimp(expr, method="fu")
    if expr.has(sp.atan2, sp.exp, sp.Abs, sp.re, sp.im) or \
            any(not p.exp.is_Integer for p in expr.atoms(sp.Pow)):
        # sympy's simplify where it is quick; a long formula with roots is left whole
        expr = sp.simplify(expr) if sp.count_ops(expr) <= BRIEF else sp.factor_terms(expr)
    if expr.is_polynomial():
        return shortest(sp.expand(expr))
    return rational(expr)


def rational(expr):
    """A quotient as the shortest of its cancelled form and the quotient plus remainder
    of its numerator's division by the denominator in each symbol of the denominator
    (M g l1 + k l1^2 l3^2/(l1^2 + l3^2))."""
    together = sp.cancel(expr)
    num, den = sp.fraction(together)
    best = sp.factor_terms(together)
    if not den.free_symbols or sp.count_ops(best) < 8:
        return best
    num, den = sp.expand(num), sp.expand(den)
    for x in sorted(den.free_symbols, key=sp.default_sort_key):
        try:
            q, r = sp.div(num, den, x)
        except (sp.PolynomialError, sp.CoercionFailed):
            continue
        if q == 0:
            continue
        candidate = shortest(sp.expand(q)) + sp.factor_terms(sp.cancel(r / den))
        if sp.count_ops(candidate) < sp.count_ops(best):
            best = candidate
    return best


def shortest(expanded):
    """A polynomial as a sum of products, or factored where that is much shorter
    ((R - r)^2 (3M/2 + m) for its six expanded terms)."""
    if not isinstance(expanded, sp.Add) or not 3 <= len(expanded.args) <= MANY:
        return expanded
    factored = sp.factor(expanded)
    return factored if sp.count_ops(factored) < 0.6 * sp.count_ops(expanded) else expanded
