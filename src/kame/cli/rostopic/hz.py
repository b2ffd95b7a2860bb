"""rostopic hz [options] /topic [/topic2 ...]: the publishing rate of topics."""

from __future__ import annotations

import sys
import threading
import time
from typing import Any

from kame.cli.topic_stats import RateStats, format_rate, format_rate_table
from kame.msg.anymsg import AnyMsg

from ._common import (
    Decoder,
    check_master,
    filter_function,
    init_node,
    load_message_class,
    option_parser,
    script_resolve_name,
    use_sim_time,
    wait_for_topic,
    wait_shutdown,
    window_size,
    write,
)


def cmd_hz(args: list[str]) -> None:
    parser = option_parser("usage: %prog hz [options] /topic_0 [/topic_1 [topic_2 [..]]]")
    parser.add_argument("-w", "--window", dest="window_size", default=-1,
                      help="window size, in # of messages, for calculating rate", metavar="WINDOW")
    parser.add_argument("--filter", dest="filter_expr", default=None,
                      help="only measure messages matching the specified Python expression", metavar="EXPR")
    parser.add_argument("--wall-time", dest="use_wtime", default=False, action="store_true",
                      help="calculates rate using wall time which can be helpful when clock isn't published "
                           "during simulation")
    parser.add_argument("--tcpnodelay", dest="tcp_nodelay", action="store_true",
                      help="use the TCP_NODELAY transport hint when subscribing to topics")
    options = parser.parse_args(args)
    rest = options.args
    if not rest:
        parser.error("topic must be specified")
    window = window_size(parser, options.window_size)
    topics = [script_resolve_name(t) for t in rest]
    filter_fn = filter_function(options.filter_expr) if options.filter_expr else None

    check_master()
    init_node()
    from kame.client import clock
    from kame.client.topics import Subscriber

    stats = {topic: RateStats(window) for topic in topics}
    lock = threading.Lock()

    def now() -> float:
        if options.use_wtime:
            return time.time()
        return float(clock.get_rostime().to_sec())

    for topic in topics:
        found = wait_for_topic(topic, stoppable=True)
        if found is None:
            return
        topic_type, real_topic, _ = found
        decoder: Decoder | None = None
        if filter_fn is not None:
            decoder = Decoder(load_message_class(topic_type))

        def callback(raw: Any, topic: str = topic, decoder: Decoder | None = decoder) -> None:
            if decoder is not None and filter_fn is not None and not filter_fn(decoder(raw), topic):
                return
            with lock:
                notice = stats[topic].add(now())
            if notice:
                write(notice + "\n")

        subscribe_class = decoder.subscribe_class if decoder is not None else AnyMsg
        Subscriber(real_topic, subscribe_class, callback, tcp_nodelay=bool(options.tcp_nodelay))
        print(f"subscribed to [{real_topic}]")
    if use_sim_time():
        sys.stderr.write("WARNING: may be using simulated time\n")
    while not wait_shutdown(1.0):
        with lock:
            if len(topics) == 1:
                text = format_rate(stats[topics[0]].summary())
            else:
                text = format_rate_table([(t, stats[t].summary()) for t in topics])
        write(text + "\n")
