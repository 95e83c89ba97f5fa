"""The equation of motion of a one-degree-of-freedom machine under given loads.

With q the driver's coordinate (rad or m) and w = q' its rate, Lagrange's equation of a
mechanism of one degree of freedom is

    J*(q) q'' + 1/2 dJ*/dq w^2 = Q(q, w, t)

    J*(q)   = sum_b m_b |G_b,q|^2 + J_b theta_b,q^2          (the reduced inertia)
    dJ*/dq  = sum_b 2 m_b Re(conj(G_b,q) G_b,qq) + 2 J_b theta_b,q theta_b,qq
    Q       = sum m Re(conj(g) G_q) - sum k (s - s0) s_q       (gravity, springs)
              + sum F Re(conj(d) P_q) h(q) + sum C theta_q h(q) + sum A l_q h(q)
              + sum_motors M(theta_q w, q, t) theta_q - sum_brakes B sgn(theta_q w) theta_q

G_q, G_qq the derivatives of every centre of mass and theta_q, theta_qq those of every
body's rotation, from the same jets of the kinematics as the vibrations' Lagrangian
(``forces.lagrange``, ``kinematics.jacobian``): the velocities at unit driver rate and
the accelerations at unit rate and zero driver acceleration.  h(q) is a load's window
(1 inside, 0 outside; model.machine).  Torques are counter-clockwise positive; a
motor's speed is its body's angular velocity theta_q w.  The generalised force of a
load is its virtual power per unit driver rate (forces.statics), so a driving torque on
the crank of a crank driver enters as itself.

Coulomb friction of ``dynamics:`` (sliders, pins, rolling resistance) depends on the
joint forces, hence on q''; it is not part of this equation and a file that has it is
refused (:func:`require_machine`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkcli.errors import InputError, SolveError
from linkcli.forces.lagrange import Lagrangian
from linkcli.kinematics import jacobian as jac
from linkcli.model.machine import in_window

#: the kinds of loads with a generalised force of their own in the machine's equation
MACHINE_LOADS = ("motor", "brake")


def require_known(mech) -> None:
    """Refuse a load left unknown where Q is asked (the motion, the reduced torque)."""
    unknown = [n for n, load in mech.loads.items() if load.value is None and load.motor is None]
    if unknown:
        raise InputError(f"load '{unknown[0]}' is unknown, and the motion under given loads "
                         "needs every load known", file=mech.file, key=f"loads.{unknown[0]}",
                         hint="give its value (a motor's characteristic, a brake's torque)")


def require_machine(mech) -> None:
    """Refuse what the machine's equation cannot take: no masses (J* = 0), Coulomb
    friction (its losses depend on the acceleration)."""
    dyn = mech.dynamics
    if dyn is None or not (dyn.bodies or dyn.masses or dyn.discs):
        raise InputError("the motion under given loads needs the masses: give them under "
                         "'dynamics:'", file=mech.file, key="dynamics",
                         hint="e.g. dynamics: {bodies: {crank: {inertia: 2, center: O}}}")
    if any(dyn.friction.values()) or any(p.radius for p in dyn.pins.values()) or any(
            d.resistance for d in dyn.discs.values()):
        raise InputError("Coulomb friction of 'dynamics:' depends on the acceleration and is "
                         "not part of the machine's equation of motion", file=mech.file,
                         key="dynamics", hint="model the losses as a 'brake' load or a motor's "
                         "characteristic, or remove the friction")


@dataclass
class Coefficients:
    """The parts of the equation at an array of driver values q (SI):
    ``J`` J*(q), ``dJ`` dJ*/dq, ``smooth`` the generalised force of gravity, springs and
    loads without a window, ``levers`` load name -> its generalised force per unit value
    (theta_q of a motor's or brake's body, the unit load's own of a windowed load)."""

    q: np.ndarray
    J: np.ndarray
    dJ: np.ndarray
    smooth: np.ndarray
    levers: dict


class Machine:
    """J*(q), dJ*/dq and Q(q, w, t) of ``mech``, from its kinematics and masses.

    Every method takes arrays (broadcast together) in SI: q in rad or m, w in rad/s or
    m/s, t in s, and returns arrays.
    """

    def __init__(self, mech, solver):
        require_machine(mech)
        self.mech = mech
        self.solver = solver
        self.lag = Lagrangian(mech, solver)
        self.angular = mech.driver.kind == "angle"
        self.windowed = [load for load in mech.loads.values()
                         if load.kind not in MACHINE_LOADS and load.window is not None]
        self.turning = [load for load in mech.loads.values() if load.kind in MACHINE_LOADS]
        elements = self.lag.elements
        self.angle_springs = [s for s in elements.springs.values() if s.measure.kind == "angle"]
        if elements.dampers or elements.forces:
            raise InputError("dampers and harmonic forces belong to a vibration problem; in "
                             "the motion of a machine give a load instead", file=mech.file,
                             key="dampers" if elements.dampers else "excitation")

    # --- the coefficients --------------------------------------------------------------
    def jet(self, q) -> jac.Jet:
        """The jet of the kinematics at driver values ``q`` (a 1-D array)."""
        return jac.jet(self.solver, np.atleast_1d(np.asarray(q, dtype=float)))

    def coefficients(self, q) -> Coefficients:
        """J*, dJ*/dq, the smooth generalised force and the loads' levers at ``q``."""
        q = np.atleast_1d(np.asarray(q, dtype=float))
        jt = self.jet(q)
        masses = self.lag.masses(jt)
        J, dJ = self._inertia(jt, masses)
        smooth = self._gravity(jt, masses) + self._springs(jt, q)
        levers = {}
        for load in self.mech.loads.values():
            c = self.lever(jt, load)
            if load.kind in MACHINE_LOADS or load.window is not None:
                levers[load.name] = c
            elif load.value is not None:
                smooth = smooth + load.value * c
        return Coefficients(q, J, dJ, smooth, levers)

    def _inertia(self, jt, masses):
        J = np.zeros(jt.shape)
        dJ = np.zeros(jt.shape)
        for m in masses:
            _, Gi, Gij = m.g
            Gq, Gqq = np.asarray(Gi)[0], np.asarray(Gij)[0, 0]
            J = J + m.mass * np.abs(Gq) ** 2
            dJ = dJ + 2 * m.mass * np.real(np.conj(Gq) * Gqq)
            if m.theta is not None and m.inertia:
                tq = np.asarray(m.theta.grad)[0]
                tqq = np.asarray(m.theta.hess)[0, 0]
                J = J + m.inertia * tq ** 2
                dJ = dJ + 2 * m.inertia * tq * tqq
        return J, dJ

    def _gravity(self, jt, masses):
        g = self.mech.dynamics.gravity
        out = np.zeros(jt.shape)
        for m in masses:
            out = out + m.mass * np.real(np.conj(g) * np.asarray(m.g[1])[0])
        return out

    def _springs(self, jt, q):
        """-sum k (s - s0) s_q; a torsional spring's angle is followed one position at a
        time from the figure (forces.lagrange), the others are arrays."""
        out = np.zeros(jt.shape)
        for spring in self.lag.elements.springs.values():
            if spring.measure.kind == "angle":
                continue
            s = self.lag.measure(jt, spring.measure, {})
            out = out - spring.stiffness * (s.value - self.lag.free[spring.name]) * s.grad[0]
        for i, qi in enumerate(q if self.angle_springs else ()):
            one = self.lag.jet(np.array([qi]), second=False)
            rotations = self.lag.rotations(np.array([qi]), one)
            for spring in self.angle_springs:
                s = self.lag.measure(one, spring.measure, rotations)
                out[i] -= spring.stiffness * (float(s.value) - self.lag.free[spring.name]) \
                    * float(np.ravel(s.grad)[0])
        return out

    def lever(self, jt, load):
        """The generalised force of a unit ``load`` (its virtual power per unit q'): a
        force's Re(conj(d) P_q), a torque's (motor's, brake's) theta_q of its body (a
        disc's spin for one on its slider), an actuator's dl/dq, 1 for the driver's load."""
        if load.kind == "force":
            return np.real(np.conj(load.direction) * jt.gradient(load.target)[0])
        if load.kind in ("torque",) + MACHINE_LOADS:
            body = self.lag.torqued(load.target)
            disc = self.lag.discs.get(body)
            s = self.lag._spin(jt, disc) if disc is not None else \
                jac.body_angle(self.mech, jt, body)
            return np.asarray(s.grad)[0] + np.zeros(jt.shape)
        if load.kind == "axial":
            act = self.mech.actuators[load.target]
            return np.asarray(jac.distance(jt, act.a, act.b).grad)[0]
        return np.ones(jt.shape)

    # --- the equation ------------------------------------------------------------------
    def inertia(self, q):
        """(J*(q), dJ*/dq) at driver values ``q``."""
        c = self.coefficients(q)
        return c.J, c.dJ

    def position_torque(self, q):
        """The part of Q that depends on q alone: gravity, springs, known loads (windows
        included); motors and brakes left out."""
        c = self.coefficients(q)
        return c.smooth + self.windowed_torque(c.q, c.levers)

    def windowed_torque(self, q, levers):
        out = np.zeros(np.shape(q))
        for load in self.windowed:
            out = out + load.value * levers[load.name] * in_window(q, load.window, self.angular)
        return out

    def turning_torque(self, q, w, t, levers):
        """Motors' M(theta_q w, q, t) theta_q and brakes' -B sgn(theta_q w) theta_q."""
        out = np.zeros(np.broadcast(q, w, t).shape)
        for load in self.turning:
            c = levers[load.name]
            if load.kind == "motor":
                out = out + load.motor.torque(c * w, q, t) * c
            else:
                out = out - load.value * np.sign(c * w) * np.abs(c)
        return out

    def torque(self, q, w, t=0.0):
        """Q(q, w, t): the generalised force of every load by virtual power."""
        require_known(self.mech)
        c = self.coefficients(q)
        return c.smooth + self.windowed_torque(c.q, c.levers) + \
            self.turning_torque(c.q, w, t, c.levers)

    def accel(self, q, w, t=0.0):
        """q'' = (Q - 1/2 dJ*/dq w^2) / J*."""
        c = self.coefficients(q)
        Q = c.smooth + self.windowed_torque(c.q, c.levers) + \
            self.turning_torque(c.q, w, t, c.levers)
        return (Q - 0.5 * c.dJ * np.asarray(w) ** 2) / c.J

    def require_inertia(self, J, q) -> None:
        """Refuse a position where the machine has no inertia reduced to q (J* <= 0)."""
        bad = np.asarray(J) <= 0
        if np.any(bad):
            where = float(np.atleast_1d(q)[np.argmax(np.atleast_1d(bad))])
            raise SolveError(f"the reduced inertia J* is zero at q = {where:.6g} (SI): nothing "
                             "with mass moves with the driver there", file=self.mech.file,
                             hint="give a mass or inertia to a body the driver moves")
