"""map_server's map files: the YAML description, the image to occupancy conversion and back.

Pure (bytes and text in, values out); the map_server and map_saver nodes do the file I/O.
As map_server 1.16's image_loader and map_saver:
- YAML fields image, resolution, origin [x, y, yaw], occupied_thresh, free_thresh, negate,
  and the optional mode (trinary, the default; scale; raw). A relative image path is relative
  to the YAML file's folder.
- Each pixel's channels are averaged (alpha left out); negate inverts; raw copies the value;
  otherwise p = (255 - value) / 255 is occupied (100) above occupied_thresh, free (0) below
  free_thresh, and between them unknown (-1) in trinary mode or 1 + 98 * ratio in scale mode
  (a pixel with alpha below 255 is unknown in scale mode). Image row 0 is the top of the map.
- map_saver writes a PGM: 254 for 0..free, 0 for >= occupied, 205 for the rest, and the YAML
  map_saver writes (its fixed thresholds 0.65 and 0.196).
What kame adds: thresholds out of [0, 1] or a free_thresh not below occupied_thresh are refused
with the reason (map_server would load a map where every cell is occupied or free).
"""

from __future__ import annotations

import io
import math
import posixpath
from dataclasses import dataclass
from typing import Any

import numpy as np
import yaml

MODES = ("trinary", "scale", "raw")
FREE, OCCUPIED, UNKNOWN = 0, 100, -1
SAVER_OCCUPIED, SAVER_FREE = 65, 25  # map_saver's --occ and --free defaults (percent)


class MapError(ValueError):
    """A map description or image that cannot be loaded; the text says why."""


@dataclass(frozen=True)
class MapDescription:
    image: str  # as the YAML names it, resolved against the YAML's folder by `image_path`
    resolution: float
    origin: tuple[float, float, float]
    occupied_thresh: float
    free_thresh: float
    negate: bool
    mode: str = "trinary"

    def image_path(self, yaml_path: str) -> str:
        if posixpath.isabs(self.image):
            return self.image
        return posixpath.join(posixpath.dirname(yaml_path), self.image)


@dataclass(frozen=True)
class Grid:
    """An occupancy grid as nav_msgs/OccupancyGrid holds it: row 0 is the bottom (y = origin y)."""

    cells: np.ndarray  # int8, shape (height, width)
    resolution: float
    origin: tuple[float, float, float]

    @property
    def width(self) -> int:
        return int(self.cells.shape[1])

    @property
    def height(self) -> int:
        return int(self.cells.shape[0])


def _number(doc: dict[str, Any], key: str, what: str) -> float:
    value = doc.get(key)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise MapError(f"The map does not contain {what} tag or it is invalid.")
    return float(value)


def parse_description(text: str) -> MapDescription:
    """The YAML of a map, with map_server's error texts for missing or invalid fields."""
    try:
        doc = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        raise MapError(f"The map description is not valid YAML: {exc}") from exc
    if not isinstance(doc, dict):
        raise MapError("The map description is not a YAML mapping.")
    resolution = _number(doc, "resolution", "a resolution")
    if resolution <= 0:
        raise MapError(f"The map's resolution must be above 0, not {resolution}.")
    negate = doc.get("negate")
    if negate not in (0, 1, True, False):
        raise MapError("The map does not contain a negate tag or it is invalid.")
    occupied = _number(doc, "occupied_thresh", "an occupied_thresh")
    free = _number(doc, "free_thresh", "a free_thresh")
    if not (0.0 <= free <= 1.0 and 0.0 <= occupied <= 1.0):
        raise MapError(f"The map's thresholds must lie in [0, 1] (free_thresh {free}, occupied_thresh {occupied}).")
    if free >= occupied:
        raise MapError(f"The map's free_thresh ({free}) must be below its occupied_thresh ({occupied}).")
    mode = doc.get("mode", "trinary")
    if mode not in MODES:
        raise MapError(f'Invalid mode tag "{mode}".')
    origin = doc.get("origin")
    if (not isinstance(origin, list) or len(origin) != 3
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                       for v in origin)):
        raise MapError("The map does not contain an origin tag or it is invalid.")
    image = doc.get("image")
    if not isinstance(image, str) or not image:
        raise MapError("The map does not contain an image tag or it is invalid.")
    return MapDescription(image, resolution, (float(origin[0]), float(origin[1]), float(origin[2])),
                          occupied, free, bool(negate), mode)


