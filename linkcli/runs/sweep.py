"""Sweeps: a range of driver values solved block by block, in vectorised passes.

Driver values are ``q_i = A + i * step`` (computed, never accumulated).  Rows
that cannot be solved are never printed as NaN: positions that cannot be
assembled are reported as ranges of q with the group and its largest
shortfall, and rows where velocities are undefined (a toggle hit exactly) are
left out and reported the same way.  Every other row is printed.

Memory: the driver values are solved in blocks of ``BLOCK`` positions, and
:func:`write` prints each block as soon as it is solved (CSV) or keeps it in a
temporary file (JSON, whose lists are one quantity each, and tables, whose
column widths are known at the end), so that a sweep takes the same memory for
10^4 as for 10^7 positions.  Ranges that cross a block's end are joined: the
reports and every printed digit are those of a sweep solved in one block.

Branches: the closed form keeps each dyad's branch sign chosen at the file's
position; Newton continues the configuration step by step.  Where a group
passes a toggle, its conditioning measure (the sine of the angle between its
constraint normals; for Newton |det J| over the product of the row norms)
touches zero; such a driver value is reported as a branch point, because the
real mechanism may leave there on either branch.  It is found between any two
neighbouring samples: three samples whose middle one dips in a V; two samples
where the angle between the constraint normals heads for 0 or 180 degrees at the
first and comes back from it at the second (their tangents, from the rates, meet
at or near it); for Newton, the sign of det J (the side the dyads close on)
changing; an exact toggle at the first or the last sample.  Each one is then located
on the conditioning itself (``kinematics.toggles.locate``), to the accuracy that module
states, whatever path the solver took to the samples.
"""
from __future__ import annotations

import math
import tempfile
from dataclasses import dataclass, field

import numpy as np

from linkcli.errors import AtRestError, NoWorkError, AssemblyError, InputError, SelfLockingError, \
    SolveError
from linkcli.kinematics import toggles
from linkcli.kinematics.closed_form import Kinematics
from linkcli.kinematics.groups import Dist, Line
from linkcli.kinematics.refusals import SINGULAR
from linkcli.model.mechanism import split_rate
from linkcli.answers.memory import LONG, keep_freed_memory
from linkcli.answers.quantities import needed_orders, plan_for, report_names, require_driver
from linkcli.kinematics.solvers import solver_for

MAX_POSITIONS = 10 ** 7
#: positions solved at once.  Measured on a six-bar, 10^6 positions to JSON: the time is the
#: same within 3 % for blocks of 2^12 to 2^16 positions (10.6 to 10.3 s of CPU), while the
#: peak memory grows with the block (37, 41, 48, 63, 93 MB): larger blocks only fill fresh
#: memory pages.  2^14 is also the Newton solver's batch.  benchmarks/memory.py: the peak
#: does not grow with the sweep's length.
BLOCK = 1 << 14
#: rows formatted at once: their text (Python strings) takes far more memory than the numbers
LINES = 4096
#: names listed at most in a message (then '... and N more')
LISTED = 10


def listing(names, limit: int = LISTED) -> str:
    """'a, b, c' for at most ``limit`` names, then '... and N more' (never quadratic text)."""
    names = list(names)
    shown = ", ".join(names[:limit])
    return shown + (f" ... and {len(names) - limit} more" if len(names) > limit else "")


@dataclass
class Issue:
    """A range of driver values (display units) where something must be said."""

    kind: str            # 'assembly' | 'singular' | 'branch' | 'no-work' | 'at-rest' |
    #                      'self-locking'
    group: str
    lo: float
    hi: float
    count: int
    amount: float        # shortfall (display length; inf: no configuration) or conditioning
    q_unit: str
    l_unit: str
    index: int = field(default=-1, repr=False, compare=False)   # the group's, for sorting
    closure: bool = False   # the amount is Newton's closure error, not links' shortfall

    def text(self) -> str:
        where = (f"at q = {self.lo:.6g} {self.q_unit}" if self.count == 1 or self.lo == self.hi
                 else f"for q in [{self.lo:.6g}, {self.hi:.6g}] {self.q_unit}")
        if self.kind == "assembly":
            why = "no configuration found" if not math.isfinite(self.amount) else \
                f"no convergence, closure error up to {self.amount:.4g} {self.l_unit}" \
                if self.closure else f"links short by up to {self.amount:.4g} {self.l_unit}"
            return f"cannot assemble {where}: {self.group}, {why}"
        if self.kind == "singular":
            return (f"velocities undefined {where}: {self.group} at a toggle (conditioning "
                    f"{self.amount:.2e}); rows left out")
        if self.kind == "no-work":
            return (f"the unknown load {self.group} does no work {where} (a dead centre for "
                    f"it: coefficient {self.amount:.1e} of the largest load's); rows left out")
        if self.kind == "self-locking":
            return (f"the friction locks the mechanism {where} (self-locking, with "
                    f"{self.group}); rows left out")
        if self.kind == "at-rest":
            return (f"{self.group} is undetermined {where}: its pair is at rest (relative "
                    f"rate {self.amount:.1e} of the largest), so the sense of the loss is "
                    "unknown; rows left out")
        return (f"branch point at q = {self.lo:.6g} {self.q_unit}: {self.group} passes a toggle "
                "(its conditioning touches 0); the sweep keeps its branch, the mechanism may "
                "leave on either")

    def as_dict(self) -> dict:
        out = {"kind": self.kind, "group": self.group, "from": self.lo, "to": self.hi,
               "positions": self.count, "message": self.text()}
        if self.kind == "assembly":
            out["shortfall"] = self.amount if math.isfinite(self.amount) else None
            out["unit"] = self.l_unit
        else:
            out["conditioning"] = self.amount
        return out


