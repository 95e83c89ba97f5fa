"""Pictures: quantities against the driver, the mechanism with its vector polygon, motion.

matplotlib (Agg, no display) is imported inside the functions, so the other
commands never pay for it.  Every picture is written to a temporary file in
the target folder and renamed into place: a failure leaves nothing half-written.

The vector polygon follows the exams: vector ``z_i`` runs from the
alphabetically first vertex of a link to the next one; when the file names its
angles ``phi1 .. phiN`` (the angle of the vector from the first point to the
second), those vectors are drawn and labelled ``z1 .. zN`` with their angles.
"""
from __future__ import annotations

import math
import os
import re
import tempfile

import numpy as np

from .errors import InputError
from .model import FRAME
from .model import split_rate

IMAGE_FORMATS = ("png", "svg", "pdf")
MAX_STEPS = 100_000
COLORS = ["#1f77b4", "#2ca02c", "#9467bd", "#8c564b", "#17becf", "#bcbd22", "#ff7f0e",
          "#7f7f7f", "#e377c2"]
VECTOR = "#b22222"


# --- command-line helpers ------------------------------------------------------------------
def parse_sweep(text: str) -> np.ndarray:
    """'FROM:TO:STEPS' -> STEPS + 1 driver values FROM + i (TO - FROM) / STEPS (display units)."""
    parts = str(text).split(":")
    try:
        if len(parts) != 3:
            raise ValueError
        start, stop, steps = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError:
        raise InputError(f"cannot read sweep '{text}'", key="--sweep",
                         hint="write FROM:TO:STEPS, e.g. 0:360:72: driver values in the "
                         "file's units, STEPS intervals") from None
    if not (math.isfinite(start) and math.isfinite(stop)) or not 1 <= steps <= MAX_STEPS:
        raise InputError(f"sweep '{text}': need finite FROM, TO and 1 <= STEPS <= {MAX_STEPS}",
                         key="--sweep")
    return start + np.arange(steps + 1) * ((stop - start) / steps)


def check_names(mech, names):
    """Refuse names that the file does not define (quantities, their rates, loads)."""
    from .results import report_names
    if not names:
        raise InputError("give at least one quantity to plot", key="--y",
                         hint="e.g. --y " + (report_names(mech) or ["q"])[0])
    for name in names:
        base, order = split_rate(name)
        quantity = mech.quantities.get(base)
        ok = quantity is not None and (order == 0 if quantity.kind == "load" else True)
        if not ok:
            shown = report_names(mech)
            raise InputError(f"'{name}' is not defined by this file", file=mech.file, key="--y",
                             hint="its report defines: " + (", ".join(shown) or "nothing") +
                             "; define others under 'quantities'")


def _driver_text(mech) -> tuple[str, str, float]:
    d = mech.driver
    base = "angle" if d.kind == "angle" else "length"
    unit, factor = mech.units.display(base, 0)
    what = {"angle": f"angle of {d.a}->{d.b}", "length": f"length {d.a}{d.b}",
            "x": f"x of {d.a}", "y": f"y of {d.a}"}[d.kind]
    return what, unit, factor


def check_output(path: str, formats) -> str:
    """The picture format from the output path's extension; refuse others early."""
    ext = os.path.splitext(str(path))[1].lower().lstrip(".")
    if ext not in formats:
        raise InputError(f"cannot write {'.' + ext if ext else 'files without an extension'} "
                         "here", file=path, key="-o", hint="use " + ", ".join("." + f for f in
                                                                               formats))
    if os.path.isdir(path):
        raise InputError("the output path is a folder", file=path, key="-o")
    return ext


def _save(path: str, write, formats) -> None:
    """Write a picture through ``write(tmp_path, ext)`` to a temporary file, then rename."""
    ext = check_output(path, formats)
    folder = os.path.dirname(os.path.abspath(path))
    try:
        handle, tmp = tempfile.mkstemp(prefix=".linkcli-", suffix="." + ext, dir=folder)
    except OSError as exc:
        raise InputError(f"cannot write output file: {exc.strerror}", file=path, key="-o",
                         hint="check the folder exists and is writable") from None
    os.close(handle)
    try:
        write(tmp, ext)
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)
        os.replace(tmp, path)
    except OSError as exc:
        _remove(tmp)
        raise InputError(f"cannot write output file: {exc.strerror}", file=path, key="-o",
                         hint="check the folder exists and is writable") from None
    except BaseException:
        _remove(tmp)
        raise


