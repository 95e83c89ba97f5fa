"""Every shipped file moved, turned and scaled (tests/geometry_transform.py, written from the
file format): its answers must follow.

The frame: the whole figure turned by THETA about the origin and moved by T (frame and moving
points, guides' lines and directions, loads' and gravity's directions, an angle driver's
value).  Lengths, speeds, forces, torques, frequencies stay; absolute angles turn by THETA
(modulo a turn); a point's coordinates move as the point (R p + t, their rates R v).  A file
driven along an axis or with coordinates along one (x, y) is only moved (THETA = 0).

The scale: the geometry times s, masses and times kept, loads as their dimension (see the
transformation's docstring): every answer scales as s to its unit's length power.  Beyond
the range a double carries (1e200, 1e-200) every file with a length is refused by name
(exit 2): never assembled, never called a toggle.

A file whose untouched solve fails must fail the same way after the transformation.  Every
file is solved at each k its answer keys name and at its default.  Answers whose change the
transformation does not know (an x component of a reaction, an expression of parameters)
are counted, not compared; files with a key it does not know are listed.  LINKCLI_EXPLORE=1
adds random angles, translations and scales.
"""
from __future__ import annotations

import glob
import json
import math
import os
import random
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from tests import geometry_transform as gt
from tests.cli_helpers import run

ROOT = Path(__file__).resolve().parent.parent
FILES = sorted(glob.glob(str(ROOT / "mechanisms" / "*.yaml")))
EXPLORE = os.environ.get("LINKCLI_EXPLORE") == "1"
THETA = 37.0
SCALES = (1e-6, 1e-3, 1e3, 1e6)
REL = 1e-7
#: the files' length units in metres (to move a coordinate printed in another unit)
METRES = {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "km": 1e3, "in": 0.0254, "ft": 0.3048}


@dataclass
class Sheet:
    code: int
    values: dict = field(default_factory=dict)
    units: dict = field(default_factory=dict)
    err: str = ""

    @property
    def warnings(self) -> int:
        return self.err.count("warning:")


def solve(doc: dict, tmp_path: Path, name: str, k) -> Sheet:
    path = tmp_path / f"{name}.yaml"
    path.write_text(gt.write(doc), encoding="utf-8")
    args = ["solve", path, "--format", "json"] + ([] if k is None else ["--k", k])
    code, out, err = run(args)
    if code != 0:
        return Sheet(code, err=err)
    sheet = json.loads(out)
    return Sheet(code, sheet["values"], sheet["units"], err)


def digits(doc) -> list:
    """The default k and every k the answer keys name."""
    ks = [None]
    for entry in doc.get("keys") or []:
        if isinstance(entry, dict) and "k" in entry and str(entry["k"]) != str(doc.get("k")):
            ks.append(str(entry["k"]))
    return sorted(set(ks), key=str)


def augmented(doc: dict) -> dict:
    """The file with every moving point's coordinates (and their rates where the file
    asks for rates) added to its report, so that a turned point can be compared."""
    if "driver" not in doc or not isinstance(doc.get("report"), dict):
        return doc
    doc = dict(doc)
    report = dict(doc["report"])
    moving = list(doc.get("points") or {})
    for section, suffix in (("position", ""), ("velocity", "dot"), ("acceleration", "ddot")):
        if section in report or section == "position":
            names = list(report.get(section) or [])
            names += [f"{a}{p}{suffix}" for p in moving for a in "xy"
                      if f"{a}{p}{suffix}" not in names]
            report[section] = names
    doc["report"] = report
    return doc


def known_answers(doc: dict, report: "Report") -> dict:
    """The file reporting only the answers whose change under a rigid motion is known (an
    x coordinate's time ratio is another quantity once turned, and may not exist), the
    others listed as skipped."""
    if not isinstance(doc.get("report"), dict):
        return doc
    kept = {}
    for section, names in doc["report"].items():
        if isinstance(names, list) and section != "points":       # answers, not points
            unknown = [n for n in names if isinstance(n, str) and gt.frame_class(doc, n) is None]
            report.skipped += [f"{n} (not reported: its change is not known)" for n in unknown]
            names = [n for n in names if n not in unknown]
        kept[section] = names
    return dict(doc, report=kept)


