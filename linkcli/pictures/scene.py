"""What a picture of a mechanism shows, as plain geometry: no matplotlib here.

Points are complex numbers ``x + iy`` in the file's display length unit; sizes
of symbols are fractions of the scene's ``size`` (the larger of the width and
height of the mechanism's points), so pictures look alike at any scale.

The vector polygon follows the exams: vector ``z_i`` runs from the
alphabetically first vertex of a link to the next one; when the file names its
angles ``phi1 .. phiN`` (the angle of the vector from the first point to the
second), those vectors are labelled ``z1 .. zN`` with their angles.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from linkcli.answers.formats import fmt
from linkcli.forces.motion import rigid_point
from linkcli.forces.pairs import line_direction
from linkcli.model.mechanism import FRAME

GREEK = {"phi": "φ", "theta": "θ", "alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ",
         "psi": "ψ"}
LOAD_LENGTH = 0.16          # force arrows, in scene sizes


def extent(points) -> float:
    """The larger of the width and height of ``points`` (never zero)."""
    xs, ys = [z.real for z in points], [z.imag for z in points]
    return max(max(xs) - min(xs), max(ys) - min(ys), 1e-300)


def pick(z, index=None) -> complex:
    """One value of a position: the scalar itself, or element ``index`` (default 0)."""
    arr = np.asarray(z)
    return complex(arr if arr.ndim == 0 else arr.reshape(-1)[index or 0])


class Scene:
    """Positions (display length units) and the size of the picture at one driver value."""

    def __init__(self, mech, pos, index=None):
        self.mech = mech
        _, self.lf = mech.units.display("length", 0)
        self.l_unit = mech.units.names["length"]
        self.p = {name: pick(z, index) / self.lf for name, z in pos.items()}
        self.size = extent([self.p[n] for n in mech.points])

    def centroid(self, names) -> complex:
        """The mean position of the points ``names``."""
        return sum(self.p[n] for n in names) / max(len(names), 1)


def used_points(mech) -> set:
    """Points that belong to some body (virtual guide points do not)."""
    return {p for b in mech.bodies.values() for p in b.points}


def line_through(point, u, half):
    """The segment of half-length ``half`` along unit ``u`` centred on ``point``."""
    return [point - half * u, point + half * u]


# --- bodies ---------------------------------------------------------------------------------
def links(scene) -> list:
    """Vertices of each link: a bar's two ends, a plate's corners by angle about its centroid."""
    out = []
    for body in scene.mech.bodies.values():
        if body.kind != "link":
            continue
        pts = [scene.p[n] for n in body.points]
        if len(pts) > 2:
            centre = sum(pts) / len(pts)
            pts = sorted(pts, key=lambda z: math.atan2((z - centre).imag, (z - centre).real))
        out.append(pts)
    return out


def actuators(scene) -> list:
    """(a, cylinder end, b, rod end) of each actuator: the cylinder from a, the rod from b."""
    out = []
    for act in scene.mech.actuators.values():
        a, b = scene.p[act.a], scene.p[act.b]
        out.append((a, a + 0.55 * (b - a), b, b - 0.6 * (b - a)))
    return out


@dataclass
class Block:
    """A slider at its point ``centre``; ``axis`` is the unit vector C - B of its guide."""

    centre: complex
    axis: complex
    arms: list                  # (centre, point) to the block's other points
    guide: list | None          # the fixed guide's line; None on a moving carrier or a disc
    disc: object | None         # the rolling disc on this slider, if any

    def corners(self, size) -> list:
        """The box: 0.075 size along the guide, 0.045 size across."""
        w, h, u = 0.075 * size, 0.045 * size, self.axis
        return [self.centre + u * (sx * w / 2) + 1j * u * (sy * h / 2)
                for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]

    def rolling(self, scene, turn=0.0):
        """(radius, ground line, tip of the marked radius turned by ``turn``) of the disc.

        The contact point is H = C - R s i u (s = +1: centre left of u).
        """
        radius = self.disc.radius / scene.lf
        ground = self.centre - radius * (self.disc.side * 1j * self.axis)
        tip = self.centre + radius * self.axis * complex(math.cos(turn), math.sin(turn))
        return radius, line_through(ground, self.axis, 0.75 * scene.size), tip


def blocks(scene, dyn=None) -> list[Block]:
    """Every slider block, with its guide line when the guide belongs to the frame."""
    out = []
    for body in scene.mech.bodies.values():
        if body.kind != "block":
            continue
        g, p = body.guide, scene.p
        u = (p[g.c] - p[g.b]) / abs(p[g.c] - p[g.b])
        centre = p[body.points[0]]
        disc = dyn.disc_on(body.name) if dyn is not None else None
        guide = line_through(centre, u, 0.75 * scene.size) \
            if g.carrier == FRAME and disc is None else None
        arms = [(centre, p[other]) for other in body.points[1:]]
        out.append(Block(centre, u, arms, guide, disc))
    return out


@dataclass
class Contact:
    """A disc of ``rolling:`` or a pulley of ``cords:``: its circle, and what it rolls on or
    what leaves it (display units)."""

    centre: complex
    radius: float
    ground: list | None = None      # the line it rolls on
    track: tuple | None = None      # (centre, radius) of the fixed circle it rolls in or on
    strand: list | None = None      # the straight cord or belt strand it turns with


def contacts(scene) -> list[Contact]:
    """Every rolling disc and pulley: a line contact at C + s r i u (``Rolling.side``), a
    cord from the tangent point C + s r i u to its point, a belt strand between the two
    tangent points."""
    out = []
    for r in scene.mech.rolling.values():
        c, rad = scene.p[r.center], r.radius / scene.lf
        u = complex(line_direction(scene.mech, r, scene.p))   # a body's line turns with it
        tangent = c + r.side * rad * 1j * u
        shape = Contact(c, rad)
        if r.kind == "line":
            shape.ground = line_through(tangent, u, 2.5 * rad)
        elif r.kind == "cord":
            p = scene.p[r.point]
            shape.strand = [tangent, tangent + ((p - tangent) * u.conjugate()).real * u]
        elif r.kind == "belt":
            far = scene.p[r.track] + r.other_side * r.track_radius / scene.lf * 1j * u
            shape.strand = [tangent, far]
        elif r.kind == "circle":
            shape.track = (scene.p[r.track], r.track_radius / scene.lf)
        out.append(shape)
    return out


def grounds(scene) -> list:
    """Fixed pivots that belong to a body (virtual points ``~...`` are not shown)."""
    used = used_points(scene.mech)
    return [scene.p[n] for n in scene.mech.fixed if not n.startswith("~") and n in used]


def ground_symbol(z, size):
    """(triangle, base line, five hatches) of the ground under a fixed pivot at ``z``."""
    t = 0.028 * size
    triangle = [z, z + complex(-t, -1.7 * t), z + complex(t, -1.7 * t)]
    base = z.imag - 1.7 * t
    line = [complex(z.real - 1.5 * t, base), complex(z.real + 1.5 * t, base)]
    hatches = []
    for k in range(5):
        x0 = z.real - 1.5 * t + k * 0.75 * t
        hatches.append([complex(x0, base), complex(x0 - 0.5 * t, base - 0.6 * t)])
    return triangle, line, hatches


def pivots(scene) -> list:
    """(name, position, unit direction of its label): outwards from the middle of the
    mechanism; beside a fixed pivot, whose ground symbol is below it."""
    used = used_points(scene.mech)
    middle = scene.centroid(used)
    out = []
    for name in sorted(used):
        z = scene.p[name]
        away = z - middle
        away = away / abs(away) if abs(away) > 0 else 1j
        if name in scene.mech.fixed:
            away = complex(-0.8, 0.6) if away.real <= 0 else complex(0.8, 0.6)
        out.append((name, z, away))
    return out


# --- the vector polygon -------------------------------------------------------------------
def greek(name: str) -> str:
    """``phi3`` -> ``φ3``; other names unchanged."""
    m = re.match(r"^([A-Za-z]+?)(\d*)$", name)
    if m and m.group(1) in GREEK:
        return GREEK[m.group(1)] + m.group(2)
    return name


def polygon_vectors(mech):
    """(label, angle label, tail, head): the exam's vectors z_i.

    The file's angle quantities when it has any (``phi3`` gives ``z3``, from its
    first point to its second); otherwise each link's vectors from its
    alphabetically first vertex to the others, numbered in order, but in a
    vibration problem a vector that an angle coordinate measures runs as the
    coordinate does and is named after it (``theta: {angle: [O, B]}``: from O to B, 'θ = 270°' as ``solve``
    prints it for a hanging rod, not 90°).
    """
    angles = [q for q in mech.quantities.values() if q.kind == "angle"]
    if angles:
        return _named_vectors(angles)
    measured = [c for c in mech.coordinates if c.kind == "angle" and c.b is not None
                and mech.elements is not None]      # a vibration problem's answers
    by_pair = {frozenset((c.a, c.b)): c for c in measured}
    out = []
    for i, (a, b) in enumerate(_link_pairs(mech, [(c.a, c.b) for c in measured])):
        c = by_pair.get(frozenset((a, b)))
        out.append((f"z{i + 1}", f"φ{i + 1}", a, b) if c is None else
                   (f"z{i + 1}", greek(c.name), c.a, c.b))
    return out


def _named_vectors(angles):
    digits = [re.match(r"^[A-Za-z_]*?(\d+)$", q.name) for q in angles]
    if all(digits) and len({m.group(1) for m in digits}) == len(digits):
        pairs = sorted(zip(angles, digits), key=lambda t: int(t[1].group(1)))
        return [(f"z{m.group(1)}", greek(q.name), q.a, q.b) for q, m in pairs]
    return [(f"z{i + 1}", greek(q.name), q.a, q.b) for i, q in enumerate(angles)]


def _link_pairs(mech, measured=()):
    """Each link's (first vertex, other vertex): the first alphabetically, or the tail of
    an angle coordinate that measures the link (``measured``: their (tail, head))."""
    pairs = []
    for body in mech.bodies.values():
        if body.kind == "link":
            pts = sorted(body.points)
            base = next((a for a, b in measured if {a, b} <= set(pts)), pts[0])
            pairs += [(base, other) for other in pts if other != base]
    pairs = list(dict.fromkeys(pairs))
    ends = [tuple(sorted((act.a, act.b))) for act in mech.actuators.values()]
    return pairs + [pair for pair in ends if pair not in pairs]


@dataclass
class Vector:
    """One drawn z_i with its label and the arc of its angle phi (deg, in [0, 360))."""

    label: str
    angle_name: str
    tail: complex
    head: complex
    label_at: complex
    radius: float               # of the angle's arc; larger for each vector from one tail
    phi: float
    angle_at: complex

    @property
    def arc_middle(self) -> complex:
        """The middle of the angle's arc."""
        bis = math.radians(self.phi / 2)
        return self.tail + self.radius * complex(math.cos(bis), math.sin(bis))


