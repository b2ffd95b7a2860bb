"""cv_bridge: sensor_msgs/Image and CompressedImage to numpy arrays (OpenCV images) and back.

CvBridge follows ROS 1's cv_bridge: images come out as numpy arrays of the encoding's type
(2-D for one channel), and a desired encoding converts as cv_bridge's C++ code does: colour
orders and channel counts with OpenCV's rules (grey = (9798 R + 19235 G + 3735 B + 2^14) >> 15,
alpha at the depth's maximum), depth changes between 8 and 16 bits scaled, numeric (non-colour)
types cast without scaling. Those conversions are numpy only; with OpenCV (`cv2`) installed it
does them instead, and is needed for Bayer and YUV sources and for compressed images.
"""

from __future__ import annotations

import re
import sys
from typing import Any

import numpy

from sensor_msgs.msg import CompressedImage, Image

__all__ = ["CvBridge", "CvBridgeError", "getCvType"]


class CvBridgeError(TypeError):
    """An image that cannot be converted (cv_bridge's exception)."""


_DEPTHS = ("8U", "8S", "16U", "16S", "32S", "32F", "64F")
_NUMPY = {"8U": "uint8", "8S": "int8", "16U": "uint16", "16S": "int16", "32S": "int32", "32F": "float32",
          "64F": "float64"}
_COLOUR = {  # encoding -> (format, cv type name)
    "mono8": ("GRAY", "8UC1"), "mono16": ("GRAY", "16UC1"),
    "bgr8": ("BGR", "8UC3"), "rgb8": ("RGB", "8UC3"), "bgr16": ("BGR", "16UC3"), "rgb16": ("RGB", "16UC3"),
    "bgra8": ("BGRA", "8UC4"), "rgba8": ("RGBA", "8UC4"), "bgra16": ("BGRA", "16UC4"), "rgba16": ("RGBA", "16UC4"),
    "bayer_rggb8": ("BAYER_RGGB", "8UC1"), "bayer_bggr8": ("BAYER_BGGR", "8UC1"),
    "bayer_gbrg8": ("BAYER_GBRG", "8UC1"), "bayer_grbg8": ("BAYER_GRBG", "8UC1"),
    "bayer_rggb16": ("BAYER_RGGB", "16UC1"), "bayer_bggr16": ("BAYER_BGGR", "16UC1"),
    "bayer_gbrg16": ("BAYER_GBRG", "16UC1"), "bayer_grbg16": ("BAYER_GRBG", "16UC1"),
    "yuv422": ("YUV422", "8UC2"), "yuv422_yuy2": ("YUV422_YUY2", "8UC2"),
}
_ORDER = {"GRAY": "L", "RGB": "RGB", "BGR": "BGR", "RGBA": "RGBA", "BGRA": "BGRA"}
# OpenCV conversion codes for the sources numpy does not convert (cv_bridge's table)
_CV_CODES = {
    ("BAYER_RGGB", "GRAY"): "COLOR_BayerBG2GRAY", ("BAYER_RGGB", "RGB"): "COLOR_BayerBG2RGB",
    ("BAYER_RGGB", "BGR"): "COLOR_BayerBG2BGR", ("BAYER_BGGR", "GRAY"): "COLOR_BayerRG2GRAY",
    ("BAYER_BGGR", "RGB"): "COLOR_BayerRG2RGB", ("BAYER_BGGR", "BGR"): "COLOR_BayerRG2BGR",
    ("BAYER_GBRG", "GRAY"): "COLOR_BayerGR2GRAY", ("BAYER_GBRG", "RGB"): "COLOR_BayerGR2RGB",
    ("BAYER_GBRG", "BGR"): "COLOR_BayerGR2BGR", ("BAYER_GRBG", "GRAY"): "COLOR_BayerGB2GRAY",
    ("BAYER_GRBG", "RGB"): "COLOR_BayerGB2RGB", ("BAYER_GRBG", "BGR"): "COLOR_BayerGB2BGR",
    **{("YUV422", fmt): f"COLOR_YUV2{fmt}_UYVY" for fmt in ("GRAY", "RGB", "BGR", "RGBA", "BGRA")},
    **{("YUV422_YUY2", fmt): f"COLOR_YUV2{fmt}_YUY2" for fmt in ("GRAY", "RGB", "BGR", "RGBA", "BGRA")},
}
_NUMERIC = re.compile(r"(8U|8S|16U|16S|32S|32F|64F)(?:C([0-9]+))?\Z")


