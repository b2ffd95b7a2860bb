"""rosbag.bag: kame.client.bag under rosbag's name."""

from kame.client.bag import (
    Bag,
    BagMessage,
    BagMessageWithConnectionHeader,
    Compression,
    CompressionTuple,
    ROSBagEncryptException,
    ROSBagEncryptNotSupportedException,
    ROSBagException,
    ROSBagFormatException,
    ROSBagUnindexedException,
    TopicTuple,
    TypesAndTopicsTuple,
    message_class,
)

__all__ = [
    "Bag",
    "BagMessage",
    "BagMessageWithConnectionHeader",
    "Compression",
    "CompressionTuple",
    "ROSBagEncryptException",
    "ROSBagEncryptNotSupportedException",
    "ROSBagException",
    "ROSBagFormatException",
    "ROSBagUnindexedException",
    "TopicTuple",
    "TypesAndTopicsTuple",
    "message_class",
]
