"""The constraint equations of the whole mechanism, evaluated on batches.

The unknowns X are the coordinates (x, y) of every moving point.  Each row of
:mod:`linkcli.equations` reads g = Re(k conj(U) V) - v(q) (divided by its
length scale), so its gradient is analytic:

    dg = Re(conj(k V) dU) + Re(conj(conj(k) U) dV),

and the Jacobian J = dg/dX is dimensionless.  Velocities solve J v = -dg/dq qdot;
accelerations J a = -(d2g/dt2 without the unknown accelerations).

Each rolling contact or cord adds the row g = a sum c_k (mu_k - mu_k0) of its relation
(``kinematics.contacts``; a the arm |M - C| of its disc, so that g is a length), with
dg = a sum_P Re(conj(G_P) dP).

A turn measured on points (a disc's, an arm's: ``Turn`` without a coordinate) is counted
continuously, any number of turns: each row of X carries, after the n unknowns, the
absolute angle W_k of every such vector at a configuration it was reached from, and the
angle now is theta_k = W_k + arg(Z_k e^{-i W_k}), Z_k = P_b - P_a (exact while the vector
turns less than half a turn between the two; :meth:`Constraints.rebase` moves W_k to
theta_k after every Newton step).  Rows that carry no such angles start from the
figure's: within half a turn of it (:meth:`Constraints.augment`).
"""
from __future__ import annotations

import numpy as np

from linkcli.kinematics.contacts import Turn, relations
from linkcli.kinematics.dyads import cis
from linkcli.kinematics.equations import ONE, ZERO, mechanism_rows
from linkcli.errors import StructureError


