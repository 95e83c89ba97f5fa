"""Kinetic energy, potential energy and dissipation of a mechanism in its coordinates.

With the coordinates q (n of them) and the jets of every point
(``kinematics.jacobian``):

    T = 1/2 q'^T M(q) q',   M_ij = sum_b m_b Re(conj(G_i) G_j) + J_b theta_i theta_j
    V = sum_springs 1/2 k (s - s0)^2 - sum_b m_b Re(conj(g) G) - sum_loads (F.P, T theta, F l)
    D = 1/2 q'^T R(q) q',   R_ij = sum_dampers c s_i s_j

G the centre of mass of each massive body (point masses and rolling discs
included), theta its rotation, g gravity, s the measure of each element.
Differentiating V gives the generalised forces and the stiffness

    Q_i = -dV/dq_i = -sum k (s - s0) s_i + sum m Re(conj(g) G_i) + sum F Re(conj(d) P_i) ...
    K_ij = d2V/dq_i dq_j = sum [k s_i s_j + N s_ij] - sum m Re(conj(g) G_ij) - ...

with N = k (s - s0) the spring's force (tension positive): the preload and
gravity terms of K come from the Hessians.  A harmonic force F e^{i Omega t} at
P along d, or a torque C on a body, gives the forcing F Re(conj(d) P_i) or
C theta_i.  The convective terms of the equations of motion are
c_i = sum m Re(conj(G_i) sum_jk G_jk q'_j q'_k) + J theta_i sum_jk theta_jk q'_j q'_k,
so that M q'' + c + R q' = Q + forcing is Lagrange's equation.

Rotations.  A body's angle is measured continuously from the figure: its value
at the figure is the drawn one, and at any other configuration it is followed
along the straight path from the nearest configuration already measured (the
figure, or the last one), so a rod that turns past 180 deg keeps turning
instead of jumping by a turn.  A torsional spring's free angle names a
direction, written in any range: it is taken a whole number of turns from the
figure's relative angle so that the figure's deflection lies in [-180, 180]
deg.  A rolling disc turns by theta = -s (x_C - x_C,figure) / R (x_C its centre
along the floor's direction u, s its side), 0 in the figure.  A torque (constant
or harmonic) on a disc's slider acts on the spinning disc (the block slides on a
fixed guide and cannot take it); a torsional element names the disc or the block.

Its twin in formulas is ``forces.symbolic``: the same terms from the same model, T, V and D
written in the parameters (``--symbolic``); ``tests/test_roundtrip_symbolic.py`` puts the
numbers into those formulas and finds these matrices.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from linkcli.errors import SolveError
from linkcli.kinematics import jacobian as jac
from linkcli.model import elements as el
from linkcli.model.mechanism import FRAME

#: a rotation is followed from a measured configuration in steps that move every coordinate
#: by at most STEP of its scale (1 rad; the mechanism's size) and turn every body by less
#: than a quarter turn; at most FOLLOW positions are solved for one configuration
STEP = math.pi / 4
FOLLOW = 256


@dataclass
class Mass:
    """One massive body at a configuration: centre G (with derivatives) and rotation."""

    name: str
    mass: float
    inertia: float
    g: tuple            # (G, [G_i], {(i, j): G_ij})
    theta: jac.Scalar | None


@dataclass
class Terms:
    """The Lagrangian's terms at one configuration (SI; matrices n x n)."""

    q: np.ndarray
    M: np.ndarray
    K: np.ndarray
    R: np.ndarray
    Q: np.ndarray                 # generalised forces -dV/dq
    V: float
    forces: dict                  # spring name -> force N = k (s - s0) (tension > 0)
    measures: dict                # element name -> jac.Scalar
    masses: list
    jet: jac.Jet
    rotations: dict               # body name -> jac.Scalar, measured from the figure


