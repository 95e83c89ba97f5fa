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
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkcli.errors import SolveError
from linkcli.kinematics import jacobian as jac
from linkcli.model import elements as el


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


class Lagrangian:
    """The energies of ``mech`` as functions of its coordinates.

    ``free`` holds each spring's free measure s0 (SI), fixed from the figure
    when the spring is unstretched or preloaded there; springs whose preload is
    chosen for equilibrium ('static') get theirs from ``forces.equilibrium``.
    """

    def __init__(self, mech, solver):
        self.mech = mech
        self.solver = solver
        self.n = len(mech.coordinates)
        self.elements = mech.elements or el.Elements()
        self.dyn = mech.dynamics
        self.figure = np.array([c.value for c in mech.coordinates], dtype=float)
        points = np.array(list(mech.fixed.values()) + list(mech.moving.values()))
        self.size = float(np.max(np.abs(points - points.mean()))) or 1.0   # m
        self.free: dict = {}
        figure = self.jet(self.figure, second=False)
        for spring in self.elements.springs.values():
            s = float(self.measure(figure, spring.measure).value)
            if spring.mode == el.FREE:
                self.free[spring.name] = spring.value
            elif spring.mode == el.PRELOAD:
                self.free[spring.name] = s - spring.value / spring.stiffness
            else:           # unstretched; 'static' until its preload is solved
                self.free[spring.name] = s

    # kinematics -------------------------------------------------------------------------
    def jet(self, q, second=True) -> jac.Jet:
        q = np.asarray(q, dtype=float)
        return jac.jet(self.solver, q[0] if self.n == 1 else tuple(q), second=second)

    def measure(self, jt, m: el.Measure) -> jac.Scalar:
        if m.kind == "distance":
            if np.any(jt.pos[m.a] == jt.pos[m.b]):
                raise SolveError(f"an element between {m.a} and {m.b} has no direction: the two "
                                 "points coincide", file=self.mech.file,
                                 hint="check the points' positions and the element's ends")
            return jac.distance(jt, m.a, m.b)
        if m.kind == "along":
            return jac.along(jt, m.a, m.b, m.direction)
        a, b = jac.body_angle(self.mech, jt, m.a), jac.body_angle(self.mech, jt, m.b)
        return jac.Scalar(b.value - a.value, b.grad - a.grad, b.hess - a.hess)

    def masses(self, jt) -> list:
        out = []
        if self.dyn is None:
            return out
        for mb in self.dyn.bodies.values():
            out.append(Mass(mb.body, mb.mass, mb.inertia,
                            jac.body_point(self.mech, jt, mb.body, mb.center),
                            jac.body_angle(self.mech, jt, mb.body)))
        for disc in self.dyn.discs.values():
            guide = self.mech.bodies[disc.slider].guide
            u = self.mech.fixed[guide.c] - self.mech.fixed[guide.b]
            u = u / abs(u)
            roll = jac.along(jt, None, disc.center, u)
            k = -disc.side / disc.radius      # omega = -s (v_C . u) / R
            spin = jac.Scalar(k * roll.value, k * roll.grad, k * roll.hess)
            out.append(Mass(disc.name, disc.mass, disc.inertia, jac.point(jt, disc.center),
                            spin))
        for p, mass in self.dyn.masses.items():
            out.append(Mass(p, mass, 0.0, jac.point(jt, p), None))
        return out

    # the terms --------------------------------------------------------------------------
    def terms(self, q) -> Terms:
        """M, K, R, Q and V at the coordinates ``q`` (one configuration, SI)."""
        q = np.asarray(q, dtype=float)
        jt = self.jet(q)
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
            s = measures[spring.name] = self.measure(jt, spring.measure)
            force = spring.stiffness * (s.value - self.free[spring.name])
            forces[spring.name] = float(force)
            V += 0.5 * spring.stiffness * float(s.value - self.free[spring.name]) ** 2
            Q -= force * s.grad
            K += spring.stiffness * np.outer(s.grad, s.grad) + force * s.hess
        for damper in self.elements.dampers.values():
            s = measures[damper.name] = self.measure(jt, damper.measure)
            R += damper.coefficient * np.outer(s.grad, s.grad)
        V += self._loads(jt, Q, K)
        if not all(np.all(np.isfinite(x)) for x in (M, K, R, Q)):
            raise SolveError("the energies are not finite numbers at this configuration: the "
                             "data overflow floating-point arithmetic", file=self.mech.file,
                             hint="check the magnitudes of masses, stiffnesses and lengths")
        return Terms(q, M, K, R, Q, V, forces, measures, masses, jt)

    def _loads(self, jt, Q, K) -> float:
        """Add the constant loads of ``loads:`` (V = -work) to Q and K; returns their V."""
        V = 0.0
        for load in self.mech.loads.values():
            s = self.load_measure(jt, load)
            if s is None or load.value is None:
                continue
            V -= load.value * float(s.value)
            Q += load.value * np.asarray(s.grad, dtype=float)
            K -= load.value * np.asarray(s.hess, dtype=float)
        return V

    def load_measure(self, jt, load) -> jac.Scalar | None:
        """The measure a load works through: P along d, the body's angle, the actuator's length."""
        if load.kind == "force":
            return jac.along(jt, None, load.target, load.direction)
        if load.kind == "torque":
            return jac.body_angle(self.mech, jt, load.target)
        if load.kind == "axial":
            act = self.mech.actuators[load.target]
            return jac.distance(jt, act.a, act.b)
        return None

    def forcing(self, jt) -> np.ndarray:
        """Complex amplitudes of the generalised harmonic forces, sum F e^{i phase} Re(conj(d) P_i)
        and C e^{i phase} theta_i."""
        f = np.zeros(self.n, dtype=complex)
        for h in self.elements.forces.values():
            if h.kind == "force":
                s = jac.along(jt, None, h.target, h.direction)
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
        kin = self.solver.positions(q[0] if self.n == 1 else tuple(q))
        pos = kin.pos
        jt = jac.Jet(pos, n=self.n)             # positions only: zero derivatives
        V = 0.0
        g = self.dyn.gravity if self.dyn is not None else 0j
        for m in self.masses(jt):
            V -= m.mass * float(np.real(np.conj(g) * m.g[0]))
        for spring in self.elements.springs.values():
            s = float(self.measure(jt, spring.measure).value)
            V += 0.5 * spring.stiffness * (s - self.free[spring.name]) ** 2
        for load in self.mech.loads.values():
            s = self.load_measure(jt, load)
            if s is not None and load.value is not None:
                V -= load.value * float(s.value)
        return V


def require_mass(mech, M, free) -> None:
    """Refuse a mass matrix that is not positive definite on the free coordinates,
    naming the coordinate that carries no mass."""
    Mf = M[np.ix_(free, free)]
    values, vectors = np.linalg.eigh(Mf)
    scale = max(float(np.max(np.abs(np.diag(Mf)))), 1e-300)
    if values[0] <= 1e-12 * scale:
        index = free[int(np.argmax(np.abs(vectors[:, 0])))]
        name = mech.coordinates[index].name
        raise SolveError(f"coordinate {name} carries no mass: the mass matrix is singular "
                         f"(smallest eigenvalue {values[0]:.3g} against {scale:.3g})",
                         file=mech.file, hint=f"give a mass or inertia to a body that moves "
                         f"with {name}, or make {name} an imposed coordinate")
