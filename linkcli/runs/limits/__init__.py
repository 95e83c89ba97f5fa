"""The limits of the motion: extremes of a quantity N over a range of the driver q.

A module per concept, each stating the equation it solves and its sign conventions:
``names`` (the quantity asked, the range of q, the report's names that are limits),
``search`` (the extremes as the zeros of dN/dq where it changes sign), ``extremes`` (what
is found: ``Extreme``, ``Limits``), ``dwell`` (N held to rounding over a stretch, or
constant), ``monotonic`` (why N has no extreme, in words), ``strokes`` (greatest maximum -
least minimum), ``quick_return`` (the sweeps, times and time ratio of a crank's full turn),
``limit_positions`` (the maximum, the minimum and where they are: dead centres), ``report``
(the report's limit quantities, one value for a range) and ``table`` (``linkcli limits``'s
output).  Importers name the module they use; nothing is re-exported here.
"""