def size_of(doc) -> float:
    """The largest numeric coordinate of the figure (file units), 1 if none is a number."""
    values = [abs(c) for section in ("frame", "points") for xy in (doc.get(section) or {}).values()
              if isinstance(xy, list) for c in xy if isinstance(c, (int, float))]
    return max(values, default=0.0) or 1.0


def close(actual, expected, scale) -> bool:
    return abs(actual - expected) <= REL * max(abs(actual), abs(expected), scale)


def magnitudes(sheet: Sheet) -> dict:
    """The largest magnitude printed in each unit: the scale a rounding is measured on."""
    out = {}
    for name, v in sheet.values.items():
        if isinstance(v, (int, float)):
            unit = sheet.units.get(name, "")
            out[unit] = max(out.get(unit, 0.0), abs(v))
    return out


class Report:
    """What a transformation compared, and what it could not."""

    def __init__(self):
        self.compared = 0
        self.skipped: list = []
        self.failures: list = []

    def check(self, name, ok, text):
        self.compared += 1
        if not ok:
            self.failures.append(f"{name}: {text}")


def frame_expected(doc, sim, base: Sheet, name, t_display):
    """The answer ``name`` after the rigid motion, from the untouched sheet; None when its
    change is not known.  Returns (value, period): an angle compares modulo its turn."""
    cls = gt.frame_class(doc, name)
    value = base.values[name]
    unit = base.units.get(name, "")
    _, order = gt.split_rate(name)
    if cls == "driver":
        driver = doc.get("driver") or {}
        axis = next((a for a in ("x", "y") if a in driver), None)
        if axis is not None:                    # the driven point's coordinate
            cls = ("component", axis, driver[axis])
            if sim.turns:
                return None
        else:
            cls = "angle" if "angle" in driver and order == 0 else "invariant"
    if cls == "invariant":
        return value, None
    if cls == "angle":
        turn = {"deg": 360.0, "rad": 2 * math.pi}.get(unit)
        if turn is None:
            return None
        return value + sim.theta_deg * turn / 360.0, turn
    if isinstance(cls, tuple):
        _, axis, point = cls
        suffix = name[len(gt.split_rate(name)[0]):]
        pair = [base.values.get(f"{a}{point}{suffix}") for a in "xy"]
        if sim.turns and None in pair:
            return None
        if sim.turns:
            x, y = pair
            x, y = sim.c * x - sim.sn * y, sim.sn * x + sim.c * y
        else:
            x = y = value
        moved = x if axis == "x" else y
        if order == 0:
            factor = t_display.get(unit)
            if factor is None:
                return None
            moved += sim.t[0 if axis == "x" else 1] * factor
        return moved, None
    return None


def compare(doc, base: Sheet, moved: Sheet, expected, report: Report, label):
    """Every answer of ``base`` against ``moved`` through ``expected(name)``."""
    if base.code != 0 or moved.code != 0:
        report.check(label, base.code == moved.code,
                     f"exit {base.code} untouched, {moved.code} transformed: {moved.err.strip()[:300]}"
                     f" / {base.err.strip()[:200]}")
        return
    report.check(label + " warnings", base.warnings == moved.warnings,
                 f"{base.warnings} warnings untouched, {moved.warnings} transformed:\n"
                 f"{base.err}\n---\n{moved.err}")
    scale = magnitudes(base)
    for name, value in base.values.items():
        if not isinstance(value, (int, float)) or isinstance(value, bool):
            report.skipped.append(f"{label}: {name} (not a number)")
            continue
        want = expected(name)
        if want is None:
            report.skipped.append(f"{label}: {name}")
            continue
        target, period = want
        got = moved.values.get(name)
        if not isinstance(got, (int, float)):
            report.check(f"{label}: {name}", False, f"missing after the transformation: {got}")
            continue
        if period is not None:
            diff = math.remainder(got - target, period)
            report.check(f"{label}: {name}", abs(diff) <= REL * period,
                         f"{got!r}, expected {target!r} (mod {period})")
        else:
            unit = base.units.get(name, "")
            report.check(f"{label}: {name}", close(got, target, scale.get(unit, 0.0)),
                         f"{got!r}, expected {target!r} ({unit})")


