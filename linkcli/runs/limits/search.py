"""The search for the extremes of a quantity over a range of the driver: the zeros of its rate.

A quantity N(q) is extreme where its rate dN/dq is zero and changes sign: a maximum where
dN/dq goes from + to - as q grows, a minimum from - to +.  The rate is sampled on a grid of
GRID intervals over the range (a full turn of an angle driver by default, the turn's
assembled part for a rocker driver); every sign change is refined by Brent's method on the
solver's exact rate, to XTOL of the driver's display unit.  The rates solved:

- N a position quantity (coordinate, angle, length, projection, rotation ...):
  dN/dq = Ndot / qdot, solved at qdot = 1;
- N the rate Xdot of one (xBdot, phi3dot): dN/dq = Xddot / qdot at the driver's rate and
  qddot = 0, the driver turning at constant speed as the textbooks' crank;
- N a speed |v_P| (or |v_B - v_A|): d(|v|^2 / 2)/dq = (xdot xddot + ydot yddot) / qdot, of
  the sign of d|v|/dq and smooth where v = 0 (a speed's minima at the dead centres).

Zero up to rounding: a sampled rate has no sign where it is within the rounding it carries
(``kinematics.toggles.negligible``, the rule the dyads' toggles use), that is TOGGLE times the
quantity's scale per radian of the driver (its square for a speed), amplified by
1 / m^(level + 2) at a position whose smallest conditioning is m (level 0 for a position
quantity, whose rate is a velocity; 1 for a rate, whose rate is an acceleration): the
rounding of the positions next to a toggle, carried into the rates.  Samples whose rate is
rounding are a dwell, or over the whole range a constant (``runs.limits.dwell``); a
quantity without a sign change is told in words (``runs.limits.monotonic``).  A sign change
through a jump of the rate (above POLE of its run's largest) is not an extreme.  From the
extremes follow the stroke (``runs.limits.strokes``) and, over a full turn of a crank, the
time ratio (``runs.limits.quick_return``).
"""
from __future__ import annotations

import math

import numpy as np

from linkcli.answers import quantities
from linkcli.errors import SolveError
from linkcli.kinematics import toggles
from linkcli.model.mechanism import split_rate
from linkcli.runs.limits import dwell, monotonic, quick_return, strokes
from linkcli.runs.limits.extremes import Extreme, Limits, num
from linkcli.runs.limits.names import driver_span, target
from linkcli.runs.sweep.blocks import mechanism_size, sweep

#: grid intervals over the range: extremes closer together than a grid step are not told apart
GRID = 3600
#: the driver value of an extreme is found to XTOL of the driver's display unit
XTOL = 1e-10
#: a refined zero whose rate is above POLE times the largest of its run is a jump, not a zero
POLE = 1e-6
SPEEDS = ("speed", "relative_speed")


class _Probe:
    """The names to solve for N and its rate dN/dq (display units of N per driver unit;
    for a speed, a function of the same sign and zeros)."""

    def __init__(self, mech, quantity, order, name, qdot=None, method="closed", tol=None):
        self.mech, self.name, self.method, self.tol = mech, name, method, tol
        units = mech.units
        base = mech.driver.base
        self.q_factor = units.display(base, 0)[1]
        rate_factor = units.display(base, 1)[1]
        self.qdot_si = mech.driver.rate if qdot is None else qdot * rate_factor
        #: 0 for a position quantity (its rate is a velocity), 1 for a rate or a speed
        self.level = level = order + (1 if quantity.kind in SPEEDS else 0)
        if level == 1 and self.qdot_si == 0:
            raise SolveError(f"the driver's rate is 0, so '{name}' is 0 at every position and "
                             "has no extremes", file=mech.file,
                             hint="give the driver a rate (driver: rate:)")
        # the driver's rate the names are solved at (display units): 1 SI unit per second
        # for a position quantity, whose value does not depend on it
        self.speed = self.qdot_si if level == 1 else 1.0
        self.qdot = self.speed / rate_factor
        if quantity.kind in SPEEDS:
            ends = [quantity.a] if quantity.kind == "speed" else [quantity.a, quantity.b]
            self.parts = [[axis + p + suffix for p in ends] for axis in "xy"
                          for suffix in ("dot", "ddot")]
            self.names = [name] + [n for part in self.parts for n in part]
        else:
            base_name = split_rate(name, mech.quantities)[0]
            self.rate_name = base_name + ("dot", "ddot")[order]
            self.parts = None
            self.names = [name, self.rate_name]

    def rate(self, values):
        """dN/dq from solved ``values`` (for a speed: d(|v|^2/2)/dq)."""
        if self.parts is None:
            slope = np.asarray(values[self.rate_name], float)
        else:
            def relative(part):
                return values[part[-1]] - (values[part[0]] if len(part) == 2 else 0.0)
            xd, xdd, yd, ydd = (np.asarray(relative(p), float) for p in self.parts)
            slope = xd * xdd + yd * ydd
        return slope / self.speed * self.q_factor

    def solve(self, q, names):
        return quantities.evaluate(self.mech, q=np.asarray(q, float), qdot=self.qdot, qddot=0.0,
                                   names=names, method=self.method, tol=self.tol)

    def rate_at(self, q: float) -> float:
        result = self.solve(np.array([q]), self.names[1:])
        return float(np.ravel(self.rate(result.values))[0])


