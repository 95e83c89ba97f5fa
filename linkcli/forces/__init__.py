"""Forces: statics by virtual work, inverse dynamics, joint reactions, power balance.

``statics`` (virtual-power coefficients and the unknown load), ``inputs`` (one unknown
load per driver of several), ``motion``
(centres of mass, spins, energies, the power of gravity and inertia),
``friction``, ``pairs`` (directions of sliding pairs and contacts),
``newton_euler`` (the equations of every body), ``joint_forces`` (their
solution) and ``balance`` (the d'Alembert power and dE/dt = W_m - W_r - W_l).
May import: ``linkcli.errors``, ``linkcli.model``, ``linkcli.kinematics``.
"""
