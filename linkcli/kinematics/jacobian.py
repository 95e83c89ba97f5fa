"""First and second derivatives of the mechanism with respect to its coordinates.

For coordinates q = (q_1 .. q_n) every point P(q) has the Jacobian columns
P_j = dP/dq_j and the Hessian P_ij = d2P/dq_i dq_j.  Both come from the
closed-form rate solver: the velocities for the unit rate e_j are P_j, and the
accelerations for the rates v with no coordinate acceleration are

    P'' = sum_ij P_ij v_i v_j,

so v = e_i gives P_ii and v = e_i + e_j gives P_ii + 2 P_ij + P_jj.

The *measures* that forces act through follow by the chain rule, with
z = P_b - P_a and u = z / |z|:

    coordinate along e:  m = Re(conj(e) P)   m_i = Re(conj(e) P_i)   m_ij = Re(conj(e) P_ij)
    distance:            m = |z|             m_i = Re(conj(u) z_i)
                         m_ij = Re(conj(u) z_ij) + (Re(conj(z_i) z_j) - m_i m_j) / |z|
    angle of z:          m = arg z           m_i = Im(z_i / z)
                         m_ij = Im(z_ij / z - z_i z_j / z^2)

A point of a body at the constant offset c from the body's origin point K is
G = K + c e^{i theta}, so G_i = K_i + i theta_i c e^{i theta} and
G_ij = K_ij + (i theta_ij - theta_i theta_j) c e^{i theta}.
Every array has the shape of the coordinates' values (one configuration or many).
"""
from __future__ import annotations

import cmath
from dataclasses import dataclass, field

import numpy as np

from linkcli.model.mechanism import FRAME


@dataclass
class Jet:
    """Positions and their first and second derivatives at one set of coordinate values.

    ``first[j][P]`` is dP/dq_j and ``second[(i, j)][P]`` (i <= j) is d2P/dq_i dq_j;
    fixed points are absent from both (their derivatives are zero).
    """

    pos: dict
    first: list
    second: dict = field(default_factory=dict)
    n: int = 1

    def d1(self, point, j):
        return self.first[j].get(point, 0.0)

    def d2(self, point, i, j):
        return self.second.get((min(i, j), max(i, j)), {}).get(point, 0.0)


@dataclass
class Scalar:
    """A scalar measure m(q): its value, gradient m_i and Hessian m_ij (lists of arrays)."""

    value: object
    grad: list
    hess: list            # hess[i][j]

    def rate(self, qd):
        """m' = sum_i m_i q'_i for coordinate rates ``qd``."""
        return sum(g * v for g, v in zip(self.grad, qd))


def jet(solver, q, second: bool = True) -> Jet:
    """The jet of the mechanism at coordinates ``q`` (as ``solver.positions`` takes them)."""
    kin = solver.positions(q)
    solver.check(kin, velocities=False)
    n = solver.n
    shape = kin.shape
    zero = np.zeros(shape)

    def unit(*indices):
        return [np.ones(shape) if j in indices else zero for j in range(n)]

    def rates(v):
        return v[0] if n == 1 else v

    first = []
    for j in range(n):
        solver.velocities(kin, rates(unit(j)))
        if j == 0:
            solver.check(kin, velocities=True)
        first.append(dict(kin.vel))
    out = Jet(dict(kin.pos), first, n=n)
    if not second:
        kin.linear.clear()
        return out
    diagonal = {}
    for i in range(n):
        for j in range(i, n):
            solver.velocities(kin, rates(unit(i, j)))
            solver.accelerations(kin, rates([zero] * n), keep=True)
            diagonal[(i, j)] = dict(kin.acc)
    kin.linear.clear()
    for (i, j), acc in diagonal.items():
        if i == j:
            out.second[(i, i)] = acc
            continue
        aii, ajj = diagonal[(i, i)], diagonal[(j, j)]
        out.second[(i, j)] = {p: 0.5 * (a - aii.get(p, 0.0) - ajj.get(p, 0.0))
                              for p, a in acc.items()}
    return out


# --- measures ----------------------------------------------------------------------------
def _pairs(n):
    return [(i, j) for i in range(n) for j in range(n)]


def _vector(jt: Jet, a, b):
    """z = P_b - P_a with its derivatives (fixed points contribute nothing to them)."""
    z = jt.pos[b] - jt.pos[a]
    zi = [jt.d1(b, i) - jt.d1(a, i) for i in range(jt.n)]
    zij = {(i, j): jt.d2(b, i, j) - jt.d2(a, i, j) for i, j in _pairs(jt.n)}
    return z, zi, zij


