"""Safe YAML loading that remembers where every value came from.

The document is composed into nodes with PyYAML's safe loader, then turned into
plain Python data while recording the line of every key (``lines``) and the
original text of every scalar (``raw``; answer keys are compared at their
printed precision).  Anchors and aliases are refused: mechanism files do not
need them and they are the way to build alias bombs.  Size, depth and node
count are bounded.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import yaml

from .errors import InputError

MAX_BYTES = 1_000_000
MAX_NODES = 200_000
MAX_DEPTH = 40

Path = tuple


@dataclass
class Document:
    """Plain data of a YAML file plus the source position of each path."""

    name: str
    data: object
    lines: dict = field(default_factory=dict)
    raw: dict = field(default_factory=dict)

    def line(self, path: Path) -> int | None:
        """Line of ``path``, or of its nearest ancestor that has one."""
        path = tuple(path)
        while path:
            if path in self.lines:
                return self.lines[path]
            path = path[:-1]
        return None


def path_text(path: Path) -> str:
    out = ""
    for part in path:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def load_text(text: str, name: str) -> Document:
    if len(text.encode("utf-8", "replace")) > MAX_BYTES:
        raise InputError(f"file is larger than {MAX_BYTES // 1000} kB", file=name)
    try:
        node = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark
        line = mark.line + 1 if mark else None
        raise InputError(f"YAML syntax error: {exc.problem}", file=name, line=line,
                         hint="check indentation and the ':' after each key") from None
    except yaml.YAMLError as exc:
        raise InputError(f"YAML error: {exc}", file=name) from None
    except RecursionError:
        raise InputError("YAML nesting is too deep", file=name) from None
    doc = Document(name, None)
    if node is None:
        raise InputError("file is empty", file=name, hint="start from 'linkcli init'")
    builder = _Builder(doc)
    doc.data = builder.build(node, (), 0)
    return doc


def load_file(path: str) -> Document:
    if path == "-":
        import sys
        return load_text(sys.stdin.read(), "<stdin>")
    try:
        with open(path, "rb") as handle:
            blob = handle.read(MAX_BYTES + 1)
    except OSError as exc:
        raise InputError(f"cannot read file: {exc.strerror}", file=path) from None
    try:
        text = blob.decode("utf-8")
    except UnicodeDecodeError:
        raise InputError("file is not UTF-8 text", file=path) from None
    return load_text(text, path)


class _Builder:
    def __init__(self, doc: Document):
        self.doc = doc
        self.count = 0
        self.constructor = yaml.SafeLoader("")  # resolves scalar tags safely
        self.seen: set[int] = set()

    def fail(self, detail: str, node) -> InputError:
        return InputError(detail, file=self.doc.name, line=node.start_mark.line + 1)

    def build(self, node, path: Path, depth: int):
        self.count += 1
        if self.count > MAX_NODES:
            raise self.fail(f"document has more than {MAX_NODES} values", node)
        if depth > MAX_DEPTH:
            raise self.fail(f"document nested deeper than {MAX_DEPTH} levels", node)
        if id(node) in self.seen:
            raise self.fail("YAML anchors and aliases are not supported", node)
        self.seen.add(id(node))
        if isinstance(node, yaml.ScalarNode):
            self.doc.raw[path] = node.value
            try:
                return self.constructor.construct_object(node, deep=True)
            except (yaml.YAMLError, ValueError, OverflowError):
                return node.value
        if isinstance(node, yaml.SequenceNode):
            return [self.build(item, path + (i,), depth + 1) for i, item in enumerate(node.value)]
        result = {}
        for key_node, value_node in node.value:
            if not isinstance(key_node, yaml.ScalarNode):
                raise self.fail("mapping keys must be plain names", key_node)
            key = str(key_node.value)
            if key == "<<":
                raise self.fail("YAML merge keys are not supported", key_node)
            if key in result:
                raise self.fail(f"duplicate key '{key}'", key_node)
            self.doc.lines[path + (key,)] = key_node.start_mark.line + 1
            result[key] = self.build(value_node, path + (key,), depth + 1)
        return result
