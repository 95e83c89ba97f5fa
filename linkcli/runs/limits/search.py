"""Limit positions and extremes of a quantity over a range of the driver.

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
rounding of the positions next to a toggle, carried into the rates.  A quantity whose every
sampled rate is rounding is constant: its maximum and minimum are that constant (the stroke
0), and where it is (at_maximum) is every position, which is refused, never a position that
rounding picked.  A stretch of two or more samples whose rate is rounding, between a rising
and a falling part, is an extreme held over that stretch (a dwell): its value is given with
the stretch, and its position refused the same way.

From the extremes: the stroke, greatest maximum - least minimum (of an angle, its swing along
the motion); for a crank making full turns, with one maximum and one minimum, the driver's
sweeps d1 + d2 = one turn between them, the time ratio max(d1, d2) / min(d1, d2) (the longer
sweep is the working stroke) and the stroke times d / |qdot|.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

import numpy as np

from linkcli.answers import quantities
from linkcli.runs import sweep as sweep_mod
from linkcli.answers.formats import csv_text, fmt
from linkcli.errors import Caution, InputError, SolveError
from linkcli.kinematics import toggles
from linkcli.model.mechanism import limit_refusal, split_rate

#: grid intervals over the range: extremes closer together than a grid step are not told apart
GRID = 3600
#: the driver value of an extreme is found to XTOL of the driver's display unit
XTOL = 1e-10
#: a refined zero whose rate is above POLE times the largest of its run is a jump, not a zero
POLE = 1e-6
SPEEDS = ("speed", "relative_speed")
#: what a limit quantity of each kind is, in messages
WORDS = {"maximum": "the maximum", "minimum": "the minimum", "at_maximum": "where the maximum is",
         "at_minimum": "where the minimum is", "stroke": "the stroke",
         "time_ratio": "the time ratio", "stroke_time": "the stroke time"}


@dataclass(frozen=True)
class Extreme:
    """A stationary point of a quantity: driver value and value, display units."""

    q: float
    value: float
    kind: str                   # 'maximum' | 'minimum'
    level: float = field(default=0.0, compare=False)   # the value along the motion (unwrapped)
    #: (first, last) driver value of a dwell: the value held, to rounding, over that stretch
    span: tuple | None = field(default=None, compare=False)

    def where(self) -> str:
        """Its driver value, or the stretch of a dwell."""
        return _num(self.q) if self.span is None else f"{_num(self.span[0])}..{_num(self.span[1])}"


@dataclass
class Limits:
    """The extremes of the quantity ``name`` over the driver range ``start``..``stop``."""

    name: str
    unit: str
    q_unit: str
    start: float
    stop: float
    periodic: bool                                   # the range is one full turn
    turn: float | None = None                        # one turn, display units (angle driver)
    extremes: list = field(default_factory=list)     # [Extreme], by driver value
    stroke: float | None = None                      # greatest maximum - least minimum
    sweeps: tuple | None = None                      # (working, return) driver sweeps
    times: tuple | None = None                       # (working, return) strokes' times, s
    notes: list = field(default_factory=list)        # what could not be solved, with where
    why: str = ""                                    # why there is no extreme, when none
    whole: bool = True                               # every grid value assembled
    position: bool = True                            # a position quantity: it has strokes
    constant: float | None = None                    # the value, where constant to rounding

    @property
    def time_ratio(self) -> float | None:
        return None if self.sweeps is None else self.sweeps[0] / self.sweeps[1]

    def range_text(self) -> str:
        return f"q = {_num(self.start)}..{_num(self.stop)} {self.q_unit}"

    def of(self, kind: str) -> list:
        return [e for e in self.extremes if e.kind == kind]


def _num(x: float) -> str:
    return f"{x:.10g}"


# --- what is asked ---------------------------------------------------------------------------
def target(mech, name, key="--of", line=None):
    """(quantity, order) of ``name``, whose extremes are asked; refused when the file does
    not define it or it has no rate to find them from."""
    if not isinstance(name, str) or not name:
        raise InputError(f"expected a quantity name, got {name!r}", file=mech.file, key=key,
                         line=line)
    base, order = split_rate(name, mech.quantities)
    quantity = mech.quantities.get(base)
    if quantity is None:
        raise InputError(f"'{name}' is not a quantity of this file", file=mech.file, key=key,
                         line=line, hint="defined: " + sweep_mod.listing(sorted(mech.quantities)))
    refusal = limit_refusal(name, quantity, order)
    if refusal:
        raise InputError(refusal, file=mech.file, key=key, line=line,
                         hint="ask for a position or velocity quantity: a coordinate, an "
                         "angle, a speed, or the rate of one, e.g. xBdot")
    return quantity, order


def driver_span(mech, start=None, stop=None, key="--from", line=None):
    """(start, stop, periodic) in the driver's display unit: a full turn of an angle driver
    when no range is given; ``periodic`` when the range is one turn."""
    units = mech.units
    q_unit, q_factor = units.display(mech.driver.base, 0)
    turn = 2 * math.pi / q_factor if mech.driver.base == "angle" else None

    def refuse(detail, hint=None):
        return InputError(detail, file=mech.file, key=key, line=line, hint=hint)

    if start is None and stop is None:
        if turn is None:
            raise refuse("the driver is a length, which has no natural range: give the range "
                         "of q", hint="--from A --to B, or from: and to: in the quantity, in "
                         f"{q_unit}")
        return 0.0, turn, True
    if start is None or stop is None:
        raise refuse("give both ends of the range of q", hint="--from A --to B")
    if not (math.isfinite(start) and math.isfinite(stop)) or not start < stop:
        raise refuse(f"the range of q goes from a smaller to a larger value, got "
                     f"{_num(start)}..{_num(stop)} {q_unit}", hint="e.g. --from 0 --to 360")
    if turn is not None and stop - start > turn * (1 + 1e-12):
        raise refuse(f"the range {_num(start)}..{_num(stop)} {q_unit} is longer than a turn "
                     f"({_num(turn)} {q_unit}): the motion repeats", hint="give one turn at most")
    periodic = turn is not None and abs(stop - start - turn) <= 1e-12 * turn
    return start, stop, periodic


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


# --- the search ------------------------------------------------------------------------------
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
    swept = sweep_mod.sweep(mech, q, probe.names, method=method, tol=tol, qdot=probe.qdot,
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
                              sweep_mod.mechanism_size(mech))
    for where, turns in _runs(rows, grid, periodic, found.whole):
        picked = np.searchsorted(rows, where)
        qs = q[where] + turns * (turn or 0.0)
        slope = probe.rate({n: v[picked] for n, v in values.items()})
        shown = values[name][picked]
        level = shown if period is None else np.unwrap(shown, period=period)
        levels.append((qs, level))
        m = conditioning[picked]
        zero = toggles.negligible(slope, _rounding(probe, level, natural, per_q, m))
        held = _held(probe, shown, level, natural, m) if zero.all() else None
        scales.append((qs, shown, level, held))
        if held is None:
            roots += _refine(probe, qs, slope, zero, found, lambda part: _held(
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
    found.constant = None if found.extremes else _constant(scales, period)
    found.why = "" if found.extremes or found.constant is not None else _why(found, scales)
    _strokes(found, probe)
    return found


def _rounding(probe, level, natural, per_q, conditioning):
    """The rounding each sampled rate dN/dq carries (display units of N per display unit of
    q): TOGGLE's scale for ``toggles.negligible``, the quantity's size (its largest value
    over the run, at least its natural size) per radian of the driver, squared for a speed
    (whose rate is that of |v|^2 / 2), over m^(level + 2) with m the sample's conditioning."""
    size = max(float(np.max(np.abs(level))) if level.size else 0.0, natural)
    scale = (size * size if probe.parts is not None else size) * per_q
    return scale / np.maximum(conditioning, toggles.EPS) ** (probe.level + 2)


