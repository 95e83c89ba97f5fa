"""Evaluate a mechanism's report: every named quantity in its display unit.

Angles of a vector ``z = P_b - P_a`` and their rates follow from
``w = z'/z``: ``phi' = Im w``, ``phi'' = Im(z''/z - w^2)``; lengths:
``r' = r Re w``, ``r'' = r (Re(z''/z - w^2) + (Re w)^2)``.

The textbook's questions (docs/schema.md, "quantities") come from the same positions,
velocities and accelerations: speeds |v|, tangential and normal accelerations
``Re(conj(v) a)/|v|`` and ``|Im(conj(v) a)|/|v|``, projections ``Re(conj(u) P)`` with
rates ``Re(conj(u) v_P)``, rotations of bodies (``forces.motion``), instant centres
``I = P + i v_P / omega``, joint forces (``forces.joint_forces``) and velocity ratios
(rates at a unit driver rate).  Where one is undefined (a point at rest, a body that
translates) it is a located SolveError, never NaN.
"""
from __future__ import annotations

import math
import os
import weakref
from dataclasses import dataclass, field

import numpy as np

from linkcli.answers.memory import LONG, keep_freed_memory
from linkcli.errors import InputError, LinkcliError, SolveError
from linkcli.forces import motion
from linkcli.kinematics.closed_form import own_coordinates, where_text
from linkcli.kinematics.compiled import ANGLE as ANGLE_PROBE, LENGTH as LENGTH_PROBE, \
    X as X_PROBE, Y as Y_PROBE, compiled, program_of
from linkcli.kinematics.solvers import solver_for
from linkcli.model.mechanism import FRAME, REPORT_SECTIONS, VIBRATION, Quantity, split_rate
from linkcli.forces.statics import unknown_load
from linkcli.input.report import LEVEL
from linkcli.model.units import ANGLE, FORCE, LENGTH, TORQUE

TWO_PI = 2 * math.pi
#: a long array of driver values is solved this many positions at a time (see Plan._in_blocks)
BLOCK = 1 << 15
#: the compiled loop (kinematics.compiled), where it is on, solves arrays of up to this many
#: driver values: 2.5-3 times NumPy's speed at 360, about the same at 2048 (benchmarks/
#: speed.py); at 4096 NumPy's loops over whole arrays (vectorised sin, cos, arctan2) were
#: 10-30 % faster than its scalar ones
COMPILED_MOST = 1 << 11
#: on at most this many threads (the processors this process may use, up to 4)
WORKERS = min(4, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
              else os.cpu_count() or 1)
#: a point is at rest (its velocity has no direction) where its speed is at most AT_REST
#: times the largest speed of the mechanism's points; a body translates where its angular
#: velocity is at most AT_REST times the largest rate of the mechanism (the largest angular
#: velocity of its bodies, or its largest speed over its size)
AT_REST = 1e-9
#: the kinds of docs/schema.md's textbook quantities (speeds, projections, rotations ...)
TEXTBOOK = ("speed", "acceleration", "tangential_acceleration", "normal_acceleration",
            "along", "normal_to", "relative", "relative_speed", "relative_acceleration",
            "rotation", "between", "instant_centre", "instant_centre_distance", "reaction",
            "slider_force", "velocity_ratio", "least_speed", "least_speed_at")


@dataclass
class Result:
    """Solved values of a report, in display units (floats or arrays)."""

    mechanism: object
    values: dict = field(default_factory=dict)
    units: dict = field(default_factory=dict)
    points: dict = field(default_factory=dict)       # name -> (x, y) in length units
    kinematics: object = None
    analysis: object = None                          # the vibration analysis, if any
    cautions: list = field(default_factory=list)     # warnings to print with the results

    @property
    def k(self):
        return self.mechanism.k


def needed_orders(mech, names):
    """The highest order of rates (0, 1 or 2) solving ``names`` takes; a rate a quantity has
    not (the rate of an acceleration) is refused here, before anything is solved."""
    orders = {0}
    for name in names:
        base, order = split_rate(name)
        quantity = mech.quantities.get(base)
        if quantity is not None and quantity.kind != "load":
            require_rate(mech, name, quantity, order)
            orders.add(_needs(mech, quantity, order))
        else:
            # loads need velocities (virtual work); with masses also accelerations
            orders.add(2 if mech.dynamics is not None else 1)
    return max(orders)


def _needs(mech, quantity, order) -> int:
    """The order of the kinematics that ``quantity``'s rate of ``order`` is computed from."""
    kind = quantity.kind
    if kind in ("reaction", "slider_force"):
        return 2 if mech.dynamics is not None else 0
    if kind in ("instant_centre", "instant_centre_distance", "velocity_ratio",
                "least_speed_at"):
        return 1
    return min(2, LEVEL.get(kind, 0) + order)


def require_rate(mech, name, quantity, order) -> None:
    """Refuse ``name``, the rate of ``order`` of ``quantity``, when it has no such rate."""
    if order <= quantity.rates or quantity.kind in VIBRATION:
        return
    kind = quantity.kind.replace("_", " ")
    has = "no rates" if quantity.rates == 0 else f"only one rate, {quantity.name}dot"
    article = "an" if kind[0] in "aeiou" else "a"
    raise InputError(f"'{name}' is not defined: '{quantity.name}' is {article} {kind}, which has "
                     f"{has}",
                     file=mech.file, key=f"quantities.{quantity.name}", line=quantity.line,
                     hint="the rate of a speed is the tangential acceleration"
                     if quantity.kind == "speed" else f"ask for '{quantity.name}' itself")


def report_names(mech):
    names = []
    for section in REPORT_SECTIONS:
        names += mech.report.get(section, [])
    return names


