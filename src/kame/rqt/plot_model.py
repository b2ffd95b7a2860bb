"""rqt_plot's model: what to plot, and each series' bounded history (pure; numpy arrays).

Rules:
- A series is named `/topic/field/sub[index]`; `/turtle1/pose/x:y` is two series sharing the
  path before the last field (`/turtle1/pose/x`, `/turtle1/pose/y`), as rqt_plot reads it.
  Which part is the topic is decided against the master's topic list (the longest topic that
  is a prefix at a `/`).
- Plottable fields are numbers and bools, time and duration (in seconds), and elements of
  numeric arrays; completion lists the numeric fields of a message type, arrays as `name[0]`.
- A series keeps (t, value) pairs in numpy arrays, oldest first; points older than `history`
  seconds before its newest are dropped, and never more than `max_points` are kept.
  Appending is amortised O(1): the arrays have room to grow, and are compacted when full.
- What a frame draws is thinned to the pixels (visible_peaks); the value axis of an
  automatic range spans the finite values drawn (value_range), padded on both sides.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from kame.msg.fieldpath import FieldPath, FieldPathError, parse_field_path
from kame.msg.spec import split_array

DEFAULT_HISTORY = 60.0
MAX_POINTS = 2_000_000
NUMERIC = frozenset({"bool", "byte", "char", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64",
                     "float32", "float64", "time", "duration"})


def expand_series_args(args: Iterable[str]) -> list[str]:
    """`/a/b/x:y` -> `/a/b/x`, `/a/b/y`; several arguments (or commas/spaces within one) each."""
    out: list[str] = []
    for arg in args:
        for word in arg.replace(",", " ").split():
            head, _, last = word.rpartition("/")
            for field in last.split(":"):
                if field:
                    name = f"{head}/{field}" if head or word.startswith("/") else field
                    if name not in out:
                        out.append(name)
    return out


class SeriesNameError(ValueError):
    """A series name that names no published topic, or no plottable field of it."""


@dataclass(frozen=True)
class SeriesSpec:
    name: str  # as the user gave it: /turtle1/pose/x
    topic: str
    type: str
    path: FieldPath


def split_series(name: str, topic_types: Sequence[tuple[str, str]], field_check: Any = None) -> SeriesSpec:
    """The topic and field of `name` among (topic, type) pairs. `field_check(type, field)` says
    what type the field has (or raises FieldPathError); it is skipped when None (unknown class)."""
    candidates = sorted((t for t in topic_types if name.startswith(t[0].rstrip("/") + "/")), key=lambda t: -len(t[0]))
    if not candidates:
        if any(t == name for t, _ in topic_types):
            raise SeriesNameError(f"{name} is a topic: name one of its numeric fields (/topic/field)")
        raise SeriesNameError(f"no published topic in {name}")
    topic, type_name = candidates[0]
    field = name[len(topic.rstrip("/")):]
    try:
        path = parse_field_path(field)
    except FieldPathError as exc:
        raise SeriesNameError(str(exc)) from None
    if path is None:
        raise SeriesNameError(f"{name} is a topic: name one of its numeric fields (/topic/field)")
    if field_check is not None:
        try:
            kind = field_check(type_name, field.strip("/"))
        except FieldPathError as exc:
            raise SeriesNameError(str(exc)) from None
        base, is_array, _ = split_array(kind)
        if base not in NUMERIC or is_array:
            raise SeriesNameError(f"{name} is a {kind}, not a number: plot one of its numeric fields")
    return SeriesSpec(name, topic, type_name, path)


def numeric_fields(cls: Any, prefix: str = "") -> list[str]:
    """The plottable fields of a message class: `x`, `linear/x`, `position[0]`, `header/stamp`."""
    out: list[str] = []
    classes = getattr(cls, "_slot_classes", {})
    for name, slot_type in zip(cls.__slots__, cls._slot_types, strict=True):
        base, is_array, _ = split_array(slot_type)
        path = f"{prefix}{name}"
        if base in NUMERIC:
            out.append(f"{path}[0]" if is_array else path)
        elif name in classes:
            out += numeric_fields(classes[name], f"{path}[0]/" if is_array else f"{path}/")
    return out


def as_number(value: Any) -> float:
    """A field's value as a float; raises TypeError for what is not a number."""
    if isinstance(value, bool | int | float):
        return float(value)
    to_sec = getattr(value, "to_sec", None)
    if callable(to_sec):
        return float(to_sec())
    raise TypeError(f"{type(value).__name__} is not a number")


