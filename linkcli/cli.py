"""The command line: parse arguments, call the library, print.

Exit codes: 0 ok, 1 check found disagreeing values, 2 invalid input,
3 mechanism cannot be solved (assembly, singular position, mobility,
structure).  Errors are one line on stderr; ``--traceback`` shows the Python
traceback for bug reports.  Colour is used only on a terminal (and never
when ``NO_COLOR`` is set); ``--quiet`` keeps only results and problems.
"""
from __future__ import annotations

import os
import sys
import warnings

import click

from linkcli import __version__
from linkcli.errors import InputError, LinkcliError

FORMATS = ["exam", "table", "json", "csv"]
K_OPTION = click.option("--k", "k", type=int, default=None,
                        help="Last digit of the matricola (0-9).")


def _load(path, k):
    """The validated model of ``path`` for digit ``k``."""
    from linkcli.api import load
    return load(path, k).model


def _style(text: str, **style) -> str:
    """``text`` in colour; click.echo drops the colour when not on a terminal."""
    return text if os.environ.get("NO_COLOR") else click.style(text, **style)


def _quiet() -> bool:
    ctx = click.get_current_context(silent=True)
    return bool(ctx and ctx.find_root().obj and ctx.find_root().obj.get("quiet"))


def _emit(text: str, output):
    if output is None:
        click.echo(text)
        return
    try:
        with open(output, "w", encoding="utf-8") as handle:
            handle.write(text + "\n")
    except OSError as exc:
        raise InputError(f"cannot write output file: {exc.strerror}", file=output,
                         hint="check the folder exists and is writable") from None


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="linkcli")
@click.option("-q", "--quiet", is_flag=True,
              help="Print only results and problems (no OK lines, no summaries).")
@click.option("--traceback", is_flag=True, help="Show the Python traceback on errors.")
@click.pass_context
def cli(ctx, quiet, traceback):
    """Planar linkage solver: write the mechanism as the exam states it, get the answer sheet.

    FILE arguments may be '-' to read standard input.

    \b
    Examples:
      linkcli init my-exam.yaml
      linkcli validate my-exam.yaml
      linkcli solve mechanisms/padova-2020-07.yaml
      linkcli solve mechanisms/padova-2020-07.yaml --lang it -o answers.txt
      linkcli batch mechanisms/padova-2020-02.yaml --k 0-9
      linkcli check mechanisms/
      linkcli explain mechanisms/padova-2023-01.yaml

    \b
    Exit status:
      0  success
      1  linkcli check found values that disagree with the answer key
      2  invalid input: YAML, keys, names, expressions, options
      3  the mechanism cannot be solved: mobility, structure, assembly,
         singular position
    """
    obj = ctx.ensure_object(dict)
    obj["traceback"] = traceback
    obj["quiet"] = quiet


@cli.command()
@click.argument("file")
@K_OPTION
@click.option("--format", "form", type=click.Choice(FORMATS), default="exam", show_default=True)
@click.option("--decimals", type=click.IntRange(0, 12), default=None,
              help="Decimals shown (default: the file's report.decimals, else 1).")
@click.option("--lang", type=click.Choice(["en", "it"]), default="en", show_default=True,
              help="Language of the exam format's headings.")
@click.option("-o", "--output", default=None, help="Write to this file instead of stdout.")
@click.option("--method", type=click.Choice(["closed", "newton"]), default="closed",
              show_default=True, help="Closed form of the Assur groups, or Newton-Raphson on "
              "all constraint equations (also solves class-III groups).")
@click.option("--tol", type=float, default=None,
              help="Newton's tolerance, relative to the mechanism's size [default: 1e-12].")
@click.option("--reactions", is_flag=True,
              help="Also print the force in every joint (Newton-Euler, with the masses).")
def solve(file, k, form, decimals, lang, output, method, tol, reactions):
    """Solve FILE and print the exam's results table.

    \b
    Examples:
      linkcli solve mechanisms/padova-2020-02.yaml --k 5
      linkcli solve mechanisms/padova-2022-09.yaml --format json
      linkcli solve mechanisms/fourbar-inverse-dynamics.yaml --reactions
    """
    from linkcli.answers.formats import render
    mech = _load(file, k)
    decimals = mech.report.get("decimals", 1) if decimals is None else decimals
    from linkcli.answers.sheet import evaluate
    text = render(evaluate(mech, method=method, tol=_tol(tol)), form, decimals, lang)
    if reactions:
        from linkcli.answers.reaction_table import append_report
        text = append_report(text, mech, form, decimals)
    _emit(text, output)