def _cv2() -> Any:
    try:
        import cv2
    except ImportError:
        return None
    return cv2


def getCvType(encoding: str) -> int:
    """OpenCV's type number for an encoding (CV_8UC3 is 16); CvBridgeError if unknown."""
    name = _COLOUR[encoding][1] if encoding in _COLOUR else encoding
    found = _NUMERIC.match(name)
    if found is None:
        raise CvBridgeError(f"Unrecognized image encoding [{encoding}]")
    channels = int(found.group(2) or 1)
    return _DEPTHS.index(found.group(1)) + ((channels - 1) << 3)


def _type_name(cv_type: int) -> str:
    return f"{_DEPTHS[cv_type & 7]}C{(cv_type >> 3) + 1}"


def _bit_depth(encoding: str) -> int:
    return {"8U": 8, "8S": 8, "16U": 16, "16S": 16, "32S": 32, "32F": 32, "64F": 64}[_DEPTHS[getCvType(encoding) & 7]]


def _channels(encoding: str) -> int:
    return (getCvType(encoding) >> 3) + 1


def _convert_depth(image: numpy.ndarray[Any, Any], dtype: numpy.dtype[Any], scale: float) -> numpy.ndarray[Any, Any]:
    """OpenCV's convertTo: scale, round half to even, saturate to the target type."""
    values = image.astype(numpy.float64) * scale if scale != 1.0 else image
    if numpy.issubdtype(dtype, numpy.integer):
        info = numpy.iinfo(dtype)
        rounded = numpy.rint(values) if numpy.issubdtype(numpy.asarray(values).dtype, numpy.floating) else values
        return numpy.clip(rounded, info.min, info.max).astype(dtype)
    return numpy.asarray(values).astype(dtype)


def _to_gray(image: numpy.ndarray[Any, Any], order: str) -> numpy.ndarray[Any, Any]:
    r, g, b = (image[..., order.index(c)].astype(numpy.int64) for c in "RGB")
    gray = (r * 9798 + g * 19235 + b * 3735 + (1 << 14)) >> 15  # OpenCV's fixed point for 8 and 16 bits
    return gray.astype(image.dtype)


def _reorder(image: numpy.ndarray[Any, Any], src: str, dst: str) -> numpy.ndarray[Any, Any]:
    """A colour conversion between GRAY/RGB/BGR/RGBA/BGRA in numpy, as cv::cvtColor does it."""
    src_order, dst_order = _ORDER[src], _ORDER[dst]
    if dst_order == "L":
        return image.copy() if src_order == "L" else _to_gray(image, src_order)
    alpha_max = numpy.iinfo(image.dtype).max if numpy.issubdtype(image.dtype, numpy.integer) else 1.0
    planes = []
    for channel in dst_order:
        if src_order == "L" and channel != "A":
            planes.append(image)
        elif channel in src_order:
            planes.append(image[..., src_order.index(channel)])
        else:  # alpha the source does not have
            planes.append(numpy.full(image.shape[:2], alpha_max, dtype=image.dtype))
    return numpy.ascontiguousarray(numpy.stack(planes, axis=-1))


