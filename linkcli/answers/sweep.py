"""Sweeps: a range of driver values solved in one vectorised pass.

Driver values are ``q_i = A + i * step`` (computed, never accumulated).  Rows
that cannot be solved are never printed as NaN: positions that cannot be
assembled are reported as ranges of q with the group and its largest
shortfall, and rows where velocities are undefined (a toggle hit exactly) are
left out and reported the same way.  Every other row is printed.

Branches: the closed form keeps each dyad's branch sign chosen at the file's
position; Newton continues the configuration step by step.  Where a group
passes a toggle, its conditioning measure (the sine of the angle between its
constraint normals; for Newton |det J| over the product of the row norms)
touches zero; such a driver value is reported as a branch point, because the
real mechanism may leave there on either branch.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from linkcli.errors import AssemblyError, InputError
from linkcli.kinematics.closed_form import SINGULAR, Kinematics
from linkcli.model.mechanism import split_rate
from linkcli.answers.quantities import collect, needed_orders, report_names, require_driver
from linkcli.kinematics.solvers import solver_for

MAX_POSITIONS = 10 ** 7


@dataclass
class Issue:
    """A range of driver values (display units) where something must be said."""

    kind: str            # 'assembly' | 'singular' | 'branch'
    group: str
    lo: float
    hi: float
    count: int
    amount: float        # shortfall (display length; inf: no configuration) or conditioning
    q_unit: str
    l_unit: str

    def text(self) -> str:
        where = (f"at q = {self.lo:.6g} {self.q_unit}" if self.count == 1 or self.lo == self.hi
                 else f"for q in [{self.lo:.6g}, {self.hi:.6g}] {self.q_unit}")
        if self.kind == "assembly":
            why = "no configuration found" if not math.isfinite(self.amount) else \
                f"links short by up to {self.amount:.4g} {self.l_unit}"
            return f"cannot assemble {where}: {self.group}, {why}"
        if self.kind == "singular":
            return (f"velocities undefined {where}: {self.group} at a toggle (conditioning "
                    f"{self.amount:.2e}); rows left out")
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


def driver_values(start: float, stop: float, steps: int | None = None,
                  step: float | None = None) -> np.ndarray:
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
    q = start + np.arange(count) * delta
    if steps is not None:
        q[-1] = stop
    return q


def check_names(mech, names) -> list:
    """The report's names, or ``names`` after checking that each is defined."""
    if not names:
        return report_names(mech)
    for name in names:
        base, _ = split_rate(name)
        if base not in mech.quantities:
            raise InputError(f"'{name}' is not a quantity of this file", key="--names",
                             hint="defined: " + ", ".join(sorted(mech.quantities)))
    return list(names)


