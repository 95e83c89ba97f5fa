r"""An independent parser of Moodle's embedded-answers (Cloze) syntax, for tests.

Written from Moodle's documented grammar (the "Embedded Answers (Cloze)
question type" page of docs.moodle.org) and from the grammar constants of
``question/type/multianswer/questiontype.php`` (``ANSWER_REGEX`` and the
``ANSWER_ALTERNATIVE_*``, ``NUMBER_REGEX``, ``NUMERICAL_ALTERNATIVE_REGEX``
and ``ANSWER_TYPE_DEF_REGEX`` it is built from), together with the checks of
``qtype_multianswer_validate_question``.  It shares no code with linkcli's
exporter, so a test can read an export back the way Moodle would and compare.

Grammar
-------
An embedded answer ("subquestion") in the question text (HTML) is::

    subquestion  := "{" weight ":" type ":" alternative ( "~" alternative )* "}"
    weight       := digit*                       empty means 1
    type         := one of TYPES below (upper case, no spaces)
    alternative  := fraction? answer ( "#" feedback )?
    fraction     := "=" | "%" "-"? digit+ ( ("." | ",") digit* )? "%"
    answer       := one or more characters, up to an unescaped "~", "#" or "}"
    feedback     := zero or more characters, up to an unescaped "~" or "}"

A subquestion starts at a ``{`` followed by optional digits and a ``:`` (a
``{`` preceded by a backslash, or followed by anything else, such as the
``{#1}`` placeholders or LaTeX groups, is ordinary text).

Fractions are returned in percent, as written: ``=`` gives 100, ``%n%`` gives
n (a comma is accepted as the decimal mark, as Moodle does), no prefix gives
0.  Moodle itself divides by 100, and for MULTIRESPONSE rescales the positive
fractions so that they add up to 1; this parser does not rescale.

NUMERICAL answers are ``value`` or ``value:tolerance`` where both match
Moodle's NUMBER_REGEX ``-?(([0-9]+[.,]?[0-9]*|[.,][0-9]+)([eE][-+]?[0-9]+)?)``
(no spaces, no "+" sign, a comma may be the decimal mark), or ``*`` (the
catch-all "any other answer").  The tolerance is an absolute error, 0 when
omitted.

Escapes
-------
Inside answers and feedback a backslash escapes the characters ``} # ~ / " \``
(``\}``, ``\#``, ``\~``, ``\/``, ``\"``, ``\\``): the escaped character is
literal and never a delimiter.  A backslash before any other character is an
ordinary backslash.  ``unescape`` undoes these escapes.

Note that Moodle's PHP only *removes* the backslash of ``\}`` and ``\#``
(``str_replace('\}', '}')`` and ``str_replace('\#', '#')`` after
``html_entity_decode``); in the versions read, a ``\~`` is not a separator
but is stored with its backslash.  ``moodle_php_decode`` reproduces that
literal behaviour, so tests can check what Moodle would actually store;
``Answer.text`` uses the documented rule (all six escapes removed).

HTML entities
-------------
The text is HTML, so answers and feedback may contain character references
(``&eacute;``, ``&#8364;``, ``&#x20AC;``).  Moodle's answer regex refuses to
end an answer at a ``~``, ``#`` or ``}`` directly preceded by ``&`` or by
``&amp;`` (the lookbehind ``(?<!\\|&|&amp;)``), so that the ``#`` of a
numeric reference such as ``&#039;`` -- or of a doubly encoded ``&amp;#039;``
-- does not start the feedback; it then applies ``html_entity_decode`` once
to non-numerical answers and to feedback.  This parser:

* reads a complete character reference ``&name;`` / ``&#123;`` / ``&#x7B;``
  as one literal unit and decodes it (once, like ``html_entity_decode``), so
  ``&#125;`` is a literal ``}`` and never closes a subquestion;
* after ``&amp;``, reads ``#123;`` / ``#x7B;`` literally too (Moodle's
  ``&amp;`` lookbehind), giving the text ``&#123;`` after the single decoding;
* rejects (``ClozeError``) a ``~``, ``#`` or ``}`` directly after a bare
  ``&`` or after ``&amp;`` when it does not begin a character reference:
  Moodle would silently take that delimiter as literal text, which is never
  what an exporter means.

Stricter than Moodle
--------------------
To make a useful test oracle, the parser raises ``ClozeError`` on text that
Moodle would accept but read in a way nobody intends:

* an unterminated subquestion, or a new ``{weight:`` subquestion opening
  inside another one (a missing ``}``); unbalanced ``{``/``}`` in the text
  around the subquestions (backslash-escaped braces excepted; pass
  ``check_text_braces=False`` to skip this check);
* an unknown or lower-case type (Moodle leaves such a ``{...}`` as plain
  text), or a malformed ``{weight:TYPE:`` header;
* an empty alternative (``~~``, a trailing ``~``, ``{1:SA:}``) or a blank
  answer;
* a ``%...%`` prefix that is not a valid fraction, or a fraction outside
  [-100, 100];
* an unescaped ``#`` inside feedback (Moodle keeps it literally);
* an escaped backslash ``\\`` directly followed by ``}``, ``#`` or ``~``
  (Moodle's one-character lookbehind sees ``\}`` and would not end there);
* a NUMERICAL answer that is neither a number (with optional tolerance) nor
  ``*``;
* a subquestion without a correct answer (one at 100 %; for MULTIRESPONSE
  at least one positive fraction), and a MULTICHOICE/MULTIRESPONSE with
  fewer than two answers -- these two are Moodle's own validation rules.
"""
from __future__ import annotations

