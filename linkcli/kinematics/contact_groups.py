"""The groups contacts form in the Assur decomposition.

A contact (a disc rolling without slipping, a cord, a belt) is a relation
sum c_k (mu_k - mu_k0) = 0 between measures of the bodies it touches (``contacts``): turns
of discs, distances along lines.  In the decomposition it gives

- a ``roll`` group, where only one disc's turn is unknown: the disc's second point follows
  from its centre and that turn (``turns``);
- a side of a dyad (a ``Track``), where the relation leaves the unknown point P (with the
  points translating with it) on a line: one contact whose other measures are known, or k
  contacts with k - 1 unknown turns between them, combined with weights lambda_i in the
  null space of their coefficients on those turns (sum lambda_i R_i leaves every turn out:
  a rope over several pulleys); the contacts left then turn the discs one by one.
"""
from __future__ import annotations

from itertools import combinations

import numpy as np

from linkcli.kinematics.contacts import Relation, Track, Turn
from linkcli.kinematics.groups import Group
from linkcli.model.mechanism import FRAME


class ContactGroups:
    """The decomposition's steps with contacts; reads the decomposer's ``known``,
    ``known_bodies``, ``relations``, ``consumed``, ``contacts_at``, ``contact_order``,
    ``bodies_at``, ``figure`` and ``figure_size``."""

    def roll(self) -> bool:
        """A disc turned by a contact that leaves only its turn unknown: its centre known,
        its second point placed by the turn the relation gives (kinematics.contacts)."""
        for name, rel in self.relations.items():
            if name in self.consumed:
                continue
            unknown = [t for t, _, _ in rel.terms if not self.term_known(t)]
            if len(unknown) != 1 or not isinstance(unknown[0], Turn):
                continue
            turn = unknown[0]
            body = self.turned_body(turn)
            if body is None:
                continue
            self.groups.append(Group("roll", turn.b, (rel, turn), (body.name,),
                                     note=contact_text(self.mech, name, body.name)))
            self.consumed.add(name)
            self.known.add(turn.b)
            self.settle(body, [turn.a, turn.b])
            return True
        return False

    def roll_together(self) -> bool:
        """A disc turned by two contacts that share another unknown turn (a planet in mesh
        with a sun and a ring, its arm's turn unknown): their weighted sum without the
        shared turn leaves only the disc's (``combined_turn``); a ``roll`` group places it,
        one of the two is spent, and the other then turns the shared disc."""
        open_ = [(n, r) for n, r in self.relations.items() if n not in self.consumed]
        for (n1, r1), (n2, r2) in combinations(open_, 2):
            found = self.combined_turn(r1, r2)
            if found is None:
                continue
            rel, turn, body = found
            self.groups.append(Group("roll", turn.b, (rel, turn), (body.name,),
                                     note=contact_text(self.mech, n1, body.name) + " and " +
                                     contact_text(self.mech, n2, body.name)))
            self.consumed.add(n1)
            self.known.add(turn.b)
            self.settle(body, [turn.a, turn.b])
            return True
        return False

    def combined_turn(self, r1, r2):
        """(relation, turn, body) where ``r1`` and ``r2`` leave unknown the same two turns
        and nothing else, one of which places a link (``turned_body``): the combination
        lambda_1 r1 + lambda_2 r2 without the other turn; None otherwise."""
        turns = self.unknown_turns(r1)
        if len(turns) != 2 or set(turns) != set(self.unknown_turns(r2)) or \
                any(not isinstance(t, Turn) and not self.term_known(t)
                    for r in (r1, r2) for t, _, _ in r.terms):
            return None
        for turn, other in (turns, turns[::-1]):
            body = self.turned_body(turn)
            if body is None:
                continue
            c1, c2 = r1.coefficient(other), r2.coefficient(other)
            rel = Relation.combine([(r1, c2), (r2, -c1)], (other,))
            scale = max(abs(c1), abs(c2)) * max(abs(r1.coefficient(turn)),
                                                abs(r2.coefficient(turn)))
            if abs(rel.coefficient(turn)) <= 1e-9 * scale:
                continue            # the two contacts say the same of this turn
            mine = next(t for t, _, _ in rel.terms if t == turn)
            return rel, mine, body
        return None

    def term_known(self, term) -> bool:
        """Whether a measure of a contact is known: its points are placed, or it is a turn
        an angle coordinate gives."""
        if isinstance(term, Turn) and term.coord is not None:
            return True
        return all(p in self.known for p in term.points)

    def turned_body(self, turn):
        """The link a contact's turn would place: unplaced, its first two points the turn's
        a (known) and b (unknown)."""
        if turn.a not in self.known or turn.b in self.known:
            return None
        return next((b for b in self.mech.bodies.values() if b.kind == "link" and
                     b.name not in self.known_bodies and tuple(b.points[:2]) == (turn.a, turn.b)),
                    None)

    def tracks(self, p) -> list:
        """The contacts that put the unknown point ``p`` on a line (``contacts.Track``): one
        whose other measures are known, or the fewest whose unknown disc turns a weighted
        sum of them leaves out (k contacts, k - 1 turns: a rope over several pulleys).  The
        points of a slider that translates with ``p`` count as ``p`` (a hook block's
        pulleys)."""
        rigid = self.translating(p)
        near = sorted({n for x in rigid for n in self.contacts_at.get(x, ())},
                      key=self.contact_order.get)            # in the file's order
        usable = [(n, self.relations[n]) for n in near
                  if n not in self.consumed and self.on_line(self.relations[n], rigid)]
        found = [Track(r, p, rigid=rigid, spend=(n,)) for n, r in usable
                 if not self.unknown_turns(r)]
        for size in range(2, len(usable) + 1):
            for subset in combinations(usable, size):
                track = self.combined(subset, p, rigid)
                if track is not None:
                    found.append(track)
            if len(found) > 0:
                break
        return found

    def unknown_turns(self, rel) -> list:
        return [t for t, _, _ in rel.terms if isinstance(t, Turn) and not self.term_known(t)]

    def combined(self, subset, p, rigid):
        """The Track of sum lambda_i R_i over ``subset`` (k contacts with k - 1 unknown turns
        between them) that leaves every turn out; None when they do not cancel, or when the
        contacts left could not then turn the discs one by one."""
        turns = list(dict.fromkeys(t for _, r in subset for t in self.unknown_turns(r)))
        if len(turns) != len(subset) - 1:
            return None
        a = np.array([[r.coefficient(t) for t in turns] for _, r in subset])
        _, sv, vt = np.linalg.svd(a.T) if turns else (None, np.array([]), np.ones((1, 1)))
        if turns and (sv.size < len(turns) or sv[-1] < 1e-9 * sv[0]):
            return None             # the turns are not independent: no single combination
        weights = vt[-1]
        if np.min(np.abs(weights)) < 1e-9 * np.max(np.abs(weights)):
            return None             # a smaller set does it
        rel = Relation.combine([(r, w) for (_, r), w in zip(subset, weights)], turns)
        if not self.on_line(rel, rigid):
            return None
        for spent, _ in subset:
            rest = [r for n, r in subset if n != spent]
            if self.turned_one_by_one(rest, turns):
                return Track(rel, p, rigid=rigid, spend=(spent,))
        return None

    def turned_one_by_one(self, rels, turns) -> bool:
        """Whether ``rels`` give the ``turns`` one at a time (each step a contact with one
        turn left unknown), once the point they share is placed."""
        left, todo = set(turns), list(rels)
        while todo:
            step = next((r for r in todo if len(left & set(self.unknown_turns(r))) == 1), None)
            if step is None:
                return not left
            left -= set(self.unknown_turns(step))
            todo.remove(step)
        return not left

    def translating(self, p) -> dict:
        """{point: its constant offset from p} of the points that translate with ``p``: a
        slider's points on a fixed guide (p among them), or p alone."""
        block = next((b for b in self.bodies_at.get(p, ()) if b.kind == "block"
                      and b.guide.carrier == FRAME), None)
        if block is None:
            return {p: 0j}
        g = block.guide
        axis = self.mech.fixed[g.c] - self.mech.fixed[g.b]
        u = axis / abs(axis)
        return {x: (block.local[x] - block.local[p]) * u for x in block.points
                if x not in self.known}

    def on_line(self, rel, rigid) -> bool:
        """Whether ``rel`` leaves unknown only the turns of discs and the points of
        ``rigid`` (one translating body), these linearly: a line through them, once the
        turns are left out."""
        if not set(rigid) & rel.points():
            return False
        known = self.known
        for term, _, _ in rel.terms:
            if isinstance(term, Turn) and not self.term_known(term):
                continue                # a disc's turn: left out by the combination
            inside = set(term.points) & set(rigid)
            if inside:
                if not all(term.linear(x, known) for x in inside) or \
                        any(x not in known for x in term.points if x not in rigid):
                    return False
            elif not self.term_known(term):
                return False
        w = sum(c * term.grad(self.figure, x) for term, c, _ in rel.terms for x in rigid
                if not (isinstance(term, Turn) and not self.term_known(term)))
        return abs(w) > 1e-9 / self.figure_size     # a line, not a degenerate one


def contact_text(mech, name, disc) -> str:
    """'NAME (rolling on a fixed line)', the cord's point, the belt's disc ... as the
    decomposition describes a contact."""
    r = mech.rolling[name]
    on = "a fixed line" if r.carrier == FRAME else f"a line of {r.carrier}"
    what = {"line": f"rolling on {on}", "cord": f"the cord to {r.point}",
            "circle": f"rolling {'inside' if r.inside else 'outside'} the circle about "
                      f"{r.track}",
            "disc": f"rolling {'inside' if r.inside else 'outside'} disc {r.other}",
            "belt": f"the belt from disc {r.other}" if disc == r.disc else
                    f"the belt from disc {r.disc}"}
    return f"{name} ({what[r.kind]})"