class Lagrangian:
    """The energies of ``mech`` as functions of its coordinates.

    ``free`` holds each spring's free measure s0 (SI), fixed from the figure
    when the spring is unstretched or preloaded there; springs whose preload is
    chosen for equilibrium ('static') get theirs from ``forces.equilibrium``.
    ``scales`` is each coordinate's scale: 1 rad for an angle, the mechanism's
    size for a length.
    """

    def __init__(self, mech, solver):
        self.mech = mech
        self.solver = solver
        self.n = len(mech.coordinates)
        self.elements = mech.elements or el.Elements()
        self.dyn = mech.dynamics
        self.figure = np.array([c.value for c in mech.coordinates], dtype=float)
        points = np.array(mech.figure_points)
        self.size = float(np.max(np.abs(points - points.mean()))) or 1.0   # m
        self.scales = np.array([1.0 if c.kind == "angle" else self.size
                                for c in mech.coordinates])
        self.discs = dict(self.dyn.discs) if self.dyn is not None else {}
        self.rotating = self._rotating()
        self.turning = sorted(self.rotating - set(self.discs) - {FRAME})
        figure = self.jet(self.figure, second=False)
        self._rolled = {d.name: float(self._roll(figure, d).value) for d in self.discs.values()}
        raw = {b: float(jac.body_angle(mech, figure, b).value) for b in self.turning}
        self._anchors = [(self.figure.copy(), raw)]
        rotations = self.rotations(self.figure, figure)
        self.free: dict = {}
        for spring in self.elements.springs.values():
            s = float(self.measure(figure, spring.measure, rotations).value)
            if spring.mode == el.FREE:
                self.free[spring.name] = self._free_measure(spring, s)
            elif spring.mode == el.PRELOAD:
                self.free[spring.name] = s - spring.value / spring.stiffness
            else:           # unstretched; 'static' until its preload is solved
                self.free[spring.name] = s

    def _rotating(self) -> set:
        """The bodies whose rotation an element or a load acts through."""
        out = set()
        for e in list(self.elements.springs.values()) + list(self.elements.dampers.values()):
            if e.measure.kind == "angle":
                out |= {e.measure.a, e.measure.b}
        torques = [h.target for h in self.elements.forces.values() if h.kind == "torque"]
        torques += [load.target for load in self.mech.loads.values() if load.kind == "torque"]
        return out | {self.torqued(name) for name in torques}

    def torqued(self, name) -> str:
        """The body a torque on ``name`` turns: the disc whose slider ``name`` is, or itself."""
        disc = self.dyn.disc_on(name) if self.dyn is not None else None
        return name if disc is None else disc.name

    def _free_measure(self, spring, s) -> float:
        """s0 of a spring given its free measure: a torsional spring's free angle is a
        direction, taken the whole number of turns from the figure's angle s that puts the
        figure's deflection in [-pi, pi] (a disc's turn is not a direction: kept as given)."""
        m = spring.measure
        if m.kind != "angle" or m.a in self.discs or m.b in self.discs:
            return spring.value
        return spring.value + 2 * math.pi * round((s - spring.value) / (2 * math.pi))

    # kinematics -------------------------------------------------------------------------
    def jet(self, q, second=True) -> jac.Jet:
        q = np.asarray(q, dtype=float)
        return jac.jet(self.solver, self._solver_q(q), second=second)

    def _solver_q(self, q):
        return q[0] if self.n == 1 else tuple(q)

    def _roll(self, jt, disc) -> jac.Scalar:
        """x_C: the disc's centre along its floor's direction u."""
        guide = self.mech.bodies[disc.slider].guide
        u = self.mech.fixed[guide.c] - self.mech.fixed[guide.b]
        return jac.along(jt, None, disc.center, u / abs(u))

    def _spin(self, jt, disc) -> jac.Scalar:
        """The disc's rotation theta = -s (x_C - x_C,figure) / R (rolling: omega = -s v / R)."""
        roll = self._roll(jt, disc)
        k = -disc.side / disc.radius
        return jac.Scalar(k * (roll.value - self._rolled.get(disc.name, 0.0)),
                          k * roll.grad, k * roll.hess)

    def rotations(self, q, jt) -> dict:
        """The rotation of every body an element or load acts through, at coordinates ``q``
        whose jet is ``jt``: measured continuously from the figure (a disc's is its spin)."""
        out = {}
        for name in self.rotating:
            disc = self.discs.get(name)
            out[name] = self._spin(jt, disc) if disc is not None else \
                jac.body_angle(self.mech, jt, name)
        if self.turning:
            raw = {b: float(out[b].value) for b in self.turning}
            for b, value in self._follow(np.asarray(q, dtype=float), raw).items():
                out[b].value = value
        return out

    def _follow(self, q, raw) -> dict:
        """The continuous rotations at ``q`` (raw values ``raw`` in (-pi, pi]), followed from
        the nearest configuration measured so far."""
        start, known = min(self._anchors, key=lambda a: self._distance(a[0], q))
        budget = [FOLLOW]
        values = self._walk(start, known, q, raw, budget)
        self._anchors[1:] = [(q.copy(), values)]
        return values

    def _distance(self, a, b) -> float:
        return float(np.max(np.abs(a - b) / self.scales)) if self.n else 0.0

    def _walk(self, qa, known, qb, raw, budget) -> dict:
        """Rotations at ``qb`` from those ``known`` at ``qa``: each body turns by the raw
        change brought into (-pi, pi], over steps short enough that no body turns by a quarter
        turn or more (halved until they are)."""
        turn = {b: (raw[b] - known[b] + math.pi) % (2 * math.pi) - math.pi for b in known}
        if self._distance(qa, qb) <= STEP and all(abs(t) < math.pi / 2 for t in turn.values()):
            return {b: known[b] + turn[b] for b in known}
        budget[0] -= 1
        if budget[0] < 0:
            raise SolveError("the bodies' rotations cannot be followed from the figure to "
                             "this configuration: they turn by a quarter turn or more over "
                             f"steps of 1/{FOLLOW} of the way", file=self.mech.file,
                             hint="draw the figure nearer the equilibrium")
        mid = 0.5 * (qa + qb)
        kin = self.solver.positions(self._solver_q(mid))
        self.solver.check(kin, velocities=False)
        halfway = {}
        for b in known:
            _, (a, c), local = jac.body_axis(self.mech, b)
            halfway[b] = float(np.angle(complex(np.ravel(kin.pos[c] - kin.pos[a])[0]))) - local
        known = self._walk(qa, known, mid, halfway, budget)
        return self._walk(mid, known, qb, raw, budget)

    def measure(self, jt, m: el.Measure, rotations) -> jac.Scalar:
        if m.kind == "distance":
            if np.any(jt.pos[m.a] == jt.pos[m.b]):
                raise SolveError(f"an element between {m.a} and {m.b} has no direction: the two "
                                 "points coincide", file=self.mech.file,
                                 hint="check the points' positions and the element's ends")
            return jac.distance(jt, m.a, m.b)
        if m.kind == "along":
            return jac.along(jt, m.a, m.b, m.direction)
        a, b = rotations[m.a], rotations[m.b]
        return jac.Scalar(b.value - a.value, b.grad - a.grad, b.hess - a.hess)

    def lever(self, jt, m: el.Measure, rotations) -> np.ndarray:
        """Per coordinate, how fast the element's ends move per unit rate: |P_a,i| + |P_b,i|
        (|theta_a,i| + |theta_b,i| for a torsional element), the most its measure's rate
        s_i can be.  An element whose s_i is a small fraction of this is carried rigidly."""
        if m.kind == "angle":
            a, b = rotations[m.a], rotations[m.b]
            return np.abs(a.grad) + np.abs(b.grad)
        return np.abs(jt.gradient(m.a)) + np.abs(jt.gradient(m.b))

    def masses(self, jt) -> list:
        out = []
        if self.dyn is None:
            return out
        for mb in self.dyn.bodies.values():
            out.append(Mass(mb.body, mb.mass, mb.inertia,
                            jac.body_point(self.mech, jt, mb.body, mb.center),
                            jac.body_angle(self.mech, jt, mb.body)))
        for disc in self.dyn.discs.values():
            out.append(Mass(disc.name, disc.mass, disc.inertia, jac.point(jt, disc.center),
                            self._spin(jt, disc)))
        for p, mass in self.dyn.masses.items():
            out.append(Mass(p, mass, 0.0, jac.point(jt, p), None))
        return out

    # the terms --------------------------------------------------------------------------
    def terms(self, q) -> Terms:
        """M, K, R, Q and V at the coordinates ``q`` (one configuration, SI)."""
        q = np.asarray(q, dtype=float)
        jt = self.jet(q)
        rotations = self.rotations(q, jt)
        n = self.n
        M, K, R = (np.zeros((n, n)) for _ in range(3))
        Q = np.zeros(n)
        V = 0.0
        masses = self.masses(jt)
        g = self.dyn.gravity if self.dyn is not None else 0j
        for m in masses:            # arrays over the coordinates: one NumPy step per body
            G, Gi, Gij = m.g
            Q += m.mass * np.real(np.conj(g) * Gi)
            M += m.mass * np.real(np.outer(np.conj(Gi), Gi))
            K -= m.mass * np.real(np.conj(g) * Gij)
            if m.theta is not None:
                M += m.inertia * np.outer(m.theta.grad, m.theta.grad)
            V -= m.mass * float(np.real(np.conj(g) * G))
        measures, forces = {}, {}
        for spring in self.elements.springs.values():
            s = measures[spring.name] = self.measure(jt, spring.measure, rotations)
            stretch = float(s.value - self.free[spring.name])
            force = spring.stiffness * stretch
            forces[spring.name] = float(force)
            V += 0.5 * force * stretch
            Q -= force * s.grad
            K += spring.stiffness * np.outer(s.grad, s.grad) + force * s.hess
        for damper in self.elements.dampers.values():
            s = measures[damper.name] = self.measure(jt, damper.measure, rotations)
            R += damper.coefficient * np.outer(s.grad, s.grad)
        V += self._loads(jt, rotations, Q, K)
        if not all(np.all(np.isfinite(x)) for x in (M, K, R, Q, V)):
            raise SolveError("the energies are not finite numbers at this configuration: the "
                             "data overflow floating-point arithmetic", file=self.mech.file,
                             hint="check the magnitudes of masses, stiffnesses and lengths")
        return Terms(q, M, K, R, Q, V, forces, measures, masses, jt, rotations)

    def _loads(self, jt, rotations, Q, K) -> float:
        """Add the constant loads of ``loads:`` (V = -work) to Q and K; returns their V."""
        V = 0.0
        for load in self.mech.loads.values():
            s = self.load_measure(jt, load, rotations)
            if s is None or load.value is None:
                continue
            V -= load.value * float(s.value)
            Q += load.value * np.asarray(s.grad, dtype=float)
            K -= load.value * np.asarray(s.hess, dtype=float)
        return V

    def load_measure(self, jt, load, rotations) -> jac.Scalar | None:
        """The measure a load works through: P along d, the body's rotation (a disc's spin
        for a torque on it or on its slider), the actuator's length."""
        if load.kind == "force":
            return jac.along(jt, None, load.target, load.direction)
        if load.kind == "torque":
            return rotations[self.torqued(load.target)]
        if load.kind == "axial":
            act = self.mech.actuators[load.target]
            return jac.distance(jt, act.a, act.b)
        return None

    def load_lever(self, jt, load, rotations) -> np.ndarray:
        """|P_i| of a force's point, |theta_i| of a torque's body, the actuator's ends' speeds."""
        if load.kind == "force":
            return np.abs(jt.gradient(load.target))
        if load.kind == "torque":
            return np.abs(np.asarray(rotations[self.torqued(load.target)].grad, dtype=float))
        act = self.mech.actuators[load.target]
        return self.lever(jt, el.Measure("distance", act.a, act.b), rotations)

    def forcing(self, jt) -> np.ndarray:
        """Complex amplitudes of the generalised harmonic forces, sum F e^{i phase} Re(conj(d) P_i)
        and C e^{i phase} theta_i (theta a disc's spin for a torque on it or on its slider)."""
        f = np.zeros(self.n, dtype=complex)
        for h in self.elements.forces.values():
            if h.kind == "force":
                s = jac.along(jt, None, h.target, h.direction)
            elif self.torqued(h.target) in self.discs:
                s = self._spin(jt, self.discs[self.torqued(h.target)])
            else:
                s = jac.body_angle(self.mech, jt, h.target)
            f += h.amplitude * np.exp(1j * h.phase) * np.asarray(s.grad, dtype=float)
        return f

    def convective(self, terms: Terms, qd) -> np.ndarray:
        """c_i = sum m Re(conj(G_i) a0_G) + J theta_i alpha0, with a0 = sum_jk G_jk q'_j q'_k."""
        qd = np.asarray(qd, dtype=float)
        c = np.zeros(self.n)
        for m in terms.masses:
            _, Gi, Gij = m.g
            a0 = qd @ Gij @ qd
            c += m.mass * np.real(np.conj(Gi) * a0)
            if m.theta is not None:
                c += m.inertia * m.theta.grad * (qd @ m.theta.hess @ qd)
        return c

    def potential(self, q) -> float:
        """V alone, from positions only (no rates): for checks of K by differences."""
        q = np.asarray(q, dtype=float)
        kin = self.solver.positions(self._solver_q(q))
        self.solver.check(kin, velocities=False)
        jt = jac.Jet(kin.pos, n=self.n)         # positions only: zero derivatives
        rotations = self.rotations(q, jt)
        V = 0.0
        g = self.dyn.gravity if self.dyn is not None else 0j
        for m in self.masses(jt):
            V -= m.mass * float(np.real(np.conj(g) * m.g[0]))
        for spring in self.elements.springs.values():
            s = float(self.measure(jt, spring.measure, rotations).value)
            V += 0.5 * spring.stiffness * (s - self.free[spring.name]) ** 2
        for load in self.mech.loads.values():
            s = self.load_measure(jt, load, rotations)
            if s is not None and load.value is not None:
                V -= load.value * float(s.value)
        return V


