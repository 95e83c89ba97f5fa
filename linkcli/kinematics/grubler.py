"""Grübler's count: the mobility of a planar mechanism.

n = 3 (m - 1) - 2 R - 2 P - H with m bodies (frame included), R revolute pairs (at a point
shared by j bodies there are j - 1), P prismatic pairs (one per slider block, one per
actuator) and H higher pairs (a disc rolling without slipping, a taut cord on a pulley).
A mechanism whose n is not its number of coordinates (1 for a file with a ``driver:``, one
per input of ``drivers:``) is refused, naming a belt strand that repeats another's relation when that is the cause.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from linkcli.errors import MobilityError
from linkcli.model.mechanism import FRAME, Mechanism


@dataclass
class Grubler:
    bodies: list
    revolutes: list        # (point, bodies at it)
    prismatics: list       # (name, body1, body2)
    higher: list = field(default_factory=list)   # rolling contacts and cords, by name

    @property
    def m(self) -> int:
        return len(self.bodies)

    @property
    def r(self) -> int:
        return sum(len(b) - 1 for _, b in self.revolutes)

    @property
    def p(self) -> int:
        return len(self.prismatics)

    @property
    def h(self) -> int:
        return len(self.higher)

    @property
    def dof(self) -> int:
        return 3 * (self.m - 1) - 2 * self.r - 2 * self.p - self.h

    def formula(self) -> str:
        if self.h:
            return (f"n = 3(m - 1) - 2R - 2P - H = 3({self.m} - 1) - 2*{self.r} - 2*{self.p} - "
                    f"{self.h} = {self.dof}")
        return (f"n = 3(m - 1) - 2R - 2P = 3({self.m} - 1) - 2*{self.r} - 2*{self.p} = "
                f"{self.dof}")


def grubler(mech: Mechanism) -> Grubler:
    bodies = [FRAME] + list(mech.bodies)
    members: dict[str, list] = {}
    for name in mech.fixed:
        if not name.startswith("~"):
            members.setdefault(name, []).append(FRAME)
    for body in mech.bodies.values():
        for p in body.points:
            members.setdefault(p, []).append(body.name)
    revolutes = [(p, tuple(b)) for p, b in members.items() if len(b) > 1]
    prismatics = [(a.name, a.name + ".cylinder", a.name + ".rod") for a in mech.actuators.values()]
    prismatics += [(b.name, b.name, b.guide.carrier) for b in mech.bodies.values()
                   if b.kind == "block"]
    return Grubler(bodies, revolutes, prismatics, list(mech.rolling))


def repeated_strands(mech: Mechanism) -> list:
    """[(strand, earlier strand)] of belt strands that repeat an earlier one's relation: the
    same two discs, both centres on the frame (the strand's run along u then never changes)
    and the same ratio of turns omega = side other_side (r_D / r) omega_D (``contacts``)."""
    seen, out = {}, []
    for r in mech.rolling.values():
        if r.kind != "belt" or r.center not in mech.fixed or r.track not in mech.fixed:
            continue
        ratio = (1 - r.slip) * r.side * r.other_side * r.track_radius / r.radius
        pair = (r.disc, r.other)
        if pair[::-1] in seen and pair not in seen:
            ratio, pair = 1.0 / ratio, pair[::-1]
        first = seen.get(pair)
        if first is not None and abs(first[1] - ratio) <= 1e-9 * abs(ratio):
            out.append((r.name, first[0]))
        else:
            seen.setdefault(pair, (r.name, ratio))
    return out


#: what to do with a mechanism of several inputs, each driven
SEVERAL_DRIVERS = ("declare one driver per input under 'drivers:', each with its value, "
                   "rate and accel, e.g. drivers: {theta1: {angle: [O, A], value: 30, rate: 2}, "
                   "theta2: {angle: [C, B], value: 60, rate: -1}}")


def one_dof(mech: Mechanism) -> Grubler:
    """Grübler's count, refusing a mechanism whose mobility is not its number of coordinates
    (1 for a file with a ``driver:``)."""
    count = grubler(mech)
    n = len(mech.coordinates)
    if count.dof == n:
        return count
    driven = mech.elements is None          # a file with drivers, not 'coordinates:'
    declared = f"1 (the one driver, {driver_text(mech.driver)})" if driven and n == 1 \
        else "1" if n == 1 else \
        f"{n} (the {'drivers' if driven else 'coordinates'} " + \
        ", ".join(f"{c.name}: {driver_text(c)}" if driven else c.name
                  for c in mech.coordinates) + ")"
    repeats = repeated_strands(mech)
    if repeats and count.dof + len(repeats) == n:
        strand, first = repeats[0]
        r = mech.rolling[strand]
        raise MobilityError(
            f"the belt strand '{strand}' joins the discs {r.disc} and {r.other} as '{first}' "
            f"does, at the same ratio of turns, their centres fixed: it repeats that "
            f"strand's relation and removes no degree of freedom, so Grübler's count says "
            f"{count.dof} degrees of freedom, not {declared}: {count.formula()}",
            file=mech.file,
            key=f"cords.{strand}",
            hint="leave the repeated strand out: one strand relates the turns of both discs")
    hint = "check that every link, slider and actuator is listed and that pins shared by " \
        "several bodies name the same point"
    if count.dof > n and driven:
        hint += f"; if the mechanism has {count.dof} inputs: {SEVERAL_DRIVERS}"
    elif count.dof < n and driven and count.dof >= 1:
        hint = f"the mechanism takes {count.dof} input{'s' if count.dof > 1 else ''}: " \
            f"drive {count.dof} of the coordinates and ask for the others as quantities; " \
            "or check that every link, slider and actuator is listed"
    elif count.dof > n:
        hint += "; a vibration problem declares one coordinate per degree of freedom under " \
            "'coordinates:'"
    raise MobilityError(f"the mechanism has {count.dof} degree{'' if count.dof == 1 else 's'} "
                        f"of freedom, not {declared}: "
                        f"{count.formula()}", file=mech.file, hint=hint)


def driver_text(d) -> str:
    """The driver (or a coordinate) in words: 'angle of A->B', 'length AB', 'x of B'."""
    return d.words
