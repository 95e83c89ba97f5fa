"""Design unknowns (``find:``): the values of parameters that give answers their targets.

Each trial builds the file again with the unknowns' values (input.document.rebuild) and
solves the targets as ``solve`` does (any answer: kinematics, statics, dynamics, limits,
vibrations, expressions), by the method asked (the closed form or Newton's); the residual
of a target is (answer - target) / |target| (the answer itself where the target is 0),
both in the answer's display unit, an angle's difference taken within half a turn.  A
trial that raises an error is a trial without an answer, except an error that holds at
every value (the structure's, a command-line option's): that is the answer.

- One unknown in an interval [a, b]: the residual is sampled at SAMPLES values (evenly, or
  geometrically, PER_DECADE a decade, where b / a > 10 with a > 0); next to a sample that
  cannot be solved, the edge of what can is found by bisection (geometric over decades),
  and each part that can is sampled again.  Each change of sign
  is refined by Brent's method (scipy.optimize.brentq) to XTOL of the root (not of the
  interval); between samples where |r| dips without changing sign, a bounded minimisation
  of |r| looks for two roots close together.  A root must be one: the answer there is its
  target within ROOT of the target's scale (|target|; for a target 0, a turn for an angle,
  else the typical |answer| met by the search), else the sign changed across a jump (an
  angle's wrap, a pole) and it is no root.  Several roots are listed, and one is taken only
  by the file's ``choose`` rule.
- Several unknowns (or one from a start value): scipy.optimize.root (Powell's hybrid
  method) from the start values, or least_squares within the intervals; the Jacobian at
  the solution (by differences) must not be singular, else the targets do not fix the
  unknowns.

Where no value gives the targets, the error says so with the targets' values at the ends
of the interval (or the residuals where the search stopped) and the jumps it passes the
target by; a trial where the mechanism cannot be assembled or solved next to a root is
named with its values (DesignError, exit 3).
"""
from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, field

import numpy as np

from linkcli.errors import (DesignError, InputError, LinkcliError, SolveError,
                             StructureError)
from linkcli.model.dimensions import param_unit_name

#: samples of the interval of one unknown (at least), and a decade's where it spans decades
SAMPLES = 9
PER_DECADE = 3
#: the most samples of one scan (an interval of hundreds of decades)
MOST = 240
#: a root of one unknown is refined to this fraction of its size (of the larger end of the
#: samples that bracket it)
XTOL = 1e-12
#: at a root of one unknown, |answer - target| is at most this fraction of the target's scale
ROOT = 1e-6
#: the residuals of a solution of several unknowns are at most this (relative to each
#: target's scale, Residuals.scale)
RESIDUAL = 1e-9
#: a Jacobian whose condition number is above this is singular (the targets do not fix the
#: unknowns independently)
SINGULAR = 1e10

_SOLVED: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


@dataclass
class Solution:
    """The unknowns' values (as the file writes them), the mechanism built with them, and
    how they were found."""

    values: dict
    mech: object
    evaluations: int
    method: str
    roots: list = field(default_factory=list)     # one unknown: every root found
    notes: list = field(default_factory=list)     # what the search met on the way
    units: dict = field(default_factory=dict)     # each target's display unit


def unsolved(mech) -> bool:
    """Whether ``mech`` asks a design question not answered yet."""
    return mech.design is not None and not mech.design.fixed


def resolved(mech, evaluate, method="closed", tol=None):
    """``mech`` itself, or, where it asks a design question, the mechanism built with the
    unknowns' solution (solved once per mechanism and method; ``evaluate`` is runs.sheet's,
    which solves a trial's targets by ``method``)."""
    return solve(mech, evaluate, method, tol).mech if unsolved(mech) else mech


def solve(mech, evaluate, method="closed", tol=None) -> Solution:
    """The unknowns of ``mech.design`` (kept once found, per mechanism object and method)."""
    kept = _SOLVED.setdefault(mech, {})
    found = kept.get((method, tol))
    if found is None:
        found = kept[(method, tol)] = _solve(mech, evaluate, method, tol)
    return found