def find(mech, name, start=None, stop=None, *, qdot=None, method="closed", tol=None,
         key="--of", line=None, grid=GRID) -> Limits:
    """The extremes of the quantity ``name`` for q in ``start``..``stop`` (display units; a
    full turn by default), with its stroke, and its time ratio over a full turn."""
    quantities.require_driver(mech, "finding the limits of the motion")
    quantity, order = target(mech, name, key, line)
    start, stop, periodic = driver_span(mech, start, stop, key=key if key != "--of" else
                                        "--from", line=line)
    probe = _Probe(mech, quantity, order, name, qdot, method, tol)
    q_unit = mech.units.display(mech.driver.base, 0)[0]
    turn = stop - start if periodic else (
        2 * math.pi / probe.q_factor if mech.driver.base == "angle" else None)
    q = start + (stop - start) * np.arange(grid + 1) / grid
    swept = sweep(mech, q, probe.names, method=method, tol=tol, qdot=probe.qdot,
                   qddot=0.0)
    found = Limits(name, swept.units.get(name, ""), q_unit, start, stop, periodic, turn)
    found.notes = [issue.text() for issue in swept.issues]
    found.position = order == 0 and quantity.kind not in SPEEDS
    found.whole = bool(swept.solved.all())
    rows = np.nonzero(swept.solved)[0]
    values = {n: np.asarray(v, float) for n, v in swept.values.items()}
    conditioning = np.asarray(swept.conditioning, float)
    period = quantities.angle_period(mech, name, found.unit)
    roots, levels, scales = [], [], []
    natural = _natural(mech, quantity, order, probe)
    per_q = probe.q_factor / (1.0 if mech.driver.base == "angle" else
                              mechanism_size(mech))
    for where, turns in _runs(rows, grid, periodic, found.whole):
        picked = np.searchsorted(rows, where)
        qs = q[where] + turns * (turn or 0.0)
        slope = probe.rate({n: v[picked] for n, v in values.items()})
        shown = values[name][picked]
        level = shown if period is None else np.unwrap(shown, period=period)
        levels.append((qs, level))
        m = conditioning[picked]
        zero = toggles.negligible(slope, _rounding(probe, level, natural, per_q, m))
        held = dwell.held(probe, shown, level, natural, m) if zero.all() else None
        scales.append((qs, shown, level, held))
        if held is None:
            roots += _refine(probe, qs, slope, zero, found, lambda part: dwell.held(
                probe, shown[part], level[part], natural, m[part]))
    roots = _distinct(roots, start, turn if periodic else None, (stop - start) / grid)
    if roots:
        at = np.array([r for r, *_ in roots])
        result = probe.solve(at, [name])
        shown = np.ravel(result.values[name]) + 0 * at
        found.unit = result.units[name]
        for (r, kind, span, held), value in zip(roots, shown):
            value = float(value) if held is None else held
            found.extremes.append(Extreme(float(r), value, kind,
                                          _level(levels, r, value, period, turn), span))
    found.constant = None if found.extremes else dwell.constant(scales, period)
    found.why = "" if found.extremes or found.constant is not None else monotonic.why(found, scales)
    strokes.stroke(found)
    quick_return.sweeps(found, probe.q_factor, probe.qdot_si)
    return found


def _rounding(probe, level, natural, per_q, conditioning):
    """The rounding each sampled rate dN/dq carries (display units of N per display unit of
    q): TOGGLE's scale for ``toggles.negligible``, the quantity's size (its largest value
    over the run, at least its natural size) per radian of the driver, squared for a speed
    (whose rate is that of |v|^2 / 2), over m^(level + 2) with m the sample's conditioning."""
    size = max(float(np.max(np.abs(level))) if level.size else 0.0, natural)
    scale = (size * size if probe.parts is not None else size) * per_q
    return scale / np.maximum(conditioning, toggles.EPS) ** (probe.level + 2)