import html
import re
from dataclasses import dataclass, field

__all__ = ["ClozeError", "Answer", "Subquestion", "TYPES", "ALIASES", "ESCAPABLE",
           "parse", "unescape", "decode", "moodle_php_decode"]


class ClozeError(ValueError):
    """Malformed embedded-answers syntax."""


# Canonical type -> (family, layout, shuffle, case_sensitive); aliases as in
# Moodle's ANSWER_TYPE_DEF_REGEX.
TYPES: dict[str, tuple[str, str | None, bool, bool]] = {
    "SHORTANSWER": ("shortanswer", None, False, False),
    "SHORTANSWER_C": ("shortanswer", None, False, True),
    "NUMERICAL": ("numerical", None, False, False),
    "MULTICHOICE": ("multichoice", "dropdown", False, False),
    "MULTICHOICE_V": ("multichoice", "vertical", False, False),
    "MULTICHOICE_H": ("multichoice", "horizontal", False, False),
    "MULTICHOICE_S": ("multichoice", "dropdown", True, False),
    "MULTICHOICE_VS": ("multichoice", "vertical", True, False),
    "MULTICHOICE_HS": ("multichoice", "horizontal", True, False),
    "MULTIRESPONSE": ("multiresponse", "vertical", False, False),
    "MULTIRESPONSE_H": ("multiresponse", "horizontal", False, False),
    "MULTIRESPONSE_S": ("multiresponse", "vertical", True, False),
    "MULTIRESPONSE_HS": ("multiresponse", "horizontal", True, False),
}

ALIASES: dict[str, str] = {name: name for name in TYPES}
ALIASES.update({
    "SA": "SHORTANSWER", "MW": "SHORTANSWER",
    "SAC": "SHORTANSWER_C", "MWC": "SHORTANSWER_C",
    "NM": "NUMERICAL",
    "MC": "MULTICHOICE", "MCV": "MULTICHOICE_V", "MCH": "MULTICHOICE_H",
    "MCS": "MULTICHOICE_S", "MCVS": "MULTICHOICE_VS", "MCHS": "MULTICHOICE_HS",
    "MR": "MULTIRESPONSE", "MRH": "MULTIRESPONSE_H",
    "MRS": "MULTIRESPONSE_S", "MRHS": "MULTIRESPONSE_HS",
})

ESCAPABLE = frozenset('}#~/"\\')
_STRUCTURAL = frozenset("}#~")

