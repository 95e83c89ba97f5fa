"""The report's quantities: every named answer in its display unit.

A newcomer finds each part by its name:

- ``plan``: the evaluation plan of a list of names (built once per mechanism), the
  :class:`Result`, ``evaluate`` and ``collect``;
- ``drive``: several drivers moved from the first (held, or tied by an expression);
- ``rows``: angles, lengths and coordinates written straight into the plan's table;
- ``geometry``: angles, lengths and coordinates of the kinematics and their rates;
- ``textbook``: speeds, accelerations, projections, rotations, instant centres, ratios;
- ``forces``: loads, joint forces and slider forces as answers;
- ``vibration``: the answers of a vibration problem (equilibrium, matrices, modes,
  damping, steady-state and free response).
"""
from linkcli.answers.quantities.geometry import angle_period, signed_angle, wrap_angle
from linkcli.answers.quantities.plan import BLOCK, COMPILED_MOST, WORKERS, Later, Plan, \
    Result, collect, evaluate, needed_orders, plan_for, report_names, require_driver, \
    require_rate
from linkcli.answers.quantities.textbook import AT_REST, TEXTBOOK, Context

__all__ = ["AT_REST", "BLOCK", "COMPILED_MOST", "TEXTBOOK", "WORKERS", "Context", "Later",
           "Plan", "Result", "angle_period", "collect", "evaluate", "needed_orders", "plan_for",
           "report_names", "require_driver", "require_rate", "signed_angle", "wrap_angle"]
