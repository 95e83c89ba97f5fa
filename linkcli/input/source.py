"""Safe YAML loading that remembers where every value came from.

The document is composed into nodes with PyYAML's safe loader, then turned into
plain Python data while recording the line of every key (``lines``) and the
original text of every scalar (``raw``; answer keys are compared at their
printed precision).  Anchors and aliases are refused: mechanism files do not
need them and they are the way to build alias bombs.  Size, depth and node
count are bounded while the document is composed, so a hostile file is refused
after reading at most ``MAX_BYTES`` and building at most ``MAX_NODES`` nodes.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import yaml

from linkcli.errors import InputError

MAX_BYTES = 1_000_000
MAX_NODES = 50_000
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
        node = _compose(text)
    except _Refused as exc:
        raise InputError(exc.detail, file=name, line=exc.line, hint=exc.hint) from None
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark else None
        what = f"{exc.context}: {exc.problem}" if exc.context else exc.problem
        raise InputError(f"YAML syntax error: {what}", file=name, line=line,
                         hint="check indentation and the ':' after each key") from None
    except yaml.YAMLError as exc:
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise InputError(f"YAML error: {first}", file=name,
                         hint="the file must be plain UTF-8 text") from None
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
        return load_text(_read_stdin(), STDIN)
    try:
        with open(path, "rb") as handle:
            blob = handle.read(MAX_BYTES + 1)
    except OSError as exc:
        raise InputError(f"cannot read file: {exc.strerror}", file=path) from None
    return load_text(_decode(blob, path, "file"), path)


STDIN = "<stdin>"


def _read_stdin() -> str:
    """Standard input as text: bytes decoded as UTF-8 when it has them (a closed or
    unreadable standard input, or bytes that are not UTF-8, are input errors)."""
    import sys
    stream = sys.stdin
    if stream is None:       # started with standard input closed ('<&-')
        raise InputError("cannot read standard input: it is closed", file=STDIN,
                         hint="give a file, or pipe the mechanism into 'linkcli ... -'")
    try:
        binary = getattr(stream, "buffer", None)
        if binary is not None:
            data = binary.read(MAX_BYTES + 1)
        else:                # a text stream without bytes (tests, embedding programs)
            data = stream.read(MAX_BYTES + 1)
    except UnicodeDecodeError as exc:
        raise _not_utf8(exc, b"", STDIN, "input") from None
    except (OSError, ValueError) as exc:   # ValueError: a closed file object
        reason = getattr(exc, "strerror", None) or "it is closed"
        raise InputError(f"cannot read standard input: {reason}", file=STDIN,
                         hint="give a file, or pipe the mechanism into 'linkcli ... -'") \
            from None
    if len(data) > MAX_BYTES:
        raise InputError(f"input is larger than {MAX_BYTES // 1000} kB", file=STDIN)
    return _decode(data, STDIN, "input") if isinstance(data, bytes) else data


def _decode(blob: bytes, name: str, what: str) -> str:
    """``blob`` as UTF-8 text, or an error at the line and byte offset of the first bad byte."""
    try:
        return blob.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise _not_utf8(exc, blob, name, what) from None


def _not_utf8(exc: UnicodeDecodeError, blob: bytes, name: str, what: str) -> InputError:
    if not blob:             # decoded by the stream: its offset is not the input's
        return InputError(f"{what} is not UTF-8 text", file=name, hint="save it as UTF-8")
    bad = blob[exc.start]
    return InputError(f"{what} is not UTF-8 text: byte 0x{bad:02x} at offset {exc.start}",
                      file=name, line=blob.count(b"\n", 0, exc.start) + 1,
                      hint="save it as UTF-8")


class _Refused(Exception):
    def __init__(self, detail: str, mark, hint: str):
        super().__init__(detail)
        self.detail = detail
        self.hint = hint
        self.line = mark.line + 1 if mark is not None else None


from yaml.parser import Parser as _PyParser   # noqa: E402
from yaml.reader import Reader                  # noqa: E402
from yaml.scanner import Scanner                # noqa: E402

try:   # libyaml's parser when available (fast), PyYAML's own otherwise
    from yaml._yaml import CParser as _Parser
except ImportError:  # pragma: no cover - PyYAML without libyaml
    _Parser = None


class _PythonParser(Reader, Scanner, _PyParser):
    """PyYAML's own reader, scanner and parser, in Python.  Its look-ahead is bounded
    (a simple key spans at most 1024 characters), so the composer's depth bound refuses a
    deep document before the scanner goes further; it words every syntax error the same
    way whichever libyaml (and its own limits) is installed."""

    def __init__(self, stream):
        Reader.__init__(self, stream)
        Scanner.__init__(self)
        _PyParser.__init__(self)


class _Bounded(yaml.composer.Composer, yaml.resolver.Resolver):
    """A safe composer (YAML events to nodes, no objects constructed) that
    refuses aliases and counts nodes and depth as it goes."""

    def _bound(self):
        yaml.composer.Composer.__init__(self)
        yaml.resolver.Resolver.__init__(self)
        self.node_count = 0
        self.depth = 0

    get_single_node = yaml.composer.Composer.get_single_node
    compose_document = yaml.composer.Composer.compose_document

    def compose_node(self, parent, index):
        if self.check_event(yaml.AliasEvent):
            raise _Refused("YAML anchors and aliases are not supported",
                           self.peek_event().start_mark,
                           "write the values out instead of '&name' and '*name'")
        self.node_count += 1
        if self.node_count > MAX_NODES:
            raise _Refused(f"document has more than {MAX_NODES} values",
                           self.peek_event().start_mark, "a mechanism file is small")
        if self.depth >= MAX_DEPTH:
            raise _Refused(f"document nested deeper than {MAX_DEPTH} levels",
                           self.peek_event().start_mark, "a mechanism file is small")
        self.depth += 1
        try:
            return yaml.composer.Composer.compose_node(self, parent, index)
        finally:
            self.depth -= 1


class _CheckingLoader(_Bounded, _PythonParser):
    """The bounded composer over PyYAML's Python parser: the wording of every error."""

    def __init__(self, stream):
        _PythonParser.__init__(self, stream)
        self._bound()


