"""The formulas of --symbolic against the numbers of the same files.

For every shipped vibration problem (every file with ``coordinates:``): the file's numbers
put into the symbolic M, K, R and F give the numeric linearisation to 1e-12 (relative to
the largest entry), the characteristic polynomial's roots are the natural frequencies, and
the JSON strings read back (sympy.sympify) to the same numbers.  The formulas are checked
once more with every literal parameter moved by a few per cent, against the numbers of
the moved file: a number that lost its formula on the way (a constant where a parameter
should be) agrees at the file's values only, and fails there.
"""
from __future__ import annotations

import glob
import json
import os
import re

import numpy as np
import pytest
import sympy as sp

import linkcli
from conftest import MECHANISMS
from linkcli.texts.symbolic import as_dict, formulas
from linkcli.forces.lagrange import Lagrangian
from linkcli.forces.vibration import linearise, modes
from linkcli.input.document import build
from linkcli.input.source import load_file
from linkcli.input.symbols import Symbolic
from linkcli.kinematics.solvers import solver_for

FILES = sorted(os.path.basename(p) for p in glob.glob(os.path.join(MECHANISMS, "*.yaml"))
               if "coordinates:" in open(p).read())
_CACHE = {}


def of(name):
    """(formulas, numeric linearisation) of a shipped file, once per session."""
    if name not in _CACHE:
        doc = load_file(os.path.join(MECHANISMS, name))
        mech = build(doc)
        _CACHE[name] = (formulas(doc), linearise(Lagrangian(mech, solver_for(mech))))
    return _CACHE[name]


def numeric(expr, values) -> np.ndarray:
    if isinstance(expr, (list, tuple)):
        return np.array([complex(sp.N(sp.sympify(x).xreplace(values), 30)) for x in expr])
    out = sp.sympify(expr).xreplace(values)
    if isinstance(out, sp.MatrixBase):
        return np.array(out.evalf(30).tolist(), dtype=complex)
    return np.complex128(complex(sp.N(out, 30)))


def assert_relative(got, expected, tol=1e-12, what=""):
    got, expected = np.atleast_1d(got), np.atleast_1d(expected)
    scale = max(float(np.max(np.abs(expected))), 1e-300)
    assert np.max(np.abs(got - expected)) <= tol * scale, (what, got, expected)


def test_every_vibration_file_is_covered():
    assert len(FILES) >= 21
    assert all(n.startswith(("vib-", "polimi-2001-")) for n in FILES)


@pytest.mark.parametrize("name", FILES)
def test_matrices_are_the_numeric_ones(name):
    f, lin = of(name)
    assert not f.missing
    values = f.numbers
    for item, expected in (("M", lin.M), ("K", lin.K), ("R", lin.R)):
        assert_relative(numeric(f.values[item], values), expected, what=f"{name} {item}")
        assert not f.values[item].has(sp.Float), (name, item)
    if lin.frequency is not None:
        expected = lin.load(lin.frequency)
        assert_relative(numeric(f.values["F"], values), expected, what=f"{name} F")


@pytest.mark.parametrize("name", FILES)
def test_characteristic_roots_are_the_natural_frequencies(name):
    f, lin = of(name)
    w = sp.Symbol("w2")
    poly = sp.Poly(f.values["characteristic"].xreplace(
        {sp.Symbol("omega", positive=True): sp.sqrt(w)}), w)
    coefficients = [complex(sp.N(c.xreplace(f.numbers), 30)).real for c in poly.all_coeffs()]
    roots = np.sort(np.roots(coefficients).real)
    expected = modes(lin).omega
    assert np.sqrt(roots) == pytest.approx(expected, rel=1e-9)
    if f.roots is not None:                       # the printed roots, where short
        printed = np.sort([complex(sp.N(r.xreplace(f.numbers), 30)).real for r in f.roots])
        assert np.sqrt(printed) == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("name", FILES)
def test_json_strings_read_back(name):
    """Every string is sympify-able with the symbols and coordinates as local names, and
    means the same numbers."""
    f, lin = of(name)
    data = json.loads(json.dumps(as_dict(f)))
    names = set(data["symbols"]) | set(data["coordinates"]) | set(data["imposed"])
    names |= {f"{n}_dot" for n in data["coordinates"] + data["imposed"]}
    names |= {f"{n}_ddot" for n in data["coordinates"] + data["imposed"]} | {"t", "omega"}
    local = {n: sp.Symbol(n) for n in names}
    plain = {sp.Symbol(s.name): v for s, v in f.numbers.items()}
    for item in ("M", "K", "R"):
        got = sp.Matrix([[sp.sympify(x, locals=local) for x in row] for row in data[item]])
        assert_relative(numeric(got, plain), getattr(lin, item), what=f"{name} {item}")
    assert set(data) >= {"coordinates", "symbols", "T", "V", "D", "M", "K", "R", "F",
                         "equations", "stability", "characteristic"}
    for text in [data["T"], data["V"], data["D"], data["characteristic"]] + \
            data["equations"] + data["stability"] + data["F"]:
        sp.sympify(text, locals=local)
    assert set(data["symbols"]) <= set(f.mech.params) | {"g"} | \
        {f"{c}_e" for c in data["coordinates"]}