@cli.command()
@click.argument("file")
@K_OPTION
@click.option("-o", "--output", default=None, help="Write to this file instead of stdout.")
def explain(file, k, output):
    """Print Grübler's count, the Assur decomposition and the solving order.

    \b
    Example:
      linkcli explain mechanisms/padova-2020-07.yaml
    """
    from linkcli.answers.explain import explain as text
    _emit(text(_load(file, k)), output)


@cli.command()
@click.argument("file")
@click.option("--k", "ks", default="0-9", show_default=True,
              help="Digits to solve: a range (0-9) or a list (1,3,5).")
@click.option("--format", "form", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True)
@click.option("--decimals", type=click.IntRange(0, 12), default=None,
              help="Decimals shown (default: the file's report.decimals, else 1).")
@click.option("-o", "--output", default=None, help="Write to this file instead of stdout.")
def batch(file, ks, form, decimals, output):
    """Solve FILE for every matricola digit k: one row per k.

    \b
    Examples:
      linkcli batch mechanisms/padova-2020-02.yaml --k 0-9
      linkcli batch mechanisms/padova-2020-01.yaml --k 1,3,5 --format csv
    """
    from linkcli.answers import batch as batch_mod
    from linkcli.input.source import load_file
    from linkcli.answers.formats import fmt
    digits = batch_mod.parse_k(ks)
    try:
        doc = load_file(file)
        columns, units, rows, shown = batch_mod.run(doc, digits)
    except LinkcliError as exc:
        raise exc.located(file)
    decimals = shown if decimals is None else decimals
    if form == "json":
        import json
        data = [dict(zip(["k"] + columns, row)) for row in rows]
        text = json.dumps({"file": file, "units": units, "rows": data}, indent=2)
    elif form == "csv":
        header = ["k"] + [f"{c} [{units[c]}]" for c in columns]
        body = [",".join(str(r[0]) if i == 0 else fmt(v, decimals) for i, v in enumerate(r))
                for r in rows]
        text = "\n".join([",".join(header)] + body)
    else:
        from tabulate import tabulate
        header = ["k"] + [f"{c}\n[{units[c]}]" for c in columns]
        body = [[r[0]] + [fmt(v, decimals) for v in r[1:]] for r in rows]
        text = tabulate(body, headers=header, disable_numparse=True, stralign="right")
    _emit(text, output)


@cli.command()
@click.argument("paths", nargs=-1)
@click.option("-v", "--verbose", is_flag=True, help="Also list every value that agrees.")
def check(paths, verbose):
    """Compare solutions with the answer keys stored in the files.

    PATHS are files or folders (default: mechanisms/).  One line per
    disagreement, a summary per file, and a last line 'N passed, N failed'.
    Exit status 1 when a value disagrees or a file cannot be solved.

    \b
    Example:
      linkcli check mechanisms/
    """
    from linkcli.answers.check import check_file, collect, summary_lines
    files = collect(paths or ["mechanisms"])
    if not files:
        raise InputError("no mechanism files found", key="PATHS",
                         hint="give .yaml files or folders that hold them")
    lines, ok = summary_lines([check_file(f) for f in files], verbose)
    colours = {"FAIL": "red", "ERROR": "red", "KNOWN": "yellow"}
    for line in lines:
        word = line.split(" ", 1)[0]
        if _quiet() and word not in ("FAIL", "ERROR") and line is not lines[-1]:
            continue
        if word in colours:
            line = _style(word, fg=colours[word], bold=True) + line[len(word):]
        click.echo(line)
    if not ok:
        sys.exit(1)


@cli.command()
@click.argument("file")
@click.option("--sweep", default=None, metavar="FROM:TO:STEPS",
              help="Driver values FROM to TO (the file's units) in STEPS intervals.")
@click.option("--frf", default=None, metavar="FROM:TO:STEPS",
              help="Vibrations: amplitude and phase against the forcing frequency Omega.")
@click.option("--modes", is_flag=True, help="Vibrations: the mode shapes on the mechanism.")
@click.option("--free", default=None, metavar="0:T:STEPS",
              help="Vibrations: free response from 'initial', linear and nonlinear (s).")
@click.option("--y", "names", multiple=True, metavar="NAME",
              help="A quantity of the report (repeat for more panels), e.g. --y c --y cdot; "
                   "with --frf or --free, coordinates (default: every free one).")
