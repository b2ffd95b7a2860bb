"""rostopic: list, info, type, find, echo, hz, bw, delay and pub, as ROS users know them.

Command-line parsing, master queries and printing; the pieces with rules live in pure
modules: kame.msg.fill (YAML arguments into messages), kame.msg.fieldpath (`/topic/a/b[1]`),
kame.msg.echo (what echo prints) and kame.cli.topic_stats (hz, bw and delay figures).

Behaviour follows ros_comm 1.15's rostopic: optparse/argparse usage errors (exit 2), one
`ERROR: ...` line on stderr and exit 1 for bad input and an unreachable master, the same
node start-up (an anonymous `/rostopic_<pid>_<ms>` node), hz and bw subscribing with
`md5sum=*`, and `pub -1` latching for 3 s. Where kame does better on purpose:
- echo, hz --filter and delay work for types kame does not have installed: they subscribe
  as AnyMsg and build the class from the publisher's message_definition;
- pub checks the whole message before publishing and names the field that does not fit,
  also when nobody subscribes yet (rostopic only fails once a subscriber serializes);
- field paths also work through array indices (`rostopic type /js/position[0]`);
- `list -b` and `echo -b` read bags through kame's rosbag (any message type, from the
  definitions stored in the bag).
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import optparse
import os
import select
import sys
import threading
import time
from collections.abc import Callable, Iterator
from typing import Any
from urllib.parse import urlparse

import yaml

from kame import names, param_yaml
from kame.bag.errors import BagError
from kame.msg.echo import as_field_value, csv_header, csv_row, field_filter, to_yaml, transform
from kame.msg.errors import MessageError
from kame.msg.fieldpath import FieldPath, FieldPathError, field_type, has_field, parse_field_path
from kame.msg.fill import FillError, fill_message_args, printable_message_args
from kame.msg.message import Message, find_type_problem
from kame.node.master_proxy import MasterError, MasterProxy
from kame.protocol.xmlrpc import Fault, MalformedError
from kame.rostime import Time

from .topic_stats import BandwidthStats, DelayStats, RateStats, format_rate, format_rate_table

NAME = "rostopic"
EX_USAGE = 64
ANYTYPE = "*"
ONCE_DELAY = 3.0
SUBSCRIBER_TIMEOUT = 5.0
DEFAULT_MASTER_URI = "http://localhost:11311/"


class RostopicError(Exception):
    """Printed as `ERROR: <text>` on stderr; exit status 1."""


class MasterUnreachable(RostopicError):
    def __init__(self) -> None:
        super().__init__("Unable to communicate with master!")


# ---------------------------------------------------------------- names and the master


def _ros_namespace() -> str:
    special = names.parse_args(sys.argv).special
    return names.make_global_ns(special.get("ns") or os.environ.get("ROS_NAMESPACE") or "/")


def script_resolve_name(name: str) -> str:
    """A name from the command line, resolved as rosgraph's script_resolve_name does."""
    ns = _ros_namespace()
    if not name:
        return ns
    if names.is_global(name):
        return name
    if names.is_private(name):
        return names.ns_join(ns + NAME, name[1:])
    return ns + name


def _master_uri() -> str:
    special = names.parse_args(sys.argv).special
    return special.get("master") or os.environ.get("ROS_MASTER_URI") or DEFAULT_MASTER_URI


class Master:
    """The master's API as the tool uses it: transport failures become MasterUnreachable."""

    def __init__(self) -> None:
        try:
            self._proxy = MasterProxy(_master_uri(), "/" + NAME, timeout=10.0)
        except ValueError as exc:
            raise RostopicError(f"invalid ROS_MASTER_URI: {exc}") from None

    def call(self, method: str, *args: object) -> Any:
        try:
            return self._proxy.call(method, *args)
        except OSError:
            raise MasterUnreachable() from None
        except MasterError as exc:
            raise RostopicError(exc.message) from None
        except (Fault, MalformedError) as exc:
            raise RostopicError(f"the master failed on {method}: {exc}") from None

    def close(self) -> None:
        self._proxy.close()


_master_instance: Master | None = None


def master() -> Master:
    global _master_instance
    if _master_instance is None:
        _master_instance = Master()
    return _master_instance


def check_master() -> None:
    master().call("getPid")


def topic_types() -> list[tuple[str, str]]:
    return [(str(t), str(ty)) for t, ty in master().call("getTopicTypes")]


# ---------------------------------------------------------------- message classes


