"""image_transport's camera subscriber, its pairing rule: an image and a camera_info with the
same stamp make a pair (message_filters' exact TimeSynchronizer). Messages wait, a few of each,
for their partner; the oldest waiting ones go when more come."""

from __future__ import annotations

from collections import OrderedDict
from typing import Any

WAITING = 5  # of each kind


def _stamp(message: Any) -> tuple[int, int]:
    return int(message.header.stamp.secs), int(message.header.stamp.nsecs)


class StampPairs:
    def __init__(self) -> None:
        self.images: OrderedDict[tuple[int, int], Any] = OrderedDict()
        self.infos: OrderedDict[tuple[int, int], Any] = OrderedDict()

    def add_image(self, image: Any) -> tuple[Any, Any] | None:
        info = self.infos.pop(_stamp(image), None)
        if info is not None:
            return image, info
        self._keep(self.images, image)
        return None

    def add_info(self, info: Any) -> tuple[Any, Any] | None:
        image = self.images.pop(_stamp(info), None)
        if image is not None:
            return image, info
        self._keep(self.infos, info)
        return None

    @staticmethod
    def _keep(waiting: OrderedDict[tuple[int, int], Any], message: Any) -> None:
        waiting[_stamp(message)] = message
        while len(waiting) > WAITING:
            waiting.popitem(last=False)
