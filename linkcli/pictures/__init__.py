"""Pictures: ``scene`` (what to draw, as geometry), ``drawing`` (matplotlib
artists) and ``plotting`` (draw, plot, animate).  matplotlib is imported inside
the functions.  May import every layer below: ``errors``, ``model``,
``input``, ``kinematics``, ``forces``, ``answers``.
"""
