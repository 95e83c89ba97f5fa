"""Static equilibrium of a mechanism with springs, gravity and constant loads.

The free coordinates q_f satisfy Q_f(q) = -dV/dq_f = 0, the imposed ones stay
at their figure values.  The equilibrium is the one the mechanism settles in
when it is let go at rest from the figure: the figure itself when it is an
equilibrium (stable or not), otherwise a minimum of V reached by descending
from the figure.  The descent is a trust-region Newton method on V in scaled
coordinates y = (q_f - q_f,figure) / c (c = 1 rad for an angle, the mechanism's
size for a length), with the gradient -c Q_f and the Hessian c K_ff c of
``forces.lagrange``: each step minimises the quadratic model within a radius
(along the direction of negative curvature where K is not positive definite),
so it cannot stop at a saddle point or a maximum, and it stops beyond REACH
scales from the figure (the potential falls without bound there).

A configuration is an equilibrium when every |Q_i| is below TOL times that
coordinate's load scale: the sum over the loads of |force| times the speed of
the point (or body) it acts on per unit rate of q_i, and over the springs of
(|N| + k L) times the speed of their ends (L the mechanism's size, 1 rad for
a torsional spring).  The scale does not vanish where a force's lever does
(a spring aligned with the motion of its end at the equilibrium).  Evaluated
in floating point, Q_i carries a rounding error of about 1e-16 of this scale,
so TOL leaves six orders of magnitude for the terms' own rounding and still
places the equilibrium to 1e-10 of the load scale over the stiffness.

Springs whose preload is 'static' get the forces N that make the figure an
equilibrium, from the linear system sum_s N_s s_i = Q_i (other loads) (each
spring's Q_i is -N s_i).  Its rank is decided on the columns s_i divided by the
speed of each spring's ends (its lever): a spring whose length changes by less
than RIGID of its ends' motion (both ends on one body) cannot hold a load.

Its twin in formulas is ``forces.symbolic`` (``Lagrangian.equilibrium``: the figure, the
root of a linear Q = 0, else this numeric equilibrium stated as the symbols q_e).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from linkcli.errors import Caution, EquilibriumError, SingularError, SolveError
from linkcli.forces.lagrange import Lagrangian, Terms
from linkcli.model import elements as el

#: the largest generalised force left at an equilibrium, as a fraction of its load scale
TOL = 1e-10
#: a spring whose measure changes by less than RIGID of its ends' speed is carried rigidly
RIGID = 1e-9
#: the descent stops this many coordinate scales away from the figure
REACH = 1e6
#: the most steps the descent takes
STEPS = 500
#: an eigenvalue of the scaled K below NEUTRAL times the largest is taken as zero
NEUTRAL = 1e-9


@dataclass
class Equilibrium:
    """The static equilibrium: coordinates (SI), the terms there, and how well it holds."""

    q: np.ndarray
    terms: Terms
    free: list                 # indices of the free coordinates
    residual: np.ndarray       # Q_f at q
    scale: np.ndarray          # load scale of each free coordinate
    preloads: dict             # 'static' spring -> the force chosen at the figure (N)
    stability: str = "stable"  # 'stable', 'neutral', 'saddle' or 'maximum' (of V)
    steps: int = 0             # descent steps from the figure (0: the figure is one)
    refused: object = None     # the error that refused the descent's last steps, if any
    cautions: list = field(default_factory=list)

    @property
    def relative(self) -> float:
        return float(np.max(np.abs(self.residual) / self.scale)) if len(self.free) else 0.0


def free_coordinates(mech) -> list:
    imposed = set(mech.elements.imposed) if mech.elements is not None else set()
    return [j for j in range(len(mech.coordinates)) if j not in imposed]


def load_scale(lag: Lagrangian, terms: Terms, free) -> np.ndarray:
    """Per free coordinate, the scale of the generalised forces: the sum over the loads
    of |force| times the speed of where it acts (gravity m|g||G_i|, forces |F||P_i|,
    torques |C||theta_i|) and over the springs of (|N| + k L) times the speed of their
    ends, L the mechanism's size (1 rad for a torsional spring): the force of a spring
    strained by the order of the mechanism."""
    n = lag.n
    scale = np.zeros(n)
    g = abs(lag.dyn.gravity) if lag.dyn is not None else 0.0
    for m in terms.masses:
        scale += m.mass * g * np.abs([m.g[1][i] for i in range(n)])
    rot = terms.rotations
    for spring in lag.elements.springs.values():
        strain = spring.stiffness * (1.0 if spring.measure.kind == "angle" else lag.size)
        lever = lag.lever(terms.jet, spring.measure, rot)
        scale += (abs(terms.forces[spring.name]) + strain) * lever
    for load in lag.mech.loads.values():
        if load.value is not None and load.kind in ("force", "torque", "axial"):
            scale += abs(load.value) * lag.load_lever(terms.jet, load, rot)
    scale = scale[free]
    fallback = float(np.max(scale)) if scale.size and np.max(scale) > 0 else 1.0
    return np.where(scale > 0, scale, fallback)


def static_preloads(lag: Lagrangian, free) -> dict:
    """Solve the forces of the 'static' springs that make the figure an equilibrium and
    set their free measures; returns {spring: N}."""
    static = [s for s in lag.elements.springs.values() if s.mode == el.STATIC]
    if not static:
        return {}
    terms = lag.terms(lag.figure)      # static springs are unstretched here: N = 0
    A = np.array([[terms.measures[s.name].grad[i] for s in static] for i in free], dtype=float)
    b = terms.Q[free]
    names = ", ".join(s.name for s in static)
    rank = _lever_rank(lag, terms, static, free, A)
    if rank < len(static):
        raise EquilibriumError(
            f"the preloads of {names} are not determined by equilibrium: {len(static)} "
            f"unknown forces, {rank} independent equations (a spring whose length changes by "
            f"less than {RIGID:g} of its ends' motion holds no load)", reason="undetermined",
            file=lag.mech.file, hint="give the other springs a free length or a preload, and "
            "'preload: static' to one spring per coordinate, between points of different "
            "bodies")
    scale = load_scale(lag, terms, free)      # each equation over its load scale: a
    forces, *_ = np.linalg.lstsq(A / scale[:, None], b / scale, rcond=None)   # length's
    residual = A @ forces - b                 # and an angle's weigh alike at any size
    if np.any(np.abs(residual) > TOL * scale):
        worst = int(np.argmax(np.abs(residual) / scale))
        raise EquilibriumError(
            f"no preload of {names} makes the figure an equilibrium: the force on coordinate "
            f"{lag.mech.coordinates[free[worst]].name} is left at {residual[worst]:.6g} (SI)",
            reason="inconsistent", residual=float(np.max(np.abs(residual) / scale)),
            file=lag.mech.file, hint="let the equilibrium be solved ('equilibrium: solve'), "
            "or give 'preload: static' to a spring acting on that coordinate")
    out = {}
    for spring, force in zip(static, forces):
        lag.free[spring.name] -= float(force) / spring.stiffness
        out[spring.name] = float(force)
    return out


def _lever_rank(lag, terms, static, free, A) -> int:
    """The rank of the static springs' columns s_i, each divided by its spring's lever
    (the largest speed of its ends over the free coordinates, each coordinate taken over
    its scale): singular values below RIGID are rounding, not equations."""
    c = lag.scales[free]
    levers = np.array([lag.lever(terms.jet, s.measure, terms.rotations)[free] * c
                       for s in static]).T
    top = np.max(levers, axis=0)
    scaled = np.where(top > 0, (A * c[:, None]) / np.where(top > 0, top, 1.0), 0.0)
    if not scaled.size:
        return 0
    return int(np.sum(np.linalg.svd(scaled, compute_uv=False) > RIGID))


def equilibrium(lag: Lagrangian) -> Equilibrium:
    """The static equilibrium reached from the figure (or the figure, 'equilibrium: figure')."""
    mech = lag.mech
    free = free_coordinates(mech)
    preloads = static_preloads(lag, free)
    mode = mech.elements.equilibrium if mech.elements is not None else "solve"
    q = lag.figure.copy()
    terms = lag.terms(q)
    result = _result(lag, terms, free, preloads)
    if mode == "solve" and free and result.relative > TOL:
        result = _descend(lag, terms, free, preloads)
        if result.relative <= TOL and result.stability in ("saddle", "maximum"):
            raise EquilibriumError(
                f"the search from the figure stopped at a {_kind(result)} of the potential "
                f"energy ({_where(lag, result)}), not at a stable equilibrium",
                reason="stalled", residual=result.relative, file=mech.file,
                hint="draw the figure nearer the equilibrium the exam means")
    if result.stability in ("saddle", "maximum") and result.relative <= TOL:
        result.cautions.append(Caution(
            "unstable", f"the static equilibrium, the figure ({_where(lag, result)}), is "
            f"unstable: a {_kind(result)} of the potential energy, which the mechanism leaves "
            "at the least disturbance", mech.file))
    if result.relative > TOL and result.refused is not None:
        what = "a toggle or dead point" if isinstance(result.refused, SingularError) else \
            "it cannot be assembled further"
        raise EquilibriumError(
            f"no static equilibrium found from the figure: the search stops at "
            f"{_where(lag, result, 4)}, where the mechanism cannot move on ({what}) and the "
            "potential energy still falls", reason="stalled", residual=result.relative,
            file=mech.file, hint="the equilibrium may lie beyond it: take as coordinate the "
            "angle of a link that keeps turning there, or check the springs and loads")
    if result.relative > TOL:
        forces = ", ".join(f"{mech.coordinates[j].name}: {result.terms.Q[j]:.6g}" for j in free)
        where = "the figure is not a static equilibrium" if mode == "figure" else \
            "no static equilibrium found from the figure"
        raise EquilibriumError(
            f"{where}: residual generalised forces {forces} (SI; {result.relative:.2e} of the "
            "load scale)", reason="figure" if mode == "figure" else "stalled",
            residual=result.relative, file=mech.file,
            hint="check the springs' free lengths and preloads, the masses and gravity"
            + ("; or let it be solved ('equilibrium: solve')" if mode == "figure" else ""))
    return result


def _kind(result) -> str:
    return "saddle point" if result.stability == "saddle" else result.stability


def _where(lag, result, digits=6) -> str:
    """The free coordinates at the result, in the file's angle and length units."""
    out = []
    for j in result.free:
        c = lag.mech.coordinates[j]
        unit, factor = lag.mech.units.display("angle" if c.kind == "angle" else "length", 0)
        out.append(f"{c.name} = {result.q[j] / factor:.{digits}g} {unit}")
    return ", ".join(out)


