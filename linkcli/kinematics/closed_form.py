"""Positions along the solving order: the closed-form solver of one mechanism.

The groups of the Assur decomposition (``assur``) are solved in order, each from the points
placed before it, on whole arrays of coordinate values at once (points are complex
x + i y in SI units, angles counter-clockwise from +x):

- a crank driven by coordinate q: P = pivot + L e^{i q} (-L when the driving vector runs
  from P to the pivot);
- a slider driven by x (or y) = q: P on its guide, cross(C - B, P - B) = value;
- a point placed rigidly on a body whose pose is known: P = K + (M - N) w;
- a dyad: its point on two constraints, |P - A| = L or cross(C - B, P - B) = value
  (``groups``), in closed form (``dyads``), on the assembly branch +1/-1 chosen once from
  the figure (``branches``);
- a disc's second point, turned by a contact (``turns``).

Each group gives its shortfall (m: > 0 where it cannot close, inf where its lines are
parallel, ``refusals``) and, for a dyad, where it is a toggle within rounding (``flat``).
The velocities and accelerations follow along the same order (``rates``).

Its twin in formulas is ``kinematics.symbolic``: the same groups in the same order, each
point a formula of the coordinates and the parameters, and a linkage's closure equations
with their rate systems.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from linkcli.errors import InputError
from linkcli.kinematics import branches, dyads
from linkcli.kinematics.assur import analyse
from linkcli.kinematics.contacts import Track
from linkcli.kinematics.dyads import cross
from linkcli.kinematics.groups import Dist, Line
from linkcli.kinematics.rates import DriverRates, DyadRates, place_rate
from linkcli.kinematics.refusals import (SINGULAR, assembly_error, exceeds, length_text,
                                         singular_error, under)
from linkcli.kinematics.turns import roll_position, turn_rate


@dataclass
class Kinematics:
    """Positions (and rates) of every point, complex arrays in SI units.

    ``q``, ``qd``, ``qdd`` are the first coordinate (the driver) and its rates;
    ``coords``, ``rates``, ``accels`` hold every coordinate's, in order.
    """

    q: np.ndarray
    qd: np.ndarray | None = None
    qdd: np.ndarray | None = None
    coords: tuple = ()
    rates: tuple = ()
    accels: tuple = ()
    pos: dict = field(default_factory=dict)
    vel: dict = field(default_factory=dict)
    acc: dict = field(default_factory=dict)
    short: dict = field(default_factory=dict)     # group index -> shortfall (m) array, where
    #                                               some position might not close
    measure: dict = field(default_factory=dict)   # group index -> conditioning array
    flat: dict = field(default_factory=dict)      # group index -> toggle within rounding
    linear: dict = field(default_factory=dict, repr=False)  # group index -> rate-system inverse
    #                                                          (a driver's: its arm P - pivot)
    vectors: dict = field(default_factory=dict, repr=False)  # (a, b) -> (z, z'/z) for reports

    def __post_init__(self):
        if not self.coords:
            self.coords = (self.q,)

    def at_rest(self):
        """The same positions with no rates yet (for velocities per unit rate)."""
        return Kinematics(self.q, pos=self.pos, coords=self.coords)

    @property
    def shape(self) -> tuple:
        """The shape of the positions: every coordinate's broadcast together."""
        return np.broadcast_shapes(*(np.shape(c) for c in self.coords)) if self.coords \
            else np.shape(self.q)


