"""map_server: serve a map file as ROS's map_server does.

    rosrun map_server map_server mymap.yaml [__name:=NAME] [remappings]

Publishes the latched `map` (nav_msgs/OccupancyGrid) and `map_metadata` (nav_msgs/MapMetaData),
serves `static_map` (nav_msgs/GetMap); the frame is the private param ~frame_id ("map"). Its
log lines and error texts are map_server's; a bad map file is an error line and status 255
(map_server's exit(-1)), never a traceback.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from typing import Any

from kame.stage import runtime
from kame.stage.mapfile import Grid, MapError, load, parse_description

USAGE = """USAGE: map_server <map.yaml>
  map.yaml: map description file
DEPRECATED USAGE: map_server <map> <resolution>
  map: image file to load
  resolution: map resolution [meters/pixel]"""


def read_map(yaml_path: str) -> Grid:
    """The grid of a map description file, or MapError with map_server's text."""
    try:
        with open(yaml_path, encoding="utf-8") as f:
            text = f.read()
    except (OSError, UnicodeDecodeError):
        raise MapError(f"Map_server could not open {yaml_path}.") from None
    description = parse_description(text)
    image = description.image_path(yaml_path)
    runtime.info('Loading map from image "%s"', image)
    try:
        with open(image, "rb") as f:
            data = f.read()
    except OSError as exc:
        raise MapError(f'Failed to open image file "{image}": {exc.strerror or exc}') from None
    return load(description, data, image)


def grid_message(grid: Grid, frame_id: str, stamp: Any) -> Any:
    """The nav_msgs/OccupancyGrid of a grid (and its info, the map_metadata)."""
    import math

    from nav_msgs.msg import MapMetaData, OccupancyGrid

    info = MapMetaData()
    info.map_load_time = stamp
    info.resolution = grid.resolution
    info.width, info.height = grid.width, grid.height
    x, y, yaw = grid.origin
    info.origin.position.x, info.origin.position.y = x, y
    info.origin.orientation.z, info.origin.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    msg = OccupancyGrid()
    msg.header.frame_id = frame_id
    msg.header.stamp = stamp
    msg.info = info
    msg.data = grid.cells.reshape(-1)  # int8[] fields take numpy arrays whole
    return msg


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    args = runtime.without_remappings(argv)[1:]
    if len(args) not in (1, 2):
        runtime.error("%s", USAGE)
        return 255
    if len(args) == 2:
        runtime.error("map_server <map> <resolution> is deprecated and not supported by kame: "
                      "write a map.yaml (see map_server's documentation)")
        return 255
    runtime.init("map_server", argv)
    try:
        grid = read_map(args[0])
    except MapError as exc:
        runtime.error("%s", exc)
        runtime.signal_shutdown("bad map")
        return 255
    runtime.info("Read a %d X %d map @ %.3f m/cell", grid.width, grid.height, grid.resolution)
    from nav_msgs.msg import MapMetaData, OccupancyGrid
    from nav_msgs.srv import GetMap, GetMapResponse

    frame_id = str(runtime.get_param("~frame_id", "map"))
    message = grid_message(grid, frame_id, runtime.Time.now())

    def static_map(_request: Any) -> Any:
        runtime.info("Sending map")
        return GetMapResponse(message)

    runtime.Service("static_map", GetMap, static_map)
    metadata = runtime.Publisher("map_metadata", MapMetaData, queue_size=1, latch=True)
    metadata.publish(message.info)
    grid_publisher = runtime.Publisher("map", OccupancyGrid, queue_size=1, latch=True)
    grid_publisher.publish(message)
    try:
        while not runtime.wait_for_shutdown(None):
            pass
    except KeyboardInterrupt:
        pass
    runtime.signal_shutdown("map_server exiting")
    return 0


if __name__ == "__main__":
    sys.exit(main())
