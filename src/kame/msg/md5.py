"""md5sums and full definition texts, exactly as genmsg computes them.

md5 text: constants (`TYPE NAME=VALUE`) then fields; a builtin field is `TYPE NAME` as
declared (array suffix and alias kept), a message field is `<md5 of its type> NAME` (array
suffix dropped). Lines joined by newlines, outer whitespace stripped.
A service's md5 is the md5 of its request md5 text followed directly by its response's.
The full text (`message_definition`) is the type's own text, then for every dependency in
depth-first pre-order a line of 80 '=', `MSG: pkg/Type` and that type's text; the final
character of the whole is dropped.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable

from kame.msg.spec import MsgSpec, SrvSpec

Lookup = Callable[[str], MsgSpec]
DEFINITION_SEPARATOR = "=" * 80


class Md5Cache:
    """Memoises md5 texts by type name; a lookup maps 'pkg/Type' to its spec."""

    def __init__(self, lookup: Lookup) -> None:
        self._lookup = lookup
        self._md5: dict[str, str] = {}

    def md5_text(self, spec: MsgSpec) -> str:
        lines = [f"{c.type} {c.name}={c.value_text}" for c in spec.constants]
        for f in spec.fields:
            if f.is_builtin:
                lines.append(f"{f.type} {f.name}")
            else:
                lines.append(f"{self.md5sum_of(f.base_type)} {f.name}")
        return "\n".join(lines).strip()

    def md5sum(self, spec: MsgSpec) -> str:
        return hashlib.md5(self.md5_text(spec).encode("utf-8")).hexdigest()

    def md5sum_of(self, full_name: str) -> str:
        cached = self._md5.get(full_name)
        if cached is None:
            cached = self._md5[full_name] = self.md5sum(self._lookup(full_name))
        return cached

    def srv_md5sum(self, srv: SrvSpec) -> str:
        text = self.md5_text(srv.request) + self.md5_text(srv.response)
        return hashlib.md5(text.encode("utf-8")).hexdigest()


def all_dependencies(spec: MsgSpec, lookup: Lookup) -> list[str]:
    """Every message type `spec` uses, depth-first pre-order in field order, each once."""
    ordered: dict[str, None] = {}

    def walk(current: MsgSpec) -> None:
        for dep in current.message_dependencies():
            if dep not in ordered:
                ordered[dep] = None
                walk(lookup(dep))

    walk(spec)
    return list(ordered)


def full_text(spec: MsgSpec, lookup: Lookup) -> str:
    parts = [spec.text, "\n"]
    for dep in all_dependencies(spec, lookup):
        parts += [DEFINITION_SEPARATOR, "\n", f"MSG: {dep}\n", lookup(dep).text, "\n"]
    return "".join(parts)[:-1]


def split_full_text(text: str) -> tuple[str, dict[str, str]]:
    """Inverse of full_text: the main type's text and each dependency's text by name.

    The joining newlines belong to the separators, so each piece is its file's text again.
    """
    blocks = text.split("\n" + DEFINITION_SEPARATOR + "\n")
    main = blocks[0]
    deps: dict[str, str] = {}
    for block in blocks[1:]:
        header, _, body = block.partition("\n")
        if not header.startswith("MSG: "):
            continue
        deps[header[len("MSG: "):].strip()] = body
    return main, deps
