"""ROS graph resource names: canonical form, resolution, legality, command-line ROS arguments.

Rules (ros1-interop spec §1.1-1.2, as rosgraph.names and rospy.names implement them):
- `/x` is global, `~x` private (relative to the node's full name), anything else relative to the
  node's namespace; an empty name resolves to the namespace itself.
- Canonical form collapses repeated slashes and drops a trailing one. Resolution canonicalises
  first, then applies remappings, which match a fully resolved name exactly (no prefixes).
- The master resolves every name argument against the caller_id with these same rules, so this
  module must reproduce rosgraph's corner cases (e.g. a relative caller_id) rather than tidy them.
Pure functions only: no environment, no argv, no clock. Callers pass those in.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping

SEP = "/"
GLOBAL_NS = "/"
PRIVATE_PREFIX = "~"
REMAP = ":="
ANY_TYPE = "*"

#: The `__key:=value` arguments that configure a node rather than remap a name.
SPECIAL_KEYS = ("__name", "__ns", "__master", "__ip", "__hostname", "__log")

_LEGAL_NAME = re.compile(r"[~/A-Za-z][\w/]*\Z")
_LEGAL_BASE_NAME = re.compile(r"[A-Za-z]\w*\Z")
# rospy only treats `SRC:=DST` as a ROS argument when SRC looks like a name or a special key;
# roscpp takes any argument containing `:=`. We follow rospy, the stricter of the two, so a
# Python program's own `a:=b`-looking arguments that are not names stay in its argv.
_LEGAL_REMAP = re.compile(r"([~/A-Za-z]|_|__)[\w/]*:=.*\Z", re.DOTALL)


def is_global(name: str) -> bool:
    return name.startswith(SEP)


def is_private(name: str) -> bool:
    return name.startswith(PRIVATE_PREFIX)


def canonicalize(name: str) -> str:
    """`a//b/` -> `a/b`, `//a/` -> `/a`; the empty name and `/` are returned unchanged."""
    if not name or name == SEP:
        return name
    parts = [p for p in name.split(SEP) if p]
    if name[0] == SEP:
        return SEP + SEP.join(parts)
    return SEP.join(parts)


def namespace(name: str) -> str:
    """The namespace of a name, with a trailing slash: `/ns/node` -> `/ns/`, `node` -> `/`."""
    if not name:
        return GLOBAL_NS
    if name[-1] == SEP:
        name = name[:-1]
    return name[: name.rfind(SEP) + 1] or GLOBAL_NS


def ns_join(ns: str, name: str) -> str:
    """Join a namespace and a name; global and private names are not joinable and come back as is."""
    if is_private(name) or is_global(name):
        return name
    if ns == PRIVATE_PREFIX:
        return PRIVATE_PREFIX + name
    if not ns:
        return name
    if ns[-1] == SEP:
        return ns + name
    return ns + SEP + name


def make_global_ns(name: str) -> str:
    """`ns` -> `/ns/` (how `__ns` and ROS_NAMESPACE are turned into a namespace)."""
    if is_private(name):
        raise ValueError(f"cannot turn [{name}] into a global name")
    if not is_global(name):
        name = SEP + name
    if name[-1] != SEP:
        name += SEP
    return name


def resolve(name: str, caller_id: str, remappings: Mapping[str, str] | None = None) -> str:
    """Resolve `name` for the node `caller_id` (a full node name such as `/ns/node`).

    `remappings` maps fully resolved names to their replacement (see `resolve_remappings`).
    """
    if not name:
        return namespace(caller_id)
    name = canonicalize(name)
    if name[0] == SEP:
        resolved = name
    elif name[0] == PRIVATE_PREFIX:
        resolved = canonicalize(caller_id + SEP + name[1:])
    else:
        resolved = namespace(caller_id) + name
    if remappings:
        return remappings.get(resolved, resolved)
    return resolved


def is_legal_name(name: str) -> bool:
    """A letter, `/` or `~` first, then letters, digits, `_` or `/`, and no `//`.

    The empty name is legal (it names the caller's namespace). ROS does not enforce this on the
    master; tools and client libraries check it.
    """
    if name == "":
        return True
    return _LEGAL_NAME.match(name) is not None and "//" not in name


def is_legal_base_name(name: str) -> bool:
    """A node name without namespace (or a message field name): a letter, then `\\w` characters."""
    return _LEGAL_BASE_NAME.match(name) is not None


def is_ros_arg(arg: str) -> bool:
    """True for the argv elements that rospy treats as ROS arguments (`SRC:=DST`)."""
    return _LEGAL_REMAP.match(arg) is not None


class RosArgs:
    """The ROS arguments found in an argv, unresolved.

    `remappings` keep their source text (`chatter`, `~x`); `resolve_remappings` turns them into
    the resolved table once the node name is known. `params` are the `_name:=value` assignments,
    keyed by the private name they set (`~name`), with the raw value text: rospy parses it as
    YAML and roscpp as int/double/bool/string, so typing it is the client library's business.
    `special` holds `__name`, `__ns`, ... keyed
    without the leading underscores. `argv` is the program's own arguments (rospy's myargv()).
    """

    __slots__ = ("argv", "params", "remappings", "special")

    def __init__(self) -> None:
        self.remappings: dict[str, str] = {}
        self.params: dict[str, str] = {}
        self.special: dict[str, str] = {}
        self.argv: list[str] = []


def parse_args(argv: Iterable[str]) -> RosArgs:
    """Split argv into ROS arguments and the program's own arguments.

    A later assignment of the same key wins, as in rospy. Unknown `__keys` are dropped: they are
    ROS arguments (so not the program's), but neither remappings nor known settings.
    """
    out = RosArgs()
    for arg in argv:
        if not is_ros_arg(arg):
            out.argv.append(arg)
            continue
        src, _, dst = arg.partition(REMAP)
        src, dst = src.strip(), dst.strip()
        if not src or not dst:
            continue
        if src.startswith("__"):
            if src in SPECIAL_KEYS:
                out.special[src[2:]] = dst
        elif src.startswith("_"):
            out.params[PRIVATE_PREFIX + src[1:]] = dst
        else:
            out.remappings[src] = dst
    return out


def resolve_remappings(remappings: Mapping[str, str], node_name: str) -> dict[str, str]:
    """Resolve both sides of each `from:=to` against the node's full name, as rospy does.

    `~from` is resolved against the node name and `from` against its namespace; the result is the
    table `resolve` takes.
    """
    return {resolve(src, node_name): resolve(dst, node_name) for src, dst in remappings.items()}

