"""map_saver: write the map being published to a PGM and a YAML file, as map_server's map_saver.

    rosrun map_server map_saver [--occ <threshold_occupied>] [--free <threshold_free>] [-f <mapname>]

Waits for one message on `map`, writes <mapname>.pgm and <mapname>.yaml, says so and exits.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from typing import Any

from kame.net.signal_wake import SignalSafeEvent
from kame.stage import runtime
from kame.stage.mapfile import SAVER_FREE, SAVER_OCCUPIED, Grid, MapError, saved_pgm, saved_yaml, saver_thresholds

USAGE = "Usage: \n  map_saver -h\n  map_saver [--occ <threshold_occupied>] [--free <threshold_free>] [-f <mapname>] " \
        "[ROS remapping args]"


def parse_args(args: Sequence[str]) -> tuple[str, int, int] | str:
    """(map name, occupied, free) or the text to print and exit with."""
    name, occupied, free = "map", SAVER_OCCUPIED, SAVER_FREE
    i = 0
    while i < len(args):
        arg = args[i]
        if arg in ("-h", "--help"):
            return USAGE
        if arg in ("-f", "--occ", "--free"):
            if i + 1 >= len(args):
                return USAGE
            value = args[i + 1]
            if arg == "-f":
                name = value
            else:
                try:
                    number = int(value)
                except ValueError:
                    return f"{arg} takes an integer percentage, not {value!r}\n{USAGE}"
                occupied, free = (number, free) if arg == "--occ" else (occupied, number)
            i += 2
            continue
        return USAGE
    try:
        saver_thresholds(occupied, free)
    except MapError as exc:
        return str(exc)
    return name, occupied, free


def grid_of(msg: Any) -> Grid:
    import math

    import numpy as np

    q = msg.info.origin.orientation
    yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
    data = msg.data
    if isinstance(data, bytes):
        cells = np.frombuffer(data, dtype=np.int8)
    else:
        cells = np.asarray(data, np.int16).astype(np.int8)
    if cells.size != msg.info.width * msg.info.height:
        raise MapError(f"the map has {cells.size} cells, not width x height = {msg.info.width * msg.info.height}")
    return Grid(cells.reshape(msg.info.height, msg.info.width), msg.info.resolution,
                (msg.info.origin.position.x, msg.info.origin.position.y, yaw))


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    parsed = parse_args(runtime.without_remappings(argv)[1:])
    if isinstance(parsed, str):
        print(parsed, file=sys.stderr)
        return 1
    name, occupied, free = parsed
    runtime.init("map_saver", argv, anonymous=True)
    from nav_msgs.msg import OccupancyGrid

    received: list[Any] = []
    got = SignalSafeEvent()  # the main thread waits on it

    def on_map(msg: Any) -> None:
        if not got.is_set():
            received.append(msg)
            got.set()

    runtime.on_shutdown(got.set)  # Ctrl-C while waiting
    runtime.info("Waiting for the map")
    subscriber = runtime.Subscriber("map", OccupancyGrid, on_map, queue_size=1)
    try:
        got.wait()
    except KeyboardInterrupt:
        return 1
    finally:
        subscriber.unregister()
    if not received:
        return 1
    msg = received[0]
    runtime.info("Received a %d X %d map @ %.3f m/pix", msg.info.width, msg.info.height, msg.info.resolution)
    status = 0
    try:
        grid = grid_of(msg)
        pgm = f"{name}.pgm"
        runtime.info("Writing map occupancy data to %s", pgm)
        with open(pgm, "wb") as f:
            f.write(saved_pgm(grid, occupied, free))
        yaml_name = f"{name}.yaml"
        runtime.info("Writing map occupancy data to %s", yaml_name)
        with open(yaml_name, "w", encoding="utf-8") as text:
            text.write(saved_yaml(pgm, grid))  # the name as given, as map_saver writes it
        runtime.info("Done\n")
    except (MapError, OSError) as exc:
        runtime.error("Could not save the map: %s", exc)
        status = 1
    runtime.signal_shutdown("map saved")
    return status


if __name__ == "__main__":
    sys.exit(main())
