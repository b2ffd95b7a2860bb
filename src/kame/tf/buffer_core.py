"""tf2's BufferCore: the tree of frames, each child's cache of transforms to its parent, and
lookups between any two frames at a time.

Rules (tf2's, messages included): frame ids are stored without a leading '/'; lookups refuse
empty or '/'-prefixed ids (InvalidArgumentException) and unknown ones (LookupException); time 0
means the latest time every link of the chain has data for; a lookup walks both frames up to
their common ancestor and fails with ConnectivityException when there is none or the tree has a
loop, ExtrapolationException when a link has no data at that time. Transforms with NaNs,
no frame ids or a frame as its own parent are refused with tf2's message; a non-unit
quaternion is normalized with a warning (tf2 refuses it). Pure: no clock, no locks (the
node-layer Buffer serializes calls and waits).

Successful lookups are remembered by (target, source, time), with the frames the walk read and
their generations (each frame's count of transforms stored into its cache): a lookup whose
frames have taken no new data since is answered from memory, as the walk would give the same
answer. Errors are never remembered; clear() forgets everything.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from operator import itemgetter
from typing import Any, NamedTuple

from . import rotation
from .cache import Cache, StaticCache, Stored, TimeCache
from .errors import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TransformException,
)
from .rotation import Quaternion, Vector

DEFAULT_CACHE_TIME = 10 * 10**9
MAX_GRAPH_DEPTH = 1000
NO_PARENT = "NO_PARENT"
REMEMBERED_LOOKUPS = 4096  # results kept; the oldest is forgotten first
_LOOP = "The tf tree is invalid because it contains a loop."


class Transform(NamedTuple):
    """The pose of `child` in `parent` at `stamp` (ns): p_parent = rotation * p_child + translation."""
    parent: str
    child: str
    stamp: int
    translation: Vector
    rotation: Quaternion


class _Walk:
    """The transforms from two frames up to their common ancestor, accumulated (tf2's TransformAccum)."""

    def __init__(self) -> None:
        self.source_rotation = rotation.IDENTITY
        self.source_translation = rotation.ZERO
        self.target_rotation = rotation.IDENTITY
        self.target_translation = rotation.ZERO

    def result(self) -> tuple[Vector, Quaternion]:
        """source in target: (inverse of target-to-top) * (source-to-top)."""
        inverse_rotation = rotation.inverse(self.target_rotation)
        inverse_translation = rotation.rotate(inverse_rotation, rotation.negate(self.target_translation))
        return (rotation.add(rotation.rotate(inverse_rotation, self.source_translation), inverse_translation),
                rotation.multiply(inverse_rotation, self.source_rotation))


def strip_slash(frame: str) -> str:
    return frame[1:] if frame.startswith("/") else frame


class BufferCore:
    def __init__(self, cache_time: int = DEFAULT_CACHE_TIME, warn: Callable[[str], None] | None = None) -> None:
        """`warn` is told what tf2 logs as a warning without failing (bad frame ids given to
        can_transform); set_transform returns its refusals instead."""
        self.cache_time = cache_time
        self.warn: Callable[[str], None] = warn or (lambda text: None)
        self._names: list[str] = [NO_PARENT]
        self._numbers: dict[str, int] = {}
        self._caches: list[Cache | None] = [None]
        self._generations: list[int] = [0]
        self._remembered: dict[tuple[int, int, int], tuple[Transform, Any, Any]] = {}
        self.authority: dict[int, str] = {}

    # ------------------------------------------------------------------ frames

    def _number(self, frame: str) -> int:
        return self._numbers.get(frame, 0)

    def _insert_frame(self, frame: str) -> int:
        number = self._numbers.get(frame)
        if number is None:
            number = len(self._names)
            self._names.append(frame)
            self._numbers[frame] = number
            self._caches.append(None)
            self._generations.append(0)
        return number

    def frame_exists(self, frame: str) -> bool:
        return frame in self._numbers

    def frames(self) -> list[str]:
        return list(self._names[1:])

    def parent_of(self, frame: str, time: int = 0) -> str | None:
        """The parent of `frame` at `time`, None for a root or unknown frame."""
        cache = self._caches[self._number(frame)]
        item = cache.get(time) if cache is not None else ""
        return self._names[item.parent] if isinstance(item, Stored) else None

    def _validate(self, what: str, frame: str) -> int:
        if not frame:
            raise InvalidArgumentException(f"Invalid argument passed to {what} in tf2 frame_ids cannot be empty")
        if frame.startswith("/"):
            raise InvalidArgumentException(
                f'Invalid argument "{frame}" passed to {what} in tf2 frame_ids cannot start with a \'/\' like: ')
        number = self._number(frame)
        if not number:
            raise LookupException(f'"{frame}" passed to {what} does not exist. ')
        return number

    # ------------------------------------------------------------------ input

    def set_transform(self, transform: Transform, authority: str, is_static: bool = False) -> str | None:
        """Store one transform; None when stored, else tf2's error text. A quaternion off unit
        length by tf2's tolerance or more is normalized and stored, with a warning to `warn`
        (tf2 refuses it; ROS users expect it fixed, and a zero or infinite one is refused)."""
        child, parent = transform.child, transform.parent
        if child[:1] == "/":
            child = child[1:]
        if parent[:1] == "/":
            parent = parent[1:]
        if child == parent:
            return (f'TF_SELF_TRANSFORM: Ignoring transform from authority "{authority}" with frame_id and '
                    f'child_frame_id  "{child}" because they are the same')
        if not child:
            return (f'TF_NO_CHILD_FRAME_ID: Ignoring transform from authority "{authority}" '
                    "because child_frame_id not set ")
        if not parent:
            return (f'TF_NO_FRAME_ID: Ignoring transform with child_frame_id "{child}"  from authority "{authority}" '
                    f"because frame_id not set")
        tx, ty, tz = transform.translation
        qx, qy, qz, qw = transform.rotation
        total = tx + ty + tz + qx + qy + qz + qw
        if total != total and any(math.isnan(v) for v in (tx, ty, tz, qx, qy, qz, qw)):  # NaN != NaN
            numbers = " ".join(f"{v:f}" for v in transform.translation), " ".join(f"{v:f}" for v in transform.rotation)
            return (f'TF_NAN_INPUT: Ignoring transform for child_frame_id "{child}" from authority "{authority}" '
                    f"because of a nan value in the transform ({numbers[0]}) ({numbers[1]})")
        norm_squared = qx * qx + qy * qy + qz * qz + qw * qw
        if abs(norm_squared - 1.0) >= 10e-6:
            quaternion = " ".join(f"{v:f}" for v in transform.rotation)
            if not 0.0 < norm_squared < math.inf:
                return (f'TF_DENORMALIZED_QUATERNION: Ignoring transform for child_frame_id "{child}" from authority '
                        f'"{authority}" because of an invalid quaternion in the transform ({quaternion})')
            norm = math.sqrt(norm_squared)
            qx, qy, qz, qw = qx / norm, qy / norm, qz / norm, qw / norm
            self.warn(f'TF_DENORMALIZED_QUATERNION: Normalizing the quaternion ({quaternion}) of length {norm:f} '
                      f'in the transform for child_frame_id "{child}" from authority "{authority}"')
        known = self._numbers
        child_number = known.get(child) or self._insert_frame(child)
        parent_number = known.get(parent) or self._insert_frame(parent)
        cache = self._caches[child_number]
        if cache is None:
            cache = StaticCache() if is_static else TimeCache(self.cache_time)
            self._caches[child_number] = cache
        # tuple.__new__ skips the named tuple's Python-level __new__: this runs for every transform received
        item = tuple.__new__(Stored, (int(transform.stamp), parent_number, (tx + 0.0, ty + 0.0, tz + 0.0),
                                      (qx + 0.0, qy + 0.0, qz + 0.0, qw + 0.0)))
        refusal = cache.insert(item)
        if refusal is None:
            self.authority[child_number] = authority
            self._generations[child_number] += 1
            return None
        return (f"{refusal.value} for frame {child} at time {transform.stamp / 1e9:f} "
                f"according to authority {authority}")

    def clear(self) -> None:
        """Forget every dynamic transform (static ones stay, as in tf2)."""
        for cache in self._caches:
            if cache is not None:
                cache.clear()
        self._remembered.clear()

    # ------------------------------------------------------------------ lookups

    def lookup_transform(self, target: str, source: str, time: int) -> Transform:
        """The pose of `source` in `target` at `time` (0: the latest common time)."""
        target_number = self._validate("lookupTransform argument target_frame", target)
        source_number = self._validate("lookupTransform argument source_frame", source)
        if target_number == source_number:
            if time == 0:
                cache = self._caches[target_number]
                time = cache.latest()[0] if cache is not None else 0
            return Transform(target, source, time, rotation.ZERO, rotation.IDENTITY)
        return self._resolve(target_number, source_number, time)

    def _resolve(self, target: int, source: int, time: int) -> Transform:
        """The lookup between two distinct known frames: remembered, or walked and remembered."""
        key = (target, source, time)
        remembered = self._remembered.get(key)
        if remembered is not None:
            found, generations_of, generations = remembered
            if generations_of(self._generations) == generations:
                return found
        read: list[int] = []
        walk, stamp = self._walk(target, source, time, read)
        found = Transform(self._names[target], self._names[source], stamp, *walk.result())
        if len(self._remembered) >= REMEMBERED_LOOKUPS:
            del self._remembered[next(iter(self._remembered))]
        generations_of = itemgetter(*read)  # read holds both frames, so this always gives a tuple
        self._remembered[key] = (found, generations_of, generations_of(self._generations))
        return found

    def lookup_transform_full(self, target: str, target_time: int, source: str, source_time: int,
                              fixed: str) -> Transform:
        """`source` at `source_time` in `target` at `target_time`, through `fixed`, a frame that
        does not move between the two times."""
        self._validate("lookupTransform argument target_frame", target)
        self._validate("lookupTransform argument source_frame", source)
        self._validate("lookupTransform argument fixed_frame", fixed)
        source_in_fixed = self.lookup_transform(fixed, source, source_time)
        fixed_in_target = self.lookup_transform(target, fixed, target_time)
        return Transform(target, source, fixed_in_target.stamp, *compose(fixed_in_target, source_in_fixed))

    def can_transform(self, target: str, source: str, time: int) -> tuple[bool, str]:
        """(possible, why not), never raising (tf2's canTransform with its error string)."""
        for what, frame in (("canTransform argument target_frame", target),
                            ("canTransform argument source_frame", source)):
            if not frame:
                self.warn(f"Invalid argument passed to {what} in tf2 frame_ids cannot be empty")
                return False, ""
            if frame.startswith("/"):
                self.warn(f'Invalid argument "{frame}" passed to {what} in tf2 frame_ids cannot start '
                          f"with a '/' like: ")
                return False, ""
        target_number, source_number = self._number(target), self._number(source)
        if not target_number or not source_number:
            missing = []
            if not target_number:
                missing.append(f"canTransform: target_frame {target} does not exist.")
            if not source_number:
                missing.append(f"canTransform: source_frame {source} does not exist.")
            return False, " ".join(missing)
        if target_number == source_number:
            return True, ""
        try:
            self._resolve(target_number, source_number, time)
        except (ConnectivityException, ExtrapolationException) as exc:
            return False, str(exc)
        return True, ""

    def can_transform_full(self, target: str, target_time: int, source: str, source_time: int,
                           fixed: str) -> tuple[bool, str]:
        ok, why = self.can_transform(target, fixed, target_time)
        if not ok:
            return ok, why
        return self.can_transform(fixed, source, source_time)

    def latest_common_time(self, target: str, source: str) -> int:
        target_number = self._validate("getLatestCommonTime argument target_frame", target)
        source_number = self._validate("getLatestCommonTime argument source_frame", source)
        try:
            return self._latest_common_time(target_number, source_number, [])
        except ConnectivityException as exc:
            raise TransformException(str(exc)) from None  # tf2_py raises the base class here

    def _walk(self, target: int, source: int, time: int, read: list[int]) -> tuple[_Walk, int]:
        """Both frames' transforms up to their common ancestor at `time` (0: the latest common
        time), as tf2's walkToTopParent; raises what a lookup raises. Appends to `read` every
        frame whose cache it (or the latest common time) looked at: the answer depends on them only."""
        if time == 0:
            time = self._latest_common_time(target, source, read)
        walk = _Walk()
        caches = self._caches
        chain = rotation.chain
        translation, quaternion = rotation.ZERO, rotation.IDENTITY
        frame, top, extrapolation, extrapolated = source, source, "", False
        for _ in range(MAX_GRAPH_DEPTH + 1):
            read.append(frame)
            cache = caches[frame]
            if cache is None:  # a root
                top = frame
                break
            item = cache.get(time)
            if isinstance(item, str):
                top, extrapolation, extrapolated = frame, item, True
                break
            if frame == target:  # target is an ancestor of source
                walk.source_translation, walk.source_rotation = translation, quaternion
                return walk, time
            translation, quaternion = chain(item.rotation, item.translation, quaternion, translation)
            top, frame = frame, item.parent
        else:
            raise ConnectivityException(_LOOP + "\n" + self.all_frames_as_string())
        walk.source_translation, walk.source_rotation = translation, quaternion
        translation, quaternion = rotation.ZERO, rotation.IDENTITY
        frame = target
        for _ in range(MAX_GRAPH_DEPTH + 1):
            if frame == top:
                break
            read.append(frame)
            cache = caches[frame]
            if cache is None:
                break
            item = cache.get(time)
            if isinstance(item, str):
                raise ExtrapolationException(self._when(item, source, target))
            if frame == source:  # source is an ancestor of target
                walk.source_rotation, walk.source_translation = rotation.IDENTITY, rotation.ZERO
                walk.target_translation, walk.target_rotation = translation, quaternion
                return walk, time
            translation, quaternion = chain(item.rotation, item.translation, quaternion, translation)
            frame = item.parent
        else:
            raise ConnectivityException(_LOOP + "\n" + self.all_frames_as_string())
        if frame != top:
            if extrapolated:
                raise ExtrapolationException(self._when(extrapolation, source, target))
            raise ConnectivityException(self._unconnected(target, source))
        walk.target_translation, walk.target_rotation = translation, quaternion
        return walk, time

    def _when(self, error: str, source: int, target: int) -> str:
        return (f"{error}, when looking up transform from frame [{self._names[source]}] "
                f"to frame [{self._names[target]}]")

    def _unconnected(self, target: int, source: int) -> str:
        return (f"Could not find a connection between '{self._names[target]}' and '{self._names[source]}' "
                f"because they are not part of the same tree.Tf has two or more unconnected trees.")

    def _links_up(self, frame: int, read: list[int]) -> Iterator[tuple[int, int]]:
        """(newest stamp, parent) of each link from `frame` up to its root (tf2's
        getLatestTimeAndParent); appends each frame it reads to `read`."""
        for _ in range(MAX_GRAPH_DEPTH + 1):
            read.append(frame)
            cache = self._caches[frame]
            if cache is None:
                return
            stamp, parent = cache.latest()
            if parent == 0:
                return
            yield stamp, parent
            frame = parent
        raise ConnectivityException(_LOOP + "\n" + self.all_frames_as_string())

    def _latest_common_time(self, target: int, source: int, read: list[int]) -> int:
        """The newest time every link between the two frames has data for (tf2's
        getLatestCommonTime); static links do not limit it, and 0 means any time."""
        if source == target:
            cache = self._caches[source]
            return cache.latest()[0] if cache is not None else 0
        source_links: list[tuple[int, int]] = []
        common = 0
        for stamp, parent in self._links_up(source, read):
            common = _earlier(common, stamp)
            source_links.append((stamp, parent))
            if parent == target:
                return common
        source_parents = {parent for _, parent in source_links}
        common, common_parent = 0, 0
        for stamp, parent in self._links_up(target, read):
            common = _earlier(common, stamp)
            if parent in source_parents:
                common_parent = parent
                break
            if parent == source:
                return common
        if not common_parent:
            raise ConnectivityException(self._unconnected(target, source))
        for stamp, parent in source_links:
            common = _earlier(common, stamp)
            if parent == common_parent:
                break
        return common

    # ------------------------------------------------------------------ descriptions

    def all_frames_as_string(self) -> str:
        lines = []
        for number in range(1, len(self._names)):
            cache = self._caches[number]
            if cache is None:
                continue
            item = cache.get(0)
            parent = item.parent if isinstance(item, Stored) else 0
            lines.append(f"Frame {self._names[number]} exists with parent {self._names[parent]}.\n")
        return "".join(lines)

    def all_frames_as_yaml(self, current_time: float = 0.0) -> str:
        if len(self._names) == 1:
            return "[]"
        out = []
        for number in range(1, len(self._names)):
            cache = self._caches[number]
            if cache is None:
                continue
            item = cache.get(0)
            if not isinstance(item, Stored):
                continue
            latest, oldest = cache.latest()[0] / 1e9, cache.oldest_stamp() / 1e9
            rate = len(cache) / max(latest - oldest, 0.0001)
            out.append(f"{self._names[number]}: \n"
                       f"  parent: '{self._names[item.parent]}'\n"
                       f"  broadcaster: '{self.authority.get(number, 'no recorded authority')}'\n"
                       f"  rate: {rate:.3f}\n"
                       f"  most_recent_transform: {latest:.3f}\n"
                       f"  oldest_transform: {oldest:.3f}\n")
            if current_time > 0:
                out.append(f"  transform_delay: {current_time - latest:.3f}\n")
            out.append(f"  buffer_length: {latest - oldest:.3f}\n")
        return "".join(out)

    def all_frames_as_dot(self, current_time: float = 0.0) -> str:
        """The tree in graphviz's dot language, as tf2's allFramesAsDot (view_frames draws it)."""
        out = ["digraph G {\n"]
        if len(self._names) == 1:
            out.append('"no tf data recieved"')
        for number in range(1, len(self._names)):
            cache = self._caches[number]
            item = cache.get(0) if cache is not None else None
            if cache is None or not isinstance(item, Stored):
                continue
            latest, oldest = cache.latest()[0] / 1e9, cache.oldest_stamp() / 1e9
            rate = len(cache) / max(latest - oldest, 0.0001)
            age = f"( {current_time - latest:.3f} sec old)" if current_time > 0 else ""
            out.append(f'"{self._names[item.parent]}" -> "{self._names[number]}"[label="'
                       f"Broadcaster: {self.authority.get(number, 'no recorded authority')}\\n"
                       f"Average rate: {rate:.3f} Hz\\n"
                       f"Most recent transform: {latest:.3f} {age}\\n"
                       f'Buffer length: {latest - oldest:.3f} sec\\n"];\n')
        legend = ' subgraph cluster_legend { style=bold; color=black; label ="view_frames Result";\n'
        recorded = f'"Recorded at time: {current_time:.3f}"[ shape=plaintext ] ;\n ' if current_time > 0 else ""
        for number in range(1, len(self._names)):
            cache = self._caches[number]
            if cache is None:
                if current_time > 0:
                    out.append(f'edge [style=invis];\n{legend}{recorded}}}->"{self._names[number]}";\n')
                continue
            item = cache.get(0)
            if not isinstance(item, Stored):
                out.append(f'edge [style=invis];\n{legend}{recorded}}}->"{self._names[number]}";\n')
        out.append("}")
        return "".join(out)

    def chain(self, target: str, source: str, time: int = 0) -> list[str]:
        """The frames between source and target, both included (tf's `chain`)."""
        up_from = {}
        for start in (source, target):
            frames = [start]
            while (parent := self.parent_of(frames[-1], time)) is not None and len(frames) <= MAX_GRAPH_DEPTH:
                frames.append(parent)
            up_from[start] = frames
        down = up_from[target]
        path = []
        for frame in up_from[source]:
            path.append(frame)
            if frame in down:
                return path + list(reversed(down[:down.index(frame)]))
        return []


def _earlier(common: int, stamp: int) -> int:
    """The earlier of two times where 0 means 'no limit' (static links)."""
    if stamp == 0:
        return common
    return stamp if common == 0 else min(common, stamp)


def compose(outer: Transform, inner: Transform) -> tuple[Vector, Quaternion]:
    """outer * inner: inner's pose expressed through outer; the rotation goes through 3x3
    matrices as tf2::Transform's product does, so its sign is tf2's."""
    product = rotation.matrix_product(rotation.to_matrix(outer.rotation), rotation.to_matrix(inner.rotation))
    return (rotation.add(rotation.rotate(outer.rotation, inner.translation), outer.translation),
            rotation.from_matrix(product))

