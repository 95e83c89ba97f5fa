"""Options shared by several commands, and the checks of their values.

Each is refused here, blamed on the option, before the file is read: ``--k`` a
digit, ``--tol`` a relative tolerance, ``--numbers`` and ``--seconds`` only with
``--symbolic``.
"""
from __future__ import annotations

import click

from linkcli.errors import InputError

FORMATS = ["exam", "table", "json", "csv"]
METHODS = ["closed", "newton"]


def digit(ctx, param, value):
    """--k: a digit, refused here (blamed on the option) before the file is read."""
    if value is not None and not 0 <= value <= 9:
        raise InputError(f"k must be a digit 0-9, got {value}", key="--k",
                         hint="k is the last digit of the matricola")
    return value


K_OPTION = click.option("--k", "k", type=int, default=None, callback=digit,
                        help="Last digit of the matricola (0-9).")
OUTPUT_OPTION = click.option("-o", "--output", default=None,
                             help="Write to this file instead of stdout.")
PICTURE_OPTION = click.option("-o", "--output", required=True,
                              help="Picture to write (.png, .svg or .pdf).")
DECIMALS_OPTION = click.option("--decimals", type=click.IntRange(0, 12), default=None,
                               help="Decimals shown (default: the file's report.decimals, "
                               "else 1).")
SYMBOLIC_OPTION = click.option(
    "--symbolic", is_flag=True, help="Also write the formulas: a vibration problem's T, V, D, "
    "equations, equilibrium, stability, M, K, R, F and characteristic equation in its "
    "parameters; a linkage's closure equations and rate systems.")
NUMBERS_OPTION = click.option("--numbers", default=None, metavar="NAMES",
                              help="With --symbolic: the parameters (and g) given their "
                              "numbers, e.g. --numbers M,L.")
SECONDS_OPTION = click.option("--seconds", type=float, default=None, metavar="S",
                              help="With --symbolic: the processor time the formulas may "
                              "take (default 10); those not reached are named.")


def symbolic_options(f):
    """--symbolic, --numbers and --seconds, in that order."""
    return SYMBOLIC_OPTION(NUMBERS_OPTION(SECONDS_OPTION(f)))


def check_symbolic(symbolic, numbers, seconds):
    """--numbers and --seconds go with --symbolic; --seconds is a time, not negative."""
    if numbers is not None and not symbolic:
        raise InputError("--numbers goes with --symbolic", key="--numbers",
                         hint="add --symbolic, or drop --numbers")
    if seconds is not None and not symbolic:
        raise InputError("--seconds goes with --symbolic", key="--seconds",
                         hint="add --symbolic, or drop --seconds")
    if seconds is not None and not seconds >= 0:
        raise InputError(f"--seconds must be a time of at least 0 s, got {seconds:g}",
                         key="--seconds", hint="e.g. --seconds 30")


def check_tol(tol):
    """--tol: Newton's tolerance relative to the mechanism's size, strictly between 0 and 1."""
    if tol is not None and not (0 < tol < 1):
        raise InputError(f"--tol must be between 0 and 1, got {tol}", key="--tol",
                         hint="a tolerance relative to the mechanism's size, e.g. 1e-12")
    return tol
