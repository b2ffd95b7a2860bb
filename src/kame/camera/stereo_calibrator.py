"""camera_calibration's stereo calibrator (no ROS, no window): pairs of chessboard views from a
left and a right camera in; each camera's K and D, the pair's rotation and translation, and the
rectification (R and P of each) out.

Rules (camera_calibration 1.17's StereoCalibrator): a pair is used when the board is found in
both pictures; its X, Y, Size and Skew are the left view's, and coverage and "enough" are the
monocular calibrator's. Calibration is each camera's calibrateCamera (with the same -k and
options), then stereoCalibrate with those intrinsics fixed, then stereoRectify at alpha 0.
After calibration, a pair's epipolar error is the RMS difference of the rectified corners' rows
(0: rows line up), and its dimension the board's square size triangulated from the pair.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from kame.camera.calibrator import (
    Board,
    Calibration,
    Options,
    coverage,
    enough,
    find_chessboard,
    intrinsics,
    is_new_view,
    object_points,
    view_params,
)
from kame.camera.opencv import cv2_for


@dataclass
class StereoCalibration:
    left: Calibration
    right: Calibration
    rotation: np.ndarray  # the right camera's, in the left's frame
    translation: np.ndarray  # metres


@dataclass
class StereoView:
    params: tuple[float, float, float, float]
    left: np.ndarray  # corners
    right: np.ndarray
    left_grey: np.ndarray
    right_grey: np.ndarray


@dataclass
class StereoCalibrator:
    board: Board
    options: Options = field(default_factory=Options)
    camera_name: str = "narrow_stereo"
    views: list[StereoView] = field(default_factory=list)
    size: tuple[int, int] | None = None
    calibration: StereoCalibration | None = None
    maps: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)
    cv2: Any = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self.cv2 = cv2_for("camera_calibration")

    def _grey(self, picture: np.ndarray) -> np.ndarray:
        if picture.ndim == 2:
            return picture
        converted: np.ndarray = self.cv2.cvtColor(picture, self.cv2.COLOR_BGR2GRAY)
        return converted

    def handle(self, left: np.ndarray, right: np.ndarray) -> tuple[np.ndarray | None, np.ndarray | None, bool]:
        """The corners found in each picture, and whether the pair was kept."""
        left_grey, right_grey = self._grey(left), self._grey(right)
        size = (left_grey.shape[1], left_grey.shape[0])
        if (right_grey.shape[1], right_grey.shape[0]) != size:
            raise ValueError(f"left and right images differ in size: {size} and {right_grey.shape[::-1]}")
        if self.size is not None and size != self.size:
            raise ValueError(f"Image size changed: {size[0]}x{size[1]} after {self.size[0]}x{self.size[1]}")
        self.size = size
        left_corners = find_chessboard(self.cv2, left_grey, self.board)
        right_corners = find_chessboard(self.cv2, right_grey, self.board)
        if left_corners is None or right_corners is None:
            return left_corners, right_corners, False
        params = view_params(left_corners, self.board, size)
        kept = self.calibration is None and is_new_view(params, [view.params for view in self.views])
        if kept:
            self.views.append(StereoView(params, left_corners, right_corners, left_grey, right_grey))
        return left_corners, right_corners, kept

    def progress(self) -> list[tuple[str, float, float, float]]:
        return coverage([view.params for view in self.views])

    @property
    def goodenough(self) -> bool:
        return enough(self.progress(), len(self.views))

    def calibrate(self) -> StereoCalibration:
        if not self.views or self.size is None:
            raise ValueError("Cannot calibrate, no good frames")
        cv2, size = self.cv2, self.size
        lefts, rights = [view.left for view in self.views], [view.right for view in self.views]
        _, k1, d1 = intrinsics(cv2, lefts, self.board, size, self.options)
        _, k2, d2 = intrinsics(cv2, rights, self.board, size, self.options)
        points = [object_points(self.board)] * len(lefts)
        error, k1, d1, k2, d2, rotation, translation, _, _ = cv2.stereoCalibrate(
            points, lefts, rights, k1, d1, k2, d2, size, flags=cv2.CALIB_FIX_INTRINSIC)
        r1, r2, p1, p2, _, _, _ = cv2.stereoRectify(k1, d1, k2, d2, size, rotation, translation, alpha=0.0)
        self.calibration = StereoCalibration(Calibration(k1, d1, r1, p1, size, float(error)),
                                             Calibration(k2, d2, r2, p2, size, float(error)), rotation, translation)
        self.maps = [cv2.initUndistortRectifyMap(side.K, side.D, side.R, side.P, size, cv2.CV_16SC2)
                     for side in (self.calibration.left, self.calibration.right)]
        return self.calibration

    def rectify(self, left: np.ndarray, right: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        assert self.maps
        return (self.cv2.remap(left, *self.maps[0], self.cv2.INTER_LINEAR),
                self.cv2.remap(right, *self.maps[1], self.cv2.INTER_LINEAR))

    def rectified_corners(self, left: np.ndarray, right: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        assert self.calibration is not None
        sides = (self.calibration.left, self.calibration.right)
        left_points, right_points = (self.cv2.undistortPoints(corners, side.K, side.D, R=side.R, P=side.P)
                                     for corners, side in zip((left, right), sides, strict=True))
        return left_points, right_points


def epipolar_error(left: np.ndarray, right: np.ndarray) -> float:
    """RMS of the rows' differences between rectified corners (pixels)."""
    difference = left[:, 0, 1] - right[:, 0, 1]
    return math.sqrt(float(np.mean(difference ** 2)))


def square_size(cv2: Any, calibration: StereoCalibration, left: np.ndarray, right: np.ndarray, board: Board) -> float:
    """The board's square size in metres, triangulated from a rectified pair of corners."""
    points = cv2.triangulatePoints(calibration.left.P, calibration.right.P, left.reshape(-1, 2).T,
                                   right.reshape(-1, 2).T)
    grid = (points[:3] / points[3]).T.reshape(board.rows, board.cols, 3)
    steps = np.concatenate([np.linalg.norm(np.diff(grid, axis=1), axis=2).ravel(),
                            np.linalg.norm(np.diff(grid, axis=0), axis=2).ravel()])
    return float(steps.mean())
