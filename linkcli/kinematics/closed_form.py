"""Positions, velocities and accelerations along the solving order.

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
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from linkcli.kinematics import dyads
from linkcli.kinematics.dyads import cross
from linkcli.errors import AssemblyError, Caution, InputError, SingularError
from linkcli.kinematics.contacts import Track
from linkcli.kinematics.assur import analyse
from linkcli.kinematics.groups import Coord, Dist, Line

SINGULAR = 1e-9
#: dyads with an assembly branch to choose
BRANCHED = ("RRR", "RRP", "PRR", "RPR")
#: a solved point farther than FAR times the mechanism's size from its figure position is
#: reported; a figure point whose distances to the two assemblies differ by less than
#: AMBIGUOUS times their separation is reported as ambiguous
FAR = 0.05
AMBIGUOUS = 0.1
#: the most steps the search for an assembling combination of branches takes
SEARCH = 4096


def figure_coordinates(mech):
    """The coordinates measured on the figure's points (the driver's, or each declared one)
    as the solver takes them: the configuration the figure draws."""
    figure = {**mech.fixed, **mech.moving}
    values = []
    for c in mech.coordinates:
        if len(mech.coordinates) > 1 or mech.elements is not None:
            values.append(c.value)          # coordinates are measured on the figure already
            continue
        if c.kind == "angle":
            values.append(float(np.angle(figure[c.b] - figure[c.a])))
        elif c.kind == "length":
            values.append(abs(figure[c.b] - figure[c.a]))
        else:
            z = figure[c.a]
            values.append(z.real if c.kind == "x" else z.imag)
    return values[0] if len(values) == 1 else tuple(values)


def _fails(short) -> bool:
    """Whether a group's shortfall says it cannot be assembled (None: nothing to close)."""
    return short is not None and bool(np.any(np.asarray(short) > 0))


def _paired(rank, judge) -> tuple:
    """Every coordinate as the pair [ranked, judged]: a dyad's branches are ranked by their
    distance to the figure at the first, their closure judged at the second."""
    return tuple(np.array([float(a), float(b)]) for a, b in zip(rank, judge))


def _judged(short):
    """The shortfall at the judged value of a pair (the last), None or a number as is."""
    return np.ravel(short)[-1] if np.ndim(short) else short


def own_coordinates(mech):
    """The file's own coordinate values (the driver's ``value``)."""
    values = [c.value for c in mech.coordinates]
    return values[0] if len(values) == 1 else tuple(values)


@dataclass
class Kinematics:
    """Positions (and rates) of every point, complex arrays in SI units.

    ``q``, ``qd``, ``qdd`` are the first coordinate (the driver) and its rates;
    ``coords``, ``rates``, ``accels`` hold every coordinate's, in order.
    """

    q: np.ndarray
    qd: np.ndarray | None = None
    qdd: np.ndarray | None = None
    coords: tuple = ()
    rates: tuple = ()
    accels: tuple = ()
    pos: dict = field(default_factory=dict)
    vel: dict = field(default_factory=dict)
    acc: dict = field(default_factory=dict)
    short: dict = field(default_factory=dict)     # group index -> shortfall (m) array, where
    #                                               some position might not close
    measure: dict = field(default_factory=dict)   # group index -> conditioning array
    flat: dict = field(default_factory=dict)      # group index -> toggle within rounding
    linear: dict = field(default_factory=dict, repr=False)  # group index -> rate-system inverse
    #                                                          (a driver's: its arm P - pivot)
    vectors: dict = field(default_factory=dict, repr=False)  # (a, b) -> (z, z'/z) for reports

    def __post_init__(self):
        if not self.coords:
            self.coords = (self.q,)

    def at_rest(self):
        """The same positions with no rates yet (for velocities per unit rate)."""
        return Kinematics(self.q, pos=self.pos, coords=self.coords)

    @property
    def shape(self) -> tuple:
        """The shape of the positions: every coordinate's broadcast together."""
        return np.broadcast_shapes(*(np.shape(c) for c in self.coords)) if self.coords \
            else np.shape(self.q)