def vectors(scene) -> list[Vector]:
    """The polygon's vectors at this position; vectors of zero length are left out."""
    out, tails, s = [], {}, scene.size
    for label, angle_name, a, b in polygon_vectors(scene.mech):
        tail, head = scene.p[a], scene.p[b]
        if abs(head - tail) == 0:
            continue
        normal = 1j * (head - tail) / abs(head - tail)
        count = tails[a] = tails.get(a, -1) + 1
        radius = (0.06 + 0.04 * count) * s
        phi = math.degrees(math.atan2((head - tail).imag, (head - tail).real)) % 360.0
        bis = math.radians(phi / 2)
        angle_at = tail + (radius + 0.035 * s) * complex(math.cos(bis), math.sin(bis))
        out.append(Vector(label, angle_name, tail, head, (tail + head) / 2 + 0.035 * s * normal,
                          radius, phi, angle_at))
    return out


# --- loads ------------------------------------------------------------------------------------
@dataclass
class LoadSymbol:
    """One load as drawn: kind 'arrow' onto point ``at`` along ``direction``, 'torque' a
    curved arrow about ``at``, 'axial' arrows at both ``ends`` of a line.  ``sign`` is -1
    for a negative value (arrows reversed), else +1."""

    kind: str
    text: str
    unknown: bool
    sign: float
    at: complex = 0j
    direction: complex = 0j
    ends: tuple = ()


