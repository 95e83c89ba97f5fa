"""The terminal: what is printed on standard output and standard error.

Text read from a file is data: the control characters a terminal would act on are
removed before it is echoed.  Colour only on a terminal, never with ``NO_COLOR``;
``--quiet`` keeps only results and problems.  A standard output that cannot be
written is an input error (exit 2), a closed pipe (``| head``) a quiet stop.
"""
from __future__ import annotations

import errno
import os
import re
import sys

import click

from linkcli.errors import InputError

# characters a terminal may act on (C0 but the newline, DEL, C1: escape sequences,
# carriage return, bell): never echoed from a file, whose text is data.  Whole escape
# sequences go first (CSI ... final byte; OSC, DCS ... up to BEL or ST), so that no
# '[31m' is left behind, then any control character left.
ESCAPES = re.compile("\x1b\\[[0-?]*[ -/]*[@-~]|\x9b[0-?]*[ -/]*[@-~]"
                     "|[\x1b][]PX^_][^\x07\x1b\x9c]*(?:\x07|\x1b\\\\|\x9c)?"
                     "|\x1b[ -/]*[0-~]")
CONTROL = re.compile("[\x00-\x09\x0b-\x1f\x7f-\x9f]")


def style(text: str, **how) -> str:
    """``text`` in colour; click.echo drops the colour when not on a terminal."""
    return text if os.environ.get("NO_COLOR") else click.style(text, **how)


def error_prefix() -> str:
    """The start of an error line: 'linkcli: error: ', the word in red on a terminal."""
    return f"linkcli: {style('error:', fg='red', bold=True)} "


def quiet() -> bool:
    """Whether --quiet was given to the command being run."""
    ctx = click.get_current_context(silent=True)
    return bool(ctx and ctx.find_root().obj and ctx.find_root().obj.get("quiet"))


def clean(text) -> str:
    """``text`` without the control characters a terminal would act on (newlines kept)."""
    text = str(text)
    if CONTROL.search(text) is None:      # the usual case: no copy of a long output
        return text
    return CONTROL.sub("", ESCAPES.sub("", text))


def drop_stdout():
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


class PipeClosed(BaseException):
    """The reader of standard output went away (``| head``): stop quietly."""


def output_failed(exc: OSError):
    """A failed write to standard output: quiet for a closed pipe, else an input error."""
    drop_stdout()
    if isinstance(exc, BrokenPipeError) or exc.errno == errno.EPIPE:
        raise PipeClosed() from None
    raise InputError(f"cannot write to standard output: {exc.strerror or exc}") from None


def echo(text="", err=False, prefix="", nl=True):
    """Print ``text`` (from the file: control characters removed) after ``prefix`` (ours,
    perhaps coloured).  A standard output that cannot be written is an error, not a bug."""
    try:
        click.echo(prefix + clean(text), err=err, nl=nl)
    except OSError as exc:
        if err:
            return        # nowhere left to report it
        output_failed(exc)


def flush_stdout():
    """Flush standard output here, so that a failed write is reported, not left to exit."""
    stream = sys.stdout
    if stream is None:
        return
    try:
        stream.flush()
    except OSError as exc:
        output_failed(exc)
