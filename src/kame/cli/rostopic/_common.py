"""What the rostopic verbs share: errors, names and the master, message classes, finding a
topic, the tool's node, bags, and option parsing.
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
from collections.abc import Callable, Iterator
from typing import Any

from kame import environ, names
from kame.bag.errors import BagError
from kame.cli._options import OptionParser
from kame.msg import lookup
from kame.msg.anymsg import AnyMsg
from kame.msg.errors import MessageError
from kame.msg.fieldpath import FieldPath, FieldPathError, has_field, parse_field_path
from kame.msg.message import Message
from kame.node.master_proxy import MasterError, MasterProxy
from kame.node.remote_poll import poll_remote
from kame.protocol.xmlrpc import Fault, MalformedError

NAME = "rostopic"
ANYTYPE = "*"


class RostopicError(Exception):
    """Printed as `ERROR: <text>` on stderr; exit status 1."""


class MasterUnreachable(RostopicError):
    def __init__(self) -> None:
        super().__init__("Unable to communicate with master!")


def _ros_namespace() -> str:
    return environ.namespace(os.environ, names.parse_args(sys.argv).special)


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
    return environ.master_uri(os.environ, names.parse_args(sys.argv).special)


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


def close_master() -> None:
    global _master_instance
    if _master_instance is not None:
        _master_instance.close()
        _master_instance = None


def check_master() -> None:
    master().call("getPid")


def topic_types() -> list[tuple[str, str]]:
    return [(str(t), str(ty)) for t, ty in master().call("getTopicTypes")]


def load_message_class(type_name: str) -> type[Message] | None:
    """The class of a message type (kame's packages, or user packages on ROS_PACKAGE_PATH)."""
    try:
        return lookup.message_class(type_name)
    except MessageError as exc:
        raise RostopicError(str(exc)) from None


def _dynamic_class(header: dict[str, str]) -> type[Message]:
    """The class of a message that came from a publisher: installed, or made from its message_definition."""
    type_name = header.get("type", "")
    cls = None
    if type_name and type_name != ANYTYPE:
        cls = lookup.class_for(type_name, header.get("md5sum", ""), header.get("message_definition", ""))
    if cls is None:
        raise RostopicError(f"the publisher [{header.get('callerid', '?')}] did not send the definition of its "
                            f"message type [{type_name}], and kame does not have it installed")
    return cls


class Decoder:
    """Turns what a subscription delivers into a message: as is, or from AnyMsg bytes."""

    def __init__(self, cls: type[Message] | None) -> None:
        self.cls = cls
        self._dynamic: dict[tuple[str, str], type[Message]] = {}

    @property
    def subscribe_class(self) -> type[Any]:
        return self.cls if self.cls is not None else AnyMsg

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


def wait_for_topic(topic: str, stoppable: bool = False) -> tuple[str, str, FieldPath | None] | None:
    """The topic's type, name and field path once the master lists it; None if the node shut
    down first (`stoppable`: the node is up). Without a node, Ctrl-C ends the wait."""
    found = find_topic(topic)
    if found is not None:
        return found
    sys.stderr.write(f"WARNING: topic [{topic}] does not appear to be published yet\n")
    sys.stderr.flush()
    if not stoppable:
        return poll_remote(lambda: find_topic(topic))
    from kame.client import core

    return poll_remote(lambda: find_topic(topic), core.wait_for_shutdown)


def init_node(disable_rosout: bool = False, disable_rostime: bool = False) -> None:
    from kame.client import process

    process.init_node(NAME, anonymous=True, disable_rosout=disable_rosout, disable_rostime=disable_rostime)


def is_shutdown() -> bool:
    from kame.client import core

    return core.is_shutdown()


def wait_shutdown(seconds: float | None) -> bool:
    """Sleep `seconds` of wall time (None: until shutdown), waking at shutdown; True once shut down."""
    from kame.client import core

    if core.get_node() is None:
        threading.Event().wait(seconds)  # Ctrl-C ends it
        return False
    return core.wait_for_shutdown(seconds)


def use_sim_time() -> bool:
    try:
        from kame.client import process

        return bool(process.get_param("/use_sim_time", False))
    except Exception:
        return False


def write(text: str) -> None:
    sys.stdout.write(text)
    sys.stdout.flush()


TypedTopics = tuple[list[tuple[str, str, list[str]]], list[tuple[str, str, list[str]]]]


def typed_topics(state: Any, topic_types: list[Any]) -> TypedTopics:
    """(publications, subscriptions) of a getSystemState answer as (topic, type, nodes), the
    type the first getTopicTypes names for the topic, or `unknown type`."""
    types = {str(t): str(ty) for t, ty in reversed(topic_types)}

    def typed(entries: list[Any]) -> list[tuple[str, str, list[str]]]:
        return [(str(t), types.get(str(t), "unknown type"), [str(n) for n in nodes]) for t, nodes in entries]

    return typed(state[0]), typed(state[1])


def topic_list() -> TypedTopics:
    return typed_topics(master().call("getSystemState"), topic_types())


def open_bag(path: str) -> Any:
    if not os.path.exists(path):
        raise RostopicError(f"bag file [{path}] does not exist")
    from kame.client.bag import Bag

    try:
        return Bag(path)
    except BagError as exc:
        raise RostopicError(f"unable to use bag file: {exc}") from None


@contextlib.contextmanager
def bag_errors() -> Iterator[None]:
    """A damaged bag found while reading (after it opened) ends the command with one line."""
    try:
        yield
    except (BagError, MessageError) as exc:
        raise RostopicError(f"unable to use bag file: {exc}") from None


def option_parser(usage: str) -> OptionParser:
    return OptionParser(usage=usage, prog=NAME)


def filter_function(expr: str) -> Callable[[Any, str], bool]:
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


def window_size(parser: OptionParser, value: Any) -> int:
    try:
        return int(value)
    except (TypeError, ValueError):
        parser.error("window size must be an integer")
