"""One solve as a single loop over the positions, compiled when the ``jit`` extra is there.

At a few hundred positions a NumPy solve is a few hundred operations on short arrays, each
costing about a microsecond whatever it computes; the same arithmetic done position by
position in compiled code costs a few nanoseconds an operation.  This module writes the
common closed-form groups as a *program* of numbers, and the values asked for as *probes*,
and runs them in one function, :func:`_run`, position by position:

- ``CRANK``: P = pivot + L e^{i q}; P' = i q' (P - pivot) + pivot',
  P'' = (i q'' - q'^2)(P - pivot) + pivot'' (the driver, one coordinate);
- ``RRR``: P on the circles |P - A| = r1, |P - B| = r2 (fixed lengths), as
  :func:`dyads.circle_circle`: P = A + (B - A)(t + i branch s);
- ``CIRCLE_LINE``: P on |P - A| = r and on a guide through fixed points (RRP, PRR), as
  :func:`dyads.circle_line`;
- ``PLACE``: P = K + (M - N) w, a point fixed to a body;
- ``LINE_DRIVER``: P on a guide through fixed points with its x (or y) the coordinate q
  (a slider or an actuator's end driven along its guide);

the rates of a dyad from its 2x2 system Re(conj(G_i) P') = r_i (``rates``' module
docstring), with G = 2 (P - A) for a circle and the constant G = i (C - B) (r = 0) for the
fixed guide.  Probes: the angle of z = P_b - P_a in [0, 2 pi) (or (-pi, pi]) and its
rates Im w, Im(z''/z) - 2 Re w Im w with w = z'/z; its length |z| and rates |z| Re w,
|z| (Re(z''/z - w^2) + (Re w)^2); a point's x or y and their rates; each over its
display factor.

The loop refuses, and the caller then solves with NumPy (which words the error or decides
the close case), wherever a position is not clearly regular: a discriminant within twice
the rounding bound the NumPy groups use for a toggle, coincident centres, a rate system
whose conditioning is under ``SINGULAR``, a probe's vector of zero length, a value that is
not finite.  Anything else the solver does (other groups, several coordinates, driven
lengths, moving guides, rolling contacts) is not written as a program: ``program_of``
returns None.

:func:`_run` is plain Python in the subset numba compiles.  ``LINKCLI_JIT=1`` in the
environment and numba installed (``pip install linkcli[jit]``): the first solve compiles it
(cached on disk by numba), and every evaluation of a plan it can express runs it.  Without
either, nothing is imported and nothing changes.  The compiled loop and NumPy agree to
rounding (the same formulas, in another order for a few of them).
"""
from __future__ import annotations

import math
import os

import numpy as np

from linkcli.kinematics.rates import constant_norms, fixed_guide
from linkcli.kinematics.dyads import ROUNDING, TOGGLE
from linkcli.kinematics.groups import Dist
from linkcli.kinematics.refusals import SINGULAR

#: group kinds of a program
CRANK, RRR, CIRCLE_LINE, PLACE, LINE_DRIVER = 1, 2, 3, 4, 5
#: probe kinds
ANGLE, X, Y, LENGTH = 1, 2, 3, 4
TWO_PI = 2 * math.pi
#: an angle within this of 2 pi is 0 (as ``answers.quantities.wrap_angle``)
WRAP = 1e-12

_state: dict = {}


