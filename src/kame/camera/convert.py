"""camera_calibration_parsers' convert: `rosrun camera_calibration_parsers convert in.yaml out.ini`
reads a calibration in one format and writes it in the other (or the same), as the C++ tool
does, with its usage and messages."""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path

from kame.camera.calibration_files import CalibrationFileError, dump, file_format, parse


def main(argv: Sequence[str] | None = None) -> int:
    args = list(sys.argv if argv is None else argv)
    program = Path(args[0]).name
    if len(args) < 3:
        print(f"Usage: {program} input.yml output.ini\n       {program} input.ini output.yml")
        return 0
    source, target = args[1], args[2]
    try:
        calibration = parse(Path(source).read_text(), file_format(source))
    except (OSError, CalibrationFileError) as exc:
        print(f"Failed to load camera model from file {source}: {exc}")
        return 255
    try:
        Path(target).write_text(dump(calibration, file_format(target)))
    except (OSError, CalibrationFileError) as exc:
        print(f"Failed to save camera model to file {target}: {exc}")
        return 255
    print(f"Saved {target}")
    return 0
