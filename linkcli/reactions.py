"""Joint reactions (Newton-Euler) and the power balance of inverse dynamics.

The entry points, gathered from the modules that hold them:

- ``newton_euler``: the equations of every body and pin (rows, unknowns, terms);
- ``pairs``: directions and points of application of sliding pairs and rolling contacts;
- ``friction``: Coulomb friction at the sliders;
- ``joint_forces``: ``solve``, the equations solved at every driver value;
- ``state``: ``kinematics``, positions to accelerations with the file's driver rates;
- ``inverse_dynamics``: ``dynamic_power``, the d'Alembert terms of the virtual power;
- ``balance``: ``balance`` and ``balance_lines``, dE/dt = W_motor - W_resistant - W_lost;
- ``reaction_table``: ``rows``, ``render``, ``as_dict`` and ``append_report``.
"""
from __future__ import annotations

from .balance import balance, balance_lines
from .friction import friction_power
from .inverse_dynamics import dynamic_power
from .joint_forces import COND_LIMIT, Reactions, solve
from .pairs import PairForce
from .reaction_table import append_report, as_dict, render, rows
from .state import kinematics

__all__ = ["COND_LIMIT", "PairForce", "Reactions", "append_report", "as_dict", "balance",
           "balance_lines", "dynamic_power", "friction_power", "kinematics", "render", "rows",
           "solve"]
