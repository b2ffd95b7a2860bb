"""What camera_calibration writes of a monocular calibration: ost.yaml (camera_calibration_parsers'
YAML, laid out as calibrator.py's yaml()), ost.txt (the oST 5.0 INI text of its lrost()), the
D/K/R/P lines printed after CALIBRATE, and the sensor_msgs/CameraInfo that COMMIT sends."""

from __future__ import annotations

import numpy as np

from kame.camera.calibrator import Calibration
from sensor_msgs.msg import CameraInfo


def _matrix(values: np.ndarray, precision: int) -> str:
    text = np.array2string(values, precision=precision, suppress_small=True, separator=", ")
    return "[" + text.replace("[", "").replace("]", "").replace("\n", "\n        ") + "]"


def ost_yaml(calibration: Calibration, camera_name: str) -> str:
    width, height = calibration.size
    return "\n".join([
        f"image_width: {width}", f"image_height: {height}", f"camera_name: {camera_name}",
        "camera_matrix:", "  rows: 3", "  cols: 3", "  data: " + _matrix(calibration.K, 5),
        f"distortion_model: {calibration.distortion_model}",
        "distortion_coefficients:", "  rows: 1", f"  cols: {calibration.D.size}",
        "  data: [" + ", ".join(f"{x:8f}" for x in calibration.D.flat) + "]",
        "rectification_matrix:", "  rows: 3", "  cols: 3", "  data: " + _matrix(calibration.R, 8),
        "projection_matrix:", "  rows: 3", "  cols: 4", "  data: " + _matrix(calibration.P, 5), ""])


def _rows(matrix: np.ndarray) -> list[str]:
    return [" ".join(f"{x:8f}" for x in row) for row in matrix]


def ost_txt(calibration: Calibration, camera_name: str) -> str:
    width, height = calibration.size
    lines = ["# oST version 5.0 parameters", "", "", "[image]", "", "width", str(width), "", "height", str(height), "",
             f"[{camera_name}]", "", "camera matrix", *_rows(calibration.K), "", "distortion",
             " ".join(f"{x:8f}" for x in calibration.D.flat), "", "", "rectification", *_rows(calibration.R), "",
             "projection", *_rows(calibration.P), ""]
    return "\n".join(lines) + "\n"


def report(calibration: Calibration) -> str:
    return "\n".join([f"D =  {np.ravel(calibration.D).tolist()}", f"K =  {np.ravel(calibration.K).tolist()}",
                      f"R =  {np.ravel(calibration.R).tolist()}", f"P =  {np.ravel(calibration.P).tolist()}"])


def camera_info(calibration: Calibration) -> CameraInfo:
    width, height = calibration.size
    return CameraInfo(width=width, height=height, distortion_model=calibration.distortion_model,
                      D=[float(x) for x in calibration.D.flat], K=[float(x) for x in calibration.K.flat],
                      R=[float(x) for x in calibration.R.flat], P=[float(x) for x in calibration.P.flat])
