"""First and second derivatives of the mechanism with respect to its coordinates.

For coordinates q = (q_1 .. q_n) every point P(q) has the Jacobian columns
P_j = dP/dq_j and the Hessian P_ij = d2P/dq_i dq_j.  Both come from the
closed-form rate solver: the velocities for the unit rate e_j are P_j, and the
accelerations for the rates v with no coordinate acceleration are

    P'' = sum_ij P_ij v_i v_j,

so v = e_i gives P_ii and v = e_i + e_j gives P_ii + 2 P_ij + P_jj.  Every unit rate
is one entry of an array of rates, and every pair (i, j) one entry of another, so the
solver runs once for all the columns and once (per block of BLOCK pairs) for all the
Hessians, whatever n: the work is in NumPy's loops, not in a Python loop per pair.

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
Gradients are arrays with the coordinate first (shape (n,) + the coordinates' shape),
Hessians with both coordinates first ((n, n) + that shape): one configuration or many.
"""
from __future__ import annotations

import cmath
from dataclasses import dataclass, field

import numpy as np

from linkcli.model.mechanism import FRAME

#: the pairs (i, j) of second derivatives solved at once (bounds the solver's arrays)
BLOCK = 4096


class Block:
    """A square array over the coordinates, shape (n, n) + S, that is zero outside the rows
    and columns ``idx`` (sorted): ``values`` holds those, shape (k, k) + S.  The Hessian of
    a point of a chain of n bodies depends on a few coordinates, not on all n, so a
    mechanism's Hessians take memory in proportion to their non-zero entries.

    Sums, differences, products by numbers (or arrays of shape S), ``real``, ``imag``,
    ``conj`` and ``@`` with a vector of n keep the block; NumPy sees the full array
    (``np.asarray(block)``, ``K += block``), and ``block[i, j]``, ``block[i][j]`` read it."""

    __array_priority__ = 20        # ndarray <op> Block calls Block's reflected operation

    def __array_ufunc__(self, ufunc, method, *inputs, out=None, **kwargs):
        """``K += block`` and ``K -= block`` add the block into the array K where it is not
        zero; a number times a block is a block; anything else sees the full array."""
        if method == "__call__" and not kwargs and len(inputs) == 2:
            a, b = inputs
            if out is not None and len(out) == 1 and out[0] is a and b is self \
                    and ufunc in (np.add, np.subtract) and isinstance(a, np.ndarray):
                where = (self.idx[:, None], self.idx[None, :])
                a[where] = ufunc(a[where], self.values)
                return a
            if out is None and ufunc is np.multiply and np.ndim(a) == 0 and b is self:
                return Block(self.idx, a * self.values, self.n)
            if out is None and ufunc in (np.add, np.subtract) and isinstance(a, Block) \
                    and isinstance(b, Block):
                return a._combine(b, ufunc)
        if method == "__call__" and ufunc is np.conjugate and len(inputs) == 1 and out is None:
            return self.conj()
        inputs = tuple(np.asarray(x) if isinstance(x, Block) else x for x in inputs)
        if out is not None:
            kwargs["out"] = tuple(np.asarray(x) if isinstance(x, Block) else x for x in out)
        return getattr(ufunc, method)(*inputs, **kwargs)

    def __init__(self, idx, values, n):
        self.idx = np.asarray(idx, dtype=int)
        self.values = np.asarray(values)
        self.n = n

    @classmethod
    def zero(cls, n, shape=(), dtype=complex):
        return cls(np.zeros(0, dtype=int), np.zeros((0, 0) + tuple(shape), dtype=dtype), n)

    @property
    def shape(self):
        return (self.n, self.n) + self.values.shape[2:]

    def __array__(self, dtype=None, copy=None):
        full = np.zeros(self.shape, dtype=dtype or self.values.dtype)
        if self.idx.size:
            full[self.idx[:, None], self.idx[None, :]] = self.values
        return full

    def dense(self):
        return np.asarray(self)

    def within(self, idx):
        """The values on the rows and columns ``idx`` (a sorted superset of self.idx)."""
        if np.array_equal(idx, self.idx):
            return self.values
        out = np.zeros((len(idx), len(idx)) + self.values.shape[2:], dtype=self.values.dtype)
        where = np.searchsorted(idx, self.idx)
        out[where[:, None], where[None, :]] = self.values
        return out

    def _combine(self, other, op):
        if isinstance(other, Block):
            idx = np.union1d(self.idx, other.idx)
            return Block(idx, op(self.within(idx), other.within(idx)), self.n)
        if np.ndim(other) == 0 and other == 0:
            return self
        return op(self.dense(), other)

    def __add__(self, other):
        return self._combine(other, np.add)

    def __radd__(self, other):
        return self._combine(other, lambda a, b: np.add(b, a))

    def __sub__(self, other):
        return self._combine(other, np.subtract)

    def __rsub__(self, other):
        return self._combine(other, lambda a, b: np.subtract(b, a))

    def __neg__(self):
        return Block(self.idx, -self.values, self.n)

    def __mul__(self, number):
        """Times a number or an array of the configurations' shape S."""
        return Block(self.idx, self.values * number, self.n)

    __rmul__ = __mul__

    def __truediv__(self, number):
        return Block(self.idx, self.values / number, self.n)

    @property
    def real(self):
        return Block(self.idx, np.real(self.values), self.n)

    @property
    def imag(self):
        return Block(self.idx, np.imag(self.values), self.n)

    def conj(self):
        return Block(self.idx, np.conj(self.values), self.n)

    def __matmul__(self, vector):
        """B v for a vector of n (one configuration)."""
        out = np.zeros(self.n, dtype=np.result_type(self.values, vector))
        out[self.idx] = self.values @ np.asarray(vector)[self.idx]
        return out

    def __rmatmul__(self, vector):
        """v^T B for a vector of n (one configuration)."""
        out = np.zeros(self.n, dtype=np.result_type(self.values, vector))
        out[self.idx] = np.asarray(vector)[self.idx] @ self.values
        return out

    def __getitem__(self, key):
        if isinstance(key, tuple) and len(key) == 2 and all(np.ndim(k) == 0 for k in key):
            i, j = key
            a, b = np.searchsorted(self.idx, [i, j])
            if a < self.idx.size and b < self.idx.size and self.idx[a] == i and self.idx[b] == j:
                return self.values[a, b]
            return np.zeros(self.values.shape[2:], dtype=self.values.dtype)[()]
        return self.dense()[key]


