"""`explain --pseudocode`: the exam's Assur answer as calls of the dyad functions.

The printed procedure is run here by a small interpreter of its pseudo-MATLAB (numbers,
names, + - * /, the calls of the exam's library written from their definitions, never
Python's ``eval``): a name read before it is assigned fails, a point assigned twice
fails, and the points it computes must be the solver's and the answer keys' points.
Where seed 002 prints the expected procedure (the lifting platform and the toggle
press of its Assur questions) the calls are compared with it line by line.
"""
import ast
import cmath
import glob
import math
import os
import re

import pytest

import linkcli
from linkcli.texts.pseudocode import Call, procedure, render
from linkcli.kinematics.solvers import solver_for
from linkcli.kinematics.groups import Group

from cli_helpers import run
from conftest import MECHANISMS

PADOVA = sorted(glob.glob(os.path.join(MECHANISMS, "padova-*.yaml")))
SHIPPED = sorted(glob.glob(os.path.join(MECHANISMS, "*.yaml")))
TESTDATA = sorted(glob.glob(os.path.join(os.path.dirname(__file__), "data", "*.yaml")))


# --- the exam's library, from its definitions -------------------------------------------
def diade_rrr(p1, p2, l1, l2, s):
    """P with |P - P1| = l1, |P - P2| = l2, left ('sx') or right ('dx') of P1->P2
    (law of cosines in the triangle P1 P2 P)."""
    d = abs(p2 - p1)
    gamma = math.acos((l1 * l1 + d * d - l2 * l2) / (2 * l1 * d))
    return p1 + l1 * cmath.exp(1j * (cmath.phase(p2 - p1) + (gamma if s == "sx" else -gamma)))


def diade_rrp(p1, o, alpha, length, e, s):
    """(P, K): P at |P - P1| = l, at e to the left of the line through O at angle alpha,
    ahead ('pos') or behind ('neg') the foot of P1 along alpha; K the foot of P."""
    u = cmath.exp(1j * alpha)
    rel = (p1 - o) / u                       # P1 in the line's axes
    along = rel.real + (1 if s == "pos" else -1) * math.sqrt(length ** 2 - (e - rel.imag) ** 2)
    return o + complex(along, e) * u, o + along * u


FUNCTIONS = {"complex": complex, "angle": cmath.phase, "abs": abs, "exp": cmath.exp,
             "deg2rad": math.radians, "real": lambda z: z.real, "imag": lambda z: z.imag,
             "cos": math.cos, "sin": math.sin, "tan": math.tan,
             "diadeRRR": diade_rrr, "diadeRRP": diade_rrp}
OPERATORS = {ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b,
             ast.Mult: lambda a, b: a * b, ast.Div: lambda a, b: a / b}


def value(node, names):
    if isinstance(node, ast.Constant):
        return node.value
    if isinstance(node, ast.Name):
        assert node.id in names, f"{node.id} is read before it is assigned"
        return names[node.id]
    if isinstance(node, ast.BinOp):
        return OPERATORS[type(node.op)](value(node.left, names), value(node.right, names))
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        return -value(node.operand, names)
    if isinstance(node, ast.Call):
        assert node.func.id in FUNCTIONS, f"{node.func.id} is not a function of the library"
        return FUNCTIONS[node.func.id](*(value(a, names) for a in node.args))
    raise AssertionError(f"not pseudo-MATLAB of the procedure: {ast.dump(node)}")


def statements(text):
    """(names assigned, right-hand side) of every statement, comments dropped."""
    out = []
    for line in text.splitlines():
        code = line.split("%", 1)[0].strip()
        if not code:
            continue
        left, right = code.rstrip(";").split(" = ", 1)
        out.append((tuple(n.strip() for n in left.strip("[]").split(",")), right.strip()))
    return out


def interpret(text):
    """The names the procedure assigns (SI-free: the file's units), each assigned once."""
    names = {}
    for outputs, right in statements(text):
        expression = re.sub(r"\b1i\b", "1j", right)
        result = value(ast.parse(expression, mode="eval").body, names)
        results = result if isinstance(result, tuple) else (result,)
        for name, r in zip(outputs, results):
            assert name not in names, f"{name} is assigned twice"
            names[name] = r
    return names


def load(path):
    return linkcli.load(path).model


def solved(mech):
    """The closed-form solver's points at the file's driver value, in the file's length unit."""
    f = mech.units.factor("length")
    kin = solver_for(mech).positions(mech.driver.value)
    return {p: complex(kin.pos[p]) / f for p in mech.moving}


# --- every shipped Padova file -------------------------------------------------------------
@pytest.mark.parametrize("path", PADOVA, ids=os.path.basename)
def test_the_procedure_computes_the_solvers_points(path):
    mech = load(path)
    names = interpret(render(procedure(mech)))
    size = max(abs(z) for z in solved(mech).values())
    for point, z in solved(mech).items():
        assert abs(names[point] - z) <= 1e-8 * size, (point, names[point], z)


