"""Sweeps of the driver by continuation from the file's position.

A predictor X + X' dq and Newton's corrector walk from the file's position,
up and down, through about NODES driver values spread over the sweep, the step halved
whenever the corrector fails or lands farther than JUMP shortest links from
the prediction (so a step never jumps to another assembly branch).  The
configurations reached are anchors; every other driver value is corrected in
vectorised batches from the nearest anchor of its assembled interval, and the
rare values that still fail (near folds) by sub-stepping from that anchor.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkcli.kinematics.corrector import CHUNK, MAX_ITER

NODES = 64               # continuation nodes along a long sweep
CORRECTOR_ITER = 12      # Newton iterations allowed to a continuation corrector
JUMP = 0.05              # largest corrector move, as a fraction of the shortest link
MIN_STEP = 1e-10         # smallest continuation step (rad, or fraction of the size)


@dataclass(frozen=True)
class Anchors:
    """Solved configurations X (A, n) and tangents dX/dq at the sorted driver values q."""

    q: np.ndarray
    X: np.ndarray
    dX: np.ndarray

    @classmethod
    def of(cls, states):
        """From (q, X, dX) triples, sorted by q (stable)."""
        states = sorted(states, key=lambda t: t[0])
        return cls(*(np.array([t[i] for t in states]) for i in range(3)))


class Continuation:
    """Continuation of ``corrector``'s configurations from (q0, x0).

    ``q_scale`` is 1 for an angle driver and the mechanism's size for a length.
    """

    def __init__(self, corrector, q0, x0, q_scale):
        self.corrector = corrector
        self.q0, self.x0 = q0, x0
        self.min_step = MIN_STEP * q_scale
        self.jump = JUMP * corrector.shortest

    # single steps --------------------------------------------------------------
    def _tangent(self, X, q):
        return self.corrector.tangent(X[None], np.array([q]))[0]

    def _predict_correct(self, X, dX, q_from, q_to):
        """Correct the predictions X + dX (q_to - q_from), row by row; returns
        (X, accepted): converged and no farther than :meth:`_allowed` from the prediction."""
        pred = X + dX * (q_to - q_from)[:, None]
        Xc, conv = self.corrector.newton(pred, q_to, CORRECTOR_ITER)
        n = self.corrector.system.n
        return Xc, conv & (np.max(np.abs(Xc[:, :n] - pred[:, :n]), axis=1) <= self._allowed(pred))

    def _allowed(self, pred):
        """The largest corrector move: JUMP shortest links, or JUMP of how far beyond the
        mechanism's size a point is predicted from the file's position (a point running off
        towards infinity, where two guides turn parallel, is followed in steps that grow
        with its distance, not in millions of steps of a link's size)."""
        n = self.corrector.system.n
        far = np.max(np.abs(pred[:, :n] - self.x0[:n]), axis=1) - self.corrector.size
        return np.maximum(self.jump, JUMP * far)

    def _advance(self, X, dX, q, target):
        """Continue from (q, X) to ``target``, doubling the step after a success and
        halving it after a failure; returns (X, dX, q reached, arrived)."""
        h = target - q
        while q != target:
            if abs(h) < self.min_step:
                return X, dX, q, False
            if abs(h) >= abs(target - q):
                h, q_next = target - q, target
            else:
                q_next = q + h
            Xn, ok = self._predict_correct(X[None], dX[None], q, np.array([q_next]))
            if ok[0]:
                X, q = Xn[0], q_next
                dX = self._tangent(X, q)
                h *= 2.0
            else:
                h *= 0.5
        return X, dX, q, True

    def reach(self, target):
        """The configuration at ``target`` continued from (q0, x0), None when missed."""
        X, _, _, arrived = self._advance(self.x0, self._tangent(self.x0, self.q0), self.q0,
                                         float(target))
        return X if arrived else None

    def _chain(self, state, targets, anchors):
        """Continue from ``state`` (q, X, dX) through ``targets`` in order, adding every
        new configuration reached to ``anchors``; stops at the first target missed.
        Returns (the last state, the number of targets reached)."""
        for count, target in enumerate(targets):
            q, X, dX = state
            Xn, dXn, qn, arrived = self._advance(X, dX, q, target)
            if qn != q:
                state = (qn, Xn, dXn)
                anchors.append(state)
            if not arrived:
                return state, count
        return state, len(targets)

    # walks from the file's position ------------------------------------------
    def _walk(self, nodes):
        """Continue from the file's position through ``nodes`` (in walking order).

        A missed node closes an assembled interval; the walk resumes at the first
        later node Newton assembles from scratch, and first walks back from it
        towards the gap.  Returns anchors [(q, X, dX)] and intervals [(q_a, q_b)].
        """
        state = (self.q0, self.x0, self._tangent(self.x0, self.q0))
        anchors, segments, start, i = [state], [], self.q0, 0
        while True:
            state, reached = self._chain(state, nodes[i:], anchors)
            i += reached
            segments.append((start, state[0]))
            if i == len(nodes):
                return anchors, segments
            beyond = self._cross_gap(state, nodes[i:], anchors)
            if beyond is None:
                return anchors, segments
            state, start, skipped = beyond
            i += skipped

    def _cross_gap(self, edge, rest, anchors):
        """Resume beyond a gap whose edge is the state ``edge``: at the first value
        rest[k] Newton assembles from scratch, then back from it towards the edge.
        Returns (the state at rest[k], the new interval's start, k + 1), or None."""
        restart = self._restart(edge[1], rest)
        if restart is None:
            return None
        k, X = restart
        q = float(rest[k])
        state = (q, X, self._tangent(X, q))
        anchors.append(state)
        back = [float(x) for x in rest[:k][::-1]] + [edge[0]]
        return state, self._chain(state, back, anchors)[0][0], k + 1

    def _restart(self, X_edge, rest):
        """(k, X) of the value rest[k] where Newton resumes beyond a gap, from its edge
        ``X_edge``, the file's position or the figure's with the crank turned to rest[k];
        None when no start assembles any value.

        The first value assembled on the file's side of the toggles (the sign of det J at
        the file's position: its assembly branch) is taken when it comes first, or when
        continuation from it back to the first value assembled on another side stays
        assembled (that value has the file's branch too); else the first value on any side
        (a side that changes with the driver itself, as the crossing of two guides' lines
        after they were parallel)."""
        rest = np.asarray(rest, dtype=float)
        own = self._sides(self.x0[None], np.array([self.q0]))[0]
        starts = [np.repeat(x[None], len(rest), axis=0) for x in (X_edge, self.x0)]
        if hasattr(self.corrector, "figure_starts"):
            starts.append(self.corrector.figure_starts(rest))
        same, other = [], []
        for start in starts:
            X, ok = self.corrector.newton(start, rest, MAX_ITER, damped=True)
            good = ok & (self._sides(X, rest) == own)
            for mask, found in ((good, same), (ok, other)):
                if mask.any():
                    k = int(np.argmax(mask))
                    found.append((k, X[k]))
            if same and same[-1][0] == 0:
                break               # the first value, on the file's side: nothing better
        if not other:
            return None
        first = min(other, key=lambda item: item[0])
        if not same:
            return first
        best = min(same, key=lambda item: item[0])
        if best[0] == first[0]:
            return best
        q = float(rest[best[0]])
        X, _, _, back = self._advance(best[1], self._tangent(best[1], q), q,
                                      float(rest[first[0]]))
        return (first[0], X) if back else first

    def _sides(self, X, q):
        """The sign of det J at each configuration: which side of the toggles it is on."""
        system = self.corrector.system
        return np.sign(np.linalg.det(system.jacobian(system.points(X), q)))

    # whole sweeps ---------------------------------------------------------------
    def track(self, qs):
        """Solve every driver value of the flat array ``qs``; returns (X (N, n), ok)."""
        qs = np.asarray(qs, dtype=float)
        X = np.zeros((qs.size, self.corrector.system.width))
        ok = np.zeros(qs.size, bool)
        if qs.size == 0:
            return X, ok
        states, segments = [], []
        for part in _nodes(qs, self.q0):
            a, s = self._walk(part)
            states += a
            segments += s
        anchors = Anchors.of(states)
        lo = np.array([min(a, b) for a, b in segments])
        hi = np.array([max(a, b) for a, b in segments])
        seg_of = _interval_of(qs, lo, hi)
        choose = _nearest_anchor(qs, anchors.q, seg_of, lo, hi)
        failed = self._correct(qs, np.nonzero(seg_of >= 0)[0], choose, anchors, X, ok)
        self._substep(qs, failed, choose, anchors, X, ok)
        return X, ok

    def _correct(self, qs, idx, choose, anchors, X, ok):
        """Correct qs[idx] from their anchors ``choose`` in batches of CHUNK into X, ok;
        returns the indices not accepted."""
        failed = []
        for start in range(0, idx.size, CHUNK):
            sl = idx[start:start + CHUNK]
            a = choose[sl]
            Xc, good = self._predict_correct(anchors.X[a], anchors.dX[a], anchors.q[a], qs[sl])
            X[sl[good]] = Xc[good]
            ok[sl[good]] = True
            failed.append(sl[~good])
        return np.concatenate(failed) if failed else np.zeros(0, int)

    def _substep(self, qs, failed, choose, anchors, X, ok):
        """Chained continuation from each anchor through its failed values, outwards
        on each side, until one is missed (rare: near folds)."""
        for a in np.unique(choose[failed]):
            group = failed[choose[failed] == a]
            qa = anchors.q[a]
            for side in (group[qs[group] >= qa], group[qs[group] < qa]):
                state = (float(qa), anchors.X[a], anchors.dX[a])
                self._chain_into(state, side[np.argsort(np.abs(qs[side] - qa), kind="stable")],
                                 qs, X, ok)

    def _chain_into(self, state, order, qs, X, ok):
        """Continue from ``state`` (q, X, dX) through qs[order], storing each configuration
        reached in X, ok; stops at the first value missed."""
        q, Xc, dXc = state
        for j in order:
            Xc, dXc, q, arrived = self._advance(Xc, dXc, q, float(qs[j]))
            if not arrived:
                return
            X[j], ok[j] = Xc, True


def _nodes(qs, q0):
    """At most about NODES distinct finite values of qs (the ends included), split into
    those above q0 (ascending) and below it (descending)."""
    uniq = np.unique(qs[np.isfinite(qs)])
    step = max(1, int(np.ceil(uniq.size / NODES)))
    nodes = np.unique(np.concatenate([uniq[::step], uniq[-1:]]))
    return nodes[nodes > q0], nodes[nodes < q0][::-1]


def _interval_of(qs, lo, hi):
    """Index of the first assembled interval [lo, hi] holding each q (-1: none)."""
    seg_of = np.full(qs.size, -1)
    for j in range(len(lo)):
        seg_of[(qs >= lo[j]) & (qs <= hi[j]) & (seg_of < 0)] = j
    return seg_of


def _nearest_anchor(qs, aq, seg_of, lo, hi):
    """Per q the nearer of its two neighbouring anchors, or the other one when only
    that one lies in the q's assembled interval."""
    pos = np.searchsorted(aq, qs)
    left = np.clip(pos - 1, 0, len(aq) - 1)
    right = np.clip(pos, 0, len(aq) - 1)
    choose = np.where(np.abs(aq[right] - qs) < np.abs(qs - aq[left]), right, left)
    for cand in (left, right):
        bad = ~_within(aq[choose], seg_of, lo, hi)
        choose = np.where(bad, cand, choose)
    return choose


def _within(values, seg_of, lo, hi):
    """Whether each value lies in the interval seg_of (False for -1)."""
    j = np.clip(seg_of, 0, len(lo) - 1)
    return (seg_of >= 0) & (values >= lo[j]) & (values <= hi[j])
