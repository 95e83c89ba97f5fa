"""Input: from YAML text to the validated model.

``source`` reads bounded YAML with line numbers, ``expressions`` evaluates the
safe arithmetic of values (never ``eval``), ``reader`` holds the located-error
readers, and the sections are read by ``bodies``, ``loads``, ``quantities`` (with a
module per family of kinds), ``report``, ``keys`` and ``dynamics``; ``document.build``
assembles them into one
:class:`~linkcli.model.mechanism.Mechanism`.  ``schema.json`` and
``templates/`` ship with it.  May import: ``linkcli.errors``, ``linkcli.model``.
"""
