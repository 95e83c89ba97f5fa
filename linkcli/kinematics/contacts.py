"""Rolling contacts and cords as relations between measures of the mechanism's points.

Integrated from the figure, every contact of ``model.Rolling`` (a disc rolling without
slipping, a taut cord or belt strand on a pulley) is one relation

    sum_k c_k (mu_k - mu_k0) = 0

over three kinds of measure (mu_k0 its value on the figure):

- ``Turn(a, b)``: the angle of P_b - P_a, within half a turn of the figure's; when a -> b
  (or b -> a) is the vector of an angle coordinate q_j, it is q_j - q_j0, any number of
  turns;
- ``Along(u, a, b)``: Re(conj(u) (P_a - P_b)), u a fixed unit vector (no b: P_a's own);
- ``Carried(b, c, a, o, rho)``: Re(conj(rho Z) (P_a - P_o)) / L with Z = P_c - P_b and
  L = |Z|: how far P_a is from P_o along the direction rho Z / L of a body that carries
  b, c and o (rho = e^{i gamma}, a constant turn from the body's axis to the line).

The disc (centre C, second point M, radius r, the model's side s) turns by Turn(C, M):

- on a fixed line u:          -Turn(C, M) + (s / r) Along(u, C)
- on a line of body B:        -Turn(C, M) + Turn(b, c) + (s / r) Carried(b, c, C, o, rho)
  (b -> c B's axis, o one of its points: the disc rolls on a fixed line of B's own frame)
- a cord to P along u:        -Turn(C, M) + (s / r) Along(u, C, P)
- a belt strand to disc E (centre D, second point N, radius r_E, side s_E), slipping by
  the fraction f (0 unless given; the pulley C is the follower):
                              -Turn(C, M) + (1 - f) [(s / r) Along(u, C, D)
                                                     + (s s_E r_E / r) Turn(D, N)]
- a circle about O, radius R: -Turn(C, M) + k Turn(O, C), k = -(R - r) / r inside,
                              (R + r) / r outside
- disc E about its centre O:  as the circle, + (R / r) Turn(O, N) inside, - (R / r) outside.

Differentiated in time, sum c_k mu_k' = 0 and sum c_k mu_k'' = 0: each measure gives its
rates from the points' (``rate``, ``accel``) and its gradient G_P with
d mu = Re(conj(G_P) dP) (``grad``).  A relation is solved for the one thing it leaves
unknown (``assur``): the turn of a disc (its second point M = C + |M - C| e^{i theta}),
or a point X on which it is linear, which it puts on the line Re(conj(w) X) = v with
w = sum c_k G_X,k (a constraint of a dyad, like a guide).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from linkcli.model.mechanism import FRAME


def _get(d, name):
    return d.get(name, 0.0)


@dataclass(frozen=True)
class Turn:
    """mu = arg(P_b - P_a) from the figure's, within half a turn; with ``coord`` j (the
    vector of angle coordinate j, ``flip`` when it runs b -> a) mu = q_j - q_j0."""

    a: str
    b: str
    coord: int | None = None

    @property
    def points(self):
        """The points it is measured on: none through a coordinate (q gives it)."""
        return () if self.coord is not None else (self.a, self.b)

    def linear(self, p, known) -> bool:
        return False

    def reference(self, figure, q0):
        if self.coord is not None:
            return q0[self.coord]
        z = figure[self.b] - figure[self.a]
        return z / abs(z)

    def relative(self, pos, q, ref, turns=None):
        """Through a coordinate, or as a disc turned earlier in the solving order found it
        (``turns``, any number of turns), else within half a turn of the figure."""
        if self.coord is not None:
            return q[self.coord] - ref
        if turns and (self.a, self.b) in turns:
            return turns[(self.a, self.b)]
        return np.angle((pos[self.b] - pos[self.a]) * np.conj(ref))

    def rate(self, pos, d, qrate):
        if self.coord is not None:
            return qrate[self.coord]
        return ((_get(d, self.b) - _get(d, self.a)) / (pos[self.b] - pos[self.a])).imag

    def accel(self, pos, vel, d, qrate):
        if self.coord is not None:
            return qrate[self.coord]
        z = pos[self.b] - pos[self.a]
        w = (_get(vel, self.b) - _get(vel, self.a)) / z
        return ((_get(d, self.b) - _get(d, self.a)) / z - w * w).imag

    def grad(self, pos, p):
        """d mu = Im(dZ / Z) = Re(conj(i Z) dZ) / |Z|^2 (0 through a coordinate)."""
        if self.coord is not None:
            return 0j
        z = pos[self.b] - pos[self.a]
        g = 1j * z / (np.abs(z) ** 2)
        return g if p == self.b else -g if p == self.a else 0j


@dataclass(frozen=True)
class Along:
    """mu = Re(conj(u) (P_a - P_b)) (``b`` None: of P_a alone); linear in the points."""

    u: complex
    a: str
    b: str | None = None

    @property
    def points(self):
        return (self.a,) if self.b is None else (self.a, self.b)

    def linear(self, p, known) -> bool:
        return p in self.points

    def value(self, pos):
        z = pos[self.a] - (pos[self.b] if self.b else 0)
        return (np.conj(self.u) * z).real

    def reference(self, figure, q0):
        return self.value(figure)

    def relative(self, pos, q, ref, turns=None):
        return self.value(pos) - ref

    def rate(self, pos, d, qrate):
        return (np.conj(self.u) * (_get(d, self.a) - (_get(d, self.b) if self.b else 0))).real

    def accel(self, pos, vel, d, qrate):
        return self.rate(pos, d, qrate)

    def grad(self, pos, p):
        return self.u if p == self.a else -self.u if p == self.b else 0j


@dataclass(frozen=True)
class Carried:
    """mu = Re(conj(rho Z) R) / L, Z = P_c - P_b, R = P_a - P_o, L = |Z| (constant: b, c
    are points of one rigid body); bilinear in the points."""

    b: str
    c: str
    a: str
    o: str
    rho: complex
    length: float

    @property
    def points(self):
        return (self.b, self.c, self.a, self.o)

    def linear(self, p, known) -> bool:
        """Linear in P_a or P_o while b and c are known (and the other way round)."""
        if p in (self.a, self.o):
            return self.b in known and self.c in known and p not in (self.b, self.c)
        if p in (self.b, self.c):
            return self.a in known and self.o in known
        return False

    def value(self, pos):
        z = pos[self.c] - pos[self.b]
        return (np.conj(self.rho * z) * (pos[self.a] - pos[self.o])).real / self.length

    def reference(self, figure, q0):
        return self.value(figure)

    def relative(self, pos, q, ref, turns=None):
        return self.value(pos) - ref

    def _parts(self, pos, d):
        z = pos[self.c] - pos[self.b]
        r = pos[self.a] - pos[self.o]
        dz = _get(d, self.c) - _get(d, self.b)
        dr = _get(d, self.a) - _get(d, self.o)
        return z, r, dz, dr

    def rate(self, pos, d, qrate):
        z, r, dz, dr = self._parts(pos, d)
        rho = self.rho
        return ((np.conj(rho * dz) * r).real + (np.conj(rho * z) * dr).real) / self.length

    def accel(self, pos, vel, d, qrate):
        _, _, vz, vr = self._parts(pos, vel)
        return self.rate(pos, d, qrate) + 2.0 * (np.conj(self.rho * vz) * vr).real / self.length

    def grad(self, pos, p):
        """G_a = -G_o = rho Z / L, G_c = -G_b = conj(rho) R / L."""
        g = 0j
        if p in (self.a, self.o):
            z = self.rho * (pos[self.c] - pos[self.b]) / self.length
            g = z if p == self.a else -z
        if p in (self.b, self.c):
            r = np.conj(self.rho) * (pos[self.a] - pos[self.o]) / self.length
            g = g + (r if p == self.c else -r)
        return g


@dataclass
class Relation:
    """sum c_k (mu_k - mu_k0) = 0 over ``terms`` (measure, c_k, mu_k0) of the contacts
    ``names`` (one; two when a disc's turn was eliminated between them)."""

    names: tuple
    terms: tuple
    disc: str | None = None         # the disc the contact turns (its Turn has c = -1)

    @property
    def name(self) -> str:
        return " and ".join(self.names)

    def points(self) -> set:
        return {p for term, _, _ in self.terms for p in term.points}

    def residual(self, pos, q, turns=None, skip=None):
        """sum c_k (mu_k - mu_k0), ``skip`` left out; ``turns`` as :meth:`Turn.relative`."""
        return sum(c * term.relative(pos, q, ref, turns) for term, c, ref in self.terms
                   if term is not skip)

    def rate(self, pos, d, qrate, skip=None):
        """sum c_k mu_k' from the rates ``d`` (absent ones zero), ``skip`` left out."""
        return sum(c * term.rate(pos, d, qrate) for term, c, _ in self.terms
                   if term is not skip)

    def accel(self, pos, vel, d, qrate, skip=None):
        return sum(c * term.accel(pos, vel, d, qrate) for term, c, _ in self.terms
                   if term is not skip)

    def grad(self, pos, p):
        """w with d(sum c_k mu_k) = Re(conj(w) dP) for point ``p``."""
        return sum(c * term.grad(pos, p) for term, c, _ in self.terms)

    def coefficient(self, term) -> float:
        return sum(c for t, c, _ in self.terms if t == term)

    @staticmethod
    def combine(weighted, dropped=()) -> "Relation":
        """sum lambda_i R_i of ``weighted`` [(R_i, lambda_i)], the measures ``dropped`` left
        out (turns the weights cancel); the same measure's coefficients added."""
        merged = {}
        for rel, weight in weighted:
            for term, c, ref in rel.terms:
                if term in dropped:
                    continue
                old = merged.get(term, (0.0, ref))[0]
                merged[term] = (old + weight * c, ref)
        names = tuple(n for rel, _ in weighted for n in rel.names)
        return Relation(names, tuple((t, c, ref) for t, (c, ref) in merged.items()))


@dataclass
class Track:
    """A relation as a constraint on one unknown point ``p`` of a dyad: the line
    Re(conj(w) P) = v, w = sum c_k G_P,k, v from the other (known) measures.  As a guide
    it is the line cross(C - B, P - B) = value with B = 0, C = i w, value = -v.  The points
    of ``rigid`` move with P by a constant offset (a slider's points on a fixed guide), so
    their gradients add to w; ``spend`` names the contacts the dyad that uses it consumes."""

    relation: Relation
    p: str
    body: str = ""
    rigid: dict | None = None
    spend: tuple = ()

    def __post_init__(self):
        self.body = self.body or self.relation.name
        self.rigid = self.rigid or {self.p: 0j}

    def line(self, pos, q, turns=None):
        """(B, C, value) of the line through the known positions ``pos``."""
        without = dict(pos)
        without.update(self.rigid)          # P at the origin, its body's points with it
        w = self.grad(without)
        v = -self.relation.residual(without, q, turns)
        return 0j, 1j * w, -v

    def grad(self, pos):
        return sum(self.relation.grad(pos, x) for x in self.rigid)

    def rhs(self, pos, d, qrate, vel):
        """r of Re(conj(w) P') = r (``vel`` None) or Re(conj(w) P'') = r: minus the
        relation's rate with P's own rate left out (``d`` does not hold it yet)."""
        if vel is None:
            return -self.relation.rate(pos, d, qrate)
        return -self.relation.accel(pos, vel, d, qrate)


# --- the relations of a mechanism --------------------------------------------------------
def relations(mech) -> dict:
    """name -> Relation of every contact of ``mech``, its references on the figure."""
    figure = {**mech.fixed, **mech.moving}
    q0 = [_coordinate_reference(mech, c, figure) for c in mech.coordinates]
    out = {}
    for r in mech.rolling.values():
        terms = []
        for term, c in contact_terms(r, mech):
            if isinstance(term, Turn):
                term = _driven(term, mech)
                if term.coord is None and term.a in mech.fixed and term.b in mech.fixed:
                    continue            # a turn of the frame: zero
            terms.append((term, c, term.reference(figure, q0)))
        out[r.name] = Relation((r.name,), tuple(terms), r.disc)
    return out


def _coordinate_reference(mech, coord, figure):
    """q_j0 of an angle coordinate: the angle of its vector on the figure, on the turn
    nearest the file's value (so that the file's own value is the figure's turn)."""
    if coord.kind != "angle":
        return coord.value
    drawn = float(np.angle(figure[coord.b] - figure[coord.a]))
    return drawn + 2 * np.pi * round((coord.value - drawn) / (2 * np.pi))


def _driven(term, mech):
    """The turn as coordinate j where its vector is an angle coordinate's (either way)."""
    for j, c in enumerate(mech.coordinates):
        if c.kind == "angle" and {c.a, c.b} == {term.a, term.b}:
            return Turn(c.a, c.b, j)
    return term


def contact_terms(r, mech) -> list:
    """[(measure, c)] of contact ``r`` (module docstring), the disc's turn first."""
    disc = mech.bodies[r.disc]
    terms = [(Turn(r.center, disc.points[1]), -1.0)]
    if r.kind == "line" and r.carrier == FRAME:
        return terms + [(Along(r.direction, r.center), r.side / r.radius)]
    if r.kind == "line":
        b, c, o = carrier_axis(mech, r.carrier)
        figure = {**mech.fixed, **mech.moving}
        z = figure[c] - figure[b]
        rho = r.direction / (z / abs(z))
        terms.append((Turn(b, c), 1.0))
        return terms + [(Carried(b, c, r.center, o, complex(rho), _axis_length(mech, r.carrier,
                                                                               b, c)),
                         r.side / r.radius)]
    if r.kind == "cord":
        return terms + [(Along(r.direction, r.center, r.point), r.side / r.radius)]
    if r.kind == "belt":
        other = mech.bodies[r.other]
        kept = 1.0 - r.slip             # the follower's share of the belt's motion
        return terms + [(Along(r.direction, r.center, r.track), kept * r.side / r.radius),
                        (Turn(other.points[0], other.points[1]),
                         kept * r.side * r.other_side * r.track_radius / r.radius)]
    ratio = -(r.track_radius - r.radius) / r.radius if r.inside else \
        (r.track_radius + r.radius) / r.radius
    terms.append((Turn(r.track, r.center), ratio))
    if r.kind == "disc":
        other = mech.bodies[r.other]
        spin = (1.0 if r.inside else -1.0) * r.track_radius / r.radius
        terms.append((Turn(other.points[0], other.points[1]), spin))
    return terms


def carrier_axis(mech, name) -> tuple:
    """(b, c, o) of the body that carries a line: the points of its axis b -> c (a link's
    first two, a block's guide) and a point o of it (a block's own point)."""
    body = mech.bodies[name]
    if body.kind == "link":
        return body.points[0], body.points[1], body.points[0]
    return body.guide.b, body.guide.c, body.points[0]


def _axis_length(mech, name, b, c) -> float:
    """|P_c - P_b| of a carrier's axis (constant: a rigid body's, or a guide's)."""
    body = mech.bodies[name]
    if body.kind == "link":
        return abs(body.local[c] - body.local[b])
    figure = {**mech.fixed, **mech.moving}
    return abs(figure[c] - figure[b])