@pytest.mark.parametrize("path", PADOVA, ids=os.path.basename)
def test_the_procedure_gives_the_printed_points(path):
    mech = load(path)
    names = interpret(render(procedure(mech)))
    entries = [e for key in mech.keys if key.k in (None, mech.k) for e in key.entries
               if isinstance(e.value, tuple) and e.wrong is None and e.name in names]
    if not entries:
        pytest.skip("the key prints no point")
    for e in entries:
        half = 0.5 * 10.0 ** -e.decimals + 1e-9
        got = names[e.name]
        assert abs(got.real - e.value[0]) <= half and abs(got.imag - e.value[1]) <= half, \
            (e.name, got, e.printed)


@pytest.mark.parametrize("path", PADOVA, ids=os.path.basename)
def test_padova_procedures_use_the_exam_library_only(path):
    calls = procedure(load(path)).calls
    assert all(c.library for c in calls)
    assert {c.function for c in calls} <= {None, "diadeRRR", "diadeRRP"}


@pytest.mark.parametrize("path", SHIPPED + TESTDATA, ids=os.path.basename)
def test_calls_read_only_what_is_known_and_compute_each_point_once(path):
    mech = load(path)
    try:
        proc = procedure(mech)
    except linkcli.LinkcliError:
        pytest.skip("the decomposition refuses the file")
    known = {c.name for c in proc.constants + proc.coordinates}
    computed = []
    for call in proc.calls:
        missing = set(call.reads) - known
        assert not missing, f"{call.left} reads {missing} before they are known"
        known.update(call.outputs)
        computed += [p for p in call.outputs if p in mech.moving]
    assert sorted(computed) == sorted(mech.moving)


@pytest.mark.parametrize("path", PADOVA, ids=os.path.basename)
def test_constants_are_the_files_points_and_lengths(path):
    mech = load(path)
    proc = procedure(mech)
    f = mech.units.factor("length")
    pos = {**mech.fixed, **{p: z * f for p, z in solved(mech).items()}}
    for c in proc.constants:
        assert all(p in mech.fixed or p in mech.moving for p in c.points), c
        if c.kind == "length":
            a, b = c.points
            assert any({a, b} <= set(body.points) for body in mech.bodies.values()), c
            assert float(c.value) == pytest.approx(abs(pos[b] - pos[a]) / f, rel=1e-9), c
        if c.kind == "point" and c.points:
            z = mech.fixed[c.name] / f
            assert c.value == f"complex({z.real:.10g}, {z.imag:.10g})", c


# --- what the exam's library has no function for ---------------------------------------------
@pytest.mark.parametrize("name, function", [("quick-return.yaml", "diadeRPR"),
                                            ("double-slider.yaml", "diadePRP")])
def test_a_group_without_a_library_function_is_a_named_call(name, function):
    text = render(procedure(load(os.path.join(os.path.dirname(__file__), "data", name))))
    line = next(ln for ln in text.splitlines() if f"{function}(" in ln)
    assert "not in the exam's library" in line


def test_a_class_three_group_is_one_named_call():
    mech = load(os.path.join(MECHANISMS, "triad-class3.yaml"))
    calls = procedure(mech).calls
    triad = [c for c in calls if c.kind == "triad"]
    assert len(triad) == 1 and set(triad[0].outputs) == {"C", "D", "E"}
    assert {"B", "F", "G"} <= set(triad[0].reads) and not triad[0].library
    code, out, err = run(["explain", os.path.join(MECHANISMS, "triad-class3.yaml"),
                          "--pseudocode"])
    assert code == 0 and "[C, D, E] = triade(B, F, G" in out, err


def test_a_group_kind_the_writer_does_not_know_is_written_generically():
    mech = load(os.path.join(MECHANISMS, "padova-2020-07.yaml"))
    groups = list(solver_for(mech).groups)
    last = groups[-1]
    strange = Group("yoke", last.point, last.constraints, last.bodies, note="a new group")
    proc = procedure(mech, groups[:-1] + [strange])
    call = proc.calls[-1]
    assert isinstance(call, Call) and call.outputs == ("E",) and call.function == "yoke"
    assert not call.library and "D" in call.reads
    assert "not in the exam's library" in render(proc).splitlines()[-1]


