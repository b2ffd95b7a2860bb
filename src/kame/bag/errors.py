"""The errors of kame.bag: one base class, raised `from` the cause.

BagError is what rosbag calls ROSBagException (the rosbag shim makes them the same class).
BagFormatError: bytes that are not a valid bag (a lying length, a missing field).
BagUnindexedError: the index is missing or unreadable (a recorder killed before closing):
`rosbag reindex` repairs it. BagCompressionError: an unknown or corrupt compressed chunk.
"""

from __future__ import annotations

__all__ = ["BagCompressionError", "BagError", "BagFormatError", "BagUnindexedError"]


class BagError(Exception):
    """Any problem with a bag file; `value` is its text, as rosbag's ROSBagException has it."""

    def __init__(self, value: object = None) -> None:
        super().__init__(value)
        self.value = value

    def __str__(self) -> str:
        return str(self.value)


class BagFormatError(BagError):
    """The bytes are not a valid bag 2.0 file (or not where the index says)."""


class BagUnindexedError(BagError):
    """The bag's index is missing or broken; `rosbag reindex` rebuilds it."""


class BagCompressionError(BagError):
    """A chunk uses an unknown compression, or its compressed data is corrupt."""
