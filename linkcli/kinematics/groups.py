"""The groups of the solving order and the constraints they solve (topology only).

A constraint names points, never their coordinates (the solver looks the geometry up):

- ``Dist``: |P - A| = L, solved as g = |P - A|^2 - L^2 = 0 (L a coordinate for a driven
  length);
- ``Line``: cross(C - B, P - B) = value, P on a line carried by B, C, with
  cross(a, b) = Im(conj(a) b): positive when P lies to the left of B -> C;
- ``Coord``: x (or y) of P equals a coordinate.

A ``Group`` is one step: the point it solves, its kind (a driver, a dyad RRR, RRP, PRR, PRP,
RPP, RPR, a rigidly placed point, an actuator, a disc's turn) and, for a dyad, its
assembly branch +1/-1 (``branches``).
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Dist:
    """|P - A| = length; ``length`` None means coordinate number ``coord`` (a driven length)."""

    p: str
    a: str
    length: float | None
    body: str
    coord: int = 0


@dataclass(frozen=True)
class Line:
    """cross(C - B, P - B) = value: P on a line carried by B, C.  ``unknown`` is P or C."""

    p: str
    b: str
    c: str
    value: float
    body: str
    unknown: str


@dataclass(frozen=True)
class Coord:
    """x (axis 'x') or y of P equals coordinate number ``coord``."""

    p: str
    axis: str
    body: str = "driver"
    coord: int = 0


@dataclass
class Group:
    """One step of the solving order."""

    kind: str              # driver-angle | driver-coord | RRR | RRP | PRR | PRP | RPP | RPR | place | RPR-actuator | roll
    point: str | None      # the point it solves (None: nothing to solve)
    constraints: tuple = ()
    bodies: tuple = ()
    place: tuple = ()      # for 'place': (K, M, N, w) with P = K + (M - N) w; for a dyad
    #                        of a virtual point, the same recipe on the figure's points
    driver: bool = False
    note: str = ""
    branch: int = 1        # assembly branch (+1/-1), chosen from the figure's positions
    coord: int = 0         # the coordinate a driver group sets

    @property
    def is_dyad(self) -> bool:
        return self.kind in ("RRR", "RRP", "PRR", "PRP", "RPP", "RPR")

    def describe(self) -> str:
        if self.kind == "place" and self.point.startswith("~"):
            return f"draw the line through {self.place[0]} parallel to the slot of " \
                f"{self.bodies[0]}"
        if self.kind == "place":
            return f"place {self.point} on {self.bodies[0]} (rigid)"
        if self.kind == "RPR" and self.point.startswith("~"):
            return f"dyad RPR: {self.bodies[0]} (slot off its pivot) from {self.note} " \
                f"[{', '.join(self.bodies)}]"
        if self.kind == "driver-angle":
            return f"driver: {self.bodies[0]} (crank), {self.note}"
        if self.kind == "driver-coord":
            return f"driver: slider {self.bodies[0]}, {self.note}"
        if self.kind == "RPR-actuator":
            return f"dyad RPR: actuator {self.bodies[0]} between known points {self.note}"
        if self.kind == "roll":
            return f"{self.bodies[0]} turned by {self.note}"
        return f"dyad {self.kind}: {self.point} from {self.note} [{', '.join(self.bodies)}]" + (
            " (driven)" if self.driver else "")
