"""rosgraph's masterapi (with a substituted handle), xmlrpc (an XmlRpcNode served and called) and
roslogging (configure_logging's handlers, RosStreamHandler's lines, RospyLogger's callers);
prints JSON. Run by kame's interpreter and Debian's /usr/bin/python3 (its real rosgraph) with
ROS_IP=127.0.0.1 and ROS_HOME, ROS_LOG_DIR and ROS_ETC_DIR set by the test."""

from __future__ import annotations

import io
import json
import logging
import os
import sys
import threading
from collections.abc import Callable
from typing import Any

import rosgraph.masterapi
import rosgraph.names
import rosgraph.network
import rosgraph.rosenv
import rosgraph.roslogging
import rosgraph.xmlrpc


def outcome(call: Callable[[], Any]) -> Any:
    try:
        return call()
    except Exception as exc:
        return ["raised", type(exc).__name__, str(exc)]


class Handle:
    """Stands in for the master's XML-RPC proxy, as rosgraph's own tests do."""

    def __init__(self) -> None:
        self.calls: list[list[Any]] = []

    def __getattr__(self, method: str) -> Callable[..., Any]:
        def call(*args: Any) -> Any:
            self.calls.append([method, *args])
            return {"getPid": [1, "pid", 42], "getParam": [-1, "no such param", 0],
                    "setParam": [0, "failed", 0]}.get(method, [1, "ok", list(args)])
        return call


def master() -> dict[str, Any]:
    m = rosgraph.masterapi.Master("probe", master_uri="http://127.0.0.1:1/")
    handle = m.handle = Handle()
    return {"pid": m.getPid(), "param": outcome(lambda: m.getParam("/x")), "set": outcome(lambda: m.setParam("/x", 1)),
            "lookup": m.lookupNode("/n"), "state": m.getSystemState(), "online": m.is_online(),
            "calls": handle.calls, "caller_id": m.caller_id,
            "errors": [issubclass(rosgraph.masterapi.MasterError, rosgraph.masterapi.ROSMasterException),
                       rosgraph.masterapi.Error is rosgraph.masterapi.MasterError]}


class Adder(rosgraph.xmlrpc.XmlRpcHandler):
    def __init__(self) -> None:
        self.ready = threading.Event()
        self.events: list[str] = []

    def _ready(self, uri: str) -> None:
        self.events.append("ready")
        self.ready.set()

    def _shutdown(self, reason: str) -> None:
        self.events.append("shutdown " + reason)

    def add(self, a: int, b: int) -> int:
        return a + b

    def fail(self) -> None:
        raise ValueError("bad")


def xmlrpc_node() -> dict[str, Any]:
    handler = Adder()
    node = rosgraph.xmlrpc.XmlRpcNode(0, handler)
    node.start()
    handler.ready.wait(10)
    uri = str(node.uri)
    proxy = rosgraph.masterapi.ServerProxy(uri)
    out = {"uri": uri.startswith("http://127.0.0.1:") and uri.endswith(f":{node.port}/"),
           "add": proxy.add(2, 3), "missing": outcome(lambda: proxy.nope()), "fail": outcome(proxy.fail),
           "private": outcome(lambda: proxy._ready("x")),
           "multicall": proxy.system.multicall([{"methodName": "add", "params": [1, 1]},
                                                {"methodName": "nope", "params": []}])}
    node.shutdown("done")
    out.update(events=handler.events, after=[node.uri, node.port, node.server, node.handler, node.is_shutdown],
               isstring=[rosgraph.xmlrpc.isstring("a"), rosgraph.xmlrpc.isstring(b"a")])
    return out


def handlers(logger: logging.Logger) -> list[Any]:
    return [logging.getLevelName(logger.level), bool(logger.propagate),
            [[type(h).__name__, logging.getLevelName(h.level)] for h in logger.handlers]]


def logging_setup() -> dict[str, Any]:
    log_dir = os.environ["ROS_LOG_DIR"]
    path = rosgraph.roslogging.configure_logging("probe")
    out: dict[str, Any] = {"path": str(path).replace(log_dir, "LOG").replace(str(os.getpid()), "PID"),
                           "root": handlers(logging.getLogger()), "rosout": handlers(logging.getLogger("rosout")),
                           "logger_class": logging.getLoggerClass().__name__}
    made = os.path.join(log_dir, "a", "b")
    rosgraph.roslogging.makedirs_with_parent_perms(made)
    out["made"] = os.path.isdir(made) and os.stat(made).st_mode == os.stat(log_dir).st_mode
    return out


