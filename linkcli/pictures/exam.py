"""The exam's figure: the mechanism as the problem is drawn for the student, without answers.

It shows what the statement gives and nothing that is solved: the frame's pivots, the
links (a binary link with its length), the actuators, the sliders with their guides (a
fixed guide with its line, ``y = 320 mm``), the rolling discs, pulleys and cords, the
springs and dampers by name, the masses' centres and gravity, the known loads with
their values and directions, the unknown load in its positive sense marked '?', and
the driver with its value and the sense of its rate (for a vibration problem, each
coordinate with its positive sense).  The vector polygon, the solved angles and every
other answer of ``draw`` are left out, and so are the axes' ticks: a number drawn is a
number of the statement (:mod:`linkcli.texts.data` words the same data).

:func:`exam_figure` builds the matplotlib figure (tests read its texts); :func:`draw_exam`
writes it like ``draw``.
"""
from __future__ import annotations

import cmath
import math

from linkcli.model.mechanism import FRAME
from linkcli.texts.amounts import CLOSE, Writer, digits
from linkcli.texts.bodies import fixed_line
from linkcli.texts.loads import force_by_components
from linkcli.texts.unknowns import unknown_datum
from linkcli.pictures.drawing import (KNOWN, UNKNOWN, _arc, _arrow, _axial, _force, _line, _text,
                                      _torque, draw_elements, draw_masses, draw_mechanism, figure,
                                      set_limits)
from linkcli.pictures.labels import place_labels
from linkcli.pictures.scene import (Scene, disc_points, element_ends, greek, loads,
                                    used_points)

DRIVER = "#1f3f99"
DIMENSION = "#444444"
STATED = 6          # significant digits of a length drawn as stated; longer ones are rounded
ROUNDED = 3         # significant digits kept at least where a length is rounded


def exam_figure(mech, lang="en", method="closed", dpi=100):
    """The matplotlib figure of the exam's drawing of ``mech`` (see the module)."""
    from linkcli.pictures.plotting import _positions, figure_coordinates
    kin = _positions(mech, figure_coordinates(mech), method)
    scene = Scene(mech, kin.pos)
    dyn = mech.dynamics
    fig = figure(8.0, 6.5, dpi)
    ax = fig.add_subplot(1, 1, 1)
    view = [scene.p[n] for n in mech.points] + disc_points(mech, dyn, scene)
    set_limits(ax, view, scene.size)
    w = Writer(mech, lang)
    draw_mechanism(ax, scene, dyn)
    _lengths(ax, scene, w)
    _guides(ax, scene, w)
    draw_elements(ax, scene, mech.elements)
    _anchors(ax, scene)
    draw_masses(ax, scene, dyn, kin.pos)
    _loads(ax, scene, w)
    if mech.elements is None:
        _driver(ax, scene, w)
    else:
        _coordinates(ax, scene)
    _axes_mark(ax, scene)
    ax.set_axis_off()
    fig.tight_layout()
    place_labels(ax)
    return fig


def draw_exam(mech, output: str, lang="en", method="closed", dpi=100) -> None:
    """Write the exam's figure of ``mech`` to ``output`` (.png, .svg or .pdf)."""
    from linkcli.pictures.plotting import IMAGE_FORMATS, _save_figure, check_output
    check_output(output, IMAGE_FORMATS)
    _save_figure(exam_figure(mech, lang, method, dpi), output)


def _side(scene, a, b, distance):
    """The point ``distance`` (scene sizes) off the middle of a -> b, away from the
    mechanism's centre."""
    mid, u = (a + b) / 2, (b - a) / abs(b - a)
    normal = 1j * u
    middle = scene.centroid(scene.mech.points)
    if abs(mid + normal - middle) < abs(mid - normal - middle):
        normal = -normal
    return mid + distance * scene.size * normal


# --- dimensions -------------------------------------------------------------------------------
def _lengths(ax, scene, w):
    """Each binary link's length beside its middle (a design question's unknown by its
    name)."""
    mech = scene.mech
    for body in mech.bodies.values():
        if body.kind != "link" or len(body.points) != 2:
            continue
        a, b = (scene.p[n] for n in body.points)
        if abs(b - a) == 0:
            continue
        p, q = body.points

        def length(m):
            return abs(m.bodies[body.name].local[q] - m.bodies[body.name].local[p])
        unknown = unknown_datum(mech, length, mech.units.factor("length"))
        _text(ax, _side(scene, a, b, 0.045), unknown or _dimension(w, length(mech)), (a + b) / 2,
              color=DIMENSION, fontsize=8, ha="center", va="center", zorder=9)


