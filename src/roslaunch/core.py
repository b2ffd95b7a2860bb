"""roslaunch.core: the launch model's values as roslaunch names them (Node, Test, Param, Machine,
Master, Executable), the printlog family, child mode and the process environment.

Rules (roslaunch's core, checked against Debian's on the same inputs):
- Node validates as ROS's does, with ValueError: an empty package or type, a name with a
  namespace, respawn together with required, output other than log/screen, cwd other than
  ROS_HOME/node (`ros_home` is taken as ROS_HOME). remap_args stay the lists given.
- Node is kame's scripting Node (kame.launch.scripting), so ROSLaunch.launch takes it.
- printlog/printlog_bold/printerrlog print as kame's supervisor does (a closed stream is no
  error), after telling each handler added; a handler that raises is skipped, as in ROS.
- Master.get() is a ServerProxy on the master (kame.net.server_proxy: the stdlib's calling convention
  over kame's XML-RPC client), get_multi() a MultiCall.
"""

from __future__ import annotations

import os
import re
import uuid
from collections.abc import Callable, Mapping
from typing import Any, TypeVar
from xml.sax.saxutils import escape

import rosgraph
import rospkg
from kame.launch.model import node_problem
from kame.launch.runner import machine_is_local
from kame.launch.scripting import Node as _ScriptNode
from kame.launch.scripting import RLException
from kame.launch.supervisor import say, say_bold, say_error
from kame.net.server_proxy import MultiCall, ServerProxy
from rosgraph.network import create_local_xmlrpc_uri, parse_http_host_and_port

__all__ = ["PHASE_RUN", "PHASE_SETUP", "PHASE_TEARDOWN", "TEST_TIME_LIMIT_DEFAULT", "Executable", "Machine", "Master",
           "MultiCall", "Node", "Param", "RLException", "RosbinExecutable", "ServerProxy", "Test",
           "add_printerrlog_handler", "add_printlog_handler", "basestring", "clear_printerrlog_handlers",
           "clear_printlog_handlers", "escape", "generate_run_id", "get_master_uri_env", "get_ros_package_path",
           "get_ros_root", "is_child_mode", "is_machine_local", "local_machine", "printerrlog", "printlog",
           "printlog_bold", "remap_localhost_uri", "rle_wrapper", "set_child_mode", "setup_env", "unicode"]

basestring = unicode = str  # ROS's Python 2 names, still exported by its core

PHASE_SETUP = "setup"
PHASE_RUN = "run"
PHASE_TEARDOWN = "teardown"
TEST_TIME_LIMIT_DEFAULT = 60
DEFAULT_REGISTER_TIMEOUT = 10.0  # a Machine's timeout when none is given

_child_mode = False


def is_child_mode() -> bool:
    """Whether this roslaunch runs as a remote child."""
    return _child_mode


def set_child_mode(child_mode: bool) -> None:
    global _child_mode
    _child_mode = child_mode


def is_machine_local(machine: Machine) -> bool:
    """True when `machine`'s nodes run on this host: its address is this host's and it names no
    other user (another user on this host is reached over SSH)."""
    return machine_is_local(machine.address, machine.user)


Handler = Callable[[str], Any]
_printlog_handlers: list[Handler] = []
_printerrlog_handlers: list[Handler] = []


def _tell(handlers: list[Handler], msg: str) -> None:
    for handler in handlers:
        try:
            handler(msg)
        except Exception:  # as ROS: a handler's failure must not stop the message being printed
            pass


def printlog(msg: str) -> None:
    """`msg` to stdout and to each printlog handler."""
    _tell(_printlog_handlers, msg)
    say(str(msg))


def printlog_bold(msg: str) -> None:
    """`msg` to stdout in bold, and to each printlog handler."""
    _tell(_printlog_handlers, msg)
    say_bold(str(msg))


def printerrlog(msg: str) -> None:
    """`msg` to stderr in red, and to each printerrlog handler."""
    _tell(_printerrlog_handlers, msg)
    say_error(str(msg))


def add_printlog_handler(h: Handler) -> None:
    _printlog_handlers.append(h)


def add_printerrlog_handler(h: Handler) -> None:
    _printerrlog_handlers.append(h)


def clear_printlog_handlers() -> None:
    del _printlog_handlers[:]


def clear_printerrlog_handlers() -> None:
    del _printerrlog_handlers[:]


