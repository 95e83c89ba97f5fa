"""Shared by the CLI edge tests: linkcli in-process and in a child process, and the
reproduction four-bar of the edge cases (a figure drawn loosely: it warns)."""
from __future__ import annotations

import contextlib
import io
import sys

from linkcli.cli import main

# linkcli in a child process, on this checkout
CODE = "import sys; from linkcli.cli import main; sys.exit(main(sys.argv[1:]))"

FOURBAR = """title: "Four-bar with coupler point E, horizontal load at E"
units: {length: mm, angle: deg, force: N, torque: Nm}
frame:
  A: [0, 0]
  D: [200, 0]
points:
  B: [30, 52]
  C: [170, 115]
  E: [120, 160]
links:
  AB: {points: [A, B], length: 60}
  BCE:
    points: [B, C, E]
    shape:
      C: {length: 180}
      E: {length: 120, angle: 30}
  CD: {points: [C, D], length: 120}
driver:
  angle: [A, B]
  value: 60
  rate: 10
loads:
  FE: {type: force, at: E, x: 100}
  M: {type: driver, value: unknown}
quantities:
  phi1: {angle: [A, B]}
  phi2: {angle: [B, C]}
  phi3: {angle: [D, C]}
report:
  position: [phi1, phi2, phi3, xE, yE]
  velocity: [phi2dot, phi3dot, xEdot, yEdot]
  statics: [FE, M]
  points: [B, C, E]
"""


def run(args, stdin=""):
    """linkcli in-process: (exit status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    saved, sys.stdin = sys.stdin, io.StringIO(stdin)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main([str(a) for a in args])
    finally:
        sys.stdin = saved
    return code, out.getvalue(), err.getvalue()