def moved(name):
    """The file's document with every literal parameter moved by 1 to 4 %."""
    doc = load_file(os.path.join(MECHANISMS, name))
    params = doc.data.get("params") or {}
    for i, (key, value) in enumerate(sorted(params.items())):
        if isinstance(value, (int, float)) and not isinstance(value, bool) and value != 0:
            params[key] = value * (1 + 0.01 * (1 + i % 4))
    return doc


@pytest.mark.parametrize("name", FILES)
def test_formulas_hold_for_other_numbers(name):
    f, _ = of(name)
    doc = moved(name)
    reading = Symbolic()
    build(doc, None, symbolic=reading)
    values = dict(reading.values())
    if "g" in f.symbols:
        values[sp.Symbol("g", positive=True)] = f.numbers[sp.Symbol("g", positive=True)]
    mech = build(doc)
    lin = linearise(Lagrangian(mech, solver_for(mech)))
    for q, value in zip(f.stated, lin.eq.q[[f.mech.coordinates.index(c) for c in
                                           f.mech.coordinates if f"{c.name}_e" in
                                           {s.name for s in f.stated}]]):
        values[q] = value
    for item, expected in (("M", lin.M), ("K", lin.K), ("R", lin.R)):
        assert_relative(numeric(f.values[item], values), expected, what=f"{name} {item}")
    if lin.frequency is not None:
        assert_relative(numeric(f.values["F"], values), lin.load(lin.frequency),
                        what=f"{name} F")


# --- linkages: closure equations and rate systems ----------------------------------------
def closures_of(name):
    from linkcli.kinematics.symbolic import Closures, Symbols
    reading = Symbolic()
    mech = build(load_file(os.path.join(MECHANISMS, name)), None, symbolic=reading)
    return Closures(Symbols(mech, reading.si(), reading.values())), reading


def test_crank_slider_closure_is_the_seeds():
    """Seed 000, (2), (6) and (8): a e^{i alpha} + b e^{i beta} = c e^{i gamma},
    [[cos gamma, b sin beta], [sin gamma, -b cos beta]] [c', beta']^T =
    [-alpha' a sin alpha, alpha' a cos alpha]^T, and the accelerations' right side."""
    found, _ = closures_of("polimi-crank-slider.yaml")
    a, b = sp.symbols("a b", positive=True)
    alpha, beta, c, gamma = sp.symbols("alpha beta c gamma", real=True)
    ad, bd, add_ = sp.symbols("alpha_dot beta_dot alpha_ddot", real=True)
    dyad = found.closures[1]
    assert sp.simplify(dyad.left - (a * sp.exp(sp.I * alpha) + b * sp.exp(sp.I * beta))) == 0
    assert sp.simplify(dyad.right - c * sp.exp(sp.I * gamma)) == 0
    assert dyad.unknowns == [c, beta]
    assert (dyad.matrix - sp.Matrix([[sp.cos(gamma), b * sp.sin(beta)],
                                     [sp.sin(gamma), -b * sp.cos(beta)]])).is_zero_matrix
    assert (dyad.velocity - sp.Matrix([-ad * a * sp.sin(alpha), ad * a * sp.cos(alpha)])
            ).applyfunc(sp.simplify).is_zero_matrix
    expected = sp.Matrix([-add_ * a * sp.sin(alpha) - ad ** 2 * a * sp.cos(alpha)
                          - bd ** 2 * b * sp.cos(beta),
                          add_ * a * sp.cos(alpha) - ad ** 2 * a * sp.sin(alpha)
                          - bd ** 2 * b * sp.sin(beta)])
    assert (dyad.acceleration - expected).applyfunc(sp.simplify).is_zero_matrix
    assert found.values[gamma] == 0


@pytest.mark.parametrize("name", ["polimi-crank-slider.yaml", "khurmi-7-1-fourbar.yaml",
                                  "padova-2020-07.yaml", "padova-2020-02.yaml"])
def test_closures_hold_for_the_solved_motion(name):
    """At the file's driver value, the solver's positions, velocities and accelerations
    satisfy every closure and its two rate systems (1e-9 of the terms' size; every shipped
    linkage in tests/test_roundtrip_symbolic.py)."""
    from test_roundtrip_symbolic import check_linkage, closures_of as loop_of
    mech = linkcli.load(os.path.join(MECHANISMS, name)).model
    assert check_linkage(mech, loop_of(os.path.join("mechanisms", name))) >= 1


