"""The Python API: a loaded mechanism that solves itself by calling down the layers.

    >>> import linkcli
    >>> linkage = linkcli.load("mechanisms/padova-2020-07.yaml")
    >>> round(linkage.solve().values["phi1"], 1)
    28.9

:class:`Linkage` holds the validated model (``linkage.model``, plain data) and
forwards reads of the model's fields (``linkage.title``, ``linkage.report``...),
so the model itself never imports a solver.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Mapping

from linkcli.runs.limits.names import sweep_names
from linkcli.answers.quantities import Result
from linkcli.runs.sheet import evaluate
from linkcli.runs.sweep.blocks import Sweep, sweep
from linkcli.errors import InputError, LinkcliError
from linkcli.input.document import build
from linkcli.input.source import load_file, load_text
from linkcli.kinematics.compiled import switch
from linkcli.kinematics.solvers import solver_for
from linkcli.model.mechanism import Mechanism


class Linkage:
    """A mechanism file loaded for one matricola digit, ready to solve."""

    def __init__(self, model: Mechanism):
        self.model = model

    def __getattr__(self, name):
        # only reached for names Linkage does not define: the model's fields
        return getattr(self.__dict__["model"], name)

    def __repr__(self) -> str:
        return f"Linkage({self.model.title!r}, k={self.model.k})"

    def solver(self, method: str = "closed", tol: float | None = None):
        """The kinematic solver ('closed' form of the Assur groups, or 'newton')."""
        return solver_for(self.model, method, tol)

    def solve(self, q=None, qdot=None, qddot=None, *, names=None, method="closed",
              tol=None) -> Result:
        """Solve at driver value(s) ``q`` (display units; default from the file).

        Scalars or NumPy arrays are accepted.  Returns a :class:`Result` whose
        ``values`` maps every report name to its value in display units.
        ``method`` 'newton' uses Newton-Raphson on all constraint equations
        (relative tolerance ``tol``) instead of the closed form of the groups.

        With several drivers (``drivers:``) ``q``, ``qdot`` and ``qddot`` are the first
        driver's, the others held at the file's values and rates; a mapping
        ``{driver: value}`` sets any of them (one it leaves out keeps the file's).
        """
        model, q, qdot, qddot = per_driver(self.model, q, qdot, qddot)
        return evaluate(model, q, qdot, qddot, names=names, method=method, tol=tol)

    def sweep(self, q, qdot=None, qddot=None, *, names=None, method="closed",
              tol=None, ties=None) -> Sweep:
        """Solve at every driver value of the 1-D array ``q`` (display units), keeping the
        values that solve where others do not (:meth:`solve` refuses the whole array).

        Returns a :class:`linkcli.runs.sweep.blocks.Sweep`: ``solved`` marks the driver values
        answered, ``values`` maps each name (default: the report's, without its limits of
        the motion) to its values there, in ``units``; ``issues`` names what happened at
        each of the others (a range that cannot be assembled, a toggle, a friction that
        locks the mechanism, an unknown load that does no work, a pair at rest: ``kind``,
        ``group``, driver values ``lo``..``hi``, ``text()``) and the branch points passed.
        ``qdot`` and ``qddot`` are one value each (default the file's); raises only where
        no driver value at all can be assembled, or on invalid input.  With several drivers
        ``q`` is the first's, the others held at the file's values and rates or set by
        ``ties`` {NAME: expression of the first, display units} (``sweep --tie``).
        """
        return sweep(self.model, q, sweep_names(self.model, names), method, tol, qdot, qddot,
                     ties=ties)

    def evaluator(self, names=None, *, method="closed", tol=None):
        """The answers ``names`` (default: the report's) as a function of the driver, made
        once for calls at many positions: ``ev = linkage.evaluator(); ev(q, qdot, qddot)``
        gives a tuple of numbers for one driver value, an array (names x positions) for a
        1-D array, in display units and in the order of ``ev.names``; a few microseconds a
        position, where :meth:`solve` costs tens.  The same values (within rounding) and
        the same refusals as :meth:`solve`: see :mod:`linkcli.runs.evaluator`."""
        from linkcli.runs.evaluator import Evaluator
        return Evaluator(self.model, names, method, tol)

    def with_params(self, **params) -> "Linkage":
        """The same file with some of its ``params`` given other values (numbers as the file
        writes them): ``linkage.with_params(ks=200).solve()``."""
        from linkcli.input.document import rebuild
        return Linkage(rebuild(self.model, params))

    def vary(self, name: str, values, *, names=None):
        """The answers ``names`` (default: the report's) at each of ``values`` of the
        parameter ``name``: an ``runs.vary.Varied`` (``q`` the values, ``solved`` the
        rows answered, ``values`` name -> array over them, ``issues`` the values left out)."""
        from linkcli.runs.vary import vary
        return vary(self.model, name, values, names)


def jit(on: bool = True) -> bool:
    """Arrays of driver values solved by the compiled loop from now on (``on``), or by
    NumPy; whether the loop is on (numba installed): see :func:`linkcli.jit`."""
    return switch(on)


def load(path: str, k: int | None = None) -> Linkage:
    """Load and validate the mechanism file ``path`` for matricola digit ``k``.

    ``k`` overrides the file's default; ``path`` '-' reads standard input.
    """
    try:
        return Linkage(build(load_file(path), k))
    except LinkcliError as exc:
        raise exc.located(path)


def loads(text: str, k: int | None = None, name: str = "<text>") -> Linkage:
    """Like :func:`load`, from YAML text."""
    return Linkage(build(load_text(text, name), k))


def per_driver(model, q, qdot, qddot) -> tuple:
    """(model, q, qdot, qddot) with a mapping ``{driver: value}`` of ``q``, ``qdot`` or
    ``qddot`` (display units) written into the model's other drivers, and the first
    driver's entry (None: the file's) left as the argument.  A list or tuple for a
    mechanism of several drivers is refused: it would read as values of the first."""
    given = (q, qdot, qddot)
    coords = list(model.coordinates)
    names = [c.name for c in coords]
    if not any(isinstance(x, Mapping) for x in given):
        if len(coords) > 1 and any(isinstance(x, (list, tuple)) for x in given):
            raise InputError(f"q, qdot and qddot of a mechanism of {len(coords)} drivers are "
                             f"the first driver's ({names[0]}), a number or a NumPy array of "
                             f"its values; a list or tuple would read as values of "
                             f"{names[0]} alone", file=model.file, key="q",
                             hint="give each driver by name: {" + ", ".join(
                                 f"'{n}': ..." for n in names) + "}")
        return model, q, qdot, qddot
    firsts = []
    for order, (field, x) in enumerate(zip(("value", "rate", "accel"), given)):
        if not isinstance(x, Mapping):
            firsts.append(x)
            continue
        for name in x:
            if name not in names:
                raise InputError(f"{name}: not a driver of this file; its drivers: "
                                 + ", ".join(names), file=model.file, key=name,
                                 hint="name the drivers as the file does")
        for i, c in enumerate(coords[1:], start=1):
            if c.name in x:
                coords[i] = dataclasses.replace(c, **{field: _number(model, c, x[c.name])
                                                      * model.units.display(c.base, order)[1]})
        firsts.append(x.get(names[0]))
    if coords == list(model.coordinates):
        return (model, *firsts)
    model = dataclasses.replace(model, coordinates=tuple(coords), driver=coords[0])
    return (model, *firsts)


def _number(model, driver, value) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InputError(f"{driver.name}: {value!r} is not a number; a driver other than the "
                         f"first takes one value per call", file=model.file, key=driver.name,
                         hint="sweep the first driver, or call once per value") from None