_START = re.compile(r"\{(\d*):")
_HEADER = re.compile(r"\{(\d*):([^:{}~#\s]*):")
_LOOSE_HEADER = re.compile(r"\{(\d*):([^:{}~#]*):")
_CHARREF = re.compile(r"&(?:#[0-9]+|#[xX][0-9a-fA-F]+|[A-Za-z][A-Za-z0-9]*);")
_NUMREF_TAIL = re.compile(r"#(?:[0-9]+|[xX][0-9a-fA-F]+);")
_NUMBER = r"-?(?:[0-9]+[.,]?[0-9]*|[.,][0-9]+)(?:[eE][-+]?[0-9]+)?"
_NUMERICAL = re.compile(rf"({_NUMBER})(?::({_NUMBER}))?")
_FRACTION = re.compile(r"%(-?[0-9]+(?:[.,][0-9]*)?)%")
_FRACTION_LIKE = re.compile(r"%[-+0-9.,\s]*%")


@dataclass
class Answer:
    """One alternative: fraction in percent, decoded text and feedback.

    ``value``/``tolerance`` are set for NUMERICAL answers (None for ``*``)
    and None otherwise.  ``raw_text``/``raw_feedback`` keep the source as
    written (escapes and entities intact); they do not take part in ``==``.
    """
    fraction: float
    text: str
    feedback: str = ""
    value: float | None = None
    tolerance: float | None = None
    raw_text: str = field(default="", compare=False, repr=False)
    raw_feedback: str = field(default="", compare=False, repr=False)


@dataclass
class Subquestion:
    """One embedded answer ``{weight:TYPE:alternatives}``."""
    weight: int
    qtype: str
    answers: list[Answer]
    written_type: str = field(default="", compare=False)
    start: int = field(default=0, compare=False, repr=False)
    end: int = field(default=0, compare=False, repr=False)
    source: str = field(default="", compare=False, repr=False)

    @property
    def family(self) -> str:
        """'shortanswer', 'numerical', 'multichoice' or 'multiresponse'."""
        return TYPES[self.qtype][0]

    @property
    def layout(self) -> str | None:
        """'dropdown', 'vertical' or 'horizontal' for choices, else None."""
        return TYPES[self.qtype][1]

    @property
    def shuffle(self) -> bool:
        return TYPES[self.qtype][2]

    @property
    def case_sensitive(self) -> bool:
        return TYPES[self.qtype][3]

    @property
    def correct(self) -> list[Answer]:
        """The answers at 100 % (for MULTIRESPONSE: every positive one)."""
        if self.family == "multiresponse":
            return [a for a in self.answers if a.fraction > 0]
        return [a for a in self.answers if a.fraction == 100]


def unescape(text: str) -> str:
    """Undo the backslash escapes ``\\} \\# \\~ \\/ \\" \\\\`` (left to right).

    A backslash before any other character, or at the end, is kept.
    """
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "\\" and i + 1 < n and text[i + 1] in ESCAPABLE:
            out.append(text[i + 1])
            i += 2
        else:
            out.append(c)
            i += 1
    return "".join(out)


def decode(raw: str) -> str:
    """Raw answer/feedback source -> its text: escapes undone, entities decoded once.

    One pass: an escape pair gives its character, a character reference its
    character, ``&amp;`` followed by ``#123;`` gives ``&#123;``.
    """
    out = []
    i, n = 0, len(raw)
    while i < n:
        c = raw[i]
        if c == "\\" and i + 1 < n and raw[i + 1] in ESCAPABLE:
            out.append(raw[i + 1])
            i += 2
            continue
        if c == "&":
            m = _CHARREF.match(raw, i)
            if m:
                out.append(html.unescape(m.group()))
                i = m.end()
                if m.group() == "&amp;":
                    t = _NUMREF_TAIL.match(raw, i)
                    if t:
                        out.append(t.group())
                        i = t.end()
                continue
        out.append(c)
        i += 1
    return "".join(out)


def moodle_php_decode(raw: str) -> str:
    """What Moodle's PHP stores for a non-numerical answer or a feedback.

    ``html_entity_decode`` once, then only ``\\}`` -> ``}`` and ``\\#`` -> ``#``
    (other escapes keep their backslash).
    """
    return html.unescape(raw).replace("\\}", "}").replace("\\#", "#")


