"""roslaunch.rlutil: run ids and launch-file arguments, as scripts call them."""

from __future__ import annotations

from collections.abc import Sequence

from kame.cli.roslaunch import get_or_generate_uuid as _uuid
from kame.cli.roslaunch import resolve_launch_arguments as _resolve


def get_or_generate_uuid(options_runid: str | None, options_wait_for_master: bool) -> str:
    return _uuid(options_runid, options_wait_for_master)


def resolve_launch_arguments(args: Sequence[str]) -> list[str]:
    """`['pkg', 'file.launch', 'a:=1']` -> `['/path/to/file.launch']` (name:=value pairs left out)."""
    return _resolve(args)


__all__ = ["get_or_generate_uuid", "resolve_launch_arguments"]
