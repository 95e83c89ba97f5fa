"""The Newton-Euler equations of a mechanism, stacked over the driver values.

Rows: for every moving body (d'Alembert form, moments about the body's first point O)

    sum F + m (g - a_G) = 0,      sum (r - O) x F + M - J alpha = 0,

and for every pin p (a massless point where bodies meet; point masses and forces
applied at p act on it)

    - sum_b R_pb + F_p + m_p (g - a_p) = 0.

Columns (unknowns): ``R_pb``, the force pin p exerts on body b (x, y; the frame
included at fixed pivots); the two forces of each sliding pair or rolling contact
(``pairs``); the one force of each contact of ``rolling:`` / ``cords:`` (the friction of
a disc on what it rolls on, a cord's tension: ``pairs.contact_actions``); the one
unknown load.  Grübler's count n = 1 makes the system square:
A x = -b, with column j of A the terms per unit unknown j and b the known terms
(known loads, gravity, inertia forces and torques).

The losses (``friction``) add terms proportional to the contact forces: the friction
T = (T/N) N along a slider's guide in the column of its N, the rolling resistance
couple M = (M/N) N on a disc in the column of its N, and at a pin with a friction
circle the couple M = -rho sgn(omega_rel) e . R on the body whose eye turns on the
pin (and -M on the body the pin is fixed in) in the columns of R's x and y.
"""
from __future__ import annotations

import math

import numpy as np

from linkcli.errors import SingularError
from linkcli.forces import motion as dyn_mod
from linkcli.kinematics.dyads import cross
from linkcli.model.mechanism import FRAME
from linkcli.forces.pairs import actuator_axis, contact_actions, located_pairs, unit


#: a dimensionless condition number above COND_LIMIT is a singular position
COND_LIMIT = 1e12