def _runs(rows, grid, periodic, whole):
    """(grid indices, turns to add to q) of every run of consecutive solved grid values.
    Over a whole turn the run goes on past its end (two more values a turn later), so that a
    sign change at the seam is seen; over a turn with gaps, the run that ends the turn goes
    on into the one that starts it."""
    if rows.size == 0:
        return []
    if periodic and whole:
        where = np.concatenate([rows, rows[1:3]])
        return [(where, np.concatenate([np.zeros(rows.size), np.ones(where.size - rows.size)]))]
    cuts = np.nonzero(np.diff(rows) > 1)[0] + 1
    parts = np.split(rows, cuts)
    runs = [(part, np.zeros(part.size)) for part in parts]
    if periodic and len(parts) > 1 and parts[0][0] == 0 and parts[-1][-1] == grid:
        first, last = parts[0][1:], parts[-1]
        runs = runs[1:-1] + [(np.concatenate([last, first]),
                              np.concatenate([np.zeros(last.size), np.ones(first.size)]))]
    return runs


def _refine(probe, qs, slope, zero, found, held) -> list:
    """(q, 'maximum' or 'minimum', None, None) of every sign change of ``slope`` over the
    run ``qs`` (``zero``: the samples whose rate is rounding, which have no sign), refined
    by Brent's method on the exact rate; (first q, kind, (first, last), value) of a dwell,
    two or more samples of rounding between a rising and a falling part, whose value
    ``held(slice)`` gives from its samples."""
    if qs.size < 2:
        return []
    from scipy.optimize import brentq
    scale = float(np.max(np.abs(slope)))
    sign = np.where(zero, 0, np.sign(slope))
    signed = np.nonzero(sign)[0]
    out = []
    for j, k in zip(signed[:-1], signed[1:]):
        if sign[j] == sign[k]:
            continue
        kind = "maximum" if sign[j] > 0 else "minimum"
        if k - j > 2:
            out.append((float(qs[j + 1]), kind, (float(qs[j + 1]), float(qs[k - 1])),
                        held(slice(j + 1, k))))
            continue
        a, b = float(qs[j]), float(qs[k])
        fa, fb = probe.rate_at(a), probe.rate_at(b)
        if not fa * fb < 0:          # the grid's signs are those of the exact rate
            continue
        root = brentq(probe.rate_at, a, b, xtol=XTOL, rtol=4 * np.finfo(float).eps,
                      maxiter=200)
        if abs(probe.rate_at(root)) > POLE * scale:
            found.notes.append(f"d({probe.name})/dq changes sign by a jump at q = "
                               f"{num(root)} {found.q_unit}, not through 0: not an extreme")
            continue
        out.append((root, kind, None, None))
    return out


def _distinct(roots, start, turn, step):
    """The roots in driver order, each once (a turn's seam is seen twice), in
    [start, start + turn) over a full turn (a dwell's stretch moved with its start)."""
    out = []
    for root, kind, span, held in roots:
        if turn is not None:
            moved = start + (root - start) % turn
            if moved >= start + turn - XTOL:
                moved = start
            span = None if span is None else (moved, moved + span[1] - span[0])
            root = moved
        if not any(abs(root - r) < 1e-3 * step or (turn is not None and abs(
                abs(root - r) - turn) < 1e-3 * step) for r, *_ in out):
            out.append((root, kind, span, held))
    return sorted(out, key=lambda r: r[0])


def _level(levels, root, value, period, turn):
    """The value at ``root`` along the motion (an angle unwrapped as its run's samples)."""
    if period is None:
        return value
    for qs, level in levels:
        for shift in (0.0, turn or 0.0, -(turn or 0.0)):
            r = root + shift
            if qs[0] <= r <= qs[-1]:
                j = int(np.argmin(np.abs(qs - r)))
                return float(level[j] + (value - level[j] + period / 2) % period - period / 2)
    return value


def _natural(mech, quantity, order, probe) -> float:
    """A natural size of the quantity (display units): a turn for an angle, the figure's size
    for a length, and those times the driver's speed for their rates."""
    units = mech.units
    pos = mech.figure_points
    size = max((abs(p - pos[0]) for p in pos), default=1.0) or 1.0
    angle = quantity.angular or quantity.kind == "q" and mech.driver.base == "angle"
    base = "angle" if angle else "length"
    level = order + (1 if quantity.kind in SPEEDS else 0)
    si = 2 * math.pi if angle else size
    if level:
        driver_angle = mech.driver.base == "angle"
        si = abs(probe.qdot_si) * ((size if not angle else 1.0) if driver_angle else
                                   (1.0 if not angle else 1.0 / size))
    return si / units.display(base, level)[1]
