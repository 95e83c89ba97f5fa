"""matplotlib artists for a scene: bodies, pivots, the vector polygon, loads and masses.

matplotlib is imported inside the functions, so importing this module costs
nothing.  The geometry comes from :mod:`linkcli.scene`; here are only colours,
line widths and drawing order (``zorder``).
"""
from __future__ import annotations

from linkcli.errors import InputError
from linkcli.pictures.scene import (actuators, arrow_tail, axial_arrows, blocks, contacts, dashpot,
                                    element_ends, ground_symbol, grounds, gravity_arrow, links,
                                    loads, mass_centres, pivots, torque_arrow, vectors, zigzag)

COLORS = ["#1f77b4", "#2ca02c", "#9467bd", "#8c564b", "#17becf", "#bcbd22", "#ff7f0e",
          "#7f7f7f", "#e377c2"]
VECTOR = "#b22222"
KNOWN, UNKNOWN = "#1a7f37", "#c71585"
#: the gid of the lines and outlines that are the mechanism itself: labels keep off them
BODY = "body"


def figure(width, height, dpi=100):
    """A figure on the Agg canvas (no display); a clear error without matplotlib."""
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:
        raise InputError("pictures need matplotlib, which is not installed",
                         hint="pip install 'linkcli[plot]'") from None
    fig = Figure(figsize=(width, height), dpi=dpi)
    FigureCanvasAgg(fig)
    return fig


def set_limits(ax, points, size, margin=0.22):
    """Equal scales; the view holds ``points`` with ``margin`` sizes around them."""
    xs, ys = _xy(points)
    pad = margin * size
    ax.set_xlim(min(xs) - pad, max(xs) + pad)
    ax.set_ylim(min(ys) - pad, max(ys) + pad)
    ax.set_aspect("equal", adjustable="box")


# --- primitives on complex points -----------------------------------------------------------
def _xy(points):
    return [z.real for z in points], [z.imag for z in points]


def _line(ax, points, **style):
    ax.plot(*_xy(points), **style)


def _dot(ax, z, marker, **style):
    ax.plot(z.real, z.imag, marker, **style)


def _polygon(ax, points, **style):
    from matplotlib.patches import Polygon
    ax.add_patch(Polygon([(z.real, z.imag) for z in points], closed=True, **style))


def _arc(ax, centre, radius, theta1, theta2, **style):
    from matplotlib.patches import Arc
    ax.add_patch(Arc((centre.real, centre.imag), 2 * radius, 2 * radius, theta1=theta1,
                     theta2=theta2, **style))


def _arrow(ax, tail, head, zorder, **props):
    ax.annotate("", xy=(head.real, head.imag), xytext=(tail.real, tail.imag),
                arrowprops=props, zorder=zorder)


def _text(ax, z, text, anchor=None, **style):
    """``text`` at ``z``; with ``anchor``, the point it names (a leader line is drawn to it
    where the label must move far, :mod:`linkcli.pictures.labels`)."""
    if anchor is None:
        ax.text(z.real, z.imag, text, **style)
        return
    ax.annotate(text, (anchor.real, anchor.imag), xytext=(z.real, z.imag), textcoords="data",
                annotation_clip=False, **style)


def _label(ax, z, text, offset, **style):
    """``text`` at ``offset`` points (complex) from ``z``."""
    ax.annotate(text, (z.real, z.imag), xytext=(offset.real, offset.imag),
                textcoords="offset points", **style)


# --- the mechanism --------------------------------------------------------------------------
def draw_mechanism(ax, scene, dyn=None, labels=True, spins=None):
    """Links, actuators, sliders and discs (turned by ``spins``), grounds, pivots."""
    _contacts(ax, scene)
    _links(ax, scene)
    _actuators(ax, scene)
    _blocks(ax, scene, dyn, spins or {})
    _grounds(ax, scene)
    _pivots(ax, scene, labels)


def draw_outline(ax, scene, color):
    """The links and actuators of ``scene`` as thin lines of one colour (a displaced pose)."""
    for pts in links(scene):
        _line(ax, pts + ([pts[0]] if len(pts) > 2 else []), color=color, lw=1.6, zorder=5)
    for a, _, b, _ in actuators(scene):
        _line(ax, [a, b], color=color, lw=1.6, zorder=5)