class Program:
    """A solver's groups as numbers, in the solving order: ``ops`` rows (kind, P, A, B,
    branch, extra) and ``par`` rows of parameters (see :func:`_row`); ``x0``, ``y0``
    every point's coordinates (the fixed ones' values); ``index`` point name -> column.
    (A plain class: a dataclass would add a millisecond to every command's start-up.)"""

    __slots__ = ("ops", "par", "x0", "y0", "index")

    def __init__(self, ops, par, x0, y0, index):
        self.ops, self.par, self.x0, self.y0, self.index = ops, par, x0, y0, index

    def probes(self, rows):
        """(kinds, factors) of probes ``rows`` = [(kind, a, b, order, factor, signed)] with
        point names; None when a row names a point the program does not place."""
        kinds = np.zeros((len(rows), 5), np.int64)
        factors = np.empty(len(rows))
        for r, (kind, a, b, order, factor, signed) in enumerate(rows):
            if a not in self.index or (b is not None and b not in self.index):
                return None
            kinds[r] = (kind, self.index[a], -1 if b is None else self.index[b], order,
                        int(signed))
            factors[r] = factor
        return kinds, factors

    def run(self, probes, q, qd, qdd, order, out, kernel=None) -> bool:
        """Solve at driver values ``q`` (a 1-D array, SI) with rates ``qd``, ``qdd`` (numbers
        or arrays like ``q``) as far as ``order``, writing the probes into the rows of
        ``out`` (probes x positions); False where the loop refuses (the values written are
        then not answers).  ``kernel``: the loop to run (default the compiled one; None
        when it is not on)."""
        kernel = kernel or compiled()
        if kernel is None:
            return False
        rates = [np.ascontiguousarray(np.atleast_1d(x), dtype=float) for x in (qd, qdd)]
        kinds, factors = probes
        if any(r.ndim != 1 or r.size not in (1, q.size) for r in rates) or \
                not out.flags.c_contiguous or out.shape != (len(kinds), q.size):
            return False
        return kernel(np.ascontiguousarray(q, dtype=float), rates[0], rates[1], int(order),
                      self.ops, self.par, self.x0, self.y0, kinds, factors, out) == 0


def program_of(solver) -> Program | None:
    """The :class:`Program` of a closed-form solver, None when a group is not one of the
    module's kinds."""
    if solver.n != 1 or getattr(solver, "groups", None) is None:
        return None
    fixed = solver.fixed
    names = list(fixed) + [g.point for g in solver.groups if g.point is not None]
    index = {name: i for i, name in enumerate(dict.fromkeys(names))}
    ops, par = [], []
    for group in solver.groups:
        if group.point is None:
            continue
        row = _row(group, fixed, solver)
        if row is None:
            return None
        kind, a, b, extra, params = row
        ops.append([kind, index[group.point], index[a], index[b], group.branch,
                    index[extra] if isinstance(extra, str) else extra])
        par.append(list(params) + [0.0] * (PARAMETERS - len(params)))
    x0 = np.zeros(len(index))
    y0 = np.zeros(len(index))
    for name, z in fixed.items():
        x0[index[name]], y0[index[name]] = complex(z).real, complex(z).imag
    return Program(np.array(ops, np.int64).reshape(-1, 6),
                   np.array(par, float).reshape(-1, PARAMETERS), x0, y0, index)


#: parameters of a group in a program's ``par``
PARAMETERS = 11


