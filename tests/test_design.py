"""Design unknowns (``find:``): solved parameters against closed forms and a brute-force
fine scan of the roots, several roots, no root, singular and unreachable targets, trials
that cannot be solved, and the refusals of a question asked wrongly."""
from __future__ import annotations

import math
import os

import numpy as np
import pytest

import linkcli
from linkcli.errors import DesignError
from linkcli.runs.design import solve
from linkcli.runs.sheet import evaluate

from cli_helpers import run
from closure import SEED000_CRANK_SLIDER

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
G = 9.81

# a mass on a vertical spring and a damper: f1 = sqrt(k / m) / 2 pi, zeta = c / 2 sqrt(k m)
SPRING = """
title: mass on a spring
k: 3
units: {length: m, angle: deg, stiffness: N/m}
params: {m: 2 + k/3, ks: 1000, c: 10}
frame: {B: [0, 0]}
points: {P: [0, 0.3]}
sliders: {body: {point: P, guide: {x: 0}}}
coordinates: {y: {y: P}}
springs: {s: {between: [B, P], k: ks, preload: static}}
dampers: {d: {between: [B, P], c: c}}
dynamics: {gravity: 9.81, masses: {P: m}}
quantities:
  f1: {natural_frequency: 1, unit: Hz}
  w1: {natural_frequency: 1}
  z: {damping_ratio: 1}
  T: {expr: "2*pi/f1", unit: s}
FIND
report:
  vibration: [f1, z, T]
  decimals: 4
"""

# the centred crank-slider, a = OA, b = AB = sqrt 2 at 45 deg: c = a/sqrt2 + sqrt(2 - a^2/2),
# largest (2) at a = sqrt 2, sqrt 2 at a = 0 and a = 2
CRANK = "title: crank-slider\n" + SEED000_CRANK_SLIDER + """quantities:
  c: {x: B}
FIND
report:
  position: [c]
  decimals: 6
"""


def spring(find: str, **more):
    return linkcli.loads(SPRING.replace("FIND", find), **more)


def crank(find: str):
    return linkcli.loads(CRANK.replace("FIND", find))


def c_of(a):
    return a / math.sqrt(2) + np.sqrt(2 - a * a / 2)


def test_one_unknown_closed_form_and_few_evaluations():
    """ks for f1 = 1 Hz: ks = m (2 pi)^2, m = 3 kg at k = 3; T = 2 pi/f1 = 1 s
    (f1 is read in rad/s whatever unit it is shown in)."""
    linkage = spring("find: {unknowns: {ks: {between: [10, 100000]}}, targets: {f1: 1 Hz}}")
    result = linkage.solve()
    assert result.values["ks"] == pytest.approx(3 * (2 * math.pi) ** 2, rel=1e-10)
    assert result.units["ks"] == "N/m" and result.values["T"] == pytest.approx(1, rel=1e-10)
    assert solve(linkage.model, evaluate).evaluations < 30
    # the same answer from a target in the answer's own unit, and from rad/s
    other = spring("find: {unknowns: {ks: {between: [10, 100000]}}, targets: {w1: 6.2832}}")
    assert other.solve().values["ks"] == pytest.approx(3 * 6.2832 ** 2, rel=1e-10)


def test_two_unknowns_closed_form_and_the_digit():
    """ks and c for f1 = 2 Hz and zeta = 0.1: ks = m (4 pi)^2, c = 2 zeta sqrt(ks m); at
    k = 6 the mass is 4 kg."""
    text = "find: {unknowns: {ks: {start: 500}, c: {start: 5}}, targets: {f1: 2 Hz, z: 0.1}}"
    for k, m in ((3, 3.0), (6, 4.0)):
        values = spring(text, k=k).solve().values
        ks = m * (4 * math.pi) ** 2
        assert values["ks"] == pytest.approx(ks, rel=1e-9)
        assert values["c"] == pytest.approx(2 * 0.1 * math.sqrt(ks * m), rel=1e-9)


def test_several_roots_against_a_fine_scan_and_the_choice():
    """c(a) = 1.9 has two roots in [0.1, 1.99]: found to the rounding of a fine scan of the
    closed form; refused without a rule, taken by each rule."""
    a = np.linspace(0.1, 1.99, 2_000_001)
    f = c_of(a) - 1.9
    cuts = np.nonzero(np.sign(f[:-1]) != np.sign(f[1:]))[0]
    scanned = [a[i] - f[i] * (a[i + 1] - a[i]) / (f[i + 1] - f[i]) for i in cuts]
    assert len(scanned) == 2
    with pytest.raises(DesignError) as info:
        crank("find: {unknowns: {a: {between: [0.1, 1.99]}}, targets: {c: 1.9}}").solve()
    assert info.value.reason == "several roots" and info.value.exit_code == 3
    assert list(info.value.values) == pytest.approx(scanned, abs=1e-9)
    for rule, expected in (("smallest", scanned[0]), ("largest", scanned[1]),
                           ("{nearest: 1.8}", scanned[1])):
        linkage = crank("find: {unknowns: {a: {between: [0.1, 1.99]}}, targets: {c: 1.9}, "
                        f"choose: {rule}}}")
        values = linkage.solve().values
        assert values["a"] == pytest.approx(expected, abs=1e-9)
        assert values["c"] == pytest.approx(1.9, abs=1e-12)


