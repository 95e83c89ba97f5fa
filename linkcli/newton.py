"""Newton-Raphson on the constraint equations of the whole mechanism.

The unknowns are the coordinates (x, y) of every moving point.  Every
constraint is a bilinear form of two point differences,

    g = Re(k conj(U) V) - v(q),    U = P_c - P_b (+ e^{iq} for a driving angle),
                                   V = P_p - P_a,   k = 1 (dot) or -i (cross),

so its gradient is analytic: dg = Re(conj(k V) dU) + Re(conj(conj(k) U) dV).

- a link: |P_1 - P_0|^2 = L^2 for its first two points and, for every further
  point P_j, the dot and the cross product of P_j - P_0 with P_1 - P_0.  This
  is the same as the distances of P_j from P_0 and P_1 plus the side of P_0P_1
  it lies on, so the body stays rigid and keeps its chirality;
- a slider block: each of its points on its line, cross(C - B, P - B) = value;
  carried points also at a fixed dot(C - B, P_j - P_0);
- the driver: cross(e^{iq}, P_b - P_a) = 0 (angle; the driving link's own
  length equation then reads dot(e^{iq}, P_b - P_a) = L, so the link cannot
  point backwards), |P_b - P_a|^2 = q^2 (length), or x (y) of P_a = q.

Each equation is divided by a constant length of its own (link length, guide
length, 1 for the driver) so that residuals are lengths and the Jacobian J is
dimensionless.  Velocities solve J v = -dg/dq qdot; accelerations
J a = -(d2g/dt2 without the unknown accelerations).

Sweeps are solved by continuation from the file's position: a predictor
X + X' dq and Newton's corrector, the step halved whenever the corrector needs
many iterations or lands farther than a small fraction of the shortest link
from the prediction (so a step never jumps to another assembly branch).  The
other driver values are corrected in vectorised batches from the nearest
solved one.  Tolerances are relative to the mechanism's size.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .dyads import cis
from .errors import AssemblyError, InputError, SingularError, StructureError
from .kinematics import Kinematics, _driver_base, _q_text
from .model import FRAME
from .topology import one_dof

DEFAULT_TOL = 1e-12
CHUNK = 1 << 14          # positions per batched linear solve
NODES = 64               # continuation nodes along a long sweep
CORRECTOR_ITER = 12      # Newton iterations allowed to a continuation corrector
MAX_ITER = 80            # iterations allowed from a distant start
JUMP = 0.05              # largest corrector move, as a fraction of the shortest link
MIN_STEP = 1e-10         # smallest continuation step (rad, or fraction of the size)
FAR = 1e3                # points farther than FAR sizes from the origin: no configuration
ROUNDING = 8 * np.finfo(float).eps   # residual (relative to the size) that is exact closure
# At a toggle Newton finds the position only to about sqrt(eps) (the equations are flat
# there), so its conditioning measure stays near 1e-8: below SINGULAR_NEWTON is singular.
SINGULAR_NEWTON = 1e-7


@dataclass(frozen=True)
class Row:
    """One equation Re(k conj(P_c - P_b [+ e^{iq}]) (P_p - P_a)) = v0 + vq q + vqq q^2,
    divided by ``scale`` (a length)."""

    b: int
    c: int
    a: int
    p: int
    k: complex
    v0: float
    scale: float
    label: str
    vq: float = 0.0
    vqq: float = 0.0
    uq: bool = False


class _Whole:
    """The whole mechanism as one group, for messages and per-group reports."""

    kind = "newton"
    point = None
    branch = 0

    def __init__(self, count: int):
        self.count = count

    def describe(self) -> str:
        return f"the mechanism's {self.count} constraint equations (Newton)"


class Constraints:
    """The equations of a mechanism, evaluated on batches of configurations."""

    def __init__(self, mech):
        self.mech = mech
        fixed = list(mech.fixed)
        self.moving = list(mech.moving)
        self.names = fixed + self.moving + ["~zero", "~one"]
        index = {name: i for i, name in enumerate(self.names)}
        self.nf, self.nm = len(fixed), len(self.moving)
        self.zero, self.one = len(self.names) - 2, len(self.names) - 1
        self.base = np.array([mech.fixed[n] for n in fixed] + [0j] * self.nm + [0j, 1 + 0j])
        rows, lengths = [], []
        self.drive_pair = None     # the link whose points a, b the driving angle turns
        for body in mech.bodies.values():
            if body.kind == "link":
                rows += self._link(body, index, lengths)
            elif body.kind == "block":
                rows += self._block(body, index)
        rows.append(self._driver(mech.driver, index))
        rows = [r for r in rows if any(self.nf <= i < self.nf + self.nm
                                       for i in (r.b, r.c, r.a, r.p))]
        self.rows = rows
        self.n = 2 * self.nm
        if len(rows) != self.n:
            raise StructureError(
                f"the point equations are not square: {len(rows)} equations for {self.n} "
                "unknown coordinates", file=mech.file,
                hint="every moving point must belong to a link or a slider that fixes it")
        self.b = np.array([r.b for r in rows])
        self.c = np.array([r.c for r in rows])
        self.a = np.array([r.a for r in rows])
        self.p = np.array([r.p for r in rows])
        self.k = np.array([r.k for r in rows])
        self.v0 = np.array([r.v0 for r in rows])
        self.vq = np.array([r.vq for r in rows])
        self.vqq = np.array([r.vqq for r in rows])
        self.uq = np.array([r.uq for r in rows])
        self.inv_scale = 1.0 / np.array([r.scale for r in rows])
        self.shortest = min(lengths) if lengths else None
        # J = [Re kV, Im kV, Re k*U, Im k*U] @ scatter: the gradients placed in their columns
        R = len(rows)
        self.scatter = np.zeros((4 * R, R * self.n))
        for which, offset, sign in (("c", 0, 1.0), ("b", 0, -1.0), ("p", 2, 1.0), ("a", 2, -1.0)):
            idx = getattr(self, which)
            for r in np.nonzero((idx >= self.nf) & (idx < self.nf + self.nm))[0]:
                col = r * self.n + 2 * (idx[r] - self.nf)
                self.scatter[offset * R + r, col] += sign
                self.scatter[(offset + 1) * R + r, col + 1] += sign

    # building -----------------------------------------------------------------
    def _link(self, body, index, lengths):
        p0, p1 = body.points[:2]
        d = self.mech.driver
        driven = d.kind == "angle" and self.drive_pair is None and {d.a, d.b} <= set(body.points)
        if driven:                 # base the body on the driving vector a -> b
            p0, p1 = d.a, d.b
        local = body.local
        edge = local[p1] - local[p0]
        length = abs(edge)
        lengths.append(length)
        i0, i1 = index[p0], index[p1]
        if driven:       # dot(e^{iq}, P_b - P_a) = L; with the cross row: P_b - P_a = L e^{iq}
            self.drive_pair = (body.name, length)
            rows = [Row(self.zero, self.zero, i0, i1, 1, length, 1.0,
                        f"driver: {p0}->{p1} along q", uq=True)]
        else:
            rows = [Row(i0, i1, i0, i1, 1, length * length, length, f"{body.name}: |{p0}{p1}|")]
        for pj in [p for p in body.points if p not in (p0, p1)]:
            rel = edge.conjugate() * (local[pj] - local[p0])
            ij = index[pj]
            rows.append(Row(i0, i1, i0, ij, 1, rel.real, length, f"{body.name}: {pj} along"))
            rows.append(Row(i0, i1, i0, ij, -1j, rel.imag, length, f"{body.name}: {pj} side"))
            lengths.append(abs(local[pj] - local[p0]))
        return rows

    def _block(self, body, index):
        guide = body.guide
        if guide.carrier == FRAME:
            length = abs(self.mech.fixed[guide.c] - self.mech.fixed[guide.b])
        else:
            carrier = self.mech.bodies[guide.carrier].local
            length = abs(carrier[guide.c] - carrier[guide.b])
        ib, ic = index[guide.b], index[guide.c]
        p0 = body.points[0]
        rows = []
        for pj in body.points:
            offset = body.local[pj] - body.local[p0]
            rows.append(Row(ib, ic, ib, index[pj], -1j,
                            length * (guide.offset + body.local[pj].imag), length,
                            f"{body.name}: {pj} on its guide"))
            if pj != p0:
                rows.append(Row(ib, ic, index[p0], index[pj], 1, length * offset.real, length,
                                f"{body.name}: {pj} along the guide"))
        return rows

    def _driver(self, d, index):
        if d.kind == "angle":
            return Row(self.zero, self.zero, index[d.a], index[d.b], -1j, 0.0, 1.0,
                       f"driver: angle of {d.a}->{d.b}", uq=True)
        if d.kind == "length":
            ia, ib = index[d.a], index[d.b]
            return Row(ia, ib, ia, ib, 1, 0.0, abs(d.value), f"driver: |{d.a}{d.b}|", vqq=1.0)
        return Row(self.zero, self.one, self.zero, index[d.a], 1 if d.kind == "x" else -1j,
                   0.0, 1.0, f"driver: {d.kind} of {d.a}", vq=1.0)

    # evaluation ---------------------------------------------------------------
    def points(self, X):
        """All points (N, npts) complex from the unknowns X (N, n)."""
        P = np.empty((X.shape[0], len(self.names)), complex)
        P[:] = self.base
        P.real[:, self.nf:self.nf + self.nm] = X[:, 0::2]
        P.imag[:, self.nf:self.nf + self.nm] = X[:, 1::2]
        return P

    def _uv(self, P, q):
        U = P[:, self.c] - P[:, self.b]
        if self.uq.any():
            U[:, self.uq] += cis(q)[:, None]
        return U, P[:, self.p] - P[:, self.a]

    def residual(self, X, q):
        """Scaled residuals (N, R), lengths."""
        U, V = self._uv(self.points(X), q)
        g = (self.k * U.conj() * V).real
        g -= self.v0 + np.multiply.outer(q, self.vq) + np.multiply.outer(q * q, self.vqq)
        return g * self.inv_scale

    def jacobian(self, P, q, U=None, V=None):
        """Scaled Jacobian (N, R, n) of the residuals with respect to the unknowns."""
        if U is None:
            U, V = self._uv(P, q)
        kV = self.k * V * self.inv_scale
        kU = self.k.conj() * U * self.inv_scale
        src = np.concatenate([kV.real, kV.imag, kU.real, kU.imag], axis=1)
        return (src @ self.scatter).reshape(P.shape[0], len(self.rows), self.n)

    def system(self, X, q):
        """Residuals and Jacobian at once."""
        P = self.points(X)
        U, V = self._uv(P, q)
        g = (self.k * U.conj() * V).real
        g -= self.v0 + np.multiply.outer(q, self.vq) + np.multiply.outer(q * q, self.vqq)
        return g * self.inv_scale, self.jacobian(P, q, U, V)

    def rate_rhs(self, P, q, qd, qdd=None, W=None):
        """Right-hand side of J v = rhs (``W`` None) or J a = rhs (``W`` the velocities).

        First rates: -(dg/dq) qd.  Second: -(Re(k conj(U''_q) V) + 2 Re(k conj(U') V')
        - v''), with U''_q = (i qdd - qd^2) e^{iq} on driving-angle rows.
        """
        U, V = self._uv(P, q)
        qd = np.broadcast_to(qd, q.shape)
        e = cis(q)[:, None] if self.uq.any() else 0.0
        if W is None:
            known = np.zeros(U.shape)
            if self.uq.any():
                known[:, self.uq] = (self.k[self.uq] * np.conj(1j * qd[:, None] * e)
                                     * V[:, self.uq]).real
            known -= np.multiply.outer(qd, self.vq) + np.multiply.outer(2 * q * qd, self.vqq)
            return -known * self.inv_scale
        qdd = np.broadcast_to(qdd, q.shape)
        dU = W[:, self.c] - W[:, self.b]
        dV = W[:, self.p] - W[:, self.a]
        if self.uq.any():
            dU[:, self.uq] += 1j * qd[:, None] * e
        known = 2.0 * (self.k * dU.conj() * dV).real
        if self.uq.any():
            known[:, self.uq] += (self.k[self.uq] * np.conj((1j * qdd - qd * qd)[:, None] * e)
                                  * V[:, self.uq]).real
        known -= np.multiply.outer(qdd, self.vq)
        known -= np.multiply.outer(2 * qd * qd + 2 * q * qdd, self.vqq)
        return -known * self.inv_scale

    def measure(self, J):
        """|det J| / prod(|row|): 0 when singular, 1 when the rows are orthogonal."""
        norms = np.prod(np.linalg.norm(J, axis=2), axis=1)
        return np.abs(np.linalg.det(J)) / np.where(norms > 0, norms, 1.0)


def _solve(J, r):
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
        Jb = J[bad]
        Jt = np.swapaxes(Jb, 1, 2)
        A = Jt @ Jb
        mu = 1e-14 * np.trace(A, axis1=1, axis2=2) + 1e-300
        A = A + mu[:, None, None] * np.eye(J.shape[2])
        out[bad] = np.linalg.solve(A, Jt @ r[bad][..., None])[..., 0]
        return np.where(np.isfinite(out), out, 0.0)


class NewtonSolver:
    """Solver with the interface of :class:`linkcli.kinematics.Solver`, by Newton-Raphson."""

    method = "newton"
    singular = SINGULAR_NEWTON

    def __init__(self, mech, tol: float = DEFAULT_TOL):
        if not 0 < tol < 1:
            raise InputError(f"the tolerance must be between 0 and 1, got {tol}", key="tol",
                             hint="it is relative to the mechanism's size, e.g. 1e-12")
        self.mech = mech
        self.tol = float(tol)
        one_dof(mech)
        self.system = Constraints(mech)
        self.groups = [_Whole(len(self.system.rows))]
        self.fixed = dict(mech.fixed)
        pts = [p for n, p in mech.fixed.items() if not n.startswith("~")] + list(
            mech.moving.values())
        spread = max(abs(p - q) for p in pts for q in pts) if len(pts) > 1 else 0.0
        self.size = max(spread, self.system.shortest or 0.0, abs(mech.driver.value)
                        if mech.driver.kind != "angle" else 0.0) or 1.0
        self.shortest = self.system.shortest or self.size
        self.q_scale = 1.0 if mech.driver.kind == "angle" else self.size
        self.iterations = 0
        self.q0 = float(mech.driver.value)
        self.x0 = self._nominal()

    # one batch of Newton iterations ---------------------------------------------
    def newton(self, X, q, max_iter, damped=False):
        """Iterate every row of X (N, n) at its q; returns (X, converged mask)."""
        X = np.array(X, dtype=float)
        q = np.asarray(q, dtype=float)
        done = np.zeros(len(q), bool)
        active = np.arange(len(q))
        limit = self.tol * self.size
        cap = 0.5 * self.shortest
        far = FAR * self.size
        stalled = []
        for _ in range(max_iter):
            if active.size == 0:
                break
            Xa, qa = X[active], q[active]
            g, J = self.system.system(Xa, qa)
            dx = _solve(J, -g)
            solved = np.isfinite(dx).all(axis=1)
            near = np.max(np.abs(Xa), axis=1) <= far
            finite = solved & near
            stalled.append(active[~solved & near])
            dx[~finite] = 0.0
            big = np.max(np.abs(dx), axis=1)
            if damped:
                dx *= np.minimum(1.0, cap / np.where(big > 0, big, 1.0))[:, None]
                dx = self._line_search(Xa, qa, g, dx)
            Xa = Xa + dx
            X[active] = Xa
            self.iterations += 1
            conv = finite & (big <= limit)
            if conv.any():
                res = np.max(np.abs(self.system.residual(Xa[conv], qa[conv])), axis=1)
                ok = res <= 10 * limit + 1e-14 * self.size
                done[active[np.nonzero(conv)[0][ok]]] = True
                conv[np.nonzero(conv)[0][~ok]] = False
            active = active[~conv & finite]
        rest = np.concatenate([active] + stalled)
        if rest.size:      # at a toggle J is singular and the steps shrink only linearly:
            res = np.max(np.abs(self.system.residual(X[rest], q[rest])), axis=1)
            done[rest[res <= ROUNDING * self.size]] = True      # closed to rounding
        return X, done

    def _line_search(self, X, q, g, dx):
        """Halve each step until the residual norm decreases (Armijo)."""
        f0 = np.sum(g * g, axis=1)
        alpha = np.ones(len(q))
        todo = np.arange(len(q))
        for _ in range(12):
            trial = self.system.residual(X[todo] + alpha[todo, None] * dx[todo], q[todo])
            better = np.sum(trial * trial, axis=1) <= (1 - 1e-4 * alpha[todo]) * f0[todo]
            todo = todo[~better]
            if todo.size == 0:
                break
            alpha[todo] *= 0.5
        return dx * alpha[:, None]

    def tangent(self, X, q):
        """dX/dq at solved configurations (the velocities for a unit driver rate)."""
        P = self.system.points(X)
        J = self.system.jacobian(P, q)
        return _solve(J, self.system.rate_rhs(P, q, np.ones_like(q)))

    # the file's position ----------------------------------------------------------
    def _nominal(self):
        """Solve at the file's driver value, starting from the figure's positions."""
        sys_ = self.system
        guess = np.empty(sys_.n)
        for j, name in enumerate(sys_.moving):
            guess[2 * j], guess[2 * j + 1] = self.mech.moving[name].real, \
                self.mech.moving[name].imag
        d = self.mech.driver
        if d.kind == "angle":     # place the crank tip exactly on the driving direction
            for tip, pivot, sign in ((d.b, d.a, 1.0), (d.a, d.b, -1.0)):
                if tip in self.mech.moving and pivot in self.mech.fixed:
                    j = sys_.moving.index(tip)
                    arm = abs(self.mech.moving[tip] - self.mech.fixed[pivot])
                    z = self.mech.fixed[pivot] + sign * arm * complex(np.cos(self.q0),
                                                                       np.sin(self.q0))
                    guess[2 * j], guess[2 * j + 1] = z.real, z.imag
        X, ok = self.newton(guess[None], np.array([self.q0]), MAX_ITER, damped=True)
        if not ok[0]:
            q_unit, q_factor = self.mech.units.display(_driver_base(self.mech), 0)
            raise AssemblyError(
                f"Newton cannot assemble the mechanism at q = {self.q0 / q_factor:.6g} {q_unit} "
                "from the figure's positions", file=self.mech.file, group="newton", q=self.q0,
                shortfall=float("inf"),
                hint="check the lengths and give approximate positions closer to the figure")
        return X[0]

    # continuation ------------------------------------------------------------------
    def _advance(self, X, dX, q, target):
        """Continue from (q, X) to ``target``; returns (X, dX, q reached, arrived)."""
        h = target - q
        min_step = MIN_STEP * self.q_scale
        while q != target:
            if abs(h) < min_step:
                return X, dX, q, False
            if abs(h) >= abs(target - q):
                h, q_next = target - q, target
            else:
                q_next = q + h
            pred = X + dX * (q_next - q)
            Xn, ok = self.newton(pred[None], np.array([q_next]), CORRECTOR_ITER)
            if ok[0] and np.max(np.abs(Xn[0] - pred)) <= JUMP * self.shortest:
                X, q = Xn[0], q_next
                dX = self.tangent(X[None], np.array([q]))[0]
                h *= 2.0
            else:
                h *= 0.5
        return X, dX, q, True

    def _walk(self, nodes):
        """Continue from the file's position through ``nodes`` (in walking order).

        Returns anchors [(q, X, dX)] and assembled intervals [(q_lo, q_hi)].
        """
        q = self.q0
        X = self.x0
        dX = self.tangent(X[None], np.array([q]))[0]
        anchors, segments, start = [(q, X, dX)], [], q
        i = 0
        while i < len(nodes):
            Xn, dXn, qn, arrived = self._advance(X, dX, q, nodes[i])
            if arrived:
                X, dX, q = Xn, dXn, qn
                anchors.append((q, X, dX))
                i += 1
                continue
            if qn != q:
                anchors.append((qn, Xn, dXn))
            segments.append((start, qn))
            rest = np.asarray(nodes[i:], dtype=float)
            for start_x in (Xn, self.x0):    # from the gap's edge, then from the file's position
                Xr, ok = self.newton(np.repeat(start_x[None], len(rest), axis=0), rest,
                                     MAX_ITER, damped=True)
                if ok.any():
                    break
            else:
                return anchors, segments
            k = int(np.argmax(ok))
            q, X = float(rest[k]), Xr[k]
            dX = self.tangent(X[None], np.array([q]))[0]
            anchors.append((q, X, dX))
            Xb, dXb, qb = X, dX, q            # back through the skipped nodes to the gap's edge
            for target in [float(x) for x in rest[:k][::-1]] + [qn]:
                Xb, dXb, qb_new, arrived = self._advance(Xb, dXb, qb, target)
                if qb_new != qb:
                    anchors.append((qb_new, Xb, dXb))
                qb = qb_new
                if not arrived:
                    break
            start = qb
            i += k + 1
        segments.append((start, q))
        return anchors, segments

    def track(self, qs):
        """Solve every driver value of the flat array ``qs``; returns (X (N, n), ok)."""
        qs = np.asarray(qs, dtype=float)
        n = qs.size
        X = np.zeros((n, self.system.n))
        ok = np.zeros(n, bool)
        if n == 0:
            return X, ok
        order = np.argsort(qs, kind="stable")
        s = qs[order]
        finite = np.isfinite(s)
        uniq = np.unique(s[finite])
        step = max(1, int(np.ceil(uniq.size / NODES)))
        nodes = np.unique(np.concatenate([uniq[::step], uniq[-1:]]))
        up = nodes[nodes > self.q0]
        down = nodes[nodes < self.q0][::-1]
        anchors, segments = [], []
        for part in (up, down):
            a, sgm = self._walk(list(part))
            anchors += a
            segments += sgm
        anchors.sort(key=lambda t: t[0])
        aq = np.array([t[0] for t in anchors])
        lo = np.array([min(a, b) for a, b in segments])
        hi = np.array([max(a, b) for a, b in segments])
        inside = np.zeros(n, bool)
        seg_of = np.full(n, -1)
        for j in range(len(segments)):
            m = (qs >= lo[j]) & (qs <= hi[j])
            seg_of[m & ~inside] = j
            inside |= m
        # nearest anchor of the same interval
        pos = np.searchsorted(aq, qs)
        left = np.clip(pos - 1, 0, len(aq) - 1)
        right = np.clip(pos, 0, len(aq) - 1)
        choose = np.where(np.abs(aq[right] - qs) < np.abs(qs - aq[left]), right, left)
        for cand in (left, right):      # prefer an anchor inside the target's interval
            bad = ~_within(aq[choose], seg_of, lo, hi)
            choose = np.where(bad, cand, choose)
        idx = np.nonzero(inside)[0]
        AX = np.array([t[1] for t in anchors])
        AD = np.array([t[2] for t in anchors])
        failed = []
        for start in range(0, idx.size, CHUNK):
            sl = idx[start:start + CHUNK]
            a = choose[sl]
            pred = AX[a] + AD[a] * (qs[sl] - aq[a])[:, None]
            Xc, conv = self.newton(pred, qs[sl], CORRECTOR_ITER)
            jump = np.max(np.abs(Xc - pred), axis=1) <= JUMP * self.shortest
            good = conv & jump
            X[sl[good]] = Xc[good]
            ok[sl[good]] = True
            failed.append(sl[~good])
        failed = np.concatenate(failed) if failed else np.zeros(0, int)
        for a in np.unique(choose[failed]):   # rare (near folds): chained sub-stepping
            group = failed[choose[failed] == a]
            for side in (group[qs[group] >= aq[a]], group[qs[group] < aq[a]]):
                Xc, dXc, qc = AX[a], AD[a], float(aq[a])
                for j in side[np.argsort(np.abs(qs[side] - aq[a]), kind="stable")]:
                    Xn, dXn, qn, arrived = self._advance(Xc, dXc, qc, float(qs[j]))
                    if not arrived:
                        break
                    X[j], ok[j] = Xn, True
                    Xc, dXc, qc = Xn, dXn, qn
        return X, ok

    # the Solver interface --------------------------------------------------------
    def positions(self, q) -> Kinematics:
        q = np.asarray(q, dtype=float)
        X, ok = self.track(q.ravel())
        kin = Kinematics(q)
        kin.pos.update(self.fixed)
        for j, name in enumerate(self.system.moving):
            kin.pos[name] = (X[:, 2 * j] + 1j * X[:, 2 * j + 1]).reshape(q.shape)
        if (~ok).any():
            error = np.zeros(q.size)
            bad = np.nonzero(~ok)[0]
            res = self.system.residual(X[bad], q.ravel()[bad])
            error[bad] = np.maximum(np.max(np.abs(res), axis=1), self.tol * self.size)
            kin.short[0] = error.reshape(q.shape)
        else:
            kin.short[0] = np.zeros(q.shape)
        return kin

    def _unknowns(self, kin):
        q = np.broadcast_to(kin.q, np.shape(kin.q)).ravel()
        X = np.empty((q.size, self.system.n))
        for j, name in enumerate(self.system.moving):
            z = np.broadcast_to(kin.pos[name], kin.q.shape).ravel()
            X[:, 2 * j], X[:, 2 * j + 1] = z.real, z.imag
        return q, X

    def _rates(self, kin, qd, qdd=None):
        q, X = self._unknowns(kin)
        out = np.empty((q.size, self.system.n))
        measure = np.empty(q.size) if qdd is None else None
        qd = np.broadcast_to(np.asarray(qd, float), kin.q.shape).ravel()
        if qdd is not None:
            qdd = np.broadcast_to(np.asarray(qdd, float), kin.q.shape).ravel()
            W = self._velocity_points(kin)
        for start in range(0, q.size, CHUNK):
            sl = slice(start, start + CHUNK)
            P = self.system.points(X[sl])
            J = self.system.jacobian(P, q[sl])
            if qdd is None:
                rhs = self.system.rate_rhs(P, q[sl], qd[sl])
                measure[sl] = self.system.measure(J)
            else:
                rhs = self.system.rate_rhs(P, q[sl], qd[sl], qdd[sl], W[sl])
            out[sl] = _solve(J, rhs)
        rates = {}
        for j, name in enumerate(self.system.moving):
            rates[name] = (out[:, 2 * j] + 1j * out[:, 2 * j + 1]).reshape(kin.q.shape)
        if measure is not None:
            kin.measure[0] = measure.reshape(kin.q.shape)
        return rates

    def _velocity_points(self, kin):
        W = np.zeros((np.size(kin.q), len(self.system.names)), complex)
        for j, name in enumerate(self.system.moving):
            W[:, self.system.nf + j] = np.broadcast_to(kin.vel[name], kin.q.shape).ravel()
        return W

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

    def check(self, kin: Kinematics, velocities: bool):
        """Raise when Newton found no configuration or (for rates) J is singular."""
        q_unit, q_factor = self.mech.units.display(_driver_base(self.mech), 0)
        l_unit, l_factor = self.mech.units.display("length", 0)
        short = kin.short.get(0)
        if short is not None and np.any(short > 0):
            bad = np.broadcast_to(short > 0, kin.q.shape)
            worst = float(np.max(short))
            where = _q_text(kin.q, bad, q_factor, q_unit)
            raise AssemblyError(
                f"cannot assemble {self.groups[0].describe()} {where}: no convergence, "
                f"closure error {worst / l_factor:.4g} {l_unit}", file=self.mech.file,
                group=self.groups[0].describe(), q=kin.q, shortfall=worst,
                hint="check the lengths and the driver value")
        if not velocities:
            return
        measure = kin.measure.get(0)
        if measure is not None and np.any(measure < self.singular):
            bad = np.broadcast_to(measure < self.singular, kin.q.shape)
            where = _q_text(kin.q, bad, q_factor, q_unit)
            raise SingularError(
                f"singular position (toggle or dead point) of {self.groups[0].describe()} "
                f"{where}: conditioning {float(np.min(measure)):.2e} (|det J| over the product "
                "of its row norms); velocities are undefined there", file=self.mech.file,
                group=self.groups[0].describe(), q=kin.q, measure=float(np.min(measure)),
                hint="move the driver away from the toggle")


def _within(values, seg_of, lo, hi):
    j = np.clip(seg_of, 0, len(lo) - 1)
    return (seg_of >= 0) & (values >= lo[j]) & (values <= hi[j])


def newton_solver(mech, tol: float | None = None) -> NewtonSolver:
    """The mechanism's Newton solver for ``tol`` (cached on the mechanism)."""
    tol = DEFAULT_TOL if tol is None else float(tol)
    cache = mech.extras.setdefault("newton", {})
    if tol not in cache:
        cache[tol] = NewtonSolver(mech, tol)
    return cache[tol]