# --- the procedures printed in seed 002 ------------------------------------------------------
# The two Assur questions of seed 002 lost their figures; the files below draw them as the
# text describes them.  Lengths: the platform arms l2 = l3 = 250 crossing at their middles;
# the toggle's links a2 = a3 = a4 = 100 and the offset a5 = 30.
SCISSOR = """\
title: "Lifting platform: slider A on the x axis, arms ACE and DCB crossing at C"
units: {length: mm, angle: deg, force: N, torque: Nm}
frame:
  D: [300, 0]
points: {A: [100, 0], C: [200, 75], E: [300, 150], B: [100, 150]}
links:
  ACE: {points: [A, C, E], shape: {C: {length: 125}, E: {length: 250, angle: 0}}}
  DCB: {points: [D, C, B], shape: {C: {length: 125}, B: {length: 250, angle: 0}}}
sliders:
  SA: {point: A, guide: {y: 0}}
driver: {x: A, value: 100, rate: 10}
loads:
  Q: {type: driver, value: unknown}
report: {position: [xC]}
"""
#: seed 002, "Analisi di un meccanismo con il metodo di Assur" (lifting platform), part 4,
#: with the seed's names l2/2 -> l_AC, l3/2 -> l_CD, l2 -> l_AE and l_BD, x0 -> 300,
#: phi2 -> phi_AC, phi3 -> phi_DC
SCISSOR_SEED = [
    ("A", "complex(q, 0)"),                      # A = complex(q, 0)
    ("D", "complex(300, 0)"),                    # D = complex(x0, 0)
    ("C", "diadeRRR(A, D, l_AC, l_CD, 'sx')"),   # C = diade RRR(A, D, l2/2, l3/2, 'sx')
    ("phi_AC", "angle(C - A)"),                  # phi2 = angle(C - A)
    ("E", "A + l_AE*exp(1i*phi_AC)"),            # E = A + l2 e^(i phi2)
    ("phi_DC", "angle(C - D)"),                  # phi3 = angle(C - D)
    # B = D + l2 e^(-i phi3) in the seed: the minus is a slip, B lies on the arm D-C beyond C
    ("B", "D + l_BD*exp(1i*phi_DC)"),
]

TOGGLE = """\
title: "Toggle press, upper half: piston A, links AB and BC, rod BD, member K on the axis"
units: {length: mm, angle: deg, force: N, torque: Nm}
frame:
  C: [200, 150]
  O: [0, 0]
points: {A: [50, 30], B: [142, 68], D: [235, 30], K: [235, 0]}
links:
  AB: {points: [A, B], length: 100}
  BC: {points: [B, C], length: 100}
  BD: {points: [B, D], length: 100}
sliders:
  S1: {point: A, guide: {y: 30}}
  K: {point: K, guide: {y: 0}, carries: {D: {dx: 0, dy: 30}}}
driver: {x: A, value: 50, rate: 10}
loads:
  Q: {type: driver, value: unknown}
report: {position: [xC]}
"""
#: seed 002, "3) Analisi di un meccanismo con il metodo di Assur" (toggle press), with the
#: seed's a2 -> l_AB, a3 -> l_BC, a4 -> l_BD, a5 -> 30 or e_D, alpha -> alpha_K
TOGGLE_SEED = [
    ("A", "complex(q, 30)"),                                 # A = complex(q, a5)
    ("C", "complex(200, 150)"),                              # C = complex(xC, yC)
    ("B", "diadeRRR(A, C, l_AB, l_BC, 'dx')"),               # B = diade RRR(A, C, a2, a3, "dx")
    ("O", "complex(0, 0)"),                                  # O = complex(0, 0)
    ("alpha_K", "0"),                                        # alpha = 0
    ("D, K", "diadeRRP(B, O, alpha_K, l_BD, e_D, 'pos')"),   # [D, K] = diade RRP(B, O, alpha, a4, a5, "pos")
]


@pytest.mark.parametrize("text, seed", [(SCISSOR, SCISSOR_SEED), (TOGGLE, TOGGLE_SEED)],
                         ids=["lifting-platform", "toggle-press"])
def test_the_seeds_printed_procedures(tmp_path, text, seed):
    path = tmp_path / "assur.yaml"
    path.write_text(text)
    printed = render(procedure(load(str(path))))
    ours = {", ".join(left): right for left, right in statements(printed)}
    assert [(left, ours.get(left)) for left, _ in seed] == seed
    calls = [", ".join(c.outputs) for c in procedure(load(str(path))).calls]
    order = [left for left, _ in seed if left in calls]
    assert order == [c for c in calls if c in order]
    names = interpret(printed)
    solver = solved(load(str(path)))
    assert all(abs(names[p] - z) <= 1e-9 * 300 for p, z in solver.items())


def test_the_command_prints_the_procedure():
    path = os.path.join(MECHANISMS, "padova-2020-07.yaml")
    code, out, err = run(["explain", path, "--pseudocode"])
    assert code == 0, err
    assert interpret(out)["E"] == pytest.approx(complex(-46.4, 180.0), abs=0.05)
