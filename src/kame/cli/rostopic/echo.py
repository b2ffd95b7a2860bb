"""rostopic echo [options] /topic[/field]: print messages, live or from a bag."""

from __future__ import annotations

import sys
import threading
from collections.abc import Callable
from typing import Any

from kame.msg.echo import as_field_value, csv_header, csv_row, field_filter, to_yaml, transform
from kame.msg.errors import MessageError
from kame.msg.fieldpath import FieldPath, FieldPathError, field_type, parse_field_path
from kame.net.signal_wake import SignalSafeEvent
from kame.rostime import Time

from ._common import (
    Decoder,
    RostopicError,
    bag_errors,
    check_master,
    filter_function,
    init_node,
    load_message_class,
    open_bag,
    option_parser,
    script_resolve_name,
    use_sim_time,
    wait_for_topic,
    write,
)

# On simulated time, a quiet topic may mean nobody publishes /clock: said after this long (s).
SIM_TIME_FIRST_MESSAGE_WAIT = 2.0


def _bag_echo(path: str, topic: str, all_topics: bool, count: int | None, filter_fn: Callable[[Any, str], bool] | None,
              nostr: bool, noarr: bool, width: int | None, plot: bool) -> None:
    with open_bag(path) as bag:
        bag_topics = {c.topic for c in bag._read_side().connections.values()}
        real = None
        if not all_topics:
            real = topic if topic in bag_topics else next(
                (t for t in sorted(bag_topics, key=len, reverse=True) if topic.startswith(t + "/")), None)
            if real is None:
                return
        path_spec = parse_field_path(topic[len(real):]) if real is not None and topic != real else None
        printed = 0
        first = True
        for t, msg, stamp in bag.read_messages(topics=None if all_topics else [real]):
            if filter_fn is not None and not filter_fn(msg, t):
                continue
            data: Any = msg
            type_information = None
            if path_spec is not None:
                try:
                    data = path_spec.evaluate(msg)
                    type_information = field_type(type(msg), path_spec.pattern)
                except FieldPathError as exc:
                    sys.stderr.write(f"{exc}\n")
                    continue
                if data is None:
                    continue
            if plot:
                text = (csv_header(data, None) + "\n") if first else ""
                first = False
                text += csv_row(data, stamp, None, None) + "\n"
            else:
                value = transform(as_field_value(data, type_information), type_information, nostr, noarr)
                text = (f"topic: {t}\n" if all_topics else "") + to_yaml(value, width=width) + "\n---\n"
            write(text)
            printed += 1
            if count is not None and printed >= count:
                return


class Echo:
    """What echo does with each message: filter, pick the field, print, count."""

    def __init__(self, topic: str, decoder: Decoder, path: FieldPath | None, type_information: str | None,
                 plot: bool, filter_fn: Callable[[Any], bool] | None, clear: bool, offset: bool,
                 count: int | None, nostr: bool, noarr: bool, width: int | None) -> None:
        self.topic = topic
        self.decoder = decoder
        self.path = path
        self.type_information = type_information
        self.plot = plot
        self.filter_fn = filter_fn
        self.prefix = "\033[2J\033[;H" if clear and not plot else ""
        self.suffix = "" if plot else "\n---"
        self.offset = offset
        self.max_count = count
        self.count = 0
        self.nostr = nostr
        self.noarr = noarr
        self.width = width
        self.field_filter = field_filter(nostr, noarr) if plot else None
        self.first = True
        self.done = SignalSafeEvent()  # the main thread waits on it: Ctrl-C must end that wait
        self.heard = threading.Event()  # a message was printed, or the echo is done
        self.failure: str | None = None

    def callback(self, raw: Any) -> None:
        if self.done.is_set():
            return
        try:
            self._handle(raw)
        except BrokenPipeError:
            self.done.set()
        except (RostopicError, MessageError) as exc:
            self.failure = str(exc)
            self.done.set()
        if self.count or self.done.is_set():
            self.heard.set()

    def _handle(self, raw: Any) -> None:
        msg = self.decoder(raw)
        if self.filter_fn is not None and not self.filter_fn(msg):
            return
        if self.max_count is not None and self.count >= self.max_count:
            self.done.set()
            return
        data: Any = msg
        if self.path is not None and self.type_information is None and self.decoder.cls is None:
            self.type_information = field_type(type(msg), self.path.pattern)
        if self.path is not None:
            try:
                data = self.path.evaluate(msg)
            except FieldPathError as exc:
                sys.stderr.write(f"{exc}\n")
                return
            if data is None:
                return
        from kame.client import clock

        now = clock.get_rostime()
        time_offset: Time | None = now if self.offset else None
        self.count += 1
        if self.plot:
            text = ""
            if self.first:
                text = csv_header(data, self.field_filter) + "\n"
                self.first = False
            text += csv_row(data, now, time_offset, self.field_filter) + "\n"
        else:
            value = as_field_value(data, self.type_information)
            value = transform(value, self.type_information, self.nostr, self.noarr)
            text = self.prefix + to_yaml(value, time_offset=time_offset, width=self.width) + self.suffix + "\n"
        write(text)
        if self.max_count is not None and self.count >= self.max_count:
            self.done.set()


