"""Speed against accuracy of every solver, against a 50-digit reference (`make bench-full`).

For three mechanisms - the seed-004 four-bar, the seed-000 crank-slider and the
six-bar of mechanisms/padova-2020-07.yaml (written here in SI units) - and
N = 360, 1e5, 1e6 driver positions, it measures the time per position of
positions + velocities + accelerations of every reported quantity and the
largest error against a 50-digit mpmath reference:

- closed form, vectorised (``Mechanism.solve`` on the whole array);
- closed form, scalar (one ``solve`` per position, timed on a sample);
- Newton-Raphson on all constraint equations at tolerances 1e-4 ... 1e-14;
- scipy.optimize.fsolve / root('lm') per position on the same equations,
  rates by central finite differences (timed on a sample);
- closed-form positions with rates by finite differences at several steps;
- a hand-written NumPy closed form of the four-bar, the reference speed;
- peers (pylinkage, pyslvs, python-solvespace) when importable.

The reference is computed with mpmath at 50 digits by hand-written closed forms
(the seeds' own equations), at 200 positions spread over each sweep; its rates
are central differences of the 50-digit positions (step 1e-15, error ~1e-30).
Errors: angles in rad; lengths relative to the largest reference value; rates
relative to the largest reference value of the same quantity over the sweep.

    python benchmarks/speed_accuracy.py [--full] [--quick]

--full also runs every Newton tolerance at N = 1e6; --quick stops at N = 1e5.
Writes benchmarks/out/speed_accuracy.{txt,json,png}.
"""
from __future__ import annotations

import argparse
import importlib
import json
import math
import os
import resource
import sys
import time
import tracemalloc

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

import linkcli  # noqa: E402
from linkcli.kinematics.closed_form import Kinematics  # noqa: E402
from linkcli.kinematics.newton import Constraints  # noqa: E402
from linkcli.answers.quantities import collect  # noqa: E402

OUT = os.path.join(HERE, "out")
SIZES = (360, 10 ** 5, 10 ** 6)
TOLS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14)
FD_STEPS = (1e-2, 1e-4, 1e-6, 1e-8)
REF_POINTS = 200
SCALAR_SAMPLE = 2000
SCIPY_SAMPLE = 1000

FOURBAR = """title: seed-004 four-bar (r = 100, b = 315, c = 500, d = 425 mm, delta = 7/4 pi)
units: {length: m, angle: rad, force: N, torque: Nm}
params: {d: 0.425, delta: 7/4*pi}
frame: {A0: [0, 0], B0: [d*cos(delta), d*sin(delta)]}
points: {A: [0.1, 0], B: [0.345, 0.197]}
links:
  crank: {points: [A0, A], length: 0.1}
  coupler: {points: [A, B], length: 0.315}
  rocker: {points: [B0, B], length: 0.5}
driver: {angle: [A0, A], value: 0, rate: 5*pi, accel: 0}
quantities: {beta: {angle: [A, B]}, gamma: {angle: [B0, B]}}
report:
  position: [beta, gamma]
  velocity: [betadot, gammadot]
  acceleration: [betaddot, gammaddot]
"""

CRANK_SLIDER = """title: seed-000 centred crank-slider (OA = 1 m, AB = sqrt(2) m)
units: {length: m, angle: rad}
frame: {O: [0, 0]}
points: {A: [0.707, 0.707], B: [1.93, 0]}
links:
  OA: {points: [O, A], length: 1}
  AB: {points: [A, B], length: sqrt(2)}
sliders: {B: {point: B, guide: {y: 0}}}
driver: {angle: [O, A], value: pi/4, rate: 0.5, accel: 1}
quantities: {beta: {angle: [A, B]}}
report:
  position: [beta, xB]
  velocity: [betadot, xBdot]
  acceleration: [betaddot, xBddot]
"""

