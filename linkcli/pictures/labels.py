"""Labels apart: every text of a drawn axes moved, where it must, to a spot where it is
read whole, on no other label, on no drawn stroke and inside the picture.

A label is tried where it was drawn, then at candidate spots on rings around it
(:data:`DIRECTIONS` a ring, the rings :data:`STEP` font sizes apart), scored by its
collisions: with the labels placed before it, with every stroke of the axes (lines,
outlines, arcs, arrows, markers; a stroke may reach :data:`CLEAR` font sizes into the
label's box at the top or bottom and :data:`CLEAR_SIDE` at its sides, so that a label
may touch the line it names) and with the edge (the axes' frame where the axes are
shown, else the figure).  The nearest free spot is taken.  A
label moved further than :data:`LEADER` font sizes gets a thin leader line back to the
point it names (an annotation's point, else where it was drawn), and its spot must
leave that line off the other labels; where the point is hemmed in by labels, the
nearest spot free without a leader is taken.  Where a label finds room only beyond the
edge, the view is widened across that edge (:data:`WIDEN`, at most :data:`WIDENINGS`
times) and every label is placed again; a view is never widened for crowding, which it
would only make worse.  After that, the spot of fewest collisions is taken.
Everything is in pixels of the figure as it is saved: call :func:`place_labels` once
the axes' layout is final.
"""
from __future__ import annotations

import functools

import numpy as np

GAP = 2.0               # pixels kept between two labels, and between a label and the edge
STEP = 0.4              # font sizes between two rings of candidate spots
RINGS = 24              # rings tried around a label (twice as many where none is free)
DIRECTIONS = 16         # candidate spots a ring
CLEAR = 0.15            # font sizes a stroke may reach into a label's box, at the top or bottom
CLEAR_SIDE = 0.05       # and at its left or right side, where its letters begin
LEADER = 1.6            # font sizes moved beyond which a leader line is drawn
WIDEN = 0.12            # of the view, added on each side when a label finds no spot
WIDENINGS = 3
LEADER_GID = "leader"


def label_boxes(ax, renderer=None) -> list:
    """(text artist, its bounding box in pixels) of every label drawn on ``ax``."""
    renderer = renderer or ax.figure.canvas.get_renderer()
    return [(t, t.get_window_extent(renderer)) for t in ax.texts
            if t.get_visible() and t.get_text().strip()]


# --- strokes as segments -------------------------------------------------------------------
def _polyline_segments(xy):
    xy = np.asarray(xy, float)
    if len(xy) == 1:
        return np.hstack([xy, xy])
    return np.hstack([xy[:-1], xy[1:]])


def strokes(ax, renderer) -> tuple:
    """(segments, pads): every stroke drawn on ``ax`` as straight pieces in pixels, an
    (n, 4) array of x0, y0, x1, y1, with half each one's width; a marker is a piece of
    zero length as wide as the marker; curves are flattened as rendered."""
    from matplotlib.lines import Line2D
    from matplotlib.text import Annotation
    per_point = ax.figure.dpi / 72.0
    pieces, pads = [], []

    def add(segments, half_width):
        if len(segments):
            pieces.append(segments)
            pads.append(np.full(len(segments), half_width))

    def add_path(path, transform, width):
        for poly in transform.transform_path(path).to_polygons(closed_only=False):
            if len(poly):
                add(_polyline_segments(poly), 0.5 * width * per_point)

    for artist in list(ax.lines) + list(ax.patches):
        if not artist.get_visible():
            continue
        if isinstance(artist, Line2D):
            xy = artist.get_transform().transform(artist.get_xydata())
            if artist.get_linestyle() not in ("None", "none", "", " ") and len(xy) > 1:
                add(_polyline_segments(xy), 0.5 * artist.get_linewidth() * per_point)
            if artist.get_marker() not in (None, "None", "none", "", " "):
                add(np.hstack([xy, xy]), 0.5 * (artist.get_markersize() +
                                                artist.get_markeredgewidth()) * per_point)
        elif artist.get_linewidth() > 0:
            add_path(artist.get_path(), artist.get_transform(), artist.get_linewidth())
    for text in ax.texts:
        if isinstance(text, Annotation) and text.arrow_patch is not None:
            text.draw(renderer)     # the arrow's head takes its size in pixels when drawn
            arrow = text.arrow_patch
            add_path(arrow.get_path(), arrow.get_transform(), arrow.get_linewidth())
    if not pieces:
        return np.zeros((0, 4)), np.zeros(0)
    return np.vstack(pieces), np.concatenate(pads)