def load_message_class(type_name: str) -> type[Message] | None:
    """The class of a message type (kame's packages, or user packages on ROS_PACKAGE_PATH)."""
    if type_name == "Header":
        type_name = "std_msgs/Header"
    package, _, short = type_name.partition("/")
    if not package or not short or "/" in short or not package.isidentifier() or not short.isidentifier():
        return None
    try:
        module = importlib.import_module(f"{package}.msg")
    except ImportError:
        return None
    except MessageError as exc:
        raise RostopicError(str(exc)) from None
    cls = getattr(module, short, None)
    if isinstance(cls, type) and issubclass(cls, Message) and cls._type == type_name:
        return cls
    return None


def _dynamic_class(header: dict[str, str]) -> type[Message]:
    """The class of a message that came from a publisher, made from its message_definition."""
    from kame.msg.loader import generate_dynamic

    type_name = header.get("type", "")
    definition = header.get("message_definition", "")
    if not type_name or type_name == ANYTYPE or not definition:
        raise RostopicError(f"the publisher [{header.get('callerid', '?')}] did not send the definition of its "
                            f"message type [{type_name}], and kame does not have it installed")
    cls: type[Message] = generate_dynamic(type_name, definition)[type_name]
    return cls


class Decoder:
    """Turns what a subscription delivers into a message: as is, or from AnyMsg bytes."""

    def __init__(self, cls: type[Message] | None) -> None:
        self.cls = cls
        self._dynamic: dict[tuple[str, str], type[Message]] = {}

    @property
    def subscribe_class(self) -> type[Any]:
        if self.cls is not None:
            return self.cls
        from rospy import AnyMsg

        return AnyMsg

    def __call__(self, msg: Any) -> Message:
        if self.cls is not None:
            decoded: Message = msg
            return decoded
        header: dict[str, str] = getattr(msg, "_connection_header", None) or {}
        key = (header.get("type", ""), header.get("message_definition", ""))
        cls = self._dynamic.get(key)
        if cls is None:
            cls = self._dynamic[key] = _dynamic_class(header)
        out = cls()
        out.deserialize(msg._buff)
        out._connection_header = header  # type: ignore[attr-defined]
        return out


# ---------------------------------------------------------------- topics and fields


def _nested_ok(topic_type: str, field: str) -> bool | None:
    cls = load_message_class(topic_type)
    if cls is None:
        return None
    return has_field(cls, field)


def find_topic(topic: str) -> tuple[str, str, FieldPath | None] | None:
    """(type, topic, field path) for `topic`, which may name a field: `/turtle1/pose/x`."""
    types = topic_types()
    matches = [(t, ty) for t, ty in types if t == topic]
    if not matches:
        candidates = sorted(((t, ty) for t, ty in types if topic.startswith(t + "/")), reverse=True)
        while candidates:
            t, ty = candidates[0]
            field = topic[len(t) + 1:].rstrip("/")
            if not field:
                break
            fits = _nested_ok(ty, field)
            if fits is None:  # a type we cannot load: take the longest match
                break
            if not fits:
                candidates.pop(0)
                continue
            break
        matches = candidates[:1]
    if not matches:
        return None
    t, ty = matches[0]
    if ty == ANYTYPE:
        return None
    try:
        path = parse_field_path(topic[len(t):])
    except FieldPathError as exc:
        raise RostopicError(str(exc)) from None
    return ty, t, path


def wait_for_topic(topic: str, shutdown: Callable[[], bool]) -> tuple[str, str, FieldPath | None] | None:
    found = find_topic(topic)
    if found is not None:
        return found
    sys.stderr.write(f"WARNING: topic [{topic}] does not appear to be published yet\n")
    sys.stderr.flush()
    while not shutdown():
        time.sleep(0.1)
        found = find_topic(topic)
        if found is not None:
            return found
    return None


# ---------------------------------------------------------------- the node


def _rospy() -> Any:
    import rospy

    return rospy


def init_node(disable_rosout: bool = False, disable_rostime: bool = False) -> None:
    _rospy().init_node(NAME, anonymous=True, disable_rosout=disable_rosout, disable_rostime=disable_rostime)


def is_shutdown() -> bool:
    from rospy import core

    return core.is_shutdown()


def wait_shutdown(seconds: float) -> bool:
    """Sleep `seconds` of wall time, waking at shutdown; True once shut down."""
    from rospy import core

    if core.get_node() is None:
        time.sleep(seconds)
        return False
    return core.wait_for_shutdown(seconds)


def _use_sim_time() -> bool:
    try:
        return bool(_rospy().get_param("/use_sim_time", False))
    except Exception:
        return False


def _write(text: str) -> None:
    sys.stdout.write(text)
    sys.stdout.flush()