SIXBAR = """title: six-bar of padova-2020-07 (actuator AB, rocker BCD, rod DE, slider E)
units: {length: m, angle: rad}
frame: {A: [0, 0], C: [0.18, 0.04]}
points: {B: [0.11, 0.06], D: [0.14, 0.13], E: [-0.05, 0.18]}
links:
  BCD: {points: [B, C, D], shape: {C: {length: 0.07}, D: {length: 0.07, angle: pi/2}}}
  DE: {points: [D, E], length: 0.19}
actuators: {AB: {points: [A, B]}}
sliders: {E: {point: E, guide: {y: 0.18}}}
driver: {length: [A, B], value: 0.13, rate: -0.06, accel: 0.02}
quantities:
  phi1: {angle: [A, B]}
  phi2: {angle: [B, C]}
  phi3: {angle: [B, D]}
  phi4: {angle: [D, E]}
report:
  position: [phi1, phi2, phi3, phi4, xE]
  velocity: [phi1dot, phi2dot, phi3dot, phi4dot, xEdot]
  acceleration: [phi1ddot, phi2ddot, phi3ddot, phi4ddot, xEddot]
"""


# --- 50-digit references (the seeds' closed forms, written out with mpmath) ---------------
def _mp():
    import mpmath
    mpmath.mp.dps = 50
    return mpmath


def ref_fourbar(mp, q):
    r, b, c = mp.mpf("0.1"), mp.mpf("0.315"), mp.mpf("0.5")
    B0 = mp.mpf("0.425") * mp.expj(mp.mpf(7) / 4 * mp.pi)
    A = r * mp.expj(q)
    w = B0 - A
    L = abs(w)
    along = (b * b - c * c + L * L) / (2 * L)
    zb = (along + 1j * mp.sqrt(b * b - along * along)) * w / L    # beta = 38.8 deg at q = 0
    return {"beta": mp.arg(zb), "gamma": mp.arg(A + zb - B0)}


def ref_crank_slider(mp, q):
    a, b = mp.mpf(1), mp.sqrt(2)
    beta = mp.asin(-a * mp.sin(q) / b)                # seed 000, eq. (4)
    return {"beta": beta, "xB": a * mp.cos(q) + b * mp.cos(beta)}


def ref_sixbar(mp, q):
    A, C = mp.mpc(0, 0), mp.mpc("0.18", "0.04")
    bc, bd, de, ye = mp.mpf("0.07"), mp.mpf("0.07"), mp.mpf("0.19"), mp.mpf("0.18")
    w = C - A
    L = abs(w)
    along = (q * q - bc * bc + L * L) / (2 * L)
    B = A + (along + 1j * mp.sqrt(q * q - along * along)) * w / L   # B above AC, as in the figure
    D = B + bd * 1j * (C - B) / abs(C - B)
    E = mp.mpc(D.real - mp.sqrt(de * de - (ye - D.imag) ** 2), ye)  # E left of D
    return {"phi1": mp.arg(B - A), "phi2": mp.arg(C - B), "phi3": mp.arg(D - B),
            "phi4": mp.arg(E - D), "xE": E.real}


def reference(mp, func, q_values, qd, qdd):
    """Values, first and second time rates at each q (floats), by 50-digit arithmetic."""
    h = mp.mpf("1e-15")
    out = {}
    for q in q_values:
        x = mp.mpf(float(q))
        f0, fp, fm = func(mp, x), func(mp, x + h), func(mp, x - h)
        for name in f0:
            d1 = _wrap(mp, fp[name] - fm[name], name) / (2 * h)
            d2 = (_wrap(mp, fp[name] - f0[name], name) - _wrap(mp, f0[name] - fm[name], name)) \
                / (h * h)
            vals = out.setdefault(name, ([], [], []))
            vals[0].append(float(f0[name]))
            vals[1].append(float(d1 * qd))
            vals[2].append(float(d2 * qd * qd + d1 * qdd))
    return {n: tuple(np.array(v) for v in vals) for n, vals in out.items()}


def _wrap(mp, delta, name):
    if name.startswith(("x", "y")):
        return delta
    return delta - 2 * mp.pi * mp.nint(delta / (2 * mp.pi))


