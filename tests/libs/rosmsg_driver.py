"""rosmsg's library functions on JSON cases: messages filled from dicts written as YAML by
get_yaml_for_msg with each option, and the types of packages; prints JSON answers. Run by kame's
interpreter and Debian's /usr/bin/python3 (its real rosmsg)."""

from __future__ import annotations

import json
import sys
from typing import Any

import genpy.message
import roslib.message
import rosmsg


def message(type_name: str, fields: dict[str, Any]) -> Any:
    msg = roslib.message.get_message_class(type_name)()
    genpy.message.fill_message_args(msg, [fields])
    return msg


def value(spec: Any) -> Any:
    """A message ({"type", "fields"}), or a list or dict of them."""
    if isinstance(spec, list):
        return [value(s) for s in spec]
    if "type" in spec:
        return message(spec["type"], spec.get("fields", {}))
    return {key: value(s) for key, s in spec.items()}


def yaml_for(case: dict[str, Any]) -> str:
    options = dict(case.get("options", {}))
    if "exclude" in options:
        options["field_filter"] = rosmsg.create_names_filter(options.pop("exclude"))
    return rosmsg.get_yaml_for_msg(value(case["value"]), **options)


def listing(package: str) -> Any:
    try:
        return [rosmsg.list_msgs(package), rosmsg.list_srvs(package)]
    except Exception as exc:  # the answer is which exception, compared with upstream's
        return type(exc).__name__


def run(request: dict[str, Any]) -> dict[str, Any]:
    return {"yaml": [yaml_for(case) for case in request["yaml"]],
            "lists": [listing(package) for package in request["packages"]],
            "instances": [repr(rosmsg.get_array_type_instance(t, p)) for t, p in request["instances"]]}


if __name__ == "__main__":
    print(json.dumps(run(json.load(sys.stdin))))