def draw_elements(ax, scene, elements):
    """Springs as zigzags and dampers as dashpots between their points, with their names."""
    for kind, name, a, b in element_ends(scene, elements):
        if kind == "spring":
            _line(ax, zigzag(a, b, scene.size), color="#333333", lw=1.2, zorder=4, gid=BODY)
        else:
            rod, cup, piston = dashpot(a, b, scene.size)
            _line(ax, rod, color="#333333", lw=1.2, zorder=4, gid=BODY)
            _line(ax, cup, color="#333333", lw=1.2, zorder=4, gid=BODY)
            _line(ax, piston, color="#333333", lw=2.0, zorder=4, gid=BODY)
        _text(ax, (a + b) / 2 + 0.04 * scene.size * 1j, name, (a + b) / 2, fontsize=8,
              ha="center",
              va="bottom", zorder=7)


def _links(ax, scene):
    for i, pts in enumerate(links(scene)):
        color = COLORS[i % len(COLORS)]
        if len(pts) == 2:
            _line(ax, pts, color=color, lw=5, solid_capstyle="round", alpha=0.9, zorder=2,
                  gid=BODY)
        else:
            _polygon(ax, pts, facecolor=color, alpha=0.35, edgecolor=color, lw=2.5, zorder=2,
                     gid=BODY)


def _actuators(ax, scene):
    for a, cylinder, b, rod in actuators(scene):
        _line(ax, [a, cylinder], color="#555555", lw=9, solid_capstyle="butt", zorder=2,
              gid=BODY)
        _line(ax, [b, rod], color="#222222", lw=3, zorder=3, gid=BODY)


def _blocks(ax, scene, dyn, spins):
    for block in blocks(scene, dyn):
        if block.guide is not None:
            _line(ax, block.guide, color="#888888", lw=1, ls="-.", zorder=1)
        for arm in block.arms:
            _line(ax, arm, color="#444444", lw=3, zorder=3, gid=BODY)
        if block.disc is not None:
            _disc(ax, scene, block, spins.get(block.disc.name, 0.0))
        else:
            _polygon(ax, block.corners(scene.size), facecolor="#cccccc", edgecolor="#222222",
                     lw=1.3, zorder=3, gid=BODY)


def _disc(ax, scene, block, turn):
    from matplotlib.patches import Circle
    radius, ground, tip = block.rolling(scene, turn)
    c = block.centre
    _line(ax, ground, color="#444444", lw=1.5, zorder=1)
    ax.add_patch(Circle((c.real, c.imag), radius, facecolor="#dddddd", edgecolor="#333333",
                        lw=1.5, zorder=2))
    _line(ax, [c, tip], color="#333333", lw=1.2, zorder=3)


def _contacts(ax, scene):
    """Rolling discs and pulleys as circles (their links drawn on top), the lines and
    tracks they roll on, their cords and belt strands."""
    from matplotlib.patches import Circle
    for shape in contacts(scene):
        c = shape.centre
        ax.add_patch(Circle((c.real, c.imag), shape.radius, facecolor="#eeeeee",
                            edgecolor="#333333", lw=1.5, zorder=1))
        if shape.ground is not None:
            _line(ax, shape.ground, color="#444444", lw=1.5, zorder=1)
        if shape.track is not None:
            t, r = shape.track
            ax.add_patch(Circle((t.real, t.imag), r, fill=False, edgecolor="#444444", lw=1.5,
                                zorder=1))
        if shape.strand is not None:
            _line(ax, shape.strand, color="#8b5a2b", lw=1.6, zorder=2, gid=BODY)


def _grounds(ax, scene):
    for z in grounds(scene):
        triangle, base, hatches = ground_symbol(z, scene.size)
        _polygon(ax, triangle, facecolor="white", edgecolor="black", lw=1.2, zorder=4)
        _line(ax, base, color="black", lw=1.2, zorder=4)
        for hatch in hatches:
            _line(ax, hatch, color="black", lw=0.8, zorder=4)