def motion(doc, theta, t):
    """The file turned by ``theta`` and moved by ``t``, or only moved where a key is tied to
    the frame's axes: (similarity, moved file, why not turned or None); NotUnderstood
    where not even a translation is known."""
    try:
        sim = gt.Similarity(doc, theta, t)
        return sim, sim.apply(), None
    except gt.NotUnderstood as exc:
        if theta % 360 == 0:
            raise
        sim = gt.Similarity(doc, 0.0, t)
        return sim, sim.apply(), str(exc)


def frame_case(path, theta, shift, tmp_path, report: Report):
    """The file turned by ``theta`` (0 where it is tied to the axes) and moved by ``shift``
    times its size; returns the motion used."""
    doc = known_answers(gt.read(path), report)
    size = size_of(doc)
    sim, moved_doc, why = motion(doc, theta, (shift[0] * size, shift[1] * size))
    if why:
        report.skipped.append(f"{Path(path).name}: moved, not turned ({why})")
    unit = (doc.get("units") or {}).get("length", "m")
    t_display = {u: METRES[unit] / f for u, f in METRES.items()}
    for k in digits(doc):
        base = solve(augmented(doc), tmp_path, "untouched", k)
        moved = solve(augmented(moved_doc), tmp_path, "moved", k)
        if moved.code == 2 and "has no unit" in moved.err and base.code == 0:
            report.skipped.append(f"{Path(path).name}: not moved (a parameter whose only "
                                  "use as a value the motion rewrites)")
            continue
        label = f"{Path(path).name} k={k} theta={sim.theta_deg:g} t={sim.t}"
        compare(doc, base, moved, lambda n: frame_expected(doc, sim, base, n, t_display),
                report, label)
    return sim


def scale_case(path, scales, tmp_path, report: Report):
    doc = gt.read(path)
    for k in digits(doc):
        base = solve(doc, tmp_path, "untouched", k)
        powers = {n: gt.length_power(u) for n, u in base.units.items()}
        unknowns = set(((doc.get("find") or {}).get("unknowns") or {}))
        for s in scales:
            sim = gt.Similarity(doc, s=s)
            scaled = solve(sim.apply(), tmp_path, f"scaled-{s:g}", k)

            def expected(name):
                if name in unknowns:
                    return base.values[name], None
                if gt.reads_params(doc, name):
                    return None
                power = powers.get(name)
                return None if power is None else (base.values[name] * s ** power, None)
            compare(doc, base, scaled, expected, report, f"{Path(path).name} k={k} s={s:g}")


def beyond_range_case(path, tmp_path, report: Report):
    """At 1e200 and 1e-200 a file with lengths is refused by name (exit 2): never
    assembled, never a toggle.  A clutch problem without a plate has no length to refuse."""
    doc = gt.read(path)
    if not gt.has_lengths(doc):
        return
    for s in (1e200, 1e-200):
        sheet = solve(gt.Similarity(doc, s=s).apply(), tmp_path, f"beyond-{s:g}", None)
        report.check(f"{Path(path).name} s={s:g}", sheet.code == 2 and (
            "beyond the largest" in sheet.err or "below the smallest size" in sheet.err),
            f"exit {sheet.code}: {sheet.err.strip()[:300]}")


def ids(paths):
    return [Path(p).stem for p in paths]


# --- the shipped files ----------------------------------------------------------------------
#: files whose keys the rigid motion does not know even without turning, and why
FRAME_UNKNOWN = {
    "vib-quantumstudy-spring-period": "find.targets.length: a target the motion changes",
    "vib-tspgecet-static-deflection": "find.targets.delta: a target the motion changes",
}
#: files whose keys the scaling does not know, and why
SCALE_UNKNOWN = {
    "vib-ques10-refrigerator-isolation": "find.targets.TR: a target's dimension",
    "vib-tspgecet-static-deflection": "find.targets.delta: a target's dimension",
}


def known(path, table):
    """Skip (listed in ``table``) a file whose keys the transformation does not know."""
    reason = table.get(Path(path).stem)
    if reason is not None:
        pytest.skip(f"not transformed: {reason}")


