"""Kinematics: topology, then positions, velocities and accelerations.

``grubler`` (Grübler's count), ``assur`` (the Assur decomposition into ``groups``,
``contact_groups``), ``dyads`` (closed forms of each group), ``closed_form`` (the solver
along the groups, with ``branches``, ``rates``, ``turns``, ``refusals``), the
Newton family (``equations``, ``constraints``, ``corrector``, ``continuation``,
``newton``) and ``solvers``, the one place that picks a solver by method.
May import: ``linkcli.errors``, ``linkcli.model``.
"""
