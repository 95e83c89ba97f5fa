"""The kinematic state for force analysis: positions, velocities and accelerations with
the file's driver rates, and velocities per unit driver rate (the virtual-power
coefficients)."""
from __future__ import annotations

import numpy as np

from .results import solver_for


def kinematics(mech, q=None, method="closed", tol=None):
    """(kin, unit) at driver value(s) ``q`` (SI; default the file's): ``kin`` with the file's
    qdot and qddot, ``unit`` the velocities for qdot = 1."""
    solver = solver_for(mech, method, tol)
    d = mech.driver
    q = d.value if q is None else q
    kin = solver.positions(q)
    solver.check(kin, velocities=False)
    solver.velocities(kin, d.rate)
    solver.check(kin, velocities=True)
    solver.accelerations(kin, d.accel)
    unit = solver.velocities(type(kin)(kin.q, pos=kin.pos), np.ones_like(kin.q))
    return kin, unit
