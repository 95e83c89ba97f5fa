"""Commands that solve a file many times: ``batch`` (every matricola digit), ``check``
(the answer keys), ``sweep`` (over the driver or a parameter), ``limits`` (extremes
and strokes over the driver's range)."""
from __future__ import annotations

import sys

import click

from linkcli.cli.console import echo, error_prefix, quiet, style
from linkcli.cli.loading import load
from linkcli.cli.options import DECIMALS_OPTION, K_OPTION, METHODS, OUTPUT_OPTION, check_tol
from linkcli.cli.output import Stream, emit, not_an_input
from linkcli.errors import InputError, LinkcliError


@click.command()
@click.argument("file")
@click.option("--k", "ks", default="0-9", show_default=True,
              help="Digits to solve: a range (0-9) or a list (1,3,5).")
@click.option("--format", "form", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True)
@DECIMALS_OPTION
@OUTPUT_OPTION
def batch(file, ks, form, decimals, output):
    """Solve FILE for every matricola digit k: one row per k.

    \b
    Examples:
      linkcli batch mechanisms/padova-2020-02.yaml --k 0-9
      linkcli batch mechanisms/padova-2020-01.yaml --k 1,3,5 --format csv
    """
    from linkcli.runs import batch as batch_mod
    from linkcli.input.source import load_file
    digits = batch_mod.parse_k(ks)
    not_an_input(output, file)
    try:
        doc = load_file(file)
        columns, units, rows, shown, failures = batch_mod.run(doc, digits)
    except LinkcliError as exc:
        raise exc.located(file)
    for k, exc in failures:     # one line per digit that fails; the others' rows follow
        echo(batch_mod.failure_text(k, exc), err=True, prefix=error_prefix())
    decimals = shown if decimals is None else decimals
    text = _batch_text(file, form, decimals, columns, units, rows, failures)
    if rows or form == "json":
        emit(text, output)
    if failures:                # invalid data for a digit (2) outranks unsolvable (3)
        sys.exit(min(exc.exit_code for _, exc in failures))


def _batch_text(file, form, decimals, columns, units, rows, failures) -> str:
    """The rows of ``batch`` (k, then each column in its unit) as JSON, CSV or a table."""
    from linkcli.answers.formats import fmt
    if form == "json":
        import json
        data = [dict(zip(["k"] + columns, row)) for row in rows]
        extra = {"errors": [{"k": k, "error": str(exc)} for k, exc in failures]} \
            if failures else {}
        return json.dumps({"file": file, "units": units, "rows": data, **extra}, indent=2)
    if form == "csv":
        header = ["k"] + [f"{c} [{units[c]}]" for c in columns]
        body = [",".join(str(r[0]) if i == 0 else fmt(v, decimals) for i, v in enumerate(r))
                for r in rows]
        return "\n".join([",".join(header)] + body)
    from tabulate import tabulate
    header = ["k"] + [f"{c}\n[{units[c]}]" for c in columns]
    body = [[r[0]] + [fmt(v, decimals) for v in r[1:]] for r in rows]
    return tabulate(body, headers=header, disable_numparse=True, stralign="right")


@click.command()
@click.argument("paths", nargs=-1)
@click.option("-v", "--verbose", is_flag=True, help="Also list every value that agrees.")
@click.option("--format", "form", type=click.Choice(["text", "json"]), default="text",
              show_default=True, help="json: every compared value, for a course's CI.")
def check(paths, verbose, form):
    """Compare solutions with the answer keys stored in the files.

    PATHS are files or folders (default: mechanisms/).  One line per
    disagreement, a summary per file, and a last line 'N passed, N failed'.
    Exit status 1 when a value disagrees or a file cannot be solved.

    \b
    Examples:
      linkcli check mechanisms/
      linkcli check mechanisms/ --format json > check.json
    """
    from linkcli.runs.check import as_dict, check_file, collect, summary_lines
    files = collect(paths or ["mechanisms"])
    if not files:
        raise InputError("no mechanism files found", key="PATHS",
                         hint="give .yaml files or folders that hold them")
    reports = [check_file(f) for f in files]
    if form == "json":
        import json
        data = as_dict(reports)
        echo(json.dumps(data, indent=2))
        if not data["ok"]:
            sys.exit(1)
        return
    lines, ok = summary_lines(reports, verbose)
    colours = {"FAIL": "red", "ERROR": "red", "KNOWN": "yellow"}
    for line in lines:
        word = line.split(" ", 1)[0]
        if quiet() and word not in ("FAIL", "ERROR") and line is not lines[-1]:
            continue
        prefix = ""
        if word in colours:
            prefix, line = style(word, fg=colours[word], bold=True), line[len(word):]
        echo(line, prefix=prefix)
    if not ok:
        sys.exit(1)


@click.command()
@click.argument("file")
@click.option("--from", "start", type=float, default=None, help="First driver value.")
@click.option("--to", "stop", type=float, default=None, help="Last driver value.")
@click.option("--vary", default=None, metavar="NAME=FROM:TO:STEPS",
              help="Vary a parameter of 'params' instead of the driver: every answer at "
              "STEPS + 1 of its values (as the file writes it).")
@click.option("--steps", type=int, default=None, help="Number of intervals (N + 1 values).")
@click.option("--step", type=float, default=None, help="Interval between driver values.")
@click.option("--format", "form", type=click.Choice(["csv", "json", "table"]), default="csv",
              show_default=True)
@click.option("--every", type=int, default=1, show_default=True, help="Print every M-th row.")
@click.option("--names", default=None, help="Comma-separated quantities [default: the report].")
@click.option("--decimals", type=click.IntRange(0, 15), default=None,
              help="Fixed decimals [default: full precision; 4 in a table].")