def _remove(path):
    try:
        os.remove(path)
    except OSError:
        pass


def _figure(width, height, dpi=100):
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:
        raise InputError("pictures need matplotlib, which is not installed",
                         hint="pip install 'linkcli[plot]'") from None
    fig = Figure(figsize=(width, height), dpi=dpi)
    FigureCanvasAgg(fig)
    return fig


# --- plot ------------------------------------------------------------------------------
def plot(mech, sweep: str, names, output: str, dpi: int = 100) -> None:
    """Quantities ``names`` against the driver over ``sweep``, one panel each."""
    check_output(output, IMAGE_FORMATS)
    check_names(mech, names)
    q = parse_sweep(sweep)
    result = mech.solve(q=q, names=list(dict.fromkeys(names)))
    what, q_unit, _ = _driver_text(mech)
    fig = _figure(8.0, 1.2 + 2.4 * len(names), dpi)
    axes = fig.subplots(len(names), 1, sharex=True, squeeze=False)[:, 0]
    for ax, name, color in zip(axes, names, COLORS * len(names)):
        y = np.broadcast_to(np.asarray(result.values[name], dtype=float), q.shape)
        y = _continuous(mech, name, y, result.units[name])
        ax.plot(q, y, color=color, lw=1.8)
        ax.set_ylabel(f"{name} [{result.units[name]}]")
        ax.grid(True, alpha=0.35)
        if q[0] != q[-1]:
            ax.set_xlim(q[0], q[-1])
    axes[-1].set_xlabel(f"q = {what} [{q_unit}]")
    axes[0].set_title(_wrap(mech.title))
    fig.tight_layout()
    _save(output, lambda tmp, ext: fig.savefig(tmp, format=ext), IMAGE_FORMATS)


def _continuous(mech, name, y, unit):
    """Angles without the jumps of [0, 360): unwrapped, then shifted to a mean in [-180, 180)."""
    base, order = split_rate(name)
    quantity = mech.quantities[base]
    is_angle = quantity.kind == "angle" or (quantity.kind == "q" and mech.driver.kind == "angle")
    if order or not is_angle or y.size < 2:
        return y
    period = 360.0 if unit == "deg" else 2 * math.pi
    y = np.unwrap(y, period=period)
    return y - period * np.floor(np.mean(y) / period + 0.5)


def _wrap(text, width=80):
    import textwrap
    return "\n".join(textwrap.wrap(str(text), width)[:3])


# --- the mechanism at one position -----------------------------------------------------------
class _Scene:
    """Positions (display length units) and sizes for drawing at one driver value."""

    def __init__(self, mech, pos, index=None):
        self.mech = mech
        _, self.lf = mech.units.display("length", 0)
        self.l_unit = mech.units.names["length"]

        def at(z):
            arr = np.asarray(z)
            return complex(arr if arr.ndim == 0 else arr.reshape(-1)[index or 0]) / self.lf

        self.p = {name: at(z) for name, z in pos.items()}
        shown = [self.p[n] for n in mech.points]
        xs, ys = [z.real for z in shown], [z.imag for z in shown]
        self.size = max(max(xs) - min(xs), max(ys) - min(ys), 1e-300)


def _used_points(mech):
    return {p for b in mech.bodies.values() for p in b.points}


