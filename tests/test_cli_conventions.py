"""Command-line conventions: help with examples, --version, '-' for standard
input, --quiet, --traceback, exit codes, colour only on a terminal, -o, --lang,
init, schema and validate."""
from __future__ import annotations

import json
import os
import subprocess
import sys

import click
import pytest
from click.testing import CliRunner

from linkcli import __version__
from linkcli.cli import cli, main
from linkcli.errors import InputError

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_helpers import run  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLES = os.path.join(ROOT, "docs", "examples")
MECH = os.path.join(ROOT, "mechanisms", "padova-2020-07.yaml")
ESC = "\x1b["


def example(name):
    return os.path.join(EXAMPLES, name)


# --- help, version ----------------------------------------------------------------------
@pytest.mark.parametrize("command", sorted(cli.commands))
def test_every_command_has_help_with_examples(command):
    code, out, _ = run([command, "--help"])
    assert code == 0
    assert "Example" in out and f"linkcli {command}" in out, out


def test_top_help_lists_exit_codes_and_version():
    code, out, _ = run(["--help"])
    assert code == 0
    for line in ("0  success", "1  linkcli check", "2  invalid input", "3  the mechanism cannot"):
        assert line in out
    code, out, _ = run(["--version"])
    assert code == 0 and out.strip() == f"linkcli, version {__version__}"


# --- standard input -----------------------------------------------------------------------
@pytest.mark.parametrize("args", [["solve"], ["solve", "--format", "json"], ["explain"],
                                  ["batch", "--k", "1,2"], ["validate"], ["check"]])
def test_dash_reads_standard_input(args):
    text = open(MECH, encoding="utf-8").read()
    by_file = run(args[:1] + [MECH] + args[1:])
    by_stdin = run(args[:1] + ["-"] + args[1:], stdin=text)
    assert by_file[0] == by_stdin[0] == 0
    assert by_stdin[1] == by_file[1].replace(MECH, "<stdin>")


def test_standard_input_errors_name_stdin():
    code, _, err = run(["solve", "-"], stdin="frame: [1, 2\n")
    assert code == 2
    assert err.startswith("linkcli: error: <stdin>:")


# --- exit codes -----------------------------------------------------------------------------
@pytest.mark.parametrize("args, status", [
    (["solve", MECH], 0),
    (["check", example("wrong-key.yaml")], 1),
    (["solve", example("negative-length.yaml")], 2),
    (["solve", MECH, "--format", "xml"], 2),
    (["solve", example("short-coupler.yaml")], 3),
    (["validate", example("mobility-two.yaml")], 3),
])
def test_exit_codes(args, status):
    code, out, err = run(args)
    assert code == status, out + err
    if status in (2, 3) and args[0] == "solve":
        assert len(err.strip().splitlines()) == 1 or "Usage:" in err, err


def test_traceback_shows_the_exception_anywhere_on_the_line():
    for args in (["--traceback", "solve", example("negative-length.yaml")],
                 ["solve", example("negative-length.yaml"), "--traceback"]):
        with pytest.raises(InputError):
            main(args)


# --- quiet ------------------------------------------------------------------------------------
def test_quiet_keeps_only_results_and_problems(tmp_path):
    assert run(["--quiet", "validate", MECH]) == (0, "", "")
    assert run(["validate", MECH, "--quiet"]) == (0, "", "")
    code, out, _ = run(["-q", "validate", MECH, example("negative-length.yaml")])
    assert code == 2
    assert out.splitlines() == [f"{example('negative-length.yaml')}:11, key 'links.BC.length': "
                                "must be positive, got -150"]
    code, out, _ = run(["-q", "check", MECH])
    assert code == 0 and out.splitlines() == ["17 passed, 0 failed"]
    code, out, _ = run(["-q", "check", example("wrong-key.yaml")])
    assert code == 1 and out.splitlines()[0].startswith("FAIL ")
    code, out, err = run(["-q", "init", tmp_path / "m.yaml"])
    assert (code, out, err) == (0, "", "")
    code, _, err = run(["-q", "solve", example("negative-length.yaml")])
    assert code == 2 and "must be positive" in err


# --- colour ------------------------------------------------------------------------------------
def test_colour_only_on_a_terminal(monkeypatch):
    monkeypatch.delenv("NO_COLOR", raising=False)
    runner = CliRunner()
    bad = example("negative-length.yaml")
    terminal = runner.invoke(cli, ["validate", MECH, bad], color=True)
    assert ESC + "32m" in terminal.output and ESC + "31m" in terminal.output   # OK, FAIL
    plain = runner.invoke(cli, ["validate", MECH, bad], color=False)
    assert ESC not in plain.output and "OK " in plain.output and "FAIL " in plain.output
    monkeypatch.setenv("NO_COLOR", "1")
    no_color = runner.invoke(cli, ["validate", MECH, bad], color=True)
    assert ESC not in no_color.output


def test_piped_output_and_errors_are_plain():
    code = "import sys; from linkcli.cli import main; sys.exit(main(sys.argv[1:]))"
    env = {k: v for k, v in os.environ.items() if k != "NO_COLOR"}
    done = subprocess.run([sys.executable, "-c", code, "check", example("wrong-key.yaml"),
                           example("negative-length.yaml")], cwd=ROOT, capture_output=True,
                          text=True, env=env)
    assert done.returncode == 1
    assert "FAIL " in done.stdout and ESC not in done.stdout + done.stderr


