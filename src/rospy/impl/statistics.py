"""rospy.impl.statistics: topic statistics as rospy measures them (rosgraph_msgs/TopicStatistics
on /statistics, per publisher of a subscribed topic: traffic, delivered and dropped messages,
stamp ages and periods, over a window that widens and narrows with the rate).

A SubscriberStatisticsLogger measures what its callback() is given. kame's Subscriber does not
call one itself: /enable_statistics does not make kame's subscriptions publish /statistics.
"""

from __future__ import annotations

import logging
from math import sqrt
from typing import Any

from kame.client import core
from kame.client.clock import Duration, Time
from kame.client.process import get_param
from rosgraph_msgs.msg import TopicStatistics

__all__ = ["ConnectionStatisticsLogger", "SubscriberStatisticsLogger", "TopicStatistics", "sqrt"]

_logger = logging.getLogger("rospy.impl.statistics")


class SubscriberStatisticsLogger:
    """The statistics of one subscription, one ConnectionStatisticsLogger per publisher."""

    @classmethod
    def is_enabled(cls) -> bool:
        try:
            return bool(get_param("/enable_statistics", False))
        except Exception:
            return False

    def __init__(self, subscriber: Any) -> None:
        self.subscriber_name = subscriber.name
        self.connections: dict[str, ConnectionStatisticsLogger] = {}
        self.read_parameters()

    def read_parameters(self) -> None:
        self.min_elements = get_param("/statistics_window_min_elements", 10)
        self.max_elements = get_param("/statistics_window_max_elements", 100)
        self.min_window = get_param("/statistics_window_min_size", 4)
        self.max_window = get_param("/statistics_window_max_size", 64)

    def callback(self, msg: Any, publisher: str, stat_bytes: int) -> None:
        """`msg` arrived from `publisher`, whose connection has carried `stat_bytes` in all."""
        if self.subscriber_name in ("/clock", "/statistics"):
            return
        try:
            logger = self.connections.get(publisher)
            if logger is None:
                logger = ConnectionStatisticsLogger(self.subscriber_name, core.get_name(), publisher)
                self.connections[publisher] = logger
            logger.callback(self, msg, stat_bytes)
        except Exception as exc:
            _logger.error("Unexpected error during statistics measurement: %s", exc)

    def shutdown(self) -> None:
        for logger in self.connections.values():
            logger.shutdown()
        self.connections.clear()


def _mean_and_stddev(values: list[Any]) -> tuple[Any, Any]:
    mean = Duration(sum(values, Duration(0)).to_sec() / len(values))
    variance = sum((Duration((mean - value).to_sec() ** 2) for value in values), Duration(0)) / len(values)
    return mean, Duration(sqrt(variance.to_sec()))


class ConnectionStatisticsLogger:
    """The statistics of one publisher's connection, published on /statistics each window."""

    def __init__(self, topic: str, subscriber: str, publisher: str) -> None:
        from kame.client.topics import Publisher

        self.topic = topic
        self.subscriber = subscriber
        self.publisher = publisher
        self.pub = Publisher("/statistics", TopicStatistics, queue_size=10)
        self.last_pub_time = Time(0)
        self.pub_frequency = Duration(1.0)
        self.age_list_: list[Any] = []
        self.arrival_time_list_: list[Any] = []
        self.last_seq_ = 0
        self.dropped_msgs_ = 0
        self.window_start = Time.now()
        self.stat_bytes_last_ = 0
        self.stat_bytes_window_ = 0

    def sendStatistics(self, subscriber_statistics_logger: SubscriberStatisticsLogger) -> None:
        curtime = Time.now()
        msg = TopicStatistics()
        msg.topic = self.topic
        msg.node_sub = self.subscriber
        msg.node_pub = self.publisher
        msg.window_start = self.window_start
        msg.window_stop = curtime
        msg.traffic = self.stat_bytes_window_ - self.stat_bytes_last_
        msg.delivered_msgs = len(self.arrival_time_list_)
        msg.dropped_msgs = self.dropped_msgs_
        if self.age_list_:
            msg.stamp_age_mean, msg.stamp_age_stddev = _mean_and_stddev(self.age_list_)
            msg.stamp_age_max = max(self.age_list_)
        else:
            msg.stamp_age_mean = msg.stamp_age_stddev = msg.stamp_age_max = Duration(0)
        if len(self.arrival_time_list_) > 1:
            periods = [j - i for i, j in zip(self.arrival_time_list_[:-1], self.arrival_time_list_[1:], strict=True)]
            msg.period_mean, msg.period_stddev = _mean_and_stddev(periods)
            msg.period_max = max(periods)
        else:
            msg.period_mean = msg.period_stddev = msg.period_max = Duration(0)
        self.pub.publish(msg)
        pub_period = 1.0 / self.pub_frequency.to_sec()
        if len(self.arrival_time_list_) > subscriber_statistics_logger.max_elements \
                and pub_period / 2 >= subscriber_statistics_logger.min_window:
            self.pub_frequency *= 2
        if len(self.arrival_time_list_) < subscriber_statistics_logger.min_elements \
                and pub_period * 2 <= subscriber_statistics_logger.max_window:
            self.pub_frequency /= 2
        self.age_list_ = []
        self.arrival_time_list_ = []
        self.dropped_msgs_ = 0
        self.window_start = curtime
        self.stat_bytes_last_ = self.stat_bytes_window_

    def callback(self, subscriber_statistics_logger: SubscriberStatisticsLogger, msg: Any, stat_bytes: int) -> None:
        arrival_time = Time.now()
        self.arrival_time_list_.append(arrival_time)
        self.stat_bytes_window_ = stat_bytes
        if msg._has_header:
            self.age_list_.append(arrival_time - msg.header.stamp)
            if self.last_seq_ + 1 != msg.header.seq:
                self.dropped_msgs_ += 1
            self.last_seq_ = msg.header.seq
        if self.last_pub_time + Duration(1.0 / self.pub_frequency.to_sec()) < arrival_time:
            self.last_pub_time = arrival_time
            self.sendStatistics(subscriber_statistics_logger)

    def shutdown(self) -> None:
        self.pub.unregister()
