"""A file built again for another value of a parameter (``input.document.rebuild``, what
``sweep --vary`` and ``find:`` do at each value) against the file written with that value
and read from its text: the same answers, the same refusals, for every shipped file with
params (its first parameter at a few values, some of which do not assemble); and the
readings kept from one build to the next (parsed expressions, rate names) against their
definitions."""
from __future__ import annotations

import glob
import os

import numpy as np
import pytest
import yaml

from linkcli.errors import LinkcliError
from linkcli.input import document, expressions
from linkcli.input.bodies import BodiesSection
from linkcli.input.source import load_file, load_text
from linkcli.model.mechanism import split_rate
from linkcli.runs.sheet import evaluate

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FILES = sorted(glob.glob(os.path.join(ROOT, "mechanisms", "*.yaml")) +
               glob.glob(os.path.join(ROOT, "docs", "examples", "*.yaml")))
#: the first parameter times these: near the file's value, and far (often not assembling)
FACTORS = (0.97, 1.05, 3.0)


def _files():
    """(file, its document, the first parameter) of the files with params and no design
    question (a design's every value is a search: its files are covered by test_design)."""
    out = []
    for path in FILES:
        try:
            doc = load_file(path)
        except LinkcliError:        # an example of a refused file
            continue
        params = doc.data.get("params") if isinstance(doc.data, dict) else None
        if not isinstance(params, dict) or not params or "find" in doc.data:
            continue
        try:
            document.build(doc)
        except LinkcliError:        # an example of a refused file
            continue
        out.append((os.path.relpath(path, ROOT), doc, next(iter(params))))
    return out


CASES = _files()


def _answers(mech):
    """The report's answers (name -> array) or the refusal (class, key, message)."""
    try:
        result = evaluate(mech)
    except LinkcliError as exc:
        return (type(exc).__name__, exc.key, exc.detail)
    return {n: np.asarray(v, dtype=float) for n, v in result.values.items()}


def _written(doc, name, value):
    """The answers of ``doc`` written again with ``params.name: value`` and read from text."""
    data = dict(doc.data)
    data["params"] = {**data["params"], name: value}
    try:
        return _answers(document.build(load_text(yaml.safe_dump(data, sort_keys=False),
                                                 doc.name)))
    except LinkcliError as exc:
        return (type(exc).__name__, exc.key, exc.detail)


def _rebuilt(base, name, value):
    try:
        return _answers(document.rebuild(base, {name: value}))
    except LinkcliError as exc:
        return (type(exc).__name__, exc.key, exc.detail)


def _differences(doc, name, rebuilt_of=_rebuilt):
    """The values of ``name`` where the rebuilt file and the file written with the value
    disagree (answers beyond 1e-12 relative, or another refusal), with both."""
    try:
        base = document.build(doc)
        start = float(base.params[name])
    except (LinkcliError, KeyError, TypeError):
        return []
    out = []
    for factor in FACTORS:
        value = start * factor if start else factor - 1.0
        want, got = _written(doc, name, value), rebuilt_of(base, name, value)
        if isinstance(want, tuple) or isinstance(got, tuple):
            same = want == got
        else:
            same = want.keys() == got.keys() and all(
                np.allclose(got[n], want[n], rtol=1e-12, atol=0, equal_nan=True)
                for n in want)
        if not same:
            out.append((value, want, got))
    return out


@pytest.mark.parametrize("path, doc, name", CASES, ids=[c[0] for c in CASES])
def test_rebuilt_is_the_file_written_with_the_value(path, doc, name):
    assert _differences(doc, name) == []


def test_the_values_cover_refusals():
    """Some of the values compared do not assemble (the refusals are compared too).  Every
    case is tried at its far value (about 2 s in all): a stride over the cases picked
    other files as files were added, and with them fewer refusals, though the product
    refuses as before.  Two refusals at least, one of them a linkage that does not
    assemble."""
    refused = []
    for _, doc, name in CASES:
        base = document.build(doc)
        got = _rebuilt(base, name, float(base.params[name]) * FACTORS[-1])
        if isinstance(got, tuple):
            refused.append(got[0])
    assert len(refused) >= 2, refused
    assert "AssemblyError" in refused, refused


def _first_with_link_length():
    for path, doc, name in CASES:
        links = doc.data.get("links") or {}
        if any(isinstance(v, dict) and isinstance(v.get("length"), str) and name in
               v["length"] for v in links.values()):
            return path, doc, name
    raise AssertionError("no shipped file writes a link's length with its first parameter")


def test_a_section_that_keeps_the_files_values_is_caught(monkeypatch):
    """Planted: the links read with the file's own parameter values, not the new ones."""
    path, doc, name = _first_with_link_length()
    real = BodiesSection.links

    def stale(self, *args):
        names, own = self.names, dict(self.names)
        own.update({n: float(v) for n, v in (self.doc.data.get("params") or {}).items()
                    if isinstance(v, (int, float)) and not isinstance(v, bool)})
        self.names = own
        try:
            return real(self, *args)
        finally:
            self.names = names

    monkeypatch.setattr(BodiesSection, "links", stale)
    assert _differences(doc, name), path


def test_values_kept_by_text_are_caught(monkeypatch):
    """Planted: an expression's value kept by its text (the parameters it reads ignored)
    instead of its parsed tree."""
    path, doc, name = _first_with_link_length()
    real, kept = expressions.evaluate, {}

    def by_text(text, names=None, exact=False):
        key = repr(text)
        if key not in kept:
            kept[key] = real(text, names, exact)
        return kept[key]

    def rebuilt(base, name, value):
        with monkeypatch.context() as patch:
            patch.setattr(expressions, "evaluate", by_text)
            return _rebuilt(base, name, value)

    assert _differences(doc, name, rebuilt), path


def test_a_parsed_expression_is_evaluated_with_the_names_of_each_call():
    assert expressions.evaluate("2*b + a", {"a": 1.0, "b": 2.0}) == 5.0
    assert expressions.evaluate("2*b + a", {"a": 1.0, "b": 3.0}) == 7.0
    for text in ("2*", "a b", "x" * 500):     # refused at every call, not only the first
        for _ in range(2):
            with pytest.raises(LinkcliError):
                expressions.evaluate(text, {"a": 1.0})
    with pytest.raises(LinkcliError, match="too small"):
        expressions.evaluate("a * 1e-10", {"a": 1e-295})
    assert expressions.evaluate("a - a", {"a": 1.0}) == 0.0


@pytest.mark.parametrize("name, names, reading", [
    ("phi1ddot", (), ("phi1", 2)), ("phi1dot", (), ("phi1", 1)), ("phi1", (), ("phi1", 0)),
    ("wddot", {"w"}, ("w", 2)), ("wddot", {"wd"}, ("wd", 1)), ("wddot", {"w", "wd"}, ("w", 2)),
    ("wddot", (), ("w", 2)), ("ddot", (), ("d", 1)), ("dot", (), ("dot", 0)),
    ("doth", (), ("doth", 0))])
def test_rate_names(name, names, reading):
    """model.mechanism.split_rate as its docstring states it."""
    assert split_rate(name, names) == reading