def _conversion(src: str, dst: str) -> list[str]:
    """cv_bridge's conversion steps from encoding src to dst: colour codes, then 'SAME_FORMAT'
    (a depth change) when needed."""
    src_colour, dst_colour = src in _COLOUR, dst in _COLOUR
    same_channels = _channels(src) == _channels(dst)
    if not src_colour:
        if dst_colour:
            raise CvBridgeError(f"[{src}] is not a color format. but [{dst}] is. The conversion does not make sense")
        if not same_channels:
            raise CvBridgeError(f"[{src}] and [{dst}] do not have the same number of channel")
        return ["SAME_FORMAT"]
    if not dst_colour:
        if not same_channels:
            raise CvBridgeError(f"[{src}] is a color format but [{dst}] is not so they must have the same OpenCV "
                                "type, CV_8UC3, CV16UC1 ....")
        return ["SAME_FORMAT"]
    src_format, dst_format = _COLOUR[src][0], _COLOUR[dst][0]
    if src_format == dst_format:
        steps = ["SAME_FORMAT"]
    elif src_format in _ORDER and dst_format in _ORDER:
        steps = [f"{src_format}2{dst_format}"]
    elif (src_format, dst_format) in _CV_CODES:
        steps = [_CV_CODES[(src_format, dst_format)]]
    else:
        raise CvBridgeError(f"Unsupported conversion from [{src}] to [{dst}]")
    if _bit_depth(src) != _bit_depth(dst) and src_format != dst_format:
        steps.append("SAME_FORMAT")
    return steps


def cvtColor2(image: numpy.ndarray[Any, Any], src: str, dst: str) -> numpy.ndarray[Any, Any]:
    """`image` of encoding src converted to encoding dst (cv_bridge's cvtColor)."""
    if not dst or dst == src:
        copied: numpy.ndarray[Any, Any] = image.copy()
        return copied
    cv2 = _cv2()
    for step in _conversion(src, dst):
        if step == "SAME_FORMAT":
            target = numpy.dtype(_NUMPY[_DEPTHS[getCvType(dst) & 7]])
            src_depth, dst_depth = _bit_depth(src), _bit_depth(dst)
            scale = 65535.0 / 255.0 if (src_depth, dst_depth) == (8, 16) else \
                255.0 / 65535.0 if (src_depth, dst_depth) == (16, 8) else 1.0
            image = _convert_depth(image, target, scale)
        elif step.startswith("COLOR_"):
            if cv2 is None:
                raise CvBridgeError(f"conversion from [{src}] to [{dst}] needs OpenCV: "
                                    "pip install opencv-python-headless")
            image = cv2.cvtColor(image, getattr(cv2, step))
        elif cv2 is not None:
            image = cv2.cvtColor(image, getattr(cv2, "COLOR_" + step))
        else:
            source, _, target_format = step.partition("2")
            image = _reorder(image, source, target_format)
    return image


