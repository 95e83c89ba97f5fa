"""linkcli against hand-written NumPy, at every size (run by `make bench`).

For three mechanisms - the seed-004 four-bar, the seed-000 crank-slider and the
six-bar of mechanisms/padova-2020-07.yaml (``speed_accuracy.py`` writes them in SI
units) - it times positions, velocities and accelerations of every reported quantity
at N = 360, 2048 (``COMPILED_MOST``: the longest array the compiled loop takes), 10^4,
10^6 and 10^7 driver positions:

- linkcli: ``Linkage.solve(q, names=...)`` on the whole array (10^7: in blocks of
  16384 positions, the block size of ``linkcli sweep``, in a fresh process whose peak
  resident memory is read);
- hand-written NumPy of the same closed form (the same blocks at 10^7, with the same
  malloc settings, ``linkcli.answers.memory``), the speed to compare with;
- linkcli's compiled loop (``kinematics.compiled``, the ``jit`` extra) when numba is
  installed: the same call with the loop switched on, at the sizes it takes (up to
  ``COMPILED_MOST`` positions; NumPy solves longer arrays either way);
- peers when importable: pylinkage's numba path (``Linkage.step_fast_with_kinematics``,
  joint coordinates and their two rates, no angles) for the four-bar and the
  crank-slider (it has no link of driven length for the six-bar), up to 10^6; its
  agreement with linkcli's joint positions and velocities is printed beside it.

Next to the speed, the accuracy on the 10^4 grid: the closure residual of linkcli's
positions (every constraint of every group, relative to the square of the mechanism's
size), the rates of each method against central finite differences of its own
positions (five-point differences, step 1e-3 of the driver range, relative to the
largest rate: the differences themselves are good to ~1e-8), and the largest difference between linkcli and the
hand-written values (angles in rad, others relative).

    python benchmarks/speed.py [--quick] [--repeat R] [--mechanism NAME ...]

--quick stops at N = 10^6; --repeat R takes the median of R timings up to 10^6 (the
machine's noise, ~20 %, is larger than many a change); --mechanism times only those.  Writes benchmarks/out/speed.md (the table, also printed)
and benchmarks/out/speed.png (time per position against N).
"""
from __future__ import annotations

import argparse
import importlib
import json
import math
import os
import platform
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)

import linkcli  # noqa: E402
from linkcli.answers.quantities import COMPILED_MOST  # noqa: E402
from linkcli.kinematics import compiled  # noqa: E402
from speed_accuracy import CRANK_SLIDER, FOURBAR, SIXBAR, hand_fourbar  # noqa: E402

OUT = os.path.join(HERE, "out")
from linkcli.answers.quantities.plan import WORKERS as DEFAULT_WORKERS  # noqa: E402
SIZES = (1, 10, 100, 360, COMPILED_MOST, 10 ** 4, 10 ** 5, 10 ** 6, 10 ** 7)
#: from this many positions on, linkcli is also timed on one thread (blocks not in parallel)
THREADED = 10 ** 5
BLOCK = 16384           # positions per block at 10^7 (runs.sweep.blocks.BLOCK)
ACCURACY_N = 10 ** 4
PEERS = ("pylinkage",)


