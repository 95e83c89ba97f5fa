"""A sweep's solved rows printed as CSV (the default), JSON or a table, a block at a time.

Rows: the first column is the values swept (``q``, the driver's, or a parameter's), then
one column per name, each headed ``name [unit]``; only solved rows are printed, every
``--every``-th one counted over the whole sweep.  Numbers are ``repr`` of the float64
(CSV, JSON) unless ``--decimals`` fixes them (CSV; tables always, 4 by default).

Memory: CSV is printed as each block is solved; JSON (whose lists are one quantity each)
and tables (whose column widths are known at the end) keep the rows in unnamed temporary
files until the end, so that printing takes the same memory for 10^4 as for 10^7 rows.
The text is the one ``json.dumps(..., indent=1)`` and tabulate's 'simple' format write.
"""
from __future__ import annotations

import tempfile

import numpy as np

from linkcli.errors import InputError
from linkcli.runs.sweep.blocks import BLOCK, Block, Sweep, Sweeper, out_of_memory

#: rows formatted at once: their text (Python strings) takes far more memory than the numbers
LINES = 4096


def check_every(every: int) -> int:
    """``--every``, refused below 1."""
    if every < 1:
        raise InputError(f"--every must be at least 1, got {every}", key="--every")
    return every


def render(result: Sweep, form: str = "csv", every: int = 1, decimals: int | None = None) -> str:
    """CSV (default), JSON or a table of the solved rows, every ``every``-th one."""
    import io
    check_every(every)
    text = io.StringIO()
    block = Block(result.q, result.solved, result.values)
    write_rows(iter([block]), result.mechanism, result.method, result.names, result.units,
               result.q_unit, lambda: result.issues, form, every, decimals, text.write)
    return text.getvalue()[:-1]


def write(sweeper: Sweeper, form: str, every: int, decimals: int | None, out) -> list:
    """Solve ``sweeper`` and print it through ``out`` (a function of text, or a text stream)
    as it goes: CSV rows a block at a time, JSON and tables through temporary files (their
    lists and column widths are known at the end).  Returns the issues, to be reported;
    nothing is printed when no row can be assembled (AssemblyError)."""
    check_every(every)
    put = out if callable(out) else out.write
    try:
        write_rows(sweeper.blocks(), sweeper.mech, sweeper.method, sweeper.names,
                   sweeper.units, sweeper.q_unit, lambda: sweeper.issues, form, every,
                   decimals, put)
    except MemoryError:
        raise out_of_memory(sweeper.size) from None
    return sweeper.issues


def write_rows(blocks, mech, method, names, units, q_unit, issues, form, every, decimals,
               put, first="q"):
    """Print ``blocks`` (the rows of the sweep) as CSV, JSON or a table; ``units`` is filled
    by the time the first block with rows is done, ``issues()`` at the end.  ``first`` names
    the column of the values swept (the driver's, q, or a parameter's)."""
    if form == "csv":
        fmt = repr if decimals is None else (lambda v: f"{v:.{decimals}f}")
        seen, started = 0, False
        for part in blocks:
            columns = _printed(part, names, seen, every)
            seen += part.count
            if columns is None:
                continue
            if not started:         # the units are known once a block has rows
                put(",".join(_header(names, units, q_unit, first)) + "\n")
                started = True
            for lo in range(0, columns[0].size, LINES):     # text is bulky: a bit at a time
                text = [list(map(fmt, c[lo:lo + LINES].tolist())) for c in columns]
                put("\n".join(map(",".join, zip(*text))) + "\n")
        if not started:             # every assembled row left out: the header alone
            put(",".join(_header(names, units, q_unit, first)) + "\n")
        return
    with _Spool(1 + len(names)) as spool:
        width = _Widths(1 + len(names), 4 if decimals is None else decimals)
        seen = 0
        for part in blocks:
            columns = _printed(part, names, seen, every)
            seen += part.count
            if columns is None:
                continue
            spool.add(columns)
            if form == "table":
                width.add(columns)
        header = _header(names, units, q_unit, first)
        if form == "json":
            _json(spool, mech, method, names, units, q_unit, issues(), put, first)
        else:
            _table(spool, header, width, put)


def _header(names, units, q_unit, first="q") -> list:
    return [f"{first} [{q_unit}]"] + [f"{n} [{units.get(n, '')}]" for n in names]


def _printed(part: Block, names, seen: int, every: int):
    """The columns (q first) of ``part``'s solved rows printed with ``--every``, the
    solved rows before it numbering ``seen``; None when none is printed."""
    count = part.count
    if count == 0:
        return None
    first = (-seen) % every
    if first >= count:
        return None
    q = part.q[part.solved] if count < part.q.size else part.q
    return [np.asarray(q[first::every], dtype=float)] + [
        np.asarray(part.values[n][first::every], dtype=float) for n in names]


