"""Exact toggles, change points and dead centres at many scales: either refused as a named
singular position (exit 3), or answered with rates that agree with finite differences of
the positions; never a number that is neither.  Regular positions close to a toggle are
answered, and their rates agree with differences.

Hypothesis runs derandomized, so the cases are the same on every run (a landing does not
depend on luck); LINKCLI_EXPLORE=1 in the environment draws new cases on every run
(``make explore``), which is how new edges are found."""
from __future__ import annotations

import math
import os

import pytest
from hypothesis import given, settings, strategies as st, HealthCheck

import linkcli
from linkcli.errors import AssemblyError, SingularError

FOURBAR = """
units: {{length: mm, angle: rad}}
frame: {{A: [0, 0], D: [{d!r}, 0]}}
points: {{B: [{bx!r}, {by!r}], C: [{cx!r}, {cy!r}]}}
links: {{AB: {{points: [A, B], length: {r!r}}}, BC: {{points: [B, C], length: {b!r}}},
        CD: {{points: [C, D], length: {c!r}}}}}
driver: {{angle: [A, B], value: {q!r}, rate: 1}}
quantities: {{t3: {{angle: [B, C]}}, t4: {{angle: [D, C]}}}}
report: {{position: [t3, t4], velocity: [t3dot, t4dot]}}
"""

SLIDER = """
units: {{length: mm, angle: rad}}
frame: {{A: [0, 0]}}
points: {{B: [{bx!r}, {by!r}], C: [{cx!r}, {e!r}]}}
links: {{AB: {{points: [A, B], length: {r!r}}}, BC: {{points: [B, C], length: {l!r}}}}}
sliders: {{C: {{point: C, guide: {{y: {e!r}}}}}}}
driver: {{angle: [A, B], value: {q!r}, rate: 1}}
quantities: {{t3: {{angle: [B, C]}}}}
report: {{position: [t3, xC], velocity: [t3dot, xCdot]}}
"""

SLOTTED = """
units: {{length: mm, angle: rad}}
frame: {{A: [0, 0], O: [{d!r}, 0]}}
points: {{B: [{bx!r}, {by!r}], E: [{ex!r}, {ey!r}]}}
links: {{AB: {{points: [A, B], length: {r!r}}}, OE: {{points: [O, E], length: {L!r}}}}}
sliders: {{S: {{point: B, guide: {{along: [O, E], offset: {off!r}}}}}}}
driver: {{angle: [A, B], value: {q!r}, rate: 1}}
quantities: {{t: {{angle: [O, E]}}}}
report: {{position: [t], velocity: [tdot]}}
"""


def _cis(a):
    return complex(math.cos(a), math.sin(a))


def fourbar(scale, r, b, c, d, q, branch_point):
    """A four-bar text at crank angle q, figure near the solution on the side of branch_point."""
    B = r * _cis(q)
    D = complex(d, 0)
    dist = abs(D - B)
    # a figure point for C: the solution of the triangle (on the upper side), or a point on
    # the line B-D at the toggle, nudged to the upper side
    cosg = max(-1.0, min(1.0, (b * b + dist * dist - c * c) / (2 * b * dist)))
    C = B + b * (D - B) / dist * _cis(math.acos(cosg))
    C += 1e-3 * abs(D - B) * 1j * branch_point
    s = scale
    return FOURBAR.format(d=d * s, bx=B.real * s, by=B.imag * s, cx=C.real * s, cy=C.imag * s,
                          r=r * s, b=b * s, c=c * s, q=q)


def outcome(text, h):
    """('refused', None) or ('answered', worst relative disagreement of rates with differences)."""
    mech = linkcli.loads(text)
    q0 = mech.model.driver.value
    try:
        result = mech.solve()
    except SingularError:
        return "refused", None
    names = [n for n in mech.model.report["velocity"]]
    plus = mech.solve(q=q0 + h, names=[n[:-3] for n in names])
    minus = mech.solve(q=q0 - h, names=[n[:-3] for n in names])
    worst = 0.0
    for n in names:
        base = n[:-3]
        diff = float(plus.values[base]) - float(minus.values[base])
        if result.units[base] == "rad":
            diff = (diff + math.pi) % (2 * math.pi) - math.pi
        fd = diff / (2 * h)
        got = float(result.values[n])
        worst = max(worst, abs(got - fd) / max(abs(got), abs(fd), 1e-3))
    return "answered", worst


SCALES = st.sampled_from([1e-3, 1.0, 7.0, 1e3, 1e5])
EDGES = settings(derandomize=not os.environ.get("LINKCLI_EXPLORE"), database=None,
                 deadline=None, print_blob=True, suppress_health_check=list(HealthCheck))


@settings(EDGES, max_examples=60)
@given(scale=SCALES, r=st.floats(0.2, 1.0), b=st.floats(1.0, 3.0), c=st.floats(1.0, 3.0),
       d=st.floats(1.5, 3.0), outer=st.booleans())
