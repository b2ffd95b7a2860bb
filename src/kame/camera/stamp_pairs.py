"""Pairs of messages by stamp: image_transport's camera subscriber (an image and a camera_info
with the same stamp, message_filters' exact TimeSynchronizer) and a stereo pair's left and
right images (the same stamp, or within `slop` seconds as ApproximateTimeSynchronizer's slop).
Messages wait, a few of each, for their partner; the oldest waiting ones go when more come."""

from __future__ import annotations

from collections import OrderedDict
from typing import Any

WAITING = 5  # of each kind


def _stamp(message: Any) -> tuple[int, int]:
    return int(message.header.stamp.secs), int(message.header.stamp.nsecs)


class StampPairs:
    """`add_image` takes the pair's first member, `add_info` its second; each returns the pair
    (first, second) once both are there."""

    def __init__(self, slop: float = 0.0) -> None:
        self.slop_ns = int(slop * 1e9)
        self.images: OrderedDict[tuple[int, int], Any] = OrderedDict()
        self.infos: OrderedDict[tuple[int, int], Any] = OrderedDict()

    def _partner(self, waiting: OrderedDict[tuple[int, int], Any], stamp: tuple[int, int]) -> Any:
        if stamp in waiting or not self.slop_ns:
            return waiting.pop(stamp, None)
        wanted = stamp[0] * 10**9 + stamp[1]
        close = [key for key in waiting if abs(key[0] * 10**9 + key[1] - wanted) <= self.slop_ns]
        return waiting.pop(min(close, key=lambda key: abs(key[0] * 10**9 + key[1] - wanted))) if close else None

    def add_image(self, image: Any) -> tuple[Any, Any] | None:
        info = self._partner(self.infos, _stamp(image))
        if info is not None:
            return image, info
        self._keep(self.images, image)
        return None

    def add_info(self, info: Any) -> tuple[Any, Any] | None:
        image = self._partner(self.images, _stamp(info))
        if image is not None:
            return image, info
        self._keep(self.infos, info)
        return None

    @staticmethod
    def _keep(waiting: OrderedDict[tuple[int, int], Any], message: Any) -> None:
        waiting[_stamp(message)] = message
        while len(waiting) > WAITING:
            waiting.popitem(last=False)