def setup_env(node: Node | None, machine: Machine | None, master_uri: str,
              env: Mapping[str, str] | None = None) -> dict[str, str]:
    """The environment of a launched process: `env` (ours by default) with ROS_MASTER_URI, and for
    a node its ROS_NAMESPACE (unset at the root) and its <env>s."""
    result = dict(os.environ if env is None else env)
    result["ROS_MASTER_URI"] = master_uri
    if node is not None:
        result.pop("ROS_NAMESPACE", None)
        ns = node.namespace[:-1] if node.namespace.endswith("/") else node.namespace
        if ns:
            result["ROS_NAMESPACE"] = str(ns)
        for name, value in node.env_args:
            result[str(name)] = str(value)
    return result


R = TypeVar("R")


def rle_wrapper(fn: Callable[..., R]) -> Callable[..., R]:
    """`fn` with any exception it raises turned into RLException("ERROR: ...")."""

    def wrapped_fn(*args: Any) -> R:
        try:
            return fn(*args)
        except Exception as exc:
            raise RLException(f"ERROR: {exc}") from exc

    return wrapped_fn


get_ros_root = rospkg.get_ros_root
get_master_uri_env = rle_wrapper(rosgraph.get_master_uri)
get_ros_package_path = rospkg.get_ros_package_path


def remap_localhost_uri(uri: str, force_localhost: bool = False) -> str:
    """`uri` with `localhost` (or any host, when forced) made this host's address."""
    hostname, port = parse_http_host_and_port(uri)
    if force_localhost or hostname == "localhost":
        return create_local_xmlrpc_uri(port)
    return uri


def generate_run_id() -> str:
    return str(uuid.uuid1())


class Master:
    """The master a launch uses: its kind and URI (ROS_MASTER_URI unless given)."""

    ROSMASTER = "rosmaster"
    ZENMASTER = "zenmaster"

    def __init__(self, type_: str | None = None, uri: str | None = None, auto: int | None = None) -> None:
        self.auto = None  # no longer used, as in roslaunch
        self.type = type_ or Master.ROSMASTER
        self.uri = uri or get_master_uri_env()

    def get_host(self) -> str:
        return parse_http_host_and_port(self.uri)[0]

    def get_port(self) -> int:
        return parse_http_host_and_port(self.uri)[1]

    def get(self) -> ServerProxy:
        """An XML-RPC proxy on the master."""
        return ServerProxy(self.uri)

    def get_multi(self) -> MultiCall:
        return MultiCall(self.get())

    def is_running(self) -> bool:
        return rosgraph.is_master_online(self.uri)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Master) and (other.type, other.uri) == (self.type, self.uri)

    def __hash__(self) -> int:
        return hash((self.type, self.uri))


class Machine:
    """A <machine>: where nodes assigned to it run."""

    def __init__(self, name: str, address: str, env_loader: str | None = None, ssh_port: int = 22,
                 user: str | None = None, password: str | None = None, assignable: bool = True,
                 env_args: list[tuple[str, str]] | None = None, timeout: float | None = None) -> None:
        self.name = name
        self.address = address
        self.env_loader = env_loader
        self.ssh_port = ssh_port
        self.user = user or None
        self.password = password
        self.assignable = assignable
        self.timeout = timeout or DEFAULT_REGISTER_TIMEOUT

    def __str__(self) -> str:
        return (f"Machine(name[{self.name}] env_loader[{self.env_loader}] address[{self.address}] "
                f"ssh_port[{self.ssh_port}] user[{self.user}] assignable[{self.assignable}] timeout[{self.timeout}])")

    def __repr__(self) -> str:
        return str(self)

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, Machine) and self.name == other.name and self.assignable == other.assignable
                and self.config_equals(other))

    def __hash__(self) -> int:
        return hash(self.config_key())

    def config_key(self) -> str:
        """What makes two machines the same place to run (not their names), as roslaunch writes it."""
        return (f"Machine(address[{self.address}] env_loader[{self.env_loader}] ssh_port[{self.ssh_port}] "
                f"user[{self.user or ''}] password[{self.password or ''}] timeout[{self.timeout}])")

    def config_equals(self, other: object) -> bool:
        return isinstance(other, Machine) and self.config_key() == other.config_key()


_local_machine: Machine | None = None


def local_machine() -> Machine:
    """The machine of nodes without one: this host (the same object on every call)."""
    global _local_machine
    if _local_machine is None:
        _local_machine = Machine("", "localhost")
    return _local_machine


class Param:
    """A parameter to set: its global key and value."""

    def __init__(self, key: str, value: Any) -> None:
        self.key = rosgraph.names.canonicalize_name(key)
        self.value = value

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Param) and (other.key, other.value) == (self.key, self.value)

    def __hash__(self) -> int:
        return hash(self.key)

    def __repr__(self) -> str:
        return f"{self.key}={self.value}"

    __str__ = __repr__


def _xml_escape(value: Any) -> Any:
    return escape(value, entities={'"': "&quot;"}) if isinstance(value, str) else value


