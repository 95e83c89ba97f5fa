"""What a reader of a figure sees: the labels of a matplotlib figure measured as it is
saved, against each other, against every drawn stroke and against the figure's edge.

This measure is the tests' own: it shares no code with the placement of the labels
(linkcli/pictures/labels.py), so that a placement that measures wrongly cannot pass it.
Everything is in pixels of the figure at its own dpi, after ``canvas.draw()``:

- a label is every non-empty visible text of an axes (names, dimensions, loads, data);
  its box is ``get_window_extent`` of the rendered text;
- two labels overlap when their boxes share any area;
- a stroke is every drawn line, outline, arc, arrow (annotation arrows included) and
  marker, as rendered: its path in pixels sampled every pixel, each sample widened by
  half the line width (markers: a disc of their size); fills are not strokes (a text on
  a light, translucent plate stays readable);
- a label sits on a stroke when a sample falls inside its box shrunk by ``TOLERANCE``
  times its font size at the top and bottom (the blank of the line's ascent and descent)
  and ``ACROSS`` times at the sides (where the first and last letters begin): a stroke
  may graze the edge of the label that names it, never cross its letters;
- a label is cut when its box leaves the figure, or the axes' frame where the axes are
  shown (ticks and their numbers lie outside it).
"""
from __future__ import annotations

import numpy as np

TOLERANCE = 0.25        # of the font size: how far a stroke may reach into a label's box
ACROSS = 0.1            # from its left or right side (the letters begin at the box's sides)


def _pixels(fig, points):
    return points * fig.dpi / 72.0


def labels(ax, renderer):
    """(text, box as x0, y0, x1, y1 pixels, font size in pixels) of every label of ``ax``."""
    out = []
    for t in ax.texts:
        if not t.get_visible() or not t.get_text().strip():
            continue
        b = t.get_window_extent(renderer)
        out.append((t, np.array([b.x0, b.y0, b.x1, b.y1]),
                    _pixels(ax.figure, t.get_fontsize())))
    return out


def _sampled(polyline):
    """Points along a polyline, one every pixel or closer."""
    pts = [polyline[:1]]
    for a, b in zip(polyline[:-1], polyline[1:]):
        n = int(np.ceil(np.hypot(*(b - a)))) + 1
        pts.append(a + np.linspace(0.0, 1.0, n + 1)[1:, None] * (b - a))
    return np.vstack(pts)


def _path_samples(path, transform):
    """Samples of a path's rendered outline (curves flattened) in pixels."""
    shown = transform.transform_path(path)
    polys = shown.to_polygons(closed_only=False)
    return [_sampled(np.asarray(p, float)) for p in polys if len(p)]


def strokes(ax, renderer):
    """(samples, pads): every drawn stroke of ``ax`` sampled in pixels, with the half width
    (pixels) that each sample covers."""
    from matplotlib.lines import Line2D
    from matplotlib.text import Annotation
    fig = ax.figure
    samples, pads = [], []

    def add(points, pad):
        for p in points:
            samples.append(p)
            pads.append(np.full(len(p), pad))

    for artist in list(ax.lines) + list(ax.patches):
        if not artist.get_visible():
            continue
        if isinstance(artist, Line2D):
            xy = artist.get_transform().transform(artist.get_xydata())
            if artist.get_linestyle() not in ("None", "", " ", "none") and len(xy) > 1:
                add([_sampled(xy)], 0.5 * _pixels(fig, artist.get_linewidth()))
            if artist.get_marker() not in (None, "None", "", " ", "none"):
                add([xy], 0.5 * _pixels(fig, artist.get_markersize() +
                                        artist.get_markeredgewidth()))
            continue
        if artist.get_linewidth() > 0 and artist.get_edgecolor()[3] > 0:
            add(_path_samples(artist.get_path(), artist.get_transform()),
                0.5 * _pixels(fig, artist.get_linewidth()))
    for text in ax.texts:
        arrow = getattr(text, "arrow_patch", None) if isinstance(text, Annotation) else None
        if arrow is not None and arrow.get_visible() and text.get_visible():
            add(_path_samples(arrow.get_path(), arrow.get_transform()),
                0.5 * _pixels(fig, arrow.get_linewidth()))
    if not samples:
        return np.zeros((0, 2)), np.zeros(0)
    return np.vstack(samples), np.concatenate(pads)


def frame_of(ax, renderer):
    """The box a label must stay in: the axes' frame where it is shown, else the figure."""
    if ax.axison:
        b = ax.get_window_extent(renderer)
    else:
        b = ax.figure.bbox
    return np.array([b.x0, b.y0, b.x1, b.y1])


def defects(fig) -> list[str]:
    """What a reader would find wrong with ``fig`` as saved: each label cut, each pair of
    labels that overlap, each label sitting on a stroke (see the module)."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    found = []
    for ax in fig.axes:
        boxes = labels(ax, renderer)
        frame = frame_of(ax, renderer)
        points, pads = strokes(ax, renderer)
        for i, (text, box, size) in enumerate(boxes):
            name = repr(text.get_text())
            if box[0] < frame[0] - 0.5 or box[1] < frame[1] - 0.5 or \
                    box[2] > frame[2] + 0.5 or box[3] > frame[3] + 0.5:
                found.append(f"{name} cut by the edge")
            for other, b, _ in boxes[:i]:
                if box[0] < b[2] and b[0] < box[2] and box[1] < b[3] and b[1] < box[3]:
                    found.append(f"{name} over {other.get_text()!r}")
            inner = box + size * np.array([ACROSS, TOLERANCE, -ACROSS, -TOLERANCE])
            if len(points) and inner[0] < inner[2] and inner[1] < inner[3]:
                inside = ((points[:, 0] + pads > inner[0]) & (points[:, 0] - pads < inner[2]) &
                          (points[:, 1] + pads > inner[1]) & (points[:, 1] - pads < inner[3]))
                if inside.any():
                    found.append(f"{name} on a drawn line")
    return found