# --- peers -------------------------------------------------------------------------------
def pylinkage_peer(key):
    """pylinkage's numba path for mechanism ``key``: (run(n), check()) or None.

    ``run(n)`` steps the crank n times (the crank turns 2 pi / 360 per step; joint
    positions, velocities and accelerations at every step); ``check()`` gives the largest
    difference of its output joint's position and velocity from linkcli's at the same
    crank angles (relative to the largest).  None where pylinkage cannot state the
    mechanism (the six-bar's driven length) or is not installed."""
    try:
        from pylinkage.actuators import Crank
        from pylinkage.components import Ground
        from pylinkage.dyads import RRPDyad, RRRDyad
        from pylinkage.simulation import Linkage
    except ImportError:
        return None
    step = 2 * math.pi / 360
    if key not in ("four-bar", "crank-slider"):
        return None

    def build():
        """(linkage, output joint's index, first crank angle), the crank at its start."""
        if key == "four-bar":
            start, rate, accel = 0.0, 5 * math.pi, 0.0
            a0 = Ground(0.0, 0.0, name="A0")
            b0 = Ground(0.425 * math.cos(7 / 4 * math.pi), 0.425 * math.sin(7 / 4 * math.pi),
                        name="B0")
            crank = Crank(anchor=a0, radius=0.1, angular_velocity=step, initial_angle=start,
                          name="A")
            parts = [a0, b0, crank, RRRDyad(crank.output, b0, distance1=0.315, distance2=0.5,
                                             name="B")]
        else:
            start, rate, accel = math.pi / 4, 0.5, 1.0
            o, x = Ground(0.0, 0.0, name="O"), Ground(1.0, 0.0, name="X")
            crank = Crank(anchor=o, radius=1.0, angular_velocity=step, initial_angle=start,
                          name="A")
            parts = [o, x, crank, RRPDyad(crank.output, o, x, distance=math.sqrt(2), x=1.93,
                                          y=0.0, name="B")]
        linkage = Linkage(parts, name=key)
        linkage.set_input_velocity(crank, rate, accel)
        return linkage, len(parts) - 1, start, rate

    timed = build()[0]

    def run(n):
        return timed.step_fast_with_kinematics(iterations=n)

    def check():
        linkage, joint, start, rate = build()
        pos, vel, _ = linkage.step_fast_with_kinematics(iterations=360)
        q = start + step * np.arange(1, 361)          # one step before each output
        solver = case(key).linkage.solver()
        kin = solver.velocities(solver.positions(q), rate)
        worst = 0.0
        for got, mine in ((pos, kin.pos["B"]), (vel, kin.vel["B"])):
            z = got[:, joint, 0] + 1j * got[:, joint, 1]
            worst = max(worst, float(np.max(np.abs(z - mine)) / np.max(np.abs(mine))))
        return worst
    return run, check


# --- hand-written closed forms: values and their first and second time rates --------------
def hand_crank_slider(q, qd, qdd):
    """Centred crank-slider, OA = a, AB = b, B on y = 0 right of O:
    a sin q + b sin beta = 0, xB = a cos q + b cos beta, differentiated twice."""
    a, b = 1.0, math.sqrt(2.0)
    sq, cq = np.sin(q), np.cos(q)
    sb = -a / b * sq
    cb = np.sqrt(1.0 - sb * sb)
    beta = np.arctan2(sb, cb)
    bd = -a * cq * qd / (b * cb)
    bdd = (a * sq * qd * qd - a * cq * qdd + b * sb * bd * bd) / (b * cb)
    xd = -a * sq * qd - b * sb * bd
    xdd = -a * cq * qd * qd - a * sq * qdd - b * cb * bd * bd - b * sb * bdd
    return {"beta": beta, "xB": a * cq + b * cb, "betadot": bd, "xBdot": xd,
            "betaddot": bdd, "xBddot": xdd}


def _solve2(g1, g2, r1, r2):
    """X with Re(conj(g1) X) = r1, Re(conj(g2) X) = r2: X = i (r2 g1 - r1 g2) / cross."""
    det = (g1.conjugate() * g2).imag
    return 1j * (r2 * g1 - r1 * g2) / det


def _angle_rates(z, zd, zdd):
    """arg z and its rates: Im(z'/z), Im(z''/z - (z'/z)^2)."""
    w = zd / z
    return np.angle(z), w.imag, (zdd / z - w * w).imag


def hand_sixbar(q, qd, qdd):
    """Actuator AB = q, rocker BCD (BC = BD = 0.07, D a quarter turn from C), rod DE = 0.19,
    E on y = 0.18 left of D: circle-circle for B, a rotation for D, circle-line for E."""
    C, bc, de, ye = 0.18 + 0.04j, 0.07, 0.19, 0.18
    L2 = abs(C) ** 2
    t = (q * q - bc * bc + L2) / (2 * L2)
    s = np.sqrt(q * q / L2 - t * t)
    B = C * (t + 1j * s)
    u, v = B, B - C                         # |u| = q, |v| = bc
    Bd = _solve2(u, v, q * qd, 0.0)
    Bdd = _solve2(u, v, q * qdd + qd * qd - np.abs(Bd) ** 2, -np.abs(Bd) ** 2)
    turn = 1 - 1j * (0.07 / bc)             # D - B = i (0.07 / bc) (C - B)
    D, Dd, Ddd = B + (1j * 0.07 / bc) * (C - B), Bd * turn, Bdd * turn
    dy = ye - D.imag
    dx = -np.sqrt(de * de - dy * dy)
    E = (D.real + dx) + 1j * ye
    xd = Dd.real + dy * Dd.imag / dx
    xdd = Ddd.real - ((xd - Dd.real) ** 2 + Dd.imag ** 2 - dy * Ddd.imag) / dx
    Ed, Edd = xd + 0j, xdd + 0j
    out = {"xE": E.real, "xEdot": xd, "xEddot": xdd}
    for name, (z, zd, zdd) in {"phi1": (B, Bd, Bdd), "phi2": (C - B, -Bd, -Bdd),
                               "phi3": (D - B, Dd - Bd, Ddd - Bdd),
                               "phi4": (E - D, Ed - Dd, Edd - Ddd)}.items():
        out[name], out[name + "dot"], out[name + "ddot"] = _angle_rates(z, zd, zdd)
    return out


