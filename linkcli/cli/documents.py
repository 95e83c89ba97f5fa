"""The command that writes a document for a course: ``export`` (a Moodle question bank
with every digit's variant, or a worked solution in HTML or Markdown)."""
from __future__ import annotations

import os

import click

from linkcli.cli.console import echo
from linkcli.cli.options import METHODS, check_symbolic, symbolic_options
from linkcli.cli.output import emit, not_an_input
from linkcli.errors import InputError


@click.command()
@click.argument("file")
@click.option("--to", "target", type=click.Choice(["moodle", "html", "markdown", "exam",
                                                  "booklet"]),
              required=True, help="moodle: a Moodle XML question bank; html or markdown: a "
              "worked solution; exam: the paper exam of each digit (statement, data, "
              "figure, answers to write); booklet: each digit's worked solution and key, "
              "both HTML pages to print.")
@click.option("--k", "k_text", default=None, metavar="K",
              help="Digits: 0-9, 1,3,5 or one digit (default: the file's own).")
@click.option("--lang", type=click.Choice(["it", "en"]), default="it", show_default=True)
@click.option("--decimals", type=click.IntRange(0, 12), default=None,
              help="Decimals of the answers (default: the file's report.decimals).")
@click.option("--tolerance", type=float, default=None,
              help="Moodle: absolute tolerance of every answer (default: the file's "
              "quiz.tolerance, or half a unit of the last decimal), widened where the "
              "file's key prints a value with fewer decimals or a tolerance.")
@click.option("--no-figure", is_flag=True, help="Leave the figure out.")
@click.option("--no-given", is_flag=True, help="Moodle: leave out the boxes whose value "
              "the question gives as data (the driver's value and rates, a known load).")
@click.option("--method", type=click.Choice(METHODS), default="closed",
              show_default=True, help="Moodle: how positions are solved (newton for a "
              "class-III group).")
@click.option("-o", "--output", required=True, help="File to write.")
@click.option("--force", is_flag=True, help="Replace the output file if it exists.")
@symbolic_options
def export(file, target, k_text, lang, decimals, tolerance, no_figure, no_given, method,
           output, force, symbolic, numbers, seconds):
    """Export FILE for a course: a Moodle quiz with every digit's variant, or a worked
    solution to hand out.

    \b
    Examples:
      linkcli export mechanisms/padova-2020-02.yaml --to moodle --k 0-9 -o quiz.xml
      linkcli export mechanisms/padova-2020-02.yaml --to moodle --no-given -o quiz.xml
      linkcli export mechanisms/padova-2020-07.yaml --to html --lang it -o solution.html
      linkcli export mechanisms/padova-2020-02.yaml --to exam --k 0-9 -o exam.html
      linkcli export mechanisms/padova-2020-02.yaml --to booklet --k 0-9 -o booklet.html
    """
    from linkcli.runs.batch import parse_k
    from linkcli.input.source import load_file
    not_an_input(output, file)             # --force replaces an output, never the input
    if os.path.exists(output) and not force:
        raise InputError("the output file exists", file=output, key="-o",
                         hint="give --force to replace it, or another name")
    doc = load_file(file)
    from linkcli.input.clutch import is_clutch
    if is_clutch(doc.data):
        from linkcli.cli.loading import refuse_clutch
        refuse_clutch(file, "export as a quiz or a worked solution")
    ks = parse_k(k_text) if k_text is not None else None
    if (symbolic or numbers is not None) and target not in ("html", "markdown"):
        raise InputError("--symbolic goes with a worked solution (--to html or markdown)",
                         key="--symbolic", hint=f"drop --symbolic for --to {target}")
    check_symbolic(symbolic, numbers, seconds)
    if no_given and target not in ("moodle", "exam"):
        raise InputError("--no-given goes with a Moodle quiz or a paper exam (--to moodle "
                         "or exam): a worked solution asks no boxes", key="--no-given",
                         hint="drop --no-given for a worked solution")
    if target == "moodle":
        from linkcli.exports.moodle import export as make, repeated
        text = make(doc, ks, decimals=decimals, tolerance=tolerance, lang=lang,
                    figure=not no_figure, method=method, no_given=no_given)
        emit(text.rstrip("\n"), output)
        echo(_repeated_line(file, *repeated(doc), no_given), err=True)
        return
    if target in ("exam", "booklet"):
        from linkcli.exports import booklet
        text = booklet.exam(doc, ks, lang, not no_figure, method, no_given) \
            if target == "exam" else booklet.booklet(doc, ks, lang, not no_figure, method)
        emit(text.rstrip("\n"), output)
        return
    text = _worked(doc, ks, target, lang, no_figure, method, symbolic, numbers, seconds)
    emit(text.rstrip("\n"), output)


def _repeated_line(file, count, total, ask_given, no_given) -> str:
    """'FILE: N of M boxes ask a value the question gives', and what leaves them out:
    --no-given, the file's quiz.ask_given: false, or (neither) what --no-given would do."""
    what = "left out by --no-given" if no_given else "left out by the file's " \
        "quiz.ask_given: false" if not ask_given else "--no-given leaves them out"
    return (f"{os.path.basename(file)}: {count} of {total} box{'' if total == 1 else 'es'} "
            f"ask{'s' if count == 1 else ''} a value the question gives ({what})")


def _worked(doc, ks, target, lang, no_figure, method, symbolic, numbers, seconds) -> str:
    """A worked solution of ``doc`` for one digit, with its formulas under --symbolic."""
    if ks is not None and len(ks) > 1:
        raise InputError("a worked solution is for one digit", key="--k",
                         hint="give one digit, e.g. --k 3")
    from linkcli.exports.worked import document
    k = ks[0] if ks else None
    formulas = None
    if symbolic:
        from linkcli.texts.symbolic import formulas as symbolic_formulas, parse_numbers
        formulas = symbolic_formulas(doc, k, parse_numbers(numbers), seconds)
    return document(doc, k, target, lang, figure=not no_figure, formulas=formulas,
                    method=method)
