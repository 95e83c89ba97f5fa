"""The exam's Assur answer in pseudo-MATLAB: the solving order as calls of the dyad functions.

The Padova exams ask for the position analysis as calls of a small library of
functions on complex numbers (a point is ``P = x + iy``, angles in radians,
counter-clockwise from +x):

- ``P = complex(x, y)``: a point given by its coordinates;
- ``P = diadeRRR(P1, P2, l1, l2, s)``: the pin of two links pivoted at the known
  points P1 and P2, ``|P - P1| = l1``, ``|P - P2| = l2``; ``s = 'sx'`` puts P to the
  left of the direction P1->P2, ``'dx'`` to its right;
- ``[P, K] = diadeRRP(P1, O, alpha, l, e, s)``: the pin of a link pivoted at P1
  (``|P - P1| = l``) and of a slider on the line through O at the angle alpha, P at the
  signed distance e to the left of the line, K its foot on the line; ``s = 'pos'``
  puts P ahead of the foot of P1 along alpha, ``'neg'`` behind it;
- ``angle(z)``, ``abs(z)`` and ``exp(1i*phi)`` for what follows rigidly: a point P of
  a body whose points K and M are known is ``P = K + l_KP*exp(1i*(angle(M - K) + beta_P))``
  with beta_P the angle from K->M to K->P on the body.

A group the library has no function for (a slotted link, a point on two guides, a
rolling contact or cord, a kind of group the decomposition learns later) is written as a
call named after its kind and marked by a comment; it is never left out.
"""
from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass

import numpy as np

from linkcli.errors import StructureError
from linkcli.kinematics.dyads import cross
from linkcli.kinematics.solvers import solver_for
from linkcli.kinematics.contacts import Track
from linkcli.kinematics.assur import partial
from linkcli.kinematics.groups import Dist, Line
from linkcli.model.mechanism import FRAME

#: the functions of the exam's library, with the argument order of their legend line
LIBRARY = {
    "diadeRRR": "P = diadeRRR(P1, P2, l1, l2, s): |P - P1| = l1, |P - P2| = l2; "
                "s = 'sx' puts P left of P1->P2, 'dx' right",
    "diadeRRP": "[P, K] = diadeRRP(P1, O, alpha, l, e, s): |P - P1| = l, P at e left of the "
                "line through O at angle alpha, K its foot; s = 'pos' puts P ahead of P1's foot "
                "along alpha, 'neg' behind",
}
#: a coordinate within this fraction of the mechanism's size of another is the same
SAME = 1e-9


@dataclass(frozen=True)
class Constant:
    """A geometric constant: ``name = value`` (the value as written, in the file's units).

    kind 'point' (a frame point or a point of a guide), 'length' (between ``points``),
    'angle', 'offset' (a pin's distance from its guide, or a fixed vector), 'ratio' (the
    complex factor w of a placement P = K + (M - N) w) or 'coordinate' (the driver's value,
    or an independent coordinate's as the figure draws it)."""

    name: str
    value: str
    kind: str
    points: tuple = ()
    note: str = ""


@dataclass(frozen=True)
class Call:
    """One line of the procedure: ``outputs = function(args)``, or ``outputs = args[0]``
    when ``function`` is None (an expression).

    ``reads`` are the names it needs (points, constants, earlier outputs); ``kind`` is the
    decomposition group's kind it comes from ('RRR', 'place', 'driver-angle', ...),
    'direction' for an ``angle(M - K)`` a placement needs, 'triad' for a class-III group;
    ``library`` is False for a function the exam's library does not define; ``step`` is
    the group's number in the solving order (0 for a rigid placement that follows it)."""

    outputs: tuple
    function: str | None
    args: tuple
    reads: tuple
    kind: str
    library: bool = True
    note: str = ""
    step: int = 0
    heading: str = ""

    @property
    def right(self) -> str:
        if self.function is None:
            return self.args[0]
        return f"{self.function}({', '.join(self.args)})"

    @property
    def left(self) -> str:
        return self.outputs[0] if len(self.outputs) == 1 else f"[{', '.join(self.outputs)}]"