def asked(mech, names) -> list:
    """``names`` without the targets of ``mech``'s design question: a course document gives
    the targets as data and asks the unknowns, not the targets back."""
    targets = {t.name for t in mech.design.targets} if mech.design is not None else set()
    return [n for n in names if n not in targets]


def answer(mech, name):
    """(value, unit) of the solved unknown ``name`` of ``mech`` (built with it)."""
    return float(mech.params[name]), param_unit_name(mech, name)


# --- the residuals ------------------------------------------------------------------------
class Residuals:
    """The targets' relative residuals as a function of the unknowns' values, counting the
    evaluations (each one the file built and solved)."""

    def __init__(self, mech, evaluate, method="closed", tol=None):
        self.mech = mech
        self.evaluate = evaluate
        self.method, self.tol = method, tol
        self.design = mech.design
        self.names = self.design.names
        self.evaluations = 0
        self.last = {}              # target -> its answer at the last trial (display units)
        self.units = {}
        self.goals = {}             # target -> its value in the answer's display unit
        self.periods = {}           # target -> its turn where it is an angle, else None
        self.scales = {}            # target -> its scale, settled after the scan
        self.history = []           # (x, {target: answer}) of every trial solved

    def variant(self, x):
        from linkcli.input.document import rebuild
        return rebuild(self.mech, {n: float(v) for n, v in zip(self.names, np.atleast_1d(x))})

    def __call__(self, x) -> np.ndarray:
        from linkcli.answers.quantities import angle_period
        self.evaluations += 1
        try:
            variant = self.variant(x)
            result = self.evaluate(variant, names=[t.name for t in self.design.targets],
                                   method=self.method, tol=self.tol)
        except LinkcliError as exc:
            if _every_trial(exc):
                raise
            raise Trial(exc, np.atleast_1d(x)) from None
        out, answers = [], {}
        for t in self.design.targets:
            value = answers[t.name] = float(np.asarray(result.values[t.name]))
            unit = self.units[t.name] = result.units[t.name]
            if not math.isfinite(value):
                raise Trial(SolveError(f"{t.name} is not a finite number there"),
                            np.atleast_1d(x))
            goal = self.goals[t.name] = self.goal(t, variant, unit)
            self.periods[t.name] = angle_period(variant, t.name, unit)
            out.append(self.difference(t.name, value) / (abs(goal) if goal else 1.0))
        self.last = answers
        self.history.append((np.atleast_1d(x).copy(), dict(answers)))
        return np.array(out)

    @staticmethod
    def goal(target, variant, unit) -> float:
        """The target's value in the answer's display unit ``unit``."""
        from linkcli.model.dimensions import dimension
        from linkcli.model.units import parse_unit
        if target.unit is None:
            return target.value
        dim = dimension(variant, target.name)
        return target.value * parse_unit(target.unit, dim)[1] / parse_unit(unit, dim)[1]

    def difference(self, name, value) -> float:
        """answer - target in the display unit, an angle's within half a turn."""
        diff = value - self.goals[name]
        period = self.periods.get(name)
        return math.remainder(diff, period) if period else diff

    def settle(self) -> None:
        """Fix each target's scale (:meth:`scale`) at the trials solved so far: those of the
        scan (or the start), before any search closes in on a root or a jump."""
        self.scales = {t.name: self.scale(t.name) for t in self.design.targets
                       if t.name in self.goals}

    def scale(self, name) -> float:
        """The size |answer - target| is measured against: |target|; for a target 0, a turn
        for an angle, else the median |answer| of the trials solved (the answer's typical
        size over the search), as settled."""
        goal = self.goals[name]
        if goal:
            return abs(goal)
        if self.periods.get(name):
            return self.periods[name]
        if name in self.scales:
            return self.scales[name]
        met = [abs(answers[name]) for _, answers in self.history if answers[name]]
        return float(np.median(met)) if met else 1.0

    def miss(self) -> float:
        """The largest |answer - target| of the last trial, each relative to its scale
        (dimensionless)."""
        return max(abs(self.difference(n, v)) / self.scale(n) for n, v in self.last.items())

    def text(self, x) -> str:
        """'ks = 120 N/m' of the unknowns' values ``x``."""
        return ", ".join(f"{n} = {v:.6g}" + (f" {u}" if (u := param_unit_name(self.mech, n))
                                              else "")
                         for n, v in zip(self.names, np.atleast_1d(x)))

    def answers(self) -> str:
        """The targets' answers at the last trial, with their units."""
        return ", ".join(f"{n} = {v:.6g} {self.units.get(n, '')}".rstrip()
                         for n, v in self.last.items())


