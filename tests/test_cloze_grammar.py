"""Tests of the independent Cloze (embedded answers) parser in cloze_grammar.py.

The valid examples follow the syntax of Moodle's documentation page "Embedded
Answers (Cloze) question type" (docs.moodle.org/en/Cloze); the states/capitals
and Warsaw/Poland examples are those of university course pages that reproduce
it (wnpspt.waseda.jp, ecampus.polytechnic.wa.edu.au).  The invalid ones are the
malformations the parser must refuse.
"""
from __future__ import annotations

import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(__file__))

from cloze_grammar import (ALIASES, TYPES, Answer, ClozeError, Subquestion,  # noqa: E402
                           decode, moodle_php_decode, parse, unescape)


# --- valid: examples of the documentation --------------------------------------------

def test_numerical_with_tolerance_and_half_credit():
    text = ("<p>23.8 is {2:NUMERICAL:=23.8:0.1#Feedback for correct answer 23.8"
            "~%50%23.8:2#Feedback for half credit answer in the nearby of the correct "
            "answer}</p>")
    (sub,) = parse(text)
    assert sub == Subquestion(2, "NUMERICAL", [
        Answer(100, "23.8:0.1", "Feedback for correct answer 23.8", 23.8, 0.1),
        Answer(50, "23.8:2", "Feedback for half credit answer in the nearby of the "
                             "correct answer", 23.8, 2.0),
    ])
    assert sub.family == "numerical" and sub.correct == sub.answers[:1]
    assert text[sub.start:sub.end] == sub.source and sub.source.startswith("{2:NUMERICAL:")


def test_numerical_forms_of_number_regex():
    (a, b, c, d), = [s.answers for s in parse(
        "{1:NM:=-1,5e3:0,25~%50%.5~%25%7.:1E-2#near~*#anything else}")]
    assert (a.value, a.tolerance) == (-1500.0, 0.25)          # comma as decimal mark
    assert (b.fraction, b.value, b.tolerance) == (50, 0.5, 0.0)   # tolerance 0 when omitted
    assert (c.value, c.tolerance, c.feedback) == (7.0, 0.01, "near")
    assert (d.text, d.value, d.tolerance, d.fraction) == ("*", None, None, 0)


def test_multichoice_states_with_partial_credit_and_feedback():
    text = ("San Francisco: {1:MULTICHOICE:=California#OK~Arizona#Incorrect}<br>"
            "Tucson: {1:MULTICHOICE:California#Incorrect~%100%Arizona#OK}<br>"
            "Phoenix: {1:MULTICHOICE:%0%California#Incorrect~=Arizona#OK}<br>"
            "Capital of France is {2:SHORTANSWER:%100%Paris#Congratulation!"
            "~%50%Marseille#No, it's the second largest city in France"
            "~*#Incorrect The capital of France is Paris.}")
    subs = parse(text)
    assert [s.qtype for s in subs] == ["MULTICHOICE"] * 3 + ["SHORTANSWER"]
    assert [s.weight for s in subs] == [1, 1, 1, 2]
    assert [(a.fraction, a.text, a.feedback) for a in subs[1].answers] == [
        (0, "California", "Incorrect"), (100, "Arizona", "OK")]
    assert [(a.fraction, a.text) for a in subs[3].answers] == [
        (100, "Paris"), (50, "Marseille"), (0, "*")]
    assert subs[3].answers[2].feedback == "Incorrect The capital of France is Paris."
    assert all(a.value is None and a.tolerance is None for s in subs for a in s.answers)


def test_vertical_multichoice_with_three_kinds_of_fraction():
    (sub,) = parse("Which country: {1:MCV:%50%Warsaw#No, a city~%100%Poland#yes, that is "
                   "correct~Austria#Nope}")
    assert sub.qtype == "MULTICHOICE_V" and sub.layout == "vertical" and not sub.shuffle
    assert [a.fraction for a in sub.answers] == [50, 100, 0]


