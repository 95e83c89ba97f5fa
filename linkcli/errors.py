"""Exception types of linkcli.

One base class, :class:`LinkcliError`; every error carries structured fields
and builds its message in ``__str__``.  The CLI catches the base class once and
maps it to an exit code: 2 for invalid input, 3 for a mechanism that cannot be
solved.
"""
from __future__ import annotations

from dataclasses import dataclass


class LinkcliError(Exception):
    """Base class of every error linkcli raises on purpose."""

    exit_code = 1

    def __init__(self, detail: str, *, file: str | None = None, key: str | None = None,
                 line: int | None = None, hint: str | None = None):
        super().__init__(detail)
        self.detail = detail
        self.file = file
        self.key = key
        self.line = line
        self.hint = hint

    def located(self, file: str | None = None) -> "LinkcliError":
        """Return self with ``file`` filled in when it was not known yet."""
        if self.file is None and file is not None:
            self.file = file
        return self

    def where(self) -> str:
        parts = []
        if self.file:
            parts.append(self.file if self.line is None else f"{self.file}:{self.line}")
        if self.key:
            parts.append(f"key '{self.key}'")
        return ", ".join(parts)

    def __str__(self) -> str:
        where = self.where()
        msg = f"{where}: {self.detail}" if where else self.detail
        if self.hint:
            msg += f" ({self.hint})"
        return msg


class InputError(LinkcliError):
    """The file or the command line is invalid: syntax, schema, references."""

    exit_code = 2


class ExpressionError(InputError):
    """A parameter expression is malformed, unsafe or out of bounds."""


class ScaleError(InputError):
    """A length outside the range the solvers carry in double precision: ``value`` (m) is
    beyond ``bound`` (m), above it (``side`` 'large') or, for the file's largest length,
    below it ('small')."""

    def __init__(self, detail: str, *, value: float, bound: float, side: str, **kw):
        super().__init__(detail, **kw)
        self.value = value
        self.bound = bound
        self.side = side


class SolveError(LinkcliError):
    """A valid mechanism that cannot be solved as asked."""

    exit_code = 3


class EquilibriumError(SolveError):
    """No static equilibrium to linearise about, or preloads it cannot determine.

    ``reason`` names the case: 'figure' (the figure is not an equilibrium), 'stalled' (the
    search from the figure stopped short of one), 'unbounded' (the potential energy keeps
    falling beyond reach of the figure), 'undetermined' or 'inconsistent' (preloads chosen
    for equilibrium); ``residual`` is the largest generalised force left, as a fraction of
    its load scale, where one applies."""

    def __init__(self, detail: str, *, reason: str, residual: float | None = None, **kw):
        super().__init__(detail, **kw)
        self.reason = reason
        self.residual = residual


class MobilityError(SolveError):
    """Grübler's count is not 1."""


class StructureError(SolveError):
    """The structure does not decompose into the supported Assur groups."""


class DesignError(SolveError):
    """A design question (``find:``) without one answer: ``reason`` is 'no root', 'several
    roots', 'unreachable', 'singular' or 'trial' (a trial of the search that cannot be
    solved: the mechanism does not assemble there, a value is out of range); ``values`` the
    unknowns' values concerned (the roots found, the trial)."""

    def __init__(self, detail: str, *, reason: str = "", values=(), **kw):
        super().__init__(detail, **kw)
        self.reason = reason
        self.values = tuple(values)


class AssemblyError(SolveError):
    """A group cannot be assembled: its links fall short (or overlap)."""

    def __init__(self, detail: str, *, group: str = "", q=None, shortfall: float = 0.0, **kw):
        super().__init__(detail, **kw)
        self.group = group
        self.q = q
        self.shortfall = shortfall


class SingularError(SolveError):
    """Velocities are undefined: a toggle or dead point (singular Jacobian)."""

    def __init__(self, detail: str, *, group: str = "", q=None, measure: float = 0.0, **kw):
        super().__init__(detail, **kw)
        self.group = group
        self.q = q
        self.measure = measure


class AtRestError(SingularError):
    """A friction whose sense is unknown at some driver values: its pair is at rest there
    (a slider that stops, a pin whose bodies do not turn relative to each other, a disc that
    does not roll).  ``rows`` marks them, ``what`` names the friction, ``measure`` is the
    relative rate as a fraction of the mechanism's largest."""

    def __init__(self, detail: str, *, what: str = "", rows=None, **kw):
        super().__init__(detail, **kw)
        self.what = what
        self.rows = rows