@K_OPTION
@click.option("-o", "--output", required=True, help="Picture to write (.png, .svg or .pdf).")
def plot(file, sweep, frf, modes, free, names, k, output):
    """Plot quantities of FILE against the driver, or a vibration problem's response.

    \b
    Examples:
      linkcli plot mechanisms/polimi-crank-slider.yaml --sweep 0:360:360 --y c --y beta -o pos.png
      linkcli plot mechanisms/fourbar-inverse-dynamics.yaml --sweep 0:360:360 --y Mm -o mm.png
      linkcli plot mechanisms/polimi-2001-09-18-vibration.yaml --modes -o modes.png
    """
    chosen = [flag for flag, value in (("--sweep", sweep), ("--frf", frf), ("--modes", modes),
                                       ("--free", free)) if value]
    if len(chosen) != 1:
        raise InputError("give one of --sweep, --frf, --modes, --free", key="plot",
                         hint="--sweep FROM:TO:STEPS --y NAME for a mechanism with a driver")
    mech = _load(file, k)
    if sweep:
        from linkcli.pictures.plotting import plot as make
        make(mech, sweep, list(names), output)
        return
    from linkcli.pictures import vibration as pictures
    if frf:
        pictures.frf(mech, frf, list(names), output)
    elif free:
        pictures.free(mech, free, list(names), output)
    else:
        pictures.modes(mech, output)


@cli.command()
@click.argument("file")
@K_OPTION
@click.option("-o", "--output", required=True, help="Picture to write (.png, .svg or .pdf).")
def draw(file, k, output):
    """Draw FILE at its driver value: links, sliders, pivots, the vector polygon z_i, loads.

    \b
    Example:
      linkcli draw mechanisms/padova-2020-07.yaml -o mechanism.png
    """
    from linkcli.pictures.plotting import draw as make
    make(_load(file, k), output)


@cli.command()
@click.argument("file")
@click.option("--sweep", default=None, metavar="FROM:TO:STEPS",
              help="Driver values (the file's units); default a full turn in 72 frames.")
@click.option("--fps", type=click.IntRange(1, 60), default=12, show_default=True)
@K_OPTION
@click.option("-o", "--output", required=True, help="Animated GIF to write.")
def animate(file, sweep, fps, k, output):
    """Animate the motion of FILE over a sweep of the driver (GIF).

    \b
    Examples:
      linkcli animate mechanisms/polimi-crank-slider.yaml -o motion.gif
      linkcli animate mechanisms/padova-2020-07.yaml --sweep 120:140:20 -o lift.gif
    """
    from linkcli.pictures.plotting import animate as make
    make(_load(file, k), output, sweep, fps)


@cli.command()
@click.argument("files", nargs=-1, required=True)
@click.option("--k", "k", type=int, default=None,
              help="Check this digit only (default: the file's k and every other digit).")
def validate(files, k):
    """Check FILES without solving: every problem at once, with its key and line.

    Reads each file, checks every key, name and expression (for every digit k
    when the file sets one; masses and friction too) and the structure
    (Grübler's count, Assur groups).
    Prints one line per problem and 'OK FILE' for each valid file.  Exit
    status 2 when a file has invalid input, 3 when its structure cannot be
    solved.

    \b
    Examples:
      linkcli validate mechanisms/padova-2020-07.yaml
      linkcli validate mechanisms/*.yaml
      linkcli validate - < my-exam.yaml
    """
    from linkcli.answers.validate import validate_file
    worst = 0
    for path in files:
        outcome = validate_file(path, k)
        for line in outcome.problems:
            click.echo(line)
        if outcome.exit_code:   # invalid input (2) outranks an unsolvable structure (3)
            worst = 2 if 2 in (worst, outcome.exit_code) else outcome.exit_code
            if not _quiet():
                count = len(outcome.problems)
                click.echo(f"{_style('FAIL', fg='red', bold=True)} {outcome.file}: {count} "
                           f"problem{'s' if count != 1 else ''}")
        elif not _quiet():
            click.echo(f"{_style('OK', fg='green', bold=True)} {outcome.file} "
                       f"({outcome.summary})")
    if worst:
        sys.exit(worst)


@cli.command()
@click.option("-o", "--output", default=None, help="Write to this file instead of stdout.")
def schema(output):
    """Print the JSON Schema of mechanism files, for editors.

    Save it next to your files and point the editor's YAML extension at it for
    completion and live errors (see docs/cli.md).  Rules that need the whole
    file (undefined names, exactly one unknown load, mobility) are checked by
    'linkcli validate'.

    \b
    Examples:
      linkcli schema -o linkcli.schema.json
      linkcli schema
    """
    from importlib.resources import files
    _emit(files("linkcli.input").joinpath("schema.json").read_text(encoding="utf-8").rstrip("\n"),
          output)