def crossing(boxes, segments, pads):
    """For each box (x0, y0, x1, y1 in pixels, an (m, 4) array): whether a segment, widened
    by its pad, passes through it."""
    if segments.shape[0] == 0:
        return np.zeros(len(boxes), bool)
    return hits(boxes, segments, pads).any(axis=-1)


def hits(boxes, segments, pads):
    """(m, n): whether segment j, widened by its pad, passes through box i (Liang-Barsky:
    the part of the segment P0 + t (P1 - P0), t in [0, 1], inside the box is not empty)."""
    boxes = np.asarray(boxes, float)[:, None, :]
    x0, y0, x1, y1 = (segments[None, :, i] for i in range(4))
    lo_x, lo_y = boxes[..., 0] - pads, boxes[..., 1] - pads
    hi_x, hi_y = boxes[..., 2] + pads, boxes[..., 3] + pads
    dx, dy = x1 - x0, y1 - y0
    t0 = np.zeros(np.broadcast(lo_x, x0).shape)
    t1 = np.ones_like(t0)
    outside = np.zeros(t0.shape, bool)
    for p, q in ((-dx, x0 - lo_x), (dx, hi_x - x0), (-dy, y0 - lo_y), (dy, hi_y - y0)):
        p = np.broadcast_to(p, t0.shape)
        q = np.broadcast_to(q, t0.shape)
        flat = p == 0
        outside |= flat & (q < 0)
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.where(flat, 0.0, q / np.where(flat, 1.0, p))
        t0 = np.where(~flat & (p < 0), np.maximum(t0, r), t0)
        t1 = np.where(~flat & (p > 0), np.minimum(t1, r), t1)
    return ~outside & (t0 <= t1)


# --- candidate spots -------------------------------------------------------------------------
def _moves(size, rings):
    """(m, 2) pixel moves: none first, then ``rings`` rings outwards."""
    return _unit_moves(rings) * (STEP * size)


@functools.lru_cache(maxsize=None)
def _unit_moves(rings):
    angles = 2 * np.pi * np.arange(DIRECTIONS) / DIRECTIONS
    ring = np.stack([np.cos(angles), np.sin(angles)], axis=1)
    steps = np.repeat(np.arange(1, rings + 1), DIRECTIONS)[:, None]
    return np.vstack([np.zeros((1, 2)), steps * np.tile(ring, (rings, 1))])


def _overlaps(boxes, others):
    """For each of ``boxes`` (m, 4): how many of ``others`` (k, 4) it overlaps."""
    if len(others) == 0:
        return np.zeros(len(boxes), int)
    b, o = boxes[:, None, :], np.asarray(others)[None, :, :]
    return ((b[..., 0] < o[..., 2]) & (o[..., 0] < b[..., 2]) &
            (b[..., 1] < o[..., 3]) & (o[..., 1] < b[..., 3])).sum(axis=1)