def loads(scene, values, units_text) -> list[LoadSymbol]:
    """The file's loads with their values (``None``: not solved, shown as '?')."""
    out = []
    for load in scene.mech.loads.values():
        value, unknown = values.get(load.name), load.value is None
        shown = "?" if value is None else fmt(value, 1)     # never '-0.0'
        text = f"{load.name} = {shown} {units_text.get(load.name, '')}" + \
            (" (unknown)" if unknown else " (brake)" if load.kind == "brake" else "")
        if load.kind == "motor":    # a characteristic, no single value
            text = f"{load.name} (motor)"
        sign = 1.0 if value is None or value >= 0 else -1.0
        out.append(_place(scene, load, LoadSymbol("", text, unknown, sign)))
    return out


def _place(scene, load, mark):
    """Where ``load`` acts: a force on its point, a torque on its body (the driver's on the
    fixed pivot), the driver of a coordinate along its axis, an axial load along its line."""
    mech, d, p = scene.mech, scene.mech.driver, scene.p
    driver = load.kind == "driver"
    if load.kind == "force":
        mark.kind, mark.at, mark.direction = "arrow", p[load.target], load.direction * mark.sign
    elif load.kind in ("torque", "motor", "brake"):
        mark.kind, mark.at = "torque", scene.centroid(_body_points(mech, load.target))
    elif driver and d.kind == "angle":
        mark.kind, mark.at = "torque", p[d.a] if d.a in mech.fixed else p[d.b]
    elif driver and d.kind in ("x", "y"):
        mark.kind, mark.at = "arrow", p[d.a]
        mark.direction = (1.0 if d.kind == "x" else 1j) * mark.sign
    else:
        mark.kind, mark.ends = "axial", (d.a, d.b) if driver else _ends(mech, load.target)
    return mark