def _every_trial(exc) -> bool:
    """Whether ``exc`` holds whatever the unknowns' values: the file's structure (its Assur
    groups), or a command-line option the file does not take; it is then the answer itself,
    with its own advice, not a trial's failure."""
    return isinstance(exc, StructureError) or (
        isinstance(exc, InputError) and str(exc.key or "").startswith("--"))


class Trial(Exception):
    """A trial of the search that could not be solved: ``error``, at the values ``x``."""

    def __init__(self, error, x):
        super().__init__(str(error))
        self.error, self.x = error, x


def _fail(mech, residuals, trial: Trial, where="") -> DesignError:
    exc = trial.error
    return DesignError(f"a trial of the design search cannot be solved at "
                       f"{residuals.text(trial.x)}{where}: {exc.detail}", file=mech.file,
                       key="find", reason="trial", values=trial.x,
                       hint="narrow the search to values where the mechanism assembles")


# --- the search ----------------------------------------------------------------------------
def _solve(mech, evaluate, method, tol) -> Solution:
    residuals = Residuals(mech, evaluate, method, tol)
    unknowns = mech.design.unknowns
    if len(unknowns) == 1 and unknowns[0].interval:
        return _one(mech, residuals, unknowns[0])
    return _several(mech, residuals)


def _decades(lo: float, hi: float) -> float:
    """How many decades [lo, hi] spans (0 where it is not positive)."""
    return math.log10(hi) - math.log10(lo) if lo > 0 else 0.0


def samples(lo: float, hi: float, count: int = SAMPLES, per_decade: int = PER_DECADE) \
        -> np.ndarray:
    """At least ``count`` values from lo to hi: geometric, ``per_decade`` a decade (at most
    MOST), for a positive range over a decade; else even."""
    decades = _decades(lo, hi)
    if decades > 1:
        return np.geomspace(lo, hi, max(count, min(MOST, math.ceil(per_decade * decades) + 1)))
    return np.linspace(lo, hi, count)


def middle(a: float, b: float) -> float:
    """The middle of [a, b]: geometric where it spans over a decade of positive values."""
    lo, hi = min(a, b), max(a, b)
    return math.sqrt(lo) * math.sqrt(hi) if _decades(lo, hi) > 1 else 0.5 * (a + b)


def _one(mech, residuals, unknown) -> Solution:
    """One unknown in [lo, hi]: every sign change of the residual refined by Brent's method,
    kept where the answer there is its target (not a jump)."""
    scan = Scan(residuals)
    scan.at(samples(unknown.lo, unknown.hi))
    if scan.failed and len(scan.failed) < len(scan.points):
        scan.edges()
        scan.fill()
    residuals.settle()
    roots, jumps = [], []
    brackets = [b for run in scan.runs() for b in _brackets(residuals, run)]
    for a, b, fa, fb in brackets:
        if fa == 0 or fb == 0:
            roots.append(a if fa == 0 else b)
            continue
        start = len(residuals.history)
        try:
            x = _polish(residuals, a, b)
            residuals([x])
        except Trial as trial:
            raise _fail(mech, residuals, trial, f", between {a:.6g} and {b:.6g}") from None
        if residuals.miss() <= ROOT:
            roots.append(x)
        else:       # the trials closing in on a jump are not answers met on the way
            jumps.append((x, dict(residuals.last)))
            del residuals.history[start:]
    roots = _distinct(sorted(roots))
    notes = scan.gaps()
    notes += [f"a jump, not a root, at {residuals.text([x])}: " + _answers(residuals, seen)
              for x, seen in jumps]
    if not roots:
        raise _no_root(mech, residuals, unknown, scan, jumps)
    value = _choose(mech, residuals, roots)
    return Solution({unknown.name: value}, residuals.variant([value]),
                    residuals.evaluations, "scan and Brent's method", roots, notes,
                    dict(residuals.units))