def require_driver(mech, what: str) -> None:
    """Refuse a request that varies the driver on a file declared with coordinates."""
    if mech.elements is not None or len(mech.coordinates) > 1:
        raise InputError(f"{what} varies the driver, and this file declares coordinates "
                         "(a vibration problem) instead", file=mech.file,
                         hint="use 'linkcli solve', or 'linkcli plot' with --frf, --modes or "
                         "--free")


def evaluate(mech, q=None, qdot=None, qddot=None, names=None, method="closed",
             tol=None) -> Result:
    """Solve ``mech`` at driver value(s) ``q`` (display units) and evaluate ``names``."""
    require_driver(mech, "solving at driver values")
    return plan_for(mech, names, method, tol).evaluate(mech, q, qdot, qddot)


def collect(mech, solver, kin, names) -> Result:
    """Evaluate ``names`` (display units) on kinematics ``kin`` solved as far as they need."""
    return plan_for(mech, names).collect(mech, solver, kin)


# --- the evaluation plan --------------------------------------------------------------------
_PLANS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def plan_for(mech, names=None, method="closed", tol=None) -> "Plan":
    """The :class:`Plan` of ``names`` (default: the report's) on ``mech``, built at the first
    call and kept, keyed by the mechanism object (which stays plain data), like its solvers."""
    key = (None if names is None else tuple(names), method, tol)
    plans = _PLANS.setdefault(mech, {})
    plan = plans.get(key)
    if plan is None:
        plan = plans[key] = Plan(mech, report_names(mech) if names is None else list(names),
                                 method, tol)
    return plan