# --- cases ---------------------------------------------------------------------------------
class Case:
    def __init__(self, key, text, ref, lo, hi, q_scale):
        self.key, self.ref, self.lo, self.hi, self.q_scale = key, ref, lo, hi, q_scale
        self.mech = linkcli.loads(text, name=f"{key}.yaml")
        self.names = [n for section in ("position", "velocity", "acceleration")
                      for n in self.mech.report[section]]
        self.base = self.mech.report["position"]
        self.qd, self.qdd = self.mech.driver.rate, self.mech.driver.accel

    def grid(self, n):
        return self.lo + (self.hi - self.lo) * np.arange(n) / n if self.key != "six-bar" \
            else self.lo + (self.hi - self.lo) * np.arange(n) / (n - 1)


def errors(case, ref, values, idx):
    """(position, velocity, acceleration) errors of ``values`` at grid indices ``idx``."""
    worst = [0.0, 0.0, 0.0]
    for name in case.base:
        for order, suffix in enumerate(("", "dot", "ddot")):
            got = np.asarray(values[name + suffix], dtype=float)[idx]
            want = ref[name][order]
            diff = got - want
            if order == 0 and not name.startswith(("x", "y")):
                diff = np.angle(np.exp(1j * diff))
                scale = 1.0
            else:
                scale = max(float(np.max(np.abs(want))), 1e-300)
            worst[order] = max(worst[order], float(np.max(np.abs(diff))) / scale)
    return worst


def best_time(func, repeat):
    best, out = math.inf, None
    for _ in range(repeat):
        start = time.perf_counter()
        out = func()
        best = min(best, time.perf_counter() - start)
    return best, out


# --- methods -------------------------------------------------------------------------------
def hand_fourbar(alpha, ad, add):
    """The four-bar written out by hand in NumPy: angles and their rates."""
    r, b, c = 0.1, 0.315, 0.5
    B0 = 0.425 * np.exp(1j * 7 / 4 * np.pi)
    A = r * np.exp(1j * alpha)
    w = B0 - A
    L2 = w.real * w.real + w.imag * w.imag
    L = np.sqrt(L2)
    along = (b * b - c * c + L2) / (2 * L)
    zb = (along + 1j * np.sqrt(b * b - along * along)) * (w / L)
    zc = zb - w
    beta, gamma = np.angle(zb), np.angle(zc)
    cb = (zc.conjugate() * zb).imag            # Im(conj(zc) zb)
    K = ad * A                                 # ad A + bd zb - gd zc = 0
    bd = -(zc.conjugate() * K).imag / cb
    gd = -(zb.conjugate() * K).imag / cb
    K = (add + 1j * ad * ad) * A + 1j * (bd * bd * zb - gd * gd * zc)
    bdd = -(zc.conjugate() * K).imag / cb
    gdd = -(zb.conjugate() * K).imag / cb
    return {"beta": beta, "gamma": gamma, "betadot": bd, "gammadot": gd,
            "betaddot": bdd, "gammaddot": gdd}


def finite_difference_values(case, q, h):
    """Closed-form positions at q and q +- h; rates by central differences."""
    mech = case.mech
    f0 = mech.solve(q, names=case.base).values
    fp = mech.solve(q + h, names=case.base).values
    fm = mech.solve(q - h, names=case.base).values
    out = {}
    for name in case.base:
        angle = not name.startswith(("x", "y"))
        up = np.angle(np.exp(1j * (fp[name] - f0[name]))) if angle else fp[name] - f0[name]
        dn = np.angle(np.exp(1j * (f0[name] - fm[name]))) if angle else f0[name] - fm[name]
        d1, d2 = (up + dn) / (2 * h), (up - dn) / (h * h)
        out[name] = f0[name]
        out[name + "dot"] = d1 * case.qd
        out[name + "ddot"] = d2 * case.qd ** 2 + d1 * case.qdd
    return out


