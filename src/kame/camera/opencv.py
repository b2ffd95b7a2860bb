"""OpenCV for the camera packages, imported in one place so that a missing install is one clear
line naming the feature that needs it, not a traceback (OpenCV is kame's `camera` extra)."""

from __future__ import annotations

from typing import Any


class OpenCVMissing(RuntimeError):
    """OpenCV is not installed; the message names the feature and the install command."""


def cv2_for(feature: str) -> Any:
    """The cv2 module, or OpenCVMissing naming `feature`."""
    try:
        import cv2
    except ImportError as exc:
        raise OpenCVMissing(f"{feature} needs OpenCV: pip install 'kame[camera]' "
                            f"(opencv-python-headless) ({exc})") from None
    return cv2