def _held(probe, shown, level, natural, conditioning) -> float:
    """The value a run constant to rounding holds: the middle of its samples, 0 where that
    is itself rounding (TOGGLE of the quantity's size over m^(level + 1), the rounding of
    a value of that order next to a toggle), so noise such as 1e-10 is never a value."""
    value = float(np.median(shown))
    size = max(float(np.max(np.abs(level))), natural)
    least = max(float(np.min(conditioning)), toggles.EPS)
    return 0.0 if toggles.negligible(value, size / least ** (probe.level + 1)) else value


def _constant(scales, period) -> float | None:
    """The value of a quantity constant (to rounding) over every run of the range, when all
    the runs hold the same value to 1e-9 of it; None otherwise."""
    held = [value for *_, value in scales]
    if not held or any(value is None for value in held):
        return None
    gap = np.abs(np.array(held) - held[0])
    if period is not None:
        gap = np.minimum(gap, period - gap % period)
    size = max(float(np.max(np.abs(held))), 1e-300)
    return held[0] if float(np.max(gap)) <= 1e-9 * size else None


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
                               f"{_num(root)} {found.q_unit}, not through 0: not an extreme")
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


def _why(found, scales) -> str:
    """Why ``found`` has no extreme: the quantity is constant, or it only rises or falls."""
    if not scales:
        return "the mechanism cannot be assembled anywhere in the range"
    parts = []
    for qs, shown, level, held in scales:
        if held is not None:
            parts.append(f"it is constant ({fmt(held, 4)} {found.unit}) for q in "
                         f"{_num(qs[0])}..{_num(qs[-1])} {found.q_unit}")
            continue
        last = qs.size - 1
        end = _num(qs[last])
        if qs[last] > found.stop and found.periodic:     # a run across the turn's end
            end = f"{_num(qs[last] - found.turn)} (through {_num(found.stop)})"
        elif qs[last] > found.stop:
            inside = qs <= found.stop
            last = int(np.nonzero(inside)[0][-1]) if inside.any() else last
            end = _num(qs[last])
        trend = "rises" if level[last] > level[0] else "falls"
        parts.append(f"its rate d({found.name})/dq keeps its sign: it {trend} from "
                     f"{fmt(shown[0], 4)} to {fmt(shown[last], 4)} {found.unit} (by "
                     f"{fmt(abs(level[last] - level[0]), 4)}) as q goes from {_num(qs[0])} to "
                     f"{end} {found.q_unit}")
    return "; ".join(parts)


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


