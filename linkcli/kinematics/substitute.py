"""Coordinates the Assur decomposition cannot place: the angle of a link that no coordinate
placed before it pivots (a four-bar's coupler).

Such a coordinate is a function of the positions, q_k = f_k(p) = arg(P_b - P_a), and the
mechanism is solved in substitute coordinates p that the decomposition does place: for each
such q_k, the angle of a link pivoted on the frame (or a slider's x or y on a fixed guide).
Every set of substitutes that the decomposition places is a chart; the one best conditioned
in the figure is tried first, and another takes over where a substitute reaches the end of
its travel (a rocker at its limit) before the file's coordinate does.  The closed-form
solver works in p, and this one converts, with J = df/dp (one column per unit rate of p):

    positions:      f(p) = q, solved for p by Newton's method from the nearest solution known
    velocities:     p' = J^-1 q'
    accelerations:  p'' = J^-1 (q'' - f''(p', p'' = 0))

The conditioning is |det S|, S the rows of J each divided by the most that angle can turn
per unit rate (its link's ends' speeds over its length), every coordinate over its scale
(1 rad, the mechanism's size): 0 where the coupler's angle is stationary as the mechanism
moves, so that it is not a coordinate there (the rates are refused as at a toggle).
"""
from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np

from linkcli.errors import AssemblyError, SingularError, SolveError
from linkcli.kinematics.closed_form import Solver
from linkcli.kinematics.assur import partial
from linkcli.kinematics.refusals import SINGULAR
from linkcli.model.mechanism import Driver

#: Newton's tolerance on f(p) = q, over each coordinate's scale
TOLERANCE = 1e-13
#: the most substitute sets tried, and Newton's most iterations
TRIES = 256
ITERATIONS = 60
#: a Newton step is halved at most HALVINGS times while the mechanism does not assemble
HALVINGS = 12


def substitute_solver(mech):
    """The solver of ``mech`` through substitute coordinates, or None when the coordinates the
    decomposition leaves are not link angles or no substitute places them."""
    charts = []
    for inner, replaced in substitutes(mech):
        try:
            charts.append(Chart(mech, Solver(inner), replaced))
        except SolveError:
            continue
    if not charts:
        return None
    replaced = charts[0].replaced
    solver = SubstituteSolver(mech, charts, replaced)
    if solver.figure_measure > SINGULAR:
        return solver
    names = ", ".join(f"{mech.coordinates[j].name} (the angle of "
                      f"{mech.coordinates[j].a}->{mech.coordinates[j].b})" for j in replaced)
    raise SingularError(f"{names} cannot serve as a coordinate: it does not change as the "
                        f"mechanism moves from the figure (its rate is below {SINGULAR:g} of its "
                        "ends' speeds over its length, whichever link pivoted on the frame "
                        "drives it)",
                        file=mech.file, measure=solver.figure_measure,
                        hint="choose as coordinate the angle of a link that turns (a crank or a "
                        "rocker)")


def substitutes(mech):
    """(the mechanism with substitute coordinates, the indices of the file's coordinates they
    replace) for each set of substitutes, at most TRIES; none where the decomposition places
    every coordinate or leaves one that is not a link's angle.  The formulas of
    ``kinematics.symbolic`` take the first set the decomposition places."""
    try:
        pending = partial(mech).pending
    except SolveError:
        return
    if not pending or any(c.kind != "angle" for c in pending):
        return
    replaced = [j for j, c in enumerate(mech.coordinates) if c in pending]
    for combo in itertools.islice(itertools.combinations(_candidates(mech), len(replaced)),
                                  TRIES):
        coords = list(mech.coordinates)
        for j, c in zip(replaced, combo):
            coords[j] = c
        yield dataclasses.replace(mech, coordinates=tuple(coords), driver=coords[0]), replaced


