"""kame.bag: ROS bag format 2.0.

- records (pure): records to bytes and back; compression: none/bz2/lz4; info: what
  `rosbag info` prints from an index; errors: BagError and its kinds.
- reader.BagReader and writer.BagWriter: the file I/O (messages as serialized bytes).
rosbag.Bag (the user API) turns bytes into message objects.
"""

from __future__ import annotations

from kame.bag.errors import BagCompressionError, BagError, BagFormatError, BagUnindexedError

__all__ = ["BagCompressionError", "BagError", "BagFormatError", "BagUnindexedError"]