class Case:
    def __init__(self, key, text, hand, lo, hi):
        self.key, self.hand, self.lo, self.hi = key, hand, lo, hi
        self.linkage = linkcli.loads(text, name=f"{key}.yaml")
        self.mech = self.linkage.model
        report = self.mech.report
        self.base = report["position"]
        self.names = [n for s in ("position", "velocity", "acceleration") for n in report[s]]
        self.qd, self.qdd = self.mech.driver.rate, self.mech.driver.accel

    def grid(self, n):
        return self.lo + (self.hi - self.lo) * (np.arange(n) + 0.5) / n

    def solve(self, q, jit=False):
        """linkcli's values at ``q``; ``jit``: by the compiled loop (kinematics.compiled),
        else NumPy (the switch is set at each call, the same small cost either way)."""
        compiled.switch(jit)
        return self.linkage.solve(q, names=self.names).values

    def evaluator(self):
        """``Linkage.evaluator`` of the names: made once, called at each position set."""
        compiled.switch(False)
        return self.linkage.evaluator(self.names)

    def by_hand(self, q):
        return self.hand(q, self.qd, self.qdd)


CASES = {"four-bar": (FOURBAR, hand_fourbar, 0.0, 2 * math.pi),
         "crank-slider": (CRANK_SLIDER, hand_crank_slider, 0.0, 2 * math.pi),
         "six-bar": (SIXBAR, hand_sixbar, 0.12, 0.20)}


def case(key) -> Case:
    text, hand, lo, hi = CASES[key]
    return Case(key, text, hand, lo, hi)


# --- timing ----------------------------------------------------------------------------
def best_time(func, budget=1.0, most=200):
    """The best of repeated runs, as many as fit ``budget`` seconds (at least 3)."""
    best, spent, runs = math.inf, 0.0, 0
    while runs < 3 or (spent < budget and runs < most):
        start = time.perf_counter()
        func()
        took = time.perf_counter() - start
        best, spent, runs = min(best, took), spent + took, runs + 1
    return best


def median_times(funcs, budget, repeat):
    """Per function, the median of ``repeat`` best times (:func:`best_time`), the functions'
    runs interleaved so that a slow spell of the machine falls on all of them."""
    times = [[] for _ in funcs]
    for _ in range(max(1, repeat)):
        for func, got in zip(funcs, times):
            got.append(best_time(func, budget))
    return [float(np.median(got)) for got in times]


def in_blocks(func, c, n):
    """Solve ``n`` positions block by block (values dropped): seconds."""
    start = time.perf_counter()
    for lo in range(0, n, BLOCK):
        q = c.lo + (c.hi - c.lo) * (np.arange(lo, min(n, lo + BLOCK)) + 0.5) / n
        func(q)
    return time.perf_counter() - start


def one_thread(on: bool = True) -> None:
    """linkcli's blocks of a long array solved one after the other (``on``), or on its
    default threads."""
    from linkcli.answers.quantities import plan
    plan.WORKERS = 1 if on else DEFAULT_WORKERS


def high_water() -> float:
    """Peak resident memory of this process (MB)."""
    with open("/proc/self/status", encoding="ascii") as handle:
        for line in handle:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    import resource
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def child(key, method, n):
    """Run in a fresh process: one blocked solve of ``n`` positions, its time and peak RSS
    (``method`` linkcli1: linkcli on one thread)."""
    from linkcli.answers.memory import keep_freed_memory
    if method == "linkcli1":
        one_thread()
        method = "linkcli"
    c = case(key)
    keep_freed_memory()                     # both with the malloc settings linkcli's solves
    func = c.solve if method == "linkcli" else c.by_hand    # of blocks take
    func(c.grid(BLOCK))                     # warm: plans and solvers built
    before = high_water()
    seconds = in_blocks(func, c, n)
    return {"seconds": seconds, "rss_MB": high_water(), "rss_before_MB": before}