def _candidates(mech) -> list:
    """Coordinates the decomposition places: the angle of a link from a frame point to
    another of its points, a slider's x or y on a fixed guide; measured on the figure."""
    figure = {**mech.fixed, **mech.moving}
    used = {(c.kind, c.a, c.b) for c in mech.coordinates}
    out = []
    for body in mech.bodies.values():
        if body.kind == "link":
            pivots = [p for p in body.points if p in mech.fixed]
            for pivot in pivots[:1]:
                tip = next((p for p in body.points if p not in mech.fixed), None)
                if tip is not None and ("angle", pivot, tip) not in used:
                    z = figure[tip] - figure[pivot]
                    out.append(Driver("angle", pivot, tip, math.atan2(z.imag, z.real), 0.0,
                                      0.0, f"{body.name} angle"))
        elif body.kind == "block" and body.guide.carrier == "frame":
            p = body.points[0]
            for kind in ("x", "y"):
                if (kind, p, None) not in used:
                    value = figure[p].real if kind == "x" else figure[p].imag
                    out.append(Driver(kind, p, None, value, 0.0, 0.0, f"{kind} of {p}"))
    return out


def _pack(values):
    return values[0] if len(values) == 1 else tuple(values)


def _wrap(x):
    return (x + math.pi) % (2 * math.pi) - math.pi


class Chart:
    """One set of substitute coordinates p: the closed-form solver ``inner`` of the mechanism
    with them, and the map f(p) to the file's coordinates."""

    def __init__(self, mech, inner: Solver, replaced):
        self.mech = mech
        self.inner = inner
        self.n = inner.n
        self.replaced = replaced
        points = np.array(mech.figure_points)
        self.size = float(np.max(np.abs(points - points.mean()))) or 1.0
        self.q_scale = np.array([1.0 if c.kind == "angle" else self.size
                                 for c in mech.coordinates])
        self.p_scale = np.array([1.0 if c.kind == "angle" else self.size
                                 for c in inner.mech.coordinates])
        self.p_figure = np.array([c.value for c in inner.mech.coordinates], dtype=float)

    def at(self, p):
        """The inner positions at p (..., n), assembled or raising."""
        kin = self.inner.positions(_pack(list(np.moveaxis(p, -1, 0))))
        self.inner.check(kin, velocities=False)
        return kin

    def measured(self, kin, goal):
        """f(p): the kept coordinates are p's; a replaced angle is arg(P_b - P_a), taken the
        whole number of turns nearest the goal."""
        out = np.broadcast_to(np.stack(np.broadcast_arrays(*kin.coords), axis=-1),
                              goal.shape).astype(float).copy()
        for j in self.replaced:
            c = self.mech.coordinates[j]
            raw = np.angle(kin.pos[c.b] - kin.pos[c.a])
            out[..., j] = goal[..., j] + _wrap(raw - goal[..., j])
        return out

    def p_of(self, pos, q, near):
        """This chart's p at the configuration ``pos`` whose file coordinates are ``q``: the
        kept coordinates' values, a substitute angle measured the turns nearest ``near``."""
        p = np.array(q, dtype=float)
        for j in self.replaced:
            c = self.inner.mech.coordinates[j]
            z = pos[c.a] if c.b is None else pos[c.b] - pos[c.a]
            if c.kind == "angle":
                p[j] = near[j] + _wrap(float(np.angle(z)) - near[j])
            else:
                p[j] = z.real if c.kind == "x" else z.imag
        return p

    def jacobian(self, kin, shape):
        """J[..., k, i] = d f_k / d p_i from the inner velocities of unit rates of p, and
        L[..., k, i] = (|P_b,i| + |P_a,i|) / |P_b - P_a|, the most a replaced angle can turn
        per unit rate of p_i (1 for a kept coordinate's own p)."""
        n = self.n
        J = np.zeros(shape + (n, n))
        L = np.zeros(shape + (n, n))
        for i in range(n):
            unit = [np.ones(shape) if j == i else np.zeros(shape) for j in range(n)]
            self.inner.velocities(kin, _pack(unit))
            for k in range(n):
                c = self.mech.coordinates[k]
                if k in self.replaced:
                    z = kin.pos[c.b] - kin.pos[c.a]
                    vb, va = kin.vel.get(c.b, 0.0), kin.vel.get(c.a, 0.0)
                    J[..., k, i] = np.imag((vb - va) / z)
                    L[..., k, i] = (np.abs(vb) + np.abs(va)) / np.abs(z)
                else:
                    J[..., k, i] = L[..., k, i] = 1.0 if k == i else 0.0
        kin.linear.clear()
        return J, L

    def conditioning(self, J, L):
        """|det S|, S the rows of J each divided by its largest lever (every coordinate over
        its scale): 0 where a replaced angle is stationary however fast its link's ends move,
        up to 1 for a kept coordinate's row."""
        top = np.max(L * self.p_scale, axis=-1, keepdims=True)
        return np.abs(np.linalg.det(J * self.p_scale / np.where(top > 0, top, 1.0)))

    def solve(self, goal, p):
        """Newton's method on f(p) = goal from p, each step at most half a scale and halved
        while the mechanism does not assemble; returns (kin, p)."""
        kin = self.at(p)
        shape = goal.shape[:-1]
        for _ in range(ITERATIONS):
            miss = self.measured(kin, goal) - goal
            if np.all(np.abs(miss) <= TOLERANCE * self.q_scale):
                return kin, p
            J, _ = self.jacobian(kin, shape)
            step = np.linalg.solve(J, miss[..., None])[..., 0]
            largest = np.max(np.abs(step) / self.p_scale, axis=-1, keepdims=True)
            step = step * np.minimum(1.0, 0.5 / np.maximum(largest, 1e-300))
            for _ in range(HALVINGS):
                try:
                    kin = self.at(p - step)
                    break
                except AssemblyError:
                    step = 0.5 * step
            else:
                break                       # the substitute is at the end of its travel
            p = p - step
        raise AssemblyError(f"no position of the mechanism reached from the figure has "
                            f"{', '.join(self.mech.coordinates[j].name for j in self.replaced)}"
                            f" = {', '.join(f'{np.ravel(goal[..., j])[0]:.6g}' for j in self.replaced)}"
                            " (SI)", file=self.mech.file,
                            hint="keep the coordinates in the range the mechanism reaches")