def _polish(residuals, a, b) -> float:
    """The root of the residual in [a, b] (a sign change) by Brent's method, to XTOL of the
    bracket's larger end: relative to the root's size, not to the interval's."""
    from scipy.optimize import brentq
    return brentq(lambda x: float(residuals([x])[0]), a, b,
                  xtol=XTOL * max(abs(a), abs(b)), rtol=4 * np.finfo(float).eps)


def _answers(residuals, seen) -> str:
    return ", ".join(f"{n} = {v:.6g} {residuals.units.get(n, '')}".rstrip()
                     for n, v in seen.items())


#: bisections of the step between a sample that is solved and one that is not
EDGE = 12


class Scan:
    """The samples of one unknown's residual: x -> residual (None where the file cannot be
    solved), and the trials that could not be."""

    def __init__(self, residuals):
        self.residuals = residuals
        self.points = {}
        self.failed = []

    def at(self, xs) -> None:
        for x in xs:
            x = float(x)
            if x in self.points:
                continue
            try:
                self.solve(x)
            except Trial as trial:
                self.points[x] = None
                self.failed.append(trial)

    def solve(self, x) -> None:
        self.points[x] = float(self.residuals([x])[0])

    def sorted(self) -> list:
        return sorted(self.points.items())

    def gaps(self) -> list:
        """'no answer at ...' of each run of samples that cannot be solved, with the error
        of its first."""
        errors = {float(t.x[0]): t.error.detail for t in self.failed}
        runs, run = [], []
        for x, f in self.sorted() + [(None, 0.0)]:
            if f is None:
                run.append(x)
            elif run:
                runs.append(run)
                run = []
        text = self.residuals.text
        return [f"no answer at {text([r[0]])}: {errors[r[0]]}" if len(r) == 1 else
                f"no answer at the {len(r)} samples from {text([r[0]])} to {text([r[-1]])}: "
                f"{errors[r[0]]}" for r in runs]

    def runs(self) -> list:
        """The runs of consecutive samples that are solved, each a list of (x, residual):
        no root is bracketed across a value where the file cannot be solved."""
        out = [[]]
        for x, f in self.sorted():
            if f is None:
                out.append([])
            else:
                out[-1].append((x, f))
        return [run for run in out if run]

    def edges(self) -> None:
        """Between each sample that cannot be solved and one that can, the edge of what can
        by bisection (EDGE halvings, geometric over decades); every value met is a sample."""
        for (a, fa), (b, fb) in zip(self.sorted(), self.sorted()[1:]):
            if (fa is None) == (fb is None):
                continue
            good, bad = (a, b) if fa is not None else (b, a)
            for _ in range(EDGE):
                x = middle(good, bad)
                try:
                    self.solve(x)
                    good = x
                except Trial:
                    bad = x

    def fill(self) -> None:
        """Each run of samples that can be solved sampled again from end to end, SAMPLES
        values (the scan met values where the file cannot be solved, and the bisections
        crowd the edges)."""
        for run in self.runs():
            if len(run) > 1:
                self.at(samples(run[0][0], run[-1][0], per_decade=0)[1:-1])