# --- accuracy --------------------------------------------------------------------------
def _diff(a, b, angle):
    d = np.asarray(a, float) - np.asarray(b, float)
    return np.angle(np.exp(1j * d)) if angle else d


def accuracy(c):
    """(closure residual, linkcli rates vs FD, hand rates vs FD, linkcli vs hand)."""
    from linkcli.kinematics.closed_form import residuals
    q = c.grid(ACCURACY_N)
    solver = c.linkage.solver()
    kin = solver.positions(q)
    size = max(float(np.max(np.abs(z))) for z in kin.pos.values())
    closure = max(float(np.max(np.abs(r))) for r in residuals(solver, kin).values()) / size ** 2
    h = 1e-3 * (c.hi - c.lo)
    out = []
    for func in (c.solve, c.by_hand):
        f0 = func(q)
        steps = {k: func(q + k * h) for k in (-2, -1, 1, 2)}
        worst = 0.0
        for name in c.base:
            angle = not name.startswith(("x", "y"))
            d = {k: _diff(f[name], f0[name], angle) for k, f in steps.items()}
            d1 = (8 * (d[1] - d[-1]) - (d[2] - d[-2])) / (12 * h)        # five points
            d2 = (16 * (d[1] + d[-1]) - (d[2] + d[-2])) / (12 * h * h)
            for rate, fd in ((f0[name + "dot"], d1 * c.qd),
                             (f0[name + "ddot"], d2 * c.qd ** 2 + d1 * c.qdd)):
                scale = max(float(np.max(np.abs(rate))), 1e-300)
                worst = max(worst, float(np.max(np.abs(rate - fd))) / scale)
        out.append(worst)
    mine, hand = c.solve(q), c.by_hand(q)
    agree = 0.0
    for name in c.names:
        angle = not name.startswith(("x", "y")) and name in c.base
        scale = 1.0 if angle else max(float(np.max(np.abs(hand[name]))), 1e-300)
        agree = max(agree, float(np.max(np.abs(_diff(mine[name], hand[name], angle)))) / scale)
    return closure, out[0], out[1], agree


def compiled_against_numpy(c) -> float:
    """The largest difference of the compiled loop's values from NumPy's on the longest
    grid the loop solves (angles in rad, others relative)."""
    q = c.grid(COMPILED_MOST)
    mine, jit = c.solve(q), c.solve(q, jit=True)
    worst = 0.0
    for name in c.names:
        angle = not name.startswith(("x", "y")) and name in c.base
        scale = 1.0 if angle else max(float(np.max(np.abs(mine[name]))), 1e-300)
        worst = max(worst, float(np.max(np.abs(_diff(jit[name], mine[name], angle)))) / scale)
    return worst


