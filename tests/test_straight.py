"""The straight-line solve (kinematics.straight): the general path's values within rounding
(1e-12 of each quantity's scale) wherever it answers, on every shipped file with a driver,
on both assembly branches, at random driver values and next to toggles and the ends of the
assembled range; it refuses (leaves to the general path) every position the general path
refuses, so a call gives the same errors with the same fields; and the comparison catches a
sign flipped in one generated group.
"""
from __future__ import annotations

import glob
import math
import os

import numpy as np
import pytest

import linkcli
from linkcli.answers.quantities import plan as quantities
from linkcli.answers.quantities import plan_for, report_names
from linkcli.answers.quantities.plan import Later, solved
from linkcli.errors import AssemblyError, LinkcliError, SingularError
from linkcli.kinematics import straight
from linkcli.kinematics.closed_form import Solver
from linkcli.kinematics.solvers import solver_for
from linkcli.model.mechanism import split_rate
from test_compiled import CRANK_SLIDER
from test_plan import FOURBAR

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PROBED = ("angle", "length", "x", "y")
#: agreement asked: of each quantity's largest magnitude over the positions compared
CLOSE = 1e-12


def _driven(path):
    try:
        mech = linkcli.load(path).model
    except LinkcliError:
        return None
    return mech if mech.elements is None and len(mech.coordinates) == 1 \
        and mech.design is None else None


FILES = [p for p in sorted(glob.glob(os.path.join(ROOT, "mechanisms", "*.yaml")) +
                           glob.glob(os.path.join(ROOT, "docs", "examples", "*.yaml")))
         if _driven(p) is not None]


def _names(mech):
    """The report's names the straight-line solve takes (angles, lengths, coordinates and
    their rates), at least one angle of a link where the report has none."""
    return [n for n in dict.fromkeys(report_names(mech))
            if mech.quantities.get(split_rate(n, mech.quantities)[0]) is not None
            and mech.quantities[split_rate(n, mech.quantities)[0]].kind in PROBED]


def _setup(mech, names, flip=False):
    """(plan, solver, straight) for ``names``; ``flip``: a solver of its own with every
    dyad on the other branch (the figure of the mirrored assembly)."""
    plan = plan_for(mech, names)
    solver = Solver(mech) if flip else solver_for(mech)
    if flip:
        for group in solver.groups:
            if group.branch in (1, -1):
                group.branch = -group.branch
    fast = straight.straight_of(solver, plan.probes, plan.order(mech)) \
        if plan.probes is not None else None
    return plan, solver, fast


def _general(mech, plan, solver, q, w, al):
    """The general path's table (names x positions; the report's points after) or its
    error."""
    try:
        kin = solved(solver, plan.order(mech), q, w, al)
        result = plan.collect(mech, solver, kin)
    except LinkcliError as error:
        return error
    rows = [np.asarray(result.values[n], float) for n in plan.names]
    for p, *_ in plan.points:
        rows += [np.asarray(c, float) for c in result.points[p]]
    return np.array(rows)


def _periods(mech, plan):
    """Per row, the period of an angle (its display unit's turn), else None."""
    out = []
    for (kind, a, b, order, factor, signed) in plan.probes:
        out.append(2 * math.pi / factor if kind == straight.ANGLE and order == 0 else None)
    return out


def _worst(expected, got, periods, scales):
    """The largest difference of ``got`` from ``expected`` (rows), relative to each row's
    scale; angles as angles (their wrap at a turn is no difference)."""
    worst = 0.0
    for row, (e, g, period, scale) in enumerate(zip(expected, got, periods, scales)):
        d = np.abs(np.asarray(g, float) - np.asarray(e, float))
        if period is not None:
            d = np.minimum(d, period - d)
        worst = max(worst, float(np.max(d)) / scale)
    return worst


def _driver_range(mech, count, seed):
    """Driver values (SI): a whole turn for an angle, +-20 % for a length, random."""
    rng = np.random.default_rng(seed)
    value = mech.driver.value
    spread = 2 * math.pi if mech.driver.kind == "angle" else 0.4 * max(abs(value), 1e-9)
    return value + spread * rng.uniform(-0.5, 0.5, count)


