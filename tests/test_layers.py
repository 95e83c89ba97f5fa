"""The package's layers: imports go only downward and there is no import cycle.

Every ``import`` statement of every module is read from the source (at module
level and inside functions alike), resolved to a module of the package, and
checked against the layer each folder belongs to.
"""
from __future__ import annotations

import ast
import os
import textwrap

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PACKAGE = os.path.join(ROOT, "linkcli")

#: what each layer may import, besides itself
ALLOWED = {
    "errors": set(),
    "model": {"errors"},
    "input": {"errors", "model"},
    "kinematics": {"errors", "model"},
    "forces": {"errors", "model", "kinematics"},
    "answers": {"errors", "model", "input", "kinematics", "forces"},
    "runs": {"errors", "model", "input", "kinematics", "forces", "answers"},
    "texts": {"errors", "model", "input", "kinematics", "forces", "answers", "runs"},
    "pictures": {"errors", "model", "input", "kinematics", "forces", "answers", "runs", "texts"},
    "exports": {"errors", "model", "input", "kinematics", "forces", "answers", "runs", "texts",
                "pictures"},
    "api": {"errors", "model", "input", "kinematics", "forces", "answers", "runs"},
    "cli": {"errors", "model", "input", "kinematics", "forces", "answers", "runs", "texts",
            "pictures", "exports", "api", "package"},
    "package": {"errors", "api"},
}


def modules(package_dir: str, name: str) -> dict:
    """{dotted module name: path} of every .py file below ``package_dir``."""
    out = {}
    for folder, _, files in os.walk(package_dir):
        for f in files:
            if f.endswith(".py"):
                rel = os.path.relpath(os.path.join(folder, f), package_dir)[:-3].split(os.sep)
                if rel[-1] == "__init__":
                    rel = rel[:-1]
                out[".".join([name] + rel)] = os.path.join(folder, f)
    return out


def imports(path: str, module: str, is_package: bool, known: set) -> set:
    """The package modules that ``path`` imports anywhere in its body."""
    tree = ast.parse(open(path, encoding="utf-8").read(), path)
    base = module.split(".") if is_package else module.split(".")[:-1]
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            prefix = base[:len(base) - node.level + 1] if node.level else []
            stem = ".".join(prefix + ([node.module] if node.module else []))
            targets = [stem] + [f"{stem}.{alias.name}" for alias in node.names]
        else:
            continue
        for target in targets:
            while target and target not in known:
                target = target.rpartition(".")[0]
            if target and target != module:
                found.add(target)
    return found


def layer(module: str) -> str:
    parts = module.split(".")
    return "package" if len(parts) == 1 else parts[1]


def graph(package_dir: str, name: str) -> dict:
    mods = modules(package_dir, name)
    known = set(mods)
    return {m: imports(p, m, p.endswith("__init__.py"), known) for m, p in mods.items()}


def upward(edges: dict) -> list:
    """Imports that leave a layer for one it may not use."""
    bad = []
    for src, targets in edges.items():
        for dst in targets:
            a, b = layer(src), layer(dst)
            if a != b and b not in ALLOWED.get(a, set()):
                bad.append(f"{src} -> {dst} ({a} may not import {b})")
    return sorted(bad)


def cycles(edges: dict) -> list:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


def test_every_folder_is_a_known_layer():
    layers = {layer(m) for m in modules(PACKAGE, "linkcli")}
    assert layers <= set(ALLOWED), layers - set(ALLOWED)


def test_imports_go_only_down_the_layers():
    assert upward(graph(PACKAGE, "linkcli")) == []


def test_the_package_has_no_import_cycle():
    assert cycles(graph(PACKAGE, "linkcli")) == []


#: the most lines a module may hold: past it, a module has always held more than one concept
#: (the splits of the sweep, the statement, the limits, the command line and the solver)
LONGEST_MODULE = 700


def test_no_module_is_longer_than_one_concept_needs():
    long = {os.path.relpath(p, ROOT): n for p in modules(PACKAGE, "linkcli").values()
            if (n := sum(1 for _ in open(p, encoding="utf-8"))) > LONGEST_MODULE}
    assert long == {}, f"split these by concept (docs/architecture.md): {long}"


