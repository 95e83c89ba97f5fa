"""Branch points of a sweep: the toggles a group passes between two neighbouring samples.

The closed form keeps each dyad's branch sign chosen at the file's position; Newton
continues the configuration step by step.  Where a group passes a toggle, its conditioning
measure (the sine of the angle between its constraint normals; for Newton |det J| over
the product of the row norms) touches zero; such a driver value is reported as a branch
point, because the real mechanism may leave there on either branch.  It is found between
any two neighbouring samples: three samples whose middle one dips in a V; two samples
where the angle between the constraint normals heads for 0 or 180 degrees at the first
and comes back from it at the second (their tangents, from the rates, meet at or near
it); for Newton, the sign of det J (the side the dyads close on) changing; an exact toggle
at the first or the last sample.  Each one is then located on the conditioning itself
(``kinematics.toggles.locate``), to the accuracy that module states, whatever path the
solver took to the samples.  Samples are looked at block by block: the last two of a
block are kept for the next, so the points found are those of a sweep in one block.
Driver values are in display units (``q_factor`` converts them to SI).
"""
from __future__ import annotations

import math

import numpy as np

from linkcli.kinematics import toggles
from linkcli.kinematics.groups import Dist, Line
from linkcli.kinematics.refusals import SINGULAR
from linkcli.runs.sweep.issues import Issue
from linkcli.runs.sweep.newton_path import solve_near


