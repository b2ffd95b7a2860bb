"""compressed_image_transport's codec: sensor_msgs/Image to CompressedImage (jpeg or png) and back.

Compressing follows compressed_image_transport's publisher: colour images (rgb/bgr/rgba/bgra, 8
or 16 bits) are turned to bgr8 for jpeg and to bgr8 or bgr16 for png, alpha dropped, and the
format names both ends ("rgb8; jpeg compressed bgr8"); other 8- and 16-bit images are written as
they are ("mono8; png compressed ", with its trailing space), a type the codec cannot hold
saturated to 8 bits as OpenCV's imencode does. Depths other than 8 and 16 bits, unknown
encodings and formats other than jpeg and png are refused with upstream's words.

Decompressing follows its subscriber: the encoding is the format's text before ';' (a format
without one is mono8 or bgr8 by the channel count) and colours are put back in that encoding's
order, alpha added at the depth's maximum. One difference: when the codec changed the depth
(an rgb16 image sent as 8-bit jpeg), the pixels are scaled back to 16 bits, so the data always
fits the encoding it is named by, where upstream returns 8-bit data named rgb16.

The codec is OpenCV's imencode/imdecode when `cv2` is installed (as cv_bridge uses it), else
Pillow's; Pillow cannot write 16-bit colour png and says so.
"""

from __future__ import annotations

import io
import re
from dataclasses import dataclass
from typing import Any, Protocol

import numpy

from sensor_msgs.msg import CompressedImage, Image

FORMATS = ("jpeg", "png")
_COLOUR = re.compile(r"(rgb|bgr)(a?)(8|16)\Z")
_NUMERIC = re.compile(r"(8U|8S|16U|16S|32S|32F|64F)(?:C([1-9][0-9]*))?\Z")
_DTYPES = {"8U": "u1", "8S": "i1", "16U": "u2", "16S": "i2", "32S": "i4", "32F": "f4", "64F": "f8"}
_ONE_CHANNEL = {"mono8": "8U", "mono16": "16U", **{f"bayer_{p}{d}": f"{d}U" for p in ("rggb", "bggr", "gbrg", "grbg")
                                                   for d in ("8", "16")}}


class CompressionError(ValueError):
    """An image the compressed transport refuses or cannot decode."""


@dataclass(frozen=True)
class Settings:
    """The compressed publisher's parameters (its dynamic_reconfigure config), upstream's defaults."""

    format: str = "jpeg"
    jpeg_quality: int = 80
    jpeg_progressive: bool = False
    jpeg_optimize: bool = False
    jpeg_restart_interval: int = 0
    png_level: int = 9


def layout(encoding: str) -> tuple[str, int]:
    """(numpy type code, channels) of a ROS image encoding, as sensor_msgs/image_encodings.h has them."""
    colour = _COLOUR.match(encoding)
    if colour:
        return ("u1" if colour.group(3) == "8" else "u2"), 4 if colour.group(2) else 3
    if encoding in _ONE_CHANNEL:
        return _DTYPES[_ONE_CHANNEL[encoding]], 1
    if encoding in ("yuv422", "yuv422_yuy2"):
        return "u1", 2
    numeric = _NUMERIC.match(encoding)
    if numeric is None:
        raise CompressionError(f"Unknown encoding {encoding}")
    return _DTYPES[numeric.group(1)], int(numeric.group(2) or 1)


def to_array(image: Any) -> numpy.ndarray[Any, Any]:
    """The image's pixels, (height, width) or (height, width, channels), in native byte order."""
    code, channels = layout(image.encoding)
    dtype = numpy.dtype(code).newbyteorder(">" if image.is_bigendian else "<")
    row = image.width * channels * dtype.itemsize
    data = bytes(image.data)
    if image.step < row or len(data) < image.step * image.height:
        raise CompressionError(f"a {image.width}x{image.height} {image.encoding} image needs {row} bytes a row and "
                               f"step x height bytes; it has step {image.step} and {len(data)} bytes")
    pixels = numpy.ndarray((image.height, image.width, channels), dtype, data,
                           strides=(image.step, channels * dtype.itemsize, dtype.itemsize))
    native: numpy.ndarray[Any, Any] = pixels.astype(dtype.newbyteorder("="), copy=False)  # a view when it can be
    return native[..., 0] if channels == 1 else native