def _result(lag, terms, free, preloads, steps=0) -> Equilibrium:
    residual = terms.Q[free]
    result = Equilibrium(terms.q, terms, free, residual, load_scale(lag, terms, free), preloads,
                         steps=steps)
    result.stability = stability(lag, terms, free)
    return result


def stability(lag, terms, free) -> str:
    """What V has at q: 'stable' (a minimum: K_ff positive definite), 'neutral' (positive
    semi-definite), 'saddle' or 'maximum', from the eigenvalues of c K_ff c."""
    if not free:
        return "stable"
    c = lag.scales[free]
    w = np.linalg.eigvalsh(c[:, None] * terms.K[np.ix_(free, free)] * c[None, :])
    floor = NEUTRAL * max(float(np.max(np.abs(w))), 1e-300)
    if w[0] > floor:
        return "stable"
    if w[0] >= -floor:
        return "neutral"
    return "maximum" if w[-1] < -floor else "saddle"


def _descend(lag, start: Terms, free, preloads) -> Equilibrium:
    """A minimum of V from the figure by a trust-region Newton method (module docstring)."""
    c = lag.scales[free]
    figure = start.q

    refused = []

    def at(y):
        q = figure.copy()
        q[free] = figure[free] + c * y
        try:
            return lag.terms(q)
        except SolveError as exc:       # not assembled there: the step is refused
            refused[:] = [exc]
            return None

    energy = _energy(lag, start, free, c)
    noise = 1e-12
    y, t, radius = np.zeros(len(free)), start, 0.25
    for step in range(1, STEPS + 1):
        g, H = _model(t, free, c, energy)
        p = _trust_step(g, H, radius)
        if np.max(np.abs(y + p)) > REACH:
            raise _unbounded(lag, start, free, y + p)
        new = at(y + p)
        predicted = -(g @ p + 0.5 * p @ H @ p)
        if new is None:
            radius = 0.25 * np.linalg.norm(p)
            continue
        fall = (t.V - new.V) / energy
        closer = np.linalg.norm(new.Q[free] * c / energy) < np.linalg.norm(g)
        if fall > 0.1 * predicted or (closer and fall >= -noise):
            y, t = y + p, new
            result = _result(lag, t, free, preloads, step)
            if result.relative <= TOL and result.stability in ("stable", "neutral"):
                return _polish(lag, result, at, c, energy)
        ratio = fall / predicted if predicted > 0 else -1.0
        if ratio < 0.25:
            radius = 0.25 * np.linalg.norm(p)
        elif ratio > 0.75 and np.linalg.norm(p) > 0.99 * radius:
            radius = min(2 * radius, REACH)
        if radius < 1e-15 * max(1.0, np.linalg.norm(y)):
            break
    result = _result(lag, t, free, preloads, step)
    result.refused = refused[0] if refused and radius < 1e-6 else None
    return result


