"""Commands about one file's answers: ``solve``, ``explain``, ``validate``, and the
files that help write one: ``schema`` (for editors), ``init`` (a template)."""
from __future__ import annotations

import os
import sys

import click

from linkcli.cli.console import echo, quiet, style
from linkcli.cli.loading import symbolic_load
from linkcli.cli.options import (DECIMALS_OPTION, FORMATS, K_OPTION, METHODS, OUTPUT_OPTION,
                                 check_tol, digit, symbolic_options)
from linkcli.cli.output import emit, not_an_input
from linkcli.errors import InputError


@click.command()
@click.argument("file")
@K_OPTION
@click.option("--format", "form", type=click.Choice(FORMATS), default="exam", show_default=True)
@DECIMALS_OPTION
@click.option("--lang", type=click.Choice(["en", "it"]), default="en", show_default=True,
              help="Language of the exam format's headings.")
@OUTPUT_OPTION
@click.option("--method", type=click.Choice(METHODS), default="closed",
              show_default=True, help="Closed form of the Assur groups, or Newton-Raphson on "
              "all constraint equations (also solves class-III groups).")
@click.option("--tol", type=float, default=None,
              help="Newton's tolerance, relative to the mechanism's size [default: 1e-12].")
@click.option("--reactions", is_flag=True,
              help="Also print the force in every joint (Newton-Euler, with the masses).")
@symbolic_options
def solve(file, k, form, decimals, lang, output, method, tol, reactions, symbolic, numbers,
          seconds):
    """Solve FILE and print the exam's results table.

    \b
    Examples:
      linkcli solve mechanisms/padova-2020-02.yaml --k 5
      linkcli solve mechanisms/padova-2022-09.yaml --format json
      linkcli solve mechanisms/fourbar-inverse-dynamics.yaml --reactions
    """
    from linkcli.answers.formats import render
    not_an_input(output, file)
    if symbolic and form == "csv":
        raise InputError("--symbolic writes formulas in the exam, table or json format, not "
                         "csv", key="--format", hint="give --format json for machine-readable "
                         "formulas")
    tol = check_tol(tol)
    mech, doc = symbolic_load(file, k, symbolic, numbers, seconds, method=method, tol=tol,
                              clutch=True)
    decimals = mech.report.get("decimals", 1) if decimals is None else decimals
    from linkcli.runs.sheet import evaluate
    result = evaluate(mech, method=method, tol=tol)
    text = render(result, form, decimals, lang)
    if reactions:   # the joint forces at the positions of the same method
        from linkcli.answers.reaction_table import append_report
        text = append_report(text, mech, form, decimals, method=method, tol=tol)
    if doc is not None:
        from linkcli.texts.symbolic import append
        text = append(text, form, doc, k, numbers, lang, seconds)
    emit(text, output)
    for caution in result.cautions:       # after the answers: what the reader should check
        echo(f"linkcli: {caution}", err=True)


@click.command()
@click.argument("file")
@K_OPTION
@click.option("--pseudocode", is_flag=True,
              help="Print the solving order as pseudo-MATLAB calls of the dyad functions.")
@OUTPUT_OPTION
@click.option("--method", type=click.Choice(METHODS), default="closed",
              show_default=True, help="What is explained: the closed form's decomposition, "
              "or the constraint equations Newton-Raphson solves together.")
@symbolic_options
def explain(file, k, pseudocode, output, method, symbolic, numbers, seconds):
    """Print Grübler's count, the Assur decomposition and the solving order.

    \b
    Examples:
      linkcli explain mechanisms/padova-2020-07.yaml
      linkcli explain mechanisms/padova-2020-07.yaml --pseudocode
      linkcli explain mechanisms/triad-class3.yaml --method newton
    """
    if pseudocode and method != "closed":
        raise InputError("--pseudocode writes the closed form's calls of the dyad functions",
                         key="--method", hint="drop --method newton for --pseudocode (a "
                         "class-III group is written as one call solved numerically)")
    not_an_input(output, file)
    mech, doc = symbolic_load(file, k, symbolic, numbers, seconds, designed=pseudocode,
                              clutch="explain")
    if pseudocode:
        from linkcli.texts.pseudocode import pseudocode as text
        out = text(mech)
    else:
        from linkcli.texts.explain import explain as text
        out = text(mech, method)
    if doc is not None:
        from linkcli.texts.symbolic import append
        out = append(out, "exam", doc, k, numbers, seconds=seconds)
    emit(out, output)


@click.command()
@click.argument("files", nargs=-1, required=True)
@click.option("--k", "k", type=int, default=None, callback=digit,
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
    from linkcli.runs.validate import validate_file
    worst = 0
    for path in files:
        outcome = validate_file(path, k)
        for line in outcome.problems:
            echo(line)
        if outcome.exit_code:   # invalid input (2) outranks an unsolvable structure (3)
            worst = 2 if 2 in (worst, outcome.exit_code) else outcome.exit_code
            if not quiet():
                count = len(outcome.problems)
                echo(f" {outcome.file}: {count} problem{'s' if count != 1 else ''}",
                     prefix=style('FAIL', fg='red', bold=True))
        elif not quiet():
            echo(f" {outcome.file} ({outcome.summary})",
                 prefix=style('OK', fg='green', bold=True))
    if worst:
        sys.exit(worst)


@click.command()
@OUTPUT_OPTION
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
    not_an_input(output)
    emit(files("linkcli.input").joinpath("schema.json").read_text(encoding="utf-8").rstrip("\n"),
         output)


@click.command()
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
        echo(text, nl=False)
        return
    if os.path.exists(path) and not force:
        raise InputError("file exists", file=path, hint="use --force to overwrite it, or "
                         "give another name")
    emit(text.rstrip("\n"), path)
    if not quiet():
        echo(f"wrote {path}; next: linkcli validate {path} && linkcli solve {path}")