class Plan:
    """How a list of names is evaluated on one mechanism, worked out once.

    Building it parses the names (base quantity, order of rate), refuses the ones that are
    not defined (rates of loads, rates a quantity has not), finds the order of kinematics
    they need and each one's display unit and SI factor, and picks each one's evaluation:
    angles, lengths, coordinates and the driver by a few array operations written straight
    into one preallocated (names x positions) array; the other kinds by :func:`_value`.
    Evaluating then solves and runs that list; the values are checked to be finite once for
    the whole array.  The plan holds no reference to the mechanism (it is passed to each
    call), so the mechanism and its plans are freed together.
    """

    def __init__(self, mech, names, method="closed", tol=None):
        self.method, self.tol = method, tol
        self.names = list(dict.fromkeys(names))
        self._order = None
        self.wants_loads = False
        for name in self.names:
            base, order = split_rate(name)
            quantity = mech.quantities.get(base)
            if quantity is not None and quantity.kind == "load":
                self.wants_loads = True
                if order:
                    raise InputError(f"'{name}': a load has no rates", file=mech.file,
                                     key="names", hint=f"ask for the load itself, '{base}'")
        driver = "angle" if mech.driver is not None and mech.driver.kind == "angle" \
            else "length"
        self.q_factors = [mech.units.display(driver, i)[1] for i in range(3)]
        self.steps = [_step(mech, name) for name in self.names]
        #: every name's display unit, in order (those of _value's names come with their values)
        self.units = {name: unit for name, (_, unit) in zip(self.names, self.steps)}
        #: (row, name) of the names evaluated by _value (their units come with the values)
        self.others = [(i, name) for i, (name, (fn, _)) in enumerate(zip(self.names, self.steps))
                       if fn is None]
        self.generic = bool(self.others)
        angles = {i: fn for i, (fn, _) in enumerate(self.steps) if isinstance(fn, AngleRow)}
        #: kernel(kin, table) writing rows of the table: the angles together, then each other
        self.kernels = ([Angles(angles)] if angles else []) + \
            [_Row(i, fn) for i, (fn, _) in enumerate(self.steps)
             if fn is not None and not isinstance(fn, AngleRow)]
        l_unit, l_factor = mech.units.display("length", 0)
        self.points = [(p, l_unit, l_factor) for p in mech.report.get("points", [])]
        #: the names as probes of a compiled solve (kinematics.compiled), None when one is
        #: not an angle, a length, a coordinate or one of their rates, or loads are asked
        self.probes = [_probe(fn) for fn, _ in self.steps]
        if None in self.probes or self.wants_loads:
            self.probes = None
        else:           # the report's points: x and y rows after the names'
            self.probes += [(axis, p, None, 0, f, False) for p, _, f in self.points
                            for axis in (X_PROBE, Y_PROBE)]
        self._program = False           # (program, probes) built at the first compiled call

    def order(self, mech) -> int:
        """The highest order of rates the names need (checked at the first call)."""
        if self._order is None:
            self._order = needed_orders(mech, self.names)
        return self._order

    def evaluate(self, mech, q=None, qdot=None, qddot=None) -> Result:
        """Solve at driver value(s) ``q`` (display units; default the file's) as far as the
        names need, refusing unassembled and singular positions, and evaluate them."""
        solver = solver_for(mech, self.method, self.tol)
        order = self.order(mech)
        driver = self._driver_si(mech.driver, q, qdot, qddot)
        if q is not None and self.probes is not None and np.size(q) <= COMPILED_MOST \
                and compiled() is not None:
            result = self._compiled(mech, solver, order, *driver)
            if result is not None:
                return result
        if q is not None and np.size(q) >= LONG:
            keep_freed_memory()
        if q is not None and np.size(q) > BLOCK and self._blockwise:
            result = self._in_blocks(mech, solver, order, *driver)
            if result is not None:
                return result
        result = self.collect(mech, solver, _solved(solver, order, *driver))
        if q is None:       # the file's own position: what the figure check says of it
            from linkcli.answers.validate import figure_cautions
            result.cautions = figure_cautions(mech) if self.method == "closed" else []
        return result

    @property
    def _blockwise(self) -> bool:
        """Whether every name is a kernel of the positions and rates alone (no loads, no
        quantity that looks at all the positions at once, no points): then a long array of
        driver values may be solved block by block."""
        return self.method == "closed" and not self.generic and not self.wants_loads \
            and not self.points

    def _driver_si(self, driver, q, qdot, qddot) -> tuple:
        """(q, q', q'') in SI from display units, the file's values where not given."""
        f0, f1, f2 = self.q_factors
        return (driver.value if q is None else np.asarray(q, float) * f0,
                driver.rate if qdot is None else np.asarray(qdot, float) * f1,
                driver.accel if qddot is None else np.asarray(qddot, float) * f2)

    def _in_blocks(self, mech, solver, order, qs, qd, qdd):
        """:meth:`evaluate` of a long 1-D array of driver values, BLOCK positions at a time:
        the arrays of a block stay in the processor's cache, several times faster than
        passes over arrays of millions.  The blocks are solved on up to :data:`WORKERS`
        threads at once (NumPy's loops run without the interpreter's lock; each block writes
        its own columns of the table).  The values are the whole-array ones (every
        operation is position by position).  None when anything is refused or not of the
        driver values' shape: the whole-array path then decides, and words its errors for
        every position at once.  ``qs``, ``qd``, ``qdd``: the driver's values and rates (SI)."""
        if qs.ndim != 1 or solver.n != 1 or any(np.ndim(x) and np.shape(x) != qs.shape
                                                for x in (qd, qdd)):
            return None
        table = np.empty((len(self.names), qs.size))

        def solve(lo):
            hi = min(qs.size, lo + BLOCK)
            part = _solved(solver, order, qs[lo:hi], qd[lo:hi] if np.ndim(qd) else qd,
                           qdd[lo:hi] if np.ndim(qdd) else qdd)
            for kernel in self.kernels:
                kernel(part, table[:, lo:hi])

        starts = range(0, qs.size, BLOCK)
        try:
            workers = min(WORKERS, len(starts))
            if workers > 1:
                from concurrent.futures import ThreadPoolExecutor
                with ThreadPoolExecutor(workers) as pool:
                    for _ in pool.map(solve, starts):
                        pass
            else:
                for lo in starts:
                    solve(lo)
            if not _finite(table):
                return None
        except LinkcliError:
            return None
        return self._tabled(mech, table, Later(solver, qs, qd, qdd, order))

    def _compiled(self, mech, solver, order, qs, qd, qdd):
        """:meth:`evaluate` by the compiled loop of ``kinematics.compiled`` (a 1-D array of
        driver values, SI); None where it cannot express the names or refuses a position:
        the NumPy path then decides, and words the error."""
        program = self._compiled_program(solver)
        if program is None or qs.ndim != 1 or not qs.size:
            return None
        program, probes = program
        table = np.empty((len(probes[0]), qs.size))
        if not program.run(probes, qs, qd, qdd, order, table):
            return None
        return self._tabled(mech, table, Later(solver, qs, qd, qdd, order))

    def _compiled_program(self, solver):
        """(program, probes) of the compiled loop for these names on ``solver``, None where
        it cannot express them (worked out at the first call)."""
        if self._program is False:
            program = program_of(solver) if self.probes is not None and \
                self.method == "closed" else None
            probes = None if program is None else program.probes(self.probes)
            self._program = None if probes is None else (program, probes)
        return self._program

    def _tabled(self, mech, table, kinematics) -> Result:
        """The result of the rows of ``table``, one per name, then x and y of each of the
        report's points, solved on ``kinematics``."""
        result = Result(mech, kinematics=kinematics)
        result.units = dict(self.units)
        count = len(self.names)
        result.values = dict(zip(self.names, table[:count]))
        for i, (p, l_unit, _) in enumerate(self.points):
            result.points[p] = (table[count + 2 * i], table[count + 2 * i + 1])
            result.units[p] = l_unit
        return result

    def collect(self, mech, solver, kin) -> Result:
        """Evaluate the names (display units) on ``kin`` solved as far as they need."""
        result = Result(mech, kinematics=kin)
        shape = np.shape(kin.q)
        if len(kin.coords) > 1 and kin.shape != shape:     # coordinates of several shapes
            return _collect_each(mech, solver, kin, self.names, result)
        loads = _loads(mech, solver, kin, self.names) if self.wants_loads else {}
        context = Context(mech, solver, kin) if self.generic else None
        table = np.empty((len(self.names),) + shape)
        for kernel in self.kernels:
            kernel(kin, table)
        result.units = dict(self.units)
        for i, name in self.others:
            table[i, ...], result.units[name] = _value(mech, name, kin, loads, context)
        if not _finite(table):
            _require_finite(mech, dict(zip(self.names, table)))
        result.values = dict(zip(self.names, table))
        for p, l_unit, l_factor in self.points:
            z = kin.pos[p]
            result.points[p] = (np.real(z) / l_factor + 0 * kin.q,
                                np.imag(z) / l_factor + 0 * kin.q)
            result.units[p] = l_unit
        if self.points:
            _require_finite(mech, {p: xy for p, xy in result.points.items()})
        return result


class Later:
    """The kinematics of a blockwise or compiled evaluation (:meth:`Plan._in_blocks`,
    :meth:`Plan._compiled`), solved over the whole array when first read: joining the
    blocks' costs more than solving again, and most callers read only the values.  ``q``
    is at hand; any other attribute is that of the :class:`Kinematics` the whole-array
    path makes."""

    def __init__(self, solver, q, qd, qdd, order):
        self.q = q
        self._solve = (solver, qd, qdd, order)
        self._kin = None

    def __getattr__(self, name):
        if name.startswith("__") or "_solve" not in self.__dict__:
            raise AttributeError(name)
        if self._kin is None:
            solver, qd, qdd, order = self._solve
            self._kin = _solved(solver, order, self.q, qd, qdd)
        return getattr(self._kin, name)


