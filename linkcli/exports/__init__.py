"""Exports: a course's documents made from the same answers as ``solve`` and ``batch``.

``moodle`` writes a Moodle XML question bank (one embedded-answers question per
matricola digit), ``worked`` a worked solution as one self-contained HTML page
or Markdown, ``booklet`` the paper exam and the solutions booklet of a set of
digits as HTML pages to print.  They draw the figure and write the texts, so they sit above
``pictures`` and ``texts``.  A new document goes here.
May import: ``linkcli.errors``, ``linkcli.model``, ``linkcli.input``,
``linkcli.kinematics``, ``linkcli.forces``, ``linkcli.answers``, ``linkcli.runs``,
``linkcli.texts``, ``linkcli.pictures``.
"""
