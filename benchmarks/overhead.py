"""Where the time of one call at 360 positions goes (run by `make bench`).

At 360 positions a call is a few hundred NumPy operations on short arrays, each costing
about a microsecond whatever it computes, plus the Python that strings them.  For the
seed-004 four-bar (angles of the coupler and rocker and their two rates) and the seed-000
crank-slider (the rod's angle, the slider's x and their rates) this times:

- linkcli's call ``Linkage.solve(q, names=...)`` (from its second call the straight-line
  solve of ``kinematics/straight.py``) and the phases of its general path (positions,
  velocities, accelerations with their checks, the report's values), which answers the
  positions the straight-line solve leaves;
- ``straight``: linkcli's algorithm written as one straight-line NumPy function for each
  mechanism: the same circle intersection, the same 2x2 rate systems on the points, the
  same refusals (assembly, toggle within rounding, singular rate system, finiteness), the
  same angles in [0, 2 pi) and rates from w = z'/z; no Python structure at all;
- ``hand``: the hand-written closed form of ``speed.py`` (no checks, angles in (-pi, pi]).

``straight`` against ``hand`` is what the checks and the general formulation cost;
linkcli against ``straight`` is what is left of the structure (the plan, the result).

    python benchmarks/overhead.py [--rounds R]

Writes benchmarks/out/overhead.md (also printed).
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)

from speed import OUT, case, machine  # noqa: E402
from linkcli.kinematics import compiled  # noqa: E402

TWO_PI = 2 * math.pi
EPS = np.finfo(float).eps


class Refused(Exception):
    """A position the straight-line version refuses, as linkcli would."""


def straight_fourbar(q, qd, qdd, r=0.1, b=0.315, c=0.5,
                     b0=0.425 * complex(math.cos(7 / 4 * math.pi), math.sin(7 / 4 * math.pi))):
    """The four-bar by linkcli's algorithm, straight-line: crank A = r e^{iq}; B on the
    circles |B - A| = b, |B - B0| = c (B = A + (B0 - A)(t + i s)); the point rates from
    Re(conj(G_i) B') = r_i with G_1 = B - A, G_2 = B - B0; angles and rates of B - A and
    B - B0 from w = z'/z, stacked."""
    a = np.empty(q.shape, complex)
    np.cos(q, out=a.real)
    np.sin(q, out=a.imag)
    a *= r
    d = b0 - a
    d2 = d.real * d.real + d.imag * d.imag
    t = (b * b - c * c + d2) / (2.0 * d2)
    e = b * b / d2 - t * t
    lowest = e.min()
    if not lowest > 2048 * EPS * b * b / d2.min() * (1.0 + (np.abs(a).max() + abs(b0))
                                                     / math.sqrt(d2.min())):
        raise Refused("cannot assemble or toggle")
    z = np.empty(q.shape, complex)
    z.real = t
    np.sqrt(e, out=z.imag)
    p = a + d * z
    u1, u2 = p - a, p - b0
    det = u1.real * u2.imag - u1.imag * u2.real
    measure = np.abs(det) / (b * c)
    if measure.min() < 1e-9:
        raise Refused("singular")
    inv = 1.0 / det
    k1 = np.empty(q.shape, complex)
    np.multiply(u2.imag, inv, out=k1.real)
    np.multiply(u2.real, -inv, out=k1.imag)
    k2 = np.empty(q.shape, complex)
    np.multiply(u1.imag, -inv, out=k2.real)
    np.multiply(u1.real, inv, out=k2.imag)
    va = a * (1j * qd)
    vp = (u1.conjugate() * va).real * k1
    vp += 0.0
    aa = a * (1j * qdd - qd * qd)
    dv = vp - va
    ap = ((u1.conjugate() * aa).real - (dv.real * dv.real + dv.imag * dv.imag)) * k1 \
        - (vp.real * vp.real + vp.imag * vp.imag) * k2
    ap += 0.0
    zs = np.empty((3, 2) + q.shape, complex)
    np.subtract(p, a, out=zs[0, 0])
    np.subtract(p, b0, out=zs[0, 1])
    np.subtract(vp, va, out=zs[1, 0])
    zs[1, 1] = vp
    np.subtract(ap, aa, out=zs[2, 0])
    zs[2, 1] = ap
    table = np.empty((3, 2) + q.shape)
    angle = table[0]
    np.arctan2(zs[0].imag, zs[0].real, out=angle)
    np.add(angle, TWO_PI, out=angle, where=angle <= 0)
    np.copyto(angle, 0.0, where=angle > TWO_PI - 1e-12)
    w = zs[1:] / zs[0]
    np.add(w[0].imag, 0.0, out=table[1])
    np.multiply(w[0].real, w[0].imag, out=table[2])
    table[2] *= -2.0
    table[2] += w[1].imag
    if not np.isfinite(table).all():
        raise Refused("not finite")
    return dict(zip(("beta", "gamma", "betadot", "gammadot", "betaddot", "gammaddot"),
                    table.reshape(6, -1)))


def straight_crank_slider(q, qd, qdd, a=1.0, b=math.sqrt(2.0)):
    """The centred crank-slider by linkcli's algorithm, straight-line: crank A = a e^{iq};
    B on |B - A| = b and the line y = 0 (B = along + 0i, along = Re A + sqrt(b^2 - Im A^2));
    the rates of B from Re(conj(G_i) B') = r_i with G_1 = B - A, G_2 = i (the guide's
    normal); the angle of B - A from w = z'/z; x of B and its rates."""
    p = np.empty(q.shape, complex)
    np.cos(q, out=p.real)
    np.sin(q, out=p.imag)
    p *= a
    dist = p.imag
    disc = b * b - dist * dist
    lowest = disc.min()
    if not lowest > 2048 * EPS * (b * b + b * (np.abs(p).max() + b)):
        raise Refused("cannot assemble or toggle")
    pb = np.empty(q.shape, complex)
    np.add(p.real, np.sqrt(disc), out=pb.real)
    pb.imag = 0.0
    u1 = pb - p
    det = u1.real                       # cross(G_1, i) = Re G_1
    if (np.abs(det) / b).min() < 1e-9:
        raise Refused("singular")
    inv = 1.0 / det
    k1 = np.empty(q.shape, complex)     # K_1 = -i G_2 / det = 1 / det
    k1.real = inv
    k1.imag = 0.0
    va = p * (1j * qd)
    vb = (u1.conjugate() * va).real * k1
    vb += 0.0
    aa = p * (1j * qdd - qd * qd)
    dv = vb - va
    ab = ((u1.conjugate() * aa).real - (dv.real * dv.real + dv.imag * dv.imag)) * k1
    ab += 0.0
    table = np.empty((6,) + q.shape)
    angle = table[0]
    np.arctan2(u1.imag, u1.real, out=angle)
    np.add(angle, TWO_PI, out=angle, where=angle <= 0)
    np.copyto(angle, 0.0, where=angle > TWO_PI - 1e-12)
    w = dv / u1
    np.add(w.imag, 0.0, out=table[2])
    np.multiply(w.real, w.imag, out=table[4])
    table[4] *= -2.0
    table[4] += ((ab - aa) / u1).imag
    np.add(pb.real, 0.0, out=table[1])
    np.add(vb.real, 0.0, out=table[3])
    np.add(ab.real, 0.0, out=table[5])
    if not np.isfinite(table).all():
        raise Refused("not finite")
    return dict(zip(("beta", "xB", "betadot", "xBdot", "betaddot", "xBddot"), table))


def phases(c, q):
    """Seconds of each phase of one evaluation (fresh kinematics, as a call makes)."""
    from linkcli.answers.quantities import plan_for
    from linkcli.kinematics.solvers import solver_for
    solver, plan = solver_for(c.mech), plan_for(c.mech, c.names)
    clock = time.perf_counter
    t0 = clock()
    kin = solver.positions(q)
    solver.check(kin, velocities=False)
    t1 = clock()
    solver.velocities(kin, c.qd)
    solver.check(kin, velocities=True)
    t2 = clock()
    solver.accelerations(kin, c.qdd)
    t3 = clock()
    plan.collect(c.mech, solver, kin)
    t4 = clock()
    return np.diff([t0, t1, t2, t3, t4])


STRAIGHT = {"four-bar": straight_fourbar, "crank-slider": straight_crank_slider}


def measure(key, rounds):
    """(us per call of linkcli, straight, hand; linkcli's phases in us; straight - linkcli)."""
    c = case(key)
    q = c.grid(360)
    straight = STRAIGHT[key]
    mine, same = c.solve(q), straight(q, c.qd, c.qdd)
    agree = max(float(np.max(np.abs(mine[n] - same[n]))) for n in mine)
    funcs = {"linkcli": lambda: c.solve(q), "straight": lambda: straight(q, c.qd, c.qdd),
             "hand": lambda: c.by_hand(q)}
    if compiled.switch(True):           # numba installed: the compiled loop too
        funcs["compiled"] = lambda: c.solve(q, jit=True)
    best = dict.fromkeys(funcs, math.inf)
    parts = np.full(4, math.inf)
    for _ in range(rounds):
        for name, func in funcs.items():
            start = time.perf_counter()
            for _ in range(200):
                func()
            best[name] = min(best[name], (time.perf_counter() - start) / 200)
        parts = np.minimum(parts, np.min([phases(c, q) for _ in range(200)], axis=0))
    return {k: v * 1e6 for k, v in best.items()}, parts * 1e6, agree


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=15, help="rounds of 200 calls each")
    args = parser.parse_args(argv)
    lines = ["# One call at 360 positions", "",
             f"{time.strftime('%Y-%m-%d')}, {machine()}. Best of {args.rounds} rounds of 200 "
             "calls (phases: the best of each).", "",
             "| mechanism | linkcli | linkcli's algorithm and checks, straight-line | "
             "hand-written, no checks | linkcli's general path, phases: positions, velocities, "
             "accelerations, report values | straight - linkcli | linkcli, compiled loop |",
             "| --- | ---: | ---: | ---: | --- | ---: | ---: |"]
    for key in STRAIGHT:
        us, parts, agree = measure(key, args.rounds)
        hand = us["hand"]
        lines.append(f"| {key} | {us['linkcli']:.1f} us ({us['linkcli'] / hand:.2f}x) | "
                     f"{us['straight']:.1f} us ({us['straight'] / hand:.2f}x) | {hand:.1f} us | "
                     + ", ".join(f"{v:.1f}" for v in parts) + f" us | {agree:.1e} | "
                     + (f"{us['compiled']:.1f} us ({us['compiled'] / hand:.2f}x) |"
                        if "compiled" in us else "numba not installed |"))
        print(lines[-1], flush=True)
    lines += ["", "Straight-line: the same operations as linkcli for this mechanism, in one "
              "function (the values agree bit for bit); what it costs over the hand-written "
              "code is the general formulation and the checks, what linkcli costs over it is "
              "what is left of its structure: a call is written out the same way once per "
              "mechanism (kinematics/straight.py); the phases are those of the general path "
              "(groups, dictionaries, the plan), which answers what that leaves. The compiled loop "
              "(kinematics.compiled, LINKCLI_JIT=1 with numba) does the same work position by "
              "position in one compiled function."]
    text = "\n".join(lines)
    print("\n" + text)
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, "overhead.md"), "w", encoding="utf-8") as handle:
        handle.write(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