def _dimension(w, si) -> str:
    """A length as the exam prints it: a stated number whole ('220 mm', '0.035 m'), a
    number that no short decimal writes (a length of sqrt(2) m) rounded to the report's
    decimals, keeping at least ROUNDED significant digits."""
    value = si / w.units.factor("length")
    if digits(value) <= STATED:
        return w.length(si)
    places = max(w.mech.report.get("decimals", 1),
                 ROUNDED - 1 - math.floor(math.log10(abs(value))))
    return f"{w.num(round(value, places))} {w.units.names['length']}"


def _guides(ax, scene, w):
    """A fixed guide's line: ``y = c`` or ``x = c``, or its angle beside the line."""
    mech = scene.mech
    for body in mech.bodies.values():
        g = body.guide
        if body.kind != "block" or g is None or g.carrier != FRAME:
            continue
        p0, u = fixed_line(mech, g)
        if abs(u - 1) < CLOSE:
            text = f"y = {w.length(p0.imag)}"
        elif abs(u - 1j) < CLOSE:
            text = f"x = {w.length(p0.real)}"
        else:
            text = w.angle(cmath.phase(u) % (2 * math.pi))
        on = scene.p[body.points[0]] + 0.3 * scene.size * u
        _text(ax, on + 0.03 * scene.size * 1j * u, text, on, color=DIMENSION, fontsize=8,
              ha="center", va="center", zorder=9)


def _anchors(ax, scene):
    """The ground at a spring's or damper's fixed end that no body holds: a short wall
    across the element, hatched on the side away from it."""
    mech = scene.mech
    held = used_points(mech)
    ends = {}
    for _, _, a, b in element_ends(scene, mech.elements):
        ends[a], ends[b] = b, a
    for name, z in scene.p.items():
        if name not in mech.fixed or name in held or z not in ends:
            continue
        u = (z - ends[z]) / abs(z - ends[z]) if abs(z - ends[z]) else 1j
        half = 0.03 * scene.size * 1j * u
        _line(ax, [z - half, z + half], color="black", lw=1.4, zorder=4)
        for k in range(4):
            start = z - half + 2 * half * (k + 0.5) / 4
            _line(ax, [start, start + 0.02 * scene.size * (u - 1j * u)], color="black",
                  lw=0.8, zorder=4)


# --- loads ------------------------------------------------------------------------------------
def _loads(ax, scene, w):
    """Known loads with their stated values, the unknown in its positive sense with '?'."""
    mech = scene.mech
    values = {n: load.value for n, load in mech.loads.items() if load.value is not None}
    for load, mark in zip(mech.loads.values(), loads(scene, values, {})):
        color = UNKNOWN if mark.unknown else KNOWN
        mark.text = _load_text(w, load)
        {"arrow": _force, "torque": _torque, "axial": _axial}[mark.kind](ax, scene, mark, color)


def _load_text(w, load) -> str:
    """'F = 450 N' (the value's size: the arrow shows its sense), 'Q = ?' for the unknown,
    the name alone for a force the statement gives by components."""
    mech = w.mech
    if load.value is None:
        return f"{load.name} = ?"
    if load.pressure is not None:
        return f"{load.name}: p = {w.amount(load.pressure[0], 'pressure')}"
    if load.kind == "force" and force_by_components(w, load):
        return load.name
    kind = mech.load_unit_kind(load) if load.kind == "driver" else \
        "torque" if load.kind == "torque" else "force"
    return f"{load.name} = {w.amount(abs(load.value), kind)}"


# --- the driver and the coordinates --------------------------------------------------------------
def _driver(ax, scene, w):
    """Each driver's value and the sense of its rate (``_one_driver``): q for one driver,
    each by its name for several."""
    drivers = scene.mech.coordinates
    for d in drivers:
        _one_driver(ax, scene, w, d, "q" if len(drivers) == 1 else d.name)


