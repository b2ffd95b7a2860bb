"""rostopic as a library: topic types and classes, and the hz and bw statistics, as ROS code
calls them (`rostopic.get_topic_type('/chatter')`). The `rostopic` command is kame.cli.rostopic;
this module shares its master queries and statistics.
"""

from __future__ import annotations

import os
import sys
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from operator import itemgetter
from typing import Any
from urllib.parse import urlparse

import rosgraph.names
import roslib.message
from kame.cli import rostopic as _command
from kame.cli.rostopic import _common
from kame.cli.rostopic import pub as _pub
from kame.cli.rostopic.info import info_text
from kame.cli.topic_stats import BandwidthStats, DelayStats, RateStats, format_rate, format_rate_table
from kame.client import clock, core, log
from kame.client.topics import Publisher
from kame.msg import echo, lookup
from kame.msg.errors import MessageError
from kame.msg.fieldpath import FieldPath, FieldPathError
from kame.protocol.xmlrpc import Fault  # what a fault of kame's XML-RPC calls raises
from kame.rostime import Time

__all__ = [
    "NAME",
    "SUBSCRIBER_TIMEOUT",
    "CallbackEcho",
    "Fault",
    "ROSTopicBandwidth",
    "ROSTopicDelay",
    "ROSTopicException",
    "ROSTopicHz",
    "ROSTopicIOException",
    "argv_publish",
    "create_field_filter",
    "create_publisher",
    "create_value_transform",
    "file_yaml_arg",
    "find_by_type",
    "get_api",
    "get_info_text",
    "get_topic_class",
    "get_topic_list",
    "get_topic_type",
    "itemgetter",
    "long",
    "msgevalgen",
    "param_publish",
    "param_publish_once",
    "publish_message",
    "rostopicmain",
    "stdin_publish",
    "stdin_yaml_arg",
    "urlparse",
    "wait_for_subscriber",
]

NAME = "rostopic"
SUBSCRIBER_TIMEOUT = 5.0
long = int


class ROSTopicException(Exception):
    """Base of rostopic's errors."""


class ROSTopicIOException(ROSTopicException):
    """The master (or a node) could not be reached."""


def _evaluator(path: FieldPath | None) -> Callable[[Any], Any] | None:
    """The field `path` picks out of a message; a field the message lacks (or an index past an
    array's end) is said on stderr and gives None, as rostopic's msgeval."""
    if path is None:
        return None

    def msgeval(msg: Any) -> Any:
        try:
            return path.evaluate(msg)
        except FieldPathError as exc:
            print(exc, file=sys.stderr)
            return None

    return msgeval


def msgevalgen(pattern: str) -> Callable[[Any], Any] | None:
    """A function picking the field `pattern` (`/pose/x`, `/ranges[0:3]`) out of a message; None
    when the pattern names no field, or is malformed (then said on stderr), as rostopic's."""
    from kame.msg.fieldpath import parse_field_path

    try:
        return _evaluator(parse_field_path(pattern))
    except FieldPathError as exc:
        print(exc, file=sys.stderr)
        return None


def create_field_filter(echo_nostr: bool, echo_noarr: bool) -> Callable[[Any], Iterator[str]]:
    """The fields of a message `rostopic echo` prints: without arrays (`echo_noarr`) and
    strings (`echo_nostr`)."""
    def field_filter(val: Any) -> Iterator[str]:
        for name, slot_type in zip(val.__slots__, val._slot_types, strict=False):
            if echo_noarr and "[" in slot_type:
                continue
            if echo_nostr and "string" in slot_type:
                continue
            yield name

    return field_filter


def _str_plot_fields(val: Any, f: str, field_filter: Callable[[Any], Any] | None) -> str:
    """The CSV header `rostopic echo -p` prints (after its `%`): `time,` and the field names under `f`."""
    return "time," + (echo.csv_names(val, f, field_filter) or "")


def _str_plot(val: Any, time_offset: Time | None = None, current_time: Time | None = None,
              field_filter: Callable[[Any], Any] | None = None, type_information: str | None = None,
              fixed_numeric_width: int | None = None, value_transform: Any = None) -> str:
    """One CSV line of `rostopic echo -p`: the time in ns (`current_time`, else the header's
    stamp, else ROS time now; less `time_offset`), then the values."""
    if current_time is None and not getattr(val, "_has_header", False):
        current_time = clock.get_rostime()  # ROSInitException before init_node, as rospy's
    return echo.csv_row(val, current_time or Time(), time_offset, field_filter, receipt_time=current_time)