def _row(group, fixed, solver):
    """(kind, A, B, extra, parameters) of one group (A, B, extra: point names; extra of a
    circle and a guide: 1 when the guide is the first constraint), None for another kind.

    Parameters: CRANK (L), A the pivot; PLACE (Re w, Im w), A = K, B = M, extra N; RRR
    (r1, r2, |G_1| |G_2|, driven 1, driven 2), A and B the centres; CIRCLE_LINE (r, Re B,
    Im B, Re u, Im u, e, Re G, Im G, |G_1| |G_2|, driven, |B| + |e|), A the centre;
    LINE_DRIVER (Re B, Im B, Re u, Im u, e, Re G, Im G, |G_1| |G_2|), extra 0 for x and 1
    for y.  u, e: the guide's frame, G = i (C - B) its constant gradient; |G_1| |G_2| is 0
    where it varies (a driven length: computed at each position); a length driven by q
    is 1 in its 'driven' column."""
    kind = group.kind
    if kind == "driver-angle":
        pivot, length, reverse = group.constraints
        if group.coord != 0:
            return None
        return CRANK, pivot, pivot, 0, [-length if reverse else length]
    if kind == "place":
        k, m, n, w = group.place
        return PLACE, k, m, n, [complex(w).real, complex(w).imag]
    if kind == "driver-coord":
        line, coord = group.constraints
        if coord.coord != 0 or not fixed_guide(line, group.point, fixed):
            return None
        return LINE_DRIVER, group.point, group.point, int(coord.axis != "x"), \
            _guide(line, fixed, solver) + [_norms(group, fixed)]
    if kind not in ("RRR", "RRP", "PRR"):
        return None
    c1, c2 = group.constraints
    if kind == "RRR":
        if any(c.length is None and c.coord != 0 for c in (c1, c2)):
            return None
        return RRR, c1.a, c2.a, 0, [_length(c1), _length(c2), _norms(group, fixed),
                                    _driven(c1), _driven(c2)]
    dist, line = (c1, c2) if kind == "RRP" else (c2, c1)
    if not (isinstance(dist, Dist) and fixed_guide(line, group.point, fixed)) or \
            (dist.length is None and dist.coord != 0):
        return None
    guide = _guide(line, fixed, solver)
    bx, by, e = guide[0], guide[1], guide[4]
    return CIRCLE_LINE, dist.a, dist.a, int(kind == "PRR"), \
        [_length(dist)] + guide + [_norms(group, fixed), _driven(dist),
                                   abs(bx) + abs(by) + abs(e)]


def _guide(line, fixed, solver) -> list:
    """[Re B, Im B, Re u, Im u, e, Re G, Im G] of a guide through fixed points B, C: its
    frame (u, e) and constant gradient G = i (C - B)."""
    u, e = solver._frame(line)
    b, c = complex(fixed[line.b]), complex(fixed[line.c])
    g = 1j * (c - b)
    return [b.real, b.imag, complex(u).real, complex(u).imag, float(e), g.real, g.imag]


def _length(dist) -> float:
    return 0.0 if dist.length is None else float(dist.length)


def _driven(dist) -> float:
    """1 for a distance whose length is the coordinate q (an actuator), else 0."""
    return 1.0 if dist.length is None else 0.0


def _norms(group, fixed) -> float:
    """|G_1| |G_2| where constant (``rates.constant_norms``), else 0: computed at
    each position."""
    norms = constant_norms(group, fixed)
    return 0.0 if norms is None else float(norms)


def compiled():
    """The compiled :func:`_run`, None unless ``LINKCLI_JIT=1`` and numba is installed;
    decided (and compiled) once per process."""
    if "kernel" not in _state:
        _state["kernel"] = _compile() if os.environ.get("LINKCLI_JIT", "0") == "1" else None
    return _state["kernel"]


def switch(on: bool) -> bool:
    """Turn the compiled loop on (where numba is installed and compiles it) or off for this
    process, as ``LINKCLI_JIT`` does at the first solve; whether it is on."""
    _state["kernel"] = _compile() if on else None
    return _state["kernel"] is not None


def _compile():
    """:func:`_run` compiled for its one signature (contiguous arrays), cached on disk by
    numba; None without numba, or where it fails to compile (an optional accelerator never
    stops a solve: the NumPy path is there)."""
    if "compiled" in _state:
        return _state["compiled"]
    _state["compiled"] = None
    try:
        import numba
        from numba import float64 as f, int64 as i
        jit = numba.njit(cache=True, nogil=True, error_model="numpy")
        for name in HELPERS:            # what _run calls is compiled with it
            globals()[name] = jit(globals()[name])
        signature = i(f[::1], f[::1], f[::1], i, i[:, ::1], f[:, ::1], f[::1], f[::1],
                      i[:, ::1], f[::1], f[:, ::1])
        _state["compiled"] = numba.njit(signature, cache=True, nogil=True,
                                        error_model="numpy")(_run)
    except Exception:                   # noqa: BLE001 (ImportError, or numba's own errors)
        pass
    return _state["compiled"]


#: the functions :func:`_run` calls
HELPERS = ("_place", "_velocity_rhs", "_accel_rhs", "_circles", "_circle_guide", "_slide",
           "_angle", "_angle_rate", "_length_rate")


