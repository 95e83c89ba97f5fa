"""The command line: parse arguments, call the library, print.

Exit codes: 0 ok, 1 check found disagreeing values, 2 invalid input,
3 mechanism cannot be solved (assembly, singular position, mobility,
structure).  Errors are one line on stderr; ``--traceback`` shows the Python
traceback for bug reports.  Colour is used only on a terminal (and never
when ``NO_COLOR`` is set); ``--quiet`` keeps only results and problems.

This module holds the group, ``main(args) -> exit status`` and the one place
errors are caught.  ``options`` (shared options and their checks), ``loading``
(the model of FILE), ``console`` (the terminal), ``output`` (results and ``-o``
files, the input never overwritten) and ``signals`` serve the commands:
``answers`` (solve, explain, validate, schema, init), ``runs`` (batch, check,
sweep, limits), ``pictures`` (draw, plot, animate) and ``documents`` (export).
A command imports the library only when it runs: start-up stays light.
May import: ``linkcli``, ``linkcli.errors``, ``linkcli.model``, ``linkcli.input``,
``linkcli.kinematics``, ``linkcli.forces``, ``linkcli.answers``, ``linkcli.runs``,
``linkcli.texts``, ``linkcli.pictures``, ``linkcli.exports``, ``linkcli.api``.
"""
from __future__ import annotations

import signal
import sys
import warnings

import click

from linkcli import __version__
from linkcli.cli import answers, documents, pictures, runs
from linkcli.cli.console import PipeClosed, echo, error_prefix, flush_stdout, output_failed
from linkcli.cli.signals import Signalled, signal_received, signals
from linkcli.errors import InputError, LinkcliError


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


for _command in (answers.solve, answers.explain, answers.validate, answers.schema,
                 answers.init, runs.batch, runs.check, runs.sweep, runs.limits,
                 pictures.draw, pictures.plot, pictures.animate, documents.export):
    cli.add_command(_command)

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
    with signals():
        try:
            return _run(args, prog_name, show_traceback)
        except Signalled as exc:        # Ctrl-C 130, SIGTERM 143: nothing printed
            return 128 + exc.signum
        except PipeClosed:              # '| head': the reader has what it wanted
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
        flush_stdout()
        return status
    except LinkcliError as exc:
        signalled = signal_received()
        if signalled is not None:       # the error came on the way out of a signal
            raise signalled from None
        if show_traceback:
            raise
        echo(exc, err=True, prefix=error_prefix())
        return exc.exit_code
    except click.exceptions.Abort as exc:
        if isinstance(exc.__context__, KeyboardInterrupt):
            return 130              # Ctrl-C outside main()'s handler: nothing printed
        echo("linkcli: aborted", err=True)
        return 1
    except click.ClickException as exc:
        exc.show()
        return 2
    except KeyboardInterrupt:
        return 130
    except Exception as exc:  # a bug: say so briefly, traceback on request
        if isinstance(exc, OSError) and _writing_stdout(exc):   # click's own (--help)
            return _report_output_error(exc)
        signalled = signal_received()
        if signalled is not None:       # a library's clean-up failed on the way out
            raise signalled from None
        if show_traceback:
            raise
        echo("linkcli: internal error (please report it; rerun with --traceback for "
             "details)", err=True)
        return 70


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
        output_failed(exc)        # raises
    except InputError as error:
        echo(error, err=True, prefix=error_prefix())
        return error.exit_code
    return 2                      # pragma: no cover


def entry():  # pragma: no cover - console script
    sys.exit(main())