def _strokes(found: Limits, probe) -> None:
    """The stroke from the extremes (0 for a constant); over a whole turn with one maximum
    and one minimum, neither a dwell, the driver's sweeps of the working and return strokes
    and their times."""
    maxima, minima = found.of("maximum"), found.of("minimum")
    if found.constant is not None and found.position:
        found.stroke = 0.0
    if not maxima or not minima or not found.position:
        return
    found.stroke = max(e.level for e in maxima) - min(e.level for e in minima)
    if not (found.periodic and found.whole and len(maxima) == 1 and len(minima) == 1) or \
            maxima[0].span is not None or minima[0].span is not None:
        return
    rise = (maxima[0].q - minima[0].q) % found.turn
    sweeps = sorted([rise, found.turn - rise], reverse=True)
    found.sweeps = tuple(sweeps)
    if probe.qdot_si != 0:
        found.times = tuple(s * probe.q_factor / abs(probe.qdot_si) for s in sweeps)


# --- named quantities of the report ----------------------------------------------------------
def is_limit(mech, name) -> bool:
    return getattr(mech.quantities.get(name), "limit", False)


def pointwise(mech, names):
    """``names`` without the limits of the motion (one value for a range, not a function of
    the driver): what a sweep can list."""
    return [n for n in names if not is_limit(mech, n)]


def evaluate(mech, q=None, qdot=None, qddot=None, names=None, method="closed", tol=None):
    """The report's values (``answers.quantities.evaluate``) with its limits of the motion,
    each one value for its range, repeated at every driver value of ``q``."""
    names = list(names) if names is not None else quantities.report_names(mech)
    others = pointwise(mech, names)
    result = quantities.evaluate(mech, q, qdot, qddot, names=others, method=method, tol=tol)
    found = {}
    values, units = {}, {}
    for name in names:
        if name in others:
            values[name], units[name] = result.values[name], result.units[name]
            continue
        quantity = mech.quantities[name]
        span = quantity.span or (None, None)
        key = (quantity.a, span)
        if key not in found:
            found[key] = find(mech, quantity.a, *span, qdot=qdot, method=method, tol=tol,
                              key=f"quantities.{name}", line=quantity.line)
            if not found[key].whole:
                result.cautions.append(Caution(
                    "limits", f"the limits of {quantity.a} are over the part of "
                    f"{found[key].range_text()} where the mechanism assembles: "
                    + "; ".join(found[key].notes), mech.file))
        value, unit = answer(mech, quantity, found[key])
        values[name] = np.asarray(value + 0 * np.asarray(result.kinematics.q, float)) + 0.0
        units[name] = unit
    result.values, result.units = values, dict(result.units, **units)
    return result