class Solver:
    """Closed-form solver of one mechanism along its Assur decomposition."""

    def __init__(self, mech):
        self.mech = mech
        self.topology = analyse(mech)
        self.groups = self.topology.groups
        self.fixed = dict(mech.fixed)
        self.n = len(mech.coordinates)
        self._frames = {}               # fixed guides: (B, C, value) -> (u, e), found once
        self._choose_branches()
        #: (point, rate step) of every group that solves a point, in the solving order
        self._rates = [(g.point, self._rate_step(i, g)) for i, g in enumerate(self.groups)
                       if g.point is not None]

    # branches ------------------------------------------------------------------
    def _choose_branches(self):
        """Each dyad's assembly branch as in the figure, chosen once.

        The branches are ranked where the figure is drawn: at the coordinates measured on
        the figure's points (so that another driver value, another digit k, keeps the
        figure's assembly), each dyad's nearer branch first.  Whether a combination closes
        is judged at the file's own coordinates (the driver's value), where it is solved:
        the figure's value may lie where the nearer branch cannot close while the file's
        does, or the other way round.  Going down the groups, each dyad takes the branch
        nearest its figure point; when a later dyad cannot close, the earlier choices are
        searched for the assembling combination nearest the figure, and the forced choice
        is reported.  Only when no combination closes at the file's value is the closure
        judged at the figure's.  ``cautions`` lists what the reader should check.
        """
        self.cautions = []
        self.undetermined = None
        dyads = [g for g in self.groups if g.kind in BRANCHED]
        figure = self._coords(figure_coordinates(self.mech), "q")
        own = self._coords(own_coordinates(self.mech), "q")
        found = self._search(_paired(figure, own))
        if found is None:
            found = self._search(_paired(figure, figure))
        if found is None:
            for g in dyads:
                g.branch = 1
            self.undetermined = self._unassembled(figure)
            self._place_all(figure)
            return
        branches, forced = found
        for g, b in zip(dyads, branches):
            g.branch = b
        self._place_all(figure)
        if forced:
            self.cautions.append(Caution("branch", forced, self.mech.file))
        self.cautions += self._ambiguous(figure) + self._far(self.mech)

    def _place_all(self, q):
        """Positions at ``q`` with the chosen branches."""
        pos = dict(self.fixed)
        for group in self.groups:
            if group.point is not None:
                pos[group.point] = self._position(group, pos, q)[0]
        return pos

    def _candidates(self, group, pos, q):
        """[(distance to the figure point, branch, position, assembles)] of a dyad; with
        ``q`` a pair (:func:`_paired`) the distance is the first value's, whether it
        assembles the second's, and the position holds both."""
        target = self._target(group)
        out = []
        for branch in (1, -1):
            group.branch = branch
            p, short, *_ = self._position(group, pos, q)
            near = complex(np.ravel(p)[0])
            ok = not _fails(_judged(short))
            out.append((abs(near - target), branch, p, ok))
        return sorted(out, key=lambda c: c[0])

    def _target(self, group) -> complex:
        """Where the figure draws a dyad's point; a virtual point (``~BLOCK.slot``) is
        drawn by its recipe ``group.place`` = (K, M, N, w): K + (M - N) w."""
        target = self.mech.moving.get(group.point)
        if target is None:
            figure = {**self.mech.fixed, **self.mech.moving}
            k, m, n, w = group.place
            target = figure[k] + (figure[m] - figure[n]) * w
        return target

    def _search(self, q):
        """(branches, forced text) of the assembling combination nearest the figure, found
        nearest-first with backtracking; None when no combination assembles at ``q``.

        Depth first, each dyad's nearer branch first, the first complete assembly wins; at
        most SEARCH branch choices are tried (a structure that needs more is left
        undetermined).  The walk keeps its own stack, so a chain of thousands of groups
        takes no recursion."""
        groups = self.groups
        pos = dict(self.fixed)
        placed = []             # the points placed so far, in order (undone on backtracking)
        stack = []              # per dyad decided: [index, its candidates, next one, placed]
        i, steps = 0, 0
        while True:
            i = self._place_until_branch(i, pos, placed, q)
            if i == len(groups):
                break
            if i >= 0:          # a dyad with a branch to choose: its candidates, nearer first
                steps += 1
                if steps > SEARCH:
                    return None
                stack.append([i, self._candidates(groups[i], pos, q), 0, len(placed)])
            i = self._next_choice(stack, pos, placed)
            if i is None:
                return None
        chosen = [(groups[i], candidates[k - 1][1], k - 1) for i, candidates, k, _ in stack]
        farther = [g for g, _, rank in chosen if rank]
        forced = ""
        if farther:
            names = ", ".join(g.describe() for g in farther)
            forced = (f"{names} assembled on the branch farther from the figure: on the nearer "
                      "one a later group cannot close")
        return [b for _, b, _ in chosen], forced

    def _place_until_branch(self, i, pos, placed, q) -> int:
        """Place the groups from ``i`` on that have no branch to choose; returns the index
        of the next dyad with one (len(groups) when all are placed, -1 when one fails)."""
        groups = self.groups
        while i < len(groups):
            group = groups[i]
            if group.kind in BRANCHED:
                return i
            if group.point is not None:
                p, short, *_ = self._position(group, pos, q)
                if _fails(_judged(short)):
                    return -1
                pos[group.point] = p
                placed.append(group.point)
            i += 1
        return i

    def _next_choice(self, stack, pos, placed):
        """Take the next assembling candidate of the innermost dyad that has one (undoing
        what was placed after it); returns the index of the group after it, None when no
        dyad has a candidate left."""
        while stack:
            frame = stack[-1]
            i, candidates, k, mark = frame
            point = self.groups[i].point
            for placed_point in placed[mark:]:
                del pos[placed_point]
            del placed[mark:]
            while k < len(candidates) and not candidates[k][3]:
                k += 1
            if k < len(candidates):
                frame[2] = k + 1
                pos[point] = candidates[k][2]
                placed.append(point)
                return i + 1
            stack.pop()
        return None

    def _unassembled(self, q):
        """The text of the first group that cannot close at the figure's coordinates."""
        pos = dict(self.fixed)
        for group in self.groups:
            if group.point is None:
                continue
            p, short, *_ = self._position(group, pos, q)
            if _fails(short):
                worst = float(np.max(short))
                return (f"the figure's position cannot be assembled: {group.describe()} falls "
                        f"short by {length_text(self.mech, worst)}; the assembly branch is "
                        "not determined (+ taken)")
            pos[group.point] = p
        return "the figure's position cannot be assembled; the assembly branch is not determined"

    def _ambiguous(self, q) -> list:
        """Dyads whose figure point is nearly as far from both assemblies (AMBIGUOUS of the
        distance between them)."""
        out = []
        pos = dict(self.fixed)
        for group in self.groups:
            if group.kind in BRANCHED:
                keep = group.branch
                (d1, _, p1, _), (d2, _, p2, _) = self._candidates(group, pos, q)
                group.branch = keep
                gap = abs(p1 - p2)
                if gap > 0 and abs(d1 - d2) < AMBIGUOUS * gap:
                    unit, f = self.mech.units.display("length", 0)
                    out.append(Caution(
                        "ambiguous", f"the figure's {group.point} is nearly as far from both "
                        f"assemblies of {group.describe()} ({d1 / f:.4g} and {d2 / f:.4g} "
                        f"{unit}): the branch may not be the one drawn", self.mech.file,
                        {group.point: d1 / f}))
            if group.point is not None:
                pos[group.point] = self._position(group, pos, q)[0]
        return out

    def _far(self, mech) -> list:
        """Points solved far from the figure at the file's own coordinates (more than FAR
        of the mechanism's size), when the file is solved for the digit it draws."""
        if not mech.as_drawn:
            return []
        q = self._coords(own_coordinates(mech), "q")
        kin = self.positions(q)
        pos = kin.pos
        for index, short in kin.short.items():
            if np.any(short > 0):
                group = self.groups[index]
                worst = float(np.max(short))
                reason = "the links are parallel" if not np.isfinite(worst) else \
                    f"falls short by {length_text(mech, worst)}"
                return [Caution("unassembled", f"the file's own position cannot be assembled: "
                                f"{group.describe()} {where_text(mech, kin.q, True)} {reason} "
                                "(the branch is the figure's)", mech.file)]
        return far_from_figure(mech, pos)

    # positions -------------------------------------------------------------------
    def _position(self, group, pos, q, turns=None):
        """(P, shortfall, ...) of the group's point; ``turns`` collects the discs' turns
        (:meth:`_roll_position`), which contacts solved later read."""
        kind = group.kind
        if kind == "roll":
            return self._roll_position(group, pos, q, turns), None
        if kind == "place":
            k, m, n, w = group.place
            return pos[k] + (pos[m] - pos[n]) * w, None
        if kind == "driver-angle":        # P = pivot + L e^{i q}, written into one array
            pivot, length, reverse = group.constraints
            p = dyads.cis(q[group.coord])
            base = pos[pivot]
            if not dyads.writable(p, base):
                return base + (-length if reverse else length) * p, None
            p *= -length if reverse else length
            if not dyads.is_number(base, 0.0):     # nothing to add about the origin
                p += base
            return p, None
        if kind == "driver-coord":
            line, coord = group.constraints
            value = q[coord.coord]
            u, e = dyads.line_frame(pos[line.b], pos[line.c], line.value)
            if coord.axis == "x":
                p, parallel = dyads.line_line(pos[line.b], u, e, value + 0j, 1j, 0.0)
            else:
                p, parallel = dyads.line_line(pos[line.b], u, e, 1j * value, 1.0 + 0j, 0.0)
            return p, np.where(parallel, np.inf, 0.0)
        c1, c2 = group.constraints
        if kind == "RRR":
            return dyads.circle_circle(pos[c1.a], self._length(c1, q), pos[c2.a],
                                       self._length(c2, q), group.branch, flat=True)
        if kind in ("RRP", "PRR"):
            dist, line = (c1, c2) if kind == "RRP" else (c2, c1)
            b, c, value = _guide_of(line, pos, q, turns)
            return dyads.circle_line(pos[dist.a], self._length(dist, q), b, c, value,
                                     group.branch, flat=True, frame=self._frame(line))
        if kind in ("PRP", "RPP"):         # a point on two lines (RPP: module assur)
            b1, g1, v1 = _guide_of(c1, pos, q, turns)
            b2, g2, v2 = _guide_of(c2, pos, q, turns)
            u1, e1 = dyads.line_frame(b1, g1, v1)
            u2, e2 = dyads.line_frame(b2, g2, v2)
            p, parallel = dyads.line_line(b1, u1, e1, b2, u2, e2)
            return p, np.where(parallel, np.inf, 0.0)
        if kind == "RPR":
            return dyads.slotted(pos[c1.a], c1.length, pos[c2.p], c2.value, group.branch,
                                 flat=True)
        return None, None

    def _frame(self, line):
        """The (u, e) of a line whose points are fixed (kept), None for a moving one."""
        if isinstance(line, Track):
            return None
        key = (line.b, line.c, line.value)
        frame = self._frames.get(key)
        if frame is None and line.b in self.fixed and line.c in self.fixed:
            frame = self._frames[key] = dyads.line_frame(self.fixed[line.b],
                                                         self.fixed[line.c], line.value)
        return frame

    def _roll_position(self, group, pos, q, turns=None):
        """The second point M = C + |M - C| e^{i theta} of a disc a contact turns: the
        relation sum c_k (mu_k - mu_k0) = 0 (kinematics.contacts) solved for the disc's turn,
        theta - theta0 = -(sum of the other terms) / c, theta0 the figure's.  The turn is
        kept in ``turns`` (any number of turns) for the contacts solved after it."""
        rel, turn = group.constraints
        body = self.mech.bodies[group.bodies[0]]
        arm = abs(body.local[turn.b] - body.local[turn.a])
        ref = next(ref for t, _, ref in rel.terms if t is turn)
        theta = -rel.residual(pos, q, turns, skip=turn) / rel.coefficient(turn)
        if turns is not None:
            turns[(turn.a, turn.b)] = theta
        return pos[turn.a] + (arm * ref) * np.exp(1j * theta)

    @staticmethod
    def _length(dist, q):
        return q[dist.coord] if dist.length is None else dist.length

    def _coords(self, q, what) -> tuple:
        """Every coordinate as a float array: ``q`` itself with one coordinate, else a
        sequence of ``n`` values or arrays (they broadcast together)."""
        if self.n == 1:
            return (np.asarray(q, dtype=float),)
        if np.ndim(q) == 0 or len(q) != self.n:
            raise InputError(f"{what}: give one value (or array) per coordinate, "
                             f"{self.n} in all", file=self.mech.file, key="coordinates",
                             hint="in the order of 'coordinates': " +
                             ", ".join(c.name for c in self.mech.coordinates))
        return tuple(np.asarray(x, dtype=float) for x in q)

    def positions(self, q) -> Kinematics:
        """Every point at coordinate value(s) ``q`` (SI): one array, or one per coordinate."""
        qs = self._coords(q, "q")
        kin = Kinematics(qs[0], coords=qs)
        q = qs
        pos = kin.pos
        pos.update(self.fixed)
        turns = {}
        for index, group in enumerate(self.groups):
            if group.point is None:
                continue
            p, short, *flat = self._position(group, pos, q, turns)
            pos[group.point] = p
            if short is not None and (type(short) is not float or short != 0.0):
                kin.short[index] = short        # (the number 0.0: every position closes)
            if flat and flat[0] is not False and flat[0].any():
                kin.flat[index] = flat[0]
        return kin

    # rates ---------------------------------------------------------------------
    def velocities(self, kin: Kinematics, qd) -> Kinematics:
        """Velocities of every point for coordinate rate(s) ``qd``, as ``q`` in positions."""
        kin.rates = self._coords(qd, "qdot")
        kin.qd = kin.rates[0]
        kin.vel.clear()
        kin.vectors.clear()
        vel, rates = kin.vel, kin.rates
        for point, step in self._rates:
            vel[point] = step(kin, vel, rates, None)
        return kin

    def accelerations(self, kin: Kinematics, qdd, keep=False) -> Kinematics:
        """Accelerations of every point for coordinate acceleration(s) ``qdd`` and the
        velocities already on ``kin``; ``keep`` keeps the rate systems for another call."""
        kin.accels = self._coords(qdd, "qddot")
        kin.qdd = kin.accels[0]
        kin.acc.clear()
        acc, accels, vel = kin.acc, kin.accels, kin.vel
        for point, step in self._rates:
            acc[point] = step(kin, acc, accels, vel)
        if not keep:
            kin.linear.clear()          # rates done: free the cached systems
        return kin

    def _rate_step(self, index, group):
        """The function step(kin, d, qrate, vel) giving the first (``vel`` None) or second
        time derivative of the group's point (see :meth:`_rate`), chosen once per group."""
        if group.kind == "driver-angle":
            return DriverRates(index, group, self.fixed)
        if group.kind in ("place", "roll"):
            return lambda kin, d, qrate, vel: self._rate(group, kin, d, qrate, vel)
        return DyadRates(index, group, self.fixed)

    def _rate(self, group, kin, d, qrate, vel):
        """First (vel None) or second time derivative of the point of a placed point or of
        a disc's second point M, turned by a contact: omega = -(sum of the other terms'
        rates) / c (the same of their second rates for alpha), M' = C' + i omega (M - C),
        M'' = C'' + (i alpha - omega^2) (M - C).

        ``d`` holds the rates found so far; the group's own point is not in it
        yet, so every rate read from ``d`` is a known one.
        """
        pos = kin.pos
        if group.kind == "place":
            k, m, n, w = group.place
            return _get(d, k) + (_get(d, m) - _get(d, n)) * w
        rel, turn = group.constraints
        arm = pos[group.point] - pos[turn.a]
        c = rel.coefficient(turn)
        if vel is None:
            omega = -rel.rate(pos, d, qrate, skip=turn) / c
            return _get(d, turn.a) + 1j * omega * arm
        omega = -rel.rate(pos, vel, kin.rates, skip=turn) / c
        alpha = -rel.accel(pos, vel, d, qrate, skip=turn) / c
        return _get(d, turn.a) + (1j * alpha - omega * omega) * arm

    def rate_system(self, index, kin, order):
        """The 2x2 rate system of dyad ``index`` as solved at ``kin`` (rates of ``order``
        1 or 2 already on ``kin``): (G_1, G_2, r_1, r_2, P') with Re(conj(G_i) P') = r_i,
        for the worked solution."""
        group = self.groups[index]
        system = DyadRates(index, group, self.fixed)
        g1, g2 = (g(kin.pos) if callable(g) else g for g in system.grads)
        d = dict(kin.vel if order == 1 else kin.acc)
        solved = d.pop(group.point)
        rates = kin.rates if order == 1 else kin.accels
        vel = None if order == 1 else kin.vel
        r1, r2 = (rhs(g, kin, d, rates, vel) for rhs, g in zip(system.rhs, (g1, g2)))
        return g1, g2, r1, r2, solved

    # failures ------------------------------------------------------------------
    def check(self, kin: Kinematics, velocities: bool):
        """Raise when a group cannot be assembled or (for rates) is singular."""
        for index, short in kin.short.items():
            if not _exceeds(short, 0.0):    # the common case, decided on the array as it is
                continue
            bad = short > 0
            bad = np.broadcast_to(bad, kin.shape) if np.ndim(short) else bad
            if np.any(bad):
                worst = float(np.max(np.where(bad, short, 0.0)))
                reason = "the links are parallel" if not np.isfinite(worst) else \
                    f"the links fall short by {length_text(self.mech, worst)}"
                raise assembly_error(self.mech, self.groups[index], kin.q, bad, worst, reason)
        if not velocities:
            return
        for index, measure in kin.measure.items():
            if _under(measure, SINGULAR):
                bad = measure < SINGULAR
                raise singular_error(self.mech, self.groups[index], kin.q,
                                     np.broadcast_to(bad, kin.shape), measure,
                                     "sine of the angle between its constraint directions")