@contextmanager
def _master_session() -> Iterator[None]:
    """The command's master queries, their errors as rostopic's exceptions; the connection is
    dropped after, so each call reads ROS_MASTER_URI afresh as upstream's do."""
    try:
        yield
    except _common.MasterUnreachable:
        raise ROSTopicIOException("Unable to communicate with master!") from None
    except _common.RostopicError as exc:
        raise ROSTopicException(str(exc)) from None
    finally:
        _common.close_master()


def _find(topic: str) -> tuple[str, str, FieldPath | None] | None:
    with _master_session():
        return _common.find_topic(topic)


def get_topic_type(topic: str, blocking: bool = False) -> tuple[str | None, str | None, Callable[[Any], Any] | None]:
    """(type, the published topic, a function picking the named field or None) for `topic`,
    which may name a field inside a topic (`/turtle1/pose/x`); (None, None, None) when nothing
    publishes it, or, `blocking`, waits until something does (or shutdown)."""
    found = _find(topic)
    if found is None and blocking:
        sys.stderr.write(f"WARNING: topic [{topic}] does not appear to be published yet\n")
        while found is None and not core.is_shutdown():
            time.sleep(0.1)  # rostopic's own poll of the master; nothing tells us of a new publisher
            found = _find(topic)
    if found is None:
        return None, None, None
    topic_type, real_topic, path = found
    return topic_type, real_topic, _evaluator(path)


def get_topic_class(topic: str, blocking: bool = False) -> tuple[Any, str | None, Callable[[Any], Any] | None]:
    """(message class, the published topic, field function) for `topic`; (None, None, None)
    when nothing publishes it; ROSTopicException when its type cannot be loaded."""
    topic_type, real_topic, msg_eval = get_topic_type(topic, blocking=blocking)
    if topic_type is None:
        return None, None, None
    try:
        msg_class = lookup.message_class(topic_type)
    except MessageError:
        msg_class = None
    if msg_class is None:
        raise ROSTopicException(f"Cannot load message class for [{topic_type}]. Are your messages built?")
    return msg_class, real_topic, msg_eval


def get_topic_list(master: Any = None) -> tuple[list[tuple[str, str, list[str]]], list[tuple[str, str, list[str]]]]:
    """(publications, subscriptions), each a list of (topic, type, nodes); the type is
    `unknown type` when the master has none. `master`: a rosgraph.Master to ask instead."""
    if master is not None:
        return _common.typed_topics(master.getSystemState(), master.getTopicTypes())
    with _master_session():
        return _common.topic_list()


def get_info_text(topic: str) -> str:
    """What `rostopic info` prints for `topic`."""
    with _master_session():
        return info_text(topic)


class ROSTopicHz:
    """The publishing rate of topics, fed by a subscription callback (`callback_hz`)."""

    def __init__(self, window_size: int, filter_expr: Callable[[Any], bool] | None = None,
                 use_wtime: bool = False) -> None:
        self.lock = threading.Lock()
        self.filter_expr = filter_expr
        self.use_wtime = use_wtime
        self.window_size = 50000 if window_size < 0 else window_size
        self._stats: dict[str | None, RateStats] = {}

    def _topic(self, topic: str | None) -> RateStats:
        if topic not in self._stats:
            self._stats[topic] = RateStats(self.window_size)
        return self._stats[topic]

    def callback_hz(self, m: Any, topic: str | None = None) -> None:
        """Count a message of `topic` (None: the only topic) arriving now (ROS time, or wall time)."""
        if self.filter_expr is not None and not self.filter_expr(m):
            return
        with self.lock:
            stamp = Time.from_sec(time.time()) if self.use_wtime else clock.get_rostime()
            now = stamp.to_sec()  # wall time too goes through a Time (nanoseconds), as upstream
            notice = self._topic(topic).add(now)
        if notice:
            print(notice)

    def get_hz(self, topic: str | None = None) -> tuple[float, float, float, float, int] | None:
        """(rate, min interval, max interval, std dev, window) since the last call; None when
        nothing new arrived."""
        with self.lock:
            summary = self._topic(topic).summary()
        if summary is None:
            return None
        return summary.rate, summary.min, summary.max, summary.std_dev, summary.window

    def print_hz(self, topics: Sequence[str | None] = (None,)) -> None:
        """The rate report (a table for several topics; each row with its own window, where
        upstream repeats the first topic's)."""
        with self.lock:
            summaries = [(topic, self._topic(topic).summary()) for topic in topics]
        if len(summaries) == 1:
            print(format_rate(summaries[0][1]))
        else:
            print(format_rate_table([(str(topic), summary) for topic, summary in summaries]))