def sweep(mech, q, names=None, method="closed", tol=None, qdot=None, qddot=None) -> Sweep:
    """Solve ``mech`` at every driver value of ``q`` (display units, 1-D)."""
    require_driver(mech, "a sweep")
    solver = solver_for(mech, method, tol)
    names = check_names(mech, names)
    units = mech.units
    base = "angle" if mech.driver.kind == "angle" else "length"
    q = np.asarray(q, dtype=float).ravel()
    q_unit, q_factor = units.display(base, 0)
    l_unit, l_factor = units.display("length", 0)
    qd = mech.driver.rate if qdot is None else qdot * units.display(base, 1)[1]
    qdd = mech.driver.accel if qddot is None else qddot * units.display(base, 2)[1]
    out = Sweep(mech, method, q, np.zeros(q.shape, bool), names, q_unit=q_unit)
    kin = solver.positions(q * q_factor)
    good = np.ones(q.shape, bool)
    for index in sorted(kin.short):
        short = np.broadcast_to(kin.short[index], q.shape)
        bad = short > 0
        own = bad & good          # downstream groups of a failed one are not blamed
        for lo, hi in _runs(own):
            out.issues.append(Issue("assembly", _describe(solver, index), q[lo], q[hi],
                                    hi - lo + 1, float(np.max(short[lo:hi + 1][own[lo:hi + 1]]))
                                    / l_factor, q_unit, l_unit))
        good &= ~bad
    if not good.any():
        raise AssemblyError(out.issues[0].text() if out.issues else "nothing to solve",
                            file=mech.file, hint="check the range and the lengths")
    sub = kin if good.all() else _subset(kin, good)
    solver.velocities(sub, qd)      # also gives every group's conditioning measure
    rows = np.nonzero(good)[0]
    keep = np.ones(rows.size, bool)
    for index in sorted(sub.measure):
        measure = np.broadcast_to(sub.measure[index], rows.shape)
        for i, qb in _touches(measure, q[rows], rows):
            out.issues.append(Issue("branch", _describe(solver, index), qb, qb, 1,
                                    float(measure[i]), q_unit, l_unit))
        singular = measure < getattr(solver, "singular", SINGULAR)
        if needed_orders(mech, names) >= 1:
            for lo, hi in _runs(singular & keep):
                out.issues.append(Issue("singular", _describe(solver, index), q[rows[lo]],
                                        q[rows[hi]], hi - lo + 1,
                                        float(np.min(measure[lo:hi + 1])), q_unit, l_unit))
            keep &= ~singular
    if not keep.all():
        sub = _subset(sub, keep)
        good[rows[~keep]] = False
    if needed_orders(mech, names) >= 2:
        solver.accelerations(sub, qdd)
    result = collect(mech, solver, sub, names)
    out.solved = good
    out.values = {n: np.broadcast_to(result.values[n], sub.q.shape) for n in names}
    out.units = dict(result.units)
    out.issues.sort(key=lambda issue: (min(issue.lo, issue.hi), issue.kind))
    return out


def _describe(solver, index) -> str:
    return solver.groups[index].describe()


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


def _subset(kin, mask) -> Kinematics:
    """The rows ``mask`` of a 1-D sweep's kinematics (positions, rates, measures)."""
    shape = kin.q.shape

    def pick(value):
        return value[mask] if np.shape(value) == shape else value

    out = Kinematics(kin.q[mask])
    out.qd = None if kin.qd is None else pick(kin.qd)
    out.qdd = None if kin.qdd is None else pick(kin.qdd)
    for src, dst in ((kin.pos, out.pos), (kin.vel, out.vel), (kin.acc, out.acc),
                     (kin.short, out.short), (kin.measure, out.measure)):
        for key, value in src.items():
            dst[key] = pick(value)
    return out


# output ----------------------------------------------------------------------------
def render(result: Sweep, form: str = "csv", every: int = 1, decimals: int | None = None) -> str:
    """CSV (default), JSON or a table of the solved rows, every ``every``-th one."""
    if every < 1:
        raise InputError(f"--every must be at least 1, got {every}", key="--every")
    q = result.q[result.solved][::every]
    columns = [result.values[n][::every] for n in result.names]
    if form == "json":
        import json
        data = {"file": result.mechanism.file, "title": result.mechanism.title,
                "k": result.mechanism.k, "method": result.method,
                "units": {"q": result.q_unit, **{n: result.units[n] for n in result.names}},
                "q": q.tolist(), "values": {n: c.tolist() for n, c in zip(result.names, columns)},
                "issues": [issue.as_dict() for issue in result.issues]}
        return json.dumps(data, indent=1)
    fmt = repr if decimals is None else (lambda v: f"{v:.{decimals}f}")
    header = [f"q [{result.q_unit}]"] + [f"{n} [{result.units[n]}]" for n in result.names]
    if form == "table":
        from tabulate import tabulate
        fmt = (lambda v: f"{v:.{4 if decimals is None else decimals}f}")
        body = [[fmt(float(v)) for v in row] for row in zip(q, *columns)]
        return tabulate(body, headers=header, disable_numparse=True, stralign="right")
    lines = [",".join(header)]
    for row in zip(q.tolist(), *(c.tolist() for c in columns)):
        lines.append(",".join(fmt(float(v)) for v in row))
    return "\n".join(lines)