def stream_lines() -> dict[str, Any]:
    os.environ["ROSCONSOLE_FORMAT"] = "[${severity}] ${logger} ${node} ${function} ${line}: ${message}"
    stdout, stderr = io.StringIO(), io.StringIO()
    handler = rosgraph.roslogging.RosStreamHandler(colorize=True, stdout=stdout, stderr=stderr)
    logger = logging.getLogger("probe.stream")
    logger.addHandler(handler)
    logger.setLevel(logging.DEBUG)
    logger.propagate = False
    for level in (logging.DEBUG, logging.INFO, logging.WARNING, logging.ERROR, logging.CRITICAL):
        logger.log(level, "at %s", logging.getLevelName(level))

    class Talker:
        def run(self) -> None:
            self._base_logger("from a method")

        def _base_logger(self, text: str) -> None:  # rospy's log functions' inner frame
            logger.info(text)

    Talker().run()
    return {"stdout": stdout.getvalue().splitlines(), "stderr": stderr.getvalue().splitlines()}


def network_and_names() -> dict[str, Any]:
    import socket

    sender, receiver = socket.socketpair()
    with sender, receiver:
        sent = rosgraph.network.write_ros_handshake_header(sender, {"callerid": "/me", "topic": "/t"})
        sender.sendall(b"\x02\x00\x00\x00hi")
        buffer = io.BytesIO()
        header = rosgraph.network.read_ros_handshake_header(receiver, buffer, 65536)
        sender.shutdown(socket.SHUT_WR)
        closed = outcome(lambda: rosgraph.network.read_ros_handshake_header(receiver, io.BytesIO(), 65536))
    names = ["/a/b", "~p", "a", "1a", "a-b", "_x:=y", "__name:=n", "a:=b", "/a/b:=c", "a b"]
    patterns = [rosgraph.names.NAME_LEGAL_CHARS_P, rosgraph.names.BASE_NAME_LEGAL_CHARS_P,
                rosgraph.names.REMAP_PATTERN]
    return {"sent": sent, "header": header, "left": buffer.getvalue().hex(), "closed": closed,
            "patterns": [[bool(p.match(n)) for n in names] for p in patterns],
            "constants": [rosgraph.network.ROS_IP, rosgraph.network.ROS_HOSTNAME, rosgraph.network.ROS_IPV6,
                          rosgraph.network.SIOCGIFCONF, rosgraph.network.SIOCGIFADDR, rosgraph.network.python3,
                          rosgraph.network.logger.name, rosgraph.rosenv.DEFAULT_MASTER_PORT]}


def stdlib_servers() -> dict[str, Any]:
    """rosgraph.xmlrpc's ThreadingXMLRPCServer serving a function, called by xmlrpc.client."""
    import xmlrpc.client

    server = rosgraph.xmlrpc.ThreadingXMLRPCServer(("127.0.0.1", 0), False)
    server.register_function(lambda a, b: a * b, "mul")
    serving = threading.Thread(target=server.serve_forever)
    serving.start()
    try:
        proxy = xmlrpc.client.ServerProxy(f"http://127.0.0.1:{server.server_address[1]}/")
        product = proxy.mul(6, 7)
    finally:
        server.shutdown()
        serving.join()
        server.server_close()
    return {"product": product, "daemon_threads": server.daemon_threads, "reuse": server.allow_reuse_address,
            "protocol": rosgraph.xmlrpc.SilenceableXMLRPCRequestHandler.protocol_version,
            "bases": [issubclass(rosgraph.xmlrpc.ThreadingXMLRPCServer, rosgraph.xmlrpc.SimpleXMLRPCServer),
                      issubclass(rosgraph.xmlrpc.ForkingXMLRPCServer, rosgraph.xmlrpc.SimpleXMLRPCServer),
                      issubclass(rosgraph.xmlrpc.SilenceableXMLRPCRequestHandler,
                                 rosgraph.xmlrpc.SimpleXMLRPCRequestHandler)]}


def main() -> None:
    out = {"network": network_and_names(), "master": master(), "xmlrpc": xmlrpc_node(), "logging": logging_setup(),
           "stream": stream_lines(), "servers": stdlib_servers()}
    sys.stdout.write(json.dumps(out))


if __name__ == "__main__":
    main()
