"""SDF and URDF text read safely into a small tree that remembers each element's line.

Why expat directly (as kame.launch.xmltree does) and not defusedxml: refusing a DOCTYPE at its
start refuses every entity declaration, hence entity expansion and external entities, with no
dependency; and expat gives each element's line, which error messages need.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, field
from xml.parsers import expat

from kame.gazebo.errors import GazeboError

MAX_DEPTH = 200  # deeper nesting is refused, so walking a hostile file cannot exhaust the stack


@dataclass
class Element:
    tag: str
    attrs: dict[str, str]
    line: int
    source: str  # the file (or "<string>") the element was read from
    children: list[Element] = field(default_factory=list)
    text: str = ""

    def where(self) -> str:
        return f"<{self.tag}> at {self.source}:{self.line}"

    def child(self, tag: str) -> Element | None:
        return next((c for c in self.children if c.tag == tag), None)

    def each(self, tag: str) -> Iterator[Element]:
        return (c for c in self.children if c.tag == tag)

    def child_text(self, tag: str) -> str | None:
        found = self.child(tag)
        return found.text.strip() if found is not None else None

    def number(self, tag: str, default: float) -> float:
        """The child's finite number (SDF writes 1e16 for "no limit", never inf or nan)."""
        text = self.child_text(tag)
        if text is None or text == "":
            return default
        value = parse_float(text, self.child(tag) or self)
        if not math.isfinite(value):
            raise GazeboError(f"{(self.child(tag) or self).where()}: expected a finite number, not {text!r}")
        return value

    def integer(self, tag: str, default: int) -> int:
        value = self.number(tag, default)
        if value != int(value):
            raise GazeboError(f"{(self.child(tag) or self).where()}: expected a whole number, not {value}")
        return int(value)

    def flag(self, tag: str, default: bool) -> bool:
        text = self.child_text(tag)
        if text is None or text == "":
            return default
        if text.lower() in ("1", "true"):
            return True
        if text.lower() in ("0", "false"):
            return False
        raise GazeboError(f"{(self.child(tag) or self).where()}: expected true or false, not {text!r}")

    def vector(self, tag: str, default: tuple[float, ...]) -> tuple[float, ...]:
        found = self.child(tag)
        if found is None or not found.text.strip():
            return default
        return parse_vector(found.text, len(default), found)

    def as_dict(self) -> dict[str, object]:
        """The element's children as nested dicts: a leaf's text, an element with children a dict
        (attributes under "@name"); a repeated tag becomes a list."""
        out: dict[str, object] = {f"@{k}": v for k, v in self.attrs.items()}
        for c in self.children:
            value: object = c.as_dict() if c.children or c.attrs else c.text.strip()
            if c.tag in out:
                previous = out[c.tag]
                out[c.tag] = [*previous, value] if isinstance(previous, list) else [previous, value]
            else:
                out[c.tag] = value
        return out


def parse_float(text: str, element: Element) -> float:
    try:
        return float(text)
    except ValueError:
        raise GazeboError(f"{element.where()}: expected a number, not {text.strip()!r}") from None


def parse_vector(text: str, size: int, element: Element) -> tuple[float, ...]:
    parts = text.split()
    if len(parts) != size:
        raise GazeboError(f"{element.where()}: expected {size} numbers, not {text.strip()!r}")
    return tuple(parse_float(p, element) for p in parts)


def parse(data: bytes | str, source: str) -> Element:
    """The document's root element; GazeboError for malformed XML, any DOCTYPE, or nesting deeper than MAX_DEPTH."""
    parser = expat.ParserCreate()
    stack: list[Element] = []
    roots: list[Element] = []

    def refuse_dtd(*_args: object) -> None:
        raise GazeboError(f"{source}:{parser.CurrentLineNumber}: DOCTYPE and entity declarations are not accepted")

    def start(tag: str, attrs: dict[str, str]) -> None:
        if len(stack) >= MAX_DEPTH:
            raise GazeboError(f"{source}:{parser.CurrentLineNumber}: elements nested more than {MAX_DEPTH} deep")
        element = Element(tag, dict(attrs), parser.CurrentLineNumber, source)
        (stack[-1].children if stack else roots).append(element)
        stack.append(element)

    def end(_tag: str) -> None:
        stack.pop()

    def chars(text: str) -> None:
        if stack:
            stack[-1].text += text

    parser.StartDoctypeDeclHandler = refuse_dtd
    parser.EntityDeclHandler = refuse_dtd
    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = chars
    try:
        parser.Parse(data, True)
    except expat.ExpatError as exc:
        raise GazeboError(f"{source}: malformed XML: {exc}") from None
    if not roots:
        raise GazeboError(f"{source}: no XML element in it")
    return roots[0]
