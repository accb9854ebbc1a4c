"""Reading a case file's YAML safely: text only, bounded, no tags, no repeated keys.

``yaml.safe_load`` trusts its input in ways a case file should not be trusted: it recurses once
per nesting level (``RecursionError`` on ``[[[[…]]]]``), shares aliased nodes that every consumer
then walks again (a 1 KB "billion laughs" file is 10⁹ numbers to validate), keeps the last of two
equal keys silently, and calls a ``!!python/…`` tag a syntax error. Here the document is built
from the parser's event stream with an explicit stack, and every event is checked before it is
used:

* the file is at most ``case_bytes`` long (read no further) and UTF-8 text without control
  characters (a binary or UTF-16 file is "not UTF-8 text");
* nesting deeper than ``yaml_depth`` is refused at the first event that exceeds it;
* every node is counted with each alias expanded (an alias adds the size of its anchor's whole
  subtree, known when the anchor closed), so an alias bomb is refused after reading its few
  hundred events, whatever its expanded size, when the count passes ``yaml_nodes``;
* any explicit tag (``!!python/object``, ``!custom``, ``!!str``) is refused: tags are not allowed;
* a key repeated in one mapping is refused, naming the key and both lines;
* merge keys (``<<``), recursive aliases and multi-document streams are refused.

The limits are :mod:`theory.core.validation`'s. Errors are :class:`~theory.core.errors.CaseError`
naming the field (the dotted path of the offending node, or ``<file>`` / ``<yaml>``).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

import yaml

from theory.core.errors import CaseError
from theory.core.validation import LIMITS, limit

__all__ = ["decode_text", "load_yaml", "read_case_bytes"]

_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
_NON_PRINTABLE = re.compile(
    "[^\x09\x0a\x0d\x20-\x7e\x85\xa0-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]"
)
_UTF16_BOMS = (b"\xff\xfe", b"\xfe\xff")
_MERGE = "tag:yaml.org,2002:merge"
_NO_KEY = object()


def read_case_bytes(path: str) -> bytes:
    """The bytes of the file ``path``, refusing it unread past the ``case_bytes`` limit."""
    bound = limit("case_bytes")
    try:
        with open(path, "rb") as handle:
            raw = handle.read(bound + 1)
    except OSError as error:
        raise CaseError("<file>", "a readable YAML file", error.strerror, file=path) from None
    if len(raw) > bound:
        raise CaseError(
            "<file>",
            f"a case file of at most {bound:,} bytes (limit 'case_bytes')",
            f"more than {bound:,} bytes (read no further)",
            file=path,
            hint=LIMITS["case_bytes"].hint(),
        )
    return raw


def decode_text(raw: bytes) -> str:
    """``raw`` as UTF-8 text (a UTF-8 byte-order mark is dropped)."""
    hint = "Save the case file as UTF-8 text."
    if raw.startswith(_UTF16_BOMS):
        raise CaseError(
            "<file>", "UTF-8 text", "not UTF-8 text (a UTF-16 byte-order mark)", hint=hint
        )
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        got = f"not UTF-8 text (byte 0x{raw[error.start]:02x} at offset {error.start})"
        raise CaseError("<file>", "UTF-8 text", got, hint=hint) from None
    bad = _NON_PRINTABLE.search(text)
    if bad:
        line = text.count("\n", 0, bad.start()) + 1
        got = f"not UTF-8 text (control character U+{ord(bad.group()):04X} on line {line})"
        raise CaseError("<file>", "UTF-8 text", got, hint=hint)
    return text


@dataclass
class _Frame:
    """An open sequence or mapping: its value so far and the bookkeeping to place children."""

    path: str
    value: Any
    anchor: str | None
    start: int
    key: Any = _NO_KEY
    key_lines: dict[Any, int] = field(default_factory=dict)

    def child_path(self) -> str:
        if isinstance(self.value, list):
            return f"{self.path}[{len(self.value) + 1}]"
        if self.key is _NO_KEY:
            return self.path
        return f"{self.path}.{self.key}" if self.path else str(self.key)


class _Builder:
    """Builds the document from parser events with an explicit stack (no recursion)."""

    def __init__(self) -> None:
        self.stack: list[_Frame] = []
        self.anchors: dict[str, tuple[Any, int]] = {}
        self.open_anchors: set[str] = set()
        self.count = 0
        self.documents = 0
        self.root: Any = None
        self.max_depth = limit("yaml_depth")
        self.max_nodes = limit("yaml_nodes")
        self.scalars = yaml.SafeLoader("")

    def path(self) -> str:
        return self.stack[-1].child_path() if self.stack else ""

    def feed(self, event: yaml.Event) -> None:
        if isinstance(event, yaml.DocumentStartEvent):
            self.documents += 1
            if self.documents > 1:
                raise CaseError("<yaml>", "a single YAML document", "a second document ('---')")
        elif isinstance(event, yaml.ScalarEvent):
            self._refuse_tag(event)
            self._count(1)
            self._place(self._scalar(event), event, 1, event.anchor)
        elif isinstance(event, yaml.SequenceStartEvent | yaml.MappingStartEvent):
            self._open(event)
        elif isinstance(event, yaml.SequenceEndEvent | yaml.MappingEndEvent):
            frame = self.stack.pop()
            if frame.anchor is not None:
                self.open_anchors.discard(frame.anchor)
            self._place(frame.value, event, self.count - frame.start, frame.anchor)
        elif isinstance(event, yaml.AliasEvent):
            self._alias(event)

    def _open(self, event: yaml.CollectionStartEvent) -> None:
        self._refuse_tag(event)
        where = self.path() or "<top level>"
        if len(self.stack) >= self.max_depth:
            raise self.too_deep(event.start_mark.line + 1)
        if self.stack and self.stack[-1].key is _NO_KEY and isinstance(self.stack[-1].value, dict):
            raise CaseError(where, "plain keys (strings or numbers)", "a list or mapping as a key")
        start = self.count
        self._count(1)
        value: Any = [] if isinstance(event, yaml.SequenceStartEvent) else {}
        if event.anchor is not None:
            self.open_anchors.add(event.anchor)
        self.stack.append(_Frame(self.path(), value, event.anchor, start))

    def too_deep(self, line: int) -> CaseError:
        """The error for nesting deeper than the ``yaml_depth`` limit, seen on ``line``."""
        return CaseError(
            self.path() or "<top level>",
            f"YAML nested at most {self.max_depth} levels deep (limit 'yaml_depth')",
            f"more than {self.max_depth} levels (line {line})",
            hint=LIMITS["yaml_depth"].hint(),
        )

    def _alias(self, event: yaml.AliasEvent) -> None:
        if event.anchor in self.open_anchors:
            raise CaseError(
                self.path() or "<top level>", "no recursive aliases", f"*{event.anchor}"
            )
        if event.anchor not in self.anchors:
            raise CaseError(
                self.path() or "<top level>", "an alias to an earlier anchor", f"*{event.anchor}"
            )
        value, size = self.anchors[event.anchor]
        self._count(size)
        self._place(value, event, size, None)

    def _count(self, size: int) -> None:
        self.count += size
        if self.count > self.max_nodes:
            raise CaseError(
                self.path() or "<top level>",
                f"at most {self.max_nodes:,} YAML nodes with aliases expanded (limit 'yaml_nodes')",
                f"more than {self.max_nodes:,}",
                hint=LIMITS["yaml_nodes"].hint(),
            )

    def _refuse_tag(self, event: yaml.NodeEvent) -> None:
        if getattr(event, "tag", None) is not None:
            raise CaseError(
                self.path() or "<top level>",
                "plain YAML data: tags are not allowed",
                f"the tag {event.tag[:80]!r} (line {event.start_mark.line + 1})",
            )

    def _scalar(self, event: yaml.ScalarEvent) -> Any:
        node = yaml.ScalarNode(None, event.value, event.start_mark, event.end_mark, event.style)
        node.tag = self.scalars.resolve(yaml.ScalarNode, event.value, event.implicit)
        if node.tag == _MERGE:
            raise CaseError(self.path() or "<top level>", "no merge keys ('<<')", event.value)
        construct = self.scalars.yaml_constructors.get(node.tag)
        if construct is None:
            return event.value
        try:
            return construct(self.scalars, node)
        except (ValueError, yaml.YAMLError):
            got = f"{event.value[:60]!r} (line {event.start_mark.line + 1})"
            raise CaseError(
                self.path() or "<top level>", f"a valid {node.tag.rsplit(':', 1)[-1]}", got
            ) from None

    def _place(self, value: Any, event: yaml.Event, size: int, anchor: str | None) -> None:
        if anchor is not None:
            self.anchors[anchor] = (value, size)
        if not self.stack:
            self.root = value
            return
        frame = self.stack[-1]
        if isinstance(frame.value, list):
            frame.value.append(value)
        elif frame.key is _NO_KEY:
            self._key(frame, value, event.start_mark.line + 1)
        else:
            frame.value[frame.key] = value
            frame.key = _NO_KEY

    def _key(self, frame: _Frame, key: Any, line: int) -> None:
        if isinstance(key, list | dict):
            raise CaseError(
                frame.path or "<top level>",
                "plain keys (strings or numbers)",
                "a list or mapping as a key",
            )
        if key in frame.key_lines:
            dotted = f"{frame.path}.{key}" if frame.path else str(key)
            raise CaseError(
                dotted,
                "each key once in a mapping",
                f"{key!r} twice, on lines {frame.key_lines[key]} and {line}",
                hint="YAML would silently keep only the last value; remove one of them.",
            )
        frame.key_lines[key] = line
        frame.key = key


def load_yaml(text: str) -> Any:
    """The one YAML document in ``text``, as plain data, checked as the module docstring says."""
    builder = _Builder()
    try:
        for event in yaml.parse(text, Loader=_LOADER):
            builder.feed(event)
    except yaml.YAMLError as error:
        if "nesting depth" in str(getattr(error, "problem", "")):  # libyaml's own bound
            raise builder.too_deep(error.problem_mark.line + 1) from None
        raise CaseError("<yaml>", "valid YAML", _syntax(error)) from None
    return builder.root


def _syntax(error: yaml.YAMLError) -> str:
    mark = getattr(error, "problem_mark", None)
    where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else "an unknown place"
    problem = getattr(error, "problem", None)
    return f"a syntax error at {where}" + (f" ({problem})" if problem else "")
