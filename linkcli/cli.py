"""The command line: parse arguments, call the library, print.

Exit codes: 0 ok, 1 check found disagreeing values, 2 invalid input,
3 mechanism cannot be solved (assembly, singular position, mobility,
structure).  Errors are one line on stderr; ``--traceback`` shows the Python
traceback for bug reports.  Colour is used only on a terminal (and never
when ``NO_COLOR`` is set); ``--quiet`` keeps only results and problems.
"""
from __future__ import annotations

import contextlib
import errno
import os
import re
import signal
import stat
import sys
import threading
import warnings

import click

from linkcli import __version__
from linkcli.errors import InputError, LinkcliError

FORMATS = ["exam", "table", "json", "csv"]
# characters a terminal may act on (C0 but the newline, DEL, C1: escape sequences,
# carriage return, bell): never echoed from a file, whose text is data.  Whole escape
# sequences go first (CSI ... final byte; OSC, DCS ... up to BEL or ST), so that no
# '[31m' is left behind, then any control character left.
ESCAPES = re.compile("\x1b\\[[0-?]*[ -/]*[@-~]|\x9b[0-?]*[ -/]*[@-~]"
                     "|[\x1b][]PX^_][^\x07\x1b\x9c]*(?:\x07|\x1b\\\\|\x9c)?"
                     "|\x1b[ -/]*[0-~]")
CONTROL = re.compile("[\x00-\x09\x0b-\x1f\x7f-\x9f]")


def _digit(ctx, param, value):
    """--k: a digit, refused here (blamed on the option) before the file is read."""
    if value is not None and not 0 <= value <= 9:
        raise InputError(f"k must be a digit 0-9, got {value}", key="--k",
                         hint="k is the last digit of the matricola")
    return value


K_OPTION = click.option("--k", "k", type=int, default=None, callback=_digit,
                        help="Last digit of the matricola (0-9).")
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


def _symbolic_options(symbolic, numbers, seconds):
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


def _symbolic_load(file, k, symbolic, numbers, seconds, designed=True, method="closed",
                   tol=None):
    """(model, formulas' source) of ``file``: the document is read once when the formulas
    are asked for (standard input cannot be read twice); a design question answered (by
    ``method``) unless ``designed`` is False."""
    _symbolic_options(symbolic, numbers, seconds)
    if not symbolic:
        return _load(file, k, designed, method, tol), None
    from linkcli.input.document import build
    from linkcli.input.source import load_file
    doc = load_file(file)
    return build(doc, k), doc


def _load(path, k, designed=True, method="closed", tol=None):
    """The validated model of ``path`` for digit ``k``; where the file asks a design question
    (``find:``), built with its solution (each trial solved by ``method``) unless
    ``designed`` is False."""
    from linkcli.api import load
    model = load(path, k).model
    if designed and model.design is not None:
        from linkcli.runs.design import resolved
        from linkcli.runs.sheet import evaluate
        try:
            model = resolved(model, evaluate, method, tol)
        except LinkcliError as exc:
            raise exc.located(path)
    return model


def _style(text: str, **style) -> str:
    """``text`` in colour; click.echo drops the colour when not on a terminal."""
    return text if os.environ.get("NO_COLOR") else click.style(text, **style)


def _quiet() -> bool:
    ctx = click.get_current_context(silent=True)
    return bool(ctx and ctx.find_root().obj and ctx.find_root().obj.get("quiet"))


def _clean(text) -> str:
    """``text`` without the control characters a terminal would act on (newlines kept)."""
    text = str(text)
    if CONTROL.search(text) is None:      # the usual case: no copy of a long output
        return text
    return CONTROL.sub("", ESCAPES.sub("", text))


