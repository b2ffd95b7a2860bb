"""map_server's map files: YAML fields, the pixel rules of each mode, map_saver's output."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

from kame.stage.mapfile import (
    MapError,
    load,
    occupancy,
    parse_description,
    saved_pgm,
    saved_yaml,
    saver_thresholds,
)

YAML = ("image: m.pgm\nresolution: 0.05\norigin: [-1.0, -2.0, 0.0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n")


def _png(pixels: np.ndarray, mode: str) -> bytes:
    out = io.BytesIO()
    Image.fromarray(pixels, mode).save(out, format="PNG")
    return out.getvalue()


def test_the_fields_are_read() -> None:
    d = parse_description(YAML + "mode: scale\n")
    assert (d.image, d.resolution, d.origin, d.negate, d.mode) == ("m.pgm", 0.05, (-1.0, -2.0, 0.0), False, "scale")
    assert d.image_path("maps/x.yaml") == "maps/m.pgm" and d.image_path("x.yaml") == "m.pgm"
    assert parse_description(YAML.replace("m.pgm", "/abs/m.pgm")).image_path("maps/x.yaml") == "/abs/m.pgm"
    assert parse_description(YAML).mode == "trinary"


@pytest.mark.parametrize(("change", "error"), [
    (("resolution: 0.05\n", ""), "does not contain a resolution tag"),
    (("image: m.pgm\n", ""), "does not contain an image tag"),
    (("negate: 0\n", "negate: 7\n"), "does not contain a negate tag"),
    (("origin: [-1.0, -2.0, 0.0]\n", "origin: [1, 2]\n"), "does not contain an origin tag"),
    (("free_thresh: 0.196\n", "free_thresh: 0.9\n"), "must be below its occupied_thresh"),
    (("occupied_thresh: 0.65\n", "occupied_thresh: 1.5\n"), "must lie in [0, 1]"),
    (("free_thresh: 0.196\n", "free_thresh: .nan\n"), "does not contain a free_thresh tag"),
    (("negate: 0\n", "negate: 0\nmode: fancy\n"), 'Invalid mode tag "fancy".'),
    (("resolution: 0.05\n", "resolution: 0\n"), "resolution must be above 0"),
])
def test_bad_descriptions_say_why(change: tuple[str, str], error: str) -> None:
    with pytest.raises(MapError) as raised:
        parse_description(YAML.replace(*change))
    assert error in str(raised.value)


def test_not_yaml_or_not_a_mapping() -> None:
    for text in ("[unclosed", "- a list\n"):
        with pytest.raises(MapError):
            parse_description(text)


def test_trinary_pixels_and_rows_from_the_bottom() -> None:
    pixels = np.array([[0, 254, 205], [100, 255, 180]], dtype=np.uint8)  # top row first
    grid = load(parse_description(YAML), _png(pixels, "L"), "m.png")
    # occ = (255 - v) / 255: 0 -> 1.0 occupied; 254 -> 0.004 free; 205 -> 0.196.. (not < 0.196) unknown;
    # 100 -> 0.61 unknown; 180 -> 0.29 unknown
    assert grid.cells.tolist() == [[-1, 0, -1], [100, 0, -1]]


def test_negate_scale_and_raw() -> None:
    pixels = np.array([[0, 128, 255]], dtype=np.uint8)
    negated = occupancy(pixels, None, parse_description(YAML.replace("negate: 0", "negate: 1")))
    assert negated.cells.tolist() == [[0, -1, 100]]
    scaled = occupancy(pixels, None, parse_description(YAML + "mode: scale\n"))
    ratio = ((255 - 128) / 255 - 0.196) / (0.65 - 0.196)
    assert scaled.cells.tolist() == [[100, int(1 + 98 * ratio), 0]]
    raw = occupancy(np.array([[0, 42, 100]], dtype=np.uint8), None, parse_description(YAML + "mode: raw\n"))
    assert raw.cells.tolist() == [[0, 42, 100]]
    see_through = occupancy(pixels, np.array([[255, 0, 255]], dtype=np.uint8),
                            parse_description(YAML + "mode: scale\n"))
    assert see_through.cells.tolist() == [[100, -1, 0]]


def test_colour_pixels_are_averaged() -> None:
    rgb = np.array([[[255, 255, 255], [0, 0, 30], [255, 255, 0]]], dtype=np.uint8)  # white, dark, yellow (avg 170)
    grid = load(parse_description(YAML), _png(rgb, "RGB"), "m.png")
    assert grid.cells.tolist() == [[0, 100, -1]]


def test_an_image_that_is_not_one() -> None:
    with pytest.raises(MapError, match=r'Failed to open image file "m\.pgm"'):
        load(parse_description(YAML), b"not an image", "m.pgm")


def huge_png(width: int, height: int) -> bytes:
    """A PNG of a few bytes whose header says `width` x `height` grey pixels."""
    import struct
    import zlib

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IEND", b"")


def test_an_image_header_claiming_ten_billion_pixels_is_a_map_error() -> None:
    # Pillow's DecompressionBombError is no OSError: map_server died of it with a traceback
    with pytest.raises(MapError, match=r'Failed to open image file "m\.png": Image size \(10000000000 pixels\) '
                                       r"exceeds limit of \d+ pixels, could be decompression bomb DOS attack"):
        load(parse_description(YAML), huge_png(100_000, 100_000), "m.png")


def test_saver_writes_what_map_server_reads_back() -> None:
    pixels = np.array([[0, 254, 205, 254], [254, 254, 0, 205]], dtype=np.uint8)
    description = parse_description(YAML)
    grid = load(description, _png(pixels, "L"), "m.png")
    pgm = saved_pgm(grid)
    assert pgm.startswith(b"P5\n# CREATOR: map_saver.cpp 0.050 m/pix\n4 2\n255\n")
    again = np.asarray(Image.open(io.BytesIO(pgm)))
    assert again.tolist() == pixels.tolist()
    assert saved_yaml("mymap.pgm", grid) == ("image: mymap.pgm\nresolution: 0.050000\n"
                                             "origin: [-1.000000, -2.000000, 0.000000]\nnegate: 0\n"
                                             "occupied_thresh: 0.65\nfree_thresh: 0.196\n\n")


def test_saver_thresholds() -> None:
    saver_thresholds(65, 25)
    for occupied, free in ((50, 50), (101, 0), (65, -1)):
        with pytest.raises(MapError):
            saver_thresholds(occupied, free)