def _edges(mech, plan, solver, count=240):
    """Driver values next to where the general path starts or stops refusing (an end of
    the assembled range, a toggle), found by bisection to 1e-10 of the grid, both sides."""
    grid = np.sort(_driver_range(mech, count, 7))
    refused = [isinstance(_general(mech, plan, solver, np.array([q]), mech.driver.rate,
                                   mech.driver.accel), LinkcliError) for q in grid]
    out = []
    for i in range(count - 1):
        if refused[i] == refused[i + 1]:
            continue
        lo, hi = grid[i], grid[i + 1]
        for _ in range(30):
            mid = 0.5 * (lo + hi)
            bad = isinstance(_general(mech, plan, solver, np.array([mid]), mech.driver.rate,
                                      mech.driver.accel), LinkcliError)
            lo, hi = (lo, mid) if bad != refused[i] else (mid, hi)
        out += [lo, hi, lo + 1e-7 * (hi - lo + abs(lo)), hi - 1e-7 * (hi - lo + abs(hi))]
    return np.array(out)


def _scalar(fast, q, w, al):
    """The scalar version's answer, None where it refuses (an arithmetic exception
    included, as the plan takes it)."""
    try:
        return fast.scalar(q, w, al)
    except (ArithmeticError, ValueError):
        return None


def _conditioning(solver, q, w, al):
    """The least conditioning of the groups' rate systems at driver value ``q``."""
    kin = solved(solver, 1, np.array([q]), w, al)
    return min([float(np.min(m)) for m in kin.measure.values()] + [1.0])


def compare(mech, names, flip=False, seed=0, extra=()):
    """(worst difference, positions answered, random positions left to the general path
    while it answers) of the straight-line solve against the general path, one position at
    a time and all at once, relative to each quantity's largest magnitude at the random
    positions; next to an edge, where a rate grows as the conditioning m falls, relative to
    the larger of that and the value itself, times the amplification of rounding there,
    1 / m^(k+1) for a rate of order k (``kinematics.toggles``).  Asserts the
    refusals: every position the general path refuses, the straight-line solve leaves to
    it."""
    plan, solver, fast = _setup(mech, names, flip)
    if fast is None:
        return None
    w, al = mech.driver.rate, mech.driver.accel
    randoms = np.concatenate([[mech.driver.value], _driver_range(mech, 40, seed)])
    edges = np.concatenate([extra, _edges(mech, plan, solver)])
    found, left = [], 0
    for q in np.concatenate([randoms, edges]):
        general = _general(mech, plan, solver, np.array([q]), w, al)
        mine = _scalar(fast, float(q), w, al)
        if isinstance(general, LinkcliError):
            assert mine is None, (q, str(general))
            assert fast.array(np.array([q]), w, al) is None, q
        elif mine is None:
            left += q in randoms    # next to an edge (within its margin) it may leave
        else:
            found.append((q, general[:, 0], np.array(mine)))
    if not found:
        return 0.0, 0, left
    periods = _periods(mech, plan)
    orders = np.array([order for _, _, _, order, *_ in plan.probes])
    plain = [(e, g) for q, e, g in found if q in randoms]
    scales = np.maximum(np.max(np.abs([e for e, _ in plain or found]), axis=0), 1e-300)
    worst = 0.0
    for q, e, g in found:
        amplified = scales
        if q not in randoms:
            m = _conditioning(solver, q, w, al)
            amplified = np.maximum(scales, np.abs(e)) * \
                np.maximum(1.0, 1.0 / max(m, 1e-300)) ** (orders + 1)
        worst = max(worst, _worst(e[:, None], g[:, None], periods, amplified))
    # all at once: the random positions answered one by one (next to an edge the array's
    # checks, on its least and largest values, may leave the whole array)
    answered = [q for q, _, _ in found if q in randoms]
    if answered:
        table = fast.array(np.array(answered), w, al)
        assert table is not None
        rows = _general(mech, plan, solver, np.array(answered), w, al)
        worst = max(worst, _worst(rows, table, periods, scales))
        short = fast.short(np.array(answered[:straight.SHORT]), w, al)    # a few positions
        worst = max(worst, _worst(rows[:, :straight.SHORT], short, periods, scales))
    return worst, len(found), left