def test_two_roots_between_samples_are_found():
    """c = 1.9999 has two roots 0.01 apart about a = sqrt 2, between two samples of the
    scan: the dip of |c - 1.9999| is looked into."""
    linkage = crank("find: {unknowns: {a: {between: [0.1, 1.99]}}, targets: {c: 1.9999}}")
    with pytest.raises(DesignError) as info:
        linkage.solve()
    roots = info.value.values
    assert len(roots) == 2
    assert c_of(np.array(roots)) == pytest.approx(1.9999, abs=1e-12)


def test_no_root_says_so_with_the_values_at_the_ends():
    code, _, err = run(["solve", "-"], stdin=CRANK.replace(
        "FIND", "find: {unknowns: {a: {between: [0.1, 1.2]}}, targets: {c: 2.5}}"))
    assert code == 3 and "no value of a in [0.1, 1.2] gives c = 2.5 m" in err, err
    assert f"c is {c_of(0.1):.6g} m at a = 0.1 m and {c_of(1.2):.6g} m at a = 1.2 m" in err


def test_a_trial_that_does_not_assemble_is_named():
    """In [1.5, 2.9] the scan's samples beyond a = 2 do not assemble, and the sign change of
    c - 1.5 lies between a solved sample and one that fails: the trial is named."""
    with pytest.raises(DesignError) as info:
        crank("find: {unknowns: {a: {start: 2.5}}, targets: {c: 1.5}}").solve()
    assert info.value.reason == "trial" and "cannot assemble" in str(info.value)
    # a scan that meets unassembled values but brackets the root among solved ones
    values = crank("find: {unknowns: {a: {between: [1.5, 2.9]}}, targets: {c: 1.5}}")\
        .solve().values
    assert c_of(values["a"]) == pytest.approx(1.5, abs=1e-12)


def test_a_singular_jacobian_is_named():
    """f1 and w1 are one target twice: they do not fix ks and c."""
    text = "find: {unknowns: {ks: {start: 500}, c: {start: 5}}, targets: {f1: 2 Hz, w1: 12.566}}"
    with pytest.raises(DesignError) as info:
        spring(text).solve()
    assert info.value.reason == "singular", str(info.value)


def test_an_unreachable_target_is_named():
    text = "find: {unknowns: {ks: {start: 500}, c: {start: 5}}, targets: {f1: 2 Hz, z: -0.5}}"
    with pytest.raises(DesignError) as info:
        spring(text).solve()
    assert info.value.reason in ("unreachable", "trial"), str(info.value)


@pytest.mark.parametrize("find, key, words", [
    ("find: {unknowns: {zz: {between: [1, 2]}}, targets: {f1: 1 Hz}}", "find.unknowns.zz",
     "'zz' is not a parameter"),
    ("find: {unknowns: {ks: {between: [1, 2]}, c: {start: 1}}, targets: {f1: 1 Hz}}", "find",
     "2 unknowns and 1 target"),
    ("find: {unknowns: {ks: {between: [2, 1]}}, targets: {f1: 1 Hz}}",
     "find.unknowns.ks.between", "the interval goes up"),
    ("find: {unknowns: {ks: {between: [1, 2], unit: kg}}, targets: {f1: 1 Hz}}",
     "find.unknowns.ks.unit", "'ks' is a stiffness (M T^-2) and the unit 'kg' is a mass"),
    ("find: {unknowns: {ks: {between: [1, 2]}}, targets: {f1: 1 mm}}", "find.targets.f1",
     "the target's unit 'mm' is a length"),
    ("find: {unknowns: {ks: {between: [1, 2]}}, targets: {nope: 1}}", "find.targets.nope",
     "the target 'nope' is not an answer"),
    ("find: {unknowns: {ks: {start: 1}}, targets: {f1: 1 Hz}, choose: largest}", "find.choose",
     "'choose' picks one of several roots of one unknown searched in an interval"),
    ("find: {unknowns: {ks: {between: [1, 2], start: 1}}, targets: {f1: 1 Hz}}",
     "find.unknowns.ks", "give either between"),
])
def test_refusals_name_the_key(find, key, words):
    code, _, err = run(["validate", "-"], stdin=SPRING.replace("FIND", find))
    assert code == 2 and f"key '{key}'" in err + _ and words in err + _, err + _