def _solved(solver, order, q, qd, qdd):
    """The kinematics at driver values ``q`` (SI) solved as far as ``order`` (0 positions, 1
    velocities at ``qd``, 2 accelerations at ``qdd``), unassembled and singular positions
    refused (a located SolveError)."""
    kin = solver.positions(q)
    solver.check(kin, velocities=False)
    if order >= 1:
        solver.velocities(kin, qd)
        solver.check(kin, velocities=True)
    if order >= 2:
        solver.accelerations(kin, qdd)
    return kin


def _collect_each(mech, solver, kin, names, result):
    """Every name evaluated on its own (coordinates whose arrays differ in shape)."""
    loads = _loads(mech, solver, kin, names)
    context = Context(mech, solver, kin)
    for name in names:
        result.values[name], result.units[name] = _value(mech, name, kin, loads, context)
    l_unit, l_factor = mech.units.display("length", 0)
    for p in mech.report.get("points", []):
        z = kin.pos[p]
        result.points[p] = (np.real(z) / l_factor + 0 * kin.q, np.imag(z) / l_factor + 0 * kin.q)
        result.units[p] = l_unit
    _require_finite(mech, {**result.values, **result.points})
    return result


def _finite(table) -> bool:
    """Whether every value is finite: one sum decides the common case (a NaN or an infinity
    makes it so); a sum that overflows is looked at value by value."""
    return math.isfinite(table.sum()) or bool(np.isfinite(table).all())


def _require_finite(mech, named):
    """Refuse to return NaN or infinity: overflowing data or coincident points."""
    for name, value in named.items():
        if not np.all(np.isfinite(np.asarray(value, dtype=float))):
            raise SolveError(f"'{name}' is not a finite number: the data overflow floating-point "
                             "arithmetic or the points that define it coincide",
                             file=mech.file, hint="check the magnitudes of lengths, rates and "
                             "loads, and the driver value")


def _step(mech, name):
    """(kernel, display unit) of ``name``: ``kernel(kin, out)`` writes the value in display
    units into ``out`` (an array of the driver values' shape); for an angle or its rates an
    :class:`AngleRow` instead, evaluated with the plan's other angles (:class:`Angles`);
    (None, None): the value and its unit come from :func:`_value` (the driver, textbook
    kinds, loads)."""
    base_name, order = split_rate(name)
    quantity = mech.quantities.get(base_name)
    if quantity is None or quantity.kind not in ("angle", "length", "x", "y") \
            or quantity.kind in TEXTBOOK:
        return None, None
    base = "angle" if quantity.kind == "angle" else "length"
    unit, factor = mech.units.display(base, order)
    if quantity.unit:
        unit, factor = _override(quantity.unit, base, order)
    a, b = quantity.a, quantity.b
    if quantity.kind in ("x", "y"):
        return CoordRow(a, quantity.kind == "x", order, factor), unit
    if base == "angle":
        return AngleRow(a, b, order, factor, quantity.signed and order == 0), unit
    return LengthRow(a, b, order, factor), unit


@dataclass(frozen=True)
class LengthRow:
    """A name that is the length of z = P_b - P_a (``order`` 0) or one of its rates (1, 2),
    in display units (SI over ``factor``): ``row(kin, out)`` writes it (:func:`_vector`)."""

    a: str
    b: str
    order: int
    factor: float

    def __call__(self, kin, out):
        if self.order == 0:
            value = np.abs(_rates(kin, self.a, self.b, rate=False)[0])
        else:
            value = _vector_rate(kin, self.a, self.b, self.order, False)
        _put(value, self.factor, kin, out)


@dataclass(frozen=True)
class CoordRow:
    """A name that is the x (``real``) or y of point ``a`` (``order`` 0) or one of its rates
    (1, 2), in display units (SI over ``factor``): ``row(kin, out)`` writes it."""

    a: str
    real: bool
    order: int
    factor: float

    def __call__(self, kin, out):
        z = (kin.pos, kin.vel, kin.acc)[self.order].get(self.a, 0j)
        _put(np.real(z) if self.real else np.imag(z), self.factor, kin, out)


def _probe(row):
    """(kind, a, b, order, factor, signed) of a compiled solve's probe for a name's row
    (:class:`AngleRow`, :class:`CoordRow`, :class:`LengthRow`), None for another."""
    if isinstance(row, AngleRow):
        return ANGLE_PROBE, row.a, row.b, row.order, row.factor, row.signed
    if isinstance(row, CoordRow):
        return X_PROBE if row.real else Y_PROBE, row.a, None, row.order, row.factor, False
    if isinstance(row, LengthRow):
        return LENGTH_PROBE, row.a, row.b, row.order, row.factor, False
    return None


class _Row:
    """A name's own kernel(kin, out) writing row ``i`` of the table."""

    __slots__ = ("i", "fn")

    def __init__(self, i, fn):
        self.i, self.fn = i, fn

    def __call__(self, kin, table):
        self.fn(kin, table[self.i, ...])


@dataclass(frozen=True)
class AngleRow:
    """A name that is the angle of z = P_b - P_a (``order`` 0) or one of its rates (1, 2), in
    display units (SI over ``factor``); ``signed``: in (-pi, pi] instead of [0, 2 pi)."""

    a: str
    b: str
    order: int
    factor: float
    signed: bool = False


