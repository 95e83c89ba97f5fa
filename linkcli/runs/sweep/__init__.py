"""Sweeps over the driver: a range of driver values solved block by block, in vectorised passes.

A newcomer finds each part by its name:

- ``driver_range``: the driver values ``q_i = A + i * step`` of ``--from``/``--to``/``--steps``
  or ``--step`` (computed, never accumulated), made a block at a time;
- ``names``: the quantities a sweep reports, checked against the file;
- ``issues``: what is said of the rows without answers (ranges of q that cannot be
  assembled, toggles, loads without work, branch points);
- ``blocks``: the sweep solved a block of driver values at a time (``Sweeper``, ``sweep``),
  the rows that cannot be solved reported as ranges of q, never printed as NaN;
- ``branch_points``: the toggles a group passes between two neighbouring samples;
- ``newton_path``: Newton's positions over a sweep longer than a block, and near a toggle;
- ``output``: the solved rows printed as CSV, JSON or a table, a block at a time.

Units: every driver value and every answer a sweep holds is in display units; the
solvers are called in SI (``Sweeper.q_factor`` converts the driver's values).
"""