def cmd_echo(args: list[str]) -> None:
    parser = option_parser("usage: %prog echo [options] /topic")
    parser.add_argument("-b", "--bag", dest="bag", default=None, help="echo messages from .bag file",
                      metavar="BAGFILE")
    parser.add_argument("-p", dest="plot", default=False, action="store_true",
                      help="echo in a plotting friendly format")
    parser.add_argument("-w", dest="fixed_numeric_width", default=None, metavar="NUM_WIDTH",
                      help="fixed width for numeric values")
    parser.add_argument("--filter", dest="filter_expr", default=None, metavar="FILTER-EXPRESSION",
                      help="Python expression to filter messages that are printed. Expression can use Python "
                           "builtins as well as m (the message) and topic (the topic name).")
    parser.add_argument("--nostr", dest="nostr", default=False, action="store_true", help="exclude string fields")
    parser.add_argument("--noarr", dest="noarr", default=False, action="store_true", help="exclude arrays")
    parser.add_argument("-c", "--clear", dest="clear", default=False, action="store_true",
                      help="clear screen before printing next message")
    parser.add_argument("-a", "--all", dest="all_topics", default=False, action="store_true",
                      help="display all message in bag, only valid with -b option")
    parser.add_argument("-n", dest="msg_count", default=None, metavar="COUNT", help="number of messages to echo")
    parser.add_argument("--offset", dest="offset_time", default=False, action="store_true",
                      help="display time as offsets from current time (in seconds)")
    options = parser.parse_args(args)
    rest = options.args
    if len(rest) > 1:
        parser.error("you may only specify one input topic")
    if options.all_topics and not options.bag:
        parser.error("Display all option is only valid when echoing from bag files")
    if options.offset_time and options.bag:
        parser.error("offset time option is not valid with bag files")
    topic = ""
    if not options.all_topics:
        if not rest:
            parser.error("topic must be specified")
        topic = script_resolve_name(rest[0])
    try:
        count = int(options.msg_count) if options.msg_count else None
    except ValueError:
        parser.error("COUNT must be an integer")
    width: int | None = None
    try:
        width = int(options.fixed_numeric_width) if options.fixed_numeric_width else None
    except ValueError:
        parser.error("NUM_WIDTH must be an integer")
    if width is not None and width < 2:
        parser.error("Fixed width for numeric values must be at least 2")
    filter_fn = filter_function(options.filter_expr) if options.filter_expr else None
    if options.bag:
        with bag_errors():
            _bag_echo(options.bag, topic.rstrip("/") or "/", options.all_topics, count, filter_fn, options.nostr,
                      options.noarr, width, options.plot)
        return
    if topic.endswith("/"):
        topic = topic.rstrip("/") or "/"

    check_master()
    init_node()
    found = wait_for_topic(topic, stoppable=True)
    if found is None:
        return
    topic_type, real_topic, path = found
    cls = load_message_class(topic_type)
    type_information = None
    if path is not None and cls is not None:
        try:
            type_information = field_type(cls, topic[len(real_topic):])
        except FieldPathError as exc:
            raise RostopicError(str(exc)) from None
    decoder = Decoder(cls)
    echo = Echo(topic, decoder, path, type_information, options.plot,
                (lambda m: filter_fn(m, topic)) if filter_fn else None, options.clear, options.offset_time,
                count, options.nostr, options.noarr, width)
    sim_time = use_sim_time()
    from kame.client.topics import Subscriber

    Subscriber(real_topic, decoder.subscribe_class, echo.callback)
    from kame.client import core

    if sim_time:
        with core.woken_at_shutdown(echo.heard):
            echo.heard.wait(SIM_TIME_FIRST_MESSAGE_WAIT)
        if core.is_shutdown():
            return
        if echo.count == 0 and not echo.done.is_set():
            sys.stderr.write("WARNING: no messages received and simulated time is active.\n"
                             "Is /clock being published?\n")
    core.on_shutdown(echo.done.set)  # Ctrl-C or rosnode kill ends the wait at once
    echo.done.wait()
    if echo.failure:
        raise RostopicError(echo.failure)