def _where(text: str, pos: int) -> str:
    line = text.count("\n", 0, pos) + 1
    snippet = text[max(0, pos - 20):pos + 30]
    return f"at offset {pos} (line {line}) near {snippet!r}"


def _scan_body(text: str, i: int, start: int) -> tuple[list[tuple[str, str | None, int]], int]:
    """Split the alternatives of the subquestion whose body starts at ``i``.

    Returns ([(raw answer incl. fraction, raw feedback or None, offset)], end)
    with ``end`` just past the closing brace.
    """
    n = len(text)
    alts: list[tuple[str, str | None, int]] = []
    answer: list[str] = []
    feedback: list[str] | None = None
    alt_start = i

    def current() -> list[str]:
        return answer if feedback is None else feedback

    def finish():
        alts.append(("".join(answer), None if feedback is None else "".join(feedback),
                     alt_start))

    while i < n:
        c = text[i]
        if c == "\\":
            nxt = text[i + 1] if i + 1 < n else ""
            if nxt in ESCAPABLE and nxt:
                if nxt == "\\" and i + 2 < n and text[i + 2] in _STRUCTURAL:
                    raise ClozeError(
                        f"escaped backslash '\\\\' directly before {text[i + 2]!r} "
                        f"{_where(text, i)}: Moodle reads '\\{text[i + 2]}' there as an "
                        f"escaped character; put something between them")
                current().append(c + nxt)
                i += 2
                continue
            current().append(c)
            i += 1
            continue
        if c == "&":
            m = _CHARREF.match(text, i)
            if m:
                current().append(m.group())
                i = m.end()
                if m.group() == "&amp;" and i < n and text[i] in _STRUCTURAL:
                    t = _NUMREF_TAIL.match(text, i)
                    if not t:
                        raise ClozeError(
                            f"{text[i]!r} directly after '&amp;' {_where(text, i)}: Moodle "
                            f"does not treat it as a delimiter; escape it or separate it")
                    current().append(t.group())
                    i = t.end()
                continue
            if i + 1 < n and text[i + 1] in _STRUCTURAL:
                raise ClozeError(
                    f"{text[i + 1]!r} directly after a bare '&' {_where(text, i)}: Moodle "
                    f"does not treat it as a delimiter; write '&amp;' or escape it")
            current().append(c)
            i += 1
            continue
        if c == "}":
            finish()
            return alts, i + 1
        if c == "~":
            finish()
            answer, feedback = [], None
            i += 1
            alt_start = i
            continue
        if c == "#":
            if feedback is None:
                feedback = []
                i += 1
                continue
            raise ClozeError(f"unescaped '#' in feedback {_where(text, i)}: write '\\#'")
        if c == "{" and (i == 0 or text[i - 1] != "\\") and _START.match(text, i):
            raise ClozeError(
                f"a new embedded answer opens {_where(text, i)} inside the one opened "
                f"{_where(text, start)}: unbalanced braces (missing '}}'?)")
        current().append(c)
        i += 1
    raise ClozeError(f"unterminated embedded answer {_where(text, start)}: "
                     f"unbalanced braces (no closing '}}')")


def _number(s: str) -> float:
    return float(s.replace(",", "."))