# --- the run ---------------------------------------------------------------------------
def machine() -> str:
    model = platform.processor() or "unknown CPU"
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="replace") as handle:
            model = next((line.split(":", 1)[1].strip() for line in handle
                          if line.startswith("model name")), model)
    except OSError:
        pass
    return (f"{os.cpu_count()} cores ({model}), Python {platform.python_version()}, "
            f"NumPy {np.__version__}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="stop at N = 10^6")
    parser.add_argument("--repeat", type=int, default=1, metavar="R",
                        help="up to 10^6: the median of R timings, each the best of its runs "
                        "(a shared machine varies by ~20 %%)")
    parser.add_argument("--mechanism", action="append", choices=list(CASES),
                        help="time only this mechanism (repeatable)")
    parser.add_argument("--child", nargs=3, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child:
        print(json.dumps(child(args.child[0], args.child[1], int(args.child[2]))))
        return 0
    sizes = [n for n in SIZES if not args.quick or n <= 10 ** 6]
    jit = compiled.switch(True)             # numba installed: linkcli's compiled loop too
    if jit:
        case("crank-slider").solve(np.linspace(0, 1, 8), jit=True)     # compiled or loaded
    os.makedirs(OUT, exist_ok=True)
    rows, checks, agreement = [], {}, {}
    for key in args.mechanism or CASES:
        c = case(key)
        c.solve(c.grid(8))
        closure, fd_mine, fd_hand, agree = accuracy(c)
        print(f"{key}: closure {closure:.1e}, rates vs FD {fd_mine:.1e} (hand {fd_hand:.1e}), "
              f"linkcli - hand {agree:.1e}", flush=True)
        if jit:
            agreement[key] = same = compiled_against_numpy(c)
            print(f"  compiled loop against NumPy: {same:.1e} (angles in rad, others relative)",
                  flush=True)
        peer = pylinkage_peer(key)
        if peer is not None:
            peer[0](8)                  # compiled (numba) before timing
            checks[key] = peer[1]()
            print(f"  pylinkage: joint positions and velocities within {checks[key]:.1e} of "
                  "linkcli's", flush=True)
        for n in sizes:
            row = {"mechanism": key, "N": n, "closure": closure, "fd": fd_mine,
                   "fd_hand": fd_hand, "agree": agree}
            if n <= 10 ** 6:
                q = c.grid(n) if n > 1 else float(c.grid(1)[0])     # one position: a number
                budget = 0.5 if n < 360 else 2.0 if n < 10 ** 6 else 1.0
                ev = c.evaluator()
                funcs = {"linkcli": lambda: c.solve(q, jit=False), "evaluator": lambda: ev(q),
                         "hand": lambda: c.by_hand(q)}
                if n >= THREADED:
                    funcs["linkcli_1"] = lambda: (one_thread(), c.solve(q, jit=False),
                                                  one_thread(False))
                if jit and n <= COMPILED_MOST:
                    funcs["compiled"] = lambda: c.solve(q, jit=True)
                if peer is not None:
                    funcs["pylinkage"] = lambda: peer[0](n)
                times = median_times(list(funcs.values()), budget, args.repeat)
                row.update({k: t / n for k, t in zip(funcs, times)})
            else:
                for method in ("linkcli", "linkcli1", "hand"):
                    run = subprocess.run([sys.executable, os.path.abspath(__file__), "--child",
                                          key, method, str(n)], capture_output=True, text=True,
                                         check=True)
                    got = json.loads(run.stdout.strip().splitlines()[-1])
                    name = "linkcli_1" if method == "linkcli1" else method
                    row[name] = got["seconds"] / n
                    row[name + "_rss"] = got["rss_MB"]
            rows.append(row)
            other = f"  pylinkage {row['pylinkage'] * 1e9:8.1f} ns/pos" if "pylinkage" in row \
                else ""
            other += f"  compiled {row['compiled'] * 1e9:8.1f} ns/pos" if "compiled" in row \
                else ""
            other += f"  evaluator {row['evaluator'] * 1e9:8.1f} ns/pos" if "evaluator" in row \
                else ""
            other += f"  one thread {row['linkcli_1'] / row['hand']:.2f}x" if "linkcli_1" in row \
                else ""
            print(f"  N={n:<9d} linkcli {row['linkcli'] * 1e9:8.1f} ns/pos  hand "
                  f"{row['hand'] * 1e9:8.1f} ns/pos  ratio {row['linkcli'] / row['hand']:.2f}"
                  f"{other}", flush=True)
    peers = []
    for name in PEERS:
        try:
            module = importlib.import_module(name)
        except ImportError:
            peers.append(f"{name}: not installed, skipped (pip install pylinkage numba)")
            continue
        agree = ", ".join(f"{k} {v:.1e}" for k, v in checks.items())
        peers.append(f"{name} {getattr(module, '__version__', '?')}, numba path "
                     "(step_fast_with_kinematics: joint coordinates and their rates, no angles), "
                     f"its output joint against linkcli's, relative: {agree or 'not run'}")
    if jit:
        import numba
        peers.append(f"linkcli compiled: numba {numba.__version__}, against linkcli's NumPy "
                     "values (angles in rad, others relative): "
                     + ", ".join(f"{k} {v:.1e}" for k, v in agreement.items()))
    else:
        peers.append("linkcli compiled: numba not installed, skipped (pip install numba)")
    text = table(rows, peers)
    print("\n" + text)
    with open(os.path.join(OUT, "speed.md"), "w", encoding="utf-8") as handle:
        handle.write(text + "\n")
    with open(os.path.join(OUT, "speed.json"), "w", encoding="utf-8") as handle:
        json.dump({"machine": machine(), "rows": rows, "peers": peers}, handle, indent=1)
    print(f"\nchart: {chart(rows)}")
    return 0


def table(rows, peers) -> str:
    lines = ["# linkcli against hand-written NumPy", "",
             f"{time.strftime('%Y-%m-%d')}, {machine()}.", "",
             "Time per position of positions, velocities and accelerations of every reported "
             "quantity (N <= 360: per call); 10^7 in blocks of 16384 in a fresh process "
             "(peak RSS of that process). linkcli: `Linkage.solve(q, names=...)`; "
             "evaluator: `Linkage.evaluator(names)` made once, then called; one thread: "
             "linkcli with its blocks solved one after the other (from 10^5 on). Accuracy "
             "on 10^4 positions: closure residual (relative to size^2), rates against "
             "five-point finite differences (relative; the differences are good to ~1e-8), "
             "linkcli against hand-written.", "",
             "| mechanism | N | linkcli | evaluator | hand-written | ratio | evaluator ratio "
             "| one thread ratio | linkcli compiled (ratio) | pylinkage (numba) "
             "| peak RSS linkcli / hand | closure | rates vs FD (hand) | linkcli - hand |",
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: "
             "| ---: | ---: | ---: |"]

    def shown(seconds, n):
        return f"{seconds * n * 1e6:.1f} us" if n < 360 else \
            f"{seconds * n * 1e3:.3f} ms" if n == 360 else f"{seconds * 1e9:.0f} ns"
    for r in rows:
        n = r["N"]
        mine, hand = shown(r["linkcli"], n), shown(r["hand"], n)
        ev = shown(r["evaluator"], n) if "evaluator" in r else ""
        ev_ratio = f"{r['evaluator'] / r['hand']:.2f}x" if "evaluator" in r else ""
        one = f"{r['linkcli_1'] / r['hand']:.2f}x" if "linkcli_1" in r else ""
        peer = shown(r["pylinkage"], n) if "pylinkage" in r else ""
        jit = f"{shown(r['compiled'], n)} ({r['compiled'] / r['hand']:.2f}x)" \
            if "compiled" in r else ""
        rss = f"{r['linkcli_rss']:.0f} / {r['hand_rss']:.0f} MB" if "linkcli_rss" in r else ""
        size = str(n) if n < 10 ** 4 else f"10^{round(math.log10(n))}"
        lines.append(f"| {r['mechanism']} | {size} | {mine} | {ev} | {hand} | "
                     f"{r['linkcli'] / r['hand']:.2f}x | {ev_ratio} | {one} | {jit} | {peer} | "
                     f"{rss} | {r['closure']:.1e} | "
                     f"{r['fd']:.1e} ({r['fd_hand']:.1e}) | {r['agree']:.1e} |")
    lines += ["", "Peers: " + "; ".join(peers) + ".", "",
              f"linkcli compiled: the same call with the compiled loop switched on "
              f"(kinematics.compiled), which takes arrays of up to {COMPILED_MOST} positions "
              "(longer ones are solved by NumPy, the linkcli column)."]
    return "\n".join(lines)


#: the paths of the chart: (row key, label, line style)
PATHS = (("linkcli", "linkcli solve", "-o"), ("linkcli_1", "linkcli solve, one thread", "-x"),
         ("evaluator", "linkcli evaluator", "-v"), ("hand", "hand-written", "--s"),
         ("compiled", "linkcli compiled", "-.d"), ("pylinkage", "pylinkage (numba)", ":^"))


def chart(rows) -> str:
    """Time per call against N (1 to 10^7) for each path, and each path over hand-written."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    keys = [k for k in CASES if any(r["mechanism"] == k for r in rows)]
    fig, axes = plt.subplots(2, len(keys), figsize=(5.5 * len(keys), 8.5), squeeze=False)
    for j, key in enumerate(keys):
        ax, ratio = axes[0, j], axes[1, j]
        mine = [r for r in rows if r["mechanism"] == key]
        for i, (path, label, style) in enumerate(PATHS):
            got = [(r["N"], r[path] * r["N"] * 1e6, r[path] / r["hand"]) for r in mine
                   if path in r]
            if not got:
                continue
            n, per_call, over = zip(*got)
            ax.loglog(n, per_call, style, color=f"C{i}", label=label)
            if path != "hand":
                ratio.semilogx(n, over, style, color=f"C{i}", label=label)
        ax.set_title(f"{key}: positions, velocities, accelerations")
        ax.set_xlabel("positions N")
        ax.set_ylabel("time per call [us]")
        ratio.axhline(1.0, color="grey", lw=0.8)
        ratio.set_xlabel("positions N")
        ratio.set_ylabel("time over hand-written")
        ratio.set_ylim(0, 4)            # (pylinkage's larger ratios run off the top)
        for a in (ax, ratio):
            a.grid(True, which="both", alpha=0.3)
            a.legend(fontsize=7)
    fig.tight_layout()
    path = os.path.join(OUT, "speed.png")
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


if __name__ == "__main__":
    sys.exit(main())
