"""Every command example in README.md and docs/*.md runs as documented.

In a fenced block marked ``sh``, ``shell``, ``console`` or ``bash``:

* a line ``linkcli ARGS`` or ``$ linkcli ARGS`` is run (in-process, from a
  scratch folder that sees the repository's ``mechanisms/``, ``docs/`` and
  ``tests/``; the commands of one document share that folder, in order);
* a trailing ``# exit N`` states the expected exit status (default 0); other
  ``# ...`` comments are ignored;
* ``< FILE`` feeds standard input, ``> FILE`` saves standard output, ``A && B``
  runs both, and ``| ...`` is ignored (the status is linkcli's);
* after a ``$ linkcli`` line, the lines up to the next ``$`` line are its
  expected output: each must appear, in this order, among the lines printed
  (standard output, then standard error).
"""
from __future__ import annotations

import contextlib
import glob
import io
import os
import re
import shlex
import sys
from dataclasses import dataclass, field

import pytest

from linkcli.cli import main

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOCS = [os.path.join(ROOT, "README.md")] + sorted(glob.glob(os.path.join(ROOT, "docs", "*.md")))
SHELLS = {"sh", "shell", "console", "bash"}
EXIT = re.compile(r"#\s*exit\s+(\d+)\s*$")


@dataclass
class Example:
    line: int
    command: str
    exit_code: int = 0
    output: list = field(default_factory=list)
    check_output: bool = False


def examples(path: str) -> list[Example]:
    """The command examples of one markdown file, in order."""
    found: list[Example] = []
    fence = None
    current = None
    for number, raw in enumerate(open(path, encoding="utf-8"), 1):
        line = raw.rstrip("\n")
        stripped = line.strip()
        if stripped.startswith("```"):
            if fence is None:
                fence = stripped[3:].strip().lower() or "text"
            else:
                fence, current = None, None
            continue
        if fence not in SHELLS:
            continue
        prompt = stripped.startswith("$ ")
        text = stripped[2:].strip() if prompt else stripped
        if text.startswith("linkcli ") or text == "linkcli":
            match = EXIT.search(text)
            current = Example(number, text, int(match.group(1)) if match else 0,
                              check_output=prompt)
            found.append(current)
        elif prompt:
            current = None
        elif current is not None and current.check_output and stripped:
            current.output.append(line.rstrip())
    return found


def run_command(command: str) -> tuple[int, str, str]:
    """Run one documented command line; returns (status, stdout, stderr)."""
    tokens = shlex.split(command, comments=True)
    if "|" in tokens:
        tokens = tokens[:tokens.index("|")]
    chains, part = [], []
    for token in tokens + ["&&"]:
        if token == "&&":
            chains.append(part)
            part = []
        else:
            part.append(token)
    status, out, err = 0, "", ""
    for part in chains:
        status, o, e = _run_one(part)
        out, err = out + o, err + e
        if status:
            break
    return status, out, err


def _run_one(tokens: list[str]) -> tuple[int, str, str]:
    assert tokens and tokens[0] == "linkcli", tokens
    args, stdin, target = [], "", None
    rest = iter(tokens[1:])
    for token in rest:
        if token == "<":
            stdin = open(next(rest), encoding="utf-8").read()
        elif token == ">":
            target = next(rest)
        elif any(c in token for c in "*?["):
            args += sorted(glob.glob(token)) or [token]
        else:
            args.append(token)
    out, err = io.StringIO(), io.StringIO()
    saved = sys.stdin
    sys.stdin = io.StringIO(stdin)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            status = main(args)
    finally:
        sys.stdin = saved
    if target:
        with open(target, "w", encoding="utf-8") as handle:
            handle.write(out.getvalue())
        return status, "", err.getvalue()
    return status, out.getvalue(), err.getvalue()


def _in_order(expected: list[str], actual: list[str]) -> str | None:
    """None when every expected line appears in ``actual`` in order, else the first missing."""
    position = 0
    for want in expected:
        while position < len(actual) and actual[position] != want:
            position += 1
        if position == len(actual):
            return want
        position += 1
    return None


@pytest.mark.parametrize("path", DOCS, ids=lambda p: os.path.relpath(p, ROOT))
def test_documented_commands(path, tmp_path, monkeypatch):
    found = examples(path)
    if not found:
        pytest.skip("no command examples")
    for name in ("mechanisms", "docs", "tests"):
        os.symlink(os.path.join(ROOT, name), tmp_path / name)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("NO_COLOR", "1")
    for example in found:
        status, out, err = run_command(example.command)
        where = f"{os.path.relpath(path, ROOT)}:{example.line}: {example.command}"
        assert status == example.exit_code, \
            f"{where}\nexit {status}, documented {example.exit_code}\n{out}\n{err}"
        missing = _in_order(example.output, [x.rstrip() for x in
                                             (out.splitlines() + err.splitlines())])
        assert missing is None, f"{where}\ndocumented line not printed: {missing!r}\n" \
                                f"printed:\n{out}{err}"


def test_the_example_format_is_read_as_documented(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("text\n```sh\n$ linkcli solve x.yaml   # exit 2\nlinkcli: error: x\n\n"
                    "$ ls\nignored\nlinkcli validate a.yaml\n```\n```yaml\nlinkcli solve y\n```\n")
    found = examples(str(page))
    assert [(e.command, e.exit_code, e.output) for e in found] == [
        ("linkcli solve x.yaml   # exit 2", 2, ["linkcli: error: x"]),
        ("linkcli validate a.yaml", 0, []),
    ]
    assert _in_order(["a", "c"], ["a", "b", "c"]) is None
    assert _in_order(["c", "a"], ["a", "b", "c"]) == "a"