class _Signalled(BaseException):
    """SIGINT or SIGTERM: unwinds like KeyboardInterrupt (so that ``finally`` blocks and
    the pictures' temporary files are cleaned up), and main() exits 128 + the signal."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


_RECEIVED: list = []      # the signals received while main() runs, in order


def _raise_signal(signum, frame):
    _RECEIVED.append(signum)
    raise _Signalled(signum)


def _signal_received():
    """The last signal received while main() runs, as a _Signalled to raise, or None.

    An error raised after a signal came is the signal's doing, whatever it looks like: a
    writer's ``finally`` that fails when the signal cut it short (a GIF closed before its
    first frame), or a library's compiled code that turned the handler's exception into
    its own error (matplotlib's 'Invalid bounding box')."""
    return _Signalled(_RECEIVED[-1]) if _RECEIVED else None


@contextlib.contextmanager
def _signals():
    """SIGINT and SIGTERM raise _Signalled while main() runs (in the main thread, and
    unless the signal is ignored, as for a background job)."""
    saved = {}
    _RECEIVED.clear()
    if threading.current_thread() is threading.main_thread():
        for signum in (signal.SIGINT, signal.SIGTERM):
            try:
                if signal.getsignal(signum) is not signal.SIG_IGN:
                    saved[signum] = signal.signal(signum, _raise_signal)
            except (ValueError, OSError):   # pragma: no cover - no signals here
                pass
    try:
        yield
    finally:
        for signum, handler in saved.items():
            signal.signal(signum, handler if handler is not None else signal.SIG_DFL)


def _drop_stdout():
    """Point file descriptor 1 at /dev/null after a failed write, so that the output still
    buffered does not fail again (with a traceback) when Python exits."""
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):   # not a real file (tests)
        return
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, fd)
    finally:
        os.close(devnull)


class _PipeClosed(BaseException):
    """The reader of standard output went away (``| head``): stop quietly."""


def _output_failed(exc: OSError):
    """A failed write to standard output: quiet for a closed pipe, else an input error."""
    _drop_stdout()
    if isinstance(exc, BrokenPipeError) or exc.errno == errno.EPIPE:
        raise _PipeClosed() from None
    raise InputError(f"cannot write to standard output: {exc.strerror or exc}") from None


def _echo(text="", err=False, prefix="", nl=True):
    """Print ``text`` (from the file: control characters removed) after ``prefix`` (ours,
    perhaps coloured).  A standard output that cannot be written is an error, not a bug."""
    try:
        click.echo(prefix + _clean(text), err=err, nl=nl)
    except OSError as exc:
        if err:
            return        # nowhere left to report it
        _output_failed(exc)


def _emit(text: str, output):
    if output is None:
        _echo(text)
        return
    try:
        with open(output, "w", encoding="utf-8") as handle:
            handle.write(_clean(text) + "\n")
    except OSError as exc:
        raise InputError(f"cannot write output file: {exc.strerror}", file=output,
                         hint="check the folder exists and is writable") from None


def _same_file(output, path) -> bool:
    """Whether writing ``output`` would write the input ``path``: the same inode (a symbolic
    or hard link), else the same real path; '-' is standard input, when it is a file."""
    if path == "-":
        try:
            held, target = os.fstat(sys.stdin.fileno()), os.stat(output)
        except (AttributeError, OSError, ValueError):    # a pipe, a terminal, no output yet
            return False
        return stat.S_ISREG(held.st_mode) and \
            (held.st_dev, held.st_ino) == (target.st_dev, target.st_ino)
    try:
        return os.path.samefile(output, path)
    except (OSError, ValueError):
        return os.path.realpath(output) == os.path.realpath(path)


def _not_an_input(output, *inputs):
    """Refuse ``-o`` naming a folder (no file can be written there, ``--force`` or not), or
    one of the input files (also through a link, and standard input read from that file):
    it would be overwritten before, or instead of, being read."""
    if output is None:
        return
    if os.path.isdir(output):
        raise InputError("the output path is a folder", file=output, key="-o",
                         hint="give the name of a file to write, such as "
                         f"{os.path.join(output, 'NAME')}")
    for path in inputs:
        if path is None:
            continue
        if _same_file(output, path):
            what = "the file read on standard input" if path == "-" else f"the input file {path}"
            raise InputError(f"the output file is {what}", file=output,
                             key="-o", hint="give -o another name: writing it would "
                             "replace the mechanism")


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
@SYMBOLIC_OPTION
@NUMBERS_OPTION
@SECONDS_OPTION
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
    _not_an_input(output, file)
    if symbolic and form == "csv":
        raise InputError("--symbolic writes formulas in the exam, table or json format, not "
                         "csv", key="--format", hint="give --format json for machine-readable "
                         "formulas")
    tol = _tol(tol)
    mech, doc = _symbolic_load(file, k, symbolic, numbers, seconds, method=method, tol=tol)
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
    _emit(text, output)
    for caution in result.cautions:       # after the answers: what the reader should check
        _echo(f"linkcli: {caution}", err=True)


