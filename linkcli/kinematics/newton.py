"""Newton-Raphson on the constraint equations of the whole mechanism.

The solver has the interface of :class:`linkcli.kinematics.Solver`.  Positions
come from :mod:`linkcli.continuation` (predictor-corrector from the file's
position, which Newton finds from the figure's points); velocities and
accelerations solve J v = rhs and J a = rhs (:mod:`linkcli.constraints`), with
J the Jacobian of the equations of :mod:`linkcli.equations`.  Tolerances are
relative to the mechanism's size.
"""
from __future__ import annotations

import numpy as np

from linkcli.kinematics.constraints import Constraints
from linkcli.kinematics.continuation import Continuation
from linkcli.kinematics.corrector import CHUNK, MAX_ITER, Corrector, solve_linear
from linkcli.errors import AssemblyError, InputError
from linkcli.kinematics.branches import far_from_figure, figure_coordinates
from linkcli.kinematics.closed_form import Kinematics
from linkcli.kinematics.grubler import one_dof
from linkcli.kinematics.refusals import assembly_error, length_text, singular_error, where_text

__all__ = ["Constraints", "NewtonSolver", "DEFAULT_TOL", "SINGULAR_NEWTON"]

DEFAULT_TOL = 1e-12
# At a toggle Newton finds the position only to about sqrt(eps) (the equations are flat
# there), so its conditioning measure stays near 1e-8: below SINGULAR_NEWTON is singular.
SINGULAR_NEWTON = 1e-7


class _Whole:
    """The whole mechanism as one group, for messages and per-group reports."""

    kind = "newton"
    point = None
    branch = 0

    def __init__(self, count: int):
        self.count = count

    def describe(self) -> str:
        return f"the mechanism's {self.count} constraint equations (Newton)"