def decode_image(data: bytes, name: str) -> tuple[np.ndarray, np.ndarray | None]:
    """(channel average, alpha or None) of an image file's bytes, as uint8 arrays, row 0 at the top."""
    from PIL import Image, UnidentifiedImageError

    # a header claiming more pixels than Pillow's bound (a 100,000 x 100,000 image in a few bytes)
    # raises its DecompressionBombError, an Exception of its own, before any pixel is allocated

    try:
        with Image.open(io.BytesIO(data)) as image:
            image.load()
            has_alpha = image.mode in ("RGBA", "LA", "PA") or "transparency" in image.info
            if image.mode in ("I", "I;16", "F"):  # 16-bit greys: 65535 is white
                grey = np.asarray(image.convert("F"), dtype=np.float64)
                return np.clip(grey * (255.0 / 65535.0), 0, 255).astype(np.uint8), None
            if image.mode in ("1", "L", "LA"):
                rgba = np.asarray(image.convert("LA"), dtype=np.int32)[:, :, [0, 0, 0, 1]]
                average = rgba[:, :, 0]
            else:
                rgba = np.asarray(image.convert("RGBA"), dtype=np.int32)
                average = rgba[:, :, :3].sum(axis=2) // 3  # map_server's integer average
            alpha = rgba[:, :, 3].astype(np.uint8) if has_alpha else None
            return average.astype(np.uint8), alpha
    except (UnidentifiedImageError, OSError, ValueError, Image.DecompressionBombError) as exc:
        raise MapError(f'Failed to open image file "{name}": {exc}') from exc


def occupancy(average: np.ndarray, alpha: np.ndarray | None, description: MapDescription) -> Grid:
    """The occupancy grid of an image's pixels under a map description."""
    values = average.astype(np.int32)
    if description.negate:
        values = 255 - values
    if description.mode == "raw":
        cells = values.astype(np.int8)  # raw keeps the byte (values above 127 wrap, as in map_server)
    else:
        occ = (255 - values) / 255.0
        cells = np.full(values.shape, UNKNOWN, dtype=np.int8)
        if description.mode == "scale":
            span = description.occupied_thresh - description.free_thresh
            ratio = (occ - description.free_thresh) / span
            scaled = (1 + 98 * ratio).astype(np.int8)  # C's truncating conversion
            opaque = np.ones(values.shape, dtype=bool) if alpha is None else alpha == 255
            cells = np.where(opaque, scaled, UNKNOWN).astype(np.int8)
        cells[occ > description.occupied_thresh] = OCCUPIED
        cells[occ < description.free_thresh] = FREE
    return Grid(np.ascontiguousarray(cells[::-1]), description.resolution, description.origin)


def load(description: MapDescription, image_bytes: bytes, image_name: str) -> Grid:
    average, alpha = decode_image(image_bytes, image_name)
    return occupancy(average, alpha, description)


def saved_pgm(grid: Grid, occupied: int = SAVER_OCCUPIED, free: int = SAVER_FREE) -> bytes:
    """map_saver's PGM of a grid: a header naming the resolution, then rows from the top."""
    cells = grid.cells.astype(np.int16)[::-1]
    pixels = np.full(cells.shape, 205, dtype=np.uint8)
    pixels[(cells >= 0) & (cells <= free)] = 254
    pixels[cells >= occupied] = 0
    header = f"P5\n# CREATOR: map_saver.cpp {grid.resolution:.3f} m/pix\n{grid.width} {grid.height}\n255\n"
    return header.encode("ascii") + pixels.tobytes()


def saved_yaml(image_name: str, grid: Grid) -> str:
    """map_saver's YAML beside its PGM (thresholds fixed at 0.65 and 0.196, as map_saver writes)."""
    x, y, yaw = grid.origin
    return (f"image: {image_name}\nresolution: {grid.resolution:f}\norigin: [{x:f}, {y:f}, {yaw:f}]\n"
            "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n\n")


def saver_thresholds(occupied: int, free: int) -> None:
    """map_saver's check of --occ and --free."""
    if not (0 <= free < occupied <= 100):
        raise MapError(f"--free ({free}) must be below --occ ({occupied}), both in 0..100")
