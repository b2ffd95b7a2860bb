"""rviz's colour transformers for point clouds and laser scans (rviz 1.14's
point_cloud_transformers.cpp): each point's colour from a field of the cloud, vectorised over
every point at once.

- RGB8: the packed `rgb` (or `rgba`) field, 0x00RRGGBB in 4 bytes (float32 or uint32).
- RGBF32: float `r`, `g`, `b` fields, 0..1.
- MONO8: the packed rgb as grey (0.3 R + 0.59 G + 0.11 B).
- Intensity: a field ("Channel Name", default "intensity"; a scan's intensities) between Min and
  Max Intensity (the cloud's own bounds while "Autocompute Intensity Bounds"), as rviz's rainbow
  (the lowest red, the highest magenta; "Invert Rainbow" turns it) or, without "Use rainbow",
  blended from Min Color to Max Color.
- AxisColor: the rainbow along X, Y or Z ("Axis") of the fixed frame ("Use Fixed Frame") or
  of the cloud's own, between Min and Max Value ("Autocompute Value Bounds").
- FlatColor: "Color" for every point.

Which applies, as rviz chooses: the named one while the cloud has what it reads; otherwise
(and for "", a display that never saw a cloud) RGB8 when the cloud has rgb, else Intensity. An
Intensity channel the cloud lacks draws the flat colour.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from kame.rviz.display import parse_color
from kame.rviz.scene import Color

RGB8, RGBF32, MONO8, INTENSITY = "RGB8", "RGBF32", "MONO8", "Intensity"
AXIS_COLOR, FLAT_COLOR = "AxisColor", "FlatColor"


def rainbow(values: np.ndarray) -> np.ndarray:
    """rviz's getRainbowColor for each value (0..1, clamped): an HSV hue from red at 1 to
    magenta at 0 (NaN: magenta, a point drawn nowhere); N x 3 float32."""
    value = np.nan_to_num(np.clip(np.asarray(values, dtype=np.float32), 0.0, 1.0), nan=0.0)
    h = value * 5.0 + 1.0
    i = np.floor(h).astype(np.int32)
    f = h - i
    f = np.where(i % 2 == 0, 1.0 - f, f)
    n = (1.0 - f).astype(np.float32)
    zero, one = np.zeros_like(n), np.ones_like(n)
    out = np.empty((len(value), 3), dtype=np.float32)
    for channel, (low, two, three, four, high) in enumerate((
            (n, zero, zero, n, one), (zero, n, one, one, n), (one, one, n, zero, zero))):
        out[:, channel] = np.select([i <= 1, i == 2, i == 3, i == 4], [low, two, three, four], high)
    return out


def chosen(name: str, fields: Mapping[str, np.ndarray] | Any) -> str:
    """The transformer rviz uses for a cloud with these field names."""
    has_rgb = "rgb" in fields or "rgba" in fields
    supported = {RGB8: has_rgb, MONO8: has_rgb, RGBF32: all(c in fields for c in "rgb"),
                 INTENSITY: True, AXIS_COLOR: True, FLAT_COLOR: True}
    if supported.get(name, False):
        return name
    return RGB8 if has_rgb else INTENSITY


def _bounds(options: Mapping[str, Any], auto_key: str, low_key: str, high_key: str,
            values: np.ndarray) -> tuple[float, float]:
    """rviz's Min/Max: the values' own while autocomputing (the default), else the options'. A
    .rviz file keeps AxisColor's as children of "Autocompute Value Bounds"."""
    auto = options.get(auto_key, True)
    nested = auto if isinstance(auto, Mapping) else options
    flag = nested.get("Value", True) if isinstance(auto, Mapping) else auto
    if str(flag).lower() != "false" and len(values):
        finite = values[np.isfinite(values)]
        if len(finite):
            return float(finite.min()), float(finite.max())
    try:
        return float(nested.get(low_key, 0.0)), float(nested.get(high_key, 1.0))
    except (TypeError, ValueError):
        return 0.0, 1.0


def _flag(options: Mapping[str, Any], key: str, default: bool) -> bool:
    value = options.get(key, default)
    return value if isinstance(value, bool) else str(value).lower() == "true"


