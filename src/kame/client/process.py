"""init_node, spin, parameters, myargv and the other top-level functions (rospy's)."""

from __future__ import annotations

import os
import signal
import sys
import threading
import time
from types import TracebackType
from typing import Any

from kame import environ, names
from kame.client import clock, core
from kame.client import log as _log
from kame.client.core import spin as spin  # rospy.spin: the services' spin() uses it too, so it lives in core
from kame.client.errors import InvalidCommandLineParams, ROSException, ROSInitException, ROSInterruptException
from kame.console import roscpp_colour, roscpp_line
from kame.net.signal_wake import SignalSafeEvent
from kame.node.config import node_config
from kame.node.master_proxy import MasterError
from kame.node.node import Node

DEFAULT_MASTER_URI = environ.DEFAULT_MASTER_URI
_unspecified = object()
_init_lock = threading.Lock()
_init_args: tuple[Any, ...] | None = None
_log_file: str | None = None


def myargv(argv: list[str] | None = None) -> list[str]:
    """argv without the ROS arguments (`a:=b`, `__name:=x`, `_p:=v`)."""
    return names.parse_args(sys.argv if argv is None else argv).argv


def _print_shutdown_call(caller_id: str, msg: str) -> None:
    """What rospy prints on stdout when the master or `rosnode kill` asks it to shut down; a port
    of a C++ program prints roscpp's two warnings instead (its shutdown callback's)."""
    if _log.roscpp_console():
        colour = roscpp_colour(os.environ)
        for text in ("Shutdown request received.", f"Reason given for shutdown: [{msg}]"):
            sys.stderr.write(roscpp_line("WARN", text, time.time_ns(), colour) + "\n")
        sys.stderr.flush()
        return
    print(f"shutdown request: {msg}" if msg else "shutdown requst", flush=True)  # sic: rospy's typo


# A master that is not up yet sends no event: init_node asks again five times a second, and
# shutdown (Ctrl-C) ends the wait at once.
MASTER_POLL_PERIOD = 0.2


def _wait_for_master(node: Node, master_uri: str) -> None:
    warned = False
    while not core.is_shutdown():
        try:
            node.master.call("getPid", timeout=2.0)
            return
        except (OSError, MasterError):
            if not warned:
                _log.emit(_log.ERROR, "Unable to immediately register with master node [%s]: "
                          "master may not be running yet. Will keep trying.", (master_uri,),
                          caller=("client.py", 0, "init_node", None))
                warned = True
            core.wait_for_shutdown(MASTER_POLL_PERIOD)
    raise ROSInitException("init_node interrupted before it could complete")


_interrupt_busy_main = True  # kame's own programs; a rospy program's Ctrl-C never raises (rospy_ctrl_c)


def rospy_ctrl_c() -> None:
    """Ctrl-C as rospy's handler takes it, for the programs that import rospy: the node shuts
    down and nothing is raised in the main thread, whatever it is doing (rospy swallows the
    KeyboardInterrupt), so `while not rospy.is_shutdown(): ...` ends at its next check, with no
    traceback, even when the Ctrl-C comes between two sleeps."""
    global _interrupt_busy_main
    _interrupt_busy_main = False


def install_signal_handlers() -> None:
    def handler(signum: int, frame: Any) -> None:
        # The shutdown runs on a thread of its own: the interrupted main thread may hold a lock
        # the shutdown needs (it may be in the middle of a publish). A main thread waiting in
        # rospy (spin, sleep, Rate) wakes up through the shutdown event and leaves quietly. In
        # kame's own programs one busy elsewhere (reading keys) gets a ROSInterruptException, a
        # KeyboardInterrupt too; a rospy program's goes on to its next is_shutdown(), as in rospy.
        waiting = core.main_thread_is_waiting()
        threading.Thread(target=core.signal_shutdown, args=(f"signal-{signum}",), name="rospy-shutdown").start()
        if signum == signal.SIGINT and not waiting and _interrupt_busy_main:
            raise ROSInterruptException("ROS shutdown request")

    if threading.current_thread() is not threading.main_thread():
        raise ValueError("signal only works in main thread")
    signal.signal(signal.SIGINT, handler)
    signal.signal(signal.SIGTERM, handler)