@dataclass
class Sweep:
    """Solved rows of a sweep (display units) and what could not be solved."""

    mechanism: object
    method: str
    q: np.ndarray                 # every requested driver value
    solved: np.ndarray            # mask of the rows in ``values``
    names: list
    values: dict = field(default_factory=dict)     # name -> array over solved rows
    units: dict = field(default_factory=dict)
    q_unit: str = ""
    issues: list = field(default_factory=list)
    #: the smallest conditioning of the groups at each solved row (1 where none has one)
    conditioning: np.ndarray = field(default_factory=lambda: np.zeros(0))


# --- driver values -------------------------------------------------------------------------
class DriverRange:
    """The driver values ``start + i * delta`` (i < count; the last one ``last`` when given),
    made a block at a time: a 10^7-position sweep never holds them all."""

    def __init__(self, start: float, delta: float, count: int, last: float | None = None):
        self.start, self.delta, self.size, self.last = start, delta, count, last

    def __len__(self) -> int:
        return self.size

    def block(self, lo: int, hi: int) -> np.ndarray:
        q = self.start + np.arange(lo, hi) * self.delta
        if self.last is not None and hi == self.size and hi > lo:
            q[-1] = self.last
        return q

    def __array__(self, dtype=None, copy=None):
        q = self.block(0, self.size)
        return q if dtype is None else q.astype(dtype)


def driver_range(start: float, stop: float, steps: int | None = None,
                 step: float | None = None) -> DriverRange:
    """q_i = start + i * step; ``steps`` intervals (both ends included) or a ``step`` > 0."""
    if (steps is None) == (step is None):
        raise InputError("give either --steps N or --step S", key="--steps",
                         hint="--steps 360 splits the range into 360 intervals")
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise InputError("--from and --to must be finite numbers", key="--from")
    if steps is not None:
        if steps < 1:
            raise InputError(f"--steps must be at least 1, got {steps}", key="--steps")
        count = steps + 1
        delta = (stop - start) / steps
    else:
        if not (math.isfinite(step) and step > 0):
            raise InputError(f"--step must be a positive number, got {step}", key="--step",
                             hint="the direction follows --from and --to")
        span = abs(stop - start)
        count = int(math.floor(span / step * (1 + 1e-12))) + 1 if span / step < 1e12 else \
            MAX_POSITIONS + 1
        delta = math.copysign(step, stop - start) if stop != start else step
    if count > MAX_POSITIONS:
        raise InputError(f"{count} positions is more than the limit of {MAX_POSITIONS}",
                         key="--steps", hint="use fewer steps or split the range")
    return DriverRange(start, delta, count, stop if steps is not None else None)


def driver_values(start: float, stop: float, steps: int | None = None,
                  step: float | None = None) -> np.ndarray:
    """The values of :func:`driver_range` as one array."""
    return np.asarray(driver_range(start, stop, steps, step))


def check_names(mech, names, key: str = "--names") -> list:
    """The report's names, or ``names`` after checking that each is defined (and that
    none is the rate of a load: loads are solved, their rates are not)."""
    if not names:
        return report_names(mech)
    for name in names:
        base, order = split_rate(name, mech.quantities)
        if base not in mech.quantities:
            raise InputError(f"'{name}' is not a quantity of this file", key=key,
                             hint="defined: " + listing(sorted(mech.quantities)))
        if order and mech.quantities[base].kind == "load":
            raise load_rate_error(name, base, key=key)
    return list(names)


def load_rate_error(name, base, **where) -> InputError:
    """``name`` asks for the rate of the load ``base``, which linkcli does not compute."""
    return InputError(f"'{name}' is a rate of the load '{base}': linkcli solves loads, not "
                      "their rates", hint=f"ask for '{base}' itself", **where)


def _out_of_memory(size) -> SolveError:
    return SolveError(f"not enough memory to solve the sweep ({size} positions, in blocks of "
                      f"{BLOCK})", hint="close other programs, use fewer steps or split the "
                      "range into several sweeps")


# --- solving -------------------------------------------------------------------------------
@dataclass
class Block:
    """One block of a sweep: its driver values, the mask of the solved ones and their
    values (display units, name -> array over the solved rows)."""

    q: np.ndarray
    solved: np.ndarray
    values: dict
    #: the smallest conditioning of the groups at each solved row (1 where none has one)
    conditioning: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def count(self) -> int:
        return int(np.count_nonzero(self.solved))


