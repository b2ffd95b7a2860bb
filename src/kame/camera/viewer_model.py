"""image_view's model (no Qt): the newest picture, the window's settings and the saved files'
names, as image_view 1.16 has them.

Rules: the window is named after the image topic unless `window_name` says otherwise;
`autosize` fits the window to the picture; a right click saves the shown picture as
`filename_format % count` (frame%04i.jpg by default), counting from 0; a left click only warns,
once, as upstream's ("Left-clicking no longer saves images. Right-click instead."). kame's
window also saves on the `s` key.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kame.camera.pictures import format_filename

LEFT_CLICK_WARNING = "Left-clicking no longer saves images. Right-click instead."


@dataclass
class ViewerSettings:
    topic: str
    window_name: str = ""
    autosize: bool = False
    filename_format: str = "frame%04i.jpg"

    @property
    def title(self) -> str:
        return self.window_name or self.topic


class ViewerModel:
    def __init__(self, settings: ViewerSettings) -> None:
        self.settings = settings
        self.picture: np.ndarray | None = None  # BGR or grey, as it is saved
        self.saved = 0
        self.left_click_warned = False

    def show(self, picture: np.ndarray) -> None:
        self.picture = picture

    def next_filename(self) -> str | None:
        """The name the shown picture is saved under, None while nothing is shown."""
        if self.picture is None:
            return None
        name = format_filename(self.settings.filename_format, self.saved)
        self.saved += 1
        return name

    def left_click(self) -> str | None:
        """The warning to log, the first time only."""
        if self.left_click_warned:
            return None
        self.left_click_warned = True
        return LEFT_CLICK_WARNING