class System:
    """Rows, columns and terms of the Newton-Euler equations at the positions of ``kin``.

    A term is added to a vector over the rows (shape + (rows,)): a column of A or b.
    """

    def __init__(self, mech, dyn, kin):
        self.mech, self.dyn, self.kin = mech, dyn, kin
        self.pos = kin.pos
        self.shape = np.shape(kin.q)
        self.bodies = list(mech.bodies)
        self.pin_bodies = _pin_bodies(mech)
        self.rows, self.n_rows = _rows(self.bodies, self.pin_bodies)
        self.pairs = located_pairs(mech, dyn, kin.pos)
        self.pair = dict(self.pairs)
        self.columns = _columns(self.pin_bodies, self.pairs, mech.rolling,  # (kind, key, part)
                                _unknown_keys(mech))
        self.index = {c: i for i, c in enumerate(self.columns)}
        self.length = _length_scale(mech, self.pos)

    # --- forces and moments ---------------------------------------------------------
    def new(self):
        """A zero vector over the rows."""
        return np.zeros(self.shape + (self.n_rows,))

    def _add_force(self, vec, row, force):
        """Add a force's x and y to rows ``row`` and ``row + 1``; return it as an array."""
        force = np.broadcast_to(force + 0j, self.shape)
        vec[..., row] += force.real
        vec[..., row + 1] += force.imag
        return force

    def body_force(self, vec, body, force, at):
        """Force F applied at ``at`` on ``body``: F and (at - O) x F (nothing on the frame)."""
        if body == FRAME:
            return
        r = self.rows[body]
        origin = self.pos[self.mech.bodies[body].points[0]]
        force = self._add_force(vec, r, force)
        vec[..., r + 2] += np.broadcast_to(cross(at - origin + 0j, force), self.shape)

    def body_moment(self, vec, body, moment):
        """Moment (counter-clockwise positive) on ``body`` (nothing on the frame)."""
        if body != FRAME:
            vec[..., self.rows[body] + 2] += np.broadcast_to(moment, self.shape)

    def pin_force(self, vec, point, force):
        """Force on pin ``point``; a fixed point of no body is held by the frame (no rows)."""
        if ("pin", point) in self.rows:
            self._add_force(vec, self.rows[("pin", point)], force)

    def axial(self, vec, act, value):
        """Axial force ``value`` of an actuator, pushing its ends apart: +u on the rod,
        -u on the cylinder, at the rod's end."""
        u, at = actuator_axis(act, self.pos)
        self.body_force(vec, act.name + ".rod", u * value, at)
        self.body_force(vec, act.name + ".cylinder", -u * value, at)

    # --- loads ----------------------------------------------------------------------
    def apply_load(self, vec, load, value):
        """Add the effect of ``load`` with ``value`` (SI) to ``vec``."""
        mech = self.mech
        if load.kind == "force":
            self.pin_force(vec, load.target, load.direction * value)
        elif load.kind == "torque":
            target = load.target + ".cylinder" if load.target in mech.actuators else load.target
            self.body_moment(vec, target, value)
        elif load.kind == "axial":
            self.axial(vec, mech.actuators[load.target], value)
        else:
            self.driver_load(vec, value, _driver_of(mech, load))

    def driver_load(self, vec, value, d=None):
        """The load conjugate to the driver q (or ``d``, one of several): a torque on the
        crank (angle), a force along q (length: pushing the ends apart), or a force along x
        or y (coordinate)."""
        d = self.mech.driver if d is None else d
        if d.kind == "angle":
            self.body_moment(vec, _crank(self.mech, d), value)
        elif d.kind == "length":
            self._length_driver_load(vec, value, d)
        else:
            self.pin_force(vec, d.a, (1.0 if d.kind == "x" else 1j) * value)

    def _length_driver_load(self, vec, value, d):
        act = next((a for a in self.mech.actuators.values() if {a.a, a.b} == {d.a, d.b}), None)
        if act is not None:        # q = |AB| either way: Q pushes the ends apart
            self.axial(vec, act, value)
            return
        u = unit(self.pos[d.b] - self.pos[d.a])
        self.pin_force(vec, d.b, u * value)
        self.pin_force(vec, d.a, -u * value)

    # --- the matrix A and the known terms b ---------------------------------------------
    def matrix(self, losses):
        """A (shape + (rows, columns)): column j holds the equations' terms per unit unknown j.

        ``losses`` (``friction.Losses``) gives each slider's T/N = -mu sgn(v_rel) s, each
        disc's M/N = -u_r sgn(omega) s (s the assumed sign of N) and each friction circle's
        couple per unit component of R.
        """
        a = np.zeros(self.shape + (self.n_rows, len(self.columns)))
        for j, column in enumerate(self.columns):
            a[..., :, j] = self.column(column, losses)
        return a

    def column(self, column, losses):
        """Terms of a unit value of one unknown: x (part 0) or y (part 1) of a pin force,
        a pair's first or second force, or the unknown load."""
        kind, key, part = column
        vec = self.new()
        if kind == "pin":
            p, b = key
            force = 1.0 if part == 0 else 1j
            self.body_force(vec, b, force, self.pos[p])
            self.pin_force(vec, p, -force)
            couple = losses.pin_factor(p, b, part)
            if couple is not None:           # the friction circle: M on b, -M on the holder
                self.body_moment(vec, b, couple)
                self.body_moment(vec, losses.pins[p].holder, -couple)
        elif kind == "pair":
            factor = losses.disc_factor(key) if self.pair[key].kind == "disc" \
                else losses.slider_factor(key)
            self.pair_column(vec, self.pair[key], part, factor)
        elif kind == "contact":
            for target, force, at in contact_actions(self.mech, self.mech.rolling[key],
                                                     self.pos):
                if isinstance(target, tuple):
                    self.pin_force(vec, target[1], force)
                else:
                    self.body_force(vec, target, force, at)
        else:                   # the unknown load (by its name with several drivers)
            load = self.mech.unknown_load() if key is None else self.mech.loads[key]
            self.apply_load(vec, load, 1.0)
        return vec

    def pair_column(self, vec, pf, part, fcoef):
        """Disc: T = 1 along u (part 0) or N = 1 along n (part 1) at the contact, with the
        rolling resistance couple fcoef (M/N) on the disc.  Slider, actuator: N = 1 along n
        with its friction fcoef (T/N) along u (part 0), or M = 1 (part 1); on the moving
        part, the opposite on the carrier."""
        if pf.kind == "disc":
            self.body_force(vec, pf.on, pf.u if part == 0 else pf.n, pf.at)
            if part == 1:
                self.body_moment(vec, pf.on, fcoef)
        elif part == 0:
            force = pf.n + fcoef * pf.u
            self.body_force(vec, pf.on, force, pf.at)
            self.body_force(vec, pf.carrier, -force, pf.at)
        else:
            self.body_moment(vec, pf.on, 1.0)
            self.body_moment(vec, pf.carrier, -1.0)

    def known(self):
        """b: the known loads, gravity and the inertia terms (A x = -b)."""
        vec = self.new()
        for load in self.mech.loads.values():
            if load.value is not None:
                self.apply_load(vec, load, load.value)
        if self.dyn is not None:
            self._mass_terms(vec)
        return vec

    def _mass_terms(self, vec):
        """m (g - a_G) at G and -J alpha on every body and rolling disc (a disc's on its
        block); m_p (g - a_p) on the pin of every point mass."""
        mech, dyn, kin = self.mech, self.dyn, self.kin
        for mb in dyn.bodies.values():
            g, _, acc = dyn_mod.rigid_point(mech, mb.body, mb.center, kin.pos, kin.vel, kin.acc)
            _, alpha = dyn_mod.rotation(mech, mb.body, kin.pos, kin.vel, kin.acc)
            self._inertia(vec, mb.body, mb.mass, mb.inertia, g, acc, alpha)
        for disc in dyn.discs.values():
            _, alpha = dyn_mod.disc_spin(mech, disc, kin.pos, kin.vel, kin.acc)
            acc = kin.acc.get(disc.center, 0.0)
            self._inertia(vec, disc.slider, disc.mass, disc.inertia, kin.pos[disc.center], acc,
                          alpha)
        for p, mass in dyn.masses.items():
            self.pin_force(vec, p, mass * (dyn.gravity - kin.acc.get(p, 0.0)))

    def _inertia(self, vec, body, mass, inertia, g, acc, alpha):
        """d'Alembert force m (g - a_G) at G and torque -J alpha on ``body``."""
        self.body_force(vec, body, mass * (self.dyn.gravity - acc), g)
        self.body_moment(vec, body, -inertia * alpha)

    # --- scaling ------------------------------------------------------------------------
    def scales(self):
        """Row and column scales making A dimensionless: moment rows / L, moment columns * L
        (L the mechanism's size)."""
        rows = np.ones(self.n_rows)
        for b in self.bodies:
            rows[self.rows[b] + 2] = 1.0 / self.length
        cols = np.array([self.length if self._is_moment(c) else 1.0 for c in self.columns])
        return rows, cols

    def _is_moment(self, column):
        kind, key, part = column
        if kind == "pair":
            return part == 1 and self.pair[key].kind != "disc"
        return kind == "unknown" and _unknown_is_moment(
            self.mech, None if key is None else self.mech.loads[key])

    def value(self, x, column):
        """The solution's component for ``column`` at every driver value."""
        return x[..., self.index[column]]

    # --- solving --------------------------------------------------------------------------
    def scaled(self, a):
        """R A C with the row and column scales R, C (:meth:`scales`): dimensionless."""
        rows, cols = self.scales()
        return a * rows[:, None] * cols[None, :]

    def solve(self, a, rhs, check=True):
        """x from (R A C) y = R rhs, x = C y at every driver value (:meth:`solve_scaled`)."""
        return self.solve_scaled(self.scaled(a), rhs, check)

    def solve_scaled(self, scaled, rhs, check=True):
        """x from the scaled matrix R A C: (R A C) y = R rhs, x = C y; ``check`` refuses a
        singular matrix (:meth:`require_regular`), else an exactly singular one is solved as
        the identity (its x is no answer: the caller leaves it out)."""
        rows, cols = self.scales()
        if check:
            self.require_regular(scaled)
        try:
            y = np.linalg.solve(scaled, (rhs * rows)[..., None])[..., 0]
        except np.linalg.LinAlgError:
            scaled = np.where(self.regular(scaled)[..., None, None], scaled,
                              np.eye(scaled.shape[-1]))
            y = np.linalg.solve(scaled, (rhs * rows)[..., None])[..., 0]
        return y * cols

    def regular(self, scaled):
        """At each driver value: whether the scaled matrix is finite and not singular to
        rounding (its determinant's magnitude at least eps; the entries are of order 1)."""
        sign, logdet = self._slogdet(scaled)
        return (sign != 0) & (logdet > math.log(np.finfo(float).eps))

    def side(self, scaled):
        """The sign of det (R A C) at every driver value (0 where singular or not finite):
        which side of a singular A the matrix is on."""
        return self._slogdet(scaled)[0]

    @staticmethod
    def _slogdet(scaled):
        """(sign, log |det|) of each matrix, (0, -inf) where one is not finite."""
        finite = np.all(np.isfinite(scaled), axis=(-2, -1))
        if finite.all():
            return np.linalg.slogdet(scaled)
        sign, logdet = np.linalg.slogdet(np.where(finite[..., None, None], scaled,
                                                  np.eye(scaled.shape[-1])))
        return np.where(finite, sign, 0.0), np.where(finite, logdet, -np.inf)

    def require_regular(self, scaled):
        """Refuse non-finite matrices and condition numbers above ``COND_LIMIT``."""
        if not np.all(np.isfinite(scaled)):
            raise SingularError("the reactions are undefined here (non-finite geometry)",
                                file=self.mech.file)
        cond = np.linalg.cond(scaled)
        if np.any(~np.isfinite(cond) | (cond > COND_LIMIT)):
            worst = float(np.max(np.where(np.isfinite(cond), cond, np.inf)))
            raise SingularError(
                "the joint reactions are not determined at this position (the Newton-Euler "
                f"system is singular: dimensionless condition number {worst:.2e})",
                file=self.mech.file, measure=1.0 / worst if worst > 0 else 0.0,
                hint="a toggle position, or a structure whose forces are statically "
                "indeterminate")


