"""Texts: a solution described in words and formulas, for the terminal and the documents.

``data`` (the problem's data in words, Italian or English: ``bodies``, ``loads``,
``masses`` and ``elements`` state each part, ``amounts`` its numbers with their units,
``phrases`` the words of both languages, ``unknowns`` a design question's unknowns),
``quantities`` (what each reported quantity is), ``explain`` (Grübler's count, the decomposition and the
solving order), ``pseudocode`` (that order as the exam's pseudo-MATLAB dyad
calls), ``symbolic`` (the formulas of ``--symbolic`` as text and JSON) and
``notation`` (a formula written as the exam writes it: text, LaTeX, MathML).
The documents (``linkcli.exports``) and the exam's figure (``linkcli.pictures``)
are made from these texts.
May import: ``linkcli.errors``, ``linkcli.model``, ``linkcli.input``,
``linkcli.kinematics``, ``linkcli.forces``, ``linkcli.answers``, ``linkcli.runs``.
"""
