"""rospy.topics: Publisher and Subscriber (kame.client.topics)."""

from kame.client.topics import (
    Publisher,
    SubscribeListener,
    Subscriber,
    Topic,
)

__all__ = [
    "Publisher",
    "SubscribeListener",
    "Subscriber",
    "Topic",
]