class Angles:
    """Every :class:`AngleRow` of a plan, evaluated together: the vectors z = P_b - P_a
    stacked in one (vectors x positions) array, their rates z', z'' likewise, so each
    operation below is one pass over all the angles at once.

    Angles: arctan2 in (-pi, pi], those <= 0 gaining 2 pi, those within 1e-12 rad of
    2 pi (+-0 included) being 0 (:func:`wrap_angle`).  Rates, with w = z'/z:
    phi' = Im w, phi'' = Im(z''/z) - 2 Re w Im w.  A -0.0 is written as 0.0.  Element by
    element these are the operations of :func:`_value`, so the values are the same.
    """

    def __init__(self, rows: dict):
        """``rows``: table row -> AngleRow."""
        pairs = list(dict.fromkeys((r.a, r.b) for r in rows.values()))
        self.pairs = pairs
        self.slots = []                 # (order, table rows, vector indices, factors, signed)
        for order in (0, 1, 2):
            mine = [(i, r) for i, r in rows.items() if r.order == order]
            if not mine:
                continue
            index = [pairs.index((r.a, r.b)) for _, r in mine]
            if index == list(range(len(pairs))):
                index = slice(None)         # every vector, in order: no gather
            factors = np.array([r.factor for _, r in mine])
            signed = np.array([r.signed for _, r in mine])
            at = [i for i, _ in mine]
            if at == list(range(at[0], at[-1] + 1)):
                at = slice(at[0], at[-1] + 1)     # written in place, no scatter
            self.slots.append((order, at, index, None if np.all(factors == 1) else factors,
                               signed if signed.any() else None))
        self.rates = max(order for order, *_ in self.slots)

    def __call__(self, kin, table):
        shape = table.shape[1:]
        z = self._stack(kin.pos, shape)
        w = zz = None
        if self.rates >= 1:
            w = self._stack(kin.vel, shape)
            w /= z
        if self.rates >= 2:
            zz = self._stack(kin.acc, shape)
            zz /= z
        column = (-1,) + (1,) * len(shape)      # a value per vector, down the table
        for order, rows, index, factors, signed in self.slots:
            if factors is not None:
                factors = factors.reshape(column)
            out = table[rows] if type(rows) is slice else \
                np.empty((len(rows),) + shape)
            if order == 0:
                v = z[index]
                np.arctan2(v.imag, v.real, out=out)
                _wrap_principal(out)
                if signed is not None:
                    np.subtract(out, TWO_PI, out=out, where=(out > math.pi) & signed.reshape(column))
            elif order == 1:
                v = w[index].imag
                if factors is None:
                    np.add(v, 0.0, out=out)
                else:
                    np.divide(v, factors, out=out)
            else:
                v = w[index]
                np.multiply(v.real, v.imag, out=out)
                out *= -2.0
                out += zz[index].imag
                if factors is not None:
                    out /= factors
                else:
                    out += 0.0
            if order == 0 and factors is not None:
                out /= factors
            if type(rows) is not slice:
                table[rows] = out

    def _stack(self, points, shape):
        """(P_b - P_a) of every pair, stacked; an absent point (fixed: no rates) is 0."""
        out = np.empty((len(self.pairs),) + shape, complex)
        for i, (a, b) in enumerate(self.pairs):
            row = out[i, ...]
            pa, pb = points.get(a), points.get(b)
            if pa is None:
                row[...] = 0j if pb is None else pb
            elif pb is None:
                np.negative(pa, out=row)
            else:
                np.subtract(pb, pa, out=row)
        return out


def _put(value, factor, kin, out):
    """``value`` (SI) in display units into ``out``; -0.0 becomes 0.0 as in :func:`_value`."""
    if getattr(value, "shape", ()) != out.shape:
        out[...] = value / factor + 0 * kin.q
    elif factor != 1:
        np.divide(value, factor, out=out)
    else:
        np.add(value, 0.0, out=out)


def _loads(mech, solver, kin, names):
    """SI values of every load, solving the unknown one when a load is asked for."""
    wanted = any(mech.quantities.get(split_rate(n)[0]) is not None
                 and mech.quantities[split_rate(n)[0]].kind == "load" for n in names)
    if not wanted:
        return {}
    values = {n: load.value for n, load in mech.loads.items()}
    unit_kin = solver.velocities(kin.at_rest(), np.ones_like(kin.q))
    unknown = mech.unknown_load()
    extra = 0.0
    if mech.dynamics is not None:   # inertia, gravity, friction (d'Alembert)
        from linkcli.forces.balance import dynamic_power
        extra = dynamic_power(mech, kin, unit_kin)
    values[unknown.name] = unknown_load(mech, kin.pos, unit_kin.vel, extra_power=extra,
                                        q=kin.q)
    return values


def _value(mech, name, kin, loads, context=None):
    base_name, order = split_rate(name)
    quantity = mech.quantities[base_name]
    units = mech.units
    if quantity.kind in TEXTBOOK:
        return _textbook(quantity, order, kin, context or Context(mech, None, kin))
    if quantity.kind == "load":
        load = mech.loads[quantity.a]
        value = loads[load.name]
        if quantity.component:
            value = value * (load.direction.real if quantity.component == "x"
                             else load.direction.imag)
        kind = mech.load_unit_kind(load)
        unit = quantity.unit or units.names[kind]
        table = FORCE if kind == "force" else TORQUE
        return value / table[unit], unit
    if quantity.kind == "q":
        value = [kin.q, kin.qd, kin.qdd][order]
        base = "angle" if mech.driver.kind == "angle" else "length"
        if order == 0 and base == "angle":
            value = wrap_angle(value)
    elif quantity.kind in ("x", "y"):
        z = [kin.pos, kin.vel, kin.acc][order].get(quantity.a, 0j)
        value = np.real(z) if quantity.kind == "x" else np.imag(z)
        base = "length"
    else:
        value, base = _vector(quantity, kin, order)
        if quantity.signed and order == 0:
            value = signed_angle(value)
    unit, factor = units.display(base, order)
    if quantity.unit:
        unit, factor = _override(quantity.unit, base, order)
    if np.shape(value) == np.shape(kin.q):      # a fresh array; -0.0 becomes 0.0
        if factor != 1:
            return value / factor, unit
        if quantity.kind in ("angle", "length") and isinstance(value, np.ndarray) \
                and value.flags.owndata:        # computed here: normalise in place
            value += 0.0
            return value, unit
        return value + 0.0, unit
    return value / factor + 0 * kin.q, unit