def test_short_answer_with_escaped_brace_tilde_and_hash():
    (sub,) = parse(r"{1:SA:=f(x) = \{x\}\~1 \#2#set \} and \~ and \# in feedback"
                   r"~%-25%a\/b \"c\" d\\e#minus}")
    first, second = sub.answers
    assert first.text == "f(x) = \\{x}~1 #2"             # "\{" is not an escape: kept
    assert first.feedback == "set } and ~ and # in feedback"
    assert first.raw_text == r"f(x) = \{x\}\~1 \#2"
    assert (second.fraction, second.text, second.feedback) == (-25, 'a/b "c" d\\e', "minus")


def test_weight_defaults_to_one_and_may_be_zero():
    assert [s.weight for s in parse("{:SA:=x} {0:SA:=y} {12:SA:=z}")] == [1, 0, 12]


@pytest.mark.parametrize("written, canonical", sorted(ALIASES.items()))
def test_every_type_and_alias_maps_to_its_canonical_name(written, canonical):
    answers = "=1~2" if TYPES[canonical][0] != "numerical" else "=1:0.5"
    (sub,) = parse(f"{{3:{written}:{answers}}}")
    assert (sub.qtype, sub.written_type, sub.weight) == (canonical, written, 3)


@pytest.mark.parametrize("written, layout, shuffle, family", [
    ("MC", "dropdown", False, "multichoice"), ("MCS", "dropdown", True, "multichoice"),
    ("MULTICHOICE_H", "horizontal", False, "multichoice"),
    ("MCHS", "horizontal", True, "multichoice"), ("MCVS", "vertical", True, "multichoice"),
    ("MR", "vertical", False, "multiresponse"), ("MRHS", "horizontal", True, "multiresponse"),
])
def test_multichoice_variants(written, layout, shuffle, family):
    (sub,) = parse(f"{{1:{written}:=A#good~B#bad~%50%C}}")
    assert (sub.layout, sub.shuffle, sub.family) == (layout, shuffle, family)
    assert [a.text for a in sub.answers] == ["A", "B", "C"]


def test_multiresponse_needs_only_positive_fractions():
    (sub,) = parse("{2:MULTIRESPONSE:%50%red~%50%blue~%-100%green}")
    assert [a.fraction for a in sub.correct] == [50, 50]
    assert parse("{1:SAC:=Moodle}")[0].case_sensitive
    assert not parse("{1:SA:=Moodle}")[0].case_sensitive


def test_decimal_fractions_with_point_or_comma():
    (sub,) = parse("{1:MC:=a~%33.3%b~%33,5%c~%-12.%d}")
    assert [a.fraction for a in sub.answers] == [100, 33.3, 33.5, -12]


def test_html_entities_in_answers_and_feedback():
    (sub,) = parse("{1:MC:=caf&eacute;#d&#039;accord~&#8364;5 &amp; more#price in &#x20AC;"
                   "~&#125; brace~&amp;#35; double}")
    assert [a.text for a in sub.answers] == ["café", "€5 & more", "} brace", "&#35; double"]
    assert [a.feedback for a in sub.answers] == ["d'accord", "price in €", "", ""]


def test_html_around_subquestions_placeholders_and_latex_are_text():
    text = ("<p>\\(x^{2}\\) and {#1} and &#123;1:NUMERICAL:=666&#125; are text; "
            "{1:SA:=<b>bold</b>#see <a href=\"/x\">link</a>}</p>\n<p>{1:NM:=2}</p>")
    subs = parse(text)
    assert [s.qtype for s in subs] == ["SHORTANSWER", "NUMERICAL"]
    assert subs[0].answers[0] == Answer(100, "<b>bold</b>", 'see <a href="/x">link</a>')


def test_answers_and_feedback_may_span_lines():
    (sub,) = parse("{1:MC:=first\nline#multi\nline feedback~second}")
    assert sub.answers[0].text == "first\nline"
    assert sub.answers[0].feedback == "multi\nline feedback"


