"""Peak memory of `linkcli sweep` against the number of positions (`make bench`: to 10^6;
`make bench-full`: to 10^7).

For a four-bar (mechanisms/fourbar-inverse-dynamics.yaml) and a six-bar
(mechanisms/padova-2020-01.yaml), each over a full turn, it runs

    linkcli sweep FILE --from 0 --to 360 --steps N-1 --format F > /dev/null

in a fresh process for N = 10^4, 10^5, 10^6, 10^7 and F = csv, json, and reads
that process's peak resident memory (ru_maxrss, from wait4) and wall time.
Sweeps are solved and written in blocks, so the peak should not grow with N.

    python benchmarks/memory.py [--quick]

--quick stops at N = 10^6.  Writes benchmarks/out/memory.txt (the table, also
printed) and benchmarks/out/memory.png (peak memory against N).  The 10^7 runs
take a few minutes each.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
OUT = os.path.join(HERE, "out")
CASES = [("four-bar", "fourbar-inverse-dynamics.yaml"), ("six-bar", "padova-2020-01.yaml")]
FORMATS = ("csv", "json")
SIZES = (10 ** 4, 10 ** 5, 10 ** 6, 10 ** 7)
LIMIT_MB = 500          # the peak any sweep may take
CODE = "import sys; from linkcli.cli import main; sys.exit(main(sys.argv[1:]))"


def peak(path, positions, form):
    """(peak RSS in MB, seconds, exit status) of one sweep in a child process."""
    args = [sys.executable, "-c", CODE, "sweep", path, "--from", "0", "--to", "360",
            "--steps", str(positions - 1), "--format", form]
    env = dict(os.environ, PYTHONPATH=ROOT + os.pathsep + os.environ.get("PYTHONPATH", ""))
    start = time.perf_counter()
    with open(os.devnull, "w") as sink:
        proc = subprocess.Popen(args, stdout=sink, stderr=subprocess.DEVNULL, env=env)
        _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    kb = usage.ru_maxrss if sys.platform != "darwin" else usage.ru_maxrss / 1024
    return kb / 1024, time.perf_counter() - start, proc.returncode


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="stop at 10^6 positions")
    args = parser.parse_args()
    sizes = [n for n in SIZES if not args.quick or n <= 10 ** 6]
    os.makedirs(OUT, exist_ok=True)
    rows = []
    header = f"{'mechanism':10} {'format':6} {'positions':>10} {'peak MB':>9} {'seconds':>8} exit"
    print(header, flush=True)
    for label, name in CASES:
        path = os.path.join(ROOT, "mechanisms", name)
        for form in FORMATS:
            for n in sizes:
                mb, seconds, code = peak(path, n, form)
                rows.append((label, form, n, mb, seconds, code))
                print(f"{label:10} {form:6} {n:>10} {mb:>9.1f} {seconds:>8.1f} {code}", flush=True)
    worst = max(r[3] for r in rows)
    lines = [header] + [f"{a:10} {b:6} {n:>10} {mb:>9.1f} {s:>8.1f} {c}"
                        for a, b, n, mb, s, c in rows]
    lines.append(f"largest peak {worst:.1f} MB (limit {LIMIT_MB} MB); "
                 f"{sum(r[5] != 0 for r in rows)} runs failed")
    print(lines[-1])
    with open(os.path.join(OUT, "memory.txt"), "w", encoding="utf-8") as handle:
        handle.write("\n".join(lines) + "\n")
    _chart(rows, os.path.join(OUT, "memory.png"))
    return 0 if worst < LIMIT_MB and all(r[5] == 0 for r in rows) else 1


def _chart(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=100)
    for label, _ in CASES:
        for form, style in zip(FORMATS, ("-o", "--s")):
            points = [(n, mb) for a, b, n, mb, _, _ in rows if a == label and b == form]
            if points:
                ax.plot(*zip(*points), style, label=f"{label}, {form}")
    ax.axhline(LIMIT_MB, color="grey", lw=1, ls=":", label=f"limit {LIMIT_MB} MB")
    ax.set_xscale("log")
    ax.set_ylim(bottom=0)
    ax.set_xlabel("positions in the sweep")
    ax.set_ylabel("peak resident memory [MB]")
    ax.set_title("linkcli sweep: peak memory (one process per run)")
    ax.grid(True, alpha=0.35)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path)


if __name__ == "__main__":
    sys.exit(main())