@pytest.mark.parametrize("path", FILES, ids=ids(FILES))
def test_frame_invariance(path, tmp_path):
    known(path, FRAME_UNKNOWN)
    report = Report()
    frame_case(path, THETA, (3.1, -1.7), tmp_path, report)
    if EXPLORE:
        rng = random.Random()
        for _ in range(3):
            frame_case(path, rng.uniform(-720, 720), (rng.uniform(-50, 50), rng.uniform(-50, 50)),
                       tmp_path, report)
    assert not report.failures, "\n".join(report.failures)
    assert report.compared > 0 or report.skipped


@pytest.mark.parametrize("path", FILES, ids=ids(FILES))
def test_scale_invariance(path, tmp_path):
    known(path, SCALE_UNKNOWN)
    report = Report()
    scales = SCALES
    if EXPLORE:
        rng = random.Random()
        scales = SCALES + tuple(10 ** rng.uniform(-70, 70) for _ in range(3))   # in range
    scale_case(path, scales, tmp_path, report)
    beyond_range_case(path, tmp_path, report)
    assert not report.failures, "\n".join(report.failures)


@pytest.mark.parametrize("name, s", [
    ("polimi-2001-02-07-vibration", 1.6e-20),      # the resonance test in mixed units
    ("vib-edwards-penney-7-4-24-car", 6.8e-22),    # the static preloads by least squares
    ("vib-edwards-penney-7-4-24-car", 4.6e58),     # in mixed units
    ("vib-cdquestions-spring-mass", 1e70),         # the equilibrium's energies squared
    ("vib-gate-me-2009-suspension", 1e72),
    ("polimi-2001-07-17-vibration", 1e-72),        # a determinant of energies
])
def test_vibrations_at_far_scales(name, s, tmp_path):
    """Scales the random exploration found refused although the lengths are carried."""
    report = Report()
    scale_case(shipped(name), (s,), tmp_path, report)
    assert not report.failures, "\n".join(report.failures)
    assert report.compared > 0


def coverage():
    """(files the motion only moves, files it does not know, files the scale does not know)
    with the reasons, over every shipped file (reading them only)."""
    moved_only, frame, scale = {}, {}, {}
    for path in FILES:
        doc, name = gt.read(path), Path(path).stem
        try:
            _, _, why = motion(doc, THETA, (1.0, 1.0))
            if why:
                moved_only[name] = why
        except gt.NotUnderstood as exc:
            frame[name] = str(exc)
        try:
            gt.Similarity(doc, s=10.0).apply()
        except gt.NotUnderstood as exc:
            scale[name] = str(exc)
    return moved_only, frame, scale


def test_files_not_transformed_are_listed():
    """Every file whose keys a transformation does not know is in the lists above (so none
    passes silently), and every listed file still needs to be; the counts are printed."""
    moved_only, frame, scale = coverage()
    assert frame == FRAME_UNKNOWN
    assert scale == SCALE_UNKNOWN
    print(f"\n{len(FILES)} files: {len(FILES) - len(frame) - len(moved_only)} turned and "
          f"moved, {len(moved_only)} only moved ({', '.join(sorted(moved_only))}), "
          f"{len(frame)} not moved; {len(FILES) - len(scale)} scaled, {len(scale)} not")


# --- the checks bite: defects planted on purpose ----------------------------------------------
def shipped(name):
    return str(ROOT / "mechanisms" / f"{name}.yaml")


def turned_failures(tmp_path) -> list:
    """What the frame check reports on a crank-slider with a guide {y: c}, turned."""
    report = Report()
    frame_case(shipped("bevan-3-4a-slider-crank-accelerations"), THETA, (3.1, -1.7), tmp_path,
               report)
    return report.failures


def test_frame_catches_a_guides_angle_ignored(tmp_path, monkeypatch):
    """A guide's angle ignored (every {through, angle} guide along +x): the file as shipped
    ({y: c} guides) is not touched by it, the turned one is."""
    import numpy as np
    from linkcli.input.bodies import BodiesSection
    original = BodiesSection.guide

    def planted(self, value, path, units, pool, bodies, fixed, slider):
        guide = original(self, value, path, units, pool, bodies, fixed, slider)
        if isinstance(value, dict) and "angle" in value:
            b = fixed[guide.b]
            fixed[guide.c] = b + abs(fixed[guide.c] - b)
        return guide
    monkeypatch.setattr(BodiesSection, "guide", planted)
    assert turned_failures(tmp_path)