if _Parser is not None:
    class _BoundedLoader(_Bounded, _Parser):
        """The bounded composer over libyaml's parser: the fast path of a good file."""

        def __init__(self, stream):
            _Parser.__init__(self, stream)
            self._bound()
else:  # pragma: no cover - PyYAML without libyaml
    _BoundedLoader = _CheckingLoader


def _compose(text: str):
    """The document's node tree.  A file that libyaml refuses is read again by the
    Python parser, so that what the user is told (the error, its line, or the depth and
    size bounds, which libyaml's own limits may pre-empt) does not depend on the libyaml
    build installed; a file it accepts is read once, fast."""
    try:
        return _BoundedLoader(text).get_single_node()
    except yaml.YAMLError:
        if _BoundedLoader is _CheckingLoader:   # pragma: no cover - no libyaml
            raise
    return _CheckingLoader(text).get_single_node()


class _Builder:
    def __init__(self, doc: Document):
        self.doc = doc
        self.count = 0
        self.constructor = yaml.SafeLoader("")  # resolves scalar tags safely
        self.seen: set[int] = set()

    def fail(self, detail: str, node, hint: str | None = None) -> InputError:
        return InputError(detail, file=self.doc.name, line=node.start_mark.line + 1, hint=hint)

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
                raise self.fail("mapping keys must be plain names", key_node,
                                "a key is a name such as A, links or length")
            key = str(key_node.value)
            if key == "<<":
                raise self.fail("YAML merge keys are not supported", key_node,
                                "write the keys out instead of '<<'")
            if key in result:
                raise self.fail(f"duplicate key '{key}'", key_node,
                                "each key appears once in a mapping")
            self.doc.lines[path + (key,)] = key_node.start_mark.line + 1
            result[key] = self.build(value_node, path + (key,), depth + 1)
        return result
