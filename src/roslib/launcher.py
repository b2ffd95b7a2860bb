"""roslib.launcher: load_manifest, a no-op for catkin packages (as every package kame finds is)."""

from __future__ import annotations

from typing import Any

__all__ = ["get_depends", "load_manifest"]


def get_depends(package: str, rospack: Any) -> list[str]:
    """The packages `package` depends on (all the way down) that are rosbuild (not catkin) packages."""
    return [name for name in rospack.get_depends(package, implicit=True) if not rospack.get_manifest(name).is_catkin]


def load_manifest(package_name: str, bootstrap_version: str = "0.7") -> None:
    """A no-op, as in catkin-era ROS: packages and their messages are found on import."""
