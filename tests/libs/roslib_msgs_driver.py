"""roslib.msgs on JSON cases: specs of .msg texts, types parsed and checked, a type loaded by name;
prints JSON answers. Run by kame's interpreter and Debian's (real roslib)."""

from __future__ import annotations

import json
import sys
from typing import Any

import roslib.msgs as msgs


def spec_answer(spec: Any) -> list[Any]:
    return [spec.types, spec.names, [[c.type, c.name, c.val, c.val_text] for c in spec.constants], spec.has_header(),
            spec.full_name, spec.short_name, spec.package, [repr(f) for f in spec.parsed_fields()], spec.fields()]


def run(request: dict[str, Any]) -> dict[str, Any]:
    loaded = []
    for text, package in request["texts"]:
        try:
            loaded.append(spec_answer(msgs.load_from_string(text, package, f"{package}/T", "T")))
        except msgs.MsgSpecException:
            loaded.append("MsgSpecException")
    parsed = []
    for type_ in request["types"]:
        try:
            parsed.append(list(msgs.parse_type(type_)))
        except msgs.MsgSpecException as exc:
            parsed.append(str(exc))
    found, by_type = msgs.load_by_type("std_msgs/Header")
    return {"loaded": loaded, "parsed": parsed,
            "valid": [msgs.is_valid_msg_type(t) for t in request["types"]],
            "resolved": [msgs.resolve_type(t, "pkg") for t in request["types"] if t],
            "base": [msgs.base_msg_type(t) for t in request["types"]],
            "builtin": [msgs.is_builtin(t) for t in ("time", "Header", "uint8", "string[]")],
            "header": [found, by_type.types, by_type.names, by_type.has_header()],
            "listed": "Header" in msgs.list_msg_types("std_msgs", False)}


if __name__ == "__main__":
    print(json.dumps(run(json.load(sys.stdin))))
