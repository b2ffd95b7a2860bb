"""rosbag: read and write ROS bags (format 2.0) from Python, as ROS 1 users do.

`rosbag.Bag(path, 'r'|'w'|'a', compression=...)` over kame.bag; the command-line tool is
kame.cli.rosbag.
"""

from rosbag.bag import (
    Bag,
    BagMessage,
    Compression,
    ROSBagEncryptException,
    ROSBagEncryptNotSupportedException,
    ROSBagException,
    ROSBagFormatException,
    ROSBagUnindexedException,
)
from rosbag.rosbag_main import rosbagmain

__all__ = [
    "Bag",
    "BagMessage",
    "Compression",
    "ROSBagEncryptException",
    "ROSBagEncryptNotSupportedException",
    "ROSBagException",
    "ROSBagFormatException",
    "ROSBagUnindexedException",
    "rosbagmain",
]
