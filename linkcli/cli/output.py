"""Writing a command's result: to standard output, or to the file of ``-o``.

The input is never overwritten: ``-o`` naming a folder, an input file (also through
a link) or the file standard input is read from is refused before anything is read
or written, ``--force`` or not.  A file that cannot be written is an input error
that names it.
"""
from __future__ import annotations

import os
import stat
import sys

from linkcli.cli.console import clean, echo
from linkcli.errors import InputError


def _unwritable(output, exc: OSError) -> InputError:
    return InputError(f"cannot write output file: {exc.strerror}", file=output,
                      hint="check the folder exists and is writable")


def emit(text: str, output):
    """``text`` on standard output, or as the file ``output`` (with a final newline)."""
    if output is None:
        echo(text)
        return
    try:
        with open(output, "w", encoding="utf-8") as handle:
            handle.write(clean(text) + "\n")
    except OSError as exc:
        raise _unwritable(output, exc) from None


class Stream:
    """Text written as it is made (rows printed as each block is solved): to standard
    output, or to ``output``, opened at the first piece.  ``close()`` when done."""

    def __init__(self, output):
        self.output = output
        self.handle = None

    def put(self, text: str):
        if self.output is None:
            echo(text, nl=False)
            return
        try:
            if self.handle is None:
                self.handle = open(self.output, "w", encoding="utf-8")
            self.handle.write(clean(text))
        except OSError as exc:
            raise _unwritable(self.output, exc) from None

    def close(self):
        if self.handle is not None:
            self.handle.close()


def same_file(output, path) -> bool:
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


def not_an_input(output, *inputs):
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
        if same_file(output, path):
            what = "the file read on standard input" if path == "-" else f"the input file {path}"
            raise InputError(f"the output file is {what}", file=output,
                             key="-o", hint="give -o another name: writing it would "
                             "replace the mechanism")