@cli.command()
@click.argument("file")
@K_OPTION
@click.option("--pseudocode", is_flag=True,
              help="Print the solving order as pseudo-MATLAB calls of the dyad functions.")
@click.option("-o", "--output", default=None, help="Write to this file instead of stdout.")
@click.option("--method", type=click.Choice(["closed", "newton"]), default="closed",
              show_default=True, help="What is explained: the closed form's decomposition, "
              "or the constraint equations Newton-Raphson solves together.")
@SYMBOLIC_OPTION
@NUMBERS_OPTION
@SECONDS_OPTION
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
    _not_an_input(output, file)
    mech, doc = _symbolic_load(file, k, symbolic, numbers, seconds, designed=pseudocode)
    if pseudocode:
        from linkcli.texts.pseudocode import pseudocode as text
        out = text(mech)
    else:
        from linkcli.texts.explain import explain as text
        out = text(mech, method)
    if doc is not None:
        from linkcli.texts.symbolic import append
        out = append(out, "exam", doc, k, numbers, seconds=seconds)
    _emit(out, output)


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
    from linkcli.runs import batch as batch_mod
    from linkcli.input.source import load_file
    from linkcli.answers.formats import fmt
    digits = batch_mod.parse_k(ks)
    _not_an_input(output, file)
    try:
        doc = load_file(file)
        columns, units, rows, shown, failures = batch_mod.run(doc, digits)
    except LinkcliError as exc:
        raise exc.located(file)
    for k, exc in failures:     # one line per digit that fails; the others' rows follow
        _echo(batch_mod.failure_text(k, exc), err=True,
              prefix=f"linkcli: {_style('error:', fg='red', bold=True)} ")
    decimals = shown if decimals is None else decimals
    if form == "json":
        import json
        data = [dict(zip(["k"] + columns, row)) for row in rows]
        extra = {"errors": [{"k": k, "error": str(exc)} for k, exc in failures]} \
            if failures else {}
        text = json.dumps({"file": file, "units": units, "rows": data, **extra}, indent=2)
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
    if rows or form == "json":
        _emit(text, output)
    if failures:                # invalid data for a digit (2) outranks unsolvable (3)
        sys.exit(min(exc.exit_code for _, exc in failures))


@cli.command()
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
        _echo(json.dumps(data, indent=2))
        if not data["ok"]:
            sys.exit(1)
        return
    lines, ok = summary_lines(reports, verbose)
    colours = {"FAIL": "red", "ERROR": "red", "KNOWN": "yellow"}
    for line in lines:
        word = line.split(" ", 1)[0]
        if _quiet() and word not in ("FAIL", "ERROR") and line is not lines[-1]:
            continue
        prefix = ""
        if word in colours:
            prefix, line = _style(word, fg=colours[word], bold=True), line[len(word):]
        _echo(line, prefix=prefix)
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
@click.option("--vary", default=None, metavar="NAME=FROM:TO:STEPS",
              help="Answers against a parameter of 'params' (any file, vibrations too).")
@click.option("--y", "names", multiple=True, metavar="NAME",
              help="A quantity of the report (repeat for more panels), e.g. --y c --y cdot; "
                   "with --frf or --free, coordinates (default: every free one).")
