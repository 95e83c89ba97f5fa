"""Newton-Raphson on the constraint equations, for batches of configurations.

Each row of X (N, n) iterates X <- X + dx with J dx = -g at its own driver
value.  A row has converged when its step is at most tol * size and its
residual confirms it; at a toggle J is singular and the steps shrink only
linearly, so a row that stops there counts when its residual is at rounding
level.  Damped iterations (from a distant start) cap the step at half the
shortest link and backtrack until the residual norm decreases (Armijo).
A row of X holds the n unknowns and then the angles of the turns its contacts count
(:meth:`linkcli.kinematics.constraints.Constraints.rebase`), which follow every step.
"""
from __future__ import annotations

import numpy as np

CHUNK = 1 << 14          # positions per batched linear solve
MAX_ITER = 80            # iterations allowed from a distant start
FAR = 1e3                # points farther than FAR sizes from the origin: no configuration
ROUNDING = 8 * np.finfo(float).eps   # residual (relative to the size) that is exact closure
ARMIJO = 1e-4            # sufficient decrease of |g|^2 per unit step
HALVINGS = 12            # backtracking steps of the line search


def solve_linear(J, r):
    """Batched J x = r.  Exactly singular matrices (and only those) are solved with a
    tiny Tikhonov regularisation instead, so they cannot spoil the others."""
    try:
        return np.linalg.solve(J, r[..., None])[..., 0]
    except np.linalg.LinAlgError:
        det = np.linalg.det(J)
        bad = ~(np.isfinite(det) & (det != 0))
        out = np.empty(r.shape)
        if (~bad).any():
            out[~bad] = np.linalg.solve(J[~bad], r[~bad][..., None])[..., 0]
        out[bad] = _regularised(J[bad], r[bad])
        return np.where(np.isfinite(out), out, 0.0)


def _regularised(J, r):
    """(J^T J + mu I) x = J^T r with mu = 1e-14 trace(J^T J): least squares of singular J."""
    Jt = np.swapaxes(J, 1, 2)
    A = Jt @ J
    mu = 1e-14 * np.trace(A, axis1=1, axis2=2) + 1e-300
    A = A + mu[:, None, None] * np.eye(J.shape[2])
    return np.linalg.solve(A, Jt @ r[..., None])[..., 0]


class Corrector:
    """Newton's iteration on ``system`` (:class:`linkcli.constraints.Constraints`).

    ``tol`` is relative to ``size`` (a length of the mechanism); ``shortest`` is
    its shortest link; ``iterations`` counts the batched iterations done.
    """

    def __init__(self, system, tol, size, shortest):
        self.system = system
        self.tol = float(tol)
        self.size = size
        self.shortest = shortest
        self.iterations = 0

    def newton(self, X, q, max_iter, damped=False):
        """Iterate every row of X (N, n) at its q; returns (X, converged mask)."""
        X = np.array(X, dtype=float)
        q = np.asarray(q, dtype=float)
        done = np.zeros(len(q), bool)
        active = np.arange(len(q))
        limit = self.tol * self.size
        stalled = []
        for _ in range(max_iter):
            if active.size == 0:
                break
            Xa, qa = X[active], q[active]
            dx, big, finite, stuck = self._step(Xa, qa, damped)
            stalled.append(active[stuck])
            Xa = self.system.moved(Xa, dx)
            X[active] = Xa
            self.iterations += 1
            conv = self._confirmed(Xa, qa, finite & (big <= limit), limit)
            done[active[conv]] = True
            active = active[~conv & finite]
        rest = np.concatenate([active] + stalled)
        done[rest[self._closed(X[rest], q[rest])]] = True
        return X, done

    def _step(self, X, q, damped):
        """The step dx of J dx = -g per row, zero where it cannot be taken.

        Returns (dx, max |dx| before damping, finite: a step was taken, stuck:
        J is singular at a configuration that is not far away).
        """
        g, J = self.system.system(X, q)
        dx = solve_linear(J, -g)
        solved = np.isfinite(dx).all(axis=1)
        near = np.max(np.abs(X), axis=1) <= FAR * self.size
        finite = solved & near
        dx[~finite] = 0.0
        big = np.max(np.abs(dx), axis=1)
        if damped:
            dx *= np.minimum(1.0, 0.5 * self.shortest / np.where(big > 0, big, 1.0))[:, None]
            dx = self._line_search(X, q, g, dx)
        return dx, big, finite, ~solved & near

    def _confirmed(self, X, q, conv, limit):
        """``conv`` cleared where the residual exceeds 10 ``limit`` (plus rounding)."""
        if conv.any():
            rows = np.nonzero(conv)[0]
            res = np.max(np.abs(self.system.residual(X[rows], q[rows])), axis=1)
            conv[rows[~(res <= 10 * limit + 1e-14 * self.size)]] = False
        return conv

    def _closed(self, X, q):
        """Whether each configuration closes to rounding: max |g| <= ROUNDING size."""
        if not q.size:
            return np.zeros(0, bool)
        res = np.max(np.abs(self.system.residual(X, q)), axis=1)
        return res <= ROUNDING * self.size

    def _line_search(self, X, q, g, dx):
        """Halve each step until |g|^2 decreases by ARMIJO alpha at least (Armijo)."""
        f0 = np.sum(g * g, axis=1)
        alpha = np.ones(len(q))
        todo = np.arange(len(q))
        for _ in range(HALVINGS):
            trial = self.system.residual(self.system.moved(X[todo], alpha[todo, None] * dx[todo]),
                                         q[todo])
            better = np.sum(trial * trial, axis=1) <= (1 - ARMIJO * alpha[todo]) * f0[todo]
            todo = todo[~better]
            if todo.size == 0:
                break
            alpha[todo] *= 0.5
        return dx * alpha[:, None]

    def tangent(self, X, q):
        """dX/dq at solved configurations (the velocities for a unit driver rate), with
        the rates of the angles X carries."""
        P = self.system.points(X)
        J = self.system.jacobian(P, q)
        V = solve_linear(J, self.system.rate_rhs(P, q, np.ones_like(q)))
        return np.concatenate([V, self.system.turn_rates(X, V)], axis=1)