def test_error_prefix_is_red_on_a_terminal(monkeypatch):
    monkeypatch.delenv("NO_COLOR", raising=False)
    seen = []
    monkeypatch.setattr(click, "echo", lambda text="", err=False, **kw: seen.append(text))
    assert main(["solve", example("negative-length.yaml")]) == 2
    assert seen[-1].startswith(f"linkcli: {ESC}31m") and "must be positive" in seen[-1]


# --- output files, languages ------------------------------------------------------------
@pytest.mark.parametrize("args", [["solve", MECH], ["solve", MECH, "--format", "csv"],
                                  ["batch", MECH, "--k", "0-1"], ["explain", MECH], ["schema"]])
def test_dash_o_writes_what_stdout_would_show(args, tmp_path):
    target = tmp_path / "out.txt"
    code, shown, _ = run(args)
    assert code == 0
    assert run(args + ["-o", target]) == (0, "", "")
    assert target.read_text(encoding="utf-8") == shown


def test_exam_headings_in_italian_and_english():
    _, italian, _ = run(["solve", MECH, "--lang", "it"])
    for heading in ("Analisi Cinematica di POSIZIONE", "Analisi Cinematica di VELOCITA'",
                    "Analisi STATICA"):
        assert heading in italian.splitlines()
    _, english, _ = run(["solve", MECH])
    assert "Position analysis" in english and "POSIZIONE" not in english
    assert [x.split("=")[-1] for x in italian.splitlines() if "=" in x] == \
        [x.split("=")[-1] for x in english.splitlines() if "=" in x]


# --- init, schema --------------------------------------------------------------------------
def test_init_writes_a_template_that_validates_and_solves(tmp_path):
    path = tmp_path / "exam.yaml"
    code, out, _ = run(["init", path])
    assert code == 0 and "wrote" in out
    text = path.read_text(encoding="utf-8")
    assert text.count("#") > 20, "the template explains its sections in comments"
    assert run(["validate", path])[0] == 0
    code, out, _ = run(["solve", path, "--format", "json"])
    assert code == 0 and json.loads(out)["values"]
    code, _, err = run(["init", path])
    assert code == 2 and "file exists" in err
    path.write_text("changed", encoding="utf-8")
    assert run(["init", path, "--force"])[0] == 0
    assert path.read_text(encoding="utf-8") == text
    code, out, _ = run(["init", "-"])
    assert code == 0 and out == text


def test_schema_prints_the_packaged_schema():
    code, out, _ = run(["schema"])
    assert code == 0
    packaged = json.load(open(os.path.join(ROOT, "linkcli", "input", "schema.json"), encoding="utf-8"))
    assert json.loads(out) == packaged


# --- validate --------------------------------------------------------------------------------
def test_validate_reports_every_problem_with_line_and_key():
    code, out, _ = run(["validate", example("bad-bodies.yaml")])
    assert code == 2
    problems = [x for x in out.splitlines() if x.startswith(example("bad-bodies.yaml") + ":")]
    assert len(problems) == 23
    assert all(", key '" in x for x in problems)
    assert out.splitlines()[-1].endswith("bad-bodies.yaml: 23 problems")
    lines = [int(x.split(":")[1].split(",")[0]) for x in problems]
    assert lines == sorted(lines)


def test_validate_finds_problems_of_other_digits(tmp_path):
    path = tmp_path / "k.yaml"
    text = open(MECH, encoding="utf-8").read().replace(
        "units:", "k: 2\nparams: {r: sqrt(4 - k)}\nunits:")
    path.write_text(text, encoding="utf-8")
    assert run(["solve", path])[0] == 0                   # fine for the file's k = 2
    code, out, _ = run(["validate", path])
    assert code == 2
    assert "out of its domain" in out and "[k = 5, 6, 7, 8, 9]" in out
    assert run(["validate", path, "--k", "3"])[0] == 0


def test_validate_status_is_the_worst_of_its_files():
    assert run(["validate", MECH, example("mobility-two.yaml")])[0] == 3
    assert run(["validate", example("mobility-two.yaml"), example("empty.yaml"), MECH])[0] == 2


# --- hostile files are refused within bounded time ------------------------------------------
def test_a_file_over_the_size_limit_is_refused(tmp_path):
    path = tmp_path / "big.yaml"
    path.write_text("title: " + "x" * 1_000_001 + "\n", encoding="utf-8")
    code, _, err = run(["validate", path])
    assert code == 2
    code, _, err = run(["solve", path])
    assert code == 2 and "file is larger than 1000 kB" in err
    code, _, err = run(["solve", "-"], stdin="x" * 1_000_001)
    assert code == 2 and "input is larger than 1000 kB" in err


def test_too_many_values_are_refused(tmp_path):
    code, _, err = run(["solve", "-"], stdin="[" + ",".join(["1"] * 60_000) + "]")
    assert code == 2 and "document has more than 50000 values" in err