def test_fourbar_exact_toggles(scale, r, b, c, d, outer):
    """B, C, D aligned: |BD| = b + c (outer) or |b - c| (inner).  Change-point linkages (two
    lengths' sum equal to the other two's: kites, parallelograms and every linkage on Grashof's
    boundary) align all four links at once, where the two assemblies cross instead of meeting
    at a fold: they are tested apart, below."""
    if _change_point_gap(r, b, c, d) < 1e-3:
        return
    target = b + c if outer else abs(b - c)
    cos_q = (r * r + d * d - target * target) / (2 * r * d)
    if not -1 < cos_q < 1 or target < 1e-3:
        return
    q = math.acos(cos_q)
    kind, worst = outcome(fourbar(scale, r, b, c, d, q, 1), 1e-7)
    assert kind == "refused" or worst < 1e-4, (kind, worst)
    # a regular position near the toggle, on the side where it assembles, is answered
    answered = []
    for near in (q - 1e-5, q + 1e-5):
        try:
            answered.append(outcome(fourbar(scale, r, b, c, d, near, 1), 1e-9))
        except AssemblyError:
            continue
    assert answered, "neither side of the toggle assembles"
    for kind, worst in answered:
        assert kind == "answered" and worst < 1e-3, (kind, worst)


def _change_point_gap(r, b, c, d):
    """How far the linkage is from Grashof's boundary s + l = p + q (0 on it)."""
    return min(abs(r + d - b - c), abs(r + b - c - d), abs(r + c - b - d))


def _exact_branches(r, b, c, d, q):
    """Both assemblies of the four-bar at crank angle q, to 40 digits of the given floats:
    [(t3, t4, t3dot, t4dot)] for a unit crank rate.  Closure r e^{iq} + b e^{i t3} =
    d + c e^{i t4}; its derivative r e^{iq} + b w3 e^{i t3} = c w4 e^{i t4}, times e^{-i t4}
    (or e^{-i t3}), imaginary part."""
    import mpmath as mp
    branches = []
    with mp.workdps(40):
        r, b, c, d, q = (mp.mpf(x) for x in (r, b, c, d, q))
        B = r * mp.expj(q)
        BD = d - B
        dist = abs(BD)
        gamma = mp.acos((b * b + dist * dist - c * c) / (2 * b * dist))
        for side in (1, -1):
            t3 = mp.arg(BD) + side * gamma
            t4 = mp.arg(B + b * mp.expj(t3) - d)
            w3 = r * mp.sin(t4 - q) / (b * mp.sin(t3 - t4))
            w4 = r * mp.sin(q - t3) / (c * mp.sin(t4 - t3))
            branches.append(tuple(float(x) for x in (t3 % (2 * mp.pi), t4 % (2 * mp.pi),
                                                     w3, w4)))
    return branches


def _angle_gap(a, b):
    return abs((a - b + math.pi) % (2 * math.pi) - math.pi)


@settings(EDGES, max_examples=40)
@given(scale=SCALES, r=st.floats(0.2, 1.0), b=st.floats(1.0, 3.0), c=st.floats(1.0, 3.0),
       form=st.sampled_from(["r+d=b+c", "r+b=c+d", "r+c=b+d"]))
def test_fourbar_change_points(scale, r, b, c, form):
    """On Grashof's boundary the four links align at q = 0 or 180 deg and both assemblies
    pass through that figure with different rates: the change point itself is refused.  Close
    to it each assembly is regular but its triangle is flat (height proportional to the
    distance), so finite differences are no reference: positions and rates are compared with
    the branch computed to 40 digits."""
    d = {"r+d=b+c": b + c - r, "r+b=c+d": r + b - c, "r+c=b+d": r + c - b}[form]
    q0 = math.pi if form == "r+d=b+c" else 0.0
    if d < 1.2 * r or abs(b - c) < 1e-2 or _change_point_gap(r, b, c, d) > 1e-12:
        return     # the crank not the shortest link, or B reaching D (b = c, forms 2 and 3)
    assert outcome(fourbar(scale, r, b, c, d, q0, 1), 1e-7)[0] == "refused"
    for eps in (1e-3, -1e-3, 1e-4, -1e-4, 1e-5, -1e-5, 3e-6, -3e-6, 1e-6, -1e-6):
        q = q0 + eps
        mech = linkcli.loads(fourbar(scale, r, b, c, d, q, 1))
        try:
            got = mech.solve().values
        except SingularError:
            assert abs(eps) < 1e-4, f"refused {eps} rad from the change point"
            continue
        t3, t4, w3, w4 = (float(got[n]) for n in ("t3", "t4", "t3dot", "t4dot"))
        branch = min(_exact_branches(r, b, c, d, q),
                     key=lambda e: _angle_gap(e[0], t3) + _angle_gap(e[1], t4))
        assert _angle_gap(branch[0], t3) < 1e-8 and _angle_gap(branch[1], t4) < 1e-8
        size = max(abs(branch[2]), abs(branch[3]))
        tolerance = 1e-4 if abs(eps) >= 1e-5 else 1e-2     # where answering stops: 3e-3
        assert abs(w3 - branch[2]) < tolerance * size and \
            abs(w4 - branch[3]) < tolerance * size, (eps, (w3, w4), branch)


