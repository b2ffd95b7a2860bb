"""Which of a marker topic's waiting messages can change what the display ends up with. Each
marker is an absolute order for its (ns, id): ADD/MODIFY sets it, DELETE removes it, DELETEALL
removes every one; so an older message whose every (ns, id) a newer one names again, or that a
newer DELETEALL clears, leaves no trace once the newer ones are applied. Reading (ns, id, action)
off the serialized bytes costs about a tenth of decoding the message (a 1,000-marker array:
under 2 ms against 10-20), so a backlog of arrays that repeat their ids is decoded once, not
once per array."""

from __future__ import annotations

import struct

from kame.rviz.markers import DELETEALL

MARKER, MARKER_ARRAY = "visualization_msgs/Marker", "visualization_msgs/MarkerArray"

_U32 = struct.Struct("<I")
_ID_ACTION = struct.Struct("<i4xi")  # id, type (skipped), action
# header: seq, stamp (12 bytes) before frame_id; after ns: id, type, action, pose (7 doubles),
# scale (3 doubles), colour (4 floats), lifetime (2 ints), frame_locked, then the points' count
_BEFORE_FRAME_ID, _BEFORE_POINTS = 12, 117

Summary = list[tuple[bytes, int, int]]  # each marker's ns (utf-8), id and action, in order


def marker_keys(payload: bytes | memoryview, array: bool) -> Summary:
    """The (ns, id, action) of each marker of a serialized Marker (`array` False) or
    MarkerArray; struct.error or ValueError when the bytes are not one."""
    buf = memoryview(payload)
    u32, id_action = _U32.unpack_from, _ID_ACTION.unpack_from
    count, end = (u32(buf, 0)[0], 4) if array else (1, 0)
    found: Summary = []
    for _ in range(count):
        end += _BEFORE_FRAME_ID + 4 + u32(buf, end + _BEFORE_FRAME_ID)[0]
        start = end + 4
        end = start + u32(buf, end)[0]
        ns = bytes(buf[start:end])
        marker_id, action = id_action(buf, end)
        end += _BEFORE_POINTS + 4 + 24 * u32(buf, end + _BEFORE_POINTS)[0]
        end += 4 + 16 * u32(buf, end)[0]  # colours
        end += 4 + u32(buf, end)[0]  # text
        end += 4 + u32(buf, end)[0] + 1  # mesh_resource, mesh_use_embedded_materials
        found.append((ns, marker_id, action))
    if end > len(buf):
        raise ValueError("truncated marker message")
    return found


def needed(summaries: list[Summary | None]) -> list[bool]:
    """For each waiting message, oldest first, whether applying it can change the final markers
    (None: unreadable, kept for the decoder to judge). The newest is always needed (it is the
    display's last message); a DELETEALL is needed unless a newer one follows."""
    keep = [False] * len(summaries)
    named: set[tuple[bytes, int]] = set()  # by a newer message
    cleared = False  # a newer message has a DELETEALL
    for index in range(len(summaries) - 1, -1, -1):
        summary = summaries[index]
        if summary is None:
            keep[index] = True
            continue
        clears = any(action == DELETEALL for _, _, action in summary)
        keys = {(ns, marker_id) for ns, marker_id, action in summary if action != DELETEALL}
        keep[index] = index == len(summaries) - 1 or (not cleared and (clears or not keys <= named))
        named |= keys
        cleared = cleared or clears
    return keep


def still_needed(payloads: list[bytes], array: bool) -> list[bytes]:
    """The serialized marker messages (Marker, or MarkerArray if `array`) that needed() keeps."""
    summaries: list[Summary | None] = []
    for payload in payloads:
        try:
            summaries.append(marker_keys(payload, array))
        except (struct.error, ValueError):
            summaries.append(None)
    return [payload for payload, keep in zip(payloads, needed(summaries), strict=True) if keep]