def point_colors(options: Mapping[str, Any], fields: Mapping[str, np.ndarray], fixed_axis: np.ndarray | None,
                 local: np.ndarray, flat: Color) -> np.ndarray | Color:
    """The points' colours under the display's options: N x 4 uint8 (alpha from "Alpha"), or
    the one colour `flat` (RGBA floats) when every point has it. `fields` are the cloud's
    fields, one value per point; `local` the points (N x 3) in the cloud's own frame;
    `fixed_axis` the 4 x 4 placement of that frame in the fixed frame (AxisColor's "Use Fixed
    Frame")."""
    name = chosen(str(options.get("Color Transformer", "")), fields)
    alpha = round(255 * min(1.0, max(0.0, float(flat[3]))))
    if name in (RGB8, MONO8):
        packed = np.ascontiguousarray(fields["rgb"] if "rgb" in fields else fields["rgba"])
        packed = packed.view(np.uint32) if packed.dtype.itemsize == 4 else packed.astype(np.uint32)
        colors = np.empty((len(packed), 4), dtype=np.uint8)
        for channel, shift in enumerate((16, 8, 0)):
            colors[:, channel] = (packed >> shift) & 255
        if name == MONO8:
            grey = (0.3 * colors[:, 0] + 0.59 * colors[:, 1] + 0.11 * colors[:, 2]).astype(np.uint8)
            colors[:, 0] = colors[:, 1] = colors[:, 2] = grey
        if "rgb" in fields:
            colors[:, 3] = alpha
        else:  # rgba's own alpha in the top byte, under the display's
            colors[:, 3] = ((packed >> 24) & 255) * alpha // 255
        return colors
    if name == RGBF32:
        rgb = np.column_stack([np.asarray(fields[c], dtype=np.float32) for c in "rgb"])
        return _bytes(rgb, alpha)
    if name == INTENSITY:
        channel_name = str(options.get("Channel Name", "intensity") or "intensity")
        if channel_name not in fields:
            return flat
        values = np.asarray(fields[channel_name], dtype=np.float32)
        low, high = _bounds(options, "Autocompute Intensity Bounds", "Min Intensity", "Max Intensity", values)
        span = high - low if high != low else 1e20  # rviz's: one intensity is the rainbow's red
        normalised = (values - low) / span
        if _flag(options, "Use rainbow", True):
            value = 1.0 - normalised
            return _bytes(rainbow(1.0 - value if _flag(options, "Invert Rainbow", False) else value), alpha)
        normalised = np.clip(normalised, 0.0, 1.0)[:, None]
        low_color = np.array(parse_color(options.get("Min Color"), (0.0, 0.0, 0.0, 1.0))[:3], dtype=np.float32)
        high_color = np.array(parse_color(options.get("Max Color"), (1.0, 1.0, 1.0, 1.0))[:3], dtype=np.float32)
        return _bytes(high_color * normalised + low_color * (1.0 - normalised), alpha)
    if name == AXIS_COLOR:
        axis = "XYZ".index(str(options.get("Axis", "Z"))) if str(options.get("Axis", "Z")) in "XYZ" else 2
        if fixed_axis is not None and _flag(options, "Use Fixed Frame", True):
            row = fixed_axis[axis]
            values = (local[:, 0] * row[0] + local[:, 1] * row[1] + local[:, 2] * row[2] + row[3]).astype(np.float32)
        else:
            values = np.asarray(local[:, axis], dtype=np.float32)
        low, high = _bounds(options, "Autocompute Value Bounds", "Min Value", "Max Value", values)
        span = high - low if high != low else 0.001
        return _bytes(rainbow(1.0 - (values - low) / span), alpha)
    return flat


def _bytes(rgb: np.ndarray, alpha: int) -> np.ndarray:
    """N x 3 floats 0..1 as N x 4 uint8 with `alpha`: a quarter of the bytes to upload."""
    colors = np.empty((len(rgb), 4), dtype=np.uint8)
    colors[:, :3] = np.clip(np.nan_to_num(rgb * 255 + 0.5, nan=0.0), 0, 255)
    colors[:, 3] = alpha
    return colors