def _energy(lag, start: Terms, free, c) -> float:
    """The energy the descent measures V in: the load scales times the coordinates' scales
    (J), so that its gradient and Hessian are numbers of order one whatever the size (their
    squares in the norms would overflow a double from sizes of about 1e75 m on)."""
    return float(np.sum(load_scale(lag, start, free) * c)) or 1.0


def _model(t: Terms, free, c, energy):
    """The gradient -c Q_f and the Hessian c K_ff c of V in the scaled coordinates, over
    ``energy``."""
    ix = np.ix_(free, free)
    return -t.Q[free] * c / energy, c[:, None] * t.K[ix] * c[None, :] / energy


def _polish(lag, result: Equilibrium, at, c, energy) -> Equilibrium:
    """Newton steps from an accepted equilibrium while they reduce the residual: the answer is
    then as exact as the rounding of Q allows, not just within TOL."""
    free = result.free
    if result.stability != "stable":
        return result
    y = (result.q[free] - lag.figure[free]) / c
    for _ in range(4):
        t = result.terms
        g, H = _model(t, free, c, energy)
        new = at(y - np.linalg.solve(H, g))
        if new is None or np.linalg.norm(new.Q[free] * c / energy) >= np.linalg.norm(g):
            break
        y = y - np.linalg.solve(H, g)
        result = _result(lag, new, free, result.preloads, result.steps + 1)
    return result


