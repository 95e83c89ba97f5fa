"""The command line: parse arguments, call the library, print.

Exit codes: 0 ok, 1 check found disagreeing values, 2 invalid input,
3 mechanism cannot be solved (assembly, singular position, mobility,
structure).  Errors are one line on stderr; ``--traceback`` shows the Python
traceback for bug reports.
"""
from __future__ import annotations

import sys

import click

from . import __version__
from .errors import InputError, LinkcliError

FORMATS = ["exam", "table", "json", "csv"]


def _load(path, k):
    from . import load
    return load(path, k)


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
@click.option("--traceback", is_flag=True, help="Show the Python traceback on errors.")
@click.pass_context
def cli(ctx, traceback):
    """Planar linkage solver: write the mechanism as the exam states it, get the answer sheet.

    \b
    Examples:
      linkcli solve mechanisms/padova-2020-07.yaml
      linkcli batch mechanisms/padova-2020-02.yaml --k 0-9
      linkcli check mechanisms/
      linkcli explain mechanisms/padova-2023-01.yaml
    """
    ctx.ensure_object(dict)["traceback"] = traceback


@cli.command()
@click.argument("file")
@click.option("--k", "k", type=int, default=None, help="Last digit of the matricola (0-9).")
@click.option("--format", "form", type=click.Choice(FORMATS), default="exam", show_default=True)
@click.option("--decimals", type=click.IntRange(0, 12), default=None,
              help="Decimals shown (default: the file's report.decimals, else 1).")
@click.option("--lang", type=click.Choice(["en", "it"]), default="en", show_default=True,
              help="Language of the exam format's headings.")
@click.option("-o", "--output", default=None, help="Write to this file instead of stdout.")
def solve(file, k, form, decimals, lang, output):
    """Solve FILE and print the exam's results table.

    \b
    Examples:
      linkcli solve mechanisms/padova-2020-02.yaml --k 5
      linkcli solve mechanisms/padova-2022-09.yaml --format json
    """
    from .report import render
    mech = _load(file, k)
    decimals = mech.report.get("decimals", 1) if decimals is None else decimals
    _emit(render(mech.solve(), form, decimals, lang), output)


@cli.command()
@click.argument("file")
@click.option("--k", "k", type=int, default=None, help="Last digit of the matricola (0-9).")
def explain(file, k):
    """Print Grübler's count, the Assur decomposition and the solving order.

    \b
    Example:
      linkcli explain mechanisms/padova-2020-07.yaml
    """
    from .explain import explain as text
    click.echo(text(_load(file, k)))


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
    from . import batch as batch_mod
    from .yamlsource import load_file
    from .report import fmt
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
    from .check import check_file, collect, summary_lines
    files = collect(paths or ["mechanisms"])
    if not files:
        raise InputError("no mechanism files found", key="PATHS",
                         hint="give .yaml files or folders that hold them")
    lines, ok = summary_lines([check_file(f) for f in files], verbose)
    click.echo("\n".join(lines))
    if not ok:
        sys.exit(1)


def main(args=None, prog_name="linkcli") -> int:
    """Run the CLI; return the exit status instead of raising."""
    args = list(sys.argv[1:] if args is None else args)
    show_traceback = "--traceback" in args
    try:
        cli.main(args=args, prog_name=prog_name, standalone_mode=False)
    except LinkcliError as exc:
        if show_traceback:
            raise
        click.echo(f"linkcli: error: {exc}", err=True)
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
