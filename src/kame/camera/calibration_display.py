"""camera_calibration's window, drawn as its calibrator node draws it (OpenCV on a BGR picture):
the camera's picture (a stereo pair's side by side; with the board's corners once found;
rectified once calibrated), and a white sidebar 100 pixels wide with the X, Y, Size and Skew
bars (each parameter's kept range, red to yellow as coverage grows, green when enough) and the
CALIBRATE, SAVE and COMMIT buttons (grey until usable); once calibrated, the sidebar reads out
the view's errors.
`button_at` is the window's click: which button a point is on, if it is usable."""

from __future__ import annotations

from typing import Any

import numpy as np

SIDEBAR = 100
BUTTONS = (("CALIBRATE", 180), ("SAVE", 280), ("COMMIT", 380))  # label, top; each 100 pixels high
FONT_SCALE = 0.6


def _y(row: int) -> int:
    return 30 + 40 * row


def _text(cv2: Any, picture: np.ndarray, text: str, origin: tuple[int, int],
          colour: tuple[int, int, int] = (0, 0, 0)) -> None:
    cv2.putText(picture, text, origin, cv2.FONT_HERSHEY_SIMPLEX, FONT_SCALE, colour, 2)


def _text_width(cv2: Any, text: str) -> tuple[int, int]:
    (width, height), _ = cv2.getTextSize(text, cv2.FONT_HERSHEY_SIMPLEX, FONT_SCALE, 2)
    return int(width), int(height)


def _button(cv2: Any, area: np.ndarray, label: str, enabled: bool) -> None:
    area.fill(255)
    width, height = area.shape[1], area.shape[0]
    cv2.circle(area, (width // 2, height // 2), min(width, height) // 2,
               (155, 155, 80) if enabled else (224, 224, 224), -1)
    text_width, text_height = _text_width(cv2, label)
    _text(cv2, area, label, ((width - text_width) // 2, (height + text_height) // 2), (255, 255, 255))


def render(cv2: Any, picture: np.ndarray, progress: list[tuple[str, float, float, float]], goodenough: bool,
           calibrated: bool, readouts: list[tuple[str, float | None]]) -> np.ndarray:
    """The window's picture: `picture` (BGR) with the sidebar on its right; once calibrated the
    sidebar reads out each (label, value): the linear error ("lin.") of a monocular view, the
    epipolar error ("epi.") and the board's square size ("dim") of a stereo pair."""
    height, width = picture.shape[:2]
    display = np.zeros((max(480, height), width + SIDEBAR, 3), np.uint8)
    display[:height, :width] = picture if picture.ndim == 3 else picture[..., None]
    display[:, width:].fill(255)
    for (label, top), enabled in zip(BUTTONS, (goodenough, calibrated, calibrated), strict=True):
        _button(cv2, display[top:top + 100, width:width + SIDEBAR], label, enabled)
    if not calibrated:
        for row, (label, low, high, done) in enumerate(progress):
            text_width, _ = _text_width(cv2, label)
            _text(cv2, display, label, (width + (SIDEBAR - text_width) // 2, _y(row)))
            colour = (0, 255, 0) if done >= 1.0 else (0, int(done * 255.0), 255)
            cv2.line(display, (int(width + low * SIDEBAR), _y(row) + 20), (int(width + high * SIDEBAR), _y(row) + 20),
                     colour, 4)
    else:
        for row, (label, value) in enumerate(readouts):
            _text(cv2, display, label, (width, _y(2 * row)))
            _text(cv2, display, "?" if value is None or value < 0 else f"{value:.2f}" if label != "dim"
                  else f"{value:.3f}", (width, _y(2 * row + 1)))
    return display


def button_at(x: int, y: int, picture_width: int, goodenough: bool, calibrated: bool) -> str | None:
    """The usable button at window point (x, y), or None."""
    if x < picture_width:
        return None
    for (label, top), enabled in zip(BUTTONS, (goodenough, calibrated, calibrated), strict=True):
        if top <= y < top + 100 and enabled:
            return label
    return None
