"""sensor_msgs.point_cloud2: kame's against Debian's real module on random clouds, and the numpy
fast paths against the per-point reads."""

from __future__ import annotations

import math
import random
import struct
from io import BytesIO
from pathlib import Path
from typing import Any

import pytest

from sensor_msgs import point_cloud2
from sensor_msgs.msg import PointCloud2, PointField
from std_msgs.msg import Header

from . import debian
from .cloud_driver import run

DRIVER = Path(__file__).with_name("cloud_driver.py")
SIZES = {PointField.INT8: 1, PointField.UINT8: 1, PointField.INT16: 2, PointField.UINT16: 2,
         PointField.INT32: 4, PointField.UINT32: 4, PointField.FLOAT32: 4, PointField.FLOAT64: 8}
FORMATS = {PointField.INT8: "b", PointField.UINT8: "B", PointField.INT16: "h", PointField.UINT16: "H",
           PointField.INT32: "i", PointField.UINT32: "I", PointField.FLOAT32: "f", PointField.FLOAT64: "d"}


def random_fields(rng: random.Random) -> list[PointField]:
    fields, offset = [], 0
    for index in range(rng.randrange(1, 6)):
        datatype = rng.choice(sorted(SIZES))
        count = rng.choice([1, 1, 1, 2, 3])
        offset += rng.choice([0, 0, 1, 4])  # gaps the readers must skip
        fields.append(PointField(f"f{index}", offset, datatype, count))
        offset += SIZES[datatype] * count
    rng.shuffle(fields)  # the readers order fields by offset
    return fields


def random_cloud(rng: random.Random) -> PointCloud2:
    fields = random_fields(rng)
    end = max(f.offset + SIZES[f.datatype] * f.count for f in fields)
    point_step = end + rng.choice([0, 0, 3, 8])
    width, height = rng.randrange(0, 20), rng.randrange(1, 4)
    row_step = point_step * width + rng.choice([0, 5])
    bigendian = rng.random() < 0.2
    data = bytearray(rng.randbytes(row_step * height))
    for v in range(height):  # some float fields NaN, for skip_nans
        for u in range(width):
            for f in fields:
                if f.datatype in (PointField.FLOAT32, PointField.FLOAT64) and rng.random() < 0.15:
                    fmt = (">" if bigendian else "<") + FORMATS[f.datatype]
                    struct.pack_into(fmt, data, row_step * v + point_step * u + f.offset, math.nan)
    return PointCloud2(header=Header(frame_id="cloud"), height=height, width=width, fields=fields,
                       is_bigendian=bigendian, point_step=point_step, row_step=row_step,
                       data=bytes(data), is_dense=False)


def hexed(msg: Any) -> str:
    buffer = BytesIO()
    msg.serialize(buffer)
    return buffer.getvalue().hex()


def request() -> dict[str, Any]:
    rng = random.Random(2)
    reads = []
    for _ in range(60):
        cloud = random_cloud(rng)
        names = [f.name for f in cloud.fields]
        field_names = None if rng.random() < 0.4 else rng.sample(names, rng.randrange(1, len(names) + 1))
        cells = [[u, v] for u in range(cloud.width) for v in range(cloud.height)]
        uvs = rng.sample(cells, min(len(cells), rng.randrange(0, 4)))
        reads.append({"cloud": hexed(cloud), "field_names": field_names, "skip_nans": rng.random() < 0.5,
                      "uvs": uvs})
    creates = []
    for _ in range(30):
        fields = random_fields(rng)
        points = []
        for _ in range(rng.randrange(0, 15)):
            point: list[Any] = []
            for f in sorted(fields, key=lambda f: f.offset):
                for _ in range(f.count):
                    if f.datatype in (PointField.FLOAT32, PointField.FLOAT64):
                        point.append(rng.uniform(-1e3, 1e3))
                    else:
                        bits = SIZES[f.datatype] * 8
                        signed = f.datatype in (PointField.INT8, PointField.INT16, PointField.INT32)
                        low = -(1 << (bits - 1)) if signed else 0
                        point.append(rng.randrange(low, low + (1 << bits)))
            points.append(point)
        creates.append({"fields": [[f.name, f.offset, f.datatype, f.count] for f in fields], "points": points,
                        "xyz": False})
    creates.append({"fields": [], "points": [[rng.uniform(-5, 5) for _ in range(3)] for _ in range(9)],
                    "xyz": True})
    return {"reads": reads, "creates": creates}


