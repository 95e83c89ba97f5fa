"""The constraint equations of a whole mechanism, one bilinear row each.

Every equation is a bilinear form of two point differences,

    g = Re(k conj(U) V) - v(q),    U = P_c - P_b (+ e^{iq} for a driving angle),
                                   V = P_p - P_a,   k = 1 (dot) or -i (cross),
    v(q) = v0 + vq q + vqq q^2,

divided by a constant length of its own (link length, guide length, 1 for the
driver) so that residuals are lengths.

- a link: |P_1 - P_0|^2 = L^2 for its first two points and, for every further
  point P_j, the dot and the cross product of P_j - P_0 with P_1 - P_0.  This
  is the same as the distances of P_j from P_0 and P_1 plus the side of P_0P_1
  it lies on, so the body stays rigid and keeps its chirality;
- a slider block: each of its points on its line, cross(C - B, P - B) = value;
  carried points also at a fixed dot(C - B, P_j - P_0);
- the driver: cross(e^{iq}, P_b - P_a) = 0 (angle; the driving link's own
  length equation then reads dot(e^{iq}, P_b - P_a) = L, so the link cannot
  point backwards), |P_b - P_a|^2 = q^2 (length), or x (y) of P_a = q.

Points are given by their index in the list of point names, which ends with
the virtual points ``~zero`` (0) and ``~one`` (1).
"""
from __future__ import annotations

from dataclasses import dataclass

from linkcli.model.mechanism import FRAME

ZERO, ONE = "~zero", "~one"


@dataclass(frozen=True)
class Row:
    """One equation Re(k conj(P_c - P_b [+ e^{iq}]) (P_p - P_a)) = v0 + vq q + vqq q^2,
    divided by ``scale`` (a length); ``uq`` marks the driving-angle term e^{iq}."""

    b: int
    c: int
    a: int
    p: int
    k: complex
    v0: float
    scale: float
    label: str
    vq: float = 0.0
    vqq: float = 0.0
    uq: bool = False


def mechanism_rows(mech, index):
    """Rows of every link, slider block and the driver; returns (rows, lengths), the
    lengths being every link's distances from its base point P_0."""
    driving = _driving_link(mech)
    rows, lengths = [], []
    for body in mech.bodies.values():
        if body.kind == "link":
            body_rows, body_lengths = link_rows(mech, body, index, body.name == driving)
            rows += body_rows
            lengths += body_lengths
        elif body.kind == "block":
            rows += block_rows(mech, body, index)
    rows.append(driver_row(mech.driver, index))
    return rows, lengths


def _driving_link(mech):
    """Name of the first link holding both points of a driving angle (None: no such link)."""
    d = mech.driver
    if d.kind != "angle":
        return None
    return next((body.name for body in mech.bodies.values()
                 if body.kind == "link" and {d.a, d.b} <= set(body.points)), None)


def link_rows(mech, body, index, driven=False):
    """|P_1 - P_0|^2 = L^2, and dot / cross(P_1 - P_0, P_j - P_0) fixed for further points.

    A ``driven`` link is based on the driving vector a -> b, and its length row
    becomes dot(e^{iq}, P_b - P_a) = L.  Returns (rows, distances from P_0).
    """
    d = mech.driver
    p0, p1 = (d.a, d.b) if driven else body.points[:2]
    local = body.local
    edge = local[p1] - local[p0]
    length = abs(edge)
    i0, i1 = index[p0], index[p1]
    zero = index[ZERO]
    if driven:
        rows = [Row(zero, zero, i0, i1, 1, length, 1.0, f"driver: {p0}->{p1} along q", uq=True)]
    else:
        rows = [Row(i0, i1, i0, i1, 1, length * length, length, f"{body.name}: |{p0}{p1}|")]
    lengths = [length]
    for pj in [p for p in body.points if p not in (p0, p1)]:
        rel = edge.conjugate() * (local[pj] - local[p0])
        ij = index[pj]
        rows.append(Row(i0, i1, i0, ij, 1, rel.real, length, f"{body.name}: {pj} along"))
        rows.append(Row(i0, i1, i0, ij, -1j, rel.imag, length, f"{body.name}: {pj} side"))
        lengths.append(abs(local[pj] - local[p0]))
    return rows, lengths


def block_rows(mech, body, index):
    """cross(C - B, P_j - B) = |C - B| (offset + y_j) for every point of the block, and
    dot(C - B, P_j - P_0) = |C - B| x_j for the ones it carries."""
    guide = body.guide
    length = _guide_length(mech, guide)
    ib, ic = index[guide.b], index[guide.c]
    p0 = body.points[0]
    rows = []
    for pj in body.points:
        offset = body.local[pj] - body.local[p0]
        rows.append(Row(ib, ic, ib, index[pj], -1j,
                        length * (guide.offset + body.local[pj].imag), length,
                        f"{body.name}: {pj} on its guide"))
        if pj != p0:
            rows.append(Row(ib, ic, index[p0], index[pj], 1, length * offset.real, length,
                            f"{body.name}: {pj} along the guide"))
    return rows


def _guide_length(mech, guide):
    """|C - B| of a guide, on the frame or on its carrier body; on an actuator's line
    (offset 0, the block's only point on it: every row reads cross(C - B, P - B) = 0) the
    figure's, as the rows' length scale."""
    if guide.carrier == FRAME:
        return abs(mech.fixed[guide.c] - mech.fixed[guide.b])
    if mech.bodies[guide.carrier].kind == "cylinder":
        figure = {**mech.fixed, **mech.moving}
        return abs(figure[guide.c] - figure[guide.b]) or 1.0
    carrier = mech.bodies[guide.carrier].local
    return abs(carrier[guide.c] - carrier[guide.b])


def driver_row(d, index):
    """cross(e^{iq}, P_b - P_a) = 0 (angle), |P_b - P_a|^2 = q^2 (length) or x (y) of P_a = q."""
    zero, one = index[ZERO], index[ONE]
    if d.kind == "angle":
        return Row(zero, zero, index[d.a], index[d.b], -1j, 0.0, 1.0,
                   f"driver: angle of {d.a}->{d.b}", uq=True)
    if d.kind == "length":
        ia, ib = index[d.a], index[d.b]
        return Row(ia, ib, ia, ib, 1, 0.0, abs(d.value), f"driver: |{d.a}{d.b}|", vqq=1.0)
    return Row(zero, one, zero, index[d.a], 1 if d.kind == "x" else -1j,
               0.0, 1.0, f"driver: {d.kind} of {d.a}", vq=1.0)
