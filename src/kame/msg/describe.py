"""Types described as rosmsg and rossrv print them, on top of a MsgCatalog.

Rules (real rosmsg's, so that output is byte-identical):
- a definition is shown as its constants (`byte DEBUG=1`), then its fields (`TYPE NAME`, the
  type resolved: `std_msgs/Header header`, `geometry_msgs/Vector3[] v`); a message field is
  followed by its own type's definition indented two more spaces, recursively;
- a service is its request, a `---` line, then its response;
- a bare name (`Twist`) matches `pkg/Twist` in every package that has it, packages in name order;
- a package "has messages" when it has a msg/ folder or .action files (whose seven generated
  messages are listed as installed ROS lists them), and "has services" with a srv/ folder;
- lookup failures read as genmsg words them (`Cannot locate message [X]: unknown package [p]
  on search path [{...}]`, `... in package [p] with paths [[...]]`, `invalid name [a/b/c]`).
"""

from __future__ import annotations

from enum import Enum

from kame.msg.catalog import MsgCatalog
from kame.msg.errors import MsgNotFoundError
from kame.msg.spec import MsgSpec, SrvSpec

INDENT = "  "


class Kind(Enum):
    """The two kinds of interface rosmsg and rossrv deal with; the value is the folder name."""

    MSG = "msg"
    SRV = "srv"


def _split(catalog: MsgCatalog, full_name: str, kind: Kind) -> tuple[str, str]:
    """'pkg/Type' -> ('pkg', 'Type') if the package exists, else the genmsg error."""
    parts = full_name.split("/")
    if len(parts) != 2:
        raise MsgNotFoundError(f"invalid name [{full_name}]")
    package, short = parts
    if package not in catalog.packages:
        search_path = {name: [str(pkg.path / kind.value)] for name, pkg in catalog.packages.items()}
        raise MsgNotFoundError(
            f"Cannot locate message [{short}]: unknown package [{package}] on search path [{search_path}]"
        )
    return package, short


def _not_in_package(catalog: MsgCatalog, package: str, short: str, kind: Kind) -> MsgNotFoundError:
    folder = str(catalog.packages[package].path / kind.value)
    return MsgNotFoundError(
        f"Cannot locate message [{short}] in package [{package}] with paths [[{folder!r}]]"
    )


def load_msg(catalog: MsgCatalog, full_name: str) -> MsgSpec:
    """The spec of message type 'pkg/Type'; MsgNotFoundError worded as genmsg words it."""
    package, short = _split(catalog, full_name, Kind.MSG)
    if full_name not in types_in_package(catalog, package, Kind.MSG):
        raise _not_in_package(catalog, package, short, Kind.MSG)
    return catalog.msg_spec(full_name)


def load_srv(catalog: MsgCatalog, full_name: str) -> SrvSpec:
    """The spec of service type 'pkg/Type'; MsgNotFoundError worded as genmsg words it."""
    package, short = _split(catalog, full_name, Kind.SRV)
    if full_name not in types_in_package(catalog, package, Kind.SRV):
        raise _not_in_package(catalog, package, short, Kind.SRV)
    return catalog.srv_spec(full_name)


def _lookup_dependency(catalog: MsgCatalog, full_name: str) -> MsgSpec:
    # A spec may be known without a file (e.g. added from a message_definition).
    try:
        return catalog.msg_spec(full_name)
    except MsgNotFoundError:
        return load_msg(catalog, full_name)


def _describe_into(catalog: MsgCatalog, spec: MsgSpec, indent: str, out: list[str]) -> None:
    for constant in spec.constants:
        out.append(f"{indent}{constant.type} {constant.name}={constant.value_text}\n")
    for field in spec.fields:
        out.append(f"{indent}{field.type} {field.name}\n")
        if field.is_message:
            _describe_into(catalog, _lookup_dependency(catalog, field.base_type), indent + INDENT, out)


def describe_msg(catalog: MsgCatalog, spec: MsgSpec) -> str:
    """rosmsg's expanded text of a message: one line per constant and field, each ending in a newline."""
    out: list[str] = []
    _describe_into(catalog, spec, "", out)
    return "".join(out)


def describe_srv(catalog: MsgCatalog, spec: SrvSpec) -> str:
    """rossrv's expanded text of a service: request, `---`, response."""
    return describe_msg(catalog, spec.request) + "---\n" + describe_msg(catalog, spec.response)


def has_kind(catalog: MsgCatalog, package: str, kind: Kind) -> bool:
    pkg = catalog.packages[package]
    if (pkg.path / kind.value).is_dir():
        return True
    return kind is Kind.MSG and bool(pkg.interface_files("action"))


def packages_with(catalog: MsgCatalog, kind: Kind) -> list[str]:
    """Names of the packages having messages (or services), sorted."""
    return sorted(name for name in catalog.packages if has_kind(catalog, name, kind))


def types_in_package(catalog: MsgCatalog, package: str, kind: Kind) -> list[str]:
    """'pkg/Type' of every message (or service) of a known package, sorted by type name."""
    if kind is Kind.MSG:
        return sorted(catalog.message_types(package))
    return sorted(catalog.service_types(package))


def all_types(catalog: MsgCatalog, kind: Kind) -> list[str]:
    """Every 'pkg/Type' of one kind, grouped by package in name order, as `rosmsg list` prints them."""
    return [t for package in packages_with(catalog, kind) for t in types_in_package(catalog, package, kind)]


def find_by_short_name(catalog: MsgCatalog, short: str, kind: Kind) -> list[str]:
    """Every 'pkg/<short>' of one kind, packages in name order."""
    found = []
    for package in packages_with(catalog, kind):
        candidate = f"{package}/{short}"
        if candidate in types_in_package(catalog, package, kind):
            found.append(candidate)
    return found
