"""Order and name invariance: every shipped file with its sections and entries in another
order, or with its points and links renamed, gives the same answers.

The rewritings (tests/transforms.py):

- ``reverse``: the sections, the entries of frame, points, links, loads, quantities,
  actuators, sliders, springs, dampers, rolling and cords, of the dynamics' and the
  excitation's mappings, and the report's lists, in the reverse order;
- ``permute``: the same in a random order (a seed per file);
- ``prefix``: every point P renamed pP and every link L lL wherever they are referenced
  (links' points and shapes, sliders, drivers, coordinates, loads, quantities, expressions,
  the report's ``xP``, keys' ``P: [x, y]``, dynamics, springs, excitation, find targets);
  the alphabetical order of the points is kept, so each vector z_i of the key convention
  (from a link's alphabetically first vertex) runs as before, and the figure is the same;
- ``shuffle``: points renamed N0, N1 ... and links b0, b1 ... in a random order, with the
  entries permuted.  The alphabetical order of the points changes: only the figure's vector
  labels follow it, no answer does, so the answers must still agree.

Answers are compared as in tests/test_invariance_units.py (SI, angles modulo a turn, 1e-9);
the names of the renamed file's answers are the renamed ones (``xB`` -> ``xpB``).  Parameters
and coordinates keep their order (a parameter reads the ones before it; modes are normalised
by the first coordinate).  Planted defects at the end: the crank taken as the first link in
the file's order, or as the alphabetically first link; the figure's positions given to the
moving points by their alphabetical rank.  ``make explore`` draws new permutations and
renamings (:func:`test_random_orders_and_names`).
"""
from __future__ import annotations

import os
import random
import warnings
import zlib

import pytest
from hypothesis import given
from hypothesis import strategies as st

import transforms as T
from test_invariance_units import FILES, RANDOM, baseline, caught, data_of
from linkcli.input.document import Parser
from linkcli.kinematics import assur

VARIANTS = ("reverse", "permute", "prefix", "shuffle")

#: files the renamer leaves alone, and why
NOT_RENAMED = {
    "docs/examples/no-frame.yaml": "a section that is not a mapping (links)",
}


def _seed(path: str, salt: int = 0) -> int:
    return zlib.crc32(path.encode()) + salt


def rewrite(path: str, variant: str, seed: int):
    """(the rewritten data, its renamer or None) of ``path``."""
    data = data_of(path)
    if variant == "reverse":
        return T.reverse(data), None
    if variant == "permute":
        return T.permute(data, random.Random(seed)), None
    if variant == "prefix":
        renamer = T.Rename(data)
        return renamer.run(), renamer
    rng = random.Random(seed)
    renamer = T.shuffle_names(data, rng)
    return T.permute(renamer.run(), rng), renamer


def check(path: str, variant: str, seed: int) -> list:
    """The differences between ``path`` and its rewriting, for every digit it is solved for."""
    new, renamer = rewrite(path, variant, seed)
    names = {} if renamer is None else {"rename": renamer.answer, "point": renamer.point}
    out = []
    for k in T.digits(data_of(path)):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            outcome = T.solve(T.to_yaml(new), k, path)
        out += [f"k={k}: {d}" for d in T.differences(baseline(path, k), outcome,
                                                      T.own_units(data_of(path)), **names)]
    return out


@pytest.mark.parametrize("variant", VARIANTS)
@pytest.mark.parametrize("path", FILES)
def test_same_answers_in_another_order_and_names(path, variant, invariance_counter):
    if path in NOT_RENAMED and variant in ("prefix", "shuffle"):
        with pytest.raises((AttributeError, TypeError)):
            rewrite(path, variant, _seed(path))
        invariance_counter["names: not renamed"] += 1
        pytest.skip(f"not renamed: {NOT_RENAMED[path]}")
    differences = check(path, variant, _seed(path))
    invariance_counter[f"order and names: {variant}"] += len(T.digits(data_of(path)))
    assert not differences, f"{path} ({variant}):\n" + "\n".join(differences)


# --- the renamer itself -------------------------------------------------------------------
def test_every_reference_is_renamed():
    """A renamed file names no old point or link anywhere (only slider, actuator and load
    names may coincide with old point names, as 'E: {point: E}' does)."""
    data = data_of("mechanisms/padova-2020-07.yaml")
    new = T.Rename(data).run()
    text = T.to_yaml({k: v for k, v in new.items() if k not in ("sliders", "actuators")})
    for old in ("A", "B", "C", "D", "E", "BCD", "DE"):
        assert f"[{old}," not in text and f", {old}]" not in text and f" {old}:" not in text
    assert new["report"]["position"][-1] == "xpE"
    assert new["keys"][0]["values"]["Q"] == data["keys"][0]["values"]["Q"]
    assert new["sliders"]["E"] == {"point": "pE", "guide": {"y": 180}}
    assert T.Rename({"points": {"B": [0, 0]}}).expression("xBdot + 2*yB") == "xpBdot + 2 * ypB"


def test_renaming_refuses_a_clash():
    with pytest.raises(ValueError):
        T.Rename({"points": {"B": [0, 0]}, "quantities": {"pB": {"x": "B"}}})


# --- planted defects ----------------------------------------------------------------------
def _first_link(self, *points):
    """Planted: the crank is the first link in the file, whatever its points."""
    return next(b.name for b in self.mech.bodies.values() if b.kind == "link")


def _alphabetical_link(self, *points):
    """Planted: the crank is the alphabetically first link, whatever its points."""
    return min(b.name for b in self.mech.bodies.values() if b.kind == "link")


def _positions_by_rank(original):
    """Planted: the figure's positions given to the moving points in the order of their
    names, not by name."""
    def moving(self, *args):
        found = original(self, *args)
        return dict(zip(sorted(found), found.values()))
    return moving


PLANTED = [("crank: first link in the file", "_DECOMPOSER", "body_with", _first_link,
            "mechanisms/polimi-crank-slider.yaml", "reverse"),
           ("crank: alphabetically first link", "_DECOMPOSER", "body_with",
            _alphabetical_link, "mechanisms/khurmi-8-4-fourbar-accelerations.yaml", "shuffle"),
           ("figure: positions by the points' rank", "PARSER", "moving",
            _positions_by_rank(Parser.moving), "mechanisms/padova-2020-01.yaml", "shuffle")]
TARGETS = {"_DECOMPOSER": assur._Decomposer, "PARSER": Parser}


@pytest.mark.parametrize("what, target, attribute, planted, path, variant", PLANTED,
                         ids=[p[0] for p in PLANTED])
def test_a_name_or_order_defect_is_caught(monkeypatch, what, target, attribute, planted, path,
                                          variant):
    found = caught(lambda: check(path, variant, _seed(path)),
                   lambda: monkeypatch.setattr(TARGETS[target], attribute, planted))
    assert found, f"planted '{what}' not caught"


# --- random orders and names (make explore draws new ones) --------------------------------
RENAMED = [p for p in FILES if p not in NOT_RENAMED]


@RANDOM
@given(path=st.sampled_from(RENAMED), variant=st.sampled_from(("permute", "shuffle")),
       seed=st.integers(0, 2 ** 32 - 1))
def test_random_orders_and_names(path, variant, seed, invariance_counter):
    invariance_counter["order and names: random"] += 1
    differences = check(path, variant, seed)
    assert differences == [], f"{path} ({variant}, seed {seed}):\n" + "\n".join(differences)