def _crank(mech, d=None) -> str:
    """The link carrying both points of an angle driver (``d``, default the driver)."""
    d = mech.driver if d is None else d
    return next(b.name for b in mech.bodies.values()
                if b.kind == "link" and d.a in b.points and d.b in b.points)


def _unknown_is_moment(mech, load=None) -> bool:
    load = mech.unknown_load() if load is None else load
    return load.kind == "torque" or (load.kind == "driver" and
                                     _driver_of(mech, load).kind == "angle")


def _driver_of(mech, load):
    """The driver a driver load acts on: the one of several its ``target`` names, else q's."""
    return next((c for c in mech.coordinates if c.name == load.target), mech.driver)


def _unknown_keys(mech) -> list:
    """The keys of the unknown loads' columns: None for the one unknown of one driver, each
    unknown's name with several drivers (one per driver)."""
    if len(mech.coordinates) > 1 and mech.elements is None:
        return [load.name for load in mech.unknown_loads()]
    return [None]


def _pin_bodies(mech) -> dict:
    """Point -> bodies meeting there (frame first at fixed pivots); points on moving bodies only."""
    out = {}
    for body in mech.bodies.values():
        for p in body.points:
            out.setdefault(p, []).append(body.name)
    return {p: ([FRAME] if p in mech.fixed else []) + out[p] for p in sorted(out)}


def _rows(bodies, pin_bodies):
    """First row of every body (x, y, moment) and pin (x, y), and the number of rows."""
    rows, row = {}, 0
    for b in bodies:
        rows[b] = row
        row += 3
    for p in pin_bodies:
        rows[("pin", p)] = row
        row += 2
    return rows, row


def _columns(pin_bodies, pairs, contacts=(), unknowns=(None,)) -> list:
    """(kind, key, part) of every unknown: pin forces, pair forces, the contacts' forces,
    the unknown load (one per driver, by name, with several: ``unknowns``)."""
    columns = []
    for p, bodies in pin_bodies.items():
        for b in bodies:
            columns += [("pin", (p, b), 0), ("pin", (p, b), 1)]
    for name, _ in pairs:
        columns += [("pair", name, 0), ("pair", name, 1)]
    columns += [("contact", name, 0) for name in contacts]
    columns += [("unknown", key, 0) for key in unknowns]
    return columns


def _length_scale(mech, pos) -> float:
    """The mechanism's size: the largest distance of a point from the first one (m)."""
    first = pos[mech.points[0]]
    scale = max(float(np.max(np.abs(np.asarray(pos[p] - first)))) for p in mech.points)
    return scale if scale > 0 else 1.0