class SubstituteSolver:
    """Positions and rates in the file's coordinates through the ``charts`` (substitute
    coordinates, best conditioned at the figure first); ``replaced`` are the indices of the
    file's coordinates measured on the positions."""

    def __init__(self, mech, charts, replaced):
        self.mech = mech
        self.replaced = list(replaced)
        self.n = len(mech.coordinates)
        self._figure = np.array([c.value for c in mech.coordinates], dtype=float)
        self._last = None           # (q, positions, chart, p) of the last single solution
        measured = []
        for chart in charts:
            try:
                kin, p = chart.solve(self._figure, chart.p_figure)
                measured.append((float(chart.conditioning(*chart.jacobian(kin, ()))), chart))
            except SolveError:
                continue
        if not measured:
            raise AssemblyError("the figure cannot be assembled through any substitute "
                                "coordinate", file=mech.file)
        measured.sort(key=lambda m: -m[0])
        self.charts = [c for _, c in measured]
        self.figure_measure = measured[0][0]
        self.inner = self.charts[0].inner

    def __getattr__(self, name):
        return getattr(self.inner, name)

    def _coords(self, q) -> list:
        if self.n == 1:
            return [np.asarray(q, dtype=float)]
        return [np.asarray(x, dtype=float) for x in q]

    # positions -----------------------------------------------------------------------------
    def positions(self, q):
        """Every point at the file's coordinates ``q``, by Newton's method in a chart from the
        nearest configuration solved (the figure, or the last single one); another chart takes
        over where the first does not reach (its substitute at a limit of its travel)."""
        target = np.broadcast_arrays(*self._coords(q))
        goal = np.stack(target, axis=-1)                    # (..., n)
        error = None
        for chart, p in self._starts(goal):
            try:
                kin, p = chart.solve(goal, p)
            except AssemblyError as exc:
                error = error or exc
                continue
            kin.substitute = (chart, p) + chart.jacobian(kin, goal.shape[:-1])
            kin.q = target[0]
            if not goal.shape[:-1]:
                self._last = (goal.copy(), {k: complex(v) for k, v in kin.pos.items()},
                              chart, p.copy())
            return kin
        raise error

    def _starts(self, goal):
        """(chart, p) to start Newton from: the last single solution's chart and p when it is
        nearer than the figure, then every other chart at that configuration (where its
        closed form assembles it as it is); else each chart at the figure."""
        figure = [(c, np.broadcast_to(c.p_figure, goal.shape).copy()) for c in self.charts]
        last = self._last
        if last is None or goal.shape != last[0].shape or \
                np.max(np.abs(goal - last[0])) >= np.max(np.abs(goal - self._figure)):
            yield from figure
            return
        q, pos, chart, p = last
        yield chart, p.copy()
        for other in self.charts:
            if other is chart:
                continue
            guess = other.p_of(pos, q, other.p_figure)
            try:
                kin = other.at(guess)
            except SolveError:
                continue
            if max(abs(complex(kin.pos[k]) - v) for k, v in pos.items()) <= 1e-9 * other.size:
                yield other, guess
        yield from figure

    def conditioning(self, kin):
        chart, _, J, L = kin.substitute
        return chart.conditioning(J, L)

    def check(self, kin, velocities: bool):
        chart = kin.substitute[0]
        chart.inner.check(kin, velocities)
        if not velocities:
            return
        measure = self.conditioning(kin)
        if np.any(measure < SINGULAR):
            raise SingularError(f"{self._names()} cannot serve as coordinates here: "
                                f"{self._what()} is stationary as the mechanism moves "
                                f"(conditioning {float(np.min(measure)):.2e} of the map from "
                                f"{self._substitutes(chart)})", file=self.mech.file,
                                measure=float(np.min(measure)),
                                hint="choose as coordinate the angle of a link that keeps "
                                "turning here (a crank or a rocker)")

    # rates ---------------------------------------------------------------------------------
    def velocities(self, kin, qd):
        """p' = J^-1 q'."""
        chart, _, J, _ = kin.substitute
        rates = np.stack(np.broadcast_arrays(*self._coords(qd)), axis=-1)
        # (rates may hold more configurations than the positions: the columns of a jet)
        rates = np.broadcast_to(rates, np.broadcast_shapes(rates.shape, J.shape[:-1]))
        pd = np.linalg.solve(J, rates[..., None])[..., 0]
        return chart.inner.velocities(kin, _pack(list(np.moveaxis(pd, -1, 0))))

    def accelerations(self, kin, qdd, keep=False):
        """p'' = J^-1 (q'' - f''), f'' the replaced angles' second rates at p'' = 0."""
        chart, _, J, _ = kin.substitute
        shape = np.broadcast_shapes(J.shape[:-2], *(np.shape(v) for v in kin.vel.values()))
        zero = [np.zeros(shape) for _ in range(self.n)]
        chart.inner.accelerations(kin, _pack(zero), keep=True)
        curvature = np.zeros(shape + (self.n,))
        for k in self.replaced:
            c = self.mech.coordinates[k]
            z = kin.pos[c.b] - kin.pos[c.a]
            w = (kin.vel.get(c.b, 0.0) - kin.vel.get(c.a, 0.0)) / z
            curvature[..., k] = np.imag((kin.acc.get(c.b, 0.0) - kin.acc.get(c.a, 0.0)) / z
                                        - w * w)
        wanted = np.broadcast_to(np.stack(np.broadcast_arrays(*self._coords(qdd)), axis=-1),
                                 curvature.shape)
        pdd = np.linalg.solve(J, (wanted - curvature)[..., None])[..., 0]
        return chart.inner.accelerations(kin, _pack(list(np.moveaxis(pdd, -1, 0))), keep)

    # words ---------------------------------------------------------------------------------
    def substitution(self) -> list:
        """How the file's coordinates are reached, for ``explain``."""
        return [f"{self.mech.coordinates[j].name} is reached through "
                f"{self.inner.mech.coordinates[j].name} = "
                f"{_what(self.inner.mech.coordinates[j])} (Newton's method on the angle; "
                "the decomposition places the substitute; another takes over where it stops)"
                for j in self.replaced]

    def _names(self) -> str:
        return ", ".join(self.mech.coordinates[j].name for j in self.replaced)

    def _what(self) -> str:
        return ", ".join(f"the angle of {c.a}->{c.b}" for c in
                         (self.mech.coordinates[j] for j in self.replaced))

    def _substitutes(self, chart) -> str:
        return ", ".join(chart.inner.mech.coordinates[j].name for j in self.replaced)

def _what(c) -> str:
    return f"angle of {c.a}->{c.b}" if c.kind == "angle" else f"{c.kind} of {c.a}"