def _body_points(mech, name) -> tuple:
    """The points of body ``name``, or the two ends of actuator ``name``."""
    body = mech.bodies.get(name)
    return body.points if body else _ends(mech, name)


def _ends(mech, name) -> tuple:
    return mech.actuators[name].a, mech.actuators[name].b


def arrow_tail(mark, size) -> complex:
    """Start of a force arrow of length 0.16 size that ends on the loaded point."""
    return mark.at - LOAD_LENGTH * size * mark.direction


def torque_arrow(mark, size):
    """(radius, tip, back): an arc from -60 to 200 deg about the centre, the arrowhead
    from ``back`` to ``tip`` at its counter-clockwise end (clockwise for a negative value)."""
    r = 0.07 * size
    end = math.radians(200 if mark.sign > 0 else -60)
    ray = complex(math.cos(end), math.sin(end))
    tip = mark.at + r * ray
    return r, tip, tip - 0.03 * size * (1j if mark.sign > 0 else -1j) * ray


def axial_arrows(scene, mark):
    """((tail, tip) at each end, label position): arrows along the line a -> b, the label
    beside its middle on the side away from the mechanism's centroid."""
    a, b = (scene.p[n] for n in mark.ends)
    u, length = (b - a) / abs(b - a), LOAD_LENGTH * scene.size
    arrows = [(tip - 0.6 * length * direction * mark.sign, tip) for tip, direction in
              ((b, u), (a, -u))]
    mid, middle = (a + b) / 2, scene.centroid(scene.mech.points)
    side = 1j * u if abs(mid + 1j * u - middle) > abs(mid - 1j * u - middle) else -1j * u
    return arrows, mid + 0.07 * scene.size * side


