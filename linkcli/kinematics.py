"""Positions, velocities and accelerations along the solving order.

Every constraint of a dyad is a quadratic form ``g(X) = 0`` in the point
coordinates (and q).  Differentiating once and twice in time gives, for the
dyad's unknown point P,

    Re(conj(G_i) dP/dt)   = -rate_i(X, V)                      (velocity)
    Re(conj(G_i) d2P/dt2) = -rate_i(X, A) - curv_i(V)           (acceleration)

with ``G_i`` the gradient of g_i with respect to P, ``rate_i`` the part of
dg_i/dt linear in the known rates, and ``curv_i = 2 B_i(V, V)`` the quadratic
(centripetal and Coriolis) part.  Both are 2x2 linear systems solved by
Cramer's rule on whole arrays of positions at once.  ``measure`` is
``|det| / (|G_1| |G_2|)``, the sine of the angle between the two constraint
normals: 0 at a toggle (dead point), 1 when best conditioned; it does not
depend on the length unit.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import dyads
from .dyads import cross
from .errors import AssemblyError, SingularError
from .topology import Coord, Dist, Line, analyse

SINGULAR = 1e-9


@dataclass
class Kinematics:
    """Positions (and rates) of every point, complex arrays in SI units."""

    q: np.ndarray
    qd: np.ndarray | None = None
    qdd: np.ndarray | None = None
    pos: dict = field(default_factory=dict)
    vel: dict = field(default_factory=dict)
    acc: dict = field(default_factory=dict)
    short: dict = field(default_factory=dict)     # group index -> shortfall (m) array
    measure: dict = field(default_factory=dict)   # group index -> conditioning array


class Solver:
    """Closed-form solver of one mechanism along its Assur decomposition."""

    def __init__(self, mech):
        self.mech = mech
        self.topology = analyse(mech)
        self.groups = self.topology.groups
        self.fixed = dict(mech.fixed)
        self._choose_branches()

    # branches ------------------------------------------------------------------
    def _choose_branches(self):
        """Pick each dyad's assembly branch nearest to the figure's positions."""
        pos = dict(self.fixed)
        q = np.asarray(self.mech.driver.value, dtype=float)
        for group in self.groups:
            if group.kind in ("RRR", "RRP", "PRR", "RPR"):
                target = self.mech.moving[group.point]
                best = None
                for branch in (1, -1):
                    group.branch = branch
                    p, _ = self._position(group, pos, q)
                    dist = abs(complex(p) - target)
                    if best is None or dist < best[0]:
                        best = (dist, branch)
                group.branch = best[1]
            if group.point is not None:
                pos[group.point] = self._position(group, pos, q)[0]

    # positions -------------------------------------------------------------------
    def _position(self, group, pos, q):
        kind = group.kind
        if kind == "place":
            k, m, n, w = group.place
            return pos[k] + (pos[m] - pos[n]) * w, None
        if kind == "driver-angle":
            pivot, length, reverse = group.constraints
            return pos[pivot] + (-length if reverse else length) * np.exp(1j * q), None
        if kind == "driver-coord":
            line, coord = group.constraints
            u, e = dyads.line_frame(pos[line.b], pos[line.c], line.value)
            if coord.axis == "x":
                p, parallel = dyads.line_line(pos[line.b], u, e, q + 0j, 1j, 0.0)
            else:
                p, parallel = dyads.line_line(pos[line.b], u, e, 1j * q, 1.0 + 0j, 0.0)
            return p, np.where(parallel, np.inf, 0.0)
        c1, c2 = group.constraints
        if kind == "RRR":
            return dyads.circle_circle(pos[c1.a], self._length(c1, q), pos[c2.a],
                                       self._length(c2, q), group.branch)
        if kind in ("RRP", "PRR"):
            dist, line = (c1, c2) if kind == "RRP" else (c2, c1)
            return dyads.circle_line(pos[dist.a], self._length(dist, q), pos[line.b],
                                     pos[line.c], line.value, group.branch)
        if kind == "PRP":
            u1, e1 = dyads.line_frame(pos[c1.b], pos[c1.c], c1.value)
            u2, e2 = dyads.line_frame(pos[c2.b], pos[c2.c], c2.value)
            p, parallel = dyads.line_line(pos[c1.b], u1, e1, pos[c2.b], u2, e2)
            return p, np.where(parallel, np.inf, 0.0)
        if kind == "RPR":
            return dyads.slotted(pos[c1.a], c1.length, pos[c2.p], c2.value, group.branch)
        return None, None

    @staticmethod
    def _length(dist, q):
        return q if dist.length is None else dist.length

    def positions(self, q) -> Kinematics:
        q = np.asarray(q, dtype=float)
        kin = Kinematics(q)
        pos = kin.pos
        pos.update(self.fixed)
        for index, group in enumerate(self.groups):
            if group.point is None:
                continue
            p, short = self._position(group, pos, q)
            pos[group.point] = p
            if short is not None:
                kin.short[index] = short
        return kin

    # rates ---------------------------------------------------------------------
    def velocities(self, kin: Kinematics, qd) -> Kinematics:
        kin.qd = np.asarray(qd, dtype=float)
        for index, group in enumerate(self.groups):
            if group.point is None:
                continue
            kin.vel[group.point] = self._rate(index, group, kin, kin.vel, kin.qd, None)
        return kin

    def accelerations(self, kin: Kinematics, qdd) -> Kinematics:
        kin.qdd = np.asarray(qdd, dtype=float)
        for index, group in enumerate(self.groups):
            if group.point is None:
                continue
            kin.acc[group.point] = self._rate(index, group, kin, kin.acc, kin.qdd, kin.vel)
        return kin

    def _rate(self, index, group, kin, d, qrate, vel):
        """First (vel None) or second time derivative of the group's point."""
        pos = kin.pos
        if group.kind == "place":
            k, m, n, w = group.place
            return _get(d, k) + (_get(d, m) - _get(d, n)) * w
        if group.kind == "driver-angle":
            pivot = group.constraints[0]
            arm = pos[group.point] - pos[pivot]
            if vel is None:
                return _get(d, pivot) + 1j * qrate * arm
            return _get(d, pivot) + (1j * qrate - kin.qd ** 2) * arm
        p = group.point
        g, r = [], []
        for c in group.constraints:
            g.append(_grad(c, pos, p))
            rhs = -_rate_known(c, pos, d, kin.q, qrate)
            if vel is not None:
                rhs = rhs - _curv(c, vel, kin.qd)
            r.append(rhs)
        det = cross(g[0], g[1])
        if vel is None:
            kin.measure[index] = np.abs(det) / (np.abs(g[0]) * np.abs(g[1]))
        safe = np.where(det == 0, 1.0, det)
        vx = (r[0] * g[1].imag - r[1] * g[0].imag) / safe
        vy = (g[0].real * r[1] - g[1].real * r[0]) / safe
        return vx + 1j * vy

    # failures ------------------------------------------------------------------
    def check(self, kin: Kinematics, velocities: bool):
        """Raise when a group cannot be assembled or (for rates) is singular."""
        q_unit, q_factor = self.mech.units.display(_driver_base(self.mech), 0)
        l_unit, l_factor = self.mech.units.display("length", 0)
        for index, short in kin.short.items():
            bad = np.broadcast_to(short > 0, kin.q.shape) if np.ndim(short) else short > 0
            if np.any(bad):
                group = self.groups[index]
                worst = float(np.max(np.where(bad, short, 0.0)))
                where = _q_text(kin.q, bad, q_factor, q_unit)
                amount = "are parallel" if not np.isfinite(worst) else \
                    f"fall short by {worst / l_factor:.4g} {l_unit}"
                raise AssemblyError(
                    f"cannot assemble {group.describe()} {where}: the links {amount}",
                    file=self.mech.file, group=group.describe(), q=kin.q, shortfall=worst,
                    hint="check the lengths and the driver value")
        if not velocities:
            return
        for index, measure in kin.measure.items():
            bad = measure < SINGULAR
            if np.any(bad):
                group = self.groups[index]
                where = _q_text(kin.q, np.broadcast_to(bad, kin.q.shape), q_factor, q_unit)
                raise SingularError(
                    f"singular position (toggle or dead point) of {group.describe()} {where}: "
                    f"conditioning {float(np.min(measure)):.2e} (sine of the angle between its "
                    "constraint directions); velocities are undefined there",
                    file=self.mech.file, group=group.describe(), q=kin.q,
                    measure=float(np.min(measure)), hint="move the driver away from the toggle")