def scipy_values(case, q, how):
    """Positions per driver value by scipy (warm-started), rates by central differences."""
    from scipy import optimize
    system = Constraints(case.mech.model)
    x = case.mech.solver("newton").x0.copy()               # the file's configuration, to start
    h = 1e-5 * case.q_scale

    def solve_one(qv, start):
        qa = np.array([qv])
        fun = lambda X: system.residual(X[None], qa)[0]          # noqa: E731
        jac = lambda X: system.jacobian(system.points(X[None]), qa)[0]   # noqa: E731
        if how == "fsolve":
            return optimize.fsolve(fun, start, fprime=jac, xtol=1e-13)
        return optimize.root(fun, start, jac=jac, method="lm", options={"xtol": 1e-13}).x

    X0, Xp, Xm = (np.empty((q.size, system.n)) for _ in range(3))
    start = time.perf_counter()
    for i, qv in enumerate(q):
        x = solve_one(qv, x)
        X0[i], Xp[i], Xm[i] = x, solve_one(qv + h, x), solve_one(qv - h, x)
    elapsed = time.perf_counter() - start
    kin = Kinematics(q)
    kin.pos.update(case.mech.fixed)
    for j, name in enumerate(system.moving):
        z0, zp, zm = (X[:, 2 * j] + 1j * X[:, 2 * j + 1] for X in (X0, Xp, Xm))
        kin.pos[name] = z0
        d1, d2 = (zp - zm) / (2 * h), (zp - 2 * z0 + zm) / (h * h)
        kin.vel[name] = d1 * case.qd
        kin.acc[name] = d2 * case.qd ** 2 + d1 * case.qdd
    kin.qd = np.full(q.shape, case.qd)
    kin.qdd = np.full(q.shape, case.qdd)
    return elapsed, collect(case.mech.model, case.mech.solver(), kin, case.names).values


PEERS = ("pylinkage", "pyslvs", "python_solvespace", "mechanism")