def _command_line_params(texts: dict[str, str]) -> dict[str, Any]:
    """The `_p:=value` arguments' values, loaded before the node registers. A value that is not
    YAML, or that an alias bomb would blow up, raises rospy's ROSInitException("invalid
    command-line parameters: ..."), which a program may catch; uncaught, it ends the program with
    that one line on stderr (exit 1), as a bad command-line option does, since its traceback
    says nothing more than its message."""
    if not texts:  # the usual case: no YAML parser loaded (tests/rospy/test_import_footprint.py)
        return {}
    import yaml

    from kame import param_yaml

    values: dict[str, Any] = {}
    for key, text in texts.items():
        try:
            values[key] = param_yaml.safe_load(text) if text else ""
        except (yaml.YAMLError, param_yaml.ParamValueError) as exc:
            problem = " ".join(str(exc).split())
            _print_uncaught_as_one_line()
            raise InvalidCommandLineParams(f"invalid command-line parameters: {key}: {problem}") from None
    return values


def _print_uncaught_as_one_line() -> None:
    """sys.excepthook prints an uncaught InvalidCommandLineParams as `[ERROR] <message>`; every
    other exception goes to the hook there was."""
    previous = sys.excepthook

    def hook(kind: type[BaseException], value: BaseException, tb: TracebackType | None) -> None:
        if isinstance(value, InvalidCommandLineParams):
            print(f"[ERROR] {value}", file=sys.stderr)
        else:
            previous(kind, value, tb)

    sys.excepthook = hook


def init_node(name: str, argv: list[str] | None = None, anonymous: bool = False, log_level: int | None = None,
              disable_rostime: bool = False, disable_rosout: bool = False, disable_signals: bool = False,
              xmlrpc_port: int = 0, tcpros_port: int = 0) -> None:
    """Register this process as the node `name` with the master (rospy.init_node)."""
    global _init_args
    args = (name, anonymous, log_level, disable_rostime, disable_rosout, disable_signals)
    with _init_lock:
        if _init_args is not None:
            if _init_args != args:
                raise ROSException("rospy.init_node() has already been called with different arguments: "
                                   + str(_init_args))
            return
        if not name:
            raise ValueError("name must not be empty")
        if names.SEP in name:
            raise ValueError("namespaces are not allowed in node names")
        ros_args = names.parse_args(sys.argv if argv is None else argv)
        private_params = _command_line_params(ros_args.params)
        special = ros_args.special
        if "name" in special:
            name = special["name"]
        elif anonymous:
            name = f"{name}_{os.getpid()}_{int(time.time() * 1000)}"
        if not names.is_legal_base_name(name):
            import warnings

            warnings.warn(f"'{name}' is not a legal ROS base name. This may cause problems with other ROS tools.",
                          stacklevel=2)
        config = node_config(name, {**special, "name": name}, os.environ, ros_args.remappings,
                             xmlrpc_port=xmlrpc_port, tcpros_port=tcpros_port)
        namespace, caller_id, master_uri = environ.namespace(os.environ, special), config.name, config.master_uri
        remappings = dict(config.remappings)
        if log_level is not None:
            _log.set_level(log_level)
        if not disable_signals:
            install_signal_handlers()
        node = Node(config)
        node.on_shutdown_request = core.signal_shutdown
        node.on_shutdown_call = _print_shutdown_call
        core.set_node(node, caller_id, namespace, remappings)
        _init_args = args
    _log.configure_file_logging(caller_id, special.get("log"))
    _log.route_runtime_logs()
    _wait_for_master(node, master_uri)
    for key, value in private_params.items():
        set_param(key, value)
    core.run_deferred()
    if not disable_rosout:
        start_rosout(node)
    if not disable_rostime:
        start_time(node)
    else:
        clock.set_rostime_initialized(True)
    _start_logger_services()


_started: set[str] = set()  # "rosout", "time": what start_rosout and start_time have done


def start_rosout(node: Node) -> None:
    """Publish the process's log lines on /rosout as `node` (once; init_node calls it unless disable_rosout)."""
    with _init_lock:
        if "rosout" in _started:
            return
        _started.add("rosout")
    from kame.client.topics import Publisher
    from rosgraph_msgs.msg import Log

    publisher = Publisher("/rosout", Log, latch=True, queue_size=100)
    try:
        omit_topics = bool(get_param("/rosout_disable_topics_generation", False))
    except Exception:
        omit_topics = False

    def publish(level: int, text: str, file: str, function: str, line: int) -> None:
        if core.is_shutdown() or publisher.impl is None:
            return
        msg = Log(level=level, name=node.name, msg=text, file=file, function=function, line=line,
                  topics=[] if omit_topics else sorted({*node.publications, *node.subscriptions}))
        msg.header.stamp = clock.get_rostime() if clock.is_rostime_initialized() else clock.Time()
        publisher.publish(msg)

    _log.set_rosout_publisher(publish)