# ---------------------------------------------------------------- list / info / type / find


def _topic_list() -> tuple[list[tuple[str, str, list[str]]], list[tuple[str, str, list[str]]]]:
    state = master().call("getSystemState")
    types = dict(reversed(topic_types()))

    def typed(entries: list[Any]) -> list[tuple[str, str, list[str]]]:
        return [(str(t), types.get(str(t), "unknown type"), [str(n) for n in nodes]) for t, nodes in entries]

    return typed(state[0]), typed(state[1])


def _print_list(pubs: list[tuple[str, str, list[str]]], subs: list[tuple[str, str, list[str]]],
                publishers_only: bool, subscribers_only: bool, verbose: bool, indent: str = "") -> None:
    if verbose:
        lines: list[str] = []
        if not subscribers_only:
            lines.append(f"\n{indent}Published topics:")
            for t, ty, nodes in pubs:
                count = f"{len(nodes)} publishers" if len(nodes) > 1 else "1 publisher"
                lines.append(f"{indent} * {t} [{ty}] {count}")
        if not publishers_only:
            lines.append(indent)
            lines.append(f"{indent}Subscribed topics:")
            for t, ty, nodes in subs:
                count = f"{len(nodes)} subscribers" if len(nodes) > 1 else "1 subscriber"
                lines.append(f"{indent} * {t} [{ty}] {count}")
        lines.append("")
        print("\n".join(lines))
        return
    if publishers_only:
        topics = [t for t, _, _ in pubs]
    elif subscribers_only:
        topics = [t for t, _, _ in subs]
    else:
        topics = list({t for t, _, _ in pubs} | {t for t, _, _ in subs})
    print("\n".join(indent + t for t in sorted(topics)))


def _open_bag(path: str) -> Any:
    if not os.path.exists(path):
        raise RostopicError(f"bag file [{path}] does not exist")
    import rosbag

    try:
        return rosbag.Bag(path)
    except rosbag.ROSBagException as exc:
        raise RostopicError(f"unable to use bag file: {exc}") from None


@contextlib.contextmanager
def _bag_errors() -> Iterator[None]:
    """A damaged bag found while reading (after it opened) ends the command with one line."""
    try:
        yield
    except (BagError, MessageError) as exc:
        raise RostopicError(f"unable to use bag file: {exc}") from None


def _bag_list(path: str, topic: str | None, verbose: bool) -> None:
    with _open_bag(path) as bag:
        info = bag.get_type_and_topic_info()
    topics = sorted(info.topics)
    if topic:
        ns = names.make_global_ns(topic)
        topics = [t for t in topics if t == topic or t.startswith(ns)]
    if verbose:
        print("\nPublished topics:")
        for t in topics:
            print(f" * {t} [{info.topics[t].msg_type}] {info.topics[t].message_count} msgs")
        return
    print("\n".join(topics))


def _bag_echo(path: str, topic: str, all_topics: bool, count: int | None, filter_fn: Callable[[Any, str], bool] | None,
              nostr: bool, noarr: bool, width: int | None, plot: bool) -> None:
    with _open_bag(path) as bag:
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
            _write(text)
            printed += 1
            if count is not None and printed >= count:
                return


def _parser(usage: str) -> optparse.OptionParser:
    return optparse.OptionParser(usage=usage, prog=NAME)