@K_OPTION
@click.option("-o", "--output", required=True, help="Picture to write (.png, .svg or .pdf).")
def plot(file, sweep, frf, modes, free, vary, names, k, output):
    """Plot quantities of FILE against the driver, or a vibration problem's response.

    \b
    Examples:
      linkcli plot mechanisms/polimi-crank-slider.yaml --sweep 0:360:360 --y c --y beta -o pos.png
      linkcli plot mechanisms/fourbar-inverse-dynamics.yaml --sweep 0:360:360 --y Mm -o mm.png
      linkcli plot mechanisms/polimi-2001-09-18-vibration.yaml --modes -o modes.png
      linkcli plot mechanisms/polimi-2001-09-18-vibration.yaml --vary ks=50:150:50 --y w1 -o w.png
    """
    chosen = [flag for flag, value in (("--sweep", sweep), ("--frf", frf), ("--modes", modes),
                                       ("--free", free), ("--vary", vary)) if value]
    if len(chosen) != 1:
        raise InputError("give one of --sweep, --frf, --modes, --free, --vary", key="plot",
                         hint="--sweep FROM:TO:STEPS --y NAME for a mechanism with a driver")
    _not_an_input(output, file)
    mech = _load(file, k, designed=not vary)     # a design question: solved at each value
    if vary:
        from linkcli.pictures.plotting import plot_vary
        plot_vary(mech, vary, list(names), output)
        return
    if sweep:
        from linkcli.runs.limits.names import sweep_names
        from linkcli.pictures.plotting import plot as make
        make(mech, sweep, sweep_names(mech, list(names), key="--y"), output)
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
@click.option("--exam", is_flag=True, help="The exam's figure: the data only, no answer.")
@click.option("--lang", type=click.Choice(["it", "en"]), default="en", show_default=True,
              help="Numbers of --exam with a decimal comma (it) or point (en).")
@click.option("--method", type=click.Choice(["closed", "newton"]), default="closed",
              show_default=True, help="How positions (and loads) are solved: newton for a "
              "class-III group.")
def draw(file, k, output, exam, lang, method):
    """Draw FILE at its driver value: links, sliders, pivots, the vector polygon z_i, loads.

    With --exam, the figure of the exam's statement instead: the mechanism with its data
    (lengths, guides, known loads, the driver's value and sense), nothing solved.

    \b
    Examples:
      linkcli draw mechanisms/padova-2020-07.yaml -o mechanism.png
      linkcli draw mechanisms/padova-2020-07.yaml --exam --lang it -o esame.png
    """
    _not_an_input(output, file)
    if exam:
        from linkcli.pictures.exam import draw_exam
        # the problem as asked: a design question's unknowns are not drawn solved
        draw_exam(_load(file, k, designed=False), output, lang=lang, method=method)
        return
    from linkcli.pictures.plotting import draw as make
    make(_load(file, k), output, method=method)


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
    _not_an_input(output, file)
    make(_load(file, k), output, sweep, fps)