@pytest.mark.skipif(not debian.has("sensor_msgs.point_cloud2"), reason="Debian's python3-sensor-msgs is not installed")
def test_same_points_and_clouds_as_debian_on_random_clouds() -> None:
    case = request()
    theirs = debian.run(DRIVER, case)
    ours = run(case)
    assert sum(len(r["points"]) for r in theirs["reads"]) > 200
    assert any("nan" in value for r in theirs["reads"] for p in r["points"] for value in p)
    for index, (mine, reference) in enumerate(zip(ours["reads"], theirs["reads"], strict=True)):
        assert mine == reference, index
    assert ours["made"] == theirs["made"]


def test_read_points_skips_nans_and_reads_cells() -> None:
    cloud = point_cloud2.create_cloud_xyz32(Header(), [(1, 2, 3), (math.nan, 0, 0), (4, 5, 6)])
    assert list(point_cloud2.read_points(cloud, skip_nans=True)) == [(1.0, 2.0, 3.0), (4.0, 5.0, 6.0)]
    assert list(point_cloud2.read_points(cloud, field_names=("z",), uvs=[(2, 0)])) == [(6.0,)]
    point = point_cloud2.read_points_list(cloud)[0]
    assert (point.x, point.y, point.z) == (1.0, 2.0, 3.0)
    with pytest.raises(AssertionError, match=r"not a sensor_msgs\.msg\.PointCloud2"):
        list(point_cloud2.read_points(Header()))


numpy = pytest.importorskip("numpy")


def test_numpy_reads_equal_the_per_point_reads_on_random_clouds() -> None:
    rng = random.Random(5)
    for _ in range(80):
        cloud = random_cloud(rng)
        skip = rng.random() < 0.5
        array = point_cloud2.read_points_array(cloud, skip_nans=skip)
        points = list(point_cloud2.read_points(cloud, skip_nans=skip))
        assert len(array) == len(points)
        flat = [tuple(value for name in array.dtype.names for value in numpy.atleast_1d(row[name]).tolist())
                for row in array]
        assert [tuple(map(repr, p)) for p in flat] == [tuple(map(repr, p)) for p in points]


def test_read_points_numpy_has_one_column_per_value() -> None:
    cloud = point_cloud2.create_cloud_xyz32(Header(), [(1, 2, 3), (math.nan, 0, 0), (4, 5, 6)])
    assert point_cloud2.read_points_numpy(cloud, skip_nans=True).tolist() == [[1, 2, 3], [4, 5, 6]]
    assert point_cloud2.read_points_numpy(cloud, uvs=[(2, 0)], field_names=["y"]).tolist() == [[5]]


def test_create_cloud_from_a_structured_array_equals_from_lists() -> None:
    fields = [PointField("x", 0, PointField.FLOAT32, 1), PointField("i", 6, PointField.UINT16, 1),
              PointField("d", 8, PointField.FLOAT64, 2)]
    rows = [(1.5, 7, (0.25, -3.0)), (-2.0, 65535, (1e10, 2.0))]
    array = numpy.array(rows, dtype=[("x", "f4"), ("i", "u2"), ("d", "f8", (2,))])
    from_array = point_cloud2.create_cloud(Header(), fields, array)
    from_lists = point_cloud2.create_cloud(Header(), fields, [(x, i, *d) for x, i, d in rows])
    assert hexed(from_array) == hexed(from_lists)
    assert from_array.width == 2 and from_array.point_step == 24
