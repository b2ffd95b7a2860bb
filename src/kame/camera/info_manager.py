"""camera_info_manager on kame.client: a camera driver's CameraInfo, loaded from its calibration
URL, and the `set_camera_info` service that the calibrator's COMMIT calls, which stores the new
calibration and writes it to the URL's file (YAML or INI by its extension, the folders made as
needed).

As camera_info_manager 1.12: a URL that names no file, or a file that is not there, leaves the
camera uncalibrated with a warning; a calibration is one whose K[0] is not zero.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from kame.camera.calibration_files import Calibration, CalibrationFileError, dump, file_format, parse
from kame.camera.info_url import CalibrationURLError, resolve, valid_camera_name
from kame.client import log
from kame.client.services import Service
from sensor_msgs.msg import CameraInfo
from sensor_msgs.srv import SetCameraInfo, SetCameraInfoResponse


def ros_home() -> str:
    return os.environ.get("ROS_HOME") or os.path.join(os.path.expanduser("~"), ".ros")


def find_package(name: str) -> str | None:
    from kame.catkin import executables

    package = executables.packages(os.environ).get(name)
    return None if package is None else str(package.path)


def calibration_file(url: str, camera_name: str) -> str:
    """The file `url` names for the camera (CalibrationURLError if none)."""
    return resolve(url, camera_name, ros_home(), find_package)


def load_calibration(url: str, camera_name: str) -> Calibration | None:
    """The calibration at `url`, or None with camera_info_manager's warning."""
    try:
        path = calibration_file(url, camera_name)
        text = Path(path).read_text()
    except CalibrationURLError as exc:
        log.emit(log.WARN, "%s", (exc,))
        return None
    except OSError:
        log.emit(log.WARN, "Camera calibration file %s not found.", (path,))
        return None
    try:
        return parse(text, file_format(path))
    except CalibrationFileError as exc:
        log.emit(log.ERROR, "Failed to parse camera calibration from file [%s]: %s", (path, exc))
        return None


def save_calibration(url: str, camera_name: str, info: Any) -> str:
    """Writes `info` to the file `url` names; returns its path (CalibrationURLError,
    CalibrationFileError or OSError when it cannot)."""
    path = calibration_file(url, camera_name)
    text = dump(Calibration(camera_name, info), file_format(path))
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(text)
    return path


class CameraInfoManager:
    """One camera's CameraInfo, its calibration URL and its `<namespace>set_camera_info` service."""

    def __init__(self, camera_name: str, url: str = "", namespace: str = "~") -> None:
        self.camera_name = camera_name
        self.url = url
        self.info = CameraInfo()
        if not valid_camera_name(camera_name):
            log.emit(log.ERROR, "invalid camera name: %s", (camera_name,))
        loaded = load_calibration(url, camera_name)
        if loaded is not None:
            self.info = loaded.info
        self.service = Service(namespace.rstrip("/") + "/set_camera_info" if namespace != "~" else "~set_camera_info",
                               SetCameraInfo, self._set_camera_info)

    def is_calibrated(self) -> bool:
        return bool(self.info.K[0] != 0.0)

    def get_camera_info(self) -> Any:
        return self.info

    def set_camera_info(self, info: Any) -> None:
        self.info = info

    def set_camera_name(self, name: str) -> bool:
        if not valid_camera_name(name):
            return False
        self.camera_name = name
        return True

    def _set_camera_info(self, request: Any) -> Any:
        self.info = request.camera_info
        try:
            path = save_calibration(self.url, self.camera_name, request.camera_info)
        except (CalibrationURLError, CalibrationFileError, OSError) as exc:
            log.emit(log.ERROR, "Error storing camera calibration: %s", (exc,))
            return SetCameraInfoResponse(success=False, status_message=f"Error storing camera calibration: {exc}")
        log.emit(log.INFO, "Camera calibration written to %s", (path,))
        return SetCameraInfoResponse(success=True, status_message="")