def _run(q, qd, qdd, order, ops, par, x0, y0, probes, factors, out):
    """Solve every position and write the probes (see the module); 0, or 1 where refused.

    The points and their rates live in arrays indexed by the program; the helpers it calls
    take and return numbers only: numba passes an array to a function with reference
    counting, which made the same loop split into functions of arrays five times slower."""
    m = x0.shape[0]
    px, py = x0.copy(), y0.copy()
    vx, vy = np.zeros(m), np.zeros(m)
    ax, ay = np.zeros(m), np.zeros(m)
    nqd, nqdd = qd.shape[0], qdd.shape[0]
    total = 0.0
    for i in range(q.shape[0]):
        qi = q[i]
        w = qd[i if nqd > 1 else 0]
        al = qdd[i if nqdd > 1 else 0]
        if not (math.isfinite(qi) and math.isfinite(w) and math.isfinite(al)):
            return 1
        for g in range(ops.shape[0]):
            kind, p, a, b = ops[g, 0], ops[g, 1], ops[g, 2], ops[g, 3]
            if kind == CRANK:
                length = par[g, 0]
                rx, ry = length * math.cos(qi), length * math.sin(qi)
                px[p], py[p] = px[a] + rx, py[a] + ry
                if order >= 1:
                    vx[p], vy[p] = vx[a] - ry * w, vy[a] + rx * w
                if order >= 2:
                    ax[p] = ax[a] - rx * (w * w) - ry * al
                    ay[p] = ay[a] + rx * al - ry * (w * w)
                continue
            if kind == PLACE:
                c, wx, wy = ops[g, 5], par[g, 0], par[g, 1]
                px[p], py[p] = _place(px, py, a, b, c, wx, wy)
                if order >= 1:
                    vx[p], vy[p] = _place(vx, vy, a, b, c, wx, wy)
                if order >= 2:
                    ax[p], ay[p] = _place(ax, ay, a, b, c, wx, wy)
                continue
            if kind == RRR:
                d1, d2 = par[g, 3] > 0, par[g, 4] > 0      # lengths driven by q
                ok, px[p], py[p] = _circles(px[a], py[a], px[b], py[b],
                                            qi if d1 else par[g, 0], qi if d2 else par[g, 1],
                                            ops[g, 4])
                x1, y1 = 2.0 * (px[p] - px[a]), 2.0 * (py[p] - py[a])
                x2, y2 = 2.0 * (px[p] - px[b]), 2.0 * (py[p] - py[b])
                c1, c2, first = a, b, False
            elif kind == LINE_DRIVER:
                ok, px[p], py[p] = _slide(ops[g, 5], qi, par[g, 0], par[g, 1], par[g, 2],
                                          par[g, 3], par[g, 4])
                x1, y1, norms = par[g, 5], par[g, 6], par[g, 7]
                x2, y2 = (1.0, 0.0) if ops[g, 5] == 0 else (0.0, 1.0)
                c1, c2, first, d1, d2 = p, p, True, False, False
            else:                               # CIRCLE_LINE
                d1 = par[g, 9] > 0
                ok, px[p], py[p] = _circle_guide(px[a], py[a], qi if d1 else par[g, 0],
                                                 ops[g, 4], par[g, 1], par[g, 2], par[g, 3],
                                                 par[g, 4], par[g, 5], par[g, 10])
                x1, y1 = 2.0 * (px[p] - px[a]), 2.0 * (py[p] - py[a])
                x2, y2 = par[g, 6], par[g, 7]
                first, d2 = ops[g, 5] == 1, False
                if first:                       # PRR: the guide is the first constraint
                    x1, y1, x2, y2, d1, d2 = x2, y2, x1, y1, False, d1
                c1, c2 = a, a
            if not ok:
                return 1
            if order < 1:
                continue
            if kind == RRR:
                norms = par[g, 2]
            elif kind == CIRCLE_LINE:
                norms = par[g, 8]
            if norms == 0:                      # a driven length: the gradients' own
                norms = math.hypot(x1, y1) * math.hypot(x2, y2)
                norms = norms if norms > 0 else 1.0
            det = x1 * y2 - y1 * x2
            if not abs(det) / norms >= SINGULAR:
                return 1
            inv = 1.0 / det
            guide = kind != RRR                 # its guide's right-hand side is 0
            r1 = 0.0 if guide and first else _velocity_rhs(x1, y1, vx[c1], vy[c1], d1, qi, w)
            r2 = w if kind == LINE_DRIVER else 0.0 if guide and not first else \
                _velocity_rhs(x2, y2, vx[c2], vy[c2], d2, qi, w)
            vx[p] = r1 * (y2 * inv) + r2 * (y1 * -inv)
            vy[p] = r1 * (x2 * -inv) + r2 * (x1 * inv)
            if order < 2:
                continue
            r1 = 0.0 if guide and first else \
                _accel_rhs(x1, y1, ax[c1], ay[c1], vx[p] - vx[c1], vy[p] - vy[c1], d1, qi, w, al)
            r2 = al if kind == LINE_DRIVER else 0.0 if guide and not first else \
                _accel_rhs(x2, y2, ax[c2], ay[c2], vx[p] - vx[c2], vy[p] - vy[c2], d2, qi, w, al)
            ax[p] = r1 * (y2 * inv) + r2 * (y1 * -inv)
            ay[p] = r1 * (x2 * -inv) + r2 * (x1 * inv)
        for k in range(probes.shape[0]):
            kind, a, b, rate = probes[k, 0], probes[k, 1], probes[k, 2], probes[k, 3]
            if kind == X or kind == Y:
                xs = px if rate == 0 else (vx if rate == 1 else ax)
                ys = py if rate == 0 else (vy if rate == 1 else ay)
                value = xs[a] if kind == X else ys[a]
            elif kind == LENGTH:
                ok, value = _length_rate(px[b] - px[a], py[b] - py[a], vx[b] - vx[a],
                                         vy[b] - vy[a], ax[b] - ax[a], ay[b] - ay[a], rate)
                if not ok:
                    return 1
            elif rate == 0:
                value = _angle(px[b] - px[a], py[b] - py[a], probes[k, 4] == 1)
            else:
                ok, value = _angle_rate(px[b] - px[a], py[b] - py[a], vx[b] - vx[a],
                                        vy[b] - vy[a], ax[b] - ax[a], ay[b] - ay[a], rate)
                if not ok:
                    return 1
            value = value / factors[k] + 0.0
            out[k, i] = value
            total += value
    return 0 if math.isfinite(total) else 1