class _Spool:
    """Columns of float64 written to unnamed temporary files (removed however the program
    ends), read back a block at a time."""

    def __init__(self, count: int):
        self.count = count
        self.files = []
        self.rows = 0

    def __enter__(self):
        try:
            self.files = [tempfile.TemporaryFile(prefix="linkcli-sweep-") for _ in
                          range(self.count)]
        except OSError as exc:
            raise _spool_error(exc) from None
        return self

    def __exit__(self, *exc):
        for handle in self.files:
            handle.close()
        return False

    def add(self, columns):
        try:
            for handle, column in zip(self.files, columns):
                np.ascontiguousarray(column, dtype=np.float64).tofile(handle)
        except OSError as exc:
            raise _spool_error(exc) from None
        self.rows += columns[0].size

    def column(self, j):
        """The values of column ``j``, a block at a time."""
        handle = self.files[j]
        handle.flush()
        handle.seek(0)
        left = self.rows
        while left:
            part = np.fromfile(handle, dtype=np.float64, count=min(left, BLOCK))
            left -= part.size
            yield part

    def blocks(self):
        """Every column's values together, a block at a time."""
        readers = [self.column(j) for j in range(self.count)]
        yield from zip(*readers)


def _spool_error(exc) -> InputError:
    return InputError(f"cannot write the sweep's temporary file: {exc.strerror or exc}",
                      file=tempfile.gettempdir(), hint="JSON and tables of a sweep are kept "
                      "there until the end: free some space, set TMPDIR to another folder, or "
                      "use --format csv, which is printed as it goes")


class _Widths:
    """The widest text of each column at ``decimals`` fixed decimals: that of its largest
    value without a minus sign, or of its largest magnitude with one."""

    def __init__(self, count: int, decimals: int):
        self.decimals = decimals
        self.plus = [None] * count
        self.minus = [None] * count

    def add(self, columns):
        for j, c in enumerate(columns):
            negative = np.signbit(c)
            if (~negative).any():
                top = float(np.max(c[~negative]))
                self.plus[j] = top if self.plus[j] is None else max(self.plus[j], top)
            if negative.any():
                top = float(np.max(-c[negative]))
                self.minus[j] = top if self.minus[j] is None else max(self.minus[j], top)

    def text(self, j) -> int:
        d = self.decimals
        sizes = [len(f"{self.plus[j]:.{d}f}")] if self.plus[j] is not None else []
        if self.minus[j] is not None:
            sizes.append(1 + len(f"{self.minus[j]:.{d}f}"))
        return max(sizes, default=0)


TABLE_PADDING = 2       # tabulate's MIN_PADDING: a header is at least 2 narrower than its column
TABLE_GAP = "  "        # tabulate's 'simple' format: columns apart by two spaces


def _table(spool, header, widths, put):
    """The rows as tabulate's 'simple' table of right-aligned text, written a block at a time
    (the widths are known from the largest values)."""
    size = [max(len(h) + TABLE_PADDING, widths.text(j)) for j, h in enumerate(header)]
    put(TABLE_GAP.join(h.rjust(w) for h, w in zip(header, size)) + "\n")
    put(TABLE_GAP.join("-" * w for w in size))
    d = widths.decimals
    for columns in spool.blocks():
        for lo in range(0, columns[0].size, LINES):
            text = [[f"{v:.{d}f}".rjust(w) for v in c[lo:lo + LINES].tolist()]
                    for c, w in zip(columns, size)]
            put("\n" + "\n".join(map(TABLE_GAP.join, zip(*text))))
    put("\n")


def _json(spool, mech, method, names, units, q_unit, issues, put, first="q"):
    """json.dumps(..., indent=1) of the sweep, its lists written a block at a time."""
    import json
    marks = [f"\x00linkcli-column-{j}\x00" for j in range(1 + len(names))]
    data = {"file": mech.file, "title": mech.title, "k": mech.k, "method": method,
            "units": {first: q_unit, **{n: units.get(n, "") for n in names}},
            first: marks[0], "values": {n: m for n, m in zip(names, marks[1:])},
            "issues": [issue.as_dict() for issue in issues]}
    text = json.dumps(data, indent=1)
    for j, mark in enumerate(marks):
        quoted = json.dumps(mark)
        head, text = text.split(quoted, 1)
        put(head)
        _json_list(spool.column(j), _indent(head), put)
    put(text + "\n")


def _indent(head: str) -> int:
    """The indentation of the last line of ``head`` (the line that opens a list)."""
    line = head[head.rfind("\n") + 1:]
    return len(line) - len(line.lstrip(" "))


def _json_list(parts, depth, put):
    """A list of floats as json.dumps(..., indent=1) writes it at nesting ``depth``."""
    pad = "\n" + " " * (depth + 1)
    first = True
    for block in parts:
        for lo in range(0, block.size, LINES):
            put(("[" if first else ",") + pad +
                ("," + pad).join(map(repr, block[lo:lo + LINES].tolist())))
            first = False
    put("[]" if first else "\n" + " " * depth + "]")