def answer(mech, quantity, found: Limits):
    """(value, unit) of the limit ``quantity`` from the extremes ``found``; a located
    SolveError when it is not defined (no such extreme, no full turn, no driver rate)."""
    kind, of = quantity.kind, quantity.a

    def undefined(detail, hint=None):
        return SolveError(f"'{quantity.name}' ({WORDS[kind]} of {of}) is undefined: {detail}",
                          file=mech.file, key=f"quantities.{quantity.name}", line=quantity.line,
                          hint=hint)

    if found.constant is not None:
        return _of_constant(found, kind, undefined)
    if not found.extremes:
        raise undefined(f"{of} has no extreme over {found.range_text()}: {found.why}" +
                        "".join(f"; {note}" for note in found.notes),
                        hint="ask for a quantity that goes back and forth")
    for wanted in ("maximum", "minimum"):
        if not found.of(wanted) and (kind in (wanted, "at_" + wanted) or kind not in (
                "maximum", "minimum", "at_maximum", "at_minimum")):
            other = "minimum" if wanted == "maximum" else "maximum"
            raise undefined(f"{of} has no {wanted} over {found.range_text()}, only a {other}"
                            f" at q = {', '.join(_num(e.q) for e in found.of(other))} "
                            f"{found.q_unit}")
    if kind in ("maximum", "minimum", "at_maximum", "at_minimum"):
        wanted = kind.replace("at_", "")
        some = found.of(wanted)
        pick = _first_extreme(some, wanted)
        if kind.startswith("at_"):
            if pick.span is not None:
                raise undefined(f"{of} holds its {wanted} ({fmt(pick.value, 4)} {found.unit}) "
                                f"over q = {pick.where()} {found.q_unit} (its rate is 0 to "
                                "rounding there), not at one position",
                                hint=f"ask for the {wanted} itself")
            return pick.q, found.q_unit
        return pick.value, found.unit
    if kind == "stroke":
        return found.stroke, found.unit
    if found.sweeps is None:
        raise undefined(_no_ratio(found), hint="the time ratio is of a crank making full turns")
    if kind == "time_ratio":
        return found.time_ratio, ""
    if found.times is None:
        raise undefined("the driver's rate is 0", hint="give the driver a rate (driver: rate:)")
    return found.times[0 if quantity.component == "working" else 1], "s"


def _of_constant(found: Limits, kind: str, undefined):
    """(value, unit) of a limit of a quantity constant to rounding: its maximum and minimum
    are the constant, its stroke 0; where they are, or a time ratio, is refused."""
    value = f"{fmt(found.constant, 4)} {found.unit}".rstrip()
    if kind in ("maximum", "minimum"):
        return found.constant, found.unit
    if kind == "stroke" and found.stroke is not None:
        return found.stroke, found.unit
    what = "its maximum and minimum are at every position" if kind.startswith("at_") else \
        "it has no strokes"
    raise undefined(f"{found.name} is constant ({value}) over {found.range_text()}, its rate "
                    f"0 to rounding: {what}", hint="ask for the maximum or minimum itself")


def _first_extreme(some: list, wanted: str) -> Extreme:
    """The greatest maximum (least minimum); of several equal to rounding (1e-9 of the
    largest value), the first in driver order (a speed's two equal maxima)."""
    sign = 1.0 if wanted == "maximum" else -1.0
    best = max(sign * e.level for e in some)
    size = max(abs(e.level) for e in some)
    return next(e for e in some if sign * e.level >= best - 1e-9 * size)


def _no_ratio(found: Limits) -> str:
    if not found.periodic:
        return f"the range {found.range_text()} is not a full turn of the crank"
    if not found.whole:
        return ("the crank cannot make a full turn: " + "; ".join(found.notes))
    held = [e for e in found.extremes if e.span is not None]
    if held and len(found.extremes) == 2:
        return (f"{found.name} holds its {held[0].kind} over q = {held[0].where()} "
                f"{found.q_unit}: the strokes have no single start")
    return (f"{found.name} has {len(found.extremes)} extremes over the turn (at q = "
            f"{', '.join(e.where() for e in found.extremes)} {found.q_unit}), not one maximum "
            "and one minimum")


