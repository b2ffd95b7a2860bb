"""camera_calibration's monocular calibrator (no ROS, no window): chessboard views in, K, D, R
and P out, with the coverage that decides when there are enough views.

Rules (camera_calibration 1.17's calibrator.py, whose behaviour users know):
- A view is a chessboard of `cols`x`rows` inner corners found by OpenCV (found on a copy scaled
  to about VGA, refined at full size), ordered so that its first corner is the top left, not
  within 8 pixels of the image's border.
- Each view has four parameters in 0..1: X and Y (where the board is), Size (its area's share of
  the image) and Skew (how far its corners are from square). A view is kept when the sum of its
  parameters' distances to every kept view's exceeds 0.2.
- Coverage ("progress") of each parameter is its kept range over 0.7 (X, Y), 0.4 (Size), 0.5
  (Skew), capped at 1, counting Size and Skew from 0; calibration is allowed once all are 1 or
  40 views are kept.
- Calibration is OpenCV's calibrateCamera with -k's coefficients (2: k1, k2; 3: plumb_bob's k3;
  more: the rational model), --fix-principal-point, --fix-aspect-ratio and --zero-tangent-dist;
  R is the identity and P the optimal new camera matrix at alpha 0.
- The linear error of a view is the RMS distance of each row's inner corners from the straight
  line through the row's end corners (0 for a perfect rectification).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from kame.camera.opencv import cv2_for

PARAM_NAMES = ("X", "Y", "Size", "Skew")
PARAM_RANGES = (0.7, 0.7, 0.4, 0.5)
BORDER = 8  # pixels: a board with a corner closer to the image's edge is not used
ENOUGH_VIEWS = 40


@dataclass(frozen=True)
class Board:
    cols: int  # inner corners along a row
    rows: int
    square: float  # metres

    @classmethod
    def parse(cls, size: str, square: float) -> Board:
        """"8x6" and 0.108, as --size and --square give them."""
        cols, _, rows = size.lower().partition("x")
        if not cols.isdigit() or not rows.isdigit() or int(cols) < 2 or int(rows) < 2:
            raise ValueError(f"board size {size!r}: COLSxROWS of inner corners, such as 8x6")
        return cls(int(cols), int(rows), square)


@dataclass(frozen=True)
class Options:
    k_coefficients: int = 2
    fix_principal_point: bool = False
    fix_aspect_ratio: bool = False
    zero_tangent_dist: bool = False
    max_chessboard_speed: float = -1.0  # pixels a frame; -1: any


@dataclass
class Calibration:
    K: np.ndarray
    D: np.ndarray
    R: np.ndarray
    P: np.ndarray
    size: tuple[int, int]  # width, height
    reprojection_error: float

    @property
    def distortion_model(self) -> str:
        return "rational_polynomial" if self.D.size > 5 else "plumb_bob"


@dataclass
class Detection:
    corners: np.ndarray | None  # (n, 1, 2) float32, or None when no board was found
    params: tuple[float, float, float, float] | None = None


def calibration_flags(cv2: Any, options: Options) -> int:
    flags = 0
    if options.fix_principal_point:
        flags |= cv2.CALIB_FIX_PRINCIPAL_POINT
    if options.fix_aspect_ratio:
        flags |= cv2.CALIB_FIX_ASPECT_RATIO
    if options.zero_tangent_dist:
        flags |= cv2.CALIB_ZERO_TANGENT_DIST
    k = options.k_coefficients
    if k > 3:
        flags |= cv2.CALIB_RATIONAL_MODEL
    for number, flag in enumerate(("CALIB_FIX_K1", "CALIB_FIX_K2", "CALIB_FIX_K3", "CALIB_FIX_K4", "CALIB_FIX_K5",
                                   "CALIB_FIX_K6"), 1):
        if k < number:
            flags |= getattr(cv2, flag)
    return flags


def find_chessboard(cv2: Any, grey: np.ndarray, board: Board) -> np.ndarray | None:
    """The board's corners in `grey`, first corner top left, or None."""
    height, width = grey.shape
    scale = min(1.0, math.sqrt(640 * 480 / (width * height)))
    small = grey if scale == 1.0 else cv2.resize(grey, (int(width * scale), int(height * scale)),
                                                  interpolation=cv2.INTER_AREA)
    flags = cv2.CALIB_CB_ADAPTIVE_THRESH | cv2.CALIB_CB_NORMALIZE_IMAGE | cv2.CALIB_CB_FAST_CHECK
    found, corners = cv2.findChessboardCorners(small, (board.cols, board.rows), flags=flags)
    if not found:
        return None
    corners = corners.reshape(-1, 1, 2) / scale  # (n, 1, 2) whatever the OpenCV release returns
    if not all(BORDER < x < width - BORDER and BORDER < y < height - BORDER for x, y in corners[:, 0]):
        return None
    if board.rows != board.cols:
        if corners[0, 0, 1] > corners[-1, 0, 1]:  # upside down: start from the top
            corners = np.ascontiguousarray(corners[::-1])
    else:
        direction = corners[-1, 0] - corners[0, 0]
        while direction[0] < 0 or direction[1] < 0:  # square boards: turn until it runs right and down
            corners = np.ascontiguousarray(np.rot90(corners.reshape(board.rows, board.cols, 2)).reshape(-1, 1, 2))
            direction = corners[-1, 0] - corners[0, 0]
    radius = max(2, math.ceil(min(_min_spacing(corners, board) * 0.5, 1 / scale * 5)))
    criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 0.01)
    refined: np.ndarray = cv2.cornerSubPix(grey, corners.astype(np.float32), (radius, radius), (-1, -1), criteria)
    return refined.reshape(-1, 1, 2)


