"""Launch XML read safely into a small tree that remembers where each element starts.

Why expat directly (as kame.protocol.xmlrpc does) and not defusedxml: refusing a DOCTYPE at its
start refuses every entity declaration, hence entity expansion and external entities, with no
dependency; and expat gives each element's line, which error messages need.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from xml.parsers import expat
from xml.sax.saxutils import escape, quoteattr

from kame.launch.errors import LaunchError


@dataclass
class Element:
    tag: str
    attrs: dict[str, str]
    line: int
    filename: str
    children: list[Element] = field(default_factory=list)
    text: str = ""  # the element's own text and CDATA, concatenated (not its children's)
    _parts: list[str | Element] = field(default_factory=list, repr=False)

    def get(self, name: str) -> str | None:
        return self.attrs.get(name)

    def toxml(self) -> str:
        """The element as minidom's toxml() writes it (roslaunch quotes it in errors)."""
        attrs = "".join(f" {k}={quoteattr(v)}" for k, v in self.attrs.items())
        if not self._parts:
            return f"<{self.tag}{attrs}/>"
        inner = "".join(escape(p) if isinstance(p, str) else p.toxml() for p in self._parts)
        return f"<{self.tag}{attrs}>{inner}</{self.tag}>"


#: Deepest element nesting accepted. Real launch files nest a handful of groups; without a
#: bound, a file of thousands of nested tags ended every recursive walk in a RecursionError.
MAX_DEPTH = 200


def parse(data: bytes | str, filename: str) -> Element:
    """The document's root element; LaunchError for bad XML, any DOCTYPE, or nesting deeper
    than MAX_DEPTH."""
    parser = expat.ParserCreate()
    stack: list[Element] = []
    roots: list[Element] = []

    def refuse_dtd(*_args: object) -> None:
        raise LaunchError("Invalid roslaunch XML syntax: DOCTYPE and entity declarations are not accepted",
                          filename, parser.CurrentLineNumber)

    def start(tag: str, attrs: dict[str, str]) -> None:
        if len(stack) >= MAX_DEPTH:
            raise LaunchError(f"Invalid roslaunch XML syntax: elements nested more than {MAX_DEPTH} deep",
                              filename, parser.CurrentLineNumber)
        element = Element(tag, dict(attrs), parser.CurrentLineNumber, filename)
        if stack:
            stack[-1].children.append(element)
            stack[-1]._parts.append(element)
        else:
            roots.append(element)
        stack.append(element)

    def end(_tag: str) -> None:
        stack.pop()

    def chars(data: str) -> None:
        if stack:
            stack[-1].text += data
            parts = stack[-1]._parts
            if parts and isinstance(parts[-1], str):
                parts[-1] += data
            else:
                parts.append(data)

    parser.StartDoctypeDeclHandler = refuse_dtd
    parser.EntityDeclHandler = refuse_dtd
    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = chars
    parser.ordered_attributes = False
    try:
        parser.Parse(data.encode() if isinstance(data, str) else data, True)
    except expat.ExpatError as exc:
        raise LaunchError(f"Invalid roslaunch XML syntax: {exc}", filename, exc.lineno) from None
    return roots[0]


def find_all(root: Element, tag: str) -> list[Element]:
    """Every element named `tag` at or below `root`, in document order."""
    found: list[Element] = []
    pending = [root]
    while pending:
        element = pending.pop()
        if element.tag == tag:
            found.append(element)
        pending.extend(reversed(element.children))
    return found
