"""rostopic bw [-w WINDOW] /topic: the bandwidth a topic uses."""

from __future__ import annotations

import threading
import time
from typing import Any

from kame.cli.topic_stats import BandwidthStats
from kame.msg.anymsg import AnyMsg

from ._common import (
    check_master,
    init_node,
    option_parser,
    script_resolve_name,
    wait_for_topic,
    wait_shutdown,
    window_size,
    write,
)


def cmd_bw(args: list[str]) -> None:
    parser = option_parser("usage: %prog bw /topic")
    parser.add_argument("-w", "--window", dest="window_size", default=None,
                      help="window size, in # of messages, for calculating rate", metavar="WINDOW")
    options = parser.parse_args(args)
    rest = options.args
    if not rest:
        parser.error("topic must be specified")
    if len(rest) > 1:
        parser.error("you may only specify one input topic")
    window = window_size(parser, options.window_size) if options.window_size is not None else None
    topic = script_resolve_name(rest[0])

    check_master()
    found = wait_for_topic(topic)
    if found is None:
        return
    init_node(disable_rostime=True)
    from kame.client import topics
    stats = BandwidthStats(window)
    lock = threading.Lock()

    def callback(raw: Any) -> None:
        with lock:
            stats.add(time.time(), len(raw._buff))

    topics.Subscriber(found[1], AnyMsg, callback)
    print(f"subscribed to [{found[1]}]")
    while not wait_shutdown(1.0):
        with lock:
            text = stats.report(time.time())
        if text is not None:
            write(text + "\n")
