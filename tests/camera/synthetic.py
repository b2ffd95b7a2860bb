"""Chessboard views rendered through a known camera (K and distortion), for the calibration and
rectification tests: each pixel is traced back through the distortion (OpenCV's undistortPoints,
once for every view) to the board's plane, at 2x2 samples a pixel averaged (anti-aliased edges)."""

from __future__ import annotations

import cv2
import numpy as np

from kame.camera.calibrator import Board

WIDTH, HEIGHT = 640, 480
K = np.array([[610.0, 0.0, 318.5], [0.0, 605.0, 243.25], [0.0, 0.0, 1.0]])
D = np.array([-0.28, 0.09, 0.0008, -0.0005, 0.0])
BOARD = Board(8, 6, 0.108)
SUPERSAMPLE = 2


def _rays(k: np.ndarray, d: np.ndarray, width: int, height: int) -> np.ndarray:
    """The undistorted normalized coordinates of every sub-pixel sample, (h*s, w*s, 2)."""
    s = SUPERSAMPLE
    us = (np.arange(width * s) + 0.5) / s - 0.5
    vs = (np.arange(height * s) + 0.5) / s - 0.5
    grid = np.stack(np.meshgrid(us, vs), axis=-1).reshape(-1, 1, 2)
    criteria = (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 40, 1e-9)
    # the iterations to convergence: undistortPointsIter before OpenCV 5, undistortPoints' criteria since
    undistort = getattr(cv2, "undistortPointsIter", None)
    rays: np.ndarray = (undistort(grid, k, d, None, None, criteria) if undistort is not None
                        else cv2.undistortPoints(grid, k, d, None, None, None, criteria))
    return rays.reshape(height * s, width * s, 2)


class Renderer:
    def __init__(self, k: np.ndarray = K, d: np.ndarray = D, width: int = WIDTH, height: int = HEIGHT,
                 board: Board = BOARD) -> None:
        self.rays = _rays(k, d, width, height)
        self.width, self.height, self.board = width, height, board

    def view(self, rvec: tuple[float, float, float], tvec: tuple[float, float, float]) -> np.ndarray:
        """A grey picture of the board at pose (rvec, tvec): the board's first inner corner at its
        origin, its rows along x, a white margin of one square, a grey background."""
        rotation, _ = cv2.Rodrigues(np.array(rvec, np.float64))
        plane_to_image = np.column_stack([rotation[:, 0], rotation[:, 1], np.array(tvec, np.float64)])
        image_to_plane = np.linalg.inv(plane_to_image)
        xn, yn = self.rays[..., 0], self.rays[..., 1]
        homogeneous = np.einsum("ij,jhw->ihw", image_to_plane, np.stack([xn, yn, np.ones_like(xn)]))
        x, y = homogeneous[0] / homogeneous[2], homogeneous[1] / homogeneous[2]
        square = self.board.square
        col, row = np.floor(x / square), np.floor(y / square)
        on_board = (col >= -1) & (col <= self.board.cols - 1) & (row >= -1) & (row <= self.board.rows - 1)
        margin = ((col >= -2) & (col <= self.board.cols) & (row >= -2) & (row <= self.board.rows)) & ~on_board
        picture = np.full(x.shape, 128.0)
        picture[margin] = 235.0
        picture[on_board] = np.where((col[on_board] + row[on_board]) % 2 == 0, 20.0, 235.0)
        picture[homogeneous[2] <= 0] = 128.0
        s = SUPERSAMPLE
        small = picture.reshape(self.height, s, self.width, s).mean(axis=(1, 3))
        return np.clip(small, 0, 255).astype(np.uint8)


def in_view(rvec: tuple[float, float, float], tvec: tuple[float, float, float], k: np.ndarray = K,
            d: np.ndarray = D, margin: float = 12.0) -> bool:
    """Whether the whole board, its white margin included, is seen well inside the picture."""
    square = BOARD.square
    outline = np.array([[x, y, 0.0] for x in (-2 * square, BOARD.cols * square)
                        for y in (-2 * square, BOARD.rows * square)])
    steps = np.linspace(0, 1, 9)[:, None]
    sides = ((0, 1), (1, 3), (3, 2), (2, 0))
    edges = np.concatenate([outline[i] + (outline[j] - outline[i]) * steps for i, j in sides])
    points, _ = cv2.projectPoints(edges, np.array(rvec), np.array(tvec), k, d)
    u, v = points[:, 0, 0], points[:, 0, 1]
    inside_u = (u > margin).all() and (u < WIDTH - margin).all()
    return bool(inside_u and (v > margin).all() and (v < HEIGHT - margin).all())


def poses() -> list[tuple[tuple[float, float, float], tuple[float, float, float]]]:
    """Views that cover X, Y, Size and Skew as camera_calibration asks: across the image, near and
    far, tilted both ways, each wholly in the picture."""
    centre = np.array([(BOARD.cols - 1) * BOARD.square / 2, (BOARD.rows - 1) * BOARD.square / 2, 0.0])
    found = []
    for distance in (1.55, 2.1, 3.2):
        reach = 0.33 * distance
        for dx in (-reach, 0.0, reach):
            for dy in (-0.7 * reach, 0.0, 0.7 * reach):
                for tilt in ((0.0, 0.0), (0.55, 0.0), (0.0, -0.55), (-0.4, 0.4)):
                    rvec = (tilt[0], tilt[1], 0.04)
                    rotation, _ = cv2.Rodrigues(np.array(rvec))
                    tvec = np.array([dx, dy, distance]) - rotation @ centre  # its centre at (dx, dy, distance)
                    pose = (rvec, (float(tvec[0]), float(tvec[1]), float(tvec[2])))
                    if in_view(*pose):
                        found.append(pose)
    return found


BASELINE = 0.12  # metres between a stereo pair's cameras, the right one along the left's x


def stereo_poses() -> list[tuple[tuple[float, float, float], tuple[float, float, float]]]:
    """The left camera's poses of the board at which the right camera sees it whole too."""
    return [(rvec, tvec) for rvec, tvec in poses() if in_view(rvec, (tvec[0] - BASELINE, tvec[1], tvec[2]))]