class NewtonSolver(Corrector):
    """Solver with the interface of :class:`linkcli.kinematics.Solver`, by Newton-Raphson."""

    method = "newton"
    singular = SINGULAR_NEWTON

    def __init__(self, mech, tol: float = DEFAULT_TOL):
        if not 0 < tol < 1:
            raise InputError(f"the tolerance must be between 0 and 1, got {tol}", key="tol",
                             hint="it is relative to the mechanism's size, e.g. 1e-12")
        self.mech = mech
        one_dof(mech)
        if len(mech.coordinates) > 1:
            raise InputError(f"--method newton solves a mechanism of one driver; this one has "
                             f"{len(mech.coordinates)} ("
                             + ", ".join(c.name for c in mech.coordinates) + ")",
                             file=mech.file, key="--method",
                             hint="solve it by the closed form (the default method)")
        system = Constraints(mech)
        size = _size(mech, system.shortest)
        super().__init__(system, tol, size, system.shortest or size)
        self.groups = [_Whole(len(system.rows))]
        self.fixed = dict(mech.fixed)
        self.q_scale = 1.0 if mech.driver.kind == "angle" else size
        self.q0 = float(mech.driver.value)
        self.x0 = self._nominal()
        self.continuation = Continuation(self, self.q0, self.x0, self.q_scale)
        #: what the figure check says (as the closed form's): points solved far from it
        self.undetermined = None
        self.cautions = far_from_figure(mech, {**self.fixed, **self._points(self.x0[None], ())}) \
            if mech.as_drawn else []

    # the file's position ----------------------------------------------------------
    def _nominal(self):
        """Solve at the file's driver value.  Where contacts count turns on points, by
        continuation from the figure's own driver value (where every turn is the figure's),
        so that a disc the driver turns by more than half a turn is counted whole; else (or
        when the driver cannot be followed there) from the figure's positions, a driving
        crank turned to q0, each turn within half a turn of the figure's."""
        if self.system.turns:
            X = self._from_figure()
            if X is not None:
                return X
        start = self.system.augment(self._figure()[None])
        X, ok = self.newton(start, np.array([self.q0]), MAX_ITER, damped=True)
        if not ok[0]:
            raise AssemblyError(
                f"Newton cannot assemble the mechanism {where_text(self.mech, self.q0, True)} "
                "from the figure's positions", file=self.mech.file, group="newton", q=self.q0,
                shortfall=float("inf"),
                hint="check the lengths and give approximate positions closer to the figure")
        return X[0]

    def _from_figure(self):
        """The file's position continued from the figure's, solved at the driver value the
        figure draws (an angle on the turn nearest q0); None where either fails."""
        drawn = figure_coordinates(self.mech)
        if self.mech.driver.kind == "angle":
            drawn += 2 * np.pi * round((self.q0 - drawn) / (2 * np.pi))
        figure = _unknowns([self.mech.moving[name] for name in self.system.moving], 1)
        X, ok = self.newton(self.system.augment(figure), np.array([drawn]), MAX_ITER,
                            damped=True)
        if not ok[0]:
            return None
        return Continuation(self, drawn, X[0], self.q_scale).reach(self.q0)

    def _figure(self, q=None):
        """The unknowns at the figure's positions, a driving crank's tip turned to q
        (default q0): P_tip = P_pivot +- |P_tip - P_pivot| e^{i q}; a point driven along x
        (y) moved to x = q (y = q)."""
        q = self.q0 if q is None else q
        moving = dict(self.mech.moving)
        d = self.mech.driver
        if d.kind == "angle":
            for tip, pivot, sign in ((d.b, d.a, 1.0), (d.a, d.b, -1.0)):
                if tip in moving and pivot in self.mech.fixed:
                    arm = abs(moving[tip] - self.mech.fixed[pivot])
                    moving[tip] = self.mech.fixed[pivot] + sign * arm * complex(
                        np.cos(q), np.sin(q))
        elif d.kind in ("x", "y") and d.a in moving:
            z = moving[d.a]
            moving[d.a] = complex(q, z.imag) if d.kind == "x" else complex(z.real, q)
        return _unknowns([moving[name] for name in self.system.moving], 1)[0]

    def figure_starts(self, qs):
        """Starts (N, width) for the driver values ``qs``: the figure, the crank turned."""
        return self.system.augment(np.array([self._figure(q) for q in qs]))

    # the Solver interface --------------------------------------------------------
    def track(self, qs):
        """Solve every driver value of the flat array ``qs``; returns (X (N, n), ok)."""
        return self.continuation.track(qs)

    def positions(self, q) -> Kinematics:
        q = np.asarray(q, dtype=float)
        X, ok = self.track(q.ravel())
        kin = Kinematics(q)
        kin.pos.update(self.fixed)
        kin.pos.update(self._points(X, q.shape))
        kin.short[0] = self._closure_error(X, q.ravel(), ok).reshape(q.shape)
        return kin

    def _closure_error(self, X, q, ok):
        """max |g| (at least tol size) where no configuration was found, else 0."""
        error = np.zeros(q.size)
        bad = np.nonzero(~ok)[0]
        if bad.size:
            res = self.system.residual(X[bad], q[bad])
            error[bad] = np.maximum(np.max(np.abs(res), axis=1), self.tol * self.size)
        return error

    def _points(self, X, shape):
        """The moving points (complex arrays of ``shape``) from the unknowns X (N, n)."""
        return {name: (X[:, 2 * j] + 1j * X[:, 2 * j + 1]).reshape(shape)
                for j, name in enumerate(self.system.moving)}

    def velocities(self, kin: Kinematics, qd) -> Kinematics:
        kin.qd = np.asarray(qd, dtype=float)
        kin.vel.clear()
        kin.vectors.clear()
        kin.vel.update(self._rates(kin, kin.qd))
        return kin

    def accelerations(self, kin: Kinematics, qdd) -> Kinematics:
        kin.qdd = np.asarray(qdd, dtype=float)
        kin.acc.clear()
        kin.acc.update(self._rates(kin, kin.qd, kin.qdd))
        return kin

    def _rates(self, kin, qd, qdd=None):
        """Velocities (``qdd`` None; also the conditioning) or accelerations of the
        moving points, solving J v = rhs in chunks of CHUNK positions."""
        shape = kin.q.shape
        q = kin.q.ravel()
        X = _unknowns([np.broadcast_to(kin.pos[n], shape).ravel() for n in self.system.moving],
                      q.size)
        qd = _flat(qd, shape)
        if qdd is not None:
            qdd, W = _flat(qdd, shape), self._velocity_points(kin)
        out = np.empty((q.size, self.system.n))
        measure = np.empty(q.size)
        for start in range(0, q.size, CHUNK):
            sl = slice(start, start + CHUNK)
            P = self.system.points(X[sl])
            J = self.system.jacobian(P, q[sl])
            if qdd is None:
                rhs = self.system.rate_rhs(P, q[sl], qd[sl])
                measure[sl] = self.system.measure(J)
            else:
                rhs = self.system.rate_rhs(P, q[sl], qd[sl], qdd[sl], W[sl])
            out[sl] = solve_linear(J, rhs)
        if qdd is None:
            kin.measure[0] = measure.reshape(shape)
        return self._points(out, shape)

    def _velocity_points(self, kin):
        """Velocities of all points (N, npts), zero for the fixed ones."""
        W = np.zeros((np.size(kin.q), len(self.system.names)), complex)
        for j, name in enumerate(self.system.moving):
            W[:, self.system.nf + j] = np.broadcast_to(kin.vel[name], kin.q.shape).ravel()
        return W

    def check(self, kin: Kinematics, velocities: bool):
        """Raise when Newton found no configuration or (for rates) J is singular."""
        whole = self.groups[0]
        short = kin.short.get(0)
        if short is not None and np.any(short > 0):
            worst = float(np.max(short))
            raise assembly_error(self.mech, whole, kin.q, np.broadcast_to(short > 0, kin.q.shape),
                                 worst, f"no convergence, closure error "
                                 f"{length_text(self.mech, worst)}")
        measure = kin.measure.get(0)
        if velocities and measure is not None and np.any(measure < self.singular):
            raise singular_error(self.mech, whole, kin.q,
                                 np.broadcast_to(measure < self.singular, kin.q.shape), measure,
                                 "|det J| over the product of its row norms")


def _size(mech, shortest):
    """The mechanism's size: the largest distance between its points, at least its
    shortest link and (length drivers) |q|; 1 m when all are zero."""
    pts = [p for n, p in mech.fixed.items() if not n.startswith("~")] + list(
        mech.moving.values())
    spread = max(abs(p - q) for p in pts for q in pts) if len(pts) > 1 else 0.0
    drive = abs(mech.driver.value) if mech.driver.kind != "angle" else 0.0
    return max(spread, shortest or 0.0, drive) or 1.0


def _unknowns(points, count):
    """The unknowns X (count, n) = (x_0, y_0, x_1, ...) from the moving points."""
    X = np.empty((count, 2 * len(points)))
    for j, z in enumerate(points):
        X[:, 2 * j], X[:, 2 * j + 1] = np.real(z), np.imag(z)
    return X


def _flat(values, shape):
    return np.broadcast_to(np.asarray(values, float), shape).ravel()
