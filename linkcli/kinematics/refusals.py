"""Positions the solver refuses: a group that cannot close, a rate system that is singular.

A group's shortfall (m) is > 0 where its constraints cannot meet (by how far they miss
each other), 0 or below where they close, and inf where two lines are parallel.  A rate
system's conditioning ``measure`` = |det| / (|G_1| |G_2|), the sine of the angle between
its constraint normals, is below SINGULAR (dimensionless) at a toggle or dead point, where
the velocities are undefined.  The errors name the group, the
driver values (in the file's display unit) and the shortfall or the conditioning.
"""
from __future__ import annotations

import numpy as np

from linkcli.errors import AssemblyError, SingularError

SINGULAR = 1e-9


def assembly_error(mech, group, q, bad, worst, reason) -> AssemblyError:
    """The error of ``group`` that cannot be assembled at the driver values ``bad``."""
    return AssemblyError(
        f"cannot assemble {group.describe()} {where_text(mech, q, bad)}: {reason}",
        file=mech.file, group=group.describe(), q=q, shortfall=worst,
        hint="check the lengths and the driver value")


def singular_error(mech, group, q, bad, measure, meaning) -> SingularError:
    """The error of ``group`` singular at the driver values ``bad``; ``meaning`` says what
    its conditioning ``measure`` is."""
    least = float(np.min(measure))
    return SingularError(
        f"singular position (toggle or dead point) of {group.describe()} "
        f"{where_text(mech, q, bad)}: conditioning {least:.2e} ({meaning}); velocities are "
        "undefined there", file=mech.file, group=group.describe(), q=q, measure=least,
        hint="move the driver away from the toggle")


def length_text(mech, value) -> str:
    """A length (m) in the file's display unit."""
    unit, factor = mech.units.display("length", 0)
    return f"{value / factor:.4g} {unit}"


def where_text(mech, q, bad) -> str:
    """'at q = ...' or 'for q in [...]': the driver values ``bad`` in display units; with
    several drivers (``q`` a tuple of their values) each by its name."""
    if isinstance(q, tuple):
        bad = np.broadcast_to(bad, np.broadcast_shapes(np.shape(bad), *map(np.shape, q)))
        parts = []
        for c, x in zip(mech.coordinates, q):
            unit, factor = mech.units.display(c.base, 0)
            values = np.broadcast_to(x, bad.shape)[bad] / factor if bad.any() else \
                np.atleast_1d(np.asarray(x, float).flat[0] / factor)
            parts.append(f"{c.name} = {values[0]:.6g} {unit}" if values.min() == values.max()
                         else f"{c.name} in [{values.min():.6g}, {values.max():.6g}] {unit}")
        count = int(np.count_nonzero(bad))
        return ("at " if count <= 1 else "for ") + ", ".join(parts) + \
            (f" ({count} positions)" if count > 1 else "")
    unit, factor = mech.units.display(_driver_base(mech), 0)
    return _q_text(q, bad, factor, unit)


def _driver_base(mech) -> str:
    return "angle" if mech.driver.kind == "angle" else "length"


def _q_text(q, bad, factor, unit) -> str:
    values = np.atleast_1d(q)[np.atleast_1d(bad)] / factor
    if values.size <= 1:
        value = float(values[0]) if values.size else float(np.atleast_1d(q)[0] / factor)
        return f"at q = {value:.6g} {unit}"
    return f"for q in [{values.min():.6g}, {values.max():.6g}] {unit} ({values.size} positions)"


def _anywhere(mask) -> bool:
    """np.any(mask), without its dispatch for the arrays the groups return."""
    return mask.any() if isinstance(mask, np.ndarray) else bool(np.any(mask))


def exceeds(x, level) -> bool:
    """Whether any of ``x`` is above ``level`` (NaN is not): np.any(x > level) by one
    reduction, without the mask."""
    if type(x) is np.ndarray and x.size:
        return bool(np.fmax.reduce(x, axis=None) > level)
    return _anywhere(np.asarray(x) > level)


def under(x, level) -> bool:
    """Whether any of ``x`` is below ``level`` (NaN is not), as :func:`exceeds`."""
    if type(x) is np.ndarray and x.size:
        return bool(np.fmin.reduce(x, axis=None) < level)
    return _anywhere(np.asarray(x) < level)
