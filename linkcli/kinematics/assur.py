"""The Assur decomposition: the order in which the groups place the points.

The mobility is Grübler's count (``grubler``); the groups and their constraints are
``groups``; the groups contacts form are ``contact_groups``.

The decomposition is topology only: starting from the frame and the driver it
repeatedly finds a moving point fixed by two constraints from known bodies
(a dyad: RRR, RRP/PRR, PRP, or RPR when the unknown is the orientation of a
slotted link), or a point placed rigidly on a body whose pose is known.  A
structure that does not reduce this way is refused by name.

Two dyads solve for a point of their own (``~BLOCK.slot``, a virtual point: the
answer sheet never lists it, a worked solution names it as it is):

- RPR with the slot off the pivot: a link pivoted at a known K carries a slot
  along its points D, E (neither of them K), in which a known pin A slides.  With
  W = E - D (fixed in the link), rigidity gives cross(W, D - K) = cross(W_l, D_l - K_l)
  (local coordinates), so the slot condition cross(W, A - D) = v becomes
  cross(V - K, A - K) = v + cross(W_l, D_l - K_l) for V = K + W, |V - K| = |W|: the
  slotted link through its pivot, solved for V; the link's points follow from K and V.
- RPP (Scotch yoke): a block Y translates on a guide whose pose is known (direction
  D = C_Y - B_Y); a pin A, known, slides in a slot of Y along its points S1, S2.  In
  the guide's axes S_k = Y + D w_k, so the slot condition cross(S2 - S1, A - S1) = v
  is linear in Y: cross(V - A, Y - A) = -(v + |D|^2 cross(t, w_1)) with t = w_2 - w_1
  and V = A + D t, the line through A parallel to the slot.  Y is where that line
  meets Y's own guide (two lines, as PRP).
"""
from __future__ import annotations

from dataclasses import dataclass, field

from linkcli.errors import StructureError
from linkcli.kinematics.contact_groups import ContactGroups
from linkcli.kinematics.contacts import Track, relations
from linkcli.kinematics.groups import Coord, Dist, Group, Line
from linkcli.kinematics.grubler import Grubler, one_dof
from linkcli.model.mechanism import FRAME, Mechanism


@dataclass
class Topology:
    """Grübler's count and the groups in their solving order."""

    grubler: Grubler
    groups: list = field(default_factory=list)


def analyse(mech: Mechanism) -> Topology:
    return Topology(one_dof(mech), _Decomposer(mech).run())


@dataclass
class Partial:
    """The decomposition as far as the dyads reach: the groups found in order, the points
    they place (frame points included) and the coordinates left unplaced."""

    groups: list
    known: set
    pending: list


def partial(mech: Mechanism) -> Partial:
    """The groups found before the decomposition stops (at a class-III group, say), without
    raising for the points it does not reach; a structural fault it meets still raises."""
    decomposer = _Decomposer(mech)
    while decomposer.step():
        pass
    return Partial(decomposer.groups, decomposer.known, list(decomposer.pending.values()))