def _brackets(residuals, good) -> list:
    """(a, b, f(a), f(b)) of the intervals between the samples ``good`` ((x, f) in order)
    where the residual changes sign, and two about each dip of |f| between samples of one
    sign that a bounded minimisation finds crossing zero (two roots close together)."""
    from scipy.optimize import minimize_scalar
    out = [(a, b, fa, fb) for (a, fa), (b, fb) in zip(good, good[1:]) if fa * fb <= 0]
    for (a, fa), (m, fm), (b, fb) in zip(good, good[1:], good[2:]):
        if not (fa * fm > 0 and fm * fb > 0 and abs(fm) < min(abs(fa), abs(fb))):
            continue
        sign = 1.0 if fm > 0 else -1.0
        try:
            found = minimize_scalar(lambda x: sign * float(residuals([x])[0]), bounds=(a, b),
                                    method="bounded",
                                    options={"xatol": 1e-9 * (b - a), "maxiter": 40})
        except Trial:
            continue
        if found.fun < 0:
            x, fx = float(found.x), sign * float(found.fun)
            out += [(a, x, fa, fx), (x, b, fx, fb)]
    return sorted(out)


def _distinct(roots) -> list:
    """``roots`` (sorted) with those within 64 XTOL of the previous one (relative) left
    out."""
    out = []
    for r in roots:
        if not out or r - out[-1] > 64 * XTOL * max(abs(r), abs(out[-1])):
            out.append(r)
    return out


def _choose(mech, residuals, roots) -> float:
    """The root the file's ``choose`` names; the only one; else refused with them all."""
    if len(roots) == 1:
        return roots[0]
    rule = mech.design.choose
    listed = "; ".join(residuals.text([r]) for r in roots)
    if rule is None:
        raise DesignError(f"{len(roots)} values give the targets: {listed}",
                          file=mech.file, key="find", reason="several roots", values=roots,
                          hint="say which: find: choose: smallest, largest or {nearest: V}")
    if rule[0] == "smallest":
        return roots[0]
    if rule[0] == "largest":
        return roots[-1]
    return min(roots, key=lambda r: abs(r - rule[1]))


def _no_root(mech, residuals, unknown, scan, jumps) -> DesignError:
    """No root: the target's answers at the ends of what could be solved, the least and
    the largest met on the way, and the jumps across the target that are no root."""
    target = mech.design.targets[0]
    seen = sorted((float(x[0]), answers[target.name]) for x, answers in residuals.history)
    if not seen:
        return _fail(mech, residuals, scan.failed[0])
    unit = residuals.units[target.name]

    def at(x, value):
        return f"{value:.6g} {unit}".rstrip() + f" at {residuals.text([x])}"
    low = min(seen, key=lambda pair: pair[1])
    high = max(seen, key=lambda pair: pair[1])
    want = target.text if target.unit else f"{target.text} {unit}"
    cut = (f"; {len(scan.failed)} of the {len(scan.points)} samples cannot be solved"
           if scan.failed else "")
    jumped = "".join(_jump(residuals, target.name, want.strip(), x, answers)
                     for x, answers in jumps)
    return DesignError(f"no value of {unknown.name} in [{unknown.lo:.6g}, {unknown.hi:.6g}] "
                       f"gives {target.name} = {want.strip()}: {target.name} is "
                       f"{at(*seen[0])} and {at(*seen[-1])}, between {at(*low)} and "
                       f"{at(*high)}{jumped}{cut}", file=mech.file, key="find",
                       reason="no root", values=(unknown.lo, unknown.hi),
                       hint="widen the interval, or check that the target can be reached")


def _jump(residuals, name, want, x, answers) -> str:
    """'; ...' of a sign change of answer - target across a jump, which is no root."""
    there = f"{residuals.text([x])} ({_answers(residuals, answers)} there)"
    if residuals.periods.get(name):
        return (f"; {name} - {want} changes sign only where it wraps, half a turn from the "
                f"target, at {there}: no root")
    return f"; {name} - {want} changes sign only across a jump (a pole) at {there}: no root"


