"""Runs: a mechanism file solved once or many times, to answer what the user asked.

``sheet`` (the file's answer sheet: its report by the kinematic or the vibration
path, through the runs its report needs), ``design`` (``find:``: the file built
again at each trial until its targets hold), ``sweep`` (over the driver, with
singular rows reported), ``limits`` (extremes, strokes and time ratios over the
driver's range), ``vary`` (the whole sheet over a parameter), ``coefficients``
(a vibration problem over a parameter that only sets coefficients), ``batch``
(every matricola digit), ``check`` (answer keys at their printed precision),
and ``validate`` (every problem of a file at once).  A new run (a time integration, a
periodic regime) goes here; what it returns is data, never text.
May import: ``linkcli.errors``, ``linkcli.model``, ``linkcli.input``,
``linkcli.kinematics``, ``linkcli.forces``, ``linkcli.answers``.
"""