def _pivots(ax, scene, labels):
    for name, z, away in pivots(scene):
        _dot(ax, z, "o", ms=6, mfc="white", mec="black", mew=1.3, zorder=6)
        if labels:
            _label(ax, z, name, 11 * away, fontsize=10, fontweight="bold", ha="center",
                   va="center", zorder=7)


# --- vectors, loads, masses ------------------------------------------------------------------
def draw_polygon(ax, scene):
    """The vectors z_i with their names and the arcs of their angles from +x."""
    for v in vectors(scene):
        _arrow(ax, v.tail, v.head, 8, arrowstyle="-|>", color=VECTOR, lw=1.6, shrinkA=0,
               shrinkB=4, mutation_scale=14)
        _text(ax, v.label_at, v.label, (v.tail + v.head) / 2, color=VECTOR, fontsize=10,
              ha="center", va="center", fontstyle="italic", zorder=9)
        _line(ax, [v.tail, v.tail + 1.25 * v.radius], color=VECTOR, lw=0.7, ls=":", zorder=8)
        _arc(ax, v.tail, v.radius, 0, v.phi, color=VECTOR, lw=0.9, zorder=8)
        _text(ax, v.angle_at, f"{v.angle_name} = {v.phi:.1f}°", v.arc_middle, color=VECTOR,
              fontsize=8, ha="center", va="center", zorder=9)


def draw_loads(ax, scene, values, units_text):
    """Forces as arrows onto their points, torques as curved arrows; the unknown in magenta."""
    draw = {"arrow": _force, "torque": _torque, "axial": _axial}
    for mark in loads(scene, values, units_text):
        draw[mark.kind](ax, scene, mark, UNKNOWN if mark.unknown else KNOWN)


def _force(ax, scene, mark, color):
    tail = arrow_tail(mark, scene.size)
    _arrow(ax, tail, mark.at, 10, arrowstyle="-|>", color=color, lw=2.2, shrinkA=0, shrinkB=5,
           mutation_scale=16)
    _text(ax, tail, mark.text, tail, color=color, fontsize=9, ha="center",
          va="bottom" if mark.direction.imag <= 0 else "top", zorder=11)


def _torque(ax, scene, mark, color):
    r, tip, back = torque_arrow(mark, scene.size)
    _arc(ax, mark.at, r, -60, 200, color=color, lw=2, zorder=10)
    _arrow(ax, back, tip, 10, arrowstyle="-|>", color=color, lw=2, shrinkA=0, shrinkB=0,
           mutation_scale=16)
    _text(ax, mark.at + complex(r, r), mark.text, mark.at + r * (1 + 1j) / abs(1 + 1j),
          color=color, fontsize=9, zorder=11)


def _axial(ax, scene, mark, color):
    arrows, spot = axial_arrows(scene, mark)
    for tail, tip in arrows:
        _arrow(ax, tail, tip, 10, arrowstyle="<|-" if mark.sign > 0 else "-|>", color=color,
               lw=2, shrinkA=5, shrinkB=0, mutation_scale=14)
    _text(ax, spot, mark.text, sum(scene.p[n] for n in mark.ends) / 2, color=color, fontsize=9,
          ha="center", zorder=11)


def draw_masses(ax, scene, dyn, pos):
    """Centres of mass G, point masses and the direction of gravity (after the limits)."""
    if dyn is None:
        return
    for body, g in mass_centres(scene, dyn, pos):
        _dot(ax, g, "o", ms=9, mfc="white", mec="black", zorder=7)
        _dot(ax, g, "+", ms=9, mec="black", mew=1.2, zorder=7)
        _label(ax, g, f"G {body}", complex(-8, -12), fontsize=7, zorder=7)
    for point in dyn.masses:
        _dot(ax, scene.p[point], "o", ms=10, color="black", zorder=7)
    if dyn.gravity:
        start, end = gravity_arrow(ax.get_xlim(), ax.get_ylim(), scene.size, dyn.gravity)
        _arrow(ax, start, end, 9, arrowstyle="-|>", color="black", lw=1.5, shrinkA=0, shrinkB=0)
        _label(ax, start, "g", complex(6, -4), fontsize=10, zorder=9)