@dataclass
class Procedure:
    """The position analysis as calls: constants, coordinates, then the calls in order."""

    title: str
    units: str                  # the length unit of the constants
    constants: list
    coordinates: list
    calls: list
    cautions: list = dataclasses.field(default_factory=list)


def procedure(mech, groups=None) -> Procedure:
    """The solving procedure of ``mech`` as calls (``groups``: the decomposition's, by
    default the closed-form solver's)."""
    cautions, left = [], []
    if groups is None:
        groups, left, undetermined = _decomposition(mech)
        if undetermined:
            cautions.append("the figure does not pick the branches: " + undetermined)
    writer = _Writer(mech)
    for group in groups:
        writer.group(group)
    if left:
        writer.triad(left)
    return Procedure(mech.title, mech.units.names["length"], writer.ordered_constants(),
                     writer.coordinates(), writer.calls, cautions)


def _decomposition(mech):
    """(groups, points left, undetermined): the closed-form solver's groups; for a structure
    the dyads do not reduce (a class-III group), the groups found before the decomposition
    stops, with their branches as the figure draws them, and the points it leaves."""
    try:
        solver = solver_for(mech)
    except StructureError as refused:
        try:
            found = partial(mech)
        except StructureError:
            raise refused from None
        left = [p for p in mech.moving if p not in found.known]
        if found.pending or not left:
            raise
        for group in found.groups:
            group.branch = _figure_branch(mech, group)
        return found.groups, left, None
    return solver.groups, [], solver.undetermined


def _figure_branch(mech, group) -> int:
    """The assembly branch of a dyad as the figure draws its point (+1 or -1, the solver's
    convention of each kind); 1 for a group without branches."""
    figure = {**mech.fixed, **mech.moving}
    p = figure.get(group.point)
    if p is None or group.kind not in ("RRR", "RRP", "PRR", "RPR"):
        return 1
    c1, c2 = group.constraints
    if group.kind == "RRR":
        return 1 if cross(figure[c2.a] - figure[c1.a], p - figure[c1.a]) >= 0 else -1
    if group.kind == "RPR":          # the pin ahead of the pivot along pivot->P
        return 1 if ((figure[c2.p] - figure[c1.a]) * np.conj(p - figure[c1.a])).real >= 0 \
            else -1
    dist, line = (c1, c2) if isinstance(c1, Dist) else (c2, c1)
    u = figure[line.c] - figure[line.b]
    return 1 if ((p - figure[dist.a]) * np.conj(u)).real >= 0 else -1


def render(proc: Procedure) -> str:
    """The procedure as pseudo-MATLAB text, one statement a line."""
    used = {c.function for c in proc.calls}
    lines = [f"% {proc.title}",
             f"% position analysis along the Assur decomposition ({proc.units}, rad; "
             "points are complex numbers x + 1i*y)"]
    lines += [f"% {LIBRARY[name]}" for name in LIBRARY if name in used]
    lines += [f"% {c}" for c in proc.cautions]
    lines += ["", "% geometric constants"]
    lines += [_statement(f"{c.name} = {c.value};", c.note) for c in proc.constants]
    lines += ["", "% driver" if len(proc.coordinates) == 1 else "% coordinates"]
    lines += [_statement(f"{c.name} = {c.value};", c.note) for c in proc.coordinates]
    for call in proc.calls:
        if call.heading:
            lines += ["", f"% {call.heading}"]
        lines.append(_statement(f"{call.left} = {call.right};", call.note))
    return "\n".join(lines)


def pseudocode(mech) -> str:
    return render(procedure(mech))


def _statement(code: str, note: str) -> str:
    return f"{code:<44} % {note}" if note else code


def _number(value: float) -> str:
    text = f"{float(value):.10g}"
    return "0" if text in ("-0", "0") else text


def _identifier(text: str) -> str:
    return re.sub(r"\W", "_", text)