class Solver:
    """Closed-form solver of one mechanism along its Assur decomposition."""

    def __init__(self, mech):
        self.mech = mech
        self.topology = analyse(mech)
        self.groups = self.topology.groups
        self.fixed = dict(mech.fixed)
        self.n = len(mech.coordinates)
        self._frames = {}               # fixed guides: (B, C, value) -> (u, e), found once
        branches.choose(self)
        #: (point, rate step) of every group that solves a point, in the solving order
        self._rates = [(g.point, self._rate_step(i, g)) for i, g in enumerate(self.groups)
                       if g.point is not None]

    # positions -------------------------------------------------------------------
    def _position(self, group, pos, q, turns=None):
        """(P, shortfall, ...) of the group's point; ``turns`` collects the discs' turns
        (``turns.roll_position``), which contacts solved later read."""
        kind = group.kind
        if kind == "roll":
            return roll_position(self.mech, group, pos, q, turns), None
        if kind == "place":
            k, m, n, w = group.place
            return pos[k] + (pos[m] - pos[n]) * w, None
        if kind == "driver-angle":        # P = pivot + L e^{i q}, written into one array
            pivot, length, reverse = group.constraints
            p = dyads.cis(q[group.coord])
            base = pos[pivot]
            if not dyads.writable(p, base):
                return base + (-length if reverse else length) * p, None
            p *= -length if reverse else length
            if not dyads.is_number(base, 0.0):     # nothing to add about the origin
                p += base
            return p, None
        if kind == "driver-coord":
            line, coord = group.constraints
            value = q[coord.coord]
            u, e = dyads.line_frame(pos[line.b], pos[line.c], line.value)
            if coord.axis == "x":
                p, parallel = dyads.line_line(pos[line.b], u, e, value + 0j, 1j, 0.0)
            else:
                p, parallel = dyads.line_line(pos[line.b], u, e, 1j * value, 1.0 + 0j, 0.0)
            return p, np.where(parallel, np.inf, 0.0)
        c1, c2 = group.constraints
        if kind == "RRR":
            return dyads.circle_circle(pos[c1.a], self._length(c1, q), pos[c2.a],
                                       self._length(c2, q), group.branch, flat=True)
        if kind in ("RRP", "PRR"):
            dist, line = (c1, c2) if kind == "RRP" else (c2, c1)
            b, c, value = _guide_of(line, pos, q, turns)
            return dyads.circle_line(pos[dist.a], self._length(dist, q), b, c, value,
                                     group.branch, flat=True, frame=self._frame(line))
        if kind in ("PRP", "RPP"):         # a point on two lines (RPP: module assur)
            b1, g1, v1 = _guide_of(c1, pos, q, turns)
            b2, g2, v2 = _guide_of(c2, pos, q, turns)
            u1, e1 = dyads.line_frame(b1, g1, v1)
            u2, e2 = dyads.line_frame(b2, g2, v2)
            p, parallel = dyads.line_line(b1, u1, e1, b2, u2, e2)
            return p, np.where(parallel, np.inf, 0.0)
        if kind == "RPR":
            return dyads.slotted(pos[c1.a], c1.length, pos[c2.p], c2.value, group.branch,
                                 flat=True)
        return None, None

    def _frame(self, line):
        """The (u, e) of a line whose points are fixed (kept), None for a moving one."""
        if isinstance(line, Track):
            return None
        key = (line.b, line.c, line.value)
        frame = self._frames.get(key)
        if frame is None and line.b in self.fixed and line.c in self.fixed:
            frame = self._frames[key] = dyads.line_frame(self.fixed[line.b],
                                                         self.fixed[line.c], line.value)
        return frame

    @staticmethod
    def _length(dist, q):
        return q[dist.coord] if dist.length is None else dist.length

    def _coords(self, q, what) -> tuple:
        """Every coordinate as a float array: ``q`` itself with one coordinate, else a
        sequence of ``n`` values or arrays (they broadcast together)."""
        if self.n == 1:
            return (np.asarray(q, dtype=float),)
        if np.ndim(q) == 0 or len(q) != self.n:
            raise InputError(f"{what}: give one value (or array) per coordinate, "
                             f"{self.n} in all", file=self.mech.file, key="coordinates",
                             hint="in the order of 'coordinates': " +
                             ", ".join(c.name for c in self.mech.coordinates))
        return tuple(np.asarray(x, dtype=float) for x in q)

    def positions(self, q) -> Kinematics:
        """Every point at coordinate value(s) ``q`` (SI): one array, or one per coordinate."""
        qs = self._coords(q, "q")
        kin = Kinematics(qs[0], coords=qs)
        q = qs
        pos = kin.pos
        pos.update(self.fixed)
        turns = {}
        for index, group in enumerate(self.groups):
            if group.point is None:
                continue
            p, short, *flat = self._position(group, pos, q, turns)
            pos[group.point] = p
            if short is not None and (type(short) is not float or short != 0.0):
                kin.short[index] = short        # (the number 0.0: every position closes)
            if flat and flat[0] is not False and flat[0].any():
                kin.flat[index] = flat[0]
        return kin

    # rates ---------------------------------------------------------------------
    def velocities(self, kin: Kinematics, qd) -> Kinematics:
        """Velocities of every point for coordinate rate(s) ``qd``, as ``q`` in positions."""
        kin.rates = self._coords(qd, "qdot")
        kin.qd = kin.rates[0]
        kin.vel.clear()
        kin.vectors.clear()
        vel, rates = kin.vel, kin.rates
        for point, step in self._rates:
            vel[point] = step(kin, vel, rates, None)
        return kin

    def accelerations(self, kin: Kinematics, qdd, keep=False) -> Kinematics:
        """Accelerations of every point for coordinate acceleration(s) ``qdd`` and the
        velocities already on ``kin``; ``keep`` keeps the rate systems for another call."""
        kin.accels = self._coords(qdd, "qddot")
        kin.qdd = kin.accels[0]
        kin.acc.clear()
        acc, accels, vel = kin.acc, kin.accels, kin.vel
        for point, step in self._rates:
            acc[point] = step(kin, acc, accels, vel)
        if not keep:
            kin.linear.clear()          # rates done: free the cached systems
        return kin

    def _rate_step(self, index, group):
        """The function step(kin, d, qrate, vel) giving the first (``vel`` None) or second
        time derivative of the group's point (``rates``, ``turns``), chosen once per group."""
        if group.kind == "driver-angle":
            return DriverRates(index, group, self.fixed)
        if group.kind == "place":
            return lambda kin, d, qrate, vel: place_rate(group, d)
        if group.kind == "roll":
            return lambda kin, d, qrate, vel: turn_rate(group, kin, d, qrate, vel)
        return DyadRates(index, group, self.fixed)

    def rate_system(self, index, kin, order):
        """The 2x2 rate system of dyad ``index`` as solved at ``kin`` (rates of ``order``
        1 or 2 already on ``kin``): (G_1, G_2, r_1, r_2, P') with Re(conj(G_i) P') = r_i,
        for the worked solution."""
        group = self.groups[index]
        system = DyadRates(index, group, self.fixed)
        g1, g2 = (g(kin.pos) if callable(g) else g for g in system.grads)
        d = dict(kin.vel if order == 1 else kin.acc)
        solved = d.pop(group.point)
        rates = kin.rates if order == 1 else kin.accels
        vel = None if order == 1 else kin.vel
        r1, r2 = (rhs(g, kin, d, rates, vel) for rhs, g in zip(system.rhs, (g1, g2)))
        return g1, g2, r1, r2, solved

    # failures ------------------------------------------------------------------
    def _where(self, kin: Kinematics):
        """The driver values a refusal names: q, or every driver's (a tuple) when the file
        has several."""
        several = self.n > 1 and self.mech.elements is None
        return tuple(kin.coords) if several else kin.q

    def check(self, kin: Kinematics, velocities: bool):
        """Raise when a group cannot be assembled or (for rates) is singular."""
        for index, short in kin.short.items():
            if not exceeds(short, 0.0):    # the common case, decided on the array as it is
                continue
            bad = short > 0
            bad = np.broadcast_to(bad, kin.shape) if np.ndim(short) else bad
            if np.any(bad):
                worst = float(np.max(np.where(bad, short, 0.0)))
                reason = "the links are parallel" if not np.isfinite(worst) else \
                    f"the links fall short by {length_text(self.mech, worst)}"
                raise assembly_error(self.mech, self.groups[index], self._where(kin), bad,
                                     worst, reason)
        if not velocities:
            return
        for index, measure in kin.measure.items():
            if under(measure, SINGULAR):
                bad = measure < SINGULAR
                raise singular_error(self.mech, self.groups[index], self._where(kin),
                                     np.broadcast_to(bad, kin.shape), measure,
                                     "sine of the angle between its constraint directions")