class ROSTopicBandwidth:
    """The bandwidth of a topic, fed raw messages (rospy.AnyMsg) by a subscription callback."""

    def __init__(self, window_size: int = 100) -> None:
        self.lock = threading.Lock()
        self.window_size = window_size or 100
        self._stats = BandwidthStats(self.window_size)

    @property
    def times(self) -> list[float]:
        return list(self._stats.times)

    @property
    def sizes(self) -> list[int]:
        return list(self._stats.sizes)

    def callback(self, data: Any) -> None:
        with self.lock:
            self._stats.add(time.time(), len(data._buff))

    def print_bw(self) -> None:
        """`average: 1.27KB/s` and its details; nothing before two messages arrived."""
        with self.lock:
            report = self._stats.report(time.time())
        if report is not None:
            print(report)


class ROSTopicDelay:
    """The delay of messages with a header (arrival in ROS time minus header.stamp), fed by a
    subscription callback (`callback_delay`)."""

    def __init__(self, window_size: int) -> None:
        self.lock = threading.Lock()
        self._stats = DelayStats(window_size)
        self.window_size = self._stats.window

    @property
    def delays(self) -> list[float]:
        return list(self._stats.delays)

    def callback_delay(self, msg: Any) -> None:
        if not msg._has_header:
            log.emit(log.ERROR, "msg does not have header", (), depth=2)
            return
        with self.lock:
            now = clock.get_rostime()
            notice = self._stats.add(0.0, 0.0) if now.is_zero() else self._stats.add(
                now.to_sec(), msg.header.stamp.to_sec())
        if notice:
            print(notice)

    def get_delay(self) -> tuple[float, float, float, float, int] | None:
        """(mean delay, min, max, std dev, window) since the last call; None when nothing new arrived."""
        with self.lock:
            summary = self._stats.summary()
        if summary is None:
            return None
        return summary.mean, summary.min, summary.max, summary.std_dev, summary.window

    def print_delay(self) -> None:
        """`average delay: 0.012` and its details; nothing before a delay was measured."""
        with self.lock:
            report = self._stats.report()
        if report is not None:
            print(report)


def create_value_transform(echo_nostr: bool, echo_noarr: bool) -> Callable[..., Any]:
    """`rostopic echo --nostr/--noarr`'s transform: a message whose strings and arrays (as asked)
    are replaced by `<string length: N>` and `<array type: T, length: N>`."""
    def value_transform(val: Any, type_information: str | None = None) -> Any:
        return echo.transform(val, type_information, echo_nostr, echo_noarr)

    return value_transform


def get_api(master: Any, caller_id: str) -> str:
    """The XML-RPC URI of node `caller_id`; ROSTopicIOException when the master cannot be reached."""
    try:
        return str(master.lookupNode(caller_id))
    except OSError:
        raise ROSTopicIOException("Unable to communicate with master!") from None


def find_by_type(topic_type: str) -> list[str]:
    """The published topics of type `topic_type`."""
    with _master_session():
        return [name for name, found in _common.topic_types() if found == topic_type]


def rostopicmain(argv: Sequence[str] | None = None) -> None:
    """The rostopic command on `argv` (sys.argv: the program, then the command); ends the process."""
    sys.exit(_command.main(None if argv is None else list(argv)))


# ---------------------------------------------------------------- rostopic pub's parts


@contextmanager
def _pub_errors() -> Iterator[None]:
    """rostopic pub's failures as rostopic's exception."""
    try:
        yield
    except _common.RostopicError as exc:
        raise ROSTopicException(str(exc)) from None


def create_publisher(topic_name: str, topic_type: str, latch: bool, disable_rostime: bool = True) -> tuple[Any, Any]:
    """(a Publisher of `topic_type` on `topic_name`, the message class), this process made the
    anonymous node `rostopic` first, without /rosout, as `rostopic pub` does."""
    topic_name = rosgraph.names.script_resolve_name(NAME, topic_name)
    try:
        msg_class = roslib.message.get_message_class(topic_type)
    except ValueError:
        raise ROSTopicException(f"invalid topic type: {topic_type}") from None
    if msg_class is None:
        package = topic_type.split("/")[0] if "/" in topic_type else None
        raise ROSTopicException(f"invalid message type: {topic_type}.\n"
                                f"If this is a valid message type, perhaps you need to type 'rosmake {package}'")
    _common.init_node(disable_rosout=True, disable_rostime=disable_rostime)
    return Publisher(topic_name, msg_class, latch=latch, queue_size=100), msg_class