@cli.command()
@click.argument("files", nargs=-1, required=True)
@click.option("--k", "k", type=int, default=None, callback=_digit,
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
            _echo(line)
        if outcome.exit_code:   # invalid input (2) outranks an unsolvable structure (3)
            worst = 2 if 2 in (worst, outcome.exit_code) else outcome.exit_code
            if not _quiet():
                count = len(outcome.problems)
                _echo(f" {outcome.file}: {count} problem{'s' if count != 1 else ''}",
                      prefix=_style('FAIL', fg='red', bold=True))
        elif not _quiet():
            _echo(f" {outcome.file} ({outcome.summary})",
                  prefix=_style('OK', fg='green', bold=True))
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
    _not_an_input(output)
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
        _echo(text, nl=False)
        return
    if os.path.exists(path) and not force:
        raise InputError("file exists", file=path, hint="use --force to overwrite it, or "
                         "give another name")
    _emit(text.rstrip("\n"), path)
    if not _quiet():
        _echo(f"wrote {path}; next: linkcli validate {path} && linkcli solve {path}")


def _tol(tol):
    if tol is not None and not (0 < tol < 1):
        raise InputError(f"--tol must be between 0 and 1, got {tol}", key="--tol",
                         hint="a tolerance relative to the mechanism's size, e.g. 1e-12")
    return tol


@cli.command()
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
@click.option("--method", type=click.Choice(["closed", "newton"]), default="closed",
              show_default=True)
@click.option("--tol", type=float, default=None, help="Newton's relative tolerance.")
@K_OPTION
@click.option("-o", "--output", default=None, help="Write to this file instead of stdout.")
def sweep(file, start, stop, vary, steps, step, form, every, names, decimals, method, tol, k,
          output):
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
    from linkcli.runs import sweep as sweep_mod
    _not_an_input(output, file)
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
        mech = _load(file, k, designed=False)     # a design question: solved at each value
        sweep_mod.check_every(every)
        variation = vary_mod.Variation(mech, name, values, chosen, method=method, tol=_tol(tol))
        writer = (lambda put: vary_mod.write(variation, form, decimals, put))
    else:
        if start is None or stop is None:
            raise InputError("give --from and --to (the driver's range), or --vary "
                             "NAME=FROM:TO:STEPS (a parameter's)", key="--from")
        mech = _load(file, k, method=method, tol=_tol(tol))
        q = sweep_mod.driver_range(start, stop, steps, step)
        from linkcli.runs.limits.names import sweep_names
        chosen = sweep_names(mech, chosen)      # maxima, strokes ... are not functions of q
        sweep_mod.check_every(every)
        sweeper = sweep_mod.Sweeper(mech, q, chosen, method=method, tol=_tol(tol))
        writer = (lambda put: sweep_mod.write(sweeper, form, every, decimals, put))
    opened = []

    def put(text):      # rows are printed as each block is solved; the file opened then
        if output is None:
            _echo(text, nl=False)
            return
        try:
            if not opened:
                opened.append(open(output, "w", encoding="utf-8"))
            opened[0].write(_clean(text))
        except OSError as exc:
            raise InputError(f"cannot write output file: {exc.strerror}", file=output,
                             hint="check the folder exists and is writable") from None

    try:
        issues = writer(put)
    finally:
        for handle in opened:
            handle.close()
    for issue in issues:
        _echo(issue.text(), err=True, prefix="linkcli: ")


@cli.command()
@click.argument("file")
@click.option("--of", "names", multiple=True,
              help="A quantity (repeat the option for several) [default: the report's].")
@click.option("--from", "start", type=float, default=None,
              help="First driver value [default: a full turn of a crank].")
@click.option("--to", "stop", type=float, default=None, help="Last driver value.")
@click.option("--format", "form", type=click.Choice(["table", "json", "csv"]), default="table",
              show_default=True)
@click.option("--decimals", type=click.IntRange(0, 12), default=None,
              help="Decimals shown (default: the file's report.decimals, else 1).")
@K_OPTION
@click.option("-o", "--output", default=None, help="Write to this file instead of stdout.")
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
    _not_an_input(output, file)
    mech = _load(file, k)
    decimals = mech.report.get("decimals", 1) if decimals is None else decimals
    found = [search.find(mech, name, start, stop)
             for name in (names or limit_names.default_names(mech))]
    _emit(table.render(found, form, decimals), output)
    if form != "json":
        for text in table.messages(found):
            _echo(text, err=True, prefix="linkcli: ")


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
    with _signals():
        try:
            return _run(args, prog_name, show_traceback)
        except _Signalled as exc:       # Ctrl-C 130, SIGTERM 143: nothing printed
            return 128 + exc.signum
        except _PipeClosed:             # '| head': the reader has what it wanted
            return 128 + signal.SIGPIPE


def _run(args, prog_name, show_traceback) -> int:
    try:
        with warnings.catch_warnings():
            # NumPy's floating-point warnings: results are checked to be finite instead
            warnings.filterwarnings("ignore", r"(invalid value|overflow|divide by zero)",
                                    RuntimeWarning)
            try:
                cli.main(args=args, prog_name=prog_name, standalone_mode=False)
                status = 0
            except SystemExit as exc:
                status = exc.code if isinstance(exc.code, int) else 0
        _flush_stdout()
        return status
    except LinkcliError as exc:
        signalled = _signal_received()
        if signalled is not None:       # the error came on the way out of a signal
            raise signalled from None
        if show_traceback:
            raise
        _echo(exc, err=True, prefix=f"linkcli: {_style('error:', fg='red', bold=True)} ")
        return exc.exit_code
    except click.exceptions.Abort as exc:
        if isinstance(exc.__context__, KeyboardInterrupt):
            return 130              # Ctrl-C outside main()'s handler: nothing printed
        _echo("linkcli: aborted", err=True)
        return 1
    except click.ClickException as exc:
        exc.show()
        return 2
    except KeyboardInterrupt:
        return 130
    except Exception as exc:  # a bug: say so briefly, traceback on request
        if isinstance(exc, OSError) and _writing_stdout(exc):   # click's own (--help)
            return _report_output_error(exc)
        signalled = _signal_received()
        if signalled is not None:       # a library's clean-up failed on the way out
            raise signalled from None
        if show_traceback:
            raise
        _echo("linkcli: internal error (please report it; rerun with --traceback for "
              "details)", err=True)
        return 70


def _flush_stdout():
    """Flush standard output here, so that a failed write is reported, not left to exit."""
    stream = sys.stdout
    if stream is None:
        return
    try:
        stream.flush()
    except OSError as exc:
        _output_failed(exc)


def _writing_stdout(exc: OSError) -> bool:
    """Whether ``exc`` was raised by click.echo writing to standard output."""
    tb = exc.__traceback__
    while tb is not None:
        stream = tb.tb_frame.f_locals.get("file") if tb.tb_frame.f_code.co_name == "echo" \
            else None
        if stream is not None and (stream is sys.stdout or
                                   getattr(stream, "name", None) == "<stdout>"):
            return True
        tb = tb.tb_next
    return False


def _report_output_error(exc: OSError) -> int:
    """Report click's own failed write like ours (a closed pipe still ends quietly)."""
    try:
        _output_failed(exc)       # raises
    except InputError as error:
        _echo(error, err=True, prefix=f"linkcli: {_style('error:', fg='red', bold=True)} ")
        return error.exit_code
    return 2                      # pragma: no cover


def entry():  # pragma: no cover - console script
    sys.exit(main())


@cli.command()
@click.argument("file")
@click.option("--to", "target", type=click.Choice(["moodle", "html", "markdown"]),
              required=True, help="moodle: a Moodle XML question bank; html or markdown: a "
              "worked solution.")
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
@click.option("--method", type=click.Choice(["closed", "newton"]), default="closed",
              show_default=True, help="Moodle: how positions are solved (newton for a "
              "class-III group).")
@click.option("-o", "--output", required=True, help="File to write.")
@click.option("--force", is_flag=True, help="Replace the output file if it exists.")
@SYMBOLIC_OPTION
@NUMBERS_OPTION
@SECONDS_OPTION
def export(file, target, k_text, lang, decimals, tolerance, no_figure, method, output, force,
           symbolic, numbers, seconds):
    """Export FILE for a course: a Moodle quiz with every digit's variant, or a worked
    solution to hand out.

    \b
    Examples:
      linkcli export mechanisms/padova-2020-02.yaml --to moodle --k 0-9 -o quiz.xml
      linkcli export mechanisms/padova-2020-07.yaml --to html --lang it -o solution.html
    """
    import os
    from linkcli.runs.batch import parse_k
    from linkcli.input.source import load_file
    _not_an_input(output, file)             # --force replaces an output, never the input
    if os.path.exists(output) and not force:
        raise InputError("the output file exists", file=output, key="-o",
                         hint="give --force to replace it, or another name")
    doc = load_file(file)
    ks = parse_k(k_text) if k_text is not None else None
    if (symbolic or numbers is not None) and target == "moodle":
        raise InputError("--symbolic goes with a worked solution (--to html or markdown)",
                         key="--symbolic", hint="drop --symbolic for a Moodle export")
    _symbolic_options(symbolic, numbers, seconds)
    if target == "moodle":
        from linkcli.exports.moodle import export as make
        text = make(doc, ks, decimals=decimals, tolerance=tolerance, lang=lang,
                    figure=not no_figure, method=method)
    else:
        if ks is not None and len(ks) > 1:
            raise InputError("a worked solution is for one digit", key="--k",
                             hint="give one digit, e.g. --k 3")
        if method != "closed":
            raise InputError("a worked solution follows the closed-form groups", key="--method",
                             hint="--method newton is for --to moodle")
        from linkcli.exports.worked import document
        k = ks[0] if ks else None
        formulas = None
        if symbolic:
            from linkcli.texts.symbolic import formulas as symbolic_formulas, parse_numbers
            formulas = symbolic_formulas(doc, k, parse_numbers(numbers), seconds)
        text = document(doc, k, target, lang, figure=not no_figure, formulas=formulas)
    _emit(text.rstrip("\n"), output)
