"""rostopic pub [options] /topic type [args...]: publish messages from arguments, a file or stdin."""

from __future__ import annotations

import os
import select
import sys
import threading
import time
from collections.abc import Iterator
from typing import Any

import yaml

from kame import param_yaml
from kame.msg.fill import FillError, fill_message_args, printable_message_args
from kame.msg.message import Message, find_type_problem
from kame.rostime import Time

from ._common import (
    RostopicError,
    check_master,
    init_node,
    is_shutdown,
    load_message_class,
    option_parser,
    script_resolve_name,
    wait_shutdown,
)

ONCE_DELAY = 3.0
SUBSCRIBER_TIMEOUT = 5.0


def _keys(now: Time) -> dict[str, Any]:
    from std_msgs.msg import Header

    return {"now": now, "auto": Header(stamp=now)}


def _now() -> Time:
    """What `now` and `auto` stand for: ROS time once the node runs, else the wall clock."""
    from kame.client import clock

    if clock.is_rostime_initialized():
        now: Time = clock.get_rostime()
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
    """Publishing `cls` messages through `pub` (a kame.client Publisher: rospy's)."""

    def __init__(self, pub: Any, cls: type[Message], verbose: bool) -> None:
        self.pub = pub
        self.cls = cls
        self.verbose = verbose

    @classmethod
    def advertise(cls, topic: str, msg_class: type[Message], latch: bool, verbose: bool) -> Publishing:
        from kame.client.topics import Publisher

        return cls(Publisher(topic, msg_class, latch=latch, queue_size=100), msg_class, verbose)

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
                wait_shutdown(None)
            return
        from kame.client import errors, timer
        r = timer.Rate(rate)
        while not is_shutdown():
            if substitute:
                msg = make_message(self.cls, pub_args)
            if self.verbose:
                print(f"publishing {msg}", flush=True)
            self.publish(msg)
            try:
                r.sleep()
            except errors.ROSInterruptException:
                break

    def wait_for_subscriber(self, timeout: float) -> None:
        wait_for_subscriber(self.pub, timeout)


def wait_for_subscriber(pub: Any, timeout: float) -> None:
    """Until a subscriber connects to `pub`, `timeout` seconds pass or the node shuts down."""
    from kame.client import core

    connected = threading.Event()
    impl = pub.impl
    if impl is None:
        return

    def callback(link: Any) -> None:
        connected.set()

    impl.add_connect_callback(callback)
    try:
        with core.woken_at_shutdown(connected):
            if impl.links:
                return
            connected.wait(timeout)
    finally:
        impl.remove_connect_callback(callback)


def yaml_documents_from_file(path: str) -> list[Any]:
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


def yaml_documents_from_stdin() -> Iterator[Any]:
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
    parser = option_parser("usage: %prog pub /topic type [args...]")
    parser.add_argument("-v", dest="verbose", default=False, action="store_true", help="print verbose output")
    parser.add_argument("-r", "--rate", dest="rate", default=None,
                      help="publishing rate (hz).  For -f and stdin input, this defaults to 10.  Otherwise it is "
                           "not set.")
    parser.add_argument("-1", "--once", action="store_true", dest="once", default=False,
                      help="publish one message and exit")
    parser.add_argument("-f", "--file", dest="file", metavar="FILE", default=None,
                      help="read args from YAML file (Bagy)")
    parser.add_argument("-l", "--latch", dest="latch", default=False, action="store_true",
                      help="enable latching for -f, -r and piped input.  This latches the first message.")
    parser.add_argument("-s", "--substitute-keywords", dest="substitute_keywords", default=False,
                      action="store_true",
                      help="When publishing with a rate, performs keyword ('now' or 'auto') substitution for "
                           "each message")
    parser.add_argument("--use-rostime", dest="use_rostime", default=False, action="store_true",
                      help="use rostime for time stamps, else walltime is used")
    options = parser.parse_args(args)
    rest = options.args
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
    publishing = Publishing.advertise(script_resolve_name(topic), cls, latch, options.verbose)
    if not from_input:
        publishing.publish_message(pub_args, rate, options.once, options.substitute_keywords)
        if options.once:
            wait_shutdown(ONCE_DELAY)
        return
    if rate is None and not options.latch and not options.once:
        rate = 10.0
    publish_input(publishing, rate, options.once, options.file)


def publish_input(publishing: Publishing, rate: float | None, once: bool, path: str | None) -> None:
    """Publish the YAML documents of file `path` (stdin when None), `rate` a second (as fast as
    they come when None), after waiting up to SUBSCRIBER_TIMEOUT for a subscriber."""
    documents: Iterator[Any]
    exactly_one = False
    if path:
        loaded = yaml_documents_from_file(path)
        exactly_one = len(loaded) == 1
        documents = iter(loaded)
    else:
        documents = yaml_documents_from_stdin()
    from kame.client import errors, timer
    r = timer.Rate(rate) if rate is not None else None
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
            except errors.ROSInterruptException:
                break
        if is_shutdown() or once:
            break