def publish_message(pub: Any, msg_class: Any, pub_args: list[Any], rate: float | None = None, once: bool = False,
                    verbose: bool = False, substitute_keywords: bool = False) -> None:
    """A `msg_class` message filled from `pub_args` (YAML values; `now` and `auto` stand for the
    time and a header) published on `pub`: latched and, unless `once`, until shutdown; or `rate`
    times a second until shutdown."""
    with _pub_errors():
        _pub.Publishing(pub, msg_class, verbose).publish_message(pub_args, rate, once, substitute_keywords)


def argv_publish(pub: Any, msg_class: Any, pub_args: list[Any], rate: float | None, once: bool, verbose: bool,
                 substitute_keywords: bool = False) -> None:
    """publish_message; with `once`, then stay 3 s for subscribers to get it."""
    publish_message(pub, msg_class, pub_args, rate, once, verbose=verbose, substitute_keywords=substitute_keywords)
    if once:
        _common.wait_shutdown(_pub.ONCE_DELAY)


def wait_for_subscriber(pub: Any, timeout: float) -> None:
    """Until `pub` has a subscriber, `timeout` seconds pass or the node shuts down."""
    _pub.wait_for_subscriber(pub, timeout)


def file_yaml_arg(filename: str) -> Callable[[], Iterator[list[Any]]]:
    """A function iterating over the YAML documents of `filename`, each as a list of pub args."""
    if not os.path.isfile(filename):
        raise ROSTopicException(f"file does not exist: {filename}")

    def bagy_iter() -> Iterator[list[Any]]:
        with _pub_errors():
            documents = _pub.yaml_documents_from_file(filename)
        for document in documents:
            yield [document]

    return bagy_iter


def stdin_yaml_arg() -> Iterator[Any]:
    """The YAML documents read from stdin, each ended by a `---` line, until its end or shutdown."""
    return _pub.yaml_documents_from_stdin()


def stdin_publish(pub: Any, msg_class: Any, rate: float | None, once: bool, filename: str | None,
                  verbose: bool) -> None:
    """Publish the YAML documents of `filename` (stdin when None) as `rostopic pub -f` does."""
    with _pub_errors():
        _pub.publish_input(_pub.Publishing(pub, msg_class, verbose), rate, once, filename)


def param_publish_once(pub: Any, msg_class: Any, param_name: str, verbose: bool) -> None:
    """Publish the message the parameter `param_name` holds (`rostopic pub -p` once)."""
    import rospy

    if not rospy.has_param(param_name):
        raise ROSTopicException(f"parameter does not exist: {param_name}")
    argv_publish(pub, msg_class, rospy.get_param(param_name), None, True, verbose)


