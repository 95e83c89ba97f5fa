"""Velocities and accelerations of the points, along the solving order.

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

A crank driven by coordinate q_j: P' = i q_j' (P - pivot) + pivot',
P'' = (i q_j'' - q_j'^2) (P - pivot) + pivot''.  A placed point P = K + (M - N) w:
P' = K' + (M' - N') w, the same for P''.  A disc turned by a contact: ``turns``.
Rates are counter-clockwise positive.  At a toggle within rounding (``flat``) the measure is
0 whatever the noise in det says; a det of exactly 0 is divided by 1 instead (no inf), its
measure 0: ``check`` then names the position (``refusals``).
"""
from __future__ import annotations

import numpy as np

from linkcli.kinematics import dyads
from linkcli.kinematics.contacts import Track
from linkcli.kinematics.dyads import cross
from linkcli.kinematics.groups import Coord, Dist, Line


class DriverRates:
    """P' = i q' (P - pivot) + pivot', P'' = (i q'' - q'^2) (P - pivot) + pivot'' of a
    crank driven by coordinate ``j``; the arm P - pivot is kept for the second rates."""

    def __init__(self, index, group, fixed):
        self.index, self.point, self.j = index, group.point, group.coord
        self.pivot = group.constraints[0]
        self.moving = self.pivot not in fixed

    def __call__(self, kin, d, qrate, vel):
        arm = kin.linear.get(self.index)
        if arm is None:
            centre = kin.pos[self.pivot]
            point = kin.pos[self.point]     # about a fixed pivot at the origin: P itself
            arm = kin.linear[self.index] = point if dyads.is_number(centre, 0.0) \
                and type(point) is np.ndarray else point - centre
        j = self.j
        if vel is None:
            rate = arm * (1j * _number(qrate[j]))
        else:               # w * w: a float's ** raises where it overflows, * gives inf
            w = _number(kin.rates[j])
            rate = arm * (1j * _number(qrate[j]) - w * w)
        if not self.moving or self.pivot not in d:
            return rate
        if dyads.writable(rate, d[self.pivot]):
            rate += d[self.pivot]
            return rate
        return d[self.pivot] + rate


def _number(x):
    """A 0-d array as a Python float (its arithmetic with numbers costs no array call)."""
    return float(x) if type(x) is np.ndarray and not x.ndim else x


class DyadRates:
    """The 2x2 rate system Re(conj(G_i) P') = r_i of a dyad (or a coordinate driver),
    see the module's docstring, with what its constraints' kinds and fixed points decide
    worked out once: each right-hand side (:func:`_rhs_of`) and the gradients' constant
    norms (:func:`constant_norms`)."""

    def __init__(self, index, group, fixed):
        self.index, self.group = index, group
        self.norms = constant_norms(group, fixed)
        self.rhs = tuple(_rhs_of(c, group.point, fixed) for c in group.constraints)
        self.grads = tuple(_grad_of(c, group.point, fixed) for c in group.constraints)

    def __call__(self, kin, d, qrate, vel):
        k1, k2, g1, g2 = self.inverse(kin)
        f1, f2 = self.rhs
        return _combine(f1(g1, kin, d, qrate, vel), k1, f2(g2, kin, d, qrate, vel), k2)

    def inverse(self, kin):
        """The system solved once per position: V = r_1 K_1 + r_2 K_2 with
        K_1 = -i G_2 / det, K_2 = i G_1 / det and det = cross(G_1, G_2); (K_1, K_2, G_1, G_2)
        are kept on ``kin.linear``, the conditioning on ``kin.measure``."""
        index = self.index
        lin = kin.linear.get(index)
        if lin is not None:
            return lin
        pos = kin.pos
        g1, g2 = (g(pos) if callable(g) else g for g in self.grads)
        x1, y1, x2, y2 = g1.real, g1.imag, g2.real, g2.imag
        det = x1 * y2
        det -= y1 * x2                  # cross(G_1, G_2), in real parts
        norms = self.norms
        if norms is None:
            norms = np.abs(g1) * np.abs(g2)      # hypot: no underflow of tiny guides
            if not _least(norms) > 0:       # a zero or NaN: divide those by 1
                norms = np.where(norms > 0, norms, 1.0)
        measure = np.abs(det)
        measure /= norms
        if type(det) is np.ndarray:
            if not measure.min() != 0:      # a zero det (NaN is not): divide those by 1
                det = np.where(det == 0, 1.0, det)
        elif det == 0:
            det = 1.0
        if index in kin.flat:           # a toggle within rounding: singular, whatever
            measure = np.where(kin.flat[index], 0.0, measure)   # the noise in det says
        kin.measure[index] = measure
        inv = 1.0 / det
        minus = -inv                    # -x inv = x (-inv), exactly
        shape = np.shape(det)
        k1, k2 = np.empty(shape, complex), np.empty(shape, complex)
        np.multiply(y2, inv, out=k1.real)
        np.multiply(x2, minus, out=k1.imag)
        np.multiply(y1, minus, out=k2.real)
        np.multiply(x1, inv, out=k2.imag)
        lin = kin.linear[index] = (k1, k2, g1, g2)
        return lin