class Sweeper:
    """A sweep solved block by block (:meth:`blocks`); ``issues`` once they are all done.

    The reports are those of the whole sweep: ranges that cross a block's end are joined,
    and branch points are looked for between any two neighbouring samples.
    """

    def __init__(self, mech, q, names=None, method="closed", tol=None, qdot=None, qddot=None,
                 block: int | None = None, quantities: bool = True):
        require_driver(mech, "a sweep")
        self.mech, self.method = mech, method
        self.solver = solver_for(mech, method, tol)
        self.names = check_names(mech, names) if quantities else []
        self.quantities = quantities
        units = mech.units
        base = "angle" if mech.driver.kind == "angle" else "length"
        self.q = q if isinstance(q, DriverRange) else np.asarray(q, dtype=float).ravel()
        self.size = len(self.q)
        self.block_size = max(1, int(BLOCK if block is None else block))
        self.q_unit, self.q_factor = units.display(base, 0)
        self.l_unit, self.l_factor = units.display("length", 0)
        self.qd = mech.driver.rate if qdot is None else qdot * units.display(base, 1)[1]
        self.qdd = mech.driver.accel if qddot is None else qddot * units.display(base, 2)[1]
        self.order = needed_orders(mech, self.names) if self.names else 0
        self.evaluation = plan_for(mech, self.names)     # names parsed once, for every block
        self.units: dict = {}
        self.solved_rows = 0
        self._issues: list = []          # [Issue] (assembly, singular: runs joined)
        self._open: dict = {}            # (kind, group index) -> (Issue, last row)
        self._assembled = 0              # rows assembled so far (the singular runs' index)
        self._tail: dict = {}            # group index -> the last two assembled samples
        self._touch: list = []           # (group index, row, Issue): V tips
        self._between: list = []         # (group index, row a, row b, Issue): between two
        self._done = False
        self._plan = None
        #: the driver's natural size: 1 rad, or the mechanism's size (m) for a length
        self._q_size = 1.0 if base == "angle" else mechanism_size(mech)

    # the blocks --------------------------------------------------------------------
    def values(self, lo: int, hi: int) -> np.ndarray:
        return self.q.block(lo, hi) if isinstance(self.q, DriverRange) else self.q[lo:hi]

    def blocks(self):
        """Solve block after block, yielding each :class:`Block`; raises AssemblyError at the
        end when no row at all could be assembled."""
        if self._done:
            raise RuntimeError("a Sweeper is solved once")
        if min(self.size, self.block_size) >= LONG:
            keep_freed_memory()
        try:
            for lo in range(0, self.size, self.block_size):
                yield self._block(lo, min(self.size, lo + self.block_size))
        except MemoryError:
            raise _out_of_memory(self.size) from None
        self._done = True
        self._finish_branches()
        if self._assembled == 0:        # as one block: the first group's first range
            first = min((i for i in self._issues if i.kind == "assembly"),
                        key=lambda i: i.index, default=None)
            raise AssemblyError(first.text() if first else "nothing to solve",
                                file=self.mech.file, hint="check the range and the lengths")

    @property
    def issues(self) -> list:
        """Every report, sorted by driver value (after :meth:`blocks` is exhausted)."""
        found = list(self._issues)
        touched = {(index, row) for index, row, _ in self._touch}
        found += [issue for _, _, issue in self._touch]
        found += [issue for index, a, b, issue in self._between
                  if (index, a) not in touched and (index, b) not in touched]
        found.sort(key=lambda issue: (min(issue.lo, issue.hi), issue.kind, issue.index))
        return found

    def _describe(self, index) -> str:
        return self.solver.groups[index].describe()

    def _add_run(self, kind, index, first, last, q_lo, q_hi, amount, worse):
        """Report rows first..last (indices that run on across blocks) of ``kind``,
        joining a run that goes on from the previous block."""
        first, last, q_lo, q_hi = int(first), int(last), float(q_lo), float(q_hi)
        key = (kind, index)
        previous = self._open.get(key)
        if previous is not None and previous[1] == first - 1:
            issue = previous[0]
            issue.hi = q_hi
            issue.count += last - first + 1
            issue.amount = worse(issue.amount, amount)
        else:
            issue = Issue(kind, self._describe(index), q_lo, q_hi, last - first + 1, amount,
                          self.q_unit, self.l_unit, index, self.method == "newton")
            self._issues.append(issue)
        self._open[key] = (issue, last)

    def _positions(self, q_si):
        if self.method == "newton" and self.size > self.block_size:
            return self._newton_positions(q_si)
        return self.solver.positions(q_si)

    def _block(self, lo, hi) -> Block:
        q = self.values(lo, hi)
        kin = self._positions(q * self.q_factor)
        good = np.ones(q.shape, bool)
        for index in sorted(kin.short):
            short = np.broadcast_to(kin.short[index], q.shape)
            bad = short > 0
            own = bad & good          # downstream groups of a failed one are not blamed
            for a, b in _runs(own):
                worst = float(np.max(short[a:b + 1][own[a:b + 1]])) / self.l_factor
                self._add_run("assembly", index, lo + a, lo + b, q[a], q[b], worst, max)
            good &= ~bad
        rows = np.nonzero(good)[0]
        if rows.size == 0:
            return Block(q, good, {n: np.zeros(0) for n in self.names})
        sub = kin if good.all() else _subset(kin, good)
        self.solver.velocities(sub, self.qd)   # also gives every group's conditioning measure
        self._branches(sub, q[rows], lo + rows)
        keep = np.ones(rows.size, bool)
        threshold = getattr(self.solver, "singular", SINGULAR)
        start = self._assembled
        self._assembled += rows.size
        for index in sorted(sub.measure):
            measure = np.broadcast_to(sub.measure[index], rows.shape)
            singular = measure < threshold
            if self.order >= 1:
                for a, b in _runs(singular & keep):
                    self._add_run("singular", index, start + a, start + b, q[rows[a]],
                                  q[rows[b]], float(np.min(measure[a:b + 1])), min)
                keep &= ~singular
        if not keep.all():
            sub = _subset(sub, keep)
            good[rows[~keep]] = False
        if not self.names or not keep.any():
            if self.names and not self.units:
                self._units_of(sub)
            return Block(q, good, {n: np.zeros(0) for n in self.names},
                         _conditioning(sub) if keep.any() else np.zeros(0))
        if self.order >= 2:
            self.solver.accelerations(sub, self.qdd)
        alive = np.nonzero(keep)[0]
        while True:             # each pass leaves out the rows one refusal names
            try:
                result = self.evaluation.collect(self.mech, self.solver, sub)
                break
            except (NoWorkError, AtRestError, SelfLockingError) as exc:   # rows without one
                dead = np.broadcast_to(np.asarray(exc.rows, bool), sub.q.shape)
                if not dead.any():
                    raise
                kind, name = ("no-work", exc.load) if isinstance(exc, NoWorkError) else \
                    ("at-rest", exc.what) if isinstance(exc, AtRestError) else \
                    ("self-locking", exc.what)
                for a, b in _runs(dead):
                    self._add_run(kind, -1, start + alive[a], start + alive[b],
                                  q[rows[alive[a]]], q[rows[alive[b]]], exc.measure, min)
                    self._issues[-1].group = name
                good[rows[alive[dead]]] = False
                if dead.all():
                    return Block(q, good, {n: np.zeros(0) for n in self.names})
                sub, alive = _subset(sub, ~dead), alive[~dead]
        self.units.update(result.units)
        self.solved_rows += int(np.count_nonzero(good))
        values = {n: np.broadcast_to(result.values[n], sub.q.shape) for n in self.names}
        return Block(q, good, values, _conditioning(sub))

    def _units_of(self, sub):
        """The units of the names when every assembled row of a block is left out (for a
        header without rows): from the empty selection, as a one-block sweep did."""
        try:
            self.units.update(self.evaluation.collect(self.mech, self.solver, sub).units)
        except Exception:       # noqa: BLE001 - units only; the header shows [] then
            pass

    # Newton in blocks: the anchors of the whole sweep, then each block corrected from them
    def _newton_positions(self, q_si):
        from linkcli.kinematics import continuation as cont
        solver = self.solver
        walker = solver.continuation
        if self._plan is None:
            states, segments = [], []
            for part in self._newton_nodes(cont):
                found, spans = walker._walk(part)
                states += found
                segments += spans
            anchors = cont.Anchors.of(states)
            self._plan = (anchors, np.array([min(a, b) for a, b in segments]),
                          np.array([max(a, b) for a, b in segments]))
        anchors, seg_lo, seg_hi = self._plan
        qs = np.asarray(q_si, dtype=float).ravel()
        X = np.zeros((qs.size, solver.system.width))
        ok = np.zeros(qs.size, bool)
        seg_of = cont._interval_of(qs, seg_lo, seg_hi)
        choose = cont._nearest_anchor(qs, anchors.q, seg_of, seg_lo, seg_hi)
        failed = walker._correct(qs, np.nonzero(seg_of >= 0)[0], choose, anchors, X, ok)
        walker._substep(qs, failed, choose, anchors, X, ok)
        kin = Kinematics(np.asarray(q_si, dtype=float))
        kin.pos.update(solver.fixed)
        kin.pos.update(solver._points(X, kin.q.shape))
        kin.short[0] = solver._closure_error(X, qs, ok).reshape(kin.q.shape)
        return kin

    def _newton_nodes(self, cont):
        """The continuation's nodes of the whole sweep (as ``continuation._nodes`` picks
        them from every driver value), without holding every value when they ascend or
        descend strictly."""
        q0 = self.solver.continuation.q0
        n = self.size
        if isinstance(self.q, DriverRange) and n > 1:
            ends = self.values(0, 2) * self.q_factor
            up = ends[1] > ends[0]
            monotonic, previous = True, None
            for lo in range(0, n, self.block_size):
                q = self.values(lo, min(n, lo + self.block_size)) * self.q_factor
                if previous is not None:
                    q = np.concatenate([[previous], q])
                d = np.diff(q)
                if not (np.all(np.isfinite(q)) and (np.all(d > 0) if up else np.all(d < 0))):
                    monotonic = False
                    break
                previous = q[-1]
            if monotonic:
                step = max(1, int(np.ceil(n / cont.NODES)))
                rank = np.unique(np.concatenate([np.arange(0, n, step), [n - 1]]))
                index = rank if up else n - 1 - rank
                nodes = np.unique(np.concatenate([self._at(index) * self.q_factor]))
                return nodes[nodes > q0], nodes[nodes < q0][::-1]
        return cont._nodes(np.asarray(self.q, dtype=float) * self.q_factor, q0)

    def _at(self, index) -> np.ndarray:
        if isinstance(self.q, DriverRange):
            q = self.q.start + index * self.q.delta
            if self.q.last is not None:
                q = np.where(index == self.size - 1, self.q.last, q)
            return q
        return self.q[index]

    # branch points -------------------------------------------------------------------
    def _branches(self, sub, q, rows):
        """Look for branch points among the assembled samples ``rows`` (q display units),
        the last two samples of the previous block included."""
        threshold = getattr(self.solver, "singular", SINGULAR)
        angles = self._angles(sub) if self.method != "newton" else {}
        signs = self._signs(sub) if self.method == "newton" else {}
        for index in sorted(sub.measure):
            measure = np.array(np.broadcast_to(sub.measure[index], rows.shape), dtype=float)
            theta, slope = angles.get(index, (None, None))
            sign = signs.get(index)
            new = {"m": measure, "q": q, "row": rows}
            if theta is not None:
                new.update(theta=theta, slope=slope)
            if sign is not None:
                new["sign"] = sign
            tail = self._tail.get(index)
            old = 0 if tail is None else tail["row"].size
            every = new if tail is None else {k: np.concatenate([tail[k], v]) for k, v in
                                              new.items() if k in tail}
            self._tail[index] = {k: v[-2:] for k, v in every.items()}
            m, qq, rr = every["m"], every["q"], every["row"]
            if old == 0 and rr.size and rr[0] == 0 and m[0] < threshold:   # exact toggle
                self._touch.append((index, 0, self._branch(index, qq[0], m[0])))
            for i, _ in _touches(m, qq, rr):
                qb = self._closer(index, qq[i - 1], qq[i + 1])
                if qb is None:                  # a smooth minimum, sampled coarsely
                    continue
                self._touch.append((index, int(rr[i]), self._branch(index, qb, m[i])))
            pairs = np.arange(max(old - 1, 0), rr.size - 1)
            if pairs.size == 0:
                continue
            a, b = pairs, pairs + 1
            near = (rr[b] - rr[a] == 1) & (m[a] >= threshold) & (m[b] >= threshold)
            if "theta" in every:
                hit, at = _tangents_meet(every["theta"], every["slope"], qq, a, b)
                for j in np.nonzero(near & hit)[0]:     # a suspicion: looked at closely
                    found = self._closer(index, qq[a[j]], qq[b[j]])
                    hit[j] = found is not None
                    at[j] = at[j] if found is None else found
            elif "sign" in every:             # the side the dyads close on changes
                s = every["sign"]
                hit = s[a] * s[b] < 0
                at = qq[a] + (qq[b] - qq[a]) * m[a] / np.where(m[a] + m[b] > 0, m[a] + m[b], 1)
                for j in np.nonzero(near & hit)[0]:     # located on the conditioning
                    found = self._closer(index, qq[a[j]], qq[b[j]])
                    at[j] = at[j] if found is None else found
            else:
                continue
            for j in np.nonzero(near & hit)[0]:
                self._between.append((index, int(rr[a[j]]), int(rr[b[j]]),
                                      self._branch(index, float(at[j]),
                                                   min(m[a[j]], m[b[j]]))))

    def _closer(self, index, qa, qb):
        """The toggle of group ``index`` between the samples qa and qb, located by zooming on
        its conditioning to the accuracy of ``toggles.TIP`` (``toggles.locate``); None: no
        toggle (a smooth minimum, or a gap that cannot be assembled)."""
        threshold = getattr(self.solver, "singular", SINGULAR)
        solve = self._solve_near(qa, qb) if self.method == "newton" else self.solver.positions

        def measure_at(q):
            kin = solve(q * self.q_factor)
            if kin is None or any(np.any(np.asarray(short) > 0) for short in kin.short.values()):
                return None
            self.solver.velocities(kin, 1.0)
            if index not in kin.measure:
                return None
            return np.array(np.broadcast_to(kin.measure[index], q.shape), dtype=float)

        return toggles.locate(measure_at, qa, qb, toggles.TIP * self._q_size / self.q_factor,
                              threshold)

    def _solve_near(self, qa, qb):
        """Newton's positions at the driver values (SI) of a zoom, each corrected from the
        nearer end of the zoom's interval, solved before (the first ends by one walk from the
        file's position; a value the corrector misses from there is continued to): a zoom
        costs one batch of corrections, not a walk, and never starts from its tip, where
        the tangent is undefined."""
        solver = self.solver
        walker = solver.continuation
        ends = np.array([qa, qb], dtype=float) * self.q_factor
        X, ok = solver.track(ends)
        known = {float(q): x for q, x, good in zip(ends, X, ok) if good}

        def solve(qs):
            qs = np.asarray(qs, dtype=float)
            kq = np.array([q for q in (qs[0], qs[-1]) if float(q) in known])
            if not kq.size:
                return None
            kX = np.array([known[float(q)] for q in kq])
            near = np.argmin(np.abs(qs[:, None] - kq[None, :]), axis=1)
            kdX = solver.tangent(kX, kq)
            X, ok = walker._predict_correct(kX[near], kdX[near], kq[near], qs)
            for side in range(kq.size):         # the rest continued to, outwards from an end
                missed = np.nonzero(~ok & (near == side))[0]
                order = missed[np.argsort(np.abs(qs[missed] - kq[side]), kind="stable")]
                if order.size:
                    walker._chain_into((float(kq[side]), kX[side], kdX[side]), order, qs, X, ok)
            if not ok.all():
                return None
            known.clear()
            known.update(zip(qs.tolist(), X))
            kin = Kinematics(qs)
            kin.pos.update(solver.fixed)
            kin.pos.update(solver._points(X, qs.shape))
            return kin
        return solve

    def _finish_branches(self):
        """An exact toggle at the last sample is a branch point too."""
        threshold = getattr(self.solver, "singular", SINGULAR)
        for index, tail in self._tail.items():
            if tail["row"].size and tail["row"][-1] == self.size - 1 and self.size > 1 \
                    and tail["m"][-1] < threshold:
                self._touch.append((index, self.size - 1,
                                    self._branch(index, tail["q"][-1], tail["m"][-1])))

    def _branch(self, index, q, measure) -> Issue:
        return Issue("branch", self._describe(index), float(q), float(q), 1, float(measure),
                     self.q_unit, self.l_unit, index)

    def _angles(self, sub) -> dict:
        """Per closed-form group: the angle theta in [0, pi] between its two constraint
        normals and d theta / dq (per display unit of q), from the velocities."""
        qd = np.asarray(self.qd, dtype=float)
        if qd.ndim == 0 and qd != 0:
            vel, rate = sub.vel, float(qd)
        else:
            vel, rate = self.solver.velocities(sub.at_rest(), 1.0).vel, 1.0
        out = {}
        for index in sub.measure:
            lin = sub.linear.get(index)
            group = self.solver.groups[index]
            if lin is None or len(group.constraints) != 2:
                continue
            g1, g2 = lin[2], lin[3]
            d1, d2 = (_grad_rate(c, vel, group.point) for c in group.constraints)
            z = np.conj(g1) * g2
            dz = np.conj(d1) * g2 + np.conj(g1) * d2
            safe = np.where(z == 0, 1.0, z)
            theta = np.abs(np.angle(z))
            slope = np.sign(z.imag) * (dz / safe).imag / rate * self.q_factor
            shape = np.shape(sub.q)
            out[index] = (np.array(np.broadcast_to(theta, shape), dtype=float),
                          np.array(np.broadcast_to(slope, shape), dtype=float))
        return out

    def _signs(self, sub) -> dict:
        """Newton: the sign of det J at every row (the side the dyads close on)."""
        from linkcli.kinematics.corrector import CHUNK
        system = getattr(self.solver, "system", None)
        if system is None:
            return {}
        q = np.asarray(sub.q, dtype=float).ravel()
        X = np.empty((q.size, system.n))
        for j, name in enumerate(system.moving):
            z = np.broadcast_to(sub.pos[name], np.shape(sub.q)).ravel()
            X[:, 2 * j], X[:, 2 * j + 1] = z.real, z.imag
        sign = np.empty(q.size)
        for start in range(0, q.size, CHUNK):
            sl = slice(start, start + CHUNK)
            sign[sl] = np.sign(np.linalg.det(system.jacobian(system.points(X[sl]), q[sl])))
        return {0: sign}


