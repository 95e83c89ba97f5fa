"""Exports: a course's documents made from the same answers as ``solve`` and ``batch``.

``moodle`` writes a Moodle XML question bank (one embedded-answers question per
matricola digit), ``worked`` a worked solution as one self-contained HTML page
or Markdown.  They draw the figure, so they sit above ``pictures``.  May
import every layer below: errors, model, input, kinematics, forces, answers,
pictures.
"""