def _rhs_of(c, unknown, fixed):
    """rhs(G, kin, d, qrate, vel): the right-hand side of constraint ``c`` in the rate
    system, its kind decided once: a distance's (:func:`_dist_rhs`), a coordinate's rate,
    a moving line's (:func:`_line_rhs`); a line through fixed points, on which the unknown
    point runs, gives 0."""
    if isinstance(c, Dist):
        return _dist_rhs(c, fixed)
    if isinstance(c, Track):
        return lambda g, kin, d, qrate, vel: c.rhs(kin.pos, d, qrate, vel)
    if fixed_guide(c, unknown, fixed):
        return _no_rhs
    if isinstance(c, Coord):
        j = c.coord
        return lambda g, kin, d, qrate, vel: qrate[j]

    def rhs(g, kin, d, qrate, vel):
        return _line_rhs(c, kin.pos, d, vel)
    return rhs


def _no_rhs(g, kin, d, qrate, vel):
    return 0.0


def _dist_rhs(c, fixed):
    """The right-hand side (as :func:`_line_rhs`) of g = |P - A|^2 - L^2 with G = 2 (P - A),
    P unknown: r = Re(conj(G) A') + 2 L L' for velocities, and for accelerations
    r = Re(conj(G) A'') + 2 L L'' - 2 |P' - A'|^2 + 2 L'^2; the terms of a fixed A or a
    fixed L are left out."""
    a, p, j = c.a, c.p, c.coord
    moving, driven = a not in fixed, c.length is None

    def rhs(g, kin, d, qrate, vel):
        r = 0.0
        if moving:
            va = d.get(a)
            if va is not None:
                r = (g.conjugate() * va).real
        if driven:
            r = r + 2.0 * kin.coords[j] * qrate[j]
        if vel is not None:
            dv = _delta(vel, p, a)
            if dv is not None:
                r = r - 2.0 * (dv.real * dv.real + dv.imag * dv.imag)
            if driven:
                r = r + 2.0 * kin.rates[j] * kin.rates[j]
        return r
    return rhs


def place_rate(group, d):
    """P' = K' + (M' - N') w of a point placed rigidly, P = K + (M - N) w (the same for
    P''); ``d`` holds the rates found so far, absent ones zero."""
    k, m, n, w = group.place
    return known_rate(d, k) + (known_rate(d, m) - known_rate(d, n)) * w


def known_rate(d, name):
    """The rate of point ``name`` found so far, 0 for a point that does not move."""
    return d.get(name, 0.0)


def _least(x):
    """The smallest of ``x`` (NaN if any is NaN), without np.min's dispatch."""
    return x.min() if type(x) is np.ndarray else np.min(x)


def fixed_guide(c, unknown, fixed) -> bool:
    """Whether ``c`` is a line through fixed points on which the unknown point runs: its
    gradient i (C - B) is a constant, and no known rate enters its right-hand side."""
    return isinstance(c, Line) and c.p == unknown and c.b in fixed and c.c in fixed