@pytest.mark.parametrize("path", FILES, ids=os.path.basename)
def test_the_straight_solve_gives_the_general_values_and_refusals(path):
    mech = _driven(path)
    names = _names(mech)
    if not names:
        pytest.skip("no angle, length or coordinate in the report")
    try:
        solver_for(mech)
    except LinkcliError:
        pytest.skip("not solved by the closed form")
    for flip in (False, True):
        found = compare(mech, names, flip)
        if found is None:
            pytest.skip("a group the straight-line solve does not write")
        worst, answered, left = found
        assert worst <= CLOSE, (flip, worst)
        assert left <= max(2, answered // 10), (flip, answered, left)


def test_most_shipped_files_are_written_straight():
    """Of the files whose report asks angles, lengths or coordinates and that the closed
    form solves, most are written straight (the others have a group of another kind)."""
    count, closed = 0, 0
    for path in FILES:
        mech = _driven(path)
        names = _names(mech)
        try:
            closed += bool(names) and solver_for(mech) is not None
        except LinkcliError:
            continue
        count += bool(names) and _setup(mech, names)[2] is not None
    assert count >= 3 * closed // 4, (count, closed)


def test_a_sign_flipped_in_one_generated_group_is_caught(monkeypatch):
    """A planted defect: the x of a dyad's acceleration with its sign flipped."""
    mech = linkcli.loads(FOURBAR).model
    names = ["beta", "gamma", "betadot", "gammaddot", "xB", "yBddot"]
    assert compare(mech, names)[0] <= CLOSE
    circles = straight._GROUPS[straight.RRR]

    def flipped(out, op, par, state, order):
        circles(out, op, par, state, order)
        acc = state[2][op[1]]
        acc[0] = out.neg(acc[0])
    monkeypatch.setitem(straight._GROUPS, straight.RRR, flipped)
    mech = linkcli.loads(FOURBAR).model
    assert compare(mech, names)[0] > 1e-3


def test_a_check_left_out_is_caught(monkeypatch):
    """A planted defect: the generated checks dropped.  A rod 40 mm long on a crank of 50
    reaches the guide only while 50 sin q <= 40: just inside that limit its discriminant
    is within the toggle's rounding band, a position the general path refuses (singular);
    without its checks the straight-line solve answers it, and the comparison says so."""
    text = CRANK_SLIDER.replace("length: 200", "length: 40")
    names = ["beta", "betadot", "xBddot"]
    limit = math.asin(0.040 * math.sqrt(1 - 1e-14) / 0.050)     # 40^2 - (50 sin q)^2 ~ 0
    mech = linkcli.loads(text).model
    plan, solver, _ = _setup(mech, names)
    assert isinstance(_general(mech, plan, solver, np.array([limit]), 1.0, 0.0),
                      SingularError)
    compare(mech, names, extra=[limit])
    monkeypatch.setattr(straight._Writer, "require", lambda self, lhs, rhs: None)
    with pytest.raises(AssertionError):
        compare(linkcli.loads(text).model, names, extra=[limit])


def assert_same_refusal(text, q, kind, field, monkeypatch):
    """``Linkage.solve(q)`` of the file ``text`` refuses by the default path as by the
    general path: the same type ``kind``, message, group, ``field`` and driver values."""
    errors = []
    for general in (False, True):
        if general:
            monkeypatch.setattr(quantities, "straight_of", lambda *args: None)
        with pytest.raises(LinkcliError) as error:
            linkcli.loads(text).solve(q)
        errors.append(error.value)
    monkeypatch.undo()
    fast, general = errors
    assert type(fast) is type(general) is kind
    assert str(fast) == str(general)
    assert (fast.group, getattr(fast, field)) == (general.group, getattr(general, field))
    assert np.array_equal(fast.q, general.q)


@pytest.mark.parametrize("q", [90.0, 270.0])
def test_a_toggle_is_refused_with_the_general_error(q, monkeypatch):
    """A rod as long as the crank stands across the guide at q = 90 and 270 deg: the
    rate system is singular there, one position or in an array."""
    text = CRANK_SLIDER.replace("length: 200", "length: 50").replace("B: [190, 0]", "B: [90, 0]")
    mech = linkcli.loads(text).model
    assert plan_for(mech, None)._straight_of(solver_for(mech), 2, now=True) is not None
    for args in (q, np.array([10.0, q, 30.0])):
        assert_same_refusal(text, args, SingularError, "measure", monkeypatch)
    linkage = linkcli.loads(text)
    first, fine = (linkage.solve(np.array([10.0, 30.0])) for _ in range(2))
    assert not isinstance(first.kinematics, Later)  # a first call: the general path
    assert isinstance(fine.kinematics, Later)       # then the straight-line solve


def test_an_unassemblable_position_is_refused_with_the_general_error(monkeypatch):
    text = FOURBAR.replace("length: 280", "length: 60")
    for q in (200.0, np.linspace(0, 350, 36)):
        assert_same_refusal(text, q, AssemblyError, "shortfall", monkeypatch)


def test_one_position_is_solved_straight_from_the_second_call():
    """The straight-line solve of one position, not the general path, answers from the
    second call of a plan on (the first one is a command's, or a trial's: not worth
    writing the code for)."""
    linkage = linkcli.loads(FOURBAR)
    assert not isinstance(linkage.solve(30.0).kinematics, Later)
    result = linkage.solve(45.0)
    assert isinstance(result.kinematics, Later)
    assert isinstance(result.kinematics.q, float)
    kin = result.kinematics
    assert np.isclose(float(np.degrees(np.angle(kin.pos["B"] - kin.pos["A"])) % 360),
                      result.values["beta"], rtol=0, atol=1e-10)


def test_generated_source_holds_no_text_of_the_file():
    """The source is written from numbers: no name of the file reaches it."""
    mech = linkcli.loads(FOURBAR.replace("A0", "print_A0_")).model
    names = ["beta", "gammaddot", "xB"]
    fast = _setup(mech, names)[2]
    for function in (fast.function(False), fast.function(True)):
        assert "print_A0_" not in function.__source__
        assert "beta" not in function.__source__


def test_the_evaluator_gives_solves_values_and_refusals(monkeypatch):
    """``Linkage.evaluator``: one position as a tuple, an array as rows, the values of
    ``solve``; a position ``solve`` refuses is refused with its error."""
    linkage = linkcli.loads(FOURBAR)
    names = ["beta", "gammadot", "xBddot", "AB"]
    ev = linkage.evaluator(names)
    assert ev.names == tuple(names) and ev.units == ("deg", "deg/s", "mm/s^2", "mm")
    q = np.linspace(-170.0, 190.0, 37)
    table = ev(q, 3.0, -1.0)
    expected = linkage.solve(q, 3.0, -1.0, names=names).values
    for row, name in zip(table, names):
        assert np.allclose(row, expected[name], rtol=CLOSE, atol=CLOSE * np.max(np.abs(row)))
    one = ev(q[5], 3.0, -1.0)
    assert type(one) is tuple and len(one) == 4
    assert np.allclose(one, table[:, 5], rtol=CLOSE, atol=0)
    text = FOURBAR.replace("length: 280", "length: 60")
    for q in (200.0, np.linspace(0, 350, 36)):
        with pytest.raises(AssemblyError) as fast:
            linkcli.loads(text).evaluator()(q)
        with pytest.raises(AssemblyError) as general:
            linkcli.loads(text).solve(q)
        assert str(fast.value) == str(general.value)


def test_the_evaluator_of_names_it_does_not_write_is_solves():
    """A speed is not written straight: the evaluator's call is then ``solve``'s."""
    linkage = linkcli.loads(FOURBAR.replace("AB: {length: [A0, B]}}",
                                            "AB: {length: [A0, B]}, vB: {speed: B}}"))
    ev = linkage.evaluator(["beta", "vB"])
    assert ev._straight is None
    assert ev(30.0) == tuple(float(v) for v in linkage.solve(30.0, names=["beta", "vB"])
                             .values.values())


def test_the_kinematics_evaluator_gives_the_solvers_points_and_angles():
    """``straight.evaluator`` (SI probes for the layers above kinematics): a point's x, y
    and rates, a link's angle and rates, at qd = 1 and qdd = 0 the derivatives over q."""
    mech = linkcli.loads(FOURBAR).model
    solver = solver_for(mech)
    fast = straight.evaluator(solver, [("x", "B", None, 1), ("y", "B", None, 2),
                                       ("angle", "A", "B", 0), ("angle", "A", "B", 2),
                                       ("length", "A0", "B", 1)])
    q = np.linspace(0.1, 6.0, 7)
    kin = solved(solver, 2, q, 1.0, 0.0)
    z, dz, ddz = (d["B"] - d["A"] for d in (kin.pos, kin.vel, kin.acc))
    w = dz / z
    r = kin.pos["B"] - mech.fixed["A0"]
    expected = [kin.vel["B"].real, kin.acc["B"].imag, np.angle(z) % (2 * np.pi),
                (ddz / z - w * w).imag, (r.conjugate() * kin.vel["B"]).real / np.abs(r)]
    table = fast.array(q, 1.0, 0.0)
    for i, e in enumerate(expected):
        assert np.allclose(table[i], e, rtol=0, atol=CLOSE * np.max(np.abs(e))), i
        assert np.isclose(fast.scalar(float(q[3]), 1.0, 0.0)[i], e[3], rtol=0,
                          atol=CLOSE * np.max(np.abs(e))), i
