"""camera_calibration's cameracheck.py: `rosrun camera_calibration cameracheck.py --size 8x6
--square 0.108 monocular:=/usb_cam` checks a calibration on a rectified camera: for each image of
`monocular`/image_rect with its camera_info, the chessboard's linearity error (how straight its
rows are) and its reprojection error (the board's pose solved with P, its corners projected
back), in pixels; "no chessboard" when none is seen."""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Sequence
from typing import Any

import numpy as np

from kame.camera.calibrator import Board, find_chessboard, linear_error, object_points
from kame.camera.image_feed import CameraSubscriber
from kame.camera.opencv import OpenCVMissing, cv2_for
from kame.camera.pictures import PictureError, to_bgr
from kame.client import log
from kame.client.core import resolve_name
from kame.client.process import init_node, myargv, spin


def check(cv2: Any, grey: np.ndarray, projection: Sequence[float], board: Board) -> tuple[float, float] | None:
    """(linearity RMS, reprojection RMS) in pixels of the board in a rectified picture, or None."""
    corners = find_chessboard(cv2, grey, board)
    if corners is None:
        return None
    camera = np.array(projection, np.float64).reshape(3, 4)[:, :3]
    points = object_points(board)
    _, rotation, translation = cv2.solvePnP(points, corners, camera, np.zeros((4, 1)))
    projected, _ = cv2.projectPoints(points, rotation, translation, camera, np.zeros((4, 1)))
    errors = corners.reshape(-1, 2) - projected.reshape(-1, 2)
    return linear_error(corners, board), math.sqrt(float(np.sum(errors ** 2)) / errors.size)


class CameraChecker:
    def __init__(self, cv2: Any, board: Board, monocular: str) -> None:
        self.cv2 = cv2
        self.board = board
        self.subscriber = CameraSubscriber(monocular.rstrip("/") + "/image_rect", "raw", self._pair, queue_size=10)

    def _pair(self, image: Any, info: Any) -> None:
        try:
            picture = to_bgr(image, "cameracheck.py")
        except PictureError as exc:
            log.emit_throttle(5.0, log.ERROR, "%s", (exc,))
            return
        grey = picture if picture.ndim == 2 else self.cv2.cvtColor(picture, self.cv2.COLOR_BGR2GRAY)
        errors = check(self.cv2, grey, info.P, self.board)
        if errors is None:
            print("no chessboard", flush=True)
            return
        print("Linearity RMS Error: %.3f Pixels      Reprojection RMS Error: %.3f Pixels" % errors, flush=True)  # noqa: UP031 - upstream's line


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    try:
        cv2 = cv2_for("cameracheck.py")
    except OpenCVMissing as exc:
        sys.stderr.write(f"{exc}\n")
        return 1
    parser = argparse.ArgumentParser(prog="cameracheck.py")
    parser.add_argument("-s", "--size", default="8x6", help="specify chessboard size as nxm [default: %(default)s]")
    parser.add_argument("-q", "--square", default=".108", help="specify chessboard square size in meters "
                        "[default: %(default)s]")
    parser.add_argument("--approximate", type=float, default=0.0, help="allow specified slop (in seconds) when "
                        "pairing images from unsynchronized stereo cameras (kame: monocular only)")
    options = parser.parse_args(myargv(argv)[1:])
    try:
        board = Board.parse(options.size, float(options.square))
    except ValueError as exc:
        parser.error(str(exc))
    init_node("cameracheck", argv)
    CameraChecker(cv2, board, resolve_name("monocular"))
    spin()
    return 0
