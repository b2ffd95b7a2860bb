"""roslaunch.rlutil: run ids, launch-file arguments, the terminal's title, the log directory's size,
`--files`, and check_roslaunch (what rostest's roslaunch-check reports of a launch file)."""

from __future__ import annotations

import os
import sys
from collections.abc import Sequence
from pathlib import Path

import rospkg
from kame.cli.roscore import _disk_usage_check, _title
from kame.cli.roslaunch import get_or_generate_uuid as _uuid
from kame.cli.roslaunch import resolve_launch_arguments as _resolve
from kame.launch.errors import LaunchError
from kame.launch.runner import find_program
from rosmaster import DEFAULT_MASTER_PORT

__all__ = ["DEFAULT_MASTER_PORT", "change_terminal_name", "check_log_disk_usage", "check_roslaunch",
           "get_or_generate_uuid", "print_file_list", "resolve_launch_arguments", "update_terminal_name"]


def get_or_generate_uuid(options_runid: str | None, options_wait_for_master: bool) -> str:
    return _uuid(options_runid, options_wait_for_master)


def resolve_launch_arguments(args: Sequence[str]) -> list[str]:
    """`['pkg', 'file.launch', 'a:=1']` -> `['/path/to/file.launch']` (name:=value pairs left out)."""
    from roslaunch.core import RLException

    try:
        return _resolve(args)
    except LaunchError as exc:
        raise RLException(str(exc)) from None


def check_log_disk_usage() -> None:
    """Warn when the log directory holds over 1 GB (roscore's check)."""
    try:
        _disk_usage_check(Path(rospkg.get_log_dir()))
    except OSError:
        pass  # as ROS: an unreadable log directory is no reason to stop


_terminal_name: str | None = None


def _set_terminal(text: str) -> None:
    if sys.platform.startswith(("linux", "darwin", "freebsd")):
        print(_title(text))


def update_terminal_name(ros_master_uri: str) -> None:
    """Add the master's URI to the title change_terminal_name set."""
    if _terminal_name:
        _set_terminal(f"{_terminal_name} {ros_master_uri}")


def change_terminal_name(args: Sequence[str], is_core: bool) -> None:
    """Title the terminal `roscore`, or with the launch files."""
    global _terminal_name
    _terminal_name = "roscore" if is_core else ",".join(args)
    _set_terminal(_terminal_name)


def print_file_list(roslaunch_files: Sequence[str]) -> None:
    """`roslaunch --files`: every file the launch reads; exit status 1 on an error."""
    from roslaunch.config import load_config_default
    from roslaunch.core import RLException
    from roslaunch.xmlloader import XmlLoader

    try:
        config = load_config_default(roslaunch_files, None, loader=XmlLoader(resolve_anon=True), verbose=False,
                                     assign_machines=False)
        print("\n".join(os.path.abspath(f) for f in dict.fromkeys(config.roslaunch_files)))
    except RLException as exc:
        print(str(exc), file=sys.stderr)
        sys.exit(1)


def check_roslaunch(f: str, use_test_depends: bool = False, ignore_unset_args: bool = False) -> str | None:
    """What is wrong with launch file `f` (None: nothing): it does not load, its package.xml lacks a
    package it uses, a node's package or program cannot be found, or a configuration warning."""
    from roslaunch import depends
    from roslaunch.config import load_config_default
    from roslaunch.core import RLException, printerrlog
    from roslaunch.substitution_args import ArgException

    try:
        rl_config = load_config_default([f], DEFAULT_MASTER_PORT, verbose=False, ignore_unset_args=ignore_unset_args)
    except RLException as exc:
        return str(exc)
    errors: list[str] = []
    try:
        _, file_deps, missing = depends.roslaunch_deps([f], use_test_depends=use_test_depends,
                                                       ignore_unset_args=ignore_unset_args)
    except rospkg.ResourceNotFound as exc:
        errors.append(f"Could not find package [{exc}] included from [{f}]")
        file_deps, missing = {}, {}
    except ArgException as exc:
        errors.append(f"Could not resolve arg [{exc}] in [{f}]")
        file_deps, missing = {}, {}
    rospack = rospkg.RosPack()
    for pkg, miss in missing.items():
        provided: list[str] = []
        for file_dep in file_deps:
            file_pkg = rospkg.get_package_name(file_dep)
            if file_pkg:
                provided.extend(rospack.get_depends(file_pkg, implicit=False))
        if set(miss) - set(provided):
            printerrlog(f"Missing package dependencies: {pkg}/package.xml: {', '.join(miss)}")
            errors.append(f"Missing package dependencies: {pkg}/package.xml: {', '.join(miss)}")
        elif miss:
            printerrlog(f"Missing package dependencies: {pkg}/package.xml: {', '.join(miss)} (notify upstream "
                        "maintainer)")
    nodes = [node for deps in file_deps.values() for node in deps.nodes]
    for pkg, node_type in nodes:
        try:
            rospack.get_path(pkg)
        except rospkg.ResourceNotFound:
            errors.append(f"cannot find package [{pkg}] for node [{node_type}]")
    for pkg, node_type in nodes:
        try:
            find_program(pkg, node_type, os.environ)
        except LaunchError as exc:
            if "Cannot locate node" in str(exc):
                errors.append(f"cannot find node [{node_type}] in package [{pkg}]")
            else:
                errors.append(f"unable to find node [{pkg}/{node_type}]: {exc}")
    errors += [f"ROSLaunch config error: {err}" for err in rl_config.config_errors]
    return "\n".join(errors) if errors else None