def test_an_interval_in_another_unit_and_keys_on_solved_parameters():
    """[0.01, 100] N/mm is [10, 100000] N/m; a key on ks is checked; batch solves each k."""
    text = SPRING.replace("FIND", "find: {unknowns: {ks: {between: [0.01, 100], unit: N/mm}},"
                          " targets: {f1: 1 Hz}}") + "keys:\n  - values: {ks: 118.44}\n"
    assert linkcli.loads(text).solve().values["ks"] == pytest.approx(
        3 * (2 * math.pi) ** 2, rel=1e-10)
    code, out, err = run(["check", "-v", "-"], stdin=text)
    assert code == 0 and "ks: 118.44" in out, out + err
    code, out, err = run(["batch", "-", "--k", "0,6", "--format", "csv"], stdin=text)
    rows = [line.split(",") for line in out.splitlines()[1:]]
    assert [float(r[1]) for r in rows] == pytest.approx(          # printed to 4 decimals
        [m * (2 * math.pi) ** 2 for m in (2.0, 4.0)], abs=5e-5)


# --- a vibration file in pounds and inches --------------------------------------------------
LB, LBF, INCH = 0.45359237, 0.45359237 * 9.80665, 0.0254


def _pounds(find=""):
    """tests/data/vibration/units_lb_lbf.yaml (1 lb on a 10 lb/in spring, 1 lbf at 1 Hz)
    with its stiffness and mass as params and answers computed from its answers: a period
    from a frequency shown in Hz, the same period from the matrices' entries shown in lb/in
    and lb, a force from a stiffness times an amplitude shown in inches, an acceleration
    from a force over a mass param, a ratio of two forces."""
    text = open(os.path.join(ROOT, "tests", "data", "vibration", "units_lb_lbf.yaml"),
                encoding="utf-8").read()
    for old, new in (
            ("frame: {O: [0, 0]}", "params: {kk: 10, m: 1}\nframe: {O: [0, 0]}"),
            ("k: 10, preload", "k: kk, preload"), ("masses: {P: 1}", "masses: {P: m}"),
            ("  X: {amplitude: x}\n", "  X: {amplitude: x}\n"
             "  f1: {natural_frequency: 1}\n"
             "  T1: {expr: \"2*pi/f1\", unit: s}\n"
             "  Tq: {expr: \"2*pi/sqrt(k_red/m_red)\", unit: ms}\n"
             "  Fk: {expr: \"k_red*X\", unit: lbf}\n"
             "  Fa: {expr: \"Ft/m\", unit: \"m/s^2\"}\n"
             "  Fr: {expr: \"-Ft/N\"}\n" + find + "\n"),
            ("vibration: [m_red, k_red, N, Ft, X]",
             "vibration: [m_red, k_red, N, Ft, X, f1, T1, Tq, Fk, Fa, Fr]")):
        assert old in text
        text = text.replace(old, new)
    return linkcli.loads(text, name="pounds.yaml")


def _pounds_closed_form(k_si):
    """The undamped block: omega_n = sqrt(k / m); the 1 lbf force at Omega = 2 pi rad/s
    gives X = F / (k - m Omega^2) and the spring passes F_t = k X."""
    wn = math.sqrt(k_si / LB)
    x = LBF / (k_si - LB * (2 * math.pi) ** 2)
    return wn, x, k_si * x


@pytest.mark.parametrize("find, k_si", [
    ("", 10 * LBF / INCH),
    ("find: {unknowns: {kk: {between: [1, 100]}}, targets: {Tq: 0.25 s}}",
     LB * (2 * math.pi / 0.25) ** 2),
    ("find: {unknowns: {kk: {between: [1, 100]}}, targets: {f1: 5}}",
     LB * (2 * math.pi * 5) ** 2),
], ids=["file", "find-period", "find-frequency"])
def test_expressions_read_the_answers_of_a_pound_inch_file_in_si(find, k_si):
    """Each answer an expression reads is taken in SI whatever unit it is shown in (Hz,
    lb/in, lb, in, lbf), and each expression shown in its own unit; a target on an
    expression (the period in ms, given in s) or on a frequency in Hz finds the stiffness
    of the closed form, shown in lb/in."""
    result = _pounds(find).solve()
    v = {n: float(x) for n, x in result.values.items()}
    wn, x, ft = _pounds_closed_form(k_si)
    if find:
        assert result.units["kk"] == "lb/in"
        assert v["kk"] == pytest.approx(k_si * INCH / LBF, rel=1e-9)
    assert v["k_red"] == pytest.approx(k_si * INCH / LBF, rel=1e-9)
    assert v["f1"] == pytest.approx(wn / (2 * math.pi), rel=1e-9)
    assert v["T1"] == pytest.approx(2 * math.pi / wn, rel=1e-9)
    assert v["Tq"] == pytest.approx(2000 * math.pi / wn, rel=1e-9)
    assert v["X"] == pytest.approx(x / INCH, rel=1e-9)
    assert v["Fk"] == pytest.approx(ft / LBF, rel=1e-9) and v["Ft"] == pytest.approx(ft / LBF,
                                                                                      rel=1e-9)
    assert v["Fa"] == pytest.approx(ft / LB, rel=1e-9)
    assert v["Fr"] == pytest.approx(ft / LBF, rel=1e-9)      # over the block's 1 lbf weight
    assert [result.units[n] for n in ("f1", "T1", "Tq", "Fk", "Fa")] == \
        ["Hz", "s", "ms", "lbf", "m/s^2"]