def cmd_list(args: list[str]) -> None:
    parser = _parser("usage: %prog list [/namespace]")
    parser.add_option("-b", "--bag", dest="bag", default=None, help="list topics in .bag file", metavar="BAGFILE")
    parser.add_option("-v", "--verbose", dest="verbose", default=False, action="store_true",
                      help="list full details about each topic")
    parser.add_option("-p", dest="publishers", default=False, action="store_true", help="list only publishers")
    parser.add_option("-s", dest="subscribers", default=False, action="store_true", help="list only subscribers")
    parser.add_option("--host", dest="hostname", default=False, action="store_true", help="group by host name")
    options, rest = parser.parse_args(args)
    topic = None
    if len(rest) == 1:
        topic = script_resolve_name(rest[0])
    elif len(rest) > 1:
        parser.error("you may only specify one input topic")
    if options.bag:
        if options.subscribers:
            parser.error("-s option is not valid with bags")
        elif options.publishers:
            parser.error("-p option is not valid with bags")
        elif options.hostname:
            parser.error("--host option is not valid with bags")
        with _bag_errors():
            _bag_list(options.bag, topic, options.verbose)
        return
    if options.subscribers and options.publishers:
        parser.error("you may only specify one of -p, -s")
    pubs, subs = _topic_list()
    if topic:
        ns = names.make_global_ns(topic)
        pubs = [x for x in pubs if x[0] == topic or x[0].startswith(ns)]
        subs = [x for x in subs if x[0] == topic or x[0].startswith(ns)]
    if not options.hostname:
        _print_list(pubs, subs, options.publishers, options.subscribers, options.verbose)
        return
    uris: dict[str, str] = {}

    def by_host(entries: list[tuple[str, str, list[str]]]) -> dict[str, list[tuple[str, str, list[str]]]]:
        hosts: dict[str, list[tuple[str, str, list[str]]]] = {}
        for t, ty, nodes in entries:
            for node in nodes:
                if node not in uris:
                    uris[node] = str(master().call("lookupNode", node))
                host = urlparse(uris[node]).hostname or ""
                rows = hosts.setdefault(host, [])
                for row in rows:
                    if row[0] == t:
                        row[2].append(node)
                        break
                else:
                    rows.append((t, ty, [node]))
        return hosts

    host_pubs, host_subs = by_host(pubs), by_host(subs)
    for host in sorted(set(host_pubs) | set(host_subs)):
        p, s = host_pubs.get(host, []), host_subs.get(host, [])
        if (p and not options.subscribers) or (s and not options.publishers):
            print(f"Host [{host}]:")
            _print_list(p, s, options.publishers, options.subscribers, options.verbose, indent="  ")


def info_text(topic: str) -> str:
    pubs, subs = _topic_list()
    pubs = [x for x in pubs if x[0] == topic]
    subs = [x for x in subs if x[0] == topic]
    if not pubs and not subs:
        raise RostopicError(f"Unknown topic {topic}")
    types = dict(reversed(topic_types()))
    uris: dict[str, str] = {}

    def api(node: str) -> str:
        if node not in uris:
            try:
                uris[node] = str(master().call("lookupNode", node))
            except MasterUnreachable:
                raise
            except RostopicError:
                uris[node] = f"unknown address {node}"
        return uris[node]

    out = [f"Type: {types.get(topic, 'unknown type')}\n\n"]
    for title, entries in (("Publishers", pubs), ("Subscribers", subs)):
        if entries:
            out.append(f"{title}: \n")
            out.extend(f" * {node} ({api(node)})\n" for _, _, nodes in entries for node in nodes)
        else:
            out.append(f"{title}: None\n")
        out.append("\n")
    return "".join(out)


def cmd_info(args: list[str]) -> None:
    parser = _parser("usage: %prog info /topic")
    _, rest = parser.parse_args(args)
    if not rest:
        parser.error("you must specify a topic name")
    elif len(rest) > 1:
        parser.error("you may only specify one topic name")
    print(info_text(script_resolve_name(rest[0])))


def cmd_type(args: list[str]) -> None:
    parser = argparse.ArgumentParser(prog=f"{NAME} type")
    parser.add_argument("topic_or_field", help="Topic or field name")
    topic = script_resolve_name(parser.parse_args(args).topic_or_field)
    found = find_topic(topic)
    if found is None:
        sys.stderr.write(f"unknown topic type [{topic}]\n")
        raise SystemExit(1)
    topic_type, real_topic, _ = found
    if topic == real_topic:
        print(topic_type)
        return
    field = topic[len(real_topic) + 1:]
    cls = load_message_class(topic_type)
    if cls is None:
        raise RostopicError(f"Cannot load message class for [{topic_type}]. Are your messages built?")
    try:
        print(f"{topic_type} {field} {field_type(cls, field)}")
    except FieldPathError as exc:
        raise RostopicError(str(exc)) from None


def cmd_find(args: list[str]) -> None:
    parser = _parser("usage: %prog find msg-type")
    _, rest = parser.parse_args(args)
    if not rest:
        parser.error("please specify a message type")
    if len(rest) > 1:
        parser.error("you may only specify one message type")
    print("\n".join(t for t, ty in topic_types() if ty == rest[0]))


# ---------------------------------------------------------------- echo


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
        self.done = threading.Event()
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
        rospy = _rospy()
        now = rospy.get_rostime()
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
        _write(text)
        if self.max_count is not None and self.count >= self.max_count:
            self.done.set()


def _filter(expr: str) -> Callable[[Any, str], bool]:
    try:
        code = compile(expr, "<filter>", "eval")
    except SyntaxError as exc:
        raise RostopicError(f"invalid filter expression [{expr}]: {exc.msg}") from None
    reported: list[bool] = []

    def evaluate(m: Any, topic: str = "") -> bool:
        try:
            return bool(eval(code, {}, {"m": m, "topic": topic}))
        except Exception as exc:
            if not reported:
                reported.append(True)
                sys.stderr.write(f"ERROR: filter expression [{expr}] failed: {type(exc).__name__}: {exc}\n")
            return False

    return evaluate