def energy_units(A, scales):
    """D A D, D = diag(``scales``) (1 rad for an angle, the mechanism's size for a length):
    a matrix of the coordinates (M, K, R) whose entries mix kg with kg m^2 (N/m with N m)
    brought to one unit, so that its entries compare whatever the length unit."""
    d = np.asarray(scales, float)
    return A * (d[:, None] * d[None, :])


def require_mass(mech, M, free, scales) -> None:
    """Refuse a mass matrix that is not positive definite on the free coordinates,
    naming the coordinate that carries no mass.

    The test is made on D M D, D = diag(``scales``) (1 rad for an angle, the mechanism's
    size for a length): every entry then has one unit (kg m^2), so that the smallest
    eigenvalue compares with the largest diagonal entry whatever the length unit; M itself
    mixes kg (lengths) with kg m^2 (angles), and a small mechanism's inertias would read as
    no mass against its translations' masses."""
    Mf = energy_units(M[np.ix_(free, free)], np.asarray(scales, float)[free])
    values, vectors = np.linalg.eigh(Mf)
    scale = max(float(np.max(np.abs(np.diag(Mf)))), 1e-300)
    if values[0] <= 1e-12 * scale:
        index = free[int(np.argmax(np.abs(vectors[:, 0])))]
        name = mech.coordinates[index].name
        raise SolveError(f"coordinate {name} carries no mass: the mass matrix is singular "
                         f"(smallest eigenvalue {values[0]:.3g} against {scale:.3g}, in kg m^2 "
                         "of the coordinates made dimensionless by the mechanism's size)",
                         file=mech.file, hint=f"give a mass or inertia to a body that moves "
                         f"with {name}, or make {name} an imposed coordinate")