def _one_driver(ax, scene, w, d, q):
    """The driver ``d`` (called ``q``): an angle from +x with a curved arrow, a length or a
    coordinate with a straight one."""
    mech = scene.mech
    rate_unit, rate_f = mech.units.display(d.base, 1)
    rate = f"{q}' = {w.num(abs(d.rate) / rate_f)} {rate_unit}" if d.rate else ""
    if d.kind == "angle":
        _angle_mark(ax, scene, d, f"{q} = {w.angle(d.value)}", fontsize=9)
        if d.rate:
            _spin(ax, scene, scene.p[d.b], d.rate > 0, rate)
        return
    value = f"{q} = {w.length(d.value)}"
    if d.kind == "length":
        a, b = scene.p[d.a], scene.p[d.b]
        u = (b - a) / abs(b - a)
        spot = _side(scene, a, b, -0.05)       # the unknown's label is on the other side
        off = spot - (a + b) / 2
        ha = "center" if abs(off.real) < 0.3 * abs(off) else "left" if off.real > 0 else "right"
        _text(ax, spot, value + (f", {rate}" if rate else ""), (a + b) / 2, color=DRIVER,
              fontsize=9,
              ha=ha, va="center", zorder=11)
        if d.rate:
            sense = u if d.rate > 0 else -u
            start = b + 0.05 * scene.size * 1j * u
            _arrow(ax, start, start + 0.12 * scene.size * sense, 11, arrowstyle="-|>",
                   color=DRIVER, lw=1.6, shrinkA=0, shrinkB=0, mutation_scale=12)
        return
    u = 1 if d.kind == "x" else 1j
    point = scene.p[d.a]
    sense = u if d.rate >= 0 else -u
    start = point + 0.06 * scene.size * 1j * u
    _arrow(ax, start, start + 0.12 * scene.size * sense, 11, arrowstyle="-|>", color=DRIVER,
           lw=1.6, shrinkA=0, shrinkB=0, mutation_scale=12)
    _text(ax, start + 0.06 * scene.size * 1j * u, value + (f", {rate}" if rate else ""), point,
          color=DRIVER, fontsize=9, ha="center", va="center", zorder=11)


def _angle_mark(ax, scene, coordinate, text, **style):
    """The angle of the vector a -> b from +x, as an arc at a from a dotted +x line, and
    ``text`` beside the arc's middle (a negative angle turns clockwise)."""
    tail, head = scene.p[coordinate.a], scene.p[coordinate.b]
    phi = math.fmod(math.degrees(coordinate.value), 360.0)
    radius = min(0.08 * scene.size, 0.6 * abs(head - tail))
    _line(ax, [tail, tail + 1.4 * radius], color=DRIVER, lw=0.8, ls=":", zorder=8)
    _arc(ax, tail, radius, min(0.0, phi), max(0.0, phi), color=DRIVER, lw=1.0, zorder=8)
    middle = cmath.rect(radius + 0.05 * scene.size, math.radians(phi / 2))
    _text(ax, tail + middle, text, tail + radius * middle / abs(middle), color=DRIVER,
          ha="center", va="center", zorder=11, **style)


def _spin(ax, scene, at, counter, text):
    """A curved arrow about ``at`` in the sense of the rate, with ``text``."""
    r = 0.05 * scene.size
    start, end = (-40, 130) if counter else (130, -40)
    _arc(ax, at, r, min(start, end), max(start, end), color=DRIVER, lw=1.4, zorder=10)
    ray = cmath.rect(1, math.radians(end))
    tip = at + r * ray
    back = tip - 0.025 * scene.size * (1j if counter else -1j) * ray
    _arrow(ax, back, tip, 10, arrowstyle="-|>", color=DRIVER, lw=1.4, shrinkA=0, shrinkB=0,
           mutation_scale=12)
    away = at - scene.centroid(scene.mech.points)
    away = away / abs(away) if abs(away) else 1j
    _text(ax, at + 0.1 * scene.size * away, text, at + r * away, color=DRIVER, fontsize=9,
          ha="center", va="center", zorder=11)


def _coordinates(ax, scene):
    """Each coordinate of a vibration problem by name, in its positive sense."""
    mech = scene.mech
    for c in mech.coordinates:
        if c.kind == "angle":
            _angle_mark(ax, scene, c, greek(c.name), fontsize=10, fontstyle="italic")
            continue
        u = 1 if c.kind == "x" else 1j if c.kind == "y" else None
        if u is None:
            a, b = scene.p[c.a], scene.p[c.b]
            u, at = (b - a) / abs(b - a), b
        else:
            at = scene.p[c.a]
        start = at + 0.06 * scene.size * 1j * u
        _arrow(ax, start, start + 0.1 * scene.size * u, 11, arrowstyle="-|>", color=DRIVER,
               lw=1.4, shrinkA=0, shrinkB=0, mutation_scale=12)
        _text(ax, start + 0.13 * scene.size * u, greek(c.name), start + 0.1 * scene.size * u,
              color=DRIVER, fontsize=10,
              fontstyle="italic", ha="center", va="center", zorder=11)


def _axes_mark(ax, scene):
    """Small x and y arrows in the lower right corner: the axes the data refer to."""
    (xmin, xmax), (ymin, ymax) = ax.get_xlim(), ax.get_ylim()
    o = complex(xmax - 0.04 * (xmax - xmin) - 0.1 * scene.size, ymin + 0.05 * (ymax - ymin))
    length = 0.08 * scene.size
    for u, name in ((1, "x"), (1j, "y")):
        _arrow(ax, o, o + length * u, 9, arrowstyle="-|>", color="black", lw=1.0, shrinkA=0,
               shrinkB=0, mutation_scale=10)
        _text(ax, o + 1.25 * length * u, name, o + length * u, fontsize=9, ha="center",
              va="center", zorder=9)