def cmd_echo(args: list[str]) -> None:
    parser = _parser("usage: %prog echo [options] /topic")
    parser.add_option("-b", "--bag", dest="bag", default=None, help="echo messages from .bag file",
                      metavar="BAGFILE")
    parser.add_option("-p", dest="plot", default=False, action="store_true",
                      help="echo in a plotting friendly format")
    parser.add_option("-w", dest="fixed_numeric_width", default=None, metavar="NUM_WIDTH",
                      help="fixed width for numeric values")
    parser.add_option("--filter", dest="filter_expr", default=None, metavar="FILTER-EXPRESSION",
                      help="Python expression to filter messages that are printed. Expression can use Python "
                           "builtins as well as m (the message) and topic (the topic name).")
    parser.add_option("--nostr", dest="nostr", default=False, action="store_true", help="exclude string fields")
    parser.add_option("--noarr", dest="noarr", default=False, action="store_true", help="exclude arrays")
    parser.add_option("-c", "--clear", dest="clear", default=False, action="store_true",
                      help="clear screen before printing next message")
    parser.add_option("-a", "--all", dest="all_topics", default=False, action="store_true",
                      help="display all message in bag, only valid with -b option")
    parser.add_option("-n", dest="msg_count", default=None, metavar="COUNT", help="number of messages to echo")
    parser.add_option("--offset", dest="offset_time", default=False, action="store_true",
                      help="display time as offsets from current time (in seconds)")
    options, rest = parser.parse_args(args)
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
    filter_fn = _filter(options.filter_expr) if options.filter_expr else None
    if options.bag:
        with _bag_errors():
            _bag_echo(options.bag, topic.rstrip("/") or "/", options.all_topics, count, filter_fn, options.nostr,
                      options.noarr, width, options.plot)
        return
    if topic.endswith("/"):
        topic = topic.rstrip("/") or "/"

    check_master()
    init_node()
    found = wait_for_topic(topic, is_shutdown)
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
    use_sim_time = _use_sim_time()
    _rospy().Subscriber(real_topic, decoder.subscribe_class, echo.callback)
    if use_sim_time:
        deadline = time.monotonic() + 2.0
        while time.monotonic() < deadline and echo.count == 0 and not echo.done.is_set():
            if wait_shutdown(0.1):
                return
        if echo.count == 0 and not echo.done.is_set():
            sys.stderr.write("WARNING: no messages received and simulated time is active.\n"
                             "Is /clock being published?\n")
    while not echo.done.is_set():
        if wait_shutdown(0.05):
            break
    if echo.failure:
        raise RostopicError(echo.failure)


# ---------------------------------------------------------------- hz / bw / delay


def _window(parser: optparse.OptionParser, value: Any) -> int:
    try:
        return int(value)
    except (TypeError, ValueError):
        parser.error("window size must be an integer")


def cmd_hz(args: list[str]) -> None:
    parser = _parser("usage: %prog hz [options] /topic_0 [/topic_1 [topic_2 [..]]]")
    parser.add_option("-w", "--window", dest="window_size", default=-1,
                      help="window size, in # of messages, for calculating rate", metavar="WINDOW")
    parser.add_option("--filter", dest="filter_expr", default=None,
                      help="only measure messages matching the specified Python expression", metavar="EXPR")
    parser.add_option("--wall-time", dest="use_wtime", default=False, action="store_true",
                      help="calculates rate using wall time which can be helpful when clock isn't published "
                           "during simulation")
    parser.add_option("--tcpnodelay", dest="tcp_nodelay", action="store_true",
                      help="use the TCP_NODELAY transport hint when subscribing to topics")
    options, rest = parser.parse_args(args)
    if not rest:
        parser.error("topic must be specified")
    window = _window(parser, options.window_size)
    topics = [script_resolve_name(t) for t in rest]
    filter_fn = _filter(options.filter_expr) if options.filter_expr else None

    check_master()
    init_node()
    rospy = _rospy()
    stats = {topic: RateStats(window) for topic in topics}
    lock = threading.Lock()

    def now() -> float:
        if options.use_wtime:
            return time.time()
        return float(rospy.get_rostime().to_sec())

    for topic in topics:
        found = wait_for_topic(topic, is_shutdown)
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
                _write(notice + "\n")

        subscribe_class = decoder.subscribe_class if decoder is not None else rospy.AnyMsg
        rospy.Subscriber(real_topic, subscribe_class, callback, tcp_nodelay=bool(options.tcp_nodelay))
        print(f"subscribed to [{real_topic}]")
    if _use_sim_time():
        sys.stderr.write("WARNING: may be using simulated time\n")
    while not wait_shutdown(1.0):
        with lock:
            if len(topics) == 1:
                text = format_rate(stats[topics[0]].summary())
            else:
                text = format_rate_table([(t, stats[t].summary()) for t in topics])
        _write(text + "\n")