def sweep(mech, q, names=None, method="closed", tol=None, qdot=None, qddot=None,
          block: int | None = None) -> Sweep:
    """Solve ``mech`` at every driver value of ``q`` (display units, 1-D), in blocks."""
    sweeper = Sweeper(mech, q, names, method, tol, qdot, qddot, block)
    q = np.asarray(sweeper.q, dtype=float)
    solved, parts, conditioning = [], {n: [] for n in sweeper.names}, [np.zeros(0)]
    try:
        for part in sweeper.blocks():
            solved.append(part.solved)
            conditioning.append(part.conditioning)
            for n in sweeper.names:
                parts[n].append(part.values[n])
        out = Sweep(mech, method, q, np.concatenate(solved) if solved else np.zeros(0, bool),
                    sweeper.names, q_unit=sweeper.q_unit)
        out.values = {n: np.concatenate(parts[n]) for n in sweeper.names}
        out.conditioning = np.concatenate(conditioning)
    except MemoryError:
        raise _out_of_memory(q.size) from None
    out.units = dict(sweeper.units)
    out.issues = sweeper.issues
    return out


def _conditioning(kin) -> np.ndarray:
    """The smallest conditioning measure of the groups at each position of ``kin`` (1 where
    no group has one: every group is a crank or a rigid placement)."""
    least = np.ones(np.shape(kin.q))
    for measure in kin.measure.values():
        least = np.minimum(least, measure)
    return least