# --- rates of the groups ----------------------------------------------------------------
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


def far_from_figure(mech, pos) -> list:
    """The caution listing the points solved (``pos``: every point at the file's own
    coordinates) farther than FAR of the mechanism's size from the figure's, if any."""
    points = [complex(np.ravel(pos[p])[0]) for p in mech.points if p in pos]
    size = max(abs(z - sum(points) / len(points)) for z in points) or 1.0
    unit, f = mech.units.display("length", 0)
    far = {p: abs(complex(np.ravel(pos[p])[0]) - mech.moving[p]) for p in mech.moving
           if p in pos}
    far = {p: d for p, d in far.items() if d > FAR * size}
    if not far:
        return []
    listed = ", ".join(f"{p} by {d / f:.4g} {unit}" for p, d in
                       sorted(far.items(), key=lambda item: -item[1]))
    return [Caution("figure", f"the solved position is far from the figure ({FAR:.0%} of "
                    f"the mechanism's size is {FAR * size / f:.4g} {unit}): {listed}; "
                    "check the lengths, the shapes and the driver's points",
                    mech.file, {p: d / f for p, d in far.items()})]


def assembly_error(mech, group, q, bad, worst, reason) -> AssemblyError:
    """The error of ``group`` that cannot be assembled at the driver values ``bad``."""
    return AssemblyError(
        f"cannot assemble {group.describe()} {where_text(mech, q, bad)}: {reason}",
        file=mech.file, group=group.describe(), q=q, shortfall=worst,
        hint="check the lengths and the driver value")


