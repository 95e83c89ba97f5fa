"""The assembly branch of each dyad, chosen once as the figure draws it.

A dyad whose point lies on two constraints has two assemblies, branch +1 and -1 (``dyads``:
the sign of the square root; for two circles about A and B, +1 puts the point on the left of
A -> B, counter-clockwise positive).  The branch is the one whose position at the figure's
coordinates is nearer the figure's point: distance |P_branch(q_figure) - P_figure|, the
nearer first.  Whether a combination of branches closes (every shortfall <= 0) is judged at
the file's own coordinates; when a later group cannot close on the nearer branches, the
earlier choices are searched depth first, nearer first, at most SEARCH choices.

Cautions, all relative to the mechanism's size: a figure point whose distances d_1, d_2 to
the two assemblies differ by less than AMBIGUOUS |P_1 - P_2| (ambiguous), points solved at
the file's coordinates farther than FAR times the size from the figure (far), a branch
forced away from the nearer one, a figure that cannot be assembled.
"""
from __future__ import annotations

import numpy as np

from linkcli.errors import Caution
from linkcli.kinematics.refusals import length_text, where_text

#: dyads with an assembly branch to choose
BRANCHED = ("RRR", "RRP", "PRR", "RPR")
#: a solved point farther than FAR times the mechanism's size from its figure position is
#: reported; a figure point whose distances to the two assemblies differ by less than
#: AMBIGUOUS times their separation is reported as ambiguous
FAR = 0.05
AMBIGUOUS = 0.1
#: the most steps the search for an assembling combination of branches takes
SEARCH = 4096


def figure_coordinates(mech):
    """The coordinates measured on the figure's points (each driver's, or each declared one)
    as the solver takes them: the configuration the figure draws."""
    figure = {**mech.fixed, **mech.moving}
    values = []
    for c in mech.coordinates:
        if mech.elements is not None:
            values.append(c.value)          # coordinates are measured on the figure already
            continue
        if c.kind == "angle":
            values.append(float(np.angle(figure[c.b] - figure[c.a])))
        elif c.kind == "length":
            values.append(abs(figure[c.b] - figure[c.a]))
        else:
            z = figure[c.a]
            values.append(z.real if c.kind == "x" else z.imag)
    return values[0] if len(values) == 1 else tuple(values)


def _fails(short) -> bool:
    """Whether a group's shortfall says it cannot be assembled (None: nothing to close)."""
    return short is not None and bool(np.any(np.asarray(short) > 0))


def _paired(rank, judge) -> tuple:
    """Every coordinate as the pair [ranked, judged]: a dyad's branches are ranked by their
    distance to the figure at the first, their closure judged at the second."""
    return tuple(np.array([float(a), float(b)]) for a, b in zip(rank, judge))


def _judged(short):
    """The shortfall at the judged value of a pair (the last), None or a number as is."""
    return np.ravel(short)[-1] if np.ndim(short) else short


def own_coordinates(mech):
    """The file's own coordinate values (the driver's ``value``)."""
    values = [c.value for c in mech.coordinates]
    return values[0] if len(values) == 1 else tuple(values)


def choose(solver):
    """Each dyad's assembly branch as in the figure, chosen once.

    The branches are ranked where the figure is drawn: at the coordinates measured on
    the figure's points (so that another driver value, another digit k, keeps the
    figure's assembly), each dyad's nearer branch first.  Whether a combination closes
    is judged at the file's own coordinates (the driver's value), where it is solved:
    the figure's value may lie where the nearer branch cannot close while the file's
    does, or the other way round.  Going down the groups, each dyad takes the branch
    nearest its figure point; when a later dyad cannot close, the earlier choices are
    searched for the assembling combination nearest the figure, and the forced choice
    is reported.  Only when no combination closes at the file's value is the closure
    judged at the figure's.  ``cautions`` lists what the reader should check.
    """
    solver.cautions = []
    solver.undetermined = None
    dyads = [g for g in solver.groups if g.kind in BRANCHED]
    figure = solver._coords(figure_coordinates(solver.mech), "q")
    own = solver._coords(own_coordinates(solver.mech), "q")
    found = _search(solver, _paired(figure, own))
    if found is None:
        found = _search(solver, _paired(figure, figure))
    if found is None:
        for g in dyads:
            g.branch = 1
        solver.undetermined = _unassembled(solver, figure)
        _place_all(solver, figure)
        return
    branches, forced = found
    for g, b in zip(dyads, branches):
        g.branch = b
    _place_all(solver, figure)
    if forced:
        solver.cautions.append(Caution("branch", forced, solver.mech.file))
    solver.cautions += _ambiguous(solver, figure) + _far(solver, solver.mech)