class _Layout:
    """The labels placed so far on one axes, the strokes and the frame they keep off."""

    def __init__(self, ax, renderer, frame):
        self.ax, self.frame = ax, frame
        self.segments, self.pads = strokes(ax, renderer)
        self.placed = []

    def costs(self, boxes, size, anchor):
        """(collisions of each candidate box: labels 10, the edge 10, strokes 1; whether
        its leader line, from ``anchor`` when the box is far, crosses a placed label)."""
        inner = boxes + size * np.array([CLEAR_SIDE, CLEAR, -CLEAR_SIDE, -CLEAR])
        on_lines = crossing(inner, self.segments, self.pads).astype(int)
        padded = boxes + np.array([-GAP, -GAP, GAP, GAP])
        on_labels = _overlaps(padded, self.placed)
        f = self.frame
        out = (boxes[:, 0] < f[0]) | (boxes[:, 1] < f[1]) | (boxes[:, 2] > f[2]) | \
            (boxes[:, 3] > f[3])
        leader = np.zeros(len(boxes), int)
        placed = self.open_at(anchor)
        if len(placed):
            ends = _nearest(boxes, anchor)
            seg = np.hstack([np.broadcast_to(anchor, ends.shape), ends])
            far = np.hypot(*(ends - anchor).T) > LEADER * size
            leader[far] = hits(placed, seg[far], np.zeros(far.sum())).any(axis=0)
        return 10 * on_labels + 10 * out + on_lines, leader, out

    def open_at(self, anchor):
        """The placed labels' boxes, (0, 4) where one covers ``anchor``: a leader line from
        there would start on a label, so none is drawn."""
        placed = np.asarray(self.placed).reshape(-1, 4)
        covered = ((placed[:, 0] <= anchor[0]) & (anchor[0] <= placed[:, 2]) &
                   (placed[:, 1] <= anchor[1]) & (anchor[1] <= placed[:, 3])).any()
        return placed[:0] if covered else placed

    def near(self, region):
        """This layout with only the strokes whose extent meets ``region`` (a box)."""
        seg, pad = self.segments, self.pads
        keep = ((np.minimum(seg[:, 0], seg[:, 2]) - pad <= region[2]) &
                (np.maximum(seg[:, 0], seg[:, 2]) + pad >= region[0]) &
                (np.minimum(seg[:, 1], seg[:, 3]) - pad <= region[3]) &
                (np.maximum(seg[:, 1], seg[:, 3]) + pad >= region[1]))
        local = _Layout.__new__(_Layout)
        local.ax, local.frame, local.placed = self.ax, self.frame, self.placed
        local.segments, local.pads = seg[keep], pad[keep]
        return local

    def add_leader(self, anchor, end, color):
        """A thin line from ``anchor`` to ``end`` (pixels); later labels keep off it."""
        inverse = self.ax.transData.inverted()
        (x0, y0), (x1, y1) = inverse.transform([anchor, end])
        self.ax.plot([x0, x1], [y0, y1], color=color, lw=0.6, zorder=6, gid=LEADER_GID)
        self.segments = np.vstack([self.segments, [[*anchor, *end]]])
        self.pads = np.append(self.pads, 0.3 * self.ax.figure.dpi / 72.0)


def _nearest(boxes, point):
    """The point of each box (m, 4) nearest ``point``, pulled GAP pixels out of the box
    towards it."""
    x = np.clip(point[0], boxes[:, 0] - GAP, boxes[:, 2] + GAP)
    y = np.clip(point[1], boxes[:, 1] - GAP, boxes[:, 3] + GAP)
    return np.stack([x, y], axis=1)


def _anchor(ax, text):
    """The pixel point a label names: an annotation's point, else where it was drawn."""
    from matplotlib.text import Annotation
    if isinstance(text, Annotation) and text.xycoords == "data":
        return np.asarray(ax.transData.transform(text.xy))
    return np.asarray(text.get_transform().transform(text.get_position()))


def frame_of(ax, renderer, inset=GAP):
    """The box labels stay in (x0, y0, x1, y1 pixels): the axes' frame where the axes are
    shown, else the figure, ``inset`` pixels inside."""
    b = ax.get_window_extent(renderer) if ax.axison else ax.figure.bbox
    return np.array([b.x0 + inset, b.y0 + inset, b.x1 - inset, b.y1 - inset])


# --- placing -----------------------------------------------------------------------------------
def place_labels(ax) -> int:
    """Move the labels of ``ax`` apart (see the module); the view is widened where some
    label finds no free spot.  Returns how many labels still collide (0 when all fit)."""
    ax.apply_aspect()           # an equal-aspect axes takes its final box only when drawn
    renderer = ax.figure.canvas.get_renderer()
    start = [(t, _offset(t)) for t, _ in label_boxes(ax, renderer)]
    for attempt in range(WIDENINGS + 1):
        left, frame = _place_once(ax, renderer)
        if not any(_across(left, frame)) or attempt == WIDENINGS:
            return len(left)
        for line in [line for line in ax.lines if line.get_gid() == LEADER_GID]:
            line.remove()
        for text, offset in start:
            _set_offset(text, offset)
        _widen(ax, left, frame)
        ax.apply_aspect()
    return len(left)