class _Decomposer(ContactGroups):
    def __init__(self, mech: Mechanism):
        self.mech = mech
        self.known = {p for p in mech.fixed}
        self.known_bodies = {FRAME}
        self.groups: list[Group] = []
        self.pending = dict(enumerate(mech.coordinates))
        self.relations = relations(mech)   # contact -> Relation (kinematics.contacts)
        self.consumed: set = set()         # contacts already used by a group
        self.driven: dict = {}             # {a, b} -> coordinate of a driving length
        self.done_actuators: set = set()
        self.bodies_at: dict = {}          # point -> the bodies it belongs to, in file order
        for body in mech.bodies.values():
            for p in body.points:
                self.bodies_at.setdefault(p, []).append(body)
        #: point -> the contacts whose relation reads it (a side of a dyad besides bodies)
        self.contacts_at: dict = {}
        self.contact_order = {name: i for i, name in enumerate(self.relations)}
        for name, relation in self.relations.items():
            for x in relation.points():
                self.contacts_at.setdefault(x, []).append(name)
        #: the figure's points and their farthest from the origin: a contact's line is
        #: tested there (:meth:`on_line`), once per pair of a point and a contact
        self.figure = {**mech.fixed, **mech.moving}
        self.figure_size = max((abs(z) for z in self.figure.values()), default=0.0) or 1.0
        #: the points a contact may place: those it reads and those of their bodies (a
        #: slider's point moves with the contact's points it carries)
        self.near_contact: set = set(self.contacts_at)
        for x in self.contacts_at:
            for body in self.bodies_at.get(x, ()):
                self.near_contact.update(body.points)

    def fail(self, detail: str, hint: str | None = None):
        return StructureError(detail, file=self.mech.file, hint=hint)

    def run(self) -> list:
        while self.step():
            pass
        if self.pending:
            d = next(iter(self.pending.values()))
            if len(self.mech.coordinates) == 1:
                raise self.fail(f"the driving vector {d.a}->{d.b} must join a fixed pivot to a "
                                "moving point")
            raise self.fail(f"coordinate {d.name}: the vector {d.a}->{d.b} must join a fixed "
                            "pivot, or a point placed before it, to a moving point")
        missing = [p for p in self.mech.moving if p not in self.known]
        if missing:
            several = len(self.mech.coordinates) > 1 or self.mech.elements is not None
            raise self.fail(
                f"the structure does not decompose into dyads (RRR, RRP, PRP, RPR): points "
                f"{', '.join(missing)} are not reached",
                hint=("the vibration analysis and files with several drivers or "
                      "coordinates need the closed form: check the links and contacts around "
                      "them") if several else
                "it may hold a class-III group (triad): solve it with --method newton, "
                "or check the links around them")
        unused = [n for n in self.relations if n not in self.consumed]
        if unused:
            raise self.fail(f"the contacts {', '.join(unused)} relate bodies that other links "
                            "place already: the mechanism is over-constrained",
                            hint="each rolling contact or cord removes one degree of freedom; "
                            "check the coordinates and the links at the discs")
        return self.groups

    # drivers -------------------------------------------------------------------
    def drivers(self) -> bool:
        """Place every coordinate whose reference is known; True when one was placed."""
        placed = False
        for j, d in list(self.pending.items()):
            if self.driver(j, d):
                del self.pending[j]
                placed = True
        return placed

    def driver(self, j, d) -> bool:
        """The driver group of coordinate ``j`` when its pivot or guide is known."""
        if d.kind == "angle":
            crank = self.body_with(d.a, d.b)
            if crank is None:
                raise self.fail(f"no link joins {d.a} and {d.b}, the vector of {self.label(d)}")
            if d.a in self.known and d.b in self.known:
                raise self.fail(f"the vector {d.a}->{d.b} of {self.label(d)} joins two points "
                                "already placed", hint="the angle of a link must have one end "
                                "on the frame or on a link placed before")
            if d.a in self.known:
                point, pivot = d.b, d.a
            elif d.b in self.known:
                point, pivot = d.a, d.b
            else:
                return False
            local = self.mech.bodies[crank].local
            length = abs(local[d.b] - local[d.a])
            self.groups.append(Group("driver-angle", point, (pivot, length, point == d.a),
                                     (crank,), note=f"{d.name} = angle of {d.a}->{d.b}",
                                     driver=True, coord=j))
            self.known.add(point)
            return True
        if d.kind == "length":
            if d.a in self.mech.fixed and d.b in self.mech.fixed:
                what = "the driving length" if len(self.mech.coordinates) == 1 else \
                    f"coordinate {d.name}: the length"
                raise self.fail(f"{what} {d.a}{d.b} joins two fixed points")
            self.driven[frozenset((d.a, d.b))] = j
            for act in self.mech.actuators.values():
                if {act.a, act.b} == {d.a, d.b}:
                    self.done_actuators.add(act.name)
            return True
        block = next((b for b in self.mech.bodies.values()
                      if b.kind == "block" and d.a in b.points), None)
        if block is None or block.guide.carrier != FRAME:
            article = "an" if d.kind == "x" else "a"
            what = "driver" if len(self.mech.coordinates) == 1 else f"coordinate ({d.name})"
            raise self.fail(f"{article} {d.kind} {what} needs {d.a} on a slider of a fixed guide")
        line = self.line(block, d.a, d.a)
        self.groups.append(Group("driver-coord", d.a, (line, Coord(d.a, d.kind, coord=j)),
                                 (block.name,), note=f"{d.name} = {d.kind} of {d.a}",
                                 driver=True, coord=j))
        self.known.add(d.a)
        return True

    def label(self, d) -> str:
        return "the driver" if len(self.mech.coordinates) == 1 else f"coordinate {d.name}"

    def body_with(self, *points) -> str | None:
        return next((b.name for b in self.mech.bodies.values()
                     if b.kind == "link" and all(p in b.points for p in points)), None)

    # one step ------------------------------------------------------------------
    def step(self) -> bool:
        return self.drivers() or self.place() or self.dyad() or self.rpr() or \
            self.yoke() or self.actuator() or self.roll() or self.roll_together()

    def place(self) -> bool:
        for body in self.mech.bodies.values():
            if body.name in self.known_bodies:
                continue
            known = [p for p in body.points if p in self.known]
            if body.kind == "link" and len(known) >= 2 or body.kind in ("cylinder", "rod") \
                    and known:
                self.settle(body, known)
                return True
            if body.kind == "block" and known and self.guide_known(body.guide):
                self.settle(body, known)
                return True
        return False

    def settle(self, body, known):
        """Mark ``body`` known and place its other points rigidly."""
        self.known_bodies.add(body.name)
        for p in body.points:
            if p in self.known:
                continue
            k = known[0]
            if body.kind == "link":
                m = known[1]
                w = (body.local[p] - body.local[k]) / (body.local[m] - body.local[k])
                self.groups.append(Group("place", p, bodies=(body.name,), place=(k, m, k, w)))
            else:
                g = body.guide
                w = (body.local[p] - body.local[k]) / self.guide_length(g)
                self.groups.append(Group("place", p, bodies=(body.name,), place=(k, g.c, g.b, w)))
            self.known.add(p)

    def guide_length(self, guide) -> float:
        """|C - B| of a guide: constant on the frame, a link or a block; an actuator's
        changes (the figure's is returned: its lines have offset 0)."""
        if guide.carrier == FRAME:
            return abs(self.mech.fixed[guide.c] - self.mech.fixed[guide.b])
        if self.mech.bodies[guide.carrier].kind == "cylinder":
            return abs(self.mech.moving.get(guide.c, self.mech.fixed.get(guide.c, 0j)) -
                       self.mech.moving.get(guide.b, self.mech.fixed.get(guide.b, 0j)))
        local = self.mech.bodies[guide.carrier].local
        return abs(local[guide.c] - local[guide.b])

    def guide_known(self, guide) -> bool:
        """Whether the pose of a guide's line is known: its carrier's (both points of an
        actuator, which turns with them)."""
        if guide.carrier == FRAME:
            return True
        if guide.carrier not in self.known_bodies:
            return False
        return self.mech.bodies[guide.carrier].kind != "cylinder" or \
            {guide.b, guide.c} <= self.known

    def line(self, block, point, unknown) -> Line:
        """The line on which ``point`` of ``block`` moves, as cross(C - B, P - B) = value.

        On an actuator's line (offset 0, no carried points) the value is 0 whatever the
        actuator's length."""
        g = block.guide
        if g.carrier != FRAME and self.mech.bodies[g.carrier].kind == "cylinder":
            return Line(point, g.b, g.c, 0.0, block.name, unknown)
        value = self.guide_length(g) * (g.offset + block.local[point].imag)
        return Line(point, g.b, g.c, value, block.name, unknown)

    def sides(self, p):
        """Constraints on unknown point ``p`` from bodies whose pose follows from one known point."""
        found = []
        for body in self.bodies_at.get(p, ()):
            if body.name in self.known_bodies:
                continue
            if body.kind == "link":
                known = [a for a in body.points if a in self.known]
                if len(known) == 1:
                    a = known[0]
                    found.append(Dist(p, a, abs(body.local[p] - body.local[a]), body.name))
            elif body.kind == "block" and self.guide_known(body.guide):
                found.append(self.line(body, p, p))
        for ends, j in self.driven.items():
            if p not in ends:
                continue
            other = next(iter(ends - {p}))
            if other in self.known:
                act = next((a.name for a in self.mech.actuators.values()
                            if {a.a, a.b} == ends), "".join(sorted(ends)))
                found.append(Dist(p, other, None, act, coord=j))
        return found + self.tracks(p)

    def dyad(self) -> bool:
        for p in self.mech.moving:
            if p in self.known or len(self.bodies_at.get(p, ())) < 2 and not self.driven \
                    and p not in self.near_contact:
                continue    # (one body, no driving length, no contact: one side at most)
            found = self.sides(p)
            if len(found) < 2:
                continue
            pair = tuple(found[:2])
            kind = "R" + "".join("R" if isinstance(c, Dist) else "P" for c in pair)
            kind = {"RRR": "RRR", "RRP": "RRP", "RPR": "PRR", "RPP": "PRP"}[kind]
            note = " and ".join(self.side_text(c) for c in pair)
            self.groups.append(Group(kind, p, pair, tuple(c.body for c in pair),
                                     driver=any(isinstance(c, Dist) and c.length is None
                                                for c in pair), note=note))
            for c in pair:
                if isinstance(c, Track):
                    self.consumed.update(c.spend)
            self.known.add(p)
            return True
        return False

    def side_text(self, c) -> str:
        if isinstance(c, Track):
            return f"contacts {c.relation.name}" if len(c.relation.names) > 1 \
                else f"contact {c.relation.name}"
        if isinstance(c, Dist):
            driven = self.mech.coordinates[c.coord].name if c.length is None else "length"
            return f"{c.a} ({c.body}, {driven})"
        guide = self.mech.bodies[c.body].guide
        return f"guide {guide.text} ({c.body})"

    def rpr(self) -> bool:
        """Slotted link: a block pinned at a known point slides on a link pivoted at a known point."""
        for block in self.mech.bodies.values():
            g = block.guide
            if block.kind != "block" or g.carrier in self.known_bodies or g.carrier == FRAME \
                    or self.mech.bodies[g.carrier].kind != "link":
                continue
            pins = [p for p in block.points if p in self.known]
            if not pins:
                continue
            if g.b not in self.known and g.c not in self.known:
                if self.off_pivot(block, pins[0]):
                    return True
                continue
            b, c, sign = (g.b, g.c, 1) if g.b in self.known else (g.c, g.b, -1)
            if b not in self.known or c in self.known:
                continue
            line = self.line(block, pins[0], c)
            line = Line(line.p, b, c, sign * line.value, block.name, c)
            length = self.guide_length(g)
            pair = (Dist(c, b, length, g.carrier), line)
            self.groups.append(Group("RPR", c, pair, (g.carrier, block.name),
                                     note=f"{b} ({g.carrier}) and {pins[0]} ({block.name})"))
            self.known.add(c)
            self.settle(block, pins)   # the block's pose is known now: place its other points
            return True
        return False

    def off_pivot(self, block, pin) -> bool:
        """RPR with the slot off the pivot (module docstring): solve V = K + (E - D)."""
        g = block.guide
        link = self.mech.bodies[g.carrier]
        known = [p for p in link.points if p in self.known]
        if len(known) != 1:
            return False
        k = known[0]
        local = link.local
        w_local = local[g.c] - local[g.b]
        slot = self.line(block, pin, pin).value
        value = slot + cross_local(w_local, local[g.b] - local[k])
        v = f"~{block.name}.slot"
        pair = (Dist(v, k, abs(w_local), link.name), Line(pin, k, v, value, block.name, v))
        self.groups.append(Group("RPR", v, pair, (link.name, block.name),
                                 place=(k, g.c, g.b, 1.0),    # V in the figure
                                 note=f"{k} ({link.name}) and {pin} ({block.name})"))
        self.known.add(v)
        self.known_bodies.add(link.name)
        for p in link.points:
            if p not in self.known:
                w = (local[p] - local[k]) / w_local
                self.groups.append(Group("place", p, bodies=(link.name,), place=(k, v, k, w)))
                self.known.add(p)
        self.settle(block, [pin])
        return True

    def yoke(self) -> bool:
        """RPP (Scotch yoke, module docstring): a known pin in the slot of a block whose
        guide's pose is known; solves the block's point."""
        for pin_block in self.mech.bodies.values():
            g = pin_block.guide
            if pin_block.kind != "block" or g.carrier == FRAME:
                continue
            yoke = self.mech.bodies[g.carrier]
            pins = [p for p in pin_block.points if p in self.known]
            if yoke.kind != "block" or yoke.name in self.known_bodies or not pins or \
                    not self.guide_known(yoke.guide) or any(p in self.known for p in yoke.points):
                continue
            pin, y0 = pins[0], yoke.points[0]
            size = self.guide_length(yoke.guide)
            w1 = (yoke.local[g.b] - yoke.local[y0]) / size
            t = (yoke.local[g.c] - yoke.local[g.b]) / size
            slot = self.line(pin_block, pin, pin).value
            value = -(slot + size * size * cross_local(t, w1))
            v = f"~{pin_block.name}.slot"
            self.groups.append(Group("place", v, bodies=(yoke.name,),
                                     place=(pin, yoke.guide.c, yoke.guide.b, t)))
            self.known.add(v)
            pair = (self.line(yoke, y0, y0), Line(y0, pin, v, value, pin_block.name, y0))
            self.groups.append(Group("RPP", y0, pair, (yoke.name, pin_block.name),
                                     note=" and ".join(self.side_text(c) for c in pair)))
            self.known.add(y0)
            self.settle(yoke, [y0])
            return True
        return False

    def actuator(self) -> bool:
        for act in self.mech.actuators.values():
            if act.name in self.done_actuators or not {act.a, act.b} <= self.known:
                continue
            self.done_actuators.add(act.name)
            self.groups.append(Group("RPR-actuator", None, bodies=(act.name,),
                                     note=f"{act.a}, {act.b}"))
            return True
        return False


def cross_local(a: complex, b: complex) -> float:
    """cross(a, b) = Im(conj(a) b) of two local (constant) vectors."""
    return (a.conjugate() * b).imag
