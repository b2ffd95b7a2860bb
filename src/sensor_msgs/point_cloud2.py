"""sensor_msgs.point_cloud2: reading and making sensor_msgs/PointCloud2 messages, as ROS 1's module.

read_points, read_points_list, create_cloud and create_cloud_xyz32 behave as upstream's (the
same struct layout rules: fields in offset order, gaps skipped, big- or little-endian; values
come back in offset order). With numpy installed, the fast paths read a whole cloud into an
array (read_points_array: a structured array; read_points_numpy: one column per field) and
create_cloud takes a structured array, all without a Python loop per point.

This module is written by hand: kame-genmsg only writes and removes `_*.py` message modules.
"""

from __future__ import annotations

import math
import struct
import sys
from collections import namedtuple
from collections.abc import Iterable, Iterator, Sequence
from typing import TYPE_CHECKING, Any

from kame.msg.message import Message
from sensor_msgs.msg import PointCloud2, PointField

if TYPE_CHECKING:
    import numpy

__all__ = ["create_cloud", "create_cloud_xyz32", "dtype_from_fields", "read_points", "read_points_array",
           "read_points_list", "read_points_numpy"]

_DATATYPES: dict[int, tuple[str, int]] = {
    PointField.INT8: ("b", 1),
    PointField.UINT8: ("B", 1),
    PointField.INT16: ("h", 2),
    PointField.UINT16: ("H", 2),
    PointField.INT32: ("i", 4),
    PointField.UINT32: ("I", 4),
    PointField.FLOAT32: ("f", 4),
    PointField.FLOAT64: ("d", 8),
}


def _check_cloud(cloud: Any) -> None:
    assert isinstance(cloud, Message) and cloud._type == "sensor_msgs/PointCloud2", \
        "cloud is not a sensor_msgs.msg.PointCloud2"


def _selected(fields: Iterable[Any], field_names: Iterable[str] | None) -> list[Any]:
    """The fields read, in offset order (upstream's order, whatever order field_names has)."""
    names = None if field_names is None else set(field_names)
    return [f for f in sorted(fields, key=lambda f: f.offset) if names is None or f.name in names]


def _get_struct_fmt(is_bigendian: bool, fields: Iterable[Any], field_names: Iterable[str] | None = None) -> str:
    fmt = ">" if is_bigendian else "<"
    offset = 0
    for field in _selected(fields, field_names):
        if offset < field.offset:
            fmt += "x" * (field.offset - offset)
            offset = field.offset
        if field.datatype not in _DATATYPES:
            print(f"Skipping unknown PointField datatype [{field.datatype}]", file=sys.stderr)
        else:
            datatype_fmt, datatype_length = _DATATYPES[field.datatype]
            fmt += field.count * datatype_fmt
            offset += field.count * datatype_length
    return fmt


def _offsets(cloud: Any, uvs: Iterable[tuple[int, int]]) -> Iterator[int]:
    """The byte offset of each point read: the given (u, v) cells, else every point row by row."""
    if uvs:
        for u, v in uvs:
            yield cloud.row_step * v + cloud.point_step * u
        return
    for v in range(cloud.height):
        yield from range(cloud.row_step * v, cloud.row_step * v + cloud.point_step * cloud.width, cloud.point_step)


def read_points(cloud: Any, field_names: Iterable[str] | None = None, skip_nans: bool = False,
                uvs: Iterable[tuple[int, int]] = ()) -> Iterator[tuple[Any, ...]]:
    """Yield each point's values (a tuple, fields in offset order); without the points holding
    a NaN when `skip_nans`; only the points at the (u, v) cells `uvs` when given."""
    _check_cloud(cloud)
    unpack_from = struct.Struct(_get_struct_fmt(cloud.is_bigendian, cloud.fields, field_names)).unpack_from
    data = cloud.data
    isnan = math.isnan
    for offset in _offsets(cloud, uvs):
        point = unpack_from(data, offset)
        if skip_nans and any(isnan(value) for value in point):
            continue
        yield point


def read_points_list(cloud: Any, field_names: Sequence[str] | None = None, skip_nans: bool = False,
                     uvs: Iterable[tuple[int, int]] = ()) -> list[Any]:
    """read_points as a list of namedtuples named by `field_names` (all fields when None)."""
    _check_cloud(cloud)
    if field_names is None:
        field_names = [f.name for f in cloud.fields]
    point_type = namedtuple("Point", field_names)  # type: ignore[misc]
    return [point_type._make(values) for values in read_points(cloud, field_names, skip_nans, uvs)]


def create_cloud(header: Any, fields: Sequence[Any], points: Any) -> PointCloud2:
    """A one-row PointCloud2 of `points` (each a sequence of values in the fields' offset order),
    packed little-endian with no padding after the last field, as upstream; `points` may also be
    a numpy structured array, whose fields are taken by name."""
    cloud_struct = struct.Struct(_get_struct_fmt(False, fields))
    if type(points).__module__ == "numpy":
        data = _array_bytes(points, fields, cloud_struct.size)
        count = len(points)
    else:
        buffer = bytearray(cloud_struct.size * len(points))
        pack_into = cloud_struct.pack_into
        for index, point in enumerate(points):
            pack_into(buffer, index * cloud_struct.size, *point)
        data, count = bytes(buffer), len(points)
    return PointCloud2(header=header, height=1, width=count, is_dense=False, is_bigendian=False, fields=fields,
                       point_step=cloud_struct.size, row_step=cloud_struct.size * count, data=data)