@dataclass
class Jet:
    """Positions and their first and second derivatives at one set of coordinate values.

    ``grad[P]`` is dP/dq (shape (n,) + the coordinates' shape) and ``hess[P]`` is
    d2P/dq dq, a :class:`Block` ((n, n) + that shape, stored where it is not zero); fixed
    points are absent from both (their derivatives are zero), and ``hess`` is empty for a
    jet without second derivatives.
    """

    pos: dict
    grad: dict = field(default_factory=dict)
    hess: dict = field(default_factory=dict)
    n: int = 1
    shape: tuple = ()

    def gradient(self, point):
        """dP/dq of ``point``: zeros for a fixed point."""
        out = self.grad.get(point)
        return np.zeros((self.n,) + self.shape, dtype=complex) if out is None else out

    def hessian(self, point) -> Block:
        """d2P/dq dq of ``point``: zero for a fixed point."""
        out = self.hess.get(point)
        return Block.zero(self.n, self.shape) if out is None else out

    def d1(self, point, j):
        return self.gradient(point)[j]

    def d2(self, point, i, j):
        return self.hessian(point)[i, j]


@dataclass
class Scalar:
    """A scalar measure m(q): its value, gradient m_i (an array, shape (n,) + ...) and
    Hessian m_ij (a :class:`Block` or an array, (n, n) + ...)."""

    value: object
    grad: np.ndarray
    hess: object

    def __post_init__(self):
        self.grad = np.asarray(self.grad)
        if not isinstance(self.hess, Block):
            self.hess = np.asarray(self.hess)

    def rate(self, qd):
        """m' = sum_i m_i q'_i for coordinate rates ``qd``."""
        return np.tensordot(np.asarray(qd, dtype=float), self.grad, axes=(0, 0))


def _columns(n, count, shape):
    """The rates the solver takes for ``count`` rate vectors (the columns of an n x count
    matrix) at once: one array per coordinate, broadcast over the coordinates' ``shape``."""
    def rates(matrix):
        arrays = [np.broadcast_to(matrix[j].reshape((count,) + (1,) * len(shape)),
                                  (count,) + shape) for j in range(n)]
        return arrays[0] if n == 1 else tuple(arrays)
    return rates


def jet(solver, q, second: bool = True) -> Jet:
    """The jet of the mechanism at coordinates ``q`` (as ``solver.positions`` takes them)."""
    kin = solver.positions(q)
    solver.check(kin, velocities=False)
    n = solver.n
    shape = tuple(kin.shape)
    solver.velocities(kin, _columns(n, n, shape)(np.eye(n)))
    solver.check(kin, velocities=True)
    full = (n,) + shape
    out = Jet(dict(kin.pos), {p: np.array(np.broadcast_to(v, full), dtype=complex)
                              for p, v in kin.vel.items()}, n=n, shape=shape)
    if second:
        out.hess = _hessians(solver, kin, n, shape, set(out.grad))
    kin.linear.clear()
    return out


def _hessians(solver, kin, n, shape, points) -> dict:
    """P_ij of every point of ``points``, as blocks over the coordinates whose entries are
    not zero: the diagonal from the rates e_i, then the pairs i < j from e_i + e_j, BLOCK
    pairs at a time (only their entries that are not zero are kept)."""
    diagonal = _accelerations(solver, kin, n, shape, np.arange(n), np.arange(n), points)
    entries = {p: [_nonzero(np.arange(n), np.arange(n), diagonal[p])] for p in points}
    rows, cols = np.triu_indices(n, 1)
    for start in range(0, rows.size, BLOCK):
        i, j = rows[start:start + BLOCK], cols[start:start + BLOCK]
        acc = _accelerations(solver, kin, n, shape, i, j, points)
        for p in points:
            entries[p].append(_nonzero(i, j, 0.5 * (acc[p] - diagonal[p][i] - diagonal[p][j])))
    return {p: _block(n, shape, parts) for p, parts in entries.items()}