def constant_norms(group, fixed):
    """|G_1| |G_2| of a group whose constraint gradients keep their lengths (see
    :func:`_grad`): 2 L for a distance of fixed length L (P on its circle), |C - B| for a
    line through fixed points when P is the unknown, 1 for a coordinate; None when either
    varies (a driven length, a moving guide) or the group has no rate system.  A zero
    product is 1, as for the computed norms."""
    if not (group.is_dyad or group.kind == "driver-coord") or len(group.constraints) != 2:
        return None
    out = 1.0
    for c in group.constraints:
        if isinstance(c, Dist) and c.length is not None:
            out *= 2.0 * abs(c.length)
        elif fixed_guide(c, group.point, fixed):
            out *= abs(fixed[c.c] - fixed[c.b])
        elif isinstance(c, Coord):
            pass
        else:
            return None
    return out if out > 0 else 1.0


def _grad_of(c, unknown, fixed):
    """:func:`_grad` of ``c`` decided once: the gradient itself where it is constant (a
    coordinate, a line through fixed points on which the unknown runs), else
    grad(pos)."""
    if isinstance(c, Dist):
        p, a = c.p, c.a
        return lambda pos: 2.0 * (pos[p] - pos[a])
    if isinstance(c, Track):
        return c.grad
    if fixed_guide(c, unknown, fixed):
        return _grad(c, fixed, unknown)
    if isinstance(c, Line):
        return lambda pos: _grad(c, pos, unknown)
    return _grad(c, {}, unknown)


def _grad(c, pos, unknown):
    """Gradient of constraint ``c`` with respect to point ``unknown`` (complex)."""
    if isinstance(c, Dist):
        return 2.0 * (pos[c.p] - pos[c.a])
    if isinstance(c, Track):
        return c.grad(pos)
    if isinstance(c, Line):
        if unknown == c.p:
            return 1j * (pos[c.c] - pos[c.b])
        return -1j * (pos[c.p] - pos[c.b])
    return 1.0 + 0j if c.axis == "x" else 1j


def _delta(d, x, y):
    """d[x] - d[y], absent entries being zero; None when both are absent."""
    if x in d:
        return d[x] - d[y] if y in d else d[x]
    return -d[y] if y in d else None


def _line_rhs(c, pos, d, vel):
    """Right-hand side r of Re(conj(G) V) = r for a line g = cross(C - B, P - B) - value
    whose points may move (a distance's is :func:`_dist_rhs`, a coordinate's its rate).

    r = -(part of dg/dt linear in the known rates ``d``) for velocities; for
    accelerations (``vel`` given) also minus the quadratic part 2 B(V, V).
    """
    r = 0.0
    dcb, dpb = _delta(d, c.c, c.b), _delta(d, c.p, c.b)
    if dcb is not None:
        r = r - cross(dcb + 0j, pos[c.p] - pos[c.b])
    if dpb is not None:
        r = r - cross(pos[c.c] - pos[c.b] + 0j, dpb)
    if vel is not None:
        vcb, vpb = _delta(vel, c.c, c.b), _delta(vel, c.p, c.b)
        if vcb is not None and vpb is not None:
            r = r - 2.0 * cross(vcb + 0j, vpb)
    return r


def _combine(r1, k1, r2, k2):
    """r1 K1 + r2 K2 (complex K), skipping terms whose r is a zero scalar; a zero is +0,
    as 0 + r1 K1 + r2 K2 gives."""
    zero1 = type(r1) is not np.ndarray and r1 == 0
    if type(r2) is not np.ndarray and r2 == 0:
        if zero1:                       # a point moving with the frame: zero
            return np.zeros(np.shape(k2), complex) if np.ndim(k2) else 0j
        out = r1 * k1
    else:
        out = r2 * k2 if zero1 else r1 * k1 + r2 * k2
    if type(out) is np.ndarray:
        out += 0.0
        return out
    return complex(out) + 0.0
