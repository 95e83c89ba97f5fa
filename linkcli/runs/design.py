"""Design unknowns (``find:``): the values of parameters that give answers their targets.

Each trial builds the file again with the unknowns' values (input.document.rebuild) and
solves the targets as ``solve`` does (any answer: kinematics, statics, dynamics, limits,
vibrations, expressions); the residual of a target is (answer - target) / |target|
(the answer itself where the target is 0), both in the answer's display unit, an angle's
difference taken within half a turn.

- One unknown in an interval [a, b]: the residual is sampled at SAMPLES values (evenly, or
  geometrically where b / a > 10 with a > 0); each change of sign is refined by Brent's
  method (scipy.optimize.brentq) to the parameter's rounding; between samples where |r| dips
  without changing sign, a bounded minimisation of |r| looks for two roots close together.
  Several roots are listed, and one is taken only by the file's ``choose`` rule.
- Several unknowns (or one from a start value): scipy.optimize.root (Powell's hybrid
  method) from the start values, or least_squares within the intervals; the Jacobian at
  the solution (by differences) must not be singular, else the targets do not fix the
  unknowns.

Where no value gives the targets, the error says so with the targets' values at the ends
of the interval (or the residuals where the search stopped); a trial where the mechanism
cannot be assembled or solved is named with its values (DesignError, exit 3).
"""
from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, field

import numpy as np

from linkcli.errors import DesignError, LinkcliError
from linkcli.model.dimensions import param_unit_name

#: samples of the interval of one unknown
SAMPLES = 9
#: a root of one unknown is refined to this fraction of the interval
XTOL = 1e-12
#: the residuals of a solution of several unknowns are at most this (relative)
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


def unsolved(mech) -> bool:
    """Whether ``mech`` asks a design question not answered yet."""
    return mech.design is not None and not mech.design.fixed


def resolved(mech, evaluate):
    """``mech`` itself, or, where it asks a design question, the mechanism built with the
    unknowns' solution (solved once per mechanism; ``evaluate`` is runs.sheet's, which
    solves a trial's targets)."""
    return solve(mech, evaluate).mech if unsolved(mech) else mech


def solve(mech, evaluate) -> Solution:
    """The unknowns of ``mech.design`` (kept once found, per mechanism object)."""
    found = _SOLVED.get(mech)
    if found is None:
        found = _SOLVED[mech] = _solve(mech, evaluate)
    return found


def answer(mech, name):
    """(value, unit) of the solved unknown ``name`` of ``mech`` (built with it)."""
    return float(mech.params[name]), param_unit_name(mech, name)


# --- the residuals ------------------------------------------------------------------------
class Residuals:
    """The targets' relative residuals as a function of the unknowns' values, counting the
    evaluations (each one the file built and solved)."""

    def __init__(self, mech, evaluate):
        self.mech = mech
        self.evaluate = evaluate
        self.design = mech.design
        self.names = self.design.names
        self.evaluations = 0
        self.last = {}              # target -> its answer at the last trial (display units)
        self.units = {}
        self.history = []           # (x, {target: answer}) of every trial solved

    def variant(self, x):
        from linkcli.input.document import rebuild
        return rebuild(self.mech, {n: float(v) for n, v in zip(self.names, np.atleast_1d(x))})

    def __call__(self, x) -> np.ndarray:
        from linkcli.answers.quantities import angle_period
        from linkcli.model.dimensions import dimension
        from linkcli.model.units import parse_unit
        self.evaluations += 1
        try:
            variant = self.variant(x)
            result = self.evaluate(variant, names=[t.name for t in self.design.targets])
        except LinkcliError as exc:
            raise Trial(exc, np.atleast_1d(x)) from None
        out = []
        for t in self.design.targets:
            value = self.last[t.name] = float(np.asarray(result.values[t.name]))
            unit = self.units[t.name] = result.units[t.name]
            goal = t.value
            if t.unit is not None:      # the target in the answer's display unit
                dim = dimension(variant, t.name)
                goal *= parse_unit(t.unit, dim)[1] / parse_unit(unit, dim)[1]
            diff = value - goal
            period = angle_period(variant, t.name, unit)
            if period:
                diff = math.remainder(diff, period)
            out.append(diff / (abs(goal) if goal else 1.0))
        self.history.append((np.atleast_1d(x).copy(), dict(self.last)))
        return np.array(out)

    def text(self, x) -> str:
        """'ks = 120 N/m' of the unknowns' values ``x``."""
        return ", ".join(f"{n} = {v:.6g}" + (f" {u}" if (u := param_unit_name(self.mech, n))
                                              else "")
                         for n, v in zip(self.names, np.atleast_1d(x)))

    def answers(self) -> str:
        """The targets' answers at the last trial, with their units."""
        return ", ".join(f"{n} = {v:.6g} {self.units.get(n, '')}".rstrip()
                         for n, v in self.last.items())


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
def _solve(mech, evaluate) -> Solution:
    residuals = Residuals(mech, evaluate)
    unknowns = mech.design.unknowns
    if len(unknowns) == 1 and unknowns[0].interval:
        return _one(mech, residuals, unknowns[0])
    return _several(mech, residuals)


def samples(lo: float, hi: float, count: int = SAMPLES) -> np.ndarray:
    """``count`` values from lo to hi: geometric for a positive range over a decade."""
    if lo > 0 and hi / lo > 10:
        return np.geomspace(lo, hi, count)
    return np.linspace(lo, hi, count)


