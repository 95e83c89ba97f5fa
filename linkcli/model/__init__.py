"""The model: plain typed data, filled once at load time, in SI units.

``mechanism`` (points, bodies, guides, actuators, driver, loads, quantities,
report, keys), ``dynamics`` (masses, inertias, gravity, friction, discs) and
``units`` (the unit tables and the file's display units).  No module here
solves anything.  May import: ``linkcli.errors``.
"""