def _place_once(ax, renderer):
    """(boxes of the labels that found no free spot, the frame)."""
    layout = _Layout(ax, renderer, frame_of(ax, renderer))
    left = []
    for text, box in label_boxes(ax, renderer):
        size = text.get_fontsize() * ax.figure.dpi / 72.0
        here = np.array([box.x0, box.y0, box.x1, box.y1])
        anchor = _anchor(ax, text)
        move, cost, led, wish = _best_move(layout, here, size, anchor)
        box = here + np.hstack([move, move])
        if cost > 0:
            left.append(box if wish is None else here + np.hstack([wish, wish]))
        if move[0] or move[1]:
            _shift(ax, text, *move)
        end = _nearest(box[None, :], anchor)[0]
        if led and np.hypot(*(end - anchor)) > LEADER * size and \
                len(layout.open_at(anchor)) == len(layout.placed):
            layout.add_leader(anchor, end, text.get_color())
        layout.placed.append(box)
    return left, layout.frame


RING_GROUPS = ((0, 0), (1, 3), (4, 8), (9, 16), (17, RINGS), (RINGS + 1, 2 * RINGS))


def _best_move(layout, here, size, anchor):
    """(move in pixels, its collisions, whether a leader line may be drawn, a move that
    would be free beyond the edge or None): the nearest spot free with its leader line,
    ring group by ring group (most labels are free where they were drawn); else the
    nearest free spot without a leader (one would cross a label: the label's own point is
    hemmed in); else the spot of fewest collisions."""
    moves = _moves(size, 2 * RINGS)
    rings = np.concatenate([[0], np.repeat(np.arange(1, 2 * RINGS + 1), DIRECTIONS)])
    reach = 2 * RINGS * STEP * size + size
    local = layout.near(here + np.array([-reach, -reach, reach, reach]))
    fewest, unled, wish = None, None, None
    for first, last in RING_GROUPS:
        chosen = moves[(rings >= first) & (rings <= last)]
        cost, leader, out = local.costs(here + np.hstack([chosen, chosen]), size, anchor)
        nearer = np.hypot(*chosen.T) / (10 * RINGS * STEP * size)
        score = cost + 10 * leader + nearer
        i = int(np.argmin(score))
        if score[i] < 1:
            return chosen[i], 0, True, None
        if fewest is None or score[i] < fewest[0]:
            fewest = (score[i], chosen[i], cost[i] + 10 * leader[i])
        free = np.nonzero(cost == 0)[0]
        if unled is None and len(free):
            unled = chosen[free[np.argmin(nearer[free])]]
        beyond = np.nonzero(out & (cost == 10))[0]
        if wish is None and len(beyond):
            wish = chosen[beyond[np.argmin(nearer[beyond])]]
    if unled is not None:
        return unled, 0, False, None
    return fewest[1], fewest[2], True, wish


def _across(boxes, frame):
    """(whether a box crosses the left or right edge, the bottom or top edge)."""
    boxes = np.asarray(boxes).reshape(-1, 4)
    return (bool((boxes[:, 0] < frame[0]).any() or (boxes[:, 2] > frame[2]).any()),
            bool((boxes[:, 1] < frame[1]).any() or (boxes[:, 3] > frame[3]).any()))


def _widen(ax, boxes, frame):
    """Widen the view on both sides across the edges that ``boxes`` cross (a view widened
    for labels that lie on each other or on strokes would only crowd them more)."""
    across_x, across_y = _across(boxes, frame)
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    dx, dy = WIDEN * (x1 - x0) * across_x, WIDEN * (y1 - y0) * across_y
    ax.set_xlim(x0 - dx, x1 + dx)
    ax.set_ylim(y0 - dy, y1 + dy)


def _offset(text):
    from matplotlib.text import Annotation
    if isinstance(text, Annotation) and text.anncoords == "offset points":
        return tuple(text.xyann)
    return tuple(text.get_position())


def _set_offset(text, value):
    from matplotlib.text import Annotation
    if isinstance(text, Annotation) and text.anncoords == "offset points":
        text.xyann = value
    else:
        text.set_position(value)


def _shift(ax, text, dx, dy):
    """Move ``text`` by (dx, dy) pixels: its offset for an annotation in offset points,
    else its position in data coordinates."""
    from matplotlib.text import Annotation
    if isinstance(text, Annotation) and text.anncoords == "offset points":
        scale = 72.0 / ax.figure.dpi
        x, y = text.xyann
        text.xyann = (x + dx * scale, y + dy * scale)
        return
    x, y = ax.transData.transform(text.get_position())
    text.set_position(ax.transData.inverted().transform((x + dx, y + dy)))