# --- masses, gravity, rolling discs -------------------------------------------------------------
def mass_centres(scene, dyn, pos) -> list:
    """(body, G) of every body with a mass."""
    return [(mb.body, pick(rigid_point(scene.mech, mb.body, mb.center, pos)[0]) / scene.lf)
            for mb in dyn.bodies.values() if mb.mass > 0]


def gravity_arrow(xlim, ylim, size, gravity):
    """(start, end) of an arrow along g, 0.1 size long, near the view's top left corner."""
    (xmin, xmax), (ymin, ymax) = xlim, ylim
    start = complex(xmin + 0.06 * (xmax - xmin), ymax - 0.06 * (ymax - ymin))
    return start, start + 0.1 * size * gravity / abs(gravity)


def disc_points(mech, dyn, scene) -> list:
    """Extreme points of rolling discs, pulleys and their tracks, so that the view holds
    them."""
    circles = [(scene.p[d.center], d.radius / scene.lf)
               for d in (dyn.discs.values() if dyn is not None else ())]
    for shape in contacts(scene):
        circles.append((shape.centre, shape.radius))
        if shape.track is not None:
            circles.append(shape.track)
    return [c + r * k for c, r in circles for k in (1, -1, 1j, -1j)]


def disc_turns(mech, dyn, kin) -> dict:
    """Rotation of each rolling disc from its first position: -s (displacement . u) / R."""
    out = {}
    if dyn is None:
        return out
    for disc in dyn.discs.values():
        g = mech.bodies[disc.slider].guide
        z = kin.pos[g.c] - kin.pos[g.b]
        u = z / np.abs(z)
        c = np.atleast_1d(kin.pos[disc.center])
        shift = (np.conj(u) * (c - c[0])).real
        out[disc.name] = np.broadcast_to(-disc.side * shift / disc.radius, c.shape)
    return out


# --- springs and dampers -------------------------------------------------------------------
def zigzag(a: complex, b: complex, size: float, teeth: int = 7) -> list:
    """A spring drawn from ``a`` to ``b``: straight ends, ``teeth`` zigzags between."""
    z = b - a
    if abs(z) == 0:
        return [a, b]
    u = z / abs(z)
    amp = 0.025 * size * 1j * u
    start, end = a + 0.15 * z, a + 0.85 * z
    pts = [a, start]
    for i in range(1, 2 * teeth):
        pts.append(start + (end - start) * i / (2 * teeth) + (amp if i % 2 else -amp))
    return pts + [end, b]


def dashpot(a: complex, b: complex, size: float):
    """A damper from ``a`` to ``b``: (rod, cup outline, piston) as point lists."""
    z = b - a
    if abs(z) == 0:
        return [a, b], [a], [b]
    u = z / abs(z)
    w = 0.03 * size * 1j * u
    mid = a + 0.5 * z
    cup = [mid + 0.12 * z + w, mid - 0.12 * z + w, mid - 0.12 * z - w, mid + 0.12 * z - w]
    piston = [mid + 0.02 * z + 0.8 * w, mid + 0.02 * z - 0.8 * w]
    return [a, mid - 0.12 * z, mid + 0.02 * z, b], cup, piston


def element_ends(scene, elements) -> list:
    """(kind, name, a, b) of every spring and damper joining two points."""
    out = []
    if elements is None:
        return out
    for kind, group in (("spring", elements.springs), ("damper", elements.dampers)):
        for name, e in group.items():
            m = e.measure
            if m.kind in ("distance", "along") and m.a in scene.p and m.b in scene.p:
                out.append((kind, name, scene.p[m.a], scene.p[m.b]))
    return out