class _Writer:
    """Turns decomposition groups into calls, collecting the constants they use."""

    def __init__(self, mech):
        self.mech = mech
        self.f = mech.units.factor("length")
        self.deg = mech.units.names["angle"] == "deg"
        self.constants: dict = {}
        self.calls: list = []
        self.done: set = set()          # the names computed so far
        self.directions: dict = {}      # (K, M) -> the name of angle(M - K)
        self.step = 0
        self.heading = ""               # the heading of the group being written
        points = mech.figure_points
        self.size = max((abs(z) for z in points), default=1.0) or 1.0

    # constants ------------------------------------------------------------------
    def constant(self, name, value, kind, points=(), note="") -> str:
        if name not in self.constants:
            self.constants[name] = Constant(name, value, kind, tuple(points), note)
        return name

    def ordered_constants(self) -> list:
        """Frame points in the file's order, then the guides' points, lengths, angles, offsets."""
        order = ("point", "length", "angle", "offset", "ratio")
        frame = list(self.mech.fixed)
        return sorted(self.constants.values(), key=lambda c: (
            order.index(c.kind), frame.index(c.name) if c.name in frame else len(frame)))

    def coordinates(self) -> list:
        out = []
        for c in self.mech.coordinates:
            what = {"angle": f"angle of {c.a}->{c.b}", "length": f"length {c.a}{c.b}",
                    "x": f"x of {c.a}", "y": f"y of {c.a}"}[c.kind]
            value = self.angle_text(c.value) if c.kind == "angle" else _number(c.value / self.f)
            out.append(Constant(c.name, value, "coordinate", (c.a,) + ((c.b,) if c.b else ()),
                                what))
        return out

    def angle_text(self, radians) -> str:
        if not self.deg or _number(np.degrees(radians)) == "0":
            return _number(radians)
        return f"deg2rad({_number(np.degrees(radians))})"

    @staticmethod
    def name(point) -> str:
        """A point's name in the code: a virtual point (``~BLOCK.slot``) as BLOCK_slot."""
        return _identifier(point.lstrip("~"))

    def point(self, point) -> str:
        """A point as a name; a frame point becomes a constant."""
        z, name = self.mech.fixed.get(point), self.name(point)
        if z is not None:
            self.constant(name, f"complex({_number(z.real / self.f)}, {_number(z.imag / self.f)})",
                          "point", (point,) if name == point else (),
                          "frame" if name == point else "a point of a guide")
        return name

    def length(self, a, b, value, body) -> str:
        first, second = sorted((self.name(a), self.name(b)))
        name = f"l_{first}{second}" if len(first) == len(second) == 1 else f"l_{first}_{second}"
        old = self.constants.get(name)
        if old is not None and abs(float(old.value) - value / self.f) > SAME * self.size / self.f:
            name = f"{name}_{_identifier(body)}"
        kind = self.mech.bodies[body].kind if body in self.mech.bodies else "link"
        what = {"block": "slider", "cylinder": "actuator", "rod": "actuator"}.get(kind, kind)
        return self.constant(name, _number(value / self.f), "length", (first, second),
                             f"{what} {body}")

    def dist(self, c) -> str:
        """The length of a distance constraint: a constant, or the driving coordinate."""
        if c.length is None:
            return self.mech.coordinates[c.coord].name
        return self.length(c.p, c.a, c.length, c.body)

    def direction(self, k, m) -> str:
        """The name of angle(M - K), computed once."""
        if (k, m) not in self.directions:
            k, m = self.point(k), self.point(m)
            name = f"phi_{k}{m}" if len(k) == len(m) == 1 else f"phi_{k}_{m}"
            self.directions[(k, m)] = name
            self.emit((name,), None, (f"angle({m} - {k})",), (k, m), "direction")
        return self.directions[(k, m)]

    def same(self, a, b) -> bool:
        return abs(a - b) <= SAME * self.size

    # calls ----------------------------------------------------------------------
    def emit(self, outputs, function, args, reads, kind, library=True, note=""):
        """Append a call; the first call of a group carries the group's heading."""
        heading, self.heading = self.heading, ""
        reads = tuple(r for r in reads if re.fullmatch(r"[A-Za-z]\w*", r))   # names, no literals
        call = Call(tuple(outputs), function, tuple(args), reads, kind, library, note,
                    self.step if heading else 0, heading)
        self.calls.append(call)
        self.done.update(outputs)
        return call

    def group(self, group):
        handler = self.handlers.get(group.kind, _Writer._generic)
        if any(isinstance(c, Track) for c in group.constraints):
            handler = _Writer._generic          # a point on a contact's line
        if group.kind != "place":
            self.step += 1
            self.heading = f"{self.step}. {group.describe()}"
        if group.point is not None and self.name(group.point) in self.done:
            return                      # returned already by the call of its dyad
        handler(self, group)

    def _driver_angle(self, group):
        pivot, length, reverse = group.constraints
        p, crank = group.point, group.bodies[0]
        q = self.mech.coordinates[group.coord].name
        arm = self.length(pivot, p, length, crank)
        sign = "-" if reverse else "+"
        self.emit((self.name(p),), None, (f"{self.point(pivot)} {sign} {arm}*exp(1i*{q})",),
                  (self.point(pivot), arm, q), group.kind)

    def _driver_coord(self, group):
        line, coord = group.constraints
        q = self.mech.coordinates[coord.coord].name
        u, e = self.line_frame(line)
        origin = (self.mech.fixed[line.b] + 1j * e * u) / self.f
        if coord.axis == "x" and self.same(u.imag * self.size, 0.0):
            text = f"complex({q}, {_number(origin.imag)})"
        elif coord.axis == "y" and self.same(u.real * self.size, 0.0):
            text = f"complex({_number(origin.real)}, {q})"
        else:
            o = self.constant(f"O_{_identifier(line.body)}",
                              f"complex({_number(origin.real)}, {_number(origin.imag)})",
                              "point", (), f"a point of the guide of {line.body}")
            alpha = self.constant(f"alpha_{_identifier(line.body)}",
                                  self.angle_text(np.angle(u)), "angle", (),
                                  f"direction of the guide of {line.body}")
            along = f"({q} - real({o}))/cos({alpha})" if coord.axis == "x" else \
                f"({q} - imag({o}))/sin({alpha})"
            text = f"{o} + {along}*exp(1i*{alpha})"
        self.emit((self.name(group.point),), None, (text,), (q,), group.kind)

    def line_frame(self, line):
        """Unit direction and left offset (SI) of a line on the frame."""
        b, c = self.mech.fixed[line.b], self.mech.fixed[line.c]
        return (c - b) / abs(c - b), line.value / abs(c - b)

    def axis(self, line):
        """(O, alpha, e) of the line on which ``line.p`` slides, as names or numbers."""
        block = self.mech.bodies[line.body]
        g = block.guide
        e = self.guide_offset(line) / self.f
        if g.carrier == FRAME:
            u, _ = self.line_frame(line)
            origin = self.mech.fixed[line.b]
            named = next((n for n, z in self.mech.fixed.items()
                          if not n.startswith("~") and self.same(z, origin)), None)
            if named is None:
                o = self.constant(f"O_{_identifier(block.name)}",
                                  f"complex({_number(origin.real / self.f)}, "
                                  f"{_number(origin.imag / self.f)})", "point", (),
                                  f"a point of the guide of {block.name}")
            else:
                o = self.point(named)
            alpha = self.constant(f"alpha_{_identifier(block.name)}",
                                  self.angle_text(np.angle(u)), "angle", (),
                                  f"direction of the guide of {block.name} ({g.text})")
        else:
            o, alpha = self.point(line.b), self.direction(line.b, line.c)
        if self.same(e * self.f, 0.0):
            return o, alpha, "0"
        offset = self.constant(f"e_{_identifier(line.p)}", _number(e), "offset", (line.p,),
                               f"{line.p} left of the guide of {block.name}")
        return o, alpha, offset

    def guide_offset(self, line) -> float:
        """The signed distance (SI) of ``line.p`` to the left of its guide's line B->C."""
        g = self.mech.bodies[line.body].guide
        if line.value == 0:
            return 0.0
        if g.carrier == FRAME:
            b, c = self.mech.fixed[g.b], self.mech.fixed[g.c]
        else:
            local = self.mech.bodies[g.carrier].local
            b, c = local[g.b], local[g.c]
        return line.value / abs(c - b)

    def foot(self, line) -> str | None:
        """The block's point at the foot of the pin on the guide line through B->C, if any."""
        block = self.mech.bodies[line.body]
        pin = block.local[line.p]
        return next((p for p in block.points if p != line.p and p not in self.done
                     and self.same(block.local[p].real, pin.real)
                     and self.same(block.guide.offset + block.local[p].imag, 0.0)), None)

    def _rrr(self, group):
        c1, c2 = group.constraints
        side = "'sx'" if group.branch > 0 else "'dx'"
        args = (self.point(c1.a), self.point(c2.a), self.dist(c1), self.dist(c2), side)
        self.emit((self.name(group.point),), "diadeRRR", args, args[:4], group.kind)

    def _rrp(self, group):
        c1, c2 = group.constraints
        dist, line = (c1, c2) if isinstance(c1, Dist) else (c2, c1)
        o, alpha, e = self.axis(line)
        foot = self.foot(line)
        args = (self.point(dist.a), o, alpha, self.dist(dist), e,
                "'pos'" if group.branch > 0 else "'neg'")
        self.emit((self.name(group.point),) + ((foot,) if foot else ()), "diadeRRP", args, args[:5],
                  group.kind)


    def _prp(self, group):
        axes = [self.axis(line) for line in group.constraints]
        args = tuple(a for axis in axes for a in axis)
        self.emit((self.name(group.point),), "diadePRP", args, args, group.kind, library=False,
                  note="not in the exam's library: the point where two guides cross")

    def _rpr(self, group):
        dist, line = group.constraints
        e = line.value / dist.length / self.f
        offset = "0" if self.same(e * self.f, 0.0) else self.constant(
            f"e_{_identifier(line.p)}", _number(e), "offset", (line.p,),
            f"{line.p} left of {dist.a}->{dist.p} on {line.body}")
        args = (self.point(dist.a), self.point(line.p), self.dist(dist), offset,
                "'pos'" if group.branch > 0 else "'neg'")
        self.emit((self.name(group.point),), "diadeRPR", args, args[:4], group.kind, library=False,
                  note=f"not in the exam's library: slotted link {dist.body} pivoted at "
                  f"{dist.a}, block {line.body} pinned at {line.p}")

    def _rpr_actuator(self, group):
        act = self.mech.actuators[group.bodies[0]]
        name = f"a_{_identifier(act.name)}"
        self.emit((name,), None, (f"abs({self.point(act.b)} - {self.point(act.a)})",),
                  (self.point(act.a), self.point(act.b)), group.kind,
                  note=f"actuator {act.name}: its length, both ends known")

    def _place(self, group):
        """P = K + (M - N) w: on a link (N = K) or a slider block, as a length and an angle
        from a known direction; any other recipe (a virtual point) as it stands."""
        p, body = group.point, self.mech.bodies[group.bodies[0]]
        k, m, n, w = group.place
        fixed = m in self.mech.fixed and n in self.mech.fixed
        if p not in body.local or k not in body.local or body.kind == "link" and n != k:
            if fixed:
                offset = (self.mech.fixed[m] - self.mech.fixed[n]) * w / self.f
                vector = self.constant(f"v_{self.name(p)}", f"complex({_number(offset.real)}, "
                                       f"{_number(offset.imag)})", "offset", (),
                                       f"from {k}: {group.describe()}")
                text, reads = f"{self.point(k)} + {vector}", (self.point(k), vector)
            else:
                ratio = self.constant(f"w_{self.name(p)}", f"complex({_number(w.real)}, "
                                      f"{_number(w.imag)})", "ratio", (), group.describe())
                text = f"{self.point(k)} + ({self.point(m)} - {self.point(n)})*{ratio}"
                reads = (self.point(k), self.point(m), self.point(n), ratio)
            self.emit((self.name(p),), None, (text,), reads, group.kind, note=group.describe())
            return
        arm = self.length(k, p, abs(body.local[p] - body.local[k]), body.name)
        if body.kind == "link":
            phi = self.direction(k, m)
        elif body.guide.carrier == FRAME:
            phi = self.guide_direction(body)
        else:
            phi = self.direction(n, m)
        beta = float(np.angle(w))
        turn = "" if self.same(beta * self.size, 0.0) else " + " + self.constant(
            f"beta_{self.name(p)}", self.angle_text(beta), "angle", (p,),
            f"from the direction {'of the guide' if body.kind == 'block' else k + '->' + m} "
            f"to {k}->{p} on {body.name}")
        angle = f"({phi}{turn})" if turn else phi
        self.emit((self.name(p),), None, (f"{self.point(k)} + {arm}*exp(1i*{angle})",),
                  (self.point(k), arm, phi), group.kind, note=f"{p} on {body.name} (rigid)")

    def guide_direction(self, block) -> str:
        g = block.guide
        u = self.mech.fixed[g.c] - self.mech.fixed[g.b]
        return self.constant(f"alpha_{_identifier(block.name)}", self.angle_text(np.angle(u)),
                             "angle", (), f"direction of the guide of {block.name} ({g.text})")

    def _roll(self, group):
        rel, _ = group.constraints
        r = self.mech.rolling[rel.names[0]]
        # the points the contact's measures read: the centres, the cord's end, the marks
        reads = [p for t, _, _ in rel.terms for p in t.points if p != group.point]
        args = tuple(self.point(x) for x in dict.fromkeys(reads))
        self.emit((self.name(group.point),), f"rolling{r.kind.capitalize()}", args, args, group.kind,
                  library=False, note=f"not in the exam's library: {group.describe()}")

    def triad(self, left):
        """The points no dyad reaches (a class-III group or larger): one call that reads the
        known points joined to them and the lengths of the bodies that join them."""
        self.step += 1
        known, points, lengths, bodies = set(self.mech.fixed) | self.done, [], [], []
        for body in self.mech.bodies.values():
            if body.kind != "link" or not set(body.points) & set(left):
                continue
            bodies.append(body.name)
            points += [self.point(p) for p in body.points if p in known and p not in points]
            pairs = [(a, b) for i, a in enumerate(body.points) for b in body.points[i + 1:]
                     if a in left or b in left]
            lengths += [self.length(a, b, abs(body.local[b] - body.local[a]), body.name)
                        for a, b in pairs]
        reads = points + lengths
        self.heading = (f"{self.step}. class-III group (triad or larger): "
                        f"{', '.join(left)} of {', '.join(bodies)}")
        self.emit(tuple(left), "triade", tuple(reads), tuple(reads), "triad", library=False,
                  note="not in the exam's library: no closed form, solve its closure "
                  "equations numerically (linkcli solve --method newton)")

    def _generic(self, group):
        """A group kind with no writer of its own: a call named after it, reading the known
        points its constraints name."""
        reads = []
        for c in group.constraints:
            values = [getattr(c, f.name) for f in dataclasses.fields(c)] \
                if dataclasses.is_dataclass(c) else [c]
            if isinstance(c, Track):     # the points of the contacts' measures
                values = [p for t, _, _ in c.relation.terms for p in t.points]
            for v in values:
                if isinstance(v, str) and v != group.point and v not in reads and (
                        self.name(v) in self.done or
                        v in self.mech.fixed and not v.startswith("~")):
                    reads.append(v)
        kind = _identifier(group.kind)
        name = f"diade{kind}" if set(kind) <= set("RP") else kind
        args = tuple(self.point(x) for x in reads)
        for c in group.constraints:     # a slider's guide on the frame: its axis O, alpha, e
            body = self.mech.bodies.get(getattr(c, "body", None))
            if isinstance(c, Line) and body is not None and body.kind == "block" and \
                    body.guide.carrier == FRAME and c.b == body.guide.b:
                args += self.axis(c)
        outputs = (self.name(group.point),) if group.point is not None else \
            (f"{name}_{self.step}",)
        self.emit(outputs, name, args, args, group.kind, library=False,
                  note=f"not in the exam's library: {group.describe()}")

    #: the writer of each kind of group the exam's procedure knows; any other kind is
    #: written by ``_generic``
    handlers = {"driver-angle": _driver_angle, "driver-coord": _driver_coord, "RRR": _rrr,
                "RRP": _rrp, "PRR": _rrp, "PRP": _prp, "RPR": _rpr,
                "RPR-actuator": _rpr_actuator, "place": _place, "roll": _roll}