def _driver_base(mech) -> str:
    return "angle" if mech.driver.kind == "angle" else "length"


def _q_text(q, bad, factor, unit) -> str:
    values = np.atleast_1d(q)[np.atleast_1d(bad)] / factor
    if values.size <= 1:
        value = float(values[0]) if values.size else float(np.atleast_1d(q)[0] / factor)
        return f"at q = {value:.6g} {unit}"
    return f"for q in [{values.min():.6g}, {values.max():.6g}] {unit} ({values.size} positions)"


def _get(d, name):
    return d.get(name, 0.0)


def _grad(c, pos, unknown):
    """Gradient of constraint ``c`` with respect to point ``unknown`` (complex)."""
    if isinstance(c, Dist):
        return 2.0 * (pos[c.p] - pos[c.a])
    if isinstance(c, Line):
        if unknown == c.p:
            return 1j * (pos[c.c] - pos[c.b])
        return -1j * (pos[c.p] - pos[c.b])
    return 1.0 + 0j if c.axis == "x" else 1j


def _rate_known(c, pos, d, q, qrate):
    """Part of dg/dt (or d2g/dt2 without curvature) linear in the known rates ``d``."""
    if isinstance(c, Dist):
        value = 2.0 * (np.conj(pos[c.p] - pos[c.a]) * (_get(d, c.p) - _get(d, c.a))).real
        return value - 2.0 * q * qrate if c.length is None else value
    if isinstance(c, Line):
        db = _get(d, c.b)
        return cross(_get(d, c.c) - db + 0j, pos[c.p] - pos[c.b]) + \
            cross(pos[c.c] - pos[c.b], _get(d, c.p) - db + 0j)
    value = _get(d, c.p) + 0j
    return (value.real if c.axis == "x" else value.imag) - qrate