def wrap_angle(value, principal=False):
    """Angle in [0, 2 pi); values within rounding (1e-12 rad) below 2 pi are 0.

    ``principal``: the value is already in [-pi, pi] (as from np.angle), so
    adding 2 pi to the negative ones is the same as the modulo, and cheaper.
    """
    if principal:
        return _wrap_principal(np.array(value, dtype=float))
    value = np.mod(value, TWO_PI)
    return np.where(value > TWO_PI - 1e-12, 0.0, value)


def _wrap_principal(out):
    """:func:`wrap_angle` of angles in (-pi, pi], in place: those <= 0 gain 2 pi (-0 and 0
    become 2 pi), those within 1e-12 rad of 2 pi are 0."""
    np.add(out, TWO_PI, out=out, where=out <= 0)
    np.copyto(out, 0.0, where=out > TWO_PI - 1e-12)
    return out


def signed_angle(value):
    """An angle of [0, 2 pi) in (-pi, pi]."""
    return np.where(value > math.pi, value - TWO_PI, value)


def _relative(rates, a, b):
    """rates[b] - rates[a], absent (fixed) points having zero rate."""
    if a in rates:
        return rates[b] - rates[a] if b in rates else -rates[a]
    return rates.get(b, 0j)


def _vector(quantity, kin, order):
    base = "angle" if quantity.kind == "angle" else "length"
    if order == 0:
        z = _rates(kin, quantity.a, quantity.b, rate=False)[0]
        value = wrap_angle(np.angle(z), principal=True) if base == "angle" else np.abs(z)
        return value, base
    return _vector_rate(kin, quantity.a, quantity.b, order, base == "angle"), base


def _vector_rate(kin, a, b, order, angle):
    """The rate of ``order`` (1 or 2) of the angle (``angle``) or length of P_b - P_a."""
    z, w = _rates(kin, a, b)
    if order == 1:
        return w.imag if angle else np.abs(z) * w.real
    dw = _relative(kin.acc, a, b) / z
    if angle:                           # Im(z''/z - w^2)
        return dw.imag - 2.0 * w.real * w.imag
    dw = dw - w * w
    return np.abs(z) * (dw.real + w.real ** 2)


def _rates(kin, a, b, rate=True):
    """z = P_b - P_a and (``rate``) w = z'/z, kept on ``kin`` for the other orders."""
    cache = kin.vectors if hasattr(kin, "vectors") else {}
    z, w = cache.get((a, b), (None, None))
    if z is None:
        z = kin.pos[b] - kin.pos[a]
    if rate and w is None:
        w = _relative(kin.vel, a, b) / z
    cache[(a, b)] = (z, w)
    return z, w


def _override(unit, base, order):
    """Display unit and SI factor for a quantity whose base unit is ``unit``."""
    factor = ANGLE[unit] if base == "angle" else LENGTH[unit]
    return unit + ["", "/s", "/s^2"][order], factor


# --- the textbook's quantities (docs/schema.md, "quantities") -------------------------------
class Context:
    """What several quantities of one evaluation share, computed once when first asked:
    the joint forces, the velocities per unit driver rate, the figure's positions, the
    mechanism's largest speed, size and angular velocity."""

    def __init__(self, mech, solver, kin):
        self.mech, self.solver, self.kin = mech, solver, kin
        self._cache = {}

    def _once(self, key, make):
        if key not in self._cache:
            self._cache[key] = make()
        return self._cache[key]

    def _solver(self):
        return self.solver if self.solver is not None else solver_for(self.mech)

    def reactions(self):
        from linkcli.forces.joint_forces import solve
        return self._once("reactions", lambda: solve(self.mech, self.kin))

    def unit(self):
        """The velocities for a unit driver rate (q' = 1) at the same positions."""
        return self._once("unit", lambda: self._solver().velocities(
            self.kin.at_rest(), np.ones_like(self.kin.q)))

    def figure(self) -> dict:
        """The positions of the figure: solved at the file's own driver value."""
        return self._once("figure", lambda: self._solver().positions(
            own_coordinates(self.mech)).pos)

    def speed(self):
        """The largest speed of the mechanism's points, at each position (m/s)."""
        def make():
            top = 0.0
            for v in self.kin.vel.values():
                top = np.maximum(top, np.abs(v))
            return top
        return self._once("speed", make)

    def size(self) -> float:
        """The largest distance of a point from the first one (m), over the positions."""
        def make():
            pos = self.kin.pos
            first = pos[self.mech.points[0]]
            size = max(float(np.max(np.abs(np.asarray(pos[p] - first))))
                       for p in self.mech.points)
            return size if size > 0 else 1.0
        return self._once("size", make)

    def spin(self):
        """The largest rate of the mechanism: its bodies' angular velocities and its
        largest speed over its size (1/s), at each position."""
        def make():
            mech, kin = self.mech, self.kin
            top = self.speed() / self.size()
            for name in mech.bodies:
                top = np.maximum(top, np.abs(motion.rotation(mech, name, kin.pos, kin.vel)[0]))
            for disc in (mech.dynamics.discs.values() if mech.dynamics is not None else ()):
                top = np.maximum(top, np.abs(motion.disc_spin(mech, disc, kin.pos, kin.vel)[0]))
            return top
        return self._once("spin", make)


def _textbook(quantity, order, kin, context):
    """(value, unit) of a textbook quantity's rate of ``order``, in display units."""
    mech = context.mech
    units = mech.units
    kind = quantity.kind
    if kind in ("reaction", "slider_force"):
        unit = quantity.unit or units.names["force"]
        return _force(quantity, context) / FORCE[unit] + 0 * kin.q, unit
    if kind == "velocity_ratio":
        return _ratio(quantity, context)
    value, base, level = _si(quantity, order, kin, context)
    unit, factor = units.display(base, level)
    if quantity.unit:
        unit, factor = _override(quantity.unit, base, level)
    return np.asarray(value / factor + 0 * kin.q) + 0.0, unit


