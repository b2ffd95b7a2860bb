"""rospkg.common: manifest file names and ResourceNotFound."""

from __future__ import annotations

from collections.abc import Sequence

MANIFEST_FILE = "manifest.xml"
PACKAGE_FILE = "package.xml"
STACK_FILE = "stack.xml"
ROS_STACK = "ros"


class ResourceNotFound(Exception):
    """A package or stack that is not on the ROS paths; its text lists the paths searched."""

    def __init__(self, msg: str, ros_paths: Sequence[str] | None = None) -> None:
        super().__init__(msg)
        self.ros_paths = ros_paths

    def __str__(self) -> str:
        text = str(self.args[0])
        for index, path in enumerate(self.ros_paths or ()):
            text += f"\nROS path [{index}]={path}"
        return text