def _curv(c, vel, qd):
    """Quadratic part 2 B(V, V) of d2g/dt2."""
    if isinstance(c, Dist):
        value = 2.0 * np.abs(_get(vel, c.p) - _get(vel, c.a)) ** 2
        return value - 2.0 * qd ** 2 if c.length is None else value
    if isinstance(c, Line):
        vb = _get(vel, c.b)
        return 2.0 * cross(_get(vel, c.c) - vb + 0j, _get(vel, c.p) - vb + 0j)
    return 0.0


def residuals(solver: Solver, kin: Kinematics) -> dict:
    """Closure residual of every dyad constraint (m^2 for distances), for tests."""
    out = {}
    pos = kin.pos
    for index, group in enumerate(solver.groups):
        for j, c in enumerate(group.constraints if group.is_dyad or group.kind == "driver-coord"
                              else ()):
            if isinstance(c, Dist):
                length = kin.q if c.length is None else c.length
                value = np.abs(pos[c.p] - pos[c.a]) ** 2 - length ** 2
            elif isinstance(c, Line):
                value = cross(pos[c.c] - pos[c.b], pos[c.p] - pos[c.b]) - c.value
            else:
                p = pos[c.p]
                value = (p.real if c.axis == "x" else p.imag) - kin.q
            out[(index, j)] = value
    return out