def _draw_mechanism(ax, scene, dyn=None, labels=True, spins=None):
    from matplotlib.patches import Circle, Polygon
    mech, p, s = scene.mech, scene.p, scene.size
    for i, body in enumerate(b for b in mech.bodies.values() if b.kind == "link"):
        color = COLORS[i % len(COLORS)]
        pts = [p[n] for n in body.points]
        if len(pts) == 2:
            ax.plot([pts[0].real, pts[1].real], [pts[0].imag, pts[1].imag], color=color, lw=5,
                    solid_capstyle="round", alpha=0.9, zorder=2)
        else:
            centre = sum(pts) / len(pts)
            pts = sorted(pts, key=lambda z: math.atan2((z - centre).imag, (z - centre).real))
            ax.add_patch(Polygon([(z.real, z.imag) for z in pts], closed=True, facecolor=color,
                                 alpha=0.35, edgecolor=color, lw=2.5, zorder=2))
    for act in mech.actuators.values():
        a, b = p[act.a], p[act.b]
        cyl, rod = a + 0.55 * (b - a), b - 0.6 * (b - a)
        ax.plot([a.real, cyl.real], [a.imag, cyl.imag], color="#555555", lw=9,
                solid_capstyle="butt", zorder=2)
        ax.plot([b.real, rod.real], [b.imag, rod.imag], color="#222222", lw=3, zorder=3)
    for body in mech.bodies.values():
        if body.kind != "block":
            continue
        g = body.guide
        u = p[g.c] - p[g.b]
        u = u / abs(u)
        centre = p[body.points[0]]
        disc = dyn.disc_on(body.name) if dyn is not None else None
        if g.carrier == FRAME:
            reach = 0.75 * s
            line = [centre - reach * u, centre + reach * u]
            if disc is None:
                ax.plot([z.real for z in line], [z.imag for z in line], color="#888888",
                        lw=1, ls="-.", zorder=1)
        for other in body.points[1:]:
            ax.plot([centre.real, p[other].real], [centre.imag, p[other].imag],
                    color="#444444", lw=3, zorder=3)
        if disc is not None:
            radius = disc.radius / scene.lf
            normal = disc.side * 1j * u
            ground = centre - radius * normal
            line = [ground - 0.75 * s * u, ground + 0.75 * s * u]
            ax.plot([z.real for z in line], [z.imag for z in line], color="#444444", lw=1.5,
                    zorder=1)
            ax.add_patch(Circle((centre.real, centre.imag), radius, facecolor="#dddddd",
                                edgecolor="#333333", lw=1.5, zorder=2))
            turn = (spins or {}).get(disc.name, 0.0)
            tip = centre + radius * u * complex(math.cos(turn), math.sin(turn))
            ax.plot([centre.real, tip.real], [centre.imag, tip.imag], color="#333333", lw=1.2,
                    zorder=3)
            continue
        w, h = 0.075 * s, 0.045 * s
        corners = [centre + u * (sx * w / 2) + 1j * u * (sy * h / 2)
                   for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        ax.add_patch(Polygon([(z.real, z.imag) for z in corners], closed=True,
                             facecolor="#cccccc", edgecolor="#222222", lw=1.3, zorder=3))
    used = _used_points(mech)
    for name in mech.fixed:
        if name.startswith("~") or name not in used:
            continue
        z, t = p[name], 0.028 * s
        tri = [z, z + complex(-t, -1.7 * t), z + complex(t, -1.7 * t)]
        ax.add_patch(Polygon([(c.real, c.imag) for c in tri], closed=True, facecolor="white",
                             edgecolor="black", lw=1.2, zorder=4))
        base = z.imag - 1.7 * t
        ax.plot([z.real - 1.5 * t, z.real + 1.5 * t], [base, base], color="black", lw=1.2,
                zorder=4)
        for k in range(5):
            x0 = z.real - 1.5 * t + k * 0.75 * t
            ax.plot([x0, x0 - 0.5 * t], [base, base - 0.6 * t], color="black", lw=0.8, zorder=4)
    middle = sum(p[n] for n in used) / max(len(used), 1)
    for name in sorted(used):
        z = p[name]
        ax.plot(z.real, z.imag, "o", ms=6, mfc="white", mec="black", mew=1.3, zorder=6)
        if labels:      # outwards, away from the middle of the mechanism
            away = z - middle
            away = away / abs(away) if abs(away) > 0 else 1j
            if name in mech.fixed:      # the ground symbol is below a fixed pivot
                away = complex(-0.8, 0.6) if away.real <= 0 else complex(0.8, 0.6)
            ax.annotate(name, (z.real, z.imag), xytext=(11 * away.real, 11 * away.imag),
                        textcoords="offset points", fontsize=10, fontweight="bold",
                        ha="center", va="center", zorder=7)


GREEK = {"phi": "φ", "theta": "θ", "alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ",
         "psi": "ψ"}


def _greek(name: str) -> str:
    m = re.match(r"^([A-Za-z]+?)(\d*)$", name)
    if m and m.group(1) in GREEK:
        return GREEK[m.group(1)] + m.group(2)
    return name


def polygon_vectors(mech):
    """(label, angle label, tail, head): the exam's vectors z_i.

    The file's angle quantities when it has any (``phi3`` gives ``z3``, from its
    first point to its second); otherwise each link's vectors from its
    alphabetically first vertex to the others, numbered in order.
    """
    angles = [q for q in mech.quantities.values() if q.kind == "angle"]
    if angles:
        digits = [re.match(r"^[A-Za-z_]*?(\d+)$", q.name) for q in angles]
        numbered = all(digits) and len({m.group(1) for m in digits}) == len(digits)
        if numbered:
            pairs = sorted(zip(angles, digits), key=lambda t: int(t[1].group(1)))
            return [(f"z{m.group(1)}", _greek(q.name), q.a, q.b) for q, m in pairs]
        return [(f"z{i + 1}", _greek(q.name), q.a, q.b) for i, q in enumerate(angles)]
    out, seen = [], set()
    for body in mech.bodies.values():
        if body.kind != "link":
            continue
        pts = sorted(body.points)
        for other in pts[1:]:
            if (pts[0], other) not in seen:
                seen.add((pts[0], other))
                out.append((pts[0], other))
    for act in mech.actuators.values():
        a, b = sorted((act.a, act.b))
        if (a, b) not in seen:
            out.append((a, b))
    return [(f"z{i + 1}", f"φ{i + 1}", a, b) for i, (a, b) in enumerate(out)]


def _draw_polygon(ax, scene):
    from matplotlib.patches import Arc
    p, s = scene.p, scene.size
    tails: dict = {}
    for label, angle_name, a, b in polygon_vectors(scene.mech):
        tail, head = p[a], p[b]
        if abs(head - tail) == 0:
            continue
        ax.annotate("", xy=(head.real, head.imag), xytext=(tail.real, tail.imag),
                    arrowprops=dict(arrowstyle="-|>", color=VECTOR, lw=1.6, shrinkA=0,
                                    shrinkB=4, mutation_scale=14), zorder=8)
        mid = (tail + head) / 2
        normal = 1j * (head - tail) / abs(head - tail)
        spot = mid + 0.035 * s * normal
        ax.text(spot.real, spot.imag, label, color=VECTOR, fontsize=10, ha="center",
                va="center", fontstyle="italic", zorder=9)
        count = tails.get(a, 0)
        tails[a] = count + 1
        radius = (0.06 + 0.04 * count) * s
        phi = math.degrees(math.atan2((head - tail).imag, (head - tail).real)) % 360.0
        ax.plot([tail.real, tail.real + 1.25 * radius], [tail.imag, tail.imag], color=VECTOR,
                lw=0.7, ls=":", zorder=8)
        ax.add_patch(Arc((tail.real, tail.imag), 2 * radius, 2 * radius, theta1=0, theta2=phi,
                         color=VECTOR, lw=0.9, zorder=8))
        bis = math.radians(phi / 2)
        where = tail + (radius + 0.035 * s) * complex(math.cos(bis), math.sin(bis))
        ax.text(where.real, where.imag, f"{angle_name} = {phi:.1f}°", color=VECTOR, fontsize=8,
                ha="center", va="center", zorder=9)


def _draw_loads(ax, scene, values, units_text):
    """Forces as arrows onto their points, torques as curved arrows; the unknown in magenta."""
    from matplotlib.patches import Arc
    mech, p, s = scene.mech, scene.p, scene.size
    length = 0.16 * s

    def arrow(point, direction, text, color):
        head = p[point]
        tail = head - length * direction
        ax.annotate("", xy=(head.real, head.imag), xytext=(tail.real, tail.imag),
                    arrowprops=dict(arrowstyle="-|>", color=color, lw=2.2, shrinkA=0, shrinkB=5,
                                    mutation_scale=16), zorder=10)
        ax.text(tail.real, tail.imag, text, color=color, fontsize=9, ha="center",
                va="bottom" if direction.imag <= 0 else "top", zorder=11)

    def torque(center, sign, text, color):
        r = 0.07 * s
        ax.add_patch(Arc((center.real, center.imag), 2 * r, 2 * r, theta1=-60, theta2=200,
                         color=color, lw=2, zorder=10))
        end = math.radians(200 if sign > 0 else -60)
        ray = complex(math.cos(end), math.sin(end))
        tip = center + r * ray
        back = tip - 0.03 * s * (1j if sign > 0 else -1j) * ray
        ax.annotate("", xy=(tip.real, tip.imag), xytext=(back.real, back.imag),
                    arrowprops=dict(arrowstyle="-|>", color=color, lw=2, shrinkA=0, shrinkB=0,
                                    mutation_scale=16), zorder=10)
        ax.text(center.real + r, center.imag + r, text, color=color, fontsize=9, zorder=11)

    d = mech.driver
    for load in mech.loads.values():
        value = values.get(load.name)
        unknown = load.value is None
        color = "#c71585" if unknown else "#1a7f37"
        shown = "?" if value is None else f"{value:.1f}"
        text = f"{load.name} = {shown} {units_text.get(load.name, '')}" + \
            (" (unknown)" if unknown else "")
        sign = 1.0 if value is None or value >= 0 else -1.0
        if load.kind == "force":
            arrow(load.target, load.direction * sign, text, color)
        elif load.kind == "torque" or (load.kind == "driver" and d.kind == "angle"):
            if load.kind == "torque":
                target = load.target
                body = mech.bodies.get(target)
                pts = [p[n] for n in (body.points if body else
                                      (mech.actuators[target].a, mech.actuators[target].b))]
                center = sum(pts) / len(pts)
            else:
                center = p[d.a] if d.a in mech.fixed else p[d.b]
            torque(center, sign, text, color)
        elif load.kind == "driver" and d.kind in ("x", "y"):
            arrow(d.a, (1.0 if d.kind == "x" else 1j) * sign, text, color)
        else:
            a, b = (d.a, d.b) if load.kind == "driver" else \
                (mech.actuators[load.target].a, mech.actuators[load.target].b)
            u = (p[b] - p[a]) / abs(p[b] - p[a])
            for end, direction in ((b, u), (a, -u)):
                tip = p[end]
                tail = tip - 0.6 * length * direction * sign
                ax.annotate("", xy=(tip.real, tip.imag), xytext=(tail.real, tail.imag),
                            arrowprops=dict(arrowstyle="<|-" if sign > 0 else "-|>", color=color,
                                            lw=2, shrinkA=5, shrinkB=0, mutation_scale=14),
                            zorder=10)
            mid = (p[a] + p[b]) / 2
            middle = sum(p[n] for n in mech.points) / len(mech.points)
            side = 1j * u if abs(mid + 1j * u - middle) > abs(mid - 1j * u - middle) else -1j * u
            spot = mid + 0.07 * s * side
            ax.text(spot.real, spot.imag, text, color=color, fontsize=9, ha="center",
                    zorder=11)


def _draw_masses(ax, scene, dyn, pos):
    from .dynamics import rigid_point
    if dyn is None:
        return
    mech, s = scene.mech, scene.size
    for mb in dyn.bodies.values():
        if mb.mass <= 0:
            continue
        g = complex(np.asarray(rigid_point(mech, mb.body, mb.center, pos)[0]).reshape(-1)[0])
        g = g / scene.lf
        ax.plot(g.real, g.imag, "o", ms=9, mfc="white", mec="black", zorder=7)
        ax.plot(g.real, g.imag, "+", ms=9, mec="black", mew=1.2, zorder=7)
        ax.annotate(f"G {mb.body}", (g.real, g.imag), xytext=(-8, -12),
                    textcoords="offset points", fontsize=7, zorder=7)
    for point in dyn.masses:
        z = scene.p[point]
        ax.plot(z.real, z.imag, "o", ms=10, color="black", zorder=7)
    if dyn.gravity:
        xmin, xmax = ax.get_xlim()
        ymin, ymax = ax.get_ylim()
        start = complex(xmin + 0.06 * (xmax - xmin), ymax - 0.06 * (ymax - ymin))
        end = start + 0.1 * s * dyn.gravity / abs(dyn.gravity)
        ax.annotate("", xy=(end.real, end.imag), xytext=(start.real, start.imag),
                    arrowprops=dict(arrowstyle="-|>", color="black", lw=1.5, shrinkA=0,
                                    shrinkB=0), zorder=9)
        ax.annotate("g", (start.real, start.imag), xytext=(6, -4), textcoords="offset points",
                    fontsize=10, zorder=9)


def _limits(ax, points, size, margin=0.22):
    xs = [z.real for z in points]
    ys = [z.imag for z in points]
    pad = margin * size
    ax.set_xlim(min(xs) - pad, max(xs) + pad)
    ax.set_ylim(min(ys) - pad, max(ys) + pad)
    ax.set_aspect("equal", adjustable="box")


def draw(mech, output: str, dpi: int = 100) -> None:
    """The mechanism at the file's driver value, with its vector polygon and loads."""
    from .dynamics import model
    check_output(output, IMAGE_FORMATS)
    dyn = model(mech)
    solver = mech.solver()
    kin = solver.positions(mech.driver.value)
    solver.check(kin, velocities=False)
    scene = _Scene(mech, kin.pos)
    values, units_text = {}, {}
    if mech.loads:
        result = mech.solve(names=list(mech.loads))
        for name in mech.loads:
            if name in result.values:
                values[name] = float(np.asarray(result.values[name]).reshape(-1)[0])
                units_text[name] = result.units[name]
    fig = _figure(8.0, 6.5, dpi)
    ax = fig.add_subplot(1, 1, 1)
    extra = _disc_points(mech, dyn, scene)
    _limits(ax, [scene.p[n] for n in mech.points] + extra, scene.size)
    _draw_mechanism(ax, scene, dyn)
    _draw_polygon(ax, scene)
    _draw_loads(ax, scene, values, units_text)
    _draw_masses(ax, scene, dyn, kin.pos)
    what, q_unit, q_factor = _driver_text(mech)
    ax.set_title(_wrap(mech.title) + f"\nq = {what} = {mech.driver.value / q_factor:.4g} {q_unit}",
                 fontsize=10)
    ax.set_xlabel(f"x [{scene.l_unit}]")
    ax.set_ylabel(f"y [{scene.l_unit}]")
    ax.grid(True, alpha=0.25)
    fig.tight_layout()
    _save(output, lambda tmp, ext: fig.savefig(tmp, format=ext), IMAGE_FORMATS)


def _disc_points(mech, dyn, scene):
    """Extreme points of rolling discs, so that the view holds them."""
    out = []
    if dyn is None:
        return out
    for disc in dyn.discs.values():
        c, r = scene.p[disc.center], disc.radius / scene.lf
        out += [c + r, c - r, c + 1j * r, c - 1j * r]
    return out


# --- animation ---------------------------------------------------------------------------------
def default_sweep(mech) -> str:
    """A full turn from the file's value for an angle driver; other drivers need --sweep."""
    d = mech.driver
    if d.kind != "angle":
        raise InputError("give --sweep FROM:TO:STEPS for a driver that is not an angle",
                         file=mech.file, key="--sweep",
                         hint="driver values in the file's units, inside the assembly range")
    _, unit, factor = _driver_text(mech)
    start = d.value / factor
    turn = 2 * math.pi / factor
    return f"{start}:{start + turn}:72"


def animate(mech, output: str, sweep: str | None = None, fps: int = 12, dpi: int = 80) -> int:
    """The motion over ``sweep`` as an animated GIF (pillow writer); returns the frame count."""
    from .dynamics import model
    check_output(output, ("gif",))
    dyn = model(mech)
    if sweep is None:
        q = parse_sweep(default_sweep(mech))[:-1]       # a full turn: the last frame is the first
    else:
        q = parse_sweep(sweep)
    base = "angle" if mech.driver.kind == "angle" else "length"
    _, q_factor = mech.units.display(base, 0)
    solver = mech.solver()
    kin = solver.positions(q * q_factor)
    solver.check(kin, velocities=False)
    spins = _disc_turns(mech, dyn, kin)
    every = []
    for i in range(q.size):
        scene = _Scene(mech, kin.pos, i)
        every += [scene.p[n] for n in mech.points] + _disc_points(mech, dyn, scene)
    size = max(max(z.real for z in every) - min(z.real for z in every),
               max(z.imag for z in every) - min(z.imag for z in every), 1e-300)
    what, q_unit, _ = _driver_text(mech)
    fig = _figure(6.4, 4.8, dpi)
    ax = fig.add_subplot(1, 1, 1)

    def write(tmp, ext):
        from matplotlib.animation import PillowWriter
        writer = PillowWriter(fps=fps)
        with writer.saving(fig, tmp, dpi):
            for i in range(q.size):
                ax.clear()
                scene = _Scene(mech, kin.pos, i)
                scene.size = size
                _limits(ax, every, size, margin=0.08)
                _draw_mechanism(ax, scene, dyn, labels=True,
                                spins={n: float(v[i]) for n, v in spins.items()})
                ax.set_title(f"q = {what} = {q[i]:.4g} {q_unit}", fontsize=9)
                ax.set_xlabel(f"x [{scene.l_unit}]")
                ax.grid(True, alpha=0.25)
                writer.grab_frame()

    _save(output, write, ("gif",))
    return int(q.size)


def _disc_turns(mech, dyn, kin):
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