# --- the limits command's output -------------------------------------------------------------
def rows(found: Limits, decimals: int) -> list:
    """(quantity, what, q, value, unit) rows of ``found``, as text."""
    out = []
    if found.constant is not None:
        out.append((found.name, "constant", f"{fmt(found.start, decimals)}..{fmt(found.stop, decimals)}",
                    fmt(found.constant, decimals), found.unit))
    for e in found.extremes:
        where = fmt(e.q, decimals) if e.span is None else \
            f"{fmt(e.span[0], decimals)}..{fmt(e.span[1], decimals)}"
        out.append((found.name, e.kind, where, fmt(e.value, decimals), found.unit))
    if found.stroke is not None:
        out.append((found.name, "stroke", "", fmt(found.stroke, decimals), found.unit))
    if found.sweeps is not None:
        out.append((found.name, "time_ratio", "", fmt(found.time_ratio, decimals), ""))
        for i, what in enumerate(("working_stroke", "return_stroke")):
            time = "" if found.times is None else fmt(found.times[i], decimals)
            out.append((found.name, what, fmt(found.sweeps[i], decimals), time,
                        "s" if time else ""))
    return out


def messages(found_list) -> list:
    """What to tell besides the rows, each once: the ranges that cannot be solved, the
    quantities without an extreme."""
    out = [f"over {found.range_text()}, {note}" for found in found_list for note in found.notes]
    out += [f"'{found.name}' has no extreme over {found.range_text()}: {found.why}"
            for found in found_list if not found.extremes and found.constant is None]
    return list(dict.fromkeys(out))


def as_dict(found: Limits) -> dict:
    return {"quantity": found.name, "unit": found.unit, "q_unit": found.q_unit,
            "from": found.start, "to": found.stop, "full_turn": found.periodic,
            "constant": found.constant,
            "extremes": [{"kind": e.kind, "q": e.q, "value": e.value,
                          "span": None if e.span is None else list(e.span)}
                         for e in found.extremes],
            "stroke": found.stroke, "time_ratio": found.time_ratio,
            "sweeps": None if found.sweeps is None else {"working": found.sweeps[0],
                                                          "return": found.sweeps[1]},
            "times": None if found.times is None else {"working": found.times[0],
                                                        "return": found.times[1]},
            "messages": messages([found])}


def render(found_list, form: str, decimals: int) -> str:
    """The limits of every quantity of ``found_list`` as a table, JSON or CSV."""
    if form == "json":
        return json.dumps([as_dict(f) for f in found_list], indent=2)
    q_unit = found_list[0].q_unit if found_list else ""
    header = ["quantity", "what", f"q [{q_unit}]", "value", "unit"]
    body = [row for found in found_list for row in rows(found, decimals)]
    if form == "csv":
        return csv_text(header, body).rstrip("\n")
    from tabulate import tabulate
    return tabulate(body, headers=header, disable_numparse=True)


def sweep_names(mech, names, key="--names"):
    """The names a sweep lists: ``names`` (None: the report's) without the limits of the
    motion, which are one value for a range; asking a sweep for one is refused."""
    if names is None:
        report = quantities.report_names(mech)
        if not any(is_limit(mech, n) for n in report):
            return None
        return pointwise(mech, report) or ["q"]
    for name in names:
        if is_limit(mech, name):
            raise InputError(f"'{name}' is a limit of the motion, one value for the whole range "
                             "of the driver, not a function of it", file=mech.file, key=key,
                             hint=f"print it with 'linkcli solve' or 'linkcli limits --of "
                             f"{mech.quantities[name].a}'")
    return names


def default_names(mech) -> list:
    """What ``linkcli limits`` looks at without --of: the quantities the report's limits are
    of, else the report's position and velocity quantities that have a rate (the driver's own
    angle left out)."""
    report = quantities.report_names(mech)
    asked = [mech.quantities[n].a for n in report if is_limit(mech, n)]
    if asked:
        return list(dict.fromkeys(asked))
    driver = mech.driver
    names = []
    for name in report:
        base, order = split_rate(name, mech.quantities)
        quantity = mech.quantities.get(base)
        if quantity is None or limit_refusal(name, quantity, order) or quantity.kind == "q" or (
                quantity.kind == "angle" and (quantity.a, quantity.b) == (driver.a, driver.b)):
            continue
        names.append(name)
    if not names:
        raise InputError("the report has no quantity to find the extremes of", file=mech.file,
                         key="--of", hint="name one: --of xB")
    return names