def _trust_step(g, H, radius):
    """The step p minimising g.p + 1/2 p.H.p with |p| <= radius: the Newton step when H is
    positive definite and it fits, else p = -(H + lam I)^-1 g with |p| = radius (lam >= the
    opposite of H's smallest eigenvalue, found by bisection), or along the eigenvector of
    negative curvature when g has no component on it."""
    w, U = np.linalg.eigh(H)
    gt = U.T @ g
    if w[0] > 0:
        p = -U @ (gt / w)
        if np.linalg.norm(p) <= radius:
            return p
    low = max(0.0, -w[0])
    gnorm = np.linalg.norm(g)
    if gnorm == 0 or np.linalg.norm(gt[w <= w[0] + 1e-14 * max(1.0, abs(w[0]))]) <= \
            1e-14 * gnorm and np.linalg.norm(_shifted(gt, w, low)) < radius:
        p = _shifted(gt, w, low)                      # the hard case: add negative curvature
        extra = np.sqrt(max(radius ** 2 - p @ p, 0.0))
        return U @ p + extra * U[:, 0]
    high = low + gnorm / radius
    for _ in range(200):
        lam = 0.5 * (low + high)
        if lam in (low, high):
            break
        if np.linalg.norm(gt / (w + lam)) > radius:
            low = lam
        else:
            high = lam
    return -U @ (gt / (w + high))


def _shifted(gt, w, lam):
    """-(w + lam)^-1 gt, components on a zero shifted eigenvalue left out."""
    d = w + lam
    return np.where(np.abs(d) > 0, -gt / np.where(np.abs(d) > 0, d, 1.0), 0.0)


def _unbounded(lag, start: Terms, free, y) -> EquilibriumError:
    """The refusal of a descent that leaves REACH: the potential keeps falling.  Where K at
    the figure is positive definite, its Newton step says how far the equilibrium would be."""
    mech = lag.mech
    names = [mech.coordinates[free[k]].name for k in np.argsort(-np.abs(y))[:2]
             if abs(y[k]) > 0.1 * np.max(np.abs(y))]
    detail = (f"no static equilibrium within {REACH:g} times the mechanism's size (1 rad for an "
              f"angle) of the figure: the potential energy keeps falling along "
              f"{', '.join(names)}")
    K = start.K[np.ix_(free, free)]
    if stability(lag, start, free) == "stable":
        delta = np.linalg.solve(K, start.Q[free])
        k = int(np.argmax(np.abs(delta) / lag.scales[free]))
        c = mech.coordinates[free[k]]
        unit, factor = mech.units.display("angle" if c.kind == "angle" else "length", 0)
        detail += (f" (linearised at the figure, the springs would hold the loads with "
                   f"{c.name} moved by {delta[k] / factor:.4g} {unit})")
    return EquilibriumError(detail, reason="unbounded", file=mech.file,
                            hint="check the stiffnesses against the loads and gravity: a "
                            "coordinate that no spring holds has no equilibrium")
