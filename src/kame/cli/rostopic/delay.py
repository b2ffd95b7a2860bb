"""rostopic delay [-w N] [--tcpnodelay] /topic: the delay of messages with a header."""

from __future__ import annotations

import argparse
import sys
import threading
from typing import Any

from kame.cli.topic_stats import DelayStats

from ._common import (
    NAME,
    Decoder,
    init_node,
    load_message_class,
    script_resolve_name,
    use_sim_time,
    wait_for_topic,
    wait_shutdown,
    write,
)


def cmd_delay(args: list[str]) -> None:
    parser = argparse.ArgumentParser(usage="%(prog)s delay [options] /topic", prog=NAME)
    parser.add_argument("topic", help="topic name to be calcurated the delay")
    parser.add_argument("-w", "--window", dest="window_size", default=-1, type=int,
                        help="window size, in # of messages, for calculating rate")
    parser.add_argument("--tcpnodelay", dest="tcp_nodelay", action="store_true",
                        help="use the TCP_NODELAY transport hint when subscribing to topics")
    parsed = parser.parse_args(args)
    topic = script_resolve_name(parsed.topic)

    found = wait_for_topic(topic)
    if found is None:
        return
    init_node()
    from kame.client import clock, log, topics
    decoder = Decoder(load_message_class(found[0]))
    stats = DelayStats(parsed.window_size)
    lock = threading.Lock()

    def callback(raw: Any) -> None:
        msg: Any = decoder(raw)
        if not msg._has_header:
            log.emit(log.ERROR, "msg does not have header", (), depth=2)
            return
        now = clock.get_rostime()
        with lock:
            notice = stats.add(now.to_sec(), msg.header.stamp.to_sec()) if not now.is_zero() else stats.add(0.0, 0.0)
        if notice:
            write(notice + "\n")

    topics.Subscriber(found[1], decoder.subscribe_class, callback, tcp_nodelay=parsed.tcp_nodelay)
    print(f"subscribed to [{found[1]}]")
    if use_sim_time():
        sys.stderr.write("WARNING: may be using simulated time\n")
    while not wait_shutdown(1.0):
        with lock:
            text = stats.report()
        if text is not None:
            write(text + "\n")