def from_array(pixels: numpy.ndarray[Any, Any], encoding: str, header: Any) -> Image:
    """An Image of native-order pixels (little-endian on the wire, as cv_bridge writes on x86)."""
    height, width = pixels.shape[:2]
    data = pixels.astype(pixels.dtype.newbyteorder("<"), copy=False).tobytes()
    return Image(header=header, height=height, width=width, encoding=encoding, is_bigendian=0,
                 step=len(data) // height if height else 0, data=data)


class Codec(Protocol):
    """jpeg and png in OpenCV's channel order (BGR, BGRA), or with red and blue swapped (`rgb`)."""

    def encode(self, pixels: numpy.ndarray[Any, Any], settings: Settings, rgb: bool = False) -> bytes:
        """jpeg or png bytes of 1-, 3- or 4-channel pixels of uint8 (or uint16 for png)."""

    def decode(self, data: bytes, rgb: bool = False) -> numpy.ndarray[Any, Any] | None:
        """Pixels as OpenCV's imdecode(IMREAD_UNCHANGED) gives them, None if undecodable."""


class OpenCVCodec:
    def __init__(self, cv2: Any) -> None:
        self.cv2 = cv2

    def encode(self, pixels: numpy.ndarray[Any, Any], settings: Settings, rgb: bool = False) -> bytes:
        cv2 = self.cv2
        pixels = numpy.ascontiguousarray(pixels)
        if rgb and pixels.ndim == 3:
            pixels = cv2.cvtColor(pixels, cv2.COLOR_RGB2BGR if pixels.shape[2] == 3 else cv2.COLOR_RGBA2BGRA)
        if settings.format == "jpeg":
            params = [cv2.IMWRITE_JPEG_QUALITY, settings.jpeg_quality,
                      cv2.IMWRITE_JPEG_PROGRESSIVE, int(settings.jpeg_progressive),
                      cv2.IMWRITE_JPEG_OPTIMIZE, int(settings.jpeg_optimize),
                      cv2.IMWRITE_JPEG_RST_INTERVAL, settings.jpeg_restart_interval]
        else:
            params = [cv2.IMWRITE_PNG_COMPRESSION, settings.png_level]
        ok, encoded = cv2.imencode(".jpg" if settings.format == "jpeg" else ".png", pixels, params)
        if not ok:
            raise CompressionError(f"cv::imencode ({settings.format}) failed on input image")
        return bytes(encoded)

    def decode(self, data: bytes, rgb: bool = False) -> numpy.ndarray[Any, Any] | None:
        cv2 = self.cv2
        decoded: numpy.ndarray[Any, Any] | None = cv2.imdecode(numpy.frombuffer(data, numpy.uint8),
                                                                cv2.IMREAD_UNCHANGED)
        if rgb and decoded is not None and decoded.ndim == 3 and decoded.shape[2] in (3, 4):
            decoded = cv2.cvtColor(decoded, cv2.COLOR_BGR2RGB if decoded.shape[2] == 3 else cv2.COLOR_BGRA2RGBA)
        return decoded


class PillowCodec:
    def __init__(self, image_module: Any) -> None:
        self.pil = image_module

    def encode(self, pixels: numpy.ndarray[Any, Any], settings: Settings, rgb: bool = False) -> bytes:
        if pixels.ndim == 3:
            if pixels.dtype != numpy.uint8:
                raise CompressionError("a 16-bit colour png needs OpenCV: pip install opencv-python-headless")
            keep = 4 if pixels.shape[2] == 4 and settings.format == "png" else 3  # jpeg has no alpha: OpenCV drops it
            pixels = numpy.ascontiguousarray(pixels[..., :keep] if rgb else pixels[..., [2, 1, 0, 3][:keep]])
        out = io.BytesIO()
        picture = self.pil.fromarray(pixels)
        if settings.format == "jpeg":
            picture.save(out, "JPEG", quality=settings.jpeg_quality, progressive=settings.jpeg_progressive,
                         optimize=settings.jpeg_optimize, restart_marker_blocks=settings.jpeg_restart_interval)
        else:
            picture.save(out, "PNG", compress_level=settings.png_level)
        return out.getvalue()

    def decode(self, data: bytes, rgb: bool = False) -> numpy.ndarray[Any, Any] | None:
        try:
            picture = self.pil.open(io.BytesIO(data))
            picture.load()
        except (OSError, ValueError, self.pil.DecompressionBombError):
            return None
        if picture.mode in ("L", "I;16", "I;16B", "I;16L"):
            pixels = numpy.asarray(picture)
            return pixels.astype(pixels.dtype.newbyteorder("="))
        if picture.mode == "I":  # 16-bit grey png, read by older Pillow as 32-bit
            return numpy.asarray(picture).astype(numpy.uint16)
        alpha = "A" in picture.getbands() or "transparency" in picture.info
        colour = numpy.asarray(picture.convert("RGBA" if alpha else "RGB"))
        return colour if rgb else colour[..., [2, 1, 0, 3][:colour.shape[2]]]


def default_codec() -> Codec:
    """OpenCV when installed, else Pillow; CompressionError naming what to install when neither is."""
    try:
        import cv2
    except ImportError:
        pass
    else:
        return OpenCVCodec(cv2)
    try:
        from PIL import Image as PilImage
    except ImportError:
        raise CompressionError("the compressed transport needs Pillow or OpenCV: pip install 'kame[image]'") from None
    return PillowCodec(PilImage)


def _to_8bit(pixels: numpy.ndarray[Any, Any]) -> numpy.ndarray[Any, Any]:
    """OpenCV's convertTo(CV_8U) without scale: rounded and saturated."""
    if pixels.dtype == numpy.uint8:
        return pixels
    values = numpy.rint(pixels) if pixels.dtype.kind == "f" else pixels
    saturated: numpy.ndarray[Any, Any] = numpy.clip(values, 0, 255).astype(numpy.uint8)
    return saturated


def compress(image: Any, settings: Settings = Settings(), codec: Codec | None = None) -> CompressedImage:
    """The CompressedImage compressed_image_transport publishes for `image`."""
    if settings.format not in FORMATS:
        raise CompressionError(f"Unknown compression type '{settings.format}', valid options are 'jpeg' and 'png'")
    code, channels = layout(image.encoding)
    bit_depth = numpy.dtype(code).itemsize * 8
    if bit_depth not in (8, 16):
        requirement = "color format" if settings.format == "jpeg" else "encoded color format"
        raise CompressionError(f"Compressed Image Transport - {settings.format.upper()} compression requires 8/16-bit "
                               f"{requirement} (input format is: {image.encoding})")
    pixels = to_array(image)
    target = ""
    colour = _COLOUR.match(image.encoding)
    rgb = colour is not None and colour.group(1) == "rgb"
    if colour:  # to bgr8 or bgr16 as cv_bridge converts: the codec writes it in OpenCV's order
        target = "bgr8" if settings.format == "jpeg" else f"bgr{bit_depth}"
        pixels = pixels[..., :3]
        if bit_depth == 16 and target == "bgr8":  # cv_bridge's depth change: scaled and rounded
            pixels = numpy.rint(pixels * (255.0 / 65535.0)).astype(numpy.uint8)
    if channels == 2:
        raise CompressionError(f"cannot compress a 2-channel image ({image.encoding}) as {settings.format}")
    if not (settings.format == "png" and pixels.dtype == numpy.uint16):
        pixels = _to_8bit(pixels)
    data = (codec or default_codec()).encode(pixels, settings, rgb)
    return CompressedImage(header=image.header, format=f"{image.encoding}; {settings.format} compressed {target}",
                           data=data)


def decompress(compressed: Any, codec: Codec | None = None) -> Image:
    """The Image compressed_image_transport's subscriber makes of `compressed`."""
    encoding, named, compressed_as = compressed.format.partition(";")
    colour = _COLOUR.match(encoding) if named else None
    # "compressed bgr8": the codec's order is the image's; else ("compressed rgb8") red and blue are swapped
    source = "bgr" if "compressed bgr" in compressed_as else "rgb"
    swap = colour is not None and source != colour.group(1)
    pixels = (codec or default_codec()).decode(bytes(compressed.data), rgb=swap)
    if pixels is None or pixels.size == 0:
        raise CompressionError(f"cannot decode the {compressed.format or 'compressed'} image")
    channels = 1 if pixels.ndim == 2 else pixels.shape[2]
    if not named:  # older compressed_image_transport did not name the encoding
        if channels not in (1, 3):
            raise CompressionError(f"Unsupported number of channels: {channels}")
        depth = "8" if pixels.dtype == numpy.uint8 else "16"
        return from_array(pixels, ("mono" if channels == 1 else "bgr") + depth, compressed.header)
    code, wanted_channels = layout(encoding)
    if colour and channels >= 3:
        pixels = pixels[..., :3]
        if colour.group(2):  # alpha the codec did not keep: opaque
            maximum = numpy.iinfo(pixels.dtype).max if pixels.dtype.kind == "u" else 1
            pixels = numpy.concatenate([pixels, numpy.full((*pixels.shape[:2], 1), maximum, pixels.dtype)], axis=2)
    wanted = numpy.dtype(code)
    if pixels.dtype.itemsize < wanted.itemsize:  # sent as 8 bits: back to the encoding's depth
        pixels = pixels.astype(wanted) * (257 if colour else 1)
    if (1 if pixels.ndim == 2 else pixels.shape[2]) != wanted_channels or pixels.dtype.itemsize != wanted.itemsize:
        raise CompressionError(f"the decoded {compressed.format} image has {channels} channels of {pixels.dtype}, "
                               f"which is not {encoding}")
    return from_array(pixels.view(wanted), encoding, compressed.header)