def start_time(node: Node) -> None:
    """Follow /clock when /use_sim_time is true; ROS time is then initialized (once; init_node
    calls it unless disable_rostime)."""
    with _init_lock:
        if "time" in _started:
            return
        _started.add("time")
    try:
        use_sim_time = bool(get_param("/use_sim_time", False))
    except Exception:
        use_sim_time = False
    if use_sim_time:
        from kame.client.topics import Subscriber
        from rosgraph_msgs.msg import Clock

        clock.set_sim_time(clock.Time(0, 0))
        Subscriber("/clock", Clock, lambda msg: clock.set_sim_time(msg.clock), queue_size=1)
    clock.set_rostime_initialized(True)


_LEVEL_BY_NAME = {"debug": _log.DEBUG, "info": _log.INFO, "warn": _log.WARN, "error": _log.ERROR,
                  "fatal": _log.FATAL}


def _start_logger_services() -> None:
    from kame.client.services import Service, ServiceException
    from roscpp.msg import Logger
    from roscpp.srv import GetLoggers, GetLoggersResponse, SetLoggerLevel, SetLoggerLevelResponse

    def get_loggers(request: Any) -> Any:
        level = _log.LEVEL_NAMES[_log.get_level()].lower()
        return GetLoggersResponse(loggers=[Logger(name=n, level=level) for n in ("rosout", "rospy")])

    def set_logger_level(request: Any) -> Any:
        level = _LEVEL_BY_NAME.get(request.level.lower())
        if level is None:
            raise ServiceException(f"Invalid logger level [{request.level}]")
        _log.set_level(level)
        return SetLoggerLevelResponse()

    Service("~get_loggers", GetLoggers, get_loggers)
    Service("~set_logger_level", SetLoggerLevel, set_logger_level)


def _node() -> Any:
    node = core.get_node()
    if node is None:
        raise ROSInitException("client code must call rospy.init_node() first")
    return node


def _master() -> Any:
    return _node().master


# ------------------------------------------------------------------ parameters


def get_param(param_name: str, default: Any = _unspecified) -> Any:
    try:
        return _master().call("getParam", core.resolve_name(param_name))
    except MasterError:
        if default is _unspecified:
            raise KeyError(param_name) from None
        return default


def get_param_cached(param_name: str, default: Any = _unspecified) -> Any:
    """get_param, answered from a cache the master keeps up to date (subscribeParam)."""
    node = core.get_node()
    if node is None:
        raise ROSInitException("client code must call rospy.init_node() first")
    key = core.resolve_name(param_name)
    value = node.cached_param(key)
    if value == {} and not node.master.call_raw("hasParam", key)[2]:
        if default is _unspecified:
            raise KeyError(param_name)
        return default
    return value


def set_param(param_name: str, param_value: Any) -> None:
    if param_value is None:
        raise ROSException("cannot set a parameter to None")
    _node().set_param(core.resolve_name(param_name), param_value)


def has_param(param_name: str) -> bool:
    return bool(_master().call("hasParam", core.resolve_name(param_name)))


def delete_param(param_name: str) -> None:
    try:
        _node().delete_param(core.resolve_name(param_name))
    except MasterError:
        raise KeyError(param_name) from None


def search_param(param_name: str) -> str | None:
    try:
        found: str = _master().call("searchParam", param_name)
        return found
    except MasterError:
        return None


def get_param_names() -> list[str]:
    return list(_master().call("getParamNames"))


# ------------------------------------------------------------------ graph


def get_published_topics(namespace: str = "/") -> list[list[str]]:
    return [list(pair) for pair in _master().call("getPublishedTopics", namespace)]


def get_master(env: dict[str, str] | None = None) -> Any:
    return _master()


def wait_for_message(topic: str, topic_type: type[Any], timeout: Any = None) -> Any:
    """Subscribe, wait for one message, unsubscribe; ROSException on timeout."""
    from kame.client.topics import Subscriber

    got: list[Any] = []
    event = SignalSafeEvent()  # often waited on by the main thread

    def callback(msg: Any) -> None:
        if not got:
            got.append(msg)
            event.set()

    if timeout is not None and not isinstance(timeout, (int, float)):
        timeout = float(timeout.to_sec())  # a rospy.Duration, as rospy takes too
    subscriber = Subscriber(topic, topic_type, callback)
    try:
        # the message, or shutdown, sets it; a Ctrl-C meanwhile shuts down without raising into
        # the wait, which then raises rospy's "rospy shutdown"
        with core.woken_at_shutdown(event), core.main_thread_waiting():
            event.wait(timeout)
    finally:
        subscriber.unregister()
    if got:
        return got[0]
    if core.is_shutdown():
        raise ROSInterruptException("rospy shutdown")
    raise ROSException(f"timeout exceeded while waiting for message on topic {topic}")