def _one(mech, residuals, unknown) -> Solution:
    """One unknown in [lo, hi]: every sign change of the residual refined by Brent's method."""
    from scipy.optimize import brentq
    xs = list(samples(unknown.lo, unknown.hi))
    fs, failed = [], []
    for x in xs:
        try:
            fs.append(float(residuals([x])[0]))
        except Trial as trial:
            fs.append(None)
            failed.append(trial)
    if failed and len(failed) < len(xs):
        xs, fs = _edges(residuals, xs, fs)
    brackets = _brackets(residuals, xs, fs)
    roots = []
    width = unknown.hi - unknown.lo

    def f(x):
        return float(residuals([x])[0])
    for a, b, fa, fb in brackets:
        if fa == 0 or fb == 0:
            roots.append(a if fa == 0 else b)
            continue
        try:
            roots.append(brentq(f, a, b, xtol=XTOL * width, rtol=4 * np.finfo(float).eps))
        except Trial as trial:
            raise _fail(mech, residuals, trial, f", between {a:.6g} and {b:.6g}") from None
    roots = _distinct(sorted(roots), XTOL * 64 * width)
    notes = [f"no answer at {residuals.text(t.x)}: {t.error.detail}" for t in failed]
    if not roots:
        raise _no_root(mech, residuals, unknown, xs, fs, failed)
    value = _choose(mech, residuals, roots)
    solution = Solution({unknown.name: value}, residuals.variant([value]),
                        residuals.evaluations, "scan and Brent's method", roots, notes)
    return solution


#: bisections of the step between a sample that is solved and one that is not
EDGE = 12


def _edges(residuals, xs, fs):
    """The samples with, beside each one that cannot be solved next to one that can, the
    last value solved found by bisection towards it (EDGE halvings): a root between the
    last solved sample and the edge of what assembles is then bracketed too."""
    out = list(zip(xs, fs))
    for (a, fa), (b, fb) in zip(list(out), list(out)[1:]):
        if (fa is None) == (fb is None):
            continue
        good, bad, f_good = (a, b, fa) if fa is not None else (b, a, fb)
        for _ in range(EDGE):
            middle = 0.5 * (good + bad)
            try:
                f_good, good = float(residuals([middle])[0]), middle
            except Trial:
                bad = middle
        out.append((good, f_good))
    out.sort(key=lambda pair: pair[0])
    return [x for x, _ in out], [f for _, f in out]


def _brackets(residuals, xs, fs) -> list:
    """(a, b, f(a), f(b)) of the intervals where the residual changes sign, and two about
    each dip of |f| between samples of one sign that a bounded minimisation finds crossing
    zero (two roots close together)."""
    from scipy.optimize import minimize_scalar
    good = [(x, f) for x, f in zip(xs, fs) if f is not None]
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


def _distinct(roots, tol) -> list:
    """``roots`` (sorted) with those within ``tol`` of the previous one left out."""
    out = []
    for r in roots:
        if not out or r - out[-1] > tol:
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


def _no_root(mech, residuals, unknown, xs, fs, failed) -> DesignError:
    """No sign change: the target's answers at the ends of what could be solved, and the
    least and the largest met on the way."""
    target = mech.design.targets[0]
    seen = sorted((float(x[0]), answers[target.name]) for x, answers in residuals.history)
    if not seen:
        return _fail(mech, residuals, failed[0])
    unit = residuals.units[target.name]

    def at(x, value):
        return f"{value:.6g} {unit}".rstrip() + f" at {residuals.text([x])}"
    low = min(seen, key=lambda pair: pair[1])
    high = max(seen, key=lambda pair: pair[1])
    want = target.text if target.unit else f"{target.text} {unit}"
    cut = f"; {len(failed)} of the {len(xs)} samples cannot be solved" if failed else ""
    return DesignError(f"no value of {unknown.name} in [{unknown.lo:.6g}, {unknown.hi:.6g}] "
                       f"gives {target.name} = {want.strip()}: {target.name} is "
                       f"{at(*seen[0])} and {at(*seen[-1])}, between {at(*low)} and "
                       f"{at(*high)}{cut}", file=mech.file, key="find", reason="no root",
                       values=(unknown.lo, unknown.hi),
                       hint="widen the interval, or check that the target can be reached")


def _several(mech, residuals) -> Solution:
    """Several unknowns, or one from a start value: Powell's hybrid method from the start
    values, or least squares within the intervals."""
    from scipy.optimize import least_squares, root
    unknowns = mech.design.unknowns
    x0 = np.array([u.start if u.start is not None else 0.5 * (u.lo + u.hi) for u in unknowns])
    bounded = any(u.interval for u in unknowns)
    try:
        start = residuals(x0)
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
        jacobian = _jacobian(residuals, x, r)
    except Trial as trial:
        raise _fail(mech, residuals, trial) from None
    condition = _condition(jacobian)
    if np.max(np.abs(r)) > RESIDUAL:
        if condition > SINGULAR:
            raise _singular(mech, residuals, x, condition)
        raise DesignError(f"the targets cannot be reached: the search stopped at "
                          f"{residuals.text(x)} with {residuals.answers()} (residuals "
                          + ", ".join(f"{v:.2e}" for v in r) + " of the targets)",
                          file=mech.file, key="find", reason="unreachable", values=x,
                          hint="check the targets, or give other start values or intervals")
    if condition > SINGULAR:
        raise _singular(mech, residuals, x, condition)
    return Solution(dict(zip(residuals.names, map(float, x))), residuals.variant(x),
                    residuals.evaluations, method, [], [])


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