def _min_spacing(corners: np.ndarray, board: Board) -> float:
    grid = corners.reshape(board.rows, board.cols, 2)
    along = np.linalg.norm(np.diff(grid, axis=1), axis=2).min()
    down = np.linalg.norm(np.diff(grid, axis=0), axis=2).min()
    return float(min(along, down))


def outside_corners(corners: np.ndarray, board: Board) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Top left, top right, bottom right, bottom left."""
    grid = corners.reshape(board.rows, board.cols, 2)
    return grid[0, 0], grid[0, -1], grid[-1, -1], grid[-1, 0]


def _angle(a: np.ndarray, b: np.ndarray) -> float:
    cosine = float(np.dot(a, b) / (np.linalg.norm(a) * np.linalg.norm(b)))
    return math.acos(max(-1.0, min(1.0, cosine)))


def view_params(corners: np.ndarray, board: Board, size: tuple[int, int]) -> tuple[float, float, float, float]:
    """(X, Y, Size, Skew) of a view, each in 0..1."""
    width, height = size
    up_left, up_right, down_right, down_left = outside_corners(corners, board)
    a, b, c = up_right - up_left, down_right - up_right, down_left - down_right
    p, q = b + c, a + b
    area = abs(float(p[0] * q[1] - p[1] * q[0])) / 2.0
    skew = min(1.0, 2.0 * abs(math.pi / 2.0 - _angle(a, b)))
    border = math.sqrt(area)
    xs, ys = corners[:, 0, 0], corners[:, 0, 1]
    p_x = min(1.0, max(0.0, (float(np.mean(xs)) - border / 2) / (width - border)))
    p_y = min(1.0, max(0.0, (float(np.mean(ys)) - border / 2) / (height - border)))
    return p_x, p_y, math.sqrt(area / (width * height)), skew


def object_points(board: Board) -> np.ndarray:
    """The board's corners in its own plane, metres, in the order the corners are found."""
    points = np.zeros((board.rows * board.cols, 1, 3), np.float32)
    index = np.arange(board.rows * board.cols)
    points[:, 0, 0] = index % board.cols
    points[:, 0, 1] = index // board.cols
    scaled: np.ndarray = points * np.float32(board.square)
    return scaled


def linear_error(corners: np.ndarray, board: Board) -> float:
    """RMS distance of each row's inner corners from the line through its end corners."""
    errors: list[float] = []
    for row in corners.reshape(board.rows, board.cols, 2).astype(np.float64):
        (x1, y1), (x2, y2) = row[0], row[-1]
        length = math.hypot(x2 - x1, y2 - y1)
        errors.extend(abs((x2 - x1) * (y1 - y0) - (x1 - x0) * (y2 - y1)) / length for x0, y0 in row[1:-1])
    return math.sqrt(sum(error * error for error in errors) / len(errors))


def is_new_view(params: tuple[float, float, float, float], kept: list[tuple[float, float, float, float]]) -> bool:
    """Whether a view's parameters are more than 0.2 (summed) from every kept view's."""
    return not kept or min(sum(abs(a - b) for a, b in zip(params, old, strict=True)) for old in kept) > 0.2


