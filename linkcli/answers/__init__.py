"""Answers: what a user asked for, evaluated and formatted.

``quantities`` (the report's named quantities in display units), ``sweep``,
``formats`` (exam, table, json, csv), ``reaction_table``, ``explain``,
``check`` (answer keys), ``batch`` (every digit k) and ``validate`` (every
problem of a file, which needs the topology and so lives above ``input``).
May import: ``linkcli.errors``, ``linkcli.model``, ``linkcli.input``,
``linkcli.kinematics``, ``linkcli.forces``.
"""