@settings(EDGES, max_examples=20)
@given(scale=SCALES, r=st.floats(0.2, 1.0), l_ratio=st.floats(1.2, 3.0),
       e_ratio=st.floats(-0.9, 0.9))
def test_crank_slider_rates_next_to_the_fold_against_40_digits(scale, r, l_ratio, e_ratio):
    """From 1e-14 to 1e-6 rad of the rod-perpendicular toggle, on the side that assembles:
    refused within rounding, else xC' right to 1e-3 of the 40-digit derivative of
    x_C = r cos q + sqrt(l^2 - (e - r sin q)^2) (rates grow as 1/sqrt of the distance)."""
    import mpmath as mp
    l = r * l_ratio
    e = e_ratio * r - l
    q0 = math.asin((e + l) / r)

    def x_c(t):
        return mp.mpf(r) * mp.cos(t) + mp.sqrt(mp.mpf(l) ** 2 - (e - mp.mpf(r) * mp.sin(t)) ** 2)

    answered = 0
    for eps in (1e-14, 1e-12, 1e-10, 1e-8, 1e-6):
        for q in (q0 + eps, q0 - eps):
            B = r * _cis(q)
            text = SLIDER.format(bx=B.real * scale, by=B.imag * scale, e=e * scale,
                                 cx=B.real * scale + 1e-3 * scale, r=r * scale, l=l * scale, q=q)
            try:
                got = float(linkcli.loads(text).solve().values["xCdot"]) / scale
            except (SingularError, AssemblyError):
                continue
            with mp.workdps(40):
                exact = float(mp.diff(x_c, mp.mpf(q)))
            assert abs(got - exact) < 1e-3 * abs(exact), (eps, got, exact)
            answered += 1
    assert answered >= 3, "the side that assembles is answered from 1e-10 rad on"


@pytest.mark.parametrize("scale", [1e-3, 1.0, 10.0, 1e3, 1e6])
@pytest.mark.parametrize("q", [0.0, math.pi])
def test_parallelogram_change_points_are_refused(scale, q):
    """40/100/40/100 at q = 0 and 180 deg: the links are aligned, both branches meet."""
    text = FOURBAR.format(d=100 * scale, bx=40 * scale * math.cos(q), by=1e-3 * scale,
                          cx=(100 + 40 * math.cos(q)) * scale, cy=1e-3 * scale,
                          r=40 * scale, b=100 * scale, c=40 * scale, q=q)
    assert outcome(text, 1e-7)[0] == "refused"


@settings(EDGES, max_examples=40)
@given(scale=SCALES, r=st.floats(0.2, 1.0), l_ratio=st.floats(1.0, 4.0),
       e_ratio=st.floats(-0.9, 0.9))
def test_crank_slider_rod_perpendicular_to_the_guide(scale, r, l_ratio, e_ratio):
    """The rod normal to the guide (|e - y_B| = l): the RRP toggle."""
    l = r * l_ratio
    e = e_ratio * r - l if e_ratio * r - l > -r - l else -l
    # crank angle with y_B = e + l (the rod vertical, C straight below B)
    s = (e + l) / r
    if not -1 < s < 1:
        return
    q = math.asin(s)
    B = r * _cis(q)
    text = SLIDER.format(bx=B.real * scale, by=B.imag * scale, cx=B.real * scale + 1e-3 * scale,
                         e=e * scale, r=r * scale, l=l * scale, q=q)
    kind, worst = outcome(text, 1e-7)
    assert kind == "refused" or worst < 1e-4, (kind, worst)


@pytest.mark.parametrize("scale", [1e-3, 1.0, 1e3, 1e5])
def test_slotted_link_toggle(scale):
    """The slot's offset equal to the pin's distance from the slotted link's pivot:
    |sin| = 1 in the RPR dyad, an exact toggle."""
    r, d, off = 0.5, 1.0, 0.5          # |B - O| = 0.5 = off at q = 0
    B = complex(r, 0)
    text = SLOTTED.format(d=d * scale, bx=B.real * scale, by=B.imag * scale,
                          ex=(d + 0.01) * scale, ey=2.0 * scale, r=r * scale, L=2.0 * scale,
                          off=off * scale, q=0.0)
    assert outcome(text, 1e-7)[0] == "refused"