def _accelerations(solver, kin, n, shape, i, j, points) -> dict:
    """{point: its accelerations for the rates e_i + e_j (e_i for i = j), no coordinate
    acceleration}: arrays of shape (len(i),) + shape."""
    count = len(i)
    matrix = np.zeros((n, count))
    matrix[i, np.arange(count)] = 1.0
    matrix[j, np.arange(count)] = 1.0
    rates = _columns(n, count, shape)
    solver.velocities(kin, rates(matrix))
    solver.accelerations(kin, rates(np.zeros((n, count))), keep=True)
    full = (count,) + shape
    return {p: np.broadcast_to(kin.acc.get(p, 0j), full) for p in points}


def _nonzero(i, j, value):
    """The entries (i, j, value) whose value is not zero (in some configuration)."""
    keep = np.any(value != 0, axis=tuple(range(1, value.ndim)))
    return i[keep], j[keep], np.array(value[keep])


def _block(n, shape, parts) -> Block:
    """The symmetric block of the entries (i, j, value) of ``parts``."""
    idx = np.unique(np.concatenate([np.concatenate([i, j]) for i, j, _ in parts]))
    values = np.zeros((idx.size, idx.size) + shape, dtype=complex)
    for i, j, value in parts:
        a, b = np.searchsorted(idx, i), np.searchsorted(idx, j)
        values[a, b] = value
        values[b, a] = value
    return Block(idx, values, n)


# --- measures ----------------------------------------------------------------------------
def _vector(jt: Jet, a, b):
    """z = P_b - P_a with its derivatives (fixed points contribute nothing to them)."""
    return (jt.pos[b] - jt.pos[a], jt.gradient(b) - jt.gradient(a),
            jt.hessian(b) - jt.hessian(a))


def _support(*grads_and_blocks):
    """The coordinates where gradients (arrays) or blocks are not zero, sorted."""
    out = np.zeros(0, dtype=int)
    for x in grads_and_blocks:
        if isinstance(x, Block):
            out = np.union1d(out, x.idx)
        else:
            nonzero = np.any(x != 0, axis=tuple(range(1, np.ndim(x))))
            out = np.union1d(out, np.flatnonzero(nonzero))
    return out


def _outer(x, y, n, idx) -> Block:
    """x_i y_j on the coordinates ``idx`` (x, y zero elsewhere): a block."""
    return Block(idx, x[idx][:, None] * y[idx][None, :], n)


def along(jt: Jet, a, b, direction) -> Scalar:
    """m = Re(conj(e) (P_b - P_a)) (``a`` None: m = Re(conj(e) P_b))."""
    e = np.conj(direction)
    if a is None:
        z, zi, zij = jt.pos[b], jt.gradient(b), jt.hessian(b)
    else:
        z, zi, zij = _vector(jt, a, b)
    return Scalar((e * z).real, np.real(e * zi), (zij * e).real)


def distance(jt: Jet, a, b) -> Scalar:
    """m = |P_b - P_a|."""
    z, zi, zij = _vector(jt, a, b)
    r = np.abs(z)
    u = np.conj(z) / r
    g = np.real(u * zi)
    idx = _support(zi, zij)
    h = (zij * u).real + (_outer(np.conj(zi), zi, jt.n, idx).real
                          - _outer(g, g, jt.n, idx)) / r
    return Scalar(r, g, h)


def angle_of(z, zi, zij, n=None) -> Scalar:
    """m = arg z (unwrapped near the value), from z and its derivatives."""
    w = zi / z
    idx = _support(zi, zij)
    return Scalar(np.angle(z), np.imag(w), (zij / z - _outer(w, w, len(w), idx)).imag)


def constant(jt: Jet, value=0.0) -> Scalar:
    zero = np.zeros(jt.shape)
    return Scalar(value + zero, np.zeros((jt.n,) + jt.shape), Block.zero(jt.n, jt.shape, float))


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
    s = angle_of(*_vector(jt, a, b))
    s.value = s.value - local
    return s


def body_point(mech, jt: Jet, name, local: complex):
    """Position G of the point at ``local`` coordinates of body ``name``, with G_i and
    G_ij: returns (G, G_i (n,) + S, G_ij a Block (n, n) + S)."""
    origin, _, _ = body_axis(mech, name)
    body = mech.bodies.get(name)
    offset = local - (body.local[origin] if body is not None and body.kind in ("link", "block")
                      else 0.0)
    theta = body_angle(mech, jt, name)
    c = offset * np.exp(1j * theta.value)
    g = jt.pos[origin] + c
    gi = jt.gradient(origin) + 1j * theta.grad * c
    idx = _support(theta.grad, theta.hess)
    gij = jt.hessian(origin) + (1j * theta.hess - _outer(theta.grad, theta.grad, jt.n, idx)) * c
    return g, gi, gij


def point(jt: Jet, p):
    """Position of point ``p`` with its derivatives, in the form of :func:`body_point`."""
    return jt.pos[p], jt.gradient(p), jt.hessian(p)