def _place(xs, ys, k, m, n, wx, wy):
    """K + (M - N) w in components."""
    dx, dy = xs[m] - xs[n], ys[m] - ys[n]
    return xs[k] + (dx * wx - dy * wy), ys[k] + (dx * wy + dy * wx)


def _velocity_rhs(gx, gy, x, y, driven, length, rate):
    """r = Re(conj(G) A') + 2 L L' of |P - A|^2 = L^2 (the last term where L is driven)."""
    r = gx * x + gy * y
    return r + 2.0 * length * rate if driven else r


def _accel_rhs(gx, gy, x, y, dx, dy, driven, length, rate, accel):
    """r = Re(conj(G) A'') + 2 L L'' - 2 |P' - A'|^2 + 2 L'^2 (L's terms where driven);
    (dx, dy) = P' - A'."""
    r = gx * x + gy * y
    if driven:
        r = r + 2.0 * length * accel
    r = r - 2.0 * (dx * dx + dy * dy)
    return r + 2.0 * rate * rate if driven else r


def _circles(ax, ay, bx, by, r1, r2, branch):
    """(ok, P) with |P - A| = r1, |P - B| = r2: P = A + (B - A)(t + i branch s), as
    ``dyads.circle_circle``; not ok where coincident centres or a discriminant within twice
    the rounding bound of its toggle test leave P undecided."""
    dx, dy = bx - ax, by - ay
    d2 = dx * dx + dy * dy
    if not d2 > 0:
        return False, ax, ay
    t = (r1 * r1 - r2 * r2 + d2) / (2.0 * d2)
    across2, along2 = r1 * r1 / d2, t * t
    e = across2 - along2
    reach = (abs(ax) + abs(ay) + abs(bx) + abs(by)) / math.sqrt(d2)
    if not e > 2.0 * TOGGLE * max(across2, along2) * (1.0 + reach):
        return False, ax, ay
    s = math.sqrt(e) if branch > 0 else -math.sqrt(e)
    return True, ax + (dx * t - dy * s), ay + (dx * s + dy * t)


