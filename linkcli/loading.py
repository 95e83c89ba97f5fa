"""Build a validated mechanism from a YAML document: the core sections, then the
optional ``dynamics:`` section, so that every problem is reported on load."""
from __future__ import annotations

from .parsing import parse


def build(doc, k: int | None = None):
    mech = parse(doc, k)
    if mech.extras.get("dynamics") is not None:
        from .dynamics import model
        model(mech)
    return mech