def stated_rule(folder: str) -> set:
    """The layers a folder's ``__init__.py`` says it may import (its ``May import:`` line);
    ``linkcli`` alone is the package's own ``__init__``."""
    import re
    text = ast.get_docstring(ast.parse(open(os.path.join(PACKAGE, folder, "__init__.py"),
                                            encoding="utf-8").read())) or ""
    match = re.search(r"May import:(.*?)(?:\.\s*$|\.\s*\n\s*\n)", text, re.S)
    assert match, f"linkcli/{folder}/__init__.py does not state what it may import"
    return {name or "package"
            for name in re.findall(r"``linkcli(?:\.(\w+))?``", match.group(1))}


@pytest.mark.parametrize("folder", sorted(
    d for d in os.listdir(PACKAGE) if os.path.isfile(os.path.join(PACKAGE, d, "__init__.py"))))
def test_each_folder_states_the_rule_that_is_enforced(folder):
    assert stated_rule(folder) == ALLOWED[folder]


def test_architecture_doc_states_the_rules_that_are_enforced():
    """The table of docs/architecture.md: a row per layer, its imports as enforced here."""
    import re
    text = open(os.path.join(ROOT, "docs", "architecture.md"), encoding="utf-8").read()
    rows = dict(re.findall(r"^\| `(\w+)` \| ([^|]*) \|$", text, re.M))
    stated = {name: set() if "nothing" in rule else set(re.findall(r"\w+", rule))
              for name, rule in rows.items() if name in ALLOWED}
    assert stated == {k: v for k, v in ALLOWED.items() if k != "package"}


def _fake_package(tmp_path, files: dict) -> str:
    root = tmp_path / "linkcli"
    for rel, text in files.items():
        path = root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))
    return str(root)


@pytest.mark.parametrize("files, expected", [
    # kinematics reaching up into input, inside a function
    ({"__init__.py": "", "input/__init__.py": "", "input/source.py": "",
      "kinematics/__init__.py": "",
      "kinematics/topology.py": "def f():\n    from linkcli.input.source import x\n"},
     "linkcli.kinematics.topology -> linkcli.input.source"),
    # forces importing answers with a relative import
    ({"__init__.py": "", "answers/__init__.py": "", "answers/quantities/__init__.py": "",
      "forces/__init__.py": "", "forces/balance.py": "from ..answers import quantities\n"},
     "linkcli.forces.balance -> linkcli.answers.quantities"),
])
def test_checker_catches_an_upward_import(tmp_path, files, expected):
    bad = upward(graph(_fake_package(tmp_path, files), "linkcli"))
    assert any(line.startswith(expected) for line in bad), bad


def test_checker_catches_a_cycle(tmp_path):
    root = _fake_package(tmp_path, {
        "__init__.py": "", "kinematics/__init__.py": "",
        "kinematics/a.py": "from linkcli.kinematics import b\n",
        "kinematics/b.py": "def g():\n    from . import c\n",
        "kinematics/c.py": "import linkcli.kinematics.a\n"})
    assert cycles(graph(root, "linkcli")) == [
        ["linkcli.kinematics.a", "linkcli.kinematics.b", "linkcli.kinematics.c"]]


def test_architecture_doc_lists_exactly_the_tree():
    """docs/architecture.md names every module of the package and no file that is gone."""
    import re
    text = open(os.path.join(ROOT, "docs", "architecture.md"), encoding="utf-8").read()
    named = set(re.findall(r"`(linkcli/[\w/.]+\.(?:py|json|yaml))`", text))
    missing_files = sorted(p for p in named if not os.path.exists(os.path.join(ROOT, p)))
    assert missing_files == [], f"named in docs/architecture.md but not in the tree: {missing_files}"
    tree = {os.path.relpath(p, ROOT).replace(os.sep, "/")
            for p in modules(PACKAGE, "linkcli").values()
            if not p.endswith(os.sep + "__init__.py") or os.path.dirname(p) == PACKAGE}
    assert sorted(tree - named) == [], "modules missing from docs/architecture.md"