class BranchPoints:
    """The branch points of a sweep of ``size`` samples, looked for a block at a time
    (:meth:`scan`, then :meth:`finish` after the last block; :meth:`reports`)."""

    def __init__(self, solver, method, q_factor, q_unit, l_unit, q_size, qd, size):
        self.solver, self.method, self.qd, self.size = solver, method, qd, size
        self.q_factor, self.q_unit, self.l_unit = q_factor, q_unit, l_unit
        #: the driver's natural size: 1 rad, or the mechanism's size (m) for a length
        self.q_size = q_size
        self.tail: dict = {}            # group index -> the last two assembled samples
        self.touch: list = []           # (group index, row, Issue): V tips
        self.between: list = []         # (group index, row a, row b, Issue): between two

    def reports(self) -> list:
        """The branch points found: V tips, then those between two samples that are not
        already a tip's."""
        touched = {(index, row) for index, row, _ in self.touch}
        return [issue for _, _, issue in self.touch] + [
            issue for index, a, b, issue in self.between
            if (index, a) not in touched and (index, b) not in touched]

    def scan(self, sub, q, rows):
        """Look for branch points among the assembled samples ``rows`` (q display units),
        the last two samples of the previous block included."""
        threshold = getattr(self.solver, "singular", SINGULAR)
        angles = self._angles(sub) if self.method != "newton" else {}
        signs = self._signs(sub) if self.method == "newton" else {}
        for index in sorted(sub.measure):
            measure = np.array(np.broadcast_to(sub.measure[index], rows.shape), dtype=float)
            theta, slope = angles.get(index, (None, None))
            sign = signs.get(index)
            new = {"m": measure, "q": q, "row": rows}
            if theta is not None:
                new.update(theta=theta, slope=slope)
            if sign is not None:
                new["sign"] = sign
            tail = self.tail.get(index)
            old = 0 if tail is None else tail["row"].size
            every = new if tail is None else {k: np.concatenate([tail[k], v]) for k, v in
                                              new.items() if k in tail}
            self.tail[index] = {k: v[-2:] for k, v in every.items()}
            m, qq, rr = every["m"], every["q"], every["row"]
            if old == 0 and rr.size and rr[0] == 0 and m[0] < threshold:   # exact toggle
                self.touch.append((index, 0, self._branch(index, qq[0], m[0])))
            for i, _ in _touches(m, qq, rr):
                qb = self._closer(index, qq[i - 1], qq[i + 1])
                if qb is None:                  # a smooth minimum, sampled coarsely
                    continue
                self.touch.append((index, int(rr[i]), self._branch(index, qb, m[i])))
            pairs = np.arange(max(old - 1, 0), rr.size - 1)
            if pairs.size == 0:
                continue
            a, b = pairs, pairs + 1
            near = (rr[b] - rr[a] == 1) & (m[a] >= threshold) & (m[b] >= threshold)
            if "theta" in every:
                hit, at = _tangents_meet(every["theta"], every["slope"], qq, a, b)
                for j in np.nonzero(near & hit)[0]:     # a suspicion: looked at closely
                    found = self._closer(index, qq[a[j]], qq[b[j]])
                    hit[j] = found is not None
                    at[j] = at[j] if found is None else found
            elif "sign" in every:             # the side the dyads close on changes
                s = every["sign"]
                hit = s[a] * s[b] < 0
                at = qq[a] + (qq[b] - qq[a]) * m[a] / np.where(m[a] + m[b] > 0, m[a] + m[b], 1)
                for j in np.nonzero(near & hit)[0]:     # located on the conditioning
                    found = self._closer(index, qq[a[j]], qq[b[j]])
                    at[j] = at[j] if found is None else found
            else:
                continue
            for j in np.nonzero(near & hit)[0]:
                self.between.append((index, int(rr[a[j]]), int(rr[b[j]]),
                                      self._branch(index, float(at[j]),
                                                   min(m[a[j]], m[b[j]]))))

    def _closer(self, index, qa, qb):
        """The toggle of group ``index`` between the samples qa and qb, located by zooming on
        its conditioning to the accuracy of ``toggles.TIP`` (``toggles.locate``); None: no
        toggle (a smooth minimum, or a gap that cannot be assembled)."""
        threshold = getattr(self.solver, "singular", SINGULAR)
        solve = solve_near(self.solver, qa, qb, self.q_factor) if self.method == "newton" else self.solver.positions

        def measure_at(q):
            kin = solve(q * self.q_factor)
            if kin is None or any(np.any(np.asarray(short) > 0) for short in kin.short.values()):
                return None
            self.solver.velocities(kin, 1.0)
            if index not in kin.measure:
                return None
            return np.array(np.broadcast_to(kin.measure[index], q.shape), dtype=float)

        return toggles.locate(measure_at, qa, qb, toggles.TIP * self.q_size / self.q_factor,
                              threshold)

    def finish(self):
        """An exact toggle at the last sample is a branch point too."""
        threshold = getattr(self.solver, "singular", SINGULAR)
        for index, tail in self.tail.items():
            if tail["row"].size and tail["row"][-1] == self.size - 1 and self.size > 1 \
                    and tail["m"][-1] < threshold:
                self.touch.append((index, self.size - 1,
                                    self._branch(index, tail["q"][-1], tail["m"][-1])))

    def _branch(self, index, q, measure) -> Issue:
        return Issue("branch", self.solver.groups[index].describe(), float(q), float(q), 1,
                     float(measure), self.q_unit, self.l_unit, index)

    def _angles(self, sub) -> dict:
        """Per closed-form group: the angle theta in [0, pi] between its two constraint
        normals and d theta / dq (per display unit of q), from the velocities."""
        qd = np.asarray(self.qd, dtype=float)
        if qd.ndim == 0 and qd != 0:
            vel, rate = sub.vel, float(qd)
        else:
            vel, rate = self.solver.velocities(sub.at_rest(), 1.0).vel, 1.0
        out = {}
        for index in sub.measure:
            lin = sub.linear.get(index)
            group = self.solver.groups[index]
            if lin is None or len(group.constraints) != 2:
                continue
            g1, g2 = lin[2], lin[3]
            d1, d2 = (_grad_rate(c, vel, group.point) for c in group.constraints)
            z = np.conj(g1) * g2
            dz = np.conj(d1) * g2 + np.conj(g1) * d2
            safe = np.where(z == 0, 1.0, z)
            theta = np.abs(np.angle(z))
            slope = np.sign(z.imag) * (dz / safe).imag / rate * self.q_factor
            shape = np.shape(sub.q)
            out[index] = (np.array(np.broadcast_to(theta, shape), dtype=float),
                          np.array(np.broadcast_to(slope, shape), dtype=float))
        return out

    def _signs(self, sub) -> dict:
        """Newton: the sign of det J at every row (the side the dyads close on)."""
        from linkcli.kinematics.corrector import CHUNK
        system = getattr(self.solver, "system", None)
        if system is None:
            return {}
        q = np.asarray(sub.q, dtype=float).ravel()
        X = np.empty((q.size, system.n))
        for j, name in enumerate(system.moving):
            z = np.broadcast_to(sub.pos[name], np.shape(sub.q)).ravel()
            X[:, 2 * j], X[:, 2 * j + 1] = z.real, z.imag
        sign = np.empty(q.size)
        for start in range(0, q.size, CHUNK):
            sl = slice(start, start + CHUNK)
            sign[sl] = np.sign(np.linalg.det(system.jacobian(system.points(X[sl]), q[sl])))
        return {0: sign}


