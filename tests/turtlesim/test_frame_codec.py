"""The window's frames as bytes: round trips, the raster sent only when it changed, frames cut
anywhere, and bytes that are no frame."""

from __future__ import annotations

import random

import pytest

from kame.turtlesim import World
from kame.turtlesim.frame_codec import FrameDecoder, FrameEncoder, FrameError


def drawing_world() -> World:
    world = World(rng=random.Random(5))
    world.reset()
    world.spawn("tortuga", 2.0, 3.0, 1.0)
    return world


def test_round_trip_and_the_raster_only_when_it_changed() -> None:
    world = drawing_world()
    encoder, decoder = FrameEncoder(), FrameDecoder()
    first = world.snapshot()
    whole = encoder.encode(first)
    decoder.feed(whole)
    assert decoder.latest() == first
    world.command("turtle1", 0.0, 0.0, 1.0)  # turning: the raster is the same
    world.step()
    turned = world.snapshot()
    small = encoder.encode(turned)
    assert len(small) < 200 < 500 * 500 * 3 < len(whole)
    decoder.feed(small)
    assert decoder.latest() == turned
    world.command("turtle1", 2.0, 0.0, 0.0)
    world.step()
    moved = world.snapshot()
    decoder.feed(encoder.encode(moved))
    assert decoder.latest() == moved and moved.pixels != first.pixels


def test_frames_cut_anywhere_decode_the_same() -> None:
    world = drawing_world()
    encoder, decoder = FrameEncoder(), FrameDecoder()
    stream = b""
    snapshots = []
    for _ in range(3):
        world.command("turtle1", 1.0, 0.0, 0.5)
        world.step()
        snapshots.append(world.snapshot())
        stream += encoder.encode(snapshots[-1])
    seen = []
    for start in range(0, len(stream), 4099):
        decoder.feed(stream[start:start + 4099])
        seen.append(decoder.latest())
    assert seen[-1] == snapshots[-1]
    assert {s.version for s in seen if s is not None} <= {s.version for s in snapshots}


def test_bytes_that_are_no_frame() -> None:
    with pytest.raises(FrameError, match="not a turtlesim frame"):
        FrameDecoder().feed(b"GET / HTTP/1.1\r\n\r\n" + b"\0" * 40)
    world = drawing_world()
    encoder = FrameEncoder()
    encoder.encode(world.snapshot())
    world.command("turtle1", 0.0, 0.0, 1.0)
    world.step()
    without_raster = encoder.encode(world.snapshot())
    with pytest.raises(FrameError, match="before any raster"):
        FrameDecoder().feed(without_raster)
