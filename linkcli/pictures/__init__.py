"""Pictures: ``scene`` (what to draw, as geometry), ``drawing`` (matplotlib
artists), ``plotting`` (draw, plot, animate), ``exam`` (the exam's figure with its
data), ``labels`` (labels apart, off the strokes, inside the picture) and ``vibration``
(frequency responses, mode shapes, time responses).
matplotlib is imported inside the functions.
May import: ``linkcli.errors``, ``linkcli.model``, ``linkcli.input``,
``linkcli.kinematics``, ``linkcli.forces``, ``linkcli.answers``, ``linkcli.runs``,
``linkcli.texts``.
"""