def _grad_rate(c, vel, unknown):
    """The time derivative of ``rates._grad(c, pos, unknown)``: the same combination
    of the velocities ``vel`` (absent points are fixed)."""
    if isinstance(c, Dist):
        return 2.0 * (vel.get(c.p, 0j) - vel.get(c.a, 0j))
    if isinstance(c, Line):
        if unknown == c.p:
            return 1j * (vel.get(c.c, 0j) - vel.get(c.b, 0j))
        return -1j * (vel.get(c.p, 0j) - vel.get(c.b, 0j))
    return 0j


def _touches(measure, q, rows):
    """Samples where the measure dips to zero in a V between two neighbours.

    Near a toggle the measure behaves like c |q - q*|; three consecutive samples
    m0 > m1 <= m2 then satisfy m1 <= (m0 + m2) / 4 (m1 = 0 at q*); the bound
    used, (m0 + m2) / 3, also flags a smooth minimum m* + a x^2 whose depth m* is
    under 2 a step^2, i.e. zero within the sampling.  q* is interpolated.
    """
    if measure.size < 3:
        return []
    m0, m1, m2 = measure[:-2], measure[1:-1], measure[2:]
    adjacent = (rows[1:-1] - rows[:-2] == 1) & (rows[2:] - rows[1:-1] == 1)
    total = m0 + m2
    hit = adjacent & (m1 < m0) & (m1 <= m2) & (total > 0) & (m1 <= total / 3)
    found = []
    for j in np.nonzero(hit)[0]:
        i = j + 1
        t = (m0[j] - m2[j]) / total[j]          # offset of the V's tip, in samples
        step = (q[i + 1] - q[i - 1]) / 2
        found.append((i, float(q[i] + t * step)))
    return found


def _tangents_meet(theta, slope, q, a, b):
    """Between samples a and b: does the angle theta between the constraint normals reach
    0 or pi (a toggle) in a V?  Its distance to the toggle angle falls at a and rises at b,
    and their tangents meet at most a quarter of the two distances above zero (0 for a
    straight V; a smooth minimum m* + c x^2 is flagged when m* < 3 c h^2, h the half
    step: zero within the sampling, as for three samples).  Returns (hit, q of the tip)."""
    h = q[b] - q[a]
    hit = np.zeros(a.size, bool)
    at = np.zeros(a.size)
    for toward in (0.0, math.pi):
        da, db = np.abs(theta[a] - toward), np.abs(theta[b] - toward)
        sa, sb = (slope[a], slope[b]) if toward == 0.0 else (-slope[a], -slope[b])
        v = (sa * h < 0) & (sb * h > 0)
        denominator = np.where(v, sa - sb, 1.0)
        u = (db - da - sb * h) / denominator        # where the tangents meet, from q[a]
        value = da + sa * u
        t = u / np.where(h != 0, h, 1.0)
        now = v & (t >= 0) & (t <= 1) & (value <= (da + db) / 4)
        at = np.where(now & ~hit, q[a] + u, at)
        hit |= now
    return hit, at
