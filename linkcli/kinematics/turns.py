"""A disc turned by a contact: its turn, its second point and that point's rates.

A contact relates measures mu_k of the bodies it touches (``contacts``),
sum c_k (mu_k - mu_k0) = 0.  Where the decomposition leaves only the turn theta of one disc
unknown (a ``roll`` group, ``assur``), the relation gives it,
theta - theta0 = -(sum of the other terms) / c, theta0 the figure's, counted continuously
(any number of turns, counter-clockwise positive), and the disc's second point is
M = C + |M - C| e^{i theta}.  Its rates: omega = -(sum of the other terms' rates) / c
(their second rates for alpha), M' = C' + i omega (M - C), M'' = C'' + (i alpha - omega^2)
(M - C).
"""
from __future__ import annotations

import numpy as np

from linkcli.kinematics.rates import known_rate


def roll_position(mech, group, pos, q, turns=None):
    """The second point M = C + |M - C| e^{i theta} of a disc a contact turns: the
    relation sum c_k (mu_k - mu_k0) = 0 (kinematics.contacts) solved for the disc's turn,
    theta - theta0 = -(sum of the other terms) / c, theta0 the figure's.  The turn is
    kept in ``turns`` (any number of turns) for the contacts solved after it."""
    rel, turn = group.constraints
    body = mech.bodies[group.bodies[0]]
    arm = abs(body.local[turn.b] - body.local[turn.a])
    ref = next(ref for t, _, ref in rel.terms if t is turn)
    theta = -rel.residual(pos, q, turns, skip=turn) / rel.coefficient(turn)
    if turns is not None:
        turns[(turn.a, turn.b)] = theta
    return pos[turn.a] + (arm * ref) * np.exp(1j * theta)


def turn_rate(group, kin, d, qrate, vel):
    """First (vel None) or second time derivative of a disc's second point M, turned by a
    contact (module docstring).

    ``d`` holds the rates found so far; the group's own point is not in it yet, so every
    rate read from ``d`` is a known one.
    """
    pos = kin.pos
    rel, turn = group.constraints
    arm = pos[group.point] - pos[turn.a]
    c = rel.coefficient(turn)
    if vel is None:
        omega = -rel.rate(pos, d, qrate, skip=turn) / c
        return known_rate(d, turn.a) + 1j * omega * arm
    omega = -rel.rate(pos, vel, kin.rates, skip=turn) / c
    alpha = -rel.accel(pos, vel, d, qrate, skip=turn) / c
    return known_rate(d, turn.a) + (1j * alpha - omega * omega) * arm
