"""rviz's Measure and Select tools, without Qt: what a click or a dragged rectangle does, the
text rviz's status bar shows and what the tools draw over the scene.

- Measure: a left click sets the start point (on whatever geometry is under the mouse, else the
  ground), the next the end point: a line between them and its length in the status bar; a
  third click starts again, a right click resets (rviz's MeasureTool).
- Select: the objects of every display whose position projects into the dragged rectangle (a
  click: a few pixels about it) are selected: each with its name and properties, for rviz's
  Selection panel, and marked in the view. A cloud's or a scan's objects are its points (their
  position and every field), a marker's the marker (namespace/id, type, pose, scale, colour).
  rviz picks only what is not hidden behind something nearer; this selects through.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from kame.rviz.camera import Camera
from kame.rviz.display import Display, coordinates
from kame.rviz.scene import Scene

HIGHLIGHT = (1.0, 0.35, 1.0, 1.0)  # what rviz's selection boxes are drawn in (a light magenta)
CLICK_PIXELS = 3  # a click selects what is this close to it


@dataclass
class Selected:
    display: str
    name: str
    properties: dict[str, str]
    position: np.ndarray


class Measure:
    def __init__(self) -> None:
        self.start: np.ndarray | None = None
        self.end: np.ndarray | None = None
        self.overlay = Scene()  # kept while the points are: a still view is not repainted

    @property
    def length(self) -> float | None:
        return None if self.start is None or self.end is None else float(np.linalg.norm(self.end - self.start))

    def click(self, point: np.ndarray) -> None:
        if self.start is None or self.end is not None:
            self.start, self.end = np.asarray(point, dtype=float), None
        else:
            self.end = np.asarray(point, dtype=float)
        self.overlay = Scene()
        if self.end is None:
            self.overlay.add("points", [self.start], HIGHLIGHT, 6.0, overlay=True)
        else:
            self.overlay.add("lines", [self.start, self.end], HIGHLIGHT, 2.0, overlay=True)

    def reset(self) -> None:
        self.start = self.end = None
        self.overlay = Scene()

    def status(self) -> str:
        """rviz's status bar text for the tool."""
        if self.start is None:
            return "[Left-Click] Select start point [Right-Click] Reset"
        if self.end is None:
            return f"[Left-Click] Select end point [Right-Click] Reset  start: {coordinates(self.start)}"
        return f"[Left-Click] Select start point [Right-Click] Reset  length: {self.length:.3f} m"


class Selection:
    def __init__(self) -> None:
        self.selected: list[Selected] = []
        self.total = 0  # how many were inside: `selected` keeps the first `limit`
        self.overlay = Scene()

    def select(self, displays: Sequence[Display], camera: Camera, width: int, height: int,
               corner: tuple[float, float], other: tuple[float, float], limit: int = 1000) -> None:
        (x0, x1), (y0, y1) = sorted((corner[0], other[0])), sorted((corner[1], other[1]))
        if x1 - x0 < CLICK_PIXELS and y1 - y0 < CLICK_PIXELS:
            x0, x1, y0, y1 = x0 - CLICK_PIXELS, x1 + CLICK_PIXELS, y0 - CLICK_PIXELS, y1 + CLICK_PIXELS
        self.selected, self.total = [], 0
        for display in displays:
            found = display.selectable() if display.enabled else None
            if found is None or not len(found.positions):
                continue
            pixels = camera.project(found.positions, width, height)
            with np.errstate(invalid="ignore"):  # NaN: behind the camera
                inside = np.flatnonzero((pixels[:, 0] >= x0) & (pixels[:, 0] <= x1)
                                        & (pixels[:, 1] >= y0) & (pixels[:, 1] <= y1))
            self.total += len(inside)
            for index in inside[:max(0, limit - len(self.selected))]:
                name, properties = found.describe(int(index))
                self.selected.append(Selected(display.name, name, properties, found.positions[index]))
        self.overlay = Scene()
        if self.selected:
            # over everything: a marker's position is inside it
            self.overlay.add("points", np.array([s.position for s in self.selected]), HIGHLIGHT, 8.0, overlay=True)

    def clear(self) -> None:
        self.selected, self.total, self.overlay = [], 0, Scene()