# --- the run -------------------------------------------------------------------------------
def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--full", action="store_true", help="every Newton tolerance at 1e6")
    parser.add_argument("--quick", action="store_true", help="stop at N = 1e5")
    parser.add_argument("--memory", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.memory:                  # child process: peak memory of one 1e6 six-bar sweep
        print(json.dumps(_memory(Case("six-bar", SIXBAR, ref_sixbar, 0.12, 0.20, 0.1))))
        return 0
    sizes = SIZES[:2] if args.quick else SIZES
    os.makedirs(OUT, exist_ok=True)
    mp = _mp()
    cases = [Case("four-bar", FOURBAR, ref_fourbar, 0.0, 2 * np.pi, 1.0),
             Case("crank-slider", CRANK_SLIDER, ref_crank_slider, 0.0, 2 * np.pi, 1.0),
             Case("six-bar", SIXBAR, ref_sixbar, 0.12, 0.20, 0.1)]
    import subprocess           # memory first, in a fresh process, while this one is small
    child = subprocess.run([sys.executable, os.path.abspath(__file__), "--memory"],
                           capture_output=True, text=True, check=True)
    memory = json.loads(child.stdout.strip().splitlines()[-1])
    rows = []

    def add(case, method, n, timed, seconds, err):
        rows.append({"mechanism": case.key, "method": method, "N": n, "timed": timed,
                     "us": seconds / timed * 1e6, "pos": err[0], "vel": err[1], "acc": err[2]})
        r = rows[-1]
        print(f"  {case.key:12s} {method:28s} N={n:<8d} {r['us']:10.4f} us  "
              f"pos {r['pos']:.1e}  vel {r['vel']:.1e}  acc {r['acc']:.1e}", flush=True)

    for case in cases:
        mech = case.mech
        mech.solve(names=case.names)                       # build the solvers once
        for n in sizes:
            q = case.grid(n)
            idx = np.unique(np.linspace(0, n - 1, REF_POINTS).round().astype(int))
            ref = reference(mp, case.ref, q[idx], case.qd, case.qdd)
            repeat = 7 if n <= 10 ** 5 else 5
            seconds, res = best_time(lambda: mech.solve(q, names=case.names), repeat)
            add(case, "closed form, vectorised", n, n, seconds, errors(case, ref, res.values, idx))
            if case.key == "four-bar":
                seconds, vals = best_time(lambda: hand_fourbar(q, case.qd, case.qdd), repeat)
                add(case, "hand-written NumPy", n, n, seconds, errors(case, ref, vals, idx))
            for h in FD_STEPS:
                step = h * case.q_scale
                seconds, vals = best_time(lambda: finite_difference_values(case, q, step), 1)
                add(case, f"closed + finite diff. h={h:g}", n, n, seconds,
                    errors(case, ref, vals, idx))
            tols = TOLS if n <= 10 ** 5 or args.full else (1e-12,)
            for tol in tols:
                mech.solve(method="newton", tol=tol)          # nominal solve, outside timing
                seconds, res = best_time(
                    lambda: mech.solve(q, names=case.names, method="newton", tol=tol),
                    1 if n > 10 ** 5 else 2)
                add(case, f"Newton tol={tol:g}", n, n, seconds, errors(case, ref, res.values, idx))
            if n == 360:        # per-position methods: timed on a sample, errors at the reference
                sample = case.grid(SCALAR_SAMPLE)
                start = time.perf_counter()
                for qv in sample:
                    mech.solve(qv, names=case.names)
                seconds = time.perf_counter() - start
                vals = {nm: np.array([float(mech.solve(qv, names=[nm]).values[nm])
                                      for qv in q[idx]]) for nm in case.names}
                add(case, "closed form, scalar loop", n, sample.size, seconds,
                    errors(case, ref, {k: _scatter(v, idx, n) for k, v in vals.items()}, idx))
                for how in ("fsolve", "root-lm"):
                    try:
                        seconds, _ = scipy_values(case, sample[:SCIPY_SAMPLE], how)
                        _, vals = scipy_values(case, q[idx], how)
                    except ImportError:
                        print("  scipy not installed: skipped")
                        break
                    add(case, f"scipy {how} + finite diff.", n, SCIPY_SAMPLE, seconds,
                        errors(case, ref, {k: _scatter(v, idx, n) for k, v in vals.items()},
                               idx))
    peers = []
    for name in PEERS:
        try:
            importlib.import_module(name)
            peers.append(f"{name}: importable, but no adapter in this benchmark")
        except ImportError:
            peers.append(f"{name}: not installed, skipped")
    report = _table(rows, peers, memory, sizes)
    print("\n" + report)
    with open(os.path.join(OUT, "speed_accuracy.txt"), "w", encoding="utf-8") as handle:
        handle.write(report + "\n")
    with open(os.path.join(OUT, "speed_accuracy.json"), "w", encoding="utf-8") as handle:
        json.dump({"rows": rows, "peers": peers, "memory": memory}, handle, indent=1)
    chart = _chart(rows)
    print(f"\nchart: {chart}")
    return 0


def _scatter(values, idx, n):
    out = np.zeros(n)
    out[idx] = values
    return out


def _memory(case):
    """Peak memory of a 1e6-position six-bar solve with all rates, in a fresh process."""
    q = case.grid(10 ** 6)
    case.mech.solve(names=case.names)
    before = _high_water()
    tracemalloc.start()
    case.mech.solve(q, names=case.names)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    case.mech.solve(q, names=case.names)        # untraced, for the resident size
    return {"tracemalloc_peak_MB": peak / 2 ** 20, "process_max_rss_MB": _high_water(),
            "rss_before_MB": before}


def _high_water():
    """Peak resident memory of this process (MB): VmHWM, else getrusage."""
    try:
        with open("/proc/self/status", encoding="ascii") as handle:
            for line in handle:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _table(rows, peers, memory, sizes):
    lines = ["Speed against accuracy (time per position: positions, velocities and "
             "accelerations of every reported quantity)",
             "errors against a 50-digit mpmath reference at 200 positions of each sweep; "
             "angles in rad, others relative to the largest reference value", ""]
    head = f"{'mechanism':12s} {'method':30s} {'N':>8s} {'timed on':>9s} {'us/pos':>10s} " \
           f"{'pos err':>8s} {'vel err':>8s} {'acc err':>8s}"
    lines += [head, "-" * len(head)]
    for r in rows:
        lines.append(f"{r['mechanism']:12s} {r['method']:30s} {r['N']:8d} {r['timed']:9d} "
                     f"{r['us']:10.4f} {r['pos']:8.1e} {r['vel']:8.1e} {r['acc']:8.1e}")
    lines.append("")
    big = max(sizes)

    def pick(mech, method):
        return next((r for r in rows if r["mechanism"] == mech and r["method"] == method
                     and r["N"] == big), None)

    closed4, hand = pick("four-bar", "closed form, vectorised"), pick("four-bar",
                                                                      "hand-written NumPy")
    lines.append(f"targets at N = {big}:")
    if closed4 and hand:
        lines.append(f"  four-bar closed form {closed4['us']:.4f} us/position (target 0.15): "
                     f"{'met' if closed4['us'] <= 0.15 else 'MISSED'}; "
                     f"{closed4['us'] / hand['us']:.2f}x the hand-written NumPy "
                     f"{hand['us']:.4f} us (target 1.5x): "
                     f"{'met' if closed4['us'] <= 1.5 * hand['us'] else 'MISSED'}")
    six = pick("six-bar", "closed form, vectorised")
    if six:
        lines.append(f"  six-bar closed form {six['us']:.4f} us/position (target 0.4): "
                     f"{'met' if six['us'] <= 0.4 else 'MISSED'}")
    closed = [r for r in rows if r["method"] == "closed form, vectorised"]
    pos = max(r["pos"] for r in closed)
    rates = max(max(r["vel"], r["acc"]) for r in closed)
    lines.append(f"  closed form accuracy: positions {pos:.1e} (target 1e-13): "
                 f"{'met' if pos <= 1e-13 else 'MISSED'}; rates {rates:.1e} (target 1e-11): "
                 f"{'met' if rates <= 1e-11 else 'MISSED'}")
    lines.append(f"  memory, 1e6-position six-bar sweep (fresh process): tracemalloc peak "
                 f"{memory['tracemalloc_peak_MB']:.0f} MB, process max RSS "
                 f"{memory['process_max_rss_MB']:.0f} MB, of which "
                 f"{memory['rss_before_MB']:.0f} MB before the sweep (target 1024 MB): "
                 f"{'met' if memory['process_max_rss_MB'] <= 1024 else 'MISSED'}")
    lines.append("peers: " + "; ".join(peers))
    return "\n".join(lines)


def _chart(rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(16, 5.5), sharex=True)
    families = {"closed form, vectorised": ("C0", "closed, vectorised"),
                "closed form, scalar loop": ("C1", "closed, scalar loop"),
                "hand-written NumPy": ("k", "hand-written NumPy"),
                "Newton": ("C2", "Newton (tol 1e-4 ... 1e-14)"),
                "closed + finite diff.": ("C3", "closed + finite differences"),
                "scipy": ("C4", "scipy fsolve / root + FD")}
    markers = {"four-bar": "o", "crank-slider": "s", "six-bar": "^"}
    size = max(r["N"] for r in rows if r["N"] <= 10 ** 5)
    seen = set()
    for r in rows:
        if r["N"] != size and not (r["N"] == 360 and r["timed"] != r["N"]):
            continue
        family = next(f for f in families if r["method"].startswith(f))
        colour, label = families[family]
        for ax, key in zip(axes, ("pos", "vel", "acc")):
            lab = label if (family, key) not in seen and key == "pos" else None
            seen.add((family, key))
            ax.loglog(r["us"], max(r[key], 1e-17), markers[r["mechanism"]], color=colour,
                      label=lab, alpha=0.8)
    for ax, title in zip(axes, ("positions", "velocities", "accelerations")):
        ax.set_title(f"{title}")
        ax.set_xlabel("time per position (us)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("max error (relative; 1e-17 = exact)")
    handles = [plt.Line2D([], [], color="grey", marker=m, linestyle="", label=k)
               for k, m in markers.items()]
    first = axes[0].legend(loc="upper right", fontsize=8)
    axes[0].add_artist(first)
    axes[1].legend(handles=handles, loc="upper right", fontsize=8)
    fig.suptitle(f"linkcli: error against time per position (N = {size}; per-position "
                 "methods timed on samples)")
    fig.tight_layout()
    path = os.path.join(OUT, "speed_accuracy.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


if __name__ == "__main__":
    sys.exit(main())