class Series:
    """One series' history: times (seconds) and values, oldest first."""

    def __init__(self, history: float = DEFAULT_HISTORY, max_points: int = MAX_POINTS) -> None:
        if history <= 0 or max_points < 2:
            raise ValueError("a series needs a positive history and room for two points")
        self.history = history
        self.max_points = max_points
        self._t = np.empty(1024)
        self._v = np.empty(1024)
        self._start = 0
        self._end = 0

    def __len__(self) -> int:
        return self._end - self._start

    def extend(self, times: Sequence[float] | np.ndarray, values: Sequence[float] | np.ndarray) -> None:
        count = len(times)
        if count == 0:
            return
        if count > self.max_points:
            times, values, count = times[-self.max_points:], values[-self.max_points:], self.max_points
        if self._end + count > len(self._t):
            self._make_room(count)
        self._t[self._end:self._end + count] = times
        self._v[self._end:self._end + count] = values
        self._end += count
        self._trim()

    def _make_room(self, count: int) -> None:
        kept = len(self)
        size = len(self._t)
        while size < 2 * (kept + count):  # at least half free after compacting: O(1) amortised
            size *= 2
        t, v = np.empty(size), np.empty(size)
        t[:kept], v[:kept] = self._t[self._start:self._end], self._v[self._start:self._end]
        self._t, self._v, self._start, self._end = t, v, 0, kept

    def _trim(self) -> None:
        newest = self._t[self._end - 1]
        first = int(np.searchsorted(self._t[self._start:self._end], newest - self.history, side="left"))
        self._start += first
        if len(self) > self.max_points:
            self._start = self._end - self.max_points

    def set_history(self, history: float) -> None:
        if history <= 0:
            raise ValueError("the history must be positive")
        self.history = history
        if len(self):
            self._trim()

    def clear(self) -> None:
        self._start = self._end = 0

    def data(self) -> tuple[np.ndarray, np.ndarray]:
        """Copies of the kept times and values (safe to hand to another thread)."""
        return self._t[self._start:self._end].copy(), self._v[self._start:self._end].copy()

    def peaks(self, start: float, end: float, bins: int) -> tuple[np.ndarray, np.ndarray]:
        """visible_peaks of the kept points, as new arrays (nothing shared with the series)."""
        t, v = visible_peaks(self._t[self._start:self._end], self._v[self._start:self._end], start, end, bins)
        return np.array(t), np.array(v)

    def last(self) -> tuple[float, float] | None:
        if not len(self):
            return None
        return float(self._t[self._end - 1]), float(self._v[self._end - 1])


def padded(low: float, high: float, padding: float) -> tuple[float, float]:
    """(low, high) widened by `padding` times its span on each side; a span of zero (a flat line)
    is widened to one unit, so the line is drawn mid-height instead of on an axis."""
    if high <= low:
        return low - 0.5, low + 0.5
    margin = (high - low) * padding
    return low - margin, high + margin


def value_range(values: Iterable[np.ndarray], padding: float = 0.02) -> tuple[float, float] | None:
    """The range of the value axis that shows every finite value of every array, padded (NaN
    and infinity are gaps in a curve, not part of its range); None when there is none."""
    low, high = np.inf, -np.inf
    for array in values:
        if not len(array):
            continue
        finite = array if np.isfinite(array).all() else array[np.isfinite(array)]
        if len(finite):
            low, high = min(low, float(finite.min())), max(high, float(finite.max()))
    if low > high:
        return None
    return padded(low, high, padding)


def visible_peaks(t: np.ndarray, v: np.ndarray, start: float, end: float, bins: int) -> tuple[np.ndarray, np.ndarray]:
    """The points of (t, v) between `start` and `end` (and one on each side, so lines reach the
    edges), thinned to at most 2 * `bins` + 2 points: each bin's minimum and maximum, in time
    order. What a screen `bins` pixels wide can show of them, at a cost that does not grow with
    the frame rate times the history."""
    first = max(int(np.searchsorted(t, start, side="left")) - 1, 0)
    last = min(int(np.searchsorted(t, end, side="right")) + 1, len(t))
    t, v = t[first:last], v[first:last]
    if bins < 1 or len(t) <= 2 * bins + 2:
        return t, v
    per_bin = len(t) // bins
    used = per_bin * bins
    tb, vb = t[:used].reshape(bins, per_bin), v[:used].reshape(bins, per_bin)
    low, high = vb.argmin(axis=1), vb.argmax(axis=1)
    rows = np.arange(bins)
    early = np.minimum(low, high)
    late = np.maximum(low, high)
    out_t = np.empty(2 * bins + (len(t) - used > 0))
    out_v = np.empty_like(out_t)
    out_t[0:2 * bins:2], out_t[1:2 * bins:2] = tb[rows, early], tb[rows, late]
    out_v[0:2 * bins:2], out_v[1:2 * bins:2] = vb[rows, early], vb[rows, late]
    if len(t) > used:  # the newest points that did not fill a bin: keep the last
        out_t[-1], out_v[-1] = t[-1], v[-1]
    return out_t, out_v
