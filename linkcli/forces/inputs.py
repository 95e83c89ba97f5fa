"""Statics and inverse dynamics of a mechanism of several drivers: one unknown load per
driver, by virtual work per driver's virtual motion.

For each driver j, its unit rate with the others at rest is a virtual motion (the velocities
dP/dq_j, ``kinematics.closed_form.unit_rates``); in equilibrium, or with the d'Alembert
forces of inertia and gravity (``forces.balance.dynamic_power``), the loads' powers add up
to zero for each of them:

    sum_i L_i c_ij + P_j = 0,      j = 1 .. n

with c_ij the power of a unit load i per unit rate of driver j (``statics.coefficient``;
a driver's own generalised force has c = 1 on its driver and 0 on the others) and P_j the
extra power.  The n unknown loads solve this square system, which is refused where it is
singular: where the unknowns' coefficients, each made a pure number by the mechanism's size
(``statics.normalised``), have a determinant under NO_WORK of the product of their rows'
norms (one unknown does no work that the others do not already do).
"""
from __future__ import annotations

import numpy as np

from linkcli.errors import NoWorkError
from linkcli.forces.statics import NO_WORK, coefficient, mechanism_size
from linkcli.kinematics.refusals import where_text


def load_coefficient(mech, load, pos, vel, j):
    """c_ij: the power of a unit ``load`` per unit rate of driver ``j`` (``vel`` the
    velocities of that virtual motion; ``j`` None: the one driver's, c = 1 for its load)."""
    if load.kind == "driver" and j is not None:
        return 1.0 if load.target == mech.coordinates[j].name else 0.0
    return coefficient(mech, load, pos, vel)


def _scale(mech, load, j, size) -> float:
    """The factor that makes c_ij a pure number: 1 / size for a force (length per unit q),
    times size for a length driver j (whose q is a length)."""
    target = next((c for c in mech.coordinates if c.name == load.target), None)
    per_length = load.kind in ("force", "axial") or \
        (load.kind == "driver" and target is not None and target.kind != "angle")
    angle = mech.coordinates[j].kind == "angle"
    return (1.0 / size if per_length else 1.0) * (1.0 if angle else size)


def unknown_loads(mech, pos, vels, extra=None, q=None) -> dict:
    """{name: value (SI)} of the unknown loads, one per driver; ``vels[j]`` the velocities
    of driver j's unit rate, ``extra[j]`` its extra power (0 without dynamics)."""
    unknowns = mech.unknown_loads()
    n = len(mech.coordinates)
    extra = [0.0] * n if extra is None else extra
    size = mechanism_size(mech, pos)
    rows, rhs, scaled = [], [], []
    for j in range(n):
        known = extra[j]
        for load in mech.loads.values():
            if load.value is not None:
                known = known + load.value * load_coefficient(mech, load, pos, vels[j], j)
        row = [load_coefficient(mech, u, pos, vels[j], j) for u in unknowns]
        rows.append(row)
        rhs.append(-known)
        scaled.append([c * _scale(mech, u, j, size) for c, u in zip(row, unknowns)])
    shape = np.broadcast_shapes(*(np.shape(x) for x in sum(rows, []) + rhs))
    a = np.moveaxis(np.array([[np.broadcast_to(c, shape) for c in row] for row in rows],
                             dtype=float), (0, 1), (-2, -1))
    b = np.moveaxis(np.array([np.broadcast_to(x, shape) for x in rhs], dtype=float), 0, -1)
    s = np.moveaxis(np.array([[np.broadcast_to(c, shape) for c in row] for row in scaled],
                             dtype=float), (0, 1), (-2, -1))
    _refuse_singular(mech, unknowns, s, q)
    values = np.linalg.solve(a, b[..., None])[..., 0]
    return {u.name: values[..., k] if shape else float(values[k])
            for k, u in enumerate(unknowns)}


def _refuse_singular(mech, unknowns, s, q):
    """NoWorkError where |det S| < NO_WORK prod_j |S_j| (S the pure-number coefficients)."""
    norms = np.prod(np.linalg.norm(s, axis=-1), axis=-1)
    ratio = np.abs(np.linalg.det(s)) / np.where(norms > 0, norms, 1.0)
    bad = (ratio < NO_WORK) | (norms == 0)
    if not np.any(bad):
        return
    names = ", ".join(u.name for u in unknowns)
    where = f" {where_text(mech, q, bad)}" if q is not None else ""
    raise NoWorkError(
        f"the unknown loads {names} cannot be found together{where}: their virtual power "
        f"coefficients over the drivers' motions are dependent (determinant "
        f"{float(np.min(ratio)):.1e} of the product of its rows), so one of them does no "
        "work that the others do not", file=mech.file, load=unknowns[0].name, rows=bad,
        measure=float(np.min(ratio)),
        hint="make unknown one load per driver that each driver's motion works, e.g. the "
        "drivers' own loads (type: driver, on: NAME)")