def mechanism_size(mech) -> float:
    """The mechanism's size: the largest distance of a figure point from the first (m)."""
    points = mech.figure_points
    return max((abs(p - points[0]) for p in points), default=1.0) or 1.0


def _grad_rate(c, vel, unknown):
    """The time derivative of ``rates._grad(c, pos, unknown)``: the same combination
    of the velocities ``vel`` (absent points are fixed)."""
    if isinstance(c, Dist):
        return 2.0 * (vel.get(c.p, 0j) - vel.get(c.a, 0j))
    if isinstance(c, Line):
        if unknown == c.p:
            return 1j * (vel.get(c.c, 0j) - vel.get(c.b, 0j))
        return -1j * (vel.get(c.p, 0j) - vel.get(c.b, 0j))
    return 0j


def _runs(mask):
    """(first, last) index of every run of True in a 1-D mask."""
    if not mask.any():
        return []
    edges = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    starts = np.nonzero(edges == 1)[0]
    ends = np.nonzero(edges == -1)[0] - 1
    return list(zip(starts.tolist(), ends.tolist()))


def _touches(measure, q, rows):
    """Samples where the measure dips to zero in a V between two neighbours.

    Near a toggle the measure behaves like c |q - q*|; three consecutive samples
    m0 > m1 <= m2 then satisfy m1 <= (m0 + m2) / 4 (m1 = 0 at q*); the bound
    used, (m0 + m2) / 3, also flags a smooth minimum m* + a x^2 whose depth m* is
    under 2 a step^2, i.e. zero within the sampling.  q* is interpolated.
    """
    if measure.size < 3:
        return []
    m0, m1, m2 = measure[:-2], measure[1:-1], measure[2:]
    adjacent = (rows[1:-1] - rows[:-2] == 1) & (rows[2:] - rows[1:-1] == 1)
    total = m0 + m2
    hit = adjacent & (m1 < m0) & (m1 <= m2) & (total > 0) & (m1 <= total / 3)
    found = []
    for j in np.nonzero(hit)[0]:
        i = j + 1
        t = (m0[j] - m2[j]) / total[j]          # offset of the V's tip, in samples
        step = (q[i + 1] - q[i - 1]) / 2
        found.append((i, float(q[i] + t * step)))
    return found


