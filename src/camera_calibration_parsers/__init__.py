"""camera_calibration_parsers' Python module, as Noetic's: readCalibration(file_name) ->
(camera name, sensor_msgs/CameraInfo), or None when the file cannot be read. A facade over
kame.camera.calibration_files; kame also offers writeCalibration, as the C++ library has."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from kame.camera.calibration_files import Calibration, CalibrationFileError, dump, file_format, parse

__all__ = ["readCalibration", "writeCalibration"]


def readCalibration(file_name: str) -> tuple[str, Any] | None:
    try:
        calibration = parse(Path(file_name).read_text(), file_format(file_name))
    except (OSError, CalibrationFileError):
        return None
    return calibration.camera_name, calibration.info


def writeCalibration(file_name: str, camera_name: str, camera_info: Any) -> bool:
    try:
        Path(file_name).write_text(dump(Calibration(camera_name, camera_info), file_format(file_name)))
    except (OSError, CalibrationFileError):
        return False
    return True
