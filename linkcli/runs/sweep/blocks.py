"""A sweep solved a block of driver values at a time, in vectorised passes.

Rows that cannot be solved are never printed as NaN: positions that cannot be assembled
are reported as ranges of q with the group and its largest shortfall (an
:class:`~linkcli.runs.sweep.issues.Issue`), and rows where velocities are undefined (a
toggle hit exactly) or a load's answer is (no work, a pair at rest, self-locking) are
left out and reported the same way.  Every other row is kept.  A group that fails is
blamed, the groups downstream of it are not.

Memory: the driver values are solved in blocks of ``BLOCK`` positions
(:meth:`Sweeper.blocks` yields each one as it is solved), so that a sweep takes the same
memory for 10^4 as for 10^7 positions.  Ranges that cross a block's end are joined: the
reports and every value are those of a sweep solved in one block.  Newton over more than
a block follows ``newton_path``; branch points are found by ``branch_points``.

Units: the driver values and the answers are in display units (``q_unit``, the file's
units), the solvers are called in SI (``q_factor``), shortfalls are shown in ``l_unit``.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from linkcli.answers.memory import LONG, keep_freed_memory
from linkcli.answers.quantities import needed_orders, plan_for, require_driver
from linkcli.answers.quantities.drive import Drive, Path
from linkcli.errors import AtRestError, NoWorkError, AssemblyError, SelfLockingError, \
    SolveError
from linkcli.kinematics.closed_form import Kinematics
from linkcli.kinematics.refusals import SINGULAR
from linkcli.kinematics.solvers import solver_for
from linkcli.runs.sweep.branch_points import BranchPoints
from linkcli.runs.sweep.driver_range import DriverRange, block_of
from linkcli.runs.sweep.issues import Issue
from linkcli.runs.sweep.names import check_names
from linkcli.runs.sweep.newton_path import NewtonPath

#: positions solved at once.  Measured on a six-bar, 10^6 positions to JSON: the time is the
#: same within 3 % for blocks of 2^12 to 2^16 positions (10.6 to 10.3 s of CPU), while the
#: peak memory grows with the block (37, 41, 48, 63, 93 MB): larger blocks only fill fresh
#: memory pages.  2^14 is also the Newton solver's batch.  benchmarks/memory.py: the peak
#: does not grow with the sweep's length.
BLOCK = 1 << 14


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


def out_of_memory(size) -> SolveError:
    """The refusal of a sweep of ``size`` positions whose blocks do not fit in memory."""
    return SolveError(f"not enough memory to solve the sweep ({size} positions, in blocks of "
                      f"{BLOCK})", hint="close other programs, use fewer steps or split the "
                      "range into several sweeps")


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
                 block: int | None = None, quantities: bool = True, ties=None):
        require_driver(mech, "a sweep")
        self.mech, self.method = mech, method
        self.solver = solver_for(mech, method, tol)
        #: every driver from the first (the one swept): the others held or tied to it
        self.drive = Drive(mech, ties)
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
        self._done = False
        self._branch_points = None       # BranchPoints, and Newton's path: made when solved
        self._newton = None
        #: the driver's natural size: 1 rad, or the mechanism's size (m) for a length
        self._q_size = 1.0 if base == "angle" else mechanism_size(mech)

    # the blocks --------------------------------------------------------------------
    def values(self, lo: int, hi: int) -> np.ndarray:
        return block_of(self.q, lo, hi)

    def blocks(self):
        """Solve block after block, yielding each :class:`Block`; raises AssemblyError at the
        end when no row at all could be assembled."""
        if self._done:
            raise RuntimeError("a Sweeper is solved once")
        if min(self.size, self.block_size) >= LONG:
            keep_freed_memory()
        path = Path(self.solver, self.drive) if self.drive.several else self.solver
        self._branch_points = BranchPoints(path, self.method, self.q_factor, self.q_unit,
                                           self.l_unit, self._q_size, self.qd, self.size)
        if self.method == "newton" and self.size > self.block_size:
            self._newton = NewtonPath(self.solver, self.q, self.q_factor, self.block_size)
        try:
            for lo in range(0, self.size, self.block_size):
                yield self._block(lo, min(self.size, lo + self.block_size))
        except MemoryError:
            raise out_of_memory(self.size) from None
        self._done = True
        self._branch_points.finish()
        if self._assembled == 0:        # as one block: the first group's first range
            first = min((i for i in self._issues if i.kind == "assembly"),
                        key=lambda i: i.index, default=None)
            raise AssemblyError(first.text() if first else "nothing to solve",
                                file=self.mech.file, hint="check the range and the lengths")

    @property
    def issues(self) -> list:
        """Every report, sorted by driver value (after :meth:`blocks` is exhausted)."""
        found = list(self._issues)
        if self._branch_points is not None:
            found += self._branch_points.reports()
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
        if self._newton is not None:
            return self._newton.positions(q_si)
        if not self.drive.several:
            return self.solver.positions(q_si)
        qs, rates, accels = self.drive(q_si, self.qd, self.qdd)
        kin = self.solver.positions(qs)
        kin.rates, kin.accels = rates, accels       # every driver's, row by row
        return kin

    def _rates(self, sub, order):
        """The drivers' rates of ``order`` (1, 2) at the rows of ``sub``: the first's, or
        every driver's as :meth:`_positions` found them."""
        if not self.drive.several:
            return self.qd if order == 1 else self.qdd
        return sub.rates if order == 1 else sub.accels

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
        self.solver.velocities(sub, self._rates(sub, 1))   # and each group's conditioning
        self._branch_points.scan(sub, q[rows], lo + rows)
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
            self.solver.accelerations(sub, self._rates(sub, 2))
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


def sweep(mech, q, names=None, method="closed", tol=None, qdot=None, qddot=None,
          block: int | None = None, ties=None) -> Sweep:
    """Solve ``mech`` at every driver value of ``q`` (display units, 1-D), in blocks; with
    several drivers, ``q`` is the first's and ``ties`` {name: expression of it} sets others
    (``answers.quantities.drive``)."""
    sweeper = Sweeper(mech, q, names, method, tol, qdot, qddot, block, ties=ties)
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
        raise out_of_memory(q.size) from None
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


def _runs(mask):
    """(first, last) index of every run of True in a 1-D mask."""
    if not mask.any():
        return []
    edges = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    starts = np.nonzero(edges == 1)[0]
    ends = np.nonzero(edges == -1)[0] - 1
    return list(zip(starts.tolist(), ends.tolist()))


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