def _several(mech, residuals) -> Solution:
    """Several unknowns, or one from a start value: Powell's hybrid method from the start
    values, or least squares within the intervals."""
    from scipy.optimize import least_squares, root
    unknowns = mech.design.unknowns
    x0 = np.array([u.start if u.start is not None else middle(u.lo, u.hi) for u in unknowns])
    bounded = any(u.interval for u in unknowns)
    try:
        start = residuals(x0)
        residuals.settle()
        condition = _condition(_jacobian(residuals, x0, start))
    except Trial as trial:
        raise _fail(mech, residuals, trial) from None
    if condition > SINGULAR:
        raise _singular(mech, residuals, x0, condition)
    try:
        if bounded:
            lo = np.array([u.lo if u.interval else -np.inf for u in unknowns])
            hi = np.array([u.hi if u.interval else np.inf for u in unknowns])
            found = least_squares(residuals, x0, bounds=(lo, hi), x_scale="jac",
                                  xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=200)
            x, method = found.x, "least squares within the intervals"
        else:
            found = root(residuals, x0, method="hybr", options={"xtol": 1e-13,
                                                                 "maxfev": 200})
            x, method = found.x, "Powell's hybrid method from the start values"
    except Trial as trial:
        raise _fail(mech, residuals, trial) from None
    try:
        r = residuals(x)
        miss, reached = residuals.miss(), residuals.answers()
        jacobian = _jacobian(residuals, x, r)
    except Trial as trial:
        raise _fail(mech, residuals, trial) from None
    condition = _condition(jacobian)
    if miss > RESIDUAL:
        if condition > SINGULAR:
            raise _singular(mech, residuals, x, condition)
        raise DesignError(f"the targets cannot be reached: the search stopped at "
                          f"{residuals.text(x)} with {reached} (residuals "
                          + ", ".join(f"{v:.2e}" for v in r) + " of the targets)",
                          file=mech.file, key="find", reason="unreachable", values=x,
                          hint="check the targets, or give other start values or intervals")
    if condition > SINGULAR:
        raise _singular(mech, residuals, x, condition)
    return Solution(dict(zip(residuals.names, map(float, x))), residuals.variant(x),
                    residuals.evaluations, method, [], [], dict(residuals.units))


def _jacobian(residuals, x, r) -> np.ndarray:
    """d(residuals)/d(unknowns) at ``x`` by forward differences, each unknown scaled."""
    columns = []
    for i in range(len(x)):
        h = 1e-7 * max(abs(x[i]), 1e-3)
        step = np.array(x, dtype=float)
        step[i] += h
        columns.append((residuals(step) - r) / h)
    return np.array(columns).T


def _condition(jacobian) -> float:
    return float(np.linalg.cond(jacobian)) if np.all(np.isfinite(jacobian)) else math.inf


def _singular(mech, residuals, x, condition) -> DesignError:
    return DesignError(f"the targets do not fix the unknowns independently at "
                       f"{residuals.text(x)}: the Jacobian of the targets against the "
                       f"unknowns is singular (condition number {condition:.2e})",
                       file=mech.file, key="find", reason="singular", values=x,
                       hint="the targets depend on the unknowns only through a combination: "
                       "fix one unknown, or give a target that separates them")


# --- explain -------------------------------------------------------------------------------
def explain_lines(mech, evaluate) -> list:
    """The design question and how it was answered, for ``linkcli explain``."""
    if mech.design is None:
        return []
    design = mech.design
    lines = ["", "Design (find): the unknowns' values that give the targets"]
    for u in design.unknowns:
        where = f"in [{u.lo:.6g}, {u.hi:.6g}]" if u.interval else f"from {u.start:.6g}"
        lines.append(f"  unknown {u.name} {where}")
    for t in design.targets:
        lines.append(f"  target {t.name} = {t.text}")
    try:
        found = solve(mech, evaluate)
    except LinkcliError as exc:
        return lines + [f"  {exc.detail}"]
    lines.append(f"  {found.method}: {found.evaluations} evaluations of the file")
    if len(found.roots) > 1:
        lines.append("  roots: " + ", ".join(f"{r:.6g}" for r in found.roots) +
                     f"; chosen by '{' '.join(map(str, design.choose))}'")
    lines.append("  solution: " + ", ".join(f"{n} = {v:.10g}" for n, v in found.values.items()))
    lines += [f"  {note}" for note in found.notes]
    return lines
