"""The evaluation plan: how a list of names is evaluated on one mechanism, worked out once
(:func:`plan_for`), and the :class:`Result` it returns, every value in its display unit.
"""
from __future__ import annotations

import math
import os
import weakref
from dataclasses import dataclass, field

import numpy as np

from linkcli.answers.memory import LONG, keep_freed_memory
from linkcli.answers.quantities.gearing import gear_value
from linkcli.answers.quantities.drive import Drive
from linkcli.answers.quantities.forces import JOINT_FORCES, force_value, loads_at
from linkcli.answers.quantities.geometry import override_unit, signed_angle, vector, \
    wrap_angle
from linkcli.answers.quantities.rows import AngleRow, Angles, probe_of, row_of, _Row
from linkcli.answers.quantities.textbook import Context, textbook_value, TEXTBOOK
from linkcli.input.efficiency import EFFICIENCY
from linkcli.errors import InputError, LinkcliError, SolveError
from linkcli.kinematics.compiled import X as X_PROBE, Y as Y_PROBE, compiled, program_of
from linkcli.kinematics.solvers import solver_for
from linkcli.kinematics.straight import SHORT, straight_of
from linkcli.model.mechanism import MACHINE, REPORT_SECTIONS, VIBRATION, split_rate
from linkcli.input.quantities import LEVEL
from linkcli.input.gears import GEARING
from linkcli.model.units import FORCE, TORQUE

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
    from linkcli.answers.quantities.expressions import expand
    names, _ = expand(mech, names)
    for name in names:
        base, order = split_rate(name, mech.quantities)
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
    if kind in JOINT_FORCES or kind in EFFICIENCY:
        return 2 if mech.dynamics is not None else 0
    if kind in MACHINE:
        return 1
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
    if mech.elements is not None:
        raise InputError(f"{what} varies the driver, and this file declares coordinates "
                         "(a vibration problem) instead", file=mech.file,
                         hint="use 'linkcli solve', 'linkcli sweep --vary NAME=FROM:TO:STEPS' "
                         "(a parameter), or 'linkcli plot' with --vary, --frf, --modes or "
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
        names = report_names(mech) if names is None else list(names)
        from linkcli.answers.quantities.expressions import Derived, expand
        solve, exprs = expand(mech, names)
        plan = plans[key] = Plan(mech, names, method, tol) if not exprs else \
            Derived(names, plan_for(mech, solve, method, tol), exprs)
    return plan


class Plan:
    """How a list of names is evaluated on one mechanism, worked out once.

    Building it parses the names (base quantity, order of rate), refuses the ones that are
    not defined (rates of loads, rates a quantity has not), finds the order of kinematics
    they need and each one's display unit and SI factor, and picks each one's evaluation:
    angles, lengths, coordinates and the driver by a few array operations written straight
    into one preallocated (names x positions) array; the other kinds by :func:`value_of`.
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
            base, order = split_rate(name, mech.quantities)
            quantity = mech.quantities.get(base)
            if quantity is not None and quantity.kind == "load":
                self.wants_loads = True
                if order:
                    raise InputError(f"'{name}': a load has no rates", file=mech.file,
                                     key="names", hint=f"ask for the load itself, '{base}'")
        driver = "angle" if mech.driver is not None and mech.driver.kind == "angle" \
            else "length"
        self.q_factors = [mech.units.display(driver, i)[1] for i in range(3)]
        self.steps = [row_of(mech, name) for name in self.names]
        #: every name's display unit, in order (those of value_of's names come with their values)
        self.units = {name: unit for name, (_, unit) in zip(self.names, self.steps)}
        #: (row, name) of the names evaluated by value_of (their units come with the values)
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
        self.probes = [probe_of(fn) for fn, _ in self.steps]
        if None in self.probes or self.wants_loads:
            self.probes = None
        else:           # the report's points: x and y rows after the names'
            self.probes += [(axis, p, None, 0, f, False) for p, _, f in self.points
                            for axis in (X_PROBE, Y_PROBE)]
        self._program = False           # (program, probes) built at the first compiled call
        self._straight = False          # the straight-line solve (at the second call)
        self._called = False

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
        single = len(mech.coordinates) == 1      # several drivers: the general path
        straight = self._straight_of(solver, order) if single else None
        if straight is not None:
            result = self._one_position(mech, solver, straight, q, qdot, qddot)
            if result is not None:
                return result
        driver = self._driver_si(mech, q, qdot, qddot)
        if single and q is not None and self.probes is not None and np.size(q) <= COMPILED_MOST \
                and compiled() is not None:
            result = self._compiled(mech, solver, order, *driver)
            if result is not None:
                return result
        if q is not None and np.size(q) >= LONG:
            keep_freed_memory()
        if straight is not None and q is not None:
            result = self._straight_array(mech, solver, straight, *driver)
            if result is not None:
                return result
        if single and q is not None and np.size(q) > BLOCK and self._blockwise:
            result = self._in_blocks(mech, solver, order, *driver)
            if result is not None:
                return result
        result = self.collect(mech, solver, solved(solver, order, *driver))
        if q is None:       # the file's own position: what the figure check says of it
            from linkcli.kinematics.solvers import figure_cautions
            result.cautions = figure_cautions(mech, self.method, self.tol) + result.cautions
        return result

    def _straight_of(self, solver, order, now=False):
        """The straight-line solve of these names (``kinematics.straight``), None where it
        cannot express them; worked out at the second call (or ``now``): writing it costs
        about a millisecond, the time of a few calls by the general path, which a file
        solved once (a command, a trial of a design question, a value of a parameter
        sweep) would not win back."""
        if self._straight is False:
            if not now and not self._called:
                self._called = True
                return None
            self._straight = straight_of(solver, self.probes, order) \
                if self.probes is not None and self.method == "closed" else None
        return self._straight

    def _one_position(self, mech, solver, straight, q, qdot, qddot):
        """:meth:`evaluate` of one position (numbers) by the straight-line solve; None where
        it is not one position or a check leaves it to the general path (which answers the
        close cases and words the refusals)."""
        driver = mech.driver
        f0, f1, f2 = self.q_factors
        try:
            w = driver.rate if qdot is None else as_number(qdot, f1)
            al = driver.accel if qddot is None else as_number(qddot, f2)
            qs = driver.value if q is None else as_number(q, f0)
            if qs is None or w is None or al is None:
                return None
            values = straight.scalar(qs, w, al)
        except (ArithmeticError, ValueError, TypeError):    # a domain error, a division
            return None                                     # by 0, no rate given
        if values is None:
            return None
        result = self._tabled(mech, np.array(values), Later(solver, qs, w, al, straight.order))
        if q is None:       # the file's own position: what the figure check says of it
            from linkcli.kinematics.solvers import figure_cautions
            result.cautions = figure_cautions(mech, self.method, self.tol)
        return result

    def _straight_array(self, mech, solver, straight, qs, w, al):
        """:meth:`evaluate` of a 1-D array of at most BLOCK driver values (SI) by the
        straight-line solve; None as :meth:`_one_position`."""
        if qs.ndim != 1 or qs.size > BLOCK or not qs.size or w is None or al is None or \
                any(np.ndim(x) and np.shape(x) != qs.shape for x in (w, al)):
            return None
        table = straight.short(qs, w, al) if qs.size <= SHORT else straight.array(qs, w, al)
        return None if table is None else \
            self._tabled(mech, table, Later(solver, qs, w, al, straight.order))

    @property
    def _blockwise(self) -> bool:
        """Whether every name is a kernel of the positions and rates alone (no loads, no
        quantity that looks at all the positions at once, no points): then a long array of
        driver values may be solved block by block."""
        return self.method == "closed" and not self.generic and not self.wants_loads \
            and not self.points

    def _driver_si(self, mech, q, qdot, qddot) -> tuple:
        """(q, q', q'') in SI from display units, the file's values where not given.  With
        several drivers each is a tuple over them: ``q`` and its rates are the first
        driver's, the others' are the file's (``Drive``)."""
        f0, f1, f2 = self.q_factors
        driver = mech.driver
        first = (driver.value if q is None else np.asarray(q, float) * f0,
                 driver.rate if qdot is None else np.asarray(qdot, float) * f1,
                 driver.accel if qddot is None else np.asarray(qddot, float) * f2)
        return Drive(mech)(*first)

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

        straight = self._straight_of(solver, order, now=True)
        if straight is not None:
            straight.function(True)     # written once, before the threads share it

        def solve(lo):
            hi = min(qs.size, lo + BLOCK)
            if straight is not None:
                part = straight.array(qs[lo:hi], qd[lo:hi] if np.ndim(qd) else qd,
                                      qdd[lo:hi] if np.ndim(qdd) else qdd)
                if part is not None:
                    table[:, lo:hi] = part[:len(self.names)]
                    return
            part = solved(solver, order, qs[lo:hi], qd[lo:hi] if np.ndim(qd) else qd,
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
        context = Context(mech, solver, kin) if self.generic or self.wants_loads else None
        loads = loads_at(mech, solver, kin, self.names, context) if self.wants_loads else {}
        table = np.empty((len(self.names),) + shape)
        for kernel in self.kernels:
            kernel(kin, table)
        result.units = dict(self.units)
        for i, name in self.others:
            table[i, ...], result.units[name] = value_of(mech, name, kin, loads, context)
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
        if context is not None:
            result.cautions += context.cautions()
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
            self._kin = solved(solver, order, self.q, qd, qdd)
        return getattr(self._kin, name)


def solved(solver, order, q, qd, qdd):
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


def as_number(x, factor):
    """``x`` times ``factor`` where ``x`` is one number (a float, an int, a 0-d array), else
    None."""
    if type(x) is float or type(x) is int:
        return x * factor
    if type(x) is np.ndarray and not x.ndim or isinstance(x, np.floating):
        return float(x) * factor
    return None


def _collect_each(mech, solver, kin, names, result):
    """Every name evaluated on its own (coordinates whose arrays differ in shape)."""
    loads = loads_at(mech, solver, kin, names)
    context = Context(mech, solver, kin)
    for name in names:
        result.values[name], result.units[name] = value_of(mech, name, kin, loads, context)
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


def value_of(mech, name, kin, loads, context=None):
    base_name, order = split_rate(name, mech.quantities)
    quantity = mech.quantities[base_name]
    units = mech.units
    if quantity.kind == "design":           # a solved parameter: the file's value
        from linkcli.model.dimensions import param_unit_name
        value = float(mech.params[base_name])
        return value + 0 * np.asarray(kin.q, dtype=float), param_unit_name(mech, base_name)
    if quantity.kind in GEARING:
        return gear_value(mech, quantity, kin)
    if quantity.kind in JOINT_FORCES:
        return force_value(quantity, kin, context or Context(mech, None, kin))
    if quantity.kind in EFFICIENCY:
        from linkcli.answers.quantities.efficiency import efficiency_value
        return efficiency_value(quantity, kin, context or Context(mech, None, kin))
    if quantity.kind in MACHINE:
        from linkcli.answers.quantities.machine import reduced_value
        return reduced_value(mech, quantity, kin)
    if quantity.kind in TEXTBOOK:
        return textbook_value(quantity, order, kin, context or Context(mech, None, kin))
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
        value, base = vector(quantity, kin, order)
        if quantity.signed and order == 0:
            value = signed_angle(value)
    unit, factor = units.display(base, order)
    if quantity.unit:
        unit, factor = override_unit(quantity.unit, base, order)
    if np.shape(value) == np.shape(kin.q):      # a fresh array; -0.0 becomes 0.0
        if factor != 1:
            return value / factor, unit
        if quantity.kind in ("angle", "length") and isinstance(value, np.ndarray) \
                and value.flags.owndata:        # computed here: normalise in place
            value += 0.0
            return value, unit
        return value + 0.0, unit
    return value / factor + 0 * kin.q, unit