def along(jt: Jet, a, b, direction) -> Scalar:
    """m = Re(conj(e) (P_b - P_a)) (``a`` None: m = Re(conj(e) P_b))."""
    e = np.conj(direction)
    if a is None:
        z, zi = jt.pos[b], [jt.d1(b, i) for i in range(jt.n)]
        zij = {(i, j): jt.d2(b, i, j) for i, j in _pairs(jt.n)}
    else:
        z, zi, zij = _vector(jt, a, b)
    n = jt.n
    return Scalar((e * z).real, [np.real(e * zi[i]) for i in range(n)],
                  [[np.real(e * zij[(i, j)]) for j in range(n)] for i in range(n)])


def distance(jt: Jet, a, b) -> Scalar:
    """m = |P_b - P_a|."""
    z, zi, zij = _vector(jt, a, b)
    r = np.abs(z)
    u = np.conj(z) / r
    n = jt.n
    g = [np.real(u * zi[i]) for i in range(n)]
    h = [[np.real(u * zij[(i, j)]) + (np.real(np.conj(zi[i]) * zi[j]) - g[i] * g[j]) / r
          for j in range(n)] for i in range(n)]
    return Scalar(r, g, h)


def angle_of(z, zi, zij, n) -> Scalar:
    """m = arg z (unwrapped near the value), from z and its derivatives."""
    w = [zi[i] / z for i in range(n)]
    return Scalar(np.angle(z), [np.imag(w[i]) for i in range(n)],
                  [[np.imag(zij[(i, j)] / z - w[i] * w[j]) for j in range(n)]
                   for i in range(n)])


def constant(jt: Jet, value=0.0) -> Scalar:
    n = jt.n
    zero = np.zeros(np.shape(next(iter(jt.pos.values()))))
    return Scalar(value + zero, [zero] * n, [[zero] * n for _ in range(n)])


# --- bodies ------------------------------------------------------------------------------
def body_axis(mech, name):
    """(origin point, (a, b) of a vector fixed in the body, local angle of that vector)
    for body ``name``; None for the frame."""
    if name == FRAME:
        return None
    if name in mech.actuators:
        act = mech.actuators[name]
        return act.a, (act.a, act.b), 0.0
    body = mech.bodies[name]
    if body.kind == "link":
        k, m = body.points[0], body.points[1]
        return k, (k, m), cmath.phase(body.local[m] - body.local[k])
    if body.kind == "block":
        return body.points[0], (body.guide.b, body.guide.c), 0.0
    act = mech.actuators[name.rsplit(".", 1)[0]]
    return (act.a if body.kind == "cylinder" else act.b), (act.a, act.b), 0.0


def body_angle(mech, jt: Jet, name) -> Scalar:
    """The rotation theta of body ``name`` (rad, counter-clockwise; the frame's is 0),
    measured so that theta is 0 when the body's local axes are the frame's."""
    axis = body_axis(mech, name)
    if axis is None:
        return constant(jt)
    _, (a, b), local = axis
    z, zi, zij = _vector(jt, a, b)
    s = angle_of(z, zi, zij, jt.n)
    s.value = s.value - local
    return s


def body_point(mech, jt: Jet, name, local: complex):
    """Position G of the point at ``local`` coordinates of body ``name``, with G_i and
    G_ij: returns (G, [G_i], {(i, j): G_ij})."""
    n = jt.n
    origin, _, _ = body_axis(mech, name)
    body = mech.bodies.get(name)
    offset = local - (body.local[origin] if body is not None and body.kind in ("link", "block")
                      else 0.0)
    theta = body_angle(mech, jt, name)
    c = offset * np.exp(1j * theta.value)
    g = jt.pos[origin] + c
    gi = [jt.d1(origin, i) + 1j * theta.grad[i] * c for i in range(n)]
    gij = {(i, j): jt.d2(origin, i, j) + (1j * theta.hess[i][j] - theta.grad[i] * theta.grad[j]) * c
           for i, j in _pairs(n)}
    return g, gi, gij


def point(jt: Jet, p):
    """Position of point ``p`` with its derivatives, in the form of :func:`body_point`."""
    n = jt.n
    return jt.pos[p], [jt.d1(p, i) for i in range(n)], \
        {(i, j): jt.d2(p, i, j) for i, j in _pairs(n)}