def unit_rates(solver, kin: Kinematics, j: int = 0) -> Kinematics:
    """The velocities at ``kin``'s positions for a unit rate of coordinate ``j`` and the
    others at rest: dP/dq_j, the virtual-power coefficients of driver j (any solver)."""
    one = np.ones(kin.shape)
    n = len(solver.mech.coordinates)
    if n == 1:
        return solver.velocities(kin.at_rest(), one)
    return solver.velocities(kin.at_rest(), tuple(one if i == j else 0.0 * one
                                                  for i in range(n)))


def _guide_of(c, pos, q, turns=None):
    """(B, C, value) of a dyad's line: a guide's points, or a contact's line (Track)."""
    if isinstance(c, Track):
        return c.line(pos, q, turns)
    return pos[c.b], pos[c.c], c.value


def residuals(solver: Solver, kin: Kinematics) -> dict:
    """Closure residual of every dyad constraint (m^2 for distances), for tests."""
    out = {}
    pos = kin.pos
    for index, group in enumerate(solver.groups):
        for j, c in enumerate(group.constraints if group.is_dyad or group.kind == "driver-coord"
                              else ()):
            if isinstance(c, Dist):
                length = kin.coords[c.coord] if c.length is None else c.length
                value = np.abs(pos[c.p] - pos[c.a]) ** 2 - length ** 2
            elif isinstance(c, Line):
                value = cross(pos[c.c] - pos[c.b], pos[c.p] - pos[c.b]) - c.value
            elif isinstance(c, Track):
                value = c.relation.residual(pos, kin.coords)
            else:
                p = pos[c.p]
                value = (p.real if c.axis == "x" else p.imag) - kin.coords[c.coord]
            out[(index, j)] = value
    return out