def create_cloud_xyz32(header: Any, points: Any) -> PointCloud2:
    """A PointCloud2 of three float32 fields x, y, z."""
    fields = [PointField("x", 0, PointField.FLOAT32, 1),
              PointField("y", 4, PointField.FLOAT32, 1),
              PointField("z", 8, PointField.FLOAT32, 1)]
    return create_cloud(header, fields, points)


# numpy fast paths ---------------------------------------------------------------------------

_NUMPY_TYPES = {PointField.INT8: "i1", PointField.UINT8: "u1", PointField.INT16: "i2", PointField.UINT16: "u2",
                PointField.INT32: "i4", PointField.UINT32: "u4", PointField.FLOAT32: "f4",
                PointField.FLOAT64: "f8"}


def _layout(fields: Iterable[Any], field_names: Iterable[str] | None) -> list[tuple[str, str, int, int]]:
    """(name, numpy type code, count, offset) of each known field read, in offset order."""
    return [(f.name, _NUMPY_TYPES[f.datatype], f.count, f.offset) for f in _selected(fields, field_names)
            if f.datatype in _NUMPY_TYPES]


def _dtype(layout: list[tuple[str, str, int, int]], order: str, itemsize: int | None) -> numpy.dtype[Any]:
    import numpy

    spec: dict[str, Any] = {
        "names": [name for name, _, _, _ in layout],
        "formats": [order + code if count == 1 else (order + code, (count,)) for _, code, count, _ in layout],
        "offsets": [offset for _, _, _, offset in layout],
    }
    if itemsize is not None:
        spec["itemsize"] = itemsize
    dtype: numpy.dtype[Any] = numpy.dtype(spec)  # type: ignore[call-overload]
    return dtype


def dtype_from_fields(fields: Iterable[Any], point_step: int | None = None, is_bigendian: bool = False,
                      field_names: Iterable[str] | None = None) -> numpy.dtype[Any]:
    """The numpy structured dtype of one point: each (known) field at its offset, itemsize
    point_step when given. A field with count > 1 is a sub-array."""
    return _dtype(_layout(fields, field_names), ">" if is_bigendian else "<", point_step)


def read_points_array(cloud: Any, field_names: Iterable[str] | None = None, skip_nans: bool = False,
                      uvs: Iterable[tuple[int, int]] = ()) -> numpy.ndarray[Any, Any]:
    """The points read_points yields, as a 1-D numpy structured array (a copy, native order,
    packed)."""
    import numpy

    _check_cloud(cloud)
    layout = _layout(cloud.fields, field_names)
    dtype = _dtype(layout, ">" if cloud.is_bigendian else "<", cloud.point_step)
    raw = numpy.frombuffer(bytes(cloud.data), dtype=numpy.uint8)
    rows = numpy.ascontiguousarray(raw[: cloud.row_step * cloud.height])
    grid = numpy.ndarray((cloud.height, cloud.width), dtype=dtype, buffer=rows,
                         strides=(cloud.row_step, cloud.point_step))
    cells = list(uvs)
    points = grid[[v for _, v in cells], [u for u, _ in cells]] if cells else grid.reshape(-1)
    native = numpy.dtype([(name, "=" + code, (count,)) if count > 1 else (name, "=" + code)
                          for name, code, count, _ in layout])
    packed: numpy.ndarray[Any, Any] = points.astype(native)
    if skip_nans:
        keep = numpy.ones(len(packed), dtype=bool)
        for name, code, _, _ in layout:
            if code.startswith("f"):
                keep &= ~_per_point(numpy.isnan(packed[name])).any(axis=1)
        packed = packed[keep]
    return packed


def read_points_numpy(cloud: Any, field_names: Iterable[str] | None = None, skip_nans: bool = False,
                      uvs: Iterable[tuple[int, int]] = ()) -> numpy.ndarray[Any, Any]:
    """The points as a 2-D array, one column per field value (fields in offset order); the
    fields read must share one datatype, as in ROS 2's read_points_numpy."""
    import numpy

    points = read_points_array(cloud, field_names, skip_nans, uvs)
    names = points.dtype.names or ()
    assert len({points[name].dtype for name in names}) <= 1, "read_points_numpy needs fields of one datatype"
    columns = [_per_point(points[name]) for name in names]
    table: numpy.ndarray[Any, Any] = numpy.hstack(columns) if columns else numpy.empty((len(points), 0))
    return table


def _per_point(column: numpy.ndarray[Any, Any]) -> numpy.ndarray[Any, Any]:
    """A field's column as 2-D: one row per point, one column per value (count > 1 fields)."""
    width = 1
    for extent in column.shape[1:]:
        width *= extent
    return column.reshape(column.shape[0], width)


def _array_bytes(points: Any, fields: Sequence[Any], point_step: int) -> bytes:
    """A structured array's points packed as create_cloud packs them (little-endian, fields'
    offsets, `point_step` bytes each): its fields are taken by name."""
    import numpy

    dtype = dtype_from_fields(fields, point_step)
    packed = numpy.zeros(len(points), dtype=dtype)
    for name in dtype.names or ():
        packed[name] = points[name]
    return packed.tobytes()
