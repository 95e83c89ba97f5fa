"""Answers: what one solved state of a mechanism yields, in the file's display units.

``quantities`` (the report's named quantities at driver values, or a vibration
problem's at its equilibrium: their plan, values, rates and units), ``formats``
(exam, table, json and csv renderings of a result) and ``reaction_table`` (the
joint-force table of ``--reactions``) and ``memory`` (freed working memory kept
while long arrays are solved).  Nothing here solves a file more than
once: what does is a run (``linkcli.runs``); what describes a solution in words
is a text (``linkcli.texts``).
May import: ``linkcli.errors``, ``linkcli.model``, ``linkcli.input``,
``linkcli.kinematics``, ``linkcli.forces``.
"""
