"""What every display shares: its name, Enabled, options under rviz's own keys (so a .rviz
file's values load as they are), a status (OK, or a warning with its reason), the newest
message (latest wins: messages arriving faster than the frame rate are coalesced) and the
frames it asks of tf."""

from __future__ import annotations

import abc
import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar, Protocol

import numpy as np

from kame.rviz.scene import Color, Scene

OK, WARN, ERROR = "Ok", "Warn", "Error"
FIXED_FRAME = "<Fixed Frame>"


class Frames(Protocol):
    """The tf tree as the displays see it, for the fixed frame of the frame being drawn."""

    fixed_frame: str

    def transform(self, frame_id: str) -> np.ndarray | str:
        """The 4x4 matrix taking points of `frame_id` into the fixed frame, or why there is none."""

    def names(self) -> list[str]:
        """Every frame tf knows."""

    def parent(self, frame_id: str) -> str | None:
        ...


@dataclass
class Status:
    level: str = OK
    text: str = ""


def parse_color(value: Any, default: Color = (1.0, 1.0, 1.0, 1.0)) -> Color:
    """rviz writes colours as "R; G; B" (0..255)."""
    try:
        parts = [float(p) for p in str(value).split(";")]
    except ValueError:
        return default
    if len(parts) < 3:
        return default
    return parts[0] / 255, parts[1] / 255, parts[2] / 255, 1.0


@dataclass
class Selectable:
    """What of a display rviz's Select tool can pick: the objects' fixed-frame positions
    (N x 3), and for the i-th its name and properties."""
    positions: np.ndarray
    describe: Callable[[int], tuple[str, dict[str, str]]]


def coordinates(values: Sequence[float] | np.ndarray) -> str:
    """A position as rviz's panels write one: "x; y; z"."""
    return "; ".join(f"{float(v):.4g}" for v in values)


def format_color(color: Color) -> str:
    return "; ".join(str(round(c * 255)) for c in color[:3])


def edited_option(old: Any, text: str) -> Any:
    """An option's value typed into the Displays panel: a number where the option held one
    (whole only when the text is: 0.5 typed over a Cell Size of 1 is 0.5), else the text as
    typed (a flag's "false" included: Display.flag reads it)."""
    if isinstance(old, bool) or not isinstance(old, (int, float)):
        return text
    try:
        number = float(text)
    except ValueError:
        return text
    return int(number) if isinstance(old, int) and number.is_integer() else number


class RecordingFrames:
    """Frames that remember every lookup, so a display's last scene can be reused while its
    message, options and every transform it used are the same."""

    def __init__(self, frames: Frames) -> None:
        self.frames = frames
        self.fixed_frame = frames.fixed_frame
        self.lookups: dict[str, np.ndarray | str] = {}
        self.tree: list[tuple[str, str | None]] | None = None

    def transform(self, frame_id: str) -> np.ndarray | str:
        if frame_id not in self.lookups:
            self.lookups[frame_id] = self.frames.transform(frame_id)
        return self.lookups[frame_id]

    def names(self) -> list[str]:
        names = self.frames.names()
        self.tree = [(name, self.frames.parent(name)) for name in names]
        return names

    def parent(self, frame_id: str) -> str | None:
        return self.frames.parent(frame_id)

    def unchanged(self, frames: Frames) -> bool:
        """Whether `frames` still answer every lookup (and list the same tree) as these did."""
        if frames.fixed_frame != self.fixed_frame:
            return False
        if self.tree is not None and self.tree != [(n, frames.parent(n)) for n in frames.names()]:
            return False
        for frame_id, before in self.lookups.items():
            now = frames.transform(frame_id)
            if isinstance(before, str) or isinstance(now, str):
                # a reason against a matrix (tf has just filled in) is a change; == would compare elementwise
                if not (isinstance(before, str) and isinstance(now, str) and before == now):
                    return False
            elif not np.array_equal(before, now):
                return False
        return True


