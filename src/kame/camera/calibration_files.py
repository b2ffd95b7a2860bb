"""camera_calibration_parsers: a camera's calibration (sensor_msgs/CameraInfo and its name) in
the YAML and INI files ROS reads and writes.

Rules (camera_calibration_parsers 1.12's parse_yml.cpp and parse_ini.cpp): YAML has image_width,
image_height, camera_name, and camera_matrix (3x3), distortion_model, distortion_coefficients
(1xN), rectification_matrix (3x3), projection_matrix (3x4), each matrix as rows, cols and a flat
row-major data list; a missing distortion_model is plumb_bob. INI has an [image] section with
width and height, then a section named after the camera with "camera matrix", "distortion",
"rectification" and "projection", each a label line followed by its numbers. The file's
extension chooses the format (.yml or .yaml, .ini), as readCalibration/writeCalibration do.
A file that does not parse is a CalibrationFileError saying where.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import yaml

from sensor_msgs.msg import CameraInfo


class CalibrationFileError(ValueError):
    """A calibration file that does not say what a camera's calibration needs."""


@dataclass(frozen=True)
class Calibration:
    camera_name: str
    info: Any  # sensor_msgs/CameraInfo


def file_format(path: str) -> str:
    """'yaml' or 'ini' by the extension, CalibrationFileError otherwise."""
    lowered = path.lower()
    if lowered.endswith((".yml", ".yaml")):
        return "yaml"
    if lowered.endswith(".ini"):
        return "ini"
    raise CalibrationFileError(f"Unrecognized format for calibration file {path!r}: .yml, .yaml or .ini")


def parse(text: str, format: str) -> Calibration:
    return parse_yaml(text) if format == "yaml" else parse_ini(text)


def dump(calibration: Calibration, format: str) -> str:
    return dump_yaml(calibration) if format == "yaml" else dump_ini(calibration)


def _matrix(document: dict[str, Any], key: str, rows: int | None, cols: int | None) -> list[float]:
    node = document.get(key)
    if not isinstance(node, dict) or not isinstance(node.get("data"), list):
        raise CalibrationFileError(f"{key} needs rows, cols and data")
    data = [float(value) for value in node["data"]]
    want_rows, want_cols = int(node.get("rows", rows or 1)), int(node.get("cols", cols or len(data)))
    if (rows is not None and want_rows != rows) or (cols is not None and want_cols != cols):
        raise CalibrationFileError(f"{key} is {want_rows}x{want_cols}, {rows}x{cols} expected")
    if len(data) != want_rows * want_cols:
        raise CalibrationFileError(f"{key} has {len(data)} values for {want_rows}x{want_cols}")
    return data


def parse_yaml(text: str) -> Calibration:
    try:
        document = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        raise CalibrationFileError(f"not YAML: {exc}") from exc
    if not isinstance(document, dict):
        raise CalibrationFileError("a calibration YAML file is a mapping")
    try:
        info = CameraInfo(width=int(document["image_width"]), height=int(document["image_height"]),
                          distortion_model=str(document.get("distortion_model", "plumb_bob")),
                          K=_matrix(document, "camera_matrix", 3, 3),
                          D=_matrix(document, "distortion_coefficients", 1, None) if "distortion_coefficients"
                          in document else [],
                          R=_matrix(document, "rectification_matrix", 3, 3),
                          P=_matrix(document, "projection_matrix", 3, 4))
    except KeyError as exc:
        raise CalibrationFileError(f"{exc.args[0]} is missing") from exc
    except (TypeError, ValueError) as exc:
        raise CalibrationFileError(str(exc)) from exc
    return Calibration(str(document.get("camera_name", "")), info)


def _flow(values: Sequence[float]) -> str:
    return "[" + ", ".join(repr(float(value)) for value in values) + "]"


def dump_yaml(calibration: Calibration) -> str:
    info = calibration.info
    lines = [f"image_width: {info.width}", f"image_height: {info.height}",
             f"camera_name: {calibration.camera_name}"]
    for key, rows, cols, values in (("camera_matrix", 3, 3, info.K), ("distortion_model", 0, 0, None),
                                    ("distortion_coefficients", 1, len(info.D), info.D),
                                    ("rectification_matrix", 3, 3, info.R), ("projection_matrix", 3, 4, info.P)):
        if values is None:
            lines.append(f"distortion_model: {info.distortion_model or 'plumb_bob'}")
            continue
        lines += [f"{key}:", f"  rows: {rows}", f"  cols: {cols}", f"  data: {_flow(values)}"]
    return "\n".join(lines) + "\n"


_SECTION = re.compile(r"^\[(.*)\]$")
_LABELS = {"camera matrix": ("K", 9), "distortion": ("D", None), "rectification": ("R", 9), "projection": ("P", 12)}


def parse_ini(text: str) -> Calibration:
    section = ""
    camera_name = ""
    sizes: dict[str, int] = {}
    matrices: dict[str, list[float]] = {}
    label = ""
    for number, raw in enumerate(text.splitlines(), 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        heading = _SECTION.match(line)
        if heading:
            section, label = heading.group(1), ""
            if section != "image":
                camera_name = section
            continue
        if section == "image" and line in ("width", "height"):
            label = line
            continue
        if line in _LABELS:
            label = line
            matrices.setdefault(_LABELS[line][0], [])
            continue
        try:
            values = [float(word) for word in line.split()]
        except ValueError:
            raise CalibrationFileError(f"line {number}: {raw!r} is neither a label nor numbers") from None
        if label in ("width", "height") and section == "image":
            sizes[label] = int(values[0])
        elif label in _LABELS:
            matrices[_LABELS[label][0]].extend(values)
        else:
            raise CalibrationFileError(f"line {number}: numbers with no label before them")
    for name, (field, count) in _LABELS.items():
        if field not in matrices:
            raise CalibrationFileError(f"the {name!r} entry is missing")
        if count is not None and len(matrices[field]) != count:
            raise CalibrationFileError(f"{name!r} has {len(matrices[field])} values, {count} expected")
    if set(sizes) != {"width", "height"}:
        raise CalibrationFileError("the [image] section needs width and height")
    info = CameraInfo(width=sizes["width"], height=sizes["height"], K=matrices["K"], D=matrices["D"],
                      R=matrices["R"], P=matrices["P"],
                      distortion_model="rational_polynomial" if len(matrices["D"]) == 8 else "plumb_bob")
    return Calibration(camera_name, info)


def _rows(values: Sequence[float], cols: int) -> list[str]:
    return [" ".join(f"{float(value):.5f}" for value in values[start:start + cols])
            for start in range(0, len(values), cols)]


def dump_ini(calibration: Calibration) -> str:
    info = calibration.info
    lines = ["# Camera intrinsics", "", "[image]", "", "width", str(info.width), "", "height", str(info.height), "",
             f"[{calibration.camera_name}]", "", "camera matrix", *_rows(info.K, 3), "",
             "distortion", *_rows(info.D, max(len(info.D), 1)), "", "rectification", *_rows(info.R, 3), "",
             "projection", *_rows(info.P, 4)]
    return "\n".join(lines) + "\n"
