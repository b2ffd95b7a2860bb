"""roslib.stack_manifest: a rosbuild stack's stack.xml (see roslib.manifestlib)."""

from __future__ import annotations

import os

from roslib import manifestlib
from roslib.manifestlib import ManifestException, StackDepend

__all__ = ["STACK_FILE", "ManifestException", "StackDepend", "StackManifest", "parse", "parse_file", "stack_file"]

STACK_FILE = "stack.xml"


class StackManifest(manifestlib._Manifest):
    """A stack's stack.xml."""

    __slots__: list[str] = []

    def __init__(self) -> None:
        super().__init__("stack")


def _stack_file_by_dir(stack_dir: str, required: bool = True) -> str | None:
    from roslib.stacks import InvalidROSStackException

    path = os.path.join(stack_dir, STACK_FILE)
    if not required and not os.path.exists(path):
        return path
    if not os.path.isfile(path):
        if required:
            raise InvalidROSStackException(
                f"\nStack '{stack_dir}' is improperly configured: no manifest file is present.\n")
        return None
    return path


def stack_file(stack: str, required: bool = True) -> str | None:
    """The path of `stack`'s stack.xml."""
    from roslib.stacks import get_stack_dir

    return _stack_file_by_dir(get_stack_dir(stack), required)


def parse_file(file: str) -> StackManifest:
    m = manifestlib.parse_file(StackManifest(), file)
    assert isinstance(m, StackManifest)
    return m


def parse(string: str, filename: str = "string") -> StackManifest:
    m = manifestlib.parse(StackManifest(), string, filename)
    assert isinstance(m, StackManifest)
    return m
