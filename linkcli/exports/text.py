"""The file's own text (its title and statement) as the exports may carry it.

An XML 1.0 document may hold only the characters of its ``Char`` production:
tab, newline, carriage return, U+0020-U+D7FF, U+E000-U+FFFD and U+10000-U+10FFFF.
Those and the characters XML and HTML discourage (DEL and the C1 controls
U+007F-U+009F, the noncharacters U+FDD0-U+FDEF and U+nFFFE, U+nFFFF of every
plane) are refused in the title and the statement, with the file, key and line:
a question bank or a page that a strict parser rejects, or that shows a
character nobody can see, is never written.  Text that is not the file's own
words (the file's name) has them replaced by U+FFFD, which shows.

HTML text is escaped where it is written (``html.escape``); Markdown text goes
through ``markdown``: every character that can open a CommonMark construct
inline (``\\ ` * _ [ ] < > | ! & ~``) is escaped with a backslash, and so is
one that opens a block at the start of a line (``# + - = .`` after digits).
With every ``<`` and ``[`` escaped no raw HTML, autolink or link can form, so
a ``<script>`` or a ``javascript:`` link of the file is shown as text.
"""
from __future__ import annotations

import re

from linkcli.errors import InputError

# the noncharacters U+nFFFE and U+nFFFF of the supplementary planes
NONCHARACTERS = "".join(chr(plane * 0x10000 + last) for plane in range(1, 17)
                        for last in (0xFFFE, 0xFFFF))
UNFIT = re.compile("[^\t\n\r\x20-\x7e\xa0-\ud7ff\ue000-\ufdcf\ufdf0-\ufffd"
                   f"\U00010000-\U0010ffff]|[{NONCHARACTERS}]")
FILE_TEXTS = ("title", "statement")
INLINE = re.compile(r"([\\`*_\[\]<>|!&~])")
LINE_START = re.compile(r"^([ \t]*)([#+\-=]|\d+[.)])", re.MULTILINE)


def refuse_unfit(doc) -> None:
    """Refuse a title or statement of ``doc`` (a loaded Document) holding a character an
    XML or HTML document cannot carry, naming the file, the key, its line and the
    character."""
    data = doc.data if isinstance(doc.data, dict) else {}
    for key in FILE_TEXTS:
        value = data.get(key)
        found = UNFIT.search(value) if isinstance(value, str) else None
        if found is not None:
            raise InputError(
                f"the {key} holds the character U+{ord(found.group()):04X} (character "
                f"{found.start() + 1}), which an XML or HTML document cannot carry",
                file=doc.name, key=key, line=doc.line((key,)),
                hint="remove it, or write the character meant")


def visible(text) -> str:
    """``text`` with every character unfit for XML or HTML replaced by U+FFFD."""
    return UNFIT.sub("\ufffd", str(text))


def markdown(text) -> str:
    """``text`` as literal Markdown (CommonMark): no markup of the file is interpreted."""
    text = INLINE.sub(r"\\\1", visible(text))
    return LINE_START.sub(lambda m: m.group(1) + m.group(2)[:-1] + "\\" + m.group(2)[-1], text)


def fence(lines) -> str:
    """``lines`` as a fenced code block whose fence is longer than any run of backticks in
    them, so that none of them closes it."""
    body = "\n".join(visible(x) for x in lines)
    runs = [len(r) for r in re.findall("`+", body)]
    ticks = "`" * max(3, max(runs, default=0) + 1)
    return f"{ticks}\n{body}\n{ticks}"