@cli.command()
@click.argument("path", default="mechanism.yaml")
@click.option("--force", is_flag=True, help="Overwrite PATH if it exists.")
def init(path, force):
    """Write a commented template mechanism to PATH (default mechanism.yaml).

    The template is a crank-slider that validates and solves; edit it into
    your exam.  PATH '-' prints it.

    \b
    Examples:
      linkcli init my-exam.yaml
      linkcli init - | less
    """
    from importlib.resources import files
    text = files("linkcli.input").joinpath("templates", "mechanism.yaml").read_text(encoding="utf-8")
    if path == "-":
        click.echo(text, nl=False)
        return
    if os.path.exists(path) and not force:
        raise InputError("file exists", file=path, hint="use --force to overwrite it, or "
                         "give another name")
    _emit(text.rstrip("\n"), path)
    if not _quiet():
        click.echo(f"wrote {path}; next: linkcli validate {path} && linkcli solve {path}")


def _tol(tol):
    if tol is not None and not (0 < tol < 1):
        raise InputError(f"--tol must be between 0 and 1, got {tol}", key="--tol",
                         hint="a tolerance relative to the mechanism's size, e.g. 1e-12")
    return tol


@cli.command()
@click.argument("file")
@click.option("--from", "start", type=float, required=True, help="First driver value.")
@click.option("--to", "stop", type=float, required=True, help="Last driver value.")
@click.option("--steps", type=int, default=None, help="Number of intervals (N + 1 values).")
@click.option("--step", type=float, default=None, help="Interval between driver values.")
@click.option("--format", "form", type=click.Choice(["csv", "json", "table"]), default="csv",
              show_default=True)
@click.option("--every", type=int, default=1, show_default=True, help="Print every M-th row.")
@click.option("--names", default=None, help="Comma-separated quantities [default: the report].")
@click.option("--decimals", type=click.IntRange(0, 15), default=None,
              help="Fixed decimals [default: full precision; 4 in a table].")
@click.option("--method", type=click.Choice(["closed", "newton"]), default="closed",
              show_default=True)
@click.option("--tol", type=float, default=None, help="Newton's relative tolerance.")
@K_OPTION
@click.option("-o", "--output", default=None, help="Write to this file instead of stdout.")
def sweep(file, start, stop, steps, step, form, every, names, decimals, method, tol, k, output):
    """Solve FILE over a range of driver values, one row per value.

    Values are FROM + i*STEP in the driver's display unit.  Positions that
    cannot be assembled, rows where velocities are undefined and branch points
    are reported on stderr (and in JSON); the other rows are printed.

    \b
    Examples:
      linkcli sweep mechanisms/padova-2021-02-dispari.yaml --from 0 --to 360 --steps 360
      linkcli sweep mechanisms/padova-2020-07.yaml --from 100 --to 160 --step 5 --format table
    """
    from linkcli.answers import sweep as sweep_mod
    mech = _load(file, k)
    q = sweep_mod.driver_values(start, stop, steps, step)
    chosen = [n.strip() for n in names.split(",") if n.strip()] if names else None
    result = sweep_mod.sweep(mech, q, chosen, method=method, tol=_tol(tol))
    for issue in result.issues:
        click.echo(f"linkcli: {issue.text()}", err=True)
    _emit(sweep_mod.render(result, form, every, decimals), output)


GLOBAL_FLAGS = ("--quiet", "--traceback")


def _global_options_first(args: list) -> list:
    """Accept --quiet and --traceback after the command too (before a '--')."""
    end = args.index("--") if "--" in args else len(args)
    flags = [a for a in args[:end] if a in GLOBAL_FLAGS]
    return flags + [a for a in args[:end] if a not in GLOBAL_FLAGS] + args[end:]


def main(args=None, prog_name="linkcli") -> int:
    """Run the CLI; return the exit status instead of raising."""
    args = _global_options_first(list(sys.argv[1:] if args is None else args))
    show_traceback = "--traceback" in args
    try:
        with warnings.catch_warnings():
            # NumPy's floating-point warnings: results are checked to be finite instead
            warnings.filterwarnings("ignore", r"(invalid value|overflow|divide by zero)",
                                    RuntimeWarning)
            cli.main(args=args, prog_name=prog_name, standalone_mode=False)
    except LinkcliError as exc:
        if show_traceback:
            raise
        click.echo(f"linkcli: {_style('error:', fg='red', bold=True)} {exc}", err=True)
        return exc.exit_code
    except click.exceptions.Abort:
        click.echo("linkcli: aborted", err=True)
        return 1
    except click.ClickException as exc:
        exc.show()
        return 2
    except SystemExit as exc:
        return exc.code if isinstance(exc.code, int) else 0
    except KeyboardInterrupt:
        return 130
    except Exception:  # a bug: say so briefly, traceback on request
        if show_traceback:
            raise
        click.echo("linkcli: internal error (please report it; rerun with --traceback for "
                   "details)", err=True)
        return 70
    return 0


def entry():  # pragma: no cover - console script
    sys.exit(main())