def _tangents_meet(theta, slope, q, a, b):
    """Between samples a and b: does the angle theta between the constraint normals reach
    0 or pi (a toggle) in a V?  Its distance to the toggle angle falls at a and rises at b,
    and their tangents meet at most a quarter of the two distances above zero (0 for a
    straight V; a smooth minimum m* + c x^2 is flagged when m* < 3 c h^2, h the half
    step: zero within the sampling, as for three samples).  Returns (hit, q of the tip)."""
    h = q[b] - q[a]
    hit = np.zeros(a.size, bool)
    at = np.zeros(a.size)
    for toward in (0.0, math.pi):
        da, db = np.abs(theta[a] - toward), np.abs(theta[b] - toward)
        sa, sb = (slope[a], slope[b]) if toward == 0.0 else (-slope[a], -slope[b])
        v = (sa * h < 0) & (sb * h > 0)
        denominator = np.where(v, sa - sb, 1.0)
        u = (db - da - sb * h) / denominator        # where the tangents meet, from q[a]
        value = da + sa * u
        t = u / np.where(h != 0, h, 1.0)
        now = v & (t >= 0) & (t <= 1) & (value <= (da + db) / 4)
        at = np.where(now & ~hit, q[a] + u, at)
        hit |= now
    return hit, at


def _subset(kin, mask) -> Kinematics:
    """The rows ``mask`` of a 1-D sweep's kinematics (coordinates, positions, rates,
    measures)."""
    shape = kin.q.shape

    def pick(value):
        return value[mask] if np.shape(value) == shape else value

    out = Kinematics(kin.q[mask], coords=tuple(pick(c) for c in kin.coords))
    out.qd = None if kin.qd is None else pick(kin.qd)
    out.qdd = None if kin.qdd is None else pick(kin.qdd)
    out.rates = tuple(pick(r) for r in kin.rates)
    out.accels = tuple(pick(a) for a in kin.accels)
    for src, dst in ((kin.pos, out.pos), (kin.vel, out.vel), (kin.acc, out.acc),
                     (kin.short, out.short), (kin.measure, out.measure)):
        for key, value in src.items():
            dst[key] = pick(value)
    return out