def test_frame_catches_an_angle_driver_read_from_the_guide(tmp_path, monkeypatch):
    """An angle driver's value read from the first guide's direction, not from +x: the same
    in the file as shipped (its guide along +x), THETA off when turned."""
    import cmath
    from dataclasses import replace
    from linkcli.input.document import Parser
    frame, driver = Parser.frame, Parser.driver

    def keep_frame(self, data, units):
        self.planted_fixed = frame(self, data, units)
        return self.planted_fixed

    def from_guide(self, data, units, pool, actuators):
        read = driver(self, data, units, pool, actuators)
        guide = next((n for n in self.planted_fixed if n.endswith(".1")), None)
        if guide is None or read.kind != "angle":
            return read
        u = self.planted_fixed[guide] - self.planted_fixed[guide[:-1] + "0"]
        return replace(read, value=read.value + cmath.phase(u))
    monkeypatch.setattr(Parser, "frame", keep_frame)
    monkeypatch.setattr(Parser, "driver", from_guide)
    assert turned_failures(tmp_path)


def test_scale_catches_a_toggle_threshold_in_metres(tmp_path, monkeypatch):
    """A discriminant called zero below 1e-12 m^2 (absolute): the file at 1e-6 of its size
    reads as a toggle."""
    from linkcli.kinematics import dyads
    monkeypatch.setattr(dyads, "_clear", lambda lowest, bound: False)
    monkeypatch.setattr(dyads, "negligible", lambda value, scale: abs(value) <= 1e-12)
    report = Report()
    scale_case(shipped("bevan-3-4a-slider-crank-accelerations"), (1e-6,), tmp_path, report)
    assert any("exit 0 untouched, 3 transformed" in f for f in report.failures), report.failures


def test_scale_catches_a_guides_metre_in_the_size(tmp_path, monkeypatch):
    """The mechanism's size taken over the virtual points too (a fixed guide's second point,
    at least 1 m away): at 1e-6 of its size the piston's speed reads as constant."""
    from linkcli.model.mechanism import Mechanism
    monkeypatch.setattr(Mechanism, "figure_points", property(
        lambda self: list(self.fixed.values()) + list(self.moving.values())))
    report = Report()
    scale_case(shipped("khurmi-15-3-max-piston-velocity"), (1e-6,), tmp_path, report)
    assert any("is constant" in f for f in report.failures), report.failures


def test_scale_catches_a_mass_matrix_in_mixed_units(tmp_path, monkeypatch):
    """The mass matrix tested for singularity as it is (kg beside kg m^2): at 1e-6 of its
    size the pendulum's angle reads as carrying no mass."""
    import numpy as np
    from linkcli.forces import vibration
    original = vibration.require_mass
    monkeypatch.setattr(vibration, "require_mass", lambda mech, M, free, scales: original(
        mech, M, free, np.ones(len(scales))))
    report = Report()
    scale_case(shipped("polimi-2001-02-07-vibration"), (1e-6,), tmp_path, report)
    assert any("carries no mass" in f for f in report.failures), report.failures


def test_beyond_range_catches_lengths_let_through(tmp_path, monkeypatch):
    """Without the bound on lengths, the file at 1e200 is not refused by name."""
    from linkcli.input import reader
    monkeypatch.setattr(reader, "LARGEST_LENGTH", float("inf"))
    report = Report()
    beyond_range_case(shipped("bevan-3-4a-slider-crank-accelerations"), tmp_path, report)
    assert any("s=1e+200" in f for f in report.failures), report.failures


def test_scale_catches_an_addendum_of_fixed_length(tmp_path, monkeypatch):
    """An addendum taken as 1 mm whatever the gears' size (not one module): the contact
    ratio of the scaled file changes, which the scale check reports."""
    import dataclasses
    from linkcli.kinematics import gearing
    original = gearing.contact_ratio

    def planted(pinion, wheel):
        return original(*(dataclasses.replace(g, addendum=0.001) for g in (pinion, wheel)))
    report = Report()
    scale_case(shipped("shigley-13-1-diametral-pitch"), (3.0,), tmp_path, report)
    assert not report.failures
    monkeypatch.setattr(gearing, "contact_ratio", planted)
    scale_case(shipped("shigley-13-1-diametral-pitch"), (3.0,), tmp_path, report)
    assert any("eps" in f for f in report.failures), report.failures