def _place_all(solver, q):
    """Positions at ``q`` with the chosen branches."""
    pos = dict(solver.fixed)
    for group in solver.groups:
        if group.point is not None:
            pos[group.point] = solver._position(group, pos, q)[0]
    return pos


def _candidates(solver, group, pos, q):
    """[(distance to the figure point, branch, position, assembles)] of a dyad; with
    ``q`` a pair (:func:`_paired`) the distance is the first value's, whether it
    assembles the second's, and the position holds both."""
    target = _target(solver, group)
    out = []
    for branch in (1, -1):
        group.branch = branch
        p, short, *_ = solver._position(group, pos, q)
        near = complex(np.ravel(p)[0])
        ok = not _fails(_judged(short))
        out.append((abs(near - target), branch, p, ok))
    return sorted(out, key=lambda c: c[0])


def _target(solver, group) -> complex:
    """Where the figure draws a dyad's point; a virtual point (``~BLOCK.slot``) is
    drawn by its recipe ``group.place`` = (K, M, N, w): K + (M - N) w."""
    target = solver.mech.moving.get(group.point)
    if target is None:
        figure = {**solver.mech.fixed, **solver.mech.moving}
        k, m, n, w = group.place
        target = figure[k] + (figure[m] - figure[n]) * w
    return target


def _search(solver, q):
    """(branches, forced text) of the assembling combination nearest the figure, found
    nearest-first with backtracking; None when no combination assembles at ``q``.

    Depth first, each dyad's nearer branch first, the first complete assembly wins; at
    most SEARCH branch choices are tried (a structure that needs more is left
    undetermined).  The walk keeps its own stack, so a chain of thousands of groups
    takes no recursion."""
    groups = solver.groups
    pos = dict(solver.fixed)
    placed = []             # the points placed so far, in order (undone on backtracking)
    stack = []              # per dyad decided: [index, its candidates, next one, placed]
    i, steps = 0, 0
    while True:
        i = _place_until_branch(solver, i, pos, placed, q)
        if i == len(groups):
            break
        if i >= 0:          # a dyad with a branch to choose: its candidates, nearer first
            steps += 1
            if steps > SEARCH:
                return None
            stack.append([i, _candidates(solver, groups[i], pos, q), 0, len(placed)])
        i = _next_choice(solver, stack, pos, placed)
        if i is None:
            return None
    chosen = [(groups[i], candidates[k - 1][1], k - 1) for i, candidates, k, _ in stack]
    farther = [g for g, _, rank in chosen if rank]
    forced = ""
    if farther:
        names = ", ".join(g.describe() for g in farther)
        forced = (f"{names} assembled on the branch farther from the figure: on the nearer "
                  "one a later group cannot close")
    return [b for _, b, _ in chosen], forced


def _place_until_branch(solver, i, pos, placed, q) -> int:
    """Place the groups from ``i`` on that have no branch to choose; returns the index
    of the next dyad with one (len(groups) when all are placed, -1 when one fails)."""
    groups = solver.groups
    while i < len(groups):
        group = groups[i]
        if group.kind in BRANCHED:
            return i
        if group.point is not None:
            p, short, *_ = solver._position(group, pos, q)
            if _fails(_judged(short)):
                return -1
            pos[group.point] = p
            placed.append(group.point)
        i += 1
    return i