class CvBridge:
    """Converts between ROS images and numpy arrays."""

    def __init__(self) -> None:
        self.cvtype_to_name = {getCvType(f"{d}C{c}"): f"{d}C{c}" for d in _DEPTHS for c in (1, 2, 3, 4)}
        self.numpy_type_to_cvtype = {**{v: k for k, v in _NUMPY.items()}, **_NUMPY}

    def dtype_with_channels_to_cvtype2(self, dtype: numpy.dtype[Any], n_channels: int) -> str:
        return f"{self.numpy_type_to_cvtype[dtype.name]}C{n_channels}"

    def cvtype2_to_dtype_with_channels(self, cvtype: int) -> tuple[str, int]:
        return _NUMPY[_DEPTHS[cvtype & 7]], (cvtype >> 3) + 1

    def encoding_to_cvtype2(self, encoding: str) -> int:
        return getCvType(encoding)

    def encoding_to_dtype_with_channels(self, encoding: str) -> tuple[str, int]:
        return self.cvtype2_to_dtype_with_channels(self.encoding_to_cvtype2(encoding))

    def imgmsg_to_cv2(self, img_msg: Any, desired_encoding: str = "passthrough") -> numpy.ndarray[Any, Any]:
        """The image as an array (height x width, x channels when more than one), converted to
        `desired_encoding` unless it is 'passthrough'."""
        dtype_name, n_channels = self.encoding_to_dtype_with_channels(img_msg.encoding)
        dtype = numpy.dtype(dtype_name).newbyteorder(">" if img_msg.is_bigendian else "<")
        data = bytes(img_msg.data)
        if n_channels == 1:
            im = numpy.ndarray(shape=(img_msg.height, img_msg.step // dtype.itemsize), dtype=dtype, buffer=data)
            im = im[:img_msg.height, :img_msg.width]
        else:
            im = numpy.ndarray(shape=(img_msg.height, img_msg.step // dtype.itemsize // n_channels, n_channels),
                               dtype=dtype, buffer=data)
            im = im[:img_msg.height, :img_msg.width, :]
        im = numpy.ascontiguousarray(im.astype(dtype.newbyteorder("=")))
        if desired_encoding == "passthrough":
            return im
        return cvtColor2(im, img_msg.encoding, desired_encoding)

    def cv2_to_imgmsg(self, cvim: Any, encoding: str = "passthrough", header: Any = None) -> Image:
        """An Image of the array; `encoding` must fit its type ('passthrough': named by it, 8UC3...)."""
        if not isinstance(cvim, (numpy.ndarray, numpy.generic)):
            raise TypeError("Your input type is not a numpy array")
        shape: tuple[int, ...] = cvim.shape
        img_msg = Image(height=shape[0], width=shape[1])
        if header is not None:
            img_msg.header = header
        cv_type = self.dtype_with_channels_to_cvtype2(cvim.dtype, 1 if len(shape) < 3 else shape[2])
        if encoding == "passthrough":
            img_msg.encoding = cv_type
        else:
            img_msg.encoding = encoding
            if self.cvtype_to_name.get(self.encoding_to_cvtype2(encoding)) != cv_type:
                raise CvBridgeError(f"encoding specified as {encoding}, but image has incompatible type {cv_type}")
        if cvim.dtype.byteorder == ">" or (cvim.dtype.byteorder == "=" and sys.byteorder == "big"):
            img_msg.is_bigendian = True
        img_msg.data = numpy.ascontiguousarray(cvim).tobytes()
        img_msg.step = len(img_msg.data) // img_msg.height if img_msg.height else 0
        return img_msg

    def compressed_imgmsg_to_cv2(self, cmprs_img_msg: Any, desired_encoding: str = "passthrough"
                                 ) -> numpy.ndarray[Any, Any]:
        """The decoded image (OpenCV's imdecode: BGR order), converted unless 'passthrough'."""
        cv2 = self._need_cv2()
        buf = numpy.frombuffer(bytes(cmprs_img_msg.data), dtype=numpy.uint8)
        im: numpy.ndarray[Any, Any] | None = cv2.imdecode(buf, cv2.IMREAD_UNCHANGED)
        if im is None:
            raise CvBridgeError(f"cannot decode the {cmprs_img_msg.format or 'compressed'} image")
        if desired_encoding == "passthrough":
            return im
        return cvtColor2(im, "bgr8", desired_encoding)

    def cv2_to_compressed_imgmsg(self, cvim: Any, dst_format: str = "jpg") -> CompressedImage:
        """A CompressedImage of the array in `dst_format` (jpg, png, ...: what OpenCV writes)."""
        if not isinstance(cvim, (numpy.ndarray, numpy.generic)):
            raise TypeError("Your input type is not a numpy array")
        cv2 = self._need_cv2()
        ok, encoded = cv2.imencode("." + dst_format, cvim)
        if not ok:
            raise CvBridgeError(f"OpenCV cannot write a {dst_format} image of this array")
        return CompressedImage(format=dst_format, data=numpy.asarray(encoded).tobytes())

    @staticmethod
    def _need_cv2() -> Any:
        cv2 = _cv2()
        if cv2 is None:
            raise CvBridgeError("compressed images need OpenCV: pip install opencv-python-headless")
        return cv2