def cmd_bw(args: list[str]) -> None:
    parser = _parser("usage: %prog bw /topic")
    parser.add_option("-w", "--window", dest="window_size", default=None,
                      help="window size, in # of messages, for calculating rate", metavar="WINDOW")
    options, rest = parser.parse_args(args)
    if not rest:
        parser.error("topic must be specified")
    if len(rest) > 1:
        parser.error("you may only specify one input topic")
    window = _window(parser, options.window_size) if options.window_size is not None else None
    topic = script_resolve_name(rest[0])

    check_master()
    found = wait_for_topic(topic, lambda: False)
    if found is None:
        return
    init_node(disable_rostime=True)
    rospy = _rospy()
    stats = BandwidthStats(window)
    lock = threading.Lock()

    def callback(raw: Any) -> None:
        with lock:
            stats.add(time.time(), len(raw._buff))

    rospy.Subscriber(found[1], rospy.AnyMsg, callback)
    print(f"subscribed to [{found[1]}]")
    while not wait_shutdown(1.0):
        with lock:
            text = stats.report(time.time())
        if text is not None:
            _write(text + "\n")


def cmd_delay(args: list[str]) -> None:
    parser = argparse.ArgumentParser(usage="%(prog)s delay [options] /topic", prog=NAME)
    parser.add_argument("topic", help="topic name to be calcurated the delay")
    parser.add_argument("-w", "--window", dest="window_size", default=-1, type=int,
                        help="window size, in # of messages, for calculating rate")
    parser.add_argument("--tcpnodelay", dest="tcp_nodelay", action="store_true",
                        help="use the TCP_NODELAY transport hint when subscribing to topics")
    parsed = parser.parse_args(args)
    topic = script_resolve_name(parsed.topic)

    found = wait_for_topic(topic, lambda: False)
    if found is None:
        return
    init_node()
    rospy = _rospy()
    decoder = Decoder(load_message_class(found[0]))
    stats = DelayStats(parsed.window_size)
    lock = threading.Lock()

    def callback(raw: Any) -> None:
        msg: Any = decoder(raw)
        if not msg._has_header:
            rospy.logerr("msg does not have header")
            return
        now = rospy.get_rostime()
        with lock:
            notice = stats.add(now.to_sec(), msg.header.stamp.to_sec()) if not now.is_zero() else stats.add(0.0, 0.0)
        if notice:
            _write(notice + "\n")

    rospy.Subscriber(found[1], decoder.subscribe_class, callback, tcp_nodelay=parsed.tcp_nodelay)
    print(f"subscribed to [{found[1]}]")
    if _use_sim_time():
        sys.stderr.write("WARNING: may be using simulated time\n")
    while not wait_shutdown(1.0):
        with lock:
            text = stats.report()
        if text is not None:
            _write(text + "\n")


# ---------------------------------------------------------------- pub


def _keys(now: Time) -> dict[str, Any]:
    from std_msgs.msg import Header

    return {"now": now, "auto": Header(stamp=now)}


def _now() -> Time:
    """What `now` and `auto` stand for: ROS time once the node runs, else the wall clock."""
    from rospy import rostime

    if rostime.is_rostime_initialized():
        now: Time = rostime.get_rostime()
        return now
    wall: Time = Time.from_nsec(time.time_ns())
    return wall


def _msg_text(cls: type[Message]) -> str:
    from kame.msg.md5 import split_full_text

    return split_full_text(cls._full_text)[0]


def make_message(cls: type[Message], pub_args: list[Any]) -> Message:
    """A message of `cls` filled from YAML values, checked field by field (RostopicError names the field)."""
    msg = cls()
    try:
        fill_message_args(msg, pub_args, _keys(_now()))
    except FillError as exc:
        raise RostopicError(f"{exc}\n\nArgs are: [{printable_message_args(msg)}]") from None
    problem = find_type_problem(msg)
    if problem:
        raise RostopicError("Unable to publish message. One of the fields has an incorrect type:\n"
                            f"  {problem}\n\nmsg file:\n{_msg_text(cls)}")
    return msg