class Constraints:
    """The equations of a mechanism, evaluated on batches of configurations."""

    def __init__(self, mech):
        self.mech = mech
        self._name_points(mech)
        rows, lengths = mechanism_rows(mech, {name: i for i, name in enumerate(self.names)})
        self.rows = [r for r in rows if self._moves(r)]
        self.contacts = [(rel, _arm(mech, rel)) for rel in relations(mech).values()]
        self.n = 2 * self.nm
        self._name_turns(mech)
        self._require_square()
        self._stack(self.rows)
        self.shortest = min(lengths) if lengths else None
        self.scatter = self._scatter()

    # building -----------------------------------------------------------------
    def _name_points(self, mech):
        """Point names: fixed, moving, then the virtual ~zero and ~one; their base values."""
        fixed = list(mech.fixed)
        self.moving = list(mech.moving)
        self.names = fixed + self.moving + [ZERO, ONE]
        self.nf, self.nm = len(fixed), len(self.moving)
        self.zero, self.one = len(self.names) - 2, len(self.names) - 1
        self.base = np.array([mech.fixed[n] for n in fixed] + [0j] * self.nm + [0j, 1 + 0j])

    def _name_turns(self, mech):
        """The turns measured on points (``turns``: their point pairs, ``turn_figure``: their
        angles on the figure) and ``width``, the columns of X (the unknowns, then W)."""
        pairs = []
        for rel, _ in self.contacts:
            for term, _, _ in rel.terms:
                if isinstance(term, Turn) and term.coord is None and \
                        (term.a, term.b) not in pairs:
                    pairs.append((term.a, term.b))
        self.turns = pairs
        self._turn_ends = (np.array([self.names.index(a) for a, _ in pairs], int),
                           np.array([self.names.index(b) for _, b in pairs], int))
        figure = {**mech.fixed, **mech.moving}
        self.turn_figure = np.array([np.angle(figure[b] - figure[a]) for a, b in pairs])
        self.width = self.n + len(pairs)

    def _moves(self, row):
        """Whether the row involves a moving point (else it is an identity of the frame)."""
        return any(self.nf <= i < self.nf + self.nm for i in (row.b, row.c, row.a, row.p))

    def _require_square(self):
        count = len(self.rows) + len(self.contacts)
        if count != self.n:
            raise StructureError(
                f"the point equations are not square: {count} equations for {self.n} "
                "unknown coordinates", file=self.mech.file,
                hint="every moving point must belong to a link or a slider that fixes it")

    def _stack(self, rows):
        """The rows' fields as arrays (one entry a row)."""
        for name in ("b", "c", "a", "p", "k", "v0", "vq", "vqq", "uq"):
            setattr(self, name, np.array([getattr(r, name) for r in rows]))
        self.inv_scale = 1.0 / np.array([r.scale for r in rows])

    def _scatter(self):
        """The matrix S with J = [Re kV, Im kV, Re k*U, Im k*U] S: it places each row's
        gradient with respect to P_c (+), P_b (-), P_p (+) and P_a (-) in their columns."""
        R = len(self.rows)
        scatter = np.zeros((4 * R, R * self.n))
        for which, offset, sign in (("c", 0, 1.0), ("b", 0, -1.0), ("p", 2, 1.0), ("a", 2, -1.0)):
            idx = getattr(self, which)
            for r in np.nonzero((idx >= self.nf) & (idx < self.nf + self.nm))[0]:
                col = r * self.n + 2 * (idx[r] - self.nf)
                scatter[offset * R + r, col] += sign
                scatter[(offset + 1) * R + r, col + 1] += sign
        return scatter

    # evaluation ---------------------------------------------------------------
    def points(self, X):
        """All points (N, npts) complex from the unknowns X (N, n)."""
        P = np.empty((X.shape[0], len(self.names)), complex)
        P[:] = self.base
        P.real[:, self.nf:self.nf + self.nm] = X[:, 0:self.n:2]
        P.imag[:, self.nf:self.nf + self.nm] = X[:, 1:self.n:2]
        return P

    # turns counted continuously ----------------------------------------------------
    def _angles(self, P, W):
        """theta_k = W_k + arg(Z_k e^{-i W_k}) (N, m): each turn's angle nearest W_k."""
        a, b = self._turn_ends
        return W + np.angle((P[:, b] - P[:, a]) * cis(-W))

    def rebase(self, X):
        """X with its angles W moved to the angles of its own points (in place)."""
        if self.turns:
            X[:, self.n:] = self._angles(self.points(X), X[:, self.n:])
        return X

    def moved(self, X, dx):
        """X with the unknowns moved by dx (N, n), its angles following (a new array)."""
        out = np.array(X, dtype=float)
        out[:, :self.n] += dx
        return self.rebase(out)

    def augment(self, X):
        """Unknowns X (N, n) with the angles W of their turns within half a turn of the
        figure's (N, width)."""
        out = np.empty((X.shape[0], self.width))
        out[:, :self.n] = X[:, :self.n]
        out[:, self.n:] = self.turn_figure
        return self.rebase(out)

    def turn_rates(self, X, V):
        """d theta_k = Im(dZ_k / Z_k) for the point rates V (N, n): the rates of W."""
        a, b = self._turn_ends
        P, D = self.points(X), self.points(V)
        D[:, :self.nf] = 0
        D[:, self.nf + self.nm:] = 0
        return ((D[:, b] - D[:, a]) / (P[:, b] - P[:, a])).imag

    def _uv(self, P, q):
        """U = P_c - P_b (+ e^{iq} on driving-angle rows) and V = P_p - P_a, (N, R) each."""
        U = P[:, self.c] - P[:, self.b]
        if self.uq.any():
            U[:, self.uq] += cis(q)[:, None]
        return U, P[:, self.p] - P[:, self.a]

    def _driven(self, linear, quadratic):
        """vq linear + vqq quadratic per row: the driver's part of v(q) or of its rates."""
        return np.multiply.outer(linear, self.vq) + np.multiply.outer(quadratic, self.vqq)

    def _residual(self, U, V, q):
        """(Re(k conj(U) V) - v(q)) / scale."""
        g = (self.k * U.conj() * V).real
        g -= self.v0 + self._driven(q, q * q)
        return g * self.inv_scale

    def residual(self, X, q):
        """Scaled residuals (N, R), lengths; X (N, width) (see :meth:`augment`)."""
        P = self.points(X)
        return self._with_contacts(self._residual(*self._uv(P, q), q), P, q, X)

    def jacobian(self, P, q, U=None, V=None):
        """Scaled Jacobian (N, R, n) of the residuals with respect to the unknowns."""
        if U is None:
            U, V = self._uv(P, q)
        kV = self.k * V * self.inv_scale
        kU = self.k.conj() * U * self.inv_scale
        src = np.concatenate([kV.real, kV.imag, kU.real, kU.imag], axis=1)
        J = (src @ self.scatter).reshape(P.shape[0], len(self.rows), self.n)
        if not self.contacts:
            return J
        return np.concatenate([J, self._contact_jacobian(P)], axis=1)

    def system(self, X, q):
        """Residuals and Jacobian at once."""
        P = self.points(X)
        U, V = self._uv(P, q)
        return (self._with_contacts(self._residual(U, V, q), P, q, X),
                self.jacobian(P, q, U, V))

    # contacts -------------------------------------------------------------------
    def _named(self, P):
        """{point name: its column of P} (N,) for the contacts' measures."""
        return {name: P[:, i] for i, name in enumerate(self.names)}

    def _with_contacts(self, g, P, q, X):
        """The residuals (N, R) followed by each contact's a sum c_k (mu_k - mu_k0), the
        turns on points theta_k - theta_k0 counted from the angles W of X."""
        if not self.contacts:
            return g
        pos = self._named(P)
        turns = {}
        if self.turns:
            theta = self._angles(P, X[:, self.n:]) - self.turn_figure
            turns = {pair: theta[:, k] for k, pair in enumerate(self.turns)}
        rows = [arm * np.broadcast_to(rel.residual(pos, (q,), turns), q.shape)
                for rel, arm in self.contacts]
        return np.concatenate([g, np.stack(rows, axis=1)], axis=1)

    def _contact_jacobian(self, P):
        """(N, C, n): a [Re G_P, Im G_P] in the columns of each moving point P."""
        pos = self._named(P)
        out = np.zeros((P.shape[0], len(self.contacts), self.n))
        for row, (rel, arm) in enumerate(self.contacts):
            for name in rel.points():
                j = self.names.index(name) - self.nf
                if 0 <= j < self.nm:
                    g = arm * np.broadcast_to(rel.grad(pos, name), (P.shape[0],))
                    out[:, row, 2 * j] += g.real
                    out[:, row, 2 * j + 1] += g.imag
        return out

    # rates --------------------------------------------------------------------
    def rate_rhs(self, P, q, qd, qdd=None, W=None):
        """Right-hand side of J v = rhs (``W`` None) or J a = rhs (``W`` the velocities).

        First rates: -(dg/dq) qd.  Second: -(Re(k conj(U''_q) V) + 2 Re(k conj(U') V')
        - v''), with U''_q = (i qdd - qd^2) e^{iq} on driving-angle rows.
        """
        V = P[:, self.p] - P[:, self.a]
        qd = np.broadcast_to(qd, q.shape)
        e = cis(q)[:, None] if self.uq.any() else 0.0
        if W is None:
            known = self._first_rate(V, q, qd, e)
        else:
            known = self._second_rate(V, W, q, qd, np.broadcast_to(qdd, q.shape), e)
        rhs = -known * self.inv_scale
        if not self.contacts:
            return rhs
        pos = self._named(P)
        if W is None:       # only a turn that is the driver has a known rate
            rows = [-arm * rel.rate(pos, {}, (qd,)) for rel, arm in self.contacts]
        else:               # the quadratic parts, and the driver's turn
            vel = self._named(W)
            rows = [-arm * rel.accel(pos, vel, {}, (np.broadcast_to(qdd, q.shape),))
                    for rel, arm in self.contacts]
        rows = [np.broadcast_to(r, q.shape) for r in rows]
        return np.concatenate([rhs, np.stack(rows, axis=1)], axis=1)

    def _first_rate(self, V, q, qd, e):
        """dg/dt without the unknown velocities: Re(k conj(i qd e^{iq}) V) - v'(q)."""
        known = np.zeros(V.shape)
        self._add_driving(known, 1j * qd, e, V)
        known -= self._driven(qd, 2 * q * qd)
        return known

    def _second_rate(self, V, W, q, qd, qdd, e):
        """d2g/dt2 without the unknown accelerations:
        2 Re(k conj(U') V') + Re(k conj((i qdd - qd^2) e^{iq}) V) - v''(q)."""
        dU = W[:, self.c] - W[:, self.b]
        dV = W[:, self.p] - W[:, self.a]
        if self.uq.any():
            dU[:, self.uq] += 1j * qd[:, None] * e
        known = 2.0 * (self.k * dU.conj() * dV).real
        self._add_driving(known, 1j * qdd - qd * qd, e, V)
        known -= self._driven(qdd, 2 * qd * qd + 2 * q * qdd)
        return known

    def _add_driving(self, known, z, e, V):
        """known += Re(k conj(z e^{iq}) V) on the driving-angle rows."""
        if self.uq.any():
            known[:, self.uq] += (self.k[self.uq] * np.conj(z[:, None] * e)
                                  * V[:, self.uq]).real

    def measure(self, J):
        """|det J| / prod(|row|): 0 when singular, 1 when the rows are orthogonal."""
        norms = np.prod(np.linalg.norm(J, axis=2), axis=1)
        return np.abs(np.linalg.det(J)) / np.where(norms > 0, norms, 1.0)


def _arm(mech, rel) -> float:
    """|M - C| of the disc a contact turns: the length its residual is measured in."""
    body = mech.bodies[rel.disc]
    return abs(body.local[body.points[1]] - body.local[body.points[0]]) or 1.0
