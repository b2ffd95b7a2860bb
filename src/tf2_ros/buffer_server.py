"""tf2_ros.BufferServer: answers tf2_msgs/LookupTransform goals from a Buffer (kame's
buffer_server program runs it)."""

from kame.cli.buffer_server import CODES, BufferServer

__all__ = ["CODES", "BufferServer"]