def _si(quantity, order, kin, context):
    """(SI value, 'length' or 'angle', display order) of a quantity's rate of ``order``."""
    mech = context.mech
    kind, a, b = quantity.kind, quantity.a, quantity.b
    rates = (kin.pos, kin.vel, kin.acc)
    if kind == "q":
        return [kin.q, kin.qd, kin.qdd][order], mech.driver.base, order
    elif kind in ("x", "y"):
        z = rates[order].get(a, 0j)
        return (np.real(z) if kind == "x" else np.imag(z)), "length", order
    elif kind in ("angle", "length"):
        value, base = _vector(quantity, kin, order)
        return value, base, order
    if kind in ("least_speed", "least_speed_at"):
        return _least_speed(quantity, kin, context)
    if kind in ("speed", "relative_speed"):
        v = rates[1].get(a, 0j) if kind == "speed" else _relative(kin.vel, a, b)
        if order == 0:
            return np.abs(v), "length", 1
        acc = rates[2].get(a, 0j) if kind == "speed" else _relative(kin.acc, a, b)
        _require_moving(quantity, v, kin, context, "its rate (the tangential acceleration)")
        return (np.conj(v) * acc).real / np.abs(v), "length", 2
    if kind in ("acceleration", "relative_acceleration"):
        acc = kin.acc.get(a, 0j) if kind == "acceleration" else _relative(kin.acc, a, b)
        return np.abs(acc), "length", 2
    if kind in ("tangential_acceleration", "normal_acceleration"):
        v, acc = kin.vel.get(a, 0j), kin.acc.get(a, 0j)
        _require_moving(quantity, v, kin, context, f"its {kind.replace('_', ' ')}")
        part = (np.conj(v) * acc).real if kind == "tangential_acceleration" else \
            np.abs((np.conj(v) * acc).imag)
        return part / np.abs(v), "length", 2
    if kind in ("along", "normal_to"):
        z = kin.pos[b] - kin.pos[a]
        u = z / np.abs(z) * (1 if kind == "along" else 1j)
        moved = rates[order].get(quantity.c, 0j) if quantity.d is None else \
            _relative(rates[order], quantity.c, quantity.d)
        return (np.conj(u) * moved).real, "length", order
    if kind == "relative":
        z = kin.pos[b] - kin.pos[a] if order == 0 else _relative(rates[order], a, b)
        return (np.real(z) if quantity.component == "x" else np.imag(z)), "length", order
    if kind == "rotation":
        return _rotation(quantity, order, kin, context), "angle", order
    if kind == "between":
        if order == 0:
            z1, z2 = kin.pos[b] - kin.pos[a], kin.pos[quantity.d] - kin.pos[quantity.c]
            value = wrap_angle(np.angle(z2 * np.conj(z1)), principal=True)
            return (signed_angle(value) if quantity.signed else value), "angle", 0
        first = _vector(Quantity("", "angle", a, b), kin, order)[0]
        second = _vector(Quantity("", "angle", quantity.c, quantity.d), kin, order)[0]
        return second - first, "angle", order
    centre = _instant_centre(quantity, kin, context)
    if kind == "instant_centre":
        return (centre.real if quantity.component == "x" else centre.imag), "length", 0
    return np.abs(kin.pos[b] - centre), "length", 0


def _located(quantity, mech, detail, hint=None, error=SolveError):
    return error(detail, file=mech.file, key=f"quantities.{quantity.name}", line=quantity.line,
                 hint=hint)


def _require_moving(quantity, v, kin, context, what):
    """Refuse a direction of motion where the point (or the relative motion) is at rest."""
    rest = np.abs(v) <= AT_REST * context.speed()
    if not np.any(rest):
        return
    mech = context.mech
    who = f"point {quantity.a}" if quantity.kind != "relative_speed" else \
        f"the motion of {quantity.b} relative to {quantity.a}"
    name = quantity.name + ("dot" if quantity.kind in LEVEL and LEVEL[quantity.kind] == 1 else "")
    raise _located(quantity, mech, f"'{name}' is undefined "
                   f"{where_text(mech, kin.q, np.broadcast_to(rest, np.shape(kin.q)))}: {who} "
                   f"is at rest there (its velocity is 0), so {what} has no direction",
                   hint="move the driver away from that position, or give the driver a rate")


def _spinning(quantity, context):
    """(the body's name for forces.motion, or the Disc) of a rotation or an instant centre."""
    mech = context.mech
    if quantity.of == "disc":
        return None, mech.dynamics.discs[quantity.a]
    if quantity.of == "rolling":
        return mech.rolling[quantity.a].disc, None
    if quantity.of == "actuator":
        return quantity.a + ".cylinder", None
    return quantity.a, None


def _rotation(quantity, order, kin, context):
    """The body's angle (its axis: first to second point, the guide of a slider, a to b of
    an actuator; a disc of dynamics: discs: from the figure) and its rates omega, alpha."""
    mech = context.mech
    body, disc = _spinning(quantity, context)
    if disc is None:
        if order == 0:
            z = motion.axis_vector(mech, body, kin.pos)
            value = wrap_angle(np.angle(z), principal=True)
            return signed_angle(value) if quantity.signed else value
        omega, alpha = motion.rotation(mech, body, kin.pos, kin.vel,
                                       kin.acc if order == 2 else None)
        return omega if order == 1 else alpha
    if order == 0:
        guide = mech.bodies[disc.slider].guide
        z = motion.guide_axis(mech, guide, kin.pos)
        travel = (np.conj(z / np.abs(z)) * (kin.pos[disc.center] -
                                             context.figure()[disc.center])).real
        value = wrap_angle(-disc.side / disc.radius * travel)
        return signed_angle(value) if quantity.signed else value
    omega, alpha = motion.disc_spin(mech, disc, kin.pos, kin.vel,
                                    kin.acc if order == 2 else None)
    return omega if order == 1 else alpha