def _next_choice(solver, stack, pos, placed):
    """Take the next assembling candidate of the innermost dyad that has one (undoing
    what was placed after it); returns the index of the group after it, None when no
    dyad has a candidate left."""
    while stack:
        frame = stack[-1]
        i, candidates, k, mark = frame
        point = solver.groups[i].point
        for placed_point in placed[mark:]:
            del pos[placed_point]
        del placed[mark:]
        while k < len(candidates) and not candidates[k][3]:
            k += 1
        if k < len(candidates):
            frame[2] = k + 1
            pos[point] = candidates[k][2]
            placed.append(point)
            return i + 1
        stack.pop()
    return None


def _unassembled(solver, q):
    """The text of the first group that cannot close at the figure's coordinates."""
    pos = dict(solver.fixed)
    for group in solver.groups:
        if group.point is None:
            continue
        p, short, *_ = solver._position(group, pos, q)
        if _fails(short):
            worst = float(np.max(short))
            return (f"the figure's position cannot be assembled: {group.describe()} falls "
                    f"short by {length_text(solver.mech, worst)}; the assembly branch is "
                    "not determined (+ taken)")
        pos[group.point] = p
    return "the figure's position cannot be assembled; the assembly branch is not determined"


def _ambiguous(solver, q) -> list:
    """Dyads whose figure point is nearly as far from both assemblies (AMBIGUOUS of the
    distance between them)."""
    out = []
    pos = dict(solver.fixed)
    for group in solver.groups:
        if group.kind in BRANCHED:
            keep = group.branch
            (d1, _, p1, _), (d2, _, p2, _) = _candidates(solver, group, pos, q)
            group.branch = keep
            gap = abs(p1 - p2)
            if gap > 0 and abs(d1 - d2) < AMBIGUOUS * gap:
                unit, f = solver.mech.units.display("length", 0)
                out.append(Caution(
                    "ambiguous", f"the figure's {group.point} is nearly as far from both "
                    f"assemblies of {group.describe()} ({d1 / f:.4g} and {d2 / f:.4g} "
                    f"{unit}): the branch may not be the one drawn", solver.mech.file,
                    {group.point: d1 / f}))
        if group.point is not None:
            pos[group.point] = solver._position(group, pos, q)[0]
    return out


def _far(solver, mech) -> list:
    """Points solved far from the figure at the file's own coordinates (more than FAR
    of the mechanism's size), when the file is solved for the digit it draws."""
    if not mech.as_drawn:
        return []
    q = solver._coords(own_coordinates(mech), "q")
    kin = solver.positions(q)
    pos = kin.pos
    for index, short in kin.short.items():
        if np.any(short > 0):
            group = solver.groups[index]
            worst = float(np.max(short))
            reason = "the links are parallel" if not np.isfinite(worst) else \
                f"falls short by {length_text(mech, worst)}"
            return [Caution("unassembled", f"the file's own position cannot be assembled: "
                            f"{group.describe()} {where_text(mech, kin.q, True)} {reason} "
                            "(the branch is the figure's)", mech.file)]
    return far_from_figure(mech, pos)


def far_from_figure(mech, pos) -> list:
    """The caution listing the points solved (``pos``: every point at the file's own
    coordinates) farther than FAR of the mechanism's size from the figure's, if any."""
    points = [complex(np.ravel(pos[p])[0]) for p in mech.points if p in pos]
    size = max(abs(z - sum(points) / len(points)) for z in points) or 1.0
    unit, f = mech.units.display("length", 0)
    far = {p: abs(complex(np.ravel(pos[p])[0]) - mech.moving[p]) for p in mech.moving
           if p in pos}
    far = {p: d for p, d in far.items() if d > FAR * size}
    if not far:
        return []
    listed = ", ".join(f"{p} by {d / f:.4g} {unit}" for p, d in
                       sorted(far.items(), key=lambda item: -item[1]))
    return [Caution("figure", f"the solved position is far from the figure ({FAR:.0%} of "
                    f"the mechanism's size is {FAR * size / f:.4g} {unit}): {listed}; "
                    "check the lengths, the shapes and the driver's points",
                    mech.file, {p: d / f for p, d in far.items()})]