class Publishing:
    def __init__(self, topic: str, cls: type[Message], latch: bool, verbose: bool) -> None:
        self.cls = cls
        self.verbose = verbose
        self.pub = _rospy().Publisher(topic, cls, latch=latch, queue_size=100)

    def publish(self, msg: Message) -> None:
        self.pub.publish(msg)

    def publish_message(self, pub_args: list[Any], rate: float | None, once: bool, substitute: bool) -> None:
        msg = make_message(self.cls, pub_args)
        if rate is None:
            text = f"publishing and latching [{msg}]" if self.verbose else "publishing and latching message"
            text += f" for {ONCE_DELAY} seconds" if once else ". Press ctrl-C to terminate"
            print(text, flush=True)
            self.publish(msg)
            if not once:
                while not wait_shutdown(1.0):
                    pass
            return
        rospy = _rospy()
        r = rospy.Rate(rate)
        while not is_shutdown():
            if substitute:
                msg = make_message(self.cls, pub_args)
            if self.verbose:
                print(f"publishing {msg}", flush=True)
            self.publish(msg)
            try:
                r.sleep()
            except rospy.ROSInterruptException:
                break

    def wait_for_subscriber(self, timeout: float) -> None:
        deadline = time.monotonic() + timeout
        while self.pub.get_num_connections() == 0 and time.monotonic() < deadline:
            if wait_shutdown(0.01):
                return


def _yaml_documents_from_file(path: str) -> list[Any]:
    if not os.path.isfile(path):
        raise RostopicError(f"file does not exist: {path}")
    try:
        with open(path) as f:
            documents = list(yaml.load_all(f, Loader=param_yaml.BoundedLoader))
        for document in documents:
            param_yaml.check_shape(document)
        return documents
    except (yaml.YAMLError, param_yaml.ParamValueError) as exc:
        raise RostopicError(f"invalid YAML in file: {exc}") from None
    except OSError as exc:
        raise RostopicError(f"cannot read {path}: {exc.strerror}") from None


def _yaml_documents_from_stdin() -> Iterator[Any]:
    """YAML documents on stdin separated by `---` lines; a trailing partial one is dropped."""
    buff = ""
    while not is_shutdown():
        ready, _, _ = select.select([sys.stdin], [], [], 1.0)
        if not ready:
            continue
        line = sys.stdin.readline()
        if line == "":
            return
        if line.strip() != "---":
            buff += line
            continue
        try:
            loaded = param_yaml.safe_load(buff.rstrip())
        except (yaml.YAMLError, param_yaml.ParamValueError) as exc:
            sys.stderr.write(f"Invalid YAML: {exc}\n")
            loaded = None
        buff = ""
        if loaded is not None:
            yield loaded


def cmd_pub(args: list[str]) -> None:
    parser = _parser("usage: %prog pub /topic type [args...]")
    parser.add_option("-v", dest="verbose", default=False, action="store_true", help="print verbose output")
    parser.add_option("-r", "--rate", dest="rate", default=None,
                      help="publishing rate (hz).  For -f and stdin input, this defaults to 10.  Otherwise it is "
                           "not set.")
    parser.add_option("-1", "--once", action="store_true", dest="once", default=False,
                      help="publish one message and exit")
    parser.add_option("-f", "--file", dest="file", metavar="FILE", default=None,
                      help="read args from YAML file (Bagy)")
    parser.add_option("-l", "--latch", dest="latch", default=False, action="store_true",
                      help="enable latching for -f, -r and piped input.  This latches the first message.")
    parser.add_option("-s", "--substitute-keywords", dest="substitute_keywords", default=False,
                      action="store_true",
                      help="When publishing with a rate, performs keyword ('now' or 'auto') substitution for "
                           "each message")
    parser.add_option("--use-rostime", dest="use_rostime", default=False, action="store_true",
                      help="use rostime for time stamps, else walltime is used")
    options, rest = parser.parse_args(args)
    rate: float | None = None
    if options.rate is not None:
        if options.once:
            parser.error("You cannot select both -r and -1 (--once)")
        try:
            rate = float(options.rate)
        except ValueError:
            parser.error("rate must be a number")
        if not rate > 0:
            parser.error("rate must be greater than zero")
    if not rest:
        parser.error("/topic must be specified")
    if len(rest) == 1:
        parser.error("topic type must be specified")
    if len(rest) > 2 and options.file:
        parser.error("args conflict with -f setting")
    topic, topic_type = rest[0], rest[1]
    pub_args: list[Any] = []
    try:
        for arg in rest[2:]:
            pub_args.append(param_yaml.safe_load(arg))
    except Exception as exc:
        parser.error(f"Argument error: {exc}")

    check_master()
    latch = rate is None or options.latch
    cls = load_message_class(topic_type)
    if cls is None:
        package = topic_type.split("/")[0] if "/" in topic_type else None
        raise RostopicError(f"invalid message type: {topic_type}.\n"
                            f"If this is a valid message type, perhaps you need to type 'rosmake {package}'")
    from_input = not pub_args and len(cls.__slots__) > 0
    if from_input:
        if not options.file and sys.stdin.isatty():
            parser.error("Please specify message values")
    else:
        make_message(cls, pub_args)  # bad arguments are reported before anything registers
    init_node(disable_rosout=True, disable_rostime=not options.use_rostime)
    publishing = Publishing(script_resolve_name(topic), cls, latch, options.verbose)
    if not from_input:
        publishing.publish_message(pub_args, rate, options.once, options.substitute_keywords)
        if options.once:
            deadline = time.monotonic() + ONCE_DELAY
            while time.monotonic() < deadline:
                if wait_shutdown(min(0.2, max(deadline - time.monotonic(), 0.0))):
                    break
        return
    if rate is None and not options.latch and not options.once:
        rate = 10.0
    _publish_input(publishing, rate, options.once, options.file)