def _instant_centre(quantity, kin, context):
    """I = P + i v_P / omega of the body, P any of its points; relative to another body
    (``quantity.b``, Kennedy's I_jk), I = P + i (v_P - v'_P) / (omega - omega') with v'_P the
    velocity of the other body's point at P; refused where the relative motion translates."""
    mech = context.mech
    point, omega = _spin_at(mech, *_spinning(quantity, context), kin)
    moving = kin.vel.get(point, 0j)
    relative = quantity.kind == "instant_centre" and quantity.b not in (None, FRAME)
    if relative:                     # (the b of an instant_centre_distance is its point)
        other = Quantity("", "instant_centre", quantity.b, of=quantity.c)
        anchor, turn = _spin_at(mech, *_spinning(other, context), kin)
        moving = moving - kin.vel.get(anchor, 0j) - 1j * turn * (kin.pos[point] -
                                                                  kin.pos[anchor])
        omega = omega - turn
    still = np.abs(omega) <= AT_REST * context.spin()
    if np.any(still):
        what = f"body {quantity.a}" + (f" relative to {quantity.b}" if relative else "")
        raise _located(quantity, mech, f"'{quantity.name}' is undefined "
                       f"{where_text(mech, kin.q, np.broadcast_to(still, np.shape(kin.q)))}: "
                       f"{what} does not turn there (omega = 0: it translates, or the "
                       "mechanism is at rest), so it has no instant centre",
                       hint="ask for a body that turns, or move the driver")
    return kin.pos[point] + 1j * moving / omega


def _least_speed(quantity, kin, context):
    """The point of least speed on the line through points a, b of one body, P(t) = A + t u
    (u the unit vector of A -> B): v(t) = v_A + i omega t u, omega = Im((v_B - v_A)/(B - A)),
    least at t* = -Re(conj(v_A) i omega u) / omega^2 (the foot of the perpendicular from
    the instant centre); 'least_speed' is |v(t*)| (|v_A| for a body that translates),
    'least_speed_at' is t*, refused where the body translates (every point moves alike)."""
    mech = context.mech
    a, b = quantity.a, quantity.b
    z = kin.pos[b] - kin.pos[a]
    u = z / np.abs(z)
    v_a = kin.vel.get(a, 0j)
    omega = (_relative(kin.vel, a, b) / z).imag
    still = np.abs(omega) <= AT_REST * context.spin()
    safe = np.where(still, 1.0, omega)
    t = -(np.conj(v_a) * 1j * safe * u).real / (safe * safe)
    if quantity.kind == "least_speed":
        return np.where(still, np.abs(v_a), np.abs(v_a + 1j * omega * t * u)), "length", 1
    if np.any(still):
        raise _located(quantity, mech, f"'{quantity.name}' is undefined "
                       f"{where_text(mech, kin.q, np.broadcast_to(still, np.shape(kin.q)))}: "
                       f"the body of {a} and {b} does not turn there, so all its points move "
                       "alike and none has the least speed",
                       hint="move the driver, or ask for least_speed alone")
    return t, "length", 0


def _spin_at(mech, body, disc, kin):
    """(a point of the body, its angular velocity): a link's first point, a disc's centre."""
    if disc is None:
        return mech.bodies[body].points[0], motion.rotation(mech, body, kin.pos, kin.vel)[0]
    return disc.center, motion.disc_spin(mech, disc, kin.pos, kin.vel)[0]


def _force(quantity, context):
    """The force of the pin on the body (a component or its magnitude), or a slider's N or
    T, in N, from the Newton-Euler joint forces."""
    reactions = context.reactions()
    mech = context.mech
    if quantity.kind == "slider_force":
        pair = reactions.pairs[quantity.a]
        return np.asarray(pair.normal if quantity.component == "normal" else pair.friction,
                          dtype=float)
    point, body = quantity.a, quantity.b
    keys = [(point, body)] if quantity.of != "actuator" else \
        [(point, body + ".cylinder"), (point, body + ".rod")]
    key = next((k for k in keys if k in reactions.pins), None)
    if key is None:
        raise _located(quantity, mech, f"no pin at {point} acts on {body}",
                       hint="pins: " + ", ".join(f"{p} on {b}" for p, b in reactions.pins),
                       error=InputError)
    force = reactions.pins[key]
    if quantity.component == "x":
        return np.real(force)
    if quantity.component == "y":
        return np.imag(force)
    return np.abs(force)


def _ratio(quantity, context):
    """d(NAME)/dq = NAMEdot / qdot: NAME's rate at a unit driver rate, in NAME's unit per
    driver unit."""
    mech = context.mech
    units = mech.units
    target = mech.quantities[quantity.a]
    value, base, _ = _si(target, 1, context.unit(), context)
    unit, factor = units.display(base, 0)
    if target.unit:
        unit, factor = _override(target.unit, base, 0)
    q_unit, q_factor = units.display(mech.driver.base, 0)
    return np.asarray(value * q_factor / factor + 0 * context.kin.q) + 0.0, f"{unit}/{q_unit}"


def angle_period(mech, name: str, unit: str) -> float | None:
    """The turn (360 in deg, 2 pi in rad) of a quantity that is an angle, compared and
    plotted modulo a turn: an angle, a rotation, the angle between two vectors or an angle
    driver (not their rates); None for any other quantity."""
    base, order = split_rate(name)
    quantity = mech.quantities[base]
    is_angle = quantity.angular or (quantity.kind == "q" and mech.driver is not None
                                    and mech.driver.kind == "angle")
    if order or not is_angle:
        return None
    return 360.0 if unit == "deg" else 2 * math.pi