def _circle_guide(ax, ay, r, branch, bx, by, ux, uy, e, reach):
    """(ok, P) with |P - A| = r on the guide through B along u at offset e:
    P = B + (t0 + branch sqrt(r^2 - d^2) + i e) u, as ``dyads.circle_line`` (``reach``:
    |B| + |e|); not ok within twice the rounding bound of its toggle test."""
    relx = (ax - bx) * ux + (ay - by) * uy
    rely = (ay - by) * ux - (ax - bx) * uy
    dist = rely - e
    disc = r * r - dist * dist
    if not disc > 2.0 * TOGGLE * (r * r + r * (abs(ax) + abs(ay) + reach + r)):
        return False, ax, ay
    along = relx + math.sqrt(disc) if branch > 0 else relx - math.sqrt(disc)
    return True, bx + (along * ux - e * uy), by + (along * uy + e * ux)


def _slide(axis, q, bx, by, ux, uy, e):
    """(ok, P) on the guide through B along u at offset e with its x (``axis`` 0) or y = q;
    not ok where the guide runs, within rounding, across that coordinate."""
    sx, sy = bx - e * uy, by + e * ux               # B + i e u
    along = ux if axis == 0 else uy
    if not abs(along) >= ROUNDING:
        return False, sx, sy
    t = (q - sx) / along if axis == 0 else (q - sy) / along
    return True, sx + t * ux, sy + t * uy


def _angle(zx, zy, signed):
    """The angle of z in [0, 2 pi), within 1e-12 of 2 pi being 0 (``signed``: in
    (-pi, pi]), as ``answers.quantities.wrap_angle``."""
    value = math.atan2(zy, zx)
    if value <= 0:
        value += TWO_PI
    if value > TWO_PI - WRAP:
        value = 0.0
    if signed and value > math.pi:
        value -= TWO_PI
    return value


def _angle_rate(zx, zy, wx, wy, sx, sy, rate):
    """(ok, rate) of the angle of z with z' = (wx, wy), z'' = (sx, sy): Im(z'/z) (``rate``
    1) or Im(z''/z) - 2 Re(z'/z) Im(z'/z) (2); not ok where z = 0."""
    n2 = zx * zx + zy * zy
    if not n2 > 0:
        return False, 0.0
    value = (zx * wy - zy * wx) / n2
    if rate == 2:
        value = (zx * sy - zy * sx) / n2 - 2.0 * ((zx * wx + zy * wy) / n2) * value
    return True, value


def _length_rate(zx, zy, wx, wy, sx, sy, rate):
    """(ok, value) of the length of z with z' = (wx, wy), z'' = (sx, sy): |z| (``rate``
    0), |z| Re w (1), |z| (Re(z''/z - w^2) + (Re w)^2) (2) with w = z'/z; not ok where a
    rate of z = 0 is asked."""
    r = math.hypot(zx, zy)
    if rate == 0:
        return True, r
    n2 = zx * zx + zy * zy
    if not n2 > 0:
        return False, 0.0
    wr, wi = (zx * wx + zy * wy) / n2, (zx * wy - zy * wx) / n2
    if rate == 1:
        return True, r * wr
    return True, r * (((zx * sx + zy * sy) / n2 - (wr * wr - wi * wi)) + wr * wr)