def _publish_input(publishing: Publishing, rate: float | None, once: bool, path: str | None) -> None:
    documents: Iterator[Any]
    exactly_one = False
    if path:
        loaded = _yaml_documents_from_file(path)
        exactly_one = len(loaded) == 1
        documents = iter(loaded)
    else:
        documents = _yaml_documents_from_stdin()
    rospy = _rospy()
    r = rospy.Rate(rate) if rate is not None else None
    publishing.wait_for_subscriber(SUBSCRIBER_TIMEOUT)
    for document in documents:
        if is_shutdown():
            break
        if document:
            pub_args = document if isinstance(document, list) else [document]
            if exactly_one and rate is not None:
                print("Got one message and a rate, publishing repeatedly", flush=True)
                publishing.publish_message(pub_args, rate, once, False)
            else:
                publishing.publish_message(pub_args, None, r is not None or once, False)
        if r is not None:
            try:
                r.sleep()
            except rospy.ROSInterruptException:
                break
        if is_shutdown() or once:
            break


# ---------------------------------------------------------------- main

USAGE = """rostopic is a command-line tool for printing information about ROS Topics.

Commands:
\trostopic bw\tdisplay bandwidth used by topic
\trostopic delay\tdisplay delay of topic from timestamp in header
\trostopic echo\tprint messages to screen
\trostopic find\tfind topics by type
\trostopic hz\tdisplay publishing rate of topic{TRAILING}
\trostopic info\tprint information about active topic
\trostopic list\tlist active topics
\trostopic pub\tpublish data to topic
\trostopic type\tprint topic or field type

Type rostopic <command> -h for more detailed usage, e.g. 'rostopic echo -h'
""".replace("{TRAILING}", "    ")  # the real usage text has trailing spaces there

COMMANDS: dict[str, Callable[[list[str]], None]] = {
    "bw": cmd_bw, "delay": cmd_delay, "echo": cmd_echo, "find": cmd_find, "hz": cmd_hz, "info": cmd_info,
    "list": cmd_list, "pub": cmd_pub, "type": cmd_type,
}


def _shutdown() -> None:
    from rospy import core

    if core.get_node() is not None:
        core.signal_shutdown("rostopic done")
    if _master_instance is not None:
        _master_instance.close()


def main(argv: list[str] | None = None) -> int:
    args = names.parse_args(sys.argv if argv is None else argv).argv
    if len(args) < 2 or args[1] not in COMMANDS:
        print(USAGE)
        return EX_USAGE
    try:
        COMMANDS[args[1]](args[2:])
    except RostopicError as exc:
        sys.stderr.write(f"ERROR: {exc}\n")
        return 1
    except BrokenPipeError:
        _quiet_stdout()
    except OSError:
        sys.stderr.write("Network communication failed. Most likely failed to communicate with master.\n")
        return 1
    except KeyboardInterrupt:
        pass
    finally:
        try:
            _shutdown()
        except KeyboardInterrupt:
            pass
    try:
        sys.stdout.flush()
    except BrokenPipeError:
        _quiet_stdout()
    return 0


def _quiet_stdout() -> None:
    """After a closed pipe (`rostopic echo /x | head`), let Python exit without complaining."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())


if __name__ == "__main__":
    sys.exit(main())
