"""Reads and makes point clouds with sensor_msgs.point_cloud2 and prints what it got.

Run by kame's interpreter and by Debian's /usr/bin/python3 (its real point_cloud2) on the same
JSON request: serialized clouds with the reads to do, and point lists to make clouds of.
"""

from __future__ import annotations

import json
import sys
from io import BytesIO
from typing import Any

from sensor_msgs import point_cloud2
from sensor_msgs.msg import PointCloud2, PointField
from std_msgs.msg import Header


def plain(points: list[Any]) -> list[list[str]]:
    return [[repr(value) for value in point] for point in points]  # repr: NaN compares as text


def run(request: dict[str, Any]) -> dict[str, Any]:
    reads = []
    for case in request["reads"]:
        cloud = PointCloud2().deserialize(bytes.fromhex(case["cloud"]))
        uvs = [tuple(uv) for uv in case["uvs"]]
        raw = list(point_cloud2.read_points(cloud, case["field_names"], case["skip_nans"], uvs))
        read: dict[str, Any] = {"points": plain(raw)}
        try:
            named = point_cloud2.read_points_list(cloud, case["field_names"], case["skip_nans"], uvs)
            read["named"] = [plain(named), [list(p._fields) for p in named[:1]]]
        except TypeError as exc:  # upstream's namedtuple has one name per field, not per value
            read["named"] = str(exc)
        reads.append(read)
    made = []
    for case in request["creates"]:
        header = Header(seq=3, frame_id="map")
        header.stamp.secs = 7
        fields = [PointField(name, offset, datatype, count) for name, offset, datatype, count in case["fields"]]
        points = [tuple(point) for point in case["points"]]
        if case["xyz"]:
            cloud = point_cloud2.create_cloud_xyz32(header, points)
        else:
            cloud = point_cloud2.create_cloud(header, fields, points)
        buffer = BytesIO()
        cloud.serialize(buffer)
        made.append(buffer.getvalue().hex())
    return {"reads": reads, "made": made}


if __name__ == "__main__":
    print(json.dumps(run(json.load(sys.stdin))))
