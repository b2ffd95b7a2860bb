"""compressed_image_transport's codec (kame.image_transport.compressed), through OpenCV and through
Pillow: the formats upstream writes, what comes back, what it refuses."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from kame.image_transport.compressed import (
    Codec,
    CompressionError,
    OpenCVCodec,
    PillowCodec,
    Settings,
    compress,
    decompress,
    from_array,
    to_array,
)
from sensor_msgs.msg import CompressedImage, Image
from std_msgs.msg import Header


def _codecs() -> list[Any]:
    found = []
    try:
        import cv2
    except ImportError:
        skip = pytest.mark.skip(reason="OpenCV (opencv-python-headless) is not installed")
        found.append(pytest.param(None, marks=skip, id="opencv"))
    else:
        found.append(pytest.param(OpenCVCodec(cv2), id="opencv"))
    from PIL import Image as PilImage

    found.append(pytest.param(PillowCodec(PilImage), id="pillow"))
    return found


CODECS = _codecs()
RGB = np.zeros((16, 24, 3), np.uint8)
RGB[..., 0] = np.arange(24, dtype=np.uint8)[None, :] * 8 + 40
RGB[..., 1] = np.arange(16, dtype=np.uint8)[:, None] * 12 + 30
RGB[..., 2] = 128
HEADER = Header(seq=3, frame_id="camera")


def image(encoding: str, pixels: np.ndarray) -> Image:
    return from_array(pixels, encoding, HEADER)


def samples() -> dict[str, np.ndarray]:
    alpha = np.full((16, 24, 1), 9, np.uint8)
    return {"rgb8": RGB, "bgr8": RGB[..., ::-1], "rgba8": np.concatenate([RGB, alpha], axis=2),
            "bgra8": np.concatenate([RGB[..., ::-1], alpha], axis=2), "mono8": RGB[..., 0].copy(),
            "rgb16": RGB.astype(np.uint16) * 257, "mono16": RGB[..., 0].astype(np.uint16) * 250,
            "bayer_rggb8": RGB[..., 1].copy()}


@pytest.mark.parametrize("codec", CODECS)
@pytest.mark.parametrize(("encoding", "jpeg_format", "png_format"), [
    ("rgb8", "rgb8; jpeg compressed bgr8", "rgb8; png compressed bgr8"),
    ("bgr8", "bgr8; jpeg compressed bgr8", "bgr8; png compressed bgr8"),
    ("rgba8", "rgba8; jpeg compressed bgr8", "rgba8; png compressed bgr8"),
    ("bgra8", "bgra8; jpeg compressed bgr8", "bgra8; png compressed bgr8"),
    ("mono8", "mono8; jpeg compressed ", "mono8; png compressed "),
    ("mono16", "mono16; jpeg compressed ", "mono16; png compressed "),
    ("bayer_rggb8", "bayer_rggb8; jpeg compressed ", "bayer_rggb8; png compressed "),
])
def test_formats_and_round_trips(codec: Codec, encoding: str, jpeg_format: str, png_format: str) -> None:
    original = image(encoding, samples()[encoding])
    expected = to_array(original).astype(int)
    if encoding in ("rgba8", "bgra8"):  # the alpha channel is not sent: it comes back opaque
        expected[..., 3] = 255
    png = compress(original, Settings(format="png"), codec)
    assert png.format == png_format and bytes(png.data[:8]) == b"\x89PNG\r\n\x1a\n"
    assert png.header.frame_id == "camera"
    back = decompress(png, codec)
    assert (back.encoding, back.width, back.height, back.header.frame_id) == (encoding, 24, 16, "camera")
    assert back.step == len(back.data) // 16
    assert (to_array(back).astype(int) == expected).all()  # png is lossless
    jpeg = compress(original, Settings(), codec)
    assert jpeg.format == jpeg_format and bytes(jpeg.data[:2]) == b"\xff\xd8"
    if encoding != "mono16":  # mono16 is saturated to 8 bits for jpeg, as OpenCV's imencode does
        assert np.abs(to_array(decompress(jpeg, codec)).astype(int) - expected).max() <= 12


@pytest.mark.parametrize("codec", CODECS)
def test_16_bit_images(codec: Codec) -> None:
    deep = image("mono16", np.arange(16 * 24, dtype=np.uint16).reshape(16, 24) * 170)
    assert to_array(decompress(compress(deep, Settings(format="png"), codec), codec)).tolist() == \
        to_array(deep).tolist()
    saturated = decompress(compress(deep, Settings(), codec), codec)
    assert saturated.encoding == "mono16" and to_array(saturated).max() <= 256  # 8-bit jpeg values, mono16 data
    colour = image("rgb16", RGB.astype(np.uint16) * 257 + 3)
    jpeg = decompress(compress(colour, Settings(), codec), codec)  # sent as bgr8, scaled back to 16 bits
    assert jpeg.encoding == "rgb16" and np.abs(to_array(jpeg).astype(int) - to_array(colour)).max() <= 12 * 257
    if isinstance(codec, PillowCodec):
        with pytest.raises(CompressionError, match="a 16-bit colour png needs OpenCV"):
            compress(colour, Settings(format="png"), codec)
    else:
        png = compress(colour, Settings(format="png"), codec)
        assert png.format == "rgb16; png compressed bgr16"
        assert to_array(decompress(png, codec)).tolist() == to_array(colour).tolist()


@pytest.mark.parametrize("codec", CODECS)
def test_refusals_use_upstreams_words(codec: Codec) -> None:
    depth = Image(height=2, width=2, encoding="32FC1", step=8, data=bytes(16))
    with pytest.raises(CompressionError, match=r"^Compressed Image Transport - JPEG compression requires 8/16-bit "
                                               r"color format \(input format is: 32FC1\)$"):
        compress(depth, Settings(), codec)
    with pytest.raises(CompressionError, match=r"PNG compression requires 8/16-bit encoded color format"):
        compress(depth, Settings(format="png"), codec)
    with pytest.raises(CompressionError, match=r"^Unknown compression type 'bmp', valid options are 'jpeg' and 'png'$"):
        compress(image("mono8", RGB[..., 0].copy()), Settings(format="bmp"), codec)
    with pytest.raises(CompressionError, match=r"^Unknown encoding weird$"):
        compress(Image(height=1, width=1, encoding="weird", step=1, data=b"\0"), Settings(), codec)
    with pytest.raises(CompressionError, match=r"cannot compress a 2-channel image \(yuv422\)"):
        compress(Image(height=2, width=2, encoding="yuv422", step=4, data=bytes(8)), Settings(), codec)
    with pytest.raises(CompressionError, match="needs 72 bytes a row"):
        compress(Image(height=16, width=24, encoding="rgb8", step=24, data=bytes(384)), Settings(), codec)
    with pytest.raises(CompressionError, match="cannot decode the rgb8; jpeg compressed bgr8 image"):
        decompress(CompressedImage(format="rgb8; jpeg compressed bgr8", data=b"not a jpeg"), codec)


@pytest.mark.parametrize("codec", CODECS)
def test_padded_rows_and_big_endian_input(codec: Codec) -> None:
    values = (np.arange(6, dtype=np.uint16).reshape(2, 3) + 1) * 1000
    rows = b"".join(values[y].astype(">u2").tobytes() + b"\xee\xee" for y in range(2))
    padded = Image(height=2, width=3, encoding="mono16", is_bigendian=1, step=8, data=rows)
    back = decompress(compress(padded, Settings(format="png"), codec), codec)
    assert to_array(back).tolist() == values.tolist() and (back.is_bigendian, back.step) == (0, 6)


@pytest.mark.parametrize("codec", CODECS)
def test_formats_without_an_encoding_are_mono8_or_bgr8(codec: Codec) -> None:
    colour = compress(image("bgr8", RGB[..., ::-1].copy()), Settings(format="png"), codec)
    grey = compress(image("mono8", RGB[..., 0].copy()), Settings(format="png"), codec)
    old_colour = decompress(CompressedImage(format="png", data=colour.data), codec)
    old_grey = decompress(CompressedImage(format="jpeg", data=grey.data), codec)
    assert (old_colour.encoding, old_grey.encoding) == ("bgr8", "mono8")
    assert to_array(old_colour).tolist() == RGB[..., ::-1].tolist()
    named_rgb = decompress(CompressedImage(format="bgr8; png compressed rgb8", data=colour.data), codec)
    assert to_array(named_rgb).tolist() == RGB.tolist()  # "compressed rgb8": the codec's BGR taken as RGB


@pytest.mark.parametrize("codec", CODECS)
def test_settings_reach_the_encoder(codec: Codec) -> None:
    noisy = image("rgb8", np.random.default_rng(5).integers(0, 256, (64, 64, 3), dtype=np.uint8))
    low, high = (len(compress(noisy, Settings(jpeg_quality=q), codec).data) for q in (10, 95))
    assert low < high
    progressive = bytes(compress(noisy, Settings(jpeg_progressive=True), codec).data)
    assert b"\xff\xc2" in progressive and b"\xff\xc2" not in bytes(compress(noisy, Settings(), codec).data)
    restarts = bytes(compress(noisy, Settings(jpeg_restart_interval=4), codec).data)
    assert b"\xff\xdd" in restarts  # DRI: the restart interval is written
    smooth = image("rgb8", np.repeat(RGB, 4, axis=0))
    fast, small = (len(compress(smooth, Settings(format="png", png_level=level), codec).data) for level in (1, 9))
    assert small < fast


def test_opencv_and_pillow_read_each_others_images() -> None:
    cv2 = pytest.importorskip("cv2")
    from PIL import Image as PilImage

    opencv, pillow = OpenCVCodec(cv2), PillowCodec(PilImage)
    for encoding, pixels in samples().items():
        if encoding == "rgb16":
            continue
        for writer, reader in ((opencv, pillow), (pillow, opencv)):
            png = compress(image(encoding, pixels), Settings(format="png"), writer)
            assert to_array(decompress(png, reader)).tolist() == to_array(decompress(png, writer)).tolist(), encoding