class Node(_ScriptNode):
    """A <node> to launch; ValueError when its attributes do not validate."""

    def __init__(self, package: str, node_type: str, name: str | None = None, namespace: str = "/",
                 machine_name: str | None = None, args: str = "", respawn: bool = False, respawn_delay: float = 0.0,
                 remap_args: Any = None, env_args: Any = None, output: str | None = None, cwd: str | None = None,
                 launch_prefix: str | None = None, required: bool = False, filename: str = "<unknown>") -> None:
        super().__init__(package, node_type, name=name or None, namespace=namespace, machine_name=machine_name or None,
                         args=args or "", respawn=respawn, respawn_delay=respawn_delay, output=output,
                         cwd="ROS_HOME" if cwd == "ros_home" else cwd, launch_prefix=launch_prefix or None,
                         required=required, filename=filename)
        self.namespace = re.sub("//+", "/", self.namespace)
        self.remap_args = remap_args or []  # the caller's own list, as ROS keeps it
        self.env_args = env_args or []
        self.process_name: str | None = None
        problem = node_problem(self.package, self.type, self.name, self.respawn, self.required, self.output,
                               self.cwd)
        if problem is not None:
            raise ValueError(problem)

    def xmltype(self) -> str:
        return "node"

    def xmlattrs(self) -> list[tuple[str, Any]]:
        return [("pkg", self.package), ("type", self.type), ("machine", self.machine_name), ("ns", self.namespace),
                ("args", self.args), ("output", self.output), ("cwd", self.cwd or None), ("respawn", self.respawn),
                ("respawn_delay", self.respawn_delay), ("name", self.name or None),
                ("launch-prefix", self.launch_prefix), ("required", self.required)]

    def _xml(self, skip: tuple[str, ...]) -> str:
        tag = self.xmltype()
        attrs = " ".join(f'{a}="{_xml_escape(v)}"' for a, v in self.xmlattrs() if v is not None and a not in skip)
        text = f"<{tag} {attrs}>\n"
        text += "".join(f'  <remap from="{r[0]}" to="{r[1]}" />\n' for r in self.remap_args)
        text += "".join(f'  <env name="{e[0]}" value="{e[1]}" />\n' for e in self.env_args)
        return text + f"</{tag}>"

    def to_xml(self) -> str:
        """The node as launch XML (private parameters left out)."""
        return self._xml(())

    def to_remote_xml(self) -> str:
        """The node as launch XML for a remote child: without its machine."""
        return self._xml(("machine",))


class Test(Node):
    """A <test>: a node rostest runs, with its name, time limit and retries."""

    def __init__(self, test_name: str, package: str, node_type: str, name: str | None = None, namespace: str = "/",
                 machine_name: str | None = None, args: str = "", remap_args: Any = None, env_args: Any = None,
                 time_limit: float | None = None, cwd: str | None = None, launch_prefix: str | None = None,
                 retry: int | None = None, filename: str = "<unknown>") -> None:
        super().__init__(package, node_type, name=name, namespace=namespace, machine_name=machine_name, args=args,
                         remap_args=remap_args, env_args=env_args, output="log", cwd=cwd,
                         launch_prefix=launch_prefix, filename=filename)
        self.test_name = test_name
        self.retry = retry or 0
        limit = time_limit or TEST_TIME_LIMIT_DEFAULT
        if type(limit) not in (float, int):
            raise ValueError("'time-limit' must be a number")
        if float(limit) <= 0:
            raise ValueError("'time-limit' must be a positive number")
        self.time_limit = float(limit)

    def xmltype(self) -> str:
        return "test"

    def xmlattrs(self) -> list[tuple[str, Any]]:
        attrs = [(a, v) for a, v in super().xmlattrs() if a not in ("respawn", "respawn_delay")]
        attrs.append(("test-name", self.test_name))
        if self.retry:
            attrs.append(("retry", str(self.retry)))
        if self.time_limit != TEST_TIME_LIMIT_DEFAULT:
            attrs.append(("time-limit", self.time_limit))
        return attrs


class Executable:
    """A command run around the launch: before it (PHASE_SETUP), during, or after."""

    def __init__(self, cmd: str, args: tuple[str, ...], phase: str = PHASE_RUN) -> None:
        self.command = cmd
        self.args = args
        self.phase = phase

    def __repr__(self) -> str:
        return f"{self.command} {' '.join(self.args)}"

    __str__ = __repr__


class RosbinExecutable(Executable):
    """A ROS tool's command (rosparam dump/delete)."""

    def __repr__(self) -> str:
        return f"ros/bin/{self.command} {' '.join(self.args)}"

    __str__ = __repr__