def coverage(kept: list[tuple[float, float, float, float]]) -> list[tuple[str, float, float, float]]:
    """(name, lowest, highest, progress 0..1) of each parameter over the kept views."""
    if not kept:
        return []
    values = np.array(kept)
    lows = [float(values[:, 0].min()), float(values[:, 1].min()), 0.0, 0.0]
    highs = [float(value) for value in values.max(axis=0)]
    return [(name, low, high, min((high - low) / span, 1.0))
            for name, low, high, span in zip(PARAM_NAMES, lows, highs, PARAM_RANGES, strict=True)]


def enough(progress: list[tuple[str, float, float, float]], views: int) -> bool:
    return views >= ENOUGH_VIEWS or (bool(progress) and all(done == 1.0 for *_, done in progress))


def intrinsics(cv2: Any, corners: list[np.ndarray], board: Board, size: tuple[int, int], options: Options
               ) -> tuple[float, np.ndarray, np.ndarray]:
    """OpenCV's calibrateCamera of one camera's views: (RMS reprojection error, K, D)."""
    points = [object_points(board)] * len(corners)
    error, k, d, _, _ = cv2.calibrateCamera(points, corners, size, np.eye(3), None,
                                            flags=calibration_flags(cv2, options))
    distortion = d.flat[:8].reshape(-1, 1) if options.k_coefficients > 3 else d.flat[:5].reshape(-1, 1)
    return float(error), k, distortion


@dataclass
class MonoCalibrator:
    board: Board
    options: Options = Options()
    camera_name: str = "narrow_stereo"
    views: list[tuple[tuple[float, float, float, float], np.ndarray, np.ndarray]] = field(default_factory=list)
    size: tuple[int, int] | None = None
    calibration: Calibration | None = None
    last_corners: np.ndarray | None = None
    cv2: Any = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self.cv2 = cv2_for("camera_calibration")

    def grey(self, picture: np.ndarray) -> np.ndarray:
        if picture.ndim == 2:
            return picture
        converted: np.ndarray = self.cv2.cvtColor(picture, self.cv2.COLOR_BGR2GRAY)
        return converted

    def handle(self, picture: np.ndarray) -> tuple[Detection, bool]:
        """Finds the board in a BGR or grey picture; keeps the view if it adds coverage. Returns the
        detection and whether the view was kept."""
        grey = self.grey(picture)
        size = (grey.shape[1], grey.shape[0])
        if self.size is not None and size != self.size:
            raise ValueError(f"Image size changed: {size[0]}x{size[1]} after {self.size[0]}x{self.size[1]}")
        self.size = size
        corners = find_chessboard(self.cv2, grey, self.board)
        if corners is None:
            self.last_corners = None
            return Detection(None), False
        params = view_params(corners, self.board, size)
        moving = (self.options.max_chessboard_speed > 0 and self.last_corners is not None
                  and float(np.linalg.norm(corners - self.last_corners, axis=2).mean())
                  > self.options.max_chessboard_speed)
        self.last_corners = corners
        kept = self.calibration is None and not moving and self.is_good_sample(params)
        if kept:
            self.views.append((params, corners, grey))
        return Detection(corners, params), kept

    def is_good_sample(self, params: tuple[float, float, float, float]) -> bool:
        return is_new_view(params, [kept for kept, _, _ in self.views])

    def progress(self) -> list[tuple[str, float, float, float]]:
        """(name, lowest, highest, progress 0..1) of each parameter over the kept views."""
        return coverage([params for params, _, _ in self.views])

    @property
    def goodenough(self) -> bool:
        return enough(self.progress(), len(self.views))

    def calibrate(self) -> Calibration:
        if not self.views or self.size is None:
            raise ValueError("Cannot calibrate, no good frames")
        error, k, distortion = intrinsics(self.cv2, [corners for _, corners, _ in self.views], self.board, self.size,
                                          self.options)
        new_matrix, _ = self.cv2.getOptimalNewCameraMatrix(k, distortion, self.size, 0.0)
        projection = np.zeros((3, 4))
        projection[:, :3] = new_matrix
        self.calibration = Calibration(k, distortion, np.eye(3), projection, self.size, error)
        return self.calibration

    def rectify(self, picture: np.ndarray) -> np.ndarray:
        """The picture undistorted with the calibration (P's camera matrix)."""
        assert self.calibration is not None
        calibration = self.calibration
        undistorted: np.ndarray = self.cv2.undistort(picture, calibration.K, calibration.D,
                                                     newCameraMatrix=calibration.P[:, :3])
        return undistorted

    def rectified_corners(self, corners: np.ndarray) -> np.ndarray:
        assert self.calibration is not None
        calibration = self.calibration
        points: np.ndarray = self.cv2.undistortPoints(corners, calibration.K, calibration.D, R=calibration.R,
                                                      P=calibration.P)
        return points