# output ----------------------------------------------------------------------------
def check_every(every: int) -> int:
    if every < 1:
        raise InputError(f"--every must be at least 1, got {every}", key="--every")
    return every


def render(result: Sweep, form: str = "csv", every: int = 1, decimals: int | None = None) -> str:
    """CSV (default), JSON or a table of the solved rows, every ``every``-th one."""
    import io
    check_every(every)
    text = io.StringIO()
    block = Block(result.q, result.solved, result.values)
    _write(iter([block]), result.mechanism, result.method, result.names, result.units,
           result.q_unit, lambda: result.issues, form, every, decimals, text.write)
    return text.getvalue()[:-1]


def write(sweeper: Sweeper, form: str, every: int, decimals: int | None, out) -> list:
    """Solve ``sweeper`` and print it through ``out`` (a function of text, or a text stream)
    as it goes: CSV rows a block at a time, JSON and tables through temporary files (their
    lists and column widths are known at the end).  Returns the issues, to be reported;
    nothing is printed when no row can be assembled (AssemblyError)."""
    check_every(every)
    put = out if callable(out) else out.write
    try:
        _write(sweeper.blocks(), sweeper.mech, sweeper.method, sweeper.names, sweeper.units,
               sweeper.q_unit, lambda: sweeper.issues, form, every, decimals, put)
    except MemoryError:
        raise _out_of_memory(sweeper.size) from None
    return sweeper.issues


def _write(blocks, mech, method, names, units, q_unit, issues, form, every, decimals, put,
           first="q"):
    """Print ``blocks`` (the rows of the sweep) as CSV, JSON or a table; ``units`` is filled
    by the time the first block with rows is done, ``issues()`` at the end.  ``first`` names
    the column of the values swept (the driver's, q, or a parameter's)."""
    if form == "csv":
        fmt = repr if decimals is None else (lambda v: f"{v:.{decimals}f}")
        seen, started = 0, False
        for part in blocks:
            columns = _printed(part, names, seen, every)
            seen += part.count
            if columns is None:
                continue
            if not started:         # the units are known once a block has rows
                put(",".join(_header(names, units, q_unit, first)) + "\n")
                started = True
            for lo in range(0, columns[0].size, LINES):     # text is bulky: a bit at a time
                text = [list(map(fmt, c[lo:lo + LINES].tolist())) for c in columns]
                put("\n".join(map(",".join, zip(*text))) + "\n")
        if not started:             # every assembled row left out: the header alone
            put(",".join(_header(names, units, q_unit, first)) + "\n")
        return
    with _Spool(1 + len(names)) as spool:
        width = _Widths(1 + len(names), 4 if decimals is None else decimals)
        seen = 0
        for part in blocks:
            columns = _printed(part, names, seen, every)
            seen += part.count
            if columns is None:
                continue
            spool.add(columns)
            if form == "table":
                width.add(columns)
        header = _header(names, units, q_unit, first)
        if form == "json":
            _json(spool, mech, method, names, units, q_unit, issues(), put, first)
        else:
            _table(spool, header, width, put)


def _header(names, units, q_unit, first="q") -> list:
    return [f"{first} [{q_unit}]"] + [f"{n} [{units.get(n, '')}]" for n in names]