class SelfLockingError(SolveError):
    """No joint forces consistent with the friction at some driver values: raising the losses
    from zero, the joint forces grow without bound before the given losses are reached (or
    the signs of the normal forces find no consistent set).  ``rows`` marks those driver
    values, ``reached`` is the fraction of the losses reached there (0 to 1; None where no
    set was found), ``what`` the losses."""

    def __init__(self, detail: str, *, rows=None, q=None, reached=None, what: str = "", **kw):
        super().__init__(detail, **kw)
        self.rows = rows
        self.q = q
        self.reached = reached
        self.what = what
        self.measure = 0.0 if reached is None else reached


class NoWorkError(SingularError):
    """The unknown load does no work at some driver values (a dead centre for it):
    ``rows`` marks them, ``measure`` is the smallest normalised coefficient ratio."""

    def __init__(self, detail: str, *, load: str = "", rows=None, **kw):
        super().__init__(detail, **kw)
        self.load = load
        self.rows = rows


class ModeError(SolveError):
    """A quantity of one mode that the mode has not: a damped frequency of a mode that does
    not oscillate, a damping ratio of a mode that nothing holds, a shape ratio to a
    coordinate that does not move in the mode, a component of a repeated frequency's shape.

    ``mode`` is the mode (from 1), ``reason`` one of 'overdamped', 'critically damped',
    'no stiffness', 'does not move', 'repeated'; ``values`` the numbers the message names
    (the decay rates -s in 1/s, the still coordinate's size against the largest)."""

    def __init__(self, detail: str, *, mode: int, reason: str, values=(), **kw):
        super().__init__(detail, **kw)
        self.mode = mode
        self.reason = reason
        self.values = tuple(values)


class FormulaLimit(SolveError):
    """A formula of ``--symbolic`` not written, the numeric answers standing: ``reason``
    'terms' where its expansion passes ``limit`` terms (``size`` the terms reached), 'time'
    where the processor time the formulas may take (``limit`` s) ran out before it
    (``size`` the seconds spent).  ``items`` are the formulas it stops."""

    def __init__(self, detail: str, *, reason: str, limit: float, size: float = 0.0,
                 items=(), **kw):
        super().__init__(detail, **kw)
        self.reason = reason
        self.limit = limit
        self.size = size
        self.items = tuple(items)


class ClutchError(SolveError):
    """Two shafts and a clutch (or a brake) that cannot do what is asked: ``reason``
    'never engages' (the friction torque can never equalise the speeds), 'slips again'
    (after engagement the torque the clutch must pass exceeds its capacity), 'reverses' (a
    shaft with a resisting torque would turn back) or 'never reaches' (a speed a shaft
    does not reach); ``values`` the numbers the message names (N m, rad/s^2, s)."""

    def __init__(self, detail: str, *, reason: str, values=None, **kw):
        super().__init__(detail, **kw)
        self.reason = reason
        self.values = dict(values or {})


class EfficiencyError(SolveError):
    """An efficiency that is not defined where it is asked: ``reason`` 'no input' (the
    unknown load does not drive the mechanism: its power is not positive), 'no ideal input'
    (it would not drive it without friction), 'no ideal output' (the loads would not drive
    the mechanism back even without friction) or 'never locks' (no friction up to a
    million times the given one locks it); ``values`` the numbers the message names."""

    def __init__(self, detail: str, *, reason: str, values=None, **kw):
        super().__init__(detail, **kw)
        self.reason = reason
        self.values = dict(values or {})


@dataclass
class Caution:
    """A result that is given, but that the reader must look at: a figure far from the
    solved position, an ambiguous or forced branch, a contact that lifts off.

    ``kind`` names the case; ``points`` maps the points concerned to a number (a
    distance, in the file's length unit, or a force) where one applies.
    """

    kind: str
    detail: str
    file: str | None = None
    points: dict | None = None

    def located(self, file: str | None) -> "Caution":
        if self.file is None and file is not None:
            self.file = file
        return self

    def __str__(self) -> str:
        label = "error" if self.kind == "unassembled" else "warning"
        return f"{self.file}: {label}: {self.detail}" if self.file else f"{label}: {self.detail}"


class RegimeError(SolveError):
    """A machine without the periodic regime (or the flywheel) asked: ``reason`` is
    'unbalanced' (the mean torque over a cycle is not zero: it runs away or stops),
    'stalls', 'runs away', 'stops', 'unstable' (the orbit repels), 'no convergence' (the
    shooting), 'no inertia', 'no mean speed', 'overdetermined', or 'no flywheel' (a
    coefficient of fluctuation no flywheel gives); ``values`` the numbers the message
    names."""

    def __init__(self, detail: str, *, reason: str, values=(), **kw):
        super().__init__(detail, **kw)
        self.reason = reason
        self.values = tuple(values)
