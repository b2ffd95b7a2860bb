"""camera_info_manager's calibration URLs, resolved to a file.

Rules (camera_info_manager 1.12): `${NAME}` is the camera's name and `${ROS_HOME}` ROS's home
($ROS_HOME, else ~/.ros); an empty URL is `file://${ROS_HOME}/camera_info/${NAME}.yaml`;
`file:///abs/path.yaml` names a file, `package://pkg/rel/path.yaml` a file in package pkg; any
other scheme is not supported. A camera name is letters, digits and underscores (it is part of
the default file's name).
"""

from __future__ import annotations

import re
from collections.abc import Callable

DEFAULT_URL = "file://${ROS_HOME}/camera_info/${NAME}.yaml"
_VALID_NAME = re.compile(r"^[A-Za-z0-9_]+$")


class CalibrationURLError(ValueError):
    """A URL camera_info_manager cannot load from or save to; the message is its log line."""


def valid_camera_name(name: str) -> bool:
    return bool(_VALID_NAME.match(name))


def substitute(url: str, camera_name: str, ros_home: str) -> str:
    return (url or DEFAULT_URL).replace("${NAME}", camera_name).replace("${ROS_HOME}", ros_home)


def resolve(url: str, camera_name: str, ros_home: str, find_package: Callable[[str], str | None]) -> str:
    """The file `url` names for `camera_name`; CalibrationURLError if it names none."""
    resolved = substitute(url, camera_name, ros_home)
    lowered = resolved.lower()
    if lowered.startswith("file://"):
        return resolved[len("file://"):]
    if lowered.startswith("package://"):
        package, _, rest = resolved[len("package://"):].partition("/")
        if not package or not rest:
            raise CalibrationURLError(f"Invalid package URL: {resolved}")
        root = find_package(package)
        if root is None:
            raise CalibrationURLError(f"Calibration package missing: {package} (from URL {resolved})")
        return f"{root.rstrip('/')}/{rest}"
    raise CalibrationURLError(f"Invalid camera calibration URL: {resolved}")