def _printed(part: Block, names, seen: int, every: int):
    """The columns (q first) of ``part``'s solved rows printed with ``--every``, the
    solved rows before it numbering ``seen``; None when none is printed."""
    count = part.count
    if count == 0:
        return None
    first = (-seen) % every
    if first >= count:
        return None
    q = part.q[part.solved] if count < part.q.size else part.q
    return [np.asarray(q[first::every], dtype=float)] + [
        np.asarray(part.values[n][first::every], dtype=float) for n in names]


class _Spool:
    """Columns of float64 written to unnamed temporary files (removed however the program
    ends), read back a block at a time."""

    def __init__(self, count: int):
        self.count = count
        self.files = []
        self.rows = 0

    def __enter__(self):
        try:
            self.files = [tempfile.TemporaryFile(prefix="linkcli-sweep-") for _ in
                          range(self.count)]
        except OSError as exc:
            raise _spool_error(exc) from None
        return self

    def __exit__(self, *exc):
        for handle in self.files:
            handle.close()
        return False

    def add(self, columns):
        try:
            for handle, column in zip(self.files, columns):
                np.ascontiguousarray(column, dtype=np.float64).tofile(handle)
        except OSError as exc:
            raise _spool_error(exc) from None
        self.rows += columns[0].size

    def column(self, j):
        """The values of column ``j``, a block at a time."""
        handle = self.files[j]
        handle.flush()
        handle.seek(0)
        left = self.rows
        while left:
            part = np.fromfile(handle, dtype=np.float64, count=min(left, BLOCK))
            left -= part.size
            yield part

    def blocks(self):
        """Every column's values together, a block at a time."""
        readers = [self.column(j) for j in range(self.count)]
        yield from zip(*readers)


def _spool_error(exc) -> InputError:
    return InputError(f"cannot write the sweep's temporary file: {exc.strerror or exc}",
                      file=tempfile.gettempdir(), hint="JSON and tables of a sweep are kept "
                      "there until the end: free some space, set TMPDIR to another folder, or "
                      "use --format csv, which is printed as it goes")


class _Widths:
    """The widest text of each column at ``decimals`` fixed decimals: that of its largest
    value without a minus sign, or of its largest magnitude with one."""

    def __init__(self, count: int, decimals: int):
        self.decimals = decimals
        self.plus = [None] * count
        self.minus = [None] * count

    def add(self, columns):
        for j, c in enumerate(columns):
            negative = np.signbit(c)
            if (~negative).any():
                top = float(np.max(c[~negative]))
                self.plus[j] = top if self.plus[j] is None else max(self.plus[j], top)
            if negative.any():
                top = float(np.max(-c[negative]))
                self.minus[j] = top if self.minus[j] is None else max(self.minus[j], top)

    def text(self, j) -> int:
        d = self.decimals
        sizes = [len(f"{self.plus[j]:.{d}f}")] if self.plus[j] is not None else []
        if self.minus[j] is not None:
            sizes.append(1 + len(f"{self.minus[j]:.{d}f}"))
        return max(sizes, default=0)


TABLE_PADDING = 2       # tabulate's MIN_PADDING: a header is at least 2 narrower than its column
TABLE_GAP = "  "        # tabulate's 'simple' format: columns apart by two spaces


def _table(spool, header, widths, put):
    """The rows as tabulate's 'simple' table of right-aligned text, written a block at a time
    (the widths are known from the largest values)."""
    size = [max(len(h) + TABLE_PADDING, widths.text(j)) for j, h in enumerate(header)]
    put(TABLE_GAP.join(h.rjust(w) for h, w in zip(header, size)) + "\n")
    put(TABLE_GAP.join("-" * w for w in size))
    d = widths.decimals
    for columns in spool.blocks():
        for lo in range(0, columns[0].size, LINES):
            text = [[f"{v:.{d}f}".rjust(w) for v in c[lo:lo + LINES].tolist()]
                    for c, w in zip(columns, size)]
            put("\n" + "\n".join(map(TABLE_GAP.join, zip(*text))))
    put("\n")


def _json(spool, mech, method, names, units, q_unit, issues, put, first="q"):
    """json.dumps(..., indent=1) of the sweep, its lists written a block at a time."""
    import json
    marks = [f"\x00linkcli-column-{j}\x00" for j in range(1 + len(names))]
    data = {"file": mech.file, "title": mech.title, "k": mech.k, "method": method,
            "units": {first: q_unit, **{n: units.get(n, "") for n in names}},
            first: marks[0], "values": {n: m for n, m in zip(names, marks[1:])},
            "issues": [issue.as_dict() for issue in issues]}
    text = json.dumps(data, indent=1)
    for j, mark in enumerate(marks):
        quoted = json.dumps(mark)
        head, text = text.split(quoted, 1)
        put(head)
        _json_list(spool.column(j), _indent(head), put)
    put(text + "\n")


def _indent(head: str) -> int:
    """The indentation of the last line of ``head`` (the line that opens a list)."""
    line = head[head.rfind("\n") + 1:]
    return len(line) - len(line.lstrip(" "))


def _json_list(parts, depth, put):
    """A list of floats as json.dumps(..., indent=1) writes it at nesting ``depth``."""
    pad = "\n" + " " * (depth + 1)
    first = True
    for block in parts:
        for lo in range(0, block.size, LINES):
            put(("[" if first else ",") + pad +
                ("," + pad).join(map(repr, block[lo:lo + LINES].tolist())))
            first = False
    put("[]" if first else "\n" + " " * depth + "]")