def _alternative(qtype: str, raw: str, raw_feedback: str | None, pos: int,
                 text: str) -> Answer:
    fraction = 0.0
    body = raw
    if body.startswith("="):
        fraction, body = 100.0, body[1:]
    elif body.startswith("%"):
        m = _FRACTION.match(body)
        if m:
            fraction = _number(m.group(1))
            body = body[m.end():]
            if not -100 <= fraction <= 100:
                raise ClozeError(f"fraction {m.group()} outside [-100, 100] "
                                 f"{_where(text, pos)}")
        elif _FRACTION_LIKE.match(body):
            raise ClozeError(f"malformed fraction {_FRACTION_LIKE.match(body).group()!r} "
                             f"{_where(text, pos)}: expected '%n%' with n a number, "
                             f"e.g. %50% or %-33.3%")
    if body == "":
        raise ClozeError(f"empty answer {_where(text, pos)}")
    feedback = "" if raw_feedback is None else decode(raw_feedback)
    answer_text = decode(body)
    if answer_text.strip() == "":
        raise ClozeError(f"blank answer {body!r} {_where(text, pos)}")
    value = tolerance = None
    if qtype == "NUMERICAL":
        if body != "*":
            m = _NUMERICAL.fullmatch(body)
            if not m:
                part, _, tol = body.partition(":")
                what = ("value" if not re.fullmatch(_NUMBER, part)
                        else "tolerance")
                raise ClozeError(
                    f"NUMERICAL answer {body!r} {_where(text, pos)}: its {what} "
                    f"{(part if what == 'value' else tol)!r} is not a number "
                    f"(expected value or value:tolerance, e.g. 23.8:0.1, or *)")
            value = _number(m.group(1))
            tolerance = _number(m.group(2)) if m.group(2) is not None else 0.0
    return Answer(fraction, answer_text, feedback, value, tolerance,
                  raw_text=body, raw_feedback=raw_feedback or "")


def _validate(sub: Subquestion, text: str) -> None:
    where = _where(text, sub.start)
    if sub.family in ("multichoice", "multiresponse") and len(sub.answers) < 2:
        raise ClozeError(f"{sub.qtype} {where} needs at least two answers, "
                         f"got {len(sub.answers)}")
    if not sub.correct:
        need = "a positive fraction" if sub.family == "multiresponse" else "'=' or '%100%'"
        raise ClozeError(f"{sub.qtype} {where} has no correct answer (none with {need})")


def _check_text_braces(text: str, spans: list[tuple[int, int]]) -> None:
    depth, opened = 0, []
    bounds = [(0, 0)] + spans + [(len(text), len(text))]
    for (_, a), (b, _) in zip(bounds, bounds[1:]):
        for i in range(a, b):
            c = text[i]
            if c not in "{}" or (i > 0 and text[i - 1] == "\\"):
                continue
            if c == "{":
                opened.append(i)
                depth += 1
            else:
                if depth == 0:
                    raise ClozeError(f"unbalanced braces: stray '}}' {_where(text, i)}")
                opened.pop()
                depth -= 1
    if opened:
        raise ClozeError(f"unbalanced braces: '{{' never closed {_where(text, opened[-1])}")


def parse(text: str, *, check_text_braces: bool = True) -> list[Subquestion]:
    """Every embedded answer of ``text`` (HTML), in order.

    Raises ``ClozeError`` on malformed syntax (see the module docstring).
    A text without embedded answers gives ``[]`` (Moodle refuses such a
    Cloze question; callers assert what they expect).
    """
    subs: list[Subquestion] = []
    i, n = 0, len(text)
    while i < n:
        j = text.find("{", i)
        if j < 0:
            break
        if (j > 0 and text[j - 1] == "\\") or not _START.match(text, j):
            i = j + 1
            continue
        h = _HEADER.match(text, j)
        if not h:
            loose = _LOOSE_HEADER.match(text, j)
            if loose:
                raise ClozeError(f"unknown type {loose.group(2)!r} {_where(text, j)}: "
                                 f"no spaces are allowed in '{{weight:TYPE:'")
            raise ClozeError(f"malformed embedded answer {_where(text, j)}: "
                             f"expected '{{weight:TYPE:answers}}'")
        written = h.group(2)
        if written not in ALIASES:
            hint = (f" (types are upper case: {written.upper()!r})"
                    if written.upper() in ALIASES else "")
            raise ClozeError(f"unknown type {written!r} {_where(text, j)}{hint}; known: "
                             + ", ".join(sorted(ALIASES)))
        qtype = ALIASES[written]
        raw_alts, end = _scan_body(text, h.end(), j)
        answers = [_alternative(qtype, raw, fb, pos, text) for raw, fb, pos in raw_alts]
        weight = int(h.group(1)) if h.group(1) else 1
        sub = Subquestion(weight, qtype, answers, written_type=written,
                          start=j, end=end, source=text[j:end])
        _validate(sub, text)
        subs.append(sub)
        i = end
    if check_text_braces:
        _check_text_braces(text, [(s.start, s.end) for s in subs])
    return subs
