"""cv_bridge: every encoding to arrays and back; the numpy colour conversions equal OpenCV's
(when OpenCV is installed) on random images; compressed images through OpenCV."""

from __future__ import annotations

import itertools
import zlib
from typing import Any

import numpy
import pytest

import cv_bridge
from cv_bridge import CvBridge, CvBridgeError
from sensor_msgs.msg import Image
from std_msgs.msg import Header

COLOUR = ["mono8", "mono16", "bgr8", "rgb8", "bgr16", "rgb16", "bgra8", "rgba8", "bgra16", "rgba16"]
ALL = [*COLOUR, "bayer_rggb8", "bayer_bggr8", "bayer_gbrg8", "bayer_grbg8", "bayer_rggb16", "bayer_bggr16",
       "bayer_gbrg16", "bayer_grbg16", "yuv422", "yuv422_yuy2",
       *(f"{d}C{c}" for d in ("8U", "8S", "16U", "16S", "32S", "32F", "64F") for c in (1, 2, 3, 4)), "32F", "16U"]
bridge = CvBridge()


def random_image(encoding: str, rng: numpy.random.Generator, height: int = 5, width: int = 7) -> Any:
    dtype_name, channels = bridge.encoding_to_dtype_with_channels(encoding)
    dtype = numpy.dtype(dtype_name)
    shape = (height, width) if channels == 1 else (height, width, channels)
    if numpy.issubdtype(dtype, numpy.integer):
        info = numpy.iinfo(dtype)
        return rng.integers(info.min, info.max, size=shape, endpoint=True, dtype=dtype)
    return rng.normal(size=shape).astype(dtype)


@pytest.mark.parametrize("encoding", ALL)
def test_every_encoding_round_trips(encoding: str) -> None:
    rng = numpy.random.default_rng(1)
    image = random_image(encoding, rng)
    msg = bridge.cv2_to_imgmsg(image, encoding, header=Header(frame_id="cam"))
    assert (msg.encoding, msg.height, msg.width, msg.header.frame_id) == (encoding, 5, 7, "cam")
    assert msg.step * msg.height == len(msg.data)
    back = bridge.imgmsg_to_cv2(msg)
    assert back.dtype == image.dtype and numpy.array_equal(back, image, equal_nan=True)


def test_padded_rows_and_big_endian_data() -> None:
    values = numpy.arange(12, dtype=">u2").reshape(3, 4)
    padded = b"".join(row.tobytes() + b"\xff\xff" for row in values)
    msg = Image(height=3, width=4, encoding="mono16", is_bigendian=True, step=10, data=padded)
    image = bridge.imgmsg_to_cv2(msg)
    assert image.dtype == numpy.dtype("uint16") and image.tolist() == values.tolist()
    assert bridge.imgmsg_to_cv2(msg, "mono8").tolist() == numpy.rint(values / 257.0).astype(int).tolist()


def test_passthrough_names_the_type_and_bad_encodings_are_refused() -> None:
    assert bridge.cv2_to_imgmsg(numpy.zeros((2, 3, 3), numpy.uint8)).encoding == "8UC3"
    assert bridge.cv2_to_imgmsg(numpy.zeros((2, 3), numpy.float32)).encoding == "32FC1"
    with pytest.raises(CvBridgeError, match="encoding specified as bgr8, but image has incompatible type 8UC1"):
        bridge.cv2_to_imgmsg(numpy.zeros((2, 3), numpy.uint8), "bgr8")
    with pytest.raises(TypeError, match="not a numpy array"):
        bridge.cv2_to_imgmsg([[1]])
    with pytest.raises(CvBridgeError, match=r"Unrecognized image encoding \[jpeg\]"):
        bridge.encoding_to_cvtype2("jpeg")
    msg = bridge.cv2_to_imgmsg(numpy.zeros((2, 3, 3), numpy.uint8), "8UC3")
    with pytest.raises(CvBridgeError, match=r"is not a color format\. but"):
        bridge.imgmsg_to_cv2(msg, "bgr8")
    with pytest.raises(CvBridgeError, match="do not have the same number of channel"):
        bridge.imgmsg_to_cv2(msg, "8UC1")
    assert bridge.encoding_to_cvtype2("bgr8") == 16 and bridge.encoding_to_cvtype2("32FC1") == 5


def test_numpy_conversions_known_values(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(cv_bridge, "_cv2", lambda: None)
    pixel = numpy.array([[[10, 200, 30]]], dtype=numpy.uint8)  # rgb8
    msg = bridge.cv2_to_imgmsg(pixel, "rgb8")
    assert bridge.imgmsg_to_cv2(msg, "bgr8").tolist() == [[[30, 200, 10]]]
    assert bridge.imgmsg_to_cv2(msg, "rgba8").tolist() == [[[10, 200, 30, 255]]]
    assert bridge.imgmsg_to_cv2(msg, "mono8").tolist() == [[(10 * 9798 + 200 * 19235 + 30 * 3735 + 16384) >> 15]]
    assert bridge.imgmsg_to_cv2(msg, "bgr16").tolist() == [[[30 * 257, 200 * 257, 10 * 257]]]
    bayer = bridge.cv2_to_imgmsg(numpy.zeros((4, 4), numpy.uint8), "bayer_rggb8")
    with pytest.raises(CvBridgeError, match="needs OpenCV"):
        bridge.imgmsg_to_cv2(bayer, "bgr8")


cv2 = pytest.importorskip("cv2")


@pytest.mark.parametrize(("src", "dst"), list(itertools.permutations(COLOUR, 2)))
def test_numpy_colour_conversions_equal_opencvs(src: str, dst: str, monkeypatch: pytest.MonkeyPatch) -> None:
    rng = numpy.random.default_rng(zlib.crc32(f"{src}>{dst}".encode()))
    msg = bridge.cv2_to_imgmsg(random_image(src, rng, 64, 48), src)
    with_opencv = bridge.imgmsg_to_cv2(msg, dst)
    monkeypatch.setattr(cv_bridge, "_cv2", lambda: None)
    with_numpy = bridge.imgmsg_to_cv2(msg, dst)
    assert with_numpy.dtype == with_opencv.dtype and numpy.array_equal(with_numpy, with_opencv)


@pytest.mark.parametrize("src", ["bayer_rggb8", "bayer_grbg16", "yuv422", "yuv422_yuy2"])
def test_bayer_and_yuv_convert_through_opencv(src: str) -> None:
    rng = numpy.random.default_rng(3)
    msg = bridge.cv2_to_imgmsg(random_image(src, rng, 8, 8), src)
    image = bridge.imgmsg_to_cv2(msg, "bgr8")
    assert image.shape == (8, 8, 3) and image.dtype == numpy.uint8
    assert bridge.imgmsg_to_cv2(msg, "mono8").shape == (8, 8)


def test_compressed_images_round_trip() -> None:
    rng = numpy.random.default_rng(4)
    image = random_image("bgr8", rng, 12, 10)
    compressed = bridge.cv2_to_compressed_imgmsg(image, dst_format="png")
    assert compressed.format == "png" and compressed.data[:4] == b"\x89PNG"
    assert numpy.array_equal(bridge.compressed_imgmsg_to_cv2(compressed), image)
    assert numpy.array_equal(bridge.compressed_imgmsg_to_cv2(compressed, "rgb8"), image[..., ::-1])
    jpeg = bridge.cv2_to_compressed_imgmsg(image)
    assert jpeg.format == "jpg" and bridge.compressed_imgmsg_to_cv2(jpeg).shape == (12, 10, 3)