@click.option("--method", type=click.Choice(METHODS), default="closed",
              show_default=True)
@click.option("--tol", type=float, default=None, help="Newton's relative tolerance.")
@click.option("--driver", "lead", default=None, metavar="NAME",
              help="With several drivers: the one swept [default: the first].")
@click.option("--tie", "ties", multiple=True, metavar="NAME=EXPR",
              help="With several drivers: driver NAME set to an expression of the swept one "
              "(display units), its rates by the chain rule [default: held at the file's "
              "value and rates]. Repeat for several.")
@K_OPTION
@OUTPUT_OPTION
def sweep(file, start, stop, vary, steps, step, form, every, names, decimals, method, tol,
          lead, ties, k, output):
    """Solve FILE over a range of driver values, one row per value; or, with --vary, over
    a range of one of its parameters.

    Values are FROM + i*STEP in the driver's display unit.  Positions that
    cannot be assembled, rows where velocities are undefined and branch points
    are reported on stderr (and in JSON); the other rows are printed.  With
    --vary every row is the whole answer sheet at one value of the parameter
    (vibration problems too); values without answers are reported the same way.

    \b
    Examples:
      linkcli sweep mechanisms/padova-2021-02-dispari.yaml --from 0 --to 360 --steps 360
      linkcli sweep mechanisms/padova-2020-07.yaml --from 100 --to 160 --step 5 --format table
      linkcli sweep mechanisms/polimi-2001-09-18-vibration.yaml --vary ks=50:150:10
    """
    from linkcli.runs.sweep.blocks import Sweeper
    from linkcli.runs.sweep.driver_range import driver_range
    from linkcli.runs.sweep.output import check_every, write as write_sweep
    not_an_input(output, file)
    chosen = [n.strip() for n in names.split(",") if n.strip()] if names else None
    if vary is not None:
        given = [flag for flag, value in (("--from", start), ("--to", stop), ("--steps", steps),
                                          ("--step", step)) if value is not None]
        if given:
            raise InputError(f"--vary takes the place of {', '.join(given)}", key="--vary",
                             hint="vary either the driver (--from, --to, --steps) or a "
                             "parameter (--vary NAME=FROM:TO:STEPS)")
        from linkcli.runs import vary as vary_mod
        name, values = vary_mod.parse_vary(vary)
        mech = load(file, k, designed=False, clutch=True)   # a design question: at each value
        check_every(every)
        variation = vary_mod.Variation(mech, name, values, chosen, method=method,
                                       tol=check_tol(tol))
        writer = (lambda put: vary_mod.write(variation, form, decimals, put))
    else:
        if start is None or stop is None:
            raise InputError("give --from and --to (the driver's range), or --vary "
                             "NAME=FROM:TO:STEPS (a parameter's)", key="--from")
        from linkcli.answers.quantities.drive import led_by
        mech = led_by(load(file, k, method=method, tol=check_tol(tol), clutch="sweep"), lead)
        q = driver_range(start, stop, steps, step)
        from linkcli.runs.limits.names import sweep_names
        chosen = sweep_names(mech, chosen)      # maxima, strokes ... are not functions of q
        check_every(every)
        sweeper = Sweeper(mech, q, chosen, method=method, tol=check_tol(tol),
                          ties=_ties(ties))
        writer = (lambda put: write_sweep(sweeper, form, every, decimals, put))
    stream = Stream(output)     # rows are printed as each block is solved
    try:
        issues = writer(stream.put)
    finally:
        stream.close()
    for issue in issues:
        echo(issue.text(), err=True, prefix="linkcli: ")


def _ties(texts) -> dict:
    """``--tie NAME=EXPR`` options as {NAME: EXPR}."""
    out = {}
    for text in texts:
        name, sep, expr = text.partition("=")
        if not sep or not name.strip() or not expr.strip():
            raise InputError(f"--tie {text!r}: expected NAME=EXPR", key="--tie",
                             hint="e.g. --tie phi2=180-phi1")
        out[name.strip()] = expr.strip()
    return out


@click.command()
@click.argument("file")
@click.option("--of", "names", multiple=True,
              help="A quantity (repeat the option for several) [default: the report's].")
@click.option("--from", "start", type=float, default=None,
              help="First driver value [default: a full turn of a crank].")
@click.option("--to", "stop", type=float, default=None, help="Last driver value.")
@click.option("--format", "form", type=click.Choice(["table", "json", "csv"]), default="table",
              show_default=True)
@DECIMALS_OPTION
@K_OPTION
@OUTPUT_OPTION
def limits(file, names, start, stop, form, decimals, k, output):
    """Limit positions and extremes of quantities over the driver's range.

    Each quantity's maxima and minima (where its rate is zero, to 1e-10 of the
    driver's unit), its stroke, and over a crank's full turn the time ratio and
    the working and return strokes (driver sweep, time at the driver's rate).

    \b
    Examples:
      linkcli limits mechanisms/khurmi-5-2-quick-return.yaml
      linkcli limits mechanisms/polimi-crank-slider.yaml --of c --of cdot
      linkcli limits mechanisms/khurmi-15-3-max-piston-velocity.yaml --of vP --from 0 --to 180
    """
    from linkcli.runs.limits import names as limit_names, search, table
    not_an_input(output, file)
    mech = load(file, k, clutch="find the limits of")
    decimals = mech.report.get("decimals", 1) if decimals is None else decimals
    found = [search.find(mech, name, start, stop)
             for name in (names or limit_names.default_names(mech))]
    emit(table.render(found, form, decimals), output)
    if form != "json":
        for text in table.messages(found):
            echo(text, err=True, prefix="linkcli: ")