def singular_error(mech, group, q, bad, measure, meaning) -> SingularError:
    """The error of ``group`` singular at the driver values ``bad``; ``meaning`` says what
    its conditioning ``measure`` is."""
    least = float(np.min(measure))
    return SingularError(
        f"singular position (toggle or dead point) of {group.describe()} "
        f"{where_text(mech, q, bad)}: conditioning {least:.2e} ({meaning}); velocities are "
        "undefined there", file=mech.file, group=group.describe(), q=q, measure=least,
        hint="move the driver away from the toggle")


def length_text(mech, value) -> str:
    """A length (m) in the file's display unit."""
    unit, factor = mech.units.display("length", 0)
    return f"{value / factor:.4g} {unit}"


def where_text(mech, q, bad) -> str:
    """'at q = ...' or 'for q in [...]': the driver values ``bad`` in display units."""
    unit, factor = mech.units.display(_driver_base(mech), 0)
    return _q_text(q, bad, factor, unit)


def _driver_base(mech) -> str:
    return "angle" if mech.driver.kind == "angle" else "length"


def _q_text(q, bad, factor, unit) -> str:
    values = np.atleast_1d(q)[np.atleast_1d(bad)] / factor
    if values.size <= 1:
        value = float(values[0]) if values.size else float(np.atleast_1d(q)[0] / factor)
        return f"at q = {value:.6g} {unit}"
    return f"for q in [{values.min():.6g}, {values.max():.6g}] {unit} ({values.size} positions)"