class CallbackEcho:
    """`rostopic echo`'s subscriber callback: prints each message (or the field `msg_eval`
    picks) as YAML, or as CSV with `plot`, up to `count` messages; `done` once it is through."""

    def __init__(self, topic: str, msg_eval: Callable[[Any], Any] | None, plot: bool = False,
                 filter_fn: Callable[[Any], bool] | None = None, echo_clear: bool = False,
                 echo_all_topics: bool = False, offset_time: bool = False, count: int | None = None,
                 field_filter_fn: Callable[[Any], Any] | None = None, fixed_numeric_width: int | None = None,
                 value_transform_fn: Callable[..., Any] | None = None) -> None:
        self.topic = topic[:-1] if topic and topic[-1] == "/" else topic
        self.msg_eval = msg_eval
        self.plot = plot
        self.filter_fn = filter_fn
        self.fixed_numeric_width = fixed_numeric_width
        self.prefix = "\033[2J\033[;H" if echo_clear and not plot else ""
        self.suffix = "" if plot else "\n---"  # the YAML document separator
        self.echo_all_topics = echo_all_topics
        self.offset_time = offset_time
        self.done = False
        self.max_count = count
        self.count = 0
        self.str_fn: Callable[..., str] = _str_plot if plot else self.custom_strify_message
        self.field_filter = field_filter_fn
        self.value_transform = value_transform_fn
        self.first = True
        self.last_topic: str | None = None
        self.last_msg_eval: Callable[[Any], Any] | None = None

    def custom_strify_message(self, val: Any, indent: str = "", time_offset: Time | None = None,
                              current_time: Time | None = None, field_filter: Callable[[Any], Any] | None = None,
                              type_information: str | None = None, fixed_numeric_width: int | None = None,
                              value_transform: Callable[..., Any] | None = None) -> str:
        """The YAML of `val` (a uint8[] field as numbers)."""
        if type_information and type_information.startswith("uint8[") and isinstance(val, (str, bytes)):
            val = [ord(x) if isinstance(x, str) else x for x in val]
        if value_transform is not None:
            val = value_transform(val, type_information)
        return echo.to_yaml(val, indent, time_offset, field_filter, fixed_numeric_width)

    def callback(self, data: Any, callback_args: dict[str, Any], current_time: Time | None = None) -> None:
        """Print `data`, a message of topic callback_args['topic'] (a field's type may be given as
        callback_args['type_information']); any failure ends the echo (`done`), as rostopic's."""
        topic = callback_args["topic"]
        type_information = callback_args.get("type_information")
        if self.filter_fn is not None and not self.filter_fn(data):
            return
        if self.max_count is not None and self.count >= self.max_count:
            self.done = True
            return
        try:
            msg_eval = self.msg_eval
            if topic != self.topic:
                if self.topic.startswith(topic + "/"):  # the echo names a field of this topic
                    if topic != self.last_topic:
                        self.last_msg_eval = msgevalgen(self.topic[len(topic):])
                        self.last_topic = topic
                    msg_eval = self.last_msg_eval
                elif not self.echo_all_topics:
                    return
            if msg_eval is not None:
                data = msg_eval(data)
            if data is not None:
                self.count += 1
                if self.plot and self.first:
                    sys.stdout.write("%" + _str_plot_fields(data, "field", self.field_filter) + "\n")
                    self.first = False
                time_offset = clock.get_rostime() if self.offset_time else None
                sys.stdout.write(self.prefix + self.str_fn(
                    data, time_offset=time_offset, current_time=current_time, field_filter=self.field_filter,
                    type_information=type_information, fixed_numeric_width=self.fixed_numeric_width,
                    value_transform=self.value_transform) + self.suffix + "\n")
                sys.stdout.flush()
            if self.max_count is not None and self.count >= self.max_count:
                self.done = True
        except Exception:  # rostopic's: whatever fails (a closed pipe, a bad field) ends the echo
            self.done = True


class _ParamNotifier:
    """The values a parameter takes, as the master's paramUpdate calls bring them: the whole
    value, or a part of it below the parameter (merged into the last value)."""

    def __init__(self, param_name: str, value: Any = None) -> None:
        self.lock = threading.Condition()
        self.param_name = param_name
        self.updates: list[Any] = []
        self.value = value

    def __call__(self, key: str, value: Any) -> None:
        with self.lock:
            if key.rstrip("/") != self.param_name.rstrip("/"):
                if not key.startswith(self.param_name.rstrip("/") + "/"):
                    return  # another parameter's update
                parts = [p for p in key[len(self.param_name):].split("/") if p]
                node = self.value
                for part in parts[:-1]:
                    node = node.setdefault(part, {})
                node[parts[-1]] = value
            else:
                self.value = value
            self.updates.append(self.value)
            self.lock.notify_all()


def _as_pub_args(value: Any, param_name: str) -> list[Any]:
    if isinstance(value, dict):
        return [value]
    if not isinstance(value, list):
        raise ROSTopicException(f"Parameter [{param_name}] in not a valid type")
    return value


def param_publish(pub: Any, msg_class: Any, param_name: str, rate: float | None, verbose: bool) -> None:
    """`rostopic pub -p`: publish the message the parameter holds, and again each time it changes
    (the master tells this node: subscribeParam); with `rate`, that many times a second."""
    import rospy

    node = core.get_node()
    if node is None or not rospy.has_param(param_name):
        raise ROSTopicException(f"parameter does not exist: {param_name}")
    resolved = rospy.resolve_name(param_name)
    notifier = _ParamNotifier(resolved)
    node.on_param_update.append(notifier)
    try:
        with notifier.lock:
            notifier.value = node.cached_param(resolved)
        pub_args = _as_pub_args(notifier.value, param_name)
        rate_ = rospy.Rate(rate) if rate is not None else None
        publish = True
        while not rospy.is_shutdown():
            if publish:
                try:
                    publish_message(pub, msg_class, pub_args, None, True, verbose=verbose)
                except ValueError as exc:
                    sys.stderr.write(f"{exc}\n")
                    break
            with notifier.lock:
                if rate_ is None and not notifier.updates:
                    notifier.lock.wait(1.0)  # a change, or a second to look at shutdown again
                publish = rate_ is not None or bool(notifier.updates)
                if notifier.updates:
                    pub_args = _as_pub_args(notifier.updates.pop(0), param_name)
            if rate_ is not None:
                rate_.sleep()
    finally:
        node.on_param_update.remove(notifier)
