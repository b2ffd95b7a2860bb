"""genmsg.deps: the definition files a .msg or .srv depends on, for build systems."""

from __future__ import annotations

import os

from genmsg.base import InvalidMsgSpec, MsgGenerationException
from genmsg.gentools import compute_full_type_name
from genmsg.msg_loader import MsgContext, SearchPath, load_depends, load_msg_from_file, load_srv_from_file

__all__ = ["find_msg_dependencies", "find_msg_dependencies_with_type", "find_srv_dependencies",
           "find_srv_dependencies_with_type"]


def _dependencies(msg_context: MsgContext, full_names: list[str]) -> list[tuple[str, str | None]]:
    found = {(dep, msg_context.get_file(dep)) for name in full_names for dep in msg_context.get_all_depends(name)}
    return list(found)


def find_msg_dependencies_with_type(pkg_name: str, msg_file: str, search_paths: SearchPath
                                    ) -> list[tuple[str, str | None]]:
    """(type, file) of every message the .msg file uses, in no particular order."""
    msg_context = MsgContext.create_default()
    full_type_name = compute_full_type_name(pkg_name, os.path.basename(msg_file))
    spec = load_msg_from_file(msg_context, msg_file, full_type_name)
    try:
        load_depends(msg_context, spec, search_paths)
    except InvalidMsgSpec as e:
        raise MsgGenerationException(f"Cannot read .msg for {full_type_name}: {e}") from None
    return _dependencies(msg_context, [full_type_name])


def find_msg_dependencies(pkg_name: str, msg_file: str, search_paths: SearchPath) -> list[str | None]:
    return [d[1] for d in find_msg_dependencies_with_type(pkg_name, msg_file, search_paths)]


def find_srv_dependencies_with_type(pkg_name: str, msg_file: str, search_paths: SearchPath
                                    ) -> list[tuple[str, str | None]]:
    """(type, file) of every message the .srv file's request and response use."""
    msg_context = MsgContext.create_default()
    full_type_name = compute_full_type_name(pkg_name, os.path.basename(msg_file))
    spec = load_srv_from_file(msg_context, msg_file, full_type_name)
    try:
        load_depends(msg_context, spec, search_paths)
    except InvalidMsgSpec as e:
        raise MsgGenerationException(f"Cannot read .msg for {full_type_name}: {e}") from None
    return _dependencies(msg_context, [spec.request.full_name, spec.response.full_name])


def find_srv_dependencies(pkg_name: str, msg_file: str, search_paths: SearchPath) -> list[str | None]:
    return [d[1] for d in find_srv_dependencies_with_type(pkg_name, msg_file, search_paths)]