def _get(d, name):
    return d.get(name, 0.0)


def _anywhere(mask) -> bool:
    """np.any(mask), without its dispatch for the arrays the groups return."""
    return mask.any() if isinstance(mask, np.ndarray) else bool(np.any(mask))


def _exceeds(x, level) -> bool:
    """Whether any of ``x`` is above ``level`` (NaN is not): np.any(x > level) by one
    reduction, without the mask."""
    if type(x) is np.ndarray and x.size:
        return bool(np.fmax.reduce(x, axis=None) > level)
    return _anywhere(np.asarray(x) > level)


def _under(x, level) -> bool:
    """Whether any of ``x`` is below ``level`` (NaN is not), as :func:`_exceeds`."""
    if type(x) is np.ndarray and x.size:
        return bool(np.fmin.reduce(x, axis=None) < level)
    return _anywhere(np.asarray(x) < level)


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


def _guide_of(c, pos, q, turns=None):
    """(B, C, value) of a dyad's line: a guide's points, or a contact's line (Track)."""
    if isinstance(c, Track):
        return c.line(pos, q, turns)
    return pos[c.b], pos[c.c], c.value


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


def residuals(solver: Solver, kin: Kinematics) -> dict:
    """Closure residual of every dyad constraint (m^2 for distances), for tests."""
    out = {}
    pos = kin.pos
    for index, group in enumerate(solver.groups):
        for j, c in enumerate(group.constraints if group.is_dyad or group.kind == "driver-coord"
                              else ()):
            if isinstance(c, Dist):
                length = kin.coords[c.coord] if c.length is None else c.length
                value = np.abs(pos[c.p] - pos[c.a]) ** 2 - length ** 2
            elif isinstance(c, Line):
                value = cross(pos[c.c] - pos[c.b], pos[c.p] - pos[c.b]) - c.value
            elif isinstance(c, Track):
                value = c.relation.residual(pos, kin.coords)
            else:
                p = pos[c.p]
                value = (p.real if c.axis == "x" else p.imag) - kin.coords[c.coord]
            out[(index, j)] = value
    return out
