"""Newton's path over a sweep: the positions of a block, and of a zoom near a toggle.

Newton continues the configuration from the file's position (``kinematics.continuation``):
it walks once over the nodes of the whole sweep (at most ``continuation.NODES`` of them,
picked from the driver values without holding them all when they ascend or descend),
keeps the states it reached as anchors, then corrects each block's driver values from
the nearest anchor of the same segment (a value it misses is continued to by substeps).
A sweep of one block is solved by the solver's own ``positions``.  Driver values are in
SI here (the caller converts with its ``q_factor``); a row Newton cannot close carries
its closure error as the shortfall of group 0.
"""
from __future__ import annotations

import numpy as np

from linkcli.kinematics import continuation as cont
from linkcli.kinematics.closed_form import Kinematics
from linkcli.runs.sweep.driver_range import DriverRange, block_of, values_at


class NewtonPath:
    """Newton's positions over the driver values ``q`` (display units; ``q_factor`` to SI) of
    a sweep solved ``block_size`` values at a time."""

    def __init__(self, solver, q, q_factor: float, block_size: int):
        self.solver, self.q, self.q_factor, self.block_size = solver, q, q_factor, block_size
        self.size = len(q)
        self._plan = None

    def positions(self, q_si) -> Kinematics:
        """Newton's positions at the driver values ``q_si`` (SI) of one block: corrected
        from the anchors of the whole sweep, walked once on the first call."""
        solver = self.solver
        walker = solver.continuation
        if self._plan is None:
            states, segments = [], []
            for part in self._nodes():
                found, spans = walker._walk(part)
                states += found
                segments += spans
            anchors = cont.Anchors.of(states)
            self._plan = (anchors, np.array([min(a, b) for a, b in segments]),
                          np.array([max(a, b) for a, b in segments]))
        anchors, seg_lo, seg_hi = self._plan
        qs = np.asarray(q_si, dtype=float).ravel()
        X = np.zeros((qs.size, solver.system.width))
        ok = np.zeros(qs.size, bool)
        seg_of = cont._interval_of(qs, seg_lo, seg_hi)
        choose = cont._nearest_anchor(qs, anchors.q, seg_of, seg_lo, seg_hi)
        failed = walker._correct(qs, np.nonzero(seg_of >= 0)[0], choose, anchors, X, ok)
        walker._substep(qs, failed, choose, anchors, X, ok)
        kin = Kinematics(np.asarray(q_si, dtype=float))
        kin.pos.update(solver.fixed)
        kin.pos.update(solver._points(X, kin.q.shape))
        kin.short[0] = solver._closure_error(X, qs, ok).reshape(kin.q.shape)
        return kin

    def _nodes(self):
        """The continuation's nodes of the whole sweep (as ``continuation._nodes`` picks
        them from every driver value), without holding every value when they ascend or
        descend strictly."""
        q0 = self.solver.continuation.q0
        n = self.size
        if isinstance(self.q, DriverRange) and n > 1:
            ends = block_of(self.q, 0, 2) * self.q_factor
            up = ends[1] > ends[0]
            monotonic, previous = True, None
            for lo in range(0, n, self.block_size):
                q = block_of(self.q, lo, min(n, lo + self.block_size)) * self.q_factor
                if previous is not None:
                    q = np.concatenate([[previous], q])
                d = np.diff(q)
                if not (np.all(np.isfinite(q)) and (np.all(d > 0) if up else np.all(d < 0))):
                    monotonic = False
                    break
                previous = q[-1]
            if monotonic:
                step = max(1, int(np.ceil(n / cont.NODES)))
                rank = np.unique(np.concatenate([np.arange(0, n, step), [n - 1]]))
                index = rank if up else n - 1 - rank
                nodes = np.unique(np.concatenate([values_at(self.q, index) * self.q_factor]))
                return nodes[nodes > q0], nodes[nodes < q0][::-1]
        return cont._nodes(np.asarray(self.q, dtype=float) * self.q_factor, q0)


def solve_near(solver, qa, qb, q_factor):
    """Newton's positions at the driver values (SI) of a zoom, each corrected from the
    nearer end of the zoom's interval, solved before (the first ends by one walk from the
    file's position; a value the corrector misses from there is continued to): a zoom
    costs one batch of corrections, not a walk, and never starts from its tip, where
    the tangent is undefined."""
    walker = solver.continuation
    ends = np.array([qa, qb], dtype=float) * q_factor
    X, ok = solver.track(ends)
    known = {float(q): x for q, x, good in zip(ends, X, ok) if good}

    def solve(qs):
        qs = np.asarray(qs, dtype=float)
        kq = np.array([q for q in (qs[0], qs[-1]) if float(q) in known])
        if not kq.size:
            return None
        kX = np.array([known[float(q)] for q in kq])
        near = np.argmin(np.abs(qs[:, None] - kq[None, :]), axis=1)
        kdX = solver.tangent(kX, kq)
        X, ok = walker._predict_correct(kX[near], kdX[near], kq[near], qs)
        for side in range(kq.size):         # the rest continued to, outwards from an end
            missed = np.nonzero(~ok & (near == side))[0]
            order = missed[np.argsort(np.abs(qs[missed] - kq[side]), kind="stable")]
            if order.size:
                walker._chain_into((float(kq[side]), kX[side], kdX[side]), order, qs, X, ok)
        if not ok.all():
            return None
        known.clear()
        known.update(zip(qs.tolist(), X))
        kin = Kinematics(qs)
        kin.pos.update(solver.fixed)
        kin.pos.update(solver._points(X, qs.shape))
        return kin
    return solve