# --- formats ---------------------------------------------------------------------------------
def test_worked_solution_writes_the_formulas_as_mathml_and_latex(tmp_path):
    """The HTML page stays one self-contained page (no script, nothing from the network)
    and holds each formula as MathML with its LaTeX; Markdown has the LaTeX; Chromium,
    where installed, loads it with the math in its DOM and draws a screenshot."""
    import html as html_module
    import shutil
    import subprocess
    from linkcli.exports import worked
    name = "polimi-2001-09-18-vibration.yaml"
    f, _ = of(name)
    mech = f.mech
    page = worked.to_html(worked.with_formulas(worked.blocks(mech, "en", figure=False), f))
    assert "<script" not in page
    assert not [u for u in re.findall(r'(?:src|href)="([^"]+)"', page)]
    maths = re.findall(r"<math .*?</math>", page)
    assert len(maths) >= 12
    tex = [html_module.unescape(t) for t in re.findall(
        r'<annotation encoding="application/x-tex">(.*?)</annotation>', page)]
    assert "[M] = \\begin{bmatrix} 2 m L^{2} & m L^{2} \\\\ m L^{2} & m L^{2} \\end{bmatrix}" in tex
    markdown = worked.to_markdown(worked.with_formulas(worked.blocks(mech, "en", figure=False),
                                                       f))
    assert "$$[M] = \\begin{bmatrix} 2 m L^{2}" in markdown
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        pytest.skip("chromium is not installed (apt-get install chromium)")
    path = tmp_path / "formulas.html"
    path.write_text(page, encoding="utf-8")
    flags = ["--headless", "--no-sandbox", "--disable-gpu", f"--user-data-dir={tmp_path / 'p'}"]
    dom = subprocess.run([browser, *flags, "--dump-dom", path.as_uri()], capture_output=True,
                         text=True, timeout=120)
    assert dom.returncode == 0 and dom.stdout.count("<math") == len(maths)
    shot = tmp_path / "formulas.png"
    subprocess.run([browser, *flags, f"--screenshot={shot}", "--window-size=1100,2400",
                    path.as_uri()], capture_output=True, timeout=120)
    assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_text_reads_as_the_exam_writes_it():
    f, _ = of("polimi-2001-09-18-vibration.yaml")
    from linkcli.texts.symbolic import to_text
    text = to_text(f)
    for line in ("  T = m L^2 phi'^2 + m L^2 phi' theta' cos(phi - theta) + m L^2 theta'^2/2",
                 "  [M] = [ 2 m L^2   m L^2 ]",
                 "  4 ks L^2 + 2 m g L > 0"):
        assert line in text.splitlines()
    assert not re.search(r"\d\.\d", text)          # exact numbers, no decimals


def test_a_numeric_solve_does_not_import_sympy():
    """The symbolic path only: solve and explain of a file without --symbolic start as
    before."""
    import subprocess
    import sys
    code = ("import sys, io, contextlib\nfrom linkcli.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    main(['solve', 'mechanisms/padova-2020-02.yaml'])\n"
            "    main(['solve', 'mechanisms/polimi-2001-09-18-vibration.yaml'])\n"
            "    main(['explain', 'mechanisms/polimi-2001-09-18-vibration.yaml'])\n"
            "print('sympy' in sys.modules)")
    root = os.path.dirname(MECHANISMS)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=root, check=True)
    assert out.stdout.strip().splitlines()[-1] == "False"


TWISTED = """
title: a pendulum on a twisted torsional spring
units: {length: m, angle: deg}
params: {L: 0.5, m: 2, kt: 20, th0: -60}
frame: {O: [0, 0]}
points: {P: [0, -L]}
links: {rod: {points: [O, P], length: L}}
coordinates: {th: {angle: [O, P]}}
springs: {s: {bodies: [frame, rod], k: kt, free_angle: th0}}
dynamics: {gravity: 9.81, masses: {P: m}}
quantities: {w1: {natural_frequency: 1}}
report: {vibration: [w1]}
"""


def test_an_equilibrium_without_closed_form_is_the_numeric_one_said_so():
    """kt (th - th0) + m g L cos(th) = 0 has no closed form: the equilibrium stands as the
    symbol th_e with its numeric value, the formulas keep it, and the numbers agree."""
    from linkcli.texts.symbolic import to_text
    from linkcli.input.source import load_text
    doc = load_text(TWISTED, "twisted.yaml")
    f = formulas(doc)
    mech = build(doc)
    lin = linearise(Lagrangian(mech, solver_for(mech)))
    th_e = sp.Symbol("th_e", real=True)
    assert f.how == "numeric" and f.stated == {th_e: pytest.approx(lin.eq.q[0], abs=0)}
    assert f.values["K"][0, 0].has(th_e)
    assert_relative(numeric(f.values["K"], f.numbers), lin.K)
    text = to_text(f)
    assert "Static equilibrium: no closed form, the numeric one" in text
    assert f"  th_e = {lin.eq.q[0]:.10g} rad" in text.splitlines()