def test_empty_feedback_and_no_embedded_answers():
    (sub,) = parse("{1:SA:=yes#~no#}")
    assert [a.feedback for a in sub.answers] == ["", ""]
    assert parse("<p>No boxes, {#1} only</p>") == []


def test_unescape_decode_and_moodle_php_decode():
    assert unescape(r'\}\#\~\/\"\\') == '}#~/"\\'
    assert unescape(r"\n \{ end\\") == r"\n \{ end" + "\\"
    assert unescape("\\\\}") == "\\}"                     # left to right
    assert decode(r"&lt;\}&gt;") == "<}>"
    assert moodle_php_decode(r"a\}b\#c\~d&amp;") == r"a}b#c\~d&"


# --- invalid ---------------------------------------------------------------------------

@pytest.mark.parametrize("text, message", [
    ("{1:SA:=open", "unterminated"),
    ("{1:SA:=a {1:NM:=2}", "inside the one"),
    ("{1:SA:=a}}", "stray '}'"),
    ("<p>{ {1:SA:=a}</p>", "never closed"),
    ("{1:SHORT:=a}", "unknown type 'SHORT'"),
    ("{1:sa:=a}", "upper case"),
    ("{1: SA :=a}", "no spaces"),
    ("{1:SA=a}", "malformed embedded answer"),
])
def test_unbalanced_braces_and_bad_headers(text, message):
    with pytest.raises(ClozeError, match=message):
        parse(text)


def test_text_brace_check_can_be_skipped():
    assert len(parse("a lone { and {1:SA:=x}", check_text_braces=False)) == 1


@pytest.mark.parametrize("text, message", [
    ("{1:NUMERICAL:=abc}", "value 'abc' is not a number"),
    ("{1:NM:=2:x}", "tolerance 'x' is not a number"),
    ("{1:NM:=2:}", "tolerance '' is not a number"),
    ("{1:NM:=1.5.2}", "value '1.5.2' is not a number"),
    ("{1:NM:= 2}", "is not a number"),
    ("{1:NM:=+2}", "is not a number"),
    ("{1:NM:=2~%50%two}", "value 'two'"),
])
def test_numerical_answers_must_be_numbers(text, message):
    with pytest.raises(ClozeError, match=message):
        parse(text)


@pytest.mark.parametrize("text", [
    "{1:MC:a~b}", "{1:SA:%50%Paris~Lyon}", "{1:NM:%99%3:1}",
    "{1:MR:%0%a~%-50%b}", "{1:SA:%100x%y}",
])
def test_a_correct_answer_is_required(text):
    with pytest.raises(ClozeError, match="no correct answer"):
        parse(text)


@pytest.mark.parametrize("text, message", [
    ("{1:MC:=only}", "at least two answers"),
    ("{1:MC:=a~~b}", "empty answer"),
    ("{1:MC:=a~b~}", "empty answer"),
    ("{1:SA:}", "empty answer"),
    ("{1:SA:=#fb}", "empty answer"),
    ("{1:SA:= }", "blank answer"),
    ("{1:MC:=a~%+50%b}", "malformed fraction"),
    ("{1:MC:=a~% 50%b}", "malformed fraction"),
    ("{1:MC:=a~%150%b}", "outside"),
])
def test_empty_alternatives_and_bad_fractions(text, message):
    with pytest.raises(ClozeError, match=message):
        parse(text)


@pytest.mark.parametrize("text, message", [
    ("{1:SA:=a#see # here}", "unescaped '#' in feedback"),
    ("{1:SA:=a\\\\}b}", "escaped backslash"),
    ("{1:MC:=R&~D}", "bare '&'"),
    ("{1:MC:=R&amp;~D}", "after '&amp;'"),
])
def test_unescaped_or_ambiguous_special_characters(text, message):
    with pytest.raises(ClozeError, match=message):
        parse(text)


def test_errors_say_where():
    with pytest.raises(ClozeError, match=r"offset 15 \(line 2\) near 'ok\\ntext: "):
        parse("ok\ntext: {1:NM:=x}")