class Display(abc.ABC):
    class_name: ClassVar[str] = ""
    message_types: ClassVar[tuple[str, ...]] = ()  # the first is what a new display subscribes as
    defaults: ClassVar[dict[str, Any]] = {}
    keeps_every_message: ClassVar[bool] = False  # markers: each message adds or deletes some
    topic_key: ClassVar[str] = "Topic"  # the option rviz keeps the display's topic under

    def __init__(self, name: str = "", enabled: bool = True, options: dict[str, Any] | None = None) -> None:
        self.name = name or self.class_name.split("/")[-1]
        self.enabled = enabled
        self.options: dict[str, Any] = {**self.defaults, **(options or {})}
        self.status = Status()
        self.message: Any = None
        self.version = 0  # counts what receive() changed: the cached scene is for one version
        self.expires_at = math.inf  # when the first thing drawn last is gone by time alone (draw sets it)
        self._cached: tuple[Any, RecordingFrames, Scene, Status] | None = None

    # ------------------------------------------------------------------ options

    @property
    def topic(self) -> str:
        return str(self.options.get(self.topic_key, ""))

    def color(self, key: str = "Color") -> Color:
        r, g, b, _ = parse_color(self.options.get(key), parse_color(self.defaults.get(key, "255; 255; 255")))
        return r, g, b, self.number("Alpha", 1.0)

    def number(self, key: str, default: float) -> float:
        try:
            return float(self.options.get(key, default))
        except (TypeError, ValueError):
            return default

    def flag(self, key: str, default: bool = True) -> bool:
        value = self.options.get(key, default)
        return value if isinstance(value, bool) else str(value).lower() == "true"

    def reference_frame(self, frames: Frames) -> str:
        frame = str(self.options.get("Reference Frame", FIXED_FRAME))
        return frames.fixed_frame if frame in ("", FIXED_FRAME) else frame

    # ------------------------------------------------------------------ messages

    def receive(self, messages: Iterable[Any], now: float) -> None:
        """New messages, oldest first: a display that needs only the newest keeps the last."""
        for message in messages:
            self.message = message
            self.version += 1

    def subscription(self) -> tuple[str, str] | None:
        """The topic (resolved or not) and message type this display shows; None: none."""
        return (self.topic, self.message_types[0]) if self.message_types and self.topic else None

    def side_topics(self) -> dict[str, str]:
        """Other topics (resolved or not) -> message type this display reads (Camera's CameraInfo)."""
        return {}

    def receive_side(self, topic: str, messages: list[Any], now: float) -> None:
        """New messages of one of side_topics(), oldest first (a display with none ignores this)."""
        return None

    def reset(self) -> None:
        self.message = None
        self.version += 1
        self.status = Status()

    def expired(self, now: float) -> bool:
        """Whether the scene last drawn has something that is gone by `now` alone (a marker
        whose lifetime ran out, a decayed cloud): it is drawn again then, not every frame."""
        return now > self.expires_at

    def build(self, scene: Scene, frames: Frames, now: float) -> None:
        if not self.enabled:
            self.status = Status(OK, "disabled")
            return
        if self.message_types and self.message is None:
            self.status = Status(WARN, f"no messages received on {self.topic or '(no topic)'}")
            return
        key = (self.version, repr(self.options))
        cached = self._cached
        if cached is not None and cached[0] == key and not self.expired(now) and cached[1].unchanged(frames):
            scene.extend(cached[2])
            self.status = cached[3]
            return
        self.status = Status()
        self.expires_at = math.inf
        recording = RecordingFrames(frames)
        own = Scene()
        self.draw(own, recording, now)
        own = own.merged()
        self._cached = (key, recording, own, self.status)
        scene.extend(own)

    def selectable(self) -> Selectable | None:
        """What the Select tool can pick of the scene last drawn (None: nothing)."""
        return None

    @abc.abstractmethod
    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        """Add this display's geometry, in the fixed frame, to `scene` (each kind draws its own)."""

    def placed(self, frames: Frames, frame_id: str) -> np.ndarray | None:
        """The matrix of `frame_id` in the fixed frame; None (and the status says why) if tf has none."""
        found = frames.transform(frame_id)
        if isinstance(found, str):
            self.status = Status(WARN, found)
            return None
        return found
